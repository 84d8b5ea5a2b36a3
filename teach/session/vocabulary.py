"""The session's vocabulary: its domain and the phrases read in it, held once.

Guiding can teach a new action, which gives the session a grown copy of its domain; everything
that reads the domain or parses a line (the machine, guiding, the open demonstration's words)
holds this one object, so the new action is known everywhere at once.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from teach.dialogue.phrases import PhraseBook
from teach.domain import Domain

Events = Mapping[str, tuple[Iterable[str], Iterable[str]]]


class Vocabulary:
    """The domain taught in and the phrase book built from it and the world's events."""

    def __init__(self, domain: Domain, events: Events):
        self.events = events
        self.domain = domain
        self.phrases = PhraseBook(domain, events)

    def adopt(self, domain: Domain) -> None:
        """Teach in ``domain`` from now on (the session's copy with new actions)."""
        self.domain = domain
        self.phrases = PhraseBook(domain, self.events)
