"""English speech recognition with pocketsphinx 5, restricted to the session's grammar.

The acoustic model and dictionary come inside the pocketsphinx wheel: nothing is downloaded.
Only English: no package ships an offline German recogniser (``listen.check_language`` says so).
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from teach.domain import Domain
from teach.voice.audio import Audio
from teach.voice.grammar import Grammar, domain_grammar
from teach.voice.library import require

DECODER = {"bestpath": False, "wip": 0.2, "silprob": 0.1, "topn": 8}
"""Settings measured on the round-trip test (tests/test_voice.py): the lattice's best-path rescoring
costs accuracy on a grammar; a stronger word-insertion penalty keeps "done" from becoming "go to
it"; more Gaussians per frame (topn) keep short words apart in noise."""
RATE = 16000  # the acoustic model's sample rate
DITHER = 30.0  # a noise floor (about -40 dB of speech): digital silence upsets the model's features
_DITHER_SEED = 22
_GRAMMAR, _PHONES = "teach", "phones"
REJECTED_BELOW = -6.0
"""Measured on the round-trip test's lines: each fits at -4.7 a second or better, clean and at 20 dB; other
speech mostly finds no path through the grammar at all, and a line forced onto a sound that says something
else fits worse than this. Short unrelated words ("hello" heard as "both") fit as well as real lines:
fit cannot tell those apart, so there is no "unsure" band."""
_CHANGES = (0.95, 1.05)  # the sound resampled by these and played at its own rate: 5% slower and faster
_FRAME = 400  # 25 ms at 16 kHz
_SPEECH_ABOVE_FLOOR_DB = 12.0  # a file whose loudest frame is not this far above its quietest holds no speech


@dataclass(frozen=True)
class Heard:
    line: str
    """What was recognised, as the teacher would have typed it."""
    fit: float
    """How well the line's sounds fit the sound, against the best sequence of any English sounds, per
    second (0: as well as any; below ``REJECTED_BELOW``: the sound says something else)."""
    sure: bool = True
    """False when the same sound a little faster or slower is heard as another line (``hear(checked=True)``)."""


class Recogniser:
    """One decoder for one domain's grammar (building it takes a fraction of a second)."""

    def __init__(self, domain: Domain):
        pocketsphinx = require("pocketsphinx", "pocketsphinx")
        self._decoder = pocketsphinx.Decoder(loglevel="FATAL", lm=None, **DECODER)
        self.grammar: Grammar = domain_grammar(domain, lambda word: self._decoder.lookup_word(word) is not None)
        self._decoder.add_jsgf_string(_GRAMMAR, self.grammar.jsgf())
        model = Path(pocketsphinx.get_model_path()) / "en-us" / "en-us-phone.lm.bin"
        self._decoder.add_allphone_file(_PHONES, str(model))
        self._lock = threading.Lock()

    def hear(self, audio: Audio, checked: bool = False) -> Heard | None:
        """The line ``audio`` says, or None when nothing in the grammar fits. ``checked``: also hear the
        sound 5% faster and slower; a line heard differently then is not ``sure`` (measured on the
        round-trip test: 153 of its 162 sounds are sure, and 2 of the 3 it mishears are not)."""
        heard = self._heard(audio)
        if heard is None or not checked:
            return heard
        others = [self._heard(Audio(audio.resampled(round(audio.rate * f)).samples, audio.rate)) for f in _CHANGES]
        return replace(heard, sure=all(other is not None and other.line == heard.line for other in others))

    def _heard(self, audio: Audio) -> Heard | None:
        samples = audio.resampled(RATE).samples.astype(np.float64)
        if not _has_speech(samples):
            return None
        samples += np.random.default_rng(_DITHER_SEED).normal(0.0, DITHER, len(samples))
        raw = np.clip(np.round(samples), -32768, 32767).astype("<i2").tobytes()
        with self._lock:
            line, grammar_score = self._decode(_GRAMMAR, raw)
            if not line:
                return None
            _, phones_score = self._decode(_PHONES, raw)
        fit = (grammar_score - phones_score) / (len(samples) / RATE)
        return Heard(line, fit) if fit >= REJECTED_BELOW else None

    def _decode(self, search: str, raw: bytes) -> tuple[str, float]:
        """The words a search finds in ``raw`` and their acoustic score."""
        self._decoder.activate_search(search)
        self._decoder.start_utt()
        self._decoder.process_raw(raw, full_utt=True)
        self._decoder.end_utt()
        hypothesis = self._decoder.hyp()
        segments = self._decoder.seg() or []
        return " ".join((hypothesis.hypstr if hypothesis else "").split()), sum(s.ascore for s in segments)


def _has_speech(samples: np.ndarray) -> bool:
    frames = len(samples) // _FRAME
    if frames < 2:
        return False
    energy = np.mean(samples[:frames * _FRAME].reshape(frames, _FRAME) ** 2, axis=1)
    loudest, quietest = float(np.max(energy)), float(np.percentile(energy, 10))
    return loudest > 0 and loudest > (quietest + 1.0) * 10 ** (_SPEECH_ABOVE_FLOOR_DB / 10)
