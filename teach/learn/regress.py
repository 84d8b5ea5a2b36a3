"""Rules regressed from the goal through a safe action model: the states the backchained plan
does not cover (Juba, Le & Stern's SAM acts by planning over the same model; issue 18).

The backchained tree (``teach.learn.backchain``) achieves goal literals one at a time, so
where the goal's literals interact it can find no action although the model has a way to the
goal. Regressing the goal breadth-first through the actions finds those ways: each step gives
a *rule* "where these literals hold, do A" (A's required preconditions plus what the goal still
needs after A). A rule runs A only where every precondition the learner has not ruled out
holds, so the rules are exactly as safe as the plan; nearest the goal come first.

Without parameterised actions the plan comes first and the rules fill its gaps: in a small
domain (every state can be tried) only the rules that fire where it finds no action are kept, so
the tree reads as the thesis's PA-BT with its gaps filled. Where the domain declares forms
(``teach.learn.lifting``) the model licenses acting in many states nobody showed, and there the
rules come first (after a check that the goal holds): the nearest-the-goal rule that fires leads,
in the learned model, to a state where a rule nearer the goal fires, so the robot never goes
round in circles there, which achieving goal literals one at a time does where they interact
(with the plan first 24% of blocksworld runs after 2 demonstrations looped, and 9–13% of miconic
runs, 10 conditions, after 5 or 20; none with the rules first). Behind the rules come the
learner's general exceptions (the teacher's steps where no rule fits), then nothing more (FAILURE:
the robot stops and asks). Where the regression found every condition, no other way to the goal
exists in the learned model. Where the budget cut it short, the plan is not put behind the rules
either: it achieves goal literals one at a time, and where no rule fits they interact (logistics
after 5 demonstrations at 30,000 nodes: it unloaded a parcel from a truck for one goal literal and
loaded it back for another, for ever, from 2% of held-out starts). Instead, where the
budget cut it short, the rules are followed by each goal literal no action undoes, worked back
on its own and pursued one at a time (``subgoal_rules``: visitall's goal, every cell visited,
regresses into more conditions than the budget holds; pursued cell by cell it is reached from
every start).

A pure function of the ``PlanView``, like the plan. The rules are evaluated by bitmask tests
(``PlanWithRules``) and become nodes only when the tree is assembled.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

from teach.bt.nodes import Action, Inverter, Node, Sequence, Status
from teach.bt.tick import CompiledTree
from teach.learn.action_model import Lit, literal_masks
from teach.learn.backchain import PlanView, Role, literal_node
from teach.learn.bits import mask_state, state_mask

MAX_RULE_NODES = 40_000
"""Nodes the regressed rules may add to the tree (breadth-first, the nearest the goal first): two
thirds of what a tree file may hold (``teach.limits.MAX_TREE_NODES``), the rest left to the goal
literals' own rules and the exceptions (visitall, where the budget always cuts the regression
short: 43,658 nodes after 100 demonstrations); it also bounds a replan's time (an update takes a
median 0.12-0.18 s in the logistics instance, 0.31-0.39 s in visitall).
Measured on logistics, 3 seeds, after 2 / 5 / 20 demonstrations: at 20,000 nodes 65 / 81 / 94% of
held-out starts reached, at 30,000 74 / 98 / 100% (the 98% with 2% going round in circles in the
plan that then followed the rules), at 40,000, with nothing behind the rules, 74 / 100 / 100%; at
30,000 without the plan 74 / 96 / 100%."""


GAP_RULE_NODES = 10_000
"""The budget where the plan comes first and the rules only fill its gaps (no forms): about the 400
rules of 20 literals kept before the budget was counted in nodes; a larger one doubled the time of
a replan in a 20-condition domain (330 -> 600 ms) for rules the plan rarely leaves to act."""


SUBGOAL_RULE_NODES = 10_000
"""Nodes the goal literals' own rules may add where the goal's regression was cut short
(``subgoal_rules``)."""


def rule_nodes_count(true: int, false: int) -> int:
    """The nodes of a rule's Sequence: a Condition per true literal, an Inverter and a Condition per
    false one, the Action and the Sequence."""
    return true.bit_count() + 2 * false.bit_count() + 2


@dataclass(frozen=True)
class Rule:
    """Where the literals ``true``/``false`` (bitmasks) hold, do ``action``, which makes ``makes``
    hold on the way to the goal; ``needs`` are ``action``'s own preconditions among them."""

    true: int
    false: int
    action: str
    makes: Lit
    needs: frozenset[Lit]
    pursues: Lit | None = None
    """A goal literal this rule works towards on its own (``subgoal_rules``): it fires only while
    that literal does not hold."""


