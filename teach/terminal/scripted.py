"""The scripted driver: feeds a dialogue file to a session and prints the transcript exactly
as the terminal would show it."""

from __future__ import annotations

from rich.console import Console

from teach.dialogue.model_repair import ModelOracle
from teach.dialogue.oracle import SituationOracle, answer_open_questions
from teach.dialogue.script import Script
from teach.session.machine import SessionManager
from teach.session.replies import Reply
from teach.terminal.view import render_reply, render_teacher


def run_script(script: Script, manager: SessionManager, console: Console,
               oracle: SituationOracle | None = None, model_oracle: ModelOracle | None = None) -> None:
    """Every reply is printed as the session produces it, like the terminal does."""
    def show(reply: Reply) -> None:
        view = manager.view()
        console.print(render_reply(reply, view.domain, view.lang))

    def teacher_says(line: str) -> None:
        view = manager.view()
        console.print(render_teacher(line, view.mode, view.lang))

    manager.live = show
    manager.greet()
    for _, line in script.lines:
        answer_open_questions(manager, oracle, model_oracle, lambda said: teacher_says(f"{said}   [oracle]"))
        teacher_says(line)
        manager.handle(line)
        if manager.view().finished:
            break
    answer_open_questions(manager, oracle, model_oracle, lambda said: teacher_says(f"{said}   [oracle]"))
    if not manager.view().finished:
        manager.handle("save")
