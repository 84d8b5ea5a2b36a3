"""Replay speed: 10,000 demonstrations of a random 20-condition, 10-action domain against a
random tree, through ``teach.replay.replay`` (compiling included), with a fixed seed.

Run: .venv/bin/python bench/bench_replay.py [--seed 7]

The demonstrations are produced by running the tree itself in the domain (actions set their
ramifications, with occasional external changes), so every replay walks the whole
demonstration instead of stopping at the first line; the benchmark checks that all of them
are reproduced. Target (issue 2): under 0.25 s for the 10,000.
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, size  # noqa: E402
from teach.bt.tick import compile_tree  # noqa: E402
from teach.demos import Demonstration, Step  # noqa: E402
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, ActionDef, ConditionDef, Domain, Literal  # noqa: E402
from teach.replay import replay  # noqa: E402

CONDITIONS, ACTIONS, DEMOS, MAX_LINES = 20, 10, 10_000, 25


def random_domain(rng: random.Random) -> Domain:
    names = [f"C{i:02d}" for i in range(CONDITIONS)]

    def literals(count: int) -> tuple[Literal, ...]:
        return tuple(Literal(name, rng.random() < 0.7) for name in sorted(rng.sample(names, count)))

    actions = tuple(ActionDef(i + 1, f"A{i:02d}", pre=literals(rng.randint(1, 3)), ram=literals(rng.randint(1, 2)))
                    for i in range(ACTIONS))
    return Domain("random", tuple(ConditionDef(n) for n in names), actions, literals(3))


def random_tree(rng: random.Random, domain: Domain, depth: int = 4) -> Node:
    """A tree shaped like a learned one: mostly Sequences and Fallbacks over guarded actions."""
    if depth == 0 or rng.random() < 0.25:
        if rng.random() < 0.6:
            return Condition(rng.choice(domain.condition_names))
        return Action(rng.choice(domain.action_names))
    kids = tuple(random_tree(rng, domain, depth - 1) for _ in range(rng.randint(2, 4)))
    roll = rng.random()
    if roll < 0.45:
        return Sequence(kids)
    if roll < 0.9:
        return Fallback(kids)
    if roll < 0.95:
        return Inverter(kids[0])
    return Parallel(kids, rng.randint(1, len(kids)))


def demonstrations(rng: random.Random, domain: Domain, tree: Node) -> list[Demonstration]:
    """Run the tree from random states: each line is what the tree did, as a recorder would write it."""
    compiled = compile_tree(tree, domain.condition_names)
    index = {name: i for i, name in enumerate(domain.condition_names)}
    demos = []
    for number in range(DEMOS):
        state = [rng.random() < 0.5 for _ in range(CONDITIONS)]
        steps: list[Step] = []
        while len(steps) < MAX_LINES:
            if steps and rng.random() < 0.1:  # somebody else changes the world
                steps.append(Step(tuple(state), EXTERNAL_ACTION, len(steps) + 1))
                flip = rng.randrange(CONDITIONS)
                state[flip] = not state[flip]
                continue
            status, action = compiled(tuple(state))
            if action is None:
                if status.name == "SUCCESS":
                    steps.append(Step(tuple(state), GOAL_ACTION, len(steps) + 1))
                break
            steps.append(Step(tuple(state), domain.action(action).id, len(steps) + 1))
            for literal in domain.action(action).ram:
                state[index[literal.name]] = literal.value
        if steps and steps[-1].action == EXTERNAL_ACTION:
            steps.pop()
        if steps:
            demos.append(Demonstration(f"d{number:05d}", tuple(steps)))
    return demos


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    domain = random_domain(rng)
    tree = random_tree(rng, domain)
    while size(tree) < 30:  # a tree of learned size, not a single leaf
        tree = random_tree(rng, domain)
    demos = demonstrations(rng, domain, tree)
    lines = sum(len(d.steps) for d in demos)
    times = []
    for _ in range(5):
        start = time.perf_counter()
        report = replay(tree, domain, demos)
        times.append(time.perf_counter() - start)
        if report.reproduced != len(demos):
            raise SystemExit(f"only {report.summary()}: the generated demonstrations should all be reproduced")
    print(f"random domain: {CONDITIONS} conditions, {ACTIONS} actions; tree of {size(tree)} nodes; "
          f"{len(demos)} demonstrations, {lines} lines (seed {args.seed})")
    print(f"replay, compile included: first {times[0]:.3f} s, median {statistics.median(times):.3f} s, "
          f"best {min(times):.3f} s  (target < 0.25 s)")
    print(f"  {report.summary()}, {lines / statistics.median(times):,.0f} lines per second")
    ticked = [step.state for demo in demos for step in demo.steps if step.action != EXTERNAL_ACTION]
    tick_times = []
    for _ in range(5):
        start = time.perf_counter()
        compiled = compile_tree(tree, domain.condition_names)
        for state in ticked:
            compiled(state)
        tick_times.append(time.perf_counter() - start)
    print(f"  of which compiling and ticking the {len(ticked)} lines alone: median "
          f"{statistics.median(tick_times):.3f} s (the rest is replay's per-line bookkeeping)")


if __name__ == "__main__":
    main()
