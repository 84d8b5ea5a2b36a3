"""Approach 1 (thesis §4.1, §6.2): PA-BT generations from a given action model."""

from __future__ import annotations

from dataclasses import replace

import pytest
from btcpp import assert_matches_btcpp
from conftest import colledanchise_tree

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Sequence, Status, size
from teach.bt.tick import tick_state
from teach.bt.xml import read_tree
from teach.cli import main
from teach.domain import ActionDef, ConditionDef, Domain, Literal
from teach.errors import LearnError
from teach.learn.pabt import expand, write_generations
from teach.learn.prune import prune, ramifications_of


def table_4_1(ball: Domain) -> Domain:
    """The hard-coded model of Table 4.1: each action needs the previous one's ramification."""
    actions, previous = [], ()
    for action in ball.actions:
        actions.append(replace(action, pre=previous, ram=action.ram))
        previous = action.ram
    return replace(ball, actions=tuple(actions))


def every_goal(ball: Domain) -> list[Literal]:
    return [Literal(name) for name in ball.condition_names]


def test_single_goal_gives_fig_6_1(ball):
    # Fig. 6.1: the conditions are checked in reverse order, BallPlaced first
    def step(condition: str, inner, action: str):
        return Fallback((Condition(condition), Sequence((inner, Action(action)))))

    expected = step("BallPlaced", step("BinClose", step("BallGrasped", step(
        "BallClose", Fallback((Condition("BallFound"), Action("FindBall"))), "ApproachBall"),
        "GraspBall"), "ApproachBin"), "PlaceBall")
    generations = expand(table_4_1(ball))
    assert generations[0] == Condition("BallPlaced")
    assert generations[-1] == expected
    assert len(generations) == 6
    assert_matches_btcpp(generations[-1], ball)


def test_all_five_goals_give_figs_6_2_to_6_8(ball):
    # five expansions after the initial Sequence, in goal order; 24 nodes, pruned to 16
    model = table_4_1(ball)
    generations = expand(model, every_goal(ball))
    assert generations[0] == Sequence(tuple(Condition(n) for n in ball.condition_names))
    assert [size(t) for t in generations] == [6, 8, 12, 16, 20, 24]
    # generation i has expanded the i-th goal (BallFound, BallClose, ...) and nothing after it
    for i, generation in enumerate(generations):
        kinds = [type(k) for k in generation.children]
        assert kinds == [Fallback] * i + [Condition] * (5 - i)
    assert prune(generations[-1], ramifications_of(model)) == colledanchise_tree()
    assert_matches_btcpp(generations[-1], ball)


def test_table_6_1_model_reaches_the_goal_from_nothing(ball):
    tree = expand(ball)[-1]
    assert tick_state(tree, ball.condition_names, (False,) * 5).action == "FindBall"
    assert tick_state(tree, ball.condition_names, (True, True, True, True, False)).action == "PlaceBall"
    assert tick_state(tree, ball.condition_names, (False, False, False, False, True)).status is Status.SUCCESS
    assert_matches_btcpp(tree, ball)


def test_negative_literals_become_inverters(ball):
    # goal !BallPlaced holds from the start: generation 0 is already done
    assert expand(ball, [Literal("BallPlaced", False)]) == [Inverter(Condition("BallPlaced"))]
    tree = expand(ball, [Literal("BallGrasped")])[-1]
    assert Inverter(Condition("BallGrasped")) in tree.children[1].children


def test_several_achievers_share_one_fallback():
    # Fig. 2.8: one Sequence per action that achieves the condition
    domain = Domain("two-ways", (ConditionDef("Door"), ConditionDef("Key")),
                    (ActionDef(1, "Unlock", pre=(Literal("Key"),), ram=(Literal("Door"),)),
                     ActionDef(2, "Kick", ram=(Literal("Door"),)),
                     ActionDef(3, "Fetch", ram=(Literal("Key"),))), (Literal("Door"),))
    generations = expand(domain)
    assert generations[1] == Fallback((Condition("Door"), Sequence((Condition("Key"), Action("Unlock"))),
                                       Action("Kick")))
    assert len(generations) == 2  # Kick reaches the goal, so Key is never expanded


def test_precondition_and_ramification_at_once_is_refused(ball):
    broken = replace(ball, actions=tuple(
        replace(a, pre=(Literal("BinClose"),)) if a.name == "ApproachBin" else a for a in ball.actions))
    with pytest.raises(LearnError, match="BinClose is both a precondition and a ramification of ApproachBin"):
        expand(broken)


def test_unachievable_goal_is_refused_with_the_reason(ball):
    no_placing = replace(ball, actions=tuple(replace(a, ram=()) if a.name == "PlaceBall" else a
                                             for a in ball.actions))
    with pytest.raises(LearnError, match=r"no action makes BallPlaced true.*the goal needs it.*PlaceBall"):
        expand(no_placing)
    no_finding = replace(ball, actions=tuple(replace(a, ram=()) if a.name == "FindBall" else a
                                             for a in ball.actions))
    with pytest.raises(LearnError, match="no action makes BallFound true.*GraspBall needs it as a precondition"):
        expand(no_finding)


def test_a_looping_model_is_refused():
    # Toggle makes A true and B false, Other the reverse: goal A and B can never hold together
    domain = Domain("loop", (ConditionDef("A"), ConditionDef("B")),
                    (ActionDef(1, "Toggle", ram=(Literal("A"), Literal("B", False))),
                     ActionDef(2, "Other", ram=(Literal("B"), Literal("A", False)))),
                    (Literal("A"), Literal("B")))
    with pytest.raises(LearnError, match="cannot reach the goal A and B"):
        expand(domain)


def test_no_goal_is_refused(ball):
    with pytest.raises(LearnError, match="no goal"):
        expand(replace(ball, goal=()))


def test_generations_are_written_and_read_back(ball, tmp_path):
    generations = expand(ball, every_goal(ball))
    paths = write_generations(tmp_path / "run", generations)
    assert [p.name for p in paths] == [f"gen-{i:02d}.xml" for i in range(len(generations))]
    assert [read_tree(p) for p in paths] == generations


def test_cli_learns_and_refuses_cleanly(tmp_path, capsys):
    from conftest import ROOT

    out = tmp_path / "tree.xml"
    assert main(["learn", str(ROOT / "demos" / "ball" / "domain.toml"), "--approach", "pabt", "--prune",
                 "--goal", *[n for n in ("BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced")],
                 "-o", str(out), "--generations", str(tmp_path / "gens")]) == 0
    assert "36 nodes, 16 after pruning" in capsys.readouterr().out
    assert read_tree(out) == colledanchise_tree()
    bad = tmp_path / "bad.xml"
    assert main(["learn", str(ROOT / "dialogues" / "study" / "participant1.toml"), "--approach", "pabt",
                 "-o", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "both a precondition and a ramification" in err
    assert not bad.exists()
