"""A neutral snapshot of the 3D scene, so the simulation and the rerun logger need not know each other."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class SceneShape:
    """One geometric shape with its world pose, as the logger draws it.

    ``kind`` is "box" (size = half extents), "sphere" (size = (radius,)), "capsule" or
    "cylinder" (size = (radius, half length)); ``quat`` is (w, x, y, z).
    """

    name: str
    kind: str
    size: tuple[float, ...]
    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]
    rgba: tuple[float, float, float, float]
