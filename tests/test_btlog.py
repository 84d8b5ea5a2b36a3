""".btlog files: our writer against BehaviorTree.CPP's own FileLogger2, through behaviortreepy.

BehaviorTree.CPP loads our XML of a tree, its leaves read the same scripted world as our
model's, and its ``FileLogger`` logs the run; the status changes it writes must be the ones
``BtlogWriter`` writes, tick by tick, and the file headers must be the same bytes.
"""

from __future__ import annotations

import itertools
import os
import tempfile
import time
from collections.abc import Iterable, Iterator
from pathlib import Path

import behaviortreepy as btcpp
import pytest
from conftest import BALL_DOMAIN, ROOT
from hypothesis import given, settings
from hypothesis import strategies as st
from strategies import trees

from teach.bt.btcpp_status import BtcppTree, BtStatus, Change, TickChanges
from teach.bt.btlog import MAGIC, BtlogWriter, btcpp_xml, read_btlog
from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, Status, walk
from teach.bt.tick import TickResult, tick
from teach.bt.xml import read_tree, tree_from_xml, tree_to_xml
from teach.domain import load_domain
from teach.errors import FormatError, TeachError
from teach.observe.hook import Observer
from teach.sim.executor import run_tree
from teach.sim.world import World

C, A = Condition, Action
CONDITIONS = ["Near", "Holding", "Seen", "Done"]
ACTIONS = ["Look", "Move", "Grip"]
TO_BTCPP = {Status.SUCCESS: btcpp.NodeStatus.SUCCESS, Status.FAILURE: btcpp.NodeStatus.FAILURE,
            Status.RUNNING: btcpp.NodeStatus.RUNNING}
FROM_BTCPP = {value: key for key, value in TO_BTCPP.items()}

Tick = tuple[dict[str, bool], dict[str, Status]]
"""One tick of a scripted world: which conditions hold, what each action returns if ticked."""
Logged = tuple[Status | None, list[Change]]
"""What one side logged for one tick: the root's status and the status changes."""


class ScriptedWorld:
    """Leaves for both trees: conditions and actions answer from the current tick's script;
    every action call and halt is recorded, so both sides can be compared call for call."""

    def __init__(self) -> None:
        self.conditions: dict[str, bool] = {}
        self.actions: dict[str, Status] = {}
        self.calls: list[str] = []

    def holds(self, name: str) -> bool:
        return self.conditions[name]

    def act(self, name: str) -> Status:
        self.calls.append(name)
        return self.actions[name]

    def halted(self, name: str) -> None:
        self.calls.append(f"halt {name}")


