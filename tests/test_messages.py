"""Every message a teacher sees comes from one catalogue with both languages."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from conftest import ROOT

from teach import messages
from teach.messages import Text
from teach.session.commands import COMMANDS

CATALOGUE = {name: value for name, value in vars(messages).items() if isinstance(value, Text)}
CATALOGUE |= {f"{command.name}.{part}": getattr(command, part) for command in COMMANDS for part in ("usage", "help")}
# the commands declare their usage and help with their words (teach/session/commands.py)
# the session, the terminal and the questions say nothing that is not in the catalogue
# (phrases.py, the phrase book, keeps its own en/de tables for now)
SPEAKERS = sorted([*(ROOT / "teach" / "session").glob("*.py"), *(ROOT / "teach" / "terminal").glob("*.py"),
                   *(p for p in (ROOT / "teach" / "dialogue").glob("*.py") if p.name != "phrases.py")])


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_each_message_has_english_and_german_with_the_same_fields(name):
    text = CATALOGUE[name]
    assert text.en.strip() and text.de.strip(), f"{name} lacks its English or German text"
    assert text.fields("en") == text.fields("de"), f"{name}: the languages fill in different fields"


def test_a_message_missing_a_language_is_caught():
    with pytest.raises(TypeError):
        Text("only English")  # type: ignore[call-arg]
    assert not Text("only English", "").de.strip()


def _language_switches(path: Path) -> list[int]:
    """Lines that pick a text by language themselves (``lang == "de"``) instead of the catalogue."""
    lines = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Compare) and any(isinstance(c, ast.Constant) and c.value == "de"
                                                 for c in node.comparators):
            lines.append(node.lineno)
    return lines


@pytest.mark.parametrize("path", [p for p in SPEAKERS if p.name != "messages.py"], ids=lambda p: p.name)
def test_no_speaker_chooses_a_language_itself(path):
    assert _language_switches(path) == []


def test_messages_fill_in_their_fields():
    assert messages.THANKS("de", change="Gut.") == "Danke. Gut."
    assert messages.GOODBYE("en", session="s1").endswith("--resume s1")
