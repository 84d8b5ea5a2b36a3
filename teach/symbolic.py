"""The one symbolic executor: actions make their ramifications true, a tree runs until it
reaches its goal, fails or comes back to a state it was in (a loop)."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from enum import Enum, auto

from teach.bt.nodes import Node, Status
from teach.bt.tick import compile_tree
from teach.domain import Domain, Literal, State


def assign(state: State, values: Iterable[tuple[int, bool]]) -> State:
    """``state`` with the conditions at the given indexes set to the given values."""
    after = list(state)
    for index, value in values:
        after[index] = value
    return tuple(after)


def apply_action(domain: Domain, state: State, action: str) -> State:
    """The state after ``action`` by ``domain``'s action model (preconditions not checked)."""
    return assign(state, ((domain.index(lit.name), lit.value) for lit in domain.action(action).ram))


def missing_preconditions(domain: Domain, state: State, action: str) -> list[Literal]:
    return [lit for lit in domain.action(action).pre if not domain.holds(lit, state)]


def possible_actions(domain: Domain, state: State) -> list[str]:
    """The actions whose preconditions hold in ``state`` by ``domain``'s action model."""
    return [a.name for a in domain.actions if not missing_preconditions(domain, state, a.name)]


def steps_towards(domain: Domain, state: State, action: str, max_steps: int,
                  also: tuple[Literal, ...] = ()) -> list[str] | None:
    """The shortest list of at most ``max_steps`` actions after which ``action`` can be done (and
    ``also`` holds: what the teacher's phrase for it needs), by ``domain``'s action model
    (breadth-first; the first found in the domain's order): the way to offer a teacher whose step
    was refused. None if there is none that short (or it would need the world's events)."""
    frontier: list[tuple[State, list[str]]] = [(state, [])]
    seen = {state}
    for _ in range(max_steps):
        following = []
        for here, path in frontier:
            for name in possible_actions(domain, here):
                after = apply_action(domain, here, name)
                if after in seen:
                    continue
                if not missing_preconditions(domain, after, action) and all(domain.holds(p, after) for p in also):
                    return [*path, name]
                seen.add(after)
                following.append((after, [*path, name]))
        frontier = following
    return None


class RunEnd(Enum):
    SUCCESS = auto()
    FAILURE = auto()
    LOOP = auto()
    """The last action led back to an earlier state."""
    LIMIT = auto()
    """``max_steps`` actions ran without an end."""


@dataclass
class GoalRun:
    end: RunEnd
    state: State
    """The last state ticked (for a loop: the state the repeating action led back to)."""
    actions: list[str] = field(default_factory=list)


def run_to_goal(domain: Domain, tree: Node, start: State, max_steps: int) -> GoalRun:
    """Tick ``tree`` in the symbolic world of ``domain``'s action model from ``start``."""
    compiled = compile_tree(tree, domain.condition_names)
    state, seen = start, {start}
    run = GoalRun(RunEnd.LIMIT, start)
    for _ in range(max_steps):
        status, action = compiled(state)
        if status is Status.SUCCESS:
            run.end = RunEnd.SUCCESS
            return run
        if status is Status.FAILURE or action is None:
            run.end = RunEnd.FAILURE
            return run
        run.actions.append(action)
        state = run.state = apply_action(domain, state, action)
        if state in seen:
            run.end = RunEnd.LOOP
            return run
        seen.add(state)
    return run


MAX_RUN_STEPS = 50
"""A tree that needs more ticks than this to reach its goal is looping."""


def goal_verdict(domain: Domain, tree: Node, start: State, max_steps: int = MAX_RUN_STEPS) -> tuple[bool, str]:
    """Whether ``tree`` reaches the goal of ``domain``'s action model from ``start``, and why not
    in words (it fails, loops, or runs out of steps)."""
    result = run_to_goal(domain, tree, start, max_steps)
    if result.end is RunEnd.SUCCESS:
        trace = f" ({' → '.join(result.actions)})" if result.actions else ""
        return True, "usable: reaches the goal from the empty state" + trace
    if result.end is RunEnd.FAILURE:
        return False, f"the tree fails in {_true(domain, result.state)}"
    if result.end is RunEnd.LOOP:
        return False, f"{result.actions[-1]} changes nothing in {_true(domain, result.state)}: the tree loops"
    return False, f"no goal after {max_steps} actions"


def _true(domain: Domain, state: State) -> str:
    names = [n for n, v in zip(domain.condition_names, state, strict=True) if v]
    return "{" + ", ".join(names) + "}"
