"""The situation questions of a session: which one to ask, paid for once per situation, and
what an answer teaches.

After a demonstration (from the second on), on 'ask' and after a run that stopped where it was
unsure, the learner's best question is asked while the budget allows (at most
``QUESTIONS_PER_TURN`` in a row); a situation asked about once is paid for once, even after an
undo. An answer is "yes", "no" (then: what instead?), an action, 'done', 'skip' or "that cannot
happen"; one the domain file shows cannot work there is refused with the reason and the
question stays open. Every question and answer is journalled through the session record before
the teacher hears the next line.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from teach import messages as m
from teach.dialogue.phrases import Token, UnknownPhrase, after_no, is_no, is_yes, normalize
from teach.dialogue.questions import MUST_KINDS, Question, QuestionBudget
from teach.domain import State
from teach.errors import LearnError
from teach.messages import Lang
from teach.open_demonstration import OpenDemonstration
from teach.session.commands import (
    DONE_WORDS,
    IMPOSSIBLE_WORDS,
    LIKELY_WORDS,
    NONSENSE_WORDS,
    PUZZLED_WORDS,
    SKIP_WORDS,
    UNSURE_WORDS,
    WHAT_NOW_WORDS,
    only_marks,
    without_hesitation,
)
from teach.session.describe import actions_to_name, unmet_goal, unnamed, why_refused
from teach.session.journal import Answered, Asked, Situated, parse_state_text, state_text
from teach.session.learning import DONE_ABOUT, Learning
from teach.session.record import IMPOSSIBLE, SessionRecord
from teach.session.replies import Reply, ReplyKind
from teach.session.run_report import lacked, phrase_said, way_there, why_not
from teach.session.turn import Turn
from teach.session.vocabulary import Vocabulary

QUESTIONS_PER_TURN = 2
MIN_DEMOS_BEFORE_ASKING = 2


class Asking:
    """The question budget, the question open now, and the answers to it.

    ``after_learning(started, answered)`` is the machine's: an answer learned is pruned, saved,
    shown and replayed there like a demonstration (and it may ask the next question); ``answered``
    is the situation asked about and the action the teacher named there (None: no action)."""

    def __init__(self, record: SessionRecord, learning: Learning, vocabulary: Vocabulary, turn: Turn, lang: Lang,
                 world_state: Callable[[], State], seed: int, questions: int,
                 after_learning: Callable[[float, tuple[State, str] | None], list[Reply]]):
        self.record, self.learning, self.vocabulary, self.turn, self.lang = record, learning, vocabulary, turn, lang
        self.world_state, self.seed = world_state, seed
        self.after_learning = after_learning
        self.budget = QuestionBudget(questions)
        self.pending: Question | None = None
        """The question waiting for its answer."""
        self.in_a_row = 0
        """Questions asked since the teacher last did something else."""

    def rebuilt(self, questions: int) -> None:
        """The journal was learned again: every question asked stays paid for, even when what it
        was about is undone (questions about action definitions have no state, and count too)."""
        asked = sum(not e.state for e in self.record.journal.events if isinstance(e, Asked))
        self.budget = QuestionBudget(questions, len(self.record.charged()) + asked)

    def maybe_ask(self, demos: int, force: bool = False) -> list[Reply]:
        """Ask the best question if the budget allows; unforced (after ``demos`` demonstrations), at
        most QUESTIONS_PER_TURN in a row."""
        if self.pending is not None:
            return []
        if not force and (demos < MIN_DEMOS_BEFORE_ASKING or self.in_a_row >= QUESTIONS_PER_TURN):
            return []
        return self._ask_next()

    def _ask_next(self) -> list[Reply]:
        question = self.next_question()
        return [] if question is None or not self._affordable(question.state) else self._ask(question)

    def ask_after_run(self) -> list[Reply]:
        """A run that ended "done" with the goal unmet, or doing nothing: the situation it ended
        in is the most useful question there is, so it is asked at once while questions are left."""
        state = self.world_state()
        if not self.learning.has_behaviour:  # a tree planned from action definitions: their questions come from 'model'
            return []
        if self.pending is not None or state in self.learning.asked or not self._affordable(state):
            return []
        return self._ask(self.learning.question_where_stuck(state) or Question(state, 1.0))

    def ask_again(self) -> list[Reply]:
        """The question still open when the session ended, asked again on resume at no cost (it
        was paid for when asked): it was lost, its price kept. Found again the way it was chosen
        (the learner is as it was then), else asked as a plain situation question."""
        last = next((event for event in reversed(self.record.journal.events) if not isinstance(event, Situated)), None)
        if not isinstance(last, Asked) or not last.state or self.pending is not None:
            return []
        state = parse_state_text(last.state)
        if len(state) != len(self.vocabulary.domain.conditions) or state in self.learning.asked:
            return []
        chosen = self.next_question()
        question = chosen if chosen is not None and chosen.state == state else \
            self.learning.question_where_stuck(state) or Question(state, 1.0)
        self.pending = question
        self.learning.asked.add(state)
        if self.record.open is None and state == self.world_state():
            # asked where a run stopped having done nothing: the correction it left open (a journal
            # keeps no empty one), so the step an answer names is the robot's, as before the quit
            self.record.open = OpenDemonstration()
        return [Reply(ReplyKind.INFO, m.ASKED_BEFORE_YOU_LEFT(self.lang)), self._question_reply(question)]

    def _affordable(self, state: State) -> bool:
        """Whether a question about ``state`` may be asked: one is left, or it was paid for already."""
        return self.budget.left > 0 or state_text(state) in self.record.charged()

    def _ask(self, question: Question) -> list[Reply]:
        """Ask ``question``: paid for once per situation, even if an undo made it open again."""
        if state_text(question.state) not in self.record.charged():
            self.budget.spend()
        self.in_a_row += 1
        self.pending = question
        self.learning.asked.add(question.state)
        self.record.add(Asked(state=state_text(question.state)))
        return [self._question_reply(question)]

    def _question_reply(self, question: Question) -> Reply:
        text = question.text(self.vocabulary.domain, self.lang)
        self.record.observer.on_question(text, self.budget.left)
        return Reply(ReplyKind.QUESTION, f"{text}\n   ({self._options(question)})")

    def _options(self, question: Question) -> str:
        """The answers a question takes: "yes / find the ball / … / done / skip"."""
        yes = [m.YES_WORD(self.lang)] if question.kind in MUST_KINDS else []
        domain = self.vocabulary.domain
        named = actions_to_name(domain)  # blocksworld's 40, "stack a a" among them, filled five lines
        left = unnamed(domain, named)
        more = [m.MORE_ACTIONS(self.lang, count=left)] if left else []
        return " / ".join(yes + [a.label(self.lang) for a in named] + more +
                          [m.DONE_WORD(self.lang), m.SKIP_WORD(self.lang)])

    def answer_hint(self) -> Reply:
        """After an answer nothing was close to ("2", "the second one"): what the open question takes."""
        assert self.pending is not None
        return Reply(ReplyKind.INFO, m.ANSWER_ONE_OF(self.lang, options=self._options(self.pending)))

    def next_question(self) -> Question | None:
        return self.learning.next_question(self.seed)

    def answer(self, line: str) -> list[Reply]:
        question = self.pending
        assert question is not None
        key = normalize(line)
        if key in SKIP_WORDS:
            self.pending = None
            text = question.text(self.vocabulary.domain, self.lang)
            self.record.add(Answered(state_text(question.state), "skip", text))
            self.record.observer.on_answer(text, line, "nothing (skipped)")
            return [Reply(ReplyKind.INFO, m.KEEP_CAREFUL(self.lang))]
        if key in IMPOSSIBLE_WORDS:
            return self._cannot_happen(question)
        if key in WHAT_NOW_WORDS:  # "what now?" with a question open: what it takes
            return [self.answer_hint()]
        if key in PUZZLED_WORDS:  # "huh?", "wie bitte?"
            return [Reply(ReplyKind.INFO, m.QUESTION_AGAIN(self.lang)), self._question_reply(question)]
        if key in NONSENSE_WORDS:  # "that makes no sense": perhaps it cannot happen, but that is not guessed
            return [Reply(ReplyKind.QUESTION, m.CANNOT_HAPPEN_THEN(self.lang))]
        hesitant = without_hesitation(key)
        if hesitant in UNSURE_WORDS:  # "maybe": neither a yes nor a no; the question stays open
            return [Reply(ReplyKind.QUESTION, m.NOT_SURE(self.lang))]
        doubtful_yes = hesitant in LIKELY_WORDS or only_marks(line)  # "I think so", "👍"
        if doubtful_yes and question.kind in MUST_KINDS:  # not acted on as a yes
            return [Reply(ReplyKind.QUESTION, m.IS_THAT_A_YES(self.lang))]
        yes = question.kind in MUST_KINDS and bool(line.strip()) and is_yes(line, self.lang)
        if question.kind in MUST_KINDS and is_no(line, self.lang):
            return [Reply(ReplyKind.QUESTION, m.WHAT_INSTEAD(self.lang))]  # the question stays open
        if key in DONE_WORDS or (yes and question.action is None):
            unmet = unmet_goal(self.vocabulary.domain, question.state, self.lang)
            if unmet:  # the question stays open and is not paid for again
                return [Reply(ReplyKind.ERROR, m.NOT_DONE_THERE(self.lang, unmet=unmet)),
                        self._question_reply(question)]
            return self.apply_answer(None, line)
        if yes:
            return self.answer_step(question.action, line)
        instead = after_no(line, self.lang)  # "no, find someone"
        try:
            parsed = self.vocabulary.phrases.parse(instead or line, self.lang)
        except UnknownPhrase:
            if instead is None or question.kind not in MUST_KINDS:
                raise
            # "no, the ball must be in my hand": the no is clear, what to do instead is not
            return [Reply(ReplyKind.ERROR, m.NO_TAKEN(self.lang, rest=instead)),
                    Reply(ReplyKind.QUESTION, m.WHAT_INSTEAD(self.lang))]
        tokens = [t for t in parsed if t.kind == "action"]
        if len(tokens) != 1:
            return [Reply(ReplyKind.ERROR, m.ONE_ACTION(self.lang))]
        return self.answer_step(tokens[0], line)

    def answer_step(self, step: Token | str | None, said: str) -> list[Reply]:
        """Answer the pending question with a step (a parsed one, or the one asked about), unless
        the domain file shows it cannot work there: as for 'done', that is not learned (nor "take
        the ball to the bin" where the ball is not in hand, nor either read through a typo)."""
        question = self.pending
        assert question is not None and step is not None
        answer, needs = (step, ()) if isinstance(step, str) else (step.name, step.needs)
        domain = self.vocabulary.domain
        if not lacked(domain, answer, question.state, needs):
            return self.apply_answer(answer, said)
        reason = why_not(domain, answer, question.state, self.lang, needs)
        refused = m.NOT_WITHOUT(self.lang, said=phrase_said(domain, step, self.lang), reason=reason) \
            if isinstance(step, Token) and needs else \
            m.COULD_NOT(self.lang, action=domain.action(answer).label(self.lang), reason=reason)
        return [Reply(ReplyKind.ERROR, refused), *way_there(domain, answer, question.state, self.lang, needs),
                self._question_reply(question)]

    def _cannot_happen(self, question: Question) -> list[Reply]:
        """The asked-about situation cannot happen: journalled, never asked again, and not paid for."""
        self.pending = None
        text = question.text(self.vocabulary.domain, self.lang)
        self.record.add(Answered(state_text(question.state), IMPOSSIBLE, text))
        self.learning.rule_out(question.state, f"answer to question {self.budget.used}")
        self.budget.used -= 1
        self.record.observer.on_answer(text, IMPOSSIBLE, "nothing (that situation cannot happen)")
        # a free answer is not one of the questions in a row: the next one follows, as it would have
        # after a paid answer (the teacher had to say 'ask' to go on)
        self.in_a_row -= 1
        follows = self._ask_next() if self.in_a_row < QUESTIONS_PER_TURN else []
        return [Reply(ReplyKind.INFO, m.CANNOT_HAPPEN(self.lang)), *follows]

    def apply_answer(self, answer: str | None, said: str) -> list[Reply]:
        """Learn from the answer to the pending question (None: the task is done there)."""
        question = self.pending
        assert question is not None
        started = time.perf_counter()
        text = question.text(self.vocabulary.domain, self.lang)
        source = f"answer to question {self.budget.used}"
        self.pending = None
        try:
            update = self.learning.learn_answer(question.state, answer, source, _asked_about(question))
        except LearnError as error:
            return [Reply(ReplyKind.ERROR, m.CONTRADICTS(self.lang, why=why_refused(error, self.lang))),
                    Reply(ReplyKind.INFO, m.DETAILS(self.lang, details=error.message))]
        change = self.learning.describe(update, self.lang, answered=(question, answer))
        # the answer is on disk before the teacher is thanked for it: a kill cannot lose it
        self.record.add(Answered(state_text(question.state), answer or "done", text, _asked_about(question)))
        self.record.observer.on_answer(text, said, change)
        self.learning.report("answer", update, self.lang)
        head = self.turn.say([Reply(ReplyKind.INFO, m.THANKS(self.lang, change=change))])
        return head + self.after_learning(started, None if answer is None else (question.state, answer))

    def none_text(self) -> str:
        """Why no question is asked now."""
        return (m.ALL_QUESTIONS_USED if self.budget.left <= 0 else m.NO_QUESTION_NOW)(self.lang)



def _asked_about(question: Question) -> str | None:
    """What a "may I still …?" or "is the task done?" question asked about (None: a plain one)."""
    if question.kind == "must-goal":
        return DONE_ABOUT
    return question.action if question.kind == "must-precondition" else None
