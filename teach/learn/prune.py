"""Pruning of redundant nodes (thesis §4.2.2, Algorithms 4.1–4.4), sound by construction.

The thesis walks up from every condition to see whether the same condition was already
evaluated on every path that reaches it. We compute the same knowledge top-down in one
pass per round: for every node the literals that hold whenever a tick reaches it (the
*context*), and for every subtree the literals that hold when it returns SUCCESS or
FAILURE. A subtree whose result the context already decides is then

- *neutral* (SUCCESS under a Sequence, FAILURE under a Fallback): removed, the parent
  goes on exactly as before (the thesis's redundant condition, Inverters included);
- *decisive* (FAILURE under a Sequence, SUCCESS under a Fallback): kept, and the
  siblings to its right, which no tick can reach, are removed.

Inside a Parallel every child is ticked, so a decided child is removed only with the
success threshold adjusted so that the Parallel's result cannot change. An action that
returned SUCCESS guarantees its ramifications, and under the action model's frame
assumption nothing else changed; an action outside the model may have changed anything.
In the symbolic world actions only return RUNNING, so everything learned from an action's
success or failure is vacuous there and the pruned tree ticks exactly like the original
in every state. Trees over at most ``EXACT_UP_TO`` conditions then get an exact stage on
sets of states, which also sees disjunctions (what holds after ``Fallback(a, b, X)``).
Rounds repeat until nothing changes; control nodes left with one child (not Inverters)
are replaced by that child. docs/reproduction.md lists where this departs from the
printed pseudo-code and why.
"""

from __future__ import annotations

from collections.abc import Mapping
from collections.abc import Sequence as Seq
from dataclasses import replace
from functools import reduce
from types import MappingProxyType

from teach.bt.nodes import (
    Action,
    Condition,
    Fallback,
    Inverter,
    Node,
    Parallel,
    Sequence,
    Status,
    action_names,
    condition_names,
    walk,
)
from teach.domain import Domain, Literal
from teach.errors import LearnError

Facts = dict[str, bool]
"""Literals known to hold, as condition name -> value. ``None`` stands for "impossible"."""

_NO_RAMIFICATIONS: Mapping[str, Seq[Literal]] = MappingProxyType({})


def prune(tree: Node, ramifications: Mapping[str, Seq[Literal]] = _NO_RAMIFICATIONS) -> Node:
    """The tree without redundant and unreachable nodes; it ticks like ``tree`` in every state.

    ``ramifications`` maps an action name to the literals its success makes true (the
    domain's action model, see :func:`ramifications_of`); an action it lists changes nothing
    else, an action it does not list may change anything.
    """
    return prune_with_report(tree, ramifications)[0]


def prune_with_report(tree: Node, ramifications: Mapping[str, Seq[Literal]] = _NO_RAMIFICATIONS
                      ) -> tuple[Node, list[str]]:
    """:func:`prune` plus the removed nodes as ``Kind:name#uid`` labels, in tree order."""
    facts = _facts_of_ramifications(ramifications)
    rounds = _Pruner(facts)
    while True:
        before = len(rounds.removed)
        tree = rounds.run(tree)
        if len(rounds.removed) > before:
            continue
        names = sorted(condition_names(tree).union(*(facts.get(a, {}) for a in action_names(tree))))
        if len(names) > EXACT_UP_TO:
            return tree, rounds.removed
        states = _States(names)
        tree = _Exact(states, facts, rounds.removed).visit(tree, states.all, False)[0]
        if len(rounds.removed) == before:
            return tree, rounds.removed


def ramifications_of(domain: Domain) -> dict[str, tuple[Literal, ...]]:
    """The action model's ramifications by action name, as :func:`prune` takes them; empty
    when the domain has no action model (then nothing is assumed about any action)."""
    return {a.name: a.ram for a in domain.actions} if domain.has_model else {}


