"""One observer hook for everything a session does (ticks, scene, dialogue, learner events).

The session machine, the worlds and the simulation's executor report to an ``Observer``;
``teach.observe.rerun_writer.RerunLogger`` implements it with rerun, tests can collect events,
and the default does nothing. Callers set the clock once per step with ``set_time``. An
observer only observes: pacing, run limits and viewer redraws are the world's own business.

Two channels are typed for their consumers: the tree channel (``on_status_change``: time,
node, previous status, status, as BehaviorTree.CPP's ``StatusChangeLogger`` callback has them),
derived once from the ticks by the fan-out ``Observers`` for the observers that listen; and
the session channel (``on_session_event``: the session journal's events, frozen dataclasses,
as they are journalled).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, ClassVar, Protocol

from teach.observe.status_changes import StatusChanges

if TYPE_CHECKING:
    from teach.bt.btcpp_status import BtStatus
    from teach.bt.nodes import Node
    from teach.bt.tick import TickResult
    from teach.demos import Demonstration
    from teach.domain import Domain
    from teach.observe.scene import SceneShape


class SessionEvent(Protocol):
    """A session journal event (``teach.session.journal``): a frozen dataclass with a ``kind``."""

    kind: ClassVar[str]
    __dataclass_fields__: ClassVar[dict[str, Any]]


class Observer:
    """Receives session events; every method is optional (the base class ignores them)."""


    def set_time(self, step: int | None, sim_time: float | None = None) -> None:
        """Advance the clocks: ``step`` counts session steps (None keeps the session's step),
        ``sim_time`` is simulated seconds."""

    def on_domain(self, domain: Domain) -> None:
        """The vocabulary, logged first so a recording explains itself."""

    def on_tree(self, generation: int, tree: Node, xml: str, reason: str) -> None:
        """A new tree generation (``reason`` says what produced it)."""

    def on_run_start(self, tree: Node) -> None:
        """A run of the learned tree ``tree`` begins (its ticks follow)."""

    def on_run_end(self, outcome: str, actions: int) -> None:
        """The run ended with ``outcome`` (an ``Outcome`` value) after ``actions`` actions."""

    def on_tick(self, tree: Node, result: TickResult) -> None:
        """One tick: root status, running action, and the statuses of visited nodes."""

    def on_status_change(self, time: float, node: Node, previous: BtStatus, status: BtStatus) -> None:
        """The tree channel: one node of the running tree changed status as BehaviorTree.CPP's would
        (``time``: seconds since the run's first tick). Derived once, by ``Observers``."""

    def on_session_event(self, event: SessionEvent) -> None:
        """The session channel: an event the session journalled, as journalled."""

    def on_state(self, state: Mapping[str, bool], action: str | None) -> None:
        """The symbolic state and the action running in it."""

    def on_scene(self, shapes: Sequence[SceneShape]) -> None:
        """The 3D scene's shapes at the current sim time."""

    def on_camera(self, image: Any, camera: str = "robot") -> None:
        """A camera image (H×W×3 uint8) at the current sim time: the robot's own ("robot") or
        the room's fixed overview ("overview")."""

    def on_dialogue(self, speaker: str, text: str, budget_left: int | None = None) -> None:
        """A line of the dialogue; ``speaker`` is "teacher" or "robot"."""

    def on_demonstration(self, name: str, demo: Demonstration, domain: Domain) -> None:
        """A finished demonstration, as saved."""

    def on_question(self, question: str, budget_left: int) -> None:
        """The robot asks a clarifying question."""

    def on_answer(self, question: str, answer: str, change: str) -> None:
        """The teacher's answer and what it changed in the tree."""

    def on_learner(self, event: str, detail: str, removed: Sequence[str] = (), learner: str = "") -> None:
        """What a demonstration ("specialize") or an answer ("answer") changed, in words;
        ``removed`` names the guards it removed, ``learner`` the learner that learned it."""

    def on_replay(self, reproduced: int, total: int, lenient: bool = False) -> None:
        """Replay of all demonstrations so far against the current tree."""

    def on_external(self, name: str) -> None:
        """An external action (perturbation) nobody in the tree caused."""

    def checkpoint(self) -> None:
        """Make everything reported so far survive a crash; called before each new prompt."""

    def close(self) -> None:
        """Flush and release resources."""


class Observers(Observer):
    """Fan each event out to several observers, in order."""

    def __init__(self, *observers: Observer):
        self.observers = [o for o in observers if o is not None]
        self._changes = StatusChanges(self.on_status_change)

    def _tree_listeners(self) -> list[Observer]:
        """The observers that take the tree channel (deriving it costs a BehaviorTree.CPP tick)."""
        return [o for o in self.observers if type(o).on_status_change is not Observer.on_status_change]


    def set_time(self, step: int | None, sim_time: float | None = None) -> None:
        self._changes.set_time(sim_time)
        for o in self.observers:
            o.set_time(step, sim_time)

    def on_domain(self, domain: Domain) -> None:
        for o in self.observers:
            o.on_domain(domain)

    def on_tree(self, generation: int, tree: Node, xml: str, reason: str) -> None:
        for o in self.observers:
            o.on_tree(generation, tree, xml, reason)

    def on_run_start(self, tree: Node) -> None:
        for o in self.observers:
            o.on_run_start(tree)
        if self._tree_listeners():
            self._changes.run_starts(tree)

    def on_run_end(self, outcome: str, actions: int) -> None:
        self._changes.run_ends(outcome, actions)  # its last changes before the run's end
        for o in self.observers:
            o.on_run_end(outcome, actions)

    def on_tick(self, tree: Node, result: TickResult) -> None:
        for o in self.observers:
            o.on_tick(tree, result)
        self._changes.tick(result)

    def on_status_change(self, time: float, node: Node, previous: BtStatus, status: BtStatus) -> None:
        for o in self._tree_listeners():
            o.on_status_change(time, node, previous, status)

    def on_session_event(self, event: SessionEvent) -> None:
        for o in self.observers:
            o.on_session_event(event)

    def on_state(self, state: Mapping[str, bool], action: str | None) -> None:
        for o in self.observers:
            o.on_state(state, action)

    def on_scene(self, shapes: Sequence[SceneShape]) -> None:
        for o in self.observers:
            o.on_scene(shapes)

    def on_camera(self, image: Any, camera: str = "robot") -> None:
        for o in self.observers:
            o.on_camera(image, camera)

    def on_dialogue(self, speaker: str, text: str, budget_left: int | None = None) -> None:
        for o in self.observers:
            o.on_dialogue(speaker, text, budget_left)

    def on_demonstration(self, name: str, demo: Demonstration, domain: Domain) -> None:
        for o in self.observers:
            o.on_demonstration(name, demo, domain)

    def on_question(self, question: str, budget_left: int) -> None:
        for o in self.observers:
            o.on_question(question, budget_left)

    def on_answer(self, question: str, answer: str, change: str) -> None:
        for o in self.observers:
            o.on_answer(question, answer, change)

    def on_learner(self, event: str, detail: str, removed: Sequence[str] = (), learner: str = "") -> None:
        for o in self.observers:
            o.on_learner(event, detail, removed, learner)

    def on_replay(self, reproduced: int, total: int, lenient: bool = False) -> None:
        for o in self.observers:
            o.on_replay(reproduced, total, lenient)

    def on_external(self, name: str) -> None:
        for o in self.observers:
            o.on_external(name)

    def checkpoint(self) -> None:
        for o in self.observers:
            o.checkpoint()

    def close(self) -> None:
        self._changes.run_ends(None, 0)
        for o in self.observers:
            o.close()
