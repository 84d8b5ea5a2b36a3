"""Behaviour trees as BehaviorTree.CPP v4 XML, the project's interchange format (DESIGN.md).

Writing produces what BehaviorTree.CPP and Groot2 load: memoryless control nodes as
``ReactiveSequence`` / ``ReactiveFallback``, ``Parallel`` with ``success_count`` M and
``failure_count`` N-M+1 (Table 2.2: it fails once more than N-M children fail), ``Inverter``,
leaves in the short form ``<BallFound/>`` and a sorted ``TreeNodesModel`` declaring each leaf.

Reading accepts that and the long leaf form ``<Condition ID="..."/>``, plus ``Sequence`` and
``Fallback`` (read as their memoryless versions, since our semantics have no memory). Tree
files come from other people's machines, so the parser is hardened: no DTDs, no entities, no
network, a size and a depth limit, and every problem is a ``FormatError`` naming the line.
"""

from __future__ import annotations

import io
import re
from pathlib import Path

from lxml import etree

from teach import limits
from teach.bt.builtins import BTCPP_BUILTINS
from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, children, renumber
from teach.errors import FormatError, shown
from teach.fsutil import atomic_write_text, decode_text, read_bytes

MAX_BYTES = limits.MAX_TREE_BYTES
"""Larger tree files are refused before parsing (learned trees are a few kilobytes)."""

MAX_DEPTH = limits.MAX_TREE_DEPTH
"""Deepest tree accepted; deeper ones would exhaust recursion in the tick and the learners."""

MAX_NODES = limits.MAX_TREE_NODES
"""Most elements a tree file may hold; counted before any node is built, so memory stays small."""

MAIN_TREE = "MainTree"

_SEQUENCES = ("ReactiveSequence", "Sequence")
_FALLBACKS = ("ReactiveFallback", "Fallback")
_CONTROL_TAGS = frozenset(_SEQUENCES + _FALLBACKS + ("Parallel", "Inverter", "Condition", "Action", "SubTree"))
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_METADATA = frozenset(("_uid", "_fullpath"))
"""The '_' attributes BehaviorTree.CPP writes itself to identify nodes (Groot2 logs): no behaviour."""
_COUNT = re.compile(r"-?[0-9]{1,9}", re.ASCII)
"""A Parallel count as BehaviorTree.CPP reads one: ASCII digits, '-' for counting from the end."""

# --- writing ------------------------------------------------------------------------------------

def tree_to_xml(root: Node) -> str:
    """The tree as BehaviorTree.CPP v4 XML; equal trees give identical text."""
    kinds: dict[str, str] = {}
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<root BTCPP_format="4" main_tree_to_execute="{MAIN_TREE}">',
             f'  <BehaviorTree ID="{MAIN_TREE}">']
    _write_node(root, 2, lines, kinds)
    lines.append("  </BehaviorTree>")
    lines.append("  <TreeNodesModel>")
    for kind, name in sorted((kind, name) for name, kind in kinds.items()):
        lines.append(f'    <{kind} ID="{name}"/>')
    lines.append("  </TreeNodesModel>")
    lines.append("</root>")
    return "\n".join(lines) + "\n"


