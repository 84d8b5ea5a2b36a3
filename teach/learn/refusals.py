"""What the teacher's "no" to a question says: one of the unsure literals false there is needed
(for an action: a precondition; for "done": a goal literal). A single one is kept for good; a
group is remembered, split in halves by the next questions, until one unsure literal is left.

Kept apart from ``teach.learn.learner``: it reads and confirms only the action model and the goal.
"""

from __future__ import annotations

from teach.learn.action_model import ActionModel, Lit, literals_of
from teach.learn.goal import GoalLearner


class Refusals:
    """The groups of literals the teacher said no to, per action (None: the goal), with the source."""

    def __init__(self, model: ActionModel, goal: GoalLearner, conditions: int):
        self.model = model
        self.goal = goal
        self.conditions = conditions
        self.groups: dict[str | None, list[tuple[frozenset[Lit], str]]] = {}

    def refuse(self, action: str | None, false: frozenset[Lit], source: str) -> None:
        """The teacher said no to ``action`` (None: "done") where the literals ``false`` do not hold:
        one of them is needed; a single one is kept for good, a group is remembered to be split."""
        if len(false) == 1:
            self._keep(action, next(iter(false)), source)
        elif false and not false & self._confirmed(action):
            self.groups.setdefault(action, []).append((false, source))
        self.infer_needed()

    def infer_needed(self) -> None:
        """A refused group with one unsure literal left: that one is needed."""
        for action, groups in self.groups.items():
            unsure = self._unsure(action)
            kept = []
            for group, source in groups:
                left = group & unsure
                if len(left) == 1 and not group & self._confirmed(action):
                    self._keep(action, next(iter(left)), source)
                elif len(left) > 1:
                    kept.append((group, source))
            groups[:] = kept

    def untested(self, action: str | None, literals: list[Lit]) -> list[list[Lit]]:
        """The groups of unsure literals worth asking about next, best first: all of them and then
        each half, or, where a group inside them was refused (or was impossible), each half of
        what is left of that group (a yes to all of it is known not to come)."""
        current = list(literals)
        for group, _source in reversed(self.groups.get(action, [])):
            left = [lit for lit in current if lit in group]
            if len(left) >= 2:
                half = len(left) // 2
                return [left[:half], left[half:]]
        half = len(current) // 2
        return [current, current[:half], current[half:]] if half else [current] if current else []

    def _unsure(self, action: str | None) -> set[Lit]:
        if action is None:
            return set(self.goal.unsure())
        return set(literals_of(*self.model[action].unsure, self.conditions))

    def _keep(self, action: str | None, literal: Lit, source: str) -> None:
        if action is None:
            self.goal.confirm(literal, source)
        else:
            self.model.confirm(action, literal, source)

    def _confirmed(self, action: str | None) -> frozenset[Lit]:
        if action is None:
            return frozenset(self.goal.confirmed)
        knowledge = self.model[action]
        return frozenset((*knowledge.confirmed, *knowledge.maintained))
