"""Tick semantics (Table 2.2) and the compiled tick agreeing with the traced one."""

from __future__ import annotations

import itertools

from conftest import colledanchise_tree
from hypothesis import given, settings
from strategies import trees

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Parallel, Sequence, Status, renumber, size
from teach.bt.tick import compile_tree, tick, tick_state

NAMES = ["A", "B", "C", "D"]


def test_sequence_stops_at_first_failure():
    tree = Sequence((Condition("A"), Action("X")))
    # A false: the sequence fails without reaching X
    assert tick(tree, {"A": False}).status is Status.FAILURE
    # A true: X runs and the sequence is RUNNING
    result = tick(tree, {"A": True})
    assert (result.status, result.action) == (Status.RUNNING, "X")


def test_fallback_and_inverter():
    tree = Fallback((Inverter(Condition("A")), Action("X")))
    # !A succeeds when A is false: nothing runs
    assert tick(tree, {"A": False}).status is Status.SUCCESS
    assert tick(tree, {"A": True}).action == "X"


def test_parallel_threshold():
    tree = Parallel((Condition("A"), Condition("B"), Action("X")), 2)
    # two successes reach the threshold even though X runs
    assert tick(tree, {"A": True, "B": True}).status is Status.SUCCESS
    # two failures make 2 successes impossible
    assert tick(tree, {"A": False, "B": False}).status is Status.FAILURE
    assert tick(tree, {"A": True, "B": False}).status is Status.RUNNING


def test_trace_names_every_visited_node():
    tree = renumber(colledanchise_tree())
    result = tick_state(tree, ["BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced"],
                        (True, False, False, False, False))
    # root, pair 1, BallFound, pair 2, BallClose, ApproachBall; later pairs are never visited
    assert result.action == "ApproachBall"
    assert len(result.trace) == 6 and size(tree) == 16


@settings(max_examples=300, deadline=None)
@given(trees(NAMES, ["X", "Y", "Z"]))
def test_compiled_tick_equals_traced_tick(tree):
    compiled = compile_tree(tree, NAMES)
    for state in itertools.product([False, True], repeat=len(NAMES)):
        traced = tick_state(tree, NAMES, state)
        assert compiled(state) == (traced.status, traced.action)


def test_deep_tree_compiles():
    # deeper than Python's 20 nested blocks
    tree = Condition("A")
    for i in range(60):
        tree = (Sequence if i % 2 else Fallback)((Inverter(tree), Condition("B")))
    compiled = compile_tree(tree, NAMES)
    for state in itertools.product([False, True], repeat=4):
        traced = tick_state(tree, NAMES, state)
        assert compiled(state) == (traced.status, traced.action)
