"""Every tree we write loads in BehaviorTree.CPP v4 and behaves there as in our tick (Table 2.2)."""

from __future__ import annotations

import pytest
from btcpp import assert_matches_btcpp, btcpp_tick, domain_states
from conftest import colledanchise_tree
from hypothesis import given, settings
from strategies import trees

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, Status
from teach.domain import ActionDef, ConditionDef, Domain

C, A = Condition, Action


def test_colledanchise_tree_matches(ball: Domain) -> None:
    assert_matches_btcpp(colledanchise_tree(), ball)


def test_the_harness_reports_what_bt_cpp_did(ball: Domain) -> None:
    nothing, everything = ball.state([]), ball.state(list(ball.condition_names))
    ready_to_place = ball.state(["BallFound", "BallClose", "BallGrasped", "BinClose"])
    got = btcpp_tick(colledanchise_tree(), ball, [nothing, ready_to_place, everything])
    assert got == [(Status.RUNNING, "FindBall"), (Status.RUNNING, "PlaceBall"), (Status.SUCCESS, None)]


HAND_BUILT: list[Node] = [
    # an Inverter guarding an action, and an inverted action (RUNNING stays RUNNING)
    Sequence((Inverter(C("BallPlaced")), Fallback((C("BallFound"), A("FindBall"))), Inverter(A("GraspBall")))),
    # Parallel 1 of 2: a true condition ends it with SUCCESS, halting the action started first
    Parallel((A("FindBall"), C("BallFound")), 1),
    # Parallel 2 of 3: fails once two children fail, otherwise keeps its actions running
    Parallel((C("BallFound"), A("ApproachBall"), Inverter(C("BinClose"))), 2),
    # Parallel 3 of 3 (all must succeed; one failure is enough to fail)
    Fallback((Parallel((C("BallGrasped"), C("BinClose"), A("PlaceBall")), 3), A("ApproachBin"))),
    # two running actions under a running Parallel: the first one counts
    Parallel((Sequence((C("BallFound"), A("GraspBall"))), A("ApproachBin"), C("BallPlaced")), 3),
    # a Parallel that succeeds inside a Sequence: its halted action does not count, the next one runs
    Sequence((Parallel((A("FindBall"), C("BallClose")), 1), Fallback((C("BinClose"), A("ApproachBin"))))),
    Inverter(Parallel((Inverter(A("FindBall")), Fallback((C("BallFound"), C("BallClose")))), 2)),
]


@pytest.mark.parametrize("tree", HAND_BUILT, ids=[f"tree{i}" for i in range(len(HAND_BUILT))])
def test_hand_built_trees_with_inverters_and_parallels_match(tree: Node, ball: Domain) -> None:
    assert_matches_btcpp(tree, ball)


def test_a_halted_parallel_action_is_not_reported_as_running(ball: Domain) -> None:
    # expectation: FindBall starts, BallClose succeeds, the Parallel succeeds and halts FindBall
    tree = Sequence((Parallel((A("FindBall"), C("BallClose")), 1), A("ApproachBin")))
    assert btcpp_tick(tree, ball, [ball.state(["BallClose"])]) == [(Status.RUNNING, "ApproachBin")]


@settings(max_examples=40, deadline=None)
@given(trees(["BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced"],
             ["FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall"], max_leaves=15))
def test_random_trees_match(tree: Node) -> None:
    from conftest import BALL_DOMAIN

    from teach.domain import load_domain

    assert_matches_btcpp(tree, load_domain(BALL_DOMAIN))


def test_large_domains_are_checked_on_a_fixed_sample() -> None:
    names = [f"C{i}" for i in range(14)]
    domain = Domain("wide", tuple(ConditionDef(n) for n in names),
                    tuple(ActionDef(i + 1, f"Do{i}") for i in range(3)))
    states = list(domain_states(domain))
    assert len(states) == 4096 and states == list(domain_states(domain))
    tree = Fallback((Sequence((C("C0"), C("C13"))), Parallel((Inverter(C("C7")), A("Do1"), A("Do2")), 2)))
    assert_matches_btcpp(tree, domain)


def test_bt_cpp_parallel_remembers_finished_children_unless_halted(ball: Domain) -> None:
    """Why the harness halts between states: BT.CPP's Parallel does not re-tick a child that
    finished while the Parallel keeps running, so without a halt it is not memoryless."""
    import behaviortreepy as btcpp
    from btcpp import _harness

    from teach.bt.xml import tree_to_xml

    tree = Parallel((C("BallFound"), A("FindBall")), 2)
    harness = _harness(ball.condition_names, ball.action_names)
    live = harness.factory.create_tree_from_text(tree_to_xml(tree))
    harness.state = ball.state(["BallFound"])
    assert live.tick_exactly_once() == btcpp.NodeStatus.RUNNING
    harness.state = ball.state([])
    # expectation: Table 2.2 says FAILURE (BallFound now fails); BT.CPP still remembers its SUCCESS
    assert live.tick_exactly_once() == btcpp.NodeStatus.RUNNING
    live.halt_tree()
    assert live.tick_exactly_once() == btcpp.NodeStatus.FAILURE
    live.halt_tree()
