"""Guiding the robot's body: the primitives a teacher's keys or a script produce.

A teacher guides the robot as a hand would: ``forward`` (metres along the heading, negative
backs up), ``turn`` (degrees, positive is counter-clockwise), ``lift`` (absolute height in
metres), ``open``, ``close`` and ``wait``. Each drives the actuators at a human-like speed,
with smooth starts and stops, for as long as it takes, and stops early when the body is
blocked (a wall, the bin): a hand would stop too. Closing the fingers on the ball localises it
by touch, as FindBall does for a held ball. Every control period (20 ms) the guide
records a ``Sample`` (the symbolic state, the bodies' poses and the commands) and hands it to
its listener, so a segmenter can cut the motion online.

In the MuJoCo viewer the teacher drags the robot instead (Ctrl + drag): ``by_hand`` follows the
force on the robot's bodies (``guide hand 10``: for 10 s; the session's ``guide hand`` alone follows
until the hand lets go, ``teach.session.hand``).
Script lines: ``guide forward 0.4``, ``guide turn -30``, ``guide lift 0.25``, ``guide close``
(German: ``führen vor 0.4``, ``führen drehen -30``, ``führen heben 0.25``, ``führen schließen``).
Keys (``Guide.key``): up/down move 10 cm, left/right turn 15 degrees, pageup/pagedown move
the lift 5 cm, space opens or closes the fingers.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from teach.domain import State
from teach.errors import FormatError
from teach.observe.hook import Observer
from teach.sim.skills import FrameClock
from teach.sim.world import CONTROL_STEPS, FINGER_CLOSED, FINGER_OPEN, LIFT_TOP, World, _wrap

SPEED = 0.3              # m/s: walking a robot by hand
ACCELERATION = 0.6       # m/s^2
TURN_SPEED = math.radians(60)        # rad/s
TURN_ACCELERATION = math.radians(180)
LIFT_SPEED = 0.15        # m/s
FINGER_SPEED = 0.12      # m/s of finger travel
BLOCKED_SECONDS = 0.6    # no progress for this long: the body is blocked, the primitive ends
MAX_DISTANCE = 5.0       # m: the room is 4 m wide
MAX_TURN = 720.0         # degrees
MAX_WAIT = 60.0          # seconds
HAND_DAMPING = 100.0     # N per m/s: a hand pushing with 30 N walks the robot at 0.3 m/s
HAND_TURN_DAMPING = 10.0  # N m per rad/s
KEY_STEP = 0.1           # m per arrow key
KEY_TURN = 15.0          # degrees per arrow key
KEY_LIFT = 0.05          # m per page key
DONE_DISTANCE = 0.002    # m
DONE_ANGLE = math.radians(0.3)
DONE_LIFT = 0.003        # m


@dataclass(frozen=True, slots=True)
class Sample:
    """One control period of guided motion: what held and where everything was."""

    time: float
    state: State
    base: tuple[float, float, float]        # x, y, yaw
    lift: float                             # measured height
    fingers: float                          # measured closure
    ball: tuple[float, float, float]
    bin: tuple[float, float, float]
    command: tuple[float, float, float, float]  # forward m/s, turn rad/s, lift target, finger target


@dataclass(frozen=True, slots=True)
class GuideCommand:
    """One guiding primitive: ``verb`` is forward, turn, lift, open, close or wait."""

    verb: str
    amount: float = 0.0

    def __str__(self) -> str:
        if self.verb in ("open", "close") or (self.verb == "hand" and self.amount == 0):
            return f"guide {self.verb}"
        return f"guide {self.verb} {self.amount:g}"


VERBS: dict[str, str] = {"forward": "forward", "back": "back", "turn": "turn", "lift": "lift", "open": "open",
                         "close": "close", "wait": "wait", "hand": "hand",
                         "vor": "forward", "vorwärts": "forward", "zurück": "back", "drehen": "turn",
                         "heben": "lift", "öffnen": "open", "schließen": "close", "warten": "wait",
                         "vorwarts": "forward", "zuruck": "back", "offnen": "open", "schliessen": "close"}
KEYWORDS = ("guide", "führen", "fuhren")
SIDES = {"left": 1, "links": 1, "right": -1, "rechts": -1}
"""``turn left N`` / ``turn right N`` (degrees either way; a turn to the left is positive)."""
_LIMITS = {"forward": (-MAX_DISTANCE, MAX_DISTANCE, "metres"), "back": (-MAX_DISTANCE, MAX_DISTANCE, "metres"),
           "turn": (-MAX_TURN, MAX_TURN, "degrees"), "lift": (0.0, LIFT_TOP, "metres (absolute height)"),
           "wait": (0.0, MAX_WAIT, "seconds"), "hand": (0.0, MAX_WAIT, "seconds")}


@dataclass(frozen=True, slots=True)
class Feedback:
    """What a person steering the robot needs to know, from the simulation: where the ball and
    the bin are from the hand (the grasp point between the fingers), how high the lift is, the
    hand open or closed, and what the last command did."""

    ball_distance: float  # m, in the floor plane
    ball_bearing: float   # degrees to turn to face it, counter-clockwise (positive: to the left)
    ball_height: float    # m the ball's centre is above the hand's (negative: below it)
    bin_distance: float
    bin_bearing: float
    lift: float           # m above grasp height
    hand_open: bool
    last: GuideCommand | None
    moved: float          # m the base moved in the last command
    turned: float         # degrees it turned
    lifted: float         # m the lift moved
    gripped: float        # m the fingers closed (negative: opened)
    ball_under_arm: bool = False
    """The ball is between the body and the hand (passed under the raised hand, pushed by the
    body): ahead of the robot, but behind the hand, so driving on only pushes it."""
    stopped: bool = False
    """The last command was stopped before its end (Ctrl-C: ``Guide.stop_when``)."""
    ball_held: bool = False
    """Both fingers touch the ball (``World.ball_grasped``): held, however well."""


def is_guide_line(text: str) -> bool:
    """Whether a script or prompt line is a guiding command (starts with ``guide``/``führen``)."""
    words = text.split()
    return bool(words) and words[0].lower() in KEYWORDS


def parse_guide_line(text: str, path: str | Path | None = None, line: int | None = None) -> GuideCommand:
    """``guide forward 0.4`` and the like as a command; a one-line ``FormatError`` otherwise."""
    def fail(message: str) -> FormatError:
        return FormatError(message, path if path is not None else "<guide>", line)

    words = text.split()
    if not words or words[0].lower() not in KEYWORDS:
        raise fail(f"not a guiding command: {text.strip()!r} (it starts with 'guide')")
    if len(words) < 2 or words[1].lower() not in VERBS:
        raise fail(f"guide what? say one of {', '.join(sorted(set(VERBS.values())))} (got {' '.join(words[1:])!r})")
    verb = VERBS[words[1].lower()]
    arguments = words[2:]
    side = SIDES.get(arguments[0].lower()) if verb == "turn" and arguments else None
    if side is not None:  # "turn right 150": the feedback says "150° to my right"
        arguments = arguments[1:]
    if verb == "hand" and not arguments:
        return GuideCommand("hand", 0.0)  # follow the hand until it lets go
    if verb in ("open", "close"):
        if arguments:
            raise fail(f"'guide {verb}' takes no number (got {' '.join(arguments)!r})")
        return GuideCommand(verb)
    low, high, unit = _LIMITS[verb]
    if len(arguments) != 1:
        raise fail(f"'guide {words[1]}' needs one number in {unit} (got {len(arguments)} words after it)")
    try:
        amount = float(arguments[0].replace(",", "."))
    except ValueError:
        raise fail(f"'guide {words[1]}' needs a number in {unit}, got {arguments[0]!r}") from None
    if not math.isfinite(amount) or not low <= amount <= high:
        raise fail(f"'guide {words[1]}' takes {low:g} to {high:g} {unit}, got {arguments[0]}")
    if verb == "back":
        return GuideCommand("forward", -amount)
    if side is not None:
        return GuideCommand(verb, side * abs(amount))
    return GuideCommand(verb, amount)


UNDER_ARM = 0.03
"""m: a ball this far behind the hand, along the heading, and in front of the robot's centre is under the arm."""
UNDER_ARM_WIDTH = 0.2
"""m either side of the heading: the body's half-width and the ball's radius (a ball pushed by it)."""


