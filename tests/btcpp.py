"""Check a tree against BehaviorTree.CPP v4 itself: our XML, loaded by the real library.

``assert_matches_btcpp(tree, domain)`` writes the tree with ``teach.bt.xml``, builds it in
BehaviorTree.CPP through ``behaviortreepy`` (conditions read the current state, actions
return RUNNING as in the symbolic world) and, for every state of the domain (a fixed sample
when there are more than 4096), compares the root status and the action left running with
our compiled tick. The tree is halted after every tick, so no memory carries between states.
"""

from __future__ import annotations

import functools
import itertools
import random
from collections.abc import Iterator

import behaviortreepy as btcpp

from teach.bt.nodes import Node, Status, action_names, condition_names
from teach.bt.tick import compile_tree
from teach.bt.xml import tree_to_xml
from teach.domain import Domain, State

MAX_EXHAUSTIVE = 12
SAMPLE_SIZE = 4096

_STATUS = {btcpp.NodeStatus.SUCCESS: Status.SUCCESS, btcpp.NodeStatus.FAILURE: Status.FAILURE,
           btcpp.NodeStatus.RUNNING: Status.RUNNING}


class _Harness:
    """One factory per vocabulary, with leaves that read ``state`` and record which actions ran."""

    def __init__(self, conditions: tuple[str, ...], actions: tuple[str, ...]):
        self.factory = btcpp.BehaviorTreeFactory()
        self.state: State = (False,) * len(conditions)
        self.started: list[tuple[int, str]] = []
        self.halted: set[int] = set()
        for index, name in enumerate(conditions):
            self.factory.register_simple_condition(name, self._condition(index))
        for name in actions:
            self.factory.register_simple_stateful_action(name, self._start(name), self._start(name), self._halt)

    def _condition(self, index: int):  # type: ignore[no-untyped-def]
        def check(_node: btcpp.TreeNode) -> btcpp.NodeStatus:
            return btcpp.NodeStatus.SUCCESS if self.state[index] else btcpp.NodeStatus.FAILURE
        return check

    def _start(self, name: str):  # type: ignore[no-untyped-def]
        def start(node: btcpp.TreeNode) -> btcpp.NodeStatus:
            self.started.append((node.uid(), name))
            return btcpp.NodeStatus.RUNNING
        return start

    def _halt(self, node: btcpp.TreeNode) -> None:
        self.halted.add(node.uid())

    def tick(self, tree: btcpp.Tree, state: State) -> tuple[Status, str | None]:
        """Tick a halted tree once in ``state``; the action is the first one started and not halted."""
        self.state = state
        self.started.clear()
        self.halted.clear()
        status = _STATUS[tree.tick_exactly_once()]
        ran = next((name for uid, name in self.started if uid not in self.halted), None)
        tree.halt_tree()
        return status, (ran if status is Status.RUNNING else None)


@functools.lru_cache(maxsize=32)
def _harness(conditions: tuple[str, ...], actions: tuple[str, ...]) -> _Harness:
    return _Harness(conditions, actions)


def domain_states(domain: Domain) -> Iterator[State]:
    """Every state when there are at most 2^12, else a fixed-seed sample of 4096."""
    n = len(domain.conditions)
    if n <= MAX_EXHAUSTIVE:
        yield from itertools.product((False, True), repeat=n)
        return
    rng = random.Random(20190101)
    for _ in range(SAMPLE_SIZE):
        yield tuple(rng.random() < 0.5 for _ in range(n))


def btcpp_tick(tree: Node, domain: Domain, states: list[State]) -> list[tuple[Status, str | None]]:
    """BehaviorTree.CPP's (status, running action) for each state, from our XML of ``tree``."""
    text = tree_to_xml(tree)  # first, so a name BT.CPP reserves is reported as such
    harness = _harness(domain.condition_names, domain.action_names)
    live = harness.factory.create_tree_from_text(text)
    return [harness.tick(live, state) for state in states]


def assert_matches_btcpp(tree: Node, domain: Domain) -> None:
    """BehaviorTree.CPP, loading our XML, returns our status and runs our action in every state."""
    unknown = sorted((condition_names(tree) - set(domain.condition_names))
                     | (action_names(tree) - set(domain.action_names)))
    assert not unknown, f"the tree uses names the domain does not define: {unknown}"
    compiled = compile_tree(tree, domain.condition_names)
    states = list(domain_states(domain))
    theirs = btcpp_tick(tree, domain, states)
    for state, their in zip(states, theirs, strict=False):
        ours = compiled(state)
        assert ours == their, (f"BehaviorTree.CPP gives {their[0].name} {their[1]} but teach gives "
                               f"{ours[0].name} {ours[1]} in state [{domain.describe(state)}] for\n"
                               f"{tree_to_xml(tree)}")
