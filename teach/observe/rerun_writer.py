"""Every step of a session recorded with rerun, and recordings read back: the only module that imports rerun.

``RerunLogger`` is the session's ``Observer``: it writes ``recordings/<session>.rrd`` (no viewer,
no display needed) and, with ``spawn=True``, also streams to a live viewer. Like
BehaviorTree.CPP's file logger it writes what explains the rest first (blueprint, domain,
tree), then the events. Entity paths are namespaced: ``scene/...`` and ``camera/image`` (the
world), ``state`` (symbolic state and running action), ``state/external``, ``tree/graph`` (the
tree, coloured by each tick, with the tick's trace), ``tree/xml``, ``dialogue``, ``learner/...``,
``demos``. Each event row carries
``AnyValues`` with plain fields, so ``read_recording`` gets the session back without parsing
display text; rows are put back in order by their rerun row ids, which increase monotonically
within the logging process.

rerun costs 50-270 µs per ``log`` call, so the scene is throttled to ``scene_hz`` and the camera
to ``camera_hz`` frames per second of simulated time and each shape kind is one batched call.
"""

from __future__ import annotations

import atexit
import io
import os
import shutil
import subprocess
import sys
import threading
import warnings
from collections.abc import Callable, Mapping
from collections.abc import Sequence as Seq
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import PIL.Image
import rerun as rr
import rerun.blueprint as rrb

from teach.bt.nodes import Node, Status, children, walk
from teach.bt.render import symbol
from teach.errors import FormatError, TeachError
from teach.observe.hook import Observer

if TYPE_CHECKING:
    from teach.bt.tick import TickResult
    from teach.demos import Demonstration
    from teach.domain import Domain
    from teach.observe.scene import SceneShape

APPLICATION_ID = "teach"
RECORDINGS = Path("recordings")

_STATUS_COLOURS = {Status.SUCCESS: (40, 170, 60), Status.FAILURE: (210, 50, 50), Status.RUNNING: (235, 170, 20)}
_IDLE_COLOUR = (150, 150, 150)
_SHAPE_ENTITIES = {"box": "scene/boxes", "sphere": "scene/spheres", "capsule": "scene/capsules",
                   "cylinder": "scene/cylinders"}


def default_recording_path(session_name: str) -> Path:
    """``recordings/<session>.rrd``, with characters a file name should not carry replaced."""
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in session_name).strip(".") or "session"
    return RECORDINGS / f"{safe}.rrd"


def blueprint() -> rrb.Blueprint:
    """Scene and camera, tree graph, state, dialogue: the layout the viewer opens with."""
    return rrb.Blueprint(
        rrb.Horizontal(
            rrb.Vertical(rrb.Spatial3DView(name="Scene", origin="scene"),
                         rrb.Spatial2DView(name="Camera", origin="camera"), row_shares=[3, 2]),
            rrb.Vertical(rrb.GraphView(name="Behaviour tree", origin="tree/graph"),
                         rrb.Tabs(rrb.TextDocumentView(name="State", origin="state"),
                                  rrb.TimeSeriesView(name="State over time", origin="state"),
                                  rrb.TextDocumentView(name="Tree XML", origin="tree/xml"),
                                  rrb.TextDocumentView(name="Demonstration", origin="demos/table"),
                                  rrb.TextDocumentView(name="Domain", origin="domain")),
                         row_shares=[3, 2]),
            rrb.Vertical(rrb.TextLogView(name="Dialogue", origin="dialogue"),
                         rrb.TextLogView(name="Learner and events",
                                         contents=["learner/**", "demos", "state/external"]),
                         rrb.TextLogView(name="Ticks", origin="tree/graph"), row_shares=[3, 2, 1]),
            column_shares=[3, 3, 2]),
        rrb.TimePanel(timeline="step"),
        collapse_panels=True,
    )


def has_display() -> bool:
    """Whether a viewer window can open (Linux needs X11 or Wayland; macOS and Windows always can)."""
    return sys.platform != "linux" or bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


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


