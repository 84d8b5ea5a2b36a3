"""The learner's exception rules: where the plan does not do a labelled situation's label, a rule
in front of it checks the fewest literals of that state that hold in no situation labelled
otherwise (and, for an action, a violated goal literal, so a rule never fires where the goal
holds), then does the label.

Kept apart from ``teach.learn.learner`` because choosing those literals fast needs its own index
of the situations (``Columns``); the learner keeps the situations and decides when rules are built.
"""

from __future__ import annotations

from dataclasses import dataclass

from teach.bt.nodes import Action, Node, Sequence
from teach.learn.action_model import ActionModel
from teach.learn.backchain import literal_node
from teach.learn.bits import mask_literals
from teach.learn.goal import GoalLearner

Answer = str | None
"""An action name, or None: the task is done here (the tree must return SUCCESS)."""


@dataclass
class ExceptionRule:
    """Do ``answer`` where the conditions of ``mask`` have the values of ``value`` (``node``, the
    rule as a tree); ``source``: the situation it was built for."""

    mask: int
    value: int
    answer: Answer
    source: str
    node: Node


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


def exception_rule(mask: int, answer: Answer, source: str, columns: Columns, names: tuple[str, ...],
                   goal: GoalLearner, model: ActionModel, safe: bool) -> ExceptionRule:
    """The rule for the situation ``mask``, labelled ``answer`` at ``source``. The safe learner's
    rule also checks the goal's required literals (for "done") or the action's required
    preconditions: a rule never licenses an action where a required precondition is false."""
    chosen = 0
    if answer is None:
        for index, _value in (goal.required() if safe else goal.cover):
            chosen |= 1 << index
    else:
        violated = next(((i, v) for i, v in goal.cover if bool(mask >> i & 1) != v), None)
        if violated is not None:
            chosen |= 1 << violated[0]
        if safe:
            need_pos, need_neg = model[answer].required
            chosen |= need_pos | need_neg
    chosen = columns.separate(mask, answer, chosen)
    value = mask & chosen
    leaves = [literal_node(names, lit) for lit in mask_literals(chosen, value, len(names))]
    if answer is not None:
        leaves.append(Action(answer))
    node = leaves[0] if len(leaves) == 1 else Sequence(tuple(leaves))
    return ExceptionRule(chosen, value, answer, source, node)
