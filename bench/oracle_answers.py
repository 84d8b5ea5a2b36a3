"""Answering a learner's questions from a reference tree: the one place the benches do it.

A reference tree is a teacher who knows what they want. Asked "what should I do here?", they
do what the tree does in that state. Asked the safe learner's "may I still do X here?" (kind
``must-precondition``) or "is the task done here?" (``must-goal``), they answer as a session's
teacher does: yes if the tree does X (says done) there, otherwise with what the tree does there
(``Learner.answer_question``: a no to X, and the label of that state).

Every answer records whether it changed the tree (``Update.tree_changed``).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass

from teach.bt.nodes import Node, Status
from teach.bt.tick import compile_tree
from teach.domain import Domain, State
from teach.learn.inquiry import SituationQuestion, next_question
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


def answer(learner: Learner, question: SituationQuestion, teacher: ReferenceTeacher, source: str) -> Answered:
    """Answer one learner question from ``teacher`` and teach the learner the answer."""
    kind = question.kind
    state = tuple(question.state)
    does = teacher.does[state]
    if does == SKIP:  # the teacher does not know either: charged, nothing learned
        return Answered(kind, SKIP, False)
    answer = None if does == DONE else does
    if kind.startswith(MUST):
        about = question.action if kind == "must-precondition" else None
        update = learner.answer_question(state, about, answer, source)
        return Answered(kind, "yes" if answer == about else does, update.tree_changed)
    update = learner.teach_step(state, answer, source)
    return Answered(kind, does, update.tree_changed)


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
