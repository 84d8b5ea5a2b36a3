"""A reactive tree planned backwards from a goal through an action model (PA-BT, thesis §4.1).

Each goal literal becomes the atomic BT of Fig. 2.8: ``Fallback(literal, Sequence(pre..., A),
...)`` with one Sequence per achiever A (an action with the literal among its effects), in
the order given (the learner puts the achiever the teacher demonstrated first); every
precondition is expanded the same way until it has no achiever or already appears on the
path from the root (so loops in the model end). A precondition that is the negation of the
literal being achieved is left out: inside its Fallback the literal is false already.

The learner passes every precondition it has not ruled out (the assumed ones first), so each
action runs only where all of them hold: the order is a guess, the checks are not.

With ``regression`` (the safe learner) the plan is followed by the rules regressed from the
goal through the same model (``teach.learn.regress``), for the states where achieving the goal
literals one at a time finds no action.

Optionally a *weak last resort* ends each Fallback: the first achiever again with none of its
preconditions, so where a precondition can neither be checked true nor achieved the robot
still tries the action that was shown for this literal instead of giving up.

The plan is a pure function of a ``PlanView`` (hashable), so the learner replans only when
the view changed, and the benchmark's teacher is the same function over a hidden model.
"""

from __future__ import annotations

from dataclasses import dataclass

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Sequence
from teach.learn.action_model import Lit

MAX_NODES = 400
"""Beyond this size literals are no longer expanded (deep models would grow exponentially)."""


@dataclass(frozen=True)
class PlanView:
    """Everything the planner reads: goal literals in order, each action's preconditions in
    order, and for each literal its achievers, preferred first."""

    goal: tuple[Lit, ...]
    preconditions: tuple[tuple[str, tuple[Lit, ...]], ...]
    achievers: tuple[tuple[Lit, tuple[str, ...]], ...]
    weak_last_resort: bool = True
    regression: bool = False


@dataclass(frozen=True)
class Role:
    """Why a node of the plan exists: ``kind`` is one of goal, achieve, precondition,
    achiever, last-resort, goal-sequence, and for the regressed rules (``teach.learn.regress``)
    regression (the plan and the rules), regression-first and regression-complete (rules first,
    cut short by their budget or every one of them), goal-check, rule, subgoal, pursued (a goal literal
    worked towards on its own); ``literal`` the literal it
    checks or achieves, ``action`` the action involved."""

    kind: str
    literal: Lit | None = None
    action: str | None = None


def literal_node(names: tuple[str, ...], literal: Lit) -> Node:
    condition = Condition(names[literal[0]])
    return condition if literal[1] else Inverter(condition)


def plan(view: PlanView, names: tuple[str, ...]) -> tuple[Node | None, dict[int, Role]]:
    """The backchained tree (None without a goal) and the role of each of its nodes."""
    roles: dict[int, Role] = {}
    preconditions = dict(view.preconditions)
    achievers = dict(view.achievers)
    made = [0]

    def leaf(literal: Lit, role: Role) -> Node:
        node = literal_node(names, literal)
        roles[node.uid] = role
        if isinstance(node, Inverter):
            roles[node.child.uid] = role
        made[0] += 2
        return node

    def achieve(literal: Lit, path: frozenset[Lit], role: Role) -> Node:
        check = leaf(literal, role)
        options = achievers.get(literal, ())
        if not options or made[0] > MAX_NODES:
            return check
        inner = path | {literal}
        opposite = (literal[0], not literal[1])
        branches: list[Node] = []
        for name in options:
            kids: list[Node] = []
            for pre in preconditions.get(name, ()):
                if pre == opposite:
                    continue
                pre_role = Role("precondition", pre, name)
                kids.append(leaf(pre, pre_role) if pre in inner else achieve(pre, inner, pre_role))
            action = Action(name)
            roles[action.uid] = Role("achiever", literal, name)
            kids.append(action)
            branch: Node = Sequence(tuple(kids)) if len(kids) > 1 else action
            if len(kids) > 1:
                roles[branch.uid] = Role("achiever", literal, name)
            branches.append(branch)
            made[0] += 1 + len(kids)
        if view.weak_last_resort and isinstance(branches[0], Sequence):
            last = Action(options[0])
            roles[last.uid] = Role("last-resort", literal, options[0])
            branches.append(last)
        node = Fallback((check, *branches))
        roles[node.uid] = Role("achieve", literal)
        return node

    if not view.goal:
        return None, roles
    parts = [achieve(g, frozenset(), Role("goal", g)) for g in view.goal]
    if len(parts) == 1:
        return parts[0], roles
    root = Sequence(tuple(parts))
    roles[root.uid] = Role("goal-sequence")
    return root, roles
