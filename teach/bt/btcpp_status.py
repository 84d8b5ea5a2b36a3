"""BehaviorTree.CPP's node statuses, tick by tick, for our trees (what its loggers and Groot2 see).

Our own tick (``teach.bt.tick``) is memoryless and reports only what each node returned.
BehaviorTree.CPP keeps a status in every node between ticks and notifies its loggers of every
*change*, including the resets to IDLE done by halting; a ``.btlog`` file is those changes.
``BtcppTree`` reproduces them by transliterating the tick, halt and reset logic of the
library version ``behaviortreepy`` bundles (BehaviorTree.CPP 4.8.2; the control nodes are
unchanged up to 4.10): ``TreeNode::executeTick``, ``ReactiveSequence``, ``ReactiveFallback``,
``ParallelNode``, ``InverterNode`` (with ``DecoratorNode::executeTick``), ``ConditionNode``,
``StatefulActionNode`` and ``Tree::tickRoot`` / ``Tree::haltTree``.

Two BehaviorTree.CPP behaviours differ from the memoryless semantics of Table 2.2, and the
model keeps both, since the point is to log what BehaviorTree.CPP would do:
a running ``Parallel`` does not tick again a child that already finished (its result is
remembered until the Parallel completes or is halted), and it stops ticking children as
soon as its success or failure threshold is reached. Node uids are BehaviorTree.CPP's:
pre-order positions from 1 (``btcpp_uids``).
"""

from __future__ import annotations

import itertools
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from enum import IntEnum
from typing import NamedTuple

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, Status, children, walk
from teach.bt.tick import TickResult, always_running


class BtStatus(IntEnum):
    """``BT::NodeStatus``, numbered as BehaviorTree.CPP (and its log files) number it."""

    IDLE = 0
    RUNNING = 1
    SUCCESS = 2
    FAILURE = 3
    SKIPPED = 4


_FROM_TEACH = {Status.SUCCESS: BtStatus.SUCCESS, Status.FAILURE: BtStatus.FAILURE, Status.RUNNING: BtStatus.RUNNING}
_TO_TEACH = {value: key for key, value in _FROM_TEACH.items()}


class Change(NamedTuple):
    """One status change of one node, as a ``StatusChangeLogger`` receives it."""

    uid: int
    status: BtStatus


@dataclass(frozen=True, slots=True)
class TickChanges:
    """What one tick returned at the root and every status change it caused, in order."""

    status: Status
    changes: tuple[Change, ...]


ConditionLookup = Callable[[str], bool] | Mapping[str, bool]
ActionTick = Callable[[str], Status]
HaltHook = Callable[[str], None]


def btcpp_uids(root: Node) -> list[Node]:
    """The nodes in BehaviorTree.CPP's uid order: the node with uid k is at index k - 1."""
    return list(walk(root))


class _World:
    """The leaves' view of the world during one tick or halt."""

    def __init__(self, condition: ConditionLookup, action: ActionTick, on_halt: HaltHook | None):
        self.holds = condition.__getitem__ if isinstance(condition, Mapping) else condition
        self.action = action
        self.on_halt = on_halt


class _Live(ABC):
    """``BT::TreeNode``: a status kept between ticks, every change appended to ``log``."""

    def __init__(self, uid: int, log: list[Change]):
        self.uid = uid
        self.log = log
        self.status = BtStatus.IDLE

    def set_status(self, status: BtStatus) -> None:
        if status != self.status:
            self.status = status
            self.log.append(Change(self.uid, status))

    def reset_status(self) -> None:
        self.set_status(BtStatus.IDLE)

    def execute_tick(self, world: _World) -> BtStatus:
        status = self.tick(world)
        self.set_status(status)
        return status

    @abstractmethod
    def tick(self, world: _World) -> BtStatus:
        """The node's own ``tick()``."""

    @abstractmethod
    def halt(self, world: _World) -> None:
        """The node's own ``halt()``; ends with the node IDLE."""


class _Condition(_Live):
    def __init__(self, uid: int, log: list[Change], name: str):
        super().__init__(uid, log)
        self.name = name

    def tick(self, world: _World) -> BtStatus:
        return BtStatus.SUCCESS if world.holds(self.name) else BtStatus.FAILURE

    def halt(self, world: _World) -> None:
        self.reset_status()


