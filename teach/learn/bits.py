"""States as int bitmasks (bit i = condition i), shared by the learners that index by them."""

from __future__ import annotations

from collections.abc import Sequence

from teach.domain import State

Lit = tuple[int, bool]
"""A literal: (condition index, value)."""


def state_mask(state: Sequence[bool]) -> int:
    """The bitmask of a state: bit i set iff condition i holds."""
    mask = 0
    for index, value in enumerate(state):
        if value:
            mask |= 1 << index
    return mask


_BYTES = tuple(tuple(bool(byte >> i & 1) for i in range(8)) for byte in range(256))
"""Each byte's eight conditions: a state is put together a byte at a time (a question ticks
thousands of states; bit by bit, making them took as long as ticking them)."""


def mask_state(mask: int, conditions: int) -> State:
    """The state of a bitmask over ``conditions`` conditions."""
    state: State = ()
    for shift in range(0, conditions, 8):
        state += _BYTES[mask >> shift & 255]
    return state[:conditions]


def mask_literals(mask: int, value: int, conditions: int) -> list[Lit]:
    """The literals (condition index, value) of the conditions set in ``mask``, with their values in ``value``."""
    return [(i, bool(value >> i & 1)) for i in range(conditions) if mask >> i & 1]
