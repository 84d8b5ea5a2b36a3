"""Turning trees, ticks and scene frames into rerun's batched columns: the costly part of
recording, kept apart from what is recorded when."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import rerun as rr

if TYPE_CHECKING:
    from teach.domain import Domain

SHAPE_ENTITIES = {"box": "scene/boxes", "sphere": "scene/spheres", "capsule": "scene/capsules",
                   "cylinder": "scene/cylinders"}


@dataclass
class Batch:
    """Rows of one high-rate entity waiting to go out together as columns."""

    columns: Callable[[list[tuple]], list[tuple[str, list[Any]]]]
    steps: list[int] = field(default_factory=list)
    moments: list[int] = field(default_factory=list)
    times: list[float | None] = field(default_factory=list)
    rows: list[tuple] = field(default_factory=list)


def plain_values(**fields: Any) -> rr.AnyValues:
    """Plain fields for reading back. Each is passed as a list: on a bare scalar rerun's AnyValues
    takes ~8x longer (pyarrow's scalar path probes for pandas on every call)."""
    values: dict[str, Any] = {k: v if isinstance(v, list) else [v] for k, v in fields.items() if v is not None}
    return rr.AnyValues(**values)


def step_label(action: int, domain: Domain) -> str:
    if action == 0:
        return "goal"
    if action == -1:
        return "external"
    return domain.action(action).name


_ARCHETYPES: dict[str, Any] = {"box": rr.Boxes3D, "sphere": rr.Ellipsoids3D, "capsule": rr.Capsules3D,
                               "cylinder": rr.Cylinders3D}


def _where(kind: str) -> str:
    return "translations" if kind == "capsule" else "centers"


@dataclass(frozen=True)
class SceneLayout:
    """Which shapes of a scene frame are of which kind, so frames of poses split into one column set per kind."""

    kinds: dict[str, np.ndarray]
    capsule_half: np.ndarray

    @classmethod
    def of(cls, geometry: tuple) -> SceneLayout:
        kinds: dict[str, list[int]] = {}
        for i, (name, kind, _size, _rgba) in enumerate(geometry):
            if kind not in SHAPE_ENTITIES:
                raise ValueError(f"scene shape {name!r} has unknown kind {kind!r}")
            kinds.setdefault(kind, []).append(i)
        half = np.array([geometry[i][2][1] for i in kinds.get("capsule", [])], dtype=np.float32)
        return cls({k: np.array(kinds[k]) for k in sorted(kinds)}, half)

    def poses(self, kind: str, positions: np.ndarray, rotations: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Frames × shapes of this kind: where rerun places each, and its rotation (x, y, z, w)."""
        index = self.kinds[kind]
        pos, wxyz = positions[:, index], rotations[:, index]
        if kind == "capsule":  # rerun's capsule runs from its translation along +z; MuJoCo's is centred
            pos = pos - _rotate_z(wxyz) * self.capsule_half[None, :, None]
        return pos, wxyz[..., [1, 2, 3, 0]]

    def columns(self, rows: list[tuple]) -> list[tuple[str, list[Any]]]:
        positions = np.stack([r[0] for r in rows])
        rotations = np.stack([r[1] for r in rows])
        result = []
        for kind, index in self.kinds.items():
            where, xyzw = self.poses(kind, positions, rotations)
            columns = _ARCHETYPES[kind].columns(**{_where(kind): where.reshape(-1, 3),
                                                   "quaternions": xyzw.reshape(-1, 4)})
            result.append((SHAPE_ENTITIES[kind], list(columns.partition([len(index)] * len(rows)))))
        return result


def shape_batch(kind: str, geometry: list[tuple], where: np.ndarray, xyzw: np.ndarray) -> Any:
    """All shapes of a kind (``geometry``: name, kind, size, rgba of each) with their poses, as one archetype."""
    sizes = [size for _name, _kind, size, _rgba in geometry]
    fields: dict[str, Any] = {
        _where(kind): where.reshape(-1, 3), "quaternions": xyzw.reshape(-1, 4),
        "colors": np.clip(np.array([g[3] for g in geometry]) * 255.0, 0, 255).astype(np.uint8),
        "labels": [g[0] for g in geometry], "show_labels": False, "fill_mode": rr.components.FillMode.Solid}
    if kind == "box":
        fields["half_sizes"] = np.array([size[:3] for size in sizes], dtype=np.float32)
    elif kind == "sphere":
        fields["half_sizes"] = np.array([(size[0],) * 3 for size in sizes], dtype=np.float32)
    else:
        fields["radii"] = np.array([size[0] for size in sizes], dtype=np.float32)
        fields["lengths"] = 2 * np.array([size[1] for size in sizes], dtype=np.float32)
    return _ARCHETYPES[kind].from_fields(**fields)


def tick_columns(rows: list[tuple]) -> list[tuple[str, list[Any]]]:
    """Ticks as columns: node colours and labels (the running action marked) on the graph, a text
    line, and the fields read back."""
    colours, shown, statuses, actions, generations, nodes, labels, trace_statuses = zip(*rows, strict=True)
    columns = [*rr.GraphNodes.columns(colors=[c for row in colours for c in row],
                                      labels=[label for row in shown for label in row]).partition(
                   [len(row) for row in colours]),
               *rr.TextLog.columns(text=[f"{s} {a}".rstrip() for s, a in zip(statuses, actions, strict=True)],
                                   level=statuses),
               *rr.AnyValues.columns(status=list(statuses), action=list(actions), generation=list(generations))]
    lengths = [len(row) for row in nodes]
    if any(lengths):
        columns += rr.AnyValues.columns(trace_nodes=[n for row in nodes for n in row],
                                        trace_labels=[n for row in labels for n in row],
                                        trace_status=[n for row in trace_statuses for n in row]).partition(lengths)
    return [("tree/graph", columns)]


def _rotate_z(wxyz: np.ndarray) -> np.ndarray:
    """Each quaternion's local z axis in world coordinates (third column of its rotation matrix)."""
    w, x, y, z = (wxyz[..., i] for i in range(4))
    return np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], axis=-1)
