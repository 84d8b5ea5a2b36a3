"""Random STRIPS domains that owe nothing to the learner's priors.

Assumptions (all of them; nothing else is drawn):

- ``n`` conditions ``c0..``, ``m`` actions ``a0..``, each action independent of the others;
- preconditions: 1 to 3 distinct conditions, each with a polarity drawn uniformly (true or
  false), so a precondition is as often a negative literal as a positive one, and an action
  needs its own effect not to hold yet only by chance;
- effects: 1 or 2 conditions made true and 0 or 1 made false, on conditions whose value the
  preconditions do not already fix to that value (every effect can change something);
- every one of the 2^n states is a state the world can be in (no invariants); a start is any
  state that is not a goal state and from which the goal can be reached;
- the goal: 1 to 3 distinct conditions, each with a uniformly drawn polarity;
- a draw is kept when at least 40% of all states are starts and the longest optimal plan
  has at least ``MIN_LONGEST`` steps (a task done in one step tests little); otherwise it is
  drawn again.

Unlike ``bench/random_domains.py`` nothing follows "not yet done" or "established by the step
before", the goal is not the last action's effect, and the teacher is breadth-first search.
"""

from __future__ import annotations

import random

from foreign.model import Model, Operator, Task, learner_domain

SIZES = ((6, 5), (8, 6), (10, 8))
MIN_START_SHARE = 0.4
MIN_LONGEST = 3
MAX_DRAWS = 10_000


def random_task(n: int, m: int, seed: int) -> Task:
    """The first kept draw for this size and seed."""
    rng = random.Random(f"strips-{n}x{m}-{seed}")
    for _draw in range(MAX_DRAWS):
        task = _draw_task(rng, n, m, f"strips-{n}x{m}")
        if task is not None:
            return task
    raise ValueError(f"no {n}x{m} domain kept in {MAX_DRAWS} draws")


def _draw_task(rng: random.Random, n: int, m: int, name: str) -> Task | None:
    operators = tuple(_operator(rng, n, f"a{j}") for j in range(m))
    goal_true, goal_false = _goal(rng, n)
    model = Model(tuple(f"c{i}" for i in range(n)), operators, goal_true, goal_false)
    phrases = {**{f"c{i}": f"c{i} holds" for i in range(n)}, **{o.name: f"do {o.name}" for o in operators}}
    task = Task(name, learner_domain(name, model, phrases), model, tuple(range(1 << n)))
    enough = len(task.starts()) >= MIN_START_SHARE * (1 << n)
    return task if enough and max(task.reachable.values()) >= MIN_LONGEST else None


def _operator(rng: random.Random, n: int, name: str) -> Operator:
    pre_true, pre_false = _literals(rng, n)
    add = _pick(rng, [i for i in range(n) if not pre_true >> i & 1], rng.randint(1, 2))
    delete = _pick(rng, [i for i in range(n) if not pre_false >> i & 1 and not add >> i & 1], rng.randint(0, 1))
    return Operator(name, pre_true, pre_false, add, delete)


def _pick(rng: random.Random, indices: list[int], count: int) -> int:
    return sum(1 << i for i in rng.sample(indices, min(count, len(indices))))


def _goal(rng: random.Random, n: int) -> tuple[int, int]:
    return _literals(rng, n)


def _literals(rng: random.Random, n: int) -> tuple[int, int]:
    """1 to 3 distinct conditions, each required true or false with equal chance (true, false masks)."""
    true = false = 0
    for index in rng.sample(range(n), rng.randint(1, 3)):
        if rng.random() < 0.5:
            true |= 1 << index
        else:
            false |= 1 << index
    return true, false
