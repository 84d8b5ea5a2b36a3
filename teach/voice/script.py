"""``@audio FILE.wav`` lines of a dialogue: each recognised before the dialogue runs, then handled as
the line it says, so a bad or silent file names its line before anything of a session is touched."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from teach import messages as m
from teach.dialogue.script import AUDIO, Script
from teach.domain import Domain
from teach.errors import FormatError
from teach.voice.audio import read_wav
from teach.voice.library import VoiceUnavailable
from teach.voice.recognise import Recogniser


def heard_script(script: Script, domain: Domain, lang: str) -> Script:
    """``script`` with each ``@audio`` line replaced by what its file says (files relative to the dialogue)."""
    if lang != "en":
        raise VoiceUnavailable(m.LISTEN_ENGLISH_ONLY(lang), script.path)
    recogniser = Recogniser(domain)
    lines = []
    for number, line in script.lines:
        if line.startswith(AUDIO):
            path = script.path.parent / Path(line[len(AUDIO):].strip())
            try:
                heard = recogniser.hear(read_wav(path))
            except FormatError as error:
                raise FormatError(str(error), script.path, number) from None
            if heard is None:
                raise FormatError(m.NOTHING_HEARD("en", file=path), script.path, number)
            line = heard.line
        lines.append((number, line))
    return replace(script, lines=lines)
