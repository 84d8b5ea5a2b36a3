"""A true STRIPS model with negative literals, over bitmask states (bit i = condition i).

The learner sees only ``Task.domain`` (conditions and actions, no ``pre``/``ram``, no goal);
the bench keeps ``Task.model`` to run actions, judge safety and plan the teacher's answers.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from functools import cached_property

from teach.domain import ActionDef, ConditionDef, Domain, State
from teach.learn.bits import mask_state, state_mask

MAX_STATES = 200_000
"""Reachable state spaces larger than this are refused: the teacher keeps a distance per state."""


@dataclass(frozen=True)
class Operator:
    """A grounded action: preconditions as a positive and a negative mask, STRIPS add and delete masks."""

    name: str
    pre_true: int
    pre_false: int
    add: int
    delete: int

    def applicable(self, state: int) -> bool:
        return state & self.pre_true == self.pre_true and not state & self.pre_false

    def apply(self, state: int) -> int:
        return (state & ~self.delete) | self.add


@dataclass(frozen=True)
class Model:
    """Conditions, operators (action ID = position + 1) and the goal as two masks."""

    conditions: tuple[str, ...]
    operators: tuple[Operator, ...]
    goal_true: int
    goal_false: int

    def goal_holds(self, state: int) -> bool:
        return state & self.goal_true == self.goal_true and not state & self.goal_false

    @cached_property
    def by_name(self) -> dict[str, Operator]:
        return {o.name: o for o in self.operators}

    def literals(self, mask_true: int, mask_false: int) -> set[tuple[str, bool]]:
        """The literals two masks stand for, as (condition name, value)."""
        return ({(c, True) for i, c in enumerate(self.conditions) if mask_true >> i & 1}
                | {(c, False) for i, c in enumerate(self.conditions) if mask_false >> i & 1})


@dataclass
class Task:
    """One instance: the learner's view, the true model, the states the world can be in and the
    optimal teacher. The world's states are those reachable from ``roots`` (a planning problem's
    initial state; for a random domain every state)."""

    name: str
    domain: Domain
    model: Model
    roots: tuple[int, ...]
    reachable: dict[int, int] = field(default_factory=dict)
    """Every state of the world with its distance to the goal (-1: the goal is unreachable)."""

    def __post_init__(self) -> None:
        if not self.reachable:
            self.reachable = _distances(self.model, self.roots)

    @property
    def width(self) -> int:
        return len(self.model.conditions)

    def state(self, mask: int) -> State:
        return mask_state(mask, self.width)

    def mask(self, state: State) -> int:
        return state_mask(state)

    def distance(self, state: int) -> int | None:
        """Steps of an optimal plan from ``state``; None if it is not reachable or the goal is not reachable from it."""
        found = self.reachable.get(state, -1)
        return None if found < 0 else found

    def best(self, state: int) -> Operator | None:
        """The teacher's action: the first operator (in ID order) that starts an optimal plan;
        None where the goal holds or cannot be reached."""
        distance = self.distance(state)
        if not distance:
            return None
        for operator in self.model.operators:
            if operator.applicable(state) and self.reachable.get(operator.apply(state), -1) == distance - 1:
                return operator
        raise AssertionError("a distance without a successor one step nearer")

    def plan(self, state: int) -> list[Operator] | None:
        """An optimal plan from ``state`` (empty where the goal holds), None where none exists."""
        if self.distance(state) is None:
            return None
        steps: list[Operator] = []
        while (operator := self.best(state)) is not None:
            steps.append(operator)
            state = operator.apply(state)
        return steps

    def starts(self) -> list[int]:
        """Every reachable state that is not a goal state but reaches one, in increasing mask order."""
        return sorted(s for s, d in self.reachable.items() if d > 0)


def _distances(model: Model, roots: tuple[int, ...]) -> dict[int, int]:
    """Forward search for the reachable states, then backward breadth-first distances to the goal."""
    successors: dict[int, list[int]] = {root: [] for root in roots}
    frontier = deque(successors)
    while frontier:
        state = frontier.popleft()
        for operator in model.operators:
            if operator.applicable(state):
                after = operator.apply(state)
                successors[state].append(after)
                if after not in successors:
                    if len(successors) >= MAX_STATES:
                        raise ValueError(f"more than {MAX_STATES} reachable states")
                    successors[after] = []
                    frontier.append(after)
    predecessors: dict[int, list[int]] = {s: [] for s in successors}
    for state, afters in successors.items():
        for after in afters:
            predecessors[after].append(state)
    distance = {s: -1 for s in successors}
    queue = deque(s for s in successors if model.goal_holds(s))
    for state in queue:
        distance[state] = 0
    while queue:
        state = queue.popleft()
        for before in predecessors[state]:
            if distance[before] < 0:
                distance[before] = distance[state] + 1
                queue.append(before)
    return distance


def learner_domain(name: str, model: Model, phrases: dict[str, str],
                   forms: dict[str, tuple[str, ...]] | None = None) -> Domain:
    """The domain as the learner sees it: one condition per fact, one action per operator, no model, no
    goal; ``forms``: each one's predicate or kind and objects, where the domain has them (PDDL)."""
    forms = forms or {}
    conditions = tuple(ConditionDef(c, phrases.get(c, c), form=forms.get(c, ())) for c in model.conditions)
    actions = tuple(ActionDef(i + 1, o.name, (phrases.get(o.name, o.name),), form=forms.get(o.name, ()))
                    for i, o in enumerate(model.operators))
    return Domain(name, conditions, actions)

