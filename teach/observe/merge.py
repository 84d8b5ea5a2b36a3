"""A resumed session's recording: the parts written before (and a killed process's unfinished
part) merged with the new one by rerun's own command, so one file holds the whole session."""

from __future__ import annotations

import os
import shutil
import sys
from collections.abc import Callable
from pathlib import Path

from teach.children import run_child


def print_note(message: str) -> None:
    """A note to the teacher on standard error, beside the session's own output."""
    print(f"teach: note: {message}", file=sys.stderr)


def _rerun() -> str:
    return shutil.which("rerun") or str(Path(sys.executable).with_name("rerun"))


def is_readable_recording(path: Path) -> bool:
    """Whether rerun loads the whole of a finished recording."""
    result = run_child([_rerun(), "rrd", "verify", str(path)])
    return result.returncode == 0


def keep_earlier(path: Path, part: Path, note: Callable[[str], None]) -> list[Path]:
    """Before a resumed session writes: what the session recorded so far, including the
    unfinished part file a killed process left behind. A finished recording that rerun cannot
    read is kept aside (and said so) rather than merged, which would drop what it cannot read."""
    earlier = []
    if path.exists():
        if is_readable_recording(path):
            earlier.append(path)
        else:
            aside = path.with_name(path.stem + ".damaged.rrd")
            os.replace(path, aside)
            note(f"{path}: the earlier recording is damaged: kept aside as {aside.name}, not merged")
    if part.exists():
        crashed = path.with_name(path.name + ".crashed")
        os.replace(part, crashed)
        earlier.append(crashed)
    return earlier


def merge_into_place(path: Path, part: Path, earlier: list[Path]) -> None:
    """One recording of the whole session at ``path``: the earlier parts and ``part``, merged."""
    rerun = _rerun()
    merged = path.with_name(path.name + ".merged")
    result = run_child([rerun, "rrd", "merge", "--continue-on-error", *map(str, earlier), str(part), "-o", str(merged)])
    if result.returncode != 0 or not merged.exists():
        # keep every piece rather than lose one: this part goes beside the earlier recording
        os.replace(part, path.with_name(path.stem + ".resumed.rrd"))
        return
    os.replace(merged, path)
    for piece in (part, *earlier):
        if piece != path:
            piece.unlink(missing_ok=True)


def put_back(path: Path, part: Path, earlier: list[Path]) -> None:
    """Undo ``keep_earlier`` for a session that did not open: the recording is as it was."""
    crashed = path.with_name(path.name + ".crashed")
    if crashed in earlier:
        os.replace(crashed, part)
