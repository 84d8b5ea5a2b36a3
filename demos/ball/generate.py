"""Regenerate the thesis's demonstration sets Δ1–Δ5 (§6.3) and the two reference trees.

Example:
    .venv/bin/python demos/ball/generate.py

The thesis describes the sets but does not publish them, so they are rebuilt here from
the behaviour each set was made with, run in the symbolic world of Table 6.1 (an action
makes its ramifications true and changes nothing else; PlaceBall leaves BallGrasped
true). Every choice the text leaves open is a named constant below and is explained in
demos/ball/README.md. The output is deterministic: running this twice gives the same
bytes.
"""

from __future__ import annotations

import itertools
import shutil
import sys
from collections.abc import Mapping
from pathlib import Path

from teach.bt.nodes import Action, Condition, Fallback, Node, Sequence, Status
from teach.bt.tick import compile_tree
from teach.demos import Demonstration, Step, format_demonstration
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State, load_domain
from teach.fsutil import atomic_write_text

HERE = Path(__file__).resolve().parent
MAX_STEPS = 20  # a reference behaviour that needs more steps than this is looping

# An external event: after this many robot actions, these conditions take these values.
Event = tuple[int, Mapping[str, bool]]

# The nine demonstrations Δ5 adds to Δ2 (§6.3): start state (the true conditions) and events.
# Five show the named disturbances, four an external action before the first robot action;
# one of those (someone hands the robot the ball) ends with the ball placed but not found,
# which the Table 6.1 behaviour accepts and Colledanchise & Ögren's tree does not.
EXTERNAL_DEMOS: tuple[tuple[str, tuple[str, ...], tuple[Event, ...]], ...] = (
    ("drops the ball before going to the bin", (), ((3, {"BallGrasped": False}),)),
    ("drops the ball after going to the bin", (), ((4, {"BallGrasped": False}),)),
    ("the ball is removed from its sight", (), ((1, {"BallFound": False}),)),
    ("the bin is moved after approaching it", (), ((4, {"BinClose": False}),)),
    ("loses the ball's location", (), ((2, {"BallFound": False, "BallClose": False}),)),
    ("the ball rolls into sight first", (), ((0, {"BallFound": True}),)),
    ("the bin is brought close first", (), ((0, {"BinClose": True}),)),
    ("is handed the ball first", (), ((0, {"BallGrasped": True}),)),
    ("drops the ball at the bin first", ("BallFound", "BallClose", "BallGrasped", "BinClose"),
     ((0, {"BallGrasped": False}),)),
)

# Δ2's two special cases (§6.3): BinClose holds but the ball is not close, and walking to
# the ball takes the robot out of the bin's reach.
AWAY_FROM_BIN_STARTS: tuple[tuple[str, ...], ...] = (("BinClose",), ("BallFound", "BinClose"))

# Δ3 and Δ4 are subsets of Δ2 (§6.3) whose goal states are all the same as Δ1's (§6.3,
# Table 6.2 discussion), i.e. demonstrations Colledanchise & Ögren's tree also reproduces.
# Δ3: the 8 starts with neither the ball grasped nor placed (and no special case).
# Δ4: the demonstration from the start with nothing true and the first special case (only
# BinClose true, and walking to the ball leaves the bin): every action, and BinClose both
# kept and lost. Of the pairs Colledanchise & Ögren's tree reproduces, this is one of the two
# whose Approach 2 tree has the thesis's 57 -> 36 nodes (README.md).
DELTA4 = ("d01", "d33")


def colledanchise_tree() -> Node:
    """Fig. 2.5 without AskForHelp: each condition in turn, achieved by its action if false."""
    def pair(condition: str, action: str) -> Node:
        return Fallback((Condition(condition), Action(action)))

    return Sequence((pair("BallFound", "FindBall"), pair("BallClose", "ApproachBall"),
                     pair("BallGrasped", "GraspBall"), pair("BinClose", "ApproachBin"),
                     pair("BallPlaced", "PlaceBall")))


