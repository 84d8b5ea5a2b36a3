"""Model repair: where the plan runs the wrong action in a labelled situation, a possible
precondition the prior left out is added back if that reproduces more situations; if the
teacher restored that literal at once after every external event that took it away, it is
assumed for every other action it held for too, unless that gets more situations wrong.

Kept apart from ``teach.learn.learner``: repair changes only the action model and tries the
learner's plan through the few calls of ``PlanTrials``; the learner decides when to repair.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

from teach.learn.action_model import ActionModel, Lit, literals_of
from teach.learn.labels import Answer, Situation

REPAIR_TRIALS = 4
"""Model repairs tried per update; each costs one replan and one check of every situation."""

FAILED = "<failure>"
"""What the plan does in a state where it returns FAILURE."""


class Restored:
    """Which literals an external event took away did the teacher restore with the next action?"""

    def __init__(self) -> None:
        self._restored: set[Lit] = set()
        self._left_broken: set[Lit] = set()

    def note(self, broken: list[Lit], after: int | None) -> None:
        """The literals ``broken`` were taken away; ``after``: the state after the teacher's next
        action (None: the teacher did not act next)."""
        for literal in broken:
            if after is not None and bool(after >> literal[0] & 1) == literal[1]:
                self._restored.add(literal)
            else:
                self._left_broken.add(literal)

    def maintained(self, literal: Lit) -> bool:
        """The teacher restored ``literal`` at once every time an event took it away (at least once)."""
        return literal in self._restored and literal not in self._left_broken


@dataclass(frozen=True)
class PlanTrials:
    """How repair tries the learner's plan: ``replan`` after a change of the model; ``keep``
    returns a way back to the current plan; ``output`` what the plan does in a situation (an
    action, None or ``FAILED``); ``errors(limit)`` how many situations it gets wrong, counted
    up to ``limit`` (None: all)."""

    replan: Callable[[], None]
    keep: Callable[[], Callable[[], None]]
    output: Callable[[int], Answer | str]
    errors: Callable[[int | None], int]


def repair_model(wrong: Iterable[int], situations: Mapping[int, Situation], model: ActionModel,
                 rank: Callable[[Lit], tuple[int, int]], restored: Restored, conditions: int,
                 plans: PlanTrials) -> None:
    """Add back possible preconditions the prior left out where that reproduces more
    situations: for a newly learned situation where the plan runs the wrong action, each
    possible precondition of that action false there is tried, and the one that leaves
    the fewest situations wrong is kept (ties: the one established latest, nearest the
    action). At most ``REPAIR_TRIALS`` replans per update."""
    trials = 0
    errors = plans.errors(None)
    for mask in wrong:
        situation = situations[mask]
        running = plans.output(mask)
        if trials >= REPAIR_TRIALS or not errors:
            return
        if running in situation.allowed or running is None or running == FAILED:
            continue
        knowledge = model[running]
        pos, neg = knowledge.possible
        have_pos, have_neg = knowledge.assumed
        back = plans.keep()
        best: tuple[int, tuple[int, ...], Lit] | None = None
        for literal in literals_of(pos & ~have_pos, neg & ~have_neg, conditions):
            if bool(mask >> literal[0] & 1) == literal[1] or trials >= REPAIR_TRIALS:
                continue
            trials += 1
            knowledge.confirmed[literal] = situation.sources[-1]
            plans.replan()
            # only a count that ties or beats the best so far matters exactly
            limit = errors if best is None else best[0] + 1
            score = (plans.errors(limit), tuple(-x for x in rank(literal)), literal)
            del knowledge.confirmed[literal]
            if score[0] < errors and (best is None or score < best):
                best = score
        if best is None:
            back()
            continue
        errors = best[0]
        knowledge.confirmed[best[2]] = situation.sources[-1]
        plans.replan()
        if restored.maintained(best[2]):
            errors = _extend(best[2], situation.sources[-1], errors, model, plans)


def _extend(literal: Lit, source: str, errors: int, model: ActionModel, plans: PlanTrials) -> int:
    """A maintained literal just shown to be needed by one action is needed by every action
    it held for each time that action was done: people keep what they care about. Kept only
    if no more situations go wrong; returns how many are wrong now."""
    index, value = literal
    others = []
    for knowledge in model.actions.values():
        pos, neg = knowledge.possible
        have_pos, have_neg = knowledge.assumed
        if knowledge.demonstrated and ((pos & ~have_pos) if value else (neg & ~have_neg)) >> index & 1:
            others.append(knowledge)
    if not others:
        return errors
    back = plans.keep()
    for knowledge in others:
        knowledge.maintained[literal] = source
    plans.replan()
    now = plans.errors(errors + 1)
    if now <= errors:
        return now
    for knowledge in others:
        del knowledge.maintained[literal]
    back()
    return errors