class _Action(_Live):
    """``StatefulActionNode``: onStart from IDLE, onRunning while RUNNING, onHalted when halted.
    (Its third case, returning a finished status unchanged, cannot happen under our control
    nodes: each resets a child that finished before the child is ticked again.)"""

    def __init__(self, uid: int, log: list[Change], name: str):
        super().__init__(uid, log)
        self.name = name

    def tick(self, world: _World) -> BtStatus:
        return _FROM_TEACH[world.action(self.name)]

    def halt(self, world: _World) -> None:
        if self.status == BtStatus.RUNNING and world.on_halt is not None:
            world.on_halt(self.name)
        self.reset_status()


class _Control(_Live):
    """``ControlNode``: halting a child halts it if running, then resets it to IDLE."""

    def __init__(self, uid: int, log: list[Change], kids: tuple[_Live, ...]):
        super().__init__(uid, log)
        self.children = kids

    def halt_child(self, index: int, world: _World) -> None:
        child = self.children[index]
        if child.status == BtStatus.RUNNING:
            child.halt(world)
        child.reset_status()

    def reset_children(self, world: _World) -> None:
        for index in range(len(self.children)):
            self.halt_child(index, world)

    def halt(self, world: _World) -> None:
        self.reset_children(world)
        self.reset_status()


class _Reactive(_Control):
    """``ReactiveSequence`` (``stop_on`` FAILURE) and ``ReactiveFallback`` (``stop_on`` SUCCESS)."""

    def __init__(self, uid: int, log: list[Change], kids: tuple[_Live, ...], stop_on: BtStatus):
        super().__init__(uid, log, kids)
        self.stop_on = stop_on

    def tick(self, world: _World) -> BtStatus:
        self.set_status(BtStatus.RUNNING)
        for index, child in enumerate(self.children):
            status = child.execute_tick(world)
            if status == BtStatus.RUNNING:
                for other in range(len(self.children)):
                    if other != index:
                        self.halt_child(other, world)
                return BtStatus.RUNNING
            if status == self.stop_on:
                self.reset_children(world)
                return status
        self.reset_children(world)
        return BtStatus.SUCCESS if self.stop_on == BtStatus.FAILURE else BtStatus.FAILURE


class _Parallel(_Control):
    """``ParallelNode``: finished children are not ticked again until it completes or is halted."""

    def __init__(self, uid: int, log: list[Change], kids: tuple[_Live, ...], success_count: int):
        super().__init__(uid, log, kids)
        self.success_threshold = success_count
        self.failure_threshold = len(kids) - success_count + 1
        self.completed: set[int] = set()
        self.successes = 0
        self.failures = 0

    def clear(self) -> None:
        self.completed.clear()
        self.successes = self.failures = 0

    def tick(self, world: _World) -> BtStatus:
        self.set_status(BtStatus.RUNNING)
        count = len(self.children)
        for index, child in enumerate(self.children):
            if index not in self.completed:
                status = child.execute_tick(world)
                if status == BtStatus.SUCCESS:
                    self.completed.add(index)
                    self.successes += 1
                elif status == BtStatus.FAILURE:
                    self.completed.add(index)
                    self.failures += 1
            if self.successes >= self.success_threshold:
                return self.finish(BtStatus.SUCCESS, world)
            if count - self.failures < self.success_threshold or self.failures == self.failure_threshold:
                return self.finish(BtStatus.FAILURE, world)
        return BtStatus.RUNNING

    def finish(self, status: BtStatus, world: _World) -> BtStatus:
        self.clear()
        self.reset_children(world)
        return status

    def halt(self, world: _World) -> None:
        self.clear()
        super().halt(world)


