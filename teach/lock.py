"""One writer per resource: a session, a demonstration set, an output file.

A lock is a small file holding the holder's pid and start time, locked with ``fcntl.flock``:
the kernel drops the flock when its holder dies, so a ``kill -9`` never leaves a false lock;
the file left behind is only the stale note of who held it, which the next holder explains
and takes over. A second holder gets one line naming the process that has it.

Lock files live in a per-user folder outside the project (``$TMPDIR/teach-locks-<uid>/``),
named after the resource's absolute path, so taking a lock never changes the project's
folders and a command that fails leaves nothing behind.
"""

from __future__ import annotations

import contextlib
import fcntl
import hashlib
import json
import os
import re
import stat
import sys
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType

from teach.errors import TeachError


class LockedError(TeachError):
    """The resource is held by another running process."""


@dataclass(frozen=True)
class Holder:
    """Who holds (or last held) a lock."""

    pid: int
    started: float

    @property
    def clock(self) -> str:
        """The start time as the holder's user saw it (local HH:MM, with the date when not today)."""
        then = time.localtime(self.started)
        if time.strftime("%Y-%m-%d", then) == time.strftime("%Y-%m-%d"):
            return time.strftime("%H:%M", then)
        return time.strftime("%Y-%m-%d %H:%M", then)


def default_folder() -> Path:
    return Path(tempfile.gettempdir()) / f"teach-locks-{os.getuid()}"


def _note(message: str) -> None:
    print(f"teach: note: {message}", file=sys.stderr)


class ResourceLock:
    """An exclusive, non-blocking lock on one resource, usable as a context manager.

    ``what`` names the resource in messages ("session quickstart"), ``busy`` says what the
    holder does with it ("is open in"), ``advice`` what to do ("close it there first").
    ``stale`` is set when the lock was taken over from a holder that no longer runs."""

    def __init__(self, key: str, what: str, path: str | Path | None = None, busy: str = "is open in",
                 advice: str = "close it there first", folder: Path | None = None,
                 note: Callable[[str], None] = _note):
        self.key, self.what, self.path = key, what, path
        self.busy, self.advice, self.note = busy, advice, note
        readable = re.sub(r"[^A-Za-z0-9_.-]+", "_", key)[-60:].strip("_.") or "lock"
        digest = hashlib.sha256(key.encode("utf-8", "surrogateescape")).hexdigest()[:16]
        self.folder = folder or default_folder()
        self.file = self.folder / f"{readable}-{digest}.lock"
        self.stale: Holder | None = None
        self._fd: int | None = None

    def acquire(self) -> ResourceLock:
        """Take the lock or raise ``LockedError`` naming its holder; never waits."""
        if self._fd is not None:
            raise RuntimeError(f"{self.what}: this lock is already held by this object")
        self._ensure_folder()
        while True:
            try:
                fd = os.open(self.file, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW, 0o600)
            except OSError as exc:
                raise TeachError(f"cannot lock {self.what}: {exc.strerror} ({self.file})", self.path) from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = _read_holder(fd)
                os.close(fd)
                who = f"process {holder.pid} (started {holder.clock})" if holder else "another process"
                raise LockedError(f"{self.what} {self.busy} {who}; {self.advice}", self.path) from None
            if not _same_file(fd, self.file):  # the previous holder removed it after we opened it
                os.close(fd)
                continue
            break
        previous = _read_holder(fd)
        if previous is not None and previous.pid != os.getpid():
            self.stale = previous
            state = "no longer runs" if not _running(previous.pid) else "no longer holds it"
            self.note(f"{self.what} was left open by process {previous.pid} (started {previous.clock}), "
                      f"which {state}; taking it over")
        os.ftruncate(fd, 0)
        os.pwrite(fd, (json.dumps({"pid": os.getpid(), "started": time.time(), "key": self.key}) + "\n").encode(),
                  0)
        self._fd = fd
        return self

    def release(self) -> None:
        """Give the lock up and remove its file (while still holding it, so no one else's is removed)."""
        if self._fd is None:
            return
        with contextlib.suppress(OSError):
            if _same_file(self._fd, self.file):
                os.unlink(self.file)
        os.close(self._fd)
        self._fd = None

    @property
    def held(self) -> bool:
        return self._fd is not None

    def __enter__(self) -> ResourceLock:
        return self.acquire()

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.release()

    def _ensure_folder(self) -> None:
        """The lock folder must be ours and private: anyone could create one in a shared /tmp."""
        try:
            self.folder.mkdir(mode=0o700, parents=True, exist_ok=True)
            info = os.lstat(self.folder)
        except OSError as exc:
            raise TeachError(f"cannot lock {self.what}: {exc.strerror} ({self.folder})", self.path) from None
        if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid():
            raise TeachError(f"cannot lock {self.what}: {self.folder} is not a folder of this user's", self.path)


