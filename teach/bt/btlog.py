"""Runs of our trees as BehaviorTree.CPP ``.btlog`` files, the format Groot2 replays.

The format is that of BehaviorTree.CPP's ``FileLogger2`` (``src/loggers/bt_file_logger_v2.cpp``):
the bytes ``BTCPP4-FileLogger2``, a protocol byte (1), the tree's XML preceded by its length
(int32, little-endian), the first timestamp (int64, µs since the epoch), then one 9-byte record
per status change: 6 bytes of µs since the first timestamp, 2 bytes of node uid, 1 byte of
status (``BtStatus``), little-endian. The XML is what ``WriteTreeToXML(tree, true, true)``
writes for the tree loaded from our XML by a factory that knows only the tree's leaves:
every node with ``name`` and ``_uid`` attributes, and a ``TreeNodesModel`` with BehaviorTree.CPP's
built-in node models, byte for byte, so a log written here and one written by BehaviorTree.CPP
for the same tree start with the same header.

``BtlogWriter`` ticks the tree with ``BtcppTree`` (the status changes BehaviorTree.CPP would
log), either in a world of its own (``tick``) or from the trace of a tick our executor already
ran (``log_tick``), and writes the file atomically at ``close``; ``read_btlog`` reads any
``FileLogger2`` file and reports a damaged one in one line.
"""

from __future__ import annotations

import itertools
import struct
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import NamedTuple

from lxml import etree

from teach.bt.btcpp_status import ActionTick, BtcppTree, BtStatus, Change, ConditionLookup, HaltHook, TickChanges
from teach.bt.nodes import Action, Condition, Inverter, Node, Parallel, Sequence, children, walk
from teach.bt.tick import TickResult, always_running
from teach.bt.xml import MAIN_TREE, MAX_BYTES, tree_to_xml
from teach.errors import FormatError, TeachError
from teach.fsutil import atomic_write_bytes, read_bytes

MAGIC = b"BTCPP4-FileLogger2"
PROTOCOL = 1
SUFFIX = ".btlog"
RECORD = 9
MAX_UID = 0xFFFF
"""Node uids are two bytes in a record, so a loggable tree has at most 65535 nodes."""
MAX_LOG_BYTES = 64 * 1024 * 1024
"""The largest .btlog read back (the tree's XML and some seven million records)."""
MAX_TIME_US = 1 << 48
"""Record timestamps are six bytes of µs (almost nine years after the first timestamp)."""

BTCPP_VERSION = "4.8.2"
"""The BehaviorTree.CPP whose built-in node models ``BUILTIN_MODELS`` copies (the one
``behaviortreepy`` bundles; a test compares our header with the one it writes)."""

