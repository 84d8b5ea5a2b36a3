"""A SAM-style baseline (Safe Action Model learning; Juba, Le & Stern, KR 2021), grounded.

- preconditions of an action: every literal, positive and negative, that held in every state
  where the action was applied (so nothing that might be needed is ever dropped);
- effects: every literal an application of the action changed;
- goal: every literal common to all goal states (the last lines of the demonstrations);
- tree: a regression policy over that model. The goal is regressed through the actions
  breadth-first; each regressed condition (the action's SAM preconditions plus what the goal
  still needs) becomes ``Sequence(literals..., action)``, nearest the goal first, after a
  ``Sequence(goal literals...)`` that returns SUCCESS. So an action runs only where all its
  SAM preconditions hold, and "done" only where the whole SAM goal holds.

Where the domain declares forms (``teach.learn.lifting``), it is lifted SAM: a transition of one
instance is, renamed, one of each sibling, and only conditions about an action's own objects can
be its preconditions, exactly as the default learner reads such a domain.

An action is used only once it, or (with forms) an action of its kind, was demonstrated. Online: ``update`` after each
demonstration.
"""

from __future__ import annotations

from dataclasses import dataclass

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Sequence
from teach.demos import Demonstration
from teach.domain import Domain
from teach.learn.bits import state_mask
from teach.learn.lifting import lifting_of
from teach.learn.regress import MAX_RULE_NODES, rule_nodes_count


@dataclass
class _Known:
    pre_true: int
    pre_false: int
    add: int = 0
    delete: int = 0


class SamLearner:
    """Learns online; ``tree`` is the regression policy of the model learned so far."""

    def __init__(self, domain: Domain):
        self.domain = domain
        self._n = len(domain.conditions)
        self._full = (1 << self._n) - 1
        self.known: dict[str, _Known] = {}
        self._lifting = lifting_of(domain)
        self.goal: tuple[int, int] | None = None
        self._tree: Node | None = None

    def update(self, demo: Demonstration, source: str | None = None) -> bool:
        """Learn one demonstration; True if the tree changed."""
        before = self.tree
        self.learn(demo)
        return self.tree != before

    def learn(self, demo: Demonstration) -> None:
        """Learn one demonstration's model (the tree is built when next asked for)."""
        steps = demo.steps
        for i, step in enumerate(steps):
            mask = state_mask(step.state)
            if step.action == 0:
                true, false = self.goal or (self._full, self._full)
                self.goal = (true & mask, false & ~mask & self._full)
                continue
            if step.action < 0:
                continue
            name = self.domain.action(step.action).name
            after = state_mask(steps[i + 1].state) if i + 1 < len(steps) else None
            self._learn(name, mask, after, self._full)
            for renaming in self._lifting.renamings.get(name, ()) if self._lifting else ():
                self._learn(renaming.sibling, renaming.mask(mask), None if after is None else renaming.mask(after),
                            renaming.image)
        self._tree = None

    def _learn(self, name: str, mask: int, after: int | None, known_bits: int) -> None:
        """One application of ``name`` in ``mask`` (then ``after``), saying nothing outside ``known_bits``."""
        own = self._lifting.own[name] if self._lifting else self._full
        known = self.known.setdefault(name, _Known(own, own))
        known.pre_true &= mask | ~known_bits
        known.pre_false &= ~mask | ~known_bits
        if after is not None:
            known.add |= after & ~mask & known_bits
            known.delete |= mask & ~after & known_bits

    def successors(self, state: int) -> list[int]:
        """What the learned actions make of ``state`` where all their SAM preconditions hold. In a
        STRIPS world these are true successors: an effect never seen held before and after every
        time, so it is a precondition that holds here too."""
        return [(state & ~k.delete) | k.add for k in self.known.values()
                if state & k.pre_true == k.pre_true and not state & k.pre_false]

    def done(self, state: int) -> bool:
        """Whether every literal common to the demonstrations' goal states holds in ``state``."""
        return self.goal is not None and state & self.goal[0] == self.goal[0] and not state & self.goal[1]

    @property
    def tree(self) -> Node:
        if self._tree is None:
            self._tree = self._build()
        return self._tree

    def rules(self) -> list[tuple[int, int, str]]:
        """Regressed conditions (literals true, literals false) with their action, nearest the goal first."""
        if self.goal is None:
            return []
        found: list[tuple[int, int, str]] = []
        kept = [self.goal]
        frontier = [self.goal]
        order = [a.name for a in self.domain.actions if a.name in self.known]
        nodes = 0
        while frontier:
            reached: list[tuple[int, int]] = []
            for true, false in frontier:
                for name in order:
                    k = self.known[name]
                    if not (k.add & true or k.delete & false) or k.delete & true & ~k.add or k.add & false:
                        continue
                    need_true = (true & ~k.add) | k.pre_true
                    need_false = (false & ~k.delete) | k.pre_false
                    if need_true & need_false or any(t & ~need_true == 0 and f & ~need_false == 0 for t, f in kept):
                        continue
                    nodes += rule_nodes_count(need_true, need_false)
                    if nodes > MAX_RULE_NODES:  # the learner's budget (teach.learn.regress)
                        return found
                    kept.append((need_true, need_false))
                    reached.append((need_true, need_false))
                    found.append((need_true, need_false, name))
            frontier = reached
        return found

    def _build(self) -> Node:
        kids: list[Node] = []
        if self.goal is not None:
            literals = self._literals(*self.goal)
            # nothing common to the goal states: done everywhere
            kids.append(Sequence(tuple(literals)) if literals else Fallback(self._either()))
        for true, false, name in self.rules():
            kids.append(Sequence((*self._literals(true, false), Action(name))))
        if not kids:
            return Sequence(self._either())
        return kids[0] if len(kids) == 1 else Fallback(tuple(kids))

    def _either(self) -> tuple[Node, Node]:
        """A condition and its negation: in a Fallback always SUCCESS, in a Sequence always FAILURE."""
        name = self.domain.condition_names[0]
        return Condition(name), Inverter(Condition(name))

    def _literals(self, true: int, false: int) -> list[Node]:
        names = self.domain.condition_names
        return [Condition(names[i]) if true >> i & 1 else Inverter(Condition(names[i]))
                for i in range(self._n) if (true | false) >> i & 1]
