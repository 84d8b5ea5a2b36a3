"""A behaviour tree in plain sentences: the caregiver's view of what the robot learned.

A tree is read as an ordered list of rules, "the first that fits": each action with the
checks that must hold before it is ticked (a condition in a Sequence must hold, one in a
Fallback must not, a step that comes after one that makes something hold comes only once it
holds), and "I am done" where the root succeeds. Read that way, the backchained trees the
learners build say what a teacher would say: "When the ball is in the bin, I am done.
Otherwise: if I cannot see the ball, I find the ball; ...". A check is left out where an
earlier rule would fit if it did not hold (the order says it), and so is a rule that repeats
an earlier one's step where that one always fits first. For a learned tree the first rule
that fits is what the tree does, in every state (``said_to_do``; tested on learned trees of
the ball, snacks and blocksworld): the words never promise a step the robot would not take
(before, a ball "put in the bin" without "the ball is in my hand"). A part that is neither
conditions nor Sequences and Fallbacks of them (a Parallel, an Inverter over actions) is
named by its actions, with a pointer to ``show full``. Pure: tree, domain and language in,
lines out.
"""

from __future__ import annotations

import functools
import operator
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

from teach import messages as m
from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Sequence, walk
from teach.dialogue.questions import MAX_FALSE_NAMED, join_words, only_these
from teach.domain import Domain
from teach.messages import Lang


@dataclass(frozen=True)
class _Check:
    """Something the tree tests without acting: a literal, or an all/any of checks;
    ``kind`` "opaque" for a test of a shape that has no simple words."""

    kind: str  # "literal", "all", "any", "opaque"
    name: str = ""
    value: bool = True
    parts: tuple[_Check, ...] = ()

    def holds(self, values: Mapping[str, bool]) -> bool:
        """Whether it holds where conditions have ``values`` (an opaque test never does)."""
        if self.kind == "literal":
            return values[self.name] == self.value
        if self.kind == "all":
            return all(part.holds(values) for part in self.parts)
        return self.kind == "any" and any(part.holds(values) for part in self.parts)

    def negated(self) -> _Check:
        if self.kind == "literal":
            return _Check("literal", self.name, not self.value)
        if self.kind in ("all", "any"):  # De Morgan
            return _Check("any" if self.kind == "all" else "all", parts=tuple(p.negated() for p in self.parts))
        return self


@dataclass(frozen=True)
class _Rule:
    guard: tuple[_Check, ...]
    kind: str  # "done", "action", "opaque"
    actions: tuple[str, ...] = ()
    done_when: _Check | None = None
    """For "done": what holds then (the guard is what earlier parts of the tree add to it)."""
    then: bool = False
    """It follows an action of its Sequence: it comes when that one has worked, not as the first that fits."""

    @property
    def condition(self) -> tuple[_Check, ...]:
        return self.guard + ((self.done_when,) if self.done_when is not None else ())


def done_words(tree: Node, domain: Domain, lang: Lang) -> str | None:
    """When the tree says it is done, as the first line of ``tree_lines`` says it ("When the ball
    is in the bin, I am done."); None if its root does not check that first."""
    rules = _said(tree)
    return _done_line(_goal_rules(rules), domain, lang)


def _goal_rules(rules: list[_Rule]) -> list[_Rule]:
    """The rules saying "done" that the root's Fallback tries first, taken off ``rules``."""
    goal = []
    while rules and rules[0].kind == "done" and not rules[0].guard:
        goal.append(rules.pop(0))
    return goal


def _done_line(goal: list[_Rule], domain: Domain, lang: Lang) -> str | None:
    if not goal:
        return None
    return m.WORDS_DONE_WHEN(lang, condition=m.OR(lang).join(_all_words(rule.condition, domain, lang) for rule in goal))


def tree_lines(tree: Node, domain: Domain, lang: Lang) -> list[str]:
    """What the tree does, in sentences of ``lang``, one rule a line."""
    rules = _said(tree)
    lines: list[str] = []
    goal = _goal_rules(rules)
    done = _done_line(goal, domain, lang)
    if done is not None:  # the checks the root's Fallback tries first
        lines.append(done)
    if not rules:
        lines.append((m.WORDS_OTHERWISE_NOTHING if goal else m.WORDS_NOTHING)(lang))
        return lines
    lines.append((m.WORDS_OTHERWISE_FIRST_FIT if goal else m.WORDS_FIRST_FIT)(lang))
    for number, rule in enumerate(rules):
        what = _what(rule, domain, lang)
        if rule.condition:
            text = m.WORDS_IF(lang, condition=_all_words(rule.condition, domain, lang), what=what)
        else:
            text = (m.WORDS_OTHERWISE if number else m.WORDS_FIRST)(lang, what=what)
        lines.append(m.WORDS_BULLET(lang, text=text))
    return lines


