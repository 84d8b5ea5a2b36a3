"""Listening to the teacher (English): record from the microphone, recognise with the session's grammar.

Push-to-talk: the terminal's key (F5) or the line ``listen`` records ``SECONDS``; what is heard is
shown as if typed and then handled. Where no microphone is, or the session is German, it says so
in one line and the teacher types instead.
"""

from __future__ import annotations

from collections.abc import Callable

from teach import messages as m
from teach.domain import Domain
from teach.voice.audio import Audio
from teach.voice.library import VoiceUnavailable

SECONDS = 4.0  # one instruction, said after the key


def check_language(lang: str) -> None:
    """German speech cannot be recognised offline: refuse before a session starts."""
    if lang != "en":
        raise VoiceUnavailable(m.LISTEN_ENGLISH_ONLY(lang))


class Listener:
    """Hears the teacher from ``source`` (the microphone unless given: a test hears files)."""

    def __init__(self, domain: Domain, lang: str, note: Callable[[str], None],
                 source: Callable[[], Audio | None] | None = None):
        from teach.voice.recognise import Recogniser

        check_language(lang)
        self.lang = lang
        self._note = note
        self._source = source or self._microphone
        self._recogniser = Recogniser(domain)

    def listen(self) -> tuple[str, bool] | None:
        """The line the teacher said and whether it was heard surely, or None (after saying why in one line)."""
        audio = self._source()
        if audio is None:
            return None
        heard = self._recogniser.hear(audio, checked=True)
        if heard is None:
            self._note(m.NOTHING_HEARD(self.lang, file=m.THE_MICROPHONE(self.lang)))
            return None
        return heard.line, heard.sure

    def _microphone(self) -> Audio | None:
        from teach.voice import device

        missing = device.input_missing()
        if missing is not None:
            self._note(m.LISTEN_NO_MICROPHONE(self.lang, reason=missing))
            return None
        return device.record(SECONDS)
