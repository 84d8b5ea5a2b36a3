"""The rerun logger writes real ``.rrd`` files that read back with every event, in order."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from conftest import colledanchise_tree

from teach.bt.nodes import Action, Condition, Fallback, Sequence, size
from teach.bt.tick import tick_state
from teach.bt.xml import tree_to_xml
from teach.demos import parse_demonstration
from teach.domain import Domain
from teach.errors import FormatError, TeachError
from teach.observe.layout import default_recording_path
from teach.observe.reader import read_recording
from teach.observe.rerun_writer import RerunLogger
from teach.observe.scene import SceneShape

RERUN = Path(sys.executable).with_name("rerun")

DEMO_1 = "0;0;0;0;0;1\n1;0;0;0;0;2\n1;1;0;0;0;3\n1;1;1;0;0;-1\n1;1;0;0;0;3\n1;1;1;0;0;4\n1;1;1;1;0;5\n1;1;1;1;1;0\n"
DEMO_2 = "1;0;0;0;0;2\n1;1;0;0;0;3\n1;1;1;0;0;4\n1;1;1;1;0;5\n1;1;1;1;1;0\n"


def _shapes(t: float) -> list[SceneShape]:
    return [SceneShape("floor", "box", (2.0, 2.0, 0.01), (0.0, 0.0, -0.01), (1.0, 0.0, 0.0, 0.0), (0.8, 0.8, 0.8, 1.0)),
            SceneShape("ball", "sphere", (0.04,), (0.5 + t, 0.2, 0.04), (1.0, 0.0, 0.0, 0.0), (1.0, 0.2, 0.2, 1.0)),
            SceneShape("arm", "capsule", (0.03, 0.2), (0.0, 0.0, 0.5), (0.7071, 0.7071, 0.0, 0.0),
                       (0.3, 0.3, 0.9, 1.0)),
            SceneShape("bin", "cylinder", (0.15, 0.1), (-0.5, 0.3, 0.1), (1.0, 0.0, 0.0, 0.0), (0.2, 0.6, 0.2, 1.0))]


def record_session(path: Path, ball: Domain) -> dict:
    """Drive a logger through a small session; return what was fed in, for the assertions."""
    first = Sequence((Fallback((Condition("BallFound"), Action("FindBall"))), Action("ApproachBall")))
    final = colledanchise_tree()
    demo_1 = parse_demonstration(DEMO_1, ball, "demo-001.csv", "demo-001")
    demo_2 = parse_demonstration(DEMO_2, ball, "demo-002.csv", "demo-002")
    names = ball.condition_names
    logger = RerunLogger(path, "test-session")
    step = 0

    def at(sim_time: float | None = None) -> None:
        nonlocal step
        step += 1
        logger.set_time(step, sim_time)

    logger.set_time(0)
    logger.on_domain(ball)
    logger.on_tree(0, first, tree_to_xml(first), "start")
    at()
    logger.on_dialogue("teacher", "find the ball")
    logger.on_dialogue("robot", "I find the ball.", budget_left=5)
    ticks = []
    for i, line in enumerate(demo_1.steps):
        at(0.1 * i)
        logger.on_scene(_shapes(0.1 * i))
        logger.on_camera(np.full((24, 32, 3), 10 * i, dtype=np.uint8), "overview")
        logger.on_camera(np.full((24, 32, 3), 10 * i, dtype=np.uint8))  # the robot's own, beside it
        if line.action == -1:
            logger.on_external("BallDropped")
        result = tick_state(first, names, line.state)
        ticks.append((result.status.name, result.action))
        logger.on_tick(first, result)
        logger.on_state(dict(zip(names, line.state, strict=True)), result.action)
    logger.on_demonstration("demo-001", demo_1, ball)
    at()
    logger.on_learner("specialize", "1 demonstration", removed=["(BinClose)"])
    logger.on_tree(1, final, tree_to_xml(final), "demonstration demo-001")
    logger.on_question("Must the ball be in your hand before you go to the bin?", 4)
    at()
    logger.on_answer("Must the ball be in your hand before you go to the bin?", "yes", "kept (BallGrasped)")
    logger.on_learner("prune", "2 nodes", removed=["(BallFound)", "FindBall"])
    logger.on_replay(1, 1)
    at(5.0)
    logger.on_demonstration("demo-002", demo_2, ball)
    logger.on_question("Do you need to see the ball to grasp it?", 3)
    logger.on_answer("Do you need to see the ball to grasp it?", "no", "")
    logger.on_tree(2, final, tree_to_xml(final), "answer")
    result = tick_state(final, names, ball.state(["BallFound"]))
    ticks.append((result.status.name, result.action))
    logger.on_tick(final, result)
    logger.on_replay(2, 2, lenient=True)
    logger.close()
    return {"ticks": ticks, "demos": [demo_1, demo_2], "sizes": [size(first), size(final), size(final)],
            "xml": tree_to_xml(final)}


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict]:
    from conftest import BALL_DOMAIN

    from teach.domain import load_domain

    path = tmp_path_factory.mktemp("rec") / "session.rrd"
    return path, record_session(path, load_domain(BALL_DOMAIN))


def test_file_is_complete_and_verifies(recorded: tuple[Path, dict]) -> None:
    path, _ = recorded
    # the logger renamed its .part file into place and rerun's own verifier accepts it
    assert path.is_file() and not path.with_name(path.name + ".part").exists()
    done = subprocess.run([str(RERUN), "rrd", "verify", str(path)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_tree_comes_first(recorded: tuple[Path, dict]) -> None:
    contents = read_recording(recorded[0])
    # after the static domain, the first things logged are the tree (a note that there is none yet, then
    # the first generation's graph and XML), before any dialogue, state or scene
    assert contents.first_entities[:4] == ("/tree/xml", "/tree/generation", "/tree/xml", "/learner/generations")
    assert contents.session == "test-session" and contents.has_blueprint
    assert contents.domain_name == "ball-in-bin"
    assert contents.conditions[0] == "BallFound" and "PlaceBall" in contents.actions
    assert contents.goal == ("BallPlaced",)


def test_demonstrations_in_order_with_states(recorded: tuple[Path, dict], ball: Domain) -> None:
    contents = read_recording(recorded[0])
    demos = recorded[1]["demos"]
    assert [d.name for d in contents.demonstrations] == ["demo-001", "demo-002"]
    for record, demo in zip(contents.demonstrations, demos, strict=False):
        assert record.states == tuple(s.state for s in demo.steps)
        assert record.reached_goal
    # external actions and the goal line are marked as such
    assert contents.demonstrations[0].actions == ("FindBall", "ApproachBall", "GraspBall", "external", "GraspBall",
                                                  "ApproachBin", "PlaceBall", "goal")
    assert contents.demonstrations[1].csv == DEMO_2


def test_questions_with_answers_in_order(recorded: tuple[Path, dict]) -> None:
    contents = read_recording(recorded[0])
    assert [(q.question, q.budget_left, q.answer, q.change) for q in contents.questions] == [
        ("Must the ball be in your hand before you go to the bin?", 4, "yes", "kept (BallGrasped)"),
        ("Do you need to see the ball to grasp it?", 3, "no", ""),
    ]
    kinds = [(d.kind, d.speaker) for d in contents.dialogue]
    assert kinds == [("line", "teacher"), ("line", "robot"), ("question", "robot"), ("answer", "teacher"),
                     ("question", "robot"), ("answer", "teacher")]
    assert contents.dialogue[1].budget_left == 5 and contents.dialogue[0].budget_left is None


def test_generations_learner_events_and_replays(recorded: tuple[Path, dict]) -> None:
    contents = read_recording(recorded[0])
    fed = recorded[1]
    assert [(g.generation, g.nodes) for g in contents.generations] == list(zip([0, 1, 2], fed["sizes"], strict=True))
    assert [g.reason for g in contents.generations] == ["start", "demonstration demo-001", "answer"]
    assert contents.final_tree_xml == fed["xml"]
    assert [(e.event, e.removed) for e in contents.learner_events] == [
        ("specialize", ("(BinClose)",)), ("prune", ("(BallFound)", "FindBall"))]
    assert [(r.reproduced, r.total, r.lenient) for r in contents.replays] == [(1, 1, False), (2, 2, True)]


def test_ticks_states_and_externals(recorded: tuple[Path, dict]) -> None:
    contents = read_recording(recorded[0])
    fed = recorded[1]
    assert [(t.status, t.action) for t in contents.ticks] == fed["ticks"]
    # the first tick in state 00000: (BallFound) fails, FindBall runs, the Fallback and Sequence run
    assert contents.ticks[0].trace == (("(BallFound)", "FAILURE"), ("FindBall", "RUNNING"), ("?", "RUNNING"),
                                       ("→", "RUNNING"))
    assert [t.generation for t in contents.ticks] == [0] * 8 + [2]
    assert [t.sim_time for t in contents.ticks[:3]] == pytest.approx([0.0, 0.1, 0.2])
    assert len(contents.states) == 8 and contents.states[1].state["BallFound"] is True
    assert contents.states[0].action == "FindBall"
    assert contents.externals == [(5, "BallDropped")]


def test_scene_is_throttled_to_frame_rate(recorded: tuple[Path, dict]) -> None:
    contents = read_recording(recorded[0])
    # scene offered every 0.1 s of sim time for 8 steps, logged at 10 Hz: all 8; camera at 2 Hz: t=0, 0.5
    assert contents.scene_frames == 8
    assert contents.camera_frames == 2


def test_truncated_recording_is_one_line_error(recorded: tuple[Path, dict], tmp_path: Path) -> None:
    data = recorded[0].read_bytes()
    for cut in (len(data) // 2, len(data) - 7, 100):
        broken = tmp_path / f"cut{cut}.rrd"
        broken.write_bytes(data[:cut])
        with pytest.raises(FormatError) as caught:
            read_recording(broken)
        assert str(caught.value).startswith(str(broken)) and "\n" not in str(caught.value)


def test_garbage_and_missing_files_are_errors(tmp_path: Path) -> None:
    garbage = tmp_path / "garbage.rrd"
    garbage.write_bytes(b"this is not a recording\n" * 10)
    with pytest.raises(FormatError, match="garbage.rrd"):
        read_recording(garbage)
    with pytest.raises(FormatError, match="no such recording"):
        read_recording(tmp_path / "missing.rrd")


def test_default_path() -> None:
    assert default_recording_path("ball 2026/11") == Path("recordings/ball_2026_11.rrd")


def test_unknown_shape_kind_is_refused(tmp_path: Path) -> None:
    logger = RerunLogger(tmp_path / "s.rrd", "shapes")
    try:
        logger.set_time(0, 0.0)
        with pytest.raises(ValueError, match="unknown kind"):
            logger.on_scene([SceneShape("x", "torus", (1.0,), (0, 0, 0), (1, 0, 0, 0), (1, 1, 1, 1))])
    finally:
        logger.close()


def test_batches_keep_every_tick_in_order_around_events(tmp_path: Path, ball: Domain) -> None:
    # ticks are batched (3 rows per rerun call here) but events between them flush the batch first,
    # so reading back gives every tick, and every event, in the order they were reported
    path = tmp_path / "batched.rrd"
    tree = colledanchise_tree()
    names = ball.condition_names
    states = [ball.state(names[:k]) for k in range(len(names) + 1)]
    with RerunLogger(path, "batched", batch_rows=3) as logger:
        logger.on_domain(ball)
        logger.on_tree(0, tree, tree_to_xml(tree), "start")
        for step in range(40):
            logger.set_time(step, step * 0.1)
            logger.on_tick(tree, tick_state(tree, names, states[step % len(states)]))
            if step % 7 == 0:
                logger.on_dialogue("robot", f"line {step}")
    contents = read_recording(path)
    expected = [tick_state(tree, names, states[s % len(states)]).action for s in range(40)]
    assert [t.action for t in contents.ticks] == expected
    assert [t.step for t in contents.ticks] == list(range(40))
    assert [d.text for d in contents.dialogue] == [f"line {s}" for s in range(0, 40, 7)]
    assert [d.step for d in contents.dialogue] == list(range(0, 40, 7))


def test_simulation_can_advance_sim_time_alone(tmp_path: Path, ball: Domain) -> None:
    # the session owns the step; a simulation may move only sim_time (step None keeps the session's step)
    path = tmp_path / "clock.rrd"
    tree = colledanchise_tree()
    with RerunLogger(path, "clock") as logger:
        logger.set_time(7)
        for frame in range(3):
            logger.set_time(None, 0.1 * frame)
            logger.on_tick(tree, tick_state(tree, ball.condition_names, ball.state()))
    assert [(t.step, t.sim_time) for t in read_recording(path).ticks] == [(7, 0.0), (7, 0.1), (7, 0.2)]


def test_state_is_logged_when_it_changes(tmp_path: Path, ball: Domain) -> None:
    path = tmp_path / "state.rrd"
    names = ball.condition_names
    with RerunLogger(path, "state") as logger:
        for step, (true, action) in enumerate([([], "FindBall")] * 5 + [(["BallFound"], "FindBall")] * 3
                                              + [(["BallFound"], "ApproachBall")] * 4):
            logger.set_time(step, step * 0.1)
            logger.on_state(dict(zip(names, ball.state(true), strict=True)), action)
    contents = read_recording(path)
    # twelve reports, three distinct (state, action) pairs: the viewer holds each until the next
    assert [(s.step, s.action, s.state["BallFound"]) for s in contents.states] == [
        (0, "FindBall", False), (5, "FindBall", True), (8, "ApproachBall", True)]


def test_scene_geometry_changes_and_vanishing_kinds(tmp_path: Path) -> None:
    path = tmp_path / "scene.rrd"
    with RerunLogger(path, "scene", batch_rows=2) as logger:
        for frame in range(12):
            logger.set_time(frame, frame * 0.1)
            shapes = _shapes(frame * 0.1)
            if frame >= 6:  # the ball is gone (placed out of sight), the bin changes colour
                shapes = [s for s in shapes if s.kind != "sphere"]
                shapes[-1] = SceneShape("bin", "cylinder", (0.15, 0.1), (-0.5, 0.3, 0.1), (1.0, 0.0, 0.0, 0.0),
                                        (0.9, 0.1, 0.1, 1.0))
            logger.on_scene(shapes)
            logger.on_scene(shapes)  # a second report at the same sim time is dropped (10 Hz)
    assert read_recording(path).scene_frames == 12
    done = subprocess.run([str(RERUN), "rrd", "verify", str(path)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_capsule_is_placed_from_its_end() -> None:
    from teach.observe.encode import SceneLayout

    # a capsule centred at (0, 0, 0.5), half length 0.2, turned 90° about x: its axis points along -y,
    # and rerun draws it from the end at +y towards -y
    layout = SceneLayout.of((("arm", "capsule", (0.03, 0.2), (1.0, 1.0, 1.0, 1.0)),))
    pos, xyzw = layout.poses("capsule", np.array([[[0.0, 0.0, 0.5]]], dtype=np.float32),
                             np.array([[[0.70710678, 0.70710678, 0.0, 0.0]]], dtype=np.float32))
    assert pos[0, 0] == pytest.approx([0.0, 0.2, 0.5], abs=1e-6)
    assert xyzw[0, 0] == pytest.approx([0.70710678, 0.0, 0.0, 0.70710678])


def test_unwritable_recording_is_one_line_error(tmp_path: Path) -> None:
    (tmp_path / "taken").write_text("a file where the folder should be")
    with pytest.raises(TeachError, match="cannot write the recording"):
        RerunLogger(tmp_path / "taken" / "s.rrd", "s")
    (tmp_path / "busy.rrd.part").mkdir()
    with pytest.raises(TeachError, match="busy.rrd.part: cannot write the recording: Is a directory"):
        RerunLogger(tmp_path / "busy.rrd", "s")
