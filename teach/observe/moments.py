"""The recording's ``tick`` timeline: one moment for everything that happened once.

A reviewer scrubs a session moment by moment, so each tick of a run, each step of a
demonstration and each line of the dialogue outside a run is its own moment. Within a run the
ticks are the moments: what the robot says and what the world shows between two ticks belongs to
the tick before. A demonstration's step in a simulated world opens its moment when its action
starts moving (its frames come before the lines that confirm it), and the robot's lines join it
until the next action or the teacher's next line.
"""

from __future__ import annotations

from enum import Enum


class Opened(Enum):
    """What opened the current moment."""

    START = "start"
    TICK = "tick"
    ACTION = "action"
    """A demonstration's action (or an outside event) moved the world; the robot's lines about it join it."""
    SAID = "said"
    """A line of the dialogue."""


class Moments:
    """Decides when the ``tick`` timeline moves on; ``now`` is the current moment (0 before anything)."""

    def __init__(self) -> None:
        self.now = 0
        self.opened = Opened.START
        self.in_run = False
        self._action: str | None = None

    def _next(self, opened: Opened) -> bool:
        self.now += 1
        self.opened = opened
        return True

    def tick(self) -> bool:
        """A tick of the tree: always a moment of its own."""
        return self._next(Opened.TICK)

    def action(self, action: str | None) -> bool:
        """The world moves for ``action`` (None: nothing runs, the world settles). Outside a run and
        after anything but a tick, a new action opens a moment; returns whether one was opened."""
        if self.in_run or action is None or self.opened is Opened.TICK or (
                self.opened is Opened.ACTION and self._action == action):
            return False  # (the frames after a tick belong to it, as in a run)
        self._action = action
        return self._next(Opened.ACTION)

    def line(self, teacher: bool) -> bool:
        """A line of the dialogue: its own moment outside a run, unless it is the robot's about the
        action that opened the current moment."""
        if self.in_run or (self.opened is Opened.ACTION and not teacher):
            return False
        return self._next(Opened.SAID)

    def run_starts(self) -> None:
        self.in_run = True

    def run_ends(self) -> bool:
        """A run ended: what follows (its outcome, the idle tree) is the next moment."""
        self.in_run = False
        self._action = None
        return self._next(Opened.SAID)
