"""Where a session begins when nothing can be done where nothing holds (blocksworld: no block on
the table, the hand neither empty nor full): where a demonstration beside the domain file
begins, a situation the world has been in. Without one the teacher sets a situation up with
'start'."""

from __future__ import annotations

import os
from pathlib import Path

from teach.demos import read_demonstration
from teach.domain import Domain, State
from teach.errors import TeachError
from teach.symbolic import possible_actions

MAX_LOOKED_AT = 64
"""The most demonstration files read for a start (the first in sorted order that fits is taken)."""


def demonstrated_start(domain: Domain) -> tuple[Path, State] | None:
    """The first state of the first demonstration (sorted: the folder of the domain file, then its
    subfolders) from which the domain's model allows a step and the task is not done; None if
    there is none. A file that does not read is passed over: it is not what the teacher asked for."""
    if domain.path is None:
        return None
    for path in _demonstration_files(Path(domain.path).parent):
        try:
            steps = read_demonstration(path, domain).steps
        except TeachError:
            continue
        start = steps[0].state
        if possible_actions(domain, start) and not domain.goal_holds(start):
            return path, start
    return None


def _demonstration_files(folder: Path) -> list[Path]:
    """At most ``MAX_LOOKED_AT`` ``*.csv`` files of ``folder`` and then of its subfolders, sorted."""
    found: list[Path] = []
    for place in [folder, *_entries(folder, folders=True)]:
        found += _entries(place, folders=False)
        if len(found) >= MAX_LOOKED_AT:
            break
    return found[:MAX_LOOKED_AT]


def _entries(folder: Path, folders: bool) -> list[Path]:
    """The subfolders (or the ``*.csv`` files) of ``folder``, sorted; none if it cannot be listed."""
    try:
        with os.scandir(folder) as entries:
            names = sorted(entry.name for entry in entries
                           if (entry.is_dir() if folders else entry.name.endswith(".csv") and entry.is_file()))
    except OSError:
        return []
    return [folder / name for name in names]
