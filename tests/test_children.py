"""Child processes never outlive teach: a time limit ends the child's whole group, and a child
is ended by the kernel when teach dies, even by SIGKILL (issue 23: a ``rerun rrd verify`` on a
FIFO outlived teach by fifty minutes and kept the session's lock)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from conftest import ROOT

from teach.children import run_child


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f"/proc/{pid}/stat") as stat:  # a zombie has ended, its parent has only not reaped it
        return stat.read().rsplit(")", 1)[1].split()[0] != "Z"


def _gone(pid: int) -> bool:
    """Whether ``pid`` has ended, waiting a while for the kernel to deliver a kill."""
    for _ in range(1200):
        if not _alive(pid):
            return True
        time.sleep(0.05)
    return False


def test_a_child_past_its_time_is_ended_with_its_whole_group(tmp_path: Path) -> None:
    pids = tmp_path / "pids"
    done = run_child(["sh", "-c", f"sleep 300 & echo $! > {pids}; sleep 300"], timeout=1)
    assert done.returncode == -signal.SIGKILL
    assert _gone(int(pids.read_text()))  # the grandchild in the same group too


def test_a_child_gives_its_output_and_status() -> None:
    done = run_child([sys.executable, "-c", "import sys; print('out'); print('err', file=sys.stderr); sys.exit(3)"])
    assert (done.returncode, done.stdout, done.stderr) == (3, "out\n", "err\n")


def test_a_child_ends_when_teach_is_killed(tmp_path: Path) -> None:
    pids = tmp_path / "pid"
    parent = subprocess.Popen([sys.executable, "-c", "import sys; from teach.children import run_child; "
                               f"run_child(['sh', '-c', 'echo $$ > {pids}; exec sleep 300'])"],
                              env={**os.environ, "PYTHONPATH": str(ROOT)})
    try:
        while not pids.exists() or not pids.read_text().strip():
            assert parent.poll() is None
            time.sleep(0.05)
        child = int(pids.read_text())
        assert _alive(child)
        parent.send_signal(signal.SIGKILL)
    finally:
        parent.wait()
    assert _gone(child)
