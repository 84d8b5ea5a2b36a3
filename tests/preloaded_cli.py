"""Start ``teach`` command lines in milliseconds, each in its own process that may be killed.

    python tests/preloaded_cli.py     # reads jobs on standard input, one JSON object a line

A fresh ``python -m teach.cli`` pays 2.5-4 s of imports (numpy, MuJoCo, rich, prompt_toolkit)
before its first line; the kill test starts twenty of them. This process imports all that once
and forks a child per job: ``{"argv": [...], "out": FIFO, "err": FILE}`` runs ``teach.cli.main``
with standard output (line by line, unbuffered) to the named FIFO and standard error to
``err``, and the child's pid is written back as ``{"pid": N}``. The child is a real process
running the same code from the same imports: SIGKILL ends it as it would end a fresh one, and
the reader sees its output end. Nothing here opens a GL context or a MuJoCo model (each child
makes its own after the fork). ``PreloadedCli`` is the test's side of it.
"""

from __future__ import annotations

import importlib
import io
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
from pathlib import Path
from typing import IO

from cli_batch import run_in_child

ROOT = Path(__file__).resolve().parent.parent
PRELOADED = ("teach.cli", "teach.commands.replay", "teach.commands.session", "teach.session.setup",
             "teach.session.machine", "teach.terminal.scripted", "teach.terminal.app", "teach.dialogue.oracle",
             "teach.dialogue.model_repair", "teach.dialogue.script", "teach.world.mujoco_world", "teach.sim.world",
             "teach.sim.executor", "teach.world.symbolic", "teach.bt.xml", "rich.console")
ENVIRONMENT = {"PYTHONUNBUFFERED": "1", "COLUMNS": "200"}
"""What every job's process sees, as the kill test's fresh processes did."""


def _child(job: dict) -> None:
    """Run one job; never returns."""
    def prepare() -> None:
        stdin = os.open(os.devnull, os.O_RDONLY)
        out = os.open(job["out"], os.O_WRONLY)
        err = os.open(job.get("err") or os.devnull, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
        for fd, target in ((stdin, 0), (out, 1), (err, 2)):
            os.dup2(fd, target)
            os.close(fd)
        sys.stdin = open(0, encoding="utf-8", closefd=False)  # noqa: SIM115 - the process's own, for its life
        sys.stdout = io.TextIOWrapper(open(1, "wb", buffering=0, closefd=False), encoding="utf-8",  # noqa: SIM115
                                      line_buffering=True, write_through=True)
        sys.stderr = io.TextIOWrapper(open(2, "wb", buffering=0, closefd=False), encoding="utf-8",  # noqa: SIM115
                                      line_buffering=True, write_through=True)

    run_in_child(prepare, job["argv"])


def serve() -> int:
    os.environ.update(ENVIRONMENT)
    for module in PRELOADED:
        importlib.import_module(module)
    print(json.dumps({"ready": True}), flush=True)
    for line in sys.stdin:
        _reap(block=False)  # ended children, reaped only now: a pid the test may still kill is never reused
        job = json.loads(line)
        pid = os.fork()
        if pid == 0:
            _child(job)
        print(json.dumps({"pid": pid}), flush=True)
    _reap(block=True)
    return 0


def _reap(block: bool) -> None:
    """Collect ended children (all of them, waiting, when ``block``)."""
    while True:
        try:
            pid, _ = os.waitpid(-1, 0 if block else os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return


class Child:
    """One forked command line: its pid and its standard output, read line by line."""

    def __init__(self, pid: int, stdout: IO[str]):
        self.pid, self.stdout = pid, stdout

    def kill(self) -> None:
        """SIGKILL the child (nothing happens when it has ended already)."""
        try:
            os.kill(self.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


class PreloadedCli:
    """The test's side: one preloaded parent, a child per ``start``. Close it when done."""

    def __init__(self) -> None:
        self._folder = tempfile.TemporaryDirectory(prefix="teach-preloaded-")
        self._count = 0
        self._lock = threading.Lock()
        self._parent = subprocess.Popen([sys.executable, __file__], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                        text=True, cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)})
        assert self._parent.stdout is not None
        assert json.loads(self._parent.stdout.readline()) == {"ready": True}

    def start(self, argv: list[str], stderr: Path | None = None) -> Child:
        """Fork a child running ``teach`` with ``argv``; its output is read from ``Child.stdout``."""
        assert self._parent.stdin is not None and self._parent.stdout is not None
        with self._lock:
            self._count += 1
            fifo = Path(self._folder.name) / f"out-{self._count}"
            os.mkfifo(fifo)
            job = {"argv": argv, "out": str(fifo), "err": str(stderr) if stderr else ""}
            self._parent.stdin.write(json.dumps(job) + "\n")
            self._parent.stdin.flush()
            pid = json.loads(self._parent.stdout.readline())["pid"]
        stdout = open(fifo, encoding="utf-8")  # noqa: SIM115 - the caller reads it to its end
        fifo.unlink()
        return Child(pid, stdout)

    def close(self) -> None:
        assert self._parent.stdin is not None
        self._parent.stdin.close()
        self._parent.wait(timeout=60)
        self._folder.cleanup()


if __name__ == "__main__":
    sys.exit(serve())
