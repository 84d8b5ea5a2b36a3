"""The terminal front-end: prompt_toolkit for input (completion, history, toolbar), rich for
output. A thin driver of the session machine: the loop and Ctrl-C handling only.

Ctrl-C interrupts a robot run (not the program) and clears the line at the prompt;
Ctrl-D saves and leaves.
"""

from __future__ import annotations

import signal
import threading
from pathlib import Path

from prompt_toolkit import PromptSession
from prompt_toolkit.history import FileHistory, InMemoryHistory
from prompt_toolkit.input import Input
from prompt_toolkit.output import Output
from rich.console import Console

from teach.dialogue.completion import TeachCompleter, command_words
from teach.session import messages as m
from teach.session.commands import COMMANDS, Verb
from teach.session.machine import Mode, SessionManager
from teach.session.replies import Reply
from teach.terminal.view import prompt, render_reply, toolbar


class Terminal:
    def __init__(self, manager: SessionManager, console: Console | None = None,
                 input: Input | None = None, output: Output | None = None, history: Path | None = None):
        self.manager = manager
        self.console = console or Console(highlight=False)
        words = command_words(c.usage(manager.lang) for c in COMMANDS) + [n for c in COMMANDS for n in c.names
                                                                           if n.isalpha()]
        self.prompt: PromptSession[str] = PromptSession(
            completer=TeachCompleter(sorted(set(words)), manager.phrases.phrases(manager.lang),
                                     _argument_names(manager)),
            history=FileHistory(str(history)) if history else InMemoryHistory(),
            bottom_toolbar=lambda: toolbar(self.manager), input=input, output=output, complete_while_typing=True)
        self._interrupt = threading.Event()

    def run(self) -> None:
        self.manager.live = self._show
        self.manager.greet()
        while not self.manager.finished:
            try:
                line = self.prompt.prompt(prompt(self.manager.mode, self.manager.lang))
            except KeyboardInterrupt:
                continue
            except EOFError:  # Ctrl-D: quit (with an open demonstration the first one only warns)
                self.manager.handle("quit")
                continue
            self._handle(line)

    def _show(self, reply: Reply) -> None:
        self.console.print(render_reply(reply, self.manager.domain, self.manager.lang))

    def _on_interrupt(self) -> None:
        """Ctrl-C during a run: stop the robot; what follows starts on a line of its own, not after "^C"."""
        if not self._interrupt.is_set():
            self.console.line()
        self._interrupt.set()

    def _handle(self, line: str) -> None:
        """Every line goes through the session; while the robot may run, Ctrl-C sets the
        interrupt flag instead of ending the program."""
        command, _ = self.manager.command(line)
        if command is None or command.verb is not Verb.RUN or self.manager.mode is Mode.ASKING \
                or self.manager.runnable is None:  # the session explains why it will not run
            self.manager.handle(line)
            return
        self._interrupt.clear()
        self.console.print(f"[dim]{m.ROBOT_RUNNING(self.manager.lang)}[/dim]")
        in_main = threading.current_thread() is threading.main_thread()
        previous = signal.signal(signal.SIGINT, lambda *_: self._on_interrupt()) if in_main else None
        try:
            self.manager.handle(line, interrupt=self._interrupt.is_set)
        finally:
            if in_main:
                signal.signal(signal.SIGINT, previous)


def _argument_names(manager: SessionManager) -> dict[str, list[str]]:
    """What Tab offers after 'start' (conditions) and 'why' (actions and conditions), in the session's language."""
    conditions = [c.label(manager.lang) for c in manager.domain.conditions]
    actions = [a.label(manager.lang) for a in manager.domain.actions]
    return {name: conditions if command.verb is Verb.START else actions + conditions
            for command in COMMANDS if command.verb in (Verb.START, Verb.WHY) for name in command.names}
