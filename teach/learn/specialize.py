"""Approach 3 (thesis §4.3.2): specialize an over-general tree on demonstrations, online.

The initial tree (Fig. 4.7) is a Sequence with, per action in the demonstrated order, a
Fallback of every condition and every inverted condition (the *guards*) and then the action.
One guard of each literal pair always holds, so the tree starts out returning SUCCESS. An
action runs in a state iff none of its guards holds there and every action before it is
guarded. Replaying a demonstration, wherever the tree does not run the expected action, the
thesis removes from that action's Fallback every guard that holds in that state.

Where that algorithm cannot proceed this learner extends it (with only guard removal needed,
it does exactly what the thesis does, so §6.4's figures are unaffected):

(a) a demonstration with an action not yet in the tree inserts a fresh all-guards Fallback
    for it where the order edges seen so far allow (the order is always the topological order
    of all edges seen, ties broken by first appearance, so online and batch learning end with
    the same order); a demonstration contradicting the order is refused with a
    ``LearnError`` that names both directions, and the learner is left unchanged;
(b) when an earlier action b runs where a later action a is expected, removing a's guards
    cannot help: b gets a new guard that holds here and in none of the states where b was
    shown, the smallest conjunction of this state's literals found greedily (a Sequence of
    conditions and inverted conditions, or one literal);
(c) the same when an action runs at a goal line, where SUCCESS is expected.

Keeping what was learned: removing guards of an action can make it run in a state seen
earlier where something else was expected. Every state where an action must not run is kept
per action (``protect``), and after a removal the states left without a holding guard get an
extension-(b) guard at once. So every labelled situation stays reproduced without replaying
old demonstrations; only a change of the relative order of existing actions (a new edge
against the current tie-breaking) re-checks the stored situations. The same state labelled
with two different actions (or an action and the goal) cannot be reproduced by a memoryless
tree: the ``LearnError`` names both demonstrations and the state.

Internally a state is an int bitmask (bit i = condition i), and an action's literal guards
are two bitmasks, so testing all guards of an action in a state is two ``&`` operations.
"""

from __future__ import annotations

from collections.abc import Sequence as Seq
from dataclasses import dataclass, field

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Sequence, new_uid
from teach.demos import Demonstration
from teach.domain import Domain, Literal, State
from teach.errors import LearnError
from teach.learn.bits import mask_state, state_mask
from teach.learn.order import OrderGraph, action_order, demo_source

GOAL = None
"""The label of a goal line: the tree must return SUCCESS there."""


@dataclass(frozen=True)
class Guard:
    """A guard in front of an action: while it holds, the action does not run."""

    literals: tuple[Literal, ...]
    uid: int
    origin: str
    """"initial" (Fig. 4.7), or the situation (``file:line``) that added it."""
    needed_by: tuple[str, ...]
    """Situations (``file:line``) where the action must not run and this guard stops it;
    empty when no demonstration needs the guard yet (it is an assumption)."""

    def __str__(self) -> str:
        return " & ".join(str(lit) for lit in self.literals)


@dataclass(frozen=True)
class Change:
    """One edit of the tree: a guard removed or added, an action inserted, the order changed."""

    kind: str
    action: str
    uid: int
    text: str
    source: str


@dataclass(frozen=True)
class Update:
    """What one demonstration or labelled situation changed, and a sentence saying so."""

    source: str
    changes: tuple[Change, ...] = ()
    sentence: str = ""

    @property
    def changed(self) -> bool:
        return bool(self.changes)

    def of_kind(self, kind: str) -> list[Change]:
        return [c for c in self.changes if c.kind == kind]

    @property
    def removed(self) -> list[Change]:
        return self.of_kind("removed")

    @property
    def added(self) -> list[Change]:
        return self.of_kind("added")

    @property
    def inserted(self) -> list[str]:
        return [c.action for c in self.of_kind("inserted")]


