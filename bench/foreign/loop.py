"""The session loop (issue 18, item 3): the robot runs, the teacher corrects it where it goes wrong.

Each round the robot runs its current tree in the true model from a random start that is not
held out (starts may repeat: the robot may be put in the same place again). Where the run ends
stuck, unsafe, in a loop or with a wrong "done", the teacher demonstrates an optimal plan from
the state where it went wrong (only a goal line where a loop went through the goal without
saying "done"; from the run's start if that state cannot reach the goal) and the learner
learns it (``update``); then the learner may ask up to ``questions`` questions, answered from
the true model (``foreign.questions``). After every round that changed the tree, the robot
runs from every held-out start; the loop ends when it reaches the goal (safely: a run stops
at the first unsafe action) from ``TARGET`` of them, or after ``MAX_ROUNDS`` rounds. The
held-out starts are those of ``bench_safety.py``'s tables for the same seed.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from foreign.judge import Outcomes, judge, run
from foreign.model import Task
from foreign.questions import Answered, ask
from foreign.teaching import demonstration, split_starts
from teach.bt.tick import compile_tree
from teach.domain import Domain, State

TARGET = 0.95
MAX_ROUNDS = 60
TRAINING_STARTS = 20
"""As in ``bench_safety.py``'s largest training set, so both hold out the same starts."""


@dataclass
class Progress:
    """What the teacher gave until the loop ended, and the robot's held-out outcomes then."""

    rounds: int = 0
    demonstrations: int = 0
    lines: int = 0
    answers: list[Answered] = field(default_factory=list)
    outcomes: Outcomes | None = None
    hit: bool = False

    @property
    def questions(self) -> int:
        return sum(a.charged for a in self.answers)


def session_loop(task: Task, seed: int, make: Callable[[Domain], Any], questions: int, held_out: int,
                 max_rounds: int = MAX_ROUNDS) -> Progress:
    _train, tests = split_starts(task, seed, TRAINING_STARTS, held_out)
    held = set(tests)
    pool = [s for s in task.starts() if s not in held]
    rng = random.Random(f"{task.name}-loop-{seed}")
    learner = make(task.domain)
    progress = Progress()
    names = task.domain.condition_names
    asked: list[State] = []  # as a session's: a situation asked about once is not asked again
    for number in range(1, max_rounds + 1):
        start = rng.choice(pool)
        progress.rounds = number
        before = learner.tree
        ended = run(task, compile_tree(before, names), start)
        if ended.outcome != "reached":
            where = ended.state if task.distance(ended.state) is not None else start
            demo = demonstration(task, where, f"round{number}")
            learner.update(demo, f"round {number}")
            progress.demonstrations += 1
            progress.lines += len(demo.steps)
        if questions:
            progress.answers += ask(learner, task, questions, f"round {number} question", asked)
        if progress.outcomes is None or learner.tree != before:
            progress.outcomes = judge(task, learner.tree, tests)
        if progress.outcomes.share("reached") >= TARGET:
            progress.hit = True
            break
    return progress
