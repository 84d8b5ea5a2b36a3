"""A new action from guidance: a guided segment kept as a motion primitive and replayed as a skill.

The motion is stored relative to the object it acted on: of the ball and the bin, leaving out one
carried along (it moved, but not relative to the robot), the one that moved most in the segment,
or if neither moved, the one nearest the gripper at its end. Stored are where that object lay in
the robot's frame at the segment's start, the lift and finger commands then, and the base's
path in the start frame with the commands that drove it. Replaying from another start, the
skill first brings the robot to the same pose relative to the object (around the bin to the
ball as ApproachBall drives, straight to the bin as ApproachBin does), sets lift and fingers,
then follows the path anchored on the object, the recorded commands fed forward and the pose
error fed back. SUCCESS once the effects (what
changed in the segment) hold after the path has begun; FAILURE when the object is unknown,
when the path ends without them, or on timeout.

File format (JSON, written by ``save_motion``): ``name``, ``en``/``de`` phrases, ``anchor``,
``offset`` [ahead, left] in metres, ``lift``, ``fingers``, ``effects`` (literals like
``"!BallClose"``) and ``points``, one ``[t, x, y, yaw, forward, turn, lift, fingers]`` per line.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from teach.bt.nodes import Status
from teach.domain import Domain, Literal, check_numbers
from teach.errors import FormatError, shown
from teach.fsutil import atomic_write_text, parse_json, read_text
from teach.learn.recognise import changed_literals
from teach.sim.guide import Sample
from teach.sim.segment import Segment
from teach.sim.skills import FAILURE, RUNNING, SUCCESS, Skill
from teach.sim.world import GRASP_OFFSET, LIFT_CARRY, World, _wrap

ANCHORS = ("ball", "bin")
MOVED = 0.02            # m: an object that moved this much was acted on
PLACED = 0.02           # m: the approach ends this close to the stored start pose
FACED = math.radians(1.0)
SETTLE = 0.3            # s after the path before the effects are judged
FINGER_SETTLE = 0.5     # s the fingers get to reach their start closure
APPROACH_TIMEOUT = 20.0  # s
FORMAT = "teach-guided-motion"
_KEYS = ("format", "version", "name", "en", "de", "anchor", "effects", "offset", "lift", "fingers", "points")
"""The keys of a motion file, in the order ``motion_text`` writes them: any other is refused."""
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


@dataclass(frozen=True, slots=True)
class MotionPoint:
    """One control period of the path, in the frame of the robot's pose at the segment start."""

    t: float
    x: float
    y: float
    yaw: float
    forward: float
    turn: float
    lift: float
    fingers: float


@dataclass(frozen=True)
class GuidedMotion:
    """A guided segment as a replayable primitive (see the module docstring)."""

    name: str
    anchor: str
    offset: tuple[float, float]
    lift: float
    fingers: float
    effects: tuple[Literal, ...]
    points: tuple[MotionPoint, ...]
    en: tuple[str, ...] = ()
    de: tuple[str, ...] = ()

    @property
    def duration(self) -> float:
        return self.points[-1].t if self.points else 0.0


def _acted_on(segment: Segment) -> str:
    """The object the segment's motion was done to (see the module docstring)."""
    first, last = segment.samples[0], segment.samples[-1]

    def in_robot_frame(sample: Sample, name: str) -> np.ndarray:
        x, y, yaw = sample.base
        dx, dy = getattr(sample, name)[0] - x, getattr(sample, name)[1] - y
        return np.array([dx * math.cos(yaw) + dy * math.sin(yaw), -dx * math.sin(yaw) + dy * math.cos(yaw)])

    moved = {name: float(np.linalg.norm(np.subtract(getattr(last, name)[:2], getattr(first, name)[:2])))
             for name in ANCHORS}
    carried = {name for name in ANCHORS if moved[name] >= MOVED and
               float(np.linalg.norm(in_robot_frame(last, name) - in_robot_frame(first, name))) < MOVED}
    candidates = [name for name in ANCHORS if name not in carried] or list(ANCHORS)
    if max(moved[name] for name in candidates) >= MOVED:
        return max(candidates, key=lambda name: moved[name])
    x, y, yaw = last.base
    grasp = (x + GRASP_OFFSET * math.cos(yaw), y + GRASP_OFFSET * math.sin(yaw))
    return min(candidates, key=lambda name: math.dist(grasp, getattr(last, name)[:2]))


def motion_from_segment(name: str, segment: Segment, domain: Domain, en: Sequence[str] = (),
                        de: Sequence[str] = ()) -> GuidedMotion:
    """The segment the teacher named as new, as a motion primitive with its effects."""
    if not _NAME.match(name):
        raise FormatError(f"an action name must be an identifier (letters, digits, _), got {name!r}")
    first = segment.samples[0]
    anchor = _acted_on(segment)
    x0, y0, yaw0 = first.base
    c, s = math.cos(yaw0), math.sin(yaw0)

    def local(px: float, py: float) -> tuple[float, float]:
        dx, dy = px - x0, py - y0
        return dx * c + dy * s, -dx * s + dy * c

    target = getattr(first, anchor)
    points = []
    for sample in segment.samples:
        lx, ly = local(sample.base[0], sample.base[1])
        points.append(MotionPoint(round(sample.time - first.time, 6), lx, ly, _wrap(sample.base[2] - yaw0),
                                  *sample.command))
    return GuidedMotion(name, anchor, local(target[0], target[1]), first.command[2], first.command[3],
                        changed_literals(domain, segment.before, segment.after), tuple(points), tuple(en), tuple(de))


