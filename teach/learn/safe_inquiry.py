"""The next question for the safe ``teach.learn.learner.Learner`` (``safe=True``): about what it does not know.

A pure function of the learner (nothing is copied or trial-updated). The learner is safe by
construction: it checks every precondition and goal literal it has not ruled out (see
``teach.learn.action_model``), so what it does not know makes it stop, never act on a guess.
A question is worth asking by how much its answer *settles*: how many of those unsure
literals one "yes" rules out. In order:

1. **conflicts**: a state the demonstrations labelled two ways; the answer decides it; then
   a situation where the domain's declared goal does not hold but the tree says "done" (only
   an answer can have taught that);
2. **the most settling situation**, in a domain of at most ``SETTLING_STATES`` states: of the
   states where the robot does nothing now, first those where the most predicted runs of the
   tree end (``_runs_ending_stuck``), then the one whose answer is expected to rule out the most
   unsure literals. The answer is predicted under hypotheses drawn from what the data leaves
   open (each unsure literal needed or not), each by the plan it would give; whichever action
   the teacher then names, its unsure literals that do not hold there are ruled out. The
   expectation is over the hypotheses that act there, until an asked situation taught nothing. (A "may I
   still grasp the ball?" where every hypothesis has the robot do something else first would
   only teach that something else.) Measured on other data than the ball task it was first
   looked at on: ``bench/bench_snacks_draws.py``;
3. **hypotheses**, first those asked where the robot now does nothing, then those whose
   "yes" would let the robot act (or finish) in the most
   situations it could meet where it now does nothing (for the goal: is not done), then the
   most literals settled (ties: the goal, then the action shown most often). The situations
   counted are every state of a small domain without forms; in a large one, or one with forms
   (objects), the states the learned effects lead to (``predicted``), as a state made by
   changing conditions at random mostly cannot happen there. For an action: a situation where
   every literal it needs holds but a group of its unsure ones does not — with ``predicted``
   states one of them (so not an impossible one), where the robot does nothing now if there is
   one, else a state where it was shown with the group made false ("If …, may I still grasp
   the ball?"); for the goal: a goal state with its unsure literals made false ("… is the task
   done?"). A yes rules all of them out at once. A no (or "that cannot happen") splits the
   group: the next question about that action tests half of it, so a needed literal is found
   in log2(n) questions (group testing) and then kept for good. Where every state is counted, a
   question about an action whose yes would let it run nowhere the robot now does nothing,
   asked where the robot does something, is not asked: its answer would be what it does anyway
   (the predicted states are only some of the states the robot meets, so there it is asked).
   Literals the data gives a reason for (the step before made them hold; the action undoes
   them) are asked about only when no other group is left, and only where the robot does
   nothing: they are usually needed, so elsewhere the answer would change nothing;
4. **unmet goal**: a situation, nearest the labelled ones first (with ``predicted`` states,
   one of them), where the domain's declared goal does not hold and the tree would do nothing;
5. **gaps**: a state next to a labelled one where the tree does nothing (small domains without
   forms only).

These kinds are chosen by what their answer settles, not tuned to one generator: measured on
standard planning domains and independent random domains in ``bench/bench_safety.py``.
A question is never about a state asked before, labelled already (but for conflicts), or
said to be impossible (``Learner.rule_out``). Every search is bounded by ``MAX_PROBED``.
"""

from __future__ import annotations

import itertools
import random
from collections.abc import Callable, Iterable

from teach.bt.nodes import Status
from teach.domain import State
from teach.learn.action_model import Lit, literal_masks, literals_of
from teach.learn.learner import Learner
from teach.learn.situations import (
    MAX_PROBED,
    SituationQuestion,
    first_open,
    flipped,
    not_to_ask,
    tree_does,
    unmet_goal_situations,
)

KINDS = ("conflict", "must-goal", "must-precondition", "unmet-goal", "gap")
"""Every kind of question this selector asks."""
MAX_UNMET = 64
"""The most unmet-goal situations collected per question (nearest the labelled ones first)."""


def next_safe_question(learner: Learner, asked: Iterable[State] = ()) -> SituationQuestion | None:
    """The most decisive open question, or None when nothing is left to ask."""
    skip = not_to_ask(learner, asked)
    return first_open(learner, _candidates(learner, skip), skip)