@dataclass(frozen=True)
class _Step:
    name: str
    pre: tuple[Lit, ...]
    pre_true: int
    pre_false: int
    add: int
    delete: int


def regression_rules(goal: tuple[Lit, ...], preconditions: tuple[tuple[str, tuple[Lit, ...]], ...],
                     achievers: tuple[tuple[Lit, tuple[str, ...]], ...],
                     budget: int = MAX_RULE_NODES) -> tuple[list[Rule], bool]:
    """The goal regressed breadth-first through every action with effects (a ``PlanView``'s
    fields), skipping conditions no weaker than one found before; and whether that is all of
    them (False: the ``budget`` of nodes cut the regression short)."""
    if not goal:
        return [], True
    steps = _steps(preconditions, achievers)
    return _regress(literal_masks(goal), steps, _shift(goal, steps), budget)


def subgoal_rules(goal: tuple[Lit, ...], preconditions: tuple[tuple[str, tuple[Lit, ...]], ...],
                  achievers: tuple[tuple[Lit, tuple[str, ...]], ...],
                  budget: int = SUBGOAL_RULE_NODES) -> list[Rule]:
    """Where the goal's regression was cut short: each goal literal no action undoes, in the goal's
    order, regressed alone, its rules firing only while it does not hold (``Rule.pursues``). The
    robot then achieves those literals one at a time, the first in order it has a rule for first;
    as none is ever undone and each rule leads to a state where a rule nearer its literal fires,
    it never goes round in circles. All within ``budget`` nodes."""
    steps = _steps(preconditions, achievers)
    shift = _shift(goal, steps)
    undone = {(index, not value) for (index, value), names in achievers if names}
    found: list[Rule] = []
    for literal in goal:
        if literal in undone:
            continue
        single = literal_masks((literal,))
        rules, _complete = _regress(single, steps, shift, budget)
        pursued = [Rule(rule.true | single[1], rule.false | single[0], rule.action, rule.makes, rule.needs, literal)
                   for rule in rules if not (rule.true & single[0] or rule.false & single[1])]
        budget -= sum(rule_nodes_count(rule.true, rule.false) for rule in pursued)
        if budget < 0:
            break
        found += pursued
    return found


def _steps(preconditions: tuple[tuple[str, tuple[Lit, ...]], ...],
           achievers: tuple[tuple[Lit, tuple[str, ...]], ...]) -> list[_Step]:
    effects: dict[str, list[int]] = {}
    for (index, value), names in achievers:
        for name in names:
            masks = effects.setdefault(name, [0, 0])
            masks[0 if value else 1] |= 1 << index
    return [_Step(name, pre, *literal_masks(pre), *effects[name]) for name, pre in preconditions if name in effects]


def _shift(goal: tuple[Lit, ...], steps: list[_Step]) -> int:
    """Above every condition any step or the goal mentions: where a condition's false literals start
    in its one-int form."""
    start = literal_masks(goal)
    return max([start[0] | start[1], *(s.pre_true | s.pre_false | s.add | s.delete for s in steps)]).bit_length()


