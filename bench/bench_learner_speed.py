"""Speed of the model-based learner: online updates up to 1,000 demonstrations, question choice.

    .venv/bin/python bench/bench_learner_speed.py

Demonstrations from ``bench_learn.hidden_world`` (20 conditions, 20 actions, 10% external
events). Every update of ``teach.learn.learner.Learner`` is timed, and beside it the
specialization learner's on the same demonstrations; then the next situation question is
chosen after all 1,000, and after 300 demonstrations of worlds of 5, 8, 20, 30 and 50 conditions.
Targets (issues 10 and 20): one update at 1,000 demonstrations <= 10 ms, a question <= 100 ms
at every size. Printed as measured/target ratios (below 1 is within).
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from bench_learn import hidden_world  # noqa: E402

from teach.learn.inquiry import next_question  # noqa: E402
from teach.learn.learner import Learner  # noqa: E402
from teach.learn.order import action_order  # noqa: E402
from teach.learn.specialize import Specializer  # noqa: E402

UPDATE_TARGET_MS = 10.0
QUESTION_TARGET_MS = 100.0
DEMOS = 1000
SIZES, SIZE_DEMOS = (5, 8, 20, 30, 50), 300


def main() -> None:
    domain, demos = hidden_world(20, 20, DEMOS, seed=7)
    learner = Learner(domain)
    times = []
    for demo in demos:
        start = time.perf_counter()
        learner.update(demo)
        times.append(1000 * (time.perf_counter() - start))
    specializer = Specializer(domain, action_order(domain, demos))
    theirs = []
    for demo in demos:
        start = time.perf_counter()
        specializer.update(demo)
        theirs.append(1000 * (time.perf_counter() - start))
    late = times[-100:]
    start = time.perf_counter()
    question = next_question(learner)
    question_ms = 1000 * (time.perf_counter() - start)
    print(f"{DEMOS} demonstrations, 20 conditions, 20 actions")
    print(f"update, last 100: median {statistics.median(late):.2f} ms, worst {max(late):.2f} ms "
          f"(worst/target {max(late) / UPDATE_TARGET_MS:.2f}); all: median {statistics.median(times):.2f} ms, "
          f"worst {max(times):.2f} ms")
    print(f"beside it, specialization: median {statistics.median(theirs[-100:]):.2f} ms, "
          f"worst {max(theirs[-100:]):.2f} ms (last 100)")
    print(f"situations kept: {len(learner.situations)}, conflicts: {len(learner.conflicts)}")
    print(f"next question: {question_ms:.1f} ms (ratio {question_ms / QUESTION_TARGET_MS:.2f}), "
          f"{question.kind if question else 'none left'}")
    for conditions in SIZES:
        domain, demos = hidden_world(conditions, 20, SIZE_DEMOS, seed=7)
        learner = Learner(domain)
        for demo in demos:
            learner.update(demo)
        start = time.perf_counter()
        question = next_question(learner)
        question_ms = 1000 * (time.perf_counter() - start)
        print(f"next question, {conditions} conditions, {SIZE_DEMOS} demonstrations: {question_ms:.1f} ms "
              f"(ratio {question_ms / QUESTION_TARGET_MS:.2f}), {question.kind if question else 'none left'}")


if __name__ == "__main__":
    main()
