"""Does the learner generalise? Held-out strict reproduction on random domains and on the ball task.

    .venv/bin/python bench/bench_generalise.py            # full run (about 3 minutes on one core)
    .venv/bin/python bench/bench_generalise.py --seeds 3  # a quick look

Random domains (``bench/random_domains.py``): 6x5, 8x6 and 10x8 (conditions x actions), 20
seeds each; 2, 5 and 20 training demonstrations (a fifth of them with an external event),
200 held-out demonstrations from random starts, strict replay. Beside the new learner: the
information ceiling (the share of held-out demonstrations using only actions seen in
training), the thesis's Approach 2 (``detect``: PA-BT on the detected model) and Approach 3
(``specialize``), each with its refusals (a refused set counts as 0%), and 2 demonstrations
plus up to 5 situation questions answered by the teacher's tree. The ball rows: Δ4 and Δ3
tested on Δ5, questions answered by the Table 6.1 tree. The snacks rows (Use Case 2,
``demos/snacks``): all 11 training demonstrations, and the first 3 with up to 5 questions
answered by the reference tree, each tested on the 26 held-out scenarios.
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from oracle_answers import ReferenceTeacher, ask  # noqa: E402
from random_domains import SIZES, demonstrations, domains  # noqa: E402

from teach.bt.nodes import Node  # noqa: E402
from teach.bt.xml import read_tree  # noqa: E402
from teach.demos import Demonstration, read_demo_set  # noqa: E402
from teach.domain import Domain  # noqa: E402
from teach.errors import LearnError  # noqa: E402
from teach.learn.learner import Learner, learn_online  # noqa: E402
from teach.learn.model import learn_detect  # noqa: E402
from teach.learn.specialize import specialize  # noqa: E402
from teach.replay import count_reproduced  # noqa: E402

TRAIN_SIZES = (2, 5, 20)
HELD_OUT = 200
EVENT_CHANCE = 0.2
QUESTIONS = 5


def ask_of(learner: Learner, teacher: ReferenceTeacher, budget: int) -> int:
    """Up to ``budget`` questions answered by ``teacher`` (``bench/oracle_answers.py``; a
    FAILURE there is a skip, still charged); returns how many were asked."""
    return len(list(ask(learner, teacher, budget)))


def share(tree: Node | None, domain: Domain, tests: list[Demonstration]) -> float:
    return 0.0 if tree is None else count_reproduced(tree, domain, tests) / len(tests)


def thesis_tree(approach: str, domain: Domain, train: list[Demonstration]) -> Node | None:
    """Approach 2 or 3's tree, or None when it refuses the set."""
    try:
        if approach == "detect":
            return learn_detect(domain, train)[-1]
        return specialize(domain, train).tree
    except LearnError:
        return None


def ceiling(train: list[Demonstration], tests: list[Demonstration]) -> float:
    seen = {a for d in train for a in d.actions}
    return sum(set(d.actions) <= seen for d in tests) / len(tests)


Row = dict[str, list[float]]


def run_size(n: int, m: int, seeds: int) -> dict[int, Row]:
    rows: dict[int, Row] = {k: {} for k in TRAIN_SIZES}
    for seed, hidden in enumerate(domains(n, m, seeds)):
        tests = demonstrations(hidden, random.Random(10_000 + seed), HELD_OUT, "t")
        pool = demonstrations(hidden, random.Random(20_000 + seed), max(TRAIN_SIZES), "d", EVENT_CHANCE)
        for k in TRAIN_SIZES:
            train = pool[:k]
            row = rows[k]
            learner = learn_online(hidden.domain, train)
            _add(row, "learner", share(learner.tree, hidden.domain, tests))
            _add(row, "learner refusals", 0.0)
            _add(row, "ceiling", ceiling(train, tests))
            for approach in ("detect", "specialize"):
                tree = thesis_tree(approach, hidden.domain, train)
                _add(row, approach, share(tree, hidden.domain, tests))
                _add(row, f"{approach} refusals", float(tree is None))
            if k == 2:
                ask_of(learner, ReferenceTeacher(hidden.teacher, hidden.domain), QUESTIONS)
                _add(row, "2+questions", share(learner.tree, hidden.domain, tests))
    return rows


