"""Questions answered from the true model, through one adapter (``answer_question``).

The learner proposes a question with ``teach.learn.inquiry.next_question(learner, asked)``:

- a situation question (``question.state``): the answer is the teacher's action there, the
  first action of an optimal plan in the true model, or None ("done") where the goal holds,
  given as ``learner.teach_step``. A state the world cannot be in (not reachable in the true
  model) is answered "impossible" with ``learner.rule_out`` where the learner has it (free:
  not charged to the budget), and otherwise skipped and charged; a state from which the goal
  cannot be reached has no answer the teacher could show, so it is skipped and charged;
- a yes/no question (``question.kind`` starting with "must-"): "must-precondition" asks
  whether the literal ``question.condition`` = ``question.value`` is a true precondition of
  ``question.action``, "must-goal" whether it is part of the true goal; answered with
  ``learner.settle(question, needed, source)``.

The yes/no kinds and ``rule_out`` are read with ``getattr``/``hasattr`` so the bench runs
against learners with and without them. Every answer records whether the tree changed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from foreign.model import Task
from teach.learn.inquiry import next_question

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


def answer_question(learner: Any, question: Any, task: Task, source: str) -> Answered:
    """Answer ``question`` from ``task``'s true model and give the answer to ``learner``."""
    kind = str(question.kind)
    if kind.startswith("must-"):
        yes = needed(task, kind, getattr(question, "action", None), question.condition,
                     bool(getattr(question, "value", True)))
        update = learner.settle(question, yes, source)
        return Answered(kind, "yes" if yes else "no", bool(update.tree_changed))
    state = task.mask(question.state)
    if state not in task.reachable:
        if hasattr(learner, "rule_out"):
            return Answered(kind, "impossible", bool(learner.rule_out(question.state, source).tree_changed), False)
        return Answered(kind, "impossible (skipped)", False)
    if task.distance(state) is None:
        return Answered(kind, "no way to the goal (skipped)", False)
    best = task.best(state)
    update = learner.teach_step(question.state, None if best is None else best.name, source)
    return Answered(kind, "done" if best is None else best.name, bool(update.tree_changed))


def needed(task: Task, kind: str, action: str | None, condition: str, value: bool) -> bool:
    """Is the literal ``condition`` = ``value`` part of the true goal ("must-goal") or a true
    precondition of ``action`` (any other "must-" kind)?"""
    index = task.model.conditions.index(condition)
    if kind == "must-goal":
        true, false = task.model.goal_true, task.model.goal_false
    else:
        operator = task.model.by_name[str(action)]
        true, false = operator.pre_true, operator.pre_false
    return bool((true if value else false) >> index & 1)


def ask(learner: Any, task: Task, budget: int, prefix: str = "question") -> list[Answered]:
    """Up to ``budget`` charged answers to the learner's own questions, in the order it asks them."""
    asked: list[Any] = []
    seen: list[Any] = []
    answers: list[Answered] = []
    charged = free = 0
    while charged < budget and free < MAX_FREE:
        question = next_question(learner, asked)
        if question is None or question in seen:
            break
        seen.append(question)
        asked.append(getattr(question, "state", question))
        answer = answer_question(learner, question, task, f"{prefix} {len(answers) + 1}")
        answers.append(answer)
        charged += answer.charged
        free += not answer.charged
    return answers
