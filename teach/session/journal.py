"""The session journal: what was taught, in order, so a killed session resumes intact.

The journal is the truth of a session: demonstrations are referenced by their CSV files
(written first), answers are stored with the situation they answered. Events are typed here
and stored as JSON objects with a ``kind``.

The file is JSON Lines (version 2): its first line is a snapshot of the whole journal, each
further line what one save added (new events, the step clock, the open demonstration's new
steps). ``SessionStore`` writes the snapshot atomically when it first saves (so a resume
compacts the file) and appends and fsyncs one line per save after that: a save costs what it
adds, not what the session holds. A last line without its newline is a save a kill cut short,
never acknowledged: it is left out. A version 1 journal (one JSON document) is still read.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path
from typing import Any, ClassVar

from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State, check_numbers
from teach.errors import FormatError
from teach.fsutil import Types, decode_text, parse_json, validate
from teach.session.settings import LANGUAGES, WorldKind

VERSION = 2
READABLE_VERSIONS = (1, 2)


def state_text(state: State) -> str:
    return "".join("1" if v else "0" for v in state)


def parse_state_text(text: str) -> State:
    return tuple(c == "1" for c in text)


_HEADER: dict[str, Types] = {"session": str, "domain": str, "lang": str, "questions": int, "world": str, "seed": int,
                             "step": int, "events": list, "version": int}
_HEADER_OPTIONAL: dict[str, Types] = {"origin": str, "open_steps": list, "open_state": str, "open_run": str,
                                      "open_robot": int, "guess": bool}
_SAVE_KEYS: dict[str, Types] = {"events": list, "step": int, "open_kept": int, "open_steps": list, "open_state": str,
                                "open_run": str, "open_robot": int}
"""A line after the snapshot: what one save changed. ``open_steps`` replace the open steps from
number ``open_kept`` on (the steps before it stay)."""
_EVENT_KEYS: dict[str, tuple[dict[str, Types], dict[str, Types]]] = {
    "demo": ({"kind": str, "file": str, "source": str}, {}),
    "undo": ({"kind": str}, {}),
    "redo": ({"kind": str}, {}),
    "model": ({"kind": str, "file": str}, {}),
    "asked": ({"kind": str}, {"state": str, "model_question": dict}),
    "answer": ({"kind": str, "state": str, "answer": str, "question": str}, {"asked_about": str}),
    "model_answer": ({"kind": str, "question": dict, "answer": str}, {}),
    "guided_action": ({"kind": str, "name": str, "motion": str}, {}),
    "situation": ({"kind": str, "state": str, "how": str}, {"seed": int}),
}


@dataclass(frozen=True)
class DemoLearned:
    kind: ClassVar[str] = "demo"
    file: str
    """The demonstration's CSV file, in the session's demos folder."""
    source: str


@dataclass(frozen=True)
class Undone:
    """The last learning event no longer counts."""

    kind: ClassVar[str] = "undo"


@dataclass(frozen=True)
class Redone:
    """The learning event the last undo took back counts again."""

    kind: ClassVar[str] = "redo"


@dataclass(frozen=True)
class ModelLoaded:
    kind: ClassVar[str] = "model"
    file: str
    """The action definitions' file, absolute."""


@dataclass(frozen=True)
class Asked:
    """A question was asked (and paid for): about a situation, or about the action definitions."""

    kind: ClassVar[str] = "asked"
    state: str | None = None
    model_question: dict[str, Any] | None = None


@dataclass(frozen=True)
class Answered:
    kind: ClassVar[str] = "answer"
    state: str
    answer: str
    """An action name, "done" or "skip"."""
    question: str
    asked_about: str | None = None
    """For "may I still do X here?": X; for "is the task done here?": "done" (an answer that
    names something else also says no to it)."""


@dataclass(frozen=True)
class ModelAnswered:
    kind: ClassVar[str] = "model_answer"
    question: dict[str, Any]
    answer: str
    """The teacher's words, or "skip"."""


# --- an action taught by guidance (issue 12, the guide helper)
@dataclass(frozen=True)
class GuidedActionTaught:
    """A new action the teacher named for a guided motion: in the session's domain copy, its
    motion in ``motion`` (a file in the demos folder). Not undoable: later steps may use it."""

    kind: ClassVar[str] = "guided_action"
    name: str
    motion: str