@dataclass
class _TreeView:
    """A tree as the graph shows it: node ids are pre-order positions, so they are stable."""

    tree: Node
    index: dict[int, int]
    labels: list[str]
    edges: list[tuple[str, str]]
    positions: np.ndarray

    @classmethod
    def of(cls, tree: Node) -> _TreeView:
        nodes = list(walk(tree))
        index = {node.uid: i for i, node in enumerate(nodes)}
        edges = [(str(index[n.uid]), str(index[k.uid])) for n in nodes for k in children(n)]
        return cls(tree, index, [symbol(n) for n in nodes], edges, _layout(tree, index))


def _layout(tree: Node, index: Mapping[int, int]) -> np.ndarray:
    """Top-down tidy layout: leaves side by side, each parent centred over its children."""
    positions = np.zeros((len(index), 2), dtype=np.float32)
    next_leaf = [0.0]

    def place(node: Node, level: int) -> float:
        kids = children(node)
        if kids:
            x = sum(place(k, level + 1) for k in kids) / len(kids)
        else:
            x = next_leaf[0]
            next_leaf[0] += 1.0
        positions[index[node.uid]] = (x * 140.0, level * 110.0)
        return x

    place(tree, 0)
    return positions


class RerunLogger(Observer):
    """Records a session to an ``.rrd`` file (and a live viewer with ``spawn``).

    The file is written as ``<name>.rrd.part`` and renamed when the logger closes, so a
    finished recording is never half-written; ``close`` runs at interpreter exit if the
    caller forgot it.
    """

    def __init__(self, path: Path | None, session_name: str, spawn: bool = False, *, resume: bool = False,
                 scene_hz: float = 10.0, camera_hz: float = 2.0, jpeg_quality: int = 80, batch_rows: int | None = None):
        if spawn and not has_display():
            raise TeachError("--spawn needs a display for the rerun viewer (no DISPLAY or WAYLAND_DISPLAY); "
                             "the recording is written without it, open it later with `teach review FILE --open`")
        self.path = Path(path) if path is not None else default_recording_path(session_name)
        self._part = self.path.with_name(self.path.name + ".part")
        self._earlier: list[Path] = []  # a resumed session's recording so far, merged in on close
        try:  # fail here with a clear line rather than inside rerun's writer
            self.path.parent.mkdir(parents=True, exist_ok=True)
            if resume:
                self._earlier = self._keep_earlier()
            self._part.open("wb").close()
        except OSError as exc:
            raise TeachError(f"cannot write the recording: {exc.strerror}", exc.filename or self._part) from None
        self._scene_period = 1.0 / scene_hz
        self._camera_period = 1.0 / camera_hz
        self._jpeg_quality = jpeg_quality
        self._batch_rows = batch_rows or (3 if spawn else 20)  # a live viewer should lag little
        self._rec = rr.RecordingStream(APPLICATION_ID, recording_id=session_name)
        self._rec.set_log_time_enabled(False)
        self._rec.set_log_tick_enabled(False)
        if spawn:
            self._rec.spawn(connect=False)
            self._rec.set_sinks(rr.FileSink(self._part), rr.GrpcSink(), default_blueprint=blueprint())
        else:
            self._rec.save(self._part, default_blueprint=blueprint())
        self._rec.send_recording_name(session_name)
        self._clock: tuple[int, int, float | None] = (0, 0, None)  # version, step, sim_time
        self._sim_time: float | None = None  # the last sim_time given: rerun's clocks are sticky too
        self._batches: dict[str, _Batch] = {}
        self._last_state: tuple | None = None
        self._local = threading.local()
        self._lock = threading.Lock()
        self._view: _TreeView | None = None
        self._generation = -1
        self._last_scene: float | None = None
        self._last_camera: float | None = None
        self._scene_geometry: tuple = ()  # name, kind, size and colour of each shape, as last logged
        self._scene_columns: Callable[[list[tuple]], list[tuple[str, list[Any]]]] | None = None
        self._closed = False
        atexit.register(self.close)

    # --- clocks -----------------------------------------------------------------------------

    def set_time(self, step: int | None, sim_time: float | None = None) -> None:
        """``step`` None keeps the session's step (a simulation advancing only ``sim_time``)."""
        with self._lock:
            self._clock = (self._clock[0] + 1, self._clock[1] if step is None else step, sim_time)
            if sim_time is not None:
                self._sim_time = sim_time
        self._stamp()

    def _stamp(self) -> None:
        """rerun's clock is per thread: bring this thread's up to the session's before logging."""
        version, step, sim_time = self._clock
        if getattr(self._local, "version", -1) == version:
            return
        self._local.version = version
        self._rec.set_time("step", sequence=step)
        if sim_time is not None:
            self._rec.set_time("sim_time", duration=sim_time)

    def _log(self, entity: str, *parts: Any, static: bool = False, flush: bool = True) -> None:
        """Log one row now; ``flush`` first sends the batched rows, so row ids keep the calls' order."""
        if self._closed:
            return
        if flush:
            self._flush()
        self._stamp()
        self._rec.log(entity, *parts, static=static)

    def _queue(self, stream: str, columns: Callable[[list[tuple]], list[tuple[str, list[Any]]]], row: tuple) -> None:
        """Batch one row of a high-rate stream (scene poses, ticks); sent as columns, one rerun call per
        entity per batch. ``columns`` turns the rows into (entity, columns) pairs."""
        if self._closed:
            return
        with self._lock:
            batch = self._batches.get(stream)
            if batch is not None and (batch.times[0] is None) != (self._sim_time is None):
                self._send(stream)
                batch = None
            if batch is None:
                batch = self._batches[stream] = _Batch(columns)
            batch.steps.append(self._clock[1])
            batch.times.append(self._sim_time)
            batch.rows.append(row)
            if len(batch.rows) >= self._batch_rows:
                self._send(stream)

    def _flush(self, stream: str | None = None) -> None:
        with self._lock:
            for name in [stream] if stream is not None else sorted(self._batches):
                if name in self._batches:
                    self._send(name)

    def _send(self, stream: str) -> None:
        batch = self._batches.pop(stream)
        indexes = [rr.TimeColumn("step", sequence=batch.steps)]
        if batch.times[0] is not None:
            indexes.append(rr.TimeColumn("sim_time", duration=[t for t in batch.times if t is not None]))
        for entity, columns in batch.columns(batch.rows):
            self._rec.send_columns(entity, indexes=indexes, columns=columns)

    # --- vocabulary and trees ---------------------------------------------------------------

    def on_domain(self, domain: Domain) -> None:
        names = list(domain.condition_names)
        lines = [f"# Domain {domain.name}", "", "| ID | condition | meaning |", "|---|---|---|"]
        lines += [f"| {i} | {c.name} | {c.en} |" for i, c in enumerate(domain.conditions, 1)]
        lines += ["", "| ID | action | phrases | pre | ram |", "|---|---|---|---|---|"]
        lines += [f"| {a.id} | {a.name} | {', '.join(a.en)} | {' '.join(map(str, a.pre))} | "
                  f"{' '.join(map(str, a.ram))} |" for a in domain.actions]
        if domain.goal:
            lines += ["", "Goal: " + " ".join(map(str, domain.goal))]
        self._log("domain", rr.TextDocument("\n".join(lines), media_type=rr.MediaType.MARKDOWN),
                  _values(name=domain.name, conditions=names, actions=list(domain.action_names),
                          action_ids=[a.id for a in domain.actions], goal=[str(g) for g in domain.goal] or None),
                  static=True)
        self._log("state", rr.SeriesLines(names=names, interpolation_mode="StepAfter"), static=True)
        self._log("scene", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)  # MuJoCo's convention
        if self._view is None:  # the tree comes first in every recording, even before there is one
            self._log("tree/xml", rr.TextDocument("No tree yet: the robot learns its first behaviour tree from the "
                                                  "first demonstration.", media_type=rr.MediaType.TEXT))

    def on_tree(self, generation: int, tree: Node, xml: str, reason: str) -> None:
        self._generation = generation
        self._view = _TreeView.of(tree)
        self._log_graph(self._view)
        nodes = len(self._view.labels)
        self._log("tree/xml", rr.TextDocument(xml, media_type=rr.MediaType.TEXT))
        self._log("learner/generations",
                  rr.TextLog(f"generation {generation}: {nodes} nodes ({reason})", level="generation"),
                  _values(generation=generation, reason=reason, nodes=nodes, xml=xml))

    def _log_graph(self, view: _TreeView) -> None:
        self._log("tree/graph",
                  rr.GraphNodes([str(i) for i in range(len(view.labels))], labels=view.labels,
                                positions=view.positions, colors=[_IDLE_COLOUR] * len(view.labels)),
                  rr.GraphEdges(view.edges, graph_type="directed"))

    def on_tick(self, tree: Node, result: TickResult) -> None:
        view = self._view
        if view is None or view.tree is not tree:
            if view is None or view.tree != tree:
                view = _TreeView.of(tree)
                self._log_graph(view)
            else:
                view = _TreeView.of(tree)  # same shape, other uids: the graph stands, the index changes
            self._view = view
        statuses = result.statuses()
        colours = [_IDLE_COLOUR] * len(view.labels)
        for uid, status in statuses.items():
            if uid in view.index:
                colours[view.index[uid]] = _STATUS_COLOURS[status]
        trace = [(view.index[uid], status.name) for uid, status in result.trace if uid in view.index]
        action = result.action or ""
        self._queue("tree/graph", _tick_columns,
                    (colours, result.status.name, action, self._generation, [i for i, _ in trace],
                     [view.labels[i] for i, _ in trace], [s for _, s in trace]))

    # --- the world --------------------------------------------------------------------------

    def on_state(self, state: Mapping[str, bool], action: str | None) -> None:
        """Logged when the state or the action changes (the viewer holds a value until the next)."""
        names = list(state)
        values = [bool(state[n]) for n in names]
        key = (tuple(names), tuple(values), action)
        if key == self._last_state:
            return
        self._last_state = key
        doc = [f"**Running:** {action or '—'}", "", "| condition | value |", "|---|---|"]
        doc += [f"| {n} | {'✔ true' if v else '✘ false'} |" for n, v in zip(names, values)]
        self._log("state", rr.TextDocument("\n".join(doc), media_type=rr.MediaType.MARKDOWN),
                  *([rr.Scalars(np.asarray(values, dtype=np.float64))] if values else []),
                  _values(conditions=names or None, values=values or None, action=action or ""), flush=False)

    def on_external(self, name: str) -> None:
        self._log("state/external", rr.TextLog(f"external action: {name}", level="EXTERNAL"),
                  _values(external=name))

    def on_scene(self, shapes: Seq[SceneShape]) -> None:
        sim_time = self._clock[2]
        if not self._due(sim_time, self._last_scene, self._scene_period):
            return
        self._last_scene = sim_time
        geometry = tuple((s.name, s.kind, s.size, s.rgba) for s in shapes)
        positions = np.array([s.pos for s in shapes], dtype=np.float32).reshape(-1, 3)
        rotations = np.array([s.quat for s in shapes], dtype=np.float32).reshape(-1, 4)
        if geometry == self._scene_geometry and self._scene_columns is not None:
            self._queue("scene", self._scene_columns, (positions, rotations))
            return
        # the shapes changed: everything about them once, then poses alone (a seventh of the cost)
        layout = _SceneLayout.of(geometry)
        self._flush("scene")
        for kind in sorted({g[1] for g in self._scene_geometry} - layout.kinds.keys()):
            self._log(_SHAPE_ENTITIES[kind], rr.Clear(recursive=False), flush=False)
        for kind, index in layout.kinds.items():
            where, xyzw = layout.poses(kind, positions[None], rotations[None])
            self._log(_SHAPE_ENTITIES[kind], _shape_batch(kind, [geometry[i] for i in index], where, xyzw),
                      flush=False)
        self._scene_geometry, self._scene_columns = geometry, layout.columns

    def on_camera(self, image: Any) -> None:
        sim_time = self._clock[2]
        if not self._due(sim_time, self._last_camera, self._camera_period):
            return
        self._last_camera = sim_time
        jpeg = io.BytesIO()  # Pillow directly: a third of the time of rerun's Image(...).compress()
        PIL.Image.fromarray(np.ascontiguousarray(image, dtype=np.uint8)).save(jpeg, format="JPEG",
                                                                              quality=self._jpeg_quality)
        self._log("camera/image", rr.EncodedImage(contents=jpeg.getvalue(), media_type="image/jpeg"), flush=False)

    @staticmethod
    def _due(now: float | None, last: float | None, period: float) -> bool:
        """Throttle by simulated time; a clock that went back (a reset world) starts afresh."""
        return now is None or last is None or now < last or now - last >= period - 1e-9

    # --- dialogue, demonstrations, learner --------------------------------------------------

    def _dialogue(self, kind: str, speaker: str, shown: str, level: str, *, text: str = "",
                  budget_left: int | None = None, question: str = "", answer: str = "", change: str = "") -> None:
        self._log("dialogue", rr.TextLog(shown, level=level),
                  _values(kind=kind, speaker=speaker, text=text, budget_left=-1 if budget_left is None else budget_left,
                          question=question, answer=answer, change=change))

    def on_dialogue(self, speaker: str, text: str, budget_left: int | None = None) -> None:
        shown = text if budget_left is None else f"{text}  [questions left: {budget_left}]"
        self._dialogue("line", speaker, shown, speaker, text=text, budget_left=budget_left)

    def on_question(self, question: str, budget_left: int) -> None:
        self._dialogue("question", "robot", f"{question}  [questions left: {budget_left}]", "question",
                       text=question, budget_left=budget_left, question=question)

    def on_answer(self, question: str, answer: str, change: str) -> None:
        shown = f"{answer}  → {change}" if change else answer
        self._dialogue("answer", "teacher", shown, "answer", text=answer, question=question, answer=answer,
                       change=change)

    def on_demonstration(self, name: str, demo: Demonstration, domain: Domain) -> None:
        from teach.demos import format_demonstration

        labels = [_step_label(s.action, domain) for s in demo.steps]
        states = ["".join("1" if v else "0" for v in s.state) for s in demo.steps]
        robot = [domain.action(a).name for a in demo.actions]
        ending = "goal reached" if demo.reached_goal else "no goal line"
        table = ["| # | " + " | ".join(domain.condition_names) + " | action |",
                 "|---" * (len(domain.conditions) + 2) + "|"]
        table += [f"| {i} | " + " | ".join(state) + f" | {label} |"
                  for i, (state, label) in enumerate(zip(states, labels), 1)]
        self._log("demos", rr.TextLog(f"demonstration {name}: {' → '.join(robot) or '(no actions)'} ({ending})",
                                      level="demonstration"),
                  _values(name=name, conditions=list(domain.condition_names), states=states,
                          step_actions=[s.action for s in demo.steps], step_labels=labels,
                          reached_goal=demo.reached_goal, csv=format_demonstration(demo)))
        self._log("demos/table", rr.TextDocument(f"# {name}\n\n" + "\n".join(table),
                                                 media_type=rr.MediaType.MARKDOWN))

    def on_learner(self, event: str, detail: str, removed: Seq[str] = ()) -> None:
        text = f"{event}: {detail}" + (f" (removed {', '.join(removed)})" if removed else "")
        self._log("learner/events", rr.TextLog(text, level=event),
                  _values(event=event, detail=detail, removed=list(removed) or None))

    def on_replay(self, reproduced: int, total: int, lenient: bool = False) -> None:
        mode = "lenient" if lenient else "strict"
        self._log("learner/replay", rr.TextLog(f"replay: reproduced {reproduced}/{total} ({mode})", level="replay"),
                  _values(reproduced=reproduced, total=total, lenient=lenient))

    def checkpoint(self) -> None:
        """Write what is queued to the file now, so a killed session keeps it."""
        if not self._closed:
            self._flush()
            self._rec.flush()

    def close(self) -> None:
        """Flush, finish the file (rerun writes its footer on disconnect) and move it into place."""
        if self._closed:
            return
        self._flush()
        self._closed = True
        atexit.unregister(self.close)
        self._rec.flush()
        self._rec.disconnect()
        if self._earlier:
            self._merge_into_place()
        else:
            os.replace(self._part, self.path)

    def _keep_earlier(self) -> list[Path]:
        """Before a resumed session writes: what the session recorded so far, including the
        unfinished part file a killed process left behind."""
        earlier = [self.path] if self.path.exists() else []
        if self._part.exists():
            crashed = self.path.with_name(self.path.name + ".crashed")
            os.replace(self._part, crashed)
            earlier.append(crashed)
        return earlier

    def _merge_into_place(self) -> None:
        """One recording of the whole session: the earlier parts and this one, merged by rerun."""
        rerun = shutil.which("rerun") or str(Path(sys.executable).with_name("rerun"))
        merged = self.path.with_name(self.path.name + ".merged")
        result = subprocess.run([rerun, "rrd", "merge", "--continue-on-error", *map(str, self._earlier),
                                 str(self._part), "-o", str(merged)], capture_output=True, text=True)
        if result.returncode != 0 or not merged.exists():
            # keep every piece rather than lose one: this part goes beside the earlier recording
            os.replace(self._part, self.path.with_name(self.path.stem + ".resumed.rrd"))
            return
        os.replace(merged, self.path)
        for piece in (self._part, *self._earlier):
            if piece != self.path:
                piece.unlink(missing_ok=True)

    def __enter__(self) -> RerunLogger:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.close()


