"""What a session publishes to its drivers: one view of it, taken when a driver asks.

Drivers (the terminal, the scripted replay, voice) read the session's mode, its budgets, the
guide's state and whether a run can start from a ``SessionView``, never from the machine's
members, so the machine can change inside without touching them.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from teach.domain import Domain
from teach.messages import Lang


class Mode(StrEnum):
    IDLE = "idle"
    """Waiting for a command or actions."""
    DEMONSTRATING = "demonstrating"
    """A demonstration is open."""
    ASKING = "asking"
    """A question waits for its answer."""


@dataclass(frozen=True)
class SessionView:
    """The session as its drivers see it now."""

    mode: Mode
    lang: Lang
    domain: Domain
    """The domain taught in (with the actions guiding added)."""
    phrases: tuple[str, ...]
    """The action and event phrases Tab completes, in the session's language."""
    questions_left: int
    generation: int
    can_run: bool
    """Whether 'run' would start a run now (otherwise the session says why not)."""
    guiding: bool
    """The teacher is guiding the robot (the terminal's guide mode keys drive it)."""
    guided: bool
    """The teacher has guided in this session (the toolbar then shows the labelling questions)."""
    labels_left: int
    facilitator: bool
    holds: tuple[str, ...]
    """The conditions that hold now, by name."""
    finished: bool
    """The teacher quit: the driver stops."""
    run_dir: Path
    """Where the session's per-run files go (the speech of a voiced session too)."""
