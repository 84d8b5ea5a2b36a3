"""Helpers of the kill test: a scripted session run in this process with the journal looked at
after every line (what an unkilled session has on disk at each point of its dialogue), the same
dialogue run by the CLI (a child of a preloaded process, tests/preloaded_cli.py) and killed with
SIGKILL at a moment measured from its first line, and what the teacher had seen acknowledged
before the kill."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from conftest import journal_data
from preloaded_cli import PreloadedCli

from teach.dialogue.model_repair import ModelOracle
from teach.dialogue.oracle import SituationOracle, answer_open_questions
from teach.session.machine import SessionManager

MARKER = "Session "
"""The first line a session prints, once it is open: kills are placed from there, not from the
process start (a loaded machine may take seconds to import and build the world)."""

PROMPT = "teach> "


def journal_key(path: Path) -> str:
    """The journal as it decides what a resume rebuilds: everything but the step clock (a resume
    moves it on) and the replay's origin; empty before the session saved one."""
    if not path.exists():
        return ""
    data = journal_data(path)
    for volatile in ("step", "origin"):
        data.pop(volatile, None)
    return json.dumps(data, sort_keys=True)


def drive(manager: SessionManager, lines: list[str], start: int, oracle: SituationOracle,
          model_oracle: ModelOracle,
          after_line: Callable[[int], None] | None = None) -> None:
    """Type ``lines[start:]`` as the scripted driver does (questions answered by the oracle before
    each line); ``after_line(i)`` sees the session once line ``i`` and its answers are through."""
    manager.live = lambda reply: None
    if start == 0:
        manager.greet()
    for index in range(start, len(lines)):
        answer_open_questions(manager, oracle, model_oracle)
        if after_line is not None:
            after_line(index - 1)
        manager.handle(lines[index])
        if manager.finished:
            break
    answer_open_questions(manager, oracle, model_oracle)
    if after_line is not None:
        after_line(len(lines) - 1)
    if not manager.finished:
        manager.handle("save")


@dataclass
class Killed:
    """A CLI session, perhaps killed: everything it printed (its first line the session's name)."""

    transcript: list[str] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    started: bool = False

    @property
    def typed(self) -> int:
        """How many dialogue lines the session had been given (the last may be half done)."""
        return sum(line.startswith(PROMPT) for line in self.transcript)

    @property
    def phase(self) -> str:
        """What the session was doing, told by the last telling line the teacher saw before the kill."""
        return next((found for found in map(phase, reversed(self.transcript)) if found), "start-up")

    @property
    def last_seen(self) -> str:
        return next((line for line in reversed(self.transcript) if line.strip()), "")


def kill_after_marker(cli: PreloadedCli, argv: list[str], after_line: int | None = None,
                      delay: float = 0.0) -> Killed:
    """Run ``teach`` with ``argv`` (a child of the preloaded ``cli``) and SIGKILL it ``delay``
    seconds after it printed line ``after_line`` (0: its first, which it prints once open; None:
    let it finish); the whole transcript, read to its end after the kill, with when each line
    came, in seconds from the first. Counting lines, not seconds from the process start, puts a
    kill at the same point of the session however loaded the machine is; only ``delay``, within
    one line's work, is measured in time."""
    child = cli.start(argv)
    killed = Killed()
    reached, ended = threading.Event(), threading.Event()
    began = time.monotonic()

    def read() -> None:
        nonlocal began
        with child.stdout:
            for line in child.stdout:
                if not killed.transcript:
                    began = time.monotonic()
                    killed.started = line.startswith(MARKER)
                killed.times.append(time.monotonic() - began)
                killed.transcript.append(line.rstrip("\n"))
                if after_line is not None and len(killed.transcript) > after_line:
                    reached.set()
        ended.set()  # the process ended (or died): its output is closed
        reached.set()  # before that line, maybe

    reader = threading.Thread(target=read)
    reader.start()
    if after_line is not None:
        reached.wait()
        time.sleep(delay)
        if not ended.is_set():
            child.kill()
    reader.join()
    return killed


def kill_after_start(cli: PreloadedCli, argv: list[str], delay: float) -> Killed:
    """Run ``teach`` with ``argv`` and SIGKILL it ``delay`` seconds after it was started (a kill
    during start-up, before the session printed its first line, lands by time alone)."""
    child = cli.start(argv)
    time.sleep(delay)
    child.kill()
    killed = Killed()
    with child.stdout:
        killed.transcript = [line.rstrip("\n") for line in child.stdout]
    killed.started = bool(killed.transcript) and killed.transcript[0].startswith(MARKER)
    return killed


def phase(line: str) -> str:
    """What the session was doing when ``line`` was the last it printed ("" when the line tells
    nothing, as the wrapped end of a long one): a step, a run, learning from a finished
    demonstration (its CSV, tree and generation written before they are shown), a question
    (asked after each generation, answered, learned from), the journal saved at the end of a
    turn (after its state line), or another command."""
    text = line.strip()
    said = text[len(PROMPT):].split(" ", 1)[0] if text.startswith(PROMPT) else ""
    if said in ("start", "reset", "show", "save"):
        return "other command"
    if said == "done":
        return "learning"
    if said == "run" or text.startswith(("→", "I did", "robot: Stopped", "robot: Done")):
        return "run"
    if said or text.startswith(("✓", "New demonstration", "Event:")):
        return "steps"
    if text.startswith(("robot asks", "(", "answer>", "Thank you", "│", "╭", "╰", "Generation")):
        return "questions"
    if text.startswith("state:"):
        return "end of turn"
    return ""


def since_last_prompt(transcript: list[str]) -> list[str]:
    """What the session printed in answer to the line it was given last."""
    prompts = [i for i, line in enumerate(transcript) if line.startswith(PROMPT)]
    return transcript[prompts[-1] + 1:] if prompts else []


def run_cut(transcript: list[str]) -> list[str]:
    """The actions of the run the kill cut (the teacher saw them begin, not the run's end)."""
    block = since_last_prompt(transcript)
    announced = [line[2:] for line in block if line.startswith("→ ")]
    return [] if any(line.startswith("I did") for line in block) else announced


