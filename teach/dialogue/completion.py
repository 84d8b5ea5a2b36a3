"""Completion for the terminal: a pure function (tested without a terminal) and its
prompt_toolkit wrapper."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence

from prompt_toolkit.completion import CompleteEvent, Completer, Completion
from prompt_toolkit.document import Document

from teach.dialogue.phrases import normalize


def _argument_of(text: str, arguments: Mapping[str, Sequence[str]]) -> Sequence[str] | None:
    """The names the command that ``text`` starts with takes ("why ", "start "), or None."""
    head, space, _ = text.lstrip().partition(" ")
    return arguments.get(normalize(head)) if space else None


def _part(text: str) -> str:
    """The part being typed: after the last comma."""
    return text.rsplit(",", 1)[-1].lstrip()


def complete(text: str, commands: Sequence[str], phrases: Sequence[str],
             arguments: Mapping[str, Sequence[str]] | None = None) -> list[str]:
    """Candidates for the last part of ``text``: commands at the start of a line, action and
    event phrases after a comma or at the start, and after a command in ``arguments`` (keyed
    by its normalized word: "warum", "start") the names it takes, after the command word or a comma."""
    names = _argument_of(text, arguments or {})
    if names is not None:
        head = text.lstrip().partition(" ")[2]
        lowered = _part(head).lower()
        return list(dict.fromkeys(n for n in names if n.lower().startswith(lowered)))
    part = _part(text)
    lowered = part.lower()
    candidates: list[str] = []
    if "," not in text:
        candidates += [c for c in commands if c.startswith(lowered) and lowered]
    candidates += [p for p in phrases if p.lower().startswith(lowered)]
    return list(dict.fromkeys(candidates))  # each once, in order


class TeachCompleter(Completer):
    def __init__(self, commands: Sequence[str], phrases: Sequence[str],
                 arguments: Mapping[str, Sequence[str]] | None = None):
        self.commands = list(commands)
        self.phrases = list(phrases)
        self.arguments = dict(arguments or {})

    def get_completions(self, document: Document, complete_event: CompleteEvent) -> Iterator[Completion]:
        text = document.text_before_cursor
        typed = text.lstrip().partition(" ")[2] if _argument_of(text, self.arguments) is not None else text
        part = _part(typed)
        for candidate in complete(text, self.commands, self.phrases, self.arguments):
            yield Completion(candidate, start_position=-len(part))


def command_words(usages: Iterable[str]) -> list[str]:
    return sorted({u.split()[0] for u in usages})
