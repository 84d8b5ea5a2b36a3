"""What the session says back: a reply of one kind, shown by the drivers' renderers."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from teach.bt.nodes import Node


class ReplyKind(StrEnum):
    SAY = "say"
    INFO = "info"
    ERROR = "error"
    TREE = "tree"
    STATE = "state"
    QUESTION = "question"


@dataclass(frozen=True)
class Reply:
    """Something to show: text for most kinds, a tree for ``TREE``, condition values for ``STATE``."""

    kind: ReplyKind
    text: str = ""
    tree: Node | None = None
    state: dict[str, bool] | None = None
    asked: bool = False
    """The teacher asked for it ("state", "what do you see?"): the situation is then a line of the
    dialogue too, not only the status shown after each step."""

    @property
    def spoken(self) -> bool:
        """Whether it is a line of the dialogue (questions are reported as questions)."""
        return (self.kind in (ReplyKind.SAY, ReplyKind.INFO, ReplyKind.ERROR) or self.asked) and bool(self.text)
