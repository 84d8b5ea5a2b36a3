"""Approach 2 (thesis §4.2.1): action model and goal detected from demonstrations, then PA-BT."""

from __future__ import annotations

from pathlib import Path

import pytest
from btcpp import assert_matches_btcpp
from conftest import ROOT, colledanchise_tree

from teach.bt.nodes import size
from teach.demos import parse_demonstration, read_demo_set
from teach.domain import Literal
from teach.errors import LearnError
from teach.learn.model import detect_model, learn_detect
from teach.learn.prune import prune, ramifications_of
from teach.replay import replay

BALL = ROOT / "demos" / "ball"


def lits(*texts: str) -> tuple[Literal, ...]:
    return tuple(Literal.parse(t) for t in texts)


def demo(ball, text: str, name: str = "d"):
    return parse_demonstration(text, ball, Path(f"{name}.csv"))


def test_preconditions_ramifications_and_goal_of_two_small_demonstrations(ball):
    one = demo(ball, "0;0;0;0;0;1\n1;0;0;0;0;2\n1;1;0;0;0;0\n", "one")
    two = demo(ball, "0;0;0;1;0;1\n1;0;0;1;0;2\n1;1;0;0;0;0\n", "two")
    model = detect_model(ball, [one, two])
    find, approach = model.action("FindBall"), model.action("ApproachBall")
    # FindBall ran in 00000 and 00010: everything but BinClose was constant
    assert find.pre == lits("!BallFound", "!BallClose", "!BallGrasped", "!BallPlaced")
    assert find.ram == lits("BallFound")
    # ApproachBall changed BallClose both times, BinClose only once (so it is no ramification)
    assert approach.pre == lits("BallFound", "!BallClose", "!BallGrasped", "!BallPlaced")
    assert approach.ram == lits("BallClose")
    # never demonstrated: no evidence, no model (the domain file's model is not kept)
    assert model.action("GraspBall").pre == () and model.action("GraspBall").ram == ()
    assert model.goal == lits("BallFound", "BallClose", "!BallGrasped", "!BinClose", "!BallPlaced")


def test_toggled_conditions_and_external_actions_are_not_ramifications(ball):
    # FindBall sets BallFound both times, flips BinClose both ways; the -1 line is nobody's
    first = demo(ball, "0;0;0;1;0;1\n1;0;0;0;0;-1\n1;0;0;0;1;0\n")
    second = demo(ball, "0;0;0;0;0;1\n1;0;0;1;0;0\n")
    model = detect_model(ball, [first, second])
    assert model.action("FindBall").ram == lits("BallFound")
    assert model.goal == lits("BallFound", "!BallClose", "!BallGrasped")


def test_more_demonstrations_redetect_the_model(ball):
    one = demo(ball, "0;0;0;0;0;1\n1;0;0;0;0;0\n")
    assert detect_model(ball, [one]).action("FindBall").pre == lits(
        "!BallFound", "!BallClose", "!BallGrasped", "!BinClose", "!BallPlaced")
    two = demo(ball, "0;1;1;1;1;1\n1;1;1;1;1;0\n")
    both = detect_model(ball, [one, two])
    assert both.action("FindBall").pre == lits("!BallFound")
    assert both.goal == lits("BallFound")


def test_approach2_on_delta1_gives_the_thesis_tree(ball):
    # §6.3: 41 nodes in generation 5, pruned to Colledanchise & Ögren's 16-node tree
    _, demos = read_demo_set(BALL / "delta1", ball)
    generations = learn_detect(ball, demos)
    assert len(generations) == 6 and size(generations[-1]) == 41
    pruned = prune(generations[-1], ramifications_of(detect_model(ball, demos)))
    assert pruned == colledanchise_tree()
    assert replay(generations[-1], ball, demos).reproduced == 32
    assert_matches_btcpp(generations[-1], ball)


@pytest.mark.parametrize(("name", "nodes"), [("delta2", 44), ("delta3", 53), ("delta4", 57)])
def test_approach2_node_counts_match_the_thesis(ball, name, nodes):
    _, demos = read_demo_set(BALL / name, ball)
    tree = learn_detect(ball, demos)[-1]
    assert size(tree) == nodes
    assert replay(tree, ball, demos).reproduced == len(demos)
    assert_matches_btcpp(tree, ball)


def test_no_goal_line_means_no_goal_to_detect(ball):
    with pytest.raises(LearnError, match="no demonstration reaches the goal"):
        learn_detect(ball, [demo(ball, "0;0;0;0;0;1\n1;0;0;0;0;2\n")])
