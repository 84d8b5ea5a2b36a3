"""Pruning time against tree size, on random trees shaped like the thesis's.

Example:
    .venv/bin/python bench/bench_prune.py

Trees grow as PA-BT grows them (a condition replaced by its atomic BT, Fig. 4.2) from random
action models, 50 to 2000 nodes. Each size is pruned over 12 and 14 conditions (both stages;
14 is the largest the exact stage takes, 16384 states) and over 20 (the literal stage alone),
side by side in one run. Target: a 500-node tree in under a second.
"""

from __future__ import annotations

import random
import statistics
import time

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Sequence, replace_node, size, walk
from teach.domain import Literal
from teach.learn.prune import prune

SIZES = (50, 100, 200, 500, 1000, 2000)
TARGET_SIZE, TARGET_SECONDS = 500, 1.0


def literal_node(literal: Literal) -> Node:
    return Condition(literal.name) if literal.value else Inverter(Condition(literal.name))


def thesis_like(rng: random.Random, conditions: int, actions: int, nodes: int
                ) -> tuple[Node, dict[str, tuple[Literal, ...]]]:
    """A PA-BT style tree of about ``nodes`` nodes and the random action model it came from."""
    names = [f"C{i}" for i in range(conditions)]
    model = {}
    for a in range(actions):
        chosen = rng.sample(names, 4)
        pre = tuple(Literal(n, rng.random() < 0.6) for n in chosen[:rng.randint(1, 3)])
        model[f"A{a}"] = (pre, (Literal(chosen[3], rng.random() < 0.7),))
    tree: Node = Sequence(tuple(Condition(n) for n in rng.sample(names, 3)))
    while size(tree) < nodes:
        leaf = rng.choice([n for n in walk(tree) if isinstance(n, Condition)])
        action = rng.choice(sorted(model))
        pre, _ = model[action]
        body = Sequence((*map(literal_node, pre), Action(action)))
        new = replace_node(tree, leaf.uid, Fallback((Condition(leaf.name), body)))
        assert new is not None
        tree = new
    return tree, {a: ram for a, (_, ram) in model.items()}


def seconds(tree: Node, ramifications: dict[str, tuple[Literal, ...]], repeat: int = 3) -> tuple[float, int]:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        pruned = prune(tree, ramifications)
        times.append(time.perf_counter() - start)
    return statistics.median(times), size(pruned)


def main() -> None:
    rng = random.Random(7)
    print(f"{'nodes':>6} {'12 cond: s':>11} {'after':>6} {'14 cond: s':>11} {'after':>6} "
          f"{'20 cond: s':>11} {'after':>6} {'ms/node':>8}")
    at_target = None
    for nodes in SIZES:
        tree12, ram12 = thesis_like(rng, 12, 10, nodes)
        tree20, ram20 = thesis_like(rng, 20, 14, nodes)
        tree14, ram14 = thesis_like(rng, 14, 12, nodes)
        t12, after12 = seconds(tree12, ram12)
        t20, after20 = seconds(tree20, ram20)
        t14, after14 = seconds(tree14, ram14)
        print(f"{size(tree12):>6} {t12:>11.4f} {after12:>6} {t14:>11.4f} {after14:>6} {t20:>11.4f} {after20:>6} "
              f"{1000 * max(t12, t14, t20) / size(tree12):>8.3f}")
        if nodes == TARGET_SIZE:
            at_target = max(t12, t14, t20)
    assert at_target is not None
    print(f"{TARGET_SIZE}-node tree: {at_target:.3f} s, {at_target / TARGET_SECONDS:.2f} of the "
          f"{TARGET_SECONDS:.0f} s target")


if __name__ == "__main__":
    main()
