"""Which situations can happen: the states a question may be about (issue 21, item 5).

A question about a situation that cannot happen ("the ball is in my hand and in the bin")
wastes the teacher's patience and teaches nothing. Two sources say what cannot happen:

- **the world**: a world that knows its physics (``TeachingWorld.can_happen``; MuJoCo cannot
  hold a ball that lies in the bin) rules a state out before anyone is asked;
- **the teacher**: "that cannot happen" about a state rules it out, and with it the reason the
  data shows for it: the pairs of its literals that never held together in any situation seen
  so far (h²-style mutexes). Every state in which all of those literals hold is then not asked
  about either. The reason is a guess, so it only ever *removes questions*; it never licenses
  an action or "done". A later demonstration that shows the literals together takes it back.

States are int bitmasks (bit i = condition i, ``teach.learn.bits``).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass

from teach.domain import State
from teach.learn.bits import mask_state

Seen = Callable[[int, int], bool]
"""``seen(care, value)``: whether some situation seen so far has the literals ``care``/``value``
(the conditions set in ``care`` with the values in ``value``)."""


@dataclass(frozen=True)
class Nogood:
    """Literals that cannot all hold at once (``care``: which conditions, ``value``: their values),
    learned from the teacher's "that cannot happen" in ``source``."""

    care: int
    value: int
    source: str

    def holds_in(self, mask: int) -> bool:
        return mask & self.care == self.value


class Invariants:
    """The states known not to happen: said so, shown by the world, or sharing the reason."""

    def __init__(self, width: int, can_happen: Callable[[State], bool] | None = None):
        self.width = width
        self._can_happen = can_happen
        self.impossible: dict[int, str] = {}
        """States the teacher said cannot happen, with the answer's source."""
        self.nogoods: list[Nogood] = []
        full = (1 << width) - 1
        self._with_true = [[0, 0] for _ in range(width)]
        """Per condition i and value v (0: false, 1: true): the conditions seen true together with it."""
        self._with_false = [[0, 0] for _ in range(width)]
        self._full = full

    def rule_out(self, mask: int, source: str, seen: Seen) -> None:
        """The teacher said ``mask`` cannot happen: remember it, and the pairs of its literals never
        seen together as one reason (all of them, as the data cannot say which one it is)."""
        self.impossible[mask] = source
        known = {(nogood.care, nogood.value) for nogood in self.nogoods}
        for first, second in itertools.combinations(range(self.width), 2):
            pair = 1 << first | 1 << second
            if not seen(pair, mask & pair) and (pair, mask & pair) not in known:
                self.nogoods.append(Nogood(pair, mask & pair, source))

    def saw(self, mask: int) -> None:
        """A situation was shown or answered in ``mask``: it happens, and so do the literals of every
        reason that holds in it (that reason was the wrong one)."""
        self.impossible.pop(mask, None)
        self.nogoods = [nogood for nogood in self.nogoods if not nogood.holds_in(mask)]
        false = ~mask & self._full
        for index in range(self.width):
            value = mask >> index & 1
            self._with_true[index][value] |= mask
            self._with_false[index][value] |= false

    def pairs_seen(self, mask: int) -> bool:
        """Whether every two literals of ``mask`` held together in some situation seen: a state
        the demonstrations show nothing against (in a planning domain a state one condition away
        from a seen one mostly cannot happen: a ferry at two places)."""
        false = ~mask & self._full
        for index in range(self.width):
            value = mask >> index & 1
            if mask & ~self._with_true[index][value] or false & ~self._with_false[index][value]:
                return False
        return True

    def possible(self, mask: int) -> bool:
        """Whether a question may be about ``mask``: not said to be impossible, not sharing the reason
        of one that was, and possible in the world."""
        if mask in self.impossible or any(nogood.holds_in(mask) for nogood in self.nogoods):
            return False
        return self._can_happen is None or self._can_happen(mask_state(mask, self.width))
