"""A teach recording read back with rerun's own reader into plain Python records."""

from __future__ import annotations

import json
import os
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from teach.errors import FormatError
from teach.fsutil import open_regular
from teach.observe.encode import SHAPE_ENTITIES
from teach.observe.layout import APPLICATION_ID


@dataclass(frozen=True)
class DemoRecord:
    name: str
    states: tuple[tuple[bool, ...], ...]
    actions: tuple[str, ...]
    """One label per line: an action name, "goal" or "external"."""
    reached_goal: bool
    csv: str
    step: int | None
    moment: int | None = None


@dataclass
class QuestionRecord:
    question: str
    budget_left: int
    answer: str | None = None
    change: str | None = None
    step: int | None = None
    answer_step: int | None = None
    moment: int | None = None
    """The ``tick`` timeline's moment of the question (``answer_moment``: of its answer)."""
    answer_moment: int | None = None


@dataclass(frozen=True)
class GenerationRecord:
    generation: int
    reason: str
    nodes: int
    xml: str
    step: int | None
    moment: int | None = None


@dataclass(frozen=True)
class TickRecord:
    step: int | None
    sim_time: float | None
    generation: int
    status: str
    action: str | None
    trace: tuple[tuple[str, str], ...]
    """(node label, status) in the order the tick finished them (post-order)."""
    nodes: tuple[int, ...] = ()
    """The graph's node index of each ``trace`` entry (pre-order positions in the ticked tree)."""
    moment: int | None = None
    """Its own moment on the ``tick`` timeline."""


@dataclass(frozen=True)
class GraphRecord:
    """The tree graph as the viewer draws it: node labels and (parent, child) index pairs."""

    step: int | None
    labels: tuple[str, ...]
    edges: tuple[tuple[int, int], ...]
    moment: int | None = None


@dataclass(frozen=True)
class LearnerRecord:
    event: str
    detail: str
    removed: tuple[str, ...]
    step: int | None
    moment: int | None = None
    learner: str = ""
    """The learner that learned it ("" in recordings from before it was named)."""


@dataclass(frozen=True)
class ReplayRecord:
    reproduced: int
    total: int
    lenient: bool
    step: int | None
    moment: int | None = None


@dataclass(frozen=True)
class SessionEventRecord:
    """A journalled event of the session: its kind and its fields (as the journal holds them)."""

    kind: str
    fields: dict[str, Any]
    step: int | None
    moment: int | None


@dataclass
class RunSpan:
    """A run of the tree: its ticks are the moments after ``started`` up to ``ended`` (where its
    outcome is logged)."""

    number: int
    started: int | None
    step: int | None
    ended: int | None = None
    outcome: str | None = None
    actions: int | None = None


@dataclass(frozen=True)
class DialogueRecord:
    kind: str
    """"line", "question" or "answer"."""
    speaker: str
    text: str
    budget_left: int | None
    step: int | None
    moment: int | None = None


@dataclass(frozen=True)
class StateRecord:
    step: int | None
    sim_time: float | None
    state: dict[str, bool]
    action: str | None
    moment: int | None = None


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
    graphs: list[GraphRecord] = field(default_factory=list)
    """Every graph of the run view (the tree that ran), in order (a new one whenever it changed)."""
    tick_graphs: list[int] = field(default_factory=list)
    """For each tick, the index in ``graphs`` of the graph it was drawn on (-1: none yet)."""
    generation_graphs: list[GraphRecord] = field(default_factory=list)
    """Every graph of the teaching view: one per tree generation."""
    run_view_colours: list[tuple[int | None, tuple[tuple[int, int, int], ...]]] = field(default_factory=list)
    """Each time the run view was coloured: its moment and every node's (r, g, b)."""
    states: list[StateRecord] = field(default_factory=list)
    dialogue: list[DialogueRecord] = field(default_factory=list)
    externals: list[tuple[int | None, str]] = field(default_factory=list)
    runs: list[RunSpan] = field(default_factory=list)
    session_events: list[SessionEventRecord] = field(default_factory=list)
    scene_frames: int = 0
    camera_frames: int = 0
    first_entities: tuple[str, ...] = ()
    """The first entity paths logged over time (after the static domain): the tree comes first."""

    @property
    def final_tree_xml(self) -> str | None:
        return self.generations[-1].xml if self.generations else None

    @property
    def last_moment(self) -> int:
        moments = [m for m in (*(t.moment for t in self.ticks), *(d.moment for d in self.dialogue),
                               *(g.moment for g in self.generations)) if m is not None]
        return max(moments, default=0)

    def colours_at(self, moment: int) -> tuple[tuple[int, int, int], ...]:
        """The run view's node colours as the viewer shows them at ``moment`` (the latest logged by then)."""
        shown: tuple[tuple[int, int, int], ...] = ()
        for at, colours in self.run_view_colours:
            if at is not None and at > moment:
                break
            shown = colours
        return shown

    def tick_at(self, moment: int) -> TickRecord | None:
        return next((t for t in self.ticks if t.moment == moment), None)


