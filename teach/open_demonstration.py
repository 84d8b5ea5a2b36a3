"""The one demonstration builder: a demonstration while it is being shown.

Steps are numbered from 1 as they are added, each with the words the teacher saw for it (the
session's 'steps' and 'undo' show them; a recorder without a dialogue passes the action's name).
The rules every builder of a demonstration keeps live here once: a world's event is an external
step (-1) with the state before it; an action the world halted (a slip) keeps its own part only
if that part changed anything; a run continued by the teacher keeps the robot's steps and the
events between them; the goal line (0) comes last.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from teach.demos import Demonstration, Step
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, State
from teach.errors import DomainError


@dataclass(frozen=True)
class TakenBack:
    """Steps ``first``.. as they were taken back, so they can be put back unchanged."""

    first: int
    steps: tuple[Step, ...]
    words: tuple[str, ...]


@dataclass(frozen=True)
class WorldEventStep:
    """An event of the world to record as an external step: the state before it, its words."""

    before: State
    words: str


class OpenDemonstration:
    """The steps shown so far (a run's too, when the teacher goes on from where it stopped)."""

    def __init__(self) -> None:
        self.steps: list[Step] = []
        self.words: list[str] = []
        self.robot_steps = 0
        """How many of the steps a run did: while the teacher added none, 'run' tries again instead."""

    @classmethod
    def from_steps(cls, steps: Iterable[tuple[State, int, str]]) -> OpenDemonstration:
        """Steps (state, action, words) as they were shown, e.g. read back from a journal."""
        opened = cls()
        for state, action, words in steps:
            opened.add(state, action, words)
        return opened

    @classmethod
    def from_run(cls, steps: Sequence[tuple[State, int, str]],
                 events: Sequence[tuple[int, WorldEventStep]]) -> OpenDemonstration:
        """A run to be continued as a correction: its steps (state, action, words) with each event
        ``(n, event)`` as an external step after its first n steps. They are the robot's steps."""
        opened = cls()

        def events_after(count: int) -> None:
            for event in (event for after, event in events if after == count):
                opened.add_event(event)

        for number, (state, action, words) in enumerate(steps):
            events_after(number)
            opened.add(state, action, words)
        events_after(len(steps))
        opened.robot_steps = len(opened.steps)
        return opened

    @classmethod
    def continuing(cls, demo: Demonstration) -> OpenDemonstration:
        """A finished demonstration (a run's) opened again: its goal line comes last, so it goes."""
        steps = [(step.state, step.action, "") for step in demo.steps]
        if steps and steps[-1][1] == GOAL_ACTION:
            steps.pop()
        return cls.from_steps(steps)

    def add(self, before: State, action: int, words: str) -> None:
        """The next step: ``action`` was done in state ``before``."""
        self.steps.append(Step(before, action, len(self.steps) + 1))
        self.words.append(words)

    def add_event(self, event: WorldEventStep) -> None:
        """An event of the world (a perturbation, a slip, a hand moving the ball): external (-1)."""
        self.add(event.before, EXTERNAL_ACTION, event.words)

    def halted(self, before: State, action: int, held: State, words: str, events: Sequence[WorldEventStep]) -> bool:
        """An action the world's events stopped when the state was ``held``: its own part is a
        step only if it changed anything (whether it was kept is returned), then each event."""
        kept = held != before
        if kept:
            self.add(before, action, words)
        for event in events:
            self.add_event(event)
        return kept

    def take_back(self, first: int) -> TakenBack:
        """Remove steps ``first``.. (numbered from 1); the first one's state was before them all."""
        taken = TakenBack(first, tuple(self.steps[first - 1:]), tuple(self.words[first - 1:]))
        del self.steps[first - 1:], self.words[first - 1:]
        return taken

    def put_back(self, taken: TakenBack) -> None:
        """Steps taken back, again at the end (where they were, as nothing came after them)."""
        for step, words in zip(taken.steps, taken.words, strict=True):
            self.add(step.state, step.action, words)

    def finish(self, name: str, goal: State | None, path: Path | None = None) -> Demonstration:
        """The demonstration, ending in the goal line when ``goal`` is the state the goal holds in;
        without one it ends with its last action (the CSV format has no line for a state after
        it, so it cannot end with an event). The open steps stay as they are."""
        steps = list(self.steps)
        if goal is not None:
            steps.append(Step(goal, GOAL_ACTION, len(steps) + 1))
        elif steps and steps[-1].action == EXTERNAL_ACTION:
            raise DomainError("a demonstration cannot end with a perturbation unless the goal holds "
                              "(the CSV format needs an action in the state after it)")
        if not steps:
            raise DomainError("nothing recorded: guide at least one action")
        return Demonstration(name, tuple(steps), path)
