"""The session's learner, and everything the session does with what it learns: the tree pruned
for display, the generation files, the next question, updates described in words.

This is the one module to change to give the session another default learner. A learner is
built by ``make_learner(domain)`` and must offer what ``Learner`` lists; its updates what
``teach.session.describe.describe_update`` reads (``inserted``, ``removed``, ``added``).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from teach.bt.nodes import Action, Condition, Node, walk
from teach.bt.xml import tree_to_xml
from teach.demos import Demonstration
from teach.dialogue.questions import Answer, Question, select_question
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State
from teach.observe.hook import Observer
from teach.session.describe import describe_update, literals_label, removed_names
from teach.session.store import SessionStore

if TYPE_CHECKING:
    from teach.learn.specialize import Update


class Learner(Protocol):
    """What the session needs from a learner (``teach.learn.specialize.Specializer`` today)."""

    domain: Domain

    @property
    def tree(self) -> Node:
        """The whole learned tree, as it runs."""

    @property
    def order(self) -> Sequence[str]:
        """The actions learned so far; empty while there is no behaviour yet."""

    def update(self, demo: Demonstration, source: str | None = None) -> Update:
        """Learn one more demonstration; ``LearnError`` (with a ``kind``) when it cannot."""

    def teach_step(self, state: State, action: str | None, source: str) -> Update:
        """Learn one labelled situation (None: the task is done there)."""

    def explain(self, uid: int) -> str:
        """Why node ``uid`` is (or was) in the tree."""

    def guards(self, action: str) -> Sequence:
        """The guards in front of an action: each with a ``uid``, its ``literals``, the situations
        that need it (``needed_by``) and ``str()`` as literals. The question selector also
        deep-copies the learner to try each possible answer on the copy."""


def make_learner(domain: Domain) -> Learner:
    from teach.learn.specialize import Specializer

    return Specializer(domain)


class Learning:
    """One session's learner with the demonstrations and labels it learned from."""

    def __init__(self, domain: Domain, store: SessionStore, observer: Observer):
        self.domain = domain
        self.store = store
        self.observer = observer
        self.restart()

    def restart(self) -> None:
        """Forget everything learned (an undo or a resume then learns the journal again)."""
        self.learner = make_learner(self.domain)
        self.demos: list[Demonstration] = []
        self.labels: dict[State, Answer] = {}
        self.asked: set[State] = set()
        self.pruned: Node | None = None
        self.generation = self.store.last_generation()

    @property
    def has_behaviour(self) -> bool:
        return bool(self.learner.order)

    @property
    def tree(self) -> Node:
        """The unpruned tree: what runs (pruning assumes actions have only the effects seen so far)."""
        return self.learner.tree

    # --- learning -------------------------------------------------------------------------

    def learn_demonstration(self, demo: Demonstration, source: str | None) -> Update:
        """Learn and keep a demonstration; ``LearnError`` leaves everything as it was."""
        update = self.learner.update(demo, source=source)
        self.demos.append(demo)
        for step in demo.steps:
            if step.action == GOAL_ACTION:
                self.labels[step.state] = None
            elif step.action != EXTERNAL_ACTION:
                self.labels[step.state] = self.domain.action(step.action).name
        return update

    def learn_answer(self, state: State, answer: str | None, source: str) -> Update:
        """Learn what to do in an asked-about situation; ``LearnError`` when it contradicts."""
        update = self.learner.teach_step(state, answer, source=source)
        self.labels[state] = answer
        return update

    def next_question(self, seed: int) -> Question | None:
        return select_question(self.learner, self.demos, self.labels, self.asked, seed)

    # --- results --------------------------------------------------------------------------

    def prune(self) -> Node:
        """The learner's tree pruned for display, using the effects the demonstrations show
        (it behaves as the unpruned tree in every state)."""
        from teach.learn.model import detect_model
        from teach.learn.prune import prune, ramifications_of

        self.pruned = prune(self.learner.tree, ramifications_of(detect_model(self.domain, self.demos)))
        return self.pruned

    def save_generation(self, tree: Node, reason: str) -> Path:
        """Write the next ``gen-NN.xml`` (never overwriting a kept one) and report it."""
        self.generation = self.store.last_generation() + 1
        path = self.store.write_generation(self.generation, tree)
        self.observer.on_tree(self.generation, tree, tree_to_xml(tree), f"generation {self.generation}: {reason}")
        return path

    def describe(self, update: Update, lang: str) -> str:
        return describe_update(update, self.domain, lang)

    def report(self, event: str, update: Update, lang: str) -> str:
        """Tell the observer what an update changed; returns it in words."""
        change = self.describe(update, lang)
        self.observer.on_learner(event, change, removed_names(update))
        return change

    def why(self, name: str, lang: str) -> list[str] | None:
        """Why an action or condition is in the tree, one line per reason (None: it is not)."""
        if self.domain.has_action(name) and name in self.learner.order:
            action = next(n for n in walk(self.learner.tree) if isinstance(n, Action) and n.name == name)
            lines = [self.learner.explain(action.uid)]
            for guard in self.learner.guards(name):
                lines.append(f"({literals_label(str(guard), self.domain, lang)}): {self.learner.explain(guard.uid)}")
            return lines
        matches = [n for n in walk(self.learner.tree) if isinstance(n, Condition) and n.name == name]
        return [self.learner.explain(n.uid) for n in matches] or None
