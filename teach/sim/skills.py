"""Skills: the domain's actions as controllers over the robot's actuators.

Each skill advances physics one control period (20 ms) per ``tick`` and returns RUNNING while
it moves, SUCCESS once its effect holds, and FAILURE when it cannot work (nothing to grasp,
nothing to place, the ball unknown) or after its timeout. Skills re-read the world every
period, so a perturbation in the middle is answered by the controller, not by a script.

- FindBall: turns a full circle on the spot; if the ball stays unseen it backs up 0.8 m and
  turns again, then visits room waypoints; a ball held in the gripper is found by touch.
- ApproachBall: drives until the grasp point is within ``ALIGNED`` of the remembered ball.
- GraspBall: aligns to within 2 cm, lowers the lift and closes the fingers; SUCCESS as soon as
  the ball is held (ApproachBin raises it to carry height).
- ApproachBin: raises the lift and drives until the grasp point is within ``ALIGNED`` of the bin.
- PlaceBall: aligns over the bin to within 3 cm, lowers the ball into it, opens the fingers
  and lifts the gripper out; SUCCESS once the ball rests in the bin and the gripper is up.

Approaching the ball moves the robot, so BinClose may become false on the way (the thesis's
special case in Δ2): that is physics, not a rule.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Callable, Mapping
from types import MappingProxyType

import numpy as np

from teach.bt.nodes import Status
from teach.errors import DomainError
from teach.observe.hook import Observer
from teach.sim.world import (
    CONTROL_STEPS,
    FINGER_CLOSED,
    FINGER_OPEN,
    FINGER_RELEASE,
    GRASP_OFFSET,
    LIFT_CARRY,
    LIFT_PLACE,
    ROOM,
    World,
    _wrap,
)

ALIGNED = 0.05        # approaches end with the grasp point this close to the target (m)
LOWER_SPEED = 0.5     # m/s, the lift lowering a held ball
BIN_CLEARANCE = 0.5   # the chassis centre keeps this far from the bin's centre (m)
MAX_SPEED = 1.0       # m/s
MAX_TURN = 2.5        # rad/s
FRAME_HZ = 10.0       # observer scene frames per simulated second
CAMERAS = {"overview": (2.0, 400, 300), "robot": (1.0, 320, 240)}  # images per simulated second, size

RUNNING, SUCCESS, FAILURE = Status.RUNNING, Status.SUCCESS, Status.FAILURE


class Skill:
    """A controller for one action; subclasses implement ``update`` (one control period)."""

    name = ""
    timeout = 20.0  # simulated seconds

    def __init__(self, world: World):
        self.world = world
        self.started = world.sim_time
        self.result: Status | None = None

    def tick(self) -> Status:
        """Advance physics one control period under this skill; the status after it."""
        if self.result is not None:
            return self.result
        status = self.update()
        if status is RUNNING and self.world.sim_time - self.started > self.timeout:
            status = FAILURE
        if status is RUNNING:
            self.world.step(CONTROL_STEPS)
        else:
            self.halt()
            self.result = status
        return status

    def update(self) -> Status:
        """Look at the world, set the actuator commands for the next period, say how it goes."""
        raise NotImplementedError

    def halt(self) -> None:
        """Stop the base; lift and fingers hold where they are commanded."""
        self.world.drive(0.0, 0.0)

    def go_to(self, target: np.ndarray, offset: float = GRASP_OFFSET) -> float:
        """Steer so the point ``offset`` ahead of the base reaches ``target``; its distance left."""
        x, y, yaw = self.world.base_pose()
        dx, dy = float(target[0]) - x, float(target[1]) - y
        heading = _wrap(math.atan2(dy, dx) - yaw)
        along = math.hypot(dx, dy) - offset
        turn = max(-MAX_TURN, min(MAX_TURN, 5.0 * heading))
        forward = 0.0 if abs(heading) > 0.3 else max(-0.5, min(MAX_SPEED, 2.5 * along)) * math.cos(heading)
        self.world.drive(forward, turn)
        lateral = math.hypot(dx, dy) * math.sin(heading)
        return math.hypot(along, lateral)

    def go_around_bin(self, target: np.ndarray, offset: float = GRASP_OFFSET) -> float:
        """Like ``go_to``, but the chassis keeps ``BIN_CLEARANCE`` from the bin: it stands on the
        far side of a target next to the bin and drives around the bin when it is in the way."""
        x, y, _ = self.world.base_pose()
        here, goal, bin_xy = np.array([x, y]), np.asarray(target[:2], dtype=float), self.world.bin_position()[:2]
        stand = goal - offset * _unit(goal - here)
        if offset > 0 and np.linalg.norm(stand - bin_xy) < BIN_CLEARANCE:
            stand = goal + offset * _unit(goal - bin_xy)
        if np.linalg.norm(stand - here) < 0.1:
            return self.go_to(goal, offset)
        waypoint = _detour(here, stand, bin_xy)
        if waypoint is None and np.linalg.norm(stand - (goal - offset * _unit(goal - here))) < 0.05:
            return self.go_to(goal, offset)  # the direct approach is clear
        self.go_to(waypoint if waypoint is not None else stand, 0.0)
        return float(np.linalg.norm(goal - here)) + offset

    def lift_ready(self, height: float = LIFT_CARRY) -> bool:
        self.world.set_lift(height)
        return abs(self.world.lift_height() - height) < 0.02


class FindBall(Skill):
    name = "FindBall"
    timeout = 40.0

    def __init__(self, world: World):
        super().__init__(world)
        x, y, _ = world.base_pose()
        here, spot = np.array([x, y]), 0.6 * ROOM
        corners = ((0.0, 0.0), (spot, spot), (-spot, spot), (-spot, -spot), (spot, -spot))
        waypoints = sorted((np.array(p) for p in corners if np.linalg.norm(np.array(p) - here) > 0.5),
                           key=lambda p: float(np.linalg.norm(p - here)))
        self.plan: list[tuple[str, np.ndarray | None]] = [("turn", None), ("back", None), ("turn", None)]
        for point in waypoints:
            self.plan += [("go", point), ("turn", None)]
        self._begin()

    def _begin(self) -> None:
        x, y, yaw = self.world.base_pose()
        self.since, self.origin, self.last_yaw, self.turned = self.world.sim_time, np.array([x, y]), yaw, 0.0

    def update(self) -> Status:
        world = self.world
        if world.ball_found() or world.localise_by_touch():
            return SUCCESS
        if not self.plan:
            return FAILURE  # looked everywhere
        world.set_lift(LIFT_CARRY)
        x, y, yaw = world.base_pose()
        kind, point = self.plan[0]
        elapsed = world.sim_time - self.since
        if kind == "turn":
            self.turned += abs(_wrap(yaw - self.last_yaw))
            self.last_yaw = yaw
            done = self.turned >= 2 * math.pi
            world.drive(0.0, 2.0)
        elif kind == "back":
            done = float(np.linalg.norm(np.array([x, y]) - self.origin)) > 0.8 or elapsed > 1.5
            world.drive(-0.8, 0.0)
        else:
            assert point is not None
            done = self.go_around_bin(point, 0.0) < 0.15 or elapsed > 8.0
        if done:
            self.plan.pop(0)
            self._begin()
        return RUNNING


class ApproachBall(Skill):
    name = "ApproachBall"

    def update(self) -> Status:
        world = self.world
        target = world.known_ball()
        if world.ball_grasped() or target is None:
            return FAILURE  # the ball is in the hand, or nobody knows where it is
        world.set_fingers(FINGER_OPEN)
        if world.lift_height() < LIFT_CARRY - 0.15:
            world.drive(0.0, 0.0)
            world.set_lift(LIFT_CARRY)
            return RUNNING
        world.set_lift(LIFT_CARRY)
        if self.go_around_bin(target) < ALIGNED and world.ball_close():
            return SUCCESS
        return RUNNING


class PhasedSkill(Skill):
    """A skill that moves through named phases ("align", "lower", ...), timing each one."""

    def __init__(self, world: World):
        super().__init__(world)
        self.phase = "align"
        self.since = world.sim_time

    def _enter(self, phase: str) -> None:
        self.phase, self.since = phase, self.world.sim_time


class GraspBall(PhasedSkill):
    name = "GraspBall"
    timeout = 8.0

    def update(self) -> Status:
        world = self.world
        elapsed = world.sim_time - self.since
        if self.phase == "align":
            if world.ball_grasped():
                return SUCCESS
            target = world.known_ball()
            if target is None or not world.ball_close():
                return FAILURE  # nothing known within reach
            world.set_fingers(FINGER_OPEN)
            if not self.lift_ready():
                world.drive(0.0, 0.0)
                return RUNNING
            if self.go_to(target) < 0.02:
                world.drive(0.0, 0.0)
                self._enter("lower")
        elif self.phase == "lower":
            if self.lift_ready(0.0) or elapsed > 1.0:
                self._enter("close")
        elif self.phase == "close":
            world.set_fingers(FINGER_CLOSED)
            if world.finger_closure() > FINGER_CLOSED - 0.01:
                return FAILURE  # closed on nothing
            if world.ball_grasped() and elapsed > 0.2:
                # done as soon as the ball is held: a reactive tree stops ticking this skill the
                # moment BallGrasped holds, so lifting belongs to whatever comes next
                return SUCCESS
            if elapsed > 1.0:
                return FAILURE
        return RUNNING


class ApproachBin(Skill):
    name = "ApproachBin"

    def update(self) -> Status:
        world = self.world
        if not self.lift_ready():
            world.drive(0.0, 0.0)
            return RUNNING
        if self.go_to(world.bin_position()) < ALIGNED and world.bin_close():
            return SUCCESS
        return RUNNING


class PlaceBall(PhasedSkill):
    name = "PlaceBall"
    timeout = 8.0

    def update(self) -> Status:
        world = self.world
        elapsed = world.sim_time - self.since
        if self.phase == "align":
            if world.ball_placed():
                return SUCCESS
            if not world.ball_grasped() or not world.bin_close():
                return FAILURE  # nothing to place, or no bin within reach
            if not self.lift_ready():
                world.drive(0.0, 0.0)
                return RUNNING
            if self.go_to(world.bin_position()) < 0.03:
                world.drive(0.0, 0.0)
                self._enter("lower")
        elif self.phase == "lower":  # slower than a free fall, so the ball stays on the hooks
            height = max(LIFT_PLACE, LIFT_CARRY - LOWER_SPEED * elapsed)
            if self.lift_ready(height) and height == LIFT_PLACE or elapsed > 1.5:
                self._enter("release")
        elif self.phase == "release":
            world.set_fingers(FINGER_RELEASE)
            if world.ball_placed() and world.ball_speed() < 0.05:
                self._enter("withdraw")
            elif elapsed > 1.5:
                return FAILURE
        elif self.phase == "withdraw":
            if self.lift_ready() or elapsed > 1.0:
                return SUCCESS if world.ball_placed() else FAILURE
        return RUNNING


def _unit(v: np.ndarray) -> np.ndarray:
    norm = float(np.linalg.norm(v))
    return v / norm if norm > 1e-9 else np.array([1.0, 0.0])


def _detour(start: np.ndarray, end: np.ndarray, bin_xy: np.ndarray) -> np.ndarray | None:
    """A point beside the bin to drive to first when the straight path passes too near it."""
    length = float(np.linalg.norm(end - start))
    if length < 1e-6:
        return None
    u = (end - start) / length
    t = float(np.dot(bin_xy - start, u))
    closest = start + min(max(t, 0.0), length) * u
    if np.linalg.norm(bin_xy - closest) >= BIN_CLEARANCE or t <= 0.0:
        return None
    normal = np.array([-u[1], u[0]])
    side = 1.0 if float(np.dot(closest - bin_xy, normal)) >= 0 else -1.0
    return bin_xy + side * (BIN_CLEARANCE + 0.15) * normal


BUILTIN_SKILLS: Mapping[str, type[Skill]] = MappingProxyType(
    {skill.name: skill for skill in (FindBall, ApproachBall, GraspBall, ApproachBin, PlaceBall)})
"""The ball-in-bin skills, the same in every world; a world's own are ``taught_in(world)``."""

