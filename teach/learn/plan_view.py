"""What the learner's planner reads: a ``PlanView`` (``teach.learn.backchain``) built from the
action model and the goal, literals in the order the demonstrations establish them, and the
what-if plans the question choosers compare the tree with.

Kept apart from ``teach.learn.learner``: these are pure functions of the model, the goal and
the ranks; the learner decides when to replan.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping

from teach.bt.tick import CompiledTree, compile_tree
from teach.learn.action_model import ActionModel, Lit, literals_of
from teach.learn.backchain import PlanView, plan
from teach.learn.goal import GoalLearner


class Ranks:
    """When the demonstrations establish each literal: the mean position, among a
    demonstration's actions, of the steps that made it hold."""

    def __init__(self) -> None:
        self._sum: dict[Lit, int] = {}
        self._count: dict[Lit, int] = {}

    def established(self, changed: int, after: int, position: int, conditions: int) -> None:
        """The ``position``-th action of a demonstration changed the conditions ``changed``,
        leaving the state ``after``."""
        for index in range(conditions):
            if changed >> index & 1:
                literal = (index, bool(after >> index & 1))
                self._sum[literal] = self._sum.get(literal, 0) + position
                self._count[literal] = self._count.get(literal, 0) + 1

    def rank(self, literal: Lit) -> tuple[int, int]:
        """Literals the demonstrations establish early come first (-1: never established); the
        mean step is rounded, so the plan is not rebuilt for every small change of it."""
        count = self._count.get(literal, 0)
        return (round(self._sum[literal] / count) if count else -1), literal[0]


def plan_view(model: ActionModel, goal: GoalLearner, rank: Callable[[Lit], tuple[int, int]], conditions: int,
              safe: bool) -> PlanView:
    """The view the learner plans from: the safe learner pursues every required literal (the cover
    and confirmed ones first: they are what the teacher was after), the guessing one the cover."""
    if safe:
        cover = set(goal.cover) | set(goal.confirmed)
        wanted = tuple(sorted(goal.required(), key=lambda lit: (lit not in cover, rank(lit))))
    else:
        wanted = tuple(sorted(goal.cover, key=rank))
    preconditions = []
    achievers: dict[Lit, list[str]] = {}
    for name, knowledge in model.actions.items():
        made_true, made_false = knowledge.effects
        if not made_true | made_false:
            continue
        # every required precondition is checked (or achieved) before the action: the
        # assumed ones first, in the order the demonstrations establish them
        pos, neg = knowledge.assumed
        need_pos, need_neg = knowledge.required
        pursued = sorted(literals_of(pos, neg, conditions), key=rank)
        if safe:
            pursued += sorted(literals_of(need_pos & ~pos, need_neg & ~neg, conditions), key=rank)
        preconditions.append((name, tuple(pursued)))
    for index in range(conditions):
        for value in (True, False):
            found = model.achievers((index, value))
            if found:
                achievers[(index, value)] = found
    return PlanView(wanted, tuple(preconditions), tuple((lit, tuple(a)) for lit, a in achievers.items()),
                    not safe, regression=safe)


def ruled_out_plan(view: PlanView, out: Mapping[str | None, Collection[Lit]],
                   names: tuple[str, ...]) -> CompiledTree | None:
    """The plan of ``view`` without the literals ``out[action]`` for each action (None: the goal),
    and without the regressed rules."""
    goal = tuple(lit for lit in view.goal if lit not in out.get(None, ()))
    preconditions = tuple((name, tuple(lit for lit in pursued if lit not in out.get(name, ())))
                          for name, pursued in view.preconditions)
    return _compiled(view, goal, preconditions, names)


def goal_bound_plan(view: PlanView, goal: Iterable[Lit], names: tuple[str, ...]) -> CompiledTree | None:
    """The plan of ``view`` for the goal literals ``goal`` instead, without the regressed rules."""
    return _compiled(view, tuple(goal), view.preconditions, names)


def _compiled(view: PlanView, goal: tuple[Lit, ...], preconditions: tuple[tuple[str, tuple[Lit, ...]], ...],
              names: tuple[str, ...]) -> CompiledTree | None:
    built, _roles = plan(PlanView(goal, preconditions, view.achievers, view.weak_last_resort), names)
    return None if built is None else compile_tree(built, names)