def label(node: Node) -> str:
    """``Condition:BallFound#12`` or ``Sequence#3``: how removed nodes are reported."""
    kind = type(node).__name__
    if isinstance(node, (Condition, Action)):
        return f"{kind}:{node.name}#{node.uid}"
    return f"{kind}#{node.uid}"


def _facts_of_ramifications(ramifications: Mapping[str, Seq[Literal]]) -> dict[str, Facts]:
    result: dict[str, Facts] = {}
    for action in sorted(ramifications):
        facts: Facts = {}
        for literal in ramifications[action]:
            if facts.get(literal.name, literal.value) is not literal.value:
                raise LearnError(f"action {action} has both {literal.name} and !{literal.name} "
                                 "as ramifications")
            facts[literal.name] = literal.value
        result[action] = facts
    return result


def _meet(a: Facts | None, b: Facts | None) -> Facts | None:
    """What holds on either of two paths (``None``, an impossible path, adds nothing)."""
    if a is None:
        return b
    if b is None:
        return a
    return {name: value for name, value in a.items() if b.get(name) is value}


def _join(a: Facts | None, b: Facts | None) -> Facts | None:
    """What holds when both hold; ``None`` if they contradict."""
    if a is None or b is None:
        return None
    for name, value in b.items():
        if a.get(name, value) is not value:
            return None
    return a | b


def _with(facts: Facts, name: str, value: bool) -> Facts | None:
    known = facts.get(name)
    if known is None:
        return facts | {name: value}
    return facts if known is value else None


_SWAP = {Status.SUCCESS: Status.FAILURE, Status.FAILURE: Status.SUCCESS, None: None}


class _Outcome:
    """One analysed and rebuilt subtree: its replacement, its result if the context decides
    it (no action can tick then), the literals holding after SUCCESS and after FAILURE, and
    whether it contains an action (which may change the world mid-tick)."""

    __slots__ = ("node", "known", "success", "failure", "acts")

    def __init__(self, node: Node, known: Status | None, success: Facts | None,
                 failure: Facts | None, acts: bool):
        self.node, self.known, self.success, self.failure, self.acts = node, known, success, failure, acts