@dataclass
class _Conj:
    """A guard added by extension (b)/(c): holds where ``state & mask == value``."""

    mask: int
    value: int
    node: Node
    literals: tuple[Literal, ...]
    origin: str


@dataclass
class _Slot:
    """Everything the learner keeps about one action's Fallback."""

    name: str
    fallback_uid: int
    action: Action
    literal_nodes: dict[tuple[int, bool], Node]
    pos: int
    neg: int
    conj: list[_Conj] = field(default_factory=list)
    shown: dict[int, str] = field(default_factory=dict)
    protect: dict[int, str] = field(default_factory=dict)
    node: Fallback | None = None


class Specializer:
    """The Approach-3 learner; ``update`` learns one demonstration at the cost of replaying it."""

    def __init__(self, domain: Domain, order: Seq[str] = ()):
        self.domain = domain
        self._n = len(domain.conditions)
        self._full = (1 << self._n) - 1
        self._graph = OrderGraph()
        self._slots: dict[str, _Slot] = {}
        self._order: list[str] = []
        self._position: dict[str, int] = {}
        self._labels: dict[int, tuple[str | None, str]] = {}
        self._root_uid = new_uid()
        self._tree: Node | None = None
        self._about: dict[int, tuple[str, str, object]] = {}
        self._removed: dict[int, str] = {}
        for name in order:
            self.domain.action(name)
            self._graph.add_action(name)
            self._new_slot(name)
        self._set_order(list(order))

    # --- public API ---------------------------------------------------------------------------

    @property
    def tree(self) -> Node:
        """The current (unpruned) tree; node uids stay the same across updates."""
        if self._tree is None:
            fallbacks = []
            for name in self._order:
                slot = self._slots[name]
                if slot.node is None:
                    slot.node = self._build_fallback(slot)
                fallbacks.append(slot.node)
            self._tree = Sequence(tuple(fallbacks), uid=self._root_uid)
        return self._tree

    @property
    def order(self) -> list[str]:
        return list(self._order)

    def update(self, demo: Demonstration, source: str | None = None) -> Update:
        """Learn one more demonstration without revisiting the earlier ones."""
        where = source or demo_source(demo)
        graph = self._graph
        if self._graph.is_new(self.domain, demo):
            graph = self._graph.copy()
            graph.add_demo(self.domain, demo, where)
        situations = []
        for step in demo.steps:
            if step.action < 0:
                continue
            label = None if step.action == 0 else self.domain.action(step.action).name
            situations.append((self._mask(step.state), label, f"{where}:{step.line}"))
        self._check_labels(situations)
        changes: list[Change] = []
        self._adopt(graph, where, changes)
        for mask, label, evidence in situations:
            self._learn(mask, label, evidence, changes)
        return self._finish(where, changes)

    def teach_step(self, state: State, action: str | None, source: str) -> Update:
        """Learn one labelled situation: ``action`` runs in ``state`` (None: the goal holds here)."""
        if len(state) != self._n:
            raise LearnError(f"a state needs {self._n} truth values, got {len(state)}", source)
        mask = self._mask(state)
        self._check_labels([(mask, action, source)])
        graph = self._graph
        if action is not None and action not in graph.first_seen:
            self.domain.action(action)
            graph = self._graph.copy()
            graph.add_action(action)
        changes: list[Change] = []
        self._adopt(graph, source, changes)
        self._learn(mask, action, source, changes)
        return self._finish(source, changes)

    def guards(self, action: str) -> list[Guard]:
        """The guards still in front of ``action``, with the situations that need each one."""
        slot = self._slot(action)
        result = []
        for (index, value), node in self._literal_guards(slot):
            bit = 1 << index
            needed = tuple(src for u, src in slot.protect.items() if bool(u & bit) == value)
            result.append(Guard((Literal(self.domain.conditions[index].name, value),), node.uid, "initial", needed))
        for conj in slot.conj:
            needed = tuple(src for u, src in slot.protect.items() if u & conj.mask == conj.value)
            result.append(Guard(conj.literals, conj.node.uid, conj.origin, needed))
        return result

    def shown_states(self, action: str) -> list[State]:
        """The states in which ``action`` was demonstrated, first seen first."""
        return [self._state(mask) for mask in self._slot(action).shown]

    def explain(self, uid: int) -> str:
        """Why the node ``uid`` exists (or was removed): the demonstrations and answers behind it."""
        if uid in self._removed:
            return self._removed[uid]
        if uid == self._root_uid:
            return ("the root Sequence: the actions in the demonstrated order " + " → ".join(self._order)
                    + "; an action runs when none of its guards holds and every action before it is done")
        if uid not in self._about:
            raise LearnError(f"no node {uid} in the learned tree")
        kind, action, key = self._about[uid]
        slot = self._slots[action]
        if kind == "fallback":
            first = next(iter(slot.shown.values()), None)
            return (f"the Fallback in front of {action}: {action} runs unless one of its guards holds"
                    + (f"; first demonstrated at {first}" if first else "; not demonstrated yet"))
        if kind == "action":
            if not slot.shown:
                return f"{action}: in the demonstrated order, not demonstrated in any state yet"
            sources = list(slot.shown.values())
            return f"{action}: demonstrated in {len(sources)} state(s): {_few(sources)}"
        if key in self._removed:
            return self._removed[key]  # a node inside a removed guard
        guard = next(g for g in self.guards(action) if g.uid == key)
        stops = (f"it keeps {action} from running at {_few(list(guard.needed_by))}" if guard.needed_by
                 else "no demonstration needs it yet (an assumption a question could settle)")
        if guard.origin == "initial":
            return (f"guard {guard} of {action}: in the initial tree every literal guards every action "
                    f"(Fig. 4.7); kept because {action} was never shown where {guard} holds; {stops}")
        return f"guard {guard} of {action}: added at {guard.origin}, where {action} must not run; {stops}"

    # --- learning ---------------------------------------------------------------------------------

    def _check_labels(self, situations: Seq[tuple[int, str | None, str]]) -> None:
        """Refuse a situation whose state already carries another label (before changing anything)."""
        local: dict[int, tuple[str | None, str]] = {}
        for mask, label, evidence in situations:
            known = self._labels.get(mask) or local.get(mask)
            if known is not None and known[0] != label:
                other, where = known
                raise LearnError(f"the demonstrations contradict each other: in the state "
                                 f"[{self.domain.describe(self._state(mask))}] {where} shows {_label(other)} "
                                 f"but {evidence} shows {_label(label)}; one tree cannot do both",
                                 kind="contradiction")
            local.setdefault(mask, (label, evidence))

    def _adopt(self, graph: OrderGraph, where: str, changes: list[Change]) -> None:
        """Take the checked order graph: insert new actions, reorder if an edge demands it."""
        if graph is self._graph:
            return
        self._graph = graph
        fresh = [name for name in graph.first_seen if name not in self._slots]
        for name in fresh:
            slot = self._new_slot(name)
            changes.append(Change("inserted", name, slot.fallback_uid, name, where))
        if not fresh and not graph.violated_by(self._order):
            return
        order = graph.order()
        old = [name for name in order if name not in fresh]
        moved = old != self._order
        self._set_order(order)
        if moved:
            changes.append(Change("reordered", "", self._root_uid, " → ".join(order), where))
            for slot in self._slots.values():
                slot.protect = self._protected(slot.name)
            for mask, (label, evidence) in list(self._labels.items()):
                self._fix(mask, label, evidence, changes)
        else:
            for name in fresh:
                self._slots[name].protect = self._protected(name)

    def _learn(self, mask: int, label: str | None, evidence: str, changes: list[Change]) -> None:
        if mask in self._labels:
            return  # checked: same label, and every labelled state is reproduced already
        self._labels[mask] = (label, evidence)
        if label is not None:
            self._slots[label].shown[mask] = evidence
        self._fix(mask, label, evidence, changes)
        stop = len(self._order) if label is None else self._position[label]
        for name in self._order[:stop]:
            self._slots[name].protect[mask] = evidence

    def _fix(self, mask: int, label: str | None, evidence: str, changes: list[Change]) -> None:
        """Edit until the tree does ``label`` in this state (thesis step, then extensions)."""
        while True:
            running = self._runs(mask)
            if running == label:
                return
            if label is not None and (running is None or self._position[running] > self._position[label]):
                self._remove_guards(label, mask, evidence, changes)
            else:
                self._add_guard(running, mask, evidence, changes)  # type: ignore[arg-type]

    def _runs(self, mask: int) -> str | None:
        """The action the tree runs in this state, or None when it returns SUCCESS."""
        inverse = mask ^ self._full
        for name in self._order:
            slot = self._slots[name]
            if not (mask & slot.pos or inverse & slot.neg or any(mask & c.mask == c.value for c in slot.conj)):
                return name
        return None

    def _guarded(self, slot: _Slot, mask: int) -> bool:
        return bool(mask & slot.pos or (mask ^ self._full) & slot.neg
                    or any(mask & c.mask == c.value for c in slot.conj))

    def _remove_guards(self, action: str, mask: int, evidence: str, changes: list[Change]) -> None:
        """The thesis's step: drop every guard of ``action`` that holds in this state."""
        slot = self._slots[action]
        holding_pos, holding_neg = slot.pos & mask, slot.neg & (mask ^ self._full)
        for (index, value), node in self._literal_guards(slot):
            if (holding_pos if value else holding_neg) >> index & 1:
                self._note_removed(slot, node, str(Literal(self.domain.conditions[index].name, value)),
                                   evidence, changes)
        slot.pos &= ~mask
        slot.neg &= mask
        keep = []
        for conj in slot.conj:
            if mask & conj.mask == conj.value:
                self._note_removed(slot, conj.node, " & ".join(map(str, conj.literals)), evidence, changes)
            else:
                keep.append(conj)
        slot.conj = keep
        self._changed(slot)
        for protected, where in slot.protect.items():
            if not self._guarded(slot, protected):
                self._add_guard(action, protected, where, changes)

    def _add_guard(self, action: str, mask: int, evidence: str, changes: list[Change]) -> None:
        """Extensions (b)/(c): a guard holding here and in no state where ``action`` was shown."""
        slot = self._slots[action]
        diffs = [shown ^ mask for shown in slot.shown]
        chosen = 0
        while diffs:
            best, best_count = 0, -1
            for index in range(self._n):
                if not chosen >> index & 1:
                    count = sum(d >> index & 1 for d in diffs)
                    if count > best_count:
                        best, best_count = index, count
            chosen |= 1 << best
            diffs = [d for d in diffs if not d >> best & 1]
        if not chosen:
            chosen = 1
        literals = tuple(Literal(c.name, bool(mask >> i & 1)) for i, c in enumerate(self.domain.conditions)
                         if chosen >> i & 1)
        leaves = [_literal_node(lit) for lit in literals]
        node = leaves[0] if len(leaves) == 1 else Sequence(tuple(leaves))
        conj = _Conj(chosen, mask & chosen, node, literals, evidence)
        slot.conj.append(conj)
        self._register(slot, node)
        self._changed(slot)
        changes.append(Change("added", action, node.uid, " & ".join(map(str, literals)), evidence))

    # --- bookkeeping ------------------------------------------------------------------------------

    def _new_slot(self, name: str) -> _Slot:
        literal_nodes: dict[tuple[int, bool], Node] = {}
        for index, condition in enumerate(self.domain.conditions):
            for value in (True, False):
                literal_nodes[(index, value)] = _literal_node(Literal(condition.name, value))
        slot = _Slot(name, new_uid(), Action(name), literal_nodes, self._full, self._full)
        self._slots[name] = slot
        self._about[slot.fallback_uid] = ("fallback", name, None)
        self._about[slot.action.uid] = ("action", name, None)
        for node in literal_nodes.values():
            self._register(slot, node)
        return slot

    def _register(self, slot: _Slot, node: Node) -> None:
        """Remember which guard a node (and the nodes inside it) belongs to, for ``explain``."""
        self._about[node.uid] = ("guard", slot.name, node.uid)
        for inner in (node.child,) if isinstance(node, Inverter) else getattr(node, "children", ()):
            self._about[inner.uid] = ("guard", slot.name, node.uid)
            if isinstance(inner, Inverter):
                self._about[inner.child.uid] = ("guard", slot.name, node.uid)

    def _note_removed(self, slot: _Slot, node: Node, text: str, evidence: str, changes: list[Change]) -> None:
        self._removed[node.uid] = (f"guard {text} of {slot.name} was removed at {evidence}: "
                                   f"{slot.name} was shown there while {text} held")
        changes.append(Change("removed", slot.name, node.uid, text, evidence))

    def _literal_guards(self, slot: _Slot) -> list[tuple[tuple[int, bool], Node]]:
        return [(key, node) for key, node in slot.literal_nodes.items()
                if (slot.pos if key[1] else slot.neg) >> key[0] & 1]

    def _build_fallback(self, slot: _Slot) -> Fallback:
        kids = [node for _key, node in self._literal_guards(slot)] + [c.node for c in slot.conj]
        return Fallback((*kids, slot.action), uid=slot.fallback_uid)

    def _changed(self, slot: _Slot) -> None:
        slot.node = None
        self._tree = None

    def _set_order(self, order: list[str]) -> None:
        self._order = order
        self._position = {name: i for i, name in enumerate(order)}
        self._tree = None

    def _protected(self, name: str) -> dict[int, str]:
        """The labelled states where ``name`` must not run (something later, or the goal, is due)."""
        here = self._position[name]
        return {mask: evidence for mask, (label, evidence) in self._labels.items()
                if label is None or self._position[label] > here}

    def _slot(self, action: str) -> _Slot:
        if action not in self._slots:
            raise LearnError(f"{action} is not in the learned tree")
        return self._slots[action]

    def _mask(self, state: State) -> int:
        return state_mask(state)

    def _state(self, mask: int) -> State:
        return mask_state(mask, self._n)

    def _finish(self, where: str, changes: list[Change]) -> Update:
        if not changes:
            return Update(where, (), f"{where}: the tree already does this; nothing changed")
        parts = []
        for kind, verb in (("inserted", "inserted"), ("reordered", "reordered to"),
                           ("removed", "removed"), ("added", "added")):
            items = [c for c in changes if c.kind == kind]
            if not items:
                continue
            if kind == "inserted":
                parts.append(f"inserted {', '.join(c.action for c in items)}")
            elif kind == "reordered":
                parts.append(f"reordered to {items[-1].text}")
            else:
                by_action: dict[str, list[str]] = {}
                for c in items:
                    by_action.setdefault(c.action, []).append(c.text)
                parts.append(f"{verb} " + "; ".join(
                    f"{len(texts)} guard(s) of {action} ({', '.join(texts)})" for action, texts in by_action.items()))
        return Update(where, tuple(changes), f"{where}: " + "; ".join(parts))


def _literal_node(literal: Literal) -> Node:
    condition = Condition(literal.name)
    return condition if literal.value else Inverter(condition)


def _label(label: str | None) -> str:
    return "the goal (SUCCESS)" if label is None else label


def _few(sources: list[str], limit: int = 5) -> str:
    more = f" and {len(sources) - limit} more" if len(sources) > limit else ""
    return ", ".join(sources[:limit]) + more


def specialize(domain: Domain, demos: Seq[Demonstration]) -> Specializer:
    """Batch Approach 3: the order of all demonstrations, then ``update`` with each in turn."""
    if not demos:
        raise LearnError("no demonstrations to specialize on", domain.path)
    learner = Specializer(domain, action_order(domain, demos))
    for demo in demos:
        learner.update(demo)
    return learner
