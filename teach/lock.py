"""One writer per resource: a session, a demonstration set, an output file.

A lock is a small file holding the holder's pid and start time, locked with ``fcntl.flock``:
the kernel drops the flock when its holder dies, so a ``kill -9`` never leaves a false lock;
the file left behind is only the stale note of who held it, which the next holder explains
and takes over. A second holder gets one line naming the process (and its user) that has it.

The lock file lies beside what it protects (``.NAME.teach-lock`` in the resource's folder,
gitignored), so everyone who works on those files sees it, whatever their user or ``$TMPDIR``;
it is readable and writable by the group when the folder is. Taking a lock creates nothing
else for good: a folder it had to create is removed again when the lock is released and the
folder is still empty, so a command that fails leaves no trace but, after a kill, the note.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import pwd
import stat
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType

from teach.errors import TeachError
from teach.protect import Input, Output, refuse_inputs

SUFFIX = ".teach-lock"

class LockedError(TeachError):
    """The resource is held by another running process."""


@dataclass(frozen=True)
class Holder:
    """Who holds (or last held) a lock."""

    pid: int
    started: float
    uid: int | None = None

    @property
    def clock(self) -> str:
        """The start time as the holder's user saw it (local HH:MM, with the date when not today)."""
        then = time.localtime(self.started)
        if time.strftime("%Y-%m-%d", then) == time.strftime("%Y-%m-%d"):
            return time.strftime("%H:%M", then)
        return time.strftime("%Y-%m-%d %H:%M", then)

    @property
    def who(self) -> str:
        """"process 123 (started 09:41)", with "of user NAME" when that is another user."""
        if self.uid is None or self.uid == os.getuid():
            return f"process {self.pid} (started {self.clock})"
        try:
            user = pwd.getpwuid(self.uid).pw_name
        except KeyError:
            user = str(self.uid)
        return f"process {self.pid} of user {user} (started {self.clock})"


def _note(message: str) -> None:
    print(f"teach: note: {message}", file=sys.stderr)


class ResourceLock:
    """An exclusive, non-blocking lock on one resource, usable as a context manager.

    ``file`` is the lock file, ``what`` names the resource in messages ("session quickstart"),
    ``busy`` says what the holder does with it ("is open in"), ``advice`` what to do ("close it
    there first"). ``stale`` is set when the lock was taken over from a holder that no longer runs."""

    def __init__(self, file: Path, what: str, path: str | Path | None = None, busy: str = "is open in",
                 advice: str = "close it there first", note: Callable[[str], None] = _note):
        self.file, self.what, self.path = file, what, path
        self.busy, self.advice, self.note = busy, advice, note
        self.stale: Holder | None = None
        self._fd: int | None = None
        self._created: list[Path] = []

    def acquire(self) -> ResourceLock:
        """Take the lock or raise ``LockedError`` naming its holder; never waits."""
        if self._fd is not None:
            raise RuntimeError(f"{self.what}: this lock is already held by this object")
        self._created = self._make_folders(self.file.parent)
        try:
            fd, previous = self._take()
        except BaseException:
            self._remove_created()
            raise
        if previous is not None and previous.pid != os.getpid():
            self.stale = previous
            state = "no longer runs" if not _running(previous.pid) else "no longer holds it"
            self.note(f"{self.what} was left open by {previous.who}, "
                      f"which {state}; taking it over")
        note = {"pid": os.getpid(), "started": time.time(), "uid": os.getuid()}
        with contextlib.suppress(OSError):  # the flock is the lock; the note only names its holder (a full disk)
            os.ftruncate(fd, 0)
            os.pwrite(fd, (json.dumps(note) + "\n").encode(), 0)
        self._fd = fd
        return self

    def release(self) -> None:
        """Give the lock up and remove its file (while still holding it, so no one else's is removed),
        then the folders taking it created, when they are still empty."""
        if self._fd is None:
            return
        with contextlib.suppress(OSError):
            if _same_file(self._fd, self.file):
                os.unlink(self.file)
        os.close(self._fd)
        self._fd = None
        self._remove_created()

    @property
    def held(self) -> bool:
        return self._fd is not None

    def __enter__(self) -> ResourceLock:
        return self.acquire()

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.release()

    def _take(self) -> tuple[int, Holder | None]:
        """The locked file descriptor and the stale note found in it. Another user's note this
        user may not write (a folder that is not group-writable) is replaced by a new file."""
        previous: Holder | None = None
        while True:
            fd, writable = self._open()
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = _read_holder(fd)
                os.close(fd)
                who = holder.who if holder else "another process"
                raise LockedError(f"{self.what} {self.busy} {who}; {self.advice}", self.path) from None
            if not _same_file(fd, self.file):  # the previous holder removed it after we opened it
                os.close(fd)
                continue
            previous = _read_holder(fd) or previous
            if writable:
                return fd, previous
            try:
                os.unlink(self.file)
            except OSError as exc:
                raise TeachError(f"cannot lock {self.what}: {self.file} was left by another user and cannot be "
                                 f"replaced ({exc.strerror}); remove it", self.path) from None
            finally:
                os.close(fd)

    def _open(self) -> tuple[int, bool]:
        """The lock file opened for writing (created when missing: never through a symbolic link,
        never an existing file of another user's by O_CREAT), or read-only when this user may
        only read it."""
        flags = os.O_NOFOLLOW | os.O_CLOEXEC | os.O_NONBLOCK
        while True:
            try:
                try:
                    fd, writable = os.open(self.file, os.O_RDWR | flags), True
                except PermissionError:
                    fd, writable = os.open(self.file, os.O_RDONLY | flags), False
                except FileNotFoundError:
                    try:
                        fd, writable = os.open(self.file, os.O_RDWR | os.O_CREAT | os.O_EXCL | flags, 0o600), True
                    except FileExistsError:
                        continue
                    group = os.stat(self.file.parent).st_mode & stat.S_IWGRP
                    os.fchmod(fd, 0o664 if group else 0o644)  # the group may take it over when it may write here
            except OSError as exc:
                raise TeachError(f"cannot lock {self.what}: {exc.strerror} ({self.file})", self.path) from None
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                os.close(fd)
                raise TeachError(f"cannot lock {self.what}: {self.file} is not a regular file", self.path)
            return fd, writable

    def _make_folders(self, folder: Path) -> list[Path]:
        """Create ``folder`` and its missing parents; the ones created, outermost first."""
        missing = []
        while not folder.exists() and folder != folder.parent:
            missing.append(folder)
            folder = folder.parent
        created: list[Path] = []
        for place in reversed(missing):
            try:
                place.mkdir()
            except FileExistsError:
                continue
            except OSError as exc:
                self._created = created
                self._remove_created()
                raise TeachError(f"cannot lock {self.what}: {exc.strerror} ({place})", self.path) from None
            created.append(place)
        return created

    def _remove_created(self) -> None:
        for place in reversed(self._created):
            with contextlib.suppress(OSError):
                place.rmdir()
        self._created = []