BUILTIN_MODELS: tuple[str, ...] = (
    '<Action ID="AlwaysFailure"/>',
    '<Action ID="AlwaysSuccess"/>',
    '<Control ID="AsyncFallback"/>',
    '<Control ID="AsyncSequence"/>',
    ('<Decorator ID="Delay">\n'
     '    <input_port name="delay_msec" type="unsigned int">Tick the child after a few'
     ' milliseconds</input_port>\n'
     '</Decorator>'),
    '<Control ID="Fallback"/>',
    '<Decorator ID="ForceFailure"/>',
    '<Decorator ID="ForceSuccess"/>',
    '<Control ID="IfThenElse"/>',
    '<Decorator ID="Inverter"/>',
    '<Decorator ID="KeepRunningUntilFailure"/>',
    ('<Decorator ID="LoopBool">\n'
     '    <output_port name="value" type="bool"/>\n'
     '    <input_port name="if_empty" type="BT::NodeStatus" default="SUCCESS">Status to return'
     ' if queue is empty: SUCCESS, FAILURE, SKIPPED</input_port>\n'
     '    <inout_port name="queue" type="std::shared_ptr&lt;std::deque&lt;bool,'
     ' std::allocator&lt;bool&gt; &gt; &gt;"/>\n'
     '</Decorator>'),
    ('<Decorator ID="LoopDouble">\n'
     '    <output_port name="value" type="double"/>\n'
     '    <input_port name="if_empty" type="BT::NodeStatus" default="SUCCESS">Status to return'
     ' if queue is empty: SUCCESS, FAILURE, SKIPPED</input_port>\n'
     '    <inout_port name="queue" type="std::shared_ptr&lt;std::deque&lt;double,'
     ' std::allocator&lt;double&gt; &gt; &gt;"/>\n'
     '</Decorator>'),
    ('<Decorator ID="LoopInt">\n'
     '    <output_port name="value" type="int"/>\n'
     '    <input_port name="if_empty" type="BT::NodeStatus" default="SUCCESS">Status to return'
     ' if queue is empty: SUCCESS, FAILURE, SKIPPED</input_port>\n'
     '    <inout_port name="queue" type="std::shared_ptr&lt;std::deque&lt;int,'
     ' std::allocator&lt;int&gt; &gt; &gt;"/>\n'
     '</Decorator>'),
    ('<Decorator ID="LoopString">\n'
     '    <output_port name="value" type="std::string"/>\n'
     '    <input_port name="if_empty" type="BT::NodeStatus" default="SUCCESS">Status to return'
     ' if queue is empty: SUCCESS, FAILURE, SKIPPED</input_port>\n'
     '    <inout_port name="queue" type="std::shared_ptr&lt;std::deque&lt;std::string,'
     ' std::allocator&lt;std::string&gt; &gt; &gt;"/>\n'
     '</Decorator>'),
    ('<Control ID="Parallel">\n'
     '    <input_port name="failure_count" type="int" default="1">number of children that need'
     ' to fail to trigger a FAILURE</input_port>\n'
     '    <input_port name="success_count" type="int" default="-1">number of children that need'
     ' to succeed to trigger a SUCCESS</input_port>\n'
     '</Control>'),
    ('<Control ID="ParallelAll">\n'
     '    <input_port name="max_failures" type="int" default="1">If the number of children'
     ' returning FAILURE exceeds this value, ParallelAll returns FAILURE</input_port>\n'
     '</Control>'),
    ('<Decorator ID="Precondition">\n'
     '    <input_port name="else" type="BT::NodeStatus" default="FAILURE">Return status if'
     ' condition is false</input_port>\n'
     '    <input_port name="if" type="std::string"/>\n'
     '</Decorator>'),
    '<Control ID="ReactiveFallback"/>',
    '<Control ID="ReactiveSequence"/>',
    ('<Decorator ID="Repeat">\n'
     '    <input_port name="num_cycles" type="int">Repeat a successful child up to N times. Use'
     ' -1 to create an infinite loop.</input_port>\n'
     '</Decorator>'),
    ('<Decorator ID="RetryUntilSuccessful">\n'
     '    <input_port name="num_attempts" type="int">Execute again a failing child up to N'
     ' times. Use -1 to create an infinite loop.</input_port>\n'
     '</Decorator>'),
    ('<Decorator ID="RunOnce">\n'
     '    <input_port name="then_skip" type="bool" default="true">If true, skip after the first'
     ' execution, otherwise return the same NodeStatus returned once by the child.</input_port>\n'
     '</Decorator>'),
    ('<Action ID="Script">\n'
     '    <input_port name="code" type="std::string">Piece of code that can be parsed</input_port>\n'
     '</Action>'),
    ('<Condition ID="ScriptCondition">\n'
     '    <input_port name="code" type="BT::AnyTypeAllowed">Piece of code that can be parsed.'
     ' Must return false or true</input_port>\n'
     '</Condition>'),
    '<Control ID="Sequence"/>',
    '<Control ID="SequenceWithMemory"/>',
    ('<Action ID="SetBlackboard">\n'
     '    <inout_port name="output_key" type="BT::AnyTypeAllowed">Name of the blackboard entry'
     ' where the value should be written</inout_port>\n'
     '    <input_port name="value" type="BT::AnyTypeAllowed">Value to be written into the'
     ' output_key</input_port>\n'
     '</Action>'),
    ('<Decorator ID="SkipUnlessUpdated">\n'
     '    <input_port name="entry" type="BT::Any">Entry to check</input_port>\n'
     '</Decorator>'),
    ('<Action ID="Sleep">\n'
     '    <input_port name="msec" type="unsigned int"/>\n'
     '</Action>'),
    ('<SubTree ID="SubTree">\n'
     '    <input_port name="_autoremap" type="bool" default="false">If true, all the ports with'
     ' the same name will be remapped</input_port>\n'
     '</SubTree>'),
    ('<Control ID="Switch2">\n'
     '    <input_port name="case_2" type="std::string"/>\n'
     '    <input_port name="case_1" type="std::string"/>\n'
     '    <input_port name="variable" type="std::string"/>\n'
     '</Control>'),
    ('<Control ID="Switch3">\n'
     '    <input_port name="case_3" type="std::string"/>\n'
     '    <input_port name="case_2" type="std::string"/>\n'
     '    <input_port name="case_1" type="std::string"/>\n'
     '    <input_port name="variable" type="std::string"/>\n'
     '</Control>'),
    ('<Control ID="Switch4">\n'
     '    <input_port name="case_4" type="std::string"/>\n'
     '    <input_port name="case_3" type="std::string"/>\n'
     '    <input_port name="case_2" type="std::string"/>\n'
     '    <input_port name="case_1" type="std::string"/>\n'
     '    <input_port name="variable" type="std::string"/>\n'
     '</Control>'),
    ('<Control ID="Switch5">\n'
     '    <input_port name="case_5" type="std::string"/>\n'
     '    <input_port name="case_4" type="std::string"/>\n'
     '    <input_port name="case_3" type="std::string"/>\n'
     '    <input_port name="case_2" type="std::string"/>\n'
     '    <input_port name="case_1" type="std::string"/>\n'
     '    <input_port name="variable" type="std::string"/>\n'
     '</Control>'),
    ('<Control ID="Switch6">\n'
     '    <input_port name="case_5" type="std::string"/>\n'
     '    <input_port name="case_4" type="std::string"/>\n'
     '    <input_port name="case_6" type="std::string"/>\n'
     '    <input_port name="case_3" type="std::string"/>\n'
     '    <input_port name="case_2" type="std::string"/>\n'
     '    <input_port name="case_1" type="std::string"/>\n'
     '    <input_port name="variable" type="std::string"/>\n'
     '</Control>'),
    ('<Decorator ID="Timeout">\n'
     '    <input_port name="msec" type="unsigned int">After a certain amount of time, halt() the'
     ' child if it is still running.</input_port>\n'
     '</Decorator>'),
    ('<Action ID="UnsetBlackboard">\n'
     '    <input_port name="key" type="std::string">Key of the entry to remove</input_port>\n'
     '</Action>'),
    ('<Decorator ID="WaitValueUpdate">\n'
     '    <input_port name="entry" type="BT::Any">Entry to check</input_port>\n'
     '</Decorator>'),
    ('<Action ID="WasEntryUpdated">\n'
     '    <input_port name="entry" type="BT::Any">Entry to check</input_port>\n'
     '</Action>'),
    '<Control ID="WhileDoElse"/>',
)
"""The ``TreeNodesModel`` entries BehaviorTree.CPP writes for its own nodes, as its XML printer
writes them (port order included), one element each; Groot2 reads the models from the log."""


