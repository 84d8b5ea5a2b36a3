"""The learner's training set: each distinct state labelled with what the robot must do there.

A strict replay reproduces a demonstration exactly when the tree does the label of each of its
states. A state labelled two ways is a *conflict*: kept as data, the latest label wins until
the teacher decides. Every label also tells the goal learner whether the state is a goal state
or one where the teacher kept acting.

Kept apart from ``teach.learn.learner``, which decides what the labels mean for the model and
the tree; here they are only recorded, indexed by column (``Columns``, for the exception rules
of ``teach.learn.exceptions``) and passed on to the goal.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from teach.domain import State
from teach.learn.goal import GoalLearner
from teach.learn.invariants import Invariants

Answer = str | None
"""An action name, or None: the task is done here (the tree must return SUCCESS)."""


@dataclass
class Situation:
    """A labelled state: the answers allowed there, the latest one, and where they came from."""

    state: State
    allowed: frozenset[Answer]
    answer: Answer
    sources: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class Conflict:
    """One state labelled with different answers; ``labels`` pairs each answer with its source."""

    state: State
    labels: tuple[tuple[Answer, str], ...]


class Labels:
    """The situations by state bitmask, in the order they were labelled, and the conflicts.
    ``recount(state, old, new)`` is told whenever the answers allowed in a state change."""

    def __init__(self, goal: GoalLearner, invariants: Invariants, conditions: int,
                 recount: Callable[[State, frozenset[Answer], frozenset[Answer]], None]):
        self.goal = goal
        self.invariants = invariants
        self.recount = recount
        self.situations: dict[int, Situation] = {}
        self.conflicts: dict[int, list[tuple[Answer, str]]] = {}
        """Per state in conflict, every label it was given with its source."""
        self.columns = Columns(conditions)
        self._view: dict[State, frozenset[Answer]] | None = None

    def view(self) -> dict[State, frozenset[Answer]]:
        """Every labelled state with the answers allowed there (kept until a label changes)."""
        if self._view is None:
            self._view = {s.state: s.allowed for s in self.situations.values()}
        return self._view

    def label(self, mask: int, state: State, answer: Answer, source: str) -> bool:
        """Record a label; True if it starts (or extends) a conflict."""
        situation = self.situations.get(mask)
        if situation is None:
            self.invariants.saw(mask)
            self.situations[mask] = Situation(state, frozenset({answer}), answer, [source])
            self._view = None
            self.columns.add(mask, frozenset({answer}))
            self.recount(state, frozenset(), frozenset({answer}))
            self._feed_goal(mask, frozenset({answer}), source)
            return False
        situation.sources.append(source)
        if answer in situation.allowed:
            if answer is None:
                self.goal.add_goal_state(mask, source)
            return False
        history = self.conflicts.setdefault(mask, [(situation.answer, situation.sources[0])])
        history.append((answer, source))
        self.relabel(mask, situation, frozenset({answer}), answer)
        return True

    def relabel(self, mask: int, situation: Situation, allowed: frozenset[Answer], answer: Answer) -> None:
        """Allow ``allowed`` in the situation ``mask`` from now on, ``answer`` the latest label."""
        old = situation.allowed
        if old == frozenset({None}):
            self.goal.remove_goal_state(mask)
        elif None not in old:
            self.goal.remove_acting_state(mask)
        self.columns.relabel(mask, old, allowed)
        self.recount(situation.state, old, allowed)
        situation.allowed, situation.answer = allowed, answer
        self._view = None
        self._feed_goal(mask, allowed, situation.sources[-1])

    def _feed_goal(self, mask: int, allowed: frozenset[Answer], source: str) -> None:
        if allowed == frozenset({None}):
            self.goal.add_goal_state(mask, source)
        elif None not in allowed:
            self.goal.add_acting_state(mask, source)


class Columns:
    """The labelled situations by column, for building exceptions fast: per condition, a big
    int whose bit j says whether it holds in situation j; per answer, which situations allow
    it. Separating a state from every situation that does not allow its answer is then a few
    popcounts per literal instead of a pass over all situations."""

    def __init__(self, width: int):
        self.width = width
        self.position: dict[int, int] = {}
        self.holds = [0] * width
        self.allows: dict[Answer, int] = {}
        self.everything = 0

    def add(self, mask: int, allowed: frozenset[Answer]) -> None:
        bit = 1 << len(self.position)
        self.position[mask] = len(self.position)
        self.everything |= bit
        for index in range(self.width):
            if mask >> index & 1:
                self.holds[index] |= bit
        for answer in allowed:
            self.allows[answer] = self.allows.get(answer, 0) | bit

    def relabel(self, mask: int, old: frozenset[Answer], new: frozenset[Answer]) -> None:
        bit = 1 << self.position[mask]
        for answer in old:
            self.allows[answer] &= ~bit
        for answer in new:
            self.allows[answer] = self.allows.get(answer, 0) | bit

    def firing(self, mask: int, value: int) -> int:
        """The situations in which the conditions of ``mask`` have the values of ``value``."""
        result = self.everything
        for index in range(self.width):
            if mask >> index & 1:
                result &= self.holds[index] if value >> index & 1 else ~self.holds[index]
        return result & self.everything

    def separate(self, mask: int, answer: Answer, chosen: int) -> int:
        """``chosen`` plus the fewest further conditions (greedily, most separating first) on
        which ``mask`` differs from every situation that does not allow ``answer``."""
        differs = [self.holds[i] if not mask >> i & 1 else self.everything & ~self.holds[i]
                   for i in range(self.width)]
        left = self.everything & ~self.allows.get(answer, 0)
        for index in range(self.width):
            if chosen >> index & 1:
                left &= ~differs[index]
        while left:
            best = max(range(self.width), key=lambda i: ((left & differs[i]).bit_count(), -i))
            chosen |= 1 << best
            left &= ~differs[best]
        return chosen
