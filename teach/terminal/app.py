"""The terminal front-end: prompt_toolkit for input (completion, history, toolbar), rich for
output. A thin driver of the session machine: the loop and Ctrl-C handling only.

Ctrl-C interrupts a robot run or a line of steps (not the program) and clears the line at the prompt;
Ctrl-D saves and leaves. ``guide`` alone enters the guide mode: each key drives the robot by
one ``guide …`` line (arrows, PgUp/PgDn, space); Esc leaves it, and typing a letter leaves it
with that letter as the start of the next line ("done").
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable
from pathlib import Path

from prompt_toolkit import PromptSession
from prompt_toolkit.application import Application
from prompt_toolkit.history import FileHistory, InMemoryHistory
from prompt_toolkit.input import Input
from prompt_toolkit.key_binding import KeyBindings, KeyPressEvent
from prompt_toolkit.keys import Keys
from prompt_toolkit.layout import FormattedTextControl, Layout, Window
from prompt_toolkit.output import Output
from rich.console import Console

from teach import messages as m
from teach.dialogue.completion import TeachCompleter, command_words
from teach.dialogue.phrases import is_yes
from teach.session.commands import COMMANDS, Verb
from teach.session.machine import SessionManager
from teach.session.published import Mode, SessionView
from teach.session.replies import Reply, ReplyKind
from teach.terminal.run_keys import RunKeys, is_terminal
from teach.terminal.view import prompt, render_reply, render_teacher, toolbar


class Terminal:
    def __init__(self, manager: SessionManager, console: Console | None = None,
                 input: Input | None = None, output: Output | None = None, history: Path | None = None,
                 on_shown: Callable[[Reply], None] | None = None,
                 listen: Callable[[], tuple[str, bool] | None] | None = None):
        self.manager = manager
        self._on_shown = on_shown  # sees each reply once it is shown (the robot's voice)
        self._listen = listen  # push-to-talk (F5, or the line 'listen'): the line heard and if surely, or None
        self.console = console or Console(highlight=False)
        view = manager.view()
        words = command_words(c.usage(view.lang) for c in COMMANDS) + [n for c in COMMANDS for n in c.names
                                                                        if n.isalpha()]
        self.prompt: PromptSession[str] = PromptSession(
            completer=TeachCompleter(sorted(set(words)), list(view.phrases), _argument_names(view)),
            history=FileHistory(str(history)) if history else InMemoryHistory(),
            bottom_toolbar=self._toolbar, input=input, output=output, complete_while_typing=True,
            key_bindings=self._talk_key() if listen else None)
        self._interrupt = threading.Event()
        self._keys_guiding = False  # in the guide mode, driven by keys
        self._last_state = ""  # the state line last shown
        self._typed = ""  # what a letter typed in the guide mode starts the next line with

    @property
    def view(self) -> SessionView:
        """The session as it is now (the driver reads nothing else of it)."""
        return self.manager.view()

    def run(self) -> None:
        self.manager.live = self._show
        self.manager.greet()
        while not self.view.finished:
            try:
                line = self.prompt.prompt(prompt(self.view.mode, self.view.lang), default=self._typed)
            except KeyboardInterrupt:
                continue
            except EOFError:  # Ctrl-D: quit (with an open demonstration the first one only warns)
                self.manager.handle("quit")
                continue
            finally:
                self._typed = ""
            if self._listen is not None and (line == _LISTENING or line.strip().lower() in _LISTEN_WORDS):
                heard = self._listen()
                if heard is None:
                    continue
                line, sure = heard
                self.console.print(render_teacher(line, self.view.mode, self.view.lang))
                if not sure and not self._confirmed(line):
                    continue
            self._handle(line)

    def _confirmed(self, heard: str) -> bool:
        """A line heard unsurely is handled only once the teacher says yes to it."""
        self._show(Reply(ReplyKind.QUESTION, m.HEARD_DID_YOU_MEAN(self.view.lang, line=heard)))
        try:
            answer = self.prompt.prompt(prompt("asking", self.view.lang))
        except (KeyboardInterrupt, EOFError):
            return False
        if is_yes(answer, self.view.lang):
            return True
        self._show(Reply(ReplyKind.INFO, m.SAY_IT_ANOTHER_WAY(self.view.lang)))
        return False

    def _talk_key(self) -> KeyBindings:
        """F5 at the prompt: listen now (the typed line is left)."""
        bindings = KeyBindings()

        @bindings.add("f5")
        def talk(event: KeyPressEvent) -> None:
            event.app.exit(result=_LISTENING)

        return bindings

    def _toolbar(self) -> str:
        """The bottom line; once the teacher has guided, the labelling questions left as well."""
        view = self.view
        extra = m.TOOLBAR_LABELS(view.lang, left=view.labels_left) if view.guided else ""
        return toolbar(view) + extra

    def _show(self, reply: Reply) -> None:
        if self._keys_guiding and reply.kind is ReplyKind.STATE and reply.text == self._last_state:
            return  # steering with the keys: the state line again only when it changed
        if reply.kind is ReplyKind.STATE:
            self._last_state = reply.text
        view = self.view
        self.console.print(render_reply(reply, view.domain, view.lang))
        if self._on_shown is not None:
            self._on_shown(reply)

    def _on_interrupt(self) -> None:
        """Ctrl-C during a run: stop the robot; what follows starts on a line of its own, not after "^C"."""
        if not self._interrupt.is_set():
            self.console.line()
        self._interrupt.set()

    def _handle(self, line: str) -> None:
        """Every line goes through the session; while it is handled, Ctrl-C sets the interrupt flag
        (a run or a line of steps stops) instead of ending the program."""
        command, rest = self.manager.command(line)
        if command is Verb.GUIDE and not rest.strip() \
                and self.view.mode is not Mode.ASKING:
            self.manager.handle(line)
            if self.view.guiding:
                self._guide_mode()
            return
        self._interrupt.clear()
        in_main = threading.current_thread() is threading.main_thread()
        previous = signal.signal(signal.SIGINT, lambda *_: self._on_interrupt()) if in_main else None
        try:
            if command is Verb.RUN and self.view.mode is not Mode.ASKING and self.view.can_run:
                self._run(line)
            else:  # the session explains why it will not run; a line of steps stops after the step under way
                self.manager.handle(line, interrupt=self._interrupt.is_set)
        finally:
            if in_main:
                signal.signal(signal.SIGINT, previous)

    def _run(self, line: str) -> None:
        """A run: announced as the robot is about to move; what is typed meanwhile is read (and
        answered "wait, or press Ctrl-C")."""
        keys = RunKeys(self.prompt.input, self._on_interrupt, self._typed_while_running) \
            if is_terminal(self.prompt.input) else None
        announced = False

        def interrupted() -> bool:
            # polled first as the robot is about to move: told then, after what the session said
            # before the run ("I try again from here"), and not at all when nothing moves
            nonlocal announced
            if not announced:
                announced = True
                self.console.print(f"[dim]{m.ROBOT_RUNNING(self.view.lang)}[/dim]")
            if keys is not None:
                keys.poll()
            return self._interrupt.is_set()

        with keys.reading() if keys is not None else contextlib.nullcontext():
            self.manager.handle(line, interrupt=interrupted)

    def _typed_while_running(self, line: str) -> None:
        self.console.print(f"[bold red]{m.WAIT_OR_CTRL_C(self.view.lang, line=line)}[/bold red]")

    def _guide_mode(self) -> None:
        """Keys drive the robot, one ``guide …`` line each, until Esc (or Ctrl-C, Ctrl-D) or a
        typed letter; the state line after each shows what changed."""
        self._keys_guiding = True
        quiet = self.prompt.input.raw_mode() if is_terminal(self.prompt.input) else contextlib.nullcontext()
        try:
            with quiet:  # keys pressed while the robot moves are not echoed ("^[[D"), only read after
                self._steer()
        finally:
            self._keys_guiding = False

    def _steer(self) -> None:
        """The guide mode's loop: one key, one ``guide …`` line."""
        while self.view.guiding and self.view.mode is not Mode.ASKING:
            key = self._guide_key()
            if key in _LEAVE:
                self.manager.handle("guide stop")
                return
            if key.startswith(_TYPED):
                self._typed = key[len(_TYPED):]
                return
            line = self.manager.key_line(key)
            if line is not None:
                self.manager.handle(line)

    def _guide_key(self) -> str:
        """One key press of the guide mode, by ``Guide.key``'s name (a letter as ``_TYPED`` + it)."""
        bindings = KeyBindings()

        def press(name: str) -> None:
            bindings.add(_KEYS.get(name, name), eager=True)(lambda event: event.app.exit(result=name))

        for name in (*_KEYS, *_LEAVE):
            press(name)

        @bindings.add(Keys.Any)
        def typed(event: KeyPressEvent) -> None:
            event.app.exit(result=_TYPED + event.data if event.data.isprintable() else "")

        text = FormattedTextControl(lambda: m.GUIDE_MODE_ON(self.view.lang))
        app: Application[str] = Application(layout=Layout(Window(text, height=1)), key_bindings=bindings,
                                            input=self.prompt.input, output=self.prompt.output,
                                            erase_when_done=True)  # the hint stays on one line, not one per key
        try:
            return app.run()
        except EOFError:
            return "c-d"


_KEYS = {"up": "up", "down": "down", "left": "left", "right": "right", "pageup": "pageup", "pagedown": "pagedown",
         "space": " "}
"""The guide mode's keys: ``Guide.key``'s names and prompt_toolkit's."""
_LEAVE = ("escape", "c-c", "c-d")
_TYPED = "typed:"
_LISTENING = "\x00listen"  # what the push-to-talk key ends the prompt with (no typed line holds NUL)
_LISTEN_WORDS = ("listen",)  # English only: a German session cannot listen


def _argument_names(view: SessionView) -> dict[str, list[str]]:
    """What Tab offers after 'start' (conditions) and 'why' (actions and conditions), in the session's language."""
    conditions = [c.label(view.lang) for c in view.domain.conditions]
    actions = [a.label(view.lang) for a in view.domain.actions]
    return {name: conditions if command is Verb.START else actions + conditions
            for command in COMMANDS if command in (Verb.START, Verb.WHY) for name in command.names}
