"""The behaviour tree as rerun's graph view shows it: short labels in the session's language,
BehaviorTree.CPP's status colours, and explicit positions from a compact top-down layout.

rerun's graph view would otherwise lay the nodes out with forces (a tangle for 35 nodes), so
positions are computed here: a tidy layered layout that packs subtrees by their per-level
contours, so a shallow leaf sits beside a deep neighbour instead of widening the whole row.

A tree too large to read whole in its panel (the safe learner's run trees have hundreds of
nodes) is drawn per tick as the nodes that tick reached, each run of siblings it did not reach
folded into one labelled node ("… 27 nodes"): the path to the running action at a readable size.
"""

from __future__ import annotations

import textwrap
from collections.abc import Collection, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from teach.bt.nodes import Action, Condition, Node, Status, children, size
from teach.bt.render import symbol
from teach.observe.layout import RUN_TREE_PANEL

if TYPE_CHECKING:
    from teach.domain import Domain

# Groot2's palette: success green, failure red, running orange, idle (not ticked) grey
STATUS_COLOURS = {Status.SUCCESS: (60, 180, 75), Status.FAILURE: (220, 50, 47), Status.RUNNING: (245, 150, 20)}
IDLE_COLOUR = (110, 110, 110)  # dark enough to read as a label on white
RUNNING_MARK = "▶ "

LINE_WIDTHS = (10, 12, 14, 18, 24)  # leaf labels wrap at one of these; the one that fits the panel best
CHAR_WIDTH = 7.5      # graph-view units per character of rerun's label font (measured on screenshots)
NODE_PADDING = 18.0   # the box around a label
NODE_GAP = 10.0       # between neighbouring boxes on one level
LINE_HEIGHT = 16.0
LEVEL_GAP = 16.0      # between a level's deepest box and the next level
READABLE = 0.75       # a tree drawn smaller than this in its panel is drawn folded, tick by tick
FOLDED = {"en": "… {} nodes", "de": "… {} Knoten"}
"""The label of a fold: this many nodes the tick did not reach, drawn as one."""


def phrases(domain: Domain, lang: str) -> dict[str, str]:
    """Each condition's and action's first phrase in the session's language, for the leaves."""
    named = {c.name: c.label(lang) for c in domain.conditions}
    named.update((a.name, a.label(lang)) for a in domain.actions)
    return named


def display_label(node: Node, phrases: Mapping[str, str], width: int) -> str:
    """A node's label: the thesis symbol for control nodes, the phrase (wrapped at ``width``) for leaves."""
    if isinstance(node, (Condition, Action)) and phrases.get(node.name):
        text = phrases[node.name] + ("?" if isinstance(node, Condition) else "")
        return "\n".join(textwrap.wrap(text, width)) or node.name
    return symbol(node)


@dataclass(frozen=True)
class _Drawn:
    """One node of the drawing: a tree node, or (``node`` None) a fold of ``hidden`` nodes."""

    node: Node | None
    hidden: int = 0
    kids: list[int] = field(default_factory=list)


def _drawing(tree: Node, reached: Collection[int] | None) -> list[_Drawn]:
    """The drawing's nodes in pre-order: every node (``reached`` None), or the nodes whose uids a
    tick reached with each run of siblings it did not reach folded (a lone leaf stays itself)."""
    drawn: list[_Drawn] = []

    def add(node: Node | None, hidden: int = 0) -> int:
        at = len(drawn)
        entry = _Drawn(node, hidden)
        drawn.append(entry)
        untouched: list[Node] = []
        for kid in children(node) if node is not None else ():
            if reached is None or kid.uid in reached:
                entry.kids.extend(fold(untouched))
                entry.kids.append(add(kid))
            else:
                untouched.append(kid)
        entry.kids.extend(fold(untouched))
        return at

    def fold(untouched: list[Node]) -> list[int]:
        if not untouched:
            return []
        single = untouched[0] if len(untouched) == 1 and not children(untouched[0]) else None
        at = add(single) if single is not None else add(None, sum(size(n) for n in untouched))
        untouched.clear()
        return [at]

    add(tree)
    return drawn