def _same_file(fd: int, path: Path) -> bool:
    try:
        on_disk = os.stat(path, follow_symlinks=False)
    except FileNotFoundError:
        return False
    opened = os.fstat(fd)
    return (on_disk.st_dev, on_disk.st_ino) == (opened.st_dev, opened.st_ino)


def _read_holder(fd: int) -> Holder | None:
    """The pid, start time and user written in a lock file, or None when it holds nothing readable."""
    try:
        data = json.loads(os.pread(fd, 4096, 0) or b"null")
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict):
        return None
    pid, started, uid = data.get("pid"), data.get("started"), data.get("uid")
    if isinstance(pid, bool) or not isinstance(pid, int) or pid <= 0 or not isinstance(started, (int, float)):
        return None
    return Holder(pid, float(started), uid if isinstance(uid, int) and not isinstance(uid, bool) else None)


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _key_path(path: str | Path) -> str:
    """A path as the lock sees it: absolute, with symbolic links in its existing part resolved."""
    return str(Path(os.path.abspath(path)).resolve(strict=False))


def lock_file(resource: str | Path) -> Path:
    """The lock file of a resource: ``.NAME.teach-lock`` beside it, however the path is spelled."""
    place = Path(_key_path(resource))
    return place.parent / f".{place.name}{SUFFIX}"


def session_lock(base: str | Path, session: str) -> ResourceLock:
    """The lock of a teaching session (beside its journal): one session, one process."""
    where = Path(base) / "recordings" / f"{session}.journal.json"
    return ResourceLock(lock_file(where), f"session {session}", where)


def set_lock(folder_of_set: str | Path) -> ResourceLock:
    """The lock of a demonstration set that demonstrations are recorded into."""
    return ResourceLock(lock_file(folder_of_set), "this demonstration set", folder_of_set,
                        busy="is being recorded into by", advice="wait until it has finished")


def output_lock(path: str | Path) -> ResourceLock:
    """The lock of an output file or folder a command writes."""
    return ResourceLock(lock_file(path), "this output", path, busy="is being written by",
                        advice="wait until it has finished")


@contextlib.contextmanager
def holding(*locks: ResourceLock) -> Iterator[None]:
    """Hold all ``locks`` (taken in order; all released, in reverse, however the block ends)."""
    with contextlib.ExitStack() as stack:
        for lock in locks:
            stack.enter_context(lock)
        yield


@contextlib.contextmanager
def claim_outputs(outputs: Sequence[Output], inputs: Sequence[Input] = ()) -> Iterator[None]:
    """Check every output a command will write before it writes any (so a bad second output
    leaves the first unwritten), none of them one of the ``inputs`` it reads (teach.protect),
    then hold a lock on each while the command runs."""
    from teach.fsutil import check_output, check_output_folder

    refuse_inputs(outputs, inputs)
    seen: set[str] = set()
    for kind, path in outputs:
        if _key_path(path) in seen:
            raise TeachError("is given as two outputs of one command: name two different paths", path)
        seen.add(_key_path(path))
        if kind == "file":
            check_output(path)
        else:
            check_output_folder(path)
    with holding(*(set_lock(path) if kind == "set" else output_lock(path) for kind, path in outputs)):
        yield
