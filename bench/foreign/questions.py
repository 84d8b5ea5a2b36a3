"""Questions answered from the true model, through one adapter (``answer_question``).

The learner proposes a question with ``teach.learn.inquiry.next_question(learner, asked)``:

- a situation question (``question.state``): the answer is the teacher's action there, the
  first action of an optimal plan in the true model, or None ("done") where the goal holds,
  given as ``learner.teach_step``. A state the world cannot be in (not reachable in the true
  model) is answered "impossible" with ``learner.rule_out`` where the learner has it (free:
  not charged to the budget), and otherwise skipped and charged; a state from which the goal
  cannot be reached has no answer the teacher could show, so it is skipped and charged;
- the safe learner's "may I still do X here?" (``must-precondition``, ``question.action``) and
  "is the task done here?" (``must-goal``): yes where X can run in ``question.state`` in the
  true model (the true goal holds there), else the teacher's action there — a no to X and the
  label of that state (``learner.answer_question``); a no with nothing to show where the goal
  cannot be reached from there (``learner.settle(question, True, …)``). An impossible state is
  answered "impossible" as above.

Every answer records whether the tree changed.
"""

from __future__ import annotations

from dataclasses import dataclass

from foreign.model import Task
from teach.domain import State
from teach.learn.inquiry import SituationQuestion, next_question
from teach.learn.learner import Learner

MAX_FREE = 50
"""Free answers ("impossible") per call of ``ask``: a learner that keeps proposing them still ends."""


@dataclass(frozen=True)
class Answered:
    """One answer: the question's kind, what the teacher said, whether the tree changed, and
    whether it counted against the budget."""

    kind: str
    said: str
    changed: bool
    charged: bool = True


def answer_question(learner: Learner, question: SituationQuestion, task: Task, source: str) -> Answered:
    """Answer ``question`` from ``task``'s true model and give the answer to ``learner``."""
    kind = question.kind
    state = task.mask(question.state)
    if state not in task.reachable:
        learner.rule_out(question.state, source)
        return Answered(kind, "impossible", False, False)
    if kind.startswith("must-"):
        about = question.action if kind == "must-precondition" else None
        if may(task, about, state):
            update = learner.answer_question(question.state, about, about, source)
            return Answered(kind, "yes", update.tree_changed)
        if task.distance(state) is None:
            return Answered(kind, "no", learner.settle(question, True, source).tree_changed)
        best = task.best(state)
        update = learner.answer_question(question.state, about, None if best is None else best.name, source)
        return Answered(kind, "done" if best is None else best.name, update.tree_changed)
    if task.distance(state) is None:
        return Answered(kind, "no way to the goal (skipped)", False)
    best = task.best(state)
    update = learner.teach_step(question.state, None if best is None else best.name, source)
    return Answered(kind, "done" if best is None else best.name, update.tree_changed)


def may(task: Task, action: str | None, state: int) -> bool:
    """Can ``action`` run in ``state`` in the true model (``action`` None: does the true goal hold)?"""
    if action is None:
        return task.model.goal_holds(state)
    return task.model.by_name[action].applicable(state)


def ask(learner: Learner, task: Task, budget: int, prefix: str = "question",
        asked: list[State] | None = None) -> list[Answered]:
    """Up to ``budget`` charged answers to the learner's own questions, in the order it asks them.
    ``asked``: the situations asked about before (extended here), as a session keeps them for its
    whole length; without it only this call's are kept."""
    asked = [] if asked is None else asked
    seen: list[SituationQuestion] = []
    answers: list[Answered] = []
    charged = free = 0
    while charged < budget and free < MAX_FREE:
        question = next_question(learner, asked)
        if question is None or question in seen:
            break
        seen.append(question)
        asked.append(question.state)
        answer = answer_question(learner, question, task, f"{prefix} {len(answers) + 1}")
        answers.append(answer)
        charged += answer.charged
        free += not answer.charged
    return answers
