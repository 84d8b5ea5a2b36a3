"""The teacher: optimal plans in the true model from random starts, as demonstrations."""

from __future__ import annotations

import random
from collections import deque

from foreign.model import Task
from foreign.sam import SamLearner
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


def safe_ceiling(task: Task, train: list[Demonstration], starts: list[int]) -> float:
    """The safe information ceiling: the share of ``starts`` from which the goal can be reached
    acting only on what ``train`` proves. An action is proved to run where every literal that held
    each time it (or, with forms, an action of its kind) was shown holds (SAM's preconditions;
    any other literal might be needed), and the task is proved done where every literal common
    to the goal states holds. A learner that never acts on a guess can, without questions,
    reach the goal from no more starts than this; ``ceiling`` counts a start whose plan uses
    only actions seen, whether or not it is safe to run them there."""
    sam = SamLearner(task.domain)
    for demo in train:
        sam.learn(demo)
    before: dict[int, list[int]] = {state: [] for state in task.reachable}
    for state in task.reachable:
        for after in sam.successors(state):
            if after != state and after in before:
                before[after].append(state)
    good = {state for state in task.reachable if sam.done(state)}
    queue = deque(good)
    while queue:
        for earlier in before[queue.popleft()]:
            if earlier not in good:
                good.add(earlier)
                queue.append(earlier)
    return sum(start in good for start in starts) / len(starts)