class BtcppRun:
    """BehaviorTree.CPP ticking our XML of ``tree``, logged by its FileLogger to ``path``.

    The tree is loaded from ``xml`` (our tree file's text by default) by a factory that knows
    only the tree's leaves, as ``btcpp_xml`` assumes. FileLogger2 writes from a thread of its
    own (every 10 ms or when notified), so after each tick we wait until it has written as
    many records as expected; the records counted then are that tick's, and any surplus
    shows up in the next tick's or in the final count."""

    def __init__(self, tree: Node, path: Path, world: ScriptedWorld, xml: str | None = None):
        self.world = world
        self.path = path
        factory = btcpp.BehaviorTreeFactory()
        nodes = list(walk(tree))
        for name in sorted({n.name for n in nodes if isinstance(n, Condition)}):
            factory.register_simple_condition(name, self._condition(name))
        for name in sorted({n.name for n in nodes if isinstance(n, Action)}):
            factory.register_simple_stateful_action(name, self._action(name), self._action(name), self._halt(name))
        self.tree = factory.create_tree_from_text(tree_to_xml(tree) if xml is None else xml)
        self.logger: btcpp.FileLogger | None = btcpp.FileLogger(self.tree, str(path))
        self.header = len(MAGIC) + 5 + len(btcpp_xml(tree).encode()) + 8  # its own is asserted equal
        self.counts: list[int] = [0]

    def _condition(self, name: str):  # type: ignore[no-untyped-def]
        def check(_node: btcpp.TreeNode) -> btcpp.NodeStatus:
            return btcpp.NodeStatus.SUCCESS if self.world.holds(name) else btcpp.NodeStatus.FAILURE
        return check

    def _action(self, name: str):  # type: ignore[no-untyped-def]
        def act(_node: btcpp.TreeNode) -> btcpp.NodeStatus:
            return TO_BTCPP[self.world.act(name)]
        return act

    def _halt(self, name: str):  # type: ignore[no-untyped-def]
        def halt(_node: btcpp.TreeNode) -> None:
            self.world.halted(name)
        return halt

    def _size(self) -> int:
        return os.stat(self.path).st_size

    def _records(self) -> int:
        return (self._size() - self.header) // 9

    def wait_for(self, records: int) -> None:
        """Until FileLogger2's thread has written ``records`` records (or clearly never will)."""
        give_up = time.monotonic() + 10.0
        while self._records() < records and time.monotonic() < give_up:
            time.sleep(0.0005)
        self.counts.append(self._records())

    def tick(self, expected_records: int | None) -> Status:
        """One tick; then wait for its records (None: do not wait, the ticks' records are only
        counted together, once the tree is halted)."""
        status = FROM_BTCPP[self.tree.tick_exactly_once()]
        if expected_records is not None:
            self.wait_for(expected_records)
        return status

    def halt(self, expected_records: int) -> None:
        self.tree.halt_tree()
        self.wait_for(expected_records)

    def close(self) -> list[list[Change]]:
        """Stop the logger and split its records into ticks by the counts seen after each."""
        time.sleep(0.03)  # a surplus record would be written by now
        # BehaviorTree.CPP 4.8.2's logger drops what is still queued when it is destroyed
        # (a whole run's records if its thread has not run yet); nothing is queued by now
        self.logger = None
        changes = read_btlog(self.path).changes()
        self.counts[-1] = len(changes)
        return [changes[a:b] for a, b in itertools.pairwise(self.counts)]


def run_both(tree: Node, script: Iterable[Tick], folder: Path, halt_at_end: bool = False,
             ) -> tuple[list[Logged], list[Logged], list[str], list[str]]:
    """Tick ``tree`` through ``script`` with our writer and with BehaviorTree.CPP; per tick the root
    status and the status changes each logged (status None for the final halt), then each
    side's action calls and halts."""
    ours_world, their_world = ScriptedWorld(), ScriptedWorld()
    clock = iter(range(1_700_000_000_000_000, 1 << 62, 1000))
    writer = BtlogWriter(folder / "ours.btlog", tree, clock=lambda: next(clock))
    theirs = BtcppRun(tree, folder / "theirs.btlog", their_world)
    ours: list[Logged] = []
    statuses: list[Status | None] = []
    total = 0
    for conditions, actions in script:
        for world in (ours_world, their_world):
            world.conditions, world.actions = conditions, actions
        result = writer.tick(ours_world.holds, ours_world.act, ours_world.halted)
        ours.append((result.status, list(result.changes)))
        total += len(result.changes)
        statuses.append(theirs.tick(total))
    if halt_at_end:
        changes = writer.halt(ours_world.halted)
        ours.append((None, list(changes)))
        total += len(changes)
        theirs.halt(total)
        statuses.append(None)
    writer.close()
    their_changes = theirs.close()
    assert read_btlog(folder / "ours.btlog").changes() == [c for _, tick in ours for c in tick]
    assert read_btlog(folder / "theirs.btlog").xml == btcpp_xml(tree)
    return ours, list(zip(statuses, their_changes, strict=True)), ours_world.calls, their_world.calls


