"""The session machine: a plain state machine that turns teacher lines into replies.

It interleaves demonstrations in a world, online learning after every demonstration (through
``teach.session.learning``), at most ``budget`` clarifying questions, and runs of the learned
tree that the teacher can interrupt and correct. Every driver (the terminal, scripted replays,
bench-teach) feeds lines to ``handle(line, interrupt)``, which returns every reply of that line
in order. A driver that shows replies while a line is still being handled (steps as they
happen, run progress) sets ``live``: it then sees each of those same replies once, as it is
produced; between lines it reads ``view()``. Files are read and written only through the
``SessionStore``.

The machine keeps dispatch, the commands and the learning results; the state it shares is
owned by the pieces it composes, which guiding and the hand follower get instead of the
machine: the session record (journal, store, open demonstration: the one place that
journals), the turn (the replies of one line) and ``Showing`` (the open demonstration in
words); ``Asking`` holds the situation questions, ``Definitions`` the action definitions,
``Relearning`` rebuilds what was learned from the journal (resume, undo, redo). Its older
members (``domain``, ``journal``, ``pending`` …) are windows onto these owners, in ``compat.py``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

from teach import messages as m
from teach.bt.nodes import Node, size
from teach.demos import Demonstration
from teach.dialogue.phrases import (
    PRONOUN,
    LineTooLong,
    Suggestion,
    Token,
    UnknownPhrase,
    check_length,
    command_hint,
    is_no,
    is_yes,
    normalize,
)
from teach.dialogue.questions import describe_situation, join_words
from teach.domain import Domain, State
from teach.errors import LearnError, TeachError
from teach.messages import Lang
from teach.observe.hook import Observer
from teach.session import running
from teach.session.arguments import (
    ConditionGuess,
    condition_names,
    node_named,
    says_full,
    stated_condition,
    step_number,
    untrue_asked,
    whole_number,
)
from teach.session.asked_back import done_yet, what_task, why_that
from teach.session.asking import Asking
from teach.session.commands import (
    AGAIN_WORDS,
    ANSWERING,
    ANSWERS_ONLY,
    ASKING_SOMEONE,
    BACK_WORDS,
    BLOCKED_WHILE_ASKING,
    COMMAND_NAMES,
    COMMANDS,
    DONE_YET_WORDS,
    DOUBT_WORDS,
    GOING_ON_WORDS,
    LOOKING,
    NO_MATTER_WORDS,
    NUMBERED,
    SKIP_WORDS,
    TASK_WORDS,
    WHAT_NOW_WORDS,
    WHERE_STARTS,
    WHO_WORDS,
    WHY_ASKING,
    WHY_ASKING_LINES,
    Command,
    Verb,
    after_courtesy,
    after_holding_on,
    is_greeting,
    is_praise,
    meant_instead,
    parse_command,
    typo_of_command,
    without_hesitation,
)
from teach.session.compat import CompatMembers
from teach.session.definitions import Definitions
from teach.session.describe import actions_to_name, some_actions, unmet_goal, why_refused
from teach.session.guiding import STOP_WORDS, Guiding
from teach.session.journal import Answered, Asked, DemoLearned, Event, Journal, Situated, state_text
from teach.session.learning import Learning
from teach.session.published import Mode, SessionView
from teach.session.record import IMPOSSIBLE, SessionRecord
from teach.session.relearning import Relearning
from teach.session.replies import Reply, ReplyKind
from teach.session.resumed import restore_open, restore_situation
from teach.session.settings import Settings, WorldKind
from teach.session.showing import Showing, steps_said
from teach.session.starting import demonstrated_start
from teach.session.store import SessionStore
from teach.session.tree_words import tree_lines
from teach.session.turn import Turn
from teach.session.vocabulary import Vocabulary
from teach.symbolic import possible_actions
from teach.world.protocol import TeachingWorld

MAX_WHICH = 4
"""The most steps offered for a line that names all but their last object ("put c on")."""


class SessionManager(CompatMembers):
    """One teaching session. Not thread-safe: one driver feeds it lines."""

    def __init__(self, settings: Settings, domain: Domain, world: TeachingWorld, observer: Observer | None = None,
                 journal: Journal | None = None):
        self.settings = settings
        self.world = world
        self.observer = observer or Observer()
        self.lang = settings.lang
        self.vocabulary = Vocabulary(domain, world.events)
        journal = journal or Journal(settings.session, str(domain.path or ""), settings.lang, settings.questions,
                                     settings.world, settings.seed, guess=not settings.safe)
        self.record = SessionRecord(journal, SessionStore(settings.base, settings.session, settings.record),
                                    self.observer, world.state)
        self.turn = Turn(self.observer, lambda: self.budget.left)
        self.showing = Showing(self.record, self.turn, world, self.vocabulary, self.lang)
        self.learning = Learning(domain, self.store, self.observer, settings.safe, world.can_happen)
        self.asking = Asking(self.record, self.learning, self.vocabulary, self.turn, self.lang, world.state,
                             settings.seed, settings.questions,
                             lambda started, answered: self._after_learning(True, started, answered=answered))
        self.definitions = Definitions(self.record, self.learning, lambda: self.budget, self.lang, self._tree_reply)
        self.relearning = Relearning(self.record, self.learning, self.definitions, self.asking, self.vocabulary,
                                     settings.questions, self.lang)
        self.suggestion: Suggestion | None = None  # a "Did you mean …?" waiting for yes or no
        self.retype: str | None = None  # ... of a command or an answer word: the line a yes stands for
        self.topic: str | None = None  # the object named last: what "it" means in the next line
        self.facilitator = settings.facilitator  # identifiers and the symbolic tree too (--facilitator)
        self.finished = False
        self._quit_warned_at = -2
        """The step at which quitting with an open demonstration was warned about."""
        self.step = 0
        self._interrupt: Callable[[], bool] | None = None
        self._reaching = False
        """The line is a yes to an offered way: its steps are planned again where one turns out impossible."""
        self.again: str | None = None
        """What "again" on the next line does: the step the line before did, or its guided move."""
        self.last_step: tuple[str, bool] | None = None
        """The step the line before did and whether the learned tree chose it (not the teacher):
        what "why did you do that?", "are you sure?" on the next line ask about."""
        self.restored: list[Reply] = []  # what a resume set up again, said in greet
        self.store.prepare(domain)
        self.observer.on_domain(domain)
        self.guiding = Guiding(self.showing, self.record, self.turn, settings.label_questions, self.relearning.adopt)

    # --- what drivers read (the owners' older windows: session/compat.py) -------------------

    @property
    def mode(self) -> Mode:
        if self.pending is not None or self.pending_model is not None or self.guiding.pending is not None:
            return Mode.ASKING
        return Mode.DEMONSTRATING if self.open is not None else Mode.IDLE

    def view(self) -> SessionView:
        """The session as its drivers see it now."""
        return SessionView(
            mode=self.mode, lang=self.lang, domain=self.domain, phrases=tuple(self.phrases.phrases(self.lang)),
            questions_left=self.budget.left,
            generation=self.generation, can_run=self.runnable is not None, guiding=self.guiding.active,
            guided=self.guiding.used, labels_left=self.guiding.budget.left, facilitator=self.facilitator,
            holds=tuple(n for n, v in zip(self.domain.condition_names, self.world.state(), strict=True) if v),
            finished=self.finished, run_dir=self.store.run_dir)

    def key_line(self, key: str) -> str | None:
        """The ``guide …`` line a key of the terminal's guide mode stands for (None: no such key now)."""
        return self.guiding.line_for_key(key)

    @property
    def runnable(self) -> Node | None:
        """The tree 'run' would start now (the unpruned one: pruning assumes actions have only the
        effects seen so far), or None when a run would be refused."""
        if self.open is not None and len(self.open.steps) > self.open.robot_steps:
            return None  # the teacher is showing something: finish or cancel it first
        return self.learning.tree if self.learning.has_behaviour else self.definitions.planned

    # --- the driver's interface -----------------------------------------------------------

    def greet(self) -> list[Reply]:
        replies = [Reply(ReplyKind.SAY, m.HELLO(self.lang, actions=some_actions(self.domain, self.lang)))]
        if not self.demos:  # a resumed session names itself in RESUMED_COUNTED
            replies.insert(0, Reply(ReplyKind.INFO, m.SESSION_ID(self.lang, session=self.settings.session,
                                                                 resume=self.settings.resume_words)))
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
        replies += self._start_replies()
        replies += self.asking.ask_again()  # a question left open when a resumed session ended
        self.turn.begin()
        return self.turn.close(replies)

    def handle(self, line: str, interrupt: Callable[[], bool] | None = None) -> list[Reply]:
        """One teacher line in, every reply to it out, in order. Never raises for bad input.
        ``interrupt`` is polled while the robot runs (the terminal's Ctrl-C)."""
        line = line.strip()
        if not line and self.suggestion is None and self.retype is None and self.showing.offered is None:
            return []
        self.turn.begin()
        self._interrupt = interrupt
        self._tick_clock()
        try:
            check_length(line, self.lang)
        except LineTooLong as too_long:  # neither logged nor echoed: nobody meant that much as one line
            self.suggestion = self.retype = self.showing.offered = self.again = self.last_step = None
            return self.turn.close([Reply(ReplyKind.ERROR, too_long.message)])
        self.observer.on_dialogue("teacher", line, self.budget.left)
        # what the line before left for a yes ("Did you mean …?", "To get there: … Say 'yes' …") or an
        # "again" (its step) is for this line only, but a "hmm" keeps it for the next
        suggestion, retype, offer, again = self.suggestion, self.retype, self.showing.offered, self.again
        doubted = self.last_step
        if not self._only_holding_on(line):
            self.suggestion = self.retype = self.showing.offered = self.again = self.last_step = None
        self.showing.just_done = None
        asking = self.mode is Mode.ASKING
        confirmed = retype is not None and is_yes(line, self.lang)  # the line is the guess, not read as one again
        try:
            if offer is not None and is_yes(line, self.lang) and parse_command(line)[0] is not Verb.DONE:
                self._reaching = True  # (above: "that's it" after an offer is the task finished, not a yes)
                replies = self._dispatch(offer)
            elif offer is not None and is_no(line, self.lang):
                replies = [Reply(ReplyKind.INFO, m.ALL_RIGHT(self.lang))]
            elif retype is not None and is_no(line, self.lang):
                replies = [Reply(ReplyKind.INFO, m.SAY_IT_ANOTHER_WAY(self.lang))]
            elif again is not None and normalize(line) in AGAIN_WORDS and self.pending is None:
                replies = self._dispatch(again)
            elif doubted is not None and normalize(line) in DOUBT_WORDS and self.pending_model is None \
                    and (self.pending is None or normalize(line) not in WHY_ASKING_LINES):
                replies = self._why_that(doubted)
                self.again, self.last_step = again, doubted  # "are you sure?", then "why?" or "again"
            else:
                replies = self._dispatch(retype if confirmed and retype is not None else line, suggestion)
        except UnknownPhrase as unknown:
            # during a situation question only a guessed action is kept: confirming it answers the question
            keep = not asking or (self.pending is not None and unknown.suggestion is not None
                                  and unknown.suggestion.candidate.kind == "action")
            self.suggestion = unknown.suggestion if keep else None
            if not unknown.suggestions and not confirmed and _first_word(unknown.text) == _first_word(line):
                # nothing close, and the line's first word is what was not understood: perhaps a
                # command or an answer word was meant ("hlep"; not "find the ball, xyzzy")
                self.retype = typo_of_command(line, self.lang, self._answer_words(), self.phrases.words)
            moved = None if asking or confirmed else self.guiding.offered_move(line)
            if moved is not None:  # "forward 0.3" just after guiding: "Did you mean “guide forward 0.3”?"
                self.retype, self.suggestion = moved, None
            if self.retype is None and not asking and self.topic is None:
                self.retype = self._meant_by_pronoun(line)
                if self.retype is not None:
                    self.suggestion = None  # the guess at its words ("put c on b") gives way
            which = self._meant_with_object(line) if self.retype is None and not unknown.suggestions \
                and not asking else []
            if len(which) == 1:  # "take c off" where c is on a only: "Did you mean “take c off a”?"
                self.retype, which = which[0], []
            shown = unknown if self.retype is None else UnknownPhrase(unknown.text, [self.retype], self.lang)
            replies = [Reply(ReplyKind.ERROR, shown.message)]
            if which:  # "put c on": "Which one: “put c on a” or “put c on d”?"
                steps = join_words([m.QUOTED(self.lang, text=step) for step in which], self.lang, m.OR)
                replies.append(Reply(ReplyKind.INFO, m.WHICH_STEP(self.lang, steps=steps)))
            elif not shown.suggestions and not asking:  # nothing close ("give them a snack", "what can you do?")
                can = m.WHAT_I_CAN(self.lang, actions=some_actions(self.domain, self.lang))
                if self.world.events:  # "jemand nimmt den Ball weg" was met with the actions alone
                    can += m.WHAT_CAN_HAPPEN(self.lang, events=self._event_names())
                replies.append(Reply(ReplyKind.INFO, can))
            elif not shown.suggestions and self.pending is not None:  # "2", "the second one"
                replies.append(self.asking.answer_hint())
        except ConditionGuess as guess:  # "start in the office": a yes reads it with the condition meant
            self.retype = line.replace(guess.said, guess.meant, 1) if guess.said in line else None
            replies = [Reply(ReplyKind.ERROR, str(guess))]
        except TeachError as error:
            replies = [Reply(ReplyKind.ERROR, str(error))]
        finally:
            self._interrupt, self._reaching = None, False
        if self.showing.just_done is not None:
            self.again = self.domain.action(self.showing.just_done).label(self.lang)
            self.last_step = (self.showing.just_done, False)
        turn = self.turn.close(replies)
        self.observer.checkpoint()
        self.record.note_open()
        self.record.save()  # the step clock too, so a resume goes on from it
        return turn

    def _steps_after_all(self, command: Command | None, rest: str, line: str) -> str | None:
        """A command that takes a number ('zurück': undo, 'los': run) followed by words that are none,
        where the whole line, or the words after the command, read as steps, is those steps:
        "zurück ins Büro" (the whole line), "los zum Ball" (go: "zum Ball") were "expected a whole number";
        and a phrase that begins with a command taking no words (``_phrase_not_command``)."""
        if self._phrase_not_command(command, rest, line):
            return line
        reads = NUMBERED.get(command) if command is not None else None
        if reads is None or not rest.strip():
            return None
        try:
            reads(rest, self.lang)
            return None
        except TeachError:
            pass
        for steps in (line, rest):
            try:
                self.phrases.parse(steps, self.lang, topic=self.topic)
            except UnknownPhrase:
                continue
            return steps
        return None

    def _answer_words(self) -> tuple[str, ...]:
        """The words a typo may be read as besides the commands: yes and no while a question is open."""
        if self.pending is None and self.pending_model is None:
            return ()
        return ("ja", "nein") if self.lang == Lang.DE else ("yes", "no")

    def command(self, line: str) -> tuple[Command | None, str]:
        """The command ``handle`` would read in a line ("ok run" is 'run'), and its argument."""
        try:
            command, rest = parse_command(command_hint(line, self.lang, COMMAND_NAMES) or line)
        except LineTooLong:
            return None, line
        return (None, line) if self._phrase_not_command(command, rest, line) else (command, rest)

    def _phrase_not_command(self, command: Command | None, rest: str, line: str) -> bool:
        """A line that is one of the domain's phrases is that step where it begins with a command that
        takes no words ("ask if they want something", snacks' offering, was 'ask'; "ask if …" near
        one of them is offered as it) or is, as a whole,
        one of a command's everyday sayings but its first word in either language (snacks' "go back"
        is a step; in the ball world, which has none such, it is 'undo')."""
        if command is Verb.ASK and _first_word(rest) in ASKING_SOMEONE and self._near_steps(line):
            return True  # "ask if anyone wants a cookie": the domain's step (or the nearest one offered)
        if command is None or (bool(rest.strip()) and command.value.argued):
            return False
        if not rest.strip() and normalize(line) in {normalize(command.value.en[0]), normalize(command.value.de[0])}:
            return False
        return self._names_steps(line)

    def close(self) -> None:
        self.record.save()
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
                return self.asking.answer_step(tokens[0], tokens[0].text)
            if is_no(line, self.lang):
                return [Reply(ReplyKind.INFO, m.SAY_IT_ANOTHER_WAY(self.lang))]
        waited = after_holding_on(line)
        if waited != line and not self._names_steps(line):  # "hmm", "wait, no" (not snacks' "wait until …")
            if not waited:  # what waits for a yes still waits (``handle``)
                return self._waiting()
            line = waited
        if self.pending is None and self.pending_model is None:
            praised, greeted, rest = is_praise(line), is_greeting(line), after_courtesy(line)
            if (praised or greeted or rest != line) and not self._names_steps(line):
                if praised:  # "well done" is no 'done'
                    return self._said_back(m.PRAISED(self.lang))
                if greeted:  # "hallo" was "Did you mean 'halt'?"; during a demonstration, what comes next
                    hello = m.HELLO(self.lang, actions=some_actions(self.domain, self.lang))
                    return self._said_back(m.HELLO_AGAIN(self.lang), ReplyKind.SAY, alone=hello)
                line = rest  # "great, now you try"
        asked = normalize(line)  # the phrase book is read only for a line that is one of these sayings
        if (asked in DONE_YET_WORDS or asked in WHO_WORDS or asked in TASK_WORDS) and self.pending is None \
                and self.pending_model is None and not self._names_steps(line):
            if asked in DONE_YET_WORDS:  # "is it done?"
                return done_yet(self.domain, self.world.state(), self.open is not None, self.lang)
            if asked in TASK_WORDS:  # "what is the task?"
                return what_task(self.domain, self.learning.tree if self.learning.knows_goal else None, self.lang)
            return [Reply(ReplyKind.SAY, m.HELLO(self.lang, actions=some_actions(self.domain, self.lang)))]
        meant = meant_instead(line)
        if meant is not None and self.pending is None and self.pending_model is None and self._names_steps(meant):
            return self._instead(meant)
        line = command_hint(line, self.lang, COMMAND_NAMES) or line
        command, rest = parse_command(line)
        steps = self._steps_after_all(command, rest, line)
        if steps is not None:
            command, rest, line = None, steps, steps
        guided = self._guiding_first(line, command)
        if guided is not None:
            return guided
        # "wrong"/"falsch" undo, but to an open question they are a "no", as before they named a command;
        # "go ahead" runs, but to "may I …?" it is a yes
        answering = command is None or command in ANSWERING or is_no(line, self.lang) or is_yes(line, self.lang)
        if self.pending_model is not None and answering:
            return self.definitions.answer(line)
        if self.pending is not None and answering:
            return self.asking.answer(line)
        if command is not None and self.mode is Mode.ASKING and command in BLOCKED_WHILE_ASKING:
            return [Reply(ReplyKind.ERROR, m.ANSWER_FIRST(self.lang))]
        self.asking.in_a_row = 0
        if command is Verb.SKIP and normalize(line) in GOING_ON_WORDS and self.runnable is not None:
            command = Verb.RUN  # "weiter" with nothing asked: go on ("Es ist keine Frage offen.")
        if command is not None:
            return self._handler(command)(rest)
        said = normalize(line)
        if said in NO_MATTER_WORDS:  # "sorry", "never mind", "ok"
            return self._said_back(m.ALL_RIGHT(self.lang))
        if is_no(line, self.lang):  # "no" to nothing asked: likely "that was wrong"
            return [Reply(ReplyKind.INFO, m.NO_TO_WHAT(self.lang))]
        if is_yes(line, self.lang) or without_hesitation(said) in ANSWERS_ONLY:  # "yes"/"maybe" to nothing asked
            return [Reply(ReplyKind.INFO, m.NO_QUESTION_OPEN(self.lang))]
        if said in DOUBT_WORDS:  # "are you sure?" after anything but a step
            return self._why_that(None)
        if said in AGAIN_WORDS:  # after anything but a step or a guided move: which step is meant?
            return [Reply(ReplyKind.INFO, m.AGAIN_WHAT(self.lang, example=self._example_action()))]
        if said in WHAT_NOW_WORDS or said in SKIP_WORDS:  # "what now?", "I don't know"
            return self._what_now()
        if said.startswith(WHERE_STARTS):  # "where is the ball?": the situation says it
            return self.cmd_state("")
        stated = stated_condition(self.domain, line)
        if stated is not None and not self._names_steps(line):  # "the tray is empty now": told how things are
            return self._told(*stated)
        return self._teach_actions(line)

    # --- commands --------------------------------------------------------------------------

    def cmd_help(self, rest: str) -> list[Reply]:
        """Every command this world can carry out ('guide' only where the robot can be moved by
        hand), its examples in this domain's words."""
        example = self._example_action()
        shown = [c for c in COMMANDS if c is not Verb.GUIDE or self.guiding.can_guide()]
        lines = [f"  {c.usage(self.lang):<28} {c.help(self.lang, example=example)}" if len(c.usage(self.lang)) <= 28
                 else f"  {c.usage(self.lang)}\n  {'':<28} {c.help(self.lang, example=example)}" for c in shown]
        examples = some_actions(self.domain, self.lang, say_more=False)  # one demonstration's words
        said = [m.HELP_INTRO(self.lang, examples=examples), *lines, m.HELP_ASK(self.lang)]
        return [Reply(ReplyKind.INFO, "\n".join(said))]

    def _example_action(self) -> str:
        """One of this domain's actions in the teacher's words, for examples ("why find the ball")."""
        return actions_to_name(self.domain)[0].label(self.lang)

    def cmd_guide(self, rest: str) -> list[Reply]:
        if not self.guiding.can_guide():
            return self.guiding.refusal()
        if self.open is None and not self.guiding.active and self.domain.goal_holds(self.world.state()):
            return [Reply(ReplyKind.ERROR, m.NOTHING_TO_DO(self.lang)), self._state_reply()]  # as a named step is
        replies = self.guiding.command(rest, self._interrupt) + [self._state_reply()]
        if rest.strip() and all(reply.kind is not ReplyKind.ERROR for reply in replies):
            self.again = f"{Verb.GUIDE.words(self.lang)[0]} {rest}"  # "guide forward 0.2", "again"
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
        if command is None and self.guiding.reads_as_move(line) and not self._names_steps(line):
            return self.cmd_guide(line)
        if self.guiding.active and normalize(line) in STOP_WORDS:  # "esc", "stop" alone: guiding ends
            return self.cmd_guide(line)
        if self.guiding.active and normalize(line) in BACK_WORDS:  # "step back": backing up, not 'undo'
            return self.cmd_guide(self.guiding.back_line())
        if self.guiding.active and (command is None or command is not Verb.GUIDE):
            self.guiding.end()
            if self.guiding.pending is not None:
                self.guiding.deferred = line
                return []
        return None

    def cmd_demonstrate(self, rest: str) -> list[Reply]:
        replies = self.showing.begin()
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
        return self._finish_demo(state)

    def cmd_cancel(self, rest: str) -> list[Reply]:
        if self.open is None:
            return [Reply(ReplyKind.INFO, m.NOTHING_TO_CANCEL(self.lang))]
        had_steps = self.showing.has_steps
        self.showing.discard()
        self.topic = None
        return [Reply(ReplyKind.INFO, (m.DISCARDED if had_steps else m.DISCARDED_EMPTY)(self.lang))]

    def cmd_undo(self, rest: str) -> list[Reply]:
        aside: list[Reply] = []
        if self.mode is Mode.ASKING:
            if not self._asked_after_an_answer() or rest.strip():  # after a run: what would it take back?
                return [Reply(ReplyKind.INFO, m.NO_UNDO_WHILE_ASKING(self.lang))]
            # "yes", the next question, "that was wrong": the answer before it is what is meant; the
            # open question is put aside, paid for (asked again, it costs nothing)
            aside = [Reply(ReplyKind.INFO, m.QUESTION_ASIDE(self.lang))]
        if self.showing.has_steps:
            return [Reply(ReplyKind.INFO, self.showing.take_back(step_number(rest, self.lang))), self._state_reply()]
        if rest.strip():
            return [Reply(ReplyKind.ERROR, m.NO_STEPS_TO_UNDO(self.lang))]
        brought_back = None if aside else self.showing.bring_back()  # "cancel", then "undo"
        if brought_back is not None:
            return [Reply(ReplyKind.INFO, brought_back), self._state_reply()]
        if not self.demos:
            return [Reply(ReplyKind.ERROR, m.NOTHING_TO_UNDO(self.lang))]
        text = self.relearning.undo()
        return self.turn.say([*aside, Reply(ReplyKind.INFO, text)]) + self._after_learning(ask=False)

    def _asked_after_an_answer(self) -> bool:
        """Whether the open question came right after an answer learned (not a skip, not "that
        cannot happen"): the answer an undo at the answer prompt takes back."""
        events = [e for e in self.record.journal.events if not isinstance(e, Situated)]
        before = events[-2] if len(events) >= 2 and isinstance(events[-1], Asked) else None
        return isinstance(before, Answered) and before.answer not in ("skip", IMPOSSIBLE)

    def cmd_redo(self, rest: str) -> list[Reply]:
        """Bring back what the last undo took: steps of the open demonstration, else the last
        demonstration or answer, as long as nothing new happened after the undo."""
        if self.mode is Mode.ASKING:
            return [Reply(ReplyKind.INFO, m.NO_UNDO_WHILE_ASKING(self.lang))]
        put_back = self.showing.put_back()
        if put_back is not None:
            return [Reply(ReplyKind.INFO, put_back), self._state_reply()]
        if not self.relearning.can_redo() or self.showing.has_steps:
            return [Reply(ReplyKind.ERROR, m.NOTHING_TO_REDO(self.lang))]
        text = self.relearning.redo()
        return self.turn.say([Reply(ReplyKind.INFO, text)]) + self._after_learning(ask=False)

    def cmd_steps(self, rest: str) -> list[Reply]:
        return self.showing.listing()

    def cmd_perturb(self, rest: str) -> list[Reply]:
        tokens = self.phrases.parse(rest, self.lang, perturb=True, topic=self.topic) if rest.strip() else []
        if not any(t.kind == "event" for t in tokens):
            return [Reply(ReplyKind.ERROR, m.WHICH_EVENT(self.lang, names=self._event_names()))]
        return self._act(tokens)

    def _event_names(self) -> str:
        """What the world lets happen, one phrase each, in the session's language."""
        return ", ".join(m.Text(en[0], next(iter(de), en[0]))(self.lang) for en, de in self.world.events.values())

    def cmd_run(self, rest: str) -> list[Reply]:
        if self.open is not None and self.open.steps:
            if len(self.open.steps) > self.open.robot_steps:
                return [Reply(ReplyKind.ERROR, m.FINISH_BEFORE_RUN(self.lang))]
            # only the last run's own steps are open (an answer may have unblocked it): run again from here
            self.turn.say([Reply(ReplyKind.INFO, m.RUN_AGAIN(self.lang))])
        tree = self.runnable
        if tree is None:
            return [Reply(ReplyKind.ERROR, m.NOTHING_LEARNED(self.lang))]
        told = running.run(tree, self.showing, self.observer, whole_number(rest, self.lang), self._interrupt)
        self.last_step = None if told.last is None else (told.last, True)
        self.again = f"{Verb.RUN.words(self.lang)[0]} {rest}".strip()  # "again" after a run runs again
        replies = told.replies + ([self._state_reply()] if told.state_line else [])
        return replies + (self.asking.ask_after_run() if told.ask else [])

    def cmd_stop(self, rest: str) -> list[Reply]:
        return [Reply(ReplyKind.INFO, m.NOT_RUNNING(self.lang))]

    def cmd_show(self, rest: str) -> list[Reply]:
        full = says_full(rest)
        if self.pruned is None and self.definitions.planned is not None:
            return [self._tree_reply(self.definitions.planned, full)]
        if self.pruned is None:
            return [Reply(ReplyKind.INFO, m.NO_TREE(self.lang))]
        return [self._tree_reply(self.learning.tree if full else self.pruned, full)]

    def cmd_state(self, rest: str) -> list[Reply]:
        return [self._state_reply(full=says_full(rest), asked=True)]

    def cmd_start(self, rest: str) -> list[Reply]:
        if self.showing.has_steps:
            return [Reply(ReplyKind.ERROR, m.FINISH_FIRST(self.lang))]
        names = condition_names(self.domain, rest, self.lang)
        self.world.arrange(self.domain.state(names))
        self.topic = self.phrases.topic_in(rest)  # "start ball found", then "go to it"
        self.record.add(Situated(state_text(self.world.state()), "start"))  # on disk before the teacher sees it
        return [self._state_reply()]

    def cmd_reset(self, rest: str) -> list[Reply]:
        if self.showing.has_steps:
            return [Reply(ReplyKind.ERROR, m.FINISH_FIRST(self.lang))]
        self.showing.close()
        seed = whole_number(rest, self.lang)
        self.world.reset(seed)
        self.record.add(Situated(state_text(self.world.state()), "reset", seed))  # on disk before the teacher sees it
        return self._start_replies()

    def cmd_ask(self, rest: str) -> list[Reply]:
        if self.definitions.unusable:
            return self.definitions.ask()
        replies = self.asking.maybe_ask(len(self.demos), force=True)
        return replies or [Reply(ReplyKind.INFO, self.asking.none_text())]

    def cmd_skip(self, rest: str) -> list[Reply]:
        return [Reply(ReplyKind.INFO, m.NO_QUESTION_OPEN(self.lang))]

    def cmd_why(self, rest: str) -> list[Reply]:
        if self.pending is not None and normalize(rest) in WHY_ASKING:  # "why do you ask?"
            return [Reply(ReplyKind.INFO, m.WHY_I_ASK(self.lang))]
        if rest.strip() and any(normalize(f"{why} {rest}") in DOUBT_WORDS for why in Verb.WHY.words(self.lang)):
            return self._why_that(None)  # "why did you do that?" after no step
        if self.pruned is None:
            return [Reply(ReplyKind.INFO, m.NO_TREE(self.lang))]
        if not rest.strip():  # 'why' alone said "No action or condition named '' in the tree."
            return [Reply(ReplyKind.INFO, m.WHY_WHAT(self.lang, example=self._example_action()))]
        name = node_named(self.domain, self.phrases, rest, self.lang, self.topic)
        lines = self.learning.why(name, self.lang)
        if lines is None:
            return [Reply(ReplyKind.ERROR, m.NO_SUCH_NODE(self.lang, name=rest.strip()))]
        if untrue_asked(self.domain, name, rest):  # "why is the bin out of reach": those reasons first
            untrue = self.domain.condition(name).label(self.lang, False)
            lines.sort(key=lambda line: untrue not in line)
        return [Reply(ReplyKind.INFO, "\n".join(f"- {line}" for line in lines))]

    def _why_that(self, step: tuple[str, bool] | None) -> list[Reply]:
        example = self._example_action() if self.pruned is not None else None
        return why_that(self.domain, self.learning, step, example, self.lang)

    def cmd_save(self, rest: str) -> list[Reply]:
        self.record.save()
        self.observer.checkpoint()
        where = ", ".join(map(str, self.store.places()))
        return [Reply(ReplyKind.INFO, m.SAVED(self.lang, places=where))]

    def cmd_quit(self, rest: str) -> list[Reply]:
        steps = len(self.open.steps) if self.open is not None else 0
        if steps and self._quit_warned_at != self.step - 1:  # not right after the warning
            self._quit_warned_at = self.step
            said = m.OPEN_ON_QUIT_ONE(self.lang) if steps == 1 \
                else m.OPEN_ON_QUIT(self.lang, steps=steps_said(steps, self.lang))  # "1 step … learn them"
            return [Reply(ReplyKind.ERROR, said)]
        self.finished = True
        replies = self.cmd_save(rest)
        return replies + [Reply(ReplyKind.SAY, m.GOODBYE(self.lang, resume=self.settings.resume_words))]

    def cmd_model(self, rest: str) -> list[Reply]:
        if not rest.strip():
            return [Reply(ReplyKind.ERROR, m.WHICH_FILE(self.lang))]
        return self.definitions.load(Path(rest.strip()), self.domain)

    def cmd_plan(self, rest: str) -> list[Reply]:
        if self.definitions.repair is None:
            return [Reply(ReplyKind.ERROR, m.NO_DEFINITIONS(self.lang))]
        return self.definitions.show(ask=False)

    # --- demonstrations ---------------------------------------------------------------------

    def _names_steps(self, line: str) -> bool:
        """Whether ``line`` is one of the domain's phrases as it stands (no typo read): then it is a
        step, even where it also reads as praise, a greeting or how things are (a domain may have a
        "say hello")."""
        try:
            return not any(token.guessed for token in self.phrases.parse(line, self.lang, topic=self.topic))
        except TeachError:
            return False

    def _near_steps(self, line: str) -> bool:
        """Whether ``line`` reads as the domain's steps, or as near one that it would be offered."""
        try:
            self.phrases.parse(line, self.lang, topic=self.topic)
        except UnknownPhrase as unknown:
            return unknown.suggestion is not None and unknown.suggestion.candidate.kind == "action"
        except TeachError:
            return False
        return True

    def _instead(self, steps: str) -> list[Reply]:
        """"oops, I meant go to the ball": the last step taken back (if one is open), then these."""
        taken = self.turn.say([Reply(ReplyKind.INFO, self.showing.take_back(None))]) if self.showing.has_steps else []
        return taken + self._teach_actions(steps)

    def _meant_by_pronoun(self, line: str) -> str | None:
        """A line whose "it" stands for nothing named yet, with the one object that makes its step
        possible here ("put it on b" while holding a: "put a on b"; it was offered "put c on b").
        Only offered: a yes does it."""
        pronoun = PRONOUN.search(line)
        if pronoun is None:
            return None
        possible, meant = possible_actions(self.domain, self.world.state()), []
        for thing in self.phrases.objects:
            said = line[:pronoun.start()] + thing + line[pronoun.end():]
            if self._possible_steps(said, possible) is not None:
                meant.append(said)
        return meant[0] if len(meant) == 1 else None

    def _possible_steps(self, said: str, possible: list[str]) -> list[Token] | None:
        """``said`` read word for word (no typo guessed) as steps the first of which can be done
        here (one of ``possible``), or None."""
        try:
            tokens = self.phrases.parse(said, self.lang)
        except TeachError:
            return None
        if tokens and tokens[0].kind == "action" and not any(t.guessed for t in tokens) and tokens[0].name in possible:
            return tokens
        return None

    def _meant_with_object(self, line: str) -> list[str]:
        """The steps possible here that ``line`` says but for its last object, in the teacher's words
        with it ("take c off" where c is on a: "take c off a"; "put c on" holding c: "put c on a", "put
        c on d"); at most ``MAX_WHICH`` (more: none, the line says too little). Only in a domain with
        objects (forms)."""
        possible = possible_actions(self.domain, self.world.state())
        meant: dict[str, str] = {}
        for thing in self.phrases.objects:
            said = f"{line.strip().rstrip('?.!').strip()} {thing}"
            tokens = self._possible_steps(said, possible)
            if tokens is not None and len(tokens) == 1:
                meant.setdefault(tokens[0].name, said)
        return list(meant.values()) if len(meant) <= MAX_WHICH else []

    def _teach_actions(self, text: str) -> list[Reply]:
        return self._act(self.phrases.parse(text, self.lang, topic=self.topic))

    def _act(self, tokens: list[Token]) -> list[Reply]:
        """Do the parsed steps in the world, recording each in the open demonstration (opened if need be).
        Steps where the task is already finished and no demonstration is open are refused: they
        changed nothing and were ticked as done ("✓ find the ball (nothing changed)")."""
        if self.open is None and tokens and tokens[0].kind == "action" and self.domain.goal_holds(self.world.state()):
            return [Reply(ReplyKind.ERROR, m.NOTHING_TO_DO(self.lang)), self._state_reply()]
        self.topic = self.phrases.topic(tokens) or self.topic
        return self.showing.act(tokens, self.facilitator, self._interrupt, self._reaching) + [self._state_reply()]

    def _finish_demo(self, goal: State) -> list[Reply]:
        """The open demonstration ends in ``goal`` (where the goal holds): learned and written."""
        assert self.open is not None
        started = time.perf_counter()
        path = self.store.next_demo_path()
        demo = self.open.finish(path.stem, goal, path)
        source = path.name
        try:
            update = self.learning.learn_demonstration(demo, source)
        except LearnError as error:  # the demonstration stays open to be mended
            return [Reply(ReplyKind.ERROR, m.CANNOT_LEARN(self.lang, why=why_refused(error, self.lang))),
                    Reply(ReplyKind.INFO, m.DETAILS(self.lang, details=error.message))]
        self.store.write_demonstration(path, demo)
        self.showing.close()
        self.topic = None  # "it" in the next demonstration is whatever it names first
        self.observer.on_demonstration(demo.name, demo, self.domain)
        self.learning.report("specialize", update, self.lang)
        return self._after_learning(ask=True, started=started, events=[DemoLearned(path.name, source)])

    def import_demonstrations(self, demos: list[Demonstration]) -> list[Reply]:
        """Learn demonstrations recorded elsewhere (one generation for all of them)."""
        self.turn.begin()
        started = time.perf_counter()
        events: list[Event] = []
        for demo in demos:
            path = self.store.next_demo_path()
            source = f"imported {demo.name} ({path.name})"
            self.learning.learn_demonstration(demo, source)
            self.store.write_demonstration(path, demo)
            events.append(DemoLearned(path.name, source))
            self.observer.on_demonstration(demo.name, demo, self.domain)
        return self.turn.close(self._after_learning(ask=False, started=started, events=events))

    # --- learning results -------------------------------------------------------------------

    def _after_learning(self, ask: bool, started: float | None = None, events: list[Event] | None = None,
                        answered: tuple[State, str] | None = None) -> list[Reply]:
        """Commit ``events`` to the journal, then prune, save the generation, show, replay, go on
        from an ``answered`` question (``_go_on``) and maybe ask. Journal first, as for answers: a
        kill between the two leaves a learned event whose generation the teacher never saw (a
        resume learns it again), never a generation file no journalled event explains."""
        from teach.replay import replay

        if events:
            self.record.add(*events)
        if not self.learning.has_behaviour:  # only goal states so far: there is no behaviour to show yet
            return self.turn.say([Reply(ReplyKind.INFO, m.GOAL_ONLY(self.lang))])
        pruned = self.learning.prune()
        path = self.learning.save_generation(pruned, "learned from demonstrations and answers")
        report = replay(pruned, self.domain, self.demos)
        self.observer.on_replay(report.reproduced, report.total)
        # node counts and the file are for the facilitator; the teacher hears what it means
        summary = (m.GENERATION if self.facilitator else _reproduced_text(report.reproduced, report.total))(
            self.lang, generation=self.generation, nodes=size(pruned), unpruned=size(self.learning.tree), path=path,
            reproduced=report.reproduced, total=report.total)
        replies = self.turn.say([self._tree_reply(pruned), Reply(ReplyKind.INFO, summary)])
        if answered is not None:
            replies += self._go_on(*answered)
        if ask:
            replies += self.asking.maybe_ask(len(self.demos))
        return replies

    def _go_on(self, state: State, action: str) -> list[Reply]:
        """An answer naming the step to take in the situation a correction stopped in is that step:
        the robot takes it, as the correction's next step (it was only learned: a teacher who
        answered "go to the bin" then said "put the ball in the bin", and the robot, still far
        from the bin, refused). While the correction holds only the run's steps it is the robot's
        step too, so 'run' goes on from there."""
        opened = self.open
        if opened is None or self.world.state() != state:
            return []
        robots_only = len(opened.steps) == opened.robot_steps
        replies = self._act([Token("action", action, self.domain.action(action).label(self.lang))])
        if robots_only:
            opened.robot_steps = len(opened.steps)
        return replies

    # --- resume ---------------------------------------------------------------------------

    @classmethod
    def resume(cls, settings: Settings, domain: Domain, world: TeachingWorld,
               observer: Observer | None = None) -> SessionManager:
        store = SessionStore(settings.base, settings.session, settings.record)
        journal = store.load_journal()
        manager = cls(settings, domain, world, observer, journal)
        manager.guiding.restore(journal.events)
        manager.relearning.relearn()
        manager.step = journal.step + 1  # a step of its own: the kill may have come before the save
        manager.observer.set_time(manager.step)
        current = manager.pruned or manager.definitions.planned
        if current is not None:
            from teach.bt.xml import tree_to_xml

            manager.observer.on_tree(manager.generation, current, tree_to_xml(current), "resumed")
        exact = settings.world is not WorldKind.MUJOCO
        manager.restored = restore_situation(manager.record, world, manager.domain, manager.lang, exact, manager.demos)
        manager.restored = restore_open(manager.record, world, manager.domain, manager.lang) or manager.restored
        return manager

    # --- helpers ---------------------------------------------------------------------------

    def _tree_reply(self, tree: Node, full: bool = False) -> Reply:
        """The tree in sentences of the session's language; the symbols too for a facilitator or 'show full'."""
        words = "" if full or self.facilitator else "\n".join(tree_lines(tree, self.domain, self.lang))
        return Reply(ReplyKind.TREE, words, tree=tree)

    def _start_replies(self) -> list[Reply]:
        """The situation a session or a new start begins in; where the domain's action model allows
        no action there and the task is not done (blocksworld's state where nothing holds), how to
        leave it: begin where a demonstration beside the domain file begins (``teach.session.starting``),
        or say how to set a situation up."""
        domain, state = self.domain, self.world.state()
        stuck = domain.has_model and not domain.goal_holds(state) and not possible_actions(domain, state)
        if not stuck:
            return [self._state_reply()]
        found = demonstrated_start(domain)
        if found is None:
            return [self._state_reply(), Reply(ReplyKind.INFO, m.NO_STEP_POSSIBLE(self.lang))]
        path, start = found
        self.world.arrange(start)
        self.record.add(Situated(state_text(self.world.state()), "start"))  # on disk before the teacher sees it
        shown = f"{path.parent.name}/{path.name}"
        return [Reply(ReplyKind.INFO, m.STARTED_AS_SHOWN(self.lang, demo=shown)), self._state_reply()]

    def _told(self, name: str, value: bool) -> list[Reply]:
        """The teacher said how a condition is: agreed with, or what the robot sees instead (the world
        decides, never a line), and which events could have made it so."""
        held = self.world.state()[self.domain.condition_names.index(name)]
        condition = self.domain.condition(name)
        if held == value:
            return [Reply(ReplyKind.INFO, m.STATED_HOLDS(self.lang, condition=condition.label(self.lang, value)))]
        text = m.STATED_UNTRUE(self.lang, condition=condition.label(self.lang, held))
        if self.world.events:
            text += m.STATED_WHAT_HAPPENED(self.lang, events=self._event_names())
        return [Reply(ReplyKind.INFO, text)]

    def _said_back(self, said: str, kind: ReplyKind = ReplyKind.INFO, alone: str | None = None) -> list[Reply]:
        """Praise thanked back, a greeting greeted, a "wait" waited for: during a demonstration with
        what comes next (as "what now?" where the task is finished; a greeting repeated the whole
        opening line there), else ``alone`` (default: ``said``)."""
        if self.open is None:
            return [Reply(kind, said if alone is None else alone)]
        if self.domain.has_model and self.domain.goal_holds(self.world.state()):
            return [Reply(kind, f"{said} {m.WHAT_NOW_FINISHED(self.lang)}")]
        return [Reply(kind, f"{said} {m.GO_ON(self.lang)}")]

    def _only_holding_on(self, line: str) -> bool:
        """ "hmm", "wait", "einen Moment" and nothing else (snacks' "wait" names a step)."""
        return bool(line) and not after_holding_on(line) and not self._names_steps(line)

    def _waiting(self) -> list[Reply]:
        """ "hmm", "wait", "einen Moment": nothing done; an open question stays open."""
        if self.pending is not None or self.pending_model is not None:
            return [Reply(ReplyKind.QUESTION, m.TAKE_YOUR_TIME_ASKED(self.lang))]
        return self._said_back(m.TAKE_YOUR_TIME(self.lang))

    def _what_now(self) -> list[Reply]:
        """ "what now?": the situation and the steps the domain's model allows from it (every step
        where it declares no preconditions), or that the task is finished here."""
        domain, state = self.domain, self.world.state()
        if domain.has_model and domain.goal_holds(state):  # 'done' ends a demonstration only if one is open
            finished = m.WHAT_NOW_FINISHED if self.open is not None else m.NOTHING_TO_DO
            return [self._state_reply(), Reply(ReplyKind.INFO, finished(self.lang))]
        possible = possible_actions(domain, state)
        if not possible:
            return self._start_replies()
        actions = ", ".join(domain.action(name).label(self.lang) for name in possible)
        return [self._state_reply(), Reply(ReplyKind.INFO, m.WHAT_NOW(self.lang, actions=actions))]

    def _state_reply(self, full: bool = False, asked: bool = False) -> Reply:
        """The situation in words; the conditions' names and values too for a facilitator or 'state full';
        ``asked``: the teacher asked for it (a line of the dialogue then, ``Reply.asked``)."""
        state = self.world.state()
        values = dict(zip(self.domain.condition_names, state, strict=True)) if full or self.facilitator else None
        return Reply(ReplyKind.STATE, describe_situation(self.domain, state, self.lang), state=values, asked=asked)

    def _tick_clock(self) -> None:
        self.step += 1
        self.journal.step = self.step
        self.observer.set_time(self.step)

    def _handler(self, command: Command) -> Callable[[str], list[Reply]]:
        handler: Callable[[str], list[Reply]] = getattr(self, command.handler)
        return handler


_UNHANDLED = [command.name for command in COMMANDS if not callable(getattr(SessionManager, command.handler, None))]
if _UNHANDLED:  # a command declared in teach/session/commands.py needs its cmd_ method here
    raise TypeError(f"commands without a handler: {', '.join(_UNHANDLED)}")


def _counted(count: int, none: m.Text, one: m.Text, many: m.Text) -> m.Text:
    """The text for ``count`` things: "no questions", "1 question", "2 questions"."""
    return none if count == 0 else one if count == 1 else many


def _reproduced_text(reproduced: int, total: int) -> m.Text:
    """How many demonstrations the new tree does as shown, said for one, all or some of them."""
    if total == 1:
        return m.GENERATION_PLAIN_THE_ONE if reproduced == 1 else m.GENERATION_PLAIN_NOT_THE_ONE
    if reproduced == total:
        return m.GENERATION_PLAIN_BOTH if total == 2 else m.GENERATION_PLAIN_ALL  # not "all 2 of them"
    return m.GENERATION_PLAIN


def _first_word(text: str) -> str:
    words = normalize(text).split()
    return words[0] if words else ""
