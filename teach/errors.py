"""The project's error hierarchy.

Every error a user can cause carries the file and line it concerns, so the command line
can print it as one line ``path:line: what is wrong`` and exit with status 2; ``printable``
makes that line safe for a terminal whatever the file name holds.
"""

from __future__ import annotations

import re
from pathlib import Path

_UNSAFE = re.compile("[\x00-\x1f\x7f-\x9f\u061c\u200e\u200f\u2028-\u202e\u2066-\u2069\ud800-\udfff]")
"""Characters that must not reach a terminal raw: controls (a newline splits a line, ESC starts
an ANSI sequence), line and paragraph separators, bidirectional overrides and isolates, and the
surrogates a file name that is not UTF-8 decodes to."""
_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def printable(text: str) -> str:
    """``text`` safe to print as (part of) one line: every unsafe character written as an escape
    (``\\n``, ``\\x1b``, ``\\u202e``), everything else as it is."""
    return _UNSAFE.sub(lambda match: _escape(match.group()), text)


def _escape(char: str) -> str:
    code = ord(char)
    if 0xDC80 <= code <= 0xDCFF:  # a byte of a file name that is not UTF-8 (os.fsdecode)
        code -= 0xDC00
    return _NAMED.get(char) or (f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}")


def shown(value: object, most: int = 60) -> str:
    """A value for an error message (its ``repr``), cut short so a huge one still gives a short line."""
    text = repr(value)
    return text if len(text) <= most else text[:most - 3] + "..."


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
