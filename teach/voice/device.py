"""The sound devices (sounddevice, over PortAudio): play a line, record from the microphone.

Where there is no device, or PortAudio itself is missing, ``output_missing``/``input_missing``
say why in one line and nothing is played or recorded.
"""

from __future__ import annotations

import importlib
import threading
from types import ModuleType

import numpy as np

from teach.voice.audio import Audio
from teach.voice.library import VoiceUnavailable, require


def _library() -> ModuleType:
    try:
        return importlib.import_module("sounddevice")
    except OSError as error:  # the package is there, the system's PortAudio library is not
        raise VoiceUnavailable(f"no sound device: {error} (it comes with the system package libportaudio2)") \
            from None
    except ImportError:
        return require("sounddevice", "sounddevice")  # names the package


def _missing(kind: str) -> str | None:
    """Why no default ``kind`` ("output" or "input") device can be used, or None when one can."""
    try:
        _library().query_devices(kind=kind)
    except VoiceUnavailable as error:
        return str(error)
    except Exception as error:  # PortAudio's own error: no such device
        return f"no sound {kind} device ({error})"
    return None


def output_missing() -> str | None:
    return _missing("output")


def input_missing() -> str | None:
    return _missing("input")


def play(audio: Audio, stop: threading.Event) -> None:
    """Play ``audio`` on the default output until it ends or ``stop`` is set."""
    sounddevice = _library()
    sounddevice.play(audio.samples, audio.rate)
    while sounddevice.get_stream().active and not stop.wait(0.02):
        pass
    if stop.is_set():
        sounddevice.stop()


def record(seconds: float, rate: int = 16000) -> Audio:
    """``seconds`` of sound from the default microphone."""
    sounddevice = _library()
    samples = sounddevice.rec(round(seconds * rate), samplerate=rate, channels=1, dtype="int16")
    sounddevice.wait()
    return Audio(np.asarray(samples, dtype=np.int16).reshape(-1), rate)
