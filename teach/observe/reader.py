"""A teach recording read back with rerun's own reader into plain Python records."""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from teach.errors import FormatError
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
_FRAME_ENTITIES = tuple("/" + e for e in SHAPE_ENTITIES.values())


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
    try:
        _fill(contents, rows)
    except _WrongValue as wrong:
        raise FormatError(f"damaged rerun recording: {wrong}", path) from None
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


class _WrongValue(ValueError):
    """A recorded value of the wrong type (turned into a one-line ``FormatError`` by the reader)."""


Kind = type | tuple[type, ...]


def _typed(value: Any, kind: Kind, name: str) -> Any:
    """``value`` when it has the ``kind`` the writer logs (a bool is not an integer)."""
    kinds = kind if isinstance(kind, tuple) else (kind,)
    if isinstance(value, bool) and bool not in kinds:
        raise _WrongValue(f"{name} is {value!r}, not {' or '.join(k.__name__ for k in kinds)}")
    if not isinstance(value, kinds):
        shown = repr(value) if len(repr(value)) <= 40 else repr(value)[:37] + "..."
        raise _WrongValue(f"{name} is {shown}, not {' or '.join(k.__name__ for k in kinds)}")
    return value


def _one(row: Mapping[str, Any], name: str, default: Any, kind: Kind) -> Any:
    value = row.get(name)
    if isinstance(value, list):
        value = value[0] if value else None
    return default if value is None else _typed(value, kind, name)


def _many(row: Mapping[str, Any], name: str, kind: Kind) -> list[Any]:
    value = row.get(name)
    if value is None:
        return []
    if not isinstance(value, list):
        raise _WrongValue(f"{name} is {value!r}, not a list")
    return [_typed(item, kind, name) for item in value]


def _fill(contents: RecordingContents, rows: list[tuple[bytes, str, dict[str, Any]]]) -> None:
    first: list[str] = []
    open_questions: list[QuestionRecord] = []
    for _rid, entity, row in rows:
        step = row.get("step")
        if step is not None:
            _typed(step, int, f"{entity} step")
        if step is None and entity != "/domain":
            continue  # static display settings
        if step is not None and len(first) < 8 and (not first or first[-1] != entity):
            first.append(entity)
        if entity == "/domain" and "conditions" in row:
            contents.domain_name = _one(row, "name", None, str)
            contents.conditions = tuple(_many(row, "conditions", str))
            contents.actions = tuple(_many(row, "actions", str))
            contents.goal = tuple(_many(row, "goal", str))
        elif entity == "/learner/generations":
            contents.generations.append(GenerationRecord(_one(row, "generation", -1, int), _one(row, "reason", "", str),
                                                         _one(row, "nodes", 0, int), _one(row, "xml", "", str), step))
        elif entity == "/learner/events":
            contents.learner_events.append(LearnerRecord(_one(row, "event", "", str), _one(row, "detail", "", str),
                                                         tuple(_many(row, "removed", str)), step))
        elif entity == "/learner/replay":
            contents.replays.append(ReplayRecord(_one(row, "reproduced", 0, int), _one(row, "total", 0, int),
                                                 _one(row, "lenient", False, bool), step))
        elif entity == "/tree/graph" and "status" in row:
            trace = tuple(zip(_many(row, "trace_labels", str), _many(row, "trace_status", str), strict=False))
            contents.ticks.append(TickRecord(step, row.get("sim_time"), _one(row, "generation", -1, int),
                                             _one(row, "status", "", str), _one(row, "action", None, str) or None,
                                             trace))
        elif entity == "/state":
            state = dict(zip(_many(row, "conditions", str), map(bool, _many(row, "values", (bool, int))), strict=False))
            action = _one(row, "action", None, str) or None
            contents.states.append(StateRecord(step, row.get("sim_time"), state, action))
        elif entity == "/state/external":
            contents.externals.append((step, _one(row, "external", "", str)))
        elif entity == "/demos":
            states = tuple(tuple(c == "1" for c in s) for s in _many(row, "states", str))
            contents.demonstrations.append(DemoRecord(_one(row, "name", "", str), states,
                                                      tuple(_many(row, "step_labels", str)),
                                                      _one(row, "reached_goal", False, bool),
                                                      _one(row, "csv", "", str), step))
        elif entity == "/dialogue":
            _dialogue_row(contents, row, step, open_questions)
    contents.first_entities = tuple(first)


def _dialogue_row(contents: RecordingContents, row: Mapping[str, Any], step: int | None,
                  open_questions: list[QuestionRecord]) -> None:
    kind = _one(row, "kind", "line", str)
    budget = _one(row, "budget_left", -1, int)
    text = _one(row, "text", "", str)
    contents.dialogue.append(DialogueRecord(kind, _one(row, "speaker", "", str), text,
                                            None if budget is None or budget < 0 else budget, step))
    if kind == "question":
        record = QuestionRecord(text, budget, step=step)
        contents.questions.append(record)
        open_questions.append(record)
    elif kind == "answer":
        asked = _one(row, "question", "", str)
        match = next((q for q in reversed(open_questions) if q.question == asked),
                     open_questions[-1] if open_questions else None)
        if match is None:  # an answer to a question the recording did not see: keep it anyway
            match = QuestionRecord(asked, -1, step=step)
            contents.questions.append(match)
        else:
            open_questions.remove(match)
        match.answer = _one(row, "answer", "", str)
        match.change = _one(row, "change", "", str)
