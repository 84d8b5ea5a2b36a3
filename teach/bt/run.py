"""What ticks a tree and how a run of it ended: shared by the executors below the worlds
(``teach.sim.executor``) and the worlds above them (``teach.world``), so neither imports the other."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from enum import StrEnum

from teach.bt.nodes import Node, Status
from teach.bt.tick import TickResult


class Outcome(StrEnum):
    """How a run of the learned tree ended."""

    SUCCESS = "success"
    FAILURE = "failure"
    TIMEOUT = "timeout"
    INTERRUPTED = "interrupted"


Ticker = Callable[[Node, Callable[[str], bool] | Mapping[str, bool], Callable[[str], Status]], TickResult]
"""What ticks a tree once: ``teach.bt.tick.tick``, or BehaviorTree.CPP (``teach.bt.groot``)."""
