"""An action model learned online from demonstrated transitions, kept as safe bounds.

Internally a state is an int bitmask (bit i = condition i), and a set of literals is a pair
of masks (conditions that must be true, conditions that must be false).

Per robot action (external events, -1, belong to nobody and teach no action anything):

- **effects** (SAM-style, Juba et al. 2021): a literal that changed to its value in some
  transition of the action and never changed the other way in one (never contradicted). A
  transition after which it still does not hold does not contradict it: where the world has
  hidden state (snacks left on a tray) an action makes its effect hold only sometimes, and a
  reactive tree simply does it again;
- **possible preconditions** (the upper bound): the literals that held in every state where
  the action was applied; a precondition the model does not list here cannot be real;
- **assumed preconditions** (what the planner uses): the possible ones that the data gives a
  reason for, as in the thesis's convention (§5): the negation of one of the action's own
  effects (it runs only while its effect does not hold), or a literal that the robot action
  right before it made hold, every time the action followed another one (it was done to
  enable this action; a side effect that happened only sometimes does not count);
- **confirmed preconditions** (the lower bound): possible ones the learner had to add back
  to reproduce a demonstration, or that an answer showed, with the situation behind each;
  and **maintained** ones: a literal the teacher restored at once every time an event took it
  away, once another action was shown to need it, is assumed for every action it held for;
- **guessed effects** of an action never demonstrated, from an answer (until its first
  transition replaces them).

A teacher's "yes, I may do X here" is an application of X in that state, so every literal false
there leaves X's possible preconditions: that is how answers rule literals out.

Where the domain declares parameterised actions (``teach.learn.lifting``), each transition is
also one of every sibling instance, renamed, and an action's bounds hold only conditions about its
own objects; answers about one instance are answers about its siblings.

The **required** preconditions are the possible ones. They are the safe bound
(SAM): in STRIPS-like worlds every real precondition is among them, so a tree that checks
all of them before an action never runs it where a real precondition is false. The assumed
ones only order the tree (which literals to achieve first); the rest are checked, not pursued.

Everything is updated in O(conditions) per transition (times the action's siblings where the
domain has forms); nothing is ever recomputed from the old demonstrations.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from teach.learn.bits import Lit
from teach.learn.lifting import Lifting, Renaming

EVIDENCE_KEPT = 5
"""How many sources are kept per fact for explanations (the count is always exact)."""


@dataclass
class Evidence:
    """How often something was seen, and the first few places (``file:line``) it was."""

    count: int = 0
    sources: list[str] = field(default_factory=list)

    def add(self, source: str) -> None:
        self.count += 1
        if len(self.sources) < EVIDENCE_KEPT:
            self.sources.append(source)


@dataclass
class ActionKnowledge:
    """What the transitions and answers say about one action."""

    name: str
    order: int
    full: int
    own: int = -1
    """The conditions that can be preconditions at all (``teach.learn.lifting``; -1: every one)."""
    applied: Evidence = field(default_factory=Evidence)
    transitions: int = 0
    held_true: int = -1
    held_false: int = -1
    became_true: int = 0
    became_false: int = 0
    enabled_true: int = -1
    enabled_false: int = -1
    followed: int = 0
    made: dict[Lit, Evidence] = field(default_factory=dict)
    confirmed: dict[Lit, str] = field(default_factory=dict)
    shown_itself: int = 0
    """Applications of this action itself (``applied.count`` also counts its siblings', renamed)."""
    like: str = ""
    """The first sibling whose steps were renamed onto this action (``teach.learn.lifting``)."""
    maintained: dict[Lit, str] = field(default_factory=dict)
    guessed: dict[Lit, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.held_true = self.held_false = self.full
        self.enabled_true = self.enabled_false = self.full

    @property
    def demonstrated(self) -> bool:
        return self.transitions > 0

    @property
    def known_from(self) -> str:
        """The sibling all that is known of this action comes from ("" if it was done itself)."""
        return "" if self.shown_itself else self.like

    @property
    def effects(self) -> tuple[int, int]:
        """(made true, made false) masks; before any transition, the effects guessed from answers."""
        if not self.transitions:
            made_true = made_false = 0
            for index, value in self.guessed:
                if value:
                    made_true |= 1 << index
                else:
                    made_false |= 1 << index
            return made_true, made_false
        return self.became_true & ~self.became_false, self.became_false & ~self.became_true

    @property
    def possible(self) -> tuple[int, int]:
        """The upper bound on preconditions: what held in every application."""
        if not self.applied.count:
            return 0, 0
        return self.held_true & self.own, self.held_false & self.own

    @property
    def required(self) -> tuple[int, int]:
        """The safe bound the tree checks: every possible precondition."""
        return self.possible

    @property
    def unsure(self) -> tuple[int, int]:
        """Required preconditions nobody confirmed: what a question about this action can settle."""
        pos, neg = self.required
        sure_pos, sure_neg = literal_masks({**self.confirmed, **self.maintained})
        return pos & ~sure_pos, neg & ~sure_neg

    @property
    def assumed(self) -> tuple[int, int]:
        """The preconditions the planner pursues: required ones with a reason, plus confirmed ones."""
        pos, neg = self.required
        made_true, made_false = self.effects
        enabled_true, enabled_false = (self.enabled_true, self.enabled_false) if self.followed else (0, 0)
        keep_pos = pos & (made_false | enabled_true)
        keep_neg = neg & (made_true | enabled_false)
        for (index, value) in (*self.confirmed, *self.maintained):
            if value and pos >> index & 1:
                keep_pos |= 1 << index
            elif not value and neg >> index & 1:
                keep_neg |= 1 << index
        return keep_pos, keep_neg

    def reason(self, literal: Lit) -> str:
        """Why ``literal`` is a required precondition, in words."""
        index, value = literal
        if literal in self.confirmed:
            return f"added back at {self.confirmed[literal]} to reproduce what was shown there"
        if literal in self.maintained:
            return (f"the teacher restores it at once whenever something takes it away, and another step "
                    f"was shown to need it at {self.maintained[literal]}")
        made_true, made_false = self.effects
        if (made_false if value else made_true) >> index & 1:
            return "it runs only while its own effect does not hold yet"
        pos, neg = self.assumed
        if (pos if value else neg) >> index & 1:
            return "the step right before it made it hold every time it followed another step"
        return "nobody has told me yet that it is not needed, so I check it first"


class ActionModel:
    """The learned model of every action of a domain, updated one transition at a time."""

    def __init__(self, action_names: tuple[str, ...], width: int, lifting: Lifting | None = None):
        self.width = width
        self.full = (1 << width) - 1
        self.actions = {name: ActionKnowledge(name, i, self.full) for i, name in enumerate(action_names)}
        self._renamings: dict[str, tuple[Renaming, ...]] = {}
        self.lifted = lifting is not None
        """Whether the domain has parameterised actions (``teach.learn.lifting``)."""
        if lifting is not None:
            self._renamings = lifting.renamings
            for name, own in lifting.own.items():
                self.actions[name].own = own

    def __getitem__(self, name: str) -> ActionKnowledge:
        return self.actions[name]

    def applied(self, name: str, before: int, source: str, previous: tuple[int, int] | None = None) -> None:
        """The action was chosen in ``before`` (demonstrated or answered); ``previous``: the
        literals (made true, made false) the robot action right before it changed, if any."""
        self.actions[name].shown_itself += 1
        self._applied(self.actions[name], before, self.full, source, previous)
        for renaming in self._renamings.get(name, ()):
            renamed = (renaming.mask(previous[0]), renaming.mask(previous[1])) if previous is not None else None
            sibling = self.actions[renaming.sibling]
            sibling.like = sibling.like or name
            self._applied(sibling, renaming.mask(before), renaming.image, f"{source} as {name}", renamed)

    def _applied(self, knowledge: ActionKnowledge, before: int, known: int, source: str,
                 previous: tuple[int, int] | None) -> None:
        """``applied`` for one action, saying nothing about the conditions outside ``known``."""
        knowledge.applied.add(source)
        knowledge.held_true &= before | ~known
        knowledge.held_false &= ~before & self.full | ~known
        if previous is not None:
            knowledge.followed += 1
            knowledge.enabled_true &= previous[0] | ~known
            knowledge.enabled_false &= previous[1] | ~known

    def observed(self, name: str, before: int, after: int, source: str) -> None:
        """One transition (before, action, after); ``applied`` must have been called for it."""
        self._observed(self.actions[name], before, after, self.full, source)
        for renaming in self._renamings.get(name, ()):
            self._observed(self.actions[renaming.sibling], renaming.mask(before), renaming.mask(after),
                           renaming.image, f"{source} as {name}")

    def _observed(self, knowledge: ActionKnowledge, before: int, after: int, known: int, source: str) -> None:
        knowledge.transitions += 1
        changed = (before ^ after) & known
        knowledge.became_true |= changed & after
        knowledge.became_false |= changed & ~after & self.full
        for index in range(self.width):
            if changed >> index & 1:
                literal = (index, bool(after >> index & 1))
                knowledge.made.setdefault(literal, Evidence()).add(source)

    def confirm(self, name: str, literal: Lit, source: str) -> None:
        """Keep ``literal`` as a precondition of ``name`` (and its siblings) from now on (it had to be added back)."""
        for knowledge, renamed in self._with_siblings(name, literal):
            knowledge.confirmed.setdefault(renamed, source)

    def _with_siblings(self, name: str, literal: Lit) -> list[tuple[ActionKnowledge, Lit]]:
        """``name`` with ``literal``, and each sibling with ``literal`` renamed (where it has a name there)."""
        found = [(self.actions[name], literal)]
        for renaming in self._renamings.get(name, ()):
            renamed = renaming.literal(literal)
            if renamed is not None:
                found.append((self.actions[renaming.sibling], renamed))
        return found

    def guess(self, name: str, literal: Lit, source: str) -> None:
        """An effect inferred from an answer (see ``Learner.teach_step``); transitions of the
        action, once demonstrated, replace every guess."""
        self.actions[name].guessed.setdefault(literal, source)

    def achievers(self, literal: Lit) -> list[str]:
        """Actions that have ``literal`` as an effect, the most often demonstrated doing it first."""
        index, value = literal
        found = []
        for knowledge in self.actions.values():
            made_true, made_false = knowledge.effects
            if (made_true if value else made_false) >> index & 1:
                found.append(knowledge)
        found.sort(key=lambda k: (-k.made[literal].count if literal in k.made else 0, k.order))
        return [k.name for k in found]


def literal_masks(literals: Iterable[Lit]) -> tuple[int, int]:
    """(true mask, false mask) of some literals."""
    pos = neg = 0
    for index, value in literals:
        if value:
            pos |= 1 << index
        else:
            neg |= 1 << index
    return pos, neg


def literals_of(pos: int, neg: int, width: int) -> list[Lit]:
    """The literals of a (true mask, false mask) pair in condition order."""
    result: list[Lit] = []
    for index in range(width):
        if pos >> index & 1:
            result.append((index, True))
        if neg >> index & 1:
            result.append((index, False))
    return result
