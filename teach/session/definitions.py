"""The teacher's action definitions in a session (the thesis's Approach 1, repaired by questions).

'model FILE' loads definitions of the domain's actions; a tree is planned from them, and while
none can be built the next repair question (``teach.dialogue.model_repair``) is asked, from the
session's one question budget. Loading and every answer are journalled through the session
record, so an undo or a resume plans again from the same definitions and answers.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from teach import messages as m
from teach.bt.nodes import Node
from teach.dialogue.model_repair import ModelQuestion, ModelRepair
from teach.dialogue.phrases import normalize
from teach.dialogue.questions import QuestionBudget
from teach.domain import Domain
from teach.errors import TeachError
from teach.messages import Lang
from teach.session.commands import SKIP_WORDS
from teach.session.journal import Asked, Event, ModelAnswered, ModelLoaded
from teach.session.learning import Learning
from teach.session.record import SessionRecord
from teach.session.replies import Reply, ReplyKind


class Definitions:
    """The loaded definitions, the tree planned from them and the repair question open now."""

    def __init__(self, record: SessionRecord, learning: Learning, budget: Callable[[], QuestionBudget], lang: Lang,
                 tree_reply: Callable[[Node], Reply]):
        self.record, self.learning, self.budget, self.lang = record, learning, budget, lang
        self.tree_reply = tree_reply
        self.repair: ModelRepair | None = None
        self.pending: ModelQuestion | None = None
        """The repair question waiting for its answer."""
        self.planned: Node | None = None
        """The tree planned from the definitions, once one can be built."""

    @property
    def unusable(self) -> bool:
        """Definitions are loaded and no tree can be built from them yet: 'ask' asks about them."""
        return self.repair is not None and not self.repair.plan().usable

    def load(self, path: Path, domain: Domain) -> list[Reply]:
        """'model FILE': definitions of ``domain``'s actions; a plan from them, or a question."""
        model = self.record.store.read_model(path)
        if model.condition_names != domain.condition_names or \
                not set(model.action_names) <= set(domain.action_names):
            raise TeachError(m.MODEL_MISMATCH(self.lang, domain=domain.path), path)
        self.repair = ModelRepair(model, self.budget(), lang=self.lang)
        self.pending = None
        self.record.add(ModelLoaded(str(path.resolve())))
        return self.show(ask=True)

    def show(self, ask: bool) -> list[Reply]:
        """What the action definitions give; after a change (``ask``) the tree is saved as a
        generation and, while it is not usable, the next repair question is asked."""
        assert self.repair is not None
        outcome = self.repair.plan()
        if outcome.usable and outcome.tree is not None:
            self.planned = outcome.tree
            if ask:
                self.learning.save_generation(outcome.tree, "planned from the action definitions")
            return [Reply(ReplyKind.SAY, m.CAN_BUILD(self.lang)), self.tree_reply(outcome.tree)]
        replies = [Reply(ReplyKind.SAY, m.CANNOT_BUILD(self.lang, reason=outcome.reason))]
        return replies + (self.ask() if ask else [])

    def ask(self) -> list[Reply]:
        """The next repair question, while questions are left."""
        assert self.repair is not None
        left = self.budget().left
        if left <= 0:
            return [Reply(ReplyKind.INFO, m.ALL_QUESTIONS_USED(self.lang))]
        question = self.repair.ask()
        if question is None:
            return [Reply(ReplyKind.INFO, m.NOTHING_TO_ASK(self.lang))]
        self.pending = question
        self.record.add(Asked(model_question=question.to_json()))
        text = self.repair.text(question, self.lang)
        self.record.observer.on_question(text, self.budget().left)
        return [Reply(ReplyKind.QUESTION, text)]

    def answer(self, line: str) -> list[Reply]:
        """The teacher's answer to the open repair question (an unknown phrase keeps it open)."""
        assert self.repair is not None and self.pending is not None
        question = self.pending
        text = self.repair.text(question, self.lang)
        observer = self.record.observer
        if normalize(line) in SKIP_WORDS:
            self.pending = None
            observer.on_answer(text, line, "nothing (skipped)")
            self.record.add(ModelAnswered(question.to_json(), "skip"))
            return [Reply(ReplyKind.INFO, m.ASK_ANOTHER(self.lang))]
        change = self.repair.apply(question, line)  # UnknownPhrase keeps the question open
        self.pending = None
        observer.on_answer(text, line, change)
        self.record.add(ModelAnswered(question.to_json(), line))
        return [Reply(ReplyKind.INFO, m.THANKS(self.lang, change=change))] + self.show(ask=True)

    # --- rebuilt from the journal (after an undo, on resume) -------------------------------

    def restart(self) -> None:
        self.repair, self.pending, self.planned = None, None, None

    def replay(self, event: Event) -> None:
        """One journalled event again: definitions loaded, or a repair answer applied."""
        if isinstance(event, ModelLoaded):
            self.repair = ModelRepair(self.record.store.read_model(Path(event.file)), self.budget(), lang=self.lang)
        elif isinstance(event, ModelAnswered) and self.repair is not None and event.answer != "skip":
            self.repair.apply(ModelQuestion.from_json(event.question), event.answer)

    def replan(self) -> None:
        """After the replay: the planned tree, if one can be built."""
        if self.repair is not None:
            outcome = self.repair.plan()
            self.planned = outcome.tree if outcome.usable else None
