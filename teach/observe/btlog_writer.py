"""Every run of a learned tree as a BehaviorTree.CPP ``.btlog`` file, for Groot2 to replay.

``BtlogRecorder`` is an observer: ``on_run_start`` opens a ``BtlogWriter`` on the next
``run-NNN.btlog`` of the session's run folder, each ``on_tick`` of the run logs the status
changes BehaviorTree.CPP would have logged for that tick (``BtlogWriter.log_tick``, so no skill
is ticked twice), and ``on_run_end`` halts what still runs (as BehaviorTree.CPP's ``haltTree``
does when a run is stopped) and writes the file atomically. A run stopped by its limit
(``run 3``) logs only the actions that started: the tick that would start one more is held
back until the next tick and dropped when the run ends there, as the session drops that action.
Numbers are never reused: the next one is one more than the highest in the folder, and the
session lock keeps the folder ours.

The file's first timestamp is the wall clock when the run began (BehaviorTree.CPP's too);
the records' times are simulated: seconds of simulated time since the run's first tick where
the world has a clock (MuJoCo reports it through ``set_time``), else one second per tick,
so the same run gives the same records.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from teach.bt.btlog import SUFFIX, BtlogWriter, epoch_us
from teach.observe.hook import Observer

if TYPE_CHECKING:
    from teach.bt.nodes import Node
    from teach.bt.tick import TickResult

RUN_PREFIX = "run-"
_RUN_NAME = re.compile(rf"{RUN_PREFIX}(\d+){re.escape(SUFFIX)}")
SYMBOLIC_TICK_US = 1_000_000
"""A world without a clock: its ticks are logged one second apart."""


def run_logs(folder: Path) -> list[Path]:
    """The folder's ``run-NNN.btlog`` files in the order of their numbers."""
    if not folder.is_dir():
        return []
    numbered = [(int(match.group(1)), path) for path in folder.iterdir()
                if (match := _RUN_NAME.fullmatch(path.name)) is not None]
    return [path for _, path in sorted(numbered)]


def next_run_path(folder: Path) -> Path:
    """One more than the highest run number in ``folder``: a number is never given twice."""
    numbers = [int(m.group(1)) for p in run_logs(folder) if (m := _RUN_NAME.fullmatch(p.name)) is not None]
    return folder / f"{RUN_PREFIX}{max(numbers, default=0) + 1:03d}{SUFFIX}"


class BtlogRecorder(Observer):
    """Writes each run the session reports (``on_run_start`` … ``on_run_end``) to ``folder``."""

    def __init__(self, folder: Path, wall_clock: Callable[[], int] = epoch_us):
        self.folder = folder
        self.wall_clock = wall_clock
        self.written: list[Path] = []
        self._writer: BtlogWriter | None = None
        self._sim_time: float | None = None
        self._first_sim: float | None = None
        self._ticks = 0
        self._start_us = 0
        self._now_us = 0
        self._pending: tuple[int, TickResult, bool] | None = None  # the last tick: its time, itself, starts an action
        self._last_action: str | None = None
        self._started = 0

    def set_time(self, step: int | None, sim_time: float | None = None) -> None:
        if sim_time is not None:
            self._sim_time = sim_time

    def on_run_start(self, tree: Node) -> None:
        self._finish()  # an earlier run that ended without on_run_end (its world raised)
        self._sim_time = self._first_sim = None
        self._ticks = 0
        self._pending, self._last_action, self._started = None, None, 0
        self._start_us = self._now_us = self.wall_clock()
        self._writer = BtlogWriter(next_run_path(self.folder), tree, clock=lambda: self._now_us)

    def on_tick(self, tree: Node, result: TickResult) -> None:
        if self._writer is None:
            return
        if self._sim_time is not None:
            if self._first_sim is None:
                self._first_sim = self._sim_time
            elapsed = round((self._sim_time - self._first_sim) * 1e6)
        else:
            elapsed = self._ticks * SYMBOLIC_TICK_US
        self._ticks += 1
        self._log_pending()
        starts = result.action is not None and result.action != self._last_action
        self._last_action = result.action
        self._started += starts
        self._pending = (self._start_us + elapsed, result, starts)

    def _log_pending(self) -> None:
        if self._pending is not None and self._writer is not None:
            self._now_us, result, _starts = self._pending
            self._writer.log_tick(result)
        self._pending = None

    def on_run_end(self, outcome: str, actions: int) -> None:
        """``actions``: how many actions the session kept; one more started at the last tick was
        stopped as it started (``run N``), so it is not logged."""
        if self._pending is not None and self._pending[2] and outcome == "interrupted" and self._started > actions:
            self._pending = None
        self._finish()

    def close(self) -> None:
        self._finish()

    def _finish(self) -> None:
        self._log_pending()
        writer, self._writer = self._writer, None
        if writer is None:
            return
        writer.halt()  # a stopped run: BehaviorTree.CPP halts the tree, all back to IDLE
        writer.close()
        self.written.append(writer.path)
