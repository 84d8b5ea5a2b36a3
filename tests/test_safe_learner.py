"""The safe learner (``Learner(domain, safe=True)``): it never runs an action where a precondition
it has not ruled out is false, never says done where a goal literal it has not ruled out is false,
and its questions settle those literals a group at a time. Judged in the ball task's true model
(demos/ball/domain.toml declares it; the learner never reads it)."""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st
from teacher_loop import goal_holds

from teach.bt.nodes import Status
from teach.bt.tick import compile_tree
from teach.demos import Demonstration, read_demo_set
from teach.domain import Domain, State
from teach.learn.action_model import literals_of
from teach.learn.inquiry import SituationQuestion, next_question
from teach.learn.learner import Learner, learn_online
from teach.learn.regress import _Kept
from teach.learn.safe_inquiry import may_i
from teach.replay import count_reproduced
from teach.symbolic import apply_action, missing_preconditions

BALL = Path(__file__).resolve().parent.parent / "demos" / "ball"
STATES = [tuple(bits) for bits in itertools.product((False, True), repeat=5)]


def ball(folder: str = "delta4") -> tuple[Domain, list[Demonstration]]:
    domain, demos = read_demo_set(BALL / folder)
    return domain, demos


def applicable(domain: Domain, action: str, state: State) -> bool:
    return not missing_preconditions(domain, state, action)


def outcomes(domain: Domain, learner: Learner) -> list[str]:
    """How the learned tree ends from every start state in the true model (compiled once for
    all 32 starts: compiling costs more than ticking)."""
    tick = compile_tree(learner.tree, domain.condition_names)
    return [outcome(domain, tick, start) for start in STATES]


def outcome(domain: Domain, tick: Callable[[State], tuple[Status, str | None]], start: State, limit: int = 20) -> str:
    """Tick the compiled tree from ``start`` in the true model until it stops."""
    state, seen = start, {start}
    for _ in range(limit):
        status, action = tick(state)
        if status is Status.SUCCESS:
            return "reached" if goal_holds(domain, state) else "false-done"
        if status is Status.FAILURE:
            return "stuck"
        assert action is not None
        if not applicable(domain, action, state):
            return "unsafe"
        state = apply_action(domain, state, action)
        if state in seen:
            return "loop"
        seen.add(state)
    return "loop"


def answer_from_truth(domain: Domain, learner: Learner, question: SituationQuestion) -> bool:
    """Answer one question from the true model; True if the tree changed."""
    if question.kind == "must-precondition":
        assert question.action is not None
        return learner.settle(question, not applicable(domain, question.action, question.state), "q").tree_changed
    if question.kind == "must-goal":
        return learner.settle(question, not goal_holds(domain, question.state), "q").tree_changed
    # a situation: the first step that works
    answer = None if goal_holds(domain, question.state) else next(
        (a for a in domain.action_names if applicable(domain, a, question.state)), None)
    return learner.teach_step(question.state, answer, "q").tree_changed


def ask(domain: Domain, learner: Learner, budget: int) -> int:
    asked: list[State] = []
    changed = 0
    for _ in range(budget):
        question = next_question(learner, asked)
        if question is None:
            break
        asked.append(question.state)
        changed += answer_from_truth(domain, learner, question)
    return changed


@pytest.mark.parametrize("folder", ["delta1", "delta2", "delta3", "delta4"])
def test_every_action_the_tree_runs_has_every_required_precondition(folder: str) -> None:
    domain, demos = ball(folder)
    learner = learn_online(domain, demos, safe=True)
    tick = compile_tree(learner.tree, domain.condition_names)
    for state in STATES:
        status, action = tick(state)
        if status is Status.RUNNING:
            assert action is not None
            for index, value in literals_of(*learner.model[action].required, 5):
                assert state[index] == value, (state, action)
        elif status is Status.SUCCESS:
            assert learner.goal_holds(state)


@pytest.mark.parametrize("folder", ["delta1", "delta2", "delta3", "delta4"])
def test_from_every_state_it_never_acts_unsafely_nor_says_done_wrongly(folder: str) -> None:
    domain, demos = ball(folder)
    learner = learn_online(domain, demos, safe=True)
    ends = outcomes(domain, learner)
    assert "unsafe" not in ends and "false-done" not in ends
    ask(domain, learner, 5)
    ends = outcomes(domain, learner)
    assert "unsafe" not in ends and "false-done" not in ends


def test_the_guessing_learner_is_unsafe_where_the_safe_one_is_not() -> None:
    """The reason for the safe learner, measured on every pair of Δ2: the model learner guesses."""
    domain, demos = ball("delta2")
    guessing_bad = safe_bad = 0
    for pair in itertools.combinations(demos, 2):
        for safe in (False, True):
            learner = learn_online(domain, list(pair), safe=safe)
            bad = sum(end in ("unsafe", "false-done") for end in outcomes(domain, learner))
            if safe:
                safe_bad += bad
            else:
                guessing_bad += bad
    assert safe_bad == 0
    assert guessing_bad > 0


@pytest.mark.parametrize("folder", ["delta1", "delta2", "delta3", "delta4"])
def test_training_demonstrations_are_reproduced_strictly(folder: str) -> None:
    domain, demos = ball(folder)
    learner = learn_online(domain, demos, safe=True)
    assert count_reproduced(learner.tree, domain, demos) == len(demos)


