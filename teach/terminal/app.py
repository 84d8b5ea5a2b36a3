"""The terminal front-end: prompt_toolkit for input (completion, history, toolbar), rich for
output. A thin driver of the session manager.

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
from teach.session.machine import COMMANDS, SessionManager
from teach.terminal.view import prompt, render_reply



class Terminal:
    def __init__(self, manager: SessionManager, console: Console | None = None,
                 input: Input | None = None, output: Output | None = None, history: Path | None = None):
        self.manager = manager
        self.console = console or Console(highlight=False)
        words = command_words(c.usage for c in COMMANDS) + [n for c in COMMANDS for n in c.names if n.isalpha()]
        self.prompt = PromptSession(
            completer=TeachCompleter(sorted(set(words)), manager.phrases.phrases(manager.lang)),
            history=FileHistory(str(history)) if history else InMemoryHistory(),
            bottom_toolbar=self._toolbar, input=input, output=output, complete_while_typing=True)
        self._interrupt = threading.Event()

    def _toolbar(self) -> str:
        m = self.manager
        holds = ", ".join(n for n, v in zip(m.domain.condition_names, m.world.state()) if v) or "—"
        if m.lang == "de":
            mode = {"idle": "bereit", "demonstrating": "Vorführung", "asking": "Frage offen"}[m.mode]
            return f" {mode} │ wahr: {holds} │ Fragen übrig: {m.budget.left} │ Generation {m.generation} │ Strg-D: Ende"
        return f" {m.mode} │ true: {holds} │ questions left: {m.budget.left} │ generation {m.generation} │ Ctrl-D: quit"

    def run(self) -> None:
        self.manager.live = lambda reply: self.console.print(render_reply(reply, self.manager.domain, self.manager.lang))
        self.manager.greet()
        while not self.manager.finished:
            try:
                line = self.prompt.prompt(prompt(self.manager.mode, self.manager.lang))
            except KeyboardInterrupt:
                continue
            except EOFError:
                self.manager.handle("quit")
                break
            self._handle(line)

    def _handle(self, line: str) -> None:
        """Every line goes through the session; while the robot may run, Ctrl-C sets the
        interrupt flag instead of ending the program."""
        command, _ = self.manager.command(line)
        if command is None or command.names[0] != "run" or self.manager.mode == "asking":
            self.manager.handle(line)
            return
        self._interrupt.clear()
        self.console.print("[dim]" + ("Roboter läuft, Strg-C hält ihn an ..." if self.manager.lang == "de"
                                      else "robot running, Ctrl-C interrupts ...") + "[/dim]")
        in_main = threading.current_thread() is threading.main_thread()
        previous = signal.signal(signal.SIGINT, lambda *_: self._interrupt.set()) if in_main else None
        try:
            self.manager.handle(line, interrupt=self._interrupt.is_set)
        finally:
            if in_main:
                signal.signal(signal.SIGINT, previous)
