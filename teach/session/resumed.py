"""What a resume sets up again in the world, and says: the situation the journal last saw with
no demonstration open, then the demonstration (or run) that was open when the session ended."""

from __future__ import annotations

from teach import messages as m
from teach.demos import Demonstration
from teach.dialogue.questions import describe_situation
from teach.domain import Domain
from teach.errors import TeachError
from teach.messages import Lang
from teach.open_demonstration import OpenDemonstration
from teach.session.record import SessionRecord
from teach.session.replies import Reply, ReplyKind
from teach.session.showing import steps_said
from teach.world.protocol import TeachingWorld


def restore_situation(record: SessionRecord, world: TeachingWorld, domain: Domain, lang: Lang, exact: bool,
                      demos: list[Demonstration]) -> list[Reply]:
    """Set the world up as the journal last saw it with no demonstration open, and say so. A
    'reset N' is made again exactly; otherwise the conditions are arranged (``exact``: that puts
    the world itself back; in MuJoCo it places the objects anew, and the teacher is told)."""
    last = record.last_situated()
    if last is None:
        if demos:  # a journal from before situations were journalled
            world.arrange(demos[-1].steps[-1].state)
        return []
    state = record.state(last.state, f"events[{record.journal.events.index(last)}]: state", domain)
    try:
        made_again = False
        if last.seed is not None:  # a new start that depends on the session's set-ups may differ now
            world.reset(last.seed)
            made_again = world.state() == state
        if not made_again:
            world.arrange(state)
        exact = exact or made_again
    except TeachError:  # the world cannot be put in that situation
        situation = describe_situation(domain, state, lang)
        return [Reply(ReplyKind.INFO, m.SITUATION_NOT_RESTORED(lang, situation=situation))]
    return [Reply(ReplyKind.INFO, (m.SITUATION_RESTORED if exact else m.SITUATION_RESTORED_ANEW)(lang))]


def restore_open(record: SessionRecord, world: TeachingWorld, domain: Domain, lang: Lang) -> list[Reply] | None:
    """Reopen the demonstration that was open when the session ended; a run the session ended
    in becomes the correction its finished steps begin, the world set up before the action it
    had begun. None: nothing was open, or the world cannot be put back there."""
    journalled = record.journalled_open(domain)
    if journalled is None:
        return None
    steps, where, run = journalled
    try:
        world.arrange(where)
    except TeachError:  # the world cannot be put back there: the last situation stays
        return None
    record.open = OpenDemonstration.from_steps(steps) if steps else None
    if record.open is not None:  # a stopped run the teacher had not added to: 'run' tries again, as before
        record.open.robot_steps = min(record.journal.open_robot, len(steps))
    if run:
        label = domain.action(run).label(lang)
        text = m.RUN_RESTORED(lang, action=label, steps=steps_said(len(steps), lang)) if steps else \
            m.RUN_RESTORED_NO_STEPS(lang, action=label)
    else:
        text = m.OPEN_RESTORED(lang, steps=steps_said(len(steps), lang))
    return [Reply(ReplyKind.INFO, text)]
