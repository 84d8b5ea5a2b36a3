"""Kinesthetic-style recording: the teacher guides the simulated robot, the recorder writes it down.

Every guided action runs its skill to completion; the symbolic state before and after is read
from physics, so a demonstration says what really happened (an approach that leaves the bin
behind shows BinClose dropping). Perturbations and slips become external-action lines (-1). ``done``
adds the goal line (action 0) when the domain's goal holds in the final state; otherwise the
demonstration ends with its last action, as the CSV format has no line for a state after it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from teach.bt.nodes import Status
from teach.demos import Demonstration, Step, next_demo_path, write_demonstration
from teach.domain import EXTERNAL_ACTION, Domain, State, find_domain_file, load_domain
from teach.errors import DomainError, FormatError
from teach.fsutil import atomic_write_text
from teach.observe.hook import Observer
from teach.open_demonstration import OpenDemonstration, WorldEventStep
from teach.sim.perturb import PERTURBATIONS
from teach.sim.skills import FrameClock, run_skill
from teach.sim.slip import SLIP, SlipWatch, let_fall
from teach.sim.world import DOMAIN_FILE, World


@dataclass(frozen=True, slots=True)
class RecordedStep:
    """One recorded transition: like ``teach.demos.Transition`` plus the names and the outcome."""

    before: State
    action: int
    after: State
    name: str
    status: Status | None  # None for a perturbation


class Recorder:
    """Turns guidance (actions and perturbations, one at a time) into a demonstration, built by
    the one demonstration builder (``teach.open_demonstration``) the session uses too."""

    def __init__(self, world: World, observer: Observer | None = None, prefix: Demonstration | None = None):
        self.world = world
        self.domain = world.domain
        self.observer = observer
        self.frames = FrameClock(world, observer)
        self.open = OpenDemonstration.continuing(prefix) if prefix is not None else OpenDemonstration()

    @property
    def steps(self) -> list[Step]:
        return self.open.steps

    def step(self, action: str) -> RecordedStep:
        """Run the skill for ``action`` (a name or phrase) and record (state, action, next state).

        A slip halts the skill (``teach.sim.slip``): its line is kept if it changed anything,
        then the slip's external line (-1) follows, and that is the step returned."""
        definition = self.domain.action(resolve_action(self.domain, action))
        before = self.world.state()
        watch = SlipWatch(self.world, definition.name)
        status = run_skill(self.world, definition.name, self.observer, frames=self.frames,
                           halt_when=lambda: watch.check() is not None)
        held = watch.lost()
        if held is None:
            return self._note(before, definition.id, definition.name, status)
        self.open.halted(before, definition.id, held, definition.name, [WorldEventStep(held, SLIP)])
        if self.observer is not None:
            self.observer.on_external(SLIP)
        let_fall(self.world, lambda: self.frames(None))
        return RecordedStep(held, EXTERNAL_ACTION, self.world.state(), SLIP, None)

    def perturb(self, name: str) -> RecordedStep:
        """Apply a perturbation and record it as an external action (-1)."""
        perturbation = PERTURBATIONS.get(name)
        if perturbation is None:
            raise DomainError(f"unknown perturbation {name!r} (known: {', '.join(PERTURBATIONS)})")
        before = self.world.state()
        perturbation.apply(self.world, self.world.rng)
        if self.observer is not None:
            self.observer.on_external(name)
        self.frames(None)
        self.open.add_event(WorldEventStep(before, name))
        return RecordedStep(before, EXTERNAL_ACTION, self.world.state(), name, None)

    def _note(self, before: State, action: int, name: str, status: Status | None) -> RecordedStep:
        self.open.add(before, action, name)
        return RecordedStep(before, action, self.world.state(), name, status)

    def goal_holds(self) -> bool:
        return self.domain.goal_holds(self.world.state())

    def done(self, name: str = "demo") -> Demonstration:
        """The demonstration so far; its last line is the goal state when the goal holds."""
        return self.open.finish(name, self.world.state() if self.goal_holds() else None)


def resolve_action(domain: Domain, text: str) -> str:
    """An action name from a name or one of its en/de phrases (case-insensitive)."""
    wanted = text.strip().lower()
    for action in domain.actions:
        if wanted == action.name.lower() or wanted in (p.lower() for p in action.said()):
            return action.name
    raise DomainError(f"unknown action {text!r} (known: {', '.join(domain.action_names)})", domain.path)


def record(world: World, script: Sequence[str], observer: Observer | None = None, name: str = "demo") -> Demonstration:
    """Record a whole scripted demonstration: action names/phrases and perturbation names."""
    recorder = Recorder(world, observer)
    for item in script:
        if item in PERTURBATIONS:
            recorder.perturb(item)
        else:
            recorder.step(item)
    return recorder.done(name)


def save_demonstration(demo: Demonstration, folder: str | Path, domain: Domain | None = None,
                       prefix: str = "demo") -> Path:
    """Write ``demo`` atomically as the next ``<prefix>-NNN.csv`` in ``folder``; a folder with no
    domain file in it or its parent gets a copy of the domain's, so the set reads on its own."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    try:
        existing = find_domain_file(folder)
    except FormatError:
        source = domain.path if domain is not None and domain.path is not None else DOMAIN_FILE
        atomic_write_text(folder / "domain.toml", Path(source).read_text(encoding="utf-8"))
    else:
        theirs = load_domain(existing)
        ours = domain if domain is not None else load_domain(DOMAIN_FILE)
        if theirs.condition_names != ours.condition_names or \
                [(a.id, a.name) for a in theirs.actions] != [(a.id, a.name) for a in ours.actions]:
            raise DomainError("this set's domain has other conditions or actions than the simulation's: "
                              "record into another set", existing)
    path = next_demo_path(folder, prefix)
    write_demonstration(path, demo)
    return path
