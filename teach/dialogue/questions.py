"""Clarifying questions: which situation to ask about, how to phrase it, and the budget.

The specialization learner keeps a guard in front of an action whenever every demonstration
of that action happened to agree on it. Some of those guards are real preconditions, others
are accidents of the few demonstrations seen. People answer concrete situations with actions
far more reliably than yes/no questions about preconditions (thesis §6.1), so a question is
a situation: "If <state>, what should I do?", answered with an action or "done".

Choosing the situation is active learning by *expected model change* over a committee:

1. A prior says how likely each guard is real, from what the demonstrations show about
   cause and effect: a guard that is the action's own effect (do not redo what is done), the
   effect of the action just before it (it enables this one), or an effect that completed
   the task (do nothing once done) is probably real; any other guard is probably an accident.
   Guards that a demonstration or answer needs are certainly real.
2. A committee of trees is sampled by dropping guards at random under that prior, keeping
   only trees that still do what every demonstration and answer says.
3. For each unseen situation, the committee's votes estimate what the teacher will answer
   (with a small share for actions never demonstrated: the teacher may want one); for
   each possible answer, the learner is updated on a copy, and the change of behaviour is
   measured over the situations the robot is likely to pass through (simulated from every
   start with the effects seen in the demonstrations).
4. The situation with the largest expected change is asked.

It never looks at an answer before asking, and it works for any domain: nothing in it knows
the ball task. This selector serves the specialization learner (Approach 3; measured by
``bench/bench_questions.py``); the session's default learner has its own, ``teach.learn.inquiry``.
The budget, the wording and ``Question`` are shared by both.
"""

from __future__ import annotations

import copy
import itertools
import random
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from teach import messages as m
from teach.bt.nodes import Node, Status, transform
from teach.bt.tick import CompiledTree, compile_tree
from teach.demos import Demonstration
from teach.domain import Domain, State
from teach.errors import LearnError
from teach.messages import Lang, Text
from teach.symbolic import assign

if TYPE_CHECKING:
    from teach.learn.specialize import Specializer as Learner

EXHAUSTIVE_UP_TO = 10
STATE_SAMPLE = 512
COMMITTEE_DRAWS = 300
COMMITTEE_FOR_VISITS = 40
CANDIDATE_LIMIT = 64
SURPRISE = 0.2  # share of the answer expectation spread over actions never demonstrated

PRIOR_REAL_OWN_EFFECT = 0.95
PRIOR_REAL_ENABLING = 0.9
PRIOR_REAL_TASK_DONE = 0.9
PRIOR_REAL_OTHER = 0.3

Answer = str | None  # an action name, or None: the task is done here


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


MUST_KINDS = ("must-precondition", "must-goal")
"""Questions a yes answers: may I still do it here? is the task done here?"""


@dataclass(frozen=True)
class Question:
    """A situation the robot asks about, with what it expects the answer could be."""

    state: State
    score: float
    expected: tuple[tuple[str, float], ...] = ()  # (answer or "done", committee share)
    shown: tuple[str, ...] = ()
    """For a conflict: the answers demonstrated here (action names, "" for "done")."""
    kind: str = ""
    """"must-precondition" (may I still do ``action`` here?), "must-goal" (is the task done here?),
    or a plain situation question."""
    action: str | None = None
    """The action a must-precondition question asks about; a yes is the answer "do it here"."""
    settles: tuple[tuple[str, bool], ...] = ()
    """The literals (condition, value) that always held so far and do not hold here."""
    like: str = ""
    """For a must-precondition question about an action never done itself: the step of its kind
    that was done (``teach.learn.lifting``), so the question does not claim it was done."""

    def text(self, domain: Domain, lang: Lang = Lang.EN) -> str:
        situation = describe_situation(domain, self.state, lang)
        if self.kind in MUST_KINDS:
            held = join_words([domain.condition(name).label(lang, value) for name, value in self.settles], lang)
            if self.kind == "must-goal":
                return m.MUST_GOAL_QUESTION(lang, held=held, situation=situation)
            assert self.action is not None
            action = domain.action(self.action).label(lang)
            if self.like:
                return m.MUST_KIN_QUESTION(lang, held=held, action=action, like=domain.action(self.like).label(lang),
                                           situation=situation)
            return m.MUST_ACTION_QUESTION(lang, held=held, action=action, situation=situation)
        if self.shown:
            labels = [domain.action(a).label(lang) if a else m.DONE_WORD(lang) for a in self.shown]
            return m.CONFLICT_QUESTION(lang, shown=m.OR(lang).join(labels), situation=situation)
        return m.SITUATION_QUESTION(lang, situation=situation)


