"""A resumed session's recording: the parts written before (and a killed process's unfinished
part) merged with the new one by rerun's own command, so one file holds the whole session."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path


def keep_earlier(path: Path, part: Path) -> list[Path]:
    """Before a resumed session writes: what the session recorded so far, including the
    unfinished part file a killed process left behind."""
    earlier = [path] if path.exists() else []
    if part.exists():
        crashed = path.with_name(path.name + ".crashed")
        os.replace(part, crashed)
        earlier.append(crashed)
    return earlier


def merge_into_place(path: Path, part: Path, earlier: list[Path]) -> None:
    """One recording of the whole session at ``path``: the earlier parts and ``part``, merged."""
    rerun = shutil.which("rerun") or str(Path(sys.executable).with_name("rerun"))
    merged = path.with_name(path.name + ".merged")
    result = subprocess.run([rerun, "rrd", "merge", "--continue-on-error", *map(str, earlier),
                             str(part), "-o", str(merged)], capture_output=True, text=True)
    if result.returncode != 0 or not merged.exists():
        # keep every piece rather than lose one: this part goes beside the earlier recording
        os.replace(part, path.with_name(path.stem + ".resumed.rrd"))
        return
    os.replace(merged, path)
    for piece in (part, *earlier):
        if piece != path:
            piece.unlink(missing_ok=True)