_TAUGHT: weakref.WeakKeyDictionary[World, dict[str, type[Skill]]] = weakref.WeakKeyDictionary()
"""Per world, the skills of actions taught by guidance in it; gone with the world. Kept here, not
on ``World``, so the world knows nothing of skills (skills drive the world, not back)."""


def taught_in(world: World) -> Mapping[str, type[Skill]]:
    """The skills taught by guidance in ``world``, by action name."""
    return MappingProxyType(_TAUGHT.get(world, {}))


def register(world: World, skill: type[Skill]) -> type[Skill]:
    """Make a skill runnable under its action name in ``world`` only: an action one session taught
    by guidance is no skill of another session's world, even in the same process."""
    _TAUGHT.setdefault(world, {})[skill.name] = skill
    return skill


def skill_for(world: World, name: str) -> type[Skill]:
    """The skill for action ``name`` in ``world``: one taught there, else a built-in one."""
    taught = taught_in(world)
    skill = taught.get(name) or BUILTIN_SKILLS.get(name)
    if skill is None:
        raise DomainError(f"the simulation has no skill for action {name!r} "
                          f"(it has {', '.join(sorted({*BUILTIN_SKILLS, *taught}))})")
    return skill


class FrameClock:
    """Reports scene frames and camera images to an observer at fixed rates of simulated time;
    ``on_frame`` runs after each scene frame (pacing to wall time, a viewer's redraw). A change of
    the running action is reported at once, so the observer never shows an action that ended."""

    def __init__(self, world: World, observer: Observer | None, on_frame: Callable[[], None] | None = None):
        self.world, self.observer, self.on_frame = world, observer, on_frame
        self.next_frame = world.sim_time
        self.next_camera = dict.fromkeys(CAMERAS, world.sim_time)
        self.action: str | None = None

    def __call__(self, action: str | None, force: bool = False) -> None:
        """Report a frame if one is due (or ``force``): clock, state, scene, maybe camera images."""
        world, observer = self.world, self.observer
        if observer is None or (not force and action == self.action and world.sim_time + 1e-9 < self.next_frame):
            return
        self.action = action
        self.next_frame = world.sim_time + 1.0 / FRAME_HZ
        observer.set_time(None, world.sim_time)
        observer.on_state(world.conditions(), action)
        observer.on_scene(world.shapes())
        if self.on_frame is not None:
            self.on_frame()
        for camera, (hz, width, height) in CAMERAS.items():
            if world.sim_time + 1e-9 >= self.next_camera[camera]:
                self.next_camera[camera] = world.sim_time + 1.0 / hz
                image = world.camera_image(width, height, camera)
                if image is not None:
                    observer.on_camera(image, camera)


def run_skill(world: World, name: str, observer: Observer | None = None, max_seconds: float = 60.0,
              frames: Callable[[str | None], None] | None = None,
              halt_when: Callable[[], bool] | None = None) -> Status:
    """Run the skill for action ``name`` to completion (or FAILURE after ``max_seconds``).

    ``halt_when`` is asked after every control period; when it says so the skill is halted
    where it is and RUNNING returned: it did not finish, something else stopped it."""
    skill = skill_for(world, name)(world)
    report = frames or FrameClock(world, observer)
    deadline = world.sim_time + max_seconds
    status = RUNNING
    while status is RUNNING:
        report(name)
        if world.sim_time >= deadline:
            skill.halt()
            return FAILURE
        status = skill.tick()
        if status is RUNNING and halt_when is not None and halt_when():
            skill.halt()
            return RUNNING
    report(name)
    report(None)  # the skill is over: nothing runs until the next one starts
    return status
