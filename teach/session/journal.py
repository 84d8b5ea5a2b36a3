"""The session journal: what was taught, in order, so a killed session resumes intact.

The journal is the truth of a session: demonstrations are referenced by their CSV files
(written first), answers are stored with the situation they answered. Events are typed here
and stored as JSON objects with a ``kind``; ``SessionStore`` rewrites the file atomically
after every event.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path
from typing import Any, ClassVar

from teach.domain import State
from teach.errors import FormatError
from teach.fsutil import Types, parse_json, validate
from teach.session.settings import LANGUAGES, WorldKind

VERSION = 1


def state_text(state: State) -> str:
    return "".join("1" if v else "0" for v in state)


def parse_state_text(text: str) -> State:
    return tuple(c == "1" for c in text)


_HEADER: dict[str, Types] = {"session": str, "domain": str, "lang": str, "questions": int, "world": str, "seed": int,
                             "step": int, "events": list, "version": int}
_HEADER_OPTIONAL: dict[str, Types] = {"origin": str, "open_steps": list, "open_state": str, "open_run": str,
                                      "guess": bool}
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
    guess: bool = False
    """The session learns with the guessing learner (``--guess``), not the safe one."""

    def to_text(self) -> str:
        data = {f.name: getattr(self, f.name) for f in fields(self)}
        data["events"] = [event_to_json(e) for e in self.events]
        return json.dumps(data, indent=1, ensure_ascii=False) + "\n"

    @classmethod
    def from_text(cls, text: str, where: Path) -> Journal:
        """Parse a journal file's text against its schema; damage is a one-line ``FormatError``
        naming ``where`` and the key that is wrong."""
        try:
            return cls._checked(parse_json(text, where, "the session journal"), where)
        except FormatError as error:
            raise FormatError(f"the session journal is damaged: {error.message}", where, error.line) from None

    @classmethod
    def _checked(cls, data: object, where: Path) -> Journal:
        if isinstance(data, dict) and data.get("version") != VERSION:
            raise FormatError(f"not a version {VERSION} session journal", where)
        header = validate(data, where, _HEADER, _HEADER_OPTIONAL)
        for key in ("questions", "seed", "step"):
            if int(header[key]) < 0:  # type: ignore[call-overload]
                raise FormatError(f"{key}: must be 0 or more, got {header[key]}", where)
        for key, known in (("lang", LANGUAGES), ("world", tuple(WorldKind))):
            if header[key] not in known:
                raise FormatError(f"{key}: must be one of {', '.join(known)}, got {str(header[key])[:40]!r}", where)
        open_steps: list[object] = header.get("open_steps", [])  # type: ignore[assignment]
        for number, entry in enumerate(open_steps):
            if not (isinstance(entry, list) and len(entry) == 3 and isinstance(entry[0], str)
                    and set(entry[0]) <= {"0", "1"} and type(entry[1]) is int and isinstance(entry[2], str)):
                raise FormatError(f"open_steps[{number}]: must be [state of 0s and 1s, action id, words]", where)
        if set(str(header.get("open_state", ""))) - {"0", "1"}:
            raise FormatError("open_state: must be 0s and 1s", where)
        stored: list[object] = header.pop("events")  # type: ignore[assignment]
        events = [event_from_json(e, where, n) for n, e in enumerate(stored)]
        return cls(events=events, **header)  # type: ignore[arg-type]
