"""Ticking trees: a traced tick for display and logging, a compiled tick for replay and learning.

Semantics are the classical memoryless ones of Table 2.2: every tick starts at the root,
conditions never return RUNNING. ``TickResult.action`` is the first action that returned
RUNNING during a tick whose root returned RUNNING (an action started under a Parallel that
then finished is halted at once, so it counts as not run).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from collections.abc import Sequence as Seq
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, Status, walk


def always_running(_action: str) -> Status:
    """The symbolic world's actions (thesis §5): they run, and their effects show in the next state."""
    return Status.RUNNING


@dataclass(frozen=True, slots=True)
class TickResult:
    status: Status
    action: str | None
    trace: tuple[tuple[int, Status], ...] = ()

    def statuses(self) -> dict[int, Status]:
        """uid → status of every node the tick visited."""
        return dict(self.trace)


def tick(root: Node, condition: Callable[[str], bool] | Mapping[str, bool],
         action: Callable[[str], Status] = always_running) -> TickResult:
    """Tick once and record every visited node's status (post-order)."""
    holds = condition.__getitem__ if isinstance(condition, Mapping) else condition
    trace: list[tuple[int, Status]] = []
    first_action: list[str] = []

    def run(node: Node) -> Status:
        if isinstance(node, Condition):
            status = Status.SUCCESS if holds(node.name) else Status.FAILURE
        elif isinstance(node, Action):
            status = action(node.name)
            if status is Status.RUNNING:
                first_action.append(node.name)
        elif isinstance(node, Sequence):
            status = Status.SUCCESS
            for kid in node.children:
                status = run(kid)
                if status is not Status.SUCCESS:
                    break
        elif isinstance(node, Fallback):
            status = Status.FAILURE
            for kid in node.children:
                status = run(kid)
                if status is not Status.FAILURE:
                    break
        elif isinstance(node, Inverter):
            inner = run(node.child)
            status = {Status.SUCCESS: Status.FAILURE, Status.FAILURE: Status.SUCCESS}.get(inner, inner)
        elif isinstance(node, Parallel):
            started = len(first_action)
            results = [run(kid) for kid in node.children]
            status = _parallel_status(results, node.success_threshold)
            if status is not Status.RUNNING:
                del first_action[started:]  # the Parallel finished: its running children are halted
        else:  # pragma: no cover - exhaustive over Node
            raise TypeError(f"not a node: {node!r}")
        trace.append((node.uid, status))
        return status

    status = run(root)
    ran = first_action[0] if first_action and status is Status.RUNNING else None
    return TickResult(status, ran, tuple(trace))


def _parallel_status(results: Seq[Status], threshold: int) -> Status:
    successes = sum(r is Status.SUCCESS for r in results)
    failures = sum(r is Status.FAILURE for r in results)
    if successes >= threshold:
        return Status.SUCCESS
    if failures > len(results) - threshold:
        return Status.FAILURE
    return Status.RUNNING


def tick_state(root: Node, names: Seq[str], state: Seq[bool]) -> TickResult:
    """Traced tick over a symbolic state given as truth values in ``names`` order."""
    return tick(root, dict(zip(names, state, strict=True)))


# --- compiled tick -----------------------------------------------------------------------------

_MAX_NESTING = 12  # Python allows 20 statically nested blocks; deeper subtrees become functions


@runtime_checkable
class CompiledTree(Protocol):
    """A tree compiled once into straight-line Python over state tuples, with a memo table.

    Calling it with a state returns ``(status, action)`` for the symbolic world (actions
    return RUNNING). The learners and the replay call it millions of times, so a compiled
    tree is a plain function (no method dispatch per call): the generated code itself, or
    a memo table in front of it for large trees; ``raw`` is the generated function without
    any memo, ``source`` its code.
    """

    source: str
    names: tuple[str, ...]
    raw: Callable[[tuple[bool, ...]], tuple[Status, str | None]]

    def __call__(self, state: tuple[bool, ...]) -> tuple[Status, str | None]: ...


_MEMO_LIMIT = 1 << 20
_MEMO_MIN_SIZE = 256


def compile_tree(root: Node, names: Seq[str], memoise: bool | None = None) -> CompiledTree:
    """Compile ``root`` over states in ``names`` order.

    ``memoise`` None decides by the tree: hashing a state for the memo table costs more than
    running the straight-line code of a tree without Parallel nodes and with up to 256 nodes
    (measured in bench/bench_tick.py and bench/bench_replay.py), so only larger trees and
    trees with Parallel nodes get a memo table.
    """
    source, namespace = _generate(root, {n: i for i, n in enumerate(names)})
    raw: Callable[[tuple[bool, ...]], tuple[Status, str | None]] = namespace["tick"]
    if memoise is None:
        nodes = list(walk(root))
        memoise = len(nodes) > _MEMO_MIN_SIZE or any(isinstance(n, Parallel) for n in nodes)
    compiled: Any = _memoised(raw) if memoise else raw
    compiled.source = source
    compiled.names = tuple(names)
    compiled.raw = raw
    return compiled


