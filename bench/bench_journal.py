"""A session that stays fast as it grows: 'reset' at the end of 150 demonstrations against the start.

Example:
    .venv/bin/python bench/bench_journal.py [--demos 150] [--resets 15]

Two symbolic sessions (no questions, no recording) are taught 5 and ``--demos`` demonstrations
through ``SessionManager.handle``; then they take turns answering ``--resets`` 'reset N' lines,
each timed (median, wall and CPU), so the machine's load falls on both alike. Every line saves
the journal: appended and fsynced as one line per save, so its cost does not grow with the
session. Side by side in the same run, two sessions whose journal is rewritten whole on every
save (as before issue 20) show what the growth was.
Target (issue 20): end / start within noise (about 1.0) for the appending journal.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from teach.domain import load_domain  # noqa: E402
from teach.fsutil import atomic_write_text  # noqa: E402
from teach.session.journal import Journal  # noqa: E402
from teach.session.machine import SessionManager  # noqa: E402
from teach.session.settings import Settings, WorldKind  # noqa: E402
from teach.session.store import SessionStore  # noqa: E402
from teach.world.symbolic import SymbolicWorld  # noqa: E402

DOMAIN = Path(__file__).resolve().parent.parent / "demos" / "ball" / "domain.toml"
FIRST = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"
LATER = ["start BallFound", "go to the ball, grasp the ball, go to the bin, put the ball in the bin"]


class RewritingStore(SessionStore):
    """The journal saved as before issue 20: the whole file rewritten atomically on every save."""

    def save_journal(self, journal: Journal) -> None:
        atomic_write_text(self.journal_path, journal.snapshot_text())


def grown(base: Path, store: type[SessionStore], demos: int) -> SessionManager:
    """A symbolic session (no questions, no recording) taught ``demos`` demonstrations line by line."""
    domain = load_domain(DOMAIN)
    settings = Settings(f"grow-{demos}", questions=0, world=WorldKind.SYMBOLIC, base=base, record=False)
    manager = SessionManager(settings, domain, SymbolicWorld(domain))
    manager.store = store(base, settings.session, record=False)
    manager.store.prepare(domain)
    manager.greet()
    for number in range(1, demos + 1):
        for line in ([FIRST] if number == 1 else LATER) + ["done"]:
            manager.handle(line)
    return manager


def alternated_resets(sessions: list[SessionManager], count: int) -> list[tuple[float, float]]:
    """Median wall and CPU seconds of 'reset N' in each session, the sessions taking turns line by
    line, so the machine's load falls on all of them alike."""
    wall: list[list[float]] = [[] for _ in sessions]
    cpu: list[list[float]] = [[] for _ in sessions]
    for seed in range(count):
        for number, manager in enumerate(sessions):
            start, start_cpu = time.perf_counter(), time.process_time()
            manager.handle(f"reset {seed}")
            wall[number].append(time.perf_counter() - start)
            cpu[number].append(time.process_time() - start_cpu)
    return [(statistics.median(w), statistics.median(c)) for w, c in zip(wall, cpu, strict=True)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--demos", type=int, default=150)
    parser.add_argument("--resets", type=int, default=31)
    args = parser.parse_args()
    print(f"'reset' after 5 and after {args.demos} demonstrations, median of {args.resets} taking turns "
          "(symbolic world; wall time includes each save's fsync)")
    with tempfile.TemporaryDirectory() as folder:
        base = Path(folder)
        kinds = (("appended (now)", SessionStore), ("rewritten whole (before)", RewritingStore))
        sessions = [grown(base / name.split()[0], store, demos) for name, store in kinds
                    for demos in (5, args.demos)]
        medians = alternated_resets(sessions, args.resets)
        for number, (name, _) in enumerate(kinds):
            (start, start_cpu), (end, end_cpu) = medians[2 * number], medians[2 * number + 1]
            size = sessions[2 * number + 1].store.journal_path.stat().st_size
            print(f"  journal {name:25s}: start {start * 1000:6.2f} ms, end {end * 1000:6.2f} ms, "
                  f"end/start {end / start:5.2f} (CPU {start_cpu * 1000:5.2f} / {end_cpu * 1000:5.2f} ms: "
                  f"{end_cpu / start_cpu:5.2f}); journal at the end {size / 1024:.0f} KiB")
        for manager in sessions:
            manager.close()


if __name__ == "__main__":
    main()
