"""`--groot`: trees run through BehaviorTree.CPP itself with a Groot2Publisher, leaves ticking our
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
    """A port whose successor is free too (Groot2Publisher binds both)."""
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
    # the publisher is gone with the session: the port is free again
    with socket.socket() as probe:
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
