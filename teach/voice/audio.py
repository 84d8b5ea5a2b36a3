"""Sound as numbers: mono 16-bit samples at a rate, read from and written to WAV files.

WAV is the one audio format in and out (the standard library reads and writes it), so a study's
``speech/NNN.wav`` files open in any player and ``teach hear`` takes what ``teach speak`` wrote.
"""

from __future__ import annotations

import io
import wave
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from teach.errors import FormatError
from teach.fsutil import atomic_write_bytes, read_bytes

MAX_WAV_BYTES = 64 * 1024 * 1024  # about 30 minutes of 16 kHz sound: more is not one spoken line
SILENCE_SECONDS = 0.25  # around a spoken line: players start cleanly, recognisers hear where it begins and ends


@dataclass(frozen=True)
class Audio:
    samples: np.ndarray
    """int16, mono."""
    rate: int

    @property
    def seconds(self) -> float:
        return len(self.samples) / self.rate

    def rms(self) -> float:
        """The loudness: root mean square of the samples (0 for silence)."""
        return float(np.sqrt(np.mean(self.samples.astype(np.float64) ** 2))) if len(self.samples) else 0.0

    def resampled(self, rate: int) -> Audio:
        """At another rate, band-limited (through the spectrum: no aliasing from dropping samples)."""
        if rate == self.rate or not len(self.samples):
            return Audio(self.samples, rate)
        count = max(1, round(len(self.samples) * rate / self.rate))
        spectrum = np.fft.rfft(self.samples.astype(np.float64))
        kept = np.zeros(count // 2 + 1, dtype=complex)
        shared = min(len(kept), len(spectrum))
        kept[:shared] = spectrum[:shared]
        samples = np.fft.irfft(kept, count) * (count / len(self.samples))
        return Audio(_int16(samples), rate)

    def padded(self, seconds: float = SILENCE_SECONDS) -> Audio:
        """With silence before and after."""
        silence = np.zeros(round(seconds * self.rate), dtype=np.int16)
        return Audio(np.concatenate([silence, self.samples, silence]), self.rate)


def _int16(samples: np.ndarray) -> np.ndarray:
    return np.clip(np.round(samples), -32768, 32767).astype(np.int16)


def with_noise(audio: Audio, snr_db: float, seed: int) -> Audio:
    """``audio`` with white noise added at ``snr_db`` below the power of its sound (its silent
    edges left out of that power): how a test hears a line said in a room."""
    samples = audio.samples.astype(np.float64)
    loud = np.flatnonzero(np.abs(samples) > 0)
    speech = samples[loud[0]:loud[-1] + 1] if len(loud) else samples
    power = float(np.mean(speech ** 2)) if len(speech) else 0.0
    noise = np.random.default_rng(seed).normal(0.0, np.sqrt(power / 10 ** (snr_db / 10)), len(samples))
    return Audio(_int16(samples + noise), audio.rate)


def to_wav_bytes(audio: Audio) -> bytes:
    buffer = io.BytesIO()
    with wave.open(buffer, "wb") as out:
        out.setnchannels(1)
        out.setsampwidth(2)
        out.setframerate(audio.rate)
        out.writeframes(audio.samples.astype("<i2").tobytes())
    return buffer.getvalue()


def write_wav(path: str | Path, audio: Audio) -> None:
    """Written whole or not at all (a temporary file renamed onto ``path``)."""
    atomic_write_bytes(path, to_wav_bytes(audio))


def read_wav(path: str | Path) -> Audio:
    """A 16-bit PCM WAV file, mono or with its channels mixed to one."""
    data = read_bytes(path, "WAV file", MAX_WAV_BYTES)
    try:
        with wave.open(io.BytesIO(data), "rb") as sound:
            channels, width, rate = sound.getnchannels(), sound.getsampwidth(), sound.getframerate()
            frames = sound.readframes(sound.getnframes())
    except (wave.Error, EOFError) as error:
        raise FormatError(f"not a WAV file I can read ({error or 'truncated'})", path) from None
    if width != 2:
        raise FormatError(f"a WAV file of {8 * width}-bit samples: only 16-bit PCM is read", path)
    if rate < 8000:
        raise FormatError(f"a WAV file at {rate} Hz: at least 8000 Hz is needed to hear speech", path)
    samples = np.frombuffer(frames[:len(frames) - len(frames) % (2 * channels)], dtype="<i2")
    if channels > 1:
        samples = _int16(samples.reshape(-1, channels).mean(axis=1))
    return Audio(samples.astype(np.int16), rate)
