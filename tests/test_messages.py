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
    assert messages.GOODBYE("en", resume="s1").endswith("--resume s1")


TEXTS = [(name, lang, text.de if lang == "de" else text.en) for name, text in sorted(CATALOGUE.items())
         for lang in ("en", "de")]


@pytest.mark.parametrize(("name", "lang", "said"), TEXTS, ids=[f"{n}-{lang}" for n, lang, _ in TEXTS])
def test_no_text_speaks_of_the_robots_body_as_the_teachers_or_counts_in_brackets(name, lang, said):
    # the robot speaks of itself ("my hand"); counts are said ("1 step", "2 steps"), never "step(s)"
    assert not any(word in said for word in ("your hand", "deine Hand", "deiner Hand", "(s)", "(e)"))


@pytest.mark.parametrize(("name", "text"), sorted(CATALOGUE.items()))
def test_german_texts_quote_the_german_way(name, text):
    # „so“, never “so” or ”so”
    assert "”" not in text.de and all(text.de[:i].count("„") > text.de[:i].count("“")
                                      for i, c in enumerate(text.de) if c == "“")


@pytest.mark.parametrize("path", sorted([*ROOT.glob("demos/*/domain.toml"), *ROOT.glob("dialogues/study/*.toml")]),
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_conditions_are_said_in_the_robots_first_person(path):
    from teach.domain import load_domain

    for condition in load_domain(path).conditions:
        for value in (True, False):
            for lang, second_person in (("en", {"you", "your"}), ("de", {"du", "dich", "dein", "deine", "dir"})):
                words = set(condition.label(lang, value).lower().replace(",", " ").split())
                assert not words & second_person, condition.label(lang, value)
