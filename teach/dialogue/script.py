"""Scripted dialogues: a human-writable file of teacher inputs that drives the very same
session manager as the terminal.

Format (``dialogues/*.dialogue``, UTF-8):

    # comment lines and blank lines are ignored
    @lang de              # settings before the first input line: lang, questions, seed, world
    @questions 5
    Ball finden, zum Ball gehen, Ball greifen, zum Eimer gehen, Ball in den Eimer legen
    fertig
    run

Every other line is typed at the prompt as it is. While the robot has a question open the
next line is the answer, unless an oracle answers questions (``--oracle``/``--oracle-model``),
in which case script lines are never taken as answers.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from teach.errors import FormatError
from teach.fsutil import read_text

SETTINGS = {"lang": str, "questions": int, "seed": int, "world": str, "domain": str}


@dataclass
class Script:
    path: Path
    settings: dict[str, object] = field(default_factory=dict)
    lines: list[tuple[int, str]] = field(default_factory=list)


def read_script(path: str | Path) -> Script:
    path = Path(path)
    text = read_text(path, "dialogue")
    script = Script(path)
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split(" #", 1)[0].strip() if not raw.lstrip().startswith("#") else ""
        if not line:
            continue
        if line.startswith("@"):
            if script.lines:
                raise FormatError("settings (@...) must come before the first input line", path, number)
            key, _, value = line[1:].partition(" ")
            if key not in SETTINGS:
                raise FormatError(f"unknown setting @{key} (known: {', '.join('@' + k for k in SETTINGS)})",
                                  path, number)
            try:
                script.settings[key] = SETTINGS[key](value.strip())
            except ValueError:
                raise FormatError(f"@{key} needs a {SETTINGS[key].__name__}, got {value.strip()!r}", path, number) from None
            continue
        script.lines.append((number, line))
    if not script.lines:
        raise FormatError("the dialogue has no input lines", path)
    return script
