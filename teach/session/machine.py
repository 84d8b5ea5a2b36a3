"""The session machine: a plain state machine that turns teacher lines into replies.

It interleaves demonstrations in a world, online learning after every demonstration (through
``teach.session.learning``), at most ``budget`` clarifying questions, and runs of the learned
tree that the teacher can interrupt and correct. Every driver (the terminal, scripted replays,
bench-teach) feeds lines to ``handle(line, interrupt)``, which returns every reply of that line
in order. A driver that shows replies while a line is still being handled (steps as they
happen, run progress) sets ``live``: it then sees each of those same replies once, as it is
produced. Files are read and written only through the ``SessionStore``.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING

from teach import messages as m
from teach.bt.nodes import Node, size
from teach.demos import Demonstration, Step
from teach.dialogue.phrases import (
    LineTooLong,
    PhraseBook,
    Suggestion,
    Token,
    UnknownPhrase,
    check_length,
    command_hint,
    is_no,
    is_yes,
    normalize,
)
from teach.dialogue.questions import MUST_KINDS, Question, QuestionBudget, describe_situation
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State
from teach.errors import FormatError, LearnError, TeachError
from teach.observe.hook import Observer
from teach.session.commands import (
    ANSWERING,
    BLOCKED_WHILE_ASKING,
    COMMAND_WORDS,
    COMMANDS,
    DONE_WORDS,
    IMPOSSIBLE_WORDS,
    LOOKING,
    SKIP_WORDS,
    Command,
    Verb,
    parse_command,
)
from teach.session.describe import unmet_goal, why_refused
from teach.session.guiding import Guiding
from teach.session.journal import (
    Answered,
    Asked,
    DemoLearned,
    Event,
    Journal,
    ModelAnswered,
    ModelLoaded,
    Redone,
    Situated,
    Undone,
    effective_events,
    parse_state_text,
    redoable,
    state_text,
)
from teach.session.learning import DONE_ABOUT, Learning
from teach.session.replies import Reply, ReplyKind
from teach.session.run_report import TryWatch, failed_tries, tried_lines, why_not
from teach.session.settings import Settings, WorldKind
from teach.session.store import SessionStore
from teach.session.tree_words import tree_lines
from teach.symbolic import missing_preconditions
from teach.world.protocol import ActResult, Outcome, TeachingWorld, WorldEvent

if TYPE_CHECKING:
    from teach.dialogue.model_repair import ModelQuestion, ModelRepair

QUESTIONS_PER_TURN = 2
MIN_DEMOS_BEFORE_ASKING = 2
IMPOSSIBLE = "impossible"
"""The journalled answer "that situation cannot happen"."""


class Mode(StrEnum):
    IDLE = "idle"
    """Waiting for a command or actions."""
    DEMONSTRATING = "demonstrating"
    """A demonstration is open."""
    ASKING = "asking"
    """A question waits for its answer."""


@dataclass
class _OpenDemo:
    """The demonstration being shown (or a run's steps, to be continued as a correction)."""

    steps: list[Step] = field(default_factory=list)
    words: list[str] = field(default_factory=list)  # each step as the teacher saw it, for 'steps' and 'undo'
    robot_steps: int = 0
    """How many of the steps a run did: while the teacher added none, 'run' tries again instead."""

    def add(self, step: Step, words: str) -> None:
        self.steps.append(step)
        self.words.append(words)

    def take_back(self, first: int) -> Step:
        """Remove steps ``first``.. (numbered from 1); the first removed, whose state was before them all."""
        removed = self.steps[first - 1]
        del self.steps[first - 1:], self.words[first - 1:]
        return removed


@dataclass(frozen=True)
class _StepsTakenBack:
    """What 'undo N' took from the open demonstration, so 'redo' can put it back while nothing
    happened since: the open demonstration still ends where they began and the world is as the
    undo left it."""

    first: int
    steps: tuple[Step, ...]
    words: tuple[str, ...]
    world_after: State
    """The world when the undo was said (after the steps): a redo puts it back there."""
    arranged: State
    """The world the undo left (before the steps)."""


class SessionManager:
    """One teaching session. Not thread-safe: one driver feeds it lines."""

    def __init__(self, settings: Settings, domain: Domain, world: TeachingWorld, observer: Observer | None = None,
                 journal: Journal | None = None):
        self.settings = settings
        self.domain = domain
        self.world = world
        self.observer = observer or Observer()
        self.lang = settings.lang
        self.store = SessionStore(settings.base, settings.session, settings.record)
        self.phrases = PhraseBook(domain, world.events)
        self.learning = Learning(domain, self.store, self.observer, settings.safe, world.can_happen)
        self.budget = QuestionBudget(settings.questions)
        self.pending: Question | None = None
        self.model_repair: ModelRepair | None = None
        self.pending_model: ModelQuestion | None = None
        self.planned: Node | None = None
        self.open: _OpenDemo | None = None
        self.suggestion: Suggestion | None = None  # a "Did you mean …?" waiting for yes or no
        self.topic: str | None = None  # the object named last: what "it" means in the next line
        self.facilitator = settings.facilitator  # identifiers and the symbolic tree too (--facilitator)
        self.finished = False
        self._quit_warned_at = -2
        """The step at which quitting with an open demonstration was warned about."""
        self.step = 0
        self.live: Callable[[Reply], None] | None = None  # a driver that shows replies as they are produced
        self._turn: list[Reply] = []
        self._interrupt: Callable[[], bool] | None = None
        self._turn_questions = 0
        self.journal = journal or Journal(settings.session, str(domain.path or ""), settings.lang,
                                          settings.questions, settings.world, settings.seed, guess=not settings.safe)
        self.restored: list[Reply] = []  # what a resume set up again, said in greet
        self._start_situation = state_text(world.state())
        self.store.prepare(domain)
        self.observer.on_domain(domain)
        self.guiding = Guiding(self, settings.label_questions)
        self._taken_back: _StepsTakenBack | None = None  # what 'redo' can put back into the open demonstration

    # --- what drivers and tests read --------------------------------------------------------

    @property
    def mode(self) -> Mode:
        if self.pending is not None or self.pending_model is not None or self.guiding.pending is not None:
            return Mode.ASKING
        return Mode.DEMONSTRATING if self.open is not None else Mode.IDLE

    @property
    def runnable(self) -> Node | None:
        """The tree 'run' would start now (the unpruned one: pruning assumes actions have only the
        effects seen so far), or None when a run would be refused."""
        if self.open is not None and len(self.open.steps) > self.open.robot_steps:
            return None  # the teacher is showing something: finish or cancel it first
        return self.learning.tree if self.learning.has_behaviour else self.planned

    @property
    def generation(self) -> int:
        return self.learning.generation

    @property
    def pruned(self) -> Node | None:
        return self.learning.pruned

    @property
    def demos(self) -> list[Demonstration]:
        return self.learning.demos

    # --- the driver's interface -----------------------------------------------------------

    def greet(self) -> list[Reply]:
        actions = ", ".join(a.label(self.lang) for a in self.domain.actions)
        replies = [Reply(ReplyKind.SAY, m.HELLO(self.lang, actions=actions))]
        if not self.demos:  # a resumed session names itself in RESUMED_COUNTED
            replies.insert(0, Reply(ReplyKind.INFO, m.SESSION_ID(self.lang, session=self.settings.session)))
        else:
            demos = _counted(len(self.demos), m.NO_DEMOS, m.ONE_DEMO, m.DEMOS)(self.lang, count=len(self.demos))
            asked = _counted(self.budget.used, m.NO_QUESTIONS_ASKED, m.ONE_QUESTION_ASKED,
                             m.QUESTIONS_ASKED)(self.lang, count=self.budget.used)
            replies.insert(0, Reply(ReplyKind.INFO, m.RESUMED_COUNTED(self.lang, session=self.settings.session,
                                                                      demos=demos, asked=asked,
                                                                      generation=self.generation)))
            if self.pruned is not None:
                replies.append(self._tree_reply(self.pruned))
        replies += self.restored
        self.restored = []
        replies.append(self._state_reply())
        self._turn = []
        return self._end_turn(replies)

    def handle(self, line: str, interrupt: Callable[[], bool] | None = None) -> list[Reply]:
        """One teacher line in, every reply to it out, in order. Never raises for bad input.
        ``interrupt`` is polled while the robot runs (the terminal's Ctrl-C)."""
        line = line.strip()
        if not line and self.suggestion is None:
            return []
        self._turn = []
        self._interrupt = interrupt
        self._tick_clock()
        try:
            check_length(line, self.lang)
        except LineTooLong as too_long:  # neither logged nor echoed: nobody meant that much as one line
            self.suggestion = None
            return self._end_turn([Reply(ReplyKind.ERROR, too_long.message)])
        self.observer.on_dialogue("teacher", line, self.budget.left)
        suggestion, self.suggestion = self.suggestion, None
        asking = self.mode is Mode.ASKING
        try:
            replies = self._dispatch(line, suggestion)
        except UnknownPhrase as unknown:
            # during a situation question only a guessed action is kept: confirming it answers the question
            keep = not asking or (self.pending is not None and unknown.suggestion is not None
                                  and unknown.suggestion.candidate.kind == "action")
            self.suggestion = unknown.suggestion if keep else None
            replies = [Reply(ReplyKind.ERROR, unknown.message)]
        except TeachError as error:
            replies = [Reply(ReplyKind.ERROR, str(error))]
        finally:
            self._interrupt = None
        turn = self._end_turn(replies)
        self.observer.checkpoint()
        self._note_open_demonstration()
        self.store.save_journal(self.journal)  # the step clock too, so a resume goes on from it
        return turn

    def command(self, line: str) -> tuple[Command | None, str]:
        """The command ``handle`` would read in a line ("ok run" is 'run'), and its argument."""
        try:
            return parse_command(command_hint(line, self.lang, COMMAND_WORDS) or line)
        except LineTooLong:
            return None, line

    def close(self) -> None:
        self.store.save_journal(self.journal)
        self.world.close()
        self.observer.close()

    def _dispatch(self, line: str, suggestion: Suggestion | None = None) -> list[Reply]:
        if suggestion is not None:
            if is_yes(line, self.lang):
                tokens = self.phrases.confirm(suggestion)
                if self.pending is None:
                    return self._act(tokens)
                if len(tokens) != 1 or tokens[0].kind != "action":
                    return [Reply(ReplyKind.ERROR, m.ONE_ACTION(self.lang))]
                return self.apply_answer(tokens[0].name, tokens[0].text)
            if is_no(line, self.lang):
                return [Reply(ReplyKind.INFO, m.SAY_IT_ANOTHER_WAY(self.lang))]
        line = command_hint(line, self.lang, COMMAND_WORDS) or line
        command, rest = parse_command(line)
        guided = self._guiding_first(line, command)
        if guided is not None:
            return guided
        # "wrong"/"falsch" undo, but to an open question they are a "no", as before they named a command
        answering = command is None or command in ANSWERING or is_no(line, self.lang)
        if self.pending_model is not None and answering:
            return self._answer_model(line)
        if self.pending is not None and answering:
            return self._answer(line)
        if command is not None and self.mode is Mode.ASKING and command in BLOCKED_WHILE_ASKING:
            return [Reply(ReplyKind.ERROR, m.ANSWER_FIRST(self.lang))]
        self._turn_questions = 0
        if command is None and is_no(line, self.lang):  # "no" to nothing asked: likely "that was wrong"
            return [Reply(ReplyKind.INFO, m.NO_TO_WHAT(self.lang))]
        if command is None:
            return self._teach_actions(line)
        return self._handler(command)(rest)

    # --- commands --------------------------------------------------------------------------

    def cmd_help(self, rest: str) -> list[Reply]:
        lines = [f"  {c.usage(self.lang):<28} {c.help(self.lang)}" if len(c.usage(self.lang)) <= 28
                 else f"  {c.usage(self.lang)}\n  {'':<28} {c.help(self.lang)}" for c in COMMANDS]
        examples = ", ".join(a.label(self.lang) for a in self.domain.actions)  # one demonstration's words
        return [Reply(ReplyKind.INFO, m.HELP_INTRO(self.lang, examples=examples) + "\n" + "\n".join(lines))]

    def cmd_guide(self, rest: str) -> list[Reply]:
        if not self.guiding.can_guide():
            return self.guiding.refusal()
        replies = self.guiding.command(rest) + [self._state_reply()]
        feedback = self.guiding.feedback()  # what a person steering by the keys needs to know
        return replies + ([feedback] if feedback is not None else [])

    def _guiding_first(self, line: str, command: Command | None) -> list[Reply] | None:
        """A labelling question takes the line as its answer; a line that is not guiding ends
        guidance first (and waits for the labelling answers). None: go on with the line."""
        if self.guiding.pending is not None:
            if command is None or command is Verb.SKIP or is_no(line, self.lang):
                replies = self.guiding.answer(line)
                deferred = self.guiding.take_deferred()
                return replies + (self._dispatch(deferred) if deferred else [])
            return None if command in LOOKING else [Reply(ReplyKind.ERROR, m.LABEL_GUIDE_FIRST(self.lang))]
        if self.guiding.active and (command is None or command is not Verb.GUIDE):
            self.guiding.end()
            if self.guiding.pending is not None:
                self.guiding.deferred = line
                return []
        return None

    def cmd_demonstrate(self, rest: str) -> list[Reply]:
        replies = []
        if self.open is None:
            self.open = _OpenDemo()
            replies.append(Reply(ReplyKind.INFO, m.NEW_DEMONSTRATION(self.lang)))
        if rest.strip():
            replies += self._teach_actions(rest)
        return replies

    def cmd_done(self, rest: str) -> list[Reply]:
        if self.open is None or not self.open.steps:
            return [Reply(ReplyKind.ERROR, m.NO_STEPS_YET(self.lang))]
        state = self.world.state()
        unmet = unmet_goal(self.domain, state, self.lang)
        if unmet:
            return [Reply(ReplyKind.ERROR, m.NOT_FINISHED(self.lang, unmet=unmet))]
        self.open.steps.append(Step(state, GOAL_ACTION, len(self.open.steps) + 1))
        return self._finish_demo()

    def cmd_cancel(self, rest: str) -> list[Reply]:
        if self.open is None:
            return [Reply(ReplyKind.INFO, m.NOTHING_TO_CANCEL(self.lang))]
        self.open = None
        self.topic = None
        return [Reply(ReplyKind.INFO, m.DISCARDED(self.lang))]

    def cmd_undo(self, rest: str) -> list[Reply]:
        if self.mode is Mode.ASKING:  # the answer is what is open, and there is none to take back yet
            return [Reply(ReplyKind.INFO, m.NO_UNDO_WHILE_ASKING(self.lang))]
        if self.open is not None and self.open.steps:
            return self._undo_steps(rest)
        if rest.strip():
            return [Reply(ReplyKind.ERROR, m.NO_STEPS_TO_UNDO(self.lang))]
        if not self.demos:
            return [Reply(ReplyKind.ERROR, m.NOTHING_TO_UNDO(self.lang))]
        self.pending = self.pending_model = None  # a question stays paid for, but it is about what is undone
        self._journal(Undone())
        self.store.retire_undone(self.journal)
        self._rebuild_from_journal()
        taken_back = redoable(self.journal.events)[-1]  # what this undo took (a skipped question never counts)
        text = self._learning_text(taken_back, m.UNDONE_DEMONSTRATION, m.UNDONE_ANSWER, m.UNDONE_LEARNING)
        return self._flush([Reply(ReplyKind.INFO, text)]) + self._after_learning(ask=False)

    def _learning_text(self, event: Event, demo: m.Text, answer: m.Text, other: m.Text) -> str:
        """What an undo or redo moved, in words: the demonstration's name or the question answered."""
        if isinstance(event, DemoLearned):  # demo-004.csv is "4", the teacher's fourth
            number = re.fullmatch(r"demo-0*([0-9]+)", Path(event.file).stem)
            return demo(self.lang, name=number.group(1) if number else Path(event.file).stem)
        if isinstance(event, Answered):
            return answer(self.lang, question=event.question)
        return other(self.lang)

    def _undo_steps(self, rest: str) -> list[Reply]:
        """Take back steps N.. of the open demonstration (the last one without N): the world goes
        back to the state before step N."""
        assert self.open is not None
        count = len(self.open.steps)
        first = _step_number(rest, self.lang)
        if first is None:
            first = count
        if not 1 <= first <= count:
            raise TeachError(m.NO_SUCH_STEP(self.lang, number=first, count=count))
        steps, words, world_after = tuple(self.open.steps[first - 1:]), tuple(self.open.words[first - 1:]), \
            self.world.state()
        self.world.arrange(self.open.take_back(first).state)
        self._taken_back = _StepsTakenBack(first, steps, words, world_after, self.world.state())
        undone = "; ".join(words)
        if not self.open.steps:
            self.open = None
        text = m.UNDONE_ONE_STEP if first == count else m.UNDONE_STEPS
        return [Reply(ReplyKind.INFO, text(self.lang, first=first, last=count, steps=undone)), self._state_reply()]

    def cmd_redo(self, rest: str) -> list[Reply]:
        """Bring back what the last undo took: steps of the open demonstration, else the last
        demonstration or answer, as long as nothing new happened after the undo."""
        if self.mode is Mode.ASKING:
            return [Reply(ReplyKind.INFO, m.NO_UNDO_WHILE_ASKING(self.lang))]
        taken, self._taken_back = self._taken_back, None
        open_steps = len(self.open.steps) if self.open is not None else 0
        if taken is not None and open_steps == taken.first - 1 and self.world.state() == taken.arranged:
            if self.open is None:
                self.open = _OpenDemo()
            for step, words in zip(taken.steps, taken.words, strict=True):
                self.open.add(step, words)
            self.world.arrange(taken.world_after)
            self._save_open()
            last = len(self.open.steps)
            text = (m.REDONE_ONE_STEP if last == taken.first else m.REDONE_STEPS)(
                self.lang, first=taken.first, last=last, steps="; ".join(taken.words))
            return [Reply(ReplyKind.INFO, text), self._state_reply()]
        back = redoable(self.journal.events)
        if not back or open_steps:
            return [Reply(ReplyKind.ERROR, m.NOTHING_TO_REDO(self.lang))]
        self._journal(Redone())
        self.store.bring_back_redone(self.journal)
        self._rebuild_from_journal()
        text = self._learning_text(back[-1], m.REDONE_DEMONSTRATION, m.REDONE_ANSWER, m.REDONE_LEARNING)
        return self._flush([Reply(ReplyKind.INFO, text)]) + self._after_learning(ask=False)

    def cmd_steps(self, rest: str) -> list[Reply]:
        if self.open is None or not self.open.steps:
            return [Reply(ReplyKind.INFO, m.NO_OPEN_STEPS(self.lang))]
        lines = [f"  {number}. {words}" for number, words in enumerate(self.open.words, 1)]
        return [Reply(ReplyKind.INFO, m.OPEN_STEPS(self.lang) + "\n" + "\n".join(lines))]

    def cmd_perturb(self, rest: str) -> list[Reply]:
        tokens = self.phrases.parse(rest, self.lang, perturb=True, topic=self.topic) if rest.strip() else []
        if not any(t.kind == "event" for t in tokens):
            names = ", ".join(m.Text(en[0], next(iter(de), en[0]))(self.lang) for en, de in self.world.events.values())
            return [Reply(ReplyKind.ERROR, m.WHICH_EVENT(self.lang, names=names))]
        return self._act(tokens)

    def cmd_run(self, rest: str) -> list[Reply]:
        if self.open is not None and self.open.steps:
            if len(self.open.steps) > self.open.robot_steps:
                return [Reply(ReplyKind.ERROR, m.FINISH_BEFORE_RUN(self.lang))]
            # only the last run's own steps are open (an answer may have unblocked it): run again from here
            self._flush([Reply(ReplyKind.INFO, m.RUN_AGAIN(self.lang))])
        tree = self.runnable
        if tree is None:
            return [Reply(ReplyKind.ERROR, m.NOTHING_LEARNED(self.lang))]
        stop_after = _number(rest, self.lang)
        self.open = None
        started: list[tuple[State, str]] = []

        def announce(action: str) -> None:
            started.append((self.world.state(), action))
            self._note_run(started)  # on disk before the teacher sees it: a kill mid-run keeps the steps done
            self._flush([Reply(ReplyKind.INFO, m.RUNNING_ACTION(self.lang, action=self.domain.action(action).label(
                self.lang)))])

        def heard(event: WorldEvent) -> None:
            self._flush([self._event_reply(event)])

        self.observer.on_run_start(tree)
        ticker = self.world.ticker
        watch = self.world.ticker = TryWatch(ticker, tree, self.world.state)  # what failed, for the teacher
        try:
            result = self.world.run(tree, max_actions=4 * len(self.domain.actions) + 4, interrupt=self._interrupt,
                                    stop_after=stop_after, on_action=announce, on_event=heard)
        finally:
            self.world.ticker = ticker
        self.observer.on_run_end(result.outcome.value, len(result.steps))
        unmet = unmet_goal(self.domain, self.world.state(), self.lang)
        finished = result.outcome is Outcome.SUCCESS and not unmet
        if not finished:  # what the robot did so far and what the teacher shows next become one correction,
            self.open = _OpenDemo()  # and the world's events in the run (a slip) are external steps (-1) in it

            def events_after(count: int) -> None:
                for event in (event for after, event in result.events if after == count):
                    self._add_event(event)

            for number, (state, action) in enumerate(result.steps):
                events_after(number)
                self.open.add(Step(state, self.domain.action(action).id, len(self.open.steps) + 1),
                              m.ROBOT_DID_STEP(self.lang, action=self.domain.action(action).label(self.lang)))
            events_after(len(result.steps))
            self.open.robot_steps = len(self.open.steps)
        self._note_open_demonstration("run")  # how the run ended is on disk before the teacher hears of it
        self.store.save_journal(self.journal)
        if not result.steps and finished:
            return [Reply(ReplyKind.SAY, m.NOTHING_TO_DO(self.lang))]
        done = ", ".join(self.domain.action(a).label(self.lang) for _, a in result.steps)
        replies = [Reply(ReplyKind.INFO, m.I_DID(self.lang, actions=done) if done else m.I_DID_NOTHING(self.lang))]
        tried = tried_lines(failed_tries(watch, started, result), self.domain, self.lang)
        replies += [Reply(ReplyKind.INFO, line) for line in tried]
        if finished:
            replies.append(Reply(ReplyKind.SAY, m.TASK_FINISHED(self.lang)))
            return replies + [self._state_reply()]
        if result.outcome is Outcome.INTERRUPTED and stop_after is None and started:  # Ctrl-C: say where
            message = m.STOPPED_DURING(self.lang, action=self.domain.action(started[-1][1]).label(self.lang))
        elif result.outcome is Outcome.INTERRUPTED:
            message = m.STOPPED(self.lang)
        elif result.outcome is Outcome.SUCCESS:
            message = m.THOUGHT_DONE(self.lang, unmet=unmet)
        elif result.outcome is Outcome.FAILURE and tried:  # what failed is said above
            message = m.STUCK_AFTER_TRYING(self.lang)
        else:
            message = m.STUCK(self.lang, outcome=_OUTCOME_WORDS[result.outcome](self.lang))
        replies += [Reply(ReplyKind.SAY, message), self._state_reply()]
        if result.outcome in (Outcome.SUCCESS, Outcome.FAILURE):  # "I thought I was done", or nothing fits
            replies += self._ask_after_run()
        return replies

    def cmd_stop(self, rest: str) -> list[Reply]:
        return [Reply(ReplyKind.INFO, m.NOT_RUNNING(self.lang))]

    def cmd_show(self, rest: str) -> list[Reply]:
        full = normalize(rest) in _FULL_WORDS
        if self.pruned is None and self.planned is not None:
            return [self._tree_reply(self.planned, full)]
        if self.pruned is None:
            return [Reply(ReplyKind.INFO, m.NO_TREE(self.lang))]
        return [self._tree_reply(self.learning.tree if full else self.pruned, full)]

    def cmd_state(self, rest: str) -> list[Reply]:
        return [self._state_reply(full=normalize(rest) in _FULL_WORDS)]

    def cmd_start(self, rest: str) -> list[Reply]:
        if self.open is not None and self.open.steps:
            return [Reply(ReplyKind.ERROR, m.FINISH_FIRST(self.lang))]
        names = self._condition_names(rest)
        self.world.arrange(self.domain.state(names))
        self.topic = self.phrases.topic_in(rest)  # "start ball found", then "go to it"
        self._journal(Situated(state_text(self.world.state()), "start"))  # on disk before the teacher sees it
        return [self._state_reply()]

    def _condition_names(self, text: str) -> list[str]:
        """The conditions a teacher names, as labels in either language ("the bin is within reach,
        ich sehe den Ball") or names in any case ("BallFound binclose"), parts split at commas and "and"."""
        names: list[str] = []
        for part in (p for p in _PARTS.split(text) if p.strip()):
            whole = self._condition_named(part)
            for word in [part] if whole is not None else part.split():  # else names side by side
                found = self._condition_named(word)
                if found is None:
                    known = ", ".join(c.label(self.lang) for c in self.domain.conditions)
                    raise TeachError(m.UNKNOWN_CONDITION(self.lang, name=word.strip(), known=known))
                names.append(found)
        return names

    def _condition_named(self, text: str) -> str | None:
        key = normalize(text)
        for condition in self.domain.conditions:
            if key in {normalize(condition.name), normalize(_spelled(condition.name)), normalize(condition.en),
                       normalize(condition.de)}:
                return condition.name
        return None

    def _node_named(self, text: str) -> str:
        """The action or condition ``why`` asks about: its label, its name in any case, or any
        words the prompt would take as that one step ("grab it", a typo), also a verb alone
        ("why grab", "warum greifen": read as "grab it", "ihn greifen")."""
        condition = self._condition_named(text)
        if condition is not None:
            return condition
        key = normalize(text)
        for action in self.domain.actions:
            if key in {normalize(action.name), normalize(_spelled(action.name))}:
                return action.name
        for words in (text, f"{text} it", f"it {text}"):
            try:
                tokens = self.phrases.parse(words, self.lang, topic=self.topic)
            except UnknownPhrase:
                continue
            if len(tokens) == 1 and tokens[0].kind == "action":
                return tokens[0].name
        return text.strip()

    def cmd_reset(self, rest: str) -> list[Reply]:
        if self.open is not None and self.open.steps:
            return [Reply(ReplyKind.ERROR, m.FINISH_FIRST(self.lang))]
        self.open = None
        seed = _number(rest, self.lang)
        self.world.reset(seed)
        self._journal(Situated(state_text(self.world.state()), "reset", seed))  # on disk before the teacher sees it
        return [self._state_reply()]

    def cmd_ask(self, rest: str) -> list[Reply]:
        if self.model_repair is not None and not self.model_repair.plan().usable:
            return self._ask_model()
        replies = self._maybe_ask(force=True)
        return replies or [Reply(ReplyKind.INFO, self._no_question_text())]

    def cmd_skip(self, rest: str) -> list[Reply]:
        return [Reply(ReplyKind.INFO, m.NO_QUESTION_OPEN(self.lang))]

    def cmd_why(self, rest: str) -> list[Reply]:
        if self.pruned is None:
            return [Reply(ReplyKind.INFO, m.NO_TREE(self.lang))]
        name = self._node_named(rest)
        lines = self.learning.why(name, self.lang)
        if lines is None:
            return [Reply(ReplyKind.ERROR, m.NO_SUCH_NODE(self.lang, name=rest.strip()))]
        return [Reply(ReplyKind.INFO, "\n".join(f"- {line}" for line in lines))]

    def cmd_save(self, rest: str) -> list[Reply]:
        self.store.save_journal(self.journal)
        self.observer.checkpoint()
        where = ", ".join(map(str, self.store.places()))
        return [Reply(ReplyKind.INFO, m.SAVED(self.lang, places=where))]

    def cmd_quit(self, rest: str) -> list[Reply]:
        steps = len(self.open.steps) if self.open is not None else 0
        if steps and self._quit_warned_at != self.step - 1:  # not right after the warning
            self._quit_warned_at = self.step
            return [Reply(ReplyKind.ERROR, m.OPEN_ON_QUIT(self.lang, steps=_steps(steps, self.lang)))]
        self.finished = True
        replies = self.cmd_save(rest)
        return replies + [Reply(ReplyKind.SAY, m.GOODBYE(self.lang, session=self.settings.session))]

    # --- action definitions (the thesis's Approach 1, repaired by questions) ---------------

    def cmd_model(self, rest: str) -> list[Reply]:
        from teach.dialogue.model_repair import ModelRepair

        path = Path(rest.strip())
        if not rest.strip():
            return [Reply(ReplyKind.ERROR, m.WHICH_FILE(self.lang))]
        model = self.store.read_model(path)
        if model.condition_names != self.domain.condition_names or \
                not set(model.action_names) <= set(self.domain.action_names):
            raise TeachError(m.MODEL_MISMATCH(self.lang, domain=self.domain.path), path)
        self.model_repair = ModelRepair(model, self.budget, lang=self.lang)
        self.pending_model = None
        self._journal(ModelLoaded(str(path.resolve())))
        return self._show_plan(ask=True)

    def cmd_plan(self, rest: str) -> list[Reply]:
        if self.model_repair is None:
            return [Reply(ReplyKind.ERROR, m.NO_DEFINITIONS(self.lang))]
        return self._show_plan(ask=False)

    def _show_plan(self, ask: bool) -> list[Reply]:
        """What the action definitions give; after a change (``ask``) the tree is saved as a
        generation and, while it is not usable, the next repair question is asked."""
        assert self.model_repair is not None
        outcome = self.model_repair.plan()
        if outcome.usable and outcome.tree is not None:
            self.planned = outcome.tree
            if ask:
                self.learning.save_generation(outcome.tree, "planned from the action definitions")
            return [Reply(ReplyKind.SAY, m.CAN_BUILD(self.lang)), self._tree_reply(outcome.tree)]
        replies = [Reply(ReplyKind.SAY, m.CANNOT_BUILD(self.lang, reason=outcome.reason))]
        return replies + (self._ask_model() if ask else [])

    def _ask_model(self) -> list[Reply]:
        assert self.model_repair is not None
        if self.budget.left <= 0:
            return [Reply(ReplyKind.INFO, self._no_question_text())]
        question = self.model_repair.ask()
        if question is None:
            return [Reply(ReplyKind.INFO, m.NOTHING_TO_ASK(self.lang))]
        self.pending_model = question
        self._journal(Asked(model_question=question.to_json()))
        text = self.model_repair.text(question, self.lang)
        self.observer.on_question(text, self.budget.left)
        return [Reply(ReplyKind.QUESTION, text)]

    def _answer_model(self, line: str) -> list[Reply]:
        assert self.model_repair is not None and self.pending_model is not None
        question = self.pending_model
        text = self.model_repair.text(question, self.lang)
        if normalize(line) in SKIP_WORDS:
            self.pending_model = None
            self.observer.on_answer(text, line, "nothing (skipped)")
            self._journal(ModelAnswered(question.to_json(), "skip"))
            return [Reply(ReplyKind.INFO, m.ASK_ANOTHER(self.lang))]
        change = self.model_repair.apply(question, line)  # UnknownPhrase keeps the question open
        self.pending_model = None
        self.observer.on_answer(text, line, change)
        self._journal(ModelAnswered(question.to_json(), line))
        return [Reply(ReplyKind.INFO, m.THANKS(self.lang, change=change))] + self._show_plan(ask=True)

    # --- demonstrations ---------------------------------------------------------------------

    def _teach_actions(self, text: str) -> list[Reply]:
        return self._act(self.phrases.parse(text, self.lang, topic=self.topic))

    def _act(self, tokens: list[Token]) -> list[Reply]:
        """Do the parsed steps in the world, recording each in the open demonstration (opened if need be)."""
        self.topic = self.phrases.topic(tokens) or self.topic
        replies: list[Reply] = []
        for index, token in enumerate(tokens):
            if token.kind == "event":
                result = self.world.perturb(token.name)
                demo = self._open_for_step()
                demo.add(Step(result.before, EXTERNAL_ACTION, len(demo.steps) + 1),
                         m.EVENT_STEP(self.lang, event=token.text))
                self.observer.on_external(token.name)
                self._save_open()
                replies += self._flush([Reply(ReplyKind.INFO, m.EVENT(self.lang, event=token.text))])
                continue
            result = self.world.act(token.name)
            label = self.domain.action(token.name).label(self.lang)
            if not result.ok:
                replies.append(Reply(ReplyKind.ERROR, m.COULD_NOT(self.lang, action=label,
                                                                  reason=why_not(self.domain, token.name, result.before,
                                                                                 self.lang))))
                if self.facilitator and result.message:  # the world's own words are for the facilitator
                    replies.append(Reply(ReplyKind.INFO, m.DETAILS(self.lang, details=result.message)))
                break
            if result.events:  # the world stopped it: the rest of the line no longer fits
                replies += self._flush(self._halted(token.name, result) + self._not_done(tokens[index + 1:]))
                break
            if result.after == result.before:
                # a step that changes nothing would teach two different actions in one state
                replies += self._flush([Reply(ReplyKind.INFO, m.NOTHING_CHANGED(self.lang, action=label))])
                continue
            demo = self._open_for_step()
            demo.add(Step(result.before, self.domain.action(token.name).id, len(demo.steps) + 1), label)
            self._save_open()
            replies += self._flush([Reply(ReplyKind.INFO, m.DID_STEP(self.lang, action=label))])
        replies.append(self._state_reply())
        return replies

    def _open_for_step(self) -> _OpenDemo:
        """The open demonstration, opened when its first step has happened (a failed first step opens none)."""
        if self.open is None:
            self.open = _OpenDemo()
            self._flush([Reply(ReplyKind.INFO, m.NEW_DEMONSTRATION(self.lang))])
        return self.open

    def _halted(self, action: str, result: ActResult) -> list[Reply]:
        """An action the world's events halted: its own part kept as a step if it changed
        anything (else dropped: said which), then each event as an external step (-1)."""
        label = self.domain.action(action).label(self.lang)
        if result.action_after != result.before:
            demo = self._open_for_step()
            demo.add(Step(result.before, self.domain.action(action).id, len(demo.steps) + 1),
                     m.HALTED_STEP(self.lang, action=label))
        kept = m.HALTED_KEPT if result.action_after != result.before else m.HALTED_DROPPED
        replies = [Reply(ReplyKind.INFO, kept(self.lang, action=label))]
        for event in result.events:
            self._add_event(event)
            replies.append(self._event_reply(event))
        self._save_open()  # on disk before the teacher sees the event
        return replies

    def _add_event(self, event: WorldEvent) -> None:
        """An event of the world as an external step (-1) of the open demonstration."""
        demo = self._open_for_step()
        demo.add(Step(event.before, EXTERNAL_ACTION, len(demo.steps) + 1),
                 m.EVENT_STEP(self.lang, event=m.Text(event.en, event.de)(self.lang)))

    def _event_reply(self, event: WorldEvent) -> Reply:
        return Reply(ReplyKind.INFO, m.EVENT(self.lang, event=m.Text(event.en, event.de)(self.lang)))

    def _not_done(self, tokens: list[Token]) -> list[Reply]:
        if not tokens:
            return []
        words = [t.text if t.kind == "event" else self.domain.action(t.name).label(self.lang) for t in tokens]
        return [Reply(ReplyKind.INFO, m.REST_NOT_DONE(self.lang, actions=", ".join(words)))]

    def _finish_demo(self) -> list[Reply]:
        assert self.open is not None
        started = time.perf_counter()
        path = self.store.next_demo_path()
        demo = Demonstration(path.stem, tuple(self.open.steps), path)
        source = path.name
        try:
            update = self.learning.learn_demonstration(demo, source)
        except LearnError as error:
            self.open.steps.pop()  # the goal line: the demonstration stays open to be mended
            return [Reply(ReplyKind.ERROR, m.CANNOT_LEARN(self.lang, why=why_refused(error, self.lang))),
                    Reply(ReplyKind.INFO, m.DETAILS(self.lang, details=error.message))]
        self.store.write_demonstration(path, demo)
        self.open = None
        self.topic = None  # "it" in the next demonstration is whatever it names first
        self.observer.on_demonstration(demo.name, demo, self.domain)
        self.learning.report("specialize", update, self.lang)
        return self._after_learning(ask=True, started=started, events=[DemoLearned(path.name, source)])

    def import_demonstrations(self, demos: list[Demonstration]) -> list[Reply]:
        """Learn demonstrations recorded elsewhere (one generation for all of them)."""
        self._turn = []
        started = time.perf_counter()
        events: list[Event] = []
        for demo in demos:
            path = self.store.next_demo_path()
            source = f"imported {demo.name} ({path.name})"
            self.learning.learn_demonstration(demo, source)
            self.store.write_demonstration(path, demo)
            events.append(DemoLearned(path.name, source))
            self.observer.on_demonstration(demo.name, demo, self.domain)
        return self._end_turn(self._after_learning(ask=False, started=started, events=events))

    # --- questions --------------------------------------------------------------------------

    def _maybe_ask(self, force: bool = False) -> list[Reply]:
        """Ask the best question if the budget allows; unforced, at most QUESTIONS_PER_TURN in a row."""
        if self.pending is not None:
            return []
        if not force and (len(self.demos) < MIN_DEMOS_BEFORE_ASKING or self._turn_questions >= QUESTIONS_PER_TURN):
            return []
        question = self.next_question()
        return [] if question is None or not self._affordable(question.state) else self._ask(question)

    def _ask_after_run(self) -> list[Reply]:
        """A run that ended "done" with the goal unmet, or doing nothing: the situation it ended
        in is the most useful question there is, so it is asked at once while questions are left."""
        state = self.world.state()
        if not self.learning.has_behaviour:  # a tree planned from action definitions: their questions come from 'model'
            return []
        if self.pending is not None or state in self.learning.asked or not self._affordable(state):
            return []
        return self._ask(self.learning.question_where_stuck(state) or Question(state, 1.0))

    def _affordable(self, state: State) -> bool:
        """Whether a question about ``state`` may be asked: one is left, or it was paid for already."""
        return self.budget.left > 0 or state_text(state) in self._charged()

    def _ask(self, question: Question) -> list[Reply]:
        """Ask ``question``: paid for once per situation, even if an undo made it open again."""
        if state_text(question.state) not in self._charged():
            self.budget.spend()
        self._turn_questions += 1
        self.pending = question
        self.learning.asked.add(question.state)
        self._journal(Asked(state=state_text(question.state)))
        return [self._question_reply(question)]

    def _charged(self) -> set[str]:
        """The situations asked about so far (undone or not): each was paid for once."""
        impossible = {event.state for event in self.journal.events
                      if isinstance(event, Answered) and event.answer == IMPOSSIBLE}
        return {event.state for event in self.journal.events
                if isinstance(event, Asked) and event.state and event.state not in impossible}

    def _question_reply(self, question: Question) -> Reply:
        text = question.text(self.domain, self.lang)
        self.observer.on_question(text, self.budget.left)
        yes = [m.YES_WORD(self.lang)] if question.kind in MUST_KINDS else []
        options = " / ".join(yes + [a.label(self.lang) for a in self.domain.actions] +
                             [m.DONE_WORD(self.lang), m.SKIP_WORD(self.lang)])
        return Reply(ReplyKind.QUESTION, f"{text}\n   ({options})")

    def next_question(self) -> Question | None:
        return self.learning.next_question(self.settings.seed)

    def _answer(self, line: str) -> list[Reply]:
        question = self.pending
        assert question is not None
        key = normalize(line)
        if key in SKIP_WORDS:
            self.pending = None
            text = question.text(self.domain, self.lang)
            self._journal(Answered(state_text(question.state), "skip", text))
            self.observer.on_answer(text, line, "nothing (skipped)")
            return [Reply(ReplyKind.INFO, m.KEEP_CAREFUL(self.lang))]
        if key in IMPOSSIBLE_WORDS:
            return self._cannot_happen(question)
        yes = question.kind in MUST_KINDS and bool(line.strip()) and is_yes(line, self.lang)
        if question.kind in MUST_KINDS and is_no(line, self.lang):
            return [Reply(ReplyKind.QUESTION, m.WHAT_INSTEAD(self.lang))]  # the question stays open
        if key in DONE_WORDS or (yes and question.action is None):
            unmet = unmet_goal(self.domain, question.state, self.lang)
            if unmet:  # the question stays open and is not paid for again
                return [Reply(ReplyKind.ERROR, m.NOT_DONE_THERE(self.lang, unmet=unmet)),
                        self._question_reply(question)]
            answer: str | None = None
        else:
            if yes:
                answer = question.action
            else:
                tokens = [t for t in self.phrases.parse(line, self.lang) if t.kind == "action"]
                if len(tokens) != 1:
                    return [Reply(ReplyKind.ERROR, m.ONE_ACTION(self.lang))]
                answer = tokens[0].name
            assert answer is not None
            if missing_preconditions(self.domain, question.state, answer):
                # as for 'done': an answer the domain file shows cannot work there is not learned
                label = self.domain.action(answer).label(self.lang)
                reason = why_not(self.domain, answer, question.state, self.lang)
                return [Reply(ReplyKind.ERROR, m.COULD_NOT(self.lang, action=label, reason=reason)),
                        self._question_reply(question)]
        return self.apply_answer(answer, line)

    def _cannot_happen(self, question: Question) -> list[Reply]:
        """The asked-about situation cannot happen: journalled, never asked again, and not paid for."""
        self.pending = None
        text = question.text(self.domain, self.lang)
        self._journal(Answered(state_text(question.state), IMPOSSIBLE, text))
        self.learning.rule_out(question.state, f"answer to question {self.budget.used}")
        self.budget.used -= 1
        self.observer.on_answer(text, IMPOSSIBLE, "nothing (that situation cannot happen)")
        return [Reply(ReplyKind.INFO, m.CANNOT_HAPPEN(self.lang))]

    def apply_answer(self, answer: str | None, said: str) -> list[Reply]:
        """Learn from the answer to the pending question (None: the task is done there)."""
        question = self.pending
        assert question is not None
        started = time.perf_counter()
        text = question.text(self.domain, self.lang)
        source = f"answer to question {self.budget.used}"
        self.pending = None
        try:
            update = self.learning.learn_answer(question.state, answer, source, _asked_about(question))
        except LearnError as error:
            return [Reply(ReplyKind.ERROR, m.CONTRADICTS(self.lang, why=why_refused(error, self.lang))),
                    Reply(ReplyKind.INFO, m.DETAILS(self.lang, details=error.message))]
        change = self.learning.describe(update, self.lang)
        # the answer is on disk before the teacher is thanked for it: a kill cannot lose it
        self._journal(Answered(state_text(question.state), answer or "done", text, _asked_about(question)))
        self.observer.on_answer(text, said, change)
        self.learning.report("answer", update, self.lang)
        head = self._flush([Reply(ReplyKind.INFO, m.THANKS(self.lang, change=change))])
        return head + self._after_learning(ask=True, started=started)

    def _no_question_text(self) -> str:
        return (m.ALL_QUESTIONS_USED if self.budget.left <= 0 else m.NO_QUESTION_NOW)(self.lang)

    # --- learning results -------------------------------------------------------------------

    def _after_learning(self, ask: bool, started: float | None = None,
                        events: list[Event] | None = None) -> list[Reply]:
        """Commit ``events`` to the journal, then prune, save the generation, show, replay and
        maybe ask. Journal first, as for answers: a kill between the two leaves a learned event
        whose generation the teacher never saw (a resume learns it again), never a generation
        file no journalled event explains."""
        from teach.replay import replay

        if events:
            self._journal(*events)
        if not self.learning.has_behaviour:  # only goal states so far: there is no behaviour to show yet
            return self._flush([Reply(ReplyKind.INFO, m.GOAL_ONLY(self.lang))])
        pruned = self.learning.prune()
        path = self.learning.save_generation(pruned, "learned from demonstrations and answers")
        report = replay(pruned, self.domain, self.demos)
        self.observer.on_replay(report.reproduced, report.total)
        # node counts and the file are for the facilitator; the teacher hears what it means
        summary = (m.GENERATION if self.facilitator else _reproduced_text(report.reproduced, report.total))(
            self.lang, generation=self.generation, nodes=size(pruned), unpruned=size(self.learning.tree), path=path,
            reproduced=report.reproduced, total=report.total)
        replies = self._flush([self._tree_reply(pruned), Reply(ReplyKind.INFO, summary)])
        if ask:
            replies += self._maybe_ask()
        return replies

    # --- the journal: undo and resume -------------------------------------------------------

    def _journal(self, *events: Event) -> None:
        self.journal.events.extend(events)
        for event in events:  # the observers' session channel, in the journal's order
            self.observer.on_session_event(event)
        self._note_open_demonstration()  # a finished demonstration is never also journalled as open
        self.store.save_journal(self.journal)

    def _rebuild_from_journal(self) -> None:
        """Re-learn everything in the journal (after an undo or on resume), deterministically."""
        try:
            self._replay_journal()
        except (KeyError, TypeError, ValueError, AttributeError) as error:
            raise FormatError(f"the session journal is damaged ({type(error).__name__}: {error})",
                              self.store.journal_path) from None

    def _replay_journal(self) -> None:
        from teach.dialogue.model_repair import ModelQuestion, ModelRepair

        self.learning.restart()
        self.model_repair, self.pending_model, self.planned = None, None, None
        # every question asked stays paid for, even when what it was about is undone
        asked = [e for e in self.journal.events if isinstance(e, Asked)]
        self.budget = QuestionBudget(self.settings.questions, len(self._charged()) + sum(not e.state for e in asked))
        answered = 0
        for event in effective_events(self.journal.events):
            if isinstance(event, DemoLearned):
                self.learning.learn_demonstration(self.store.read_demonstration(event.file, self.domain),
                                                  event.source)
            elif isinstance(event, ModelLoaded):
                self.model_repair = ModelRepair(self.store.read_model(Path(event.file)), self.budget, lang=self.lang)
            elif isinstance(event, ModelAnswered) and self.model_repair is not None:
                if event.answer != "skip":
                    self.model_repair.apply(ModelQuestion.from_json(event.question), event.answer)
            elif isinstance(event, Answered):
                answered += 1
                state = parse_state_text(event.state)
                if len(state) != len(self.domain.conditions):
                    raise ValueError(f"an answered state has {len(state)} values, not {len(self.domain.conditions)}")
                if event.answer not in ("skip", "done", IMPOSSIBLE) and event.answer not in self.domain.action_names:
                    raise FormatError(m.UNKNOWN_JOURNAL_ACTION(
                        "en", number=self.journal.events.index(event), action=event.answer), self.store.journal_path)
                self.learning.asked.add(state)
                if event.answer == IMPOSSIBLE:
                    self.learning.rule_out(state, f"answer to question {answered}")
                elif event.answer != "skip":
                    try:
                        self.learning.learn_answer(state, None if event.answer == "done" else event.answer,
                                                   f"answer to question {answered}", event.asked_about)
                    except LearnError:
                        pass  # it was rejected when it was given, too
        if self.learning.has_behaviour:
            self.learning.prune()
        if self.model_repair is not None:
            outcome = self.model_repair.plan()
            self.planned = outcome.tree if outcome.usable else None

    @classmethod
    def resume(cls, settings: Settings, domain: Domain, world: TeachingWorld,
               observer: Observer | None = None) -> SessionManager:
        store = SessionStore(settings.base, settings.session, settings.record)
        journal = store.load_journal()
        manager = cls(settings, domain, world, observer, journal)
        manager.guiding.restore(journal.events)
        manager._rebuild_from_journal()
        manager.step = journal.step + 1  # a step of its own: the kill may have come before the save
        manager.observer.set_time(manager.step)
        current = manager.pruned or manager.planned
        if current is not None:
            from teach.bt.xml import tree_to_xml

            manager.observer.on_tree(manager.generation, current, tree_to_xml(current), "resumed")
        manager._restore_situation()
        manager._restore_open_demonstration()
        return manager

    # --- helpers ---------------------------------------------------------------------------

    def _note_open_demonstration(self, how: str = "after") -> None:
        """Put the open demonstration's steps in the journal: every "✓" the teacher saw is on disk
        before the next prompt, and a resume (after a kill or a quit) shows them again. With none
        open, the world's situation is journalled when it changed (a demonstration finished or
        cancelled, an undo), so a resume sets it up again."""
        steps = self.open.steps if self.open is not None else []
        words = self.open.words if self.open is not None else []
        self.journal.open_steps = [[state_text(step.state), step.action, words[i] if i < len(words) else ""]
                                   for i, step in enumerate(steps)]
        self.journal.open_state = state_text(self.world.state()) if steps else ""
        self.journal.open_run = ""
        if not steps and state_text(self.world.state()) != self._last_situation():
            self.journal.events.append(situated := Situated(state_text(self.world.state()), how))
            self.observer.on_session_event(situated)

    def _save_open(self) -> None:
        """The open demonstration on disk now: a "✓" shown while a line still runs (a live
        driver shows each step at once) survives a kill during the line's next step."""
        self._note_open_demonstration()
        self.store.save_journal(self.journal)

    def _note_run(self, started: list[tuple[State, str]]) -> None:
        """Journal a run as it goes: the actions the robot finished (each ends as the next begins)
        as the open steps, and the world before the action it has just begun, so a resume after a
        kill mid-run reopens them as the corrective demonstration a stopped run would give."""
        self.journal.open_steps = [
            [state_text(state), self.domain.action(action).id,
             m.ROBOT_DID_STEP(self.lang, action=self.domain.action(action).label(self.lang))]
            for state, action in started[:-1]]
        self.journal.open_state, self.journal.open_run = state_text(started[-1][0]), started[-1][1]
        self.store.save_journal(self.journal)

    def _last_situation(self) -> str:
        """The world's situation as last journalled (its seeded start when none was)."""
        for event in reversed(self.journal.events):
            if isinstance(event, Situated):
                return event.state
        return self._start_situation

    def _journalled_state(self, text: str, what: str) -> State:
        state = parse_state_text(text)
        if len(state) != len(self.domain.conditions):
            raise FormatError(f"{what}: has {len(state)} values, not {len(self.domain.conditions)}",
                              self.store.journal_path)
        return state

    def _restore_situation(self) -> None:
        """Set the world up as the journal last saw it with no demonstration open, and say so. A
        'reset N' is made again exactly; otherwise the conditions are arranged, which in MuJoCo
        places the objects anew (the teacher is told)."""
        last = next((e for e in reversed(self.journal.events) if isinstance(e, Situated)), None)
        if last is None:
            if self.demos:  # a journal from before situations were journalled
                self.world.arrange(self.demos[-1].steps[-1].state)
            return
        state = self._journalled_state(last.state, f"events[{self.journal.events.index(last)}]: state")
        exact = self.settings.world is not WorldKind.MUJOCO
        try:
            if last.seed is not None:
                self.world.reset(last.seed)
                exact = self.world.state() == state
            if not exact or self.world.state() != state:
                self.world.arrange(state)
        except TeachError:  # the world cannot be put in that situation
            situation = describe_situation(self.domain, state, self.lang)
            self.restored = [Reply(ReplyKind.INFO, m.SITUATION_NOT_RESTORED(self.lang, situation=situation))]
            return
        text = m.SITUATION_RESTORED if exact else m.SITUATION_RESTORED_ANEW
        self.restored = [Reply(ReplyKind.INFO, text(self.lang))]

    def _restore_open_demonstration(self) -> None:
        """Reopen the demonstration that was open when the session ended; a run the session ended
        in becomes the correction its finished steps begin, the world set up before the action it
        had begun."""
        run = self.journal.open_run
        if not self.journal.open_steps and not run:
            return
        if run and run not in self.domain.action_names:
            raise FormatError(f"open_run: {run[:40]!r} is not an action of the domain", self.store.journal_path)
        steps = [(self._journalled_state(str(state), f"open_steps[{number}]"), int(action), str(words))
                 for number, (state, action, words) in enumerate(self.journal.open_steps)]
        where = self._journalled_state(self.journal.open_state, "open_state")
        try:
            self.world.arrange(where)
        except TeachError:  # the world cannot be put back there: the last situation stays
            return
        self.open = _OpenDemo() if steps else None
        for number, (state, action, words) in enumerate(steps, 1):
            assert self.open is not None
            self.open.add(Step(state, action, number), words)
        if run:
            label = self.domain.action(run).label(self.lang)
            text = m.RUN_RESTORED(self.lang, action=label, steps=_steps(len(steps), self.lang)) if steps else \
                m.RUN_RESTORED_NO_STEPS(self.lang, action=label)
        else:
            text = m.OPEN_RESTORED(self.lang, steps=_steps(len(steps), self.lang))
        self.restored = [Reply(ReplyKind.INFO, text)]

    def _tree_reply(self, tree: Node, full: bool = False) -> Reply:
        """The tree in sentences of the session's language; the symbols too for a facilitator or 'show full'."""
        words = "" if full or self.facilitator else "\n".join(tree_lines(tree, self.domain, self.lang))
        return Reply(ReplyKind.TREE, words, tree=tree)

    def _state_reply(self, full: bool = False) -> Reply:
        """The situation in words; the conditions' names and values too for a facilitator or 'state full'."""
        state = self.world.state()
        values = dict(zip(self.domain.condition_names, state, strict=True)) if full or self.facilitator else None
        return Reply(ReplyKind.STATE, describe_situation(self.domain, state, self.lang), state=values)

    def _tick_clock(self) -> None:
        self.step += 1
        self.journal.step = self.step
        self.observer.set_time(self.step)

    def _flush(self, replies: list[Reply]) -> list[Reply]:
        """The one way a reply leaves the session: told to the observer, added to the line's
        replies and shown by a live driver at once (the tree appears before a question is
        chosen). Returns nothing left to hand back."""
        for reply in replies:
            if reply.spoken:  # questions go to on_question
                self.observer.on_dialogue("robot", reply.text, self.budget.left)
        self._turn.extend(replies)
        if self.live is not None:
            for reply in replies:
                self.live(reply)
        return []

    def _end_turn(self, replies: list[Reply]) -> list[Reply]:
        """Send the last replies and hand back all of this turn's, in the order they were sent."""
        self._flush(replies)
        turn, self._turn = self._turn, []
        return turn

    def _handler(self, command: Command) -> Callable[[str], list[Reply]]:
        handler: Callable[[str], list[Reply]] = getattr(self, command.handler)
        return handler


_UNHANDLED = [command.name for command in COMMANDS if not callable(getattr(SessionManager, command.handler, None))]
if _UNHANDLED:  # a command declared in teach/session/commands.py needs its cmd_ method here
    raise TypeError(f"commands without a handler: {', '.join(_UNHANDLED)}")


_OUTCOME_WORDS = {Outcome.SUCCESS: m.OUTCOME_SUCCESS, Outcome.FAILURE: m.OUTCOME_FAILURE,
                  Outcome.TIMEOUT: m.OUTCOME_TIMEOUT, Outcome.INTERRUPTED: m.OUTCOME_INTERRUPTED}
_FULL_WORDS = ("full", "ganz", "all", "alles")
_PARTS = re.compile(r"\s*(?:,|;|\band\b|\bund\b)\s*", re.IGNORECASE)


def _counted(count: int, none: m.Text, one: m.Text, many: m.Text) -> m.Text:
    """The text for ``count`` things: "no questions", "1 question", "2 questions"."""
    return none if count == 0 else one if count == 1 else many


def _steps(count: int, lang: str) -> str:
    """How many steps, in words: "1 step", "3 steps"."""
    return (m.STEP_COUNT if count == 1 else m.STEPS_COUNT)(lang, count=count)


def _reproduced_text(reproduced: int, total: int) -> m.Text:
    """How many demonstrations the new tree does as shown, said for one, all or some of them."""
    if total == 1:
        return m.GENERATION_PLAIN_THE_ONE if reproduced == 1 else m.GENERATION_PLAIN_NOT_THE_ONE
    return m.GENERATION_PLAIN_ALL if reproduced == total else m.GENERATION_PLAIN


def _spelled(name: str) -> str:
    """An identifier as words: BallFound → "Ball Found"."""
    return re.sub(r"(?<!^)(?=[A-Z])", " ", name)


_STEP_WORDS = {"step", "steps", "schritt", "schritte", "bis", "ab", "from", "back", "zuruck"}


def _step_number(text: str, lang: str) -> int | None:
    """The step an undo goes back to: "3", "to step 3", "bis Schritt 3"; None when none is named."""
    words = [w for w in normalize(text).split() if w not in _STEP_WORDS]
    return _number(" ".join(words), lang)


def _number(text: str, lang: str) -> int | None:
    """An optional whole number argument ("run 3", "reset 7")."""
    if not text.strip():
        return None
    try:
        value = int(text.strip())
    except ValueError:
        raise TeachError(m.WHOLE_NUMBER(lang, text=text.strip())) from None
    if value < 0:
        raise TeachError(m.NOT_NEGATIVE(lang))
    return value


def _asked_about(question: Question) -> str | None:
    """What a "may I still …?" or "is the task done?" question asked about (None: a plain one)."""
    if question.kind == "must-goal":
        return DONE_ABOUT
    return question.action if question.kind == "must-precondition" else None
