"""Pruning (thesis §4.2.2): the pruned tree ticks exactly like the original in every state."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Mapping
from pathlib import Path

import pytest
from conftest import ROOT, colledanchise_tree
from equivalence import assert_equivalent, first_difference
from hypothesis import given, settings
from hypothesis import strategies as st
from strategies import trees

from teach.bt.nodes import (
    Action,
    Condition,
    Fallback,
    Inverter,
    Node,
    Parallel,
    Sequence,
    Status,
    renumber,
    replace_node,
    size,
    walk,
)
from teach.bt.tick import tick
from teach.bt.xml import read_tree, write_tree
from teach.domain import Literal, load_domain
from teach.errors import LearnError
from teach.learn.pabt import expand
from teach.learn.prune import label, prune, prune_with_report, ramifications_of

CONDITIONS = ["a", "b", "c", "d"]
ACTIONS = ["X", "Y", "Z"]
WIDE = [f"c{i}" for i in range(14)]  # beyond 12 conditions: the checker samples


def literal_nodes(conditions: list[str]) -> st.SearchStrategy[Node]:
    return st.sampled_from(conditions).flatmap(
        lambda c: st.sampled_from([Condition(c), Inverter(Condition(c))]))


@st.composite
def pabt_trees(draw: st.DrawFn, conditions: list[str], actions: list[str]) -> Node:
    """PA-BT style: goal conditions in a Sequence, then conditions replaced by atomic BTs
    Fallback(c, Sequence(preconditions..., action)), as in thesis Figs. 4.2 and 6.3-6.7."""
    goals = draw(st.lists(st.sampled_from(conditions), min_size=1, max_size=3))
    tree: Node = Sequence(tuple(Condition(g) for g in goals))
    for _ in range(draw(st.integers(0, 6))):
        leaves = [n for n in walk(tree) if isinstance(n, Condition)]
        target = draw(st.sampled_from(leaves))
        pre = draw(st.lists(literal_nodes(conditions), max_size=3))
        action = Action(draw(st.sampled_from(actions)))
        atomic = Fallback((Condition(target.name), Sequence((*pre, action)) if pre else action))
        tree = _replace(tree, target.uid, atomic)
    return tree


@st.composite
def specialization_trees(draw: st.DrawFn, conditions: list[str], actions: list[str]) -> Node:
    """Fig. 4.7 style: per action a Fallback of conditions and inverted conditions, then the
    action; some of them removed, as specialization (§4.3.2) leaves them."""
    full = [Condition(c) for c in conditions] + [Inverter(Condition(c)) for c in conditions]
    order = draw(st.permutations(actions))
    pairs = []
    for action in order:
        kept = draw(st.lists(st.booleans(), min_size=len(full), max_size=len(full)))
        guards = tuple(Condition(n.name) if isinstance(n, Condition) else Inverter(Condition(n.child.name))
                       for n, keep in zip(full, kept, strict=False) if keep)
        pairs.append(Fallback((*guards, Action(action))))
    return Sequence(tuple(pairs))


def _replace(tree: Node, uid: int, new: Node) -> Node:
    result = replace_node(tree, uid, new)
    assert result is not None
    return result


RAMS = {"X": (Literal("a"),), "Y": (Literal("b", False), Literal("c")), "Z": (Literal("d"),)}


def check(tree: Node, names: list[str], ramifications: Mapping[str, tuple[Literal, ...]] | None = None) -> Node:
    """Prune, prove the result equivalent, and check the report and that pruning is idempotent."""
    pruned, removed = prune_with_report(tree, ramifications or {})
    assert_equivalent(tree, pruned, names)
    assert size(pruned) == size(tree) - len(removed)
    assert prune(pruned, ramifications or {}) == pruned, "pruning again must change nothing"
    return pruned


# --- the property, on random trees of every shape ------------------------------------------------

@settings(max_examples=400, deadline=None)
@given(trees(CONDITIONS, ACTIONS, max_leaves=30))
def test_random_trees_keep_their_behaviour(tree: Node) -> None:
    check(tree, CONDITIONS)


@settings(max_examples=300, deadline=None)
@given(trees(CONDITIONS, ACTIONS, max_leaves=30))
def test_random_trees_with_ramifications_keep_their_behaviour(tree: Node) -> None:
    check(tree, CONDITIONS, RAMS)


@settings(max_examples=200, deadline=None)
@given(pabt_trees(CONDITIONS, ACTIONS))
def test_pabt_trees_keep_their_behaviour(tree: Node) -> None:
    check(tree, CONDITIONS, RAMS)


@settings(max_examples=150, deadline=None)
@given(specialization_trees(CONDITIONS, ACTIONS))
def test_specialization_trees_keep_their_behaviour(tree: Node) -> None:
    check(tree, CONDITIONS, RAMS)


@settings(max_examples=60, deadline=None)
@given(trees(WIDE, ACTIONS, max_leaves=40))
def test_many_conditions_keep_their_behaviour(tree: Node) -> None:
    check(tree, WIDE)


PARTIAL = {"X": RAMS["X"], "Y": RAMS["Y"]}  # Z outside the model


def _run_in_world(tree: Node, state: dict[str, bool], outcomes: list[tuple[Status, bool]]) -> tuple:
    """Tick once in a world where actions may also succeed (making their ramifications true)
    or fail (leaving them either way), as the action model's frame assumption allows; Z,
    outside the model, rewrites every condition when it succeeds or fails."""
    world, calls = dict(state), []

    def act(name: str) -> Status:
        status, value = outcomes[len(calls) % len(outcomes)]
        calls.append(name)
        if status is not Status.RUNNING and name not in PARTIAL:
            for i, condition in enumerate(CONDITIONS):
                world[condition] = value ^ (i % 2 == 0)
        for literal in RAMS.get(name, ()) if name in PARTIAL else ():
            if status is Status.SUCCESS:
                world[literal.name] = literal.value
            elif status is Status.FAILURE:
                world[literal.name] = value
        return status

    result = tick(tree, world.__getitem__, act)
    return result.status, calls, world


@settings(max_examples=300, deadline=None)
@given(trees(CONDITIONS, ACTIONS, max_leaves=30), st.lists(st.booleans(), min_size=4, max_size=4),
       st.lists(st.tuples(st.sampled_from(list(Status)), st.booleans()), min_size=1, max_size=6))
def test_same_behaviour_when_actions_succeed_or_fail(tree: Node, values: list[bool],
                                                     outcomes: list[tuple[Status, bool]]) -> None:
    # beyond the symbolic world: the same actions in the same order, the same result, the same
    # world afterwards, whatever the actions return (given that they change only their ramifications)
    state = dict(zip(CONDITIONS, values, strict=True))
    pruned = prune(tree, PARTIAL)
    assert _run_in_world(pruned, state, outcomes) == _run_in_world(tree, state, outcomes)


def test_the_checker_can_fail() -> None:
    # dropping a condition that still matters must be caught
    tree = Sequence((Condition("a"), Fallback((Condition("b"), Action("X")))))
    assert first_difference(tree, Fallback((Condition("b"), Action("X"))), CONDITIONS) is not None
    with pytest.raises(AssertionError, match="trees differ"):
        assert_equivalent(tree, Sequence((Condition("a"), Action("X"))), CONDITIONS)


# --- the thesis's examples -------------------------------------------------------------------------

def test_fig_4_4_condition_under_fallback_after_same_condition_in_sequence() -> None:
    # a is known true where the inner Fallback is reached: the Fallback always succeeds and
    # its action never runs. Dropping only the inner `a` (the caption's reading) would make
    # X run; the whole Fallback is what is redundant.
    tree = Sequence((Condition("a"), Fallback((Condition("a"), Action("X"))), Action("Y")))
    assert check(tree, CONDITIONS) == Sequence((Condition("a"), Action("Y")))


def test_fig_4_4_precondition_already_checked() -> None:
    # the precondition a inside the atomic BT was checked by the Sequence above it
    tree = Sequence((Condition("a"), Fallback((Condition("b"), Sequence((Condition("a"), Action("X")))))))
    assert check(tree, CONDITIONS) == Sequence((Condition("a"), Fallback((Condition("b"), Action("X")))))


def test_fig_4_5_through_an_inverter() -> None:
    # b failed before the Sequence is reached, so the inverted precondition !b is certain
    tree = Fallback((Condition("b"), Sequence((Inverter(Condition("b")), Action("X")))))
    assert check(tree, CONDITIONS) == Fallback((Condition("b"), Action("X")))
    # and an Inverter above the condition flips what its parent learns
    tree = Sequence((Inverter(Condition("a")), Fallback((Condition("a"), Condition("b"), Action("X")))))
    assert check(tree, CONDITIONS) == Sequence((Inverter(Condition("a")), Fallback((Condition("b"), Action("X")))))


def test_left_siblings_that_failed_under_a_fallback() -> None:
    # ?(a, b) failed: both a and b are false where the Sequence is reached
    tree = Fallback((Fallback((Condition("a"), Condition("b"))), Sequence((Inverter(Condition("a")), Action("X")))))
    assert check(tree, CONDITIONS) == Fallback((Fallback((Condition("a"), Condition("b"))), Action("X")))


def test_algorithm_4_4_would_drop_a_deciding_parent() -> None:
    # removing the redundant inner `a` together with its one-child Sequence would let X run
    # when b is false; the one-child Sequence always succeeds, so X is what is unreachable
    tree = Sequence((Condition("a"), Fallback((Condition("b"), Sequence((Condition("a"),)), Action("X")))))
    assert check(tree, CONDITIONS) == Condition("a")


def test_known_false_under_sequence_cuts_the_unreachable_rest() -> None:
    # !a is certain, so `a` fails every time it is reached: it stays, what follows goes
    head = (Inverter(Condition("a")), Fallback((Condition("b"), Action("Y"))), Condition("a"))
    tree = Sequence((*head, Action("X"), Condition("c")))
    assert check(tree, CONDITIONS, RAMS) == Sequence(head)  # Y changes b and c only
    assert check(tree, CONDITIONS) == tree  # an action outside the model may have made a true
    # and a Sequence that can only fail is itself redundant under a Fallback
    tree = Fallback((Condition("a"), Sequence((Condition("b"), Condition("a"), Action("X"))), Action("Y")))
    assert check(tree, CONDITIONS) == Fallback((Condition("a"), Action("Y")))


def test_ramification_of_an_action_that_succeeded() -> None:
    # Fallback(a, X) succeeds only with a true or X done, and X makes a true
    tree = Sequence((Fallback((Condition("a"), Action("X"))),
                     Fallback((Condition("b"), Sequence((Condition("a"), Action("Y")))))))
    expected = Sequence((Fallback((Condition("a"), Action("X"))), Fallback((Condition("b"), Action("Y")))))
    assert check(tree, CONDITIONS, RAMS) == expected
    assert check(tree, CONDITIONS) == tree  # without the action model nothing is known after X


def test_exact_stage_sees_a_disjunction() -> None:
    # past Fallback(a, b, X), a or b holds (X makes a true): where !a would succeed, b does
    tree = Sequence((Fallback((Condition("a"), Condition("b"), Action("X"))),
                     Fallback((Inverter(Condition("a")), Condition("b"), Action("Y")))))
    expected = Sequence((Fallback((Condition("a"), Condition("b"), Action("X"))),
                         Fallback((Condition("b"), Action("Y")))))
    assert check(tree, CONDITIONS, RAMS) == expected
    # without the action model, X may have left a and b false, so !a must stay
    assert check(tree, CONDITIONS) == tree


def test_a_running_or_failed_action_guarantees_nothing() -> None:
    # under a Fallback the action before `a` failed: its ramification does not hold
    tree = Fallback((Action("X"), Condition("a"), Action("Y")))
    assert check(tree, CONDITIONS, RAMS) == tree
    # an action ticked in a Parallel may have changed the state its siblings see
    tree = Sequence((Condition("a"), Parallel((Action("Y"), Condition("a")), 2)))
    assert check(tree, CONDITIONS, RAMS) == tree


def test_an_action_outside_the_model_may_change_anything() -> None:
    # Z may have made `b` false, so `b` is tested again; X only changes `a` ...
    tree = Sequence((Condition("b"), Fallback((Condition("c"), Action("Z"))), Condition("b"), Action("Y")))
    assert check(tree, CONDITIONS, PARTIAL) == tree
    assert _run_in_world(tree, dict.fromkeys(CONDITIONS, True) | {"c": False}, [(Status.SUCCESS, False)])[0] \
        is Status.FAILURE
    # ... so `b` holds after it
    tree = Sequence((Condition("b"), Fallback((Condition("c"), Action("X"))), Condition("b"), Action("Y")))
    assert check(tree, CONDITIONS, PARTIAL) == Sequence((Condition("b"), Fallback((Condition("c"), Action("X"))),
                                                         Action("Y")))


def test_parallel_absorbs_a_decided_child_in_its_threshold() -> None:
    # a is certain: Parallel(a, b, c; 2 of 3) is Parallel(b, c; 1 of 2)
    tree = Sequence((Condition("a"), Parallel((Condition("a"), Condition("b"), Condition("c")), 2)))
    assert check(tree, CONDITIONS) == Sequence((Condition("a"), Parallel((Condition("b"), Condition("c")), 1)))
    # a sure failure in a 2-of-2 Parallel cannot be absorbed: the Parallel just fails
    tree = Sequence((Inverter(Condition("a")), Parallel((Condition("a"), Action("X")), 2)))
    assert check(tree, CONDITIONS) == tree


def test_single_child_control_nodes_are_removed_but_inverters_stay() -> None:
    tree = Sequence((Fallback((Inverter(Sequence((Condition("a"),))),)),))
    assert check(tree, CONDITIONS) == Inverter(Condition("a"))


def test_fig_4_7_initial_tree_always_succeeds() -> None:
    # every Fallback holds c and !c: the tree is SUCCESS in every state, and so is what is left
    guards = tuple(Condition(c) for c in CONDITIONS) + tuple(Inverter(Condition(c)) for c in CONDITIONS)
    tree = Sequence(tuple(Fallback((*guards, Action(a))) for a in ACTIONS))
    pruned = check(tree, CONDITIONS)
    assert pruned == Fallback((Condition("a"), Inverter(Condition("a"))))


def test_colledanchise_tree_is_already_minimal(ball) -> None:  # type: ignore[no-untyped-def]
    tree = colledanchise_tree()
    assert check(tree, list(ball.condition_names), ramifications_of(ball)) == tree


def test_multi_goal_pabt_tree_prunes_to_colledanchise(ball) -> None:  # type: ignore[no-untyped-def]
    # Fig. 6.7 (Table 4.1 actions, all five goals, 24 nodes) -> Fig. 6.8 (16 nodes)
    def atomic(goal: str, pre: str | None, action: str) -> Node:
        body = Sequence((Condition(pre), Action(action))) if pre else Action(action)
        return Fallback((Condition(goal), body))

    tree = Sequence((atomic("BallFound", None, "FindBall"), atomic("BallClose", "BallFound", "ApproachBall"),
                     atomic("BallGrasped", "BallClose", "GraspBall"), atomic("BinClose", "BallGrasped", "ApproachBin"),
                     atomic("BallPlaced", "BinClose", "PlaceBall")))
    assert size(tree) == 24
    pruned = check(tree, list(ball.condition_names), ramifications_of(ball))
    assert size(pruned) == 16
    assert pruned == colledanchise_tree()


def test_pabt_expand_generations_prune_soundly(ball) -> None:  # type: ignore[no-untyped-def]
    names = list(ball.condition_names)
    for generation in expand(ball):
        check(generation, names, ramifications_of(ball))
    table41 = load_domain(ROOT / "demos" / "ball" / "reference" / "table41.toml")
    multi41 = expand(table41, goal=tuple(Literal(n) for n in names))[-1]
    assert size(multi41) == 24  # Fig. 6.7 -> Fig. 6.8
    assert check(multi41, names, ramifications_of(table41)) == colledanchise_tree()
    multi = expand(ball, goal=tuple(Literal(n) for n in names))
    assert check(multi[-1], names, ramifications_of(ball)) == colledanchise_tree()


# --- identity, determinism, errors ---------------------------------------------------------------

def test_kept_nodes_keep_their_uids_and_the_report_names_the_removed() -> None:
    tree = renumber(Sequence((Condition("a"), Fallback((Condition("b"), Sequence((Condition("a"), Action("X"))))))))
    pruned, removed = prune_with_report(tree)
    before = {n.uid: n for n in walk(tree)}
    for node in walk(pruned):
        assert type(before[node.uid]) is type(node)
    assert removed == ["Condition:a#6", "Sequence#5"]
    assert sorted({n.uid for n in walk(tree)} - {n.uid for n in walk(pruned)}) == [5, 6]
    assert label(Sequence((), uid=9)) == "Sequence#9"


@settings(max_examples=50, deadline=None)
@given(trees(CONDITIONS, ACTIONS, max_leaves=30))
def test_deterministic(tree: Node) -> None:
    a, b = renumber(tree), renumber(tree)
    assert prune_with_report(a, RAMS) == prune_with_report(b, RAMS)


def test_contradictory_ramifications_are_refused() -> None:
    with pytest.raises(LearnError, match="both a and !a"):
        prune(Action("X"), {"X": (Literal("a"), Literal("a", False))})


# --- the command ----------------------------------------------------------------------------------

def _teach(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "teach.cli", *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)


def test_prune_command(tmp_path: Path, ball) -> None:  # type: ignore[no-untyped-def]
    tree = Sequence((Fallback((Condition("BallFound"), Action("FindBall"))),
                     Fallback((Condition("BallClose"), Sequence((Condition("BallFound"), Action("ApproachBall")))))))
    source, out = tmp_path / "in.xml", tmp_path / "out.xml"
    write_tree(source, tree)
    done = _teach("prune", str(source), "-o", str(out), "--domain", str(ROOT / "demos/ball/domain.toml"))
    assert done.returncode == 0, done.stderr
    assert "9 -> 7 nodes" in done.stdout
    pruned = read_tree(out)
    assert size(pruned) == 7
    assert_equivalent(tree, pruned, list(ball.condition_names))
    # without the action model nothing can be said after FindBall
    done = _teach("prune", str(source), "-o", str(out))
    assert done.returncode == 0 and "9 -> 9 nodes" in done.stdout


def test_prune_command_bad_input(tmp_path: Path) -> None:
    bad = tmp_path / "bad.xml"
    bad.write_text("<root BTCPP_format='4'><BehaviorTree ID='x'><Sequence>")
    out = tmp_path / "out.xml"
    done = _teach("prune", str(bad), "-o", str(out))
    assert done.returncode == 2
    assert "Traceback" not in done.stderr and str(bad) in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert not out.exists()


def test_parallel_with_a_threshold_between_one_and_all_inside_another_parallel():
    # found by fuzzing: the inner 2-of-3 Parallel's result used to count as never known, so the
    # outer one looked as if it never returned, and FindBall was dropped as unreachable
    from teach.bt.nodes import Action, Condition, Inverter, Parallel, Sequence

    inner = Parallel((Condition("BallFound"), Condition("BallClose"), Condition("BinClose")), 2)
    tree = Sequence((Inverter(Parallel((inner, Condition("BallGrasped")), 2)), Action("FindBall")))
    assert_equivalent(tree, prune(tree), ["BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced"])
