"""Scripted dialogue files: settings, input lines, one-line errors."""

from __future__ import annotations

import pytest

from teach.dialogue.script import read_script
from teach.errors import FormatError


def test_reads_settings_and_lines(tmp_path):
    path = tmp_path / "a.dialogue"
    path.write_text("# hello\n@lang de\n@questions 3\n\nBall finden  # first step\nfertig\n", encoding="utf-8")
    script = read_script(path)
    assert script.settings == {"lang": "de", "questions": 3}
    assert script.lines == [(5, "Ball finden"), (6, "fertig")]


@pytest.mark.parametrize("text, line, words", [
    ("@colour red\nx\n", 1, "unknown setting"),
    ("@questions many\nx\n", 1, "needs a int"),
    ("x\n@lang de\n", 2, "before the first input line"),
    ("# only a comment\n", None, "no input lines"),
])
def test_bad_scripts(tmp_path, text, line, words):
    path = tmp_path / "bad.dialogue"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(FormatError) as info:
        read_script(path)
    assert info.value.line == line and words in str(info.value)