def epoch_us() -> int:
    """Wall-clock µs since the epoch, BehaviorTree.CPP's timestamps."""
    return time.time_ns() // 1000


# --- the XML header -----------------------------------------------------------------------------

def btcpp_xml(root: Node) -> str:
    """The tree's XML as BehaviorTree.CPP's ``FileLogger2`` writes it into a log's header."""
    tree_to_xml(root)  # the same names are refused as in tree files
    nodes = list(walk(root))
    if len(nodes) > MAX_UID:
        raise FormatError(f"the tree has {len(nodes)} nodes; a .btlog numbers at most {MAX_UID}")
    builtin = {_model_id(entry): entry for entry in BUILTIN_MODELS}
    models = dict(builtin)
    for node in nodes:
        if isinstance(node, (Condition, Action)):
            if node.name in builtin:
                raise FormatError(f"{type(node).__name__.lower()} name {node.name!r} is a BehaviorTree.CPP "
                                  f"{BTCPP_VERSION} node type; rename it")
            models[node.name] = f'<{type(node).__name__} ID="{node.name}"/>'
    lines = ['<root BTCPP_format="4">', f'    <BehaviorTree ID="{MAIN_TREE}" _fullpath="">']
    _write_node(root, 2, itertools.count(1), lines)
    lines.append("    </BehaviorTree>")
    lines.append("    <TreeNodesModel>")
    for model_id in sorted(models, key=lambda name: name.encode()):
        lines.extend("        " + line for line in models[model_id].split("\n"))
    lines.append("    </TreeNodesModel>")
    lines.append("</root>")
    return "\n".join(lines) + "\n"


