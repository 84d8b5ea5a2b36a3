"""Running trees in the simulation, and the issue's end-to-end check with Approach 3."""

from __future__ import annotations

import itertools

import pytest

from teach.bt.nodes import Action, Condition, Fallback, Sequence
from teach.demos import Demonstration
from teach.learn.specialize import specialize
from teach.observe.hook import Observer
from teach.replay import replay
from teach.sim.executor import run_tree
from teach.sim.recorder import Recorder
from teach.sim.world import World

PERTURB = ["knock_ball", "take_ball", "move_bin", "push_robot"]


def teacher(conditions: dict[str, bool]) -> str:
    """What a teacher shows in each state (as in Δ2)."""
    if not conditions["BallGrasped"]:
        if not conditions["BallFound"]:
            return "FindBall"
        return "GraspBall" if conditions["BallClose"] else "ApproachBall"
    return "PlaceBall" if conditions["BinClose"] else "ApproachBin"


def table_6_1_tree() -> Sequence:
    """A hand-written tree in the style of the thesis's Fig. 6.16."""
    def pair(condition: str, action: str) -> Fallback:
        return Fallback((Condition(condition), Action(action)))

    fetch = Fallback((Condition("BallGrasped"),
                      Sequence((pair("BallFound", "FindBall"), pair("BallClose", "ApproachBall"),
                                Action("GraspBall")))))
    return Fallback((Condition("BallPlaced"), Sequence((fetch, pair("BinClose", "ApproachBin"), Action("PlaceBall")))))


class Ticks(Observer):
    def __init__(self) -> None:
        self.ticks = 0
        self.externals: list[str] = []

    def on_tick(self, tree, result) -> None:  # type: ignore[no-untyped-def]
        self.ticks += 1

    def on_external(self, name: str) -> None:
        self.externals.append(name)


def test_tree_runs_to_success_and_becomes_a_demonstration() -> None:
    world = World(seed=5)
    world.reset(seed=5)
    observer = Ticks()
    trace = run_tree(world, table_6_1_tree(), observer, perturbations={20: "push_robot"})
    assert trace.outcome == "success" and world.conditions()["BallPlaced"]
    assert observer.ticks == trace.ticks and observer.externals == ["push_robot"]
    # ticks come at a fixed rate of simulated time (the push itself takes the teacher's time)
    gaps = {round(b - a, 3) for i, (a, b) in enumerate(zip(trace.times, trace.times[1:], strict=False)) if i + 1 != 20}
    assert gaps == {0.1}
    demo = trace.as_demonstration(world.domain)
    assert demo.reached_goal and -1 in [s.action for s in demo.steps]
    assert replay(table_6_1_tree(), world.domain, [demo]).reproduced == 1


def test_interrupted_run_continued_by_the_teacher_is_a_corrective_demonstration() -> None:
    world = World(seed=6)
    world.reset(seed=6)
    ticks = itertools.count()
    trace = run_tree(world, table_6_1_tree(), interrupt=lambda: next(ticks) >= 15)
    assert trace.outcome == "interrupted" and trace.ticks == 15
    recorder = Recorder(world, prefix=trace.as_demonstration(world.domain))
    while not world.conditions()["BallPlaced"]:
        recorder.step(teacher(world.conditions()))
    demo = recorder.done()
    assert demo.reached_goal and demo.steps[0].state == trace.states[0]


def test_step_limit_ends_a_run_as_timeout() -> None:
    world = World(seed=7)
    world.arrange({}, seed=7)
    trace = run_tree(world, Action("FindBall"), max_ticks=3)
    assert trace.outcome == "timeout" and trace.ticks == 3


def test_demonstrations_from_all_16_start_states_teach_approach_3() -> None:
    world = World(seed=0)
    demos: list[Demonstration] = []
    for number, bits in enumerate(itertools.product((False, True), repeat=4)):
        world.arrange((*bits, False), seed=number)
        recorder = Recorder(world)
        while not world.conditions()["BallPlaced"] and len(recorder.steps) < 10:
            recorder.step(teacher(world.conditions()))
        demos.append(recorder.done(f"start-{number:02d}"))
    assert all(d.reached_goal for d in demos)
    tree = specialize(world.domain, demos).tree
    placed = 0
    for run in range(20):
        world.reset(seed=1000 + run)
        perturbations = {25: PERTURB[run // 2 % 4]} if run % 2 else None
        trace = run_tree(world, tree, perturbations=perturbations)
        placed += trace.outcome == "success" and world.conditions()["BallPlaced"]
    assert placed >= 19


@pytest.mark.parametrize("name", ["Dance"])
def test_unknown_actions_are_domain_errors(name: str) -> None:
    from teach.errors import DomainError

    world = World(seed=0)
    with pytest.raises(DomainError, match="no skill"):
        run_tree(world, Action(name))
