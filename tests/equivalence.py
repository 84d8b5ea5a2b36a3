"""Behavioural equivalence of two trees in the symbolic world, for any test that rewrites trees.

Two trees are equivalent when every state gives the same status and runs the same action
(``compile_tree(tree, names)(state)``). Up to 12 conditions every state is tried; beyond,
a fixed-seed sample of 4096 states, so a failure always reproduces.
"""

from __future__ import annotations

import itertools
import random
from collections.abc import Iterator, Sequence

from teach.bt.nodes import Node
from teach.bt.tick import compile_tree

EXHAUSTIVE_UP_TO = 12
SAMPLE = 4096
SEED = 20190


def states(count: int) -> Iterator[tuple[bool, ...]]:
    """Every state over ``count`` conditions, or the fixed sample when there are too many."""
    if count <= EXHAUSTIVE_UP_TO:
        yield from itertools.product((False, True), repeat=count)
        return
    rng = random.Random(SEED)
    for _ in range(SAMPLE):
        yield tuple(rng.random() < 0.5 for _ in range(count))


def first_difference(a: Node, b: Node, names: Sequence[str]) -> str | None:
    """A description of the first state where the trees differ, or None."""
    ta, tb = compile_tree(a, names), compile_tree(b, names)
    for state in states(len(names)):
        ra, rb = ta(state), tb(state)
        if ra != rb:
            true = [n for n, v in zip(names, state, strict=True) if v]
            return f"in state {true or '(all false)'}: {ra[0].name} {ra[1]} vs {rb[0].name} {rb[1]}"
    return None


def assert_equivalent(a: Node, b: Node, names: Sequence[str]) -> None:
    """Fail with the first differing state unless ``a`` and ``b`` tick alike in every state."""
    difference = first_difference(a, b, names)
    assert difference is None, f"trees differ {difference}\n  {a}\n  {b}"
