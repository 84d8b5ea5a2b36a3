"""The session journal: what was taught, in order, so a killed session resumes intact.

The journal is the truth of a session: demonstrations are referenced by their CSV files
(written first), answers are stored with the situation they answered. It is rewritten
atomically after every event.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from teach.domain import State
from teach.errors import FormatError
from teach.fsutil import atomic_write_text

VERSION = 1


def state_text(state: State) -> str:
    return "".join("1" if v else "0" for v in state)


def parse_state_text(text: str) -> State:
    return tuple(c == "1" for c in text)


@dataclass
class Journal:
    session: str
    domain: str
    lang: str = "en"
    questions: int = 5
    world: str = "mujoco"
    seed: int = 0
    step: int = 0  # the session's step clock, so a resumed session's recording goes on from it
    events: list[dict] = field(default_factory=list)
    version: int = VERSION

    def add(self, path: Path, **event: object) -> None:
        self.events.append(dict(event))
        self.save(path)

    def save(self, path: Path) -> None:
        atomic_write_text(path, json.dumps(asdict(self), indent=1, ensure_ascii=False) + "\n")

    @classmethod
    def load(cls, path: Path) -> "Journal":
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise FormatError("no such session journal (was the session id right?)", path) from None
        except (json.JSONDecodeError, UnicodeDecodeError) as exc:
            line = getattr(exc, "lineno", None)
            raise FormatError(f"the session journal is damaged: {exc}", path, line) from None
        if not isinstance(data, dict) or data.get("version") != VERSION:
            raise FormatError(f"not a version {VERSION} session journal", path)
        try:
            return cls(**data)
        except TypeError as exc:
            raise FormatError(f"the session journal is damaged: {exc}", path) from None
