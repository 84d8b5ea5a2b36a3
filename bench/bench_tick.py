"""Ticks per second of the 16-node Colledanchise tree (Fig. 2.5 without AskForHelp) over all
32 states, for our compiled tick, our traced tick, py_trees 2.x and BehaviorTree.CPP (through
behaviortreepy, with Python leaf callbacks), measured side by side in one run.

Run: .venv/bin/python bench/bench_tick.py

Targets (issue 2): the compiled tick at least 100x py_trees and at least 10x BehaviorTree.CPP.
The compiled tick is measured as compile_tree returns it (for a tree this small: the generated
straight-line function, since hashing a state for a memo lookup costs more than the tick),
with the memo table forced on and warm, and as the generated function called directly.
"""

from __future__ import annotations

import itertools
import sys
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

from conftest import colledanchise_tree  # noqa: E402

from teach.bt.nodes import Action, Condition, Fallback, Node, Sequence, Status  # noqa: E402
from teach.bt.tick import compile_tree, tick  # noqa: E402
from teach.bt.xml import tree_to_xml  # noqa: E402

NAMES = ("BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced")
STATES = [tuple(s) for s in itertools.product((False, True), repeat=len(NAMES))]


def rate(run_all_states: Callable[[], object], budget: float = 0.4) -> float:
    """Best ticks per second over 5 timed batches of whole passes over the 32 states."""
    passes = 1
    while True:  # grow the batch until one takes a measurable time
        start = time.perf_counter()
        for _ in range(passes):
            run_all_states()
        if time.perf_counter() - start > budget / 5:
            break
        passes *= 2
    best = 0.0
    for _ in range(5):
        start = time.perf_counter()
        for _ in range(passes):
            run_all_states()
        best = max(best, passes * len(STATES) / (time.perf_counter() - start))
    return best


def ours_compiled(tree: Node) -> tuple[dict[str, Callable[[], object]], list[tuple[Status, str | None]]]:
    """The compiled tick as compile_tree chooses it (no memo for a tree this small), with a
    warm memo table forced on, and the generated function called directly."""
    chosen = compile_tree(tree, NAMES)
    memoised = compile_tree(tree, NAMES, memoise=True)
    for state in STATES:
        memoised(state)

    def over_states(fn: Callable[[tuple[bool, ...]], object]) -> Callable[[], object]:
        def run() -> None:
            for state in STATES:
                fn(state)
        return run

    runs = {"teach compiled (as compile_tree chooses)": over_states(chosen),
            "teach compiled, memo forced on, warm": over_states(memoised),
            "teach compiled, generated fn, no memo": over_states(chosen.raw)}
    return runs, [chosen(s) for s in STATES]


def ours_traced(tree: Node) -> tuple[Callable[[], object], list[tuple[Status, str | None]]]:
    mappings = [dict(zip(NAMES, s, strict=True)) for s in STATES]

    def run() -> None:
        for mapping in mappings:
            tick(tree, mapping)

    return run, [(r.status, r.action) for r in (tick(tree, m) for m in mappings)]


def py_trees_tree(tree: Node) -> tuple[Callable[[], object], list[tuple[Status, str | None]]]:
    import py_trees

    world: dict[str, bool] = {}
    running: list[str] = []

    class Check(py_trees.behaviour.Behaviour):
        def update(self) -> py_trees.common.Status:
            return py_trees.common.Status.SUCCESS if world[self.name] else py_trees.common.Status.FAILURE

    class Act(py_trees.behaviour.Behaviour):
        def update(self) -> py_trees.common.Status:
            running.append(self.name)
            return py_trees.common.Status.RUNNING

    def build(node: Node) -> py_trees.behaviour.Behaviour:
        if isinstance(node, Condition):
            return Check(node.name)
        if isinstance(node, Action):
            return Act(node.name)
        kids = [build(k) for k in node.children]  # type: ignore[union-attr]
        if isinstance(node, Sequence):
            return py_trees.composites.Sequence("→", memory=False, children=kids)
        if isinstance(node, Fallback):
            return py_trees.composites.Selector("?", memory=False, children=kids)
        raise TypeError(f"no py_trees equivalent built here for {node!r}")

    root = build(tree)
    statuses = {py_trees.common.Status.SUCCESS: Status.SUCCESS, py_trees.common.Status.FAILURE: Status.FAILURE,
                py_trees.common.Status.RUNNING: Status.RUNNING}
    mappings = [dict(zip(NAMES, s, strict=True)) for s in STATES]

    def run() -> None:
        for mapping in mappings:
            world.update(mapping)
            root.tick_once()

    results = []
    for mapping in mappings:
        world.update(mapping)
        running.clear()
        root.tick_once()
        status = statuses[root.status]
        results.append((status, running[0] if status is Status.RUNNING else None))
    return run, results


