"""Every run of a session is a .btlog file: one per run, numbered, the tree that ran, and the
status changes BehaviorTree.CPP's own FileLogger writes when it ticks that tree through the
same leaf answers (in the symbolic and in the MuJoCo world)."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import BALL_DOMAIN
from test_btlog import BtcppRun, ScriptedWorld

from teach.bt.btcpp_status import BtStatus, Change
from teach.bt.btlog import btcpp_xml, read_btlog
from teach.bt.nodes import Action, Condition, Node, Status, walk
from teach.bt.tick import TickResult
from teach.bt.xml import tree_from_xml
from teach.cli import main
from teach.domain import load_domain
from teach.observe.btlog_writer import SYMBOLIC_TICK_US, BtlogRecorder, next_run_path, run_logs
from teach.observe.hook import Observer, Observers
from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.world.protocol import TeachingWorld
from teach.world.symbolic import SymbolicWorld

WHOLE_TASK = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"
START_US = 1_767_225_600_000_000


class Run:
    """One run as the session reported it: the tree, each tick with its simulated time, the end."""

    def __init__(self, tree: Node):
        self.tree = tree
        self.ticks: list[tuple[float | None, TickResult]] = []
        self.outcome = ""
        self.actions = -1

    def started_ticks(self) -> list[tuple[float | None, TickResult]]:
        """The ticks a .btlog keeps: all but a last tick that started an action the session dropped
        (a run stopped by 'run N' as its next action started)."""
        starts, last = 0, None
        for _, result in self.ticks:
            starts += result.action is not None and result.action != last
            last = result.action
        final = self.ticks[-1][1] if self.ticks else None
        before = self.ticks[-2][1].action if len(self.ticks) > 1 else None
        if (self.outcome == "interrupted" and final is not None and final.action is not None
                and final.action != before and starts > self.actions):
            return self.ticks[:-1]
        return self.ticks


class RunCollector(Observer):
    def __init__(self) -> None:
        self.runs: list[Run] = []
        self.sim_time: float | None = None

    def set_time(self, step: int | None, sim_time: float | None = None) -> None:
        if sim_time is not None:
            self.sim_time = sim_time

    def on_run_start(self, tree: Node) -> None:
        self.runs.append(Run(tree))

    def on_tick(self, tree: Node, result: TickResult) -> None:
        assert self.runs and tree is self.runs[-1].tree
        self.runs[-1].ticks.append((self.sim_time, result))

    def on_run_end(self, outcome: str, actions: int) -> None:
        self.runs[-1].outcome, self.runs[-1].actions = outcome, actions


def _session(tmp_path: Path, world: WorldKind) -> tuple[SessionManager, RunCollector, BtlogRecorder]:
    domain = load_domain(BALL_DOMAIN)
    collector = RunCollector()
    recorder = BtlogRecorder(tmp_path / "runs", wall_clock=lambda: START_US)
    observer = Observers(recorder, collector)
    settings = Settings("t", world=world, seed=3, base=tmp_path, record=False)
    world_: TeachingWorld = SymbolicWorld(domain, 3, observer)
    if world is WorldKind.MUJOCO:
        from teach.world.mujoco_world import MujocoWorld

        world_ = MujocoWorld(domain, 3, observer, cameras=False)  # nothing here records camera images
    return SessionManager(settings, domain, world_, observer), collector, recorder


def _teach_and_run(session: SessionManager) -> None:
    for line in (WHOLE_TASK, "done", "reset 11", "run", "reset 12", "run 2"):
        session.handle(line)
    session.close()


def _script(run: Run) -> list[tuple[dict[str, bool], dict[str, Status]]]:
    """What each leaf answered in each tick of the run (leaves our tick did not reach: as log_tick has it)."""
    leaves = [n for n in walk(run.tree) if isinstance(n, (Condition, Action))]
    script = []
    for _, result in run.started_ticks():
        visited = dict(result.trace)
        conditions = {n.name: False for n in leaves if isinstance(n, Condition)}
        actions = {n.name: Status.RUNNING for n in leaves if isinstance(n, Action)}
        for leaf in leaves:
            if leaf.uid in visited and isinstance(leaf, Condition):
                conditions[leaf.name] = visited[leaf.uid] is Status.SUCCESS
            elif leaf.uid in visited:
                actions[leaf.name] = visited[leaf.uid]
        script.append((conditions, actions))
    return script


def _tick_times(run: Run, world: WorldKind) -> list[int]:
    ticks = run.started_ticks()
    if world is WorldKind.SYMBOLIC:
        return [number * SYMBOLIC_TICK_US for number in range(len(ticks))]
    first = ticks[0][0]
    assert first is not None
    return [round(((t or 0.0) - first) * 1e6) for t, _ in ticks]


def _bt_cpps_changes(run: Run, ours: list[tuple[int, Change]], folder: Path) -> list[Change]:
    """BehaviorTree.CPP ticking the run's tree through the run's leaf answers, then halting it.
    Its records are compared all together, so only the halt waits for them (all of ours): after
    a finished run, BehaviorTree.CPP writes the root's reset at the halt, not in the last tick."""
    world = ScriptedWorld()
    theirs = BtcppRun(run.tree, folder / "theirs.btlog", world)
    for conditions, actions in _script(run):
        world.conditions, world.actions = conditions, actions
        theirs.tick(None)
    theirs.halt(len(ours))
    return [change for tick in theirs.close() for change in tick]


