"""One observer hook for everything a session does (ticks, scene, dialogue, learner events).

The session manager, the simulation's executor and the learners report to an ``Observer``;
``teach.log.RerunLogger`` implements it with rerun, tests can collect events, and the default
does nothing. Callers set the clock once per step with ``set_time``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from teach.bt.nodes import Node
    from teach.bt.tick import TickResult
    from teach.demos import Demonstration
    from teach.domain import Domain
    from teach.observe.scene import SceneShape


class Observer:
    """Receives session events; every method is optional (the base class ignores them)."""

    def set_time(self, step: int | None, sim_time: float | None = None) -> None:
        """Advance the clocks: ``step`` counts session steps (None keeps the session's step),
        ``sim_time`` is simulated seconds."""

    def on_domain(self, domain: "Domain") -> None:
        """The vocabulary, logged first so a recording explains itself."""

    def on_tree(self, generation: int, tree: "Node", xml: str, reason: str) -> None:
        """A new tree generation (``reason`` says what produced it)."""

    def on_tick(self, tree: "Node", result: "TickResult") -> None:
        """One tick: root status, running action, and the statuses of visited nodes."""

    def on_state(self, state: Mapping[str, bool], action: str | None) -> None:
        """The symbolic state and the action running in it."""

    def on_scene(self, shapes: Sequence["SceneShape"]) -> None:
        """The 3D scene's shapes at the current sim time."""

    def on_camera(self, image: Any) -> None:
        """The robot's camera image (H×W×3 uint8) at the current sim time."""

    def on_dialogue(self, speaker: str, text: str, budget_left: int | None = None) -> None:
        """A line of the dialogue; ``speaker`` is "teacher" or "robot"."""

    def on_demonstration(self, name: str, demo: "Demonstration", domain: "Domain") -> None:
        """A finished demonstration, as saved."""

    def on_question(self, question: str, budget_left: int) -> None:
        """The robot asks a clarifying question."""

    def on_answer(self, question: str, answer: str, change: str) -> None:
        """The teacher's answer and what it changed in the tree."""

    def on_learner(self, event: str, detail: str, removed: Sequence[str] = ()) -> None:
        """A learner event: "specialize", "prune", "order", ...; ``removed`` names removed nodes."""

    def on_replay(self, reproduced: int, total: int, lenient: bool = False) -> None:
        """Replay of all demonstrations so far against the current tree."""

    def on_external(self, name: str) -> None:
        """An external action (perturbation) nobody in the tree caused."""

    def checkpoint(self) -> None:
        """Make everything reported so far survive a crash; called before each new prompt."""

    def close(self) -> None:
        """Flush and release resources."""


class Observers(Observer):
    """Fan one event out to several observers."""

    def __init__(self, *observers: Observer):
        self.observers = [o for o in observers if o is not None]

    def __getattribute__(self, name: str) -> Any:
        if name.startswith(("on_", "set_time", "checkpoint", "close")):
            targets = object.__getattribute__(self, "observers")

            def fan_out(*args: Any, **kwargs: Any) -> None:
                for target in targets:
                    getattr(target, name)(*args, **kwargs)

            return fan_out
        return object.__getattribute__(self, name)
