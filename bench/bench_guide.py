"""Guiding speed: real-time factor with recording on, and what segmentation and recognition add.

Example:
    .venv/bin/python bench/bench_guide.py [--rounds 3]

A fixed guided script (drive, turn, lower, close on the ball, carry, put down: changes of
state included) runs in the MuJoCo world three ways, alternating, best of ``--rounds``:
- bare: the guide alone (physics, a state sample every 20 ms control step);
- recorded: plus a ``RerunLogger`` writing a recording (scene frames at 10 Hz, state, camera
  images at 2 Hz when MuJoCo can render offscreen), as a session records;
- recorded + segmented: plus the online ``Segmenter`` and recognition of every segment.
It prints the real-time factor (simulated over wall seconds) of each, and the cost per control
step of segmentation and recognition measured alone on the recorded samples (median of rounds),
also as a share of a recorded control step: the side-by-side difference of the last two runs
is far below this shared machine's noise.
Targets (issue 12): guiding at least at real time with recording on; segmentation and
recognition under 1 ms per control step.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from teach.domain import Domain, load_domain  # noqa: E402
from teach.learn.recognise import recognise  # noqa: E402
from teach.observe.hook import Observer  # noqa: E402
from teach.observe.rerun_writer import RerunLogger  # noqa: E402
from teach.sim.guide import Guide, Sample, parse_guide_line  # noqa: E402
from teach.sim.segment import Segmenter  # noqa: E402
from teach.sim.world import DOMAIN_FILE, World  # noqa: E402

SCRIPT = ["guide lift 0.26", "guide back 0.3", "guide turn 120", "guide turn -120", "guide forward 0.3",
          "guide lift 0", "guide close", "guide lift 0.26", "guide turn 90", "guide forward 0.4", "guide lift 0",
          "guide open", "guide lift 0.26", "guide back 0.5", "guide turn -45", "guide wait 1"]


def guided_run(observer: Observer | None, segmented: bool) -> tuple[float, float, list[Sample]]:
    """Wall and simulated seconds of the script from a fixed start, and the samples it made."""
    world = World(seed=0)
    world.arrange({"BallFound": True, "BallClose": True}, seed=8)
    segmenter = Segmenter()
    domain = world.domain

    def listen(sample: Sample) -> None:
        done = segmenter.add(sample)
        if done is not None:
            recognise(domain, done.before, done.after)

    guide = Guide(world, listen if segmented else None, observer)
    start, sim0 = time.perf_counter(), world.sim_time
    for number, line in enumerate(SCRIPT, 1):
        guide.run(parse_guide_line(line, "bench", number))
    return time.perf_counter() - start, world.sim_time - sim0, guide.samples


def segmentation_cost(samples: list[Sample], domain: Domain) -> tuple[float, int]:
    """Seconds per sample of segmenting and recognising a recorded stream, and its segments."""
    segmenter = Segmenter()
    start = time.perf_counter()
    for sample in samples:
        done = segmenter.add(sample)
        if done is not None:
            recognise(domain, done.before, done.after)
    return (time.perf_counter() - start) / len(samples), len(segmenter.segments)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    ratios: dict[str, list[float]] = {"bare": [], "recorded": [], "recorded + segmented": []}
    per_step: list[float] = []
    samples: list[Sample] = []
    domain = load_domain(DOMAIN_FILE)
    with tempfile.TemporaryDirectory() as folder:
        for round_ in range(args.rounds):
            for kind in ratios:
                logger = RerunLogger(Path(folder) / f"{kind[:3]}{round_}.rrd", "bench") if kind != "bare" else None
                wall, sim, samples = guided_run(logger, kind.endswith("segmented"))
                if logger is not None:
                    logger.close()
                ratios[kind].append(sim / wall)
            per_step.append(segmentation_cost(samples, domain)[0])
    steps, segments = len(samples), segmentation_cost(samples, domain)[1]
    print(f"guided script: {len(SCRIPT)} commands, {steps} control steps ({steps * 0.02:.1f} s simulated), "
          f"{segments} segments")
    for kind, values in ratios.items():
        print(f"real-time factor, {kind:<21} {max(values):6.1f}x   (best of {args.rounds})")
    step_wall = 0.02 / max(ratios["recorded"])
    cost = statistics.median(per_step)
    print(f"segmentation + recognition alone: {cost * 1e6:.1f} us per control step (target < 1000 us), "
          f"{100 * cost / step_wall:.2f}% of a recorded control step ({step_wall * 1e3:.2f} ms wall)")


if __name__ == "__main__":
    main()
