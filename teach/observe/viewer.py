"""Opening the rerun viewer on a recording, when there is a screen to show it on."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from teach.display import has_display
from teach.errors import TeachError


def open_viewer(path: Path) -> subprocess.Popen:
    """Start the installed rerun viewer on a recording, detached from this process."""
    if not has_display():
        raise TeachError("cannot open the rerun viewer: no display (DISPLAY or WAYLAND_DISPLAY is not set); "
                         "copy the recording to a machine with a screen and run `rerun FILE.rrd` there", path)
    viewer = shutil.which("rerun") or str(Path(sys.executable).with_name("rerun"))
    if not Path(viewer).exists():
        raise TeachError("cannot open the rerun viewer: the `rerun` executable is not installed "
                         "(it comes with `pip install rerun-sdk`)", path)
    return subprocess.Popen([viewer, str(path)], start_new_session=True, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