def _under_arm(base: tuple[float, float, float], hand: list[float], ball: list[float]) -> bool:
    """Whether ``ball`` lies between the robot's centre and its hand, along its heading, and in front
    of the body: "ahead" of the robot but behind the hand."""
    x, y, yaw = base
    ahead, across = math.cos(yaw), math.sin(yaw)
    from_hand = (ball[0] - hand[0]) * ahead + (ball[1] - hand[1]) * across
    from_centre = (ball[0] - x) * ahead + (ball[1] - y) * across
    sideways = abs(-(ball[0] - x) * across + (ball[1] - y) * ahead)
    return from_hand < -UNDER_ARM and from_centre > 0 and sideways < UNDER_ARM_WIDTH


def _profile(remaining: float, speed: float, top: float, acceleration: float, dt: float) -> float:
    """The next speed towards a target ``remaining`` away (signed): accelerate, cruise, brake."""
    brake = math.sqrt(2 * acceleration * abs(remaining))
    wanted = math.copysign(min(top, brake), remaining)
    step = acceleration * dt
    return max(speed - step, min(speed + step, wanted))


class Guide:
    """Drives a ``World`` by guiding primitives and records a ``Sample`` every control period."""

    def __init__(self, world: World, listener: Callable[[Sample], object] | None = None,
                 observer: Observer | None = None, frames: FrameClock | None = None):
        self.world = world
        self.listener = listener
        self.frames = frames or FrameClock(world, observer)  # a session's clock paces and redraws too
        self.samples: list[Sample] = []
        self.lift_target = world.lift_height()
        self.finger_target = FINGER_CLOSED if world.finger_closure() > FINGER_CLOSED / 2 else FINGER_OPEN
        self._dt = CONTROL_STEPS * world.model.opt.timestep
        self.doing = "guide"  # what the recording shows as running: the command being carried out
        self._robot: tuple[int, ...] | None = None  # the robot's bodies, found on the first hand period
        self.last: GuideCommand | None = None  # the command run last, for ``feedback``
        self.stop_when: Callable[[], bool] = _never
        """Polled every control period of a command (the terminal's Ctrl-C): true stops it where it is."""
        self.stopped = False  # the last command was stopped before its end
        self._started = self.sample((0.0, 0.0))  # the sample it started from

    # --- sampling --------------------------------------------------------------------------

    def sample(self, drive: tuple[float, float]) -> Sample:
        w = self.world
        ball, bin_ = w.ball_position(), w.bin_position()
        sample = Sample(w.sim_time, w.state(), w.base_pose(), w.lift_height(), w.finger_closure(),
                        (float(ball[0]), float(ball[1]), float(ball[2])),
                        (float(bin_[0]), float(bin_[1]), float(bin_[2])),
                        (drive[0], drive[1], self.lift_target, self.finger_target))
        self.samples.append(sample)
        if self.listener is not None:
            self.listener(sample)
        self.frames(self.doing)
        return sample

    def _period(self, forward: float, turn: float) -> None:
        """One control period under the given base command, then a sample."""
        if self.stop_when():
            raise _Stopped
        self.world.drive(forward, turn)
        self.world.set_lift(self.lift_target)
        self.world.set_fingers(self.finger_target)
        self.world.step(CONTROL_STEPS)
        self.sample((forward, turn))

    # --- primitives ------------------------------------------------------------------------

    def feedback(self) -> Feedback:
        """Where things are now, and what the last command (``run``) did."""
        w = self.world
        hand, ball, bin_ = ([float(v) for v in p] for p in (w.grasp_point(), w.ball_position(), w.bin_position()))
        x, y, yaw = w.base_pose()

        def seen(point: list[float]) -> tuple[float, float]:
            """Distance from the hand, bearing from the robot's centre: turning by it faces the hand to the point."""
            bearing = math.degrees(_wrap(math.atan2(point[1] - y, point[0] - x) - yaw))
            return math.hypot(point[0] - hand[0], point[1] - hand[1]), bearing

        (ball_distance, ball_bearing), (bin_distance, bin_bearing) = seen(ball), seen(bin_)
        start = self._started
        hand_height = hand[2] + w.lift_height()  # the grasp point is at the lift's bottom: the lift raises the hand
        return Feedback(ball_distance, ball_bearing, ball[2] - hand_height, bin_distance, bin_bearing,
                        w.lift_height(), not self._hand_closed(), self.last,  # as space toggles it
                        math.hypot(x - start.base[0], y - start.base[1]),
                        math.degrees(_wrap(yaw - start.base[2])), w.lift_height() - start.lift,
                        w.finger_closure() - start.fingers,  # a ball in the bin or in the hand is not to be fetched
                        _under_arm((x, y, yaw), hand, ball) and not w.ball_placed() and not w.ball_grasped(),
                        self.stopped, w.ball_grasped())

    def _hand_closed(self) -> bool:
        """Whether the hand is closed as the teacher last made it (not as the fingers stand: round
        a held ball they give a little)."""
        return self.finger_target > FINGER_CLOSED / 2

    def run(self, command: GuideCommand) -> None:
        """Carry out one command to its end."""
        self.last, self._started = command, self.samples[-1]
        actions: dict[str, Callable[[], None]] = {
            "forward": lambda: self.forward(command.amount), "turn": lambda: self.turn(command.amount),
            "lift": lambda: self.lift(command.amount), "open": self.open, "close": self.close,
            "wait": lambda: self.wait(command.amount), "hand": lambda: self.by_hand(command.amount)}
        self.doing, self.stopped = str(command), False
        try:
            actions[command.verb]()
        except _Stopped:
            self.stopped = True
            self._stop()

    def forward(self, metres: float) -> None:
        """Move along the heading held at the start (negative: back up)."""
        x0, y0, yaw0 = self.world.base_pose()
        speed, best, since = 0.0, abs(metres), 0.0
        while True:
            x, y, yaw = self.world.base_pose()
            remaining = metres - ((x - x0) * math.cos(yaw0) + (y - y0) * math.sin(yaw0))
            if abs(remaining) < DONE_DISTANCE and abs(speed) < 0.05:
                break
            since = 0.0 if abs(remaining) < best - 0.001 else since + self._dt
            best = min(best, abs(remaining))
            if since > BLOCKED_SECONDS:
                break
            speed = _profile(remaining, speed, SPEED, ACCELERATION, self._dt)
            self._period(speed, 4.0 * _wrap(yaw0 - yaw))
        self._stop()

    def turn(self, degrees: float) -> None:
        """Turn on the spot by ``degrees`` (counter-clockwise positive)."""
        target = math.radians(degrees)
        last = self.world.base_pose()[2]
        turned, rate, best, since = 0.0, 0.0, abs(target), 0.0
        while True:
            yaw = self.world.base_pose()[2]
            turned += _wrap(yaw - last)
            last = yaw
            remaining = target - turned
            if abs(remaining) < DONE_ANGLE and abs(rate) < 0.05:
                break
            since = 0.0 if abs(remaining) < best - 0.002 else since + self._dt
            best = min(best, abs(remaining))
            if since > BLOCKED_SECONDS:
                break
            rate = _profile(remaining, rate, TURN_SPEED, TURN_ACCELERATION, self._dt)
            self._period(0.0, rate)
        self._stop()

    def lift(self, height: float) -> None:
        """Move the lift to ``height`` (metres, absolute) at a steady speed."""
        height = min(max(height, 0.0), LIFT_TOP)
        best, since = abs(height - self.world.lift_height()), 0.0
        while True:
            error = height - self.world.lift_height()
            if abs(error) < DONE_LIFT and abs(self.lift_target - height) < 1e-9:
                break
            since = 0.0 if abs(error) < best - 0.0005 else since + self._dt
            best = min(best, abs(error))
            if since > BLOCKED_SECONDS:
                break
            step = LIFT_SPEED * self._dt
            self.lift_target = max(self.lift_target - step, min(self.lift_target + step, height))
            self._period(0.0, 0.0)

    def open(self) -> None:
        self._fingers(FINGER_OPEN)

    def close(self) -> None:
        self._fingers(FINGER_CLOSED)

    def _fingers(self, closure: float) -> None:
        """Move the fingers towards ``closure`` until they get there or something stops them."""
        last, still = self.world.finger_closure(), 0.0
        while True:
            arrived = abs(self.finger_target - closure) < 1e-9
            if arrived and (abs(last - closure) < 0.001 or still >= BLOCKED_SECONDS / 2):
                break
            step = FINGER_SPEED * self._dt
            self.finger_target = max(self.finger_target - step, min(self.finger_target + step, closure))
            if closure > FINGER_OPEN:
                self.world.localise_by_touch()  # a hand closing on something feels it
            self._period(0.0, 0.0)
            now = self.world.finger_closure()
            still = still + self._dt if abs(now - last) < 0.0005 else 0.0
            last = now

    def wait(self, seconds: float) -> None:
        """Hold still for ``seconds`` of simulated time (the world goes on: a ball rolls)."""
        for _ in range(round(seconds / self._dt)):
            self._period(0.0, 0.0)

    def by_hand(self, seconds: float) -> None:
        """Follow a hand on the robot for ``seconds`` of simulated time."""
        for _ in range(round(seconds / self._dt)):
            self.hand_period()
        self._stop()

    def hand_period(self) -> None:
        """One control period following a hand on the robot: the external force and torque on
        its bodies (the MuJoCo viewer's Ctrl+drag, or ``World.push_base``; ``teach.sim.hand``)
        set its speed and turn rate, as a compliant robot follows the hand that guides it."""
        from teach.sim.hand import robot_bodies, robot_wrench

        if self._robot is None:
            self._robot = robot_bodies(self.world)
        fx, fy, torque = robot_wrench(self.world, self._robot)
        yaw = self.world.base_pose()[2]
        along = fx * math.cos(yaw) + fy * math.sin(yaw)
        forward = max(-SPEED, min(SPEED, along / HAND_DAMPING))
        turn = max(-TURN_SPEED, min(TURN_SPEED, torque / HAND_TURN_DAMPING))
        # the hand is measured, not felt: only the drives move the robot (admittance control), so the
        # viewer's stiff spring cannot fling it; the force stays for the next period's reading
        rows = list(self._robot)
        xfrc = self.world.data.xfrc_applied
        held = xfrc[rows].copy()
        xfrc[rows] = 0.0
        self.world.drive(forward, turn)
        self.world.set_lift(self.lift_target)
        self.world.set_fingers(self.finger_target)
        self.world.step(CONTROL_STEPS)
        xfrc[rows] = held
        self.sample((forward, turn))

    @property
    def period(self) -> float:
        """Seconds of simulated time per control period."""
        return self._dt

    def _stop(self) -> None:
        self.world.drive(0.0, 0.0)

    # --- keys ------------------------------------------------------------------------------

    def key(self, name: str) -> GuideCommand | None:
        """The command a key of the terminal's guide mode means (None: not a guiding key)."""
        commands = {"up": GuideCommand("forward", KEY_STEP), "down": GuideCommand("forward", -KEY_STEP),
                    "left": GuideCommand("turn", KEY_TURN), "right": GuideCommand("turn", -KEY_TURN),
                    "pageup": GuideCommand("lift", min(LIFT_TOP, round(self.lift_target + KEY_LIFT, 3))),
                    "pagedown": GuideCommand("lift", max(0.0, round(self.lift_target - KEY_LIFT, 3))),
                    "space": GuideCommand("open" if self._hand_closed() else "close")}
        return commands.get(name)


class _Stopped(Exception):
    """A command stopped where it was (``Guide.stop_when``)."""


def _never() -> bool:
    return False
