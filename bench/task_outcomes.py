"""Task success in a true action model: run a tree from a start state until it stops.

The tree is ticked (the project's compiled tick, which ``tests/test_btcpp_interop.py`` holds
equal to BehaviorTree.CPP); the action it leaves RUNNING is applied in the true model (its
``ram`` literals set, nothing else changed), and it is ticked again. One of five outcomes:

- ``reached``: the tree says done (SUCCESS) and the model's goal holds;
- ``false done``: it says done and the goal does not hold;
- ``stuck``: it returns FAILURE;
- ``unsafe``: it runs an action whose true preconditions do not hold (the run stops there);
- ``loop``: a state comes back (the tree is a function of the state, so it would go on for ever).
"""

from __future__ import annotations

import itertools
from collections import Counter

from teach.bt.nodes import Node, Status
from teach.bt.tick import CompiledTree, compile_tree
from teach.domain import Domain, State

OUTCOMES = ("reached", "false done", "stuck", "unsafe", "loop")


def outcome(tree: CompiledTree, model: Domain, start: State) -> tuple[str, str | None]:
    """Run ``tree`` from ``start`` in ``model``: the outcome (see the module docstring) and,
    when it is ``unsafe``, the action and the first of its preconditions that did not hold
    ("PlaceBall without BallGrasped")."""
    state, seen = start, {start}
    while True:
        status, action = tree(state)
        if status is Status.SUCCESS:
            return ("reached" if all(model.holds(g, state) for g in model.goal) else "false done"), None
        if status is not Status.RUNNING or action is None:
            return "stuck", None
        definition = model.action(action)
        missing = next((p for p in definition.pre if not model.holds(p, state)), None)
        if missing is not None:
            return "unsafe", f"{action} without {missing}"
        values = list(state)
        for literal in definition.ram:
            values[model.index(literal.name)] = literal.value
        state = tuple(values)
        if state in seen:
            return "loop", None
        seen.add(state)


def from_every_state(tree: Node, model: Domain) -> tuple[Counter[str], Counter[str]]:
    """How many of the model's states end in each outcome, and how many of the unsafe ones
    end with each action and missing precondition."""
    compiled = compile_tree(tree, model.condition_names)
    ends = [outcome(compiled, model, tuple(state))
            for state in itertools.product((False, True), repeat=len(model.conditions))]
    return Counter(kind for kind, _ in ends), Counter(action for _, action in ends if action is not None)