def _candidates(learner: Learner, skip: set[State]) -> Iterable[SituationQuestion]:
    names = learner.names
    done: dict[State, str] = {}  # every question kind ticks states; each is ticked once

    def does(state: State) -> str:
        if state not in done:
            done[state] = tree_does(learner, state)
        return done[state]

    for conflict in learner.conflicts:
        yield SituationQuestion(conflict.state, "conflict", tree_does=does(conflict.state))
    # in a domain too large to try every state, or one with objects (forms), only states the learned
    # effects lead to: one made by changing conditions at random mostly cannot happen (a block on
    # one held; miconic's 10 conditions: 34 of 36 such questions were about impossible states)
    everything = 1 << len(names) <= MAX_PROBED and not learner.model.lifted
    reachable = None if everything else predicted(learner)
    probes = None if reachable is None else (learner.state_of(mask) for mask in reachable)
    unmet = list(itertools.islice(unmet_goal_situations(learner, does, flipped, probes), MAX_UNMET))
    yield from (question for question in unmet if question.tree_does == "done")  # an answer taught a wrong "done"
    settling = _most_settling(learner, does, skip) if everything else None
    if settling is not None:
        yield settling
    yield from _hypotheses(learner, does, skip, reachable, reasoned=False)
    yield from (question for question in unmet if question.tree_does != "done")
    yield from _hypotheses(learner, does, skip, reachable, reasoned=True)
    if reachable is not None:
        return
    probed = 0
    for state in learner.situations:
        for index in range(len(names)):
            probe = flipped(state, index)
            probed += 1
            if probed > MAX_PROBED:
                return
            if learner.possible_when_made(learner.state_mask(probe)) and does(probe) == "nothing":
                yield SituationQuestion(probe, "gap", tree_does="nothing")


def _hypotheses(learner: Learner, does: Callable[[State], str], skip: set[State], reachable: list[int] | None,
                reasoned: bool) -> Iterable[SituationQuestion]:
    """Group questions about unsure literals, the most settled by one yes first (module docstring).
    ``reachable``: in a large domain or one with forms the ``predicted`` states, the only ones
    asked about (None: every state is); ``reasoned``: the literals the data gives a reason for (asked last),
    else the others."""
    names = learner.names
    width = len(names)
    groups: list[tuple[int, int, int, str | None, list[Lit]]] = []
    goal = learner.goal
    if goal.known and not reasoned:
        groups.append((0, 0, 0, None, goal.unsure()))
    for name, knowledge in learner.model.actions.items():
        if not knowledge.demonstrated:
            continue
        pos, neg = knowledge.unsure
        have_pos, have_neg = knowledge.assumed
        for index, value in goal.cover:  # "only while the task is not done yet": a reason too
            if value:
                have_neg |= 1 << index
            else:
                have_pos |= 1 << index
        if reasoned:
            literals = literals_of(pos & have_pos, neg & have_neg, width)
        else:
            literals = literals_of(pos & ~have_pos, neg & ~have_neg, width)
        groups.append((1, -knowledge.applied.count, knowledge.order, name, literals))
    bases = _bases(learner)
    small = reachable is None
    probes = [mask for mask in (range(1 << width) if reachable is None else reachable) if learner.possible(mask)]
    done_true, done_false = literal_masks(goal.required()) if goal.known else (0, 0)
    stuck = [mask for mask in probes
             if not goal.known or mask & done_true != done_true or mask & done_false]  # the tree is not done there

    def does_nothing(mask: int) -> bool:
        return does(learner.state_of(mask)) == "nothing"

    labelled = learner.labelled_masks()
    skipped = {learner.state_mask(state) for state in skip}
    plausible = [] if small else [mask for mask in probes if mask not in labelled and mask not in skipped]
    found: list[tuple[tuple[bool, int, int, int, int, int], SituationQuestion]] = []
    for rank, evidence, order, action, literals in groups:
        question = None
        for group in learner.untested(action, literals):
            if small:
                question = _group_question(learner, does, skip, bases.get(action, ()), action, group)
            else:
                question = _plausible_question(learner, does, does_nothing, plausible, action, group)
            if reasoned and question is not None and question.tree_does != "nothing":
                question = None  # usually needed: a no there would be what the robot does anyway
            if question is not None:
                literals = [(learner.names.index(name), value) for name, value in question.settles]
                break
        if question is None:
            continue
        # an action counts only the states where the robot now does nothing: where it does something
        # else, a yes changes nothing it does (logistics after 20 demonstrations: 3 of 5 answers)
        unblocked = len(_unblocked(learner, action, literals, stuck)) if action is None else \
            sum(map(does_nothing, _unblocked(learner, action, literals, stuck)))
        if small and not unblocked and action is not None and question.tree_does != "nothing":
            continue  # every state was counted: a yes would change nothing the robot does
        # (the predicted states of a large domain or one with forms are only some of those it meets:
        # there such questions still pay, miconic after 2 demonstrations 68 -> 79% with them)
        # asked where the robot does nothing first: there any answer is new (20 demonstrations,
        # answers that changed nothing 47 -> 42%; most of the rest "do what you do" where it acts)
        found.append(((question.tree_does != "nothing", -unblocked, -len(literals), rank, evidence, order), question))
    found.sort(key=lambda item: item[0])
    for _key, question in found:
        yield question