def assert_same_run(tree: Node, script: list[Tick], halt_at_end: bool = False) -> list[Logged]:
    with tempfile.TemporaryDirectory() as folder:
        ours, theirs, our_calls, their_calls = run_both(tree, script, Path(folder), halt_at_end)
    assert len(ours) == len(theirs)
    for number, (mine, bt) in enumerate(zip(ours, theirs, strict=True)):
        assert mine == bt, f"tick {number}: teach logs {mine}, BehaviorTree.CPP {bt} for\n{tree_to_xml(tree)}"
    assert our_calls == their_calls
    return ours


@st.composite
def scripts(draw: st.DrawFn, conditions: list[str], actions: list[str], max_ticks: int = 8) -> list[Tick]:
    """A few ticks: conditions that flip now and then, actions that run for 0-3 ticks and then
    succeed or fail (their next call after that starts a new run)."""
    ticks = draw(st.integers(1, max_ticks))
    state = draw(st.fixed_dictionaries({c: st.booleans() for c in conditions}))
    timelines: dict[str, list[Status]] = {}
    for name in actions:
        line: list[Status] = []
        while len(line) < ticks:
            line += [Status.RUNNING] * draw(st.integers(0, 3))
            line.append(draw(st.sampled_from([Status.SUCCESS, Status.FAILURE])))
        timelines[name] = line[:ticks]
    script = []
    for number in range(ticks):
        if number:
            flips = draw(st.sets(st.sampled_from(conditions), max_size=2))
            state = {c: v != (c in flips) for c, v in state.items()}
        script.append((dict(state), {name: line[number] for name, line in timelines.items()}))
    return script


# --- against BehaviorTree.CPP -------------------------------------------------------------------

@settings(max_examples=60, deadline=None)
@given(trees(CONDITIONS, ACTIONS, max_leaves=12), st.data())
def test_random_trees_log_what_bt_cpp_logs(tree: Node, data: st.DataObject) -> None:
    script = data.draw(scripts(CONDITIONS, ACTIONS))
    assert_same_run(tree, script, halt_at_end=data.draw(st.booleans()))


def test_the_ball_tasks_learned_tree_logs_a_whole_run_as_bt_cpp_does() -> None:
    """Table 6.1's tree in a world where each action runs two ticks, then succeeds and makes
    its effects true (the domain's ramifications); the run ends with the ball in the bin."""
    domain = load_domain(BALL_DOMAIN)
    tree = read_tree(ROOT / "demos" / "ball" / "reference" / "table61.xml")
    world = ScriptedWorld()
    world.conditions = dict.fromkeys(domain.condition_names, False)
    progress = dict.fromkeys(domain.action_names, 0)
    live = BtcppTree(tree)
    script: list[Tick] = []
    for _ in range(40):
        # each action returns RUNNING twice, then SUCCESS, and its effects hold from the next tick
        world.actions = {name: Status.SUCCESS if progress[name] == 2 else Status.RUNNING
                         for name in domain.action_names}
        script.append((dict(world.conditions), world.actions))
        world.calls.clear()
        result = live.tick(world.holds, world.act)
        for name in world.calls:
            progress[name] = 0 if world.actions[name] is Status.SUCCESS else progress[name] + 1
            if world.actions[name] is Status.SUCCESS:
                world.conditions.update({lit.name: lit.value for lit in domain.action(name).ram})
        if result.status is Status.SUCCESS:
            break
    ours = assert_same_run(tree, script)
    assert ours[-1][0] is Status.SUCCESS and world.conditions["BallPlaced"]
    # five actions of three ticks each, where each success lets the next action start at once
    assert len(ours) == 1 + 5 * 2


def test_a_running_parallel_remembers_finished_children() -> None:
    """BehaviorTree.CPP's Parallel does not tick a finished child again while it runs: Near
    turned false in tick 2, yet the Parallel keeps running (Table 2.2 would say FAILURE)."""
    tree = Parallel((C("Near"), A("Move")), 2)
    ours = assert_same_run(tree, [({"Near": True}, {"Move": Status.RUNNING}),
                                  ({"Near": False}, {"Move": Status.RUNNING})])
    # expectation: tick 2 ticks nobody but Move, which keeps RUNNING, so nothing changes
    assert ours[1] == (Status.RUNNING, [])


