"""Guiding primitives and the `guide ...` script lines, in the real MuJoCo world."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pytest

from teach.errors import FormatError
from teach.observe.hook import Observer
from teach.sim.guide import Guide, GuideCommand, is_guide_line, parse_guide_line
from teach.sim.world import FINGER_CLOSED, World, _wrap


@pytest.mark.parametrize(("line", "command"), [
    ("guide forward 0.4", GuideCommand("forward", 0.4)),
    ("guide back 0.2", GuideCommand("forward", -0.2)),
    ("guide turn -30", GuideCommand("turn", -30.0)),
    ("guide lift 0.25", GuideCommand("lift", 0.25)),
    ("guide close", GuideCommand("close")),
    ("Guide OPEN", GuideCommand("open")),
    ("guide wait 1.5", GuideCommand("wait", 1.5)),
    ("führen vor 0,3", GuideCommand("forward", 0.3)),
    ("führen schließen", GuideCommand("close")),
    ("guide turn right 150", GuideCommand("turn", -150.0)),  # the feedback's "150° to my right"
    ("guide turn left 30", GuideCommand("turn", 30.0)),
    ("führen drehen rechts 45", GuideCommand("turn", -45.0)),
])
def test_lines_parse(line: str, command: GuideCommand) -> None:
    assert is_guide_line(line) and parse_guide_line(line) == command
    # a command written back (a key press kept in a journal, say) reads as the same command
    assert parse_guide_line(str(command)) == command


@pytest.mark.parametrize(("line", "message"), [
    ("guide", "guide what?"),
    ("guide jump 1", "guide what?"),
    ("guide forward", "needs one number"),
    ("guide forward far", "needs a number in metres, got 'far'"),
    ("guide forward nan", "takes -5 to 5 metres"),
    ("guide lift 0.5", "takes 0 to 0.3 metres"),
    ("guide turn 1000", "takes -720 to 720 degrees"),
    ("guide wait -1", "takes 0 to 60 seconds"),
    ("guide close 3", "takes no number"),
    ("forward 0.4", "not a guiding command"),
])
def test_bad_lines_are_one_line_errors(line: str, message: str) -> None:
    with pytest.raises(FormatError) as caught:
        parse_guide_line(line, "study.dialogue", 7)
    text = str(caught.value)
    assert text.startswith("study.dialogue:7: ") and message in text and "\n" not in text


def test_primitives_reach_their_targets() -> None:
    world = World(seed=3)
    world.arrange({}, seed=3)
    guide = Guide(world)
    x0, y0, yaw0 = world.base_pose()
    guide.run(parse_guide_line("guide turn -30"))
    assert abs(math.degrees(_wrap(world.base_pose()[2] - yaw0)) + 30) < 0.5
    x1, y1, yaw1 = world.base_pose()
    guide.run(parse_guide_line("guide forward 0.4"))
    x2, y2, _ = world.base_pose()
    assert abs((x2 - x1) * math.cos(yaw1) + (y2 - y1) * math.sin(yaw1) - 0.4) < 0.005
    guide.run(parse_guide_line("guide lift 0.1"))
    assert abs(world.lift_height() - 0.1) < 0.005
    guide.run(parse_guide_line("guide close"))
    assert world.finger_closure() > FINGER_CLOSED - 0.002
    before = world.sim_time
    guide.run(parse_guide_line("guide wait 0.5"))
    assert abs(world.sim_time - before - 0.5) < 0.011
    # a sample every control period, in time order, each with the state read from physics
    times = [s.time for s in guide.samples]
    assert times == sorted(times) and len(times) > 100
    assert guide.samples[-1].state == world.state()


def test_a_human_speed_not_a_jump() -> None:
    world = World(seed=1)
    world.arrange({}, seed=1)
    guide = Guide(world)
    start = world.sim_time
    guide.forward(0.6)
    speeds = [abs(s.command[0]) for s in guide.samples]
    assert max(speeds) <= 0.3 + 1e-9 and world.sim_time - start > 2.0
    assert speeds[1] < 0.05 and speeds[-1] < 0.05  # starts and stops smoothly


def test_blocked_motion_stops() -> None:
    world = World(seed=2)
    world.arrange({}, seed=2)
    guide = Guide(world)
    guide.forward(4.9)  # into a wall of the 4 m room: the hand stops when the body does
    x, y, _ = world.base_pose()
    assert max(abs(x), abs(y)) < 2.0


class States(Observer):
    def __init__(self) -> None:
        self.running: list[str | None] = []

    def on_state(self, state: Mapping[str, bool], action: str | None) -> None:
        self.running.append(action)


def test_the_recording_shows_the_command_being_guided() -> None:
    world = World(seed=1)
    world.arrange({}, seed=1)
    states = States()
    guide = Guide(world, observer=states)
    guide.run(parse_guide_line("guide turn 90"))
    guide.run(parse_guide_line("führen vor 0,2"))
    # scene frames at 10 Hz of simulated time, each naming the command carried out
    assert set(states.running) == {"guide", "guide turn 90", "guide forward 0.2"} and len(states.running) > 20


def test_a_hand_on_the_robot_guides_it() -> None:
    world = World(seed=4)
    world.arrange({}, seed=4)
    guide = Guide(world)
    x0, y0, yaw0 = world.base_pose()
    guide.by_hand(0.5)  # nobody touches it: it stays
    assert math.dist(world.base_pose()[:2], (x0, y0)) < 0.005
    # a 20 N push along the heading and a turning hand: it walks forward and turns left
    world.push_base(20.0 * np.array([math.cos(yaw0), math.sin(yaw0)]), 2.0)
    guide.by_hand(1.0)
    world.push_base(np.zeros(2), 0.0)
    x1, y1, yaw1 = world.base_pose()
    ahead = (x1 - x0) * math.cos(yaw0) + (y1 - y0) * math.sin(yaw0)
    assert 0.1 < ahead < 0.35 and 0.1 < _wrap(yaw1 - yaw0) < 0.5
    assert guide.samples[-1].command[:2] != (0.0, 0.0)


def test_same_seed_same_motion() -> None:
    runs = []
    for _ in range(2):
        world = World(seed=5)
        world.arrange({"BallFound": True}, seed=5)
        guide = Guide(world)
        for line in ("guide turn 40", "guide forward 0.3", "guide lift 0.05", "guide close", "guide open"):
            guide.run(parse_guide_line(line))
        runs.append(guide.samples)
    assert runs[0] == runs[1]


def test_keys_mean_primitives() -> None:
    world = World(seed=1)
    guide = Guide(world)
    assert guide.key("up") == GuideCommand("forward", 0.1)
    assert guide.key("right") == GuideCommand("turn", -15.0)
    assert guide.key("pagedown") == GuideCommand("lift", round(guide.lift_target - 0.05, 3))
    assert guide.key("space") == GuideCommand("close")
    guide.run(GuideCommand("close"))
    assert guide.key("space") == GuideCommand("open")
    assert guide.key("x") is None
