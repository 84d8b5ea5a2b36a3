"""Is the question selector general? Random domains, few demonstrations, five questions.

    .venv/bin/python bench/bench_questions.py

For each random domain: a hidden true action model (a chain of conditions, each made true
by one action that needs some earlier conditions), its PA-BT tree as the teacher's
behaviour, two demonstrations of it from random starts, then up to five questions answered
by that behaviour, and a strict replay of its demonstrations from every start state.
Compared side by side: no questions, five questions about random unseen situations, and
the session's selector (expected model change over a committee).
"""

from __future__ import annotations

import random
import statistics
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from teach.demos import Demonstration, Step  # noqa: E402
from teach.dialogue.oracle import (  # noqa: E402
    SKIP,
    Oracle,
    answer_open_questions,  # noqa: E402
)
from teach.domain import ActionDef, ConditionDef, Domain, Literal, State  # noqa: E402
from teach.errors import LearnError  # noqa: E402
from teach.learn.pabt import expand  # noqa: E402
from teach.observe.hook import Observer  # noqa: E402
from teach.replay import replay  # noqa: E402
from teach.session.machine import SessionManager  # noqa: E402
from teach.session.settings import Settings, WorldKind  # noqa: E402
from teach.world.offline import OfflineWorld  # noqa: E402
from teach.world.symbolic import SymbolicWorld  # noqa: E402

DOMAINS = 40
BUDGET = 5


def random_model(rng: random.Random, n: int) -> Domain:
    conditions = tuple(ConditionDef(f"C{i}", f"c{i} holds", f"c{i} gilt", f"c{i} fails", f"c{i} gilt nicht")
                       for i in range(n))
    actions = []
    for i in range(n):
        needs = [Literal(f"C{j}") for j in range(i) if rng.random() < 0.4]
        if i and not needs:
            needs = [Literal(f"C{i - 1}")]
        actions.append(ActionDef(i + 1, f"A{i}", (f"do a{i}",), (f"mach a{i}",),
                                 (Literal(f"C{i}", False), *needs), (Literal(f"C{i}"),)))
    return Domain(f"random-{n}", conditions, tuple(actions), (Literal(f"C{n - 1}"),))


def run_reference(model: Domain, reference: Oracle, start: State, name: str) -> Demonstration | None:
    """The teacher's behaviour from ``start`` in the true model, as a demonstration."""
    world = SymbolicWorld(model)
    world.arrange(start)
    steps: list[Step] = []
    for _ in range(3 * len(model.actions)):
        state = world.state()
        answer = reference.answer(state)
        if answer is None:
            steps.append(Step(state, 0, len(steps) + 1))
            return Demonstration(name, tuple(steps))
        if answer == SKIP or not world.act(answer).ok:
            return None
        steps.append(Step(state, model.action(answer).id, len(steps) + 1))
    return None


def taught_tree(model: Domain, train: list[Demonstration], reference: Oracle, strategy: str, rng: random.Random):
    with tempfile.TemporaryDirectory() as scratch:
        settings = Settings("bench", questions=BUDGET, world=WorldKind.OFFLINE, base=Path(scratch), record=False)
        session = SessionManager(settings, model, OfflineWorld(model), Observer())
        session.import_demonstrations(train)
        if strategy == "selector":
            while session.budget.left > 0:
                session.handle("ask")
                if session.pending is None:
                    break
                answer_open_questions(session, reference)
        elif strategy in ("random", "all"):
            unseen = [s for s in all_states(len(model.conditions)) if s not in session.learning.labels]
            chosen = unseen if strategy == "all" else rng.sample(unseen, min(BUDGET, len(unseen)))
            for state in chosen:
                answer = reference.answer(state)
                if answer == SKIP:
                    continue
                try:
                    session.learning.learner.teach_step(state, answer, "random question")
                except LearnError:
                    pass
        return session.learning.learner.tree


def all_states(n: int) -> list[State]:
    return [tuple(bool(bits >> i & 1) for i in range(n)) for bits in range(1 << n)]


def run() -> None:
    print(f"{DOMAINS} random domains per size; 2 training demonstrations; budget {BUDGET}; strict replay of the "
          f"teacher's behaviour from every start state")
    print(f"{'conditions':>10} {'no questions':>14} {'random situations':>18} {'selector':>10} "
          f"{'every situation':>16}")
    for n in (5, 7):
        shares: dict[str, list[float]] = {"none": [], "random": [], "selector": [], "all": []}
        rng = random.Random(n)
        made = 0
        while made < DOMAINS:
            model = random_model(rng, n)
            try:
                reference = Oracle(expand(model)[-1], model)
            except LearnError:
                continue
            tests = [d for i, s in enumerate(all_states(n)) if (d := run_reference(model, reference, s, f"t{i}"))]
            starts = rng.sample(all_states(n), 6)
            train = [d for i, s in enumerate(starts) if (d := run_reference(model, reference, s, f"d{i}"))][:2]
            if len(train) < 2 or len(tests) < 8:
                continue
            made += 1
            for strategy in shares:
                tree = taught_tree(model, train, reference, strategy, random.Random(made))
                shares[strategy].append(replay(tree, model, tests).reproduced / len(tests))
        print(f"{n:>10} " + " ".join(f"{100 * statistics.mean(shares[k]):>{w}.1f}%" for k, w in
                                      (("none", 13), ("random", 17), ("selector", 9), ("all", 15))))


if __name__ == "__main__":
    run()
