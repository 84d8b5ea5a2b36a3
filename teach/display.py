"""Whether a window can open here: the one display check for the MuJoCo and rerun viewers."""

from __future__ import annotations

import os
import sys


def has_display() -> bool:
    """Linux needs X11 or Wayland; macOS and Windows always can."""
    return sys.platform != "linux" or bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
