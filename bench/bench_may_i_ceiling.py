"""What the safe learner's questions leave on the table in random STRIPS domains (issue 18).

    .venv/bin/python bench/bench_may_i_ceiling.py                  # 6x5 and 8x6, 3 seeds (about a minute)
    .venv/bin/python bench/bench_may_i_ceiling.py --sizes 6x5 --seeds 8

After 2 demonstrations (``--demonstrations``), four learners get 5 questions answered from the
true model (``foreign.questions.answer_question``), and each is judged by task success from
100 held-out starts:

- none: no questions;
- chooser: the learner's own questions (``teach.learn.inquiry.next_question``), as the session asks them;
- knowing, "may I": before each question every "may I still do X here?" is tried with its true
  answer and the one kept after which the robot reaches the goal from the most starts of the
  world (every state where the robot does nothing, and every demonstrated X whose required
  literals that are false there are all unsure, so a yes rules them out);
- knowing, labels: the same with "what should I do here?" (the teacher's step), as
  ``bench/question_ceiling.py`` asks on the ball.

Greedy, so an estimate, not a bound; where the knowing rows reach more than the chooser, the
shortfall is the chooser's guess of the answers, not the budget. Beside each it prints what the
kept questions were: how many literals a question put to the test, whether it was a yes, how far
the state was from the goal and from the nearest labelled state.
"""

from __future__ import annotations

import argparse
import copy
import statistics
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from foreign import strips  # noqa: E402
from foreign.judge import judge  # noqa: E402
from foreign.loop import TRAINING_STARTS  # noqa: E402
from foreign.model import Task  # noqa: E402
from foreign.questions import answer_question, ask  # noqa: E402
from foreign.teaching import demonstration, split_starts  # noqa: E402

from teach.learn.action_model import literals_of  # noqa: E402
from teach.learn.learner import Learner, learn_online  # noqa: E402
from teach.learn.safe_inquiry import may_i  # noqa: E402
from teach.learn.situations import SituationQuestion, tree_does  # noqa: E402

QUESTIONS = 5
HELD_OUT = 100
ROWS = ("none", "chooser", "knowing, may I", "knowing, labels")


def may_i_questions(learner: Learner, task: Task) -> Iterator[SituationQuestion]:
    """Every "may I still do X here?" a yes to which rules out unsure literals, where the robot does nothing."""
    width = len(task.domain.conditions)
    for mask in task.reachable:
        state = task.state(mask)
        if state in learner.situations or tree_does(learner, state) != "nothing":
            continue
        for name, knowledge in learner.model.actions.items():
            if not knowledge.demonstrated:
                continue
            unsure = set(literals_of(*knowledge.unsure, width))
            false = [(i, v) for i, v in literals_of(*knowledge.required, width) if state[i] != v]
            if false and all(literal in unsure for literal in false):
                yield may_i(learner, state, name, false, "nothing")


def label_questions(learner: Learner, task: Task) -> Iterator[SituationQuestion]:
    """ "What should I do here?" wherever the robot does nothing and the goal can be reached."""
    for mask in task.reachable:
        state = task.state(mask)
        if task.distance(mask) and state not in learner.situations and tree_does(learner, state) == "nothing":
            yield SituationQuestion(state, "gap", tree_does="nothing")


def knowing(learner: Learner, task: Task, questions: Callable[[Learner, Task], Iterator[SituationQuestion]],
            kept: list[str]) -> Learner:
    """``learner`` after ``QUESTIONS`` questions, each the one whose true answer lets the robot
    reach the goal from the most starts (a copy; ``kept`` gets a line on each)."""
    starts = task.starts()
    for _ in range(QUESTIONS):
        best: tuple[float, Learner, str] | None = None
        for question in questions(learner, task):
            trial = copy.deepcopy(learner)
            said = answer_question(trial, question, task, "a question chosen knowing its answer").said
            reached = judge(task, trial.tree, starts).share("reached")
            if best is None or reached > best[0]:
                best = (reached, trial, _described(learner, task, question, said))
        if best is None:
            break
        learner = best[1]
        kept.append(best[2])
    return learner


def _described(learner: Learner, task: Task, question: SituationQuestion, said: str) -> str:
    mask = learner.state_mask(question.state)
    nearest = min((mask ^ labelled).bit_count() for labelled in learner.labelled_masks())
    distance = task.distance(task.mask(question.state))
    tested = len(question.settles) if question.settles else "-"
    return f"{tested} literal(s), {said}, {distance if distance is not None else 'no way'} step(s) to the goal, " \
           f"{nearest} condition(s) from a labelled state"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", nargs="+", default=["6x5", "8x6"], help="random STRIPS sizes, CONDITIONSxACTIONS")
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--demonstrations", type=int, default=2)
    parser.add_argument("--verbose", action="store_true", help="the questions each knowing row kept")
    args = parser.parse_args(argv)
    started = time.perf_counter()
    for size in args.sizes:
        conditions, actions = (int(part) for part in size.split("x"))
        reached: dict[str, list[float]] = {row: [] for row in ROWS}
        kept: dict[str, list[str]] = {row: [] for row in ROWS}
        for seed in range(1, args.seeds + 1):
            task = strips.random_task(conditions, actions, seed)
            pool, starts = split_starts(task, seed, TRAINING_STARTS, HELD_OUT)  # the starts bench_safety.py draws
            train = [demonstration(task, s, f"d{i}") for i, s in enumerate(pool[:args.demonstrations])]
            learner = learn_online(task.domain, train)
            asked = copy.deepcopy(learner)
            ask(asked, task, QUESTIONS)
            learners = {"none": learner, "chooser": asked,
                        "knowing, may I": knowing(learner, task, may_i_questions, kept["knowing, may I"]),
                        "knowing, labels": knowing(learner, task, label_questions, kept["knowing, labels"])}
            for row, taught in learners.items():
                reached[row].append(judge(task, taught.tree, starts).share("reached"))
            print(f"\rstrips-{size} seed {seed}/{args.seeds}", end="", file=sys.stderr, flush=True)
        print(file=sys.stderr)
        print(f"strips-{size}, {args.demonstrations} demonstrations + {QUESTIONS} questions, reached from "
              f"{HELD_OUT} held-out starts, mean over {args.seeds} seeds:")
        for row in ROWS:
            print(f"  {row:<16} {100 * statistics.mean(reached[row]):5.1f}%")
            if args.verbose:
                for line in kept[row]:
                    print(f"      {line}")
    print(f"{time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