MAX_FALSE_NAMED = 8
"""More conditions false than this are not named one by one (in blocksworld 25 of 29 are: "not:
on a a, not: on a b, …"): what holds, "and nothing else" (or "none of the 29 conditions holds").
`state full` shows every value."""


def describe_situation(domain: Domain, state: State, lang: Lang = Lang.EN) -> str:
    """A state in plain words: what holds, then ``but`` what does not (or "and nothing else")."""
    true = [c.label(lang) for c, v in zip(domain.conditions, state, strict=True) if v]
    false = [c.label(lang, False) for c, v in zip(domain.conditions, state, strict=True) if not v]
    but = m.BUT(lang)
    if len(false) > MAX_FALSE_NAMED:
        return only_these(true, len(false), lang)
    if true and false:
        return f"{join_words(true, lang)},{but}{join_words(false, lang)}"
    return join_words(true or false, lang)


def only_these(true: list[str], false: int, lang: Lang) -> str:
    """What holds, "and nothing else" (the ``false`` other conditions not named one by one), or
    "none of the N conditions holds" when nothing does."""
    return f"{join_words(true, lang)}{m.NOTHING_ELSE(lang)}" if true else m.NOTHING_HOLDS(lang, count=false)


def join_words(items: list[str], lang: Lang, last: Text = m.AND) -> str:
    """``a``, ``a and b``, ``a, b and c`` in the session's language ("" for none); ``last``:
    the word before the last item (``m.OR``: "a, b or c")."""
    if not items:
        return ""
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + last(lang) + items[-1]


# --- what the demonstrations say about cause and effect ---------------------------------------

Lit = tuple[int, bool]  # (condition index, value)


@dataclass
class Effects:
    """Per action, the literals it made true in every demonstrated transition; which actions
    came right before it; and the effects that completed the task."""

    made: dict[str, frozenset[Lit]] = field(default_factory=dict)
    before: dict[str, set[str]] = field(default_factory=dict)
    finishing: set[Lit] = field(default_factory=set)

    def apply(self, state: State, action: str) -> State:
        return assign(state, self.made.get(action, ()))


def effects_from(domain: Domain, demos: Iterable[Demonstration]) -> Effects:
    effects = Effects()
    for demo in demos:
        previous: str | None = None
        for step, following in zip(demo.steps, demo.steps[1:], strict=False):
            if step.action <= 0:
                previous = None
                continue
            name = domain.action(step.action).name
            pairs = zip(step.state, following.state, strict=True)
            changed = frozenset((i, after) for i, (now, after) in enumerate(pairs)
                                if now != after)
            effects.made[name] = effects.made[name] & changed if name in effects.made else changed
            if previous is not None:
                effects.before.setdefault(name, set()).add(previous)
            if following.action == 0:
                effects.finishing |= changed
            previous = name
    return effects


def prior_real(domain: Domain, action: str, literals: Sequence[tuple[str, bool]], needed: bool,
               effects: Effects) -> float:
    """How likely a guard is a real precondition rather than an accident of the demonstrations."""
    if needed or len(literals) != 1:
        return 1.0
    name, value = literals[0]
    literal = (domain.index(name), value)
    if literal in effects.made.get(action, ()):
        return PRIOR_REAL_OWN_EFFECT
    if literal in effects.finishing:
        return PRIOR_REAL_TASK_DONE
    opposite = (literal[0], not value)
    if any(opposite in effects.made.get(b, ()) for b in effects.before.get(action, ())):
        return PRIOR_REAL_ENABLING
    return PRIOR_REAL_OTHER


# --- selection --------------------------------------------------------------------------------

def _answer(tree: CompiledTree, state: State) -> Answer | bool:
    """What a tree does in a state: an action, None for SUCCESS, False for FAILURE."""
    status, action = tree(state)
    if status is Status.RUNNING:
        return action
    return None if status is Status.SUCCESS else False


def all_states(n: int, seed: int = 0) -> list[State]:
    """Every state for small domains, a fixed sample for large ones."""
    if n <= EXHAUSTIVE_UP_TO:
        return [tuple(bits) for bits in itertools.product((False, True), repeat=n)]
    rng = random.Random(seed)
    return sorted({tuple(rng.random() < 0.5 for _ in range(n)) for _ in range(STATE_SAMPLE)})


def committee(learner: Learner, labels: Mapping[State, Answer], effects: Effects,
              rng: random.Random) -> list[CompiledTree]:
    """Trees the learner's guards could really stand for, each consistent with every label."""
    domain = learner.domain
    names = domain.condition_names
    guards = []
    for action in learner.order:
        for guard in learner.guards(action):
            literals = [(lit.name, lit.value) for lit in guard.literals]
            guards.append((guard.uid, prior_real(domain, action, literals, bool(guard.needed_by), effects)))
    tree = learner.tree
    members = [compile_tree(tree, names)]
    seen: set[frozenset[int]] = {frozenset()}
    for _ in range(COMMITTEE_DRAWS):
        drop = frozenset(uid for uid, p in guards if rng.random() >= p)
        if drop in seen:
            continue
        seen.add(drop)
        relaxed = transform(tree, _without(drop))
        if relaxed is None:
            continue
        member = compile_tree(relaxed, names)
        if all(_answer(member, s) == label for s, label in labels.items()):
            members.append(member)
    return members


