"""Atomic file writes: a crash never leaves a half-written demonstration, tree or journal."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from teach.errors import FormatError, TeachError


def atomic_write_text(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` via a temporary file in the same folder and a rename."""
    atomic_write_bytes(path, text.encode("utf-8"))


def atomic_write_bytes(path: str | Path, data: bytes) -> None:
    """Write via a temporary file and a rename; the file gets the mode a plain write would give
    (the umask's), and a one-line ``TeachError`` says why a path cannot be written."""
    target = Path(path)
    try:
        if target.is_dir():
            raise IsADirectoryError(21, "Is a directory", str(target))
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    except OSError as exc:
        raise TeachError(f"cannot write here: {exc.strerror}", target) from None
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def read_text(path: str | Path, what: str) -> str:
    """A UTF-8 text file, or a one-line ``FormatError`` naming ``what`` it should have been."""
    try:
        return Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise FormatError(f"{what} is not UTF-8 text", path) from None
    except IsADirectoryError:
        raise FormatError(f"is a folder, not a {what}", path) from None
    except OSError as exc:
        raise FormatError(f"cannot read {what}: {exc.strerror}", path) from None
