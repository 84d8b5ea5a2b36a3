"""Answers to what the teacher asks the robot about itself: "is it done?", "why did you do that?",
"are you sure?", "what is the task?". Each is said from what the session knows; nothing is ended or
changed."""

from __future__ import annotations

from teach import messages as m
from teach.bt.nodes import Node
from teach.dialogue.questions import join_words
from teach.domain import Domain, State
from teach.messages import Lang
from teach.session.describe import unmet_goal
from teach.session.learning import Learning
from teach.session.replies import Reply, ReplyKind
from teach.session.tree_words import done_words


def done_yet(domain: Domain, state: State, demonstrating: bool, lang: Lang) -> list[Reply]:
    """ "Is it done?": the domain's goal as it holds in ``state`` ('done' ends a demonstration;
    "are we done?" did, as "we are done" does)."""
    if not domain.goal:
        return [Reply(ReplyKind.INFO, m.ONLY_YOU_TELL_DONE(lang))]
    unmet = unmet_goal(domain, state, lang)
    if unmet:
        return [Reply(ReplyKind.INFO, m.NOT_DONE_YET(lang, unmet=unmet))]
    return [Reply(ReplyKind.INFO, (m.WHAT_NOW_FINISHED if demonstrating else m.NOTHING_TO_DO)(lang))]


def what_task(domain: Domain, tree: Node | None, lang: Lang) -> list[Reply]:
    """ "What is the task?": when the learned tree says it is done (``tree``: None before any
    demonstration ended), else the goal the domain file declares, else that the teacher shows it."""
    done = done_words(tree, domain, lang) if tree is not None else None
    if done is not None:
        return [Reply(ReplyKind.INFO, m.TASK_LEARNED(lang, done=done))]
    if domain.goal:
        goal = join_words([domain.condition(lit.name).label(lang, lit.value) for lit in domain.goal], lang)
        return [Reply(ReplyKind.INFO, m.TASK_DECLARED(lang, goal=goal))]
    return [Reply(ReplyKind.INFO, m.TASK_SHOWN(lang))]


def why_that(domain: Domain, learning: Learning, step: tuple[str, bool] | None, example: str | None,
             lang: Lang) -> list[Reply]:
    """ "Why did you do that?", "are you sure?" about ``step`` (the action just done, and whether the
    learned tree chose it): the teacher asked for it, or the tree's reasons. ``example``: a step to
    name in "'why …' says why I would do a step" (None: nothing is learned yet to ask about)."""
    if step is None:
        said = m.NO_STEP_JUST_NOW(lang)
        if example is not None:
            said += m.WHY_A_STEP(lang, example=example)
        return [Reply(ReplyKind.INFO, said)]
    name, chosen = step
    label = domain.action(name).label(lang)
    lines = learning.why(name, lang) if chosen else None
    if lines is None:
        return [Reply(ReplyKind.INFO, m.DID_AS_ASKED(lang, action=label))]
    return [Reply(ReplyKind.INFO, "\n".join([m.DID_AS_LEARNED(lang, action=label), *(f"- {line}" for line in lines)]))]
