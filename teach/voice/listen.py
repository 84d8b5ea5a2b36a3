"""Listening to the teacher (English): record from the microphone, recognise with the session's grammar.

Push-to-talk: the terminal's key (F5) or the line ``listen`` records ``SECONDS``; what is heard is
shown as if typed and then handled. Where no microphone is, or the session is German, it says so
in one line and the teacher types instead.
"""

from __future__ import annotations

from collections.abc import Callable

from teach.domain import Domain
from teach.session import messages as m
from teach.voice.library import VoiceUnavailable

SECONDS = 4.0  # one instruction, said after the key


def check_language(lang: str) -> None:
    """German speech cannot be recognised offline: refuse before a session starts."""
    if lang != "en":
        raise VoiceUnavailable(m.LISTEN_ENGLISH_ONLY(lang))


class Listener:
    def __init__(self, domain: Domain, lang: str, note: Callable[[str], None]):
        from teach.voice.recognise import Recogniser

        check_language(lang)
        self.lang = lang
        self._note = note
        self._recogniser = Recogniser(domain)

    def listen(self) -> str | None:
        """The line the teacher said, or None (after saying why in one line)."""
        from teach.voice import device

        missing = device.input_missing()
        if missing is not None:
            self._note(m.LISTEN_NO_MICROPHONE(self.lang, reason=missing))
            return None
        heard = self._recogniser.hear(device.record(SECONDS))
        if heard is None:
            self._note(m.NOTHING_HEARD(self.lang, file=m.THE_MICROPHONE(self.lang)))
            return None
        return heard.line
