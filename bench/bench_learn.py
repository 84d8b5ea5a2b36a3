"""Learner speed on random domains: batch specialization, online updates, pruning, PA-BT.

Run:  .venv/bin/python bench/bench_learn.py

Demonstrations come from a random hidden sequential behaviour (as in tests/test_specialize.py):
action i runs unless its guard (1-2 literals over its own conditions) holds, running it makes
the guard hold and flips some noise conditions; 10% of steps are external perturbations.
Targets (issue 3): 1,000 demonstrations with 20 conditions and 20 actions specialized (and
pruned) in under 2 s; one online update in under 10 ms. Everything is measured in this run,
side by side, and printed as measured/target ratios (below 1 is within target).
"""

from __future__ import annotations

import random
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from teach.bt.nodes import size  # noqa: E402
from teach.demos import Demonstration, Step  # noqa: E402
from teach.domain import ActionDef, ConditionDef, Domain, Literal  # noqa: E402
from teach.learn.order import action_order  # noqa: E402
from teach.learn.pabt import expand  # noqa: E402
from teach.learn.specialize import Specializer  # noqa: E402

BATCH_TARGET_S = 2.0
UPDATE_TARGET_MS = 10.0


def hidden_world(conditions: int, actions: int, demos: int, seed: int) -> tuple[Domain, list[Demonstration]]:
    rng = random.Random(seed)
    order = list(range(conditions))
    rng.shuffle(order)
    actions = min(actions, conditions)
    widths = [1] * actions
    for i in rng.sample(range(actions), min(actions, conditions - actions)):
        widths[i] = 2
    guards, used = [], 0
    for width in widths:
        guards.append([(c, rng.random() < 0.5) for c in order[used:used + width]])
        used += width
    noise = order[used:]
    flips = [rng.sample(noise, min(len(noise), rng.randint(0, 2))) for _ in guards]
    names = [f"C{i}" for i in range(conditions)]
    domain = Domain("bench", tuple(ConditionDef(n) for n in names),
                    tuple(ActionDef(i + 1, f"A{i}", pre=tuple(Literal(names[c], not v) for c, v in g),
                                    ram=tuple(Literal(names[c], v) for c, v in g)) for i, g in enumerate(guards)))

    def policy(state: list[bool]) -> int | None:
        return next((i for i, g in enumerate(guards) if not all(state[c] == v for c, v in g)), None)

    result = []
    for number in range(demos):
        state = [rng.random() < 0.5 for _ in range(conditions)]
        steps: list[Step] = []
        while True:
            if steps and rng.random() < 0.1:
                steps.append(Step(tuple(state), -1, len(steps) + 1))
                flip = rng.randrange(conditions)
                state[flip] = not state[flip]
                continue
            i = policy(state)
            steps.append(Step(tuple(state), 0 if i is None else i + 1, len(steps) + 1))
            if i is None:
                break
            for c, v in guards[i]:
                state[c] = v
            for c in flips[i]:
                state[c] = not state[c]
        result.append(Demonstration(f"d{number:05d}", tuple(steps), Path(f"d{number:05d}.csv")))
    return domain, result


def batch(domain: Domain, demos: list[Demonstration]) -> tuple[float, float, Specializer]:
    """Seconds for the order, seconds for all updates, and the learner."""
    start = time.perf_counter()
    order = action_order(domain, demos)
    ordered = time.perf_counter()
    learner = Specializer(domain, order)
    for demo in demos:
        learner.update(demo)
    _ = learner.tree
    return ordered - start, time.perf_counter() - ordered, learner


def online_update_ms(domain: Domain, demos: list[Demonstration], fresh: int = 200) -> tuple[float, float]:
    """Median and worst time of one update after all but the last ``fresh`` demonstrations, in ms
    (the tree is rebuilt after each update, as a session would use it)."""
    learner = Specializer(domain)
    for demo in demos[:-fresh]:
        learner.update(demo)
    times = []
    for demo in demos[-fresh:]:
        start = time.perf_counter()
        learner.update(demo)
        _ = learner.tree
        times.append((time.perf_counter() - start) * 1000)
    return statistics.median(times), max(times)


