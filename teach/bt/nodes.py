"""Behaviour-tree nodes as small immutable dataclasses (thesis §2.2, Table 2.2).

A tree is its root node. Every node carries a ``uid`` that survives edits made with the
helpers below, so a node can be traced back to the demonstration or answer that produced
it; equality and hashing ignore uids and compare structure only.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace
from enum import IntEnum


class Status(IntEnum):
    """Return values, numbered as the thesis's BT server does (0 SUCCESS, 1 FAILURE, 2 RUNNING)."""

    SUCCESS = 0
    FAILURE = 1
    RUNNING = 2


_uid_counter = itertools.count(1)


def new_uid() -> int:
    return next(_uid_counter)


def _uid() -> int:
    return field(default_factory=new_uid, compare=False, kw_only=True)


@dataclass(frozen=True, slots=True)
class Condition:
    name: str
    uid: int = _uid()


@dataclass(frozen=True, slots=True)
class Action:
    name: str
    uid: int = _uid()


@dataclass(frozen=True, slots=True)
class Sequence:
    """→: succeeds if all children succeed, memoryless (ReactiveSequence)."""

    children: tuple[Node, ...]
    uid: int = _uid()


@dataclass(frozen=True, slots=True)
class Fallback:
    """?: succeeds as soon as one child succeeds, memoryless (ReactiveFallback)."""

    children: tuple[Node, ...]
    uid: int = _uid()


@dataclass(frozen=True, slots=True)
class Parallel:
    """⇉: succeeds when at least ``success_threshold`` of its N children succeed."""

    children: tuple[Node, ...]
    success_threshold: int
    uid: int = _uid()

    def __post_init__(self) -> None:
        if not 1 <= self.success_threshold <= max(1, len(self.children)):
            raise ValueError(f"Parallel success threshold {self.success_threshold} "
                             f"is not between 1 and its {len(self.children)} children")


@dataclass(frozen=True, slots=True)
class Inverter:
    """◇: swaps SUCCESS and FAILURE of its single child."""

    child: Node
    uid: int = _uid()


Node = Condition | Action | Sequence | Fallback | Parallel | Inverter
Composite = Sequence | Fallback | Parallel
LEAVES = (Condition, Action)
COMPOSITES = (Sequence, Fallback, Parallel)


def children(node: Node) -> tuple[Node, ...]:
    if isinstance(node, Inverter):
        return (node.child,)
    if isinstance(node, COMPOSITES):
        return node.children
    return ()


def with_children(node: Node, kids: tuple[Node, ...]) -> Node:
    """The same node (same uid) with other children."""
    if isinstance(node, Inverter):
        (only,) = kids
        return replace(node, child=only)
    if isinstance(node, COMPOSITES):
        return replace(node, children=tuple(kids))
    raise TypeError(f"{type(node).__name__} has no children")


def walk(node: Node) -> Iterator[Node]:
    """All nodes in pre-order (the order they appear in XML)."""
    stack = [node]
    while stack:
        current = stack.pop()
        yield current
        stack.extend(reversed(children(current)))


def size(node: Node) -> int:
    return sum(1 for _ in walk(node))


def depth(node: Node) -> int:
    kids = children(node)
    return 1 + (max(depth(k) for k in kids) if kids else 0)


def condition_names(node: Node) -> set[str]:
    return {n.name for n in walk(node) if isinstance(n, Condition)}


def action_names(node: Node) -> set[str]:
    return {n.name for n in walk(node) if isinstance(n, Action)}


def find(node: Node, uid: int) -> Node | None:
    return next((n for n in walk(node) if n.uid == uid), None)


def parents(node: Node) -> dict[int, Node]:
    """Map from a node's uid to its parent node."""
    result: dict[int, Node] = {}
    for current in walk(node):
        for kid in children(current):
            result[kid.uid] = current
    return result


def transform(node: Node, fn: Callable[[Node], Node | None]) -> Node | None:
    """Rebuild bottom-up: ``fn`` sees each node with already-transformed children and returns
    its replacement, or None to drop it. A control node left without children is dropped too.
    Untouched nodes keep their identity and uids."""
    kids = children(node)
    if kids:
        new_kids = tuple(k for k in (transform(kid, fn) for kid in kids) if k is not None)
        if not new_kids:
            return None
        if len(new_kids) != len(kids) or any(a is not b for a, b in zip(new_kids, kids, strict=True)):
            if isinstance(node, Parallel) and node.success_threshold > len(new_kids):
                node = replace(node, success_threshold=len(new_kids))
            node = with_children(node, new_kids)
    return fn(node)


def replace_node(root: Node, uid: int, new: Node | None) -> Node | None:
    """The tree with the node ``uid`` replaced by ``new`` (or removed when ``new`` is None)."""
    return transform(root, lambda n: new if n.uid == uid else n)


def renumber(root: Node, start: int = 1) -> Node:
    """A copy whose uids are pre-order positions from ``start``: the canonical numbering
    given to trees read from files."""
    counter = itertools.count(start)

    def build(node: Node) -> Node:
        uid = next(counter)
        kids = tuple(build(k) for k in children(node))
        if isinstance(node, Inverter):
            return Inverter(kids[0], uid=uid)
        if isinstance(node, COMPOSITES):
            return replace(node, children=kids, uid=uid)
        return replace(node, uid=uid)

    return build(root)