def _add(row: Row, key: str, value: float) -> None:
    row.setdefault(key, []).append(value)


def ball() -> list[tuple[str, int, int, int]]:
    """(training set, questions allowed, questions asked, reproduced of Δ5)."""
    sets = ROOT / "demos" / "ball"
    domain, delta5 = read_demo_set(sets / "delta5")
    oracle = ReferenceTeacher(read_tree(sets / "reference" / "table61.xml"), domain)
    result = []
    for name, budget in (("delta4", 0), ("delta4", 5), ("delta3", 0), ("delta3", 2)):
        _domain, train = read_demo_set(sets / name, domain)
        learner = learn_online(domain, train)
        asked = ask_of(learner, oracle, budget)
        result.append((name, budget, asked, count_reproduced(learner.tree, domain, delta5)))
    return result


def snacks() -> list[tuple[int, int, int, int, int]]:
    """(training demonstrations, questions allowed, questions asked, reproduced, held-out total)."""
    sets = ROOT / "demos" / "snacks"
    domain, train = read_demo_set(sets / "train")
    _domain, held_out = read_demo_set(sets / "heldout", domain)
    oracle = ReferenceTeacher(read_tree(sets / "reference" / "reference.xml"), domain)
    result = []
    for count, budget in ((len(train), 0), (3, 0), (3, QUESTIONS)):
        learner = learn_online(domain, train[:count])
        asked = ask_of(learner, oracle, budget)
        result.append((count, budget, asked, count_reproduced(learner.tree, domain, held_out), len(held_out)))
    return result


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20)
    args = parser.parse_args(argv)
    started = time.perf_counter()
    print(f"held-out strict reproduction, mean (minimum) over {args.seeds} random domains per size; "
          f"{HELD_OUT} held-out demonstrations each")
    columns: list[tuple[str, Callable[[Row], str]]] = [
        ("ceiling", lambda r: _pct(r["ceiling"])),
        ("learner", lambda r: _pct(r["learner"], True)),
        ("refused", lambda r: f"{int(sum(r['learner refusals']))}"),
        ("detect", lambda r: _pct(r["detect"])),
        ("refused", lambda r: f"{int(sum(r['detect refusals']))}"),
        ("specialize", lambda r: _pct(r["specialize"])),
        ("refused", lambda r: f"{int(sum(r['specialize refusals']))}"),
    ]
    header = f"{'domain':>7} {'demos':>5} " + " ".join(f"{name:>14}" for name, _ in columns)
    print(header)
    for n, m in SIZES:
        rows = run_size(n, m, args.seeds)
        for k in TRAIN_SIZES:
            row = rows[k]
            print(f"{n}x{m:<5} {k:>5} " + " ".join(f"{fmt(row):>14}" for _name, fmt in columns))
        print(f"{n}x{m:<5} {'2+5q':>5} {'':>14} {_pct(rows[2]['2+questions'], True):>14}")
    print()
    print("ball, tested on Δ5 (43 demonstrations), questions answered by the Table 6.1 tree")
    for name, budget, asked, reproduced in ball():
        print(f"  {name} with <= {budget} questions ({asked} asked): {reproduced}/43")
    print("\nsnacks (Use Case 2), tested on the held-out scenarios, questions answered by the reference tree")
    for count, budget, asked, reproduced, total in snacks():
        print(f"  {count} demonstrations with <= {budget} questions ({asked} asked): {reproduced}/{total} "
              f"({100 * reproduced / total:.0f}%)")
    print(f"\n{time.perf_counter() - started:.0f} s")


def _pct(values: list[float], minimum: bool = False) -> str:
    text = f"{100 * statistics.mean(values):.1f}%"
    return f"{text} ({100 * min(values):.0f}%)" if minimum else text


if __name__ == "__main__":
    main()
