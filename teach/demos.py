"""Demonstrations in the thesis's CSV format (§5), read with ``file:line`` errors and written atomically.

One file is one demonstration; each line is ``v1;...;vn;A``: the conditions' truth values in
ID order, then the action observed in that state (0: goal state, -1: external action).
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

from teach import limits
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State, find_domain_file, load_domain
from teach.errors import FormatError
from teach.fsutil import atomic_write_text, read_text

_BLANKS = " \t\r"
"""What may end a line unseen: ASCII blanks and the CR of a CRLF line end, nothing else."""
_ODD = re.compile(r"[^\S \t]|[\x00-\x08\x0e-\x1f\x7f-\x9f\u200b-\u200f\u202a-\u202e\u2060-\u2069\ufeff]")
"""A character that hides in a line: a control, a Unicode space or line break (U+2028, NEL, form
feed, vertical tab, no-break space, ...) or an invisible format character."""
_ACTION_ID = re.compile(r"-?[0-9]{1,7}", re.ASCII)
"""An action ID as the format writes it: ASCII digits, '-' only for -1 (no '+', '_', spaces inside)."""


@dataclass(frozen=True, slots=True)
class Step:
    """One CSV line: a state and the action observed in it."""

    state: State
    action: int
    line: int = 0


@dataclass(frozen=True)
class Transition:
    before: State
    action: int
    after: State


@dataclass(frozen=True)
class Demonstration:
    name: str
    steps: tuple[Step, ...]
    path: Path | None = None

    @property
    def reached_goal(self) -> bool:
        return bool(self.steps) and self.steps[-1].action == GOAL_ACTION

    @property
    def actions(self) -> tuple[int, ...]:
        """The robot's actions in order (no external actions, no goal marker)."""
        return tuple(s.action for s in self.steps if s.action > 0)

    def transitions(self) -> list[Transition]:
        """Every (s, a, s') with a known successor state, external actions included."""
        return [Transition(a.state, a.action, b.state)
                for a, b in zip(self.steps, self.steps[1:], strict=False) if a.action != GOAL_ACTION]

    @property
    def goal_state(self) -> State | None:
        return self.steps[-1].state if self.reached_goal else None


def parse_demonstration(text: str, domain: Domain, path: str | Path, name: str | None = None,
                        states: dict[State, State] | None = None) -> Demonstration:
    """Parse one CSV demonstration, validating every line against the domain. Equal states share
    one tuple (``states`` may carry them across the files of a set), so memory grows with the
    number of lines, not with lines times conditions."""
    width = len(domain.conditions)
    lines = text.split("\n")  # lines end at \n (or \r\n) only, never at U+2028, NEL or a form feed
    while lines and not lines[-1].strip(_BLANKS):
        lines.pop()
    if not lines:
        raise FormatError("empty demonstration file", path)
    if len(lines) > limits.MAX_DEMO_LINES:
        raise FormatError(f"more than {limits.MAX_DEMO_LINES} lines in one demonstration", path,
                          limits.MAX_DEMO_LINES + 1)
    shared: dict[State, State] = {} if states is None else states
    steps: list[Step] = []
    for number, raw in enumerate(lines, start=1):
        line = raw.rstrip(_BLANKS)  # trailing ASCII blanks and CR are let be; anything else is part of a field
        if not line:
            raise FormatError("empty line inside a demonstration", path, number)
        odd = _ODD.search(line)
        if odd:
            raise FormatError(f"character U+{ord(odd.group()):04X} at column {odd.start() + 1} is not allowed: fields "
                              "hold only 0, 1 and an action ID, and lines end only at \\n or \\r\\n", path, number)
        if steps and steps[-1].action == GOAL_ACTION:
            raise FormatError("a line after the goal line (action 0 must be the last line)", path, number)
        fields = line.split(";")
        if len(fields) != width + 1:
            raise FormatError(f"expected {width + 1} fields ({width} conditions and an action ID) "
                              f"separated by ';', found {len(fields)}", path, number)
        state = []
        for index, value in enumerate(fields[:-1]):
            if value not in ("0", "1"):
                cname = domain.conditions[index].name
                raise FormatError(f"condition {index + 1} ({cname}) must be 0 or 1, found {_shown(value)}",
                                  path, number)
            state.append(value == "1")
        text_id = fields[-1]
        if not _ACTION_ID.fullmatch(text_id) or (text_id.startswith("-") and text_id != "-1"):
            raise FormatError(f"action ID must be an integer written in digits (0 = goal, -1 = external), "
                              f"found {_shown(text_id)}", path, number)
        action = int(text_id)
        if action not in (GOAL_ACTION, EXTERNAL_ACTION) and not domain.has_action(action):
            raise FormatError(f"unknown action ID {action} (this domain has {_known_ids(domain)}; 0 = goal, "
                              "-1 = external)", path, number)
        key = tuple(state)
        steps.append(Step(shared.setdefault(key, key), action, number))
    if steps[-1].action == EXTERNAL_ACTION:
        raise FormatError("an external action (-1) on the last line has no following state", path, len(lines))
    return Demonstration(name or Path(path).stem, tuple(steps), Path(path))


