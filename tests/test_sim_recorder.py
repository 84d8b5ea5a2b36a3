"""Recording demonstrations in the simulation, and the `teach record` command."""

from __future__ import annotations

from pathlib import Path

import pytest

from teach.cli import main
from teach.demos import read_demo_set
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION
from teach.errors import DomainError
from teach.observe.hook import Observer
from teach.sim.perturb import PERTURBATIONS
from teach.sim.recorder import Recorder, record, save_demonstration
from teach.sim.world import World


class Events(Observer):
    def __init__(self) -> None:
        self.kinds: list[str] = []
        self.times: list[float] = []

    def set_time(self, step: int, sim_time: float | None = None) -> None:
        self.times.append(float(sim_time or 0.0))

    def on_scene(self, shapes) -> None:  # type: ignore[no-untyped-def]
        self.kinds.append("scene")

    def on_external(self, name: str) -> None:
        self.kinds.append(f"external:{name}")


def test_five_actions_make_a_goal_demonstration(tmp_path: Path) -> None:
    world = World(seed=1)
    world.arrange({}, seed=1)
    events = Events()
    demo = record(world, ["FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall"], events)
    ids = [world.domain.action(n).id for n in ("FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall")]
    assert list(demo.actions) == ids and demo.reached_goal
    # every transition's states were read from physics: each action's ramification shows after it
    for transition in demo.transitions():
        action = world.domain.action(transition.action)
        assert all(world.domain.holds(lit, transition.after) for lit in action.ram)
    # scene frames come at a rate of simulated time, in order
    assert events.kinds.count("scene") > 10 and events.times == sorted(events.times)
    path = save_demonstration(demo, tmp_path / "sim", world.domain)
    domain, demos = read_demo_set(tmp_path / "sim")
    assert [d.steps for d in demos] == [tuple(s.__class__(s.state, s.action, i + 1) for i, s in enumerate(demo.steps))]
    assert path.name == "demo-001.csv" and domain.condition_names == world.domain.condition_names


def test_perturbation_is_an_external_line() -> None:
    world = World(seed=2)
    world.arrange({"BallFound": True, "BallGrasped": True}, seed=2)
    recorder = Recorder(world)
    step = recorder.perturb("knock_ball")
    assert step.action == EXTERNAL_ACTION and step.before[world.domain.index("BallGrasped")]
    assert not step.after[world.domain.index("BallGrasped")]
    with pytest.raises(DomainError, match="perturbation"):
        recorder.done()
    recorder.step("find the ball")  # phrases work too
    demo = recorder.done()
    assert demo.steps[0].action == EXTERNAL_ACTION and demo.steps[-1].action != GOAL_ACTION


@pytest.mark.parametrize("name", sorted(PERTURBATIONS))
def test_perturbations_have_phrases_and_change_the_world(name: str) -> None:
    world = World(seed=4)
    world.arrange({"BallFound": True, "BallGrasped": True, "BinClose": True}, seed=4)
    before = world.data.qpos.copy()
    PERTURBATIONS[name].apply(world, world.rng)
    assert PERTURBATIONS[name].en and PERTURBATIONS[name].de
    assert abs(world.data.qpos - before).max() > 0.05


def test_record_command_writes_the_set(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["record", "--set", "s", "--root", str(tmp_path), "--start", "BallFound,BallClose",
                 "--seed", "3", "GraspBall", "ApproachBin", "PlaceBall"])
    out = capsys.readouterr().out
    assert code == 0 and out.strip().splitlines()[-1].endswith(";0")
    assert (tmp_path / "s" / "demo-001.csv").read_text() == out
    assert (tmp_path / "s" / "domain.toml").is_file()


def test_record_command_rejects_unknown_steps(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["record", "--set", "s", "--root", str(tmp_path), "FindBall", "Dance"]) == 2
    err = capsys.readouterr().err
    assert "unknown action 'Dance'" in err and "Traceback" not in err
    assert not (tmp_path / "s").exists()
