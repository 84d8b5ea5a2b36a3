"""Learner results in the teacher's words: what an update changed, why a demonstration was
refused, which goal conditions are still missing; and the actions a greeting names."""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import TYPE_CHECKING

from teach import messages as m
from teach.dialogue.questions import MUST_KINDS, Question, join_words
from teach.domain import ActionDef, Domain, Literal, State
from teach.errors import LearnError
from teach.messages import Lang

if TYPE_CHECKING:
    from teach.learn.learner import Explanation, Update

_WHY = {"contradiction": m.WHY_CONTRADICTION, "repeated": m.WHY_REPEATED, "order": m.WHY_ORDER}


def why_refused(error: LearnError, lang: Lang) -> str:
    """A learner's refusal in the teacher's words (the details follow for the facilitator)."""
    reason = _WHY.get(error.kind)
    return reason(lang) if reason is not None else error.message


def describe_update(update: Update, learned: list[str], domain: Domain, lang: Lang,
                    answered: tuple[Question, str | None] | None = None) -> str:
    """What an update changed, in the teacher's words (``learned``: actions new in the tree;
    ``answered``: the question and its answer, when the update learned an answer)."""
    parts: list[str] = []
    if learned:
        said = m.LEARNED_STEP if len(learned) == 1 else m.LEARNED_STEPS
        parts.append(said(lang, steps=" → ".join(domain.action(a).label(lang) for a in learned)))
    elif update.tree_changed:
        parts.append(m.CHANGED(lang) if answered is None else answer_changed(*answered, domain, lang))
    if update.new_conflicts:
        parts.append(m.CONFLICT_NOTED(lang))
    if not parts:
        return m.ANYWAY(lang)
    text = "; ".join(parts)
    return text[0].upper() + text[1:] + "."


def answer_changed(question: Question, answer: str | None, domain: Domain, lang: Lang) -> str:
    """What an answer that changed the tree lets the robot do, in the question's words ("I changed
    what I do in some situations" said nothing about which). A yes to "may I still …?" (or "is the
    task done?"): that action (the end) also where the conditions it had always seen do not hold,
    exactly what the yes rules out; any other answer: what the robot now does there."""
    if question.kind in MUST_KINDS and answer == question.action:
        conditions = join_words([domain.condition(name).label(lang, not value) for name, value in question.settles],
                                lang)
        if answer is None:
            return m.NOW_DONE_TOO(lang, conditions=conditions)
        return m.NOW_MAY_TOO(lang, action=domain.action(answer).label(lang), conditions=conditions)
    if answer is None:
        return m.NOW_DONE_THERE(lang)
    return m.NOW_THERE(lang, action=domain.action(answer).label(lang))


def explain_node(why: Explanation, domain: Domain, lang: Lang) -> str:
    """A node's reason in the teacher's words ("" for the tree's own structure)."""
    sources = "; ".join(source_words(source, lang) for source in why.sources[:3]) + (
        " …" if len(why.sources) > 3 else "")
    condition = domain.condition(why.literal.name).label(lang, why.literal.value) if why.literal is not None else ""
    action = domain.action(why.action).label(lang) if why.action is not None else m.WHY_DONE_HERE(lang)
    if why.kind == "goal":
        return m.WHY_GOAL(lang, condition=condition, sources=sources)
    if why.kind == "precondition":
        return m.WHY_PRE(lang, action=action, condition=condition, sources=sources)
    if why.kind == "exception":
        return m.WHY_EXCEPTION(lang, action=action, sources=sources)
    if why.kind == "last-resort":
        return m.WHY_LAST_RESORT(lang, action=action, condition=condition)
    if why.action is not None and why.literal is not None:
        return m.WHY_EFFECT(lang, action=action, condition=condition, sources=sources)
    return ""


_DEMO_LINE = re.compile(r"^(?:imported .*\()?demo-(\d+)\.csv\)?(?::(\d+))?$")
_ANSWER = re.compile(r"^answer to question (\d+)$")


def source_words(source: str, lang: Lang) -> str:
    """Where the learner saw something, for the teacher: "demo-002.csv:3" → "demonstration 2,
    step 3", "answer to question 1" → "your answer to question 1" (anything else as it is)."""
    demo = _DEMO_LINE.match(source)
    if demo is not None:
        number = int(demo.group(1))
        if demo.group(2) is None:
            return m.SOURCE_DEMO(lang, number=number)
        return m.SOURCE_DEMO_STEP(lang, number=number, step=int(demo.group(2)))
    answer = _ANSWER.match(source)
    if answer is not None:
        return m.SOURCE_ANSWER(lang, number=int(answer.group(1)))
    return source


def literals_label(text: str, domain: Domain, lang: Lang) -> str:
    """"!BallFound & BinClose" → "I cannot see the ball and the bin is within reach"."""
    labels = []
    for part in text.split("&"):
        literal = Literal.parse(part)
        labels.append(domain.condition(literal.name).label(lang, literal.value) if domain.has_condition(literal.name)
                      else part.strip())
    return join_words(labels, lang)


def unmet_goal(domain: Domain, state: State, lang: Lang) -> str:
    """The domain's goal conditions that do not hold, in words ("" when the goal holds)."""
    return _unmet(domain, domain.goal, state, lang)


def unmet_effects(domain: Domain, action: str, state: State, lang: Lang) -> str:
    """The effects the domain file declares for ``action`` that do not hold in ``state``, in words
    ("" when all hold, or it declares none): a step begun but not finished."""
    return _unmet(domain, domain.action(action).ram, state, lang)


def _unmet(domain: Domain, literals: Iterable[Literal], state: State, lang: Lang) -> str:
    """``literals`` that do not hold in ``state``, said as what holds instead."""
    missing = [lit for lit in literals if not domain.holds(lit, state)]
    return join_words([domain.condition(lit.name).label(lang, not lit.value) for lit in missing], lang)


MAX_ACTIONS_NAMED = 12
"""More actions than this (blocksworld's 40) are not all named in the greeting and help: one of
each kind (``form``), or the first ones."""


def some_actions(domain: Domain, lang: Lang, say_more: bool = True) -> str:
    """The domain's actions in the teacher's words: every one or, beyond ``MAX_ACTIONS_NAMED``, one
    of each kind (``actions_to_name``), then "and 36 more like them" (``say_more``; 'help' and Tab
    completion know them all)."""
    shown = actions_to_name(domain)
    left = unnamed(domain, shown)
    more = m.AND_MORE(lang, count=left) if say_more and left else ""
    return ", ".join(a.label(lang) for a in shown) + more


def unnamed(domain: Domain, named: list[ActionDef]) -> int:
    """How many of the domain's actions ``named`` (``actions_to_name``) leaves out: the "36 more like them"."""
    return len(domain.actions) - len(named)


def actions_to_name(domain: Domain) -> list[ActionDef]:
    """Every action of the domain or, beyond ``MAX_ACTIONS_NAMED``, one of each kind on objects all
    different ("stack a b", not "stack a a"): what a line that offers them can hold."""
    actions = domain.actions
    if len(actions) <= MAX_ACTIONS_NAMED:
        return list(actions)
    kinds: dict[str, ActionDef] = {}
    for action in actions:
        if action.form and len(set(action.form[1:])) == len(action.form) - 1:
            kinds.setdefault(action.form[0], action)
    return list(kinds.values())[:MAX_ACTIONS_NAMED] or list(actions[:MAX_ACTIONS_NAMED])
