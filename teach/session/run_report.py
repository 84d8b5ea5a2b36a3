"""What a run did besides its finished steps, in words: each action the tree tried and that
failed, and why (what it needed and lacked), and the action a Ctrl-C stopped. The session
watches a run through the world's ticker (``TryWatch``) and hears of every action it begins."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from teach import messages as m
from teach.bt.nodes import Action, Node, Status, walk
from teach.bt.tick import TickResult
from teach.dialogue.phrases import Token
from teach.dialogue.questions import join_words
from teach.domain import Domain, Literal, State
from teach.messages import Lang
from teach.session.replies import Reply, ReplyKind
from teach.symbolic import apply_action, steps_towards
from teach.world.protocol import Outcome, RunResult, Ticker


@dataclass
class TryWatch:
    """A ticker that ticks like ``ticker`` and notes every action of ``tree`` a tick saw fail,
    with the world's state then (``state``)."""

    ticker: Ticker
    tree: Node
    state: Callable[[], State]
    failed: list[tuple[str, State]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self._actions = {node.uid: node.name for node in walk(self.tree) if isinstance(node, Action)}

    def __call__(self, tree: Node, conditions: Callable[[str], bool] | Mapping[str, bool],
                 status: Callable[[str], Status]) -> TickResult:
        result = self.ticker(tree, conditions, status)
        for uid, seen in result.trace:
            if seen is Status.FAILURE and uid in self._actions:
                self.failed.append((self._actions[uid], self.state()))
        return result


def failed_tries(watch: TryWatch, started: list[tuple[State, str]], result: RunResult) -> list[tuple[str, State]]:
    """Every action that failed in the run, in order: those a tick saw fail, and the last one
    begun when the world refused it (a symbolic world ends the run there)."""
    failed = list(watch.failed)
    if result.outcome is Outcome.FAILURE and len(started) > len(result.steps) \
            and not any(action == started[-1][1] for action, _ in failed):
        failed.append((started[-1][1], started[-1][0]))
    return failed


def tried_lines(failed: list[tuple[str, State]], domain: Domain, lang: Lang) -> list[str]:
    """ "I tried to grasp the ball (2 times), but it did not work: first this must be true: …",
    one line per action and reason, in the order they first failed."""
    counted: dict[tuple[str, str], int] = {}
    for action, state in failed:
        key = (action, why_not(domain, action, state, lang))
        counted[key] = counted.get(key, 0) + 1
    lines = []
    for (action, reason), times in counted.items():
        label = domain.action(action).label(lang)
        text = m.TRIED_FAILED if times == 1 else m.TRIED_FAILED_TIMES
        lines.append(text(lang, action=label, reason=reason, times=times))
    return lines


def why_not(domain: Domain, action: str, state: State, lang: Lang, needs: tuple[Literal, ...] = ()) -> str:
    """Why an action failed, in words: the preconditions it lacked (and what the teacher's phrase
    for it ``needs``), if it has any."""
    missing = [domain.condition(p.name).label(lang, p.value) for p in lacked(domain, action, state, needs)]
    return m.IT_NEEDS(lang, conditions=join_words(missing, lang)) if missing else m.IT_DID_NOT_WORK(lang)


def phrase_said(domain: Domain, step: Token, lang: Lang) -> str:
    """How to quote the phrase a step was refused for: as matched, where it is one of the session's
    language ("bring it to the bin": "bring the ball to the bin"), else as typed (its text is then
    the step's label, which needs none of what the phrase does)."""
    action = domain.action(step.name)
    return step.text if step.text in (action.de_when if lang == Lang.DE else action.en_when) else step.said or step.text


def untrue_now(domain: Domain, action: str, state: State, lang: Lang) -> str:
    """The preconditions an action lacks, said as they are ("the bin is out of reach")."""
    return join_words([domain.condition(p.name).label(lang, not p.value) for p in lacked(domain, action, state)], lang)


def already_so(domain: Domain, action: str, state: State, lang: Lang) -> str:
    """What an action would make so, in words, where all of it is so already ("I can see the ball"
    for a second "find the ball"); "" where something is left to do, the domain declares no effects,
    a precondition it lacks is not one its effects undo (it cannot be done for another reason), or
    it only ends something (snacks' "offer a snack" with nobody there was "nobody is there to talk
    to already": the person leaving is what offering costs, not what it is for)."""
    effects = domain.action(action).ram
    if not effects or not all(domain.holds(p, state) for p in effects) or not any(p.value for p in effects):
        return ""
    undone = {(p.name, not p.value) for p in effects}
    if any((p.name, p.value) not in undone for p in lacked(domain, action, state)):
        return ""
    # said by what it makes true ("ich halte a und b ist frei", not also "nicht: a liegt auf b, …")
    return join_words([domain.condition(p.name).label(lang, p.value) for p in effects if p.value], lang)


def lacked(domain: Domain, action: str, state: State, needs: tuple[Literal, ...] = ()) -> list[Literal]:
    """What ``action`` lacks in ``state`` by the domain's model, and of what the phrase it was said
    by ``needs``: empty where it can be done as said."""
    wanted = dict.fromkeys((*domain.action(action).pre, *needs))
    return [p for p in wanted if not domain.holds(p, state)]


WAY_STEPS = 3
"""The longest way to a refused step that is offered: longer, and it is not a hint but a plan."""


def way_there(domain: Domain, action: str, state: State, lang: Lang, needs: tuple[Literal, ...] = ()) -> list[Reply]:
    """After a step of the teacher's was refused, the steps that would make it possible ("To get
    there: go to the ball, grasp the ball, go to the bin."), if ``way_steps`` finds them."""
    steps = way_steps(domain, action, state, needs)
    if not steps:
        return []
    labels = ", ".join(domain.action(name).label(lang) for name in steps)
    return [Reply(ReplyKind.INFO, m.WAY_THERE(lang, steps=labels))]


def way_steps(domain: Domain, action: str, state: State, needs: tuple[Literal, ...] = ()) -> list[str]:
    """The actions that would make a refused ``action`` possible in ``state`` (with what the
    teacher's phrase for it ``needs``), if the domain's model has a short way that the step does
    not merely undo (putting d on a to take it off again)."""
    steps = steps_towards(domain, state, action, WAY_STEPS, needs)
    if not steps:
        return []
    for step in steps[:-1]:
        state = apply_action(domain, state, step)
    if apply_action(domain, apply_action(domain, state, steps[-1]), action) == state:
        return []  # the step would only undo the way's last one ("take d off a" where d is on the table)
    return steps
