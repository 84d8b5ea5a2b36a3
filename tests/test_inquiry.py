"""Situation questions for the model learner that guesses (``safe=False``): never about a known state,
never twice. The safe learner's questions: tests/test_safe_learner.py."""

from __future__ import annotations

import itertools
from pathlib import Path

from teach.bt.xml import tree_to_xml
from teach.demos import Demonstration, Step, read_demo_set
from teach.domain import ActionDef, ConditionDef, Domain
from teach.learn.inquiry import KINDS, next_question
from teach.learn.learner import Learner, learn_online

BALL = Path(__file__).resolve().parent.parent / "demos" / "ball"


def ball_learner() -> Learner:
    domain, demos = read_demo_set(BALL / "delta4")
    return learn_online(domain, demos, safe=False)


def test_questions_are_new_unlabelled_states_and_never_repeat() -> None:
    learner = ball_learner()
    asked: list[tuple[bool, ...]] = []
    for _ in range(10):
        question = next_question(learner, asked)
        assert question is not None and question.kind in KINDS
        assert question.state not in asked
        assert question.state not in learner.situations
        asked.append(question.state)


def test_every_answer_but_what_the_tree_does_changes_the_tree() -> None:
    learner = ball_learner()
    question = next_question(learner)
    assert question is not None
    before = tree_to_xml(learner.tree)
    other = next(a for a in learner.domain.action_names if a != question.tree_does)
    learner.teach_step(question.state, other, "question 1")
    assert tree_to_xml(learner.tree) != before
    assert learner.answer_in(question.state) == other


def test_the_first_question_fixes_the_accidental_precondition_of_delta4() -> None:
    # Δ4 never shows GraspBall without a found ball, so the learner drops BallFound as accidental
    # (the goal's bound, every literal of the goal states, would find the ball first there)
    learner = ball_learner()
    question = next_question(learner)
    assert question is not None and question.kind == "goal-bound"
    assert question.state == (False, True, False, False, False) and question.tree_does == "GraspBall"
    # afterwards the precondition questions follow: the goal's bound is asked about once
    second = next_question(learner, [question.state])
    assert second is not None and second.kind == "possible-precondition"
    assert second.action is not None and second.condition is not None


def test_the_goal_bound_question_finds_a_goal_literal_the_cover_left_out() -> None:
    # one demonstration ending with X and Y, Y made first: the cover keeps only X, the last one missing
    domain = Domain("bound", (ConditionDef("X"), ConditionDef("Y")), (ActionDef(1, "MakeX"), ActionDef(2, "MakeY")))
    learner = Learner(domain, safe=False)
    learner.update(Demonstration("one", (Step((False, False), 2, 1), Step((False, True), 1, 2),
                                         Step((True, True), 0, 3))))
    assert learner.goal.cover == [(0, True)]
    question = next_question(learner)
    assert question is not None and question.kind == "goal-bound"
    assert question.state == (True, False) and question.tree_does == "done"
    learner.teach_step(question.state, "MakeY", "question 1")
    assert learner.answer_in((True, False)) == "MakeY"
    assert not learner.goal_holds((True, False))


def test_a_conflict_is_asked_first() -> None:
    domain = Domain("two", (ConditionDef("A"), ConditionDef("B")), (ActionDef(1, "X"), ActionDef(2, "Y")))
    learner = Learner(domain, safe=False)
    learner.update(Demonstration("one", (Step((False, False), 1, 1), Step((True, False), 0, 2))))
    learner.update(Demonstration("two", (Step((False, False), 2, 1), Step((False, True), 0, 2))))
    question = next_question(learner)
    assert question is not None and question.kind == "conflict" and question.state == (False, False)
    assert next_question(learner, [question.state]) != question


def test_nothing_left_to_ask_when_every_state_is_known() -> None:
    domain = Domain("one", (ConditionDef("A"),), (ActionDef(1, "X"),))
    learner = Learner(domain, safe=False)
    learner.update(Demonstration("d", (Step((False,), 1, 1), Step((True,), 0, 2))))
    assert next_question(learner) is None
    assert all(state in learner.situations for state in itertools.product((False, True), repeat=1))


def test_questions_answered_by_the_table_6_1_tree_reproduce_all_of_delta5() -> None:
    from teach.bt.nodes import Status
    from teach.bt.tick import compile_tree
    from teach.bt.xml import read_tree
    from teach.replay import replay

    domain, delta5 = read_demo_set(BALL / "delta5")
    oracle = compile_tree(read_tree(BALL / "reference" / "table61.xml"), domain.condition_names)
    for name, budget in (("delta4", 5), ("delta3", 2)):
        _domain, train = read_demo_set(BALL / name, domain)
        learner = learn_online(domain, train, safe=False)
        asked: list[tuple[bool, ...]] = []
        for number in range(budget):
            question = next_question(learner, asked)
            assert question is not None
            asked.append(question.state)
            status, action = oracle(question.state)
            assert status is not Status.FAILURE
            learner.teach_step(question.state, action if status is Status.RUNNING else None, f"q{number}")
        assert replay(learner.tree, domain, delta5).reproduced == len(delta5), name


def test_a_situation_where_the_tree_stops_short_of_the_declared_goal_is_asked_about() -> None:
    learner = ball_learner()
    stop_short = next(s for s in itertools.product((False, True), repeat=5)
                      if s not in learner.situations and not s[-1])  # the ball not in the bin
    learner.teach_step(stop_short, None, "an answer nobody checked")  # "done" there
    question = next_question(learner, [])
    assert question is not None and question.kind == "unmet-goal" and question.tree_does == "done"
    assert not learner.domain.holds(learner.domain.goal[0], question.state)
