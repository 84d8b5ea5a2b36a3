"""Perturbations: what the teacher's hand does to the world at any moment (external actions, -1).

They are the only code that moves bodies directly, as a hand would; the robot's conditions
afterwards still come from physics (a knocked ball rolls, a pushed robot slides).

- knock_ball: the ball is knocked up and away (out of the gripper if held) and rolls off.
- take_ball: the ball is taken and put down somewhere the robot cannot see it.
- move_bin: the bin (with a ball inside) is put down at least 0.8 m from the grasp point.
- push_robot: the robot is shoved sideways with 200 N for 0.25 s, and turned.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from teach.sim.world import BALL_RADIUS, World, _far, _polar


@dataclass(frozen=True)
class Perturbation:
    name: str
    en: tuple[str, ...]
    de: tuple[str, ...]
    apply: Callable[[World, np.random.Generator], None]


def _free_spot(world: World, rng: np.random.Generator, ok: Callable[[np.ndarray], bool]) -> np.ndarray:
    """A floor spot clear of the robot and its gripper that satisfies ``ok`` (best effort)."""
    spot = rng.uniform(-1.7, 1.7, 2)
    for _ in range(500):
        if world.clear_of_robot(spot, 0.15) and _far(spot, world.grasp_point()[:2], 0.45) and ok(spot):
            break
        spot = rng.uniform(-1.7, 1.7, 2)
    return spot


def knock_ball(world: World, rng: np.random.Generator) -> None:
    up = 0.1 if world.ball_grasped() else 0.0
    world.put_ball(world.ball_position() + np.array([0.0, 0.0, up]), np.array([*(1.5 * _polar(rng, 1.0, 1.0)), 1.0]))
    for _ in range(20):  # let it fly and roll (at most 2 s)
        world.settle(0.1)
        if world.ball_speed() < 0.05 and world.ball_position()[2] < 0.05:
            break


def take_ball(world: World, rng: np.random.Generator) -> None:
    def hidden(spot: np.ndarray) -> bool:
        world.put_ball(np.array([*spot, BALL_RADIUS]))
        return _far(spot, world.bin_position()[:2], 0.3) and not world.ball_visible()

    world.put_ball(np.array([*_free_spot(world, rng, hidden), BALL_RADIUS]))
    world.settle(0.2)


def move_bin(world: World, rng: np.random.Generator) -> None:
    bin_now, ball = world.bin_position(), world.ball_position()
    carried = world.ball_placed()
    spot = _free_spot(world, rng, lambda s: _far(s, world.grasp_point()[:2], 0.8)
                      and (carried or _far(s, ball[:2], 0.3)))
    world.put_bin(spot)
    if carried:
        world.put_ball(np.array([*(ball[:2] - bin_now[:2] + spot), ball[2]]))
    world.settle(0.3)


def push_robot(world: World, rng: np.random.Generator) -> None:
    world.drive(0.0, 0.0)
    world.push_base(200.0 * _polar(rng, 1.0, 1.0), float(rng.choice([-8.0, 8.0])))
    world.settle(0.25)
    world.push_base(np.zeros(2), 0.0)
    world.settle(0.3)


PERTURBATIONS: dict[str, Perturbation] = {p.name: p for p in (
    Perturbation("knock_ball", ("knock the ball away", "knock the ball out of the hand"),
                 ("den Ball wegstoßen", "den Ball aus der Hand schlagen", "den Ball weggestoßen",
                  "den Ball aus der Hand geschlagen"), knock_ball),
    Perturbation("take_ball", ("take the ball away", "hide the ball"),
                 ("den Ball wegnehmen", "den Ball verstecken", "den Ball weggenommen", "den Ball versteckt"),
                 take_ball),
    Perturbation("move_bin", ("move the bin", "move the bin away"),
                 ("den Eimer verschieben", "den Eimer wegstellen", "den Eimer verschoben", "den Eimer weggestellt"),
                 move_bin),
    Perturbation("push_robot", ("push the robot", "push the robot aside"),
                 ("den Roboter schubsen", "den Roboter wegschieben", "den Roboter geschubst",
                  "den Roboter weggeschoben"), push_robot),
)}
