"""Speech synthesis: espeak-ng's C library, as bundled with its data by espeakng-loader, through ctypes.

espeak-ng is one global synthesizer per process (its C API has no handles), so this module keeps
one ``Synthesizer`` behind a lock. Nothing is downloaded (the English and German dictionaries come
in the wheel). It is deterministic for a sequence: the same lines said in the same order in a new
process give the same samples; but espeak-ng carries a little state (its pitch and timing) from one
line to the next, so one text said twice in a process may differ by a few samples.
"""

from __future__ import annotations

import ctypes
import threading
from functools import cache

import numpy as np

from teach.voice.audio import Audio
from teach.voice.library import require

VOICES = {"en": "en-us", "de": "de"}
"""espeak-ng's voice for each session language (American English: what the recogniser was trained on)."""
WORDS_PER_MINUTE = 150  # a little slower than espeak's 175: easier to follow for older listeners

_SYNCHRONOUS = 2  # AUDIO_OUTPUT_SYNCHRONOUS: espeak_Synth returns once the callback has had every sample
_UTF8 = 1  # espeakCHARS_UTF8
_RATE = 1  # espeakRATE
_IPA = 0x02  # espeak_TextToPhonemes: phonemes as IPA
_CALLBACK = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.POINTER(ctypes.c_short), ctypes.c_int, ctypes.c_void_p)


class _VoiceInfo(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("languages", ctypes.c_char_p), ("identifier", ctypes.c_char_p),
                ("gender", ctypes.c_ubyte), ("age", ctypes.c_ubyte), ("variant", ctypes.c_ubyte)]


class Synthesizer:
    """Text in a language → ``Audio``; one per process (see ``synthesizer``)."""

    def __init__(self) -> None:
        loader = require("espeakng_loader", "espeakng-loader")
        lib = ctypes.CDLL(loader.get_library_path())
        lib.espeak_Initialize.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_char_p, ctypes.c_int]
        lib.espeak_SetVoiceByName.argtypes = [ctypes.c_char_p]
        lib.espeak_SetParameter.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int]
        lib.espeak_Synth.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint, ctypes.c_int, ctypes.c_uint,
                                     ctypes.c_uint, ctypes.c_void_p, ctypes.c_void_p]
        lib.espeak_GetCurrentVoice.restype = ctypes.POINTER(_VoiceInfo)
        lib.espeak_TextToPhonemes.restype = ctypes.c_char_p
        lib.espeak_TextToPhonemes.argtypes = [ctypes.POINTER(ctypes.c_char_p), ctypes.c_int, ctypes.c_int]
        self.rate = lib.espeak_Initialize(_SYNCHRONOUS, 0, loader.get_data_path().encode(), 0)
        if self.rate <= 0:
            raise RuntimeError(f"espeak-ng did not start (its data: {loader.get_data_path()})")
        self._lib = lib
        self._chunks: list[np.ndarray] = []
        self._callback = _CALLBACK(self._receive)  # kept referenced: the C library calls it
        lib.espeak_SetSynthCallback(self._callback)
        self._lock = threading.Lock()
        self._lang = ""

    def _receive(self, wav: ctypes._Pointer[ctypes.c_short], count: int, events: int) -> int:
        if count > 0:
            self._chunks.append(np.ctypeslib.as_array(wav, shape=(count,)).copy())
        return 0  # go on

    def _use(self, lang: str) -> None:
        if lang != self._lang:
            if self._lib.espeak_SetVoiceByName(VOICES[lang].encode()) != 0:
                raise RuntimeError(f"espeak-ng has no voice {VOICES[lang]!r}")
            self._lib.espeak_SetParameter(_RATE, WORDS_PER_MINUTE, 0)
            self._lang = lang

    def speak(self, text: str, lang: str) -> Audio:
        """``text`` said in ``lang``'s voice, with a little silence before and after."""
        data = text.encode("utf-8")
        with self._lock:
            self._use(lang)
            self._chunks = []
            self._lib.espeak_Synth(data, len(data) + 1, 0, 0, 0, _UTF8, None, None)
            chunks, self._chunks = self._chunks, []
        samples = np.concatenate(chunks) if chunks else np.zeros(0, dtype=np.int16)
        return Audio(samples.astype(np.int16), self.rate).padded()

    def voice(self, lang: str) -> str:
        """The language espeak-ng speaks ``lang`` with (its voice's first language, e.g. "de")."""
        with self._lock:
            self._use(lang)
            info = self._lib.espeak_GetCurrentVoice().contents
            return (info.languages or b"")[1:].decode("ascii", "replace")  # after the priority byte

    def phonemes(self, text: str, lang: str) -> str:
        """How ``text`` is pronounced in ``lang``'s voice, in IPA."""
        pointer = ctypes.c_char_p(text.encode("utf-8"))
        parts = []
        with self._lock:
            self._use(lang)
            while pointer.value:
                parts.append((self._lib.espeak_TextToPhonemes(ctypes.byref(pointer), _UTF8, _IPA) or b"").decode())
        return " ".join(parts)


@cache
def synthesizer() -> Synthesizer:
    """The process's one synthesizer, started on first use."""
    return Synthesizer()


def speak(text: str, lang: str) -> Audio:
    return synthesizer().speak(text, lang)