class _Pruner:
    """One round = one top-down pass that analyses and rebuilds the tree together."""

    def __init__(self, ramifications: dict[str, Facts]):
        self.ramifications = ramifications
        self.removed: list[str] = []

    def run(self, tree: Node) -> Node:
        return self.visit(tree, {}).node

    def drop(self, node: Node) -> None:
        self.removed.extend(label(n) for n in walk(node))

    def visit(self, node: Node, context: Facts) -> _Outcome:
        if isinstance(node, Condition):
            value = context.get(node.name)
            known = None if value is None else (Status.SUCCESS if value else Status.FAILURE)
            return _Outcome(node, known, _with(context, node.name, True),
                            _with(context, node.name, False), False)
        if isinstance(node, Action):
            # The action model's frame assumption: an action changes its ramifications and
            # nothing else; SUCCESS means they hold, FAILURE that they may hold or not. (In
            # the symbolic world an action returns neither, so nothing here can matter.)
            ram = self.ramifications.get(node.name)
            if ram is None:  # not in the action model: it may change anything
                return _Outcome(node, None, {}, {}, True)
            untouched = {name: value for name, value in context.items() if name not in ram}
            return _Outcome(node, None, untouched | ram, untouched, True)
        if isinstance(node, Inverter):
            inner = self.visit(node.child, context)
            rebuilt = node if inner.node is node.child else replace(node, child=inner.node)
            return _Outcome(rebuilt, _SWAP[inner.known], inner.failure, inner.success, inner.acts)
        if isinstance(node, (Sequence, Fallback)):
            out = self.chain(node, context)
        elif isinstance(node, Parallel):
            out = self.parallel(node, context)
        else:
            raise TypeError(f"not a node: {node!r}")  # pragma: no cover
        if not out.acts:
            # Conditions alone change nothing, so the context still holds afterwards, and a
            # result that is impossible leaves the other one certain: Fallback(c, !c) succeeds.
            out.success, out.failure = _join(context, out.success), _join(context, out.failure)
            if out.known is None and out.failure is None:
                out.known = Status.SUCCESS
            elif out.known is None and out.success is None:
                out.known = Status.FAILURE
        return out

    def chain(self, node: Sequence | Fallback, context: Facts) -> _Outcome:
        """Sequence and Fallback are duals: a Sequence passes the tick on after SUCCESS
        (its *neutral* result) and stops at anything else; a Fallback after FAILURE."""
        is_sequence = isinstance(node, Sequence)
        neutral = Status.SUCCESS if is_sequence else Status.FAILURE
        current: Facts | None = context       # what holds when the next child is reached
        exits: Facts | None = None            # what holds when some child stopped the chain
        decided = True                        # every child so far had a known result
        known: Status | None = neutral
        kept: list[Node] = []
        neutral_dropped: list[Node] = []
        acts = False
        kids = node.children
        reached = 0
        for kid in kids:
            if current is None:               # no tick gets here: the rest is unreachable
                break
            reached += 1
            out = self.visit(kid, current)
            acts = acts or out.acts
            passes, leaves = (out.success, out.failure) if is_sequence else (out.failure, out.success)
            if out.known is neutral:
                neutral_dropped.append(out.node)
                current = passes
                continue
            kept.append(out.node)
            exits = _meet(exits, leaves)
            if out.known is not None:         # decisive: the later siblings are unreachable
                if decided:
                    known = out.known
                current = None
                break
            decided = False
            known = None
            current = passes
        if not kept and neutral_dropped:      # every child neutral: one keeps the result
            kept.append(neutral_dropped.pop(0))
        for gone in neutral_dropped:
            self.drop(gone)
        for gone in kids[reached:]:
            self.drop(gone)
        success, failure = (current, exits) if is_sequence else (exits, current)
        rebuilt = self.rebuilt(node, kids, kept)
        return _Outcome(rebuilt, known, success, failure, acts)

    def parallel(self, node: Parallel, context: Facts) -> _Outcome:
        """Every child is ticked, so a child with a known result is removed only where the
        threshold can absorb it: M of N with one sure success is M-1 of N-1, with one sure
        failure M of N-1."""
        outcomes: list[_Outcome] = []
        acts = False
        for kid in node.children:
            # After an action has ticked, the state it was reached in may have changed.
            outcomes.append(self.visit(kid, {} if acts else context))
            acts = acts or outcomes[-1].acts
        n, m = len(outcomes), node.success_threshold
        if all(o.known is not None for o in outcomes):
            successes = sum(o.known is Status.SUCCESS for o in outcomes)
            known: Status | None = Status.SUCCESS if successes >= m else Status.FAILURE
        else:
            known = None
        kept: list[Node] = []
        for out in outcomes:
            if out.known is Status.SUCCESS and m >= 2 and n >= 2:
                m, n = m - 1, n - 1
                self.drop(out.node)
            elif out.known is Status.FAILURE and m <= n - 1:
                n -= 1
                self.drop(out.node)
            else:
                kept.append(out.node)
        success: Facts | None = {}
        failure: Facts | None = {}
        if not acts:  # all N succeed (M = N) or all fail (M = 1), else at least one of them
            everyone = len(outcomes)
            nothing_known: Facts | None = {}
            all_succeed, all_fail = node.success_threshold == everyone, node.success_threshold == 1
            success = reduce(_join if all_succeed else _meet, (o.success for o in outcomes),
                             nothing_known if all_succeed else None)
            failure = reduce(_join if all_fail else _meet, (o.failure for o in outcomes),
                             nothing_known if all_fail else None)
        rebuilt = self.rebuilt(node, node.children, kept, m)
        return _Outcome(rebuilt, known, success, failure, acts)

    def rebuilt(self, node: Sequence | Fallback | Parallel, kids: tuple[Node, ...], kept: list[Node],
                threshold: int | None = None) -> Node:
        """The control node with ``kept`` children (same uid), or its only child."""
        if len(kept) == 1:
            self.removed.append(label(node))
            return kept[0]
        if len(kept) == len(kids) and all(a is b for a, b in zip(kept, kids, strict=True)):
            return node
        if isinstance(node, Parallel):
            assert threshold is not None, "a Parallel is rebuilt with its new threshold"
            return replace(node, children=tuple(kept), success_threshold=threshold)
        return replace(node, children=tuple(kept))


