"""The scripted driver: feeds a dialogue file to a session and prints the transcript exactly
as the terminal would show it."""

from __future__ import annotations

from rich.console import Console

from teach.dialogue.oracle import SKIP, Oracle
from teach.dialogue.script import Script
from teach.dialogue.session import Reply, SessionManager
from teach.dialogue.view import render_reply, render_teacher


def show(console: Console, manager: SessionManager, replies: list[Reply]) -> None:
    for reply in replies:
        console.print(render_reply(reply, manager.domain, manager.lang))


def answer_with_oracle(manager: SessionManager, oracle: Oracle, console: Console | None) -> None:
    """Answer open questions from the oracle until none is open (each answer may raise another)."""
    while manager.pending is not None:
        answer = oracle.answer(manager.pending.state)
        if answer == SKIP:
            said = "skip"
        elif answer is None:
            said = "done"
        else:
            said = manager.domain.action(answer).label(manager.lang)
        if console is not None:
            console.print(render_teacher(f"{said}   [oracle]"))
        replies = manager.handle(said)
        if console is not None:
            show(console, manager, replies)


def run_script(script: Script, manager: SessionManager, console: Console, oracle: Oracle | None = None) -> None:
    manager.emit = lambda reply: show(console, manager, [reply])
    show(console, manager, manager.greet())
    for _, line in script.lines:
        if oracle is not None:
            answer_with_oracle(manager, oracle, console)
        console.print(render_teacher(line))
        show(console, manager, manager.handle(line))
        if manager.finished:
            break
    if oracle is not None:
        answer_with_oracle(manager, oracle, console)
    if not manager.finished:
        show(console, manager, manager.handle("save"))
