"""The recording's text panels as documents: the dialogue, the questions asked and the learner's
events, each message whole and wrapped (a text log view cuts a row at the panel's width).

Each panel is re-logged as one markdown document when it changes, holding its latest ``KEEP``
entries with the newest at the top, so the moment under the time cursor is always in view and a
long session costs no more per line than a short one. Every entry starts with its moment on the
``tick`` timeline (``#12``), so a reader can move the time cursor there.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

from teach.observe.markdown import escaped, newest_first

KEEP = 30


@dataclass
class _Question:
    moment: int
    text: str
    left: int
    answer: str | None = None
    change: str = ""

    def markdown(self, number: int) -> str:
        asked = f"`#{self.moment}` **{number}.** {escaped(self.text)} *({self.left} left)*"
        if self.answer is None:
            return asked + "  \n→ *not answered yet*"
        return asked + f"  \n→ **{escaped(self.answer)}**" + (f": {escaped(self.change)}" if self.change else "")


class Panels:
    """Keeps each text panel's latest entries and renders its document."""

    def __init__(self) -> None:
        self._dialogue: deque[str] = deque(maxlen=KEEP)
        self._questions: deque[tuple[int, _Question]] = deque(maxlen=KEEP)
        self._asked = 0
        self._learner: deque[str] = deque(maxlen=KEEP)

    def line(self, moment: int, speaker: str, text: str) -> str:
        """A line of the dialogue; returns the dialogue document."""
        who = f"**{escaped(speaker)}:**" if speaker == "teacher" else f"{escaped(speaker)}:"
        self._dialogue.append(f"`#{moment}` {who} {escaped(text)}")
        return newest_first("Dialogue (newest first)", list(self._dialogue), "nothing said yet")

    def question(self, moment: int, text: str, left: int) -> str:
        self._asked += 1
        self._questions.append((self._asked, _Question(moment, text, left)))
        return self._questions_document()

    def answer(self, answer: str, change: str) -> str:
        """The answer to the latest open question; returns the questions document."""
        open_questions = [q for _, q in self._questions if q.answer is None]
        if open_questions:
            open_questions[-1].answer, open_questions[-1].change = answer, change
        return self._questions_document()

    def _questions_document(self) -> str:
        return newest_first("Questions asked (newest first)", [q.markdown(n) for n, q in self._questions],
                            "no question asked yet")

    def learner(self, moment: int, text: str) -> str:
        """An event of the learner (a generation, an update, a replay, a demonstration, an outside event)."""
        self._learner.append(f"`#{moment}` {escaped(text)}")
        return newest_first("Learner and events (newest first)", list(self._learner), "nothing learned yet")