# --- exact stage: sets of states ----------------------------------------------------------------

EXACT_UP_TO = 14
"""Trees over at most this many conditions also get the exact stage (sets of 2**n states)."""


class _States:
    """Sets of states as integers with one bit per state; condition i is bit i of a state's index."""

    def __init__(self, names: Seq[str]):
        self.count = 1 << len(names)
        self.all = (1 << self.count) - 1
        self.holds: dict[str, int] = {}
        self.shift: dict[str, int] = {}
        for i, name in enumerate(names):
            block, period = 1 << i, 2 << i
            pattern = ((1 << block) - 1) << block   # one period: condition false, then true
            while period < self.count:
                pattern |= pattern << period
                period *= 2
            self.holds[name], self.shift[name] = pattern, block

    def havoc(self, states: int, names: Seq[str]) -> int:
        """The states reachable by giving the named conditions any value."""
        for name in names:
            true, shift = self.holds[name], self.shift[name]
            states |= ((states & true) >> shift) | ((states & ~true & self.all) << shift)
        return states

    def assign(self, states: int, facts: Facts) -> int:
        for name, value in facts.items():
            states = self.havoc(states, (name,)) & (self.holds[name] if value else ~self.holds[name] & self.all)
        return states


class _Exact:
    """Drops a child of a Sequence or Fallback when, in every state a tick can reach it in,
    the siblings after it would give the same result without it: the child ticks no action
    there, and whenever it decides the parent (FAILURE in a Sequence, SUCCESS in a Fallback)
    the rest decides it the same way without ticking an action. This finds what literals
    alone cannot: after Fallback(a, b, X), a later !a is redundant in Fallback(!a, b, Y).

    Reach sets over-approximate the states a node is ticked in (an action's SUCCESS gives its
    ramifications, its FAILURE leaves them unknown: the same frame assumption as above); pure
    success and failure sets (no action ticked) under-approximate. After a drop the later
    siblings see other states, so a parent drops at most one child per round."""

    def __init__(self, states: _States, ramifications: dict[str, Facts], removed: list[str]):
        self.states, self.ramifications, self.removed = states, ramifications, removed
        self.pure: dict[int, tuple[int, int]] = {}

    def _counted(self, pairs: list[tuple[int, int]], threshold: int, pure: int) -> tuple[int, int]:
        """SUCCESS / FAILURE states of an M-of-N Parallel whose children are all pure there."""
        success = failure = 0
        for bit in range(pure.bit_length()):
            mask = 1 << bit
            if pure & mask:
                wins = sum(1 for won, _ in pairs if won & mask)
                if wins >= threshold:
                    success |= mask
                elif len(pairs) - wins > len(pairs) - threshold:
                    failure |= mask
        return success, failure

    def purity(self, node: Node) -> tuple[int, int]:
        """States in which the subtree returns SUCCESS / FAILURE without ticking an action."""
        key = id(node)
        if key in self.pure:
            return self.pure[key]
        s = self.states
        if isinstance(node, Condition):
            result = (s.holds[node.name], ~s.holds[node.name] & s.all)
        elif isinstance(node, Action):
            result = (0, 0)
        elif isinstance(node, Inverter):
            success, failure = self.purity(node.child)
            result = (failure, success)
        elif isinstance(node, (Sequence, Fallback)):
            passes, stops = 0, 0
            through = s.all
            for kid in node.children:
                success, failure = self.purity(kid)
                go, stop = (success, failure) if isinstance(node, Sequence) else (failure, success)
                stops |= through & stop
                through &= go
            passes = through
            result = (passes, stops) if isinstance(node, Sequence) else (stops, passes)
        else:  # Parallel: exact for every M, by counting where 1 < M < N
            pairs = [self.purity(kid) for kid in node.children]
            pure = s.all
            for success, failure in pairs:
                pure &= success | failure
            any_success = any_failure = 0
            all_success = all_failure = s.all
            for success, failure in pairs:
                any_success, any_failure = any_success | success, any_failure | failure
                all_success, all_failure = all_success & success, all_failure & failure
            if node.success_threshold == len(pairs):
                result = (all_success, pure & any_failure)
            elif node.success_threshold == 1:
                result = (pure & any_success, all_failure)
            else:
                result = self._counted(pairs, node.success_threshold, pure)
        self.pure[key] = result
        return result

    def visit(self, node: Node, reach: int, frozen: bool) -> tuple[Node, int, int]:
        """The rebuilt node and the states after it returns SUCCESS / FAILURE."""
        s = self.states
        if isinstance(node, Condition):
            return node, reach & s.holds[node.name], reach & ~s.holds[node.name]
        if isinstance(node, Action):
            ram = self.ramifications.get(node.name)
            if ram is None:
                return node, s.all, s.all
            return node, s.assign(reach, ram), s.havoc(reach, tuple(ram))
        if isinstance(node, Inverter):
            child, success, failure = self.visit(node.child, reach, frozen)
            return (node if child is node.child else replace(node, child=child)), failure, success
        if isinstance(node, Parallel):
            return self.parallel(node, reach, frozen)
        return self.chain(node, reach, frozen)

    def chain(self, node: Sequence | Fallback, reach: int, frozen: bool) -> tuple[Node, int, int]:
        is_sequence = isinstance(node, Sequence)
        kids = node.children
        tails = [0] * (len(kids) + 1)  # states where kids[i:] stop the chain purely
        for i in range(len(kids) - 1, -1, -1):
            success, failure = self.purity(kids[i])
            go, stop = (success, failure) if is_sequence else (failure, success)
            tails[i] = stop | (go & tails[i + 1])
        kept: list[Node] = []
        current, exits = reach, 0
        for i, kid in enumerate(kids):
            success, failure = self.purity(kid)
            go, stop = (success, failure) if is_sequence else (failure, success)
            if not frozen and len(kids) > 1 and current & ~(success | failure) == 0 \
                    and current & stop & ~tails[i + 1] == 0:
                self.removed.extend(label(n) for n in walk(kid))
                frozen = True
                # it ticks no action here, so the state passes through it unchanged
                current, exits = current & go, exits | (current & stop)
                continue
            rebuilt, after_success, after_failure = self.visit(kid, current, frozen)
            kept.append(rebuilt)
            passes, leaves = (after_success, after_failure) if is_sequence else (after_failure, after_success)
            exits |= leaves
            current = passes
        success, failure = (current, exits) if is_sequence else (exits, current)
        if len(kept) == 1:
            self.removed.append(label(node))
            return kept[0], success, failure
        if len(kept) == len(kids) and all(a is b for a, b in zip(kept, kids, strict=True)):
            return node, success, failure
        return replace(node, children=tuple(kept)), success, failure

    def parallel(self, node: Parallel, reach: int, frozen: bool) -> tuple[Node, int, int]:
        s = self.states
        kids: list[Node] = []
        acts = False
        for kid in node.children:
            rebuilt, _, _ = self.visit(kid, s.all if acts else reach, frozen)
            kids.append(rebuilt)
            acts = acts or any(isinstance(n, Action) for n in walk(kid))
        unchanged = all(a is b for a, b in zip(kids, node.children, strict=True))
        rebuilt_node = node if unchanged else replace(node, children=tuple(kids))
        if acts:
            return rebuilt_node, s.all, s.all
        success, failure = self.purity(node)  # exact: no child ticks an action
        return rebuilt_node, reach & success, reach & failure