class GuidedSkill(Skill):
    """Replays a ``GuidedMotion`` relative to its object; make one per motion with ``guided_skill``."""

    motion: ClassVar[GuidedMotion]

    def __init__(self, world: World):
        super().__init__(world)
        self.phase = "approach"
        self.index = 0
        self.since = world.sim_time
        self.frame: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def _anchor(self) -> np.ndarray | None:
        return self.world.known_ball() if self.motion.anchor == "ball" else self.world.bin_position()

    def _effects_hold(self) -> bool:
        state = self.world.conditions()
        return all(state.get(lit.name) == lit.value for lit in self.motion.effects)

    def update(self) -> Status:
        if self.phase in ("approach", "face", "prepare"):
            target = self._anchor()
            if target is None:
                return FAILURE  # the robot does not know where the object is
            {"approach": self._approach, "face": self._face, "prepare": self._prepare}[self.phase](target)
            return RUNNING
        if self._effects_hold():
            return SUCCESS
        if self.phase == "follow":
            self._follow()
            return RUNNING
        self.world.drive(0.0, 0.0)
        if self.world.sim_time - self.since > SETTLE:
            return FAILURE  # the path is done and its effects do not hold
        return RUNNING

    def _approach(self, target: np.ndarray) -> None:
        """Drive (arm up, as ApproachBall does) until the object is as far ahead as it was."""
        world, motion = self.world, self.motion
        world.set_fingers(motion.fingers)
        reach = math.hypot(*motion.offset)
        if not self.lift_ready(LIFT_CARRY):
            world.drive(0.0, 0.0)
        elif (self.go_around_bin(target, reach) if motion.anchor == "ball" else self.go_to(target, reach)) < PLACED:
            self.phase = "face"

    def _face(self, target: np.ndarray) -> None:
        """Turn on the spot until the object lies at the bearing it had for the teacher."""
        x, y, yaw = self.world.base_pose()
        bearing = math.atan2(self.motion.offset[1], self.motion.offset[0])
        error = _wrap(math.atan2(target[1] - y, target[0] - x) - bearing - yaw)
        self.world.drive(0.0, max(-2.0, min(2.0, 4.0 * error)))
        if abs(error) < FACED:
            self.world.drive(0.0, 0.0)
            self.phase, self.since = "prepare", self.world.sim_time

    def _prepare(self, target: np.ndarray) -> None:
        """Lift and fingers to where they started (fingers on a held ball stop short of it)."""
        world, motion = self.world, self.motion
        world.set_fingers(motion.fingers)
        fingers_set = abs(world.finger_closure() - motion.fingers) < 0.005 or \
            world.sim_time - self.since > FINGER_SETTLE
        if self.lift_ready(motion.lift) and fingers_set:
            self._anchor_frame(target)
            self.phase, self.since = "follow", world.sim_time

    def _anchor_frame(self, target: np.ndarray) -> None:
        """The start frame: the robot's heading, placed so the object lies where it lay for the teacher."""
        yaw = self.world.base_pose()[2]
        ahead, left = self.motion.offset
        c, s = math.cos(yaw), math.sin(yaw)
        self.frame = (float(target[0]) - ahead * c + left * s, float(target[1]) - ahead * s - left * c, yaw)

    def _follow(self) -> None:
        world, points = self.world, self.motion.points
        elapsed = world.sim_time - self.since
        while self.index + 1 < len(points) and points[self.index + 1].t <= elapsed + 1e-9:
            self.index += 1
        point = points[min(self.index + 1, len(points) - 1)]
        fx, fy, fyaw = self.frame
        c, s = math.cos(fyaw), math.sin(fyaw)
        goal = (fx + point.x * c - point.y * s, fy + point.x * s + point.y * c, fyaw + point.yaw)
        x, y, yaw = world.base_pose()
        ahead = (goal[0] - x) * math.cos(yaw) + (goal[1] - y) * math.sin(yaw)
        heading = _wrap(goal[2] - yaw)
        world.drive(point.forward + 3.0 * ahead, point.turn + 4.0 * heading)
        world.set_lift(point.lift)
        world.set_fingers(point.fingers)
        if self.index + 1 >= len(points):
            self.phase, self.since = "settle", world.sim_time


def guided_skill(motion: GuidedMotion) -> type[GuidedSkill]:
    """A skill class for ``motion`` under its action name (``teach.sim.skills.register`` adds it to a world)."""
    timeout = APPROACH_TIMEOUT + motion.duration + SETTLE + 1.0
    return type(motion.name, (GuidedSkill,), {"name": motion.name, "motion": motion, "timeout": timeout})


# --- the file ---------------------------------------------------------------------------------

