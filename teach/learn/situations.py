"""What both question selectors share: the question, what the tree does in a state, which
states may not be asked about, and the situations where a run would end short of the declared goal
(``teach.learn.inquiry`` for the guessing learner, ``teach.learn.safe_inquiry`` for the safe one)."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

from teach.domain import State
from teach.learn.learner import Learner

MAX_PROBED = 4096
"""The most situations searched for an unmet goal (every one of a domain of 12 conditions)."""


@dataclass(frozen=True)
class SituationQuestion:
    """A state to ask "what should I do here?" about, and what the answer settles."""

    state: State
    kind: str
    action: str | None = None
    condition: str | None = None
    tree_does: str = ""
    """What the robot would do there now: an action name, "done", or "nothing". The session
    words the question ("If <state>, what should I do?") in the teacher's language."""
    value: bool = True
    settles: tuple[tuple[str, bool], ...] = ()
    """For the safe learner's "must-" kinds: the unsure literals (condition, value) false in
    ``state`` (``teach.learn.safe_inquiry``); ``value`` is the first one's."""


def not_to_ask(learner: Learner, asked: Iterable[State]) -> set[State]:
    """The states asked about already and those said to be impossible: no question may be about
    them (nor about any state ``Learner.possible`` rules out)."""
    return set(asked) | {learner.state_of(mask) for mask in learner.impossible}


def first_open(learner: Learner, candidates: Iterable[SituationQuestion],
               skip: set[State]) -> SituationQuestion | None:
    """The first candidate about a state not in ``skip``, not labelled yet (a conflict is) and that
    can happen."""
    labelled = learner.situations
    for question in candidates:
        if question.state in skip:
            continue
        if question.kind != "conflict" and question.state in labelled:
            continue
        if question.kind != "conflict" and not learner.possible(learner.state_mask(question.state)):
            continue
        return question
    return None


def tree_does(learner: Learner, state: State) -> str:
    """What the learner's tree does in ``state``: an action name, "done", or "nothing"."""
    result = learner.answer_in(state)
    return "done" if result is None else "nothing" if result is False else str(result)


def flipped(state: State, index: int) -> State:
    """``state`` with condition ``index`` the other way."""
    return tuple(not v if i == index else v for i, v in enumerate(state))


def unmet_goal_situations(learner: Learner, does: Callable[[State], str],
                          flipped: Callable[[State, int], State],
                          probes: Iterable[State] | None = None) -> Iterable[SituationQuestion]:
    """Situations where the declared goal does not hold and the tree says "done" or does nothing,
    searched outwards from the labelled ones (one condition changed, then two, ...), so the
    first found are those a teacher most likely meets; or among ``probes`` (not labelled), in
    their order. Without a declared goal, only "nothing"."""
    position = {name: index for index, name in enumerate(learner.names)}
    goal = [(position[literal.name], literal.value) for literal in learner.domain.goal]

    def unmet(state: State) -> bool:
        return any(state[index] != value for index, value in goal)

    def worth_asking(probe: State) -> SituationQuestion | None:
        now = does(probe)
        if (now == "nothing" and (unmet(probe) or not goal)) or (now == "done" and unmet(probe)):
            return SituationQuestion(probe, "unmet-goal", tree_does=now)
        return None

    if probes is not None:
        labelled = learner.situations
        for probe in probes:
            if probe not in labelled and (question := worth_asking(probe)) is not None:
                yield question
        return
    frontier = list(learner.situations)
    seen = set(frontier)
    while frontier and len(seen) < MAX_PROBED:
        reached: list[State] = []
        for state in frontier:
            for index in range(len(learner.names)):
                probe = flipped(state, index)
                if probe in seen:
                    continue
                if len(seen) >= MAX_PROBED:  # bounded inside a ring too: the cost is fixed at any size
                    return
                seen.add(probe)
                reached.append(probe)
                if not learner.possible_when_made(learner.state_mask(probe)):
                    continue
                if (question := worth_asking(probe)) is not None:
                    yield question
        frontier = reached
