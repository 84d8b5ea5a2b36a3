"""The next situation question for ``teach.learn.learner.Learner``: about what its model does not know.

A pure function of the learner (nothing is copied or trial-updated): it proposes concrete
situations ("If <state>, what should I do?") in which the teacher's answer settles one open
point of the model, most decisive first:

1. **conflicts**: a state the demonstrations labelled two ways; the answer decides it;
   then, as the first question only, **the goal's bound**: a state next to a labelled one
   where the tree would act otherwise if the goal were every literal that held in all goal
   states; the answer shows whether those literals matter (asked once: most of them are
   accidental, and on random domains a second such question costs more than it brings);
2. **possible preconditions left out**: a state where an action was shown, with one literal
   made false that held every time the action was shown, that some known action can make
   hold, but that the learner dropped as probably accidental (the tree still does the action
   there); if the teacher wants something else, it was real;
3. **assumed preconditions**: the same with a precondition the learner assumed from the
   step before it made false; if the teacher still wants that action, it was an accident;
4. **unknown achievers**: the same with a left-out literal no known action makes hold; the
   answer may be an action never demonstrated, whose effect the learner then guesses
   (``Learner.teach_step``);
5. **gaps**: a state next to a demonstrated one where the tree knows nothing (FAILURE);
6. **the goal**: a goal state with one goal *candidate* false that the learned goal does not
   check (the tree says "done" there); an action as answer puts the literal into the goal,
   "done" drops it from the candidates;
7. **unmet goal**: any situation, nearest to the labelled ones first, where the domain's
   declared goal does not hold but the tree would say "done" (the learned goal holds there)
   or do nothing (FAILURE): a run from there ends with "I thought I was done" or does
   nothing, so every answer but "done" changes the tree. These come last only because the
   earlier kinds settle more at once; ``ask`` never says "no question" while one exists.

The order puts first the situations where, on random domains (``bench/bench_generalise.py``),
the teacher's answer most often differed from what the tree did.
A question is asked only if some answer changes the tree: the state is not labelled yet (or
is a conflict), so every answer other than what the tree does now makes it change. The same
state is never proposed twice (``asked``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from teach.bt.nodes import Status
from teach.domain import State
from teach.learn.action_model import literals_of
from teach.learn.learner import Learner
from teach.learn.safe_inquiry import next_safe_question
from teach.learn.situations import (
    SituationQuestion,
    first_open,
    flipped,
    not_to_ask,
    tree_does,
    unmet_goal_situations,
)

KINDS = ("conflict", "goal-bound", "possible-precondition", "assumed-precondition", "unknown-achiever", "gap", "goal",
         "unmet-goal")


def next_question(learner: Learner, asked: Iterable[State] = ()) -> SituationQuestion | None:
    """The most decisive open situation, or None when nothing is left to ask (the safe learner's
    questions come from ``teach.learn.safe_inquiry``)."""
    if learner.safe:
        return next_safe_question(learner, asked)
    skip = not_to_ask(learner, asked)
    return first_open(learner, _candidates(learner, first=not skip), skip)


def _candidates(learner: Learner, first: bool) -> Iterable[SituationQuestion]:
    names = learner.names
    width = len(names)

    def does(state: State) -> str:
        return tree_does(learner, state)

    for conflict in learner.conflicts:
        yield SituationQuestion(conflict.state, "conflict", tree_does=does(conflict.state))

    yield from unmet_goal_situations(learner, does, flipped)
    if first:
        yield from _goal_bound(learner, does, flipped)
    yield from _preconditions(learner, does, flipped, ("possible-precondition",))
    yield from _preconditions(learner, does, flipped, ("assumed-precondition",))
    yield from _preconditions(learner, does, flipped, ("unknown-achiever",))
    for state in learner.situations:
        for index in range(width):
            probe = flipped(state, index)
            if does(probe) == "nothing":
                yield SituationQuestion(probe, "gap", tree_does="nothing")
    goal_states = [learner.state_of(mask) for mask in learner.goal.goal_states]
    checked = set(learner.goal.cover)
    for index, value in learner.goal.candidates():
        if (index, value) in checked:
            continue
        for state in goal_states:
            probe = flipped(state, index)
            if does(probe) == "done":
                yield SituationQuestion(probe, "goal", condition=names[index], tree_does="done")
                break


def _preconditions(learner: Learner, does: Callable[[State], str], flipped: Callable[[State, int], State],
                   kinds: tuple[str, ...]) -> Iterable[SituationQuestion]:
    """A state where an action was shown, with one of its precondition literals flipped. First
    the literals already shown to matter to another action (a condition one step needs is the
    first to check for the others), then by action, the actions shown most often first (a
    literal that held every time an action was done is the likelier to matter the more often
    it was done); either way the answer is the likelier to change the tree."""
    names = learner.names
    width = len(names)
    shown = learner.shown_states()
    by_evidence = sorted(learner.model.actions.items(), key=lambda item: (-item[1].applied.count, item[1].order))
    mattered = {lit for knowledge in learner.model.actions.values()
                for lit in (*knowledge.confirmed, *knowledge.maintained)}
    for kind in kinds:
        first: list[SituationQuestion] = []
        later: list[SituationQuestion] = []
        for name, knowledge in by_evidence:
            if not knowledge.demonstrated or name not in shown:
                continue
            pos, neg = knowledge.possible
            assumed = knowledge.assumed
            made_true, made_false = knowledge.effects
            if kind == "assumed-precondition":
                # assumed from the step before, not the action's own "not done yet" check
                literals = literals_of(assumed[0] & ~made_false, assumed[1] & ~made_true, width)
            else:
                # first the literals some action is known to make hold; then those no known
                # action makes hold (the answer may be an action never demonstrated)
                left_out = literals_of(pos & ~assumed[0], neg & ~assumed[1], width)
                wanted = kind == "possible-precondition"
                literals = [lit for lit in left_out if bool(learner.model.achievers(lit)) == wanted]
            for index, value in literals:
                probe = flipped(shown[name], index)
                question = SituationQuestion(probe, kind, action=name, condition=names[index], tree_does=does(probe))
                (first if (index, value) in mattered else later).append(question)
        yield from first
        yield from later



def _goal_bound(learner: Learner, does: Callable[[State], str],
                flipped: Callable[[State, int], State]) -> Iterable[SituationQuestion]:
    """States next to labelled ones where the plan for the goal's over-specific bound acts
    otherwise than the tree (and the tree does something)."""
    bound = learner.planned_for_goal_bound()
    if bound is None:
        return
    seen: set[State] = set()
    for state in learner.situations:
        for index in range(len(learner.names)):
            probe = flipped(state, index)
            if probe in seen:
                continue
            seen.add(probe)
            now = does(probe)
            if now == "nothing":
                continue
            status, action = bound(probe)
            there = action if status is Status.RUNNING else "done" if status is Status.SUCCESS else "nothing"
            if there != now:
                yield SituationQuestion(probe, "goal-bound", tree_does=now)