def _write_node(node: Node, level: int, lines: list[str], kinds: dict[str, str]) -> None:
    if level - 2 >= MAX_DEPTH:
        raise FormatError(f"the tree is deeper than {MAX_DEPTH} levels, the most a tree file may hold")
    pad = "  " * level
    if isinstance(node, (Condition, Action)):
        kind = type(node).__name__
        if not isinstance(node.name, str) or not _NAME.match(node.name):
            raise FormatError(f"{kind.lower()} name {node.name!r} is not an identifier (letters, digits, _)")
        if node.name in BTCPP_BUILTINS or node.name in _CONTROL_TAGS:
            raise FormatError(f"{kind.lower()} name {node.name!r} is a BehaviorTree.CPP node type; rename it")
        if kinds.setdefault(node.name, kind) != kind:
            raise FormatError(f"{node.name!r} is used both as a condition and as an action")
        lines.append(f"{pad}<{node.name}/>")
        return
    kids = children(node)
    if isinstance(node, Inverter):
        open_tag, close_tag = "<Inverter>", "</Inverter>"
    elif isinstance(node, Parallel):
        n, m = len(kids), node.success_threshold
        open_tag, close_tag = f'<Parallel success_count="{m}" failure_count="{n - m + 1}">', "</Parallel>"
    elif isinstance(node, Sequence):
        open_tag, close_tag = "<ReactiveSequence>", "</ReactiveSequence>"
    elif isinstance(node, Fallback):
        open_tag, close_tag = "<ReactiveFallback>", "</ReactiveFallback>"
    else:
        raise TypeError(f"not a node: {node!r}")
    if not kids:
        raise FormatError(f"a {type(node).__name__} without children cannot be written")
    lines.append(pad + open_tag)
    for kid in kids:
        _write_node(kid, level + 1, lines, kinds)
    lines.append(pad + close_tag)


def write_tree(path: str | Path, root: Node, project: str | Path | None = None) -> None:
    """Write a tree file atomically (the text is built completely before anything is written); no
    folder between ``project`` (default: the working folder) and it may be a symbolic link. A tree
    too large to be read back (``MAX_NODES`` elements, ``MAX_BYTES``) is refused, not written."""
    text = tree_to_xml(root)
    elements = text.count("<") - text.count("</") - 1  # less the XML declaration
    if elements > MAX_NODES or len(text.encode()) > MAX_BYTES:
        raise FormatError(f"the tree has {elements} elements ({len(text.encode())} bytes): more than a tree file may "
                          f"hold ({MAX_NODES} elements, {MAX_BYTES} bytes), so it is not written", path)
    atomic_write_text(path, text, project)


# --- reading ------------------------------------------------------------------------------------

def read_tree(path: str | Path) -> Node:
    """Read a tree file; uids are the canonical pre-order numbering."""
    path = Path(path)
    return tree_from_xml(read_bytes(path, "tree file", MAX_BYTES), path)


def tree_from_xml(text: str | bytes, path: str | Path = "<string>") -> Node:
    """Parse BehaviorTree.CPP v4 XML into a tree (uids renumbered canonically)."""
    data = text.encode("utf-8") if isinstance(text, str) else text
    if len(data) > MAX_BYTES:
        raise FormatError(f"tree file is {len(data)} bytes, more than the {MAX_BYTES} accepted", path)
    decoded = decode_text(data, "tree file", path)
    if not decoded.strip():
        raise FormatError("empty tree file", path)
    for marker in ("<!DOCTYPE", "<!ENTITY"):
        at = decoded.find(marker)
        if at >= 0:
            raise FormatError(f"{marker[2:]} declarations are not allowed in tree files (entities are never expanded)",
                              path, decoded[:at].count("\n") + 1)
    try:
        document = _parse_bounded(data, path)
    except etree.XMLSyntaxError as exc:
        message = re.sub(r",? line \d+, column \d+\s*$", "", exc.msg or "").strip() or "malformed XML"
        if message.startswith("Excessive depth"):
            raise FormatError(f"the tree is more than {MAX_DEPTH} levels deep", path, exc.lineno or None) from None
        raise FormatError(f"not well-formed XML: {message}", path, exc.lineno or None) from None
    tree = document.getroottree()
    if tree.docinfo.doctype or tree.docinfo.internalDTD is not None:
        raise FormatError("DOCTYPE declarations are not allowed in tree files", path, 1)
    return renumber(_Reader(path).document(document))


