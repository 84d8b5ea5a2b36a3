"""Guiding with feedback (issue 21, item 1): a line says where the ball and the bin are from the
robot's hand, the lift, the hand and what the last key did, in words a person can steer by; a
grasp guided from that line alone works, and its ✓ comes as soon as the world settles."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from conftest import BALL_DOMAIN

from teach.domain import load_domain
from teach.session.feedback import feedback_line
from teach.session.machine import SessionManager
from teach.session.settings import Settings
from teach.sim.guide import Feedback, GuideCommand


def feedback(**changed: object) -> Feedback:
    values: dict[str, object] = dict(ball_distance=0.34, ball_bearing=20.0, ball_height=-0.05, bin_distance=1.2,
                                     bin_bearing=-3.0, lift=0.26, hand_open=True, last=GuideCommand("forward", 0.1),
                                     moved=0.1, turned=0.0, lifted=0.0, gripped=0.0)
    values.update(changed)
    return Feedback(**values)  # type: ignore[arg-type]


def test_the_feedback_line_in_english_and_german():
    assert feedback_line(feedback(), "en") == ("ball 34 cm, 20° to my left, 5 cm below my hand · bin 1.2 m ahead · "
                                               "lift 26 cm · hand open · last: ↑ moved me 10 cm")
    assert feedback_line(feedback(), "de") == ("Ball 34 cm, 20° links von mir, 5 cm unter meiner Hand · Eimer 1,2 m "
                                               "geradeaus · Hub 26 cm · Hand offen · zuletzt: ↑ hat mich 10 cm bewegt")


@pytest.mark.parametrize(("changed", "last"), [
    (dict(last=GuideCommand("forward", 0.1), moved=0.0), "↑ did nothing (something is in the way, or it was there "
                                                          "already)"),
    (dict(last=GuideCommand("turn", -15), turned=-15.0), "→ turned me 15° right"),
    (dict(last=GuideCommand("lift", 0.21), lift=0.21, lifted=-0.05), "PgDn moved the lift 5 cm down"),
    (dict(last=GuideCommand("lift", 0.3), lift=0.3, lifted=0.0), "PgUp did nothing (something is in the way, or it "
                                                                 "was there already)"),
    (dict(last=GuideCommand("close"), hand_open=False, gripped=0.05), "space closed my hand"),
    (dict(last=None), "nothing yet"),
])
def test_the_last_key_says_what_it_did_or_that_it_did_nothing(changed, last):
    assert feedback_line(feedback(**changed), "en").endswith("last: " + last)


def test_a_ball_under_the_arm_is_said_to_be_behind_the_hand():
    assert feedback_line(feedback(ball_under_arm=True, ball_distance=0.19), "en").startswith(
        "ball 19 cm behind my hand, under my arm (↓ backs me up to it), 5 cm below my hand · bin")
    assert feedback_line(feedback(ball_under_arm=True, ball_distance=0.19), "de").startswith(
        "Ball 19 cm hinter meiner Hand, unter meinem Arm (↓ fährt mich zurück zu ihm), 5 cm unter meiner Hand")


def test_behind_ahead_and_at_hand_height():
    line = feedback_line(feedback(ball_bearing=170.0, ball_height=0.01, bin_bearing=-40.0, bin_distance=0.5), "en")
    assert line.startswith("ball 34 cm behind me, at hand height · bin 50 cm, 40° to my right")


_BALL = re.compile(r"ball (\d+(?:\.\d)?) (cm|m)(?:, (\d+)° to my (left|right)| ahead| behind me)")


def test_a_grasp_guided_by_the_feedback_alone(tmp_path: Path) -> None:
    """A person who reads only the feedback line: turn until the ball is ahead, drive up to it,
    lower the lift, close the hand. The grasp is recognised at the key that closed the hand."""
    from teach.world.mujoco_world import MujocoWorld

    domain = load_domain(BALL_DOMAIN)
    settings = Settings("pilot", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, domain, MujocoWorld(domain, seed=0))
    said = manager.handle("guide")
    for _ in range(60):
        line = said[-1].text
        ball = _BALL.search(line)
        assert ball is not None, line
        distance = float(ball.group(1)) / (1 if ball.group(2) == "m" else 100)
        lift = int(re.search(r"lift (\d+) cm", line).group(1))  # type: ignore[union-attr]
        if "behind me" in ball.group(0):
            said = manager.handle("guide turn 15")
        elif ball.group(3):
            step = min(15, int(ball.group(3)))
            said = manager.handle(f"guide turn {step if ball.group(4) == 'left' else -step}")
        elif distance > 0.06:
            said = manager.handle(f"guide forward {min(0.1, distance - 0.02):.2f}")
        elif lift > 0:
            said = manager.handle(f"guide lift {max(0, lift - 5) / 100:.2f}")
        else:
            said = manager.handle("guide close")
            break
    texts = [r.text for r in said]
    assert "✓ You moved me so that now the ball is in my hand: that was “grasp the ball”." in texts
    assert texts[-1].endswith("hand closed · last: space closed my hand")
    assert manager.open is not None and [s.action for s in manager.open.steps] == [1, 2, 3]
    manager.close()


_UNDER_ARM = re.compile(r"ball (\d+) cm behind my hand, under my arm")


def test_a_ball_driven_past_is_said_to_be_under_the_arm_and_backing_up_reaches_it(tmp_path: Path) -> None:
    """Driven past with the hand raised, the ball is pushed by the body, under the arm: it was said
    to be "19 cm ahead", and forward only pushed it on, closing the hand caught nothing. It is said
    to be behind the hand; backing up by that much, lowering the lift and closing grasps it."""
    from teach.world.mujoco_world import MujocoWorld

    domain = load_domain(BALL_DOMAIN)
    settings = Settings("pilot", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, domain, MujocoWorld(domain, seed=0))
    said = manager.handle("guide")
    for _ in range(40):  # face the ball
        ball = _BALL.search(said[-1].text)
        assert ball is not None, said[-1].text
        if "behind me" in ball.group(0):
            said = manager.handle("guide turn 15")
        elif ball.group(3) and int(ball.group(3)) > 2:
            step = min(15, int(ball.group(3)))
            said = manager.handle(f"guide turn {step if ball.group(4) == 'left' else -step}")
        else:
            break
    distance = float(ball.group(1)) / (1 if ball.group(2) == "m" else 100)
    said = manager.handle(f"guide forward {distance + 0.4:.2f}")  # past it, the hand high
    under = _UNDER_ARM.search(said[-1].text)
    assert under is not None, said[-1].text
    for line in (f"guide forward -{int(under.group(1)) / 100:.2f}", "guide lift 0", "guide close"):
        said = manager.handle(line)
    assert "✓ You moved me so that now the ball is in my hand: that was “grasp the ball”." in [r.text for r in said]
    manager.close()


def test_a_hand_holding_the_ball_is_said_closed_while_the_robot_turns(tmp_path: Path) -> None:
    """Turning with the ball held, the fingers give a little round it: the line said "hand open"
    with the ball in the hand (these lines, under tmux). The hand is what the teacher last made it,
    as space toggles it."""
    from teach.world.mujoco_world import MujocoWorld

    domain = load_domain(BALL_DOMAIN)
    settings = Settings("pilot", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, domain, MujocoWorld(domain, seed=0))
    for line in ("guide turn 30", "guide forward 0.5", "guide turn 180", "guide forward 2", "guide forward -0.25",
                 "guide lift 0", "guide close"):
        manager.handle(line)
    assert manager.world.state()[domain.condition_names.index("BallGrasped")]
    for line in ("guide lift 0.26", "guide turn 119", "guide forward 3"):
        said = manager.handle(line)
        assert " · hand closed · " in said[-1].text, (line, said[-1].text)
    said = manager.handle("guide open")  # over the bin: the ball drops in, behind the hand but not to be fetched
    assert "that was “put the ball in the bin”" in " ".join(r.text for r in said)
    assert "under my arm" not in said[-1].text, said[-1].text
    manager.close()



def test_a_ball_caught_from_under_the_arm_is_not_said_to_be_under_it(tmp_path: Path) -> None:
    """Lowered onto a ball still a little under the arm, the hand can close on it (these lines as
    keys, under tmux); the line went on saying it lay under the arm (↓ backs me up to it)."""
    from teach.world.mujoco_world import MujocoWorld

    domain = load_domain(BALL_DOMAIN)
    settings = Settings("pilot", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, domain, MujocoWorld(domain, seed=0))
    lines = ["guide turn 15"] * 14 + ["guide forward 0.1"] * 17 + ["guide forward -0.1"] * 2
    for line in lines + [f"guide lift {height}" for height in (0.21, 0.16, 0.11, 0.06, 0.01, 0)]:
        said = manager.handle(line)
    assert "under my arm" in said[-1].text
    said = manager.handle("guide close")
    assert "that was “grasp the ball”" in " ".join(r.text for r in said)
    assert "under my arm" not in said[-1].text, said[-1].text
    manager.close()


def test_a_ball_held_by_its_top_and_a_hand_resting_on_the_ball_are_said():
    held = feedback(last=GuideCommand("close"), hand_open=False, ball_held=True, ball_height=-0.06, ball_distance=0.03)
    assert "6 cm below my hand, held by its top only: it will slip out" in feedback_line(held, "en")
    assert "nur oben gehalten" in feedback_line(held, "de")
    assert "held by its top" not in feedback_line(feedback(ball_held=True, ball_height=-0.04), "en")
    assert "held by its top" not in feedback_line(feedback(ball_held=False, ball_height=-0.06), "en")
    resting = feedback(last=GuideCommand("lift", 0.04), lift=0.05, lifted=-0.01, ball_distance=0.08, ball_height=-0.06)
    assert feedback_line(resting, "en").endswith("last: PgDn stopped with my hand on the ball: move me until the ball "
                                                 "is between my fingers")
    reached = feedback(last=GuideCommand("lift", 0.04), lift=0.04, lifted=-0.02, ball_distance=0.08, ball_height=-0.04)
    assert feedback_line(reached, "en").endswith("last: PgDn moved the lift 2 cm down")


def test_a_careless_grasp_on_top_of_the_ball_is_said_before_it_slips(tmp_path: Path) -> None:
    """Under tmux a teacher lowered the open hand onto a ball 8 cm ahead and closed it: "✓ grasp the
    ball", then "take it to the bin" dropped it ("the ball fell out of the gripper") with nothing
    said why. The lowering that stopped on the ball and the hold by its top are said as they
    happen; the same hold taken round the ball (lift 0) carries it to the bin."""
    from teach.world.mujoco_world import MujocoWorld

    domain = load_domain(BALL_DOMAIN)
    settings = Settings("pilot", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, domain, MujocoWorld(domain, seed=0))
    moves = (["guide turn -15"] * 11 + ["guide forward 0.1"] * 12 + ["guide turn 15"] + ["guide forward 0.1"] * 3
             + ["guide turn 15"] * 4 + ["guide back 0.1"] * 2 + ["guide turn 15"]
             + [f"guide lift {height}" for height in (0.21, 0.16, 0.11, 0.06)])
    for line in moves:
        manager.handle(line)
    assert "stopped with my hand on the ball" in manager.handle("guide lift 0.04")[-1].text
    assert "held by its top only" in manager.handle("guide close")[-1].text
    said = [r.text for r in manager.handle("take it to the bin")]
    assert "Event: the ball fell out of the gripper." in said, said
    manager.close()