def test_an_inverter_resets_its_child_before_it_reports() -> None:
    """The order Groot2 shows: parent RUNNING, child's result, child IDLE, parent's result."""
    tree = Fallback((Inverter(C("Near")), A("Move")))
    ours = assert_same_run(tree, [({"Near": False}, {"Move": Status.RUNNING})])
    running, idle, success, failure = BtStatus.RUNNING, BtStatus.IDLE, BtStatus.SUCCESS, BtStatus.FAILURE
    assert ours[0] == (Status.SUCCESS, [Change(1, running), Change(2, running), Change(3, failure),
                                        Change(3, idle), Change(2, success), Change(2, idle),
                                        Change(1, success), Change(1, idle)])


def test_a_reactive_sequence_halts_the_running_action_when_a_guard_fails() -> None:
    tree = Sequence((C("Near"), A("Grip")))
    script = [({"Near": True}, {"Grip": Status.RUNNING}), ({"Near": False}, {"Grip": Status.RUNNING})]
    ours = assert_same_run(tree, script)
    # expectation: in tick 1 Grip's RUNNING already reset Near to IDLE (a guard of the running
    # action is not shown green); in tick 2 Near fails and the sequence halts Grip
    assert ours[0][1][-1] == Change(2, BtStatus.IDLE)
    assert ours[1] == (Status.FAILURE, [Change(2, BtStatus.FAILURE), Change(2, BtStatus.IDLE),
                                        Change(3, BtStatus.IDLE), Change(1, BtStatus.FAILURE),
                                        Change(1, BtStatus.IDLE)])


# --- logging the ticks our own tick ran ---------------------------------------------------------

def _has_parallel(tree: Node) -> bool:
    return any(isinstance(n, Parallel) for n in walk(tree))


@settings(max_examples=80, deadline=None)
@given(trees(CONDITIONS, ACTIONS, max_leaves=12).filter(lambda t: not _has_parallel(t)), st.data())
def test_logging_our_ticks_gives_bt_cpps_changes_without_ticking_twice(tree: Node, data: st.DataObject) -> None:
    """Without a Parallel, BehaviorTree.CPP reaches exactly the leaves our tick reached, so the
    log made from our tick's trace is the one BehaviorTree.CPP's run would give."""
    script = data.draw(scripts(CONDITIONS, ACTIONS))
    direct = BtcppTree(tree)
    with tempfile.TemporaryDirectory() as folder:
        writer = BtlogWriter(Path(folder) / "run.btlog", tree, clock=lambda: 0)
        for conditions, actions in script:
            ours = tick(tree, conditions, actions.__getitem__)
            logged = writer.log_tick(ours)
            assert logged == direct.tick(conditions, actions.__getitem__)
            assert logged.status is ours.status


def test_a_remembering_parallel_makes_the_log_differ_from_our_tick() -> None:
    """Table 2.2 fails the Parallel once Near is false; BehaviorTree.CPP still remembers Near's
    SUCCESS and keeps running, and the log says so."""
    tree = Fallback((Parallel((C("Near"), A("Move")), 2), A("Look")))
    with tempfile.TemporaryDirectory() as folder:
        writer = BtlogWriter(Path(folder) / "run.btlog", tree, clock=lambda: 0)
        first = tick(tree, {"Near": True})
        assert writer.log_tick(first).status is first.status is Status.RUNNING
        second = tick(tree, {"Near": False})
        assert second.action == "Look" and writer.log_tick(second) == TickChanges(Status.RUNNING, ())


class BtlogObserver(Observer):
    """What a session would do: log each tick the executor reports."""

    def __init__(self, writer: BtlogWriter):
        self.writer = writer
        self.statuses: list[Status] = []

    def on_tick(self, tree: Node, result: TickResult) -> None:
        self.statuses.append(self.writer.log_tick(result).status)


