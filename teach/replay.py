"""The thesis's sanity check (§5): does a tree reproduce each demonstration?

Strict (default): for each line, A = -1 sets the next state without a tick; A = 0 needs the
tree to return SUCCESS; any other A needs RUNNING with exactly action A. Lenient (the reading
the thesis's tables appear to use): a tree returning SUCCESS before the goal line ends that
demonstration as reproduced.
"""

from __future__ import annotations

from dataclasses import dataclass

from teach.bt.nodes import Node, Status
from teach.bt.tick import CompiledTree, compile_tree
from teach.demos import Demonstration
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State


@dataclass(frozen=True)
class Divergence:
    """Where a replay left the demonstration."""

    step: int
    line: int
    state: State
    expected: str
    status: Status
    executed: str | None


@dataclass(frozen=True)
class DemoResult:
    name: str
    reproduced: bool
    divergence: Divergence | None = None


@dataclass(frozen=True)
class ReplayReport:
    results: tuple[DemoResult, ...]
    lenient: bool = False

    @property
    def reproduced(self) -> int:
        return sum(r.reproduced for r in self.results)

    @property
    def total(self) -> int:
        return len(self.results)

    def summary(self) -> str:
        return f"reproduced {self.reproduced}/{self.total}"


def replay_demo(tree: CompiledTree, domain: Domain, demo: Demonstration, lenient: bool = False) -> DemoResult:
    steps = demo.steps
    names = {a.id: a.name for a in domain.actions}
    for i, step in enumerate(steps):
        if step.action == EXTERNAL_ACTION:
            continue
        status, executed = tree(step.state)
        if step.action == GOAL_ACTION:
            ok = status is Status.SUCCESS
        else:
            if lenient and status is Status.SUCCESS:
                return DemoResult(demo.name, True)
            ok = status is Status.RUNNING and executed == names[step.action]
        if not ok:
            expected = "SUCCESS (goal)" if step.action == GOAL_ACTION else names[step.action]
            return DemoResult(demo.name, False, Divergence(i, step.line, step.state, expected, status, executed))
    return DemoResult(demo.name, True)


def replay(tree: Node | CompiledTree, domain: Domain, demos: list[Demonstration],
           lenient: bool = False) -> ReplayReport:
    compiled = tree if isinstance(tree, CompiledTree) else compile_tree(tree, domain.condition_names)
    return ReplayReport(tuple(replay_demo(compiled, domain, d, lenient) for d in demos), lenient)


def count_reproduced(tree: Node | CompiledTree, domain: Domain, demos: list[Demonstration],
                     lenient: bool = False) -> int:
    return replay(tree, domain, demos, lenient).reproduced