def _without(uids: frozenset[int]) -> Callable[[Node], Node | None]:
    """A transform step that drops the nodes ``uids``."""
    return lambda node: None if node.uid in uids else node


def visit_weights(trees: Sequence[CompiledTree], starts: Sequence[State], effects: Effects,
                  horizon: int) -> dict[State, int]:
    """How often each state is passed through when the trees run from every start, with the
    effects the demonstrations showed."""
    weights: dict[State, int] = {}
    for tree in trees:
        for state in starts:
            for _ in range(horizon):
                weights[state] = weights.get(state, 0) + 1
                action = _answer(tree, state)
                if not isinstance(action, str):
                    break
                following = effects.apply(state, action)
                if following == state:
                    break
                state = following
    return weights


def select_question(learner: Learner, demos: Sequence[Demonstration], labels: Mapping[State, Answer],
                    asked: Iterable[State] = (), seed: int = 0) -> Question | None:
    """The situation whose answer is expected to change the robot's behaviour most, or None.

    ``labels``: the right answer in every situation known so far (demonstrated or answered);
    ``asked``: situations already asked about (also the skipped ones), never asked again.
    """
    domain = learner.domain
    names = domain.condition_names
    rng = random.Random(seed * 7919 + len(labels))
    effects = effects_from(domain, demos)
    members = committee(learner, labels, effects, rng)
    states = all_states(len(names), seed)
    excluded = set(labels) | set(asked)
    unseen = [s for s in states if s not in excluded]
    if not unseen:
        return None
    weights = visit_weights(members[:COMMITTEE_FOR_VISITS], states, effects, 2 * len(domain.actions) + 2)
    current = members[0]
    now = {s: _answer(current, s) for s in unseen}
    candidates = sorted(unseen, key=lambda s: (-weights.get(s, 0), s))[:CANDIDATE_LIMIT]
    unshown: list[Answer] = [a for a in domain.action_names if a not in learner.order]
    goal = _goal_literals([s for s, label in labels.items() if label is None])
    best: Question | None = None
    for state in candidates:
        reached = goal is not None and all(state[i] == v for i, v in goal)
        shares = _answer_shares(members, state, () if reached else unshown)
        score = 0.0
        for answer, share in shares.items():
            if answer != now[state]:  # the robot already does this: no change
                score += share * _change(learner, state, answer, unseen, now, weights)
        if score > 0 and (best is None or score > best.score + 1e-9):
            expected = tuple((a or "done", p) for a, p in sorted(shares.items(), key=lambda i: (-i[1], i[0] or "")))
            best = Question(state, score, expected)
    return best


def _goal_literals(goal_states: Sequence[State]) -> list[Lit] | None:
    """The literals every demonstrated goal state shares (None before any goal was shown)."""
    if not goal_states:
        return None
    first = goal_states[0]
    return [(i, v) for i, v in enumerate(first) if all(s[i] == v for s in goal_states)]


def _answer_shares(members: Sequence[CompiledTree], state: State, unshown: Sequence[Answer]) -> dict[Answer, float]:
    """How likely each answer is: the committee's votes, and, while some actions have never
    been demonstrated, a ``SURPRISE`` share spread over them (the teacher may want one; not
    where everything every demonstrated goal state had already holds)."""
    votes: dict[Answer, int] = {}
    for member in members:
        vote = _answer(member, state)
        if not isinstance(vote, bool):  # False: the member fails there
            votes[vote] = votes.get(vote, 0) + 1
    total = sum(votes.values())
    surprise = SURPRISE if unshown else 0.0
    shares: dict[Answer, float] = {answer: surprise / len(unshown) for answer in unshown}
    for answer, count in votes.items():
        shares[answer] = shares.get(answer, 0.0) + (1 - surprise) * count / total
    return shares


def _change(learner: Learner, state: State, answer: Answer, unseen: Sequence[State],
            now: Mapping[State, Answer | bool], weights: Mapping[State, int]) -> float:
    """Weighted number of unseen situations whose behaviour would change after this answer."""
    trial = copy.deepcopy(learner)
    try:
        trial.teach_step(state, answer, source="a possible answer")
    except LearnError:
        return 0.0
    after = compile_tree(trial.tree, learner.domain.condition_names)
    return float(sum(weights.get(s, 0) for s in unseen if _answer(after, s) != now[s]))