def test_a_mujoco_run_logged_from_the_executors_ticks(tmp_path: Path) -> None:
    """The ball task in MuJoCo, logged on simulated time: the log shows the run's actions
    starting in the order the executor started them, and the tree finishing."""
    world = World(seed=5)
    world.reset(seed=5)
    tree = read_tree(ROOT / "demos" / "ball" / "reference" / "table61.xml")
    session_start_us = 1_767_225_600_000_000  # the session's own start, so files are reproducible
    writer = BtlogWriter(tmp_path / "run-01.btlog", tree, clock=lambda: session_start_us + round(world.sim_time * 1e6))
    observer = BtlogObserver(writer)
    with writer:
        trace = run_tree(world, tree, observer)
    assert trace.outcome == "success" and observer.statuses == trace.statuses
    log = read_btlog(tmp_path / "run-01.btlog")
    started = [log.names[t.uid] for t in log.transitions
               if t.status == BtStatus.RUNNING and log.names[t.uid] in load_domain(BALL_DOMAIN).action_names]
    assert started == [a for a, fresh in zip(trace.actions, trace.started, strict=True) if fresh and a]
    assert log.changes()[-2:] == [Change(1, BtStatus.SUCCESS), Change(1, BtStatus.IDLE)]
    # the last tick's changes carry its simulated time, counted from when the log was opened
    assert log.start_us + log.transitions[-1].time_us == session_start_us + round(trace.times[-1] * 1e6)


# --- the file -----------------------------------------------------------------------------------

def _run(path: Path, tree: Node) -> bytes:
    clock = iter(range(5_000_000, 1 << 62, 250))
    with BtlogWriter(path, tree, clock=lambda: next(clock)) as writer:
        writer.tick({"Near": False, "Seen": True}, lambda _name: Status.RUNNING)
        writer.tick({"Near": True, "Seen": True}, lambda _name: Status.SUCCESS)
    return path.read_bytes()


SMALL = Sequence((Fallback((C("Near"), A("Move"))), Inverter(C("Seen")), A("Grip")))


def test_the_same_run_gives_the_same_bytes_with_timestamps_from_the_clock(tmp_path: Path) -> None:
    first, second = _run(tmp_path / "a.btlog", SMALL), _run(tmp_path / "b.btlog", SMALL)
    assert first == second
    log = read_btlog(tmp_path / "a.btlog")
    assert log.start_us == 5_000_000
    # the first tick's changes carry the clock's second reading, the second tick's its third
    assert sorted({t.time_us for t in log.transitions}) == [250, 500]
    assert log.names == {1: "ReactiveSequence", 2: "ReactiveFallback", 3: "Near", 4: "Move",
                         5: "Inverter", 6: "Seen", 7: "Grip"}


def test_our_header_loads_in_bt_cpp_with_the_same_uids(tmp_path: Path) -> None:
    """BehaviorTree.CPP loads the XML of our log; logging that tree, it writes our header again."""
    BtlogWriter(tmp_path / "ours.btlog", SMALL).close()
    header = read_btlog(tmp_path / "ours.btlog").xml
    BtcppRun(SMALL, tmp_path / "reloaded.btlog", ScriptedWorld(), xml=header).close()
    assert read_btlog(tmp_path / "reloaded.btlog").xml == header