def _regress(start: tuple[int, int], steps: list[_Step], shift: int, budget: int) -> tuple[list[Rule], bool]:
    # each condition found as one int (true literals, then false ones above ``shift``): a new one
    # is skipped if it implies a kept one (``_Kept``)
    kept = _Kept(start[0] | start[1] << shift)
    frontier = [start]
    found: list[Rule] = []
    nodes = 0
    while frontier:
        reached: list[tuple[int, int]] = []
        for true, false in frontier:
            for step in steps:
                useful = step.add & true | step.delete & false
                if not useful or step.delete & true & ~step.add or step.add & false:
                    continue
                need_true = true & ~step.add | step.pre_true
                need_false = false & ~step.delete | step.pre_false
                both = need_true | need_false << shift
                if need_true & need_false or kept.implied_by(both):
                    continue
                kept.add(both)
                reached.append((need_true, need_false))
                index = (useful & -useful).bit_length() - 1
                nodes += rule_nodes_count(need_true, need_false)
                if nodes > budget:
                    return found, False
                found.append(Rule(need_true, need_false, step.name, (index, bool((step.add & true) >> index & 1)),
                                  frozenset(step.pre)))
        frontier = reached
    return found, True


class _Kept:
    """The conditions the regression kept, each one int, grouped by the highest literal each holds:
    a new condition implies a kept one only if it holds that one's highest literal, so only those
    groups are tested, each at C speed (map and all). Testing all of them was two thirds of a
    visitall update: a median 0.82-0.98 s after 20 demonstrations, 0.31-0.39 s grouped."""

    def __init__(self, first: int):
        self._by_top: dict[int, list[int]] = {}
        self.add(first)

    def add(self, condition: int) -> None:
        self._by_top.setdefault(condition.bit_length(), []).append(condition)

    def implied_by(self, condition: int) -> bool:
        """Whether ``condition`` holds every literal of some kept condition."""
        outside = ~condition
        rest = condition
        while rest:
            top = rest.bit_length()
            group = self._by_top.get(top)
            if group is not None and not all(map(outside.__and__, group)):
                return True
            rest ^= 1 << (top - 1)
        return False


SMALL_DOMAIN = 12
"""Up to this many conditions a rule is kept only if it fires in some state (every one is tried)."""


class PlanWithRules:
    """The compiled plan, then the first rule whose literals hold (or, ``rules_first``, the goal
    check and the rules, nothing after them): what the regression node does, by bitmask tests instead of
    compiled code (a logistics instance of 26 conditions has 600 rules: compiling rules on every
    replan cost 0.5 s at 400 rules of 20 literals)."""

    def __init__(self, plan: CompiledTree, rules: list[Rule], goal: tuple[Lit, ...] = (), rules_first: bool = False,
                 complete: bool = False):
        self.plan = plan
        self.rules = rules
        self.goal = goal
        self.rules_first = rules_first
        self.complete = rules_first and complete
        """Rules first, and they are every regressed condition: where none fires the learned model
        has no way to the goal (the learner's exceptions behind them are exact)."""
        self._goal_true, self._goal_false = literal_masks(goal)
        self.node: Node | None = None
        """The regression node (plan and rules in their order), once the tree was assembled."""
        self.rule_nodes: tuple[Node, ...] | None = None
        """Rules first: the goal check's and the rules' nodes, built once (the learner puts its later
        exceptions behind them, ``node_later`` the ones in ``node``)."""
        self.node_later: tuple[Node, ...] = ()

    def __call__(self, state: tuple[bool, ...]) -> tuple[Status, str | None]:
        if self.rules_first:
            decided = self.decided(state_mask(state))
            return decided if decided is not None else (Status.FAILURE, None)
        status, action = self.plan(state)
        if status is not Status.FAILURE:
            return status, action
        rule = self.first(state_mask(state))
        return (Status.FAILURE, None) if rule is None else (Status.RUNNING, rule.action)

    def decided(self, mask: int) -> tuple[Status, str | None] | None:
        """Rules first: SUCCESS where the goal holds, else the first rule's action; None where neither."""
        if mask & self._goal_true == self._goal_true and not mask & self._goal_false:
            return Status.SUCCESS, None
        rule = self.first(mask)
        return None if rule is None else (Status.RUNNING, rule.action)

    def first(self, mask: int) -> Rule | None:
        for rule in self.rules:
            if mask & rule.true == rule.true and not mask & rule.false:
                return rule
        return None


