"""The documents a recording shows beside the scene (domain, state, demonstration), as markdown."""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from teach.domain import ActionDef, Domain


def domain_document(domain: Domain) -> str:
    """The vocabulary: conditions, actions with their phrases and definitions, the goal."""
    lines = [f"# Domain {domain.name}", "", "| ID | condition | meaning |", "|---|---|---|"]
    lines += [f"| {i} | {c.name} | {c.en} |" for i, c in enumerate(domain.conditions, 1)]
    lines += ["", "| ID | action | phrases | pre | ram |", "|---|---|---|---|---|"]
    lines += [f"| {a.id} | {a.name} | {_phrases(a)} | {' '.join(map(str, a.pre))} | "
              f"{' '.join(map(str, a.ram))} |" for a in domain.actions]
    if domain.goal:
        lines += ["", "Goal: " + " ".join(map(str, domain.goal))]
    return "\n".join(lines)


def _phrases(action: ActionDef) -> str:
    """An action's English phrases, those that mean it only while ``when`` holds marked so."""
    when = f"; while {' '.join(map(str, action.when))}: {', '.join(action.en_when)}" if action.en_when else ""
    return ", ".join(action.en) + when


def state_document(names: Sequence[str], values: Sequence[bool], action: str | None) -> str:
    """The running action and each condition's value."""
    doc = [f"**Running:** {action or '—'}", "", "| condition | value |", "|---|---|"]
    doc += [f"| {n} | {'✔ true' if v else '✘ false'} |" for n, v in zip(names, values, strict=True)]
    return "\n".join(doc)


def demonstration_document(name: str, domain: Domain, states: Sequence[str], labels: Sequence[str]) -> str:
    """A demonstration as a table: one row per line, its state bits and its action label."""
    table = ["| # | " + " | ".join(domain.condition_names) + " | action |",
             "|---" * (len(domain.conditions) + 2) + "|"]
    table += [f"| {i} | " + " | ".join(state) + f" | {label} |"
              for i, (state, label) in enumerate(zip(states, labels, strict=True), 1)]
    return f"# {name}\n\n" + "\n".join(table)


_MARKDOWN_SPECIALS = str.maketrans({c: "\\" + c for c in "\\`*_[]#<>|~"})


def escaped(text: str) -> str:
    """``text`` shown as it is in a markdown document (its line breaks kept, a line that would
    start a list kept as text)."""
    lines = [re.sub(r"^(\s*\d+)([.)]\s)", r"\1\\\2", re.sub(r"^(\s*)([-+]\s)", r"\1\\\2", line))
             for line in text.translate(_MARKDOWN_SPECIALS).split("\n")]
    return "  \n".join(lines)


def newest_first(title: str, entries: Sequence[str], empty: str) -> str:
    """A panel of recent entries (markdown each), the newest at the top where a panel opens."""
    body = "\n\n".join(reversed(entries)) if entries else f"*{empty}*"
    return f"### {title}\n\n{body}"
