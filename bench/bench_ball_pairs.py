"""The thesis's ball task learned from every pair of Δ2 demonstrations (issue 18, item 4).

    .venv/bin/python bench/bench_ball_pairs.py           # all 561 pairs (under a minute on one core)
    .venv/bin/python bench/bench_ball_pairs.py --quick   # every 7th pair

Each pair of ``demos/ball/delta2`` is learned by the default learner
(``teach.learn.learner.learn_online``, the domain as the session sees it, goal declared),
then up to 5 questions are asked and answered by the Table 6.1 tree
(``bench/oracle_answers.py``); after 0, 1, ..., 5 answers the tree is measured:

- strict replay of Δ5 (43 demonstrations, ``teach.replay.count_reproduced``);
- task success from each of the 32 ball states in the true model, ``demos/ball/domain.toml``'s
  own ``pre``/``ram`` (Table 6.1; ``bench/task_outcomes.py``): reached / false done / stuck /
  unsafe / loop;
- whether both training demonstrations are still reproduced strictly.

Reported as mean and worst over all pairs and over the pairs that between them show all
five actions, with the share of answers that changed nothing in the tree. Beside the safe
learner's figure for those pairs: the same budget of questions chosen knowing their answers
(``bench/question_ceiling.py``), which tells a chooser's wrong predictions from a budget too small.
"""

from __future__ import annotations

import argparse
import itertools
import statistics
import sys
import time
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from oracle_answers import Answered, ReferenceTeacher, ask, unchanged_share  # noqa: E402
from question_ceiling import knowing_the_answers  # noqa: E402
from task_outcomes import OUTCOMES, from_every_state  # noqa: E402

from teach.bt.xml import read_tree  # noqa: E402
from teach.demos import Demonstration, read_demo_set  # noqa: E402
from teach.domain import Domain, load_domain  # noqa: E402
from teach.learn.learner import Learner, learn_online  # noqa: E402
from teach.replay import count_reproduced  # noqa: E402

BALL = ROOT / "demos" / "ball"
QUESTIONS = 5
QUICK_STRIDE = 7
TARGET_MEAN, TARGET_WORST = 41, 37
LEARNERS = {"model": (False,), "safe": (True,), "both": (False, True)}


@dataclass(frozen=True)
class Measured:
    """One pair after ``questions`` answers."""

    pair: tuple[str, str]
    shows_all: bool
    questions: int
    reproduced: int
    outcomes: Counter[str]
    unsafe_actions: Counter[str]
    training_kept: bool
    answers: tuple[Answered, ...]


@dataclass(frozen=True)
class Ball:
    domain: Domain
    model: Domain
    teacher: ReferenceTeacher
    delta2: list[Demonstration]
    delta5: list[Demonstration]


def load() -> Ball:
    domain, delta2 = read_demo_set(BALL / "delta2")
    _, delta5 = read_demo_set(BALL / "delta5", domain)
    teacher = ReferenceTeacher(read_tree(BALL / "reference" / "table61.xml"), domain)
    return Ball(domain, load_domain(BALL / "domain.toml"), teacher, delta2, delta5)


def actions_shown(demos: list[Demonstration]) -> set[int]:
    return {a for demo in demos for a in demo.actions}


def run_pair(ball: Ball, pair: tuple[Demonstration, Demonstration], budget: int = QUESTIONS,
             safe: bool = True) -> list[Measured]:
    """The pair after 0, 1, ... answered questions (fewer when the learner has none left)."""
    train = list(pair)
    names = (pair[0].name, pair[1].name)
    shows_all = actions_shown(train) == {a.id for a in ball.domain.actions}
    learner = learn_online(ball.domain, train, safe=safe)
    answers: list[Answered] = []

    def measure() -> Measured:
        outcomes, unsafe = from_every_state(learner.tree, ball.model)
        return Measured(names, shows_all, len(answers), count_reproduced(learner.tree, ball.domain, ball.delta5),
                        outcomes, unsafe, _keeps(learner, ball.domain, train), tuple(answers))

    result = [measure()]
    for answered in ask(learner, ball.teacher, budget):
        answers.append(answered)
        result.append(measure())
    return result


def _keeps(learner: Learner, domain: Domain, train: list[Demonstration]) -> bool:
    return count_reproduced(learner.tree, domain, train) == len(train)


def at_budget(runs: list[list[Measured]], budget: int) -> list[Measured]:
    """Each pair's tree with at most ``budget`` questions (its last one if it ran out)."""
    return [run[min(budget, len(run) - 1)] for run in runs]


