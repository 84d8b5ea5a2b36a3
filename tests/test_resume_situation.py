"""A resume puts the world where the session left it (issue 14): the situation a 'start' or a
'reset' made, the end of a demonstration or a run, and a run the session ended in, whose
finished steps become the correction. Sessions are "killed" by abandoning them (no quit, no
close) or by raising out of a run at the moment the teacher sees an action begin."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import BALL_DOMAIN, ROOT, journal_data

from teach import messages as m
from teach.domain import Domain, load_domain
from teach.session.machine import SessionManager
from teach.session.replies import Reply
from teach.session.settings import Settings, WorldKind
from teach.world.symbolic import SymbolicWorld

SEQUENCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"


class Killed(BaseException):
    """Raised where the process would have been killed: nothing after it runs."""


def settings(tmp_path: Path, world: WorldKind = WorldKind.SYMBOLIC, lang: str = "en") -> Settings:
    return Settings("s", lang=lang, questions=0, world=world, base=tmp_path, record=False, seed=3)


def make_world(ball: Domain, world: WorldKind):  # type: ignore[no-untyped-def]
    if world is WorldKind.MUJOCO:
        from teach.world.mujoco_world import MujocoWorld

        return MujocoWorld(ball, 3)
    return SymbolicWorld(ball)


def session(ball: Domain, tmp_path: Path, world: WorldKind = WorldKind.SYMBOLIC, lang: str = "en") -> SessionManager:
    return SessionManager(settings(tmp_path, world, lang), ball, make_world(ball, world))


def resumed(ball: Domain, tmp_path: Path, world: WorldKind = WorldKind.SYMBOLIC,
            lang: str = "en") -> tuple[SessionManager, list[str]]:
    manager = SessionManager.resume(settings(tmp_path, world, lang), ball, make_world(ball, world))
    return manager, [reply.text for reply in manager.greet()]


def kill_at_action(manager: SessionManager, number: int) -> None:
    """Make the session die as the teacher sees the ``number``-th action of a run begin."""
    seen: list[Reply] = []

    def live(reply: Reply) -> None:
        if reply.text.startswith("→"):
            seen.append(reply)
            if len(seen) == number:
                raise Killed

    manager.live = live


def test_a_start_without_steps_is_set_up_again(ball, tmp_path):
    first = session(ball, tmp_path)
    first.handle("start BallFound BinClose")  # then killed: no quit, no close
    again, said = resumed(ball, tmp_path)
    assert again.world.state() == ball.state(["BallFound", "BinClose"])
    assert m.SITUATION_RESTORED("en") in said
    assert said[-1] == again._state_reply().text  # the situation in words follows


def test_in_german_too(ball, tmp_path):
    session(ball, tmp_path, lang="de").handle("start BallFound")
    again, said = resumed(ball, tmp_path, lang="de")
    assert again.world.state() == ball.state(["BallFound"]) and m.SITUATION_RESTORED("de") in said


@pytest.mark.parametrize("last", ["done", "cancel", "undo"])
def test_the_world_stays_where_a_demonstration_left_it(ball, tmp_path, last):
    """After 'done', 'cancel' or undoing a learned demonstration the world is where the steps took
    it (none of them moves it back), and that is where the resumed world is."""
    first = session(ball, tmp_path)
    first.handle(SEQUENCE)
    first.handle("done")
    first.handle("start BallFound")
    if last != "undo":  # (an undo straight after 'cancel' would bring the discarded steps back)
        first.handle("go to the ball, grasp the ball")
    if last == "done":
        first.handle("go to the bin, put the ball in the bin")
    first.handle(last)  # 'undo' takes back the first demonstration: the world does not move
    where = first.world.state()
    assert where == ((True,) * 5 if last == "done" else ball.state(["BallFound"]) if last == "undo"
                     else ball.state(["BallFound", "BallClose", "BallGrasped"]))
    again, said = resumed(ball, tmp_path)
    assert again.world.state() == where and again.open is None
    assert m.SITUATION_RESTORED("en") in said


def test_a_finished_run_leaves_the_world_at_its_end(ball, tmp_path):
    first = session(ball, tmp_path)
    first.handle(f"model {BALL_DOMAIN}")
    first.handle("start BinClose")
    first.handle("run")
    journal = journal_data(tmp_path / "recordings" / "s.journal.json")
    assert journal["events"][-1] == {"kind": "situation", "state": "11111", "how": "run"}
    again, said = resumed(ball, tmp_path)
    assert again.world.state() == (True,) * 5 and again.open is None and m.SITUATION_RESTORED("en") in said


@pytest.mark.parametrize("world", [WorldKind.SYMBOLIC, WorldKind.MUJOCO])
def test_a_run_the_session_ended_in_becomes_the_correction(ball, tmp_path, world):
    """Killed as the third action begins: the two finished actions are the correction's first
    steps, the world is as before the third, and the teacher finishing it teaches the whole task."""
    first = session(ball, tmp_path, world)
    first.handle(f"model {BALL_DOMAIN}")
    first.handle("start BallFound")
    kill_at_action(first, 3)
    with pytest.raises(Killed):
        first.handle("run")
    journal = journal_data(tmp_path / "recordings" / "s.journal.json")
    assert journal["open_run"] == "ApproachBin" and [s[1] for s in journal["open_steps"]] == [2, 3]
    again, said = resumed(ball, tmp_path, world)
    assert again.open is not None and [s.action for s in again.open.steps] == [2, 3]
    assert again.open.words[0] == m.ROBOT_DID_STEP("en", action="go to the ball")
    assert again.world.state() == ball.state(["BallFound", "BallClose", "BallGrasped"])
    label = ball.action("ApproachBin").label("en")
    assert m.RUN_RESTORED("en", action=label, steps="2 steps") in said
    again.handle("go to the bin, put the ball in the bin")
    again.handle("done")
    assert [d.actions for d in again.demos] == [(2, 3, 4, 5)]


def test_a_run_killed_in_its_first_action_leaves_the_world_where_it_began(ball, tmp_path):
    first = session(ball, tmp_path)
    first.handle(f"model {BALL_DOMAIN}")
    first.handle("start BinClose")
    kill_at_action(first, 1)
    with pytest.raises(Killed):
        first.handle("run")
    again, said = resumed(ball, tmp_path)
    assert again.open is None and again.world.state() == ball.state(["BinClose"])
    assert m.RUN_RESTORED_NO_STEPS("en", action=ball.action("FindBall").label("en")) in said


def test_mujoco_reset_n_is_made_again_exactly_and_start_in_conditions_only(ball, tmp_path):
    first = session(ball, tmp_path, WorldKind.MUJOCO)
    first.handle("reset 11")
    poses = first.world.world.data.qpos.copy()  # type: ignore[attr-defined]
    again, said = resumed(ball, tmp_path, WorldKind.MUJOCO)
    assert (again.world.world.data.qpos == poses).all()  # type: ignore[attr-defined]
    assert m.SITUATION_RESTORED("en") in said
    again.handle("start BinClose")
    third, said = resumed(ball, tmp_path, WorldKind.MUJOCO)
    assert third.world.state() == ball.state(["BinClose"])
    assert m.SITUATION_RESTORED_ANEW("en") in said  # honest: the physical layout is a new one


@pytest.mark.parametrize(("change", "wrong"), [
    (lambda j: j["events"].append({"kind": "situation", "state": "00000", "how": "teleport"}), "events[0]: how"),
    (lambda j: j["events"].append({"kind": "situation", "state": "001", "how": "start"}), "events[0]: state"),
    (lambda j: j["events"].append({"kind": "situation", "state": "00000", "how": "reset", "seed": -1}),
     "events[0]: seed"),
    (lambda j: j.update(open_run="Teleport", open_state="01000"), "open_run"),
    (lambda j: j.update(open_run="FindBall", open_state="01"), "open_state"),
])
def test_a_damaged_situation_is_one_line(ball, tmp_path, change, wrong):  # type: ignore[no-untyped-def]
    session(ball, tmp_path).close()
    path = tmp_path / "recordings" / "s.journal.json"
    journal = journal_data(path)
    change(journal)
    path.write_text(json.dumps(journal))
    done = subprocess.run([sys.executable, "-m", "teach.cli", "session", "--resume", "s", "--no-record",
                           "--base", str(tmp_path)], input="quit\n", text=True, capture_output=True, timeout=120)
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "Traceback" not in done.stderr, done.stderr
    assert str(path) in done.stderr and wrong in done.stderr


def test_every_step_shown_while_a_line_runs_is_on_disk(ball, tmp_path):
    """A live driver shows each "✓" as its step ends; killed as the second is shown, both steps
    come back (before, they reached the journal only at the end of the line)."""
    first = session(ball, tmp_path)
    shown: list[str] = []

    def live(reply: Reply) -> None:
        if reply.text.startswith(m.DID_STEP("en", action="").split()[0]):
            shown.append(reply.text)
            if len(shown) == 2:
                raise Killed

    first.live = live
    with pytest.raises(Killed):
        first.handle(SEQUENCE)
    again, said = resumed(ball, tmp_path)
    assert again.open is not None and [s.action for s in again.open.steps] == [1, 2]
    assert m.OPEN_RESTORED("en", steps="2 steps") in said


def test_a_new_start_walked_from_a_set_up_situation_comes_back_exactly(tmp_path):
    """Blocksworld: 'reset 2' walks from the situation a 'start' set up, which a resumed world does
    not have yet; the situation is put back by its conditions, and in the symbolic world that is
    exact (it was told as "the simulation placed everything anew", MuJoCo's words)."""
    blocks = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    manager = session(blocks, tmp_path)
    manager.handle("start clear a, clear b, clear c, clear d, handempty, ontable a, ontable b, ontable c, ontable d")
    manager.handle("reset 2")
    left = manager.world.state()
    assert left != blocks.state()
    again, told = resumed(blocks, tmp_path)
    assert again.world.state() == left
    assert m.SITUATION_RESTORED.en in told and m.SITUATION_RESTORED_ANEW.en not in told
