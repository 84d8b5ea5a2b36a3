"""Is the learner safe, and does it reach the goal, on data nobody here wrote or tuned to?

    .venv/bin/python bench/bench_safety.py            # 3 seeds x 100 held-out starts
    .venv/bin/python bench/bench_safety.py --quick    # one seed

Domains: six standard planning domains grounded as tiny instances (``bench/foreign/pddl``:
blocksworld, gripper, ferry, miconic, logistics, visitall) and random STRIPS domains from an
independent generator (``bench/foreign/strips.py``, 6x5, 8x6, 10x8; its assumptions are in its
docstring). The teacher plans optimally in the true model; the learners see only the
conditions and actions (no action model, no goal) and the teacher's demonstrations from
random starts. Judged from held-out starts, disjoint from the training starts, in the true
model (``bench/foreign/judge.py``): reached / false done / stuck / unsafe / loop; beside it the
strict replay of the teacher's held-out demonstrations, the information ceiling (the
share of held-out starts whose optimal plan uses only actions seen in training) and the safe
ceiling (the share from which the goal can be reached acting only on what the demonstrations
prove: ``foreign.teaching.safe_ceiling``; no learner that never acts on a guess does better
without questions).

Learners, on the same demonstrations: the default learner (``learn_online``), the same with up
to 5 of its own questions answered from the true model (``bench/foreign/questions.py``), a
SAM-style baseline (``bench/foreign/sam.py``) and the thesis's Approaches 2 (``detect``) and 3
(``specialize``), whose refusals are counted (a refused set is stuck everywhere).

Then the session loop (``bench/foreign/loop.py``): demonstrations, teacher lines and questions
until the robot reaches the goal from 95% of held-out starts.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from foreign import ipc, strips  # noqa: E402
from foreign.judge import OUTCOMES, Outcomes, judge  # noqa: E402
from foreign.learners import BATCH  # noqa: E402
from foreign.loop import MAX_ROUNDS, TARGET, TRAINING_STARTS, Progress, session_loop  # noqa: E402
from foreign.model import Task  # noqa: E402
from foreign.questions import Answered, ask  # noqa: E402
from foreign.sam import SamLearner  # noqa: E402
from foreign.teaching import ceiling, demonstration, safe_ceiling, split_starts  # noqa: E402

from teach.learn.learner import Learner, learn_online  # noqa: E402
from teach.replay import count_reproduced  # noqa: E402

TRAIN_SIZES = (2, 5, TRAINING_STARTS)
QUESTIONS = 5
HELD_OUT = 100
SEEDS = 3
ROWS = ("learner", "learner+5q", "guessing", "sam", "detect", "specialize")
LOOPS = (("learner", Learner, 0), ("learner+5q/round", Learner, QUESTIONS), ("sam", SamLearner, 0))


@dataclass
class Cell:
    """One learner at one domain and training size, over the seeds."""

    outcomes: list[Outcomes] = field(default_factory=list)
    replay: list[float] = field(default_factory=list)
    refused: int = 0

    def share(self, outcome: str) -> float:
        return statistics.mean(o.share(outcome) for o in self.outcomes)


@dataclass
class Results:
    cells: dict[tuple[str, int, str], Cell] = field(default_factory=dict)
    ceilings: dict[tuple[str, int], list[float]] = field(default_factory=dict)
    safe_ceilings: dict[tuple[str, int], list[float]] = field(default_factory=dict)
    held: dict[str, list[int]] = field(default_factory=dict)
    answers: dict[str, list[Answered]] = field(default_factory=dict)
    """By where they were asked: after k demonstrations, or in the session loop."""
    loops: dict[tuple[str, str], list[Progress]] = field(default_factory=dict)


def tasks(names: list[str], seed: int) -> list[Task]:
    """The planning instances (the same every seed: the seed draws the starts) and one random
    domain per size and seed."""
    result = [ipc.load(name) for name in names if name in ipc.DOMAINS]
    result += [strips.random_task(n, m, seed) for n, m in strips.SIZES if f"strips-{n}x{m}" in names]
    return result


def measure(task: Task, seed: int, held_out: int, results: Results) -> None:
    pool, starts = split_starts(task, seed, max(TRAIN_SIZES), held_out)
    tests = [demonstration(task, s, f"t{i}") for i, s in enumerate(starts)]
    results.held.setdefault(task.name, []).append(len(starts))
    for k in TRAIN_SIZES:
        train = [demonstration(task, s, f"d{i}") for i, s in enumerate(pool[:k])]
        results.ceilings.setdefault((task.name, k), []).append(ceiling(task, train, starts))
        results.safe_ceilings.setdefault((task.name, k), []).append(safe_ceiling(task, train, starts))
        for row in ROWS:
            if row == "learner+5q":
                learner = learn_online(task.domain, train)
                results.answers.setdefault(f"{k} demonstrations", []).extend(ask(learner, task, QUESTIONS))
                tree = learner.tree
            else:
                tree = BATCH[row](task.domain, train)
            cell = results.cells.setdefault((task.name, k, row), Cell())
            cell.outcomes.append(judge(task, tree, starts))
            cell.replay.append(0.0 if tree is None else count_reproduced(tree, task.domain, tests) / len(tests))
            cell.refused += tree is None


def loop(task: Task, seed: int, held_out: int, rounds: int, results: Results) -> None:
    for name, make, questions in LOOPS:
        progress = session_loop(task, seed, make, questions, held_out, rounds)
        results.loops.setdefault((task.name, name), []).append(progress)
        results.answers.setdefault("session loop", []).extend(progress.answers)


def report(results: Results, names: list[str], seeds: int, rounds: int) -> None:
    held = {name: min(counts) for name, counts in results.held.items()}
    print(f"task success from held-out starts in the true model, mean over {seeds} seed(s); "
          f"{HELD_OUT} held-out starts per seed (fewer where the world has fewer: n)")
    heads = ("reached", "false", "stuck", "unsafe", "loop", "replay", "ceiling", "safe", "refused")
    print(f"{'domain':<12} {'n':>4} {'demos':>5} {'learner':<11} " + " ".join(f"{h:>7}" for h in heads))
    for name in names:
        for k in TRAIN_SIZES:
            for row in ROWS:
                cell = results.cells.get((name, k, row))
                if cell is None:
                    continue
                values = [_pct(cell.share(o)) for o in OUTCOMES]
                values += [_pct(statistics.mean(cell.replay)), _pct(statistics.mean(results.ceilings[(name, k)])),
                           _pct(statistics.mean(results.safe_ceilings[(name, k)])),
                           f"{cell.refused}/{len(cell.outcomes)}" if row in ("detect", "specialize") else ""]
                print(f"{name:<12} {held[name]:>4} {k:>5} {row:<11} " + " ".join(f"{v:>7}" for v in values))
    print("\nanswers to the learner's questions, from the true model")
    for where, answers in results.answers.items():
        said = Counter(a.said if a.said == "done" or a.said.startswith(("impossible", "no way", "yes", "no"))
                       else "an action" for a in answers)
        unchanged = sum(not a.changed for a in answers)
        print(f"  {where}: {len(answers)} answers ({', '.join(f'{v} {k}' for k, v in sorted(said.items()))}); "
              f"{unchanged} ({_pct(unchanged / max(1, len(answers)))}) changed nothing")
    verdict(results, names)
    print(f"\nsession loop: rounds until the robot reaches the goal from {_pct(TARGET)} of held-out starts "
          f"(cap {rounds} rounds), mean over seeds")
    loop_heads = ("hit", "rounds", "demos", "lines", "questions", "reached", "unsafe", "false")
    print(f"{'domain':<12} {'learner':<17} " + " ".join(f"{h:>9}" for h in loop_heads))
    for name in names:
        for row, _make, _questions in LOOPS:
            runs = results.loops.get((name, row))
            if not runs:
                continue
            final = [p.outcomes for p in runs if p.outcomes is not None]
            values = [f"{sum(p.hit for p in runs)}/{len(runs)}",
                      *(f"{statistics.mean(getattr(p, a) for p in runs):.1f}"
                        for a in ("rounds", "demonstrations", "lines", "questions")),
                      *(_pct(statistics.mean(o.share(x) for o in final)) for x in ("reached", "unsafe", "false done"))]
            print(f"{name:<12} {row:<17} " + " ".join(f"{v:>9}" for v in values))


def verdict(results: Results, names: list[str]) -> None:
    """Issue 18's bars, learner by learner: unsafe and false done at most 1% everywhere; with
    20 demonstrations within 10 points of the ceiling; 5 questions after 2 demonstrations
    worth at least 10 points."""
    print("\nissue 18's bars (worst domain and training size)")
    for row in ("learner", "learner+5q", "sam"):
        cells = {(n, k): results.cells[(n, k, row)] for n in names for k in TRAIN_SIZES if (n, k, row) in results.cells}
        if not cells:
            continue
        worst = {o: max(cells.items(), key=lambda item, o=o: item[1].share(o)) for o in ("unsafe", "false done")}
        shorts = [[n for (n, k), c in cells.items()
                   if k == max(TRAIN_SIZES) and c.share("reached") < statistics.mean(ceilings[(n, k)]) - 0.1]
                  for ceilings in (results.ceilings, results.safe_ceilings)]
        text = "; ".join(f"{o} {_pct(c.share(o))} ({n}, {k})" for o, ((n, k), c) in worst.items())
        print(f"  {row:<11} worst {text}; 20 demonstrations more than 10 points under the ceiling in "
              f"{len(shorts[0])} of {len(names)} ({', '.join(shorts[0]) or '-'}), under the safe ceiling in "
              f"{len(shorts[1])} ({', '.join(shorts[1]) or '-'})")
    gains = [results.cells[(n, 2, "learner+5q")].share("reached") - results.cells[(n, 2, "learner")].share("reached")
             for n in names if (n, 2, "learner") in results.cells]
    if gains:
        print(f"  5 questions after 2 demonstrations: {sum(g >= 0.1 for g in gains)} of {len(gains)} domains gain "
              f">= 10 points reached (mean {100 * statistics.mean(gains):+.0f})")


def _pct(value: float) -> str:
    return f"{100 * value:.0f}%"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one seed")
    parser.add_argument("--seeds", type=int, default=SEEDS)
    parser.add_argument("--held-out", type=int, default=HELD_OUT)
    everything = [*ipc.DOMAINS, *(f"strips-{n}x{m}" for n, m in strips.SIZES)]
    parser.add_argument("--domains", nargs="+", default=everything, choices=everything, metavar="DOMAIN")
    parser.add_argument("--rounds", type=int, default=MAX_ROUNDS, help="the session loop's cap")
    parser.add_argument("--no-loop", action="store_true", help="skip the session loop")
    args = parser.parse_args(argv)
    seeds = 1 if args.quick else args.seeds
    started = time.perf_counter()
    results = Results()
    for seed in range(seeds):
        for task in tasks(args.domains, seed):
            print(f"\rseed {seed + 1}/{seeds} {task.name:<12} {time.perf_counter() - started:5.0f} s",
                  end="", file=sys.stderr, flush=True)
            measure(task, seed, args.held_out, results)
            if not args.no_loop:
                loop(task, seed, args.held_out, args.rounds, results)
    print(file=sys.stderr)
    report(results, args.domains, seeds, args.rounds)
    print(f"\n{time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
