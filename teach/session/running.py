"""A run of the learned tree in a session, as the teacher sees it: each action announced as it
starts (and journalled first, so a kill mid-run keeps the steps done), the world's events as
they happen, then what the robot did, what it tried and why it stopped. A run that does not
finish opens the correction the teacher's next steps continue."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from teach import messages as m
from teach.bt.nodes import Node
from teach.domain import State
from teach.observe.hook import Observer
from teach.session.describe import unmet_effects, unmet_goal
from teach.session.replies import Reply, ReplyKind
from teach.session.run_report import TryWatch, failed_tries, tried_lines
from teach.session.showing import Showing
from teach.world.protocol import Outcome, WorldEvent

_OUTCOME_WORDS = {Outcome.SUCCESS: m.OUTCOME_SUCCESS, Outcome.FAILURE: m.OUTCOME_FAILURE,
                  Outcome.TIMEOUT: m.OUTCOME_TIMEOUT, Outcome.INTERRUPTED: m.OUTCOME_INTERRUPTED}


@dataclass(frozen=True)
class RunTold:
    """What a run's end says, and what follows it."""

    replies: list[Reply]
    state_line: bool
    """The situation follows (not after a run that had nothing to do)."""
    ask: bool
    """It ended "done" with the goal unmet, or with nothing that fits: where a question pays most."""
    last: str | None = None
    """The last action the tree ran (what "why did you do that?" asks about)."""


def run(tree: Node, showing: Showing, observer: Observer, stop_after: int | None,
        interrupt: Callable[[], bool] | None) -> RunTold:
    """Run ``tree`` in the session's world (``stop_after`` actions at most; ``interrupt`` polled)."""
    world, turn, lang, domain = showing.world, showing.turn, showing.lang, showing.vocabulary.domain
    showing.close()
    started: list[tuple[State, str]] = []

    def announce(action: str) -> None:
        started.append((world.state(), action))
        showing.save_run(started)  # on disk before the teacher sees it: a kill mid-run keeps the steps done
        turn.say([Reply(ReplyKind.INFO, m.RUNNING_ACTION(lang, action=domain.action(action).label(lang)))])

    def heard(event: WorldEvent) -> None:
        turn.say([showing.event_reply(event)])

    observer.on_run_start(tree)
    ticker = world.ticker
    watch = world.ticker = TryWatch(ticker, tree, world.state)  # what failed, for the teacher
    try:
        result = world.run(tree, max_actions=4 * len(domain.actions) + 4, interrupt=interrupt,
                           stop_after=stop_after, on_action=announce, on_event=heard)
    finally:
        world.ticker = ticker
    observer.on_run_end(result.outcome.value, len(result.steps))
    unmet = unmet_goal(domain, world.state(), lang)
    finished = result.outcome is Outcome.SUCCESS and not unmet
    # the last step, stopped by the tree midway (in MuJoCo what it checks can change as it moves)?
    unfinished = unmet_effects(domain, result.steps[-1][1], world.state(), lang) \
        if result.steps and not finished and result.outcome is not Outcome.INTERRUPTED else ""
    if not finished:  # what the robot did so far and what the teacher shows next become one correction
        showing.from_run(result, stopped_midway=bool(unfinished))
    showing.record.note_open("run")  # how the run ended is on disk before the teacher hears of it
    showing.record.save()
    if not result.steps and finished:
        return RunTold([Reply(ReplyKind.SAY, m.NOTHING_TO_DO(lang))], state_line=False, ask=False)
    labels = [domain.action(a).label(lang) for _, a in result.steps]
    if unfinished:
        labels[-1] = m.STEP_NOT_FINISHED(lang, action=labels[-1], unmet=unfinished)
    done = ", ".join(labels)
    replies = [Reply(ReplyKind.INFO, m.I_DID(lang, actions=done) if done else m.I_DID_NOTHING(lang))]
    tried = tried_lines(failed_tries(watch, started, result), domain, lang)
    replies += [Reply(ReplyKind.INFO, line) for line in tried]
    if finished:
        return RunTold(replies + [Reply(ReplyKind.SAY, m.TASK_FINISHED(lang))], state_line=True, ask=False,
                       last=result.steps[-1][1])
    if result.outcome is Outcome.INTERRUPTED and stop_after is None and started:  # Ctrl-C: say where
        message = m.STOPPED_DURING(lang, action=domain.action(started[-1][1]).label(lang))
    elif result.outcome is Outcome.INTERRUPTED:
        message = m.STOPPED(lang)
    elif result.outcome is Outcome.SUCCESS:
        message = m.THOUGHT_DONE(lang, unmet=unmet)
    elif result.outcome is Outcome.FAILURE and tried:  # what failed is said above
        message = m.STUCK_AFTER_TRYING(lang)
    else:
        message = m.STUCK(lang, outcome=_OUTCOME_WORDS[result.outcome](lang))
    return RunTold(replies + [Reply(ReplyKind.SAY, message)], state_line=True,
                   ask=result.outcome in (Outcome.SUCCESS, Outcome.FAILURE),
                   last=result.steps[-1][1] if result.steps else None)
