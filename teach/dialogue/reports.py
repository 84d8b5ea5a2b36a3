"""How people report what happened, as against how a phrase names it: "someone took the ball
away", "the bin was moved", "she walked away" for the phrases "take the ball away", "move the
bin", "they walk away". A report's key is its words without the subject and auxiliaries, each
cut to a crude English stem, in any order: two wordings with one key say the same thing.

Kept apart from ``teach.dialogue.phrases``, which asks for a key only where a line reads no
other way, and takes it only where exactly one action or event has that key (blocksworld's "b
stacked on a" fits "stack a b" and "stack b a": no reading)."""

from __future__ import annotations

from collections.abc import Iterable

_AROUND_A_REPORT = frozenset({"someone", "somebody", "i", "he", "she", "we", "you", "they", "was", "were", "is",
                              "are", "has", "have", "had", "just", "been", "did", "jemand", "ich", "er", "sie", "wir",
                              "hat", "habe", "hast", "haben", "wurde", "wurden", "wird", "ist", "sind", "gerade",
                              "eben"})
"""The subject and auxiliaries a report adds ("someone has taken …", "the bin was moved", "jemand
hat den Ball weggenommen"; German verbs are matched by the participles the phrases list)."""
_IRREGULAR = {"took": "take", "taken": "take", "left": "leave", "went": "go", "gone": "go", "came": "come",
              "gave": "give", "given": "give", "brought": "bring", "threw": "throw", "thrown": "throw",
              "fell": "fall", "fallen": "fall", "got": "get", "gotten": "get", "ran": "run", "stole": "steal",
              "stolen": "steal", "lost": "lose", "goes": "go", "going": "go", "found": "find", "held": "hold",
              "caught": "catch"}
"""English forms no suffix rule reaches ("took", "goes": a rule keeps three letters at least)."""
_SUFFIXES = ("ing", "ed", "es", "s", "d")
"""Inflections cut off a word longer than three letters, the first that fits."""
_DOUBLED = frozenset("bgmnpt")
"""Consonants doubled before "-ed" and "-ing" ("grabbed", "stopped"), undoubled after the cut."""


def stem(word: str) -> str:
    """A crude English stem, the same for every inflection of a verb people use in reports:
    "moved", "moves", "move" → "mov"; "took", "takes", "take" → "tak"; "left", "leaves" → "leav";
    "grabbed", "grab" → "grab"."""
    word = _IRREGULAR.get(word, word)
    if len(word) > 3 and not word.endswith("ss"):
        for suffix in _SUFFIXES:
            if word.endswith(suffix) and len(word) - len(suffix) >= 3:
                word = word[:-len(suffix)]
                if suffix in ("ed", "ing") and word[-1] == word[-2] and word[-1] in _DOUBLED:
                    word = word[:-1]
                break
    return word[:-1] if len(word) > 3 and word.endswith("e") else word


def report_key(words: Iterable[str]) -> tuple[str, ...]:
    """The words' stems without a report's subject and auxiliaries, sorted: what a report of a
    phrase and the phrase itself share ("someone took the ball away" and "take the ball away")."""
    return tuple(sorted(stem(word) for word in words if word not in _AROUND_A_REPORT))