# --- the world's situation (issue 14: resume restores it)

SITUATION_CAUSES = ("start", "reset", "run", "after")


@dataclass(frozen=True)
class Situated:
    """The world is in ``state`` with no demonstration open: a resume sets that situation up
    again when nothing came after it. ``how`` says what put it there: 'start', 'reset', the
    end of a run, or "after" any other line (a finished or cancelled demonstration, an undo)."""

    kind: ClassVar[str] = "situation"
    state: str
    how: str
    seed: int | None = None
    """The number of 'reset N': the same reset puts a world in exactly the same situation again."""


Event = DemoLearned | Undone | Redone | ModelLoaded | Asked | Answered | ModelAnswered | GuidedActionTaught | Situated
LEARNING_EVENTS = (DemoLearned, Answered, ModelLoaded, ModelAnswered)
_BY_KIND: dict[str, type[Event]] = {cls.kind: cls for cls in (DemoLearned, Undone, Redone, ModelLoaded, Asked,
                                                              Answered, ModelAnswered, GuidedActionTaught, Situated)}


def event_to_json(event: Event) -> dict[str, Any]:
    data = {"kind": event.kind, **asdict(event)}
    return {k: v for k, v in data.items() if v is not None}


def event_from_json(data: Any, where: Path, number: int) -> Event:
    """One stored event, checked against its kind's schema; a ``FormatError`` naming the event when it is not one."""
    place = f"events[{number}]"
    kind = validate(data, where, {"kind": str}, where=place, extra=True)["kind"]
    if kind not in _EVENT_KEYS:
        raise FormatError(f"{place}: kind: unknown event kind {kind!r} (known: {', '.join(_EVENT_KEYS)})", where)
    required, optional = _EVENT_KEYS[str(kind)]
    checked = validate(data, where, required, optional, where=place)
    state = checked.get("state")
    if isinstance(state, str) and not set(state) <= {"0", "1"}:
        raise FormatError(f"{place}: state: must be a string of 0s and 1s, got {state[:40]!r}", where)
    file = checked.get("file")
    if kind == "demo" and isinstance(file, str) and (not file or "/" in file or "\\" in file or file.startswith(".")):
        raise FormatError(f"{place}: file: must name a file in the session's demos folder, got {file[:40]!r}", where)
    if kind == "situation" and checked["how"] not in SITUATION_CAUSES:
        known = ", ".join(SITUATION_CAUSES)
        raise FormatError(f"{place}: how: must be one of {known}, got {str(checked['how'])[:40]!r}", where)
    if isinstance(checked.get("seed"), int) and int(checked["seed"]) < 0:  # type: ignore[call-overload]
        raise FormatError(f"{place}: seed: must be 0 or more, got {checked['seed']}", where)
    cls = _BY_KIND[str(kind)]
    return cls(**{k: v for k, v in checked.items() if k != "kind"})  # type: ignore[arg-type]


def effective_events(events: list[Event]) -> list[Event]:
    """The journal's learning events with every undone one removed (and every redone one back)."""
    return _replayed(events)[0]


def redoable(events: list[Event]) -> list[Event]:
    """What a 'redo' would bring back, last undone last: empty once something new was learned."""
    return _replayed(events)[1]


def _replayed(events: list[Event]) -> tuple[list[Event], list[Event]]:
    kept: list[Event] = []
    undone: list[Event] = []
    for event in events:
        if isinstance(event, Undone):
            while kept and _skipped(kept[-1]):
                kept.pop()  # a skipped question taught nothing: an undo takes back what did teach
            if kept:
                undone.append(kept.pop())
        elif isinstance(event, Redone):
            if undone:
                kept.append(undone.pop())
        elif isinstance(event, LEARNING_EVENTS):
            kept.append(event)
            undone.clear()  # something new: what was undone before it stays undone
    return kept, undone


def _skipped(event: Event) -> bool:
    return isinstance(event, Answered | ModelAnswered) and event.answer == "skip"


_CLOCK_AND_OPEN = ("step", "open_steps", "open_state", "open_run", "open_robot")
"""The journal's fields a save may change besides adding events; the others never change once written."""


@dataclass(frozen=True)
class Saved:
    """What a journal file holds after a save, to tell what the next save adds to it."""

    header: tuple[object, ...]
    events: int
    last: Event | None
    step: int
    open_steps: tuple[tuple[str | int, ...], ...]
    open_state: str
    open_run: str
    open_robot: int


