"""Clarifying questions: which situation to ask about, how to phrase it, and the budget.

The specialization learner keeps a guard in front of an action whenever every demonstration
of that action happened to agree on it. Some of those guards are real preconditions, others
are accidents of the few demonstrations seen. People answer concrete situations with actions
far more reliably than yes/no questions about preconditions (thesis §6.1), so a question here
is a situation: "If <state>, what should I do?".

Selection is a pure function of the current tree and what has been taught: for every guard,
count the unseen states whose behaviour would change if that guard were dropped (the weight
of the doubt), and ask about the guard with the most, in the state closest to where the
action was actually shown. It never looks at an answer before asking.
"""

from __future__ import annotations

import itertools
import random
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Sequence, children, replace_node, walk
from teach.bt.tick import compile_tree
from teach.domain import Domain, State

EXHAUSTIVE_UP_TO = 12
SAMPLE_SIZE = 1024


class BudgetExhausted(RuntimeError):
    """Raised if anything tries to ask beyond the budget; the session never lets it happen."""


class QuestionBudget:
    """The one place that enforces the cap on questions."""

    def __init__(self, total: int, used: int = 0):
        if total < 0:
            raise ValueError("the question budget cannot be negative")
        self.total = total
        self.used = used

    @property
    def left(self) -> int:
        return self.total - self.used

    def spend(self) -> None:
        if self.left <= 0:
            raise BudgetExhausted(f"all {self.total} questions are used")
        self.used += 1


@dataclass(frozen=True)
class Question:
    """A situation the robot asks about, with the guard that made it doubtful."""

    state: State
    action: str        # the action the doubt is about
    guard_key: str     # the guard that blocks it in this state, as text ("!BallFound")
    impact: int        # unseen states whose behaviour hinges on this guard

    def text(self, domain: Domain, lang: str = "en") -> str:
        situation = describe_situation(domain, self.state, lang)
        if lang == "de":
            return f"Wenn {situation}: was soll ich tun?"
        return f"If {situation}, what should I do?"


def describe_situation(domain: Domain, state: State, lang: str = "en") -> str:
    """A state in plain words: what holds, then ``but`` what does not."""
    true = [c.label(lang) for c, v in zip(domain.conditions, state) if v]
    false = [c.label(lang, False) for c, v in zip(domain.conditions, state) if not v]
    joiner, but = (" und ", " aber ") if lang == "de" else (" and ", " but ")

    def join(items: list[str]) -> str:
        return items[0] if len(items) == 1 else ", ".join(items[:-1]) + joiner + items[-1]

    if true and false:
        return f"{join(true)},{but}{join(false)}"
    return join(true or false)


def guard_key(guard: Node) -> str:
    """A guard as stable text, the same across processes: "BallFound", "!BallFound", "A&!B"."""
    if isinstance(guard, Condition):
        return guard.name
    if isinstance(guard, Inverter) and isinstance(guard.child, Condition):
        return f"!{guard.child.name}"
    if isinstance(guard, Sequence):
        return "&".join(guard_key(kid) for kid in guard.children)
    if isinstance(guard, Fallback):
        return "(" + "|".join(guard_key(kid) for kid in guard.children) + ")"
    return repr(guard)


def action_guards(tree: Node) -> dict[str, list[Node]]:
    """For each action, the guards to its left in its Fallback (the nodes that can skip it)."""
    guards: dict[str, list[Node]] = {}
    for node in walk(tree):
        if isinstance(node, Fallback):
            kids = children(node)
            for index, kid in enumerate(kids):
                if isinstance(kid, Action):
                    guards.setdefault(kid.name, []).extend(kids[:index])
    return guards


def candidate_states(n: int, seed: int = 0) -> list[State]:
    """Every state for small domains, a fixed sample for large ones."""
    if n <= EXHAUSTIVE_UP_TO:
        return [tuple(bits) for bits in itertools.product((False, True), repeat=n)]
    rng = random.Random(seed)
    return sorted({tuple(rng.random() < 0.5 for _ in range(n)) for _ in range(SAMPLE_SIZE)})


def select_question(tree: Node, domain: Domain, labelled: Iterable[State],
                    settled_guards: Iterable[tuple[str, str]], shown: Mapping[str, Sequence[State]]) -> Question | None:
    """The most useful situation question, or None when nothing is in doubt.

    ``labelled``: states whose right behaviour is known (demonstrated or answered);
    ``settled_guards``: (action, guard key) pairs an answer already confirmed; ``shown``: per action,
    the states where it was demonstrated.
    """
    names = domain.condition_names
    known = set(labelled)
    settled = set(settled_guards)
    states = [s for s in candidate_states(len(names)) if s not in known]
    if not states:
        return None
    current = compile_tree(tree, names)
    before = {s: current(s) for s in states}
    best: Question | None = None
    for action, guards in sorted(action_guards(tree).items()):
        for guard in guards:
            key = guard_key(guard)
            if (action, key) in settled:
                continue
            relaxed_tree = replace_node(tree, guard.uid, None)
            if relaxed_tree is None:
                continue
            relaxed = compile_tree(relaxed_tree, names)
            changed = [s for s in states if relaxed(s) != before[s] and relaxed(s)[1] == action]
            if not changed or (best is not None and len(changed) <= best.impact):
                continue
            anchor = shown.get(action, ())
            state = min(changed, key=lambda s: (_distance(s, anchor), s))
            best = Question(state, action, key, len(changed))
    return best


def _distance(state: State, anchors: Sequence[State]) -> int:
    if not anchors:
        return 0
    return min(sum(a != b for a, b in zip(state, anchor)) for anchor in anchors)
