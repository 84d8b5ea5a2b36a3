"""The observers' two typed channels: the tree channel (BehaviorTree.CPP's status changes,
derived once) and the session channel (the journal's typed events)."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import pytest
from conftest import BALL_DOMAIN

from teach.bt.btcpp_status import BtStatus
from teach.bt.nodes import Action, Node, walk
from teach.domain import load_domain
from teach.observe.hook import Observer, Observers
from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.world.symbolic import SymbolicWorld


class TreeChannel(Observer):
    def __init__(self) -> None:
        self.changes: list[tuple[float, int, BtStatus, BtStatus]] = []
        self.runs: list[int] = []  # where each run's changes begin

    def on_run_start(self, tree: Node) -> None:
        self.runs.append(len(self.changes))

    def on_status_change(self, time: float, node: Node, previous: BtStatus, status: BtStatus) -> None:
        self.changes.append((time, node.uid, previous, status))


class SessionChannel(Observer):
    def __init__(self) -> None:
        self.events: list[Any] = []

    def on_session_event(self, event: Any) -> None:
        self.events.append(event)


WHOLE_TASK = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"


def test_the_tree_channel_is_bt_cpps_status_changes_and_the_session_channel_the_journal(tmp_path: Path) -> None:
    domain = load_domain(BALL_DOMAIN)
    first, second, journal = TreeChannel(), TreeChannel(), SessionChannel()
    observer = Observers(first, journal, second)
    session = SessionManager(Settings("t", world=WorldKind.SYMBOLIC, seed=3, base=tmp_path, record=False), domain,
                             SymbolicWorld(domain, 3, observer), observer)
    for line in (WHOLE_TASK, "done", "reset 11", "run", "reset 12", "run 2"):
        session.handle(line)
    session.close()
    assert first.changes == second.changes and len(first.runs) == 2  # one derivation, the same for every listener
    last: dict[int, BtStatus] = {}
    for time, uid, previous, status in first.changes:  # each change starts where the node's last one ended
        assert previous == last.get(uid, BtStatus.IDLE) != status and time >= 0
        last[uid] = status
    assert set(last.values()) == {BtStatus.IDLE}  # both runs end with the whole tree idle
    # 'run 2' stops as its third action starts: the channel never reports that action running
    actions = {n.uid: n.name for n in walk(session.learning.tree) if isinstance(n, Action)}
    started = [actions[uid] for _, uid, _, status in first.changes[first.runs[-1]:]
               if uid in actions and status is BtStatus.RUNNING]
    assert len(dict.fromkeys(started)) == 2
    # the session channel: the journal's own events, frozen dataclasses, in the journal's order
    assert journal.events == session.journal.events
    assert {type(e).__name__ for e in journal.events} >= {"Situated", "DemoLearned"}
    with pytest.raises(dataclasses.FrozenInstanceError):
        journal.events[0].kind = "x"
