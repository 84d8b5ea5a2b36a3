"""The goal, learned from where the teacher stopped and where they kept acting.

Two bounds, as for preconditions:

- the **candidates** (the over-specific bound): the literals that held in every goal state;
  every answer "the task is done here" and every new goal state can only narrow them, and the
  teacher can rule one out ("it need not hold for the task to be done"). The candidates not
  ruled out are the **required** goal: the tree says "done" only where all of them hold, so it
  never says done where a literal it has not ruled out is false;
- the **cover** orders the tree's work: the smallest set of candidates that explains why the teacher
  kept acting, i.e. every state in which the teacher chose an action violates at least one of
  them (a greedy set cover). The intersection alone keeps accidental literals nothing
  achieves, so the tree would fail everywhere; the cover keeps only what the teacher's
  behaviour shows to matter. A state the teacher acted in that satisfies every candidate
  cannot be explained by any goal; it is reported as ``unexplained``.

A goal the domain file declares (``goal = [...]``) is the author's word, not a guess: every
other literal is ruled out from the start and the declared ones are confirmed, so the tree
says "done" where the declared literals hold (of those, the ones every goal state shown held:
a teacher who stopped where one is false has ruled it out) and no question asks about the goal.

States are bitmasks; the learner feeds distinct labelled states (adding and removing, since
the latest label of a state wins). Adding an acting state costs O(conditions); the cover is
recomputed from the stored states only when a candidate it uses disappears (at most twice
per condition) or a goal state is taken back.
"""

from __future__ import annotations

from teach.learn.action_model import Evidence, Lit

DECLARED = "the domain file's goal"
"""The source of what a declared goal rules out or confirms."""


class GoalLearner:
    def __init__(self, width: int, declared: list[Lit] | None = None):
        self.width = width
        self.full = (1 << width) - 1
        self.goal_states: dict[int, Evidence] = {}
        self.acting: dict[int, str] = {}
        self._true_in_goals = [0] * width
        self._true_in_acting = [0] * width
        self.cover: list[Lit] = []
        self.unexplained: set[int] = set()
        self.ruled_out: dict[Lit, str] = {}
        self.confirmed: dict[Lit, str] = {}
        if declared:
            self.ruled_out = {(index, value): DECLARED for index in range(width) for value in (False, True)
                              if (index, value) not in declared}
            self.confirmed = dict.fromkeys(declared, DECLARED)

    # --- the bounds ---------------------------------------------------------------------------

    @property
    def known(self) -> bool:
        return bool(self.goal_states)

    def candidates(self) -> list[Lit]:
        """Literals true in every goal state, in condition order (empty before any goal state)."""
        total = len(self.goal_states)
        if not total:
            return []
        result: list[Lit] = []
        for index, count in enumerate(self._true_in_goals):
            if count == total:
                result.append((index, True))
            elif count == 0:
                result.append((index, False))
        return result

    def required(self) -> list[Lit]:
        """The candidates not ruled out: what must hold before the tree says "done"."""
        return [lit for lit in self.candidates() if lit not in self.ruled_out]

    def unsure(self) -> list[Lit]:
        """Required literals the teacher's behaviour does not show to matter and nobody confirmed."""
        sure = set(self.cover) | set(self.confirmed)
        return [lit for lit in self.required() if lit not in sure]

    def holds(self, mask: int) -> bool:
        """Does the cover hold in this state (False while no goal is known)?"""
        return self.known and all(bool(mask >> i & 1) == v for i, v in self.cover)

    def required_holds(self, mask: int) -> bool:
        """Does every required goal literal hold in this state (False while no goal is known)?"""
        return self.known and all(bool(mask >> i & 1) == v for i, v in self.required())

    def rule_out(self, literal: Lit, source: str) -> None:
        """The teacher said ``literal`` need not hold for the task to be done."""
        self.ruled_out.setdefault(literal, source)
        self.confirmed.pop(literal, None)
        if literal in self.cover:
            self._recompute()

    def confirm(self, literal: Lit, source: str) -> None:
        """The teacher said ``literal`` must hold for the task to be done."""
        if literal not in self.ruled_out:
            self.confirmed.setdefault(literal, source)

    def violations(self, literal: Lit) -> int:
        """How many acting states violate ``literal``."""
        index, value = literal
        ones = self._true_in_acting[index]
        return len(self.acting) - ones if value else ones

    # --- updates ------------------------------------------------------------------------------

    def add_goal_state(self, mask: int, source: str) -> None:
        evidence = self.goal_states.get(mask)
        if evidence is not None:
            evidence.add(source)
            return
        before = set(self.required())
        self.goal_states[mask] = Evidence()
        self.goal_states[mask].add(source)
        self._count(self._true_in_goals, mask, 1)
        lost = before - set(self.required()) if before else set()
        if not before or lost & set(self.cover):
            self._recompute()

    def remove_goal_state(self, mask: int) -> None:
        if self.goal_states.pop(mask, None) is not None:
            self._count(self._true_in_goals, mask, -1)
            self._recompute()

    def add_acting_state(self, mask: int, source: str) -> None:
        if mask in self.acting:
            return
        self.acting[mask] = source
        self._count(self._true_in_acting, mask, 1)
        if not self.known or self._violates_cover(mask):
            return
        violated = [lit for lit in self.required() if bool(mask >> lit[0] & 1) != lit[1]]
        if not violated:
            self.unexplained.add(mask)
            return
        self.cover.append(max(violated, key=self._preference))

    def remove_acting_state(self, mask: int) -> None:
        if self.acting.pop(mask, None) is not None:
            self._count(self._true_in_acting, mask, -1)
            self.unexplained.discard(mask)

    # --- internals ----------------------------------------------------------------------------

    def _preference(self, literal: Lit) -> tuple[int, int]:
        return self.violations(literal), -literal[0]

    def _violates_cover(self, mask: int) -> bool:
        return any(bool(mask >> i & 1) != v for i, v in self.cover)

    def _count(self, counts: list[int], mask: int, step: int) -> None:
        for index in range(self.width):
            if mask >> index & 1:
                counts[index] += step

    def _recompute(self) -> None:
        """Greedy set cover of the acting states by candidate literals."""
        self.cover = []
        self.unexplained = set()
        candidates = self.required()
        if not self.goal_states:
            return
        uncovered: list[int] = []
        for mask in self.acting:
            if any(bool(mask >> i & 1) != v for i, v in candidates):
                uncovered.append(mask)
            else:
                self.unexplained.add(mask)
        while uncovered:
            remaining = uncovered
            best = max(candidates, key=lambda lit: (_violating(lit, remaining), *self._preference(lit)))
            self.cover.append(best)
            uncovered = [m for m in uncovered if bool(m >> best[0] & 1) == best[1]]


def _violating(literal: Lit, states: list[int]) -> int:
    index, value = literal
    return sum(bool(m >> index & 1) != value for m in states)
