"""The model-based learner: strict reproduction of messy demonstrations, honest SUCCESS, explanations."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

from teach.bt.nodes import walk
from teach.bt.xml import tree_to_xml
from teach.demos import Demonstration, Step, read_demo_set
from teach.domain import ActionDef, ConditionDef, Domain, State
from teach.learn.learner import EITHER, Learner, learn, learn_online
from teach.replay import replay
from tests.btcpp import assert_matches_btcpp

ROOT = Path(__file__).resolve().parent.parent
BALL = ROOT / "demos" / "ball"
SETS = ("delta1", "delta2", "delta3", "delta4", "delta5")


def demo(name: str, *lines: tuple[str, int]) -> Demonstration:
    """A demonstration from ("0101", action) pairs."""
    return Demonstration(name, tuple(Step(tuple(c == "1" for c in bits), action, i + 1)
                                     for i, (bits, action) in enumerate(lines)))


def snacks() -> Domain:
    """Use Case 2 in miniature: find a partner, offer until the tray is empty, go back."""
    conditions = tuple(ConditionDef(n) for n in ("Request", "Tray", "Partner", "Empty", "Back"))
    actions = tuple(ActionDef(i + 1, n) for i, n in enumerate(("TakeTray", "FindPartner", "Offer", "Return")))
    return Domain("snacks", conditions, actions)


def messy_snacks() -> list[Demonstration]:
    # conditions: Request Tray Partner Empty Back; actions 1 TakeTray 2 FindPartner 3 Offer 4 Return
    return [
        demo("repeat", ("10000", 1), ("11000", 2), ("11100", 3), ("11000", 2), ("11100", 3), ("11010", 4),
             ("11011", 0)),
        demo("event", ("10000", 1), ("11000", 2), ("11100", -1), ("11000", 2), ("11100", 3), ("11010", 4),
             ("11011", 0)),
        demo("no-goal", ("11000", 2), ("11100", 3)),
    ]


def all_states(domain: Domain) -> list[State]:
    return list(itertools.product((False, True), repeat=len(domain.conditions)))


@pytest.mark.parametrize("name", SETS)
def test_every_ball_set_is_reproduced_strictly_and_runs_the_same_in_btcpp(name: str) -> None:
    domain, demos = read_demo_set(BALL / name)
    tree = learn(domain, demos)
    # every training demonstration, including Δ5's external events, is reproduced strictly
    assert replay(tree, domain, demos).reproduced == len(demos)
    assert_matches_btcpp(tree, domain)


def test_delta4_generalises_to_delta5_without_questions() -> None:
    domain, delta4 = read_demo_set(BALL / "delta4")
    _domain, delta5 = read_demo_set(BALL / "delta5", domain)
    # the thesis's specialization reached 35/43 from these two demonstrations
    assert replay(learn(domain, delta4, safe=False), domain, delta5).reproduced >= 35  # by guessing


def test_repeats_loops_and_external_events_are_reproduced() -> None:
    domain = snacks()
    demos = messy_snacks()
    learner = learn_online(domain, demos)
    assert replay(learner.tree, domain, demos).reproduced == len(demos)
    assert not learner.conflicts
    assert_matches_btcpp(learner.tree, domain)


def test_two_orders_in_two_demonstrations_are_both_reproduced() -> None:
    conditions = tuple(ConditionDef(n) for n in ("X", "Y", "Noise"))
    domain = Domain("orders", conditions, (ActionDef(1, "MakeX"), ActionDef(2, "MakeY")))
    demos = [demo("xy", ("000", 1), ("100", 2), ("110", 0)),
             demo("yx", ("001", 2), ("011", 1), ("111", 0))]
    tree = learn(domain, demos)
    assert replay(tree, domain, demos).reproduced == 2
    assert_matches_btcpp(tree, domain)


def test_success_only_where_the_learned_goal_holds() -> None:
    for name in SETS:
        domain, demos = read_demo_set(BALL / name)
        learner = learn_online(domain, demos)
        for state in all_states(domain):
            if learner.answer_in(state) is None:
                assert learner.goal_holds(state), (name, state)


def test_nothing_learned_fails_everywhere() -> None:
    domain = snacks()
    learner = Learner(domain)
    assert all(learner.answer_in(s) is False for s in all_states(domain))
    assert_matches_btcpp(learner.tree, domain)
    assert all(learner.explain(node.uid) for node in walk(learner.tree))


def test_a_state_labelled_two_ways_is_a_conflict_the_latest_label_wins() -> None:
    domain = snacks()
    learner = Learner(domain)
    learner.update(demo("first", ("11000", 2), ("11100", 3), ("11010", 0)))
    update = learner.update(demo("second", ("11000", 4), ("11001", 0)))  # no refusal
    assert [c.state for c in update.new_conflicts] == [tuple(c == "1" for c in "11000")]
    (conflict,) = learner.conflicts
    assert [answer for answer, _source in conflict.labels] == ["FindPartner", "Return"]
    assert learner.answer_in(conflict.state) == "Return"
    learner.resolve(conflict.state, EITHER)
    assert not learner.conflicts
    assert learner.situations[conflict.state] == frozenset({"FindPartner", "Return"})
    learner.update(demo("third", ("11000", 2), ("11100", 3), ("11010", 0)))
    assert not learner.conflicts  # either is fine: no new conflict
    assert learner.answer_in(conflict.state) in ("FindPartner", "Return")


def test_resolve_to_one_answer() -> None:
    domain = snacks()
    learner = Learner(domain)
    learner.update(demo("first", ("11000", 2), ("11100", 3), ("11010", 0)))
    learner.update(demo("second", ("11000", 4), ("11001", 0)))
    state = learner.conflicts[0].state
    learner.resolve(state, "FindPartner")
    assert learner.answer_in(state) == "FindPartner"


def test_answers_are_learned_at_once() -> None:
    domain, demos = read_demo_set(BALL / "delta4")
    learner = learn_online(domain, demos)
    state = (False, False, True, False, False)  # grasped, nothing else
    learner.teach_step(state, "ApproachBin", "question 1")
    assert learner.answer_in(state) == "ApproachBin"
    done = (True, True, True, True, True)
    learner.teach_step(done, None, "question 2")
    assert learner.answer_in(done) is None
    assert replay(learner.tree, domain, demos).reproduced == 2


def test_online_equals_batch_and_output_is_deterministic() -> None:
    domain, demos = read_demo_set(BALL / "delta5")
    online = Learner(domain)
    for d in demos:
        online.update(d)
    assert tree_to_xml(online.tree) == tree_to_xml(learn(domain, demos)) == tree_to_xml(learn(domain, demos))


def test_explain_covers_every_node_with_its_evidence() -> None:
    domain, demos = read_demo_set(BALL / "delta4")
    learner = learn_online(domain, demos)
    learner.teach_step((False, True, False, False, False), "FindBall", "question 1")
    for node in walk(learner.tree):
        why = learner.why(node.uid)
        assert why.text
        if why.kind in ("achiever", "precondition", "goal", "exception"):
            assert why.sources, why
    texts = [learner.explain(n.uid) for n in walk(learner.tree)]
    assert any("delta4" in t and ".csv:" in t for t in texts)


def test_an_answer_naming_an_action_never_shown_teaches_its_effect() -> None:
    domain, _demos = read_demo_set(BALL / "delta4")
    # FindBall is never demonstrated: the ball is always found already
    shown = demo("found", ("10000", 2), ("11000", 3), ("11100", 4), ("11110", 5), ("11111", 0))
    learner = learn_online(domain, [shown])
    not_found = (False, False, False, False, False)  # one literal away from where ApproachBall was shown
    learner.teach_step(not_found, "FindBall", "question 1")
    achievers = [n for n in walk(learner.tree) if learner.why(n.uid).kind == "achiever"
                 and learner.why(n.uid).action == "FindBall"]
    assert achievers and "guessed from the answer at question 1" in learner.explain(achievers[0].uid)
    # the plan does it, not an exception for that one state
    assert learner.answer_in(not_found) == "FindBall"
    assert all(learner.why(n.uid).kind != "exception" for n in walk(learner.tree))
    assert replay(learner.tree, domain, [shown]).reproduced == 1


@pytest.mark.parametrize("seed", range(6))
def test_random_messy_demonstrations_are_reproduced_except_where_they_conflict(seed: int) -> None:
    """Arbitrary data: random actions with random effects, repeats, loops, external events."""
    import random

    rng = random.Random(seed)
    conditions = tuple(ConditionDef(f"C{i}") for i in range(6))
    domain = Domain("messy", conditions, tuple(ActionDef(i + 1, f"A{i}") for i in range(4)))
    demos = []
    for number in range(8):
        values = [rng.random() < 0.5 for _ in conditions]
        steps: list[Step] = []
        for _ in range(rng.randint(1, 7)):
            action = rng.choice((-1, 1, 2, 3, 4, 4))
            steps.append(Step(tuple(values), action, len(steps) + 1))
            values[rng.randrange(len(values))] = rng.random() < 0.5
        steps.append(Step(tuple(values), 0, len(steps) + 1))
        demos.append(Demonstration(f"m{number}", tuple(steps)))
    learner = learn_online(domain, demos)  # never raises
    tree = learner.tree
    conflicted = {c.state for c in learner.conflicts}
    for demo_, result in zip(demos, replay(tree, domain, demos).results, strict=True):
        if not result.reproduced:
            # only a state labelled differently later (the latest label wins) may fail
            assert result.divergence is not None and result.divergence.state in conflicted, demo_.name
    for state, allowed in learner.situations.items():
        does = learner.answer_in(state)
        assert isinstance(does, str | None) and does in allowed
    for state in all_states(domain):
        assert learner.answer_in(state) is not None or learner.goal_holds(state)
    assert_matches_btcpp(tree, domain)
    assert all(learner.explain(node.uid) for node in walk(tree))


def test_the_kept_count_of_plan_errors_matches_a_fresh_count() -> None:
    # the count is updated label by label instead of recounting every situation per update
    domain, demos = read_demo_set(BALL / "delta4")
    learner = learn_online(domain, demos)
    for number, state in enumerate(s for s in all_states(domain) if s not in learner.situations):
        learner._plan_errors()
        does = learner.answer_in(state)
        answer = None if isinstance(does, str) else domain.action_names[0]
        learner._label(learner._mask(state), state, answer, f"question {number}")  # no replan
        kept = learner._plan_errors()
        learner._counted = None
        assert kept == learner._plan_errors(), state
