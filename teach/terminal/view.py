"""How replies look: pure functions from ``Reply`` to rich renderables, shared by the
terminal and by scripted replays (so a transcript shows exactly what the terminal shows)."""

from __future__ import annotations

from rich.console import RenderableType
from rich.panel import Panel
from rich.text import Text

from teach import messages as m
from teach.domain import Domain
from teach.session.published import SessionView
from teach.session.replies import Reply, ReplyKind

STYLES = {ReplyKind.SAY: "bold cyan", ReplyKind.INFO: "white", ReplyKind.ERROR: "bold red",
          ReplyKind.QUESTION: "bold magenta"}
PREFIX = {ReplyKind.SAY: m.SAY_PREFIX, ReplyKind.QUESTION: m.QUESTION_PREFIX, ReplyKind.ERROR: m.ERROR_PREFIX}
MODES = {"idle": m.MODE_IDLE, "demonstrating": m.MODE_DEMONSTRATING, "asking": m.MODE_ASKING}


def render_reply(reply: Reply, domain: Domain, lang: str = "en") -> RenderableType:
    if reply.kind is ReplyKind.TREE and reply.text:  # the caregiver's view: the tree in sentences
        return Panel(Text(reply.text), title=m.TREE_WORDS_TITLE(lang), expand=False)
    if reply.kind is ReplyKind.TREE and reply.tree is not None:
        from teach.bt.render import render_tree

        return Panel(render_tree(reply.tree, compact=True), title=m.TREE_TITLE(lang), expand=False)
    if reply.kind is ReplyKind.STATE:
        text = Text(m.STATE_PREFIX(lang), style="dim")
        if reply.state is None:  # the caregiver's view: the situation in words
            text.append(reply.text)
        for name, value in (reply.state or {}).items():
            text.append(f"{name}", style="green" if value else "red")
            text.append("=1 " if value else "=0 ", style="dim")
        return text
    prefix = PREFIX[reply.kind](lang) if reply.kind in PREFIX else ""
    return Text(prefix + reply.text, style=STYLES.get(reply.kind, ""))


def prompt(mode: str, lang: str) -> str:
    """The prompt the terminal shows: ``teach>``, or ``answer>`` while a question is open."""
    return (m.ANSWER_PROMPT if mode == "asking" else m.PROMPT)(lang)


def render_teacher(line: str, mode: str = "idle", lang: str = "en") -> Text:
    """A typed line as it stands after the prompt (for transcripts of scripted dialogues)."""
    text = Text(prompt(mode, lang), style="bold green")
    text.append(line)
    return text


def toolbar(view: SessionView) -> str:
    """The terminal's bottom line: mode, questions left, generation; what holds (by name) for a
    facilitator only, since the state line already says it in words and names are long."""
    mode = MODES[view.mode](view.lang)
    if not view.facilitator:
        return m.TOOLBAR_PLAIN(view.lang, mode=mode, left=view.questions_left, generation=view.generation)
    return m.TOOLBAR(view.lang, mode=mode, holds=", ".join(view.holds) or "—", left=view.questions_left,
                     generation=view.generation)
