"""Why a node of the learned tree exists, as data and as an English sentence naming the evidence.

Kept apart from ``teach.learn.learner``: explaining reads what the learner built (its exception
rules, the plan's node roles, the action model and the goal) and changes none of it.
"""

from __future__ import annotations

from collections.abc import Mapping
from collections.abc import Sequence as Seq
from dataclasses import dataclass

from teach.bt.nodes import walk
from teach.domain import Literal
from teach.errors import LearnError
from teach.learn.action_model import ActionModel, Lit
from teach.learn.backchain import Role
from teach.learn.bits import mask_literals
from teach.learn.exceptions import ExceptionRule
from teach.learn.goal import GoalLearner


@dataclass(frozen=True)
class Explanation:
    """Why a node exists, as data (``kind``, the ``action`` and ``literal`` it concerns, the
    ``sources`` behind it) and as an English sentence (``text``)."""

    uid: int
    kind: str
    text: str
    action: str | None = None
    literal: Literal | None = None
    sources: tuple[str, ...] = ()


def explain_node(uid: int, root_uid: int, exceptions: Seq[ExceptionRule], roles: Mapping[int, Role],
                 planned: bool, model: ActionModel, goal: GoalLearner, names: tuple[str, ...]) -> Explanation:
    """Why the node ``uid`` exists in the tree ``Fallback(exceptions..., plan)`` whose root is
    ``root_uid`` (-1: no Fallback at the root); ``roles``: the plan's nodes and what each is for;
    ``planned``: whether there is a plan."""
    if uid == root_uid:
        return Explanation(uid, "root", "the root: situations that need an exception are checked first, "
                           "then the plan from the learned goal and action model")
    for exception in exceptions:
        if uid in {n.uid for n in walk(exception.node)}:
            what = "the task is done" if exception.answer is None else f"do {exception.answer}"
            words = " and ".join(str(_literal(names, lit))
                                 for lit in mask_literals(exception.mask, exception.value, len(names))) or "anything"
            return Explanation(uid, "exception", f"an exception: {what} where {words} holds, because the "
                               f"plan did something else at {exception.source}", exception.answer,
                               None, (exception.source,))
    role = roles.get(uid)
    if role is None:
        if not planned and not exceptions:
            return Explanation(uid, "nothing", "nothing learned yet: the tree fails in every state")
        raise LearnError(f"no node {uid} in the learned tree")
    return _explain_role(uid, role, model, goal, names)


def _explain_role(uid: int, role: Role, model: ActionModel, goal: GoalLearner, names: tuple[str, ...]) -> Explanation:
    literal = None if role.literal is None else _literal(names, role.literal)
    if role.kind == "goal-sequence":
        return Explanation(uid, role.kind, "the goal: every goal literal in turn, each achieved if it does "
                           "not hold yet")
    if role.kind == "regression":
        return Explanation(uid, role.kind, "the plan, then the ways to the goal it does not take: the goal "
                           "worked back through the actions, one rule per step")
    if role.kind in ("regression-first", "regression-complete"):
        behind = ("the model knows no way to the goal" if role.kind == "regression-complete" else
                  "the ways worked back so far do not reach")
        return Explanation(uid, role.kind, "done if the goal holds, else the ways to the goal, nearest first: "
                           "the goal worked back through the actions, one rule per step; then the exceptions "
                           f"for states no rule fits; nothing more: where none fits, {behind}, so the robot "
                           "stops and asks")
    if role.kind == "goal-check":
        return Explanation(uid, role.kind, "the goal: done where every goal literal holds")
    assert role.literal is not None and literal is not None
    if role.kind == "goal":
        holding = [src for e in goal.goal_states.values() for src in e.sources][:5]
        acting = goal.violations(role.literal)
        return Explanation(uid, "goal", f"goal literal {literal}: it held in all {len(goal.goal_states)} "
                           f"goal state(s) ({', '.join(holding)}) and was still missing in {acting} state(s) "
                           f"where the teacher kept acting", None, literal, tuple(holding))
    if role.kind == "achieve":
        return Explanation(uid, role.kind, f"achieve {literal}: done if it holds, otherwise an action that "
                           f"makes it hold", None, literal)
    assert role.action is not None
    knowledge = model[role.action]
    if role.kind == "pursued":
        return Explanation(uid, role.kind, f"{literal} does not hold yet: the goal needs it and no action undoes "
                           f"it, so it is worked towards on its own, {role.action} a step on the way",
                           role.action, literal)
    if role.kind == "subgoal":
        return Explanation(uid, role.kind, f"{literal} with {role.action}: the goal still needs it after "
                           f"{role.action}", role.action, literal)
    if role.kind == "precondition":
        applied = knowledge.applied
        return Explanation(uid, role.kind, f"{literal} before {role.action}: it held in all {applied.count} "
                           f"state(s) where {role.action} was done ({', '.join(applied.sources)}), and "
                           f"{knowledge.reason(role.literal)}", role.action, literal, tuple(applied.sources))
    if role.literal in knowledge.made:
        evidence = knowledge.made[role.literal]
        sources = tuple(evidence.sources)
        text = (f"{role.action} makes {literal} hold: seen {evidence.count} time(s) "
                f"({', '.join(sources)}) and never contradicted")
    else:
        sources = (knowledge.guessed[role.literal],)
        text = (f"{role.action} makes {literal} hold: guessed from the answer at {sources[0]} "
                f"({role.action} was never demonstrated)")
    if role.kind == "last-resort":
        text = f"last resort for {literal}: {role.action} even when its preconditions do not hold; " + text
    return Explanation(uid, role.kind, text, role.action, literal, sources)


def _literal(names: tuple[str, ...], literal: Lit) -> Literal:
    return Literal(names[literal[0]], literal[1])