@dataclass
class Journal:
    session: str
    domain: str
    lang: str = "en"
    questions: int = 5
    world: str = "mujoco"
    seed: int = 0
    step: int = 0  # the session's step clock, so a resumed session's recording goes on from it
    events: list[Event] = field(default_factory=list)
    version: int = VERSION
    origin: str = ""
    """What made the session: "replay:<dialogue file, absolute>" for a replay, "" for a live session."""
    open_steps: list[list[str | int]] = field(default_factory=list)
    """The open demonstration's steps as shown so far, ``[state, action, words]`` each, so a
    resume restores what the teacher saw acknowledged; ``open_state`` is the world after them."""
    open_state: str = ""
    open_run: str = ""
    """The action the robot had begun when the session ended in the middle of a run: then
    ``open_steps`` are the steps it finished and ``open_state`` the world before that action."""
    open_robot: int = 0
    """How many of ``open_steps`` (the first ones) a run did: a stopped run the teacher has not
    added to yet, which 'run' may try again after a resume as before it."""
    guess: bool = False
    """The session learns with the guessing learner (``--guess``), not the safe one."""

    def to_json(self) -> dict[str, Any]:
        """The whole journal as one JSON object (the snapshot line's content)."""
        data = {f.name: getattr(self, f.name) for f in fields(self)}
        data["events"] = [event_to_json(e) for e in self.events]
        data["version"] = VERSION
        return data

    def snapshot_text(self) -> str:
        """The journal as a file of one line: what a first save writes (atomically)."""
        return json.dumps(self.to_json(), ensure_ascii=False) + "\n"

    def saved(self) -> Saved:
        return Saved(self._header(), len(self.events), self.events[-1] if self.events else None, self.step,
                     tuple(map(tuple, self.open_steps)), self.open_state, self.open_run, self.open_robot)

    def changes_since(self, saved: Saved) -> str | None:
        """The line that brings a file holding ``saved`` up to this journal ("" when nothing
        changed), or None when appending cannot (a field that never changes did, events went)."""
        if saved.header != self._header() or len(self.events) < saved.events or \
                (saved.events and self.events[saved.events - 1] is not saved.last):
            return None
        change: dict[str, Any] = {}
        if len(self.events) > saved.events:
            change["events"] = [event_to_json(e) for e in self.events[saved.events:]]
        if self.step != saved.step:
            change["step"] = self.step
        steps = tuple(map(tuple, self.open_steps))
        if steps != saved.open_steps:
            kept = next((n for n, (a, b) in enumerate(zip(steps, saved.open_steps, strict=False)) if a != b),
                        min(len(steps), len(saved.open_steps)))
            change["open_kept"], change["open_steps"] = kept, self.open_steps[kept:]
        for key in ("open_state", "open_run", "open_robot"):
            if getattr(self, key) != getattr(saved, key):
                change[key] = getattr(self, key)
        return json.dumps(change, ensure_ascii=False) + "\n" if change else ""

    def _header(self) -> tuple[object, ...]:
        return tuple(getattr(self, f.name) for f in fields(self) if f.name not in ("events", *_CLOCK_AND_OPEN))

    @classmethod
    def from_bytes(cls, data: bytes, where: Path) -> Journal:
        """A journal file's content: a last line a kill cut short (no newline after a first
        line) is left out, whatever it holds; the rest as ``from_text``."""
        if data.split(b"\n", 1)[0].strip() != b"{" and b"\n" in data and not data.endswith(b"\n"):
            data = data[:data.rindex(b"\n") + 1]
        return cls.from_text(decode_text(data, "session journal", where), where)

    @classmethod
    def from_text(cls, text: str, where: Path) -> Journal:
        """Parse a journal file's text against its schema; damage is a one-line ``FormatError``
        naming ``where``, the line and the key that is wrong."""
        try:
            check_numbers(text, where, "json")
            if text.split("\n", 1)[0].strip() == "{":  # version 1: one document over many lines
                return cls._checked(parse_json(text, where, "the session journal"), where)
            lines = text.split("\n")
            if lines[-1] == "" and len(lines) > 1:
                lines.pop()
            try:
                journal = cls._checked(parse_json(lines[0], where, "the session journal"), where)
            except FormatError as error:  # the snapshot is line 1
                raise FormatError(error.message, where, error.line or 1) from None
            for number, line in enumerate(lines[1:], start=2):
                journal._apply(line, where, number)
            return journal
        except FormatError as error:
            raise FormatError(f"the session journal is damaged: {error.message}", where, error.line) from None

    def _apply(self, line: str, where: Path, number: int) -> None:
        """One saved change (a line after the snapshot), checked as the snapshot is."""
        try:
            change = validate(parse_json(line, where, "the session journal"), where, {}, _SAVE_KEYS)
            if self.version != VERSION:
                raise FormatError(f"a version {self.version} journal is one JSON document, not lines", where)
            stored: list[object] = change.get("events", [])  # type: ignore[assignment]
            self.events += [event_from_json(e, where, len(self.events) + n) for n, e in enumerate(stored)]
            if "step" in change:
                self.step = _at_least_zero("step", change["step"], where)
            if "open_steps" in change or "open_kept" in change:
                kept = _at_least_zero("open_kept", change.get("open_kept", 0), where)
                if kept > len(self.open_steps):
                    raise FormatError(f"open_kept: {kept}, but only {len(self.open_steps)} steps are open", where)
                added: list[object] = change.get("open_steps", [])  # type: ignore[assignment]
                _check_open_steps(added, where, kept)
                self.open_steps = self.open_steps[:kept] + added  # type: ignore[operator]
            if "open_state" in change:
                self.open_state = _checked_open_state(change["open_state"], where)
            if "open_run" in change:
                self.open_run = str(change["open_run"])
            if "open_robot" in change:
                self.open_robot = _at_least_zero("open_robot", change["open_robot"], where)
        except FormatError as error:
            raise FormatError(error.message, where, number) from None

    @classmethod
    def _checked(cls, data: object, where: Path) -> Journal:
        if isinstance(data, dict) and data.get("version") not in READABLE_VERSIONS:
            raise FormatError(f"not a session journal of version {' or '.join(map(str, READABLE_VERSIONS))} "
                              f"(this teach writes version {VERSION})", where)
        header = validate(data, where, _HEADER, _HEADER_OPTIONAL)
        for key in ("questions", "seed", "step"):
            _at_least_zero(key, header[key], where)
        for key, known in (("lang", LANGUAGES), ("world", tuple(WorldKind))):
            if header[key] not in known:
                raise FormatError(f"{key}: must be one of {', '.join(known)}, got {str(header[key])[:40]!r}", where)
        _check_open_steps(header.get("open_steps", []), where)  # type: ignore[arg-type]
        _checked_open_state(header.get("open_state", ""), where)
        _at_least_zero("open_robot", header.get("open_robot", 0), where)
        stored: list[object] = header.pop("events")  # type: ignore[assignment]
        events = [event_from_json(e, where, n) for n, e in enumerate(stored)]
        return cls(events=events, **header)  # type: ignore[arg-type]


