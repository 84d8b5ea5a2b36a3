"""Where a teacher's action model (pre/ram) leaves PA-BT without a plan: the literals the goal
needs, what can become true, which actions wait for each other, and PA-BT's own verdict on a
model (run in its symbolic world). ``teach.dialogue.model_repair`` turns these gaps into
questions."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from teach.bt.nodes import Action, Node, transform
from teach.bt.nodes import Sequence as SeqNode
from teach.domain import ActionDef, Domain, Literal
from teach.errors import LearnError
from teach.symbolic import goal_verdict


@dataclass(frozen=True)
class PlanOutcome:
    """PA-BT on a model: ``usable`` when it builds a tree and the tree, run in that model's
    symbolic world from the state where nothing holds, reaches the goal. ``true_usable`` says
    the same for the true model when one is known (None otherwise), with actions that fail
    whenever the true model's preconditions do not hold."""

    usable: bool
    tree: Node | None
    reason: str
    true_usable: bool | None = None
    true_reason: str = ""


def holds_at_start(literal: Literal) -> bool:
    """PA-BT starts from the state where nothing holds: exactly the negative literals are true."""
    return not literal.value


def achievers(domain: Domain, literal: Literal) -> list[ActionDef]:
    return [a for a in domain.actions if literal in a.ram]


def reachable(domain: Domain) -> set[Literal]:
    """Literals some sequence of actions could make true, ignoring that effects may undo each
    other (the usual relaxed reachability)."""
    reached = {Literal(name, False) for name in domain.condition_names}
    changed = True
    while changed:
        changed = False
        for action in domain.actions:
            if all(p in reached for p in action.pre) and not set(action.ram) <= reached:
                reached |= set(action.ram)
                changed = True
    return reached


def needed(domain: Domain, goal: Sequence[Literal]) -> list[tuple[Literal, str]]:
    """The literals the goal needs, nearest the goal first, each with the action that needs it
    ("" for the goal itself); literals that hold at the start need nothing further."""
    order: list[tuple[Literal, str]] = []
    seen: set[Literal] = set()
    queue = [(g, "") for g in goal]
    while queue:
        literal, consumer = queue.pop(0)
        if literal in seen or holds_at_start(literal):
            continue
        seen.add(literal)
        order.append((literal, consumer))
        for action in achievers(domain, literal):
            queue += [(p, action.name) for p in action.pre]
    return order


def _closure(domain: Domain, start: list[Literal], open_literals: set[Literal]) -> set[Literal]:
    """``start`` and every open precondition of an achiever of a literal in it, transitively."""
    found: set[Literal] = set()
    stack = list(start)
    while stack:
        literal = stack.pop()
        if literal in found:
            continue
        found.add(literal)
        for achiever in achievers(domain, literal):
            stack += [p for p in achiever.pre if p in open_literals]
    return found


def requires(domain: Domain, action: ActionDef, open_literals: set[Literal]) -> set[Literal]:
    """The open literals ``action`` needs, directly or through the achievers of what it needs."""
    return _closure(domain, [p for p in action.pre if p in open_literals], open_literals)


def needs_actions(domain: Domain, literal: Literal, open_literals: set[Literal]) -> set[str]:
    """Every action that may have to run before ``literal`` can hold."""
    return {a.name for needed in _closure(domain, [literal], open_literals) for a in achievers(domain, needed)}


def depends_on(domain: Domain, first: ActionDef, second: str, open_literals: set[Literal]) -> bool:
    """Whether ``first`` needs something that only ``second`` (or what follows it) makes true."""
    return any(second in needs_actions(domain, p, open_literals) for p in first.pre if p in open_literals)


def plan_model(model: Domain, goal: Sequence[Literal] | None = None, true_model: Domain | None = None) -> PlanOutcome:
    """PA-BT on ``model``, the tree run in ``model``'s symbolic world from the state where nothing
    holds, and, when ``true_model`` is given, in the true model's world, where an action whose
    true preconditions do not hold fails (as a skill that cannot start does)."""
    from teach.learn.pabt import expand

    goal = tuple(model.goal if goal is None else goal)
    try:
        tree = expand(model, goal)[-1]
    except LearnError as error:
        return PlanOutcome(False, None, error.message, None if true_model is None else False,
                           "" if true_model is None else "no tree")
    start = tuple(False for _ in model.conditions)
    usable, reason = goal_verdict(model, tree, start)
    if true_model is None:
        return PlanOutcome(usable, tree, reason)
    true_usable, true_reason = goal_verdict(true_model, guarded(tree, true_model), start)
    return PlanOutcome(usable, tree, reason, true_usable, true_reason)


def guarded(tree: Node, model: Domain) -> Node:
    """The tree with every action preceded by its preconditions in ``model``."""
    from teach.learn.pabt import literal_node

    def guard(node: Node) -> Node:
        if isinstance(node, Action) and model.has_action(node.name) and model.action(node.name).pre:
            return SeqNode(tuple(literal_node(p) for p in model.action(node.name).pre) + (node,))
        return node

    result = transform(tree, guard)
    assert result is not None
    return result
