"""Completion for the terminal: a pure function (tested without a terminal) and its
prompt_toolkit wrapper."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence

from prompt_toolkit.completion import CompleteEvent, Completer, Completion
from prompt_toolkit.document import Document


def complete(text: str, commands: Sequence[str], phrases: Sequence[str]) -> list[str]:
    """Candidates for the last part of ``text``: commands at the start of a line, action and
    event phrases after a comma or at the start."""
    part = text.rsplit(",", 1)[-1].lstrip()
    lowered = part.lower()
    candidates: list[str] = []
    if "," not in text:
        candidates += [c for c in commands if c.startswith(lowered) and lowered]
    candidates += [p for p in phrases if p.lower().startswith(lowered)]
    return list(dict.fromkeys(candidates))  # each once, in order


class TeachCompleter(Completer):
    def __init__(self, commands: Sequence[str], phrases: Sequence[str]):
        self.commands = list(commands)
        self.phrases = list(phrases)

    def get_completions(self, document: Document, complete_event: CompleteEvent) -> Iterator[Completion]:
        text = document.text_before_cursor
        part = text.rsplit(",", 1)[-1].lstrip()
        for candidate in complete(text, self.commands, self.phrases):
            yield Completion(candidate, start_position=-len(part))


def command_words(usages: Iterable[str]) -> list[str]:
    return sorted({u.split()[0] for u in usages})