def _memoised(raw: Callable[[tuple[bool, ...]], tuple[Status, str | None]]) -> Callable[..., object]:
    memo: dict[tuple[bool, ...], tuple[Status, str | None]] = {}
    lookup = memo.get

    def compiled(state: tuple[bool, ...]) -> tuple[Status, str | None]:
        result = lookup(state)
        if result is None:
            if len(memo) >= _MEMO_LIMIT:
                memo.clear()
            result = memo[state] = raw(state)
        return result

    return compiled


def _generate(root: Node, index: Mapping[str, int]) -> tuple[str, dict]:
    """Python source for ``tick(s)``: each node leaves its result in ``r`` (True = SUCCESS,
    False = FAILURE) or returns ``(RUNNING, action)`` at once; ``while True: ... break`` blocks
    give Sequence/Fallback their early exit without function calls."""
    namespace: dict = {"RUNNING": Status.RUNNING, "SUCCESS": Status.SUCCESS, "FAILURE": Status.FAILURE}
    functions: list[str] = []
    counter = [0]

    def fresh(prefix: str) -> str:
        counter[0] += 1
        return f"{prefix}{counter[0]}"

    def constant(value: object, prefix: str) -> str:
        name = fresh(prefix)
        namespace[name] = value
        return name

    def emit(node: Node, pad: str, nesting: int, out: list[str]) -> None:
        if isinstance(node, Condition):
            if node.name not in index:
                raise KeyError(f"the tree tests condition {node.name!r}, which the domain does not have")
            out.append(f"{pad}r = s[{index[node.name]}]")
        elif isinstance(node, Action):
            out.append(f"{pad}return {constant((Status.RUNNING, node.name), '_run')}")
        elif isinstance(node, Inverter):
            emit(node.child, pad, nesting, out)
            out.append(f"{pad}r = not r")
        elif isinstance(node, (Sequence, Fallback)) and nesting >= _MAX_NESTING:
            name = subroutine(node)
            out.append(f"{pad}r = {name}(s)")
            out.append(f"{pad}if r.__class__ is tuple: return r")
        elif isinstance(node, (Sequence, Fallback)):
            stop = "if not r: break" if isinstance(node, Sequence) else "if r: break"
            out.append(f"{pad}r = {isinstance(node, Sequence)}")
            out.append(f"{pad}while True:")
            inner = pad + "    "
            for kid in node.children:
                emit(kid, inner, nesting + 1, out)
                if isinstance(kid, Action):  # it returned: later siblings are unreachable
                    break
                out.append(f"{inner}{stop}")
            else:
                out.append(f"{inner}break")
        elif isinstance(node, Parallel):
            # every child is ticked (each in its own function, so an action returns from it
            # alone); the first running one is reported only if the Parallel keeps running
            ok, no, running = fresh("_ok"), fresh("_no"), fresh("_going")
            out.append(f"{pad}{ok} = {no} = 0")
            out.append(f"{pad}{running} = None")
            for kid in node.children:
                out.append(f"{pad}x = {subroutine(kid)}(s)")
                out.append(f"{pad}if x.__class__ is tuple: {running} = {running} or x")
                out.append(f"{pad}elif x: {ok} += 1")
                out.append(f"{pad}else: {no} += 1")
            limit = len(node.children) - node.success_threshold
            out.append(f"{pad}if {ok} >= {node.success_threshold}: r = True")
            out.append(f"{pad}elif {no} > {limit}: r = False")
            out.append(f"{pad}else: return {running}")
        else:  # pragma: no cover
            raise TypeError(f"not a node: {node!r}")

    def subroutine(node: Node) -> str:
        name = fresh("_sub")
        body: list[str] = [f"def {name}(s):"]
        emit(node, "    ", 0, body)
        body.append("    return r")
        functions.append("\n".join(body))
        return name

    main: list[str] = ["def tick(s):"]
    emit(root, "    ", 0, main)
    main.append("    return (SUCCESS, None) if r else (FAILURE, None)")
    source = "\n\n".join(functions + ["\n".join(main)]) + "\n"
    exec(compile(source, "<compiled behaviour tree>", "exec"), namespace)  # noqa: S102 - our own generated code
    return source, namespace
