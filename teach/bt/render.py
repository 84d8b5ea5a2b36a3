"""Pictures of trees as pure functions: rich renderables for the terminal, plain text for logs
and golden tests, Graphviz DOT for papers. Symbols follow the thesis (Table 2.2): Sequence →,
Fallback ?, Parallel ⇉ M/N, Inverter ◇, conditions in parentheses, actions plain.

``statuses`` maps node uids to their status in the last tick (``TickResult.statuses()``);
when given, visited nodes are coloured by status and unvisited ones dimmed.
"""

from __future__ import annotations

from collections.abc import Mapping

from rich.text import Text
from rich.tree import Tree

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, Status, children

STYLES = {Status.SUCCESS: "green", Status.FAILURE: "red", Status.RUNNING: "yellow"}
_DOT_COLOURS = {Status.SUCCESS: "#9be59b", Status.FAILURE: "#f4a3a3", Status.RUNNING: "#f7e07a"}


def symbol(node: Node) -> str:
    """The node's thesis symbol, or its name for leaves."""
    if isinstance(node, Sequence):
        return "→"
    if isinstance(node, Fallback):
        return "?"
    if isinstance(node, Parallel):
        return f"⇉ {node.success_threshold}/{len(node.children)}"
    if isinstance(node, Inverter):
        return "◇"
    if isinstance(node, Condition):
        return f"({node.name})"
    if isinstance(node, Action):
        return node.name
    raise TypeError(f"not a node: {node!r}")


def _label(node: Node, labels: Mapping[str, str] | None) -> str:
    text = symbol(node)
    if labels and isinstance(node, (Condition, Action)) and labels.get(node.name):
        text += f" · {labels[node.name]}"
    return text


def _simple(node: Node) -> bool:
    """A leaf, or an Inverter over a leaf: short enough to write inline."""
    return isinstance(node, (Condition, Action)) or (isinstance(node, Inverter) and
                                                     isinstance(node.child, (Condition, Action)))


def render_tree(root: Node, statuses: Mapping[int, Status] | None = None,
                labels: Mapping[str, str] | None = None, compact: bool = False) -> Tree:
    """A rich tree; ``labels`` adds a human label (e.g. the domain's English text) to leaves.
    ``compact`` writes a control node whose children are all leaves (or inverted leaves) on
    one line, ``? (BinClose) ◇(BallGrasped) ApproachBin``, so a learned tree fits a screen."""
    def style(node: Node) -> str:
        if statuses is None:
            return "bold" if not isinstance(node, (Condition, Action)) else ""
        return STYLES[statuses[node.uid]] if node.uid in statuses else "dim"

    def line(node: Node) -> Text:
        text = Text(_label(node, labels), style=style(node))
        kids = children(node)
        if compact and kids and not isinstance(node, Inverter) and all(_simple(k) for k in kids):
            for kid in kids:
                text.append(" ")
                if isinstance(kid, Inverter):
                    text.append("◇", style=style(kid))
                    kid = kid.child
                text.append(_label(kid, labels), style=style(kid))
        return text

    def build(node: Node, into: Tree) -> None:
        if compact and not isinstance(node, Inverter) and children(node) and all(_simple(k) for k in children(node)):
            return  # already written inline
        for kid in children(node):
            build(kid, into.add(line(kid)))

    top = Tree(line(root), guide_style="bright_black")
    build(root, top)
    return top


def render_text(root: Node, statuses: Mapping[int, Status] | None = None,
                labels: Mapping[str, str] | None = None) -> str:
    """Plain text with tree guides; statuses are written as ``[RUNNING]`` after the node."""
    lines: list[str] = []

    def text(node: Node) -> str:
        label = _label(node, labels)
        if statuses is not None and node.uid in statuses:
            label += f" [{statuses[node.uid].name}]"
        return label

    def build(node: Node, prefix: str) -> None:
        kids = children(node)
        for i, kid in enumerate(kids):
            last = i == len(kids) - 1
            lines.append(f"{prefix}{'└── ' if last else '├── '}{text(kid)}")
            build(kid, prefix + ("    " if last else "│   "))

    lines.append(text(root))
    build(root, "")
    return "\n".join(lines) + "\n"


def _dot_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def to_dot(root: Node, statuses: Mapping[int, Status] | None = None,
           labels: Mapping[str, str] | None = None) -> str:
    """Graphviz DOT text; node ids are pre-order positions, so equal trees give equal text."""
    nodes: list[str] = []
    edges: list[str] = []

    def emit(node: Node) -> int:
        number = len(nodes) + 1
        nodes.append(f"  n{number} [{', '.join(_dot_attributes(node, statuses, labels))}];")
        for kid in children(node):
            edges.append(f"  n{number} -> n{len(nodes) + 1};")
            emit(kid)
        return number

    emit(root)
    header = ["digraph BehaviorTree {", "  graph [ordering=out];", '  node [fontname="Helvetica"];']
    return "\n".join(header + nodes + edges + ["}"]) + "\n"


def _dot_attributes(node: Node, statuses: Mapping[int, Status] | None,
                    labels: Mapping[str, str] | None) -> list[str]:
    shape = "ellipse" if isinstance(node, Condition) else "diamond" if isinstance(node, Inverter) else "box"
    attributes = [f"label={_dot_string(_label(node, labels))}", f"shape={shape}"]
    styles = ["rounded"] if isinstance(node, Action) else []
    if statuses is not None and node.uid in statuses:
        styles.append("filled")
        attributes.append(f'fillcolor="{_DOT_COLOURS[statuses[node.uid]]}"')
    elif statuses is not None:
        attributes += ['fontcolor="gray50"', 'color="gray70"']
    if styles:
        attributes.append(f'style="{",".join(styles)}"')
    return attributes
