"""The robot's voice in a session: lines are said in a thread, one after another, never holding up
the dialogue. A question goes first and cuts short run progress being said.

Every line said is written as ``speech/NNN.wav`` (atomically, numbered in the order said) with
``speech/lines.txt`` naming each file's text, so a study can be reviewed with what the
participant heard. Sound goes to the output device when there is one; without it, files only.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path

from teach import messages as m
from teach.errors import TeachError
from teach.fsutil import atomic_write_text
from teach.voice.audio import Audio, write_wav
from teach.voice.lines import Line
from teach.voice.synth import speak, synthesizer

Player = Callable[[Audio, threading.Event], None]
"""Plays a sound until it ends or the event is set."""


class Speaker:
    def __init__(self, lang: str, folder: Path, player: Player | None, note: Callable[[str], None] = print):
        self.lang = lang
        self.folder = folder
        self._player = player
        self._note = note
        self._writing = True  # until a write fails: then said once, and sound only
        self._waiting: list[Line] = []
        self._said: list[str] = []
        self._current: Line | None = None
        self._cut = threading.Event()
        self._changed = threading.Condition()
        self._closing = False
        self._thread = threading.Thread(target=self._work, name="teach-voice", daemon=True)
        self._thread.start()

    def say(self, line: Line) -> None:
        """Queue ``line``; a question drops waiting progress lines and cuts short the one being said."""
        with self._changed:
            if line.urgent:
                self._waiting = [waiting for waiting in self._waiting if not waiting.passing]
                if self._current is not None and self._current.passing:
                    self._cut.set()
                at = next((i for i, waiting in enumerate(self._waiting) if not waiting.urgent), len(self._waiting))
                self._waiting.insert(at, line)
            else:
                self._waiting.append(line)
            self._changed.notify()

    def close(self) -> None:
        """Say what is still waiting, then stop."""
        with self._changed:
            self._closing = True
            self._changed.notify()
        self._thread.join()

    @property
    def said(self) -> list[str]:
        """The lines said so far, in order (each has its ``NNN.wav``)."""
        with self._changed:
            return list(self._said)

    def _work(self) -> None:
        while True:
            with self._changed:
                while not self._waiting and not self._closing:
                    self._changed.wait()
                if not self._waiting:
                    return
                line = self._current = self._waiting.pop(0)
                self._cut.clear()
            audio = speak(line.text, self.lang)
            with self._changed:
                self._said.append(line.text)
                number = len(self._said)
                index = "".join(f"{n:03d}.wav\t{text}\n" for n, text in enumerate(self._said, start=1))
            if self._writing:
                try:
                    write_wav(self.folder / f"{number:03d}.wav", audio)
                    atomic_write_text(self.folder / "lines.txt", index)
                except TeachError as error:
                    self._writing = False
                    self._note(m.VOICE_NOT_WRITTEN(self.lang, error=error))
            if self._player is not None:
                self._player(audio, self._cut)
            with self._changed:
                self._current = None


def session_speaker(lang: str, folder: Path, note: Callable[[str], None]) -> Speaker:
    """The voice of a session: through the sound device when there is one, else (said once) into files only.
    The synthesizer starts here, so a missing library stops the session before it opens."""
    from teach.voice import device

    synthesizer()
    missing = device.output_missing()
    if missing is not None:
        note(m.VOICE_FILES_ONLY(lang, reason=missing, folder=folder))
    return Speaker(lang, folder, None if missing else device.play, note)
