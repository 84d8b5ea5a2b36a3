"""Every run of a learned tree as a BehaviorTree.CPP ``.btlog`` file, for Groot2 to replay.

``BtlogRecorder`` is an observer: ``on_run_start`` opens a ``BtlogWriter`` on the next
``run-NNN.btlog`` of the session's run folder, every status change the tree channel reports
(``on_status_change``: what BehaviorTree.CPP would have logged, each tick replayed so no skill is
ticked twice, the resets of halting what still runs at the end) is logged, and ``on_run_end``
writes the file atomically. The channel (``teach.observe.status_changes``) reports only the
actions that started, so neither does a run stopped by its limit (``run 3``). Numbers are
never reused: the next one is one more than the highest in the folder, and the session lock
keeps the folder ours. With ``trees`` (the session's generations folder) the tree each run ran
is also written there as ``run-NNN.xml``, numbered as its ``.btlog``: the unpruned tree that
ran, beside the pruned generations the teacher sees.

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

from teach.bt.btcpp_status import BtStatus, Change, btcpp_uids
from teach.bt.btlog import SUFFIX, BtlogWriter, epoch_us
from teach.bt.xml import tree_to_xml
from teach.fsutil import atomic_write_text
from teach.observe.hook import Observer

if TYPE_CHECKING:
    from teach.bt.nodes import Node

RUN_PREFIX = "run-"
_RUN_NAME = re.compile(rf"{RUN_PREFIX}(\d+){re.escape(SUFFIX)}")
SYMBOLIC_TICK_US = 1_000_000
"""A world without a clock: its ticks are logged one second apart (the tree channel's times)."""


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
    """Writes each run the session reports (``on_run_start`` … ``on_run_end``) to ``folder``,
    from the tree channel (``on_status_change``), which the fan-out ``Observers`` derives."""

    def __init__(self, folder: Path, wall_clock: Callable[[], int] = epoch_us, trees: Path | None = None):
        self.folder = folder
        self.trees = trees
        self.wall_clock = wall_clock
        self.written: list[Path] = []
        self._writer: BtlogWriter | None = None
        self._uids: dict[int, int] = {}
        self._start_us = 0
        self._now_us = 0

    def on_run_start(self, tree: Node) -> None:
        self._finish()  # an earlier run that ended without on_run_end (its world raised)
        self._uids = {node.uid: number for number, node in enumerate(btcpp_uids(tree), 1)}
        self._start_us = self._now_us = self.wall_clock()
        self._writer = BtlogWriter(next_run_path(self.folder), tree, clock=lambda: self._now_us)
        if self.trees is not None:
            atomic_write_text(self.trees / self._writer.path.with_suffix(".xml").name, tree_to_xml(tree))

    def on_status_change(self, time: float, node: Node, previous: BtStatus, status: BtStatus) -> None:
        if self._writer is None or node.uid not in self._uids:
            return
        self._now_us = self._start_us + round(time * 1e6)
        self._writer.record((Change(self._uids[node.uid], status),))

    def on_run_end(self, outcome: str, actions: int) -> None:
        self._finish()

    def close(self) -> None:
        self._finish()

    def _finish(self) -> None:
        writer, self._writer = self._writer, None
        if writer is None:
            return
        writer.close()
        self.written.append(writer.path)