_EVENT_ENTITIES = ("/tree/graph", "/tree/generation", "/study/runs", "/session/events", "/tree/xml",
                   "/learner/generations", "/learner/events", "/learner/replay", "/dialogue", "/demos", "/state",
                   "/state/external", "/domain")
_FRAME_ENTITIES = tuple("/" + e for e in SHAPE_ENTITIES.values())


def read_recording(path: str | Path) -> RecordingContents:
    """Read a ``teach`` recording back with rerun's own reader; damage, and any value missing or of
    the wrong type, is a one-line ``FormatError``: ``FILE: entity at step N: what is wrong``."""
    path = Path(path)
    if not os.path.lexists(path):
        raise FormatError("no such recording file", path)
    fd = open_regular(path, "recording")  # rerun reads what was checked, through the descriptor
    try:
        return _read_checked(path, f"/proc/self/fd/{fd}" if os.path.isdir("/proc/self/fd") else str(path))
    finally:
        os.close(fd)


def _read_checked(path: Path, opened: str) -> RecordingContents:
    """``read_recording`` of the file checked as ``path``, read by rerun as ``opened``."""
    from rerun.chunk import RrdReader

    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            reader = RrdReader(opened)
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
        message = str(exc).replace(opened, str(path)).splitlines()[0] if str(exc) else type(exc).__name__
        raise FormatError(f"damaged rerun recording: {message}", path) from None
    contents = RecordingContents(path, store.recording_id, has_blueprint=has_blueprint)
    rows: list[tuple[bytes, str, dict[str, Any]]] = []
    frames: set[tuple[Any, Any]] = set()
    for chunk in chunks:
        entity = chunk.entity_path
        if entity in _FRAME_ENTITIES:
            frame_rows = _rows(chunk, ("step", "sim_time"))
            frames.update((row.get("step"), row.get("sim_time")) for _rid, _e, row in frame_rows)
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
             and (only is None or n in only or n == "tick")]
    columns = {n: batch.column(n).to_pylist() for n in names}
    if "sim_time" in columns:
        columns["sim_time"] = [None if v is None else v.total_seconds() for v in columns["sim_time"]]
    row_ids = batch.column("rerun.controls.RowId").to_pylist()
    return [(rid, chunk.entity_path, {n: values[i] for n, values in columns.items()})
            for i, rid in enumerate(row_ids)]


class _WrongValue(ValueError):
    """A recorded value missing or of the wrong type (``_fill`` names the file, entity and step)."""


Kind = type | tuple[type, ...]


def _shown(value: Any) -> str:
    return repr(value) if len(repr(value)) <= 40 else repr(value)[:37] + "..."


def _rgb(packed: int) -> tuple[int, int, int]:
    """rerun's packed 0xRRGGBBAA colour as (r, g, b)."""
    return (packed >> 24) & 255, (packed >> 16) & 255, (packed >> 8) & 255


def _typed(value: Any, kind: Kind, name: str) -> Any:
    """``value`` when it has the ``kind`` the writer logs (a bool is not an integer)."""
    kinds = kind if isinstance(kind, tuple) else (kind,)
    if (isinstance(value, bool) and bool not in kinds) or not isinstance(value, kinds):
        raise _WrongValue(f"{name} is {_shown(value)}, not {' or '.join(k.__name__ for k in kinds)}")
    return value