def with_rules(view: PlanView, plan: CompiledTree, width: int, lifted: bool = False) -> PlanWithRules:
    """The plan followed by the view's regressed rules; in a small domain only those that fire in
    some state where the plan does not act (a rule that never fires would only be read: "if …,
    I …" where I never do); with parameterised actions (``lifted``) the rules first (module
    docstring)."""
    budget = MAX_RULE_NODES if lifted else GAP_RULE_NODES
    rules, complete = regression_rules(view.goal, view.preconditions, view.achievers, budget)
    if lifted:
        if not complete:
            rules += subgoal_rules(view.goal, view.preconditions, view.achievers)
        return PlanWithRules(plan, rules, view.goal, rules_first=bool(rules), complete=complete)
    if width > SMALL_DOMAIN:
        return PlanWithRules(plan, rules)
    both = PlanWithRules(plan, rules)
    used = {id(rule) for rule in (both.first(mask) for mask in range(1 << width)
                                  if plan(mask_state(mask, width))[0] is Status.FAILURE) if rule is not None}
    return PlanWithRules(plan, [rule for rule in rules if id(rule) in used])


def goal_node(goal: tuple[Lit, ...], names: tuple[str, ...], roles: dict[int, Role]) -> Node:
    """``Sequence(goal literals...)``: SUCCESS where the goal holds, before any rule is tried."""
    sequence = Sequence(tuple(_literal_nodes(goal, names, roles, lambda literal: Role("goal", literal))))
    roles[sequence.uid] = Role("goal-check")
    return sequence


def _literal_nodes(literals: Iterable[Lit], names: tuple[str, ...], roles: dict[int, Role],
                   role: Callable[[Lit], Role]) -> list[Node]:
    """A node per literal (an Inverter for a false one), each with its ``role`` in ``roles``."""
    nodes: list[Node] = []
    for literal in literals:
        node = literal_node(names, literal)
        roles[node.uid] = role(literal)
        if isinstance(node, Inverter):
            roles[node.child.uid] = roles[node.uid]
        nodes.append(node)
    return nodes


def _rule_role(rule: Rule) -> Callable[[Lit], Role]:
    """A rule's literal is the action's precondition, what the goal still needs after it, or the
    goal literal it works towards on its own not holding yet."""
    pursued = None if rule.pursues is None else (rule.pursues[0], not rule.pursues[1])

    def role(literal: Lit) -> Role:
        if literal == pursued:
            return Role("pursued", rule.pursues, rule.action)
        return Role("precondition" if literal in rule.needs else "subgoal", literal, rule.action)
    return role


def rule_nodes(rules: list[Rule], names: tuple[str, ...], roles: dict[int, Role]) -> list[Node]:
    """``Sequence(literals..., action)`` for each rule, with the role of every node in ``roles``."""
    nodes: list[Node] = []
    for rule in rules:
        literals = [(index, bool(rule.true >> index & 1)) for index in range(len(names))
                    if (rule.true | rule.false) >> index & 1]
        kids = _literal_nodes(literals, names, roles, _rule_role(rule))
        action = Action(rule.action)
        roles[action.uid] = Role("achiever", rule.makes, rule.action)
        sequence = Sequence((*kids, action))
        roles[sequence.uid] = Role("rule", rule.makes, rule.action)
        nodes.append(sequence)
    return nodes
