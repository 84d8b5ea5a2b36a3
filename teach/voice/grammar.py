"""What the recogniser may hear: a grammar made from the session's domain, so that every line it
can produce is one the session understands.

It holds every English action phrase, the pronoun forms of each action's label ("grasp it"), several actions joined
by "and"/"then", each command word, "start" and "why" with a condition's label, the answer
words (yes, no, done, skip, undo, before, after, ...) and a few sayings ("again", "are you sure").
Written as JSGF for pocketsphinx.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from teach.domain import Domain

PRONOUN = "it"
JOINS = ("and", "then", "and then")
ANSWERS = ("yes", "no", "okay", "done", "skip", "undo", "i don't know")
"""Answers beside the question words (before, after, both, ...) of ``messages.ANSWER_WORDS``."""
SAYINGS = ("again", "once more", "are you sure", "is it done", "are we done", "what now", "what is the task",
           "go back")
"""Whole lines the session answers that name no step or command (outside the grammar they could not be heard)."""
_ARTICLES = ("the", "a", "an")


def spoken_words(text: str) -> list[str]:
    """A phrase as the recogniser spells it: lower case, letters and apostrophes."""
    return re.findall(r"[a-z']+", text.lower())


@dataclass(frozen=True)
class Grammar:
    actions: tuple[str, ...]
    conditions: tuple[str, ...]
    commands: tuple[str, ...]
    answers: tuple[str, ...]

    def lines(self) -> tuple[str, ...]:
        """Every single line it accepts that is not a sequence of actions or a command with an argument."""
        return self.actions + self.commands + self.answers

    def words(self) -> set[str]:
        return {w for text in (*self.lines(), *self.conditions, *JOINS, "start", "why") for w in text.split()}

    def jsgf(self) -> str:
        def rule(name: str, texts: Iterable[str]) -> str:
            return f"<{name}> = " + " | ".join(f"( {t} )" for t in texts) + ";"

        rules = [rule("action", self.actions), rule("join", JOINS), rule("command", self.commands),
                 rule("answer", self.answers)]
        line = "<action> ( <join> <action> )* | <command> | <answer>"
        if self.conditions:
            rules.append(rule("condition", self.conditions))
            line += " | start <condition> | why <condition>"
        return "#JSGF V1.0;\ngrammar teach;\n" + "\n".join(rules) + f"\npublic <line> = {line};\n"


def domain_grammar(domain: Domain, known: Callable[[str], bool] = lambda word: True) -> Grammar:
    """The English grammar of ``domain``; a text with a word ``known`` refuses (not in the
    recogniser's dictionary) is left out, since it could never be heard."""
    from teach import messages as m
    from teach.session.commands import COMMANDS

    def usable(texts: Iterable[str]) -> tuple[str, ...]:
        spelled = (" ".join(spoken_words(t)) for t in texts)
        return tuple(dict.fromkeys(t for t in spelled if t and all(known(w) for w in t.split())))

    phrases = [phrase for action in domain.actions for phrase in action.said("en")]
    # pronoun forms of the words the robot itself uses for its actions ("I can: grasp the ball, ..."):
    # of every phrase, they would crowd short commands out ("drop it" is heard for "run")
    labels = [action.label("en") for action in domain.actions]
    conditions = [text for c in domain.conditions for text in (c.label("en"), c.label("en", False))]
    commands = [command.usage("en").split()[0] for command in COMMANDS]
    answers = [*(word("en") for word in m.ANSWER_WORDS), *ANSWERS, *SAYINGS]
    return Grammar(usable([*phrases, *pronoun_forms(labels)]), usable(conditions), usable(commands),
                   usable(answers))


def pronoun_forms(phrases: Iterable[str]) -> list[str]:
    """Each phrase with one object it names ("the ball") said as "it": "take it to the bin"."""
    forms = []
    for phrase in phrases:
        words = spoken_words(phrase)
        for at, word in enumerate(words[:-1]):
            if word in _ARTICLES:
                forms.append(" ".join([*words[:at], PRONOUN, *words[at + 2:]]))
    return forms
