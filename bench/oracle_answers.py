"""Answering a learner's questions from a reference tree: the one place the benches do it.

A reference tree is a teacher who knows what they want. Asked "what should I do here?", they
do what the tree does in that state. Asked a yes/no question (a kind starting with "must-"),
they answer from everything the tree does anywhere:

- ``must-precondition`` (``action``, ``condition``, ``value``): must ``condition`` have
  ``value`` for ``action``? Not needed if the tree ever does ``action`` in a state where it
  has the other value; needed otherwise.
- ``must-goal`` (``condition``, ``value``): is it part of the goal? Not needed if the tree
  ever says "done" in a state where it has the other value.

Question fields are read with ``getattr``, and yes/no answers go to ``learner.settle``, so
this works with learners that only ask situation questions and with those that also ask
yes/no ones. Every answer records whether it changed the tree (``Update.tree_changed``).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from teach.bt.nodes import Node, Status
from teach.bt.tick import compile_tree
from teach.domain import Domain, State
from teach.learn.inquiry import next_question
from teach.learn.learner import Learner

DONE = "done"
SKIP = "skip"
MUST = "must-"


@dataclass(frozen=True)
class Answered:
    """One answered question: its kind, the answer given, and whether the tree changed."""

    kind: str
    answer: str
    tree_changed: bool


class ReferenceTeacher:
    """What a reference tree does in every state of a domain (a table built once)."""

    def __init__(self, tree: Node, domain: Domain):
        compiled = compile_tree(tree, domain.condition_names)
        self.domain = domain
        self.does: dict[State, str] = {}
        for state in itertools.product((False, True), repeat=len(domain.conditions)):
            status, action = compiled(state)
            self.does[state] = action if status is Status.RUNNING and action else \
                DONE if status is Status.SUCCESS else SKIP

    def precondition_needed(self, action: str, condition: str, value: bool) -> bool:
        """Never does ``action`` where ``condition`` is not ``value``."""
        index = self.domain.index(condition)
        return not any(does == action and state[index] != value for state, does in self.does.items())

    def goal_needed(self, condition: str, value: bool) -> bool:
        """Never says done where ``condition`` is not ``value``."""
        index = self.domain.index(condition)
        return not any(does == DONE and state[index] != value for state, does in self.does.items())


def answer(learner: Learner, question: Any, teacher: ReferenceTeacher, source: str) -> Answered:
    """Answer one learner question from ``teacher`` and teach the learner the answer."""
    kind = str(getattr(question, "kind", ""))
    if kind.startswith(MUST):
        value = bool(getattr(question, "value", True))
        condition = str(question.condition)
        if kind == "must-precondition":
            needed = teacher.precondition_needed(str(question.action), condition, value)
        else:
            needed = teacher.goal_needed(condition, value)
        settle = getattr(learner, "settle")  # noqa: B009 (yes/no kinds only: not every Learner has it)
        update = settle(question, needed, source)
        return Answered(kind, "yes" if needed else "no", bool(update.tree_changed))
    state = tuple(question.state)
    does = teacher.does[state]
    if does == SKIP:  # the teacher does not know either: charged, nothing learned
        return Answered(kind, SKIP, False)
    update = learner.teach_step(state, None if does == DONE else does, source)
    return Answered(kind, does, bool(update.tree_changed))


def ask(learner: Learner, teacher: ReferenceTeacher, budget: int) -> Iterator[Answered]:
    """Up to ``budget`` questions, each answered and taught before the next is chosen; yields
    after each answer, so a caller can measure the tree after 1, 2, ... questions."""
    asked: list[State] = []
    for number in range(1, budget + 1):
        question = next_question(learner, asked)
        if question is None:
            return
        state = getattr(question, "state", None)
        if state is not None:
            asked.append(tuple(state))
        yield answer(learner, question, teacher, f"question {number}")


def unchanged_share(answers: list[Answered]) -> float:
    """The share of answers that changed nothing in the tree (0 when none was given)."""
    return sum(not a.tree_changed for a in answers) / len(answers) if answers else 0.0