def said_to_do(tree: Node) -> Callable[[Mapping[str, bool]], str | None]:
    """What ``tree_lines`` says the robot does where the conditions have the values given: the first
    rule that fits, an action's name or "done"; None where none fits (it stops). For the trees the
    learners build this is what the tree does, in every state."""
    rules = _said(tree)

    def said(values: Mapping[str, bool]) -> str | None:
        for rule in rules:
            if all(check.holds(values) for check in rule.condition):
                if rule.kind == "done":
                    return "done"
                return " or ".join(rule.actions) or None  # a part with no simple words: one of its actions
        return None

    return said


def _said(tree: Node) -> list[_Rule]:
    """The rules ``tree_lines`` says, in order."""
    return _reachable(_shortened(_deduplicated(_rules(tree, (), at_root=True))))


def _rules(node: Node, guard: tuple[_Check, ...], at_root: bool) -> list[_Rule]:
    """The rules of ``node`` in tick order; ``at_root``: the node succeeding means the task is done."""
    if isinstance(node, Action):
        return [_Rule(guard, "action", (node.name,))]
    check = _check(node)
    if check is not None:
        return [_Rule(guard, "done", done_when=check)] if at_root else []
    if at_root and isinstance(node, Sequence):
        each = [_check(child) or _reached_when(child) for child in node.children]
        if each and all(r is not None for r in each):  # one part after the other: done when each is
            parts = tuple(r for r in each if r is not None)
            done = _Rule(guard, "done", done_when=parts[0] if len(parts) == 1 else _Check("all", parts=parts))
            in_turn = [done]
            for child, holds in zip(node.children, parts, strict=True):
                in_turn += _rules(child, guard, at_root=False)
                guard += (holds,)  # the parts after it come only once it holds
            return in_turn
    if isinstance(node, Sequence | Fallback):
        rules: list[_Rule] = []
        inside = guard
        acted = False  # in a Sequence: an action came before
        for child in node.children:
            child_check = _check(child)
            if child_check is None:
                found = _rules(child, inside, at_root and isinstance(node, Fallback))
                rules += [replace(rule, then=True) for rule in found] if acted else found
                reached = _reached_when(child) if isinstance(node, Sequence) else None
                if reached is not None:  # the steps after it come only once it holds ("the ball is in my hand")
                    inside += (reached,)
                else:
                    acted = isinstance(node, Sequence) and (acted or any(r.kind != "done" for r in found))
            elif isinstance(node, Sequence):
                inside += (child_check,)
            elif at_root:  # the task is done when it holds; later rules need not say it does not
                rules.append(_Rule(inside, "done", done_when=child_check))
            else:
                inside += (child_check.negated(),)
        return rules
    names = tuple(dict.fromkeys(n.name for n in walk(node) if isinstance(n, Action)))
    return [_Rule(guard, "opaque", names)]


def _reached_when(node: Node) -> _Check | None:
    """What holds when a Fallback that tries checks first succeeds without acting (None: not that shape)."""
    if not isinstance(node, Fallback) or _check(node) is not None:
        return None
    leading = []
    for child in node.children:
        check = _check(child)
        if check is None:
            break
        leading.append(check)
    if not leading:
        return None
    return leading[0] if len(leading) == 1 else _Check("any", parts=tuple(leading))


def _check(node: Node) -> _Check | None:
    """``node`` as a test, or None when it acts."""
    if any(isinstance(n, Action) for n in walk(node)):
        return None
    if isinstance(node, Condition):
        return _Check("literal", node.name)
    if isinstance(node, Inverter):
        inner = _check(node.child)
        return None if inner is None else inner.negated()
    if isinstance(node, Sequence | Fallback):
        parts = tuple(c for c in (_check(child) for child in node.children) if c is not None)
        if len(parts) == 1:
            return parts[0]
        return _Check("all" if isinstance(node, Sequence) else "any", parts=parts)
    return _Check("opaque")


def _deduplicated(rules: list[_Rule]) -> list[_Rule]:
    """Each rule once (a subtree the tree repeats says the same)."""
    return list(dict.fromkeys(rules))


def _reachable(rules: list[_Rule]) -> list[_Rule]:
    """The rules less those that say an earlier one again: the same step when checks that include
    all of the earlier rule's hold, where the earlier rule always fits first (a rule after an
    action of its Sequence is not the first that fits, so it neither hides nor is hidden)."""
    kept: list[_Rule] = []
    for rule in rules:
        if rule.then or not any(earlier.kind == rule.kind and earlier.actions == rule.actions
                                and set(earlier.condition) <= set(rule.condition)
                                for earlier in kept if not earlier.then):
            kept.append(rule)
    return kept


