"""Every limit on input size in one place, so readers share them and the README can state them.

The limits are generous for real teaching (a learned tree has tens to a few hundred nodes, a
domain a handful of conditions, a session tens of demonstrations) and keep reading linear in
the input with small constants: anything beyond them is refused in one line before it costs
memory or time.
"""

from __future__ import annotations

import re

KIB = 1024
MIB = 1024 * KIB

MAX_NESTING = 32
"""Deepest nesting of arrays, tables or objects in a TOML or JSON file (a domain needs 3)."""

MAX_DOMAIN_BYTES = 1 * MIB
MAX_CONDITIONS = 64
"""Conditions in a domain: a state is one bit each, and a plan over a chain of 64 actions is
still well inside the tree depth limit."""
MAX_ACTIONS = 64
MAX_PHRASES = 64
"""Phrases per action and language."""
MAX_LABEL_CHARS = 500
"""Longest condition label or action phrase."""
MAX_GOAL_LITERALS = MAX_CONDITIONS
MAX_MODEL_LITERALS = MAX_CONDITIONS
"""Literals in one action's ``pre`` or ``ram`` list (duplicates included)."""

MAX_DEMO_BYTES = 4 * MIB
"""Largest demonstration (CSV) file."""
MAX_DEMO_LINES = 10_000
"""Lines in one demonstration."""
MAX_DEMOS = 10_000
"""Demonstrations (CSV files) in one set."""
MAX_SET_LINES = 500_000
"""Lines in all demonstrations of one set together."""

MAX_TREE_BYTES = 5 * MIB
MAX_TREE_NODES = 60_000
"""Elements of a tree file: a policy regressed in a planning domain (``teach.learn.regress``) has up to
40,000 nodes of rules and 10,000 of its goal literals' own besides its exceptions (60,000 elements
are about 1.5 MB of XML). Not more: libxml2 numbers lines only up to 65,535, and every error names
its line."""
MAX_TREE_DEPTH = 200

MAX_DIALOGUE_BYTES = 1 * MIB
MAX_DIALOGUE_LINES = 20_000

MAX_JSON_BYTES = 64 * MIB
"""Largest journal or other JSON file read."""

MAX_NUMBER_DIGITS = 4300
"""Longest integer (in digits) a TOML or JSON file may write: Python's own limit on converting
text to an integer, checked before a parser meets it (a learned file's numbers have a few digits)."""

_TOO_MANY = "{" + str(MAX_NUMBER_DIGITS + 1) + ",}"
_TOO_MANY_PREFIXED = "{" + str(MAX_NUMBER_DIGITS * 4 // 5) + ",}"
"""TOML's 0x, 0o and 0b integers convert without a limit, but printing one that long in decimal
would pass Python's: 3440 hex digits are about 4140 decimal ones."""
_NUMBER_TOKENS = {  # strings (and TOML comments) are passed over; a digit run only counts from its start
    "json": re.compile(r'"(?:[^"\\]|\\.)*"|(?<![0-9])(?P<digits>[0-9]' + _TOO_MANY + ")", re.DOTALL),
    "toml": re.compile(r'"""(?:[^\\]|\\.)*?"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*'
                       r"|(?<![0-9A-Za-z_])(?P<digits>[0-9_]" + _TOO_MANY + "|0[xob][0-9A-Fa-f_]"
                       + _TOO_MANY_PREFIXED + ")", re.DOTALL),
}


def too_long_number(text: str, syntax: str) -> int | None:
    """The line of the first integer longer than ``MAX_NUMBER_DIGITS`` outside the strings of a
    JSON or TOML (``syntax``) text, or None: checked before a parser's own conversion fails on it."""
    for match in _NUMBER_TOKENS[syntax].finditer(text):
        if match.group("digits"):
            return text.count("\n", 0, match.start()) + 1
    return None
