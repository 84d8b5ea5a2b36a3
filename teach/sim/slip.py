"""Slips: the ball leaving the gripper during a skill that should have kept it.

A slip is the world's event, not part of the robot's action: the skill is halted the moment
the hold is lost and the event is recorded as an external action (-1). Whether a skill should
keep the hold comes from the domain's declared action model: an action whose ``pre`` and
``ram`` do not mention the hold neither needs it (to put the ball somewhere, as PlaceBall
does) nor makes or ends it, so losing it during that action is not the action's doing. An
action without any model says nothing about its intent, and is not watched.
"""

from __future__ import annotations

from collections.abc import Callable

from teach.domain import Domain, State
from teach.sim.world import World

HOLD = "BallGrasped"  # the condition the fingers' touch computes (World.ball_grasped)
SLIP = "ball_slipped"
SLIP_EN = "the ball fell out of the gripper"
SLIP_DE = "der Ball ist aus dem Greifer gefallen"
LOST_PERIODS = 5      # control periods (0.1 s) without touch before the hold counts as lost: contacts flicker
FALL_SECONDS = 2.0    # at most this long to let the dropped ball come to rest
REST_SPEED = 0.05     # m/s


def keeps_hold(domain: Domain, action: str) -> bool:
    """Whether ``action``'s declared model says it must not lose the hold (see the module's docstring)."""
    definition = domain.action(action)
    literals = definition.pre + definition.ram
    return bool(literals) and all(literal.name != HOLD for literal in literals)


class SlipWatch:
    """Watches one skill: armed when the ball is held as the skill starts and the action keeps hold."""

    def __init__(self, world: World, action: str):
        self.world = world
        held = HOLD in world.domain.condition_names and world.ball_grasped()
        self._last_held: State | None = world.state() if held and keeps_hold(world.domain, action) else None
        self._misses = 0

    def check(self) -> State | None:
        """After a control period: once the hold is lost, the last state with the ball held; else None."""
        if self._last_held is None:
            return None
        if self.world.ball_grasped():
            self._last_held, self._misses = self.world.state(), 0
            return None
        self._misses += 1
        return self._last_held if self._misses >= LOST_PERIODS else None

    def lost(self) -> State | None:
        """Once the skill has ended: the last state with the ball held if it is not held now."""
        if self._last_held is None or self.world.ball_grasped():
            return None
        return self._last_held


def let_fall(world: World, frame: Callable[[], None]) -> State:
    """Let the dropped ball fall and roll until it rests (``frame`` after each tenth of a second);
    the state then."""
    for _ in range(round(FALL_SECONDS / 0.1)):
        world.settle(0.1)
        frame()
        if world.ball_speed() < REST_SPEED:
            break
    return world.state()
