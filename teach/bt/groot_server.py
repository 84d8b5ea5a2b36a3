"""Groot2's monitoring protocol, served for our trees, with a tree id of its own for each tree.

BehaviorTree.CPP's ``Groot2Publisher`` stamps every reply with a 16-byte tree id, and that id
is how Groot2 notices that the tree behind a port changed. In BehaviorTree.CPP 4.8.2, the
version ``behaviortreepy`` bundles, ``CreateRandomUUID`` draws it from a default-constructed
``std::mt19937`` (seed 5489), so every publisher in every process answers the same id
(``5cbb91d0f69e4e22aefae1e7791fc3d5``; 4.8.3 seeds it from ``std::random_device``), and the
binding exposes nothing to change it. So this server answers the protocol itself
(``groot2_protocol.h``, protocol 2): a ZeroMQ REP socket on ``port`` and a PUB socket on
``port`` + 1, as the publisher binds them; a fresh random id whenever ``show`` gets a tree.

Replies, as ``Groot2Publisher::serverLoop`` gives them: the 6-byte request header echoed
(protocol, type, request id) with the tree id after it, then FULLTREE the tree's XML as
BehaviorTree.CPP writes it (``btcpp_xml``, node uids included), STATUS three bytes per node
(uid, status; 10 + the previous status for a node reset to IDLE), BLACKBOARD an empty
MessagePack map (our trees have no blackboard entries), TOGGLE_RECORDING and GET_TRANSITIONS
the recorded status changes (9 bytes each: 6 of µs, uid, status). Breakpoints are refused
with the publisher's error reply; hook dumps are empty. The statuses are ``BtcppTree``'s: the
changes BehaviorTree.CPP's loggers receive for the same leaf answers (the ``.btlog`` files'
source, checked byte for byte against BehaviorTree.CPP's own file logger).
"""

from __future__ import annotations

import struct
import threading
import time
import uuid
from dataclasses import dataclass

from teach.bt.btcpp_status import BtcppTree, BtStatus, Change
from teach.bt.btlog import btcpp_xml
from teach.bt.nodes import Node, walk
from teach.bt.tick import TickResult
from teach.bt.zeromq import PUB, REP, Context

PROTOCOL = 2
HEADER = struct.Struct("<BBI")
"""A request header: protocol, request type (a letter), request id."""
FULLTREE, STATUS, BLACKBOARD = b"T", b"S", b"B"
HOOKS_DUMP, REMOVE_ALL_HOOKS, DISABLE_ALL_HOOKS = b"D", b"A", b"X"
TOGGLE_RECORDING, GET_TRANSITIONS = b"r", b"t"
HOOK_INSERT, HOOK_REMOVE, BREAKPOINT_UNLOCK = b"I", b"R", b"U"
MAX_TRANSITIONS = 1000
"""The publisher keeps the last thousand recorded changes."""
EMPTY_MAP = b"\x80"
"""An empty MessagePack map: the blackboards of a tree that has none."""


class Groot2Server:
    """Serve ``root`` to Groot2 on ``port`` until ``close``; ``show`` swaps the tree."""

    def __init__(self, port: int, root: Node):
        self._context = Context()
        self._server, self._publisher = self._context.socket(REP), self._context.socket(PUB)
        try:
            self._server.bind(f"tcp://*:{port}")
            self._publisher.bind(f"tcp://*:{port + 1}")  # where the publisher notifies breakpoints
        except OSError:
            self._close_sockets()
            raise
        self._lock = threading.Lock()
        self._recording: float | None = None
        self._transitions: list[bytes] = []
        self.show(root)
        self._active = True
        self._thread = threading.Thread(target=self._serve, name=f"groot2-{port}", daemon=True)
        self._thread.start()

    def show(self, root: Node) -> None:
        """Serve ``root`` from now on, under a new tree id, every node IDLE."""
        xml = btcpp_xml(root).encode()
        with self._lock:
            self.tree_id = uuid.uuid4().bytes
            self._xml = xml
            self._live = BtcppTree(root)
            nodes = sum(1 for _ in walk(root))
            self._codes = bytearray(b"".join(struct.pack("<HB", uid, BtStatus.IDLE) for uid in range(1, nodes + 1)))

    def tick(self, result: TickResult) -> None:
        """The shown tree was ticked as ``result`` says: its nodes' statuses move as BehaviorTree.CPP's."""
        self._apply(self._live.replay(result).changes)

    def halt(self) -> None:
        """The run ended or begins: every node back to IDLE."""
        self._apply(self._live.halt())

    def _apply(self, changes: tuple[Change, ...]) -> None:
        """Each node's status byte: its status, or for one reset to IDLE 10 + the status it had."""
        with self._lock:
            for uid, status in changes:
                at = 3 * (uid - 1) + 2
                before = self._codes[at] if self._codes[at] < 10 else BtStatus.IDLE
                self._codes[at] = 10 + before if status is BtStatus.IDLE else int(status)
                if self._recording is not None:
                    elapsed = int((time.monotonic() - self._recording) * 1e6)
                    self._transitions.append(elapsed.to_bytes(6, "little") + struct.pack("<HB", uid, status))
            del self._transitions[:-MAX_TRANSITIONS]

    def _serve(self) -> None:
        while self._active:
            request = self._server.receive()
            if request is not None:
                self._server.send(self._reply(request))

    def _reply(self, request: list[bytes]) -> list[bytes]:
        if len(request[0]) != HEADER.size:
            return [b"error", b"wrong request header"]
        _protocol, kind, request_id = HEADER.unpack(request[0])
        with self._lock:
            header = HEADER.pack(PROTOCOL, kind, request_id) + self.tree_id
            answer = self._answer(bytes([kind]), request[1:])
        return [b"error", answer.message] if isinstance(answer, _Error) else [header, *answer]

    def _answer(self, kind: bytes, parts: list[bytes]) -> list[bytes] | _Error:
        if kind == FULLTREE:
            return [self._xml]
        if kind == STATUS:
            return [bytes(self._codes)]
        if kind == BLACKBOARD:
            return [EMPTY_MAP] if len(parts) == 1 else _Error(b"must be 2 parts message")
        if kind == HOOKS_DUMP:
            return [b"[]"]
        if kind in (REMOVE_ALL_HOOKS, DISABLE_ALL_HOOKS):
            return []
        if kind == TOGGLE_RECORDING:
            return self._toggle(parts)
        if kind == GET_TRANSITIONS:
            transitions, self._transitions = b"".join(self._transitions), []
            return [transitions]
        if kind in (HOOK_INSERT, HOOK_REMOVE, BREAKPOINT_UNLOCK):
            return _Error(b"no breakpoints in teach's trees")
        return _Error(b"Request not recognized")

    def _toggle(self, parts: list[bytes]) -> list[bytes] | _Error:
        if len(parts) != 1:
            return _Error(b"must be 2 parts message")
        if parts[0] == b"start":
            self._recording, self._transitions = time.monotonic(), []
            return [str(time.time_ns() // 1000).encode()]
        if parts[0] == b"stop":
            self._recording = None
        return []

    def close(self) -> None:
        """Stop answering and unbind both ports."""
        if self._active:
            self._active = False
            self._thread.join()
            self._close_sockets()

    def _close_sockets(self) -> None:
        self._server.close()
        self._publisher.close()
        self._context.close()


@dataclass(frozen=True)
class _Error:
    """A request the publisher refuses: it answers ``error`` and the message, without a header."""

    message: bytes
