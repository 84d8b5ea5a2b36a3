"""The project's error hierarchy.

Every error a user can cause carries the file and line it concerns, so the command line
can print it as one line ``path:line: what is wrong`` and exit with status 2.
"""

from __future__ import annotations

from pathlib import Path


class TeachError(Exception):
    """An error caused by input; printed as one line, never as a traceback."""

    def __init__(self, message: str, path: str | Path | None = None, line: int | None = None):
        super().__init__(message)
        self.message = message
        self.path = None if path is None else str(path)
        self.line = line

    def __str__(self) -> str:
        where = ""
        if self.path is not None:
            where = f"{self.path}:{self.line}: " if self.line is not None else f"{self.path}: "
        return f"{where}{self.message}"


class FormatError(TeachError):
    """A domain, demonstration, tree or dialogue file is malformed."""


class DomainError(TeachError):
    """A domain or action model cannot be used (unknown names, contradictions)."""


class LearnError(TeachError):
    """A learner cannot produce a tree from what it was given; the message says why, and
    ``kind`` names the reason ("contradiction", "repeated", "order") for front-ends that
    explain it in the teacher's language."""

    def __init__(self, message: str, path: str | Path | None = None, line: int | None = None, kind: str = ""):
        super().__init__(message, path, line)
        self.kind = kind
