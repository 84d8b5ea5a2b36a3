"""The world of a session without one: only a state, arranged by the session."""

from __future__ import annotations

from collections.abc import Callable

from teach.bt.nodes import Node
from teach.bt.run import Outcome, Ticker
from teach.bt.tick import tick
from teach.domain import Domain, State
from teach.world.protocol import ActResult, RunResult, WorldEvent


class OfflineWorld:
    """No world at all, only a state: the session learns from demonstration files and answers.
    (``SymbolicWorld`` adds actions to it.)"""

    events: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {}

    def __init__(self, domain: Domain):
        self.domain = domain
        self.ticker: Ticker = tick
        self._state: State = tuple(False for _ in domain.conditions)

    def state(self) -> State:
        return self._state

    def arrange(self, state: State) -> None:
        self._state = tuple(state)

    def can_happen(self, state: State) -> bool:
        """Without a world, or with one of conditions only, every state can happen."""
        return True

    def reset(self, seed: int | None = None) -> None:
        self._state = tuple(False for _ in self.domain.conditions)

    def act(self, action: str) -> ActResult:
        return ActResult(False, self._state, self._state, "this session has no world to act in")

    def perturb(self, event: str) -> ActResult:
        return ActResult(False, self._state, self._state, "this session has no world to act in")

    def run(self, tree: Node, max_actions: int = 20, interrupt: Callable[[], bool] | None = None,
            stop_after: int | None = None, on_action: Callable[[str], None] | None = None,
            on_event: Callable[[WorldEvent], None] | None = None) -> RunResult:
        return RunResult(Outcome.FAILURE, [], self._state)

    def close(self) -> None:
        pass
