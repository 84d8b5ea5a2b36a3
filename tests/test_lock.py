"""Locks with real second processes: one holder, a one-line refusal naming it, stale locks of
killed holders explained and taken over, nothing left behind, the commands that take them, and
locks beside what they protect, so other users and other $TMPDIRs see them."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import textwrap
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
from conftest import ROOT

from teach.lock import LockedError, ResourceLock, output_lock, session_lock, set_lock

HOLDER = textwrap.dedent("""
    import sys
    from pathlib import Path
    from teach.lock import ResourceLock
    with ResourceLock(Path(sys.argv[1]), "session quickstart"):
        print("held", flush=True)
        sys.stdin.read()  # until the test closes our stdin (or kills us)
""")


@contextmanager
def holder(file: Path, **popen: Any) -> Iterator[subprocess.Popen[str]]:
    """A second process holding the lock file ``file`` until the block ends."""
    process = subprocess.Popen([sys.executable, "-c", HOLDER, str(file)], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, env={"PYTHONPATH": str(ROOT)}, **popen)
    assert process.stdout is not None and process.stdout.readline() == "held\n"
    try:
        yield process
    finally:
        if process.poll() is None:
            assert process.stdin is not None
            process.stdin.close()
        process.wait()


def test_a_second_holder_is_told_which_process_has_it(tmp_path: Path) -> None:
    with holder(tmp_path / ".x.teach-lock") as other:
        lock = ResourceLock(tmp_path / ".x.teach-lock", "session quickstart", "recordings/quickstart.journal.json")
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
    with holder(tmp_path / ".a.teach-lock"):
        pass
    assert list(tmp_path.iterdir()) == []
    lock = ResourceLock(tmp_path / ".a.teach-lock", "the set", note=notes.append)
    with lock:
        assert lock.stale is None and notes == []
        assert len(list(tmp_path.iterdir())) == 1
    assert list(tmp_path.iterdir()) == []


def test_a_killed_holder_leaves_a_stale_lock_that_is_explained_and_taken_over(tmp_path: Path) -> None:
    notes: list[str] = []
    with holder(tmp_path / ".k.teach-lock") as other:
        other.send_signal(signal.SIGKILL)
        other.wait()
        lock = ResourceLock(tmp_path / ".k.teach-lock", "session keep", note=notes.append)
        with lock:
            assert lock.stale is not None and lock.stale.pid == other.pid
    assert len(notes) == 1
    assert notes[0].startswith(f"session keep was left open by process {other.pid} (started ")
    assert notes[0].endswith("which no longer runs; taking it over")


def test_one_process_cannot_take_the_same_lock_twice(tmp_path: Path) -> None:
    first = ResourceLock(tmp_path / ".x.teach-lock", "x")
    with first, pytest.raises(LockedError, match=f"process {os.getpid()}"):
        ResourceLock(tmp_path / ".x.teach-lock", "x").acquire()


def test_locks_name_their_resources_and_lie_beside_them(tmp_path: Path) -> None:
    session = session_lock(tmp_path, "quickstart")
    assert session.what == "session quickstart"
    assert session.file == tmp_path.resolve() / "recordings" / ".quickstart.journal.json.teach-lock"
    assert set_lock(tmp_path / "demos" / "ball").busy == "is being recorded into by"
    assert set_lock(tmp_path / "demos" / "ball").file == tmp_path.resolve() / "demos" / ".ball.teach-lock"
    same = output_lock(tmp_path / "out.xml").file
    assert output_lock(tmp_path / "." / "out.xml").file == same
    assert output_lock(tmp_path / "other.xml").file != same
    (tmp_path / "link").symlink_to(tmp_path)
    assert output_lock(tmp_path / "link" / "out.xml").file == same  # one resource, one lock, however it is spelled


def test_a_folder_the_lock_created_goes_with_it(tmp_path: Path) -> None:
    """A session that fails to open leaves no recordings folder behind."""
    with session_lock(tmp_path / "new", "s"):
        assert (tmp_path / "new" / "recordings").is_dir()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(("folder_mode", "file_mode"), [(0o775, 0o664), (0o755, 0o644)])
def test_the_group_may_take_over_a_lock_when_it_may_write_the_folder(tmp_path: Path, folder_mode: int,
                                                                       file_mode: int) -> None:
    (tmp_path / "shared").mkdir()
    (tmp_path / "shared").chmod(folder_mode)
    with output_lock(tmp_path / "shared" / "out.xml") as lock:
        assert lock.file.stat().st_mode & 0o777 == file_mode


def test_different_tmpdirs_see_one_lock(tmp_path: Path) -> None:
    """A lock lives beside what it protects, not in $TMPDIR: a session held by a process with one
    $TMPDIR is refused to a process with another."""
    dialogue = tmp_path / "s.dialogue"
    dialogue.write_text("@world symbolic\nstate\n", encoding="utf-8")
    first, second = tmp_path / "tmp-a", tmp_path / "tmp-b"
    first.mkdir(), second.mkdir()
    script = textwrap.dedent("""
        import sys
        from teach.lock import session_lock
        with session_lock(sys.argv[1], "s"):
            print("held", flush=True)
            sys.stdin.read()
    """)
    process = subprocess.Popen([sys.executable, "-c", script, str(tmp_path)], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, env={"PYTHONPATH": str(ROOT), "TMPDIR": str(first)})
    assert process.stdout is not None and process.stdout.readline() == "held\n"
    try:
        done = subprocess.run([sys.executable, "-m", "teach.cli", "replay", str(dialogue), "--no-record",
                               "--base", str(tmp_path)], capture_output=True, text=True,
                              env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "TMPDIR": str(second)})
    finally:
        assert process.stdin is not None
        process.stdin.close()
        process.wait()
    assert done.returncode == 2 and f"session s is open in process {process.pid} (started " in done.stderr
    assert done.stderr.count("\n") == 1 and not (tmp_path / "demos").exists()


NOBODY = 65534


def _forked(uid: int, work: Callable[[], str], hold: bool = False) -> tuple[int, int]:
    """A child process (forked: its interpreter is already loaded) that becomes ``uid`` and runs
    ``work``, writing what it returns to the pipe read by the parent; with ``hold`` it then waits
    for the parent to kill it. The child's pid and the pipe's reading end."""
    reading, writing = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover (the child)
        try:
            os.setgid(uid)
            os.setuid(uid)
            os.write(writing, work().encode() + b"\n")
            while hold:
                time.sleep(1)
        except BaseException as error:
            os.write(writing, f"{type(error).__name__}: {error}\n".encode())
        finally:
            os._exit(0)
    os.close(writing)
    return pid, reading


def _said(reading: int) -> str:
    with os.fdopen(reading) as pipe:
        return pipe.readline().strip()


@pytest.mark.skipif(os.getuid() != 0, reason="needs root to become another user (uid 65534) in a second process")
def test_another_users_lock_is_seen_named_and_taken_over_when_stale() -> None:
    """As root, in a shared folder: a process of uid 65534 holds a session, root is refused in one
    line naming that user and takes the lock over (explained) once it is killed; and uid 65534
    takes over a stale lock root left, which it may read but not write."""
    import pwd

    shared = Path(tempfile.mkdtemp(prefix="teach-shared-"))  # pytest's tmp_path is root's alone
    try:
        shared.chmod(0o777)
        (shared / "recordings").mkdir()
        (shared / "recordings").chmod(0o777)  # a folder the group (here: everyone) may write
        try:
            user = pwd.getpwuid(NOBODY).pw_name
        except KeyError:
            user = str(NOBODY)
        pid, reading = _forked(NOBODY, lambda: str(session_lock(shared, "s").acquire().held), hold=True)
        try:
            assert _said(reading) == "True"
            lock = session_lock(shared, "s")
            with pytest.raises(LockedError) as caught:
                lock.acquire()
            assert f"session s is open in process {pid} of user {user} (started " in str(caught.value)
            assert lock.file.stat().st_uid == NOBODY and lock.file.stat().st_mode & 0o777 == 0o664
        finally:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        notes: list[str] = []
        lock.note = notes.append
        with lock:
            assert lock.stale is not None and lock.stale.uid == NOBODY
        assert len(notes) == 1 and f"left open by process {pid} of user {user} (started " in notes[0]
        # root's stale note, owned by root and not writable by others: replaced by uid 65534
        dead = session_lock(shared, "t").acquire()
        os.close(dead._fd)  # type: ignore[arg-type]  # as a kill would: the note stays, the flock goes
        dead.file.chmod(0o644)
        pid, reading = _forked(NOBODY, lambda: str(session_lock(shared, "t").acquire().stale))
        os.waitpid(pid, 0)
        assert f"Holder(pid={os.getpid()}" in _said(reading)
    finally:
        shutil.rmtree(shared)