SAMPLES = 32
"""How many hypotheses (which unsure literals are needed) answers are predicted under."""
SETTLING_STATES = 128
"""The most states (a domain of 7 conditions) every one of which is checked under every
hypothesis: 32 plans and 4,096 ticks, well within the 100 ms a question may take (8 conditions
took 111 ms on a loaded machine)."""
REASONED_NOT_NEEDED = 0.1
"""The odds a hypothesis drops an unsure literal the data gives a reason for (the step before
made it hold, the action undoes it: usually needed); others are dropped with even odds."""


def _most_settling(learner: Learner, does: Callable[[State], str], skip: set[State]) -> SituationQuestion | None:
    """In a domain of at most ``SETTLING_STATES`` states: of the situations where the robot does
    nothing now, first those where the most predicted runs end (``_runs_ending_stuck``), then the
    one whose answer is expected to rule out the most unsure literals (whichever action the
    teacher names there rules out its own unsure literals that do not hold), the answers
    predicted by ``_predicted_answers`` and expected over the hypotheses that act there (below).
    Asked as "may I still do X?" with X the likeliest answer. In a larger domain the group
    questions of ``_hypotheses`` come first instead."""
    width = len(learner.names)
    if 1 << width > SETTLING_STATES:
        return None
    unsure, reasoned = _open_literals(learner)
    if not any(unsure.values()):
        return None
    labelled = learner.labelled_masks()
    unseen = [mask for mask in range(1 << width) if mask not in labelled and learner.possible(mask)]
    idle = [(mask, state) for mask, state in ((mask, learner.state_of(mask)) for mask in unseen)
            if state not in skip and does(state) == "nothing"]
    probes = [state for _mask, state in idle]
    ending = _runs_ending_stuck(learner, does)
    # The teacher names a step wherever the goal can be reached, so the literals an answer settles
    # are expected among the hypotheses that act there; a hypothesis doing nothing mostly holds a
    # precondition that is not one (the ball's pairs, 4 draws: 40.6 -> 42.35 of 43). Once an asked
    # situation taught nothing (no way to the goal there, or it cannot happen), the domain has such
    # states, and the hypotheses doing nothing are counted against a situation again.
    answered_everywhere = all(learner.state_mask(state) in labelled for state in skip)
    chance = random.Random(len(labelled) * 7919 + len(skip))  # the same session asks the same questions
    best: tuple[tuple[int, float], State, str | None, list[Lit]] | None = None
    for (mask, state), votes in zip(idle, _predicted_answers(learner, probes, unsure, reasoned, chance), strict=True):
        if not votes:
            continue
        settled = sum(count * len(_false_in(state, unsure.get(answer, []))) for answer, count in votes.items())
        likely = max(votes, key=votes.__getitem__)
        settles = _false_in(state, unsure.get(likely, []))
        worth = (ending.get(mask, 0), settled / sum(votes.values()) if answered_everywhere else settled)
        if settles and (best is None or worth > best[0]):
            best = (worth, state, likely, settles)
    return None if best is None else may_i(learner, best[1], best[2], best[3], does(best[1]))


MAX_RUN = 20
"""The most steps a predicted run of the tree is followed (``_runs_ending_stuck``)."""


