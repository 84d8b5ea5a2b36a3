"""The session manager's members that hand through to the owner holding the state.

Before the state had owners (the record, the turn, the vocabulary, the learning, the questions,
the definitions) it lived on the manager, and the tests, the benchmarks, the dialogue oracle and
the drivers' ``live`` still use those names. They are kept here, apart from the machine, as
plain windows onto the owners, so the machine holds only what it does; a new driver reads
``SessionManager.view()`` instead.
"""

from __future__ import annotations

from collections.abc import Callable

from teach.bt.nodes import Node
from teach.demos import Demonstration
from teach.dialogue.model_repair import ModelQuestion
from teach.dialogue.phrases import PhraseBook
from teach.dialogue.questions import Question, QuestionBudget
from teach.domain import Domain
from teach.open_demonstration import OpenDemonstration
from teach.session.asking import Asking
from teach.session.definitions import Definitions
from teach.session.journal import Journal
from teach.session.learning import Learning
from teach.session.record import SessionRecord
from teach.session.replies import Reply
from teach.session.store import SessionStore
from teach.session.turn import Turn
from teach.session.vocabulary import Vocabulary


class CompatMembers:
    """The manager's older members, each read from (or written to) the owner that holds it now."""

    vocabulary: Vocabulary
    record: SessionRecord
    turn: Turn
    learning: Learning
    asking: Asking
    definitions: Definitions

    @property
    def domain(self) -> Domain:
        return self.vocabulary.domain

    @property
    def phrases(self) -> PhraseBook:
        return self.vocabulary.phrases

    @property
    def journal(self) -> Journal:
        return self.record.journal

    @property
    def store(self) -> SessionStore:
        return self.record.store

    @store.setter
    def store(self, store: SessionStore) -> None:  # a benchmark measures another store
        self.record.store = store

    @property
    def open(self) -> OpenDemonstration | None:
        """The demonstration being shown (or a run's steps, to be continued as a correction)."""
        return self.record.open

    @open.setter
    def open(self, opened: OpenDemonstration | None) -> None:
        self.record.open = opened

    @property
    def live(self) -> Callable[[Reply], None] | None:
        """A driver that shows replies as they are produced."""
        return self.turn.live

    @live.setter
    def live(self, live: Callable[[Reply], None] | None) -> None:
        self.turn.live = live

    @property
    def budget(self) -> QuestionBudget:
        """The situation and definition questions left (the labelling questions have their own)."""
        return self.asking.budget

    @property
    def pending(self) -> Question | None:
        """The situation question waiting for its answer."""
        return self.asking.pending

    @property
    def pending_model(self) -> ModelQuestion | None:
        """The open question about the action definitions."""
        return self.definitions.pending

    @property
    def generation(self) -> int:
        return self.learning.generation

    @property
    def pruned(self) -> Node | None:
        return self.learning.pruned

    @property
    def demos(self) -> list[Demonstration]:
        return self.learning.demos