@dataclass
class TreeView:
    """A tree as the graph shows it: node ids are drawing positions (pre-order, so stable).

    ``names`` are the nodes' symbols (what the recording's trace reads back); ``labels`` what
    the viewer shows; ``actions`` the positions of the action nodes, for the running mark;
    ``scale`` how large its panel draws it; ``reached`` the uids a folded view was drawn for
    (None: the whole tree).
    """

    tree: Node
    index: dict[int, int]
    names: list[str]
    labels: list[str]
    edges: list[tuple[str, str]]
    positions: np.ndarray
    actions: frozenset[int]
    scale: float
    reached: frozenset[int] | None = None

    @classmethod
    def of(cls, tree: Node, phrases: Mapping[str, str] | None = None,
           panel: tuple[float, float] = RUN_TREE_PANEL, reached: Collection[int] | None = None,
           lang: str = "en") -> TreeView:
        """The view of ``tree`` (folded to the uids ``reached``, if given) whose labels wrap at the
        width that draws it largest in ``panel`` (the graph view's size in pixels)."""
        drawn = _drawing(tree, reached)
        kids = [entry.kids for entry in drawn]
        index = {entry.node.uid: i for i, entry in enumerate(drawn) if entry.node is not None}
        edges = [(str(i), str(k)) for i, entry in enumerate(drawn) for k in entry.kids]
        actions = frozenset(i for i, entry in enumerate(drawn) if isinstance(entry.node, Action))
        folded = FOLDED.get(lang, FOLDED["en"])
        # wide trees read best with narrow leaves, deep ones with long lines: keep the largest scale
        best: tuple[float, list[str], np.ndarray] | None = None
        for width in LINE_WIDTHS:
            labels = [folded.format(e.hidden) if e.node is None else display_label(e.node, phrases or {}, width)
                      for e in drawn]
            positions = layout(kids, labels)
            scale = panel_scale(positions, labels, panel)
            if best is None or scale > best[0] + 1e-9:
                best = (scale, labels, positions)
        assert best is not None
        names = ["…" if e.node is None else symbol(e.node) for e in drawn]
        return cls(tree, index, names, best[1], edges, best[2], actions, best[0],
                   None if reached is None else frozenset(reached))

    def colours(self, statuses: Mapping[int, Status]) -> list[tuple[int, int, int]]:
        """Each node's colour for one tick (``statuses`` by node uid; absent = not ticked)."""
        colours = [IDLE_COLOUR] * len(self.labels)
        for uid, status in statuses.items():
            if uid in self.index:
                colours[self.index[uid]] = STATUS_COLOURS[status]
        return colours

    def marked_labels(self, statuses: Mapping[int, Status]) -> list[str]:
        """The labels with the running action marked: the action node the tick left RUNNING."""
        labels = list(self.labels)
        for uid, status in statuses.items():
            i = self.index.get(uid)
            if status is Status.RUNNING and i in self.actions:
                labels[i] = RUNNING_MARK + labels[i]
        return labels


def panel_scale(positions: np.ndarray, labels: list[str], panel: tuple[float, float] = RUN_TREE_PANEL) -> float:
    """How large the graph view draws the tree when it fits the whole drawing into the panel."""
    boxes = np.array([_box(label) for label in labels])
    low = (positions - boxes / 2).min(axis=0)
    high = (positions + boxes / 2).max(axis=0)
    width, height = high - low
    return float(min(panel[0] / width, panel[1] / height))


def _box(label: str) -> tuple[float, float]:
    lines = label.split("\n")
    return max(len(line) for line in lines) * CHAR_WIDTH + NODE_PADDING, len(lines) * LINE_HEIGHT + NODE_PADDING


def layout(kids: list[list[int]], labels: list[str]) -> np.ndarray:
    """Top-down tidy layout of the drawing (``kids[i]``: node i's children; node 0 the root): each
    parent centred over its children, subtrees packed side by side as closely as their contours
    (leftmost and rightmost box edge on each level) allow."""
    boxes = [_box(label) for label in labels]
    depth_of = [0] * len(labels)
    for i in range(len(labels)):  # pre-order: a parent comes before its children
        for kid in kids[i]:
            depth_of[kid] = depth_of[i] + 1
    level_height = [0.0] * (max(depth_of) + 1)
    for i, depth in enumerate(depth_of):
        level_height[depth] = max(level_height[depth], boxes[i][1])
    level_y = np.cumsum([0.0] + [h + LEVEL_GAP for h in level_height[:-1]])
    x = np.zeros(len(labels), dtype=np.float64)

    def members(i: int) -> list[int]:
        return [i, *(m for kid in kids[i] for m in members(kid))]

    def place(i: int) -> dict[int, tuple[float, float]]:
        """Lay out the subtree with its root at x = 0; return its contour by depth."""
        half = boxes[i][0] / 2
        if not kids[i]:
            return {depth_of[i]: (-half, half)}
        contour: dict[int, tuple[float, float]] = {}
        groups: list[list[int]] = []
        offsets: list[float] = []
        for kid in kids[i]:
            kid_contour = place(kid)
            shift = 0.0 if not contour else max(
                (contour[d][1] + NODE_GAP - kid_contour[d][0] for d in kid_contour if d in contour), default=0.0)
            offsets.append(shift)
            groups.append(members(kid))
            for d, (low, high) in kid_contour.items():
                old = contour.get(d)
                contour[d] = (low + shift, high + shift) if old is None else (old[0], high + shift)
        for shift, nodes in zip(offsets, groups, strict=True):
            x[nodes] += shift
        centre = (x[kids[i][0]] + x[kids[i][-1]]) / 2
        for nodes in groups:
            x[nodes] -= centre
        contour = {d: (low - centre, high - centre) for d, (low, high) in contour.items()}
        contour[depth_of[i]] = (-half, half)
        return contour

    place(0)
    positions = np.zeros((len(labels), 2), dtype=np.float32)
    positions[:, 0] = x
    positions[:, 1] = [level_y[d] for d in depth_of]
    return positions
