"""Teaching from few demonstrations (the headline benchmark) and the session's learning latency.

    .venv/bin/python bench/bench_teach.py

1. Learn from Δ4 (2 demonstrations) and from Δ3 (8), ask 0..5 questions answered by an oracle
   holding the reference behaviour that generated Δ2/Δ5, replay Δ5 (43) strictly and leniently.
2. In a live session (symbolic world, the same code path as the terminal), the time from the
   teacher's "done" to the updated tree being shown, over 30 demonstrations.
"""

from __future__ import annotations

import io
import random
import statistics
import sys
import tempfile
import time
from contextlib import redirect_stdout
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from teach.bt.tick import compile_tree  # noqa: E402
from teach.bt.xml import read_tree  # noqa: E402
from teach.cli import main  # noqa: E402
from teach.domain import load_domain  # noqa: E402
from teach.session.machine import SessionManager  # noqa: E402
from teach.session.settings import Settings, WorldKind  # noqa: E402
from teach.world.symbolic import SymbolicWorld  # noqa: E402

BALL = ROOT / "demos" / "ball"
REFERENCE = BALL / "reference" / "table61.xml"


def bench_teach(train: str, questions: int) -> tuple[int, int, int]:
    import json

    out = io.StringIO()
    with redirect_stdout(out):
        main(["bench-teach", str(BALL / train), str(BALL / "delta5"), "--oracle", str(REFERENCE),
              "--questions", str(questions), "--json"])
    result = json.loads(out.getvalue())
    return result["reproduced"], result["lenient"], len(result["questions"])


def latency(demos: int = 30) -> list[float]:
    domain = load_domain(BALL / "domain.toml")
    reference = compile_tree(read_tree(REFERENCE), domain.condition_names)
    rng = random.Random(1)
    times: list[float] = []
    with tempfile.TemporaryDirectory() as scratch:
        settings = Settings("bench", questions=0, world=WorldKind.SYMBOLIC, base=Path(scratch), record=False)
        session = SessionManager(settings, domain, SymbolicWorld(domain))
        shown: list[float] = []
        session.live = lambda reply: shown.append(time.perf_counter()) if reply.kind == "tree" else None
        for _ in range(demos):
            state = tuple(rng.random() < 0.5 for _ in domain.conditions[:-1]) + (False,)
            session.world.arrange(state)
            actions = []
            while True:
                status, action = reference(session.world.state())
                if action is None:
                    break
                actions.append(domain.action(action).label("en"))
                session.world.act(action)
            if not actions:
                continue
            session.world.arrange(state)
            session.handle(", ".join(actions))
            start = time.perf_counter()
            shown.clear()
            session.handle("done")
            times.append((shown[0] - start) * 1000)
    return times


def run() -> None:
    print("Teaching from few demonstrations, tested on Δ5 (43 demonstrations), oracle = Table 6.1 behaviour")
    print(f"{'train':<8}{'budget':>7}{'asked':>7}{'strict':>9}{'lenient':>9}")
    for train in ("delta4", "delta3"):
        for budget in range(6):
            strict, lenient, asked = bench_teach(train, budget)
            print(f"{train:<8}{budget:>7}{asked:>7}{strict:>6}/43{lenient:>6}/43")
    times = latency()
    print(f"end of demonstration -> tree on screen over {len(times)} demonstrations: "
          f"median {statistics.median(times):.1f} ms, max {max(times):.1f} ms (target < 50 ms)")


if __name__ == "__main__":
    run()
