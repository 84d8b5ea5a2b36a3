"""Run many ``teach`` command lines quickly, each in its own process.

    python tests/cli_batch.py PARALLEL < jobs.json > results.json

jobs.json is a list of ``{"argv": [...], "cwd": DIR, "stdout": FILE, "stderr": FILE, "timeout": S}``.
The libraries every command needs are imported once here; each job then runs ``teach.cli.main``
in a forked child with its own working folder, standard streams and an alarm, so a job that
hangs is killed by SIGALRM instead of stopping the batch. A fresh interpreter per job would take
about 0.2 s of start-up alone; a fork takes milliseconds and runs the same code.
Results, in job order: ``{"status": exit status, or minus the signal that ended it, "seconds": wall time}``.
"""

from __future__ import annotations

import gc
import importlib
import json
import os
import pkgutil
import signal
import sys
import time
import traceback
from collections.abc import Callable
from typing import NoReturn

PRELOADED = ("rich.console", "rich.table", "rerun", "rerun.chunk")
"""Libraries some commands import only when they need them (reading a recording: rerun's reader,
about a second); every module of teach is imported too."""


def preload() -> None:
    """Import what the commands use, once, so no job pays for it."""
    import teach

    for module in PRELOADED:
        importlib.import_module(module)
    for found in pkgutil.walk_packages(teach.__path__, "teach."):
        importlib.import_module(found.name)


def _child(job: dict) -> None:
    """Run one job; never returns."""
    def prepare() -> None:
        os.chdir(job["cwd"])
        for fd, name, flags in ((0, os.devnull, os.O_RDONLY), (1, job["stdout"], os.O_WRONLY | os.O_CREAT),
                                (2, job["stderr"], os.O_WRONLY | os.O_CREAT)):
            opened = os.open(name, flags, 0o644)
            os.dup2(opened, fd)
            os.close(opened)
        signal.alarm(int(job["timeout"]))

    run_in_child(prepare, job["argv"])


def run_in_child(prepare: Callable[[], None], argv: list[str]) -> NoReturn:
    """In a forked child: ``prepare`` its files and limits, run ``teach.cli.main(argv)``, and end
    the process with its exit status (argparse's usage errors as theirs; anything the command line
    should never let through shown as a traceback, status 1), output flushed."""
    code = 1
    try:
        prepare()
        from teach.cli import main

        code = main(argv)
    except SystemExit as done:  # argparse's usage errors
        code = done.code if isinstance(done.code, int) else (0 if done.code is None else 1)
    except BaseException:  # what the command line should never let through: shown as a traceback
        traceback.print_exc()
        code = 1
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        finally:
            os._exit(code)


def main(argv: list[str]) -> int:
    parallel = int(argv[0]) if argv else 2
    jobs = json.load(sys.stdin)
    preload()
    gc.freeze()  # the collector then never walks (and so never copies) the parent's objects in a child
    results: list[dict | None] = [None] * len(jobs)
    running: dict[int, tuple[int, float]] = {}
    waiting = list(range(len(jobs)))[::-1]
    while waiting or running:
        while waiting and len(running) < parallel:
            index = waiting.pop()
            pid = os.fork()
            if pid == 0:
                _child(jobs[index])
            running[pid] = index, time.perf_counter()
        pid, status = os.wait()
        index, started = running.pop(pid)
        results[index] = {"status": os.waitstatus_to_exitcode(status), "seconds": time.perf_counter() - started}
    json.dump(results, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