def _parse_bounded(data: bytes, path: str | Path) -> etree._Element:
    """Parse incrementally and stop at the ``MAX_NODES``-th element, so a huge file of tiny
    elements costs no more memory than a tree at the limit (no DTD, entities or network)."""
    events = etree.iterparse(io.BytesIO(data), events=("start",), resolve_entities=False, no_network=True,
                             load_dtd=False, dtd_validation=False, huge_tree=False, remove_comments=True,
                             remove_pis=True)
    root = None
    for count, (_, element) in enumerate(events, start=1):
        if count > MAX_NODES:
            raise FormatError(f"more than {MAX_NODES} elements: a tree file may hold at most that many",
                              path, element.sourceline)
        if root is None:
            root = element
    if root is None:
        raise FormatError("no XML element in the tree file", path)
    return root


class _Reader:
    """Turns a parsed document into nodes; one instance per file, for error locations."""

    def __init__(self, path: str | Path):
        self.path = path
        self.kinds: dict[str, str] = {}

    def fail(self, message: str, element: etree._Element | None = None) -> FormatError:
        line = element.sourceline if element is not None else None
        return FormatError(message, self.path, line)

    def document(self, root: etree._Element) -> Node:
        tag = _tag(root)
        if tag != "root":
            raise self.fail(f"root element is <{tag}>, expected <root BTCPP_format=\"4\">", root)
        fmt = root.get("BTCPP_format")
        if fmt is not None and fmt != "4":
            raise self.fail(f"BTCPP_format=\"{fmt}\" is not supported; expected BehaviorTree.CPP format 4", root)
        trees: dict[str, etree._Element] = {}
        for element in _elements(root):
            kind = _tag(element)
            if kind == "BehaviorTree":
                tree_id = element.get("ID")
                if not tree_id:
                    raise self.fail("<BehaviorTree> without an ID attribute", element)
                if tree_id in trees:
                    raise self.fail(f"duplicate BehaviorTree ID {tree_id!r}", element)
                trees[tree_id] = element
            elif kind == "TreeNodesModel":
                self.model(element)
            elif kind == "include":
                raise self.fail("<include> is not supported: put the whole tree in one file", element)
            else:
                raise self.fail(f"unexpected element <{kind}> under <root> "
                                "(expected <BehaviorTree> or <TreeNodesModel>)", element)
        if not trees:
            raise self.fail("no <BehaviorTree> in the file", root)
        main = root.get("main_tree_to_execute")
        if main is None:
            if len(trees) > 1:
                raise self.fail(f"{len(trees)} BehaviorTrees and no main_tree_to_execute attribute "
                                "saying which one to use", root)
            (main,) = trees
        if main not in trees:
            raise self.fail(f"main tree {main!r} not found (the file has {', '.join(map(repr, sorted(trees)))})", root)
        body = _elements(trees[main])
        if len(body) != 1:
            raise self.fail(f"BehaviorTree {main!r} must hold exactly one root node, found {len(body)}", trees[main])
        return self.node(body[0], 1)

    def model(self, model: etree._Element) -> None:
        for element in _elements(model):
            kind = _tag(element)
            if kind in ("Decorator", "Control", "SubTree"):
                continue  # types we never use; using one in the tree is reported there
            if kind not in ("Condition", "Action"):
                raise self.fail(f"unexpected element <{kind}> in <TreeNodesModel>", element)
            name = element.get("ID")
            if not name:
                raise self.fail(f"<{kind}> in <TreeNodesModel> without an ID attribute", element)
            if self.kinds.setdefault(name, kind) != kind:
                raise self.fail(f"{name!r} is declared both as a Condition and as an Action", element)

    def node(self, element: etree._Element, level: int) -> Node:
        if level > MAX_DEPTH:
            raise self.fail(f"the tree is more than {MAX_DEPTH} levels deep", element)
        tag = _tag(element)
        self.check_attributes(element, tag)
        kids = _elements(element)
        if tag in ("Condition", "Action"):
            name = element.get("ID")
            if not name:
                raise self.fail(f"<{tag}> without an ID attribute", element)
            return self.leaf(tag, name, kids, element)
        if tag in self.kinds and tag not in _CONTROL_TAGS:
            return self.leaf(self.kinds[tag], tag, kids, element)
        if tag == "SubTree":
            raise self.fail("<SubTree> is not supported: inline the subtree into the main tree", element)
        if tag not in _CONTROL_TAGS:
            if tag in BTCPP_BUILTINS:
                raise self.fail(f"unsupported node type <{tag}>: teach trees use ReactiveSequence, "
                                "ReactiveFallback, Parallel, Inverter, conditions and actions", element)
            raise self.fail(f"unknown node type <{tag}>: not a control node and not declared "
                            "in <TreeNodesModel> as a Condition or Action", element)
        if not kids:
            raise self.fail(f"<{tag}> has no children", element)
        nodes = tuple(self.node(kid, level + 1) for kid in kids)
        if tag == "Inverter":
            if len(nodes) != 1:
                raise self.fail(f"<Inverter> must have exactly one child, found {len(nodes)}", element)
            return Inverter(nodes[0])
        if tag == "Parallel":
            return Parallel(nodes, self.parallel_threshold(element, len(nodes)))
        return Sequence(nodes) if tag in _SEQUENCES else Fallback(nodes)

    def check_attributes(self, element: etree._Element, tag: str) -> None:
        """Refuse BehaviorTree.CPP's special attributes (``_skipIf``, ``_successIf``, ``_while``,
        ``_onSuccess``, ``_post``, ...): teach does not implement them, so the tree would behave
        differently here than in BehaviorTree.CPP. Node metadata (``_uid``, ``_fullpath``) is let be."""
        for name in element.attrib:
            if str(name).startswith("_") and name not in _METADATA:
                raise self.fail(f"<{tag}> has attribute {shown(str(name))}: BehaviorTree.CPP's pre- and "
                                "post-conditions and other '_' attributes are not supported by teach, so the tree "
                                "would behave differently here than in BehaviorTree.CPP", element)

    def leaf(self, kind: str, name: str, kids: list[etree._Element], element: etree._Element) -> Node:
        if kids:
            raise self.fail(f"{kind.lower()} {name!r} is a leaf but has child elements", element)
        if not _NAME.match(name):
            raise self.fail(f"{kind.lower()} name {name!r} is not an identifier (letters, digits, _)", element)
        if self.kinds.setdefault(name, kind) != kind:
            raise self.fail(f"{name!r} is used both as a Condition and as an Action", element)
        return Condition(name) if kind == "Condition" else Action(name)

    def parallel_threshold(self, element: etree._Element, n: int) -> int:
        """M from success_count, checked against failure_count = N-M+1 (BehaviorTree.CPP's
        defaults, success_count=-1 meaning all children and failure_count=1, agree with M=N)."""
        counts = []
        for attribute, default in (("success_count", -1), ("failure_count", 1)):
            raw = element.get(attribute)
            if raw is not None and not _COUNT.fullmatch(raw):
                raise self.fail(f"<Parallel> {attribute}={shown(raw)} is not an integer", element)
            value = default if raw is None else int(raw)
            if value < 0:
                value = n + value + 1  # BehaviorTree.CPP: -1 = all children
            if not 1 <= value <= n:
                raise self.fail(f"<Parallel> {attribute}={raw} is not between 1 and its {n} children", element)
            counts.append(value)
        success, failure = counts
        if failure != n - success + 1:
            raise self.fail(f"<Parallel> failure_count={failure} does not fit success_count={success} with "
                            f"{n} children: Table 2.2 semantics need failure_count={n - success + 1}", element)
        return success


def _tag(element: etree._Element) -> str:
    return str(element.tag)


def _elements(element: etree._Element) -> list[etree._Element]:
    """Child elements, skipping comments and processing instructions."""
    return [kid for kid in element if isinstance(kid.tag, str)]