def _one(row: Mapping[str, Any], name: str, kind: Kind) -> Any:
    """A field the writer always logs, as one value (rerun keeps it as a list of one)."""
    if name not in row or row[name] is None:
        raise _WrongValue(f"{name} is missing")
    value = row[name]
    if isinstance(value, list):
        if len(value) != 1:
            raise _WrongValue(f"{name} has {len(value)} values, not one")
        value = value[0]
        if value is None:
            raise _WrongValue(f"{name} is missing")
    return _typed(value, kind, name)


def _many(row: Mapping[str, Any], name: str, kind: Kind, optional: bool = False) -> list[Any]:
    """A list field; ``optional`` ones the writer leaves out when empty."""
    value = row.get(name)
    if value is None:
        if optional:
            return []
        raise _WrongValue(f"{name} is missing")
    if not isinstance(value, list):
        raise _WrongValue(f"{name} is {_shown(value)}, not a list")
    return [_typed(item, kind, name) for item in value]


def _same_length(names: tuple[str, ...], *lists: list[Any]) -> None:
    if len({len(values) for values in lists}) > 1:
        counts = ", ".join(f"{len(values)} {name}" for name, values in zip(names, lists, strict=True))
        raise _WrongValue(f"{' and '.join(names)} differ in length ({counts})")


def _fill(contents: RecordingContents, rows: list[tuple[bytes, str, dict[str, Any]]]) -> None:
    first: list[str] = []
    open_questions: list[QuestionRecord] = []
    for _rid, entity, row in rows:
        step = row.get("step")
        try:
            if step is not None:
                _typed(step, int, "step")
            if row.get("tick") is not None:
                _typed(row["tick"], int, "tick")
            if step is None and entity != "/domain":
                continue  # static display settings
            if step is not None and len(first) < 8 and (not first or first[-1] != entity):
                first.append(entity)
            _fill_row(contents, entity, row, step, open_questions)
        except _WrongValue as wrong:
            where = "(static)" if step is None else f"at step {step}" if isinstance(step, int) else "at a step"
            raise FormatError(f"{entity.lstrip('/')} {where}: {wrong}", contents.path) from None
    contents.first_entities = tuple(first)


def _fill_row(contents: RecordingContents, entity: str, row: Mapping[str, Any], step: int | None,
              open_questions: list[QuestionRecord]) -> None:
    sim_time = row.get("sim_time")
    if sim_time is not None:
        _typed(sim_time, float, "sim_time")
    moment = row.get("tick")
    if entity == "/domain" and "conditions" in row:
        contents.domain_name = _one(row, "name", str)
        contents.conditions = tuple(_many(row, "conditions", str))
        contents.actions = tuple(_many(row, "actions", str))
        contents.goal = tuple(_many(row, "goal", str, optional=True))
    elif entity == "/learner/generations":
        contents.generations.append(GenerationRecord(_one(row, "generation", int), _one(row, "reason", str),
                                                     _one(row, "nodes", int), _one(row, "xml", str), step, moment))
    elif entity == "/learner/events":
        contents.learner_events.append(LearnerRecord(_one(row, "event", str), _one(row, "detail", str),
                                                     tuple(_many(row, "removed", str, optional=True)), step, moment,
                                                     _one(row, "learner", str) if row.get("learner") else ""))
    elif entity == "/learner/replay":
        contents.replays.append(ReplayRecord(_one(row, "reproduced", int), _one(row, "total", int),
                                             _one(row, "lenient", bool), step, moment))
    if entity == "/tree/graph" and row.get("GraphNodes:colors") is not None:
        colours = tuple(_many(row, "GraphNodes:colors", int))
        contents.run_view_colours.append((moment, tuple(_rgb(c) for c in colours)))
    if entity == "/tree/graph" and "status" in row:
        _tick_row(contents, row, step, sim_time)
    elif entity in ("/tree/graph", "/tree/generation") and row.get("GraphNodes:node_ids") is not None:
        _graph_row(contents, row, step, entity)  # (a row with colours and labels only restyles the standing graph)
    elif entity == "/study/runs" and row.get("run") is not None:
        if row.get("outcome") is None:
            contents.runs.append(RunSpan(_one(row, "run", int), moment, step))
        elif contents.runs and contents.runs[-1].number == _one(row, "run", int):
            run = contents.runs[-1]
            run.ended, run.outcome = moment, _one(row, "outcome", str)
            run.actions = _one(row, "run_actions", int)
    elif entity == "/state":
        names = _many(row, "conditions", str, optional=True)
        values = _many(row, "values", bool, optional=True)
        _same_length(("conditions", "values"), names, values)
        contents.states.append(StateRecord(step, sim_time, dict(zip(names, values, strict=True)),
                                           _one(row, "action", str) or None, moment))
    elif entity == "/state/external":
        contents.externals.append((step, _one(row, "external", str)))
    elif entity == "/demos":
        states = tuple(tuple(c == "1" for c in s) for s in _many(row, "states", str))
        labels = tuple(_many(row, "step_labels", str))
        _same_length(("states", "step_labels"), list(states), list(labels))
        contents.demonstrations.append(DemoRecord(_one(row, "name", str), states, labels,
                                                  _one(row, "reached_goal", bool), _one(row, "csv", str), step, moment))
    elif entity == "/dialogue":
        _dialogue_row(contents, row, step, open_questions)
    elif entity == "/session/events":
        try:
            fields = json.loads(_one(row, "fields", str))
        except ValueError:
            raise _WrongValue("fields is not JSON") from None
        if not isinstance(fields, dict):
            raise _WrongValue("fields is not a JSON object")
        contents.session_events.append(SessionEventRecord(_one(row, "kind", str), fields, step, moment))


