"""Locks with real second processes: one holder, a one-line refusal naming it, stale locks of
killed holders explained and taken over, nothing left behind, and the commands that take them."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from conftest import ROOT

from teach.lock import LockedError, ResourceLock, output_lock, session_lock, set_lock

HOLDER = textwrap.dedent("""
    import sys
    from pathlib import Path
    from teach.lock import ResourceLock
    lock = ResourceLock(sys.argv[1], "session quickstart", folder=Path(sys.argv[2]) if sys.argv[2] else None)
    with lock:
        print("held", flush=True)
        sys.stdin.read()  # until the test closes our stdin (or kills us)
""")


@contextmanager
def holder(key: str, folder: Path | None) -> Iterator[subprocess.Popen[str]]:
    """A second process holding the lock ``key`` until the block ends."""
    process = subprocess.Popen([sys.executable, "-c", HOLDER, key, str(folder or "")], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, env={"PYTHONPATH": str(ROOT)})
    assert process.stdout is not None and process.stdout.readline() == "held\n"
    try:
        yield process
    finally:
        if process.poll() is None:
            assert process.stdin is not None
            process.stdin.close()
        process.wait()


def test_a_second_holder_is_told_which_process_has_it(tmp_path: Path) -> None:
    with holder("session:x", tmp_path) as other:
        lock = ResourceLock("session:x", "session quickstart", "recordings/quickstart.journal.json", folder=tmp_path)
        with pytest.raises(LockedError) as caught:
            lock.acquire()
        message = str(caught.value)
        assert message.startswith("recordings/quickstart.journal.json: session quickstart is open in process "
                                  f"{other.pid} (started ")
        assert message.endswith("); close it there first")
        assert "\n" not in message and not lock.held
    with lock:  # released when its holder ends
        assert lock.held


def test_release_leaves_no_lock_file_and_the_next_holder_sees_no_stale_lock(tmp_path: Path) -> None:
    notes: list[str] = []
    with holder("set:a", tmp_path):
        pass
    assert list(tmp_path.iterdir()) == []
    lock = ResourceLock("set:a", "the set", folder=tmp_path, note=notes.append)
    with lock:
        assert lock.stale is None and notes == []
        assert len(list(tmp_path.iterdir())) == 1
    assert list(tmp_path.iterdir()) == []


def test_a_killed_holder_leaves_a_stale_lock_that_is_explained_and_taken_over(tmp_path: Path) -> None:
    notes: list[str] = []
    with holder("session:k", tmp_path) as other:
        other.send_signal(signal.SIGKILL)
        other.wait()
        lock = ResourceLock("session:k", "session keep", folder=tmp_path, note=notes.append)
        with lock:
            assert lock.stale is not None and lock.stale.pid == other.pid
    assert len(notes) == 1
    assert notes[0].startswith(f"session keep was left open by process {other.pid} (started ")
    assert notes[0].endswith("which no longer runs; taking it over")


def test_one_process_cannot_take_the_same_lock_twice(tmp_path: Path) -> None:
    first = ResourceLock("output:/x", "x", folder=tmp_path)
    with first, pytest.raises(LockedError, match=f"process {os.getpid()}"):
        ResourceLock("output:/x", "x", folder=tmp_path).acquire()


def test_locks_name_their_resources(tmp_path: Path) -> None:
    assert session_lock(tmp_path, "quickstart", tmp_path).what == "session quickstart"
    assert set_lock(tmp_path / "demos" / "ball", tmp_path).busy == "is being recorded into by"
    same = output_lock(tmp_path / "out.xml", tmp_path).file
    assert output_lock(tmp_path / "." / "out.xml", tmp_path).file == same
    assert output_lock(tmp_path / "other.xml", tmp_path).file != same


def run_teach(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "teach.cli", *args], cwd=cwd, capture_output=True, text=True,
                          env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})


@pytest.mark.parametrize(("command", "key_of"), [
    (("learn", str(ROOT / "demos/ball/delta1"), "-o", "out.xml"), lambda cwd: output_lock(cwd / "out.xml")),
    (("prune", str(ROOT / "demos/ball/reference/table61.xml"), "-o", "out.xml"),
     lambda cwd: output_lock(cwd / "out.xml")),
    (("dot", str(ROOT / "demos/ball/reference/table61.xml"), "-o", "out.xml"),
     lambda cwd: output_lock(cwd / "out.xml")),
    (("learn", str(ROOT / "demos/ball/delta1"), "-o", "l.xml", "--generations", "gens"),
     lambda cwd: output_lock(cwd / "gens")),
    (("record", "--set", "ball/sim", "FindBall"), lambda cwd: set_lock(cwd / "demos" / "ball" / "sim")),
])
def test_commands_refuse_an_output_another_process_writes(tmp_path: Path, command: tuple[str, ...], key_of) -> None:  # type: ignore[no-untyped-def]
    with holder(key_of(tmp_path).key, None) as other:
        done = run_teach(*command, cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert f" by process {other.pid} (started " in done.stderr and "wait until it has finished" in done.stderr
    assert done.stderr.count("\n") == 1 and "Traceback" not in done.stderr
    assert list(tmp_path.iterdir()) == []  # nothing written, not even the first output


def test_learn_writes_nothing_when_its_second_output_is_unusable(tmp_path: Path) -> None:
    (tmp_path / "gens").write_text("a file, not a folder")
    done = run_teach("learn", str(ROOT / "demos/ball/delta1"), "-o", "out/l.xml", "--generations", "gens/sub",
                     cwd=tmp_path)
    assert done.returncode == 2 and done.stderr == "teach: gens/sub: gens is not a folder\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["gens"]


def test_two_learns_racing_for_one_output_leave_one_whole_tree(tmp_path: Path) -> None:
    command = [sys.executable, "-m", "teach.cli", "learn", str(ROOT / "demos/ball/delta1"), "-o", "out.xml"]
    racers = [subprocess.Popen(command, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}) for _ in range(2)]
    results = [(racer.wait(), racer.communicate()[1]) for racer in racers]
    # whichever order the scheduler picks: each one wrote the tree or was refused by the other's lock
    for status, stderr in results:
        assert (status, stderr) == (0, "") or (status == 2 and "is being written by process" in stderr), stderr
    solo = tmp_path / "solo"
    solo.mkdir()
    subprocess.run([*command[:-1], "solo.xml"], cwd=solo, check=True, capture_output=True,
                   env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert (tmp_path / "out.xml").read_bytes() == (solo / "solo.xml").read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.xml", "solo"]