def _model_id(entry: str) -> str:
    return entry.split('ID="', 1)[1].split('"', 1)[0]


def _write_node(node: Node, level: int, uids: Iterator[int], lines: list[str]) -> None:
    uid = next(uids)
    if isinstance(node, (Condition, Action)):
        tag = node.name
    elif isinstance(node, Inverter):
        tag = "Inverter"
    elif isinstance(node, Parallel):
        tag = "Parallel"
    else:
        tag = "ReactiveSequence" if isinstance(node, Sequence) else "ReactiveFallback"
    opening = f'{"    " * level}<{tag} name="{tag}" _uid="{uid}"'
    if isinstance(node, Parallel):
        m = node.success_threshold
        opening += f' success_count="{m}" failure_count="{len(node.children) - m + 1}"'
    kids = children(node)
    if not kids:
        lines.append(opening + "/>")
        return
    lines.append(opening + ">")
    for kid in kids:
        _write_node(kid, level + 1, uids, lines)
    lines.append(f'{"    " * level}</{tag}>')


def _header(xml: str, start_us: int) -> bytes:
    data = xml.encode("utf-8")
    return MAGIC + bytes([PROTOCOL]) + struct.pack("<i", len(data)) + data + struct.pack("<q", start_us)


# --- writing ------------------------------------------------------------------------------------

class BtlogWriter:
    """Tick ``tree`` as BehaviorTree.CPP would and log every status change to ``path``.

    ``clock`` gives µs since the epoch (pass a fake one for byte-identical files); it is read
    once when the writer is made (the file's first timestamp) and once per tick or halt, whose
    changes all carry that time. Nothing is written before ``close`` (or the end of a ``with``
    block), and then the whole file at once, atomically."""

    def __init__(self, path: str | Path, tree: Node, clock: Callable[[], int] = epoch_us):
        self.path = Path(path)
        if self.path.suffix != SUFFIX:
            raise TeachError(f"a log for Groot2 must be named *{SUFFIX}", self.path)
        self.xml = btcpp_xml(tree)
        self.live = BtcppTree(tree)
        self.clock = clock
        self.start_us = clock()
        self.records = bytearray()

    def tick(self, condition: ConditionLookup, action: ActionTick = always_running,
             on_halt: HaltHook | None = None) -> TickChanges:
        """One tick in the world ``condition``/``action`` (see ``BtcppTree.tick``), logged."""
        result = self.live.tick(condition, action, on_halt)
        self._record(result.changes)
        return result

    def log_tick(self, result: TickResult) -> TickChanges:
        """Log a tick ``teach.bt.tick.tick`` already ran (what an observer's ``on_tick`` sees),
        as ``BtcppTree.replay`` ticks it."""
        changes = self.live.replay(result)
        self._record(changes.changes)
        return changes

    def record(self, changes: tuple[Change, ...]) -> None:
        """Log status changes derived elsewhere (an observer's tree channel), at the clock's time."""
        self._record(changes)

    def halt(self, on_halt: HaltHook | None = None) -> tuple[Change, ...]:
        """Halt the tree (a run stopped while RUNNING), logging the resets to IDLE."""
        changes = self.live.halt(on_halt)
        self._record(changes)
        return changes

    def _record(self, changes: tuple[Change, ...]) -> None:
        elapsed = self.clock() - self.start_us
        if not 0 <= elapsed < MAX_TIME_US:
            raise ValueError(f"the clock gave {elapsed} µs since the log began; a .btlog needs 0 to {MAX_TIME_US - 1}")
        stamp = elapsed.to_bytes(6, "little")
        for change in changes:
            self.records += stamp + change.uid.to_bytes(2, "little") + bytes([change.status])

    def close(self) -> None:
        atomic_write_bytes(self.path, _header(self.xml, self.start_us) + bytes(self.records))

    def __enter__(self) -> BtlogWriter:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.close()


# --- reading ------------------------------------------------------------------------------------

class Transition(NamedTuple):
    """One record: µs after the first timestamp, the node's uid, its new status."""

    time_us: int
    uid: int
    status: BtStatus


