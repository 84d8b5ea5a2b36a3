"""Learning a session again from its journal: on resume, after an undo or a redo, and when guiding
grows the domain.

The journal is what the session learned from; the learner, the action definitions and the
question budget are what it made of that. Whenever the journal's effective events change (an
undo or a redo journals what it takes or brings back) or the domain they are read in grows, all
three are rebuilt from the journal here, deterministically, so a resume ends where the session did.
"""

from __future__ import annotations

import re
from pathlib import Path

from teach import messages as m
from teach.domain import Domain
from teach.errors import FormatError, LearnError
from teach.messages import Lang
from teach.session.asking import Asking
from teach.session.definitions import Definitions
from teach.session.journal import (
    Answered,
    DemoLearned,
    Event,
    ModelAnswered,
    ModelLoaded,
    Redone,
    Undone,
    effective_events,
    parse_state_text,
    redoable,
)
from teach.session.learning import Learning
from teach.session.record import IMPOSSIBLE, SessionRecord
from teach.session.vocabulary import Vocabulary


class Relearning:
    """Rebuilds what the session learned from the journal's effective events."""

    def __init__(self, record: SessionRecord, learning: Learning, definitions: Definitions, asking: Asking,
                 vocabulary: Vocabulary, questions: int, lang: Lang):
        self.record, self.learning, self.definitions, self.asking = record, learning, definitions, asking
        self.vocabulary, self.questions, self.lang = vocabulary, questions, lang

    def relearn(self) -> None:
        """Re-learn everything in the journal; a journal that cannot be read is one error naming it."""
        try:
            self._replay()
        except (KeyError, TypeError, ValueError, AttributeError) as error:
            raise FormatError(f"the session journal is damaged ({type(error).__name__}: {error})",
                              self.record.store.journal_path) from None

    def adopt(self, domain: Domain) -> None:
        """Guiding taught a new action: learn everything again in the grown domain."""
        self.learning.domain = domain
        self.relearn()

    def undo(self) -> str:
        """Take back the last demonstration or answer learned; what it was, in words."""
        journal = self.record.journal
        self.asking.pending = self.definitions.pending = None  # paid for, but about what is undone
        self.record.add(Undone())
        self.record.store.retire_undone(journal)
        self.relearn()
        taken_back = redoable(journal.events)[-1]  # what this undo took (a skipped question never counts)
        return self._moved(taken_back, m.UNDONE_DEMONSTRATION, m.UNDONE_ANSWER, m.UNDONE_LEARNING)

    def can_redo(self) -> bool:
        """Whether an undo is left to redo (nothing new was learned after it)."""
        return bool(redoable(self.record.journal.events))

    def redo(self) -> str:
        """Bring back what the last undo took; what it was, in words."""
        journal = self.record.journal
        back = redoable(journal.events)[-1]
        self.record.add(Redone())
        self.record.store.bring_back_redone(journal)
        self.relearn()
        return self._moved(back, m.REDONE_DEMONSTRATION, m.REDONE_ANSWER, m.REDONE_LEARNING)

    def _moved(self, event: Event, demo: m.Text, answer: m.Text, other: m.Text) -> str:
        """What an undo or redo moved, in words: the demonstration's name or the question answered."""
        if isinstance(event, DemoLearned):  # demo-004.csv is "4", the teacher's fourth
            number = re.fullmatch(r"demo-0*([0-9]+)", Path(event.file).stem)
            return demo(self.lang, name=number.group(1) if number else Path(event.file).stem)
        if isinstance(event, Answered):
            return answer(self.lang, question=event.question)
        return other(self.lang)

    def _replay(self) -> None:
        learning, domain, journal, store = self.learning, self.vocabulary.domain, self.record.journal, self.record.store
        learning.restart()
        self.definitions.restart()
        self.asking.rebuilt(self.questions)
        answered = 0
        for event in effective_events(journal.events):
            if isinstance(event, DemoLearned):
                learning.learn_demonstration(store.read_demonstration(event.file, domain), event.source)
            elif isinstance(event, (ModelLoaded, ModelAnswered)):
                self.definitions.replay(event)
            elif isinstance(event, Answered):
                answered += 1
                state = parse_state_text(event.state)
                if len(state) != len(domain.conditions):
                    raise ValueError(f"an answered state has {len(state)} values, not {len(domain.conditions)}")
                if event.answer not in ("skip", "done", IMPOSSIBLE) and event.answer not in domain.action_names:
                    raise FormatError(m.UNKNOWN_JOURNAL_ACTION(
                        "en", number=journal.events.index(event), action=event.answer), store.journal_path)
                learning.asked.add(state)
                if event.answer == IMPOSSIBLE:
                    learning.rule_out(state, f"answer to question {answered}")
                elif event.answer != "skip":
                    try:
                        learning.learn_answer(state, None if event.answer == "done" else event.answer,
                                              f"answer to question {answered}", event.asked_about)
                    except LearnError:
                        pass  # it was rejected when it was given, too
        if learning.has_behaviour:
            learning.prune()
        self.definitions.replan()