def test_five_answers_from_the_truth_reproduce_more_of_delta5() -> None:
    domain, demos = ball("delta4")
    _domain, delta5 = read_demo_set(BALL / "delta5", domain)
    learner = learn_online(domain, demos, safe=True)
    before = count_reproduced(learner.tree, domain, delta5)
    changed = ask(domain, learner, 5)
    after = count_reproduced(learner.tree, domain, delta5)
    # measured: 28 -> 31 of 43 by literals settled, 30 since their expectation is over the hypotheses that
    # act (the Table 6.1 answers of bench-teach: 28 -> 43); the declared goal gives the 28
    assert after >= 30 and after > before
    assert changed >= 4


def test_a_yes_rules_a_whole_group_out_and_a_no_splits_it() -> None:
    domain, demos = ball("delta4")
    domain = dataclasses.replace(domain, goal=())  # the goal learned, not declared: questions about it too
    learner = learn_online(domain, demos, safe=True)
    goal = learner.untested(None, learner.goal.unsure())[0]
    assert len(goal) == 4
    learner.settle(group_question(learner, None, goal), needed=False, source="q1")  # the ball in the bin is all
    assert learner.goal.required() == [(4, True)]
    unsure = literals_of(*learner.model["GraspBall"].unsure, len(domain.conditions))
    pair = [lit for lit in unsure if lit[0] in (0, 3)]  # "I can see the ball", "the bin is out of reach"
    learner.settle(group_question(learner, "GraspBall", pair), needed=True, source="q2")  # one of the two is needed
    half = learner.untested("GraspBall", pair)
    assert half == [pair[:1], pair[1:]]  # the refused group is split
    learner.settle(group_question(learner, "GraspBall", half[0]), needed=False, source="q3")
    assert pair[1] in learner.model["GraspBall"].confirmed  # so the other one is needed, for good


def test_a_yes_given_as_the_action_itself_also_leaves_the_last_literal_of_a_refused_group_needed() -> None:
    """The same group testing through ``answer_question`` (the session's and the benches' way: the
    teacher names what to do there). A "yes" given as the action asked about, or a demonstration,
    rules literals out like ``settle`` does, so what is left of a refused group is needed at once
    (it was inferred only at the next "no": snacks, the request before taking the tray; miconic
    after 2 demonstrations and 5 answers 79 -> 93% reached)."""
    domain, demos = ball("delta4")
    learner = learn_online(domain, demos, safe=True)
    unsure = literals_of(*learner.model["GraspBall"].unsure, len(domain.conditions))
    pair = [lit for lit in unsure if lit[0] in (0, 3)]
    refused = group_question(learner, "GraspBall", pair)
    learner.answer_question(refused.state, "GraspBall", "FindBall", "q1")  # no: find the ball there
    allowed = group_question(learner, "GraspBall", pair[:1])
    learner.answer_question(allowed.state, "GraspBall", "GraspBall", "q2")  # yes, with only the first false
    assert pair[1] in learner.model["GraspBall"].confirmed


def group_question(learner: Learner, action: str | None, literals: list[tuple[int, bool]]) -> SituationQuestion:
    """"May I still do ``action``?" where it was shown, with ``literals`` made false."""
    shown = learner.shown_states()[action] if action else next(s for s, a in learner.situations.items() if None in a)
    state = tuple(not v if any(i == index for index, _ in literals) else v for i, v in enumerate(shown))
    return may_i(learner, state, action, literals, "nothing")


def test_a_situation_that_cannot_happen_is_never_asked_again() -> None:
    domain, demos = ball("delta4")
    learner = learn_online(domain, demos, safe=True)
    question = next_question(learner)
    assert question is not None
    before = learner.tree
    learner.rule_out(question.state, "q1")
    assert learner.tree == before
    for _ in range(10):
        later = next_question(learner)
        if later is None:
            break
        assert later.state != question.state
        learner.rule_out(later.state, "q")


def test_every_question_is_of_a_known_kind_and_new() -> None:
    from teach.learn.safe_inquiry import KINDS

    domain, demos = ball("delta2")
    learner = learn_online(domain, demos[:2], safe=True)
    questions = _all(learner)
    assert questions and all(q.kind in KINDS for q in questions)
    assert len({q.state for q in questions}) == len(questions)
    assert not any(q.state in learner.situations for q in questions if q.kind != "conflict")


def _all(learner: Learner, asked: list[State] | None = None) -> list[SituationQuestion]:
    """Every question the learner would ask in turn if each were skipped."""
    skipped = list(asked or [])
    found = []
    for _ in range(12):
        question = next_question(learner, skipped)
        if question is None:
            break
        found.append(question)
        skipped.append(question.state)
    return found


@given(st.lists(st.integers(1, 1 << 70), min_size=1, max_size=40), st.integers(0, 1 << 70))
def test_the_regressions_kept_conditions_are_found_as_by_testing_every_one(kept: list[int], condition: int) -> None:
    """``_Kept`` tests only the groups whose highest literal a new condition holds: the same answer
    as testing every kept condition (the tree is byte-identical; a visitall update 2.5x faster)."""
    grouped = _Kept(kept[0])
    for more in kept[1:]:
        grouped.add(more)
    assert grouped.implied_by(condition) == any(k & ~condition == 0 for k in kept)
