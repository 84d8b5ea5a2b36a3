"""Learner results in the teacher's words: what an update changed, why a demonstration was
refused, which goal conditions are still missing."""

from __future__ import annotations

from typing import TYPE_CHECKING

from teach.domain import Domain, Literal, State
from teach.errors import LearnError
from teach.session import messages as m

if TYPE_CHECKING:
    from teach.learn.specialize import Update

_WHY = {"contradiction": m.WHY_CONTRADICTION, "repeated": m.WHY_REPEATED, "order": m.WHY_ORDER}


def why_refused(error: LearnError, lang: str) -> str:
    """A learner's refusal in the teacher's words (the details follow for the facilitator)."""
    reason = _WHY.get(error.kind)
    return reason(lang) if reason is not None else error.message


def describe_update(update: Update, domain: Domain, lang: str) -> str:
    """What an update changed, in the teacher's words."""
    parts: list[str] = []
    if update.inserted:
        steps = " → ".join(domain.action(a).label(lang) for a in update.inserted)
        parts.append(m.LEARNED_STEPS(lang, steps=steps))
    for action in dict.fromkeys(c.action for c in update.removed if c.action not in update.inserted):
        when = [literals_label(c.text, domain, lang) for c in update.removed if c.action == action]
        parts.append(m.ALSO_WHEN(lang, action=domain.action(action).label(lang), when=m.OR(lang).join(when)))
    for change in update.added:
        parts.append(m.NOT_WHEN(lang, action=domain.action(change.action).label(lang),
                                when=literals_label(change.text, domain, lang)))
    if not parts:
        return m.ANYWAY(lang)
    text = "; ".join(parts)
    return text[0].upper() + text[1:] + "."


def literals_label(text: str, domain: Domain, lang: str) -> str:
    """"!BallFound & BinClose" → "you cannot see the ball and the bin is within reach"."""
    labels = []
    for part in text.split("&"):
        literal = Literal.parse(part)
        labels.append(domain.condition(literal.name).label(lang, literal.value) if domain.has_condition(literal.name)
                      else part.strip())
    return m.AND(lang).join(labels)


def unmet_goal(domain: Domain, state: State, lang: str) -> str:
    """The domain's goal conditions that do not hold, in words ("" when the goal holds)."""
    missing = [lit for lit in domain.goal if not domain.holds(lit, state)]
    return m.AND(lang).join(domain.condition(lit.name).label(lang, not lit.value) for lit in missing)


def removed_names(update: Update) -> list[str]:
    """The guards an update removed, as the observer names them."""
    return [change.text for change in update.removed]
