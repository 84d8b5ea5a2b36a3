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

VERSION = 1


def state_text(state: State) -> str:
    return "".join("1" if v else "0" for v in state)


def parse_state_text(text: str) -> State:
    return tuple(c == "1" for c in text)


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


@dataclass(frozen=True)
class ModelAnswered:
    kind: ClassVar[str] = "model_answer"
    question: dict[str, Any]
    answer: str
    """The teacher's words, or "skip"."""


Event = DemoLearned | Undone | ModelLoaded | Asked | Answered | ModelAnswered
LEARNING_EVENTS = (DemoLearned, Answered, ModelLoaded, ModelAnswered)
_BY_KIND: dict[str, type[Event]] = {cls.kind: cls for cls in (DemoLearned, Undone, ModelLoaded, Asked, Answered,
                                                              ModelAnswered)}


def event_to_json(event: Event) -> dict[str, Any]:
    data = {"kind": event.kind, **asdict(event)}
    return {k: v for k, v in data.items() if v is not None}


def event_from_json(data: Any) -> Event:
    """One stored event; ``ValueError`` when it is not one."""
    if not isinstance(data, dict) or data.get("kind") not in _BY_KIND:
        raise ValueError(f"unknown event {data!r}")
    cls = _BY_KIND[data["kind"]]
    names = {f.name for f in fields(cls)}
    try:
        return cls(**{k: v for k, v in data.items() if k in names})
    except TypeError as error:
        raise ValueError(f"a {data['kind']!r} event is incomplete ({error})") from None


def effective_events(events: list[Event]) -> list[Event]:
    """The journal's learning events with every undone one removed."""
    kept: list[Event] = []
    for event in events:
        if isinstance(event, Undone):
            if kept:
                kept.pop()
        elif isinstance(event, LEARNING_EVENTS):
            kept.append(event)
    return kept


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

    def to_text(self) -> str:
        data = {f.name: getattr(self, f.name) for f in fields(self)}
        data["events"] = [event_to_json(e) for e in self.events]
        return json.dumps(data, indent=1, ensure_ascii=False) + "\n"

    @classmethod
    def from_text(cls, text: str, where: Path) -> Journal:
        """Parse a journal file's text; damage is a one-line ``FormatError`` naming ``where``."""
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise FormatError(f"the session journal is damaged: {exc}", where, exc.lineno) from None
        if not isinstance(data, dict) or data.get("version") != VERSION:
            raise FormatError(f"not a version {VERSION} session journal", where)
        try:
            events = [event_from_json(e) for e in data.pop("events", [])]
            return cls(events=events, **data)
        except (TypeError, ValueError) as exc:
            raise FormatError(f"the session journal is damaged: {exc}", where) from None
