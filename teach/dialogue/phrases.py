"""Everyday teacher language → actions, events and commands, in English or German.

"Ball finden, zum Ball gehen, Ball greifen" is three actions. Phrases come from the domain's
labels and the world's perturbations; matching ignores case, accents, punctuation and
filler words, splits on commas and "and/then/und/dann", and can segment a run of phrases
without separators. Unknown words raise ``UnknownPhrase`` carrying suggestions.
"""

from __future__ import annotations

import difflib
import re
import unicodedata
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from teach.domain import Domain
from teach.errors import TeachError

_FILLERS = {"the", "a", "an", "please", "now", "bitte", "jetzt", "mal", "den", "die", "das", "dem", "der",
            "des", "ein", "eine", "einen", "to", "zu"}
_SPLIT = re.compile(r"\s*(?:[,;.!]|\band then\b|\bthen\b|\band\b|\bund dann\b|\bdann\b|\bund\b)\s*")
_TYPO_CUTOFF = 0.75
_TYPO_MARGIN = 0.1


@dataclass(frozen=True, slots=True)
class Token:
    """One recognised unit of teacher input."""

    kind: str  # "action" | "event"
    name: str
    text: str


class UnknownPhrase(TeachError):
    """A part of the input matched nothing; ``suggestions`` are the closest known phrases."""

    def __init__(self, text: str, suggestions: list[str], lang: str = "en"):
        self.text = text
        self.suggestions = suggestions
        if lang == "de":
            hint = f" Meintest du „{suggestions[0]}“?" if suggestions else ""
            message = f"Das kenne ich nicht: „{text}“.{hint}"
        else:
            hint = f" Did you mean “{suggestions[0]}”?" if suggestions else ""
            message = f"I don't know “{text}”.{hint}"
        super().__init__(message)


def normalize(text: str) -> str:
    """Lower case, no accents (ä → a, ß → ss), no punctuation, no filler words."""
    text = text.lower().replace("ß", "ss")
    text = "".join(c for c in unicodedata.normalize("NFKD", text) if not unicodedata.combining(c))
    words = re.findall(r"[a-z0-9]+", text)
    return " ".join(w for w in words if w not in _FILLERS)


class PhraseBook:
    """All phrases a teacher may type for the domain's actions and the world's events."""

    def __init__(self, domain: Domain, events: Mapping[str, tuple[Iterable[str], Iterable[str]]] = {}):
        self._phrases: dict[str, Token] = {}
        self._display: dict[str, dict[str, str]] = {"en": {}, "de": {}}
        for action in domain.actions:
            self._add("action", action.name, action.en, action.de)
        for name, (english, german) in sorted(events.items()):
            self._add("event", name, tuple(english), tuple(german))

    def _add(self, kind: str, name: str, english: tuple[str, ...], german: tuple[str, ...]) -> None:
        spelled = re.sub(r"(?<!^)(?=[A-Z])", " ", name)  # FindBall → "Find Ball"
        for lang, phrases in (("en", english), ("de", german)):
            for phrase in (*phrases, name, spelled):
                key = normalize(phrase)
                if key and key not in self._phrases:
                    self._phrases[key] = Token(kind, name, phrase)
                    if phrase not in (name, spelled):
                        self._display[lang].setdefault(phrase, name)

    def phrases(self, lang: str = "en") -> list[str]:
        """Phrases shown for completion, in the given language."""
        return sorted(self._display[lang])

    def parse(self, line: str, lang: str = "en") -> list[Token]:
        """All actions and events in a line, in order; raises UnknownPhrase for the first unknown part."""
        tokens: list[Token] = []
        for chunk in _SPLIT.split(line):
            if chunk.strip():
                tokens.extend(self._parse_chunk(chunk, lang))
        return tokens

    def _parse_chunk(self, chunk: str, lang: str) -> list[Token]:
        key = normalize(chunk)
        if not key:
            return []
        if key in self._phrases:
            return [self._phrases[key]]
        segmented = self._segment(key.split())
        if segmented is not None:
            return segmented
        close = difflib.get_close_matches(key, self._phrases, n=3, cutoff=0.45)
        if close and self._clear_typo(key, close):
            return [self._phrases[close[0]]]
        raise UnknownPhrase(chunk.strip(), [self._pretty(c, lang) for c in close], lang)

    def _clear_typo(self, key: str, close: list[str]) -> bool:
        """Accept the best match silently only when it is close and clearly better than any other action."""
        ratios = [difflib.SequenceMatcher(None, key, c).ratio() for c in close]
        rivals = [r for c, r in zip(close[1:], ratios[1:]) if self._phrases[c].name != self._phrases[close[0]].name]
        return ratios[0] >= _TYPO_CUTOFF and all(r <= ratios[0] - _TYPO_MARGIN for r in rivals)

    def _segment(self, words: list[str]) -> list[Token] | None:
        """Split a run of words into known phrases (fewest pieces), or None."""
        best: list[list[Token] | None] = [[]] + [None] * len(words)
        for end in range(1, len(words) + 1):
            for start in range(end):
                prefix = best[start]
                token = self._phrases.get(" ".join(words[start:end]))
                if prefix is not None and token is not None:
                    candidate = prefix + [token]
                    if best[end] is None or len(candidate) < len(best[end]):  # type: ignore[arg-type]
                        best[end] = candidate
        return best[-1]

    def _pretty(self, key: str, lang: str) -> str:
        token = self._phrases[key]
        for phrase, name in self._display[lang].items():
            if name == token.name:
                return phrase
        return token.text