def test_the_reader_reads_bt_cpps_own_files(tmp_path: Path) -> None:
    world = ScriptedWorld()
    world.conditions, world.actions = {"Near": False, "Seen": False}, {"Move": Status.RUNNING, "Grip": Status.RUNNING}
    run = BtcppRun(SMALL, tmp_path / "theirs.btlog", world)
    expected = BtcppTree(SMALL).tick(world.conditions).changes
    run.tick(len(expected))
    run.close()
    log = read_btlog(tmp_path / "theirs.btlog")
    assert log.changes() == list(expected) and log.names[4] == "Move"
    assert abs(log.start_us - time.time_ns() // 1000) < 3600 * 10**6  # µs since the epoch


def test_a_logs_xml_reads_back_as_the_tree(tmp_path: Path) -> None:
    tree = read_tree(ROOT / "demos" / "ball" / "reference" / "table61.xml")
    BtlogWriter(tmp_path / "run.btlog", tree).close()
    assert tree_from_xml(read_btlog(tmp_path / "run.btlog").xml) == tree


def test_a_clock_going_back_is_refused(tmp_path: Path) -> None:
    readings = iter([1000, 999])
    writer = BtlogWriter(tmp_path / "run.btlog", SMALL, clock=lambda: next(readings))
    with pytest.raises(ValueError, match="-1 µs"):
        writer.tick({"Near": True, "Seen": False})


def test_trees_too_large_for_two_byte_uids_are_refused() -> None:
    btcpp_xml(Sequence(tuple(C("Near") for _ in range(65534))))
    with pytest.raises(FormatError, match="65536 nodes; a .btlog numbers at most 65535"):
        btcpp_xml(Sequence(tuple(C("Near") for _ in range(65535))))


def test_names_bt_cpp_reserves_are_refused() -> None:
    with pytest.raises(FormatError, match="AsyncSequence.*BehaviorTree.CPP"):
        btcpp_xml(Sequence((C("Near"), A("AsyncSequence"))))
    with pytest.raises(FormatError, match="Parallel"):
        btcpp_xml(Fallback((C("Parallel"), A("Move"))))


def test_a_log_must_be_named_btlog(tmp_path: Path) -> None:
    with pytest.raises(TeachError, match=r"\.btlog"):
        BtlogWriter(tmp_path / "run.log", SMALL)


def _damaged(good: bytes) -> Iterator[tuple[str, bytes, str]]:
    size = int.from_bytes(good[19:23], "little")
    body = 23 + size + 8
    yield "empty", b"", "does not start with BTCPP4-FileLogger2"
    yield "other file", b"<root/>", "does not start with BTCPP4-FileLogger2"
    yield "protocol", MAGIC + b"\x02" + good[19:], "protocol 2 is not supported"
    yield "cut in header", good[:21], "ends inside its header"
    yield "cut in xml", good[:100], "ends inside its header"
    yield "negative size", good[:19] + (-5).to_bytes(4, "little", signed=True) + good[23:], "XML -5 bytes"
    yield "cut in record", good[:-4], "ends inside a record: 5 bytes"
    yield "bad status", good[:-1] + b"\x09", "status 9 is not a BehaviorTree.CPP status"
    yield "bad uid", good[:body + 6] + b"\x63\x00" + good[body + 8:], "node uid 99 is not in the log's tree"
    broken = good[23:23 + size].replace(b"</root>", b"</roox>")
    yield "bad xml", good[:23] + broken + good[23 + size:], "not well-formed"
    not_utf8 = good[23:23 + size].replace(b"MainTree", b"Main\xfftre")
    yield "not utf-8", good[:23] + not_utf8 + good[23 + size:], "not UTF-8"
    entity = good[23:23 + size].replace(b"<root", b"<!ENTITY x 'y'><root", 1)
    yield ("entity", good[:19] + len(entity).to_bytes(4, "little") + entity + good[23 + size:],
           "DOCTYPE or ENTITY")


def test_damaged_files_give_one_line(tmp_path: Path) -> None:
    good = _run(tmp_path / "good.btlog", SMALL)
    path = tmp_path / "bad.btlog"
    for case, data, message in _damaged(good):
        path.write_bytes(data)
        with pytest.raises(FormatError, match=message) as caught:
            read_btlog(path)
        text = str(caught.value)
        assert text.startswith(f"{path}: ") and "\n" not in text, case


def test_missing_files_and_folders_give_one_line(tmp_path: Path) -> None:
    with pytest.raises(FormatError, match="cannot read .btlog file: No such file"):
        read_btlog(tmp_path / "none.btlog")
    with pytest.raises(FormatError, match="is a folder"):
        read_btlog(tmp_path)
