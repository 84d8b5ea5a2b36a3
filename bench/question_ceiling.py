"""What the best few questions could do: a chooser that knows the teacher's answers (issue 18).

The safe learner's chooser (``teach.learn.safe_inquiry``) must predict the answer to a question
before it asks. This bench stand-in does not: before each question it tries every situation
where the robot now does nothing, with the teacher's real answer (``ReferenceTeacher``), and
keeps the one after which the robot does nothing in the fewest states of the domain. Greedy,
so an estimate, not a proof; but when it reaches a figure the chooser does not, the shortfall
is the chooser's prediction, not the questions' budget, and when it does not, no chooser asking
one situation at a time is likely to.

Used by ``bench_ball_pairs.py`` and ``bench_snacks_draws.py``: small domains only (every state
is tried, each on a copy of the learner).
"""

from __future__ import annotations

import copy

from oracle_answers import DONE, SKIP, ReferenceTeacher

from teach.domain import State
from teach.learn.learner import Learner
from teach.learn.situations import tree_does


def idle_states(learner: Learner, states: list[State]) -> int:
    """In how many of ``states`` the learner's tree does nothing (FAILURE)."""
    return sum(tree_does(learner, state) == "nothing" for state in states)


def knowing_the_answers(learner: Learner, teacher: ReferenceTeacher, budget: int) -> Learner:
    """``learner`` after up to ``budget`` questions chosen knowing their answers (a copy; the
    argument is not changed)."""
    states = list(teacher.does)  # every state of the domain
    learner = copy.deepcopy(learner)
    for _ in range(budget):
        best: tuple[int, Learner] | None = None
        for state in states:
            if teacher.does[state] == SKIP or state in learner.situations or tree_does(learner, state) != "nothing":
                continue
            trial = copy.deepcopy(learner)
            answer = None if teacher.does[state] == DONE else teacher.does[state]
            trial.answer_question(state, answer, answer, "a question chosen knowing its answer")
            idle = idle_states(trial, states)
            if best is None or idle < best[0]:
                best = (idle, trial)
        if best is None:
            break
        learner = best[1]
    return learner
