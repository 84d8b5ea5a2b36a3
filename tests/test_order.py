"""The action order of Approach 3 (thesis §4.3.1): topological, deterministic, errors that name demos."""

from __future__ import annotations

import pytest

from teach.demos import parse_demonstration
from teach.domain import ActionDef, ConditionDef, Domain
from teach.errors import LearnError
from teach.learn.order import OrderGraph, action_order


def abc_domain() -> Domain:
    return Domain("abc", (ConditionDef("X"),), (ActionDef(1, "A"), ActionDef(2, "B"), ActionDef(3, "C")))


def demo(domain: Domain, name: str, actions: list[int]):
    """A demonstration running ``actions`` (state is irrelevant to the order)."""
    text = "".join(f"0;{a}\n" for a in actions) + "1;0\n"
    return parse_demonstration(text, domain, f"{name}.csv")


def test_thesis_example_order_is_a_b_c():
    # Fig. 4.6: sequences (A,C), (B,C), (A,B) give the order (A,B,C)
    d = abc_domain()
    demos = [demo(d, "d1", [1, 3]), demo(d, "d2", [2, 3]), demo(d, "d3", [1, 2])]
    assert action_order(d, demos) == ["A", "B", "C"]


def test_ties_are_broken_by_first_appearance():
    # no edge between B and C: the one demonstrated first comes first, whatever the names
    d = abc_domain()
    assert action_order(d, [demo(d, "d1", [3]), demo(d, "d2", [2]), demo(d, "d3", [1, 3])]) == ["B", "A", "C"]
    assert action_order(d, [demo(d, "d1", [2]), demo(d, "d2", [3])]) == ["B", "C"]


def test_a_cycle_names_both_directions_and_demonstrations():
    d = abc_domain()
    demos = [demo(d, "first", [1, 2]), demo(d, "second", [3, 2, 1])]
    with pytest.raises(LearnError) as caught:
        action_order(d, demos)
    message = str(caught.value)
    assert "A before B (first.csv:1)" in message and "B before A (second.csv:2)" in message


def test_a_repeated_action_has_no_order():
    d = abc_domain()
    with pytest.raises(LearnError, match=r"A follows itself \(rep.csv:2\)"):
        action_order(d, [demo(d, "rep", [2, 1, 1])])


def test_an_external_action_starts_a_new_sequence():
    # B, external, A, B: the perturbation may undo B, so A after it is not "B before A"
    d = abc_domain()
    text = "0;2\n0;-1\n1;1\n0;2\n1;0\n"
    perturbed = parse_demonstration(text, d, "p.csv")
    assert action_order(d, [perturbed]) == ["A", "B"]


def test_a_failed_add_on_a_copy_leaves_the_graph_unchanged():
    d = abc_domain()
    graph = OrderGraph()
    graph.add_demo(d, demo(d, "d1", [1, 2]))
    trial = graph.copy()
    with pytest.raises(LearnError):
        trial.add_demo(d, demo(d, "d2", [2, 1]))
    assert graph.order() == ["A", "B"] and sorted(graph.graph.edges) == [("A", "B")]
