"""The tree channel: BehaviorTree.CPP's status changes of each run, derived once for every
observer that listens (``Observer.on_status_change``, shaped like ``StatusChangeLogger``'s
callback: time, node, previous status, status).

Each tick is replayed on a ``BtcppTree`` of the run's tree (every leaf answering as it answered
in our tick), and the end of a run halts what still runs, as ``Tree::haltTree`` does. A run
stopped by its limit (``run 3``) reports only the actions that started: a tick that starts one
more action is held back until the next tick, and dropped when the run ends there with more
actions started than the session kept. Times are seconds since the run's first tick: simulated
where the world has a clock, else one second per tick.
"""

from __future__ import annotations

from collections.abc import Callable

from teach.bt.btcpp_status import BtcppTree, BtStatus, Change, btcpp_uids
from teach.bt.nodes import Node
from teach.bt.run import Outcome
from teach.bt.tick import TickResult

StatusChange = Callable[[float, Node, BtStatus, BtStatus], None]
"""``(time, node, previous, status)``."""

class StatusChanges:
    """Turns one run at a time into status changes for ``emit``."""

    def __init__(self, emit: StatusChange):
        self.emit = emit
        self._live: BtcppTree | None = None
        self._nodes: list[Node] = []
        self._statuses: list[BtStatus] = []
        self._sim_time: float | None = None
        self._first: float | None = None
        self._ticks = 0
        self._time = 0.0
        self._held: tuple[float, TickResult, bool] | None = None
        self._last_action: str | None = None
        self._started = 0

    def set_time(self, sim_time: float | None) -> None:
        if sim_time is not None:
            self._sim_time = sim_time

    def run_starts(self, tree: Node) -> None:
        self.run_ends(None, 0)  # an earlier run that never reported its end (its world raised)
        self._live = BtcppTree(tree)
        self._nodes = btcpp_uids(tree)
        self._statuses = [BtStatus.IDLE] * len(self._nodes)
        self._sim_time = self._first = None
        self._ticks, self._time, self._held, self._last_action, self._started = 0, 0.0, None, None, 0

    def tick(self, result: TickResult) -> None:
        if self._live is None:
            return
        if self._sim_time is not None:
            self._first = self._sim_time if self._first is None else self._first
            at = self._sim_time - self._first
        else:
            at = float(self._ticks)
        self._ticks += 1
        self._release()
        starts = result.action is not None and result.action != self._last_action
        self._last_action = result.action
        self._started += starts
        self._held = (at, result, starts)

    def run_ends(self, outcome: str | None, actions: int) -> None:
        """The run ended with ``outcome`` after the session kept ``actions`` actions (None: it
        never said): the tick that started one more than those is dropped, the rest halted."""
        if self._live is None:
            return
        if self._held is not None and self._held[2] and outcome == Outcome.INTERRUPTED and self._started > actions:
            self._held = None
        self._release()
        self._send(self._time, self._live.halt())
        self._live = None

    def _release(self) -> None:
        if self._held is not None and self._live is not None:
            self._time, result, _starts = self._held
            self._send(self._time, self._live.replay(result).changes)
        self._held = None

    def _send(self, at: float, changes: tuple[Change, ...]) -> None:
        for change in changes:
            previous = self._statuses[change.uid - 1]
            self._statuses[change.uid - 1] = change.status
            self.emit(at, self._nodes[change.uid - 1], previous, change.status)