def prune_seconds(domain: Domain, tree) -> tuple[float, int] | None:  # type: ignore[no-untyped-def]
    try:
        from teach.learn.prune import prune
    except ImportError:
        return None
    start = time.perf_counter()
    pruned = prune(tree, {a.name: a.ram for a in domain.actions})
    return time.perf_counter() - start, size(pruned)


def main() -> None:
    print("Specialization (Approach 3) on random hidden behaviours; times are wall clock on this machine.\n")
    domain, demos = hidden_world(20, 20, 11_000, seed=1)
    steps = sum(len(d.steps) for d in demos[:1000])
    order_s, update_s, learner = batch(domain, demos[:1000])
    pruned = prune_seconds(domain, learner.tree)
    total = order_s + update_s + (pruned[0] if pruned else 0.0)
    median_ms, worst_ms = online_update_ms(domain, demos[:1200])
    print("Targets (20 conditions, 20 actions)")
    print(f"  batch: 1,000 demonstrations ({steps} lines): order {order_s * 1000:.0f} ms + updates "
          f"{update_s * 1000:.0f} ms" + (f" + pruning {pruned[0] * 1000:.0f} ms ({size(learner.tree)} -> "
                                         f"{pruned[1]} nodes)" if pruned else " (no teach.learn.prune)")
          + f" = {total:.3f} s   ratio to {BATCH_TARGET_S:g} s target: {total / BATCH_TARGET_S:.2f}")
    print(f"  online update after 1,000 demonstrations: median {median_ms:.2f} ms, worst {worst_ms:.2f} ms"
          f"   ratio to {UPDATE_TARGET_MS:g} ms target: {median_ms / UPDATE_TARGET_MS:.2f} (worst "
          f"{worst_ms / UPDATE_TARGET_MS:.2f})")

    print("\nTime vs demonstrations (20 conditions, 20 actions)")
    print(f"  {'demos':>6} {'lines':>7} {'order ms':>9} {'updates ms':>11} {'us/line':>8} {'nodes':>6}")
    for count in (10, 100, 1_000, 10_000):
        part = demos[:count]
        lines = sum(len(d.steps) for d in part)
        order_s, update_s, learner = batch(domain, part)
        print(f"  {count:>6} {lines:>7} {order_s * 1000:>9.1f} {update_s * 1000:>11.1f} "
              f"{update_s / lines * 1e6:>8.1f} {size(learner.tree):>6}")

    print("\nTime vs conditions (1,000 demonstrations; actions = min(20, conditions))")
    print(f"  {'conds':>6} {'actions':>7} {'updates ms':>11} {'us/line':>8} {'update ms':>10} {'nodes':>6}")
    for conditions in (5, 10, 20, 30):
        cdomain, cdemos = hidden_world(conditions, 20, 1_200, seed=conditions)
        lines = sum(len(d.steps) for d in cdemos[:1000])
        _, update_s, learner = batch(cdomain, cdemos[:1000])
        median_ms, _ = online_update_ms(cdomain, cdemos)
        print(f"  {conditions:>6} {len(cdomain.actions):>7} {update_s * 1000:>11.1f} "
              f"{update_s / lines * 1e6:>8.1f} {median_ms:>10.3f} {size(learner.tree):>6}")

    print("\nPA-BT (Approach 1) on the hidden model, 20 conditions and 20 actions, every guard a goal")
    goal = [lit for a in domain.actions for lit in a.ram]
    start = time.perf_counter()
    generations = expand(domain, goal)
    print(f"  {len(generations)} generations, {size(generations[-1])} nodes in "
          f"{(time.perf_counter() - start) * 1000:.0f} ms")


if __name__ == "__main__":
    main()
