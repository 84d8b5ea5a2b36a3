"""The teacher's hand in the MuJoCo viewer: which body a Ctrl+drag pushes, and what came of it.

The viewer (``mujoco.viewer.launch_passive``) turns a Ctrl+right-drag on a body into a spring
force towards the mouse, and a Ctrl+left-drag into a torque, written to ``data.xfrc_applied``
afresh on every ``sync``. Nothing here talks to the viewer: it reads those forces back, so a
push set by any other means (``World.push_base``, a test) counts the same.

A hand on any body of the robot (base, carriage, fingers) guides the robot: ``robot_wrench``
carries the force to the base, with the turn it makes about the base's axis, which
``Guide.by_hand`` follows. A hand on the ball or the bin moves the thing itself, which is an
external action (-1) of the demonstration: ``ObjectWatch`` notes the state when the push
begins and reports a ``Moved`` once the hand is off and the thing has come to rest.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from teach.domain import State
from teach.sim.world import World

OBJECTS = ("ball", "bin")      # the things a teacher can move that the robot does not
PUSH_EPSILON = 1e-6            # N (or N m): less than this is no hand on the body
REST_SPEED = 0.02              # m/s: slower than this the thing lies still
REST_SECONDS = 0.3             # ... and for this long it has come to rest


def robot_bodies(world: World) -> tuple[int, ...]:
    """The ids of the robot's bodies: the base and everything mounted on it."""
    model = world.model
    base = model.body("base").id
    return tuple(b for b in range(model.nbody) if b == base or _descends(model, b, base))


def _descends(model: mujoco.MjModel, body: int, ancestor: int) -> bool:
    while body > 0:
        body = int(model.body_parentid[body])
        if body == ancestor:
            return True
    return False


def robot_wrench(world: World, bodies: tuple[int, ...] | None = None) -> tuple[float, float, float]:
    """The hand's horizontal force on the robot (x, y, N) and its turn about the base's vertical
    axis (N m), summed over the robot's bodies (the viewer applies a force at the dragged body's
    centre of mass, so a sideways drag on the gripper turns the robot, as it would a real one)."""
    data = world.data
    base_x, base_y, _ = world.base_pose()
    fx = fy = torque = 0.0
    for body in bodies if bodies is not None else robot_bodies(world):
        f = data.xfrc_applied[body]
        if not np.any(np.abs(f) > PUSH_EPSILON):
            continue
        arm_x, arm_y = float(data.xipos[body][0]) - base_x, float(data.xipos[body][1]) - base_y
        fx, fy = fx + float(f[0]), fy + float(f[1])
        torque += float(f[5]) + arm_x * float(f[1]) - arm_y * float(f[0])
    return fx, fy, torque


def pushed(world: World, body: int) -> bool:
    """Whether a hand is on ``body`` now."""
    return bool(np.any(np.abs(world.data.xfrc_applied[body]) > PUSH_EPSILON))


def body_speed(world: World, body: int) -> float:
    """How fast ``body`` moves (m/s, its origin's linear speed in the world)."""
    velocity = np.zeros(6)
    mujoco.mj_objectVelocity(world.model, world.data, mujoco.mjtObj.mjOBJ_BODY, body, velocity, 0)
    return float(np.linalg.norm(velocity[3:]))


@dataclass(frozen=True, slots=True)
class Moved:
    """The teacher moved a thing: the state from before the hand touched it to when it lay still."""

    thing: str       # "ball" or "bin"
    before: State
    after: State


class ObjectWatch:
    """Watches the ball and the bin for the hand, one ``update`` per control period."""

    def __init__(self, world: World, dt: float):
        self.world, self.dt = world, dt
        self._ids = {thing: world.model.body(thing).id for thing in OBJECTS}
        self._moving: dict[str, tuple[State, float]] = {}  # thing -> (state before the push, seconds at rest)

    @property
    def busy(self) -> bool:
        """A thing is being moved, or has not come to rest since: the robot's own steps wait."""
        return bool(self._moving)

    def touched(self) -> bool:
        """Whether a hand is on the ball or the bin now."""
        return any(pushed(self.world, body) for body in self._ids.values())

    def update(self) -> list[Moved]:
        """The things that came to rest after the hand let go, since the last update."""
        done: list[Moved] = []
        for thing, body in self._ids.items():
            if pushed(self.world, body):
                before = self._moving.get(thing, (self.world.state(), 0.0))[0]
                self._moving[thing] = (before, 0.0)
            elif thing in self._moving:
                before, still = self._moving[thing]
                still = still + self.dt if body_speed(self.world, body) < REST_SPEED else 0.0
                if still + 1e-9 >= REST_SECONDS:
                    del self._moving[thing]
                    done.append(Moved(thing, before, self.world.state()))
                else:
                    self._moving[thing] = (before, still)
        return done

    def begins(self) -> bool:
        """Whether a hand is on a thing that was not being moved before (call before ``update``)."""
        return any(pushed(self.world, body) and thing not in self._moving for thing, body in self._ids.items())

    def settle_now(self) -> list[Moved]:
        """Guidance stops while things still move: each is taken as it is now."""
        done = [Moved(thing, before, self.world.state()) for thing, (before, _) in self._moving.items()]
        self._moving.clear()
        return done
