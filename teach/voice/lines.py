"""Which shown replies the robot says aloud, and in what words: the line as shown, shortened for the ear.

"✓ find the ball (nothing changed: not recorded)" is said "find the ball"; "→ go to the bin"
(run progress) is said "now I go to the bin"; a reply of several lines (help, lists) is said by its
first line, except the tree in words, which is said whole. State lines and drawn trees are not said.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from teach import messages as m
from teach.session.replies import Reply, ReplyKind

_MARKS = re.compile(r"[“”„‚‘’'\"«»()\[\]*_`–—•]")
_CHECK, _CROSS, _ARROW = "✓", "✗", "→"


@dataclass(frozen=True)
class Line:
    text: str
    urgent: bool = False
    """A question: it goes before waiting lines and cuts short a progress line being said."""
    passing: bool = False
    """Run progress: dropped or cut short when a question comes."""


def spoken_line(reply: Reply, lang: str) -> Line | None:
    """What to say for ``reply``, or None when it is not said."""
    if reply.kind is ReplyKind.STATE and not reply.asked or not reply.text \
            or (reply.kind is ReplyKind.TREE and reply.tree is not None and not reply.text):
        return None
    lines = [line.strip() for line in reply.text.splitlines() if line.strip()]
    if reply.kind is ReplyKind.TREE:  # said whole, each line a sentence of its own
        text = " ".join(line if line.endswith((".", ":", "!", "?")) else line + "." for line in lines)
    else:
        text = lines[0] if lines else ""
    passing = text.startswith(_ARROW)
    if text.startswith((_CHECK, _CROSS)):
        text = text[1:].split(" (", 1)[0]  # the confirmation in short form
    elif passing:
        text = m.SPOKEN_NOW(lang, action=text[1:].strip())
    text = re.sub(r"\s+([?!.,:;])", r"\1", " ".join(_MARKS.sub(" ", text).split()))
    return Line(text, urgent=reply.kind is ReplyKind.QUESTION, passing=passing) if text else None