def report(rows: list[Measured], total: int, states: int) -> str:
    if not rows:
        return "(no pairs)"
    reproduced = [r.reproduced for r in rows]
    outcomes: Counter[str] = sum((r.outcomes for r in rows), Counter())
    starts = len(rows) * states
    success = "  ".join(f"{name} {100 * outcomes[name] / starts:5.1f}%" for name in OUTCOMES)
    answers = [a for r in rows for a in r.answers]
    asked = statistics.mean(r.questions for r in rows)
    lost = sum(not r.training_kept for r in rows)
    mean, worst = statistics.mean(reproduced), min(reproduced)
    return (f"{len(rows):>3} pairs  Δ5 mean {mean:5.2f}/{total} worst {worst:>2}/{total}"
            f"  | {success}  | asked {asked:.1f}, unchanged {100 * unchanged_share(answers):3.0f}%"
            f"  | training lost {lost}")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help=f"every {QUICK_STRIDE}th pair only")
    parser.add_argument("--learner", choices=tuple(LEARNERS), default="both",
                        help="the model learner (guesses), the safe one, or both (default)")
    args = parser.parse_args(argv)
    started = time.perf_counter()
    ball = load()
    pairs = list(itertools.combinations(ball.delta2, 2))
    chosen = pairs[::QUICK_STRIDE] if args.quick else pairs
    for safe in LEARNERS[args.learner]:
        print(f"== the {'safe' if safe else 'model (guessing)'} learner")
        report_learner(ball, pairs, chosen, safe)
    print(f"{time.perf_counter() - started:.0f} s")


def report_learner(ball: Ball, pairs: list[tuple[Demonstration, Demonstration]],
                   chosen: list[tuple[Demonstration, Demonstration]], safe: bool) -> None:
    runs = []
    for number, pair in enumerate(chosen, start=1):
        runs.append(run_pair(ball, pair, safe=safe))
        if number % 25 == 0 or number == len(chosen):
            print(f"\rpair {number}/{len(chosen)}", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    every = sum(run[0].shows_all for run in runs)
    total, states = len(ball.delta5), 2 ** len(ball.domain.conditions)
    print(f"ball: {len(chosen)} of the {len(pairs)} pairs of Δ2 ({len(ball.delta2)} demonstrations), "
          f"{every} showing all five actions; strict replay of Δ5 ({total}); task success from all "
          f"{states} states in the true model; questions answered by the Table 6.1 tree")
    for budget in range(QUESTIONS + 1):
        rows = at_budget(runs, budget)
        print(f"<= {budget} questions")
        print(f"  all pairs      {report(rows, total, states)}")
        print(f"  all 5 actions  {report([r for r in rows if r.shows_all], total, states)}")
    print(breakdown(at_budget(runs, QUESTIONS)))
    five = [r.reproduced for r in at_budget(runs, QUESTIONS) if r.shows_all]
    if five:
        met = statistics.mean(five) >= TARGET_MEAN and min(five) >= TARGET_WORST
        print(f"issue 18's target, pairs showing all five actions with <= {QUESTIONS} questions: mean >= "
              f"{TARGET_MEAN}/{total} and worst >= {TARGET_WORST}/{total}: {'met' if met else 'not met'}")
    if safe:
        every_action = {a.id for a in ball.domain.actions}
        print(ceiling(ball, [pair for pair in chosen if actions_shown(list(pair)) == every_action]))


def ceiling(ball: Ball, pairs: list[tuple[Demonstration, Demonstration]]) -> str:
    """The pairs' Δ5 after ``QUESTIONS`` questions chosen knowing their answers."""
    reproduced = []
    for number, pair in enumerate(pairs, start=1):
        best = knowing_the_answers(learn_online(ball.domain, list(pair)), ball.teacher, QUESTIONS)
        reproduced.append(count_reproduced(best.tree, ball.domain, ball.delta5))
        print(f"\rknowing the answers: pair {number}/{len(pairs)}", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    if not reproduced:
        return "(no pair shows all five actions)"
    return (f"the same {len(pairs)} pairs with <= {QUESTIONS} questions chosen knowing their answers "
            f"(bench/question_ceiling.py): Δ5 mean {statistics.mean(reproduced):5.2f}/{len(ball.delta5)} "
            f"worst {min(reproduced)}/{len(ball.delta5)}")


def breakdown(rows: list[Measured]) -> str:
    """Which actions (and missing preconditions) the unsafe runs end with, and how often each
    kind of question changed nothing."""
    unsafe: Counter[str] = sum((r.unsafe_actions for r in rows), Counter())
    kinds: dict[str, list[Answered]] = {}
    for answered in (a for r in rows for a in r.answers):
        kinds.setdefault(answered.kind, []).append(answered)
    return (f"with <= {QUESTIONS} questions, the unsafe runs end with: "
            + ", ".join(f"{name} {count}" for name, count in unsafe.most_common(8))
            + "\nanswers by kind (unchanged = the tree did not change): "
            + ", ".join(f"{kind} {len(given)} ({100 * unchanged_share(given):.0f}% unchanged)"
                        for kind, given in sorted(kinds.items(), key=lambda item: -len(item[1]))))


if __name__ == "__main__":
    main()