def _shortened(rules: list[_Rule]) -> list[_Rule]:
    """Each rule without the checks the rules before it already say: a literal is left out where
    an earlier rule fits whenever the rest of this one holds and the literal does not (if I cannot
    see the ball I find it first, so "I go to the ball" need not say "I can see the ball"). Each
    rule still fits exactly where the tree does its step first (tested on every state of learned
    trees); a rule that follows an action of its Sequence neither loses checks nor lends them.
    Checks are bits of one number each, so "an earlier rule's checks are among these" is one test
    (blocksworld's 125 rules of 29 checks: 1.5 s as sets)."""
    bits: dict[_Check, int] = {}

    def bit(check: _Check) -> int:
        return 1 << bits.setdefault(check, len(bits))

    def all_bits(checks: tuple[_Check, ...]) -> int:
        return functools.reduce(operator.or_, map(bit, checks), 0)

    earlier: list[int] = []  # the checks of each rule that may fit first, as bits
    kept: list[_Rule] = []
    for rule in rules:
        if not rule.then:
            have = all_bits(rule.condition)
            for check in rule.guard:
                if check.kind != "literal":
                    continue
                rest = have & ~bit(check) | bit(check.negated())
                if any(not before & ~rest for before in earlier):
                    rule = replace(rule, guard=tuple(c for c in rule.guard if c != check))
                    have = all_bits(rule.condition)
            earlier.append(have)
        kept.append(rule)
    return kept


def _what(rule: _Rule, domain: Domain, lang: Lang) -> str:
    if rule.kind == "done":
        return m.WORDS_I_AM_DONE(lang)
    labels = [_action_label(name, domain, lang) for name in rule.actions]
    if rule.kind == "action":
        return m.WORDS_I_DO(lang, action=labels[0])
    if not labels:
        return m.WORDS_NOTHING_SIMPLE(lang)
    return m.WORDS_SOME_OF(lang, actions=m.OR(lang).join(m.WORDS_QUOTED(lang, action=a) for a in labels))


def _action_label(name: str, domain: Domain, lang: Lang) -> str:
    return domain.action(name).label(lang) if domain.has_action(name) else name


def _all_words(checks: tuple[_Check, ...], domain: Domain, lang: Lang) -> str:
    """Checks that must all hold. Where more than ``MAX_FALSE_NAMED`` of them are conditions that
    must be false (a rule of blocksworld's 29 conditions), what must hold is named and then the
    rest at once: "and nothing else" where every condition is tested, "and nothing else but maybe
    ontable b" where a few are not, else "and none of: …"."""
    flat = [part for check in checks for part in (check.parts if check.kind == "all" else (check,))]
    false = list(dict.fromkeys(c.name for c in flat if c.kind == "literal" and not c.value and
                               domain.has_condition(c.name)))
    if len(false) <= MAX_FALSE_NAMED:  # a check of several parts said as a list ("a, b and c", not "a and b and c")
        return join_words(list(dict.fromkeys(_check_words(c, domain, lang) for c in flat)), lang)
    rest = list(dict.fromkeys(_check_words(c, domain, lang) for c in flat
                              if not (c.kind == "literal" and not c.value and c.name in false)))
    if all(c.kind == "literal" for c in flat):
        named = {c.name for c in flat}
        untested = [c.label(lang) for c in domain.conditions if c.name not in named]
        if not untested:
            return only_these(rest, len(false), lang)
        if rest and len(untested) <= MAX_FALSE_NAMED:  # 24 conditions "none of" where 2 may hold either way
            return f"{join_words(rest, lang)}{m.NOTHING_ELSE_BUT_MAYBE(lang, conditions=join_words(untested, lang))}"
    none_of = m.NONE_OF(lang, conditions=", ".join(domain.condition(name).label(lang) for name in false))
    return f"{join_words(rest, lang)}, {none_of}" if rest else none_of


def _check_words(check: _Check, domain: Domain, lang: Lang) -> str:
    if check.kind == "literal":
        if domain.has_condition(check.name):
            return domain.condition(check.name).label(lang, check.value)
        return check.name if check.value else m.WORDS_NOT(lang, condition=check.name)
    if check.kind == "opaque" or not check.parts:
        return m.WORDS_SOME_CHECK(lang)
    joiner = m.AND(lang) if check.kind == "all" else m.OR(lang)
    return joiner.join(_check_words(part, domain, lang) for part in check.parts)
