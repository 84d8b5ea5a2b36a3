"""Trees ticked by BehaviorTree.CPP itself, served to Groot2, so Groot2 can watch a run live.

``GrootTicker`` has the signature of ``teach.bt.tick.tick`` (tree, conditions, action), so a
world ticks through it instead: our XML of the tree is loaded by a ``BehaviorTreeFactory``
whose conditions read the tick's conditions and whose actions call the world's ``action``
(``StatefulActionNode``: start and continue both ask the world, as our executor's skills know
whether an action is fresh). BehaviorTree.CPP's status is the tick's status; the trace the
observers see is our tick of the same tree with every leaf answering as it answered
BehaviorTree.CPP, so no skill is ticked twice. It is a ticker, not an observer: whoever knows
where runs begin and end calls ``halt`` there (the session's composition root does), so no run
inherits another's running nodes.

Groot2 is served by our ``Groot2Server`` on ``port`` (and ``port`` + 1), not by
BehaviorTree.CPP's ``Groot2Publisher``: the bundled publisher answers one tree id for every tree
in every process, so Groot2 could keep showing an old tree after a swap; the server gives each
tree a new id and stays bound across swaps (see ``teach.bt.groot_server``).

This is the only module that imports ``behaviortreepy`` at run time (``teach.bt.zeromq`` loads
the libzmq it ships).
"""

from __future__ import annotations

import socket
from collections.abc import Callable, Mapping
from typing import Any

from teach.bt.groot_server import Groot2Server
from teach.bt.nodes import Action, Condition, Node, Status, walk
from teach.bt.tick import TickResult, always_running, tick
from teach.bt.xml import tree_to_xml
from teach.errors import TeachError

DEFAULT_PORT = 1667
"""Groot2's default port for a tree's publisher."""


class GrootTicker:
    """Tick through BehaviorTree.CPP, serving Groot2 on ``port`` (and ``port`` + 1)."""

    def __init__(self, port: int = DEFAULT_PORT):
        try:
            import behaviortreepy
        except ImportError:
            raise TeachError("--groot needs behaviortreepy (pip install behaviortreepy)") from None
        if not behaviortreepy.GROOT2_AVAILABLE:
            raise TeachError("--groot: this behaviortreepy was built without Groot2 support")
        if not 1 <= port <= 65534:
            raise TeachError(f"--groot port {port} is not a port number (1 to 65534; Groot2 also uses the next)")
        _check_free(port)
        self.bt: Any = behaviortreepy
        self.port = port
        self._tree: Node | None = None
        self._live: Any = None
        self._server: Groot2Server | None = None
        self._conditions: Callable[[str], bool] = lambda _name: False
        self._action: Callable[[str], Status] = always_running
        self._answers: dict[str, Status] = {}

    def __call__(self, root: Node, condition: Callable[[str], bool] | Mapping[str, bool],
                 action: Callable[[str], Status] = always_running) -> TickResult:
        self._conditions = condition.__getitem__ if isinstance(condition, Mapping) else condition
        self._action = action
        self._answers = {}
        live = self._load(root)
        status = _STATUS[live.tick_exactly_once().name]
        answers = dict(self._answers)
        ours = tick(root, self._conditions, lambda name: answers.get(name, Status.RUNNING))
        if self._server is not None:
            self._server.tick(ours)
        return TickResult(status, ours.action if status is Status.RUNNING else None, ours.trace)

    def _load(self, root: Node) -> Any:
        if self._tree is root and self._live is not None:
            return self._live
        self._stop()
        bt = self.bt
        factory = bt.BehaviorTreeFactory()
        nodes = list(walk(root))
        for name in sorted({n.name for n in nodes if isinstance(n, Condition)}):
            factory.register_simple_condition(name, self._condition(name))
        for name in sorted({n.name for n in nodes if isinstance(n, Action)}):
            factory.register_simple_stateful_action(name, self._act(name), self._act(name), _halted)
        self._live = factory.create_tree_from_text(tree_to_xml(root))
        if self._server is not None:
            self._server.show(root)
        else:
            try:
                self._server = Groot2Server(self.port, root)
            except OSError as exc:
                self._live = None
                raise TeachError(f"--groot cannot publish on port {self.port}: {exc}") from None
        self._tree = root
        return self._live

    def _condition(self, name: str) -> Callable[[Any], Any]:
        def check(_node: Any) -> Any:
            return self.bt.NodeStatus.SUCCESS if self._conditions(name) else self.bt.NodeStatus.FAILURE
        return check

    def _act(self, name: str) -> Callable[[Any], Any]:
        def act(_node: Any) -> Any:
            status = self._action(name)
            self._answers[name] = status
            return getattr(self.bt.NodeStatus, status.name)
        return act

    def halt(self) -> None:
        """``Tree::haltTree``: everything back to IDLE (a run begins or ended)."""
        if self._live is not None:
            self._live.halt_tree()
        if self._server is not None:
            self._server.halt()

    def _stop(self) -> None:
        self._live = None
        self._tree = None

    def close(self) -> None:
        """Stop serving Groot2: both ports are free again."""
        self._stop()
        if self._server is not None:
            self._server.close()
            self._server = None


def _check_free(port: int) -> None:
    """Refuse a port in use now, before the session starts, rather than at its first run.
    (Groot2 asks on ``port``; ``port`` + 1 is the publisher's, as BehaviorTree.CPP binds them.)"""
    for number in (port, port + 1):
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
            try:
                probe.bind(("", number))
            except OSError as exc:
                raise TeachError(f"--groot cannot publish on port {port}: port {number} is taken ({exc.strerror})"
                                 ) from None


def _halted(_node: Any) -> None:
    """A halted action: the world's executor stops a skill when another action is ticked."""


_STATUS = {"SUCCESS": Status.SUCCESS, "FAILURE": Status.FAILURE, "RUNNING": Status.RUNNING}