_TRACE = ("trace_nodes", "trace_labels", "trace_status")


def _tick_row(contents: RecordingContents, row: Mapping[str, Any], step: int | None, sim_time: float | None) -> None:
    traced = [name for name in _TRACE if row.get(name) is not None]
    if traced and len(traced) < len(_TRACE):
        raise _WrongValue(f"{next(n for n in _TRACE if n not in traced)} is missing beside {traced[0]}")
    nodes = _many(row, "trace_nodes", int, optional=True)
    labels = _many(row, "trace_labels", str, optional=True)
    statuses = _many(row, "trace_status", str, optional=True)
    _same_length(_TRACE, nodes, labels, statuses)
    contents.ticks.append(TickRecord(step, sim_time, _one(row, "generation", int), _one(row, "status", str),
                                     _one(row, "action", str) or None, tuple(zip(labels, statuses, strict=True)),
                                     tuple(nodes), row.get("tick")))
    contents.tick_graphs.append(len(contents.graphs) - 1)


def _graph_row(contents: RecordingContents, row: Mapping[str, Any], step: int | None, entity: str) -> None:
    labels = _many(row, "GraphNodes:labels", str)
    ids = _many(row, "GraphNodes:node_ids", str)
    _same_length(("node labels", "node ids"), labels, ids)
    index = {node: i for i, node in enumerate(ids)}
    edges = []
    for edge in _many(row, "GraphEdges:edges", dict, optional=True):
        ends = (edge.get("first"), edge.get("second"))
        if not all(isinstance(end, str) and end in index for end in ends):
            raise _WrongValue(f"an edge joins {_shown(ends)}, not two of the graph's nodes")
        edges.append((index[ends[0]], index[ends[1]]))
    graphs = contents.graphs if entity == "/tree/graph" else contents.generation_graphs
    graphs.append(GraphRecord(step, tuple(labels), tuple(edges), row.get("tick")))


def _dialogue_row(contents: RecordingContents, row: Mapping[str, Any], step: int | None,
                  open_questions: list[QuestionRecord]) -> None:
    kind = _one(row, "kind", str)
    budget = _one(row, "budget_left", int)
    text = _one(row, "text", str)
    moment = row.get("tick")
    contents.dialogue.append(DialogueRecord(kind, _one(row, "speaker", str), text,
                                            None if budget < 0 else budget, step, moment))
    if kind == "question":
        record = QuestionRecord(text, budget, step=step, moment=moment)
        contents.questions.append(record)
        open_questions.append(record)
    elif kind == "answer":
        asked = _one(row, "question", str)
        match = next((q for q in reversed(open_questions) if q.question == asked),
                     open_questions[-1] if open_questions else None)
        if match is None:  # an answer to a question the recording did not see: keep it anyway
            match = QuestionRecord(asked, -1, step=step)
            contents.questions.append(match)
        else:
            open_questions.remove(match)
        match.answer_step = step
        match.answer_moment = moment
        match.answer = _one(row, "answer", str)
        match.change = _one(row, "change", str)