def _runs_ending_stuck(learner: Learner, does: Callable[[State], str]) -> dict[int, int]:
    """For each state (a bitmask), how many runs of the tree end there doing nothing: one run from
    each ``predicted`` state, each step by the learned effects of the action the tree runs, until it
    is done, does nothing, repeats a state or has gone ``MAX_RUN`` steps. A question is worth most
    where many starts lead the robot to a halt: on the ball "ball in hand, bin far away" lies on
    most ways to the bin, and literals settled alone left it unasked (78 pairs of demonstrations +
    5 questions, Δ5 mean / worst over 4 draws: 38.9 / 28.5 by literals alone, 40.6 / 31.2 with
    these runs first). Runs start from the states the learned effects lead to, not from every
    state: a run from a state that cannot happen ends where no start leads (strips-6x5 after 5
    demonstrations + 5 questions, 12 draws: runs from every state 74% reached, literals alone 79%,
    runs from these 78%)."""
    effects = {name: knowledge.effects for name, knowledge in learner.model.actions.items() if knowledge.demonstrated}
    ending: dict[int, int] = {}
    for start in predicted(learner):
        if not learner.possible(start):
            continue
        mask, seen = start, set()
        for _ in range(MAX_RUN):
            action = does(learner.state_of(mask))
            if action == "nothing":
                ending[mask] = ending.get(mask, 0) + 1
                break
            if action not in effects or mask in seen:
                break  # done, or a loop
            seen.add(mask)
            made_true, made_false = effects[action]
            mask = (mask | made_true) & ~made_false
    return ending


def _open_literals(learner: Learner) -> tuple[dict[str | None, list[Lit]], dict[str | None, set[Lit]]]:
    """Per demonstrated action (None: the goal), its unsure literals and those among them the data
    gives a reason for."""
    width = len(learner.names)
    unsure: dict[str | None, list[Lit]] = {}
    reasoned: dict[str | None, set[Lit]] = {}
    for name, knowledge in learner.model.actions.items():
        if knowledge.demonstrated:
            unsure[name] = literals_of(*knowledge.unsure, width)
            reasoned[name] = set(literals_of(*knowledge.assumed, width))
    if learner.goal.known:
        unsure[None] = learner.goal.unsure()
        reasoned[None] = set(learner.goal.cover)
    return unsure, reasoned


def _predicted_answers(learner: Learner, probes: list[State], unsure: dict[str | None, list[Lit]],
                       reasoned: dict[str | None, set[Lit]], chance: random.Random) -> list[dict[str | None, int]]:
    """For each probe, how many of ``SAMPLES`` hypotheses answer it with each action (None: done).
    A hypothesis is what the data leaves open decided at random: each unsure literal needed or
    not with even odds, one the data gives a reason for dropped with ``REASONED_NOT_NEEDED``; its
    answer is what the plan with the dropped ones ruled out does there."""
    votes: list[dict[str | None, int]] = [{} for _ in probes]
    for _ in range(SAMPLES):
        dropped = {action: [lit for lit in literals
                            if chance.random() < (REASONED_NOT_NEEDED if lit in reasoned[action] else 0.5)]
                   for action, literals in unsure.items()}
        hypothesis = learner.plan_if_ruled_out(dropped)
        if hypothesis is None:
            continue
        for counted, state in zip(votes, probes, strict=True):
            status, action = hypothesis(state)
            if status is Status.RUNNING:
                counted[action] = counted.get(action, 0) + 1
            elif status is Status.SUCCESS:
                counted[None] = counted.get(None, 0) + 1
    return votes


def _false_in(state: State, literals: list[Lit]) -> list[Lit]:
    return [(index, value) for index, value in literals if state[index] != value]


def _plausible_question(learner: Learner, does: Callable[[State], str], does_nothing: Callable[[int], bool],
                        plausible: list[int], action: str | None, literals: list[Lit]) -> SituationQuestion | None:
    """The question about as many of ``literals`` as one predicted state can settle: one where
    every other required literal holds and the most of ``literals`` do not, first one where the
    robot does nothing now (any answer there is new: where it acts, the answer is often what it
    would have done anyway)."""
    need_true, need_false = literal_masks(learner.required_of(action))
    group_true, group_false = literal_masks(literals)
    best: tuple[bool, int, int] | None = None
    for mask in plausible:
        false_true, false_false = need_true & ~mask, need_false & mask  # required literals false there
        if (false_true or false_false) and not false_true & ~group_true and not false_false & ~group_false:
            key = (does_nothing(mask), false_true.bit_count() + false_false.bit_count())
            if best is None or key > best[:2]:
                best = (*key, mask)
    if best is None:
        return None
    state = learner.state_of(best[2])
    false = [(i, v) for i, v in learner.required_of(action) if state[i] != v]
    return may_i(learner, state, action, false, does(state))


def may_i(learner: Learner, state: State, action: str | None, literals: list[Lit], does: str) -> SituationQuestion:
    """"May I still do ``action`` in ``state``?" (``action`` None: "is the task done there?"), about
    ``literals``, the unsure ones that do not hold there; ``does``: what the tree does there now."""
    settles = tuple((learner.names[index], value) for index, value in literals)
    return SituationQuestion(state, "must-goal" if action is None else "must-precondition", action=action,
                             condition=settles[0][0], tree_does=does, value=settles[0][1], settles=settles)