class _Inverter(_Live):
    """``InverterNode`` inside ``DecoratorNode::executeTick`` (which resets a finished child)."""

    def __init__(self, uid: int, log: list[Change], child: _Live):
        super().__init__(uid, log)
        self.child = child

    def reset_child(self, world: _World) -> None:
        if self.child.status == BtStatus.RUNNING:
            self.child.halt(world)
        self.child.reset_status()

    def tick(self, world: _World) -> BtStatus:
        self.set_status(BtStatus.RUNNING)
        status = self.child.execute_tick(world)
        if status in (BtStatus.SUCCESS, BtStatus.FAILURE):
            self.reset_child(world)
            return BtStatus.FAILURE if status == BtStatus.SUCCESS else BtStatus.SUCCESS
        return status

    def execute_tick(self, world: _World) -> BtStatus:
        status = super().execute_tick(world)
        if self.child.status in (BtStatus.SUCCESS, BtStatus.FAILURE):
            self.child.reset_status()
        return status

    def halt(self, world: _World) -> None:
        self.reset_child(world)
        self.reset_status()


class BtcppTree:
    """One of our trees as BehaviorTree.CPP would hold it: build once, then tick it state after
    state; each call returns the root's status and the status changes, as a logger sees them."""

    def __init__(self, root: Node):
        self.log: list[Change] = []
        self.root = self._build(root, itertools.count(1))
        self.leaves = [(n.uid, n) for n in walk(root) if isinstance(n, (Condition, Action))]

    def _build(self, node: Node, counter: Iterator[int]) -> _Live:
        uid = next(counter)
        if isinstance(node, Condition):
            return _Condition(uid, self.log, node.name)
        if isinstance(node, Action):
            return _Action(uid, self.log, node.name)
        kids = tuple(self._build(kid, counter) for kid in children(node))
        if isinstance(node, Inverter):
            return _Inverter(uid, self.log, kids[0])
        if isinstance(node, Parallel):
            return _Parallel(uid, self.log, kids, node.success_threshold)
        if isinstance(node, Sequence):
            return _Reactive(uid, self.log, kids, BtStatus.FAILURE)
        if isinstance(node, Fallback):
            return _Reactive(uid, self.log, kids, BtStatus.SUCCESS)
        raise TypeError(f"not a node: {node!r}")

    def tick(self, condition: ConditionLookup, action: ActionTick = always_running,
             on_halt: HaltHook | None = None) -> TickChanges:
        """``Tree::tickExactlyOnce``: tick the root; a finished root is reset to IDLE.

        ``condition`` says which conditions hold, ``action`` what an action returns when
        ticked (started or still running), ``on_halt`` hears of each running action halted."""
        world = _World(condition, action, on_halt)
        status = self.root.execute_tick(world)
        if status in (BtStatus.SUCCESS, BtStatus.FAILURE):
            self.root.reset_status()
        return TickChanges(_TO_TEACH[status], self._take())

    def replay(self, result: TickResult) -> TickChanges:
        """Tick as ``teach.bt.tick.tick`` already ticked (``result``): every leaf answers as it
        answered there, so no skill is ticked twice.

        BehaviorTree.CPP reaches the same leaves, or fewer (a Parallel stops at its threshold),
        unless a running Parallel remembers a child's earlier result: then it may return
        another status than our memoryless tick and reach leaves ours did not, which answer
        FAILURE (conditions) and RUNNING (actions, as if just started). The returned status
        is BehaviorTree.CPP's, so a caller can tell when that happened."""
        visited = dict(result.trace)
        conditions: dict[str, bool] = {}
        actions: dict[str, Status] = {}
        for uid, leaf in self.leaves:
            if uid in visited and isinstance(leaf, Condition):
                conditions[leaf.name] = visited[uid] is Status.SUCCESS
            elif uid in visited:
                actions[leaf.name] = visited[uid]
        return self.tick(lambda name: conditions.get(name, False), lambda name: actions.get(name, Status.RUNNING))

    def halt(self, on_halt: HaltHook | None = None) -> tuple[Change, ...]:
        """``Tree::haltTree``: halt everything (running actions hear ``on_halt``), all to IDLE.
        (BehaviorTree.CPP then halts every node once more "just in case": a no-op here, since
        a halted node leaves all its descendants IDLE.)"""
        self.root.halt(_World({}, always_running, on_halt))
        return self._take()

    def _take(self) -> tuple[Change, ...]:
        changes = tuple(self.log)
        self.log.clear()
        return changes
