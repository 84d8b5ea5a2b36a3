"""A slip during a skill is the world's event (issue 11), in real MuJoCo: the ball knocked out
of the gripper and grasped again sits badly, and falls out as the robot lifts it to carry it.

The skill is halted there; the step is split into the robot's own part (dropped here: it had
not changed anything yet) and an external action (-1), which the teacher sees, the recording
holds, and a corrective demonstration after a run keeps."""

from __future__ import annotations

import pytest

from teach.bt.nodes import Action, Condition, Fallback, Sequence
from teach.demos import read_demo_set
from teach.observe.reader import read_recording
from teach.replay import replay
from teach.session.settings import Settings, WorldKind
from teach.session.setup import opened_session
from teach.sim.executor import run_tree
from teach.sim.perturb import PERTURBATIONS
from teach.sim.recorder import record
from teach.sim.skills import run_skill
from teach.sim.slip import SLIP, keeps_hold
from teach.sim.world import World

FETCH = {"en": "find the ball, go to the ball, grasp the ball", "de": "Ball finden, zum Ball gehen, Ball greifen"}
KNOCK = {"en": "knock the ball away", "de": "den Ball wegstoßen"}
CARRY = {"en": "go to the bin, put the ball in the bin", "de": "zum Eimer gehen, Ball in den Eimer legen"}
REST = {"en": "grasp the ball, go to the bin, put the ball in the bin",
        "de": "Ball greifen, zum Eimer gehen, Ball in den Eimer legen"}
SEEN = {"en": ["✗ go to the bin (stopped before it changed anything: not recorded)",
               "Event: the ball fell out of the gripper.", "I stopped there. Not done: put the ball in the bin."],
        "de": ["✗ zum Eimer gehen (angehalten, bevor sich etwas geändert hat: nicht aufgezeichnet)",
               "Ereignis: der Ball ist aus dem Greifer gefallen.",
               "Ich habe dort aufgehört. Nicht gemacht: Ball in den Eimer legen."]}
# fetch, knock (-1), fetch again, the slip (-1) where the carry began, grasp again, carry, place, goal
DEMONSTRATION = [
    "0;0;0;0;0;1", "1;0;0;0;0;2", "1;1;0;0;0;3", "1;1;1;0;0;-1",
    "0;0;0;0;0;1", "1;0;0;0;0;2", "1;1;0;0;0;3", "1;1;1;0;0;-1",
    "1;1;0;0;0;3", "1;1;1;0;0;4", "1;1;1;1;0;5", "1;1;0;1;1;0",
]


def settings(tmp_path, lang: str, name: str = "slip") -> Settings:
    return Settings(name, lang=lang, questions=0, seed=5, world=WorldKind.MUJOCO, base=tmp_path)


def test_only_actions_whose_model_leaves_the_hold_alone_must_keep_it() -> None:
    domain = World(0).domain
    assert [keeps_hold(domain, name) for name in domain.action_names] == [True, True, False, True, False]


def test_a_slip_in_a_run_halts_the_carry_and_is_an_external_line() -> None:
    world = World(seed=5)
    for action in ("FindBall", "ApproachBall", "GraspBall"):
        run_skill(world, action)
    PERTURBATIONS["knock_ball"].apply(world, world.rng)
    for action in ("FindBall", "ApproachBall", "GraspBall"):
        run_skill(world, action)
    fetch = Fallback((Condition("BallGrasped"), Action("GraspBall")))
    tree = Fallback((Condition("BallPlaced"), Sequence((fetch, Fallback((Condition("BinClose"), Action("ApproachBin"))),
                                                        Action("PlaceBall")))))
    trace = run_tree(world, tree)
    [slip] = trace.externals
    assert (slip.name, slip.halted, slip.halted_changed) == (SLIP, "ApproachBin", False)
    assert not slip.after[world.domain.index("BallGrasped")]
    demo = trace.as_demonstration(world.domain)
    assert [step.action for step in demo.steps] == [-1, 3, 4, 5, 0]  # the carry it halted did nothing
    assert replay(tree, world.domain, [demo]).reproduced == 1


def test_a_recorded_carry_that_slips_is_an_external_line() -> None:
    script = ["FindBall", "ApproachBall", "GraspBall", "knock_ball", "FindBall", "ApproachBall", "GraspBall",
              "ApproachBin", "GraspBall", "ApproachBin", "PlaceBall"]
    demo = record(World(seed=5), script)
    assert [";".join([*("01"[v] for v in step.state), str(step.action)]) for step in demo.steps] == DEMONSTRATION


@pytest.mark.parametrize("lang", ["en", "de"])
def test_a_slip_while_carrying_is_an_event_line_in_the_demonstration(tmp_path, lang) -> None:
    with opened_session(settings(tmp_path, lang)) as manager:
        manager.handle(FETCH[lang])
        manager.handle(KNOCK[lang])
        shown = [reply.text for reply in manager.handle(f"{FETCH[lang]}, {CARRY[lang]}")]
        assert shown[3:6] == SEEN[lang]
        manager.handle(REST[lang])
        manager.handle("done" if lang == "en" else "fertig")
    _, [demo] = read_demo_set(tmp_path / "demos" / "slip")
    assert demo.path is not None and demo.path.read_text().split() == DEMONSTRATION
    externals = [name for _, name in read_recording(tmp_path / "recordings" / "slip.rrd").externals]
    assert externals == ["knock_ball", SLIP]


def test_a_slip_in_a_run_is_kept_in_the_corrective_demonstration(tmp_path) -> None:
    with opened_session(settings(tmp_path, "en")) as manager:
        manager.handle(f"{FETCH['en']}, {CARRY['en']}")
        manager.handle("done")  # a first tree: fetch the ball, carry it, put it in
        manager.handle("reset 5")
        manager.handle(FETCH["en"])
        manager.handle(KNOCK["en"])
        manager.handle(FETCH["en"])
        manager.handle("cancel")  # the world stays as it is: the ball badly in the gripper
        shown = [reply.text for reply in manager.handle("run 2")]
        assert shown[:3] == ["→ go to the bin", "Event: the ball fell out of the gripper.", "→ grasp the ball"]
        assert manager.open is not None
        steps = [(step.action, "".join("01"[v] for v in step.state)) for step in manager.open.steps]
        assert steps == [(-1, "11100"), (3, "11000")]  # the carry it halted had changed nothing yet
        manager.handle(CARRY["en"])
        manager.handle("done")
    _, demos = read_demo_set(tmp_path / "demos" / "slip")
    assert [step.action for step in demos[-1].steps] == [-1, 3, 4, 5, 0]