def _at_least_zero(key: str, value: object, where: Path) -> int:
    if int(value) < 0:  # type: ignore[call-overload]
        raise FormatError(f"{key}: must be 0 or more, got {value}", where)
    return int(value)  # type: ignore[call-overload]


def _check_open_steps(open_steps: list[object], where: Path, first: int = 0) -> None:
    for number, entry in enumerate(open_steps, start=first):
        if not (isinstance(entry, list) and len(entry) == 3 and isinstance(entry[0], str)
                and set(entry[0]) <= {"0", "1"} and type(entry[1]) is int and isinstance(entry[2], str)):
            raise FormatError(f"open_steps[{number}]: must be [state of 0s and 1s, action id, words]", where)


def check_open_actions(journal: Journal, domain: Domain, where: Path) -> None:
    """On resume: every open step's action is one of the domain's, an external one (-1) or the goal (0)."""
    for number, (_, action, _) in enumerate(journal.open_steps):
        if action not in (EXTERNAL_ACTION, GOAL_ACTION) and not domain.has_action(action):
            raise FormatError(f"the session journal is damaged: open_steps[{number}]: action {action} is not an "
                              f"action of the domain", where)


def _checked_open_state(value: object, where: Path) -> str:
    if set(str(value)) - {"0", "1"}:
        raise FormatError("open_state: must be 0s and 1s", where)
    return str(value)