def _number(value: float) -> str:
    text = f"{value:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def motion_text(motion: GuidedMotion) -> str:
    """The motion as JSON, one path point per line (byte-identical for the same motion)."""
    head = {"format": FORMAT, "version": 1, "name": motion.name, "en": list(motion.en), "de": list(motion.de),
            "anchor": motion.anchor, "effects": [str(lit) for lit in motion.effects]}
    lines = ["{"] + [f"  {json.dumps(key)}: {json.dumps(value, ensure_ascii=False)}," for key, value in head.items()]
    lines.append(f'  "offset": [{_number(motion.offset[0])}, {_number(motion.offset[1])}],')
    lines.append(f'  "lift": {_number(motion.lift)},')
    lines.append(f'  "fingers": {_number(motion.fingers)},')
    rows = ["    [" + ", ".join(_number(getattr(p, f)) for f in MotionPoint.__slots__) + "]"  # type: ignore[attr-defined]
            for p in motion.points]
    lines += ['  "points": ['] + [",\n".join(rows)] + ["  ]", "}"]
    return "\n".join(lines) + "\n"


def save_motion(motion: GuidedMotion, path: str | Path) -> None:
    atomic_write_text(path, motion_text(motion))


def load_motion(path: str | Path, domain: Domain) -> GuidedMotion:
    """Read a motion file; every problem is one ``FormatError`` naming the file and line."""
    text = read_text(path, "guided motion file")
    check_numbers(text, path, "json")
    return _motion_from_data(parse_json(text, path, "the guided motion file"), text, Path(path), domain)


def _motion_from_data(data: Any, text: str, path: Path, domain: Domain) -> GuidedMotion:
    lines = text.split("\n")  # JSON's line breaks only: the numbers errors give are the file's own

    def line_of(key: str) -> int | None:
        return next((n for n, line in enumerate(lines, 1) if f'"{key}"' in line), None)

    def fail(message: str, key: str | None = None, line: int | None = None) -> FormatError:
        return FormatError(message, path, line if line is not None else (line_of(key) if key else None))

    def number(value: Any, what: str, key: str, line: int | None = None) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float) or not -1e300 < value < 1e300:
            raise fail(f"{what} must be a number, got {shown(value)}", key, line)  # not NaN, infinite or huge
        return float(value)

    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise fail(f"not a guided motion file (it needs \"format\": \"{FORMAT}\")", "format", 1)
    for key in data:
        if key not in _KEYS:
            raise fail(f"unknown key {shown(key)} (allowed: {', '.join(_KEYS)})", key)
    if data.get("version") != 1:
        raise fail(f"unsupported version {shown(data.get('version'))} (this teach reads version 1)", "version")
    name = data.get("name")
    if not isinstance(name, str) or not _NAME.match(name):
        raise fail(f"'name' must be an identifier (letters, digits, _), got {shown(name)}", "name")
    phrases = {}
    for lang in ("en", "de"):
        value = data.get(lang, [])
        if not isinstance(value, list) or not all(isinstance(p, str) for p in value):
            raise fail(f"'{lang}' must be a list of phrases", lang)
        phrases[lang] = tuple(value)
    anchor = data.get("anchor")
    if anchor not in ANCHORS:
        raise fail(f"'anchor' must be one of {', '.join(ANCHORS)}, got {shown(anchor)}", "anchor")
    raw_effects = data.get("effects")
    if not isinstance(raw_effects, list) or not raw_effects or not all(isinstance(e, str) for e in raw_effects):
        raise fail("'effects' must be a non-empty list of literals like \"BallPlaced\" or \"!BallClose\"", "effects")
    effects = tuple(Literal.parse(e) for e in raw_effects)
    for literal in effects:
        if not domain.has_condition(literal.name):
            raise fail(f"'effects' names unknown condition {shown(literal.name)}", "effects")
    offset = data.get("offset")
    if not isinstance(offset, list) or len(offset) != 2:
        raise fail("'offset' must be [ahead, left] in metres", "offset")
    ahead, left = (number(v, "'offset'", "offset") for v in offset)
    lift = number(data.get("lift"), "'lift'", "lift")
    fingers = number(data.get("fingers"), "'fingers'", "fingers")
    raw_points = data.get("points")
    if not isinstance(raw_points, list) or not raw_points:
        raise fail("'points' must be a non-empty list of [t, x, y, yaw, forward, turn, lift, fingers]", "points")
    first_point = (line_of("points") or 0) + 1
    points: list[MotionPoint] = []
    for i, raw in enumerate(raw_points):
        line = first_point + i
        if not isinstance(raw, list) or len(raw) != 8:
            raise fail(f"point {i + 1} must be 8 numbers [t, x, y, yaw, forward, turn, lift, fingers]", line=line)
        values = [number(v, f"point {i + 1}", "points", line) for v in raw]
        if points and values[0] < points[-1].t:
            raise fail(f"point {i + 1} goes back in time ({values[0]:g} s after {points[-1].t:g} s)", line=line)
        points.append(MotionPoint(*values))
    return GuidedMotion(name, anchor, (ahead, left), lift, fingers, effects, tuple(points),
                        phrases["en"], phrases["de"])