def _shown(value: str) -> str:
    return repr(value) if len(value) <= 40 else repr(value[:37]) + "..."


def _known_ids(domain: Domain) -> str:
    ids = [str(a.id) for a in domain.actions]
    return ", ".join(ids) if len(ids) <= 12 else ", ".join(ids[:12]) + f", ... ({len(ids)} actions)"


def read_demonstration(path: str | Path, domain: Domain, states: dict[State, State] | None = None) -> Demonstration:
    return parse_demonstration(read_text(path, "demonstration", limits.MAX_DEMO_BYTES), domain, path, states=states)


def read_demo_set(folder: str | Path, domain: Domain | None = None) -> tuple[Domain, list[Demonstration]]:
    """All ``*.csv`` demonstrations of a folder in sorted name order, with their domain; a set
    holds at most ``MAX_DEMOS`` files and ``MAX_SET_LINES`` lines (teach.limits)."""
    folder = Path(folder)
    if not os.path.lexists(folder):
        raise FormatError("no such folder", folder)
    if not folder.is_dir():
        raise FormatError("not a folder of demonstrations", folder)
    if domain is None:
        domain = load_domain(find_domain_file(folder))
    names = sorted(_demo_names(folder))  # names, not paths: sorting Path objects costs 20 times more
    if not names:
        raise FormatError("no demonstrations (*.csv) in this folder", folder)
    states: dict[State, State] = {}
    demos, lines = [], 0
    for name in names:
        path = folder / name
        demo = read_demonstration(path, domain, states)
        lines += len(demo.steps)
        if lines > limits.MAX_SET_LINES:
            raise FormatError(f"the set has more than {limits.MAX_SET_LINES} lines in all; this file goes past that",
                              path)
        demos.append(demo)
    return domain, demos


def _demo_names(folder: Path) -> list[str]:
    """The names of a folder's ``*.csv`` files that are not folders, refused as soon as there are
    more than ``MAX_DEMOS`` of them (before the rest of a huge folder is listed)."""
    names: list[str] = []
    try:
        with os.scandir(folder) as entries:
            for entry in entries:
                if entry.name.endswith(".csv") and len(entry.name) > len(".csv") and not entry.is_dir():
                    names.append(entry.name)
                    if len(names) > limits.MAX_DEMOS:
                        raise FormatError(f"more than {limits.MAX_DEMOS} demonstrations: a set may hold at most "
                                          f"{limits.MAX_DEMOS}", folder)
    except OSError as exc:
        raise FormatError(f"cannot list the demonstrations: {exc.strerror}", folder) from None
    return names


def format_demonstration(demo: Demonstration) -> str:
    return "".join(";".join("1" if v else "0" for v in step.state) + f";{step.action}\n" for step in demo.steps)


def write_demonstration(path: str | Path, demo: Demonstration, root: str | Path | None = None) -> None:
    """Write one demonstration atomically, so a crash never leaves half a file; no folder between
    ``root`` (default: the working folder) and it may be a symbolic link (teach.fsutil)."""
    atomic_write_text(path, format_demonstration(demo), root)


def next_demo_path(folder: str | Path, prefix: str = "demo") -> Path:
    """The next free ``<prefix>-NNN.csv`` name in a folder (sorted order = recording order)."""
    folder = Path(folder)
    taken = {p.name for p in folder.glob(f"{prefix}-*.csv")} if folder.is_dir() else set()
    number = 1
    while f"{prefix}-{number:03d}.csv" in taken:
        number += 1
    return folder / f"{prefix}-{number:03d}.csv"
