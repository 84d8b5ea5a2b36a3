"""Child processes that never outlive teach: the one way teach runs another program and waits.

A ``rerun rrd verify`` left running on a FIFO once outlived teach by fifty minutes and kept
the session's lock. ``run_child`` gives every child a time limit, its own process group
(ended whole on the limit, on an error, on Ctrl-C), standard input from /dev/null, and on
Linux asks the kernel to end it when teach itself ends, however that happens (SIGKILL too).
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import signal
import subprocess
import sys
from collections.abc import Sequence

CHILD_SECONDS = 300.0
"""How long a child may run before it is ended (a merge of a long session's recording takes seconds)."""

_PR_SET_PDEATHSIG = 1


def _end_with_parent() -> None:
    """Run in the child before it starts the program: SIGKILL it when its parent dies."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)


def _end(process: subprocess.Popen[str]) -> None:
    """End the child's whole process group and reap it."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(process.pid, signal.SIGKILL)
    process.wait()


def run_child(argv: Sequence[str], timeout: float = CHILD_SECONDS) -> subprocess.CompletedProcess[str]:
    """Run ``argv`` to its end and give its output; a child that runs past ``timeout`` seconds is
    ended and reported with exit status -9, and one that teach stops waiting for (an error, an
    interrupt) is ended before the error goes on."""
    process = subprocess.Popen(list(argv), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, start_new_session=True,
                               preexec_fn=_end_with_parent)  # noqa: PLW1509 - only a prctl call, no locks
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        _end(process)
        return subprocess.CompletedProcess(list(argv), -signal.SIGKILL, "", f"ended after {timeout:g} s")
    except BaseException:
        _end(process)
        raise
    return subprocess.CompletedProcess(list(argv), process.returncode, out, err)
