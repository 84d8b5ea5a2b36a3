"""The ball task's 16 starts (every situation in which the ball is not in the bin yet), and how a
learned tree ends from each in real MuJoCo: reached (done with the ball in the bin), false done
(done without it), stuck (it stopped and asks to be shown), or what else the run ended with."""

from __future__ import annotations

import itertools
from collections import Counter

from teach.bt.nodes import Node
from teach.domain import Domain, State
from teach.sim.executor import run_tree
from teach.sim.world import World


def sixteen_starts(domain: Domain) -> list[State]:
    """Every situation in which the goal does not hold yet."""
    others = [n for n in domain.condition_names if n != "BallPlaced"]
    return [domain.state([n for n, v in zip(others, bits, strict=True) if v])
            for bits in itertools.product([False, True], repeat=len(others))]


def mujoco_outcomes(world: World, tree: Node, seed: int = 0, max_ticks: int = 600) -> Counter[str]:
    """How runs of ``tree`` end from each of the 16 starts (arranged with seeds ``seed``, ``seed + 1``, …)."""
    ends: Counter[str] = Counter()
    for number, start in enumerate(sixteen_starts(world.domain)):
        world.arrange(start, seed=seed + number)
        trace = run_tree(world, tree, max_ticks=max_ticks)
        placed = world.conditions()["BallPlaced"]
        if trace.outcome == "success":
            ends["reached" if placed else "false done"] += 1
        else:
            ends["stuck" if trace.outcome == "failure" else str(trace.outcome)] += 1
    return ends
