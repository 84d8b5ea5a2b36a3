"""Task success in a true world: run a tree from a start state until it stops.

The tree is ticked (the project's compiled tick, which ``tests/test_btcpp_interop.py`` holds
equal to BehaviorTree.CPP); the action it leaves RUNNING is done in the world, and it is
ticked again. The world is the true action model (``SymbolicWorld``: an action needs its
``pre`` and sets its ``ram``) or, for the snacks, the hidden-state world of ``world.toml``
(``HiddenStateWorld``, without random events). One of five outcomes:

- ``reached``: the tree says done (SUCCESS) and the goal holds;
- ``false done``: it says done and the goal does not hold;
- ``stuck``: it returns FAILURE;
- ``unsafe``: it runs an action whose true preconditions do not hold (the run stops there);
- ``loop``: a state (with the hidden variables) comes back: the tree is a function of the
  state and the world has no chance left in it, so it would go on for ever.
"""

from __future__ import annotations

import itertools
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence

from teach.bt.nodes import Node, Status
from teach.bt.tick import CompiledTree, compile_tree
from teach.domain import Domain, Literal, State
from teach.symbolic import missing_preconditions
from teach.world.hidden import HiddenStateWorld
from teach.world.symbolic import SymbolicWorld

OUTCOMES = ("reached", "false done", "stuck", "unsafe", "loop")


def outcome(tree: CompiledTree, world: SymbolicWorld, goal: Sequence[Literal]) -> tuple[str, str | None]:
    """Run ``tree`` in ``world`` from where it is now: the outcome (see the module docstring)
    and, when it is ``unsafe``, the action and the first of its preconditions that did not
    hold ("PlaceBall without BallGrasped")."""
    domain = world.domain
    seen: set[tuple[State, tuple[tuple[str, int], ...]]] = set()
    while True:
        state = world.state()
        hidden = world.hidden() if isinstance(world, HiddenStateWorld) else {}
        key = (state, tuple(sorted(hidden.items())))
        if key in seen:
            return "loop", None
        seen.add(key)
        status, action = tree(state)
        if status is Status.SUCCESS:
            return ("reached" if all(domain.holds(g, state) for g in goal) else "false done"), None
        if status is not Status.RUNNING or action is None:
            return "stuck", None
        missing = missing_preconditions(domain, state, action)
        if missing:
            return "unsafe", f"{action} without {missing[0]}"
        world.act(action)


def tally(tree: Node, world: SymbolicWorld, goal: Sequence[Literal],
          starts: Iterable[tuple[State, Mapping[str, int]]]) -> tuple[Counter[str], Counter[str]]:
    """How many starts end in each outcome, and how many of the unsafe ones end with each
    action and missing precondition. A start is a state and (hidden worlds) hidden values."""
    compiled = compile_tree(tree, world.domain.condition_names)
    ends = []
    for number, (state, hidden) in enumerate(starts):
        if isinstance(world, HiddenStateWorld):
            world.reset(number)  # the same fresh trays for every tree measured
            world.arrange(state, hidden)
        else:
            world.arrange(state)
        ends.append(outcome(compiled, world, goal))
    return Counter(kind for kind, _ in ends), Counter(detail for _, detail in ends if detail is not None)


def every_state(domain: Domain) -> list[tuple[State, Mapping[str, int]]]:
    """Every state of the domain as a start, with no hidden values."""
    return [(tuple(s), {}) for s in itertools.product((False, True), repeat=len(domain.conditions))]


def from_every_state(tree: Node, model: Domain) -> tuple[Counter[str], Counter[str]]:
    """``tally`` from every state in the true action model ``model`` (its own goal)."""
    return tally(tree, SymbolicWorld(model), model.goal, every_state(model))