@dataclass(frozen=True, slots=True)
class Btlog:
    """A ``.btlog`` file: the tree's XML, the first timestamp, node names by uid, the records."""

    xml: str
    start_us: int
    names: dict[int, str]
    transitions: tuple[Transition, ...]

    def changes(self) -> list[Change]:
        """The records without their timestamps."""
        return [Change(t.uid, t.status) for t in self.transitions]


def read_btlog(path: str | Path) -> Btlog:
    """Read a ``FileLogger2`` file (ours or BehaviorTree.CPP's); a damaged one is a FormatError."""
    return parse_btlog(read_bytes(path, ".btlog file", MAX_LOG_BYTES), path)


def parse_btlog(data: bytes, path: str | Path = "<bytes>") -> Btlog:
    """The contents of a ``.btlog`` file; ``path`` only names it in errors."""
    if not data.startswith(MAGIC):
        raise FormatError(f"not a BehaviorTree.CPP log: it does not start with {MAGIC.decode()}", path)
    at = len(MAGIC)
    if len(data) < at + 5:
        raise FormatError("the log ends inside its header", path)
    if data[at] != PROTOCOL:
        raise FormatError(f"log protocol {data[at]} is not supported (only {PROTOCOL})", path)
    (size,) = struct.unpack_from("<i", data, at + 1)
    at += 5
    if not 0 < size <= MAX_BYTES:
        raise FormatError(f"the header gives the tree XML {size} bytes (1 to {MAX_BYTES} expected)", path)
    if len(data) < at + size + 8:
        raise FormatError(f"the log ends inside its header: {size} bytes of XML and a timestamp expected, "
                          f"{len(data) - at} bytes follow", path)
    xml, names = _read_xml(data[at:at + size], path)
    (start_us,) = struct.unpack_from("<q", data, at + size)
    at += size + 8
    body = len(data) - at
    if body % RECORD:
        raise FormatError(f"the log ends inside a record: {body % RECORD} bytes after the last whole one "
                          f"(byte {len(data) - body % RECORD})", path)
    records = list(struct.iter_unpack("<IHHB", data[at:]))
    statuses = list(BtStatus)
    bad = next((i for i, (_, _, uid, status) in enumerate(records) if status >= len(statuses) or uid not in names),
               None)
    if bad is not None:
        _, _, uid, status = records[bad]
        where = f"record {bad + 1} (byte {at + bad * RECORD})"
        if status >= len(statuses):
            raise FormatError(f"{where}: status {status} is not a BehaviorTree.CPP status", path)
        raise FormatError(f"{where}: node uid {uid} is not in the log's tree", path)
    make = Transition._make
    transitions = tuple(make((low | high << 32, uid, statuses[status])) for low, high, uid, status in records)
    return Btlog(xml, start_us, names, transitions)


def _read_xml(raw: bytes, path: str | Path) -> tuple[str, dict[int, str]]:
    """The header's XML and its nodes' names by ``_uid``, parsed as cautiously as tree files."""
    try:
        xml = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise FormatError("the tree XML in the header is not UTF-8", path) from None
    if "<!DOCTYPE" in xml or "<!ENTITY" in xml:
        raise FormatError("the tree XML in the header has a DOCTYPE or ENTITY declaration", path)
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False,
                             remove_comments=True, remove_pis=True)
    try:
        document = etree.fromstring(raw, parser)
    except etree.XMLSyntaxError as exc:
        message = str(exc.msg).splitlines()[0] if exc.msg else "syntax error"  # lxml's may run over lines
        raise FormatError(f"the tree XML in the header is not well-formed (line {exc.lineno}: {message})",
                          path) from None
    names: dict[int, str] = {}
    for tree in document.iter("BehaviorTree"):
        for element in tree.iter():
            raw_uid = element.get("_uid") if isinstance(element.tag, str) else None
            if raw_uid is None:
                continue
            if not raw_uid.isdigit() or not 0 < int(raw_uid) <= MAX_UID:
                raise FormatError(f"the tree XML gives <{element.tag}> the uid {raw_uid!r}, not 1 to {MAX_UID}", path)
            if int(raw_uid) in names:
                raise FormatError(f"the tree XML gives the uid {raw_uid} to two nodes", path)
            names[int(raw_uid)] = element.get("name") or str(element.tag)
    return xml, names
