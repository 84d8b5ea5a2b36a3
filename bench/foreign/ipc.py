"""Standard planning domains (``pddl/``), grounded by pyperplan into our ``Task``.

pyperplan is used only here: it parses the PDDL, grounds it and drops static facts. Facts and
operators are then sorted by name, so condition and action order never depends on Python's
string hashing, and named as identifiers: ``(on a b)`` becomes the condition ``on_a_b`` and
``(pick-up a)`` the action ``pick_up_a``.
"""

from __future__ import annotations

import re
from pathlib import Path

from pyperplan.grounding import ground
from pyperplan.pddl.parser import Parser

from foreign.model import Model, Operator, Task, learner_domain

PDDL = Path(__file__).resolve().parent / "pddl"
DOMAINS = ("blocksworld", "gripper", "ferry", "miconic", "logistics", "visitall")
MAX_FACTS = 64
MAX_OPERATORS = 64


def identifier(atom: str) -> str:
    """``(pick-up a)`` -> ``pick_up_a``."""
    return re.sub(r"[^A-Za-z0-9]+", "_", atom.strip("()")).strip("_")


def phrase(atom: str) -> str:
    """``(pick-up a)`` -> ``pick up a``: what a teacher would type or read."""
    return atom.strip("()").replace("-", " ")


def form(atom: str, constants: frozenset[str] = frozenset()) -> tuple[str, ...]:
    """``(pick-up a)`` -> ``("pick_up", "a")``: the predicate or action and its objects. A PDDL
    constant is not a parameter: it goes into the name (``(lit switch)`` -> ``("lit_switch",)``), so
    a precondition about it stays one of every action's own (``teach.learn.lifting``)."""
    kind, *objects = atom.strip("()").split()
    name = "_".join([identifier(kind), *(f"{i}_{identifier(o)}" for i, o in enumerate(objects) if o in constants)])
    return (name, *(identifier(o) for o in objects if o not in constants))


def load(name: str, lifted: bool = True) -> Task:
    """The instance ``pddl/<name>-problem.pddl`` of ``pddl/<name>-domain.pddl``; ``lifted``: the
    learner's domain declares each fact's and operator's form (predicate and objects), as PDDL does."""
    parser = Parser(str(PDDL / f"{name}-domain.pddl"), str(PDDL / f"{name}-problem.pddl"))
    domain = parser.parse_domain()
    constants = frozenset(domain.constants)
    grounded = ground(parser.parse_problem(domain))
    facts = sorted(grounded.facts)
    operators = sorted(grounded.operators, key=lambda o: o.name)
    if len(facts) > MAX_FACTS or len(operators) > MAX_OPERATORS:
        raise ValueError(f"{name}: {len(facts)} facts and {len(operators)} operators, more than "
                         f"{MAX_FACTS} and {MAX_OPERATORS}")
    bit = {fact: 1 << i for i, fact in enumerate(facts)}

    def mask(atoms: frozenset[str] | set[str]) -> int:
        return sum(bit[a] for a in atoms)

    model = Model(tuple(identifier(f) for f in facts),
                  tuple(Operator(identifier(o.name), mask(o.preconditions), 0, mask(o.add_effects),
                                 mask(o.del_effects)) for o in operators),
                  mask(grounded.goals), 0)
    names = {identifier(a): phrase(a) for a in (*facts, *(o.name for o in operators))}
    if len(set(names)) != len(facts) + len(operators):
        raise ValueError(f"{name}: two facts or operators get the same identifier")
    forms = {identifier(a): form(a, constants) for a in (*facts, *(o.name for o in operators))} if lifted else None
    return Task(name, learner_domain(name, model, names, forms), model, (mask(grounded.initial_state),))
