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


def render_tree(root: Node, statuses: Mapping[int, Status] | None = None,
                labels: Mapping[str, str] | None = None) -> Tree:
    """A rich tree; ``labels`` adds a human label (e.g. the domain's English text) to leaves."""
    def style(node: Node) -> str:
        if statuses is None:
            return "bold" if not isinstance(node, (Condition, Action)) else ""
        return STYLES[statuses[node.uid]] if node.uid in statuses else "dim"

    def build(node: Node, into: Tree) -> None:
        for kid in children(node):
            build(kid, into.add(Text(_label(kid, labels), style=style(kid))))

    top = Tree(Text(_label(root, labels), style=style(root)), guide_style="bright_black")
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
