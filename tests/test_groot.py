"""`--groot`: trees run through BehaviorTree.CPP itself, served to Groot2 on a port, leaves ticking our
world. A run gives the same outcome and steps as our own tick, and the publisher's port takes
connections while the run goes on."""

from __future__ import annotations

import socket
from pathlib import Path

import pytest
from conftest import BALL_DOMAIN, ROOT

from teach.bt.groot import GrootTicker
from teach.bt.nodes import Node
from teach.bt.tick import TickResult
from teach.cli import main
from teach.domain import load_domain
from teach.observe.hook import Observer, Observers
from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.session.setup import HaltBetweenRuns
from teach.world.symbolic import SymbolicWorld

WHOLE_TASK = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"
LINES = (WHOLE_TASK, "done", "reset 11", "run", "reset 12", "run 2", WHOLE_TASK, "done", "reset 7", "run")


def free_port() -> int:
    """A port whose successor is free too (a Groot2 server binds both)."""
    for _ in range(50):
        with socket.socket() as probe:
            probe.bind(("", 0))
            port = int(probe.getsockname()[1])
        try:
            with socket.socket() as second:
                second.bind(("", port + 1))
        except OSError:
            continue
        return port
    raise AssertionError("no two free ports side by side")


class PortWatcher(Observer):
    """Connects to the publisher's port at every tick: it must be open throughout each run."""

    def __init__(self, port: int):
        self.port = port
        self.ticks = 0
        self.refused = 0
        self.results: list[TickResult] = []

    def on_tick(self, tree: Node, result: TickResult) -> None:
        self.ticks += 1
        self.results.append(result)
        try:
            socket.create_connection(("127.0.0.1", self.port), timeout=2).close()
        except OSError:
            self.refused += 1


def _transcript(tmp_path: Path, groot: int | None) -> tuple[list[str], PortWatcher | None]:
    domain = load_domain(BALL_DOMAIN)
    watcher = PortWatcher(groot) if groot is not None else None
    observer = Observers(*([watcher] if watcher is not None else []))
    world = SymbolicWorld(domain, 3, observer)
    if groot is not None:
        ticker = GrootTicker(groot)
        world.ticker = ticker
        observer.observers.insert(0, HaltBetweenRuns(ticker))
    session = SessionManager(Settings("t", world=WorldKind.SYMBOLIC, seed=3, base=tmp_path, record=False), domain,
                             world, observer)
    replies = [f"{r.kind}: {r.text}" for line in LINES for r in session.handle(line)]
    session.close()
    return [r.replace(str(tmp_path), "BASE") for r in replies], watcher


def test_a_session_through_bt_cpp_runs_as_through_our_tick(tmp_path: Path) -> None:
    ours, _ = _transcript(tmp_path / "ours", None)
    port = free_port()
    theirs, watcher = _transcript(tmp_path / "theirs", port)
    assert theirs == ours
    assert any("Done! The task is finished." in r for r in ours) and any("Stopped." in r for r in ours)
    assert watcher is not None and watcher.ticks >= 8 and watcher.refused == 0
    # the publisher is gone with the session: the port is free again (SO_REUSEADDR: a closed
    # connection's TIME_WAIT on it does not count, a listener still would; the bind failed without
    # it once in a full parallel run)
    with socket.socket() as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        probe.bind(("", port))


