"""How much of a question-chooser comparison is the chooser, and how much the draw of its hypotheses?

    .venv/bin/python bench/bench_question_noise.py              # offsets 0-3 (about 2 minutes)
    .venv/bin/python bench/bench_question_noise.py --offsets 8

``teach.learn.safe_inquiry`` predicts answers under ``SAMPLES`` hypotheses drawn from a
``random.Random`` seeded by the session (the same session asks the same questions). Any change to
the chooser, even one that only draws one more number, changes every later draw, so a bench run
mixes the change with a new draw. Here the same chooser is run with the seed shifted by 0, 1, ...
(the module's ``random`` is replaced for the run; nothing in ``teach`` changes), on:

- the ball pairs of Δ2 showing all five actions, <= 5 questions: Δ5 mean and worst of 43
  (``bench/bench_ball_pairs.py``);
- snacks, 3 demonstrations + <= 5 questions, the safe learner: held-out mean (worst draw)
  (``bench/bench_snacks_draws.py``);
- strips-6x5, learner+5q, 3 seeds: reached after 2 and after 5 demonstrations
  (``bench/bench_safety.py --no-loop``).

A difference between two choosers smaller than the spread across offsets is not one.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import itertools
import random
import re
import statistics
import sys
import time
import types
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

import bench_ball_pairs  # noqa: E402
import bench_safety  # noqa: E402
import bench_snacks_draws  # noqa: E402

from teach.learn import safe_inquiry  # noqa: E402


def shifted(offset: int) -> types.SimpleNamespace:
    """A stand-in for the ``random`` module whose ``Random(seed)`` is ``random.Random(seed + offset)``."""
    return types.SimpleNamespace(Random=lambda seed: random.Random(seed + offset))


def ball(data: bench_ball_pairs.Ball) -> tuple[float, int]:
    pairs = [pair for pair in itertools.combinations(data.delta2, 2)
             if bench_ball_pairs.actions_shown(list(pair)) == {a.id for a in data.domain.actions}]
    last = [bench_ball_pairs.run_pair(data, pair)[-1].reproduced for pair in pairs]
    return statistics.mean(last), min(last)


def snacks() -> tuple[int, int]:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        bench_snacks_draws.main([])
    rows = re.findall(r"3 demonstrations, <= 5 questions:\s+(\d+)% \(\s*(\d+)%\)", out.getvalue())
    mean, worst = rows[-1]  # the safe learner's section comes last
    return int(mean), int(worst)


def strips() -> tuple[int, int]:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        bench_safety.main(["--no-loop", "--domains", "strips-6x5", "--seeds", "3"])
    reached = re.findall(r"strips-6x5\s+\d+\s+(\d+) learner\+5q\s+(\d+)%", out.getvalue())
    by_size = {int(size): int(share) for size, share in reached}
    return by_size[2], by_size[5]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--offsets", type=int, default=4, help="seed offsets 0..N-1 (default 4)")
    args = parser.parse_args(argv)
    started = time.perf_counter()
    data = bench_ball_pairs.load()
    original = safe_inquiry.random
    rows = []
    try:
        for offset in range(args.offsets):
            safe_inquiry.random = shifted(offset)  # type: ignore[assignment]
            row = (*ball(data), *snacks(), *strips())
            rows.append(row)
            print(f"offset {offset}: ball {row[0]:.2f} / {row[1]} of 43   snacks 3+5q {row[2]}% ({row[3]}%)   "
                  f"strips-6x5 learner+5q 2 / 5 demos {row[4]}% / {row[5]}%", flush=True)
    finally:
        safe_inquiry.random = original
    means = [statistics.mean(column) for column in zip(*rows, strict=True)]
    spans = [max(column) - min(column) for column in zip(*rows, strict=True)]
    print(f"mean:     ball {means[0]:.2f} / {means[1]:.1f}   snacks {means[2]:.1f}% ({means[3]:.1f}%)   "
          f"strips {means[4]:.1f}% / {means[5]:.1f}%")
    print(f"span:     ball {spans[0]:.2f} / {spans[1]}   snacks {spans[2]} ({spans[3]})   "
          f"strips {spans[4]} / {spans[5]}")
    print(f"{time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
