"""Voice in a session: the observer of shown replies that hands each to the speaker."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager

from teach.session.machine import SessionManager
from teach.session.replies import Reply
from teach.voice.lines import spoken_line
from teach.voice.speaker import session_speaker


@contextmanager
def spoken_session(manager: SessionManager, note: Callable[[str], None] = print) -> Iterator[Callable[[Reply], None]]:
    """What a driver calls with each reply it shows; at the end, what is still waiting is said."""
    view = manager.view()
    speaker = session_speaker(view.lang, view.run_dir / "speech", note)

    def shown(reply: Reply) -> None:
        line = spoken_line(reply, view.lang)
        if line is not None:
            speaker.say(line)

    try:
        yield shown
    finally:
        speaker.close()