@dataclass
class _Batch:
    """Rows of one high-rate entity waiting to go out together as columns."""

    columns: Callable[[list[tuple]], list[tuple[str, list[Any]]]]
    steps: list[int] = field(default_factory=list)
    times: list[float | None] = field(default_factory=list)
    rows: list[tuple] = field(default_factory=list)


def _values(**fields: Any) -> rr.AnyValues:
    """Plain fields for reading back. Each is passed as a list: on a bare scalar rerun's AnyValues
    takes ~8x longer (pyarrow's scalar path probes for pandas on every call)."""
    values: dict[str, Any] = {k: v if isinstance(v, list) else [v] for k, v in fields.items() if v is not None}
    return rr.AnyValues(**values)


def _step_label(action: int, domain: Domain) -> str:
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
class _SceneLayout:
    """Which shapes of a scene frame are of which kind, so frames of poses split into one column set per kind."""

    kinds: dict[str, np.ndarray]
    capsule_half: np.ndarray

    @classmethod
    def of(cls, geometry: tuple) -> _SceneLayout:
        kinds: dict[str, list[int]] = {}
        for i, (name, kind, _size, _rgba) in enumerate(geometry):
            if kind not in _SHAPE_ENTITIES:
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
            result.append((_SHAPE_ENTITIES[kind], list(columns.partition([len(index)] * len(rows)))))
        return result


