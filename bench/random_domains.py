"""Random STRIPS-like domains with a hidden action model, and their teacher's demonstrations.

Each domain has ``n`` conditions and ``m`` actions. Action j makes one condition true (its
main effect), sometimes also makes another one false (a side effect, like walking away from
the bin), and needs its main effect not to hold yet plus one or two conditions that earlier
actions make true; conditions no action makes true are the world's business (accidental
context). The goal is the main effect of the last action, sometimes with another one. The
teacher is the tree backchained from the hidden model (``teach.learn.backchain``, no last
resort); a demonstration runs it from a random start in the hidden model's symbolic world
until it returns SUCCESS (kept) or fails or loops (dropped). Training demonstrations may
contain an external event (-1: a random condition flips) after which the teacher goes on.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

from teach.bt.nodes import Node, Status
from teach.bt.tick import CompiledTree, compile_tree
from teach.demos import Demonstration, Step
from teach.domain import ActionDef, ConditionDef, Domain, Literal, State
from teach.learn.backchain import PlanView, plan

SIZES = ((6, 5), (8, 6), (10, 8))


@dataclass
class Hidden:
    """A domain (without its model, as the learners see it), the model and the teacher."""

    domain: Domain
    model: Domain
    teacher: Node
    compiled: CompiledTree


def random_domain(rng: random.Random, n: int, m: int, name: str) -> Hidden | None:
    conditions = tuple(ConditionDef(f"C{i}", f"c{i} holds", f"c{i} gilt") for i in range(n))
    mains = rng.sample(range(n), m)
    actions = []
    for j, main in enumerate(mains):
        earlier = mains[:j]
        needs = [Literal(f"C{c}") for c in rng.sample(earlier, min(len(earlier), rng.choice((1, 1, 2))))]
        ram = [Literal(f"C{main}")]
        side = [c for c in range(n) if c != main and Literal(f"C{c}") not in needs]
        if rng.random() < 0.3 and side:
            ram.append(Literal(f"C{rng.choice(side)}", False))
        actions.append(ActionDef(j + 1, f"A{j}", (f"do a{j}",), (f"mach a{j}",),
                                 (Literal(f"C{main}", False), *needs), tuple(ram)))
    goal = [Literal(f"C{mains[-1]}")]
    if rng.random() < 0.3:
        goal.insert(0, Literal(f"C{mains[rng.randrange(m - 1)]}"))
    model = Domain(name, conditions, tuple(actions), tuple(goal))
    index = {c.name: i for i, c in enumerate(conditions)}
    view = PlanView(tuple((index[g.name], g.value) for g in goal),
                    tuple((a.name, tuple((index[p.name], p.value) for p in a.pre)) for a in actions),
                    tuple(((i, v), tuple(a.name for a in actions if Literal(f"C{i}", v) in a.ram))
                          for i in range(n) for v in (True, False)
                          if any(Literal(f"C{i}", v) in a.ram for a in actions)),
                    weak_last_resort=False)
    teacher, _roles = plan(view, model.condition_names)
    if teacher is None:
        return None
    bare = Domain(name, conditions, tuple(ActionDef(a.id, a.name, a.en, a.de) for a in actions))
    return Hidden(bare, model, teacher, compile_tree(teacher, model.condition_names))


def apply(model: Domain, state: State, action: str) -> State:
    values = list(state)
    for literal in model.action(action).ram:
        values[model.index(literal.name)] = literal.value
    return tuple(values)


def demonstrate(hidden: Hidden, start: State, name: str, rng: random.Random | None = None,
                event_chance: float = 0.0) -> Demonstration | None:
    """The teacher from ``start``; None if it does not reach the goal. With ``rng`` and
    ``event_chance``, one external event may flip a random condition on the way."""
    model = hidden.model
    steps: list[Step] = []
    state, seen = start, {start}
    event_left = rng is not None and rng.random() < event_chance
    for _ in range(4 * len(model.actions) + 4):
        if event_left and rng is not None and steps and rng.random() < 0.4:
            event_left = False
            steps.append(Step(state, -1, len(steps) + 1))
            flip = rng.randrange(len(state))
            state = tuple(not v if i == flip else v for i, v in enumerate(state))
            seen = {state}
        status, action = hidden.compiled(state)
        if status is Status.SUCCESS:
            steps.append(Step(state, 0, len(steps) + 1))
            return Demonstration(name, tuple(steps))
        if status is not Status.RUNNING or action is None:
            return None
        steps.append(Step(state, model.action(action).id, len(steps) + 1))
        state = apply(model, state, action)
        if state in seen:
            return None
        seen.add(state)
    return None


def random_state(rng: random.Random, n: int) -> State:
    return tuple(rng.random() < 0.5 for _ in range(n))


def demonstrations(hidden: Hidden, rng: random.Random, count: int, prefix: str,
                   event_chance: float = 0.0) -> list[Demonstration]:
    """``count`` successful demonstrations from random starts (fewer if the teacher rarely succeeds)."""
    n = len(hidden.model.conditions)
    result: list[Demonstration] = []
    for attempt in range(50 * count):
        if len(result) == count:
            break
        demo = demonstrate(hidden, random_state(rng, n), f"{prefix}{attempt}", rng, event_chance)
        if demo is not None and len(demo.steps) > 1:
            result.append(demo)
    return result


def domains(n: int, m: int, count: int, seed: int = 0) -> list[Hidden]:
    """``count`` random domains whose teacher succeeds from at least a third of all starts."""
    rng = random.Random(seed * 1000 + n * 10 + m)
    result: list[Hidden] = []
    while len(result) < count:
        hidden = random_domain(rng, n, m, f"random-{n}x{m}-{len(result)}")
        if hidden is None:
            continue
        probe = random.Random(len(result))
        wins = sum(demonstrate(hidden, random_state(probe, n), "probe") is not None for _ in range(60))
        if wins >= 20:
            result.append(hidden)
    return result
