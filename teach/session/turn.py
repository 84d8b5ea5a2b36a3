"""The turn: every reply to one teacher line, in the order it was said.

A reply leaves the session only through ``say``: it is told to the observer's dialogue, kept
for the line's answer and shown at once by a live driver (steps as they happen, the tree
before a question is chosen). The session's owners (the machine, guiding, the hand follower)
all speak through one ``Turn``, so a driver sees each reply exactly once.
"""

from __future__ import annotations

from collections.abc import Callable

from teach.observe.hook import Observer
from teach.session.replies import Reply


class Turn:
    """The replies of the line being handled; ``live`` shows each as it is said."""

    def __init__(self, observer: Observer, questions_left: Callable[[], int]):
        self.observer = observer
        self.questions_left = questions_left
        """The question budget left, logged with each line of the dialogue."""
        self.live: Callable[[Reply], None] | None = None
        self._replies: list[Reply] = []

    def begin(self) -> None:
        """A new line: what an earlier one left unsaid is dropped."""
        self._replies = []

    def say(self, replies: list[Reply]) -> list[Reply]:
        """Send ``replies`` now. Returns nothing left to hand back (the turn holds them)."""
        for reply in replies:
            if reply.spoken:  # questions go to on_question
                self.observer.on_dialogue("robot", reply.text, self.questions_left())
        self._replies.extend(replies)
        if self.live is not None:
            for reply in replies:
                self.live(reply)
        return []

    def close(self, replies: list[Reply]) -> list[Reply]:
        """Send the last replies and hand back all of this turn's, in the order they were sent."""
        self.say(replies)
        turn, self._replies = self._replies, []
        return turn
