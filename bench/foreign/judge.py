"""Task success in the true model: run a learned tree from each start and say how it ended.

From a start, the tree is ticked (compiled, as ``teach.bt.tick`` runs it; ``tests/test_bench_safety.py``
checks BehaviorTree.CPP picks the same), and the action it leaves running is applied in the
true model, until one of:

- ``reached``: the tree returns SUCCESS and the true goal holds;
- ``false done``: SUCCESS where the true goal does not hold;
- ``stuck``: FAILURE;
- ``unsafe``: the action's true preconditions do not hold in that state (the run stops there:
  a real robot would have done something it must not);
- ``loop``: a state repeats, or the run takes more than ``step_cap`` steps.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

from foreign.model import Task
from teach.bt.nodes import Node, Status
from teach.bt.tick import CompiledTree, compile_tree

OUTCOMES = ("reached", "false done", "stuck", "unsafe", "loop")


@dataclass(frozen=True)
class Run:
    """How one run ended, in which state (the last one), and after how many actions."""

    outcome: str
    state: int
    steps: int


def run(task: Task, tree: CompiledTree, start: int, step_cap: int | None = None) -> Run:
    cap = step_cap if step_cap is not None else 4 * max(task.reachable.values()) + 8
    state, seen = start, {start}
    for steps in range(cap + 1):
        status, action = tree(task.state(state))
        if status is Status.SUCCESS:
            return Run("reached" if task.model.goal_holds(state) else "false done", state, steps)
        if status is not Status.RUNNING or action is None:
            return Run("stuck", state, steps)
        operator = task.model.by_name[action]
        if not operator.applicable(state):
            return Run("unsafe", state, steps)
        state = operator.apply(state)
        if state in seen:
            return Run("loop", state, steps + 1)
        seen.add(state)
    return Run("loop", state, cap)


@dataclass(frozen=True)
class Outcomes:
    """The share of starts per outcome."""

    counts: Counter[str]
    total: int

    def share(self, outcome: str) -> float:
        return self.counts[outcome] / self.total if self.total else 0.0


def judge(task: Task, tree: Node | CompiledTree | None, starts: list[int]) -> Outcomes:
    """Run ``tree`` from every start; no tree (a learner refused) is stuck everywhere."""
    if tree is None:
        return Outcomes(Counter({"stuck": len(starts)}), len(starts))
    compiled = tree if isinstance(tree, CompiledTree) else compile_tree(tree, task.domain.condition_names)
    return Outcomes(Counter(run(task, compiled, s).outcome for s in starts), len(starts))
