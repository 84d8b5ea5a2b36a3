"""The scripted driver: feeds a dialogue file to a session and prints the transcript exactly
as the terminal would show it."""

from __future__ import annotations

from rich.console import Console

from teach.dialogue.model_repair import ModelOracle
from teach.dialogue.oracle import SituationOracle, answer_open_questions
from teach.dialogue.script import Script
from teach.session.machine import SessionManager
from teach.terminal.view import render_reply, render_teacher


def run_script(script: Script, manager: SessionManager, console: Console,
               oracle: SituationOracle | None = None, model_oracle: ModelOracle | None = None) -> None:
    """Every reply is printed as the session produces it, like the terminal does."""
    manager.live = lambda reply: console.print(render_reply(reply, manager.domain, manager.lang))

    def oracle_says(line: str) -> None:
        console.print(render_teacher(f"{line}   [oracle]", manager.mode, manager.lang))

    manager.greet()
    for _, line in script.lines:
        answer_open_questions(manager, oracle, model_oracle, oracle_says)
        console.print(render_teacher(line, manager.mode, manager.lang))
        manager.handle(line)
        if manager.finished:
            break
    answer_open_questions(manager, oracle, model_oracle, oracle_says)
    if not manager.finished:
        manager.handle("save")