def test_a_mujoco_replay_with_groot_prints_and_writes_what_one_without_does(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    dialogue = ROOT / "dialogues" / "quickstart.dialogue"
    outputs = []
    # unpaced both (--groot alone paces runs to wall time, which the next test checks)
    for name, extra in (("a", ["--pace", "0"]), ("b", ["--groot", str(free_port()), "--pace", "0"])):
        base = tmp_path / name
        assert main(["replay", str(dialogue), "--base", str(base), "--no-record", *extra]) == 0
        outputs.append(capsys.readouterr().out.replace(str(base), "BASE"))
        trees = sorted((base / "trees" / "quickstart").glob("gen-*.xml"))
        outputs.append("\n".join(p.name + p.read_text() for p in trees))
    assert outputs[0] == outputs[2] and outputs[1] == outputs[3]
    assert "The task is finished" in outputs[0]


def test_a_taken_port_is_one_line_before_the_session_starts(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    port = free_port()
    with socket.socket() as taken:
        taken.bind(("", port))
        taken.listen()
        dialogue = tmp_path / "d.dialogue"
        dialogue.write_text("@world symbolic\nhelp\n")
        assert main(["replay", str(dialogue), "--base", str(tmp_path), "--no-record", "--groot", str(port)]) == 2
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and f"--groot cannot publish on port {port}: port {port} is taken" in \
        captured.err
    assert not (tmp_path / "demos").exists()


def test_a_port_out_of_range_is_refused() -> None:
    from teach.errors import TeachError

    with pytest.raises(TeachError, match="not a port number"):
        GrootTicker(70000)


def test_replay_with_groot_is_paced_so_a_run_can_be_watched(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    """`replay --groot` holds simulated time to --pace times wall time (1 unless given): the
    MuJoCo quickstart, paced at 5, takes at least its simulated time over 5 (a lower bound,
    whatever the machine's load)."""
    import time

    from teach.observe.reader import read_recording

    started = time.monotonic()
    assert main(["replay", str(ROOT / "dialogues" / "quickstart.dialogue"), "--base", str(tmp_path),
                 "--groot", str(free_port()), "--pace", "5"]) == 0
    took = time.monotonic() - started
    simulated = max(s.sim_time for s in read_recording(tmp_path / "recordings" / "quickstart.rrd").states
                    if s.sim_time is not None)
    assert simulated > 40.0 and took >= simulated / 5  # unpaced it takes about 3 s
    capsys.readouterr()
    assert main(["replay", str(ROOT / "dialogues" / "quickstart.dialogue"), "--base", str(tmp_path),
                 "--pace", "-1"]) == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_groot_is_a_ticker_not_an_observer() -> None:
    assert not issubclass(GrootTicker, Observer)


# --- what Groot2 is served: a tree id of each tree's own --------------------------------------

class Groot2Client:
    """Asks as Groot2 does: a ZeroMQ REQ socket, a 6-byte header per request (protocol 2)."""

    def __init__(self, port: int):
        from teach.bt.zeromq import REQ, Context

        self.context = Context()
        self.socket = self.context.socket(REQ, timeout_ms=5000)
        self.socket.connect(f"tcp://127.0.0.1:{port}")
        self.requests = 0

    def ask(self, kind: bytes, *parts: bytes) -> tuple[bytes, list[bytes]]:
        """The reply's tree id and its parts after the header (the header checked)."""
        import struct

        self.requests += 1
        self.socket.send([struct.pack("<BBI", 2, kind[0], 1000 + self.requests), *parts])
        reply = self.socket.receive()
        assert reply is not None
        if reply[0] == b"error":
            return b"", reply
        assert len(reply[0]) == 22 and reply[0][:6] == struct.pack("<BBI", 2, kind[0], 1000 + self.requests)
        return reply[0][6:], reply[1:]

    def statuses(self) -> dict[int, int]:
        import struct

        _, (buffer,) = self.ask(b"S")
        return {uid: status for uid, status in struct.iter_unpack("<HB", buffer)}

    def close(self) -> None:
        self.socket.close()
        self.context.close()


def _two_trees() -> tuple[Node, Node]:
    from teach.bt.nodes import Action, Condition, Fallback, Sequence

    first = Fallback((Condition("BallPlaced"), Sequence((Condition("BallFound"), Action("ApproachBall")))))
    second = Fallback((Condition("BallFound"), Action("FindBall")))
    return first, second


def test_every_tree_is_served_under_an_id_of_its_own_changed_when_the_tree_is_swapped() -> None:
    from teach.bt.btlog import btcpp_xml

    first, second = _two_trees()
    port, other_port = free_port(), free_port()
    ticker, other = GrootTicker(port), GrootTicker(other_port)
    client, other_client = Groot2Client(port), Groot2Client(other_port)
    try:
        ticker(first, {"BallPlaced": False, "BallFound": True})
        first_id, (xml,) = client.ask(b"T")
        assert xml.decode() == btcpp_xml(first) and client.ask(b"S")[0] == first_id  # one id per tree
        other(first, {"BallPlaced": False, "BallFound": True})
        assert other_client.ask(b"T")[0] not in (first_id, b"")  # the same tree in another publisher
        ticker(second, {"BallFound": False})
        second_id, (xml,) = client.ask(b"T")
        assert xml.decode() == btcpp_xml(second) and second_id not in (first_id, b"")
        ticker(first, {"BallPlaced": False, "BallFound": True})
        assert client.ask(b"T")[0] not in (first_id, second_id)  # swapped back: a new id again
    finally:
        for closing in (client, other_client, ticker, other):
            closing.close()


def _bt_cpp_publisher(root: Node, states: list[dict[str, bool]], port: int) -> object:
    """BehaviorTree.CPP's own ``Groot2Publisher`` on ``root``, its actions RUNNING, its conditions
    read from ``states[0]`` (the caller changes it between ticks); keep the result alive."""
    import behaviortreepy as bt

    from teach.bt.nodes import Action, Condition, walk
    from teach.bt.xml import tree_to_xml

    factory = bt.BehaviorTreeFactory()
    for name in {n.name for n in walk(root) if isinstance(n, Condition)}:
        factory.register_simple_condition(name, lambda _node, name=name: bt.NodeStatus.SUCCESS
                                          if states[0][name] else bt.NodeStatus.FAILURE)
    for name in {n.name for n in walk(root) if isinstance(n, Action)}:
        factory.register_simple_stateful_action(name, lambda _node: bt.NodeStatus.RUNNING,
                                                lambda _node: bt.NodeStatus.RUNNING, lambda _node: None)
    tree = factory.create_tree_from_text(tree_to_xml(root))
    return tree, bt.Groot2Publisher(tree, port)


def test_groot2_is_served_what_behaviortree_cpps_own_publisher_serves_but_the_tree_id() -> None:
    """Tree XML and every status, tick after tick and after a halt, as BehaviorTree.CPP's
    Groot2Publisher serves them for the same leaf answers."""
    first, _ = _two_trees()
    ours, theirs = free_port(), free_port()
    states = [{"BallPlaced": False, "BallFound": True}]
    ticker, client = GrootTicker(ours), Groot2Client(ours)
    (tree, publisher), reference = _bt_cpp_publisher(first, states, theirs), Groot2Client(theirs)
    try:
        for step in ("tick", "halt", "found", "placed", "halt"):
            if step == "halt":
                ticker.halt()
                tree.halt_tree()  # type: ignore[attr-defined]
            else:
                states[0] = {"BallPlaced": step == "placed", "BallFound": step != "found"}
                ticker(first, states[0])
                tree.tick_exactly_once()  # type: ignore[attr-defined]
            assert client.statuses() == reference.statuses(), step
        assert client.ask(b"T")[1] == reference.ask(b"T")[1]
        running = {1: 1, 2: 13, 3: 1, 4: 12, 5: 1}  # uids in pre-order; 10 + status: IDLE, and from what
        states[0] = {"BallPlaced": False, "BallFound": True}
        ticker(first, states[0])
        assert client.statuses() == running
    finally:
        for closing in (client, reference, ticker):
            closing.close()
        del publisher


def test_groot2s_other_requests_are_answered_as_the_publisher_answers_them() -> None:
    first, _ = _two_trees()
    port = free_port()
    ticker, client = GrootTicker(port), Groot2Client(port)
    try:
        ticker(first, {"BallPlaced": False, "BallFound": True})
        assert client.ask(b"B", b"[]")[1] == [b"\x80"] and client.ask(b"D")[1] == [b"[]"]
        assert client.ask(b"I", b"{}")[1][0] == b"error" and client.ask(b"?")[1][0] == b"error"
        client.ask(b"r", b"start")
        ticker(first, {"BallPlaced": True, "BallFound": True})
        _, (transitions,) = client.ask(b"t")
        records = [(int.from_bytes(transitions[i + 6:i + 8], "little"), transitions[i + 8])
                   for i in range(0, len(transitions), 9)]
        # uid, BT::NodeStatus: the ball is in the bin, so the running Sequence and its action are halted
        assert records == [(2, 2), (2, 0), (5, 0), (3, 0), (1, 2), (1, 0)]
    finally:
        client.close()
        ticker.close()
    for each in (port, port + 1):  # both ports are free once the ticker is closed (TIME_WAIT aside)
        with socket.socket() as probe:
            probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            probe.bind(("", each))
