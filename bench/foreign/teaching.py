"""The teacher: optimal plans in the true model from random starts, as demonstrations."""

from __future__ import annotations

import random

from foreign.model import Task
from teach.demos import Demonstration, Step
from teach.domain import GOAL_ACTION


def split_starts(task: Task, seed: int, train: int, held_out: int) -> tuple[list[int], list[int]]:
    """``train`` training starts and ``held_out`` held-out starts, disjoint, drawn from every start
    of the task. Where the world has too few starts for both, at least half of them are held
    out and training starts repeat (a teacher may show the same start twice)."""
    rng = random.Random(f"{task.name}-{seed}")
    starts = task.starts()
    rng.shuffle(starts)
    held = min(held_out, len(starts) - min(train, len(starts) // 2))
    tests, pool = starts[:held], starts[held:]
    chosen = pool[:train] + [rng.choice(pool) for _ in range(train - len(pool))]
    return chosen, tests


def demonstration(task: Task, start: int, name: str) -> Demonstration:
    """The teacher's optimal plan from ``start``: its transitions, then a goal line (action 0)."""
    plan = task.plan(start)
    if plan is None:
        raise ValueError(f"{task.name}: the goal cannot be reached from {task.domain.describe(task.state(start))}")
    steps: list[Step] = []
    state = start
    for operator in plan:
        steps.append(Step(task.state(state), task.domain.action(operator.name).id, len(steps) + 1))
        state = operator.apply(state)
    steps.append(Step(task.state(state), GOAL_ACTION, len(steps) + 1))
    return Demonstration(name, tuple(steps))


def ceiling(task: Task, train: list[Demonstration], starts: list[int]) -> float:
    """The information ceiling: the share of ``starts`` whose optimal plan uses only actions seen in training."""
    seen = {task.domain.action(a).name for d in train for a in d.actions}
    plans = [task.plan(s) or [] for s in starts]
    return sum({o.name for o in plan} <= seen for plan in plans) / len(starts)
