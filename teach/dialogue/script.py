"""Scripted dialogues: a human-writable file of teacher inputs that drives the very same
session manager as the terminal.

Format (``dialogues/*.dialogue``, UTF-8):

    # comment lines and blank lines are ignored
    @lang de              # settings before the first input line: lang, questions, seed, world
    @questions 5
    Ball finden, zum Ball gehen, Ball greifen, zum Eimer gehen, Ball in den Eimer legen
    fertig
    run

    @audio find.wav       # a line said aloud: recognised (English), then handled as the recognised text

Every other line is typed at the prompt as it is. While the robot has a question open the
next line is the answer, unless an oracle answers questions (``--oracle``/``--oracle-model``),
in which case script lines are never taken as answers.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from teach import limits
from teach.dialogue.phrases import MAX_LINE_CHARS
from teach.errors import FormatError
from teach.fsutil import read_text
from teach.messages import Lang

AUDIO = "@audio "
"""``@audio FILE.wav``: an input line said aloud, recognised before the dialogue runs (teach/voice/script.py)."""
SETTINGS = {"lang": str, "questions": int, "seed": int, "world": str, "domain": str}
CHOICES = {"world": ("mujoco", "symbolic", "offline")}
_WHOLE_NUMBER = re.compile(r"[0-9]{1,9}", re.ASCII)
"""How @questions and @seed are written: ASCII digits only (no sign, '_', or other scripts' digits)."""


@dataclass
class Script:
    path: Path
    settings: dict[str, object] = field(default_factory=dict)
    lines: list[tuple[int, str]] = field(default_factory=list)


def read_script(path: str | Path) -> Script:
    """Read and check a dialogue: every setting's value is checked here, so a bad one names its line."""
    path = Path(path)
    text = read_text(path, "dialogue", limits.MAX_DIALOGUE_BYTES)
    lines = text.split("\n")  # line numbers as an editor counts them: U+2028, NEL, form feed end no line
    if lines[-1] == "":
        lines.pop()
    if len(lines) > limits.MAX_DIALOGUE_LINES:
        raise FormatError(f"more than {limits.MAX_DIALOGUE_LINES} lines in one dialogue", path,
                          limits.MAX_DIALOGUE_LINES + 1)
    script = Script(path)
    for number, raw in enumerate(lines, start=1):
        line = raw.split(" #", 1)[0].strip() if not raw.lstrip().startswith("#") else ""
        if not line:
            continue
        if line.startswith("@") and not line.startswith(AUDIO):
            if script.lines:
                raise FormatError("settings (@...) must come before the first input line", path, number)
            key, _, value = line[1:].partition(" ")
            if key not in SETTINGS:
                raise FormatError(f"unknown setting @{key} (known: {', '.join('@' + k for k in SETTINGS)})",
                                  path, number)
            if key in script.settings:
                raise FormatError(f"@{key} is set twice", path, number)
            script.settings[key] = _setting(key, value.strip(), path, number)
            continue
        if len(line) > MAX_LINE_CHARS:
            raise FormatError(f"the line is too long ({len(line)} characters, at most {MAX_LINE_CHARS})", path, number)
        script.lines.append((number, line))
    if not script.lines:
        raise FormatError("the dialogue has no input lines", path)
    return script


def _setting(key: str, value: str, path: Path, line: int) -> object:
    """One setting's value, checked as strictly as the command-line option it stands for."""
    shown = repr(value) if len(value) <= 40 else repr(value[:37]) + "..."
    if SETTINGS[key] is int:
        if not _WHOLE_NUMBER.fullmatch(value):
            what = "0 or more" if value.startswith("-") else "written in digits"
            raise FormatError(f"@{key} needs a int {what}, got {shown}", path, line)
        return int(value)
    if key == "lang":
        return Lang.parse(value, path, line)
    if key in CHOICES and value not in CHOICES[key]:
        raise FormatError(f"@{key} must be one of {', '.join(CHOICES[key])}, got {shown}", path, line)
    if not value:
        raise FormatError(f"@{key} needs a value", path, line)
    return value
