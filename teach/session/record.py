"""The session record: what a session taught and what it shows now, durably.

It owns the journal (``teach.session.journal``), the store (every file of the session) and the
demonstration open now, which the journal keeps too so a resume shows it again. It is the one
place that journals: an event is appended, told to the observers' session channel and saved at
once (the store appends and fsyncs one line per save), and every save carries the open
demonstration's steps, so every "✓" the teacher saw is on disk before the next prompt.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from teach.domain import Domain, State
from teach.errors import FormatError
from teach.observe.hook import Observer
from teach.open_demonstration import OpenDemonstration
from teach.session.journal import (
    Answered,
    Asked,
    Event,
    Journal,
    Situated,
    check_open_actions,
    parse_state_text,
    state_text,
)
from teach.session.store import SessionStore

IMPOSSIBLE = "impossible"
"""The journalled answer "that situation cannot happen"."""


class SessionRecord:
    """The journal, the store and the open demonstration of one session."""

    def __init__(self, journal: Journal, store: SessionStore, observer: Observer, world_state: Callable[[], State]):
        self.journal = journal
        self.store = store
        self.observer = observer
        self.world_state = world_state
        self.open: OpenDemonstration | None = None
        """The demonstration being shown (or a run's steps, to be continued as a correction)."""
        self._start_situation = state_text(world_state())

    # --- writing ---------------------------------------------------------------------------

    def add(self, *events: Event) -> None:
        """Journal ``events``, tell the observers' session channel, and save."""
        self.journal.events.extend(events)
        for event in events:  # the observers' session channel, in the journal's order
            self.observer.on_session_event(event)
        self.note_open()  # a finished demonstration is never also journalled as open
        self.save()

    def save(self) -> None:
        self.store.save_journal(self.journal)

    def save_open(self) -> None:
        """The open demonstration on disk now: a "✓" shown while a line still runs (a live
        driver shows each step at once) survives a kill during the line's next step."""
        self.note_open()
        self.save()

    def note_open(self, how: str = "after") -> None:
        """Put the open demonstration's steps in the journal (saved with the next save). With none
        open, the world's situation is journalled when it changed (a demonstration finished or
        cancelled, an undo), so a resume sets it up again."""
        steps = self.open.steps if self.open is not None else []
        words = self.open.words if self.open is not None else []
        self.journal.open_steps = [[state_text(step.state), step.action, words[i] if i < len(words) else ""]
                                   for i, step in enumerate(steps)]
        now = state_text(self.world_state())
        self.journal.open_state = now if steps else ""
        self.journal.open_run = ""
        self.journal.open_robot = self.open.robot_steps if self.open is not None else 0
        if not steps and now != self._last_situation():
            self.journal.events.append(situated := Situated(now, how))
            self.observer.on_session_event(situated)

    def save_run(self, done: Sequence[tuple[State, int, str]], begun: State, action: str) -> None:
        """A run as it goes: the actions the robot finished (state, action id, words) as the open
        steps, and the world before the action it has just begun, so a resume after a kill
        mid-run reopens them as the corrective demonstration a stopped run would give."""
        self.journal.open_steps = [[state_text(state), number, words] for state, number, words in done]
        self.journal.open_state, self.journal.open_run = state_text(begun), action
        self.journal.open_robot = len(done)
        self.save()

    def tick(self, step: int) -> None:
        """The step clock, saved with the journal so a resume goes on from it."""
        self.journal.step = step

    # --- reading ---------------------------------------------------------------------------

    def charged(self) -> set[str]:
        """The situations asked about so far (undone or not): each was paid for once."""
        impossible = {event.state for event in self.journal.events
                      if isinstance(event, Answered) and event.answer == IMPOSSIBLE}
        return {event.state for event in self.journal.events
                if isinstance(event, Asked) and event.state and event.state not in impossible}

    def last_situated(self) -> Situated | None:
        """The world's situation as last journalled, if it ever was."""
        return next((e for e in reversed(self.journal.events) if isinstance(e, Situated)), None)

    def _last_situation(self) -> str:
        last = self.last_situated()
        return last.state if last is not None else self._start_situation

    def state(self, text: str, what: str, domain: Domain) -> State:
        """A state the journal holds, checked against the domain's conditions."""
        state = parse_state_text(text)
        if len(state) != len(domain.conditions):
            raise FormatError(f"{what}: has {len(state)} values, not {len(domain.conditions)}",
                              self.store.journal_path)
        return state

    def journalled_open(self, domain: Domain) -> tuple[list[tuple[State, int, str]], State, str] | None:
        """The demonstration open when the session ended: its steps (state, action id, words),
        where the world was and the action a run had begun there (""); None when none was.
        How many of the steps a run did is ``journal.open_robot``."""
        run = self.journal.open_run
        if not self.journal.open_steps and not run:
            return None
        if run and run not in domain.action_names:
            raise FormatError(f"open_run: {run[:40]!r} is not an action of the domain", self.store.journal_path)
        check_open_actions(self.journal, domain, self.store.journal_path)
        steps = [(self.state(str(state), f"open_steps[{number}]", domain), int(action), str(words))
                 for number, (state, action, words) in enumerate(self.journal.open_steps)]
        return steps, self.state(self.journal.open_state, "open_state", domain), run
