"""What a session needs from a world: read and arrange its state, act, perturb and run a tree.

Three worlds implement it: ``OfflineWorld`` (no world, only a state), ``SymbolicWorld`` (an
action model's pre/ram) and ``MujocoWorld`` (the ball-in-bin physics of ``teach.sim``).
``Outcome`` and ``Ticker`` live in ``teach.bt.run`` (the MuJoCo executor below the worlds uses
them too) and are imported here for the worlds' users.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import NamedTuple, Protocol

from teach.bt.nodes import Node
from teach.bt.run import Outcome, Ticker
from teach.domain import Domain, State


class WorldEvent(NamedTuple):
    """Something the world did on its own (an external action, -1): a ball slipping out of the
    gripper in the middle of a skill. The world reports it to its observer when it happens."""

    name: str
    before: State
    after: State
    en: str  # what happened, in the teacher's words
    de: str
    halted: str | None = None  # the robot's action it stopped
    halted_changed: bool = False  # whether that action had changed the state before it stopped


@dataclass(frozen=True)
class ActResult:
    """One action: the state before it and after it; ``events`` happened in the middle of it,
    in order (the first one halted the action: the action's own part ends at its ``before``)."""

    ok: bool
    before: State
    after: State
    message: str = ""
    events: tuple[WorldEvent, ...] = ()

    @property
    def action_after(self) -> State:
        """The state the action itself led to, before any event of the world."""
        return self.events[0].before if self.events else self.after


@dataclass
class RunResult:
    """A run of the learned tree: outcome and the (state, action) steps it executed; ``events``
    happened on their own, each after that many of the steps."""

    outcome: Outcome
    steps: list[tuple[State, str]] = field(default_factory=list)
    final_state: State = ()
    events: list[tuple[int, WorldEvent]] = field(default_factory=list)


class TeachingWorld(Protocol):
    domain: Domain
    ticker: Ticker

    @property
    def events(self) -> Mapping[str, tuple[tuple[str, ...], tuple[str, ...]]]:
        """The events a teacher can cause, each with its English and German phrases."""

    def state(self) -> State: ...

    def arrange(self, state: State) -> None: ...

    def can_happen(self, state: State) -> bool:
        """Whether the world can be in ``state`` at all (no question is asked about one it cannot)."""

    def reset(self, seed: int | None = None) -> None: ...

    def act(self, action: str) -> ActResult: ...

    def perturb(self, event: str) -> ActResult: ...

    def run(self, tree: Node, max_actions: int, interrupt: Callable[[], bool] | None,
            stop_after: int | None = None, on_action: Callable[[str], None] | None = None,
            on_event: Callable[[WorldEvent], None] | None = None) -> RunResult:
        """Tick ``tree`` until it finishes; ``on_action`` hears of every action as it starts,
        ``on_event`` of every event of the world as it happens."""

    def close(self) -> None: ...