def _group_question(learner: Learner, does: Callable[[State], str], skip: set[State], bases: Iterable[State],
                    action: str | None, literals: list[Lit]) -> SituationQuestion | None:
    """The question about ``literals`` from the first base state where flipping them all gives a
    state not labelled, asked or impossible."""
    flips = {index for index, _value in literals}
    for base in bases:
        probe = tuple(not v if i in flips else v for i, v in enumerate(base))
        if probe in learner.situations or probe in skip or not learner.possible_when_made(learner.state_mask(probe)):
            continue
        return may_i(learner, probe, action, literals, does(probe))
    return None


def predicted(learner: Learner) -> list[int]:
    """The states a question's worth is counted on in a domain too large to count them all (or one
    with forms, where most of them cannot happen), as bitmasks: the labelled ones and,
    breadth-first, what each demonstrated action's learned effects make of them where all its
    required preconditions hold (at most ``MAX_PROBED``); in STRIPS-like worlds that prediction
    is sound, as the safe tree's actions are.
    A question about one of these is not about a state that cannot happen, as one made by
    changing conditions at random often is (a ferry at two places)."""
    actions = []
    for knowledge in learner.model.actions.values():
        made_true, made_false = knowledge.effects
        if knowledge.demonstrated and made_true | made_false:
            actions.append((knowledge.required, made_true, made_false))
    frontier = list(learner.labelled_masks())
    seen = dict.fromkeys(frontier)
    while frontier and len(seen) < MAX_PROBED:
        following = []
        for mask in frontier:
            for (need, forbid), made_true, made_false in actions:
                if mask & need != need or mask & forbid:
                    continue
                after = (mask | made_true) & ~made_false
                if after not in seen:
                    seen[after] = None
                    following.append(after)
                    if len(seen) >= MAX_PROBED:
                        return list(seen)
        frontier = following
    return list(seen)


def _unblocked(learner: Learner, action: str | None, literals: list[Lit], stuck: list[int]) -> list[int]:
    """The probed states where the tree does not say done that a yes would let ``action`` run in
    (``action`` None: let the tree say done in): those whose false required literals are all
    among ``literals``."""
    required = learner.required_of(action)
    group = set(literals)
    others_true, others_false = literal_masks([lit for lit in required if lit not in group])
    inside_true, inside_false = literal_masks([lit for lit in required if lit in group])
    return [mask for mask in stuck
            if mask & others_true == others_true and not mask & others_false
            and (mask & inside_true != inside_true or mask & inside_false)]


def unsure_here(learner: Learner, state: State) -> SituationQuestion | None:
    """Where the safe tree stopped (FAILURE) in ``state``: the action it was nearest to running, and
    the unsure literals that kept it from running there ("So far, every time I put the ball in the bin,
    the ball was in my hand. … may I still do it?"). An action whose effect already holds there is
    not asked about ("may I look for the ball I can see?"). None if only confirmed literals block
    every action (then only a demonstration helps: "show me what to do here")."""
    mask = learner.state_mask(state)
    best: tuple[int, int, str, list[Lit]] | None = None
    for name, knowledge in learner.model.actions.items():
        if not knowledge.demonstrated:
            continue
        pos, neg = knowledge.required
        false = [(i, v) for i, v in literals_of(pos, neg, len(learner.names)) if bool(mask >> i & 1) != v]
        sure_pos, sure_neg = pos & ~knowledge.unsure[0], neg & ~knowledge.unsure[1]
        made_true, made_false = knowledge.effects
        sure_pos |= made_false  # "only while its effect does not hold yet": never worth asking about here
        sure_neg |= made_true
        if not false or any((sure_pos if v else sure_neg) >> i & 1 for i, v in false):
            continue
        key = (len(false), knowledge.order)
        if best is None or key < best[:2]:
            best = (*key, name, false)
    if best is None:
        return None
    return may_i(learner, state, best[2], best[3], "nothing")


def _bases(learner: Learner) -> dict[str | None, list[State]]:
    """For each action (None: the goal), the labelled states where it is what to do, latest first."""
    bases: dict[str | None, list[State]] = {}
    for state, allowed in learner.situations.items():
        for answer in allowed:
            bases.setdefault(answer, []).insert(0, state)
    return bases
