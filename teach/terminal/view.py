"""How replies look: pure functions from ``Reply`` to rich renderables, shared by the
terminal and by scripted replays (so a transcript shows exactly what the terminal shows)."""

from __future__ import annotations

from rich.console import RenderableType
from rich.panel import Panel
from rich.text import Text

from teach.session.machine import Reply
from teach.domain import Domain

STYLES = {"say": "bold cyan", "info": "white", "error": "bold red", "question": "bold magenta"}
PREFIX = {"en": {"say": "robot: ", "question": "robot asks: ", "error": "! ", "state": "  state: "},
          "de": {"say": "Roboter: ", "question": "Roboter fragt: ", "error": "! ", "state": "  Zustand: "}}


def render_reply(reply: Reply, domain: Domain, lang: str = "en") -> RenderableType:
    if reply.kind == "tree" and reply.tree is not None:
        from teach.bt.render import render_tree

        title = "gelernter Baum" if lang == "de" else "learned tree"
        return Panel(render_tree(reply.tree, compact=True), title=title, expand=False)
    if reply.kind == "state" and reply.state is not None:
        text = Text(PREFIX[lang]["state"], style="dim")
        for name, value in reply.state.items():
            text.append(f"{name}", style="green" if value else "red")
            text.append("=1 " if value else "=0 ", style="dim")
        return text
    return Text(PREFIX[lang].get(reply.kind, "") + reply.text, style=STYLES.get(reply.kind, ""))


def prompt(mode: str, lang: str) -> str:
    """The prompt the terminal shows: ``teach>``, or ``answer>`` while a question is open."""
    if mode == "asking":
        return "Antwort> " if lang == "de" else "answer> "
    return "teach> "


def render_teacher(line: str, mode: str = "idle", lang: str = "en") -> Text:
    """A typed line as it stands after the prompt (for transcripts of scripted dialogues)."""
    text = Text(prompt(mode, lang), style="bold green")
    text.append(line)
    return text
