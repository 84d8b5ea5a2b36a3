"""The scripted driver: feeds a dialogue file to a session and prints the transcript exactly
as the terminal would show it."""

from __future__ import annotations

from rich.console import Console

from teach.dialogue.model_repair import ModelOracle
from teach.dialogue.oracle import SKIP, Oracle
from teach.dialogue.script import Script
from teach.dialogue.session import Reply, SessionManager
from teach.dialogue.view import render_reply, render_teacher


def show(console: Console, manager: SessionManager, replies: list[Reply]) -> None:
    for reply in replies:
        console.print(render_reply(reply, manager.domain, manager.lang))


def answer_with_oracle(manager: SessionManager, oracle: Oracle | None, console: Console | None,
                       model_oracle: ModelOracle | None = None) -> None:
    """Answer open questions from the oracles until none is open (each answer may raise another)."""
    while True:
        if manager.pending_model is not None and model_oracle is not None:
            said = model_oracle.answer(manager.pending_model, manager.lang)
        elif manager.pending is not None and oracle is not None:
            answer = oracle.answer(manager.pending.state)
            if answer == SKIP:
                said = "skip"
            elif answer is None:
                said = "done"
            else:
                said = manager.domain.action(answer).label(manager.lang)
        else:
            return
        if console is not None:
            console.print(render_teacher(f"{said}   [oracle]", manager.mode, manager.lang))
        manager.handle(said)  # a driver that shows replies sees them through ``manager.live``


def run_script(script: Script, manager: SessionManager, console: Console, oracle: Oracle | None = None,
               model_oracle: ModelOracle | None = None) -> None:
    """Every reply is printed as the session produces it, like the terminal does."""
    manager.live = lambda reply: show(console, manager, [reply])
    manager.greet()
    for _, line in script.lines:
        answer_with_oracle(manager, oracle, console, model_oracle)
        console.print(render_teacher(line, manager.mode, manager.lang))
        manager.handle(line)
        if manager.finished:
            break
    answer_with_oracle(manager, oracle, console, model_oracle)
    if not manager.finished:
        manager.handle("save")