def table61_tree() -> Node:
    """The Table 6.1 behaviour (goal BallPlaced), as §6.3 describes Fig. 6.16: done if the ball
    is placed; otherwise get the ball unless it is already grasped, go to the bin, place it."""
    get_ball = Sequence((Fallback((Condition("BallFound"), Action("FindBall"))),
                         Fallback((Condition("BallClose"), Action("ApproachBall"))),
                         Action("GraspBall")))
    return Fallback((Condition("BallPlaced"),
                     Sequence((Fallback((Condition("BallGrasped"), get_ball)),
                               Fallback((Condition("BinClose"), Action("ApproachBin"))),
                               Action("PlaceBall")))))


def all_states(domain: Domain) -> list[State]:
    """Every state, in counting order with the first condition as the most significant bit."""
    return [tuple(bits) for bits in itertools.product((False, True), repeat=len(domain.conditions))]


def demonstrate(domain: Domain, tree: Node, start: State, name: str,
                events: tuple[Event, ...] = (), away_from_bin: bool = False) -> Demonstration:
    """Run a reference behaviour from ``start`` until it succeeds, recording every line.

    Events are external actions (-1 lines); ``away_from_bin`` makes ApproachBall also make
    BinClose false (Δ2's special case)."""
    compiled = compile_tree(tree, domain.condition_names)
    pending = dict(events)
    state, done, steps = start, 0, []
    while len(steps) <= MAX_STEPS:
        if done in pending:
            steps.append(Step(state, EXTERNAL_ACTION))
            state = _set(domain, state, pending.pop(done))
            continue
        status, action = compiled(state)
        if status is Status.SUCCESS:
            steps.append(Step(state, GOAL_ACTION))
            return Demonstration(name, tuple(steps))
        if status is not Status.RUNNING or action is None:
            raise SystemExit(f"{name}: the reference behaviour fails in {domain.describe(state)}")
        definition = domain.action(action)
        steps.append(Step(state, definition.id))
        changes = {literal.name: literal.value for literal in definition.ram}
        if away_from_bin and action == "ApproachBall":
            changes["BinClose"] = False
        state, done = _set(domain, state, changes), done + 1
    raise SystemExit(f"{name}: the reference behaviour did not reach its goal in {MAX_STEPS} steps")


def _set(domain: Domain, state: State, changes: Mapping[str, bool]) -> State:
    values = list(state)
    for condition, value in changes.items():
        values[domain.index(condition)] = value
    return tuple(values)


def build_sets(domain: Domain) -> dict[str, list[Demonstration]]:
    """Δ1–Δ5 by folder name; demonstrations keep their Δ2 name in the subsets."""
    colledanchise, table61 = colledanchise_tree(), table61_tree()
    states = all_states(domain)
    delta1 = [demonstrate(domain, colledanchise, s, f"d{i:02d}") for i, s in enumerate(states, 1)]
    delta2 = [demonstrate(domain, table61, s, f"d{i:02d}") for i, s in enumerate(states, 1)]
    delta2 += [demonstrate(domain, table61, domain.state(true), f"d{len(states) + i:02d}", away_from_bin=True)
               for i, true in enumerate(AWAY_FROM_BIN_STARTS, 1)]
    grasped, placed = domain.index("BallGrasped"), domain.index("BallPlaced")
    delta3 = [d for d in delta2[:len(states)] if not d.steps[0].state[grasped] and not d.steps[0].state[placed]]
    delta4 = [d for d in delta2 if d.name in DELTA4]
    extra = [demonstrate(domain, table61, domain.state(true), f"d{len(delta2) + i:02d}", events)
             for i, (_, true, events) in enumerate(EXTERNAL_DEMOS, 1)]
    return {"delta1": delta1, "delta2": delta2, "delta3": delta3, "delta4": delta4, "delta5": delta2 + extra}


def main() -> int:
    from teach.bt.xml import write_tree

    domain = load_domain(HERE / "domain.toml")
    for folder, demos in build_sets(domain).items():
        target = HERE / folder
        if target.exists():
            shutil.rmtree(target)
        for demo in demos:
            atomic_write_text(target / f"{demo.name}.csv", format_demonstration(demo))
        print(f"{folder}: {len(demos)} demonstrations")
    write_tree(HERE / "reference" / "colledanchise.xml", colledanchise_tree())
    write_tree(HERE / "reference" / "table61.xml", table61_tree())
    return 0


if __name__ == "__main__":
    sys.exit(main())
