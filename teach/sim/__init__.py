"""The MuJoCo world: ball in bin, skills, perturbations, a recorder and a tree executor.

mujoco is imported only inside this package. Offscreen rendering needs an OpenGL backend
chosen before mujoco is first imported: unless ``MUJOCO_GL`` is set, EGL is used when its
library exists, else OSMesa; with neither, ``World.camera_image`` returns None.
"""

from __future__ import annotations

import ctypes.util
import os

if "MUJOCO_GL" not in os.environ:
    for _backend, _library in (("egl", "EGL"), ("osmesa", "OSMesa")):
        if ctypes.util.find_library(_library):
            os.environ["MUJOCO_GL"] = _backend
            break
