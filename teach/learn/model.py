"""Approach 2 (thesis §4.2.1): detect the action model and the goal in demonstrations, then PA-BT.

For each robot action (external actions -1 are nobody's, so they are not detected):

- precondition: a condition with the same value in every state where the action was applied;
- ramification: a condition that changed in every (s, a, s') of the action. A literal states
  one value, so a condition that changed to different values in different transitions (it
  toggled) is not a ramification;
- goal: the conditions with the same value in every goal state (last lines with action 0).

An action never demonstrated gets an empty model: there is no evidence for one. Adding
demonstrations means detecting again (the thesis notes Approach 2 is not online).
"""

from __future__ import annotations

from collections.abc import Sequence as Seq
from dataclasses import replace

from teach.bt.nodes import Node
from teach.demos import Demonstration
from teach.domain import Domain, Literal, State
from teach.errors import LearnError


def constant_literals(domain: Domain, states: Seq[State]) -> tuple[Literal, ...]:
    """The literals that hold in every one of ``states``, in condition order."""
    if not states:
        return ()
    first = states[0]
    return tuple(Literal(name, first[i]) for i, name in enumerate(domain.condition_names)
                 if all(s[i] == first[i] for s in states))


def detect_model(domain: Domain, demos: Seq[Demonstration]) -> Domain:
    """The domain with preconditions, ramifications and goal detected from ``demos``."""
    applied: dict[int, list[State]] = {a.id: [] for a in domain.actions}
    changes: dict[int, list[tuple[State, State]]] = {a.id: [] for a in domain.actions}
    for demo in demos:
        for step in demo.steps:
            if step.action > 0:
                applied[step.action].append(step.state)
        for t in demo.transitions():
            if t.action > 0:
                changes[t.action].append((t.before, t.after))
    actions = []
    for action in domain.actions:
        pre = constant_literals(domain, applied[action.id])
        ram = _ramifications(domain, changes[action.id])
        actions.append(replace(action, pre=pre, ram=ram))
    goal = constant_literals(domain, [d.goal_state for d in demos if d.goal_state is not None])
    return replace(domain, actions=tuple(actions), goal=goal)


def _ramifications(domain: Domain, pairs: Seq[tuple[State, State]]) -> tuple[Literal, ...]:
    if not pairs:
        return ()
    result = []
    for i, name in enumerate(domain.condition_names):
        after = pairs[0][1][i]
        if all(before[i] != after_state[i] and after_state[i] == after for before, after_state in pairs):
            result.append(Literal(name, after))
    return tuple(result)


def learn_detect(domain: Domain, demos: Seq[Demonstration]) -> list[Node]:
    """Approach 2: PA-BT generations on the detected model and goal."""
    from teach.learn.pabt import expand

    if not any(d.reached_goal for d in demos):
        raise LearnError("no demonstration reaches the goal (a last line with action 0), so there is "
                         "no goal to detect", domain.path)
    return expand(detect_model(domain, demos))