def _same_file(fd: int, path: Path) -> bool:
    try:
        on_disk = os.stat(path, follow_symlinks=False)
    except FileNotFoundError:
        return False
    opened = os.fstat(fd)
    return (on_disk.st_dev, on_disk.st_ino) == (opened.st_dev, opened.st_ino)


def _read_holder(fd: int) -> Holder | None:
    """The pid and start time written in a lock file, or None when it holds nothing readable."""
    try:
        data = json.loads(os.pread(fd, 4096, 0) or b"null")
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict):
        return None
    pid, started = data.get("pid"), data.get("started")
    if isinstance(pid, bool) or not isinstance(pid, int) or pid <= 0 or not isinstance(started, (int, float)):
        return None
    return Holder(pid, float(started))


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _key_path(path: str | Path) -> str:
    """A path as a lock key: absolute, with symbolic links in its existing part resolved."""
    return str(Path(os.path.abspath(path)).resolve(strict=False))


def session_lock(base: str | Path, session: str, folder: Path | None = None) -> ResourceLock:
    """The lock of a teaching session: one session, one process."""
    where = Path(base) / "recordings" / f"{session}.journal.json"
    return ResourceLock(f"session:{_key_path(Path(base) / 'recordings')}/{session}", f"session {session}", where,
                        folder=folder)


def set_lock(folder_of_set: str | Path, folder: Path | None = None) -> ResourceLock:
    """The lock of a demonstration set that demonstrations are recorded into."""
    return ResourceLock(f"set:{_key_path(folder_of_set)}", "this demonstration set", folder_of_set,
                        busy="is being recorded into by", advice="wait until it has finished", folder=folder)


def output_lock(path: str | Path, folder: Path | None = None) -> ResourceLock:
    """The lock of an output file or folder a command writes."""
    return ResourceLock(f"output:{_key_path(path)}", "this output", path, busy="is being written by",
                        advice="wait until it has finished", folder=folder)


@contextlib.contextmanager
def holding(*locks: ResourceLock) -> Iterator[None]:
    """Hold all ``locks`` (taken in order; all released, in reverse, however the block ends)."""
    with contextlib.ExitStack() as stack:
        for lock in locks:
            stack.enter_context(lock)
        yield


Output = tuple[str, Path]
"""An output a command writes: ("file", path), ("folder", path) or ("set", demonstration set folder)."""


@contextlib.contextmanager
def claim_outputs(outputs: Sequence[Output], folder: Path | None = None) -> Iterator[None]:
    """Check every output a command will write before it writes any (so a bad second output
    leaves the first unwritten), then hold a lock on each while the command runs."""
    from teach.fsutil import check_output, check_output_folder

    seen: set[str] = set()
    for kind, path in outputs:
        if _key_path(path) in seen:
            raise TeachError("is given as two outputs of one command: name two different paths", path)
        seen.add(_key_path(path))
        if kind == "file":
            check_output(path)
        else:
            check_output_folder(path)
    with holding(*(set_lock(path, folder) if kind == "set" else output_lock(path, folder)
                   for kind, path in outputs)):
        yield