@pytest.mark.parametrize("world", [WorldKind.SYMBOLIC, WorldKind.MUJOCO])
def test_each_run_is_a_btlog_bt_cpp_writes_the_same(tmp_path: Path, world: WorldKind) -> None:
    session, collector, recorder = _session(tmp_path, world)
    _teach_and_run(session)
    logs = run_logs(tmp_path / "runs")
    assert [p.name for p in logs] == ["run-001.btlog", "run-002.btlog"] == [p.name for p in recorder.written]
    assert [r.outcome for r in collector.runs] == ["success", "interrupted"]
    for run, path in zip(collector.runs, logs, strict=True):
        log = read_btlog(path)
        # the tree that ran: the learner's tree of the newest generation (gen-NN.xml holds it pruned)
        assert log.xml == btcpp_xml(run.tree) and tree_from_xml(log.xml) == run.tree == session.learning.tree
        assert log.start_us == START_US
        times = _tick_times(run, world)
        ours = [(t.time_us, Change(t.uid, t.status)) for t in log.transitions]
        assert {t for t, _ in ours} <= set(times)
        assert [c for _, c in ours] == _bt_cpps_changes(run, ours, tmp_path)
        # every run ends with the whole tree IDLE: a finished root is reset, a stopped run halted
        final = {uid: BtStatus.IDLE for uid in log.names}
        for _, change in ours:
            final[change.uid] = change.status
        assert set(final.values()) == {BtStatus.IDLE}
    # 'run 2' logs the two actions it did and not the third its last tick started as it was stopped
    stopped = collector.runs[1]
    assert len(stopped.started_ticks()) == len(stopped.ticks) - 1
    started = [log.names[t.uid] for t in read_btlog(logs[1]).transitions if t.status is BtStatus.RUNNING
               and log.names[t.uid] in session.domain.action_names]
    ticked = list(dict.fromkeys(r.action for _, r in stopped.ticks if r.action))
    assert len(ticked) == 3 and list(dict.fromkeys(started)) == ticked[:2]


def test_run_numbers_are_never_given_twice(tmp_path: Path) -> None:
    folder = tmp_path / "runs"
    assert next_run_path(folder).name == "run-001.btlog"
    folder.mkdir()
    for name in ("run-002.btlog", "run-010.btlog", "run-x.btlog", "notes.txt"):
        (folder / name).write_bytes(b"")
    assert next_run_path(folder).name == "run-011.btlog"
    assert [p.name for p in run_logs(folder)] == ["run-002.btlog", "run-010.btlog"]


def test_a_replayed_session_writes_its_runs_beside_the_recording(tmp_path: Path,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    """The composition root attaches the writer: recordings/<session>/run-NNN.btlog; a fresh
    replay of the same session starts its numbers afresh; `teach review` lists them."""
    dialogue = tmp_path / "two.dialogue"
    dialogue.write_text("@world symbolic\n" + "\n".join([WHOLE_TASK, "done", "reset 4", "run", "reset 5", "run"])
                        + "\nquit\n")
    for _ in range(2):
        assert main(["replay", str(dialogue), "--base", str(tmp_path)]) == 0
        assert [p.name for p in run_logs(tmp_path / "recordings" / "two")] == ["run-001.btlog", "run-002.btlog"]
        # the tree each run ran, beside the generations, as the .btlog holds it
        for number in ("001", "002"):
            ran = tree_from_xml((tmp_path / "trees" / "two" / f"run-{number}.xml").read_text())
            assert ran == tree_from_xml(read_btlog(tmp_path / "recordings" / "two" / f"run-{number}.btlog").xml)
    capsys.readouterr()
    assert main(["review", str(tmp_path / "recordings" / "two.rrd")]) == 0
    out = capsys.readouterr().out
    assert "run-001.btlog" in out and "run-002.btlog" in out