def _shape_batch(kind: str, geometry: list[tuple], where: np.ndarray, xyzw: np.ndarray) -> Any:
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


def _tick_columns(rows: list[tuple]) -> list[tuple[str, list[Any]]]:
    """Ticks as columns: node colours on the graph, a text line, and the fields read back."""
    colours, statuses, actions, generations, nodes, labels, trace_statuses = zip(*rows)
    columns = [*rr.GraphNodes.columns(colors=[c for row in colours for c in row]).partition(
                   [len(row) for row in colours]),
               *rr.TextLog.columns(text=[f"{s} {a}".rstrip() for s, a in zip(statuses, actions)], level=statuses),
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


# --- reading a recording back ------------------------------------------------------------------


@dataclass(frozen=True)
class DemoRecord:
    name: str
    states: tuple[tuple[bool, ...], ...]
    actions: tuple[str, ...]
    """One label per line: an action name, "goal" or "external"."""
    reached_goal: bool
    csv: str
    step: int | None


@dataclass
class QuestionRecord:
    question: str
    budget_left: int
    answer: str | None = None
    change: str | None = None
    step: int | None = None


@dataclass(frozen=True)
class GenerationRecord:
    generation: int
    reason: str
    nodes: int
    xml: str
    step: int | None


@dataclass(frozen=True)
class TickRecord:
    step: int | None
    sim_time: float | None
    generation: int
    status: str
    action: str | None
    trace: tuple[tuple[str, str], ...]
    """(node label, status) in the order the tick finished them (post-order)."""


@dataclass(frozen=True)
class LearnerRecord:
    event: str
    detail: str
    removed: tuple[str, ...]
    step: int | None


@dataclass(frozen=True)
class ReplayRecord:
    reproduced: int
    total: int
    lenient: bool
    step: int | None


@dataclass(frozen=True)
class DialogueRecord:
    kind: str
    """"line", "question" or "answer"."""
    speaker: str
    text: str
    budget_left: int | None
    step: int | None


@dataclass(frozen=True)
class StateRecord:
    step: int | None
    sim_time: float | None
    state: dict[str, bool]
    action: str | None


@dataclass
class RecordingContents:
    """A recording as plain Python data, every list in logging order."""

    path: Path
    session: str
    has_blueprint: bool = False
    """Whether the viewer layout (scene, tree graph, state, dialogue) travels with the file."""
    domain_name: str | None = None
    conditions: tuple[str, ...] = ()
    actions: tuple[str, ...] = ()
    goal: tuple[str, ...] = ()
    demonstrations: list[DemoRecord] = field(default_factory=list)
    questions: list[QuestionRecord] = field(default_factory=list)
    generations: list[GenerationRecord] = field(default_factory=list)
    learner_events: list[LearnerRecord] = field(default_factory=list)
    replays: list[ReplayRecord] = field(default_factory=list)
    ticks: list[TickRecord] = field(default_factory=list)
    states: list[StateRecord] = field(default_factory=list)
    dialogue: list[DialogueRecord] = field(default_factory=list)
    externals: list[tuple[int | None, str]] = field(default_factory=list)
    scene_frames: int = 0
    camera_frames: int = 0
    first_entities: tuple[str, ...] = ()
    """The first entity paths logged over time (after the static domain): the tree comes first."""

    @property
    def final_tree_xml(self) -> str | None:
        return self.generations[-1].xml if self.generations else None


_EVENT_ENTITIES = ("/tree/graph", "/tree/xml", "/learner/generations", "/learner/events",
                   "/learner/replay", "/dialogue", "/demos", "/state", "/state/external", "/domain")
_FRAME_ENTITIES = tuple("/" + e for e in _SHAPE_ENTITIES.values())


def read_recording(path: str | Path) -> RecordingContents:
    """Read a ``teach`` recording back with rerun's own reader; damage is a one-line ``FormatError``."""
    from rerun.chunk import RrdReader

    path = Path(path)
    if not path.is_file():
        raise FormatError("no such recording file", path)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            reader = RrdReader(path)
            stores = reader.recordings()
            has_blueprint = bool(reader.blueprints())
        if any("no footer" in str(w.message) for w in caught):
            raise FormatError("the recording is truncated (no rerun footer): the session did not finish writing it",
                              path)
        if not stores:
            raise FormatError("not a rerun recording with data (no recording store)", path)
        store = stores[0]
        if store.application_id != APPLICATION_ID:
            raise FormatError(f"not a teach recording (rerun application {store.application_id!r})", path)
        chunks = reader.stream(store=store).to_chunks()
    except (RuntimeError, ValueError, OSError) as exc:
        message = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise FormatError(f"damaged rerun recording: {message}", path) from None
    contents = RecordingContents(path, store.recording_id, has_blueprint=has_blueprint)
    rows: list[tuple[bytes, str, dict[str, Any]]] = []
    frames: set[tuple[Any, Any]] = set()
    for chunk in chunks:
        entity = chunk.entity_path
        if entity in _FRAME_ENTITIES:
            frame_rows = _rows(chunk, ("step", "sim_time"))
            frames.update((row["step"], row.get("sim_time")) for _rid, _e, row in frame_rows)
            rows.extend(frame_rows)
        elif entity == "/camera/image":
            contents.camera_frames += chunk.num_rows
        elif entity in _EVENT_ENTITIES:
            rows.extend(_rows(chunk))
    contents.scene_frames = len(frames)
    rows.sort(key=lambda row: row[0])
    _fill(contents, rows)
    return contents


def _rows(chunk: Any, only: tuple[str, ...] | None = None) -> list[tuple[bytes, str, dict[str, Any]]]:
    """Each row of a chunk as ``{column: value}`` (component values stay lists), with its row id."""
    batch = chunk.to_record_batch()
    names = [n for n in batch.schema.names if n not in ("rerun.controls.RowId", "log_time", "log_tick")
             and (only is None or n in only)]
    columns = {n: batch.column(n).to_pylist() for n in names}
    if "sim_time" in columns:
        columns["sim_time"] = [None if v is None else v.total_seconds() for v in columns["sim_time"]]
    row_ids = batch.column("rerun.controls.RowId").to_pylist()
    return [(rid, chunk.entity_path, {n: values[i] for n, values in columns.items()})
            for i, rid in enumerate(row_ids)]


def _one(row: Mapping[str, Any], name: str, default: Any = None) -> Any:
    value = row.get(name)
    if isinstance(value, list):
        return value[0] if value else default
    return default if value is None else value


def _many(row: Mapping[str, Any], name: str) -> list[Any]:
    value = row.get(name)
    return list(value) if isinstance(value, list) else []


def _fill(contents: RecordingContents, rows: list[tuple[bytes, str, dict[str, Any]]]) -> None:
    first: list[str] = []
    open_questions: list[QuestionRecord] = []
    for _rid, entity, row in rows:
        step = row.get("step")
        if step is None and entity != "/domain":
            continue  # static display settings
        if step is not None and len(first) < 8 and (not first or first[-1] != entity):
            first.append(entity)
        if entity == "/domain" and "conditions" in row:
            contents.domain_name = _one(row, "name")
            contents.conditions = tuple(_many(row, "conditions"))
            contents.actions = tuple(_many(row, "actions"))
            contents.goal = tuple(_many(row, "goal"))
        elif entity == "/learner/generations":
            contents.generations.append(GenerationRecord(_one(row, "generation", -1), _one(row, "reason", ""),
                                                         _one(row, "nodes", 0), _one(row, "xml", ""), step))
        elif entity == "/learner/events":
            contents.learner_events.append(LearnerRecord(_one(row, "event", ""), _one(row, "detail", ""),
                                                         tuple(_many(row, "removed")), step))
        elif entity == "/learner/replay":
            contents.replays.append(ReplayRecord(_one(row, "reproduced", 0), _one(row, "total", 0),
                                                 bool(_one(row, "lenient", False)), step))
        elif entity == "/tree/graph" and "status" in row:
            trace = tuple(zip(_many(row, "trace_labels"), _many(row, "trace_status")))
            contents.ticks.append(TickRecord(step, row.get("sim_time"), _one(row, "generation", -1),
                                             _one(row, "status", ""), _one(row, "action") or None, trace))
        elif entity == "/state":
            state = dict(zip(_many(row, "conditions"), map(bool, _many(row, "values"))))
            contents.states.append(StateRecord(step, row.get("sim_time"), state, _one(row, "action") or None))
        elif entity == "/state/external":
            contents.externals.append((step, _one(row, "external", "")))
        elif entity == "/demos":
            states = tuple(tuple(c == "1" for c in s) for s in _many(row, "states"))
            contents.demonstrations.append(DemoRecord(_one(row, "name", ""), states,
                                                      tuple(_many(row, "step_labels")),
                                                      bool(_one(row, "reached_goal", False)),
                                                      _one(row, "csv", ""), step))
        elif entity == "/dialogue":
            _dialogue_row(contents, row, step, open_questions)
    contents.first_entities = tuple(first)


def _dialogue_row(contents: RecordingContents, row: Mapping[str, Any], step: int | None,
                  open_questions: list[QuestionRecord]) -> None:
    kind = _one(row, "kind", "line")
    budget = _one(row, "budget_left", -1)
    text = _one(row, "text", "")
    contents.dialogue.append(DialogueRecord(kind, _one(row, "speaker", ""), text,
                                            None if budget is None or budget < 0 else budget, step))
    if kind == "question":
        record = QuestionRecord(text, budget, step=step)
        contents.questions.append(record)
        open_questions.append(record)
    elif kind == "answer":
        asked = _one(row, "question", "")
        match = next((q for q in reversed(open_questions) if q.question == asked),
                     open_questions[-1] if open_questions else None)
        if match is None:  # an answer to a question the recording did not see: keep it anyway
            match = QuestionRecord(asked, -1, step=step)
            contents.questions.append(match)
        else:
            open_questions.remove(match)
        match.answer = _one(row, "answer", "")
        match.change = _one(row, "change", "")
