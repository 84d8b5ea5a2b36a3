"""Any domain with an action model (``pre``/``ram`` in domain.toml), simulated symbolically:
an action whose preconditions hold makes its ramifications true.

A new start (``reset``) is the state where nothing holds, the ball task's start. In a domain where
nothing can be done there (blocksworld: no block on the table, the hand neither empty nor full)
that start is impossible; there a new start is a random walk through the action model from a
situation the teacher set up (``start …``), so it is one the world can be in."""

from __future__ import annotations

import random
from collections.abc import Callable

from teach.bt.nodes import Node, Status
from teach.bt.run import Outcome
from teach.bt.tick import always_running
from teach.domain import Domain, State
from teach.observe.hook import Observer
from teach.symbolic import apply_action, assign, missing_preconditions, possible_actions
from teach.world.offline import OfflineWorld
from teach.world.protocol import ActResult, RunResult, WorldEvent

WALK = 8
"""The most random steps a new start walks from a situation the teacher set up."""


class SymbolicWorld(OfflineWorld):
    """Any domain with an action model, simulated symbolically (no physics)."""

    walks_to_a_start = True
    """Where nothing can be done in the state where nothing holds, a new start walks from a
    situation the teacher set up (module docstring)."""
    events = {
        "toggle": (("change something",), ("etwas ändern",)),
    }

    def __init__(self, domain: Domain, seed: int = 0, observer: Observer | None = None):
        if not domain.has_model:
            from teach.errors import DomainError
            raise DomainError("the symbolic world needs an action model (pre/ram) in the domain file", domain.path)
        super().__init__(domain)
        self.observer = observer or Observer()
        self._rng = random.Random(seed)
        self._set_up: list[State] = []
        """Situations the teacher set up, in order: where a new start may begin."""

    def arrange(self, state: State) -> None:
        super().arrange(state)
        if tuple(state) not in self._set_up:
            self._set_up.append(tuple(state))

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self._rng = random.Random(seed)
        super().reset(seed)
        if self.walks_to_a_start and self._set_up and not possible_actions(self.domain, self._state):
            state = self._rng.choice(self._set_up)
            for _ in range(self._rng.randrange(WALK + 1)):
                possible = possible_actions(self.domain, state)
                if not possible:
                    break
                state = apply_action(self.domain, state, self._rng.choice(possible))
            self._state = state

    def act(self, action: str) -> ActResult:
        before = self._state
        missing = missing_preconditions(self.domain, before, action)
        if missing:
            return ActResult(False, before, before, "not possible now: needs " + ", ".join(map(str, missing)))
        self._state = apply_action(self.domain, before, action)
        return ActResult(True, before, self._state)

    def perturb(self, event: str) -> ActResult:
        """Flip one random condition: something outside the robot changed the world."""
        before = self._state
        index = self._rng.randrange(len(before))
        self._state = assign(before, [(index, not before[index])])
        return ActResult(True, before, self._state, f"{self.domain.conditions[index].name} changed")

    def run(self, tree: Node, max_actions: int = 20, interrupt: Callable[[], bool] | None = None,
            stop_after: int | None = None, on_action: Callable[[str], None] | None = None,
            on_event: Callable[[WorldEvent], None] | None = None) -> RunResult:
        names = self.domain.condition_names
        result = RunResult(Outcome.TIMEOUT)
        for _ in range(max_actions):
            ticked = self.ticker(tree, dict(zip(names, self._state, strict=True)), always_running)
            self.observer.on_tick(tree, ticked)
            if ticked.status is not Status.RUNNING or ticked.action is None:
                result.outcome = Outcome.SUCCESS if ticked.status is Status.SUCCESS else Outcome.FAILURE
                break
            if interrupt is not None and interrupt() or stop_after is not None and len(result.steps) >= stop_after:
                result.outcome = Outcome.INTERRUPTED
                break
            before = self._state
            if on_action is not None:
                on_action(ticked.action)
            if not self.act(ticked.action).ok:
                result.outcome = Outcome.FAILURE
                break
            result.steps.append((before, ticked.action))
        result.final_state = self._state
        return result
