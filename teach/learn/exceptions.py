"""The learner's exception rules: where the plan does not do a labelled situation's label, a rule
in front of it checks the fewest literals of that state that hold in no situation labelled
otherwise (and, for an action, a violated goal literal, so a rule never fires where the goal
holds, and one of its known effects not yet true, so it never fires where it would change
nothing it is known to change), then does the label. An *exact* rule tests every condition: it fires in its own state
only (the learner puts those in front of rules that come first, ``teach.learn.regress``).

Kept apart from ``teach.learn.learner``: a rule is a pure function of one situation, the goal,
the model and the situations' column index (``teach.learn.labels.Columns``), which makes
choosing its literals a few popcounts; the learner decides when rules are built.
"""

from __future__ import annotations

from dataclasses import dataclass

from teach.bt.nodes import Action, Node, Sequence
from teach.learn.action_model import ActionModel
from teach.learn.backchain import literal_node
from teach.learn.bits import mask_literals
from teach.learn.goal import GoalLearner
from teach.learn.labels import Answer, Columns


@dataclass
class ExceptionRule:
    """Do ``answer`` where the conditions of ``mask`` have the values of ``value`` (``node``, the
    rule as a tree); ``source``: the situation it was built for."""

    mask: int
    value: int
    answer: Answer
    source: str
    node: Node


def exception_rule(mask: int, answer: Answer, source: str, columns: Columns, names: tuple[str, ...],
                   goal: GoalLearner, model: ActionModel, safe: bool, exact: bool = False) -> ExceptionRule:
    """The rule for the situation ``mask``, labelled ``answer`` at ``source``. The safe learner's
    rule also checks the goal's required literals (for "done") or the action's required
    preconditions: a rule never licenses an action where a required precondition is false.
    ``exact``: it tests every condition, so it fires in that state only."""
    if exact:
        return _rule((1 << len(names)) - 1, mask, answer, source, names)
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
            chosen |= _pending_effect(mask, model, answer)
    return _rule(columns.separate(mask, answer, chosen), mask, answer, source, names)


def _pending_effect(mask: int, model: ActionModel, action: str) -> int:
    """One known effect of ``action`` not yet true in ``mask`` (its lowest condition; 0 if every
    known effect holds there): a rule checking it fires only where the action still changes
    something. Without it a step shown where its effect was missing was repeated where the
    effect held already, for ever (random STRIPS, 2 demonstrations and 5 answers: 6 of 15 runs)."""
    made_true, made_false = model[action].effects
    pending = made_true & ~mask | made_false & mask
    return pending & -pending


def _rule(chosen: int, mask: int, answer: Answer, source: str, names: tuple[str, ...]) -> ExceptionRule:
    value = mask & chosen
    leaves = [literal_node(names, lit) for lit in mask_literals(chosen, value, len(names))]
    if answer is not None:
        leaves.append(Action(answer))
    node = leaves[0] if len(leaves) == 1 else Sequence(tuple(leaves))
    return ExceptionRule(chosen, value, answer, source, node)
