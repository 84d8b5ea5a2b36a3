"""A session's settings, in one place: what the command line chose and a resume restores."""

from __future__ import annotations

import re
import shlex
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from teach.errors import TeachError
from teach.messages import Lang

SESSION_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_-]*$")
LANGUAGES = tuple(Lang)


class WorldKind(StrEnum):
    MUJOCO = "mujoco"
    SYMBOLIC = "symbolic"
    OFFLINE = "offline"

    @classmethod
    def parse(cls, text: str) -> WorldKind:
        if text not in tuple(cls):
            raise TeachError(f"unknown world {text!r} (choose from {', '.join(cls)})")
        return cls(text)


@dataclass(frozen=True)
class Settings:
    session: str
    domain: Path | None = None
    """The domain file; None: the ball-in-bin domain."""
    lang: Lang = Lang.EN
    """Parsed where a string enters (the command line, a dialogue's ``@lang``, a journal), with the
    file and line it came from: ``Lang.parse``; checked again here for callers mypy does not see."""
    questions: int = 5
    seed: int = 0
    world: WorldKind = WorldKind.MUJOCO
    base: Path = Path(".")
    """The folder holding demos/, trees/ and recordings/."""
    record: bool = True
    spawn: bool = False
    viewer: bool = False
    pace: float = 0.0
    """Simulated seconds per wall-clock second during runs (0: as fast as possible)."""
    label_questions: int = 5
    """The cap on labelling questions about guided motion (apart from ``questions``)."""
    safe: bool = True
    """The safe learner (the default): it checks every precondition and goal literal it has not
    ruled out, so it never acts on a guess; it stops and asks where it is unsure. False: the
    earlier model learner, which generalises by guessing (``--guess``, for comparison only)."""
    facilitator: bool = False
    """Show identifiers too: conditions by name, the symbolic tree (default: plain words)."""
    groot: int | None = None
    """Run trees through BehaviorTree.CPP with a Groot2 publisher on this port (None: our own tick)."""
    voice: bool = False
    """The robot says its lines aloud (teach/voice/) and writes them to recordings/<session>/speech/."""

    @property
    def resume_words(self) -> str:
        """What follows ``teach session --resume`` to continue this session from where it was
        started: its name, and the base folder where that is not the working folder (a hint
        without it, run elsewhere, found no journal)."""
        if Path(self.base).resolve() == Path.cwd().resolve():
            return self.session
        return f"{self.session} --base {shlex.quote(str(self.base))}"

    def __post_init__(self) -> None:
        if not SESSION_NAME.match(self.session):
            raise TeachError(f"session name {self.session!r} must be letters, digits, '-' and '_' "
                             "(it names folders under demos/ and trees/)")
        object.__setattr__(self, "lang", Lang.parse(self.lang))  # a plain "de" from unchecked code too
        if self.questions < 0:
            raise TeachError("--questions must be 0 or more")
        object.__setattr__(self, "world", WorldKind.parse(self.world))