def btcpp_tree(tree: Node) -> tuple[Callable[[], object], list[tuple[Status, str | None]]]:
    import behaviortreepy as btcpp

    factory = btcpp.BehaviorTreeFactory()
    state: list[tuple[bool, ...]] = [STATES[0]]
    started: list[str] = []
    for index, name in enumerate(NAMES):
        factory.register_simple_condition(
            name, lambda _node, i=index: btcpp.NodeStatus.SUCCESS if state[0][i] else btcpp.NodeStatus.FAILURE)
    for name in sorted({n.name for n in _leaves(tree, Action)}):
        def start(_node: btcpp.TreeNode, name: str = name) -> btcpp.NodeStatus:
            started.append(name)
            return btcpp.NodeStatus.RUNNING
        factory.register_simple_stateful_action(name, start, start)
    live = factory.create_tree_from_text(tree_to_xml(tree))
    statuses = {btcpp.NodeStatus.SUCCESS: Status.SUCCESS, btcpp.NodeStatus.FAILURE: Status.FAILURE,
                btcpp.NodeStatus.RUNNING: Status.RUNNING}

    def run() -> None:
        for s in STATES:
            state[0] = s
            live.tick_exactly_once()

    results = []
    for s in STATES:
        state[0] = s
        started.clear()
        status = statuses[live.tick_exactly_once()]
        results.append((status, started[-1] if status is Status.RUNNING else None))
    return run, results


def _leaves(tree: Node, kind: type) -> list[Node]:
    from teach.bt.nodes import walk
    return [n for n in walk(tree) if isinstance(n, kind)]


def main() -> None:
    tree = colledanchise_tree()
    compiled_runs, expected = ours_compiled(tree)
    traced, traced_results = ours_traced(tree)
    pt, pt_results = py_trees_tree(tree)
    bt, bt_results = btcpp_tree(tree)
    for label, results in (("traced", traced_results), ("py_trees", pt_results), ("BehaviorTree.CPP", bt_results)):
        if results != expected:
            raise SystemExit(f"{label} does not tick the tree like the compiled tick; the comparison would be unfair")
    rates = {
        **{label: rate(run) for label, run in compiled_runs.items()},
        "teach traced recursive tick": rate(traced),
        "py_trees 2.x (memory=False)": rate(pt),
        "BehaviorTree.CPP v4 (behaviortreepy)": rate(bt),
    }
    print(f"Colledanchise tree, 16 nodes, all {len(STATES)} states; ticks per second (best of 5)")
    for label, value in rates.items():
        print(f"  {label:42s} {value:14,.0f}")
    pt_rate, bt_rate = rates["py_trees 2.x (memory=False)"], rates["BehaviorTree.CPP v4 (behaviortreepy)"]
    print("ratios                                      vs py_trees   vs BT.CPP   (targets >= 100x, >= 10x)")
    for label in (*compiled_runs, "teach traced recursive tick"):
        print(f"  {label:42s} {rates[label] / pt_rate:9.1f}x {rates[label] / bt_rate:10.1f}x")


if __name__ == "__main__":
    main()
