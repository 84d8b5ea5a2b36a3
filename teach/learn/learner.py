"""The default learner: an action model and a goal learned online, a tree planned from them.

    learner = Learner(domain)
    learner.update(demo)                      # after every demonstration
    learner.teach_step(state, "GraspBall", "question 1")   # an answered situation question
    learner.tree                              # a teach.bt.nodes.Node
    learner.conflicts                         # states labelled two ways; the latest label wins
    learner.resolve(state, EITHER)            # the teacher's decision about a conflict
    learner.explain(uid)                      # why a node exists, naming the evidence

What it keeps (all updated in O(conditions) per step, never by replaying old data):

- the action model (``teach.learn.action_model``): effects and precondition bounds;
- the goal (``teach.learn.goal``): the smallest set of goal-state literals that explains why
  the teacher kept acting, or, where the domain file declares one, that goal;
- the labelled situations (``teach.learn.labels``): each distinct state with what the robot
  must do there, the training set; a state labelled two ways is a *conflict*, kept as data,
  the latest label wins until ``resolve``.

The tree is ``Fallback(exception..., plan)``. The plan is backchained from the goal through
the model (``teach.learn.backchain``, reading the view ``teach.learn.plan_view`` builds) and
rebuilt only when that view changed. Where the plan does not do a state's label, the learner
first tries to repair the model (``teach.learn.repair``), and otherwise adds an *exception*
in front (``teach.learn.exceptions``): the fewest literals of that state that hold in no
situation labelled otherwise, then the label. So every consistent demonstration is
reproduced strictly, and the tree returns SUCCESS only where the learned goal holds; where
nothing applies it returns FAILURE.

This module's jobs: the online update and the teacher's answers (what a "no" says is
``teach.learn.refusals``), when to replan, repair and add exceptions, and assembling the tree;
why a node exists is ``teach.learn.explain``.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, KeysView, Mapping
from collections.abc import Sequence as Seq
from dataclasses import dataclass
from typing import Protocol

from teach.bt.nodes import Condition, Fallback, Inverter, Node, Sequence, Status
from teach.bt.tick import CompiledTree, compile_tree
from teach.demos import Demonstration
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State
from teach.errors import LearnError
from teach.learn.action_model import ActionModel, Lit, literals_of
from teach.learn.backchain import PlanView, Role, plan
from teach.learn.bits import mask_literals, mask_state, state_mask
from teach.learn.exceptions import ExceptionRule, exception_rule
from teach.learn.explain import Explanation, explain_node
from teach.learn.goal import GoalLearner
from teach.learn.invariants import Invariants
from teach.learn.labels import Answer, Conflict, Labels, Situation
from teach.learn.lifting import lifting_of
from teach.learn.plan_view import Ranks, goal_bound_plan, plan_view, ruled_out_plan
from teach.learn.refusals import Refusals
from teach.learn.regress import SMALL_DOMAIN, PlanWithRules, goal_node, rule_nodes, with_rules
from teach.learn.repair import FAILED, PlanTrials, Restored, repair_model

EITHER = "<either>"
"""``resolve`` answer: every label the state was given is fine."""


class Hypothesis(Protocol):
    """A question about unsure literals (``teach.learn.inquiry.SituationQuestion``): may ``action``
    run in ``state`` (``action`` None: is the task done in ``state``)? ``settles``: the unsure
    literals (condition name, value) that are false in ``state``."""

    @property
    def state(self) -> State: ...
    @property
    def action(self) -> str | None: ...
    @property
    def settles(self) -> tuple[tuple[str, bool], ...]: ...


@dataclass(frozen=True)
class Update:
    """What one demonstration or answer did."""

    source: str
    tree_changed: bool
    new_conflicts: tuple[Conflict, ...] = ()
    sentence: str = ""

    @property
    def changed(self) -> bool:
        return self.tree_changed


class Learner:
    """Learns online from demonstrations and answers; see the module docstring."""

    def __init__(self, domain: Domain, safe: bool = True, can_happen: Callable[[State], bool] | None = None):
        """``can_happen``: the world's word on which states it can be in (``TeachingWorld.can_happen``);
        no question is asked about another (``teach.learn.invariants``)."""
        self.domain = domain
        self.names = domain.condition_names
        self._n = len(self.names)
        self._full = (1 << self._n) - 1
        self.model = ActionModel(domain.action_names, self._n, lifting_of(domain))
        self.goal = GoalLearner(self._n, [(self.names.index(lit.name), lit.value) for lit in domain.goal])
        self.safe = safe
        self._restored = Restored()
        self._ranks = Ranks()
        self._view: PlanView | None = None
        self._plan: Node | None = None
        self._roles: dict[int, Role] = {}
        self._compiled: CompiledTree | PlanWithRules | None = None
        self._counted: tuple[CompiledTree | PlanWithRules, int] | None = None
        self._exceptions: list[ExceptionRule] = []
        self._later: list[ExceptionRule] = []
        """Exceptions tried after the regressed rules, before the plan (rules-first trees only): they
        fire only where no rule does, so they never turn the robot away from a way to the goal."""
        self._tree: Node | None = None
        self._root_uid = 0
        self.invariants = Invariants(self._n, can_happen)
        self._labels = Labels(self.goal, self.invariants, self._n, self._recount)
        self._situations = self._labels.situations  # read here often; labelled through self._labels only
        self._refusals = Refusals(self.model, self.goal, self._n)
        self._trials = PlanTrials(self._replan, self._keep_plan, self._plan_output, self._plan_errors)
        self._replan()

    # --- public API ---------------------------------------------------------------------------

    @property
    def tree(self) -> Node:
        if self._tree is None:
            self._tree = self._assemble()
        return self._tree

    @property
    def conflicts(self) -> list[Conflict]:
        """Unresolved conflicts, in the order they arose."""
        return [Conflict(self._state(mask), tuple(labels)) for mask, labels in self._labels.conflicts.items()]

    @property
    def situations(self) -> dict[State, frozenset[Answer]]:
        """Every labelled state with the answers allowed there (kept until a label changes: the
        question selectors read it often)."""
        return self._labels.view()

    def update(self, demo: Demonstration, source: str | None = None) -> Update:
        """Learn one more demonstration (any order, repeats, loops, external events)."""
        where = source or (str(demo.path) if demo.path is not None else demo.name)
        touched: list[int] = []
        new_conflicts: list[int] = []
        steps = demo.steps
        previous: tuple[int, int] | None = None
        position = 0
        broken: list[Lit] = []
        for i, step in enumerate(steps):
            after = self._mask(steps[i + 1].state) if i + 1 < len(steps) else None
            mask = self._mask(step.state)
            src = f"{where}:{step.line}"
            if step.action == EXTERNAL_ACTION:
                previous = None
                if after is not None:
                    broken += self._literals(mask ^ after, mask)
                continue
            answer = None if step.action == GOAL_ACTION else self.domain.action(step.action).name
            if self._label(mask, step.state, answer, src):
                new_conflicts.append(mask)
            touched.append(mask)
            self._restored.note(broken, after if answer is not None else None)
            broken = []
            if answer is None:
                continue
            self.model.applied(answer, mask, src, previous)
            if after is None:
                continue
            self.model.observed(answer, mask, after, src)
            position += 1
            changed = mask ^ after
            previous = (changed & after, changed & ~after & self._full)
            self._ranks.established(changed, after, position, self._n)
        return self._finish(where, touched, new_conflicts)

    def teach_step(self, state: State, answer: Answer, source: str) -> Update:
        """Learn an answered situation question: do ``answer`` in ``state`` (None: done here)."""
        mask = self._checked_mask(state, source)
        if answer is not None:
            self.domain.action(answer)
        conflict = self._label(mask, tuple(state), answer, source)
        if answer is not None:
            self.model.applied(answer, mask, source)
            self._guess_effect(mask, answer, source)
        return self._finish(source, [mask], [mask] if conflict else [])

    def _guess_effect(self, mask: int, answer: str, source: str) -> None:
        """An action never demonstrated, asked for in a state one literal away from where
        another action was shown, with that literal among the other action's possible
        preconditions: the teacher wants that literal first, and this action is how. So it
        is guessed as this action's effect and confirmed as the other's precondition."""
        knowledge = self.model[answer]
        if knowledge.demonstrated or knowledge.guessed:
            return
        for other_mask, situation in self._situations.items():
            other = situation.answer
            difference = other_mask ^ mask
            if other is None or other == answer or difference & (difference - 1):
                continue
            index = difference.bit_length() - 1
            literal = (index, bool(other_mask >> index & 1))
            pos, neg = self.model[other].possible
            if (pos if literal[1] else neg) >> index & 1:
                self.model.guess(answer, literal, source)
                self.model.confirm(other, literal, source)
                return

    def resolve(self, state: State, answer: Answer, source: str = "the teacher's decision") -> Update:
        """Settle a conflict: ``answer`` is what to do there, or ``EITHER`` (every label is fine)."""
        mask = self._checked_mask(state, source)
        labels = self._labels.conflicts.pop(mask, None)
        if labels is None:
            raise LearnError(f"no conflict in the state [{self.domain.describe(tuple(state))}]", source)
        situation = self._situations[mask]
        if answer == EITHER:
            allowed = frozenset(a for a, _src in labels)
            chosen = situation.answer
        else:
            if answer is not None:
                self.domain.action(answer)
                if self.safe:
                    self.model.applied(answer, mask, source)  # the teacher chose it here: it can run here
            allowed, chosen = frozenset({answer}), answer
        self._labels.relabel(mask, situation, allowed, chosen)
        situation.sources.append(source)
        return self._finish(source, [mask], [])

    def settle(self, hypothesis: Hypothesis, needed: bool, source: str) -> Update:
        """The teacher's answer to "may I do ``action`` here?" (or "is the task done here?"): no
        (``needed``) means one of the literals it settles is needed, and a single one is then kept
        for good; yes rules every literal false there out (the action can run there, the task is
        done there)."""
        mask = self._checked_mask(hypothesis.state, source)
        action = hypothesis.action
        if not needed and action is None:
            return self.teach_step(hypothesis.state, None, source)
        if needed:
            settles = frozenset((self.names.index(name), value) for name, value in hypothesis.settles)
            self._refusals.refuse(action, settles, source)
        else:
            assert action is not None
            self.model.applied(action, mask, source)
        return self._finish(source, [], [])

    def answer_question(self, state: State, asked_about: str | None, answer: Answer, source: str) -> Update:
        """The teacher's answer to "may I still do ``asked_about`` here?" (``asked_about`` None: "is
        the task done here?") given as what to do there: the action asked about (or done) is a yes;
        anything else is a no to it and the label of ``state`` as well."""
        if answer == asked_about:
            return self.teach_step(state, answer, source)
        mask = self._checked_mask(state, source)
        false = frozenset(lit for lit in self.required_of(asked_about) if bool(mask >> lit[0] & 1) != lit[1])
        self._refusals.refuse(asked_about, false, source)
        return self.teach_step(state, answer, source)

    def rule_out(self, state: State, source: str) -> None:
        """The teacher said ``state`` cannot happen: nothing is asked about it again, nor about a state
        sharing the reason the data shows for it (``teach.learn.invariants``). It costs nothing
        and changes no tree; a group question about it is then asked in halves."""
        self.invariants.rule_out(self._checked_mask(state, source), source,
                                 lambda care, value: self._labels.columns.firing(care, value) != 0)

    @property
    def impossible(self) -> dict[int, str]:
        """The states (bitmasks) the teacher said cannot happen, with the answer's source."""
        return self.invariants.impossible

    def possible(self, mask: int) -> bool:
        """Whether a question may be about the state ``mask`` (``teach.learn.invariants``)."""
        return self.invariants.possible(mask)

    def possible_when_made(self, mask: int) -> bool:
        """``possible``, for a state made by changing conditions of a shown one: in a domain too
        large to ask about every state, also only where the demonstrations showed every two of
        its literals together (such a state mostly cannot happen there: a ferry at two places)."""
        if self._n > SMALL_DOMAIN and not self.invariants.pairs_seen(mask):
            return False
        return self.invariants.possible(mask)

    def untested(self, action: str | None, literals: list[Lit]) -> list[list[Lit]]:
        """The groups of unsure literals worth asking about next, best first: all of them and then
        each half, or, where a group inside them was refused (or was impossible), each half of
        what is left of that group (a yes to all of it is known not to come)."""
        return self._refusals.untested(action, literals)

    def required_of(self, action: str | None) -> list[Lit]:
        """What the safe tree checks before ``action`` (None: before it says "done")."""
        if action is None:
            return self.goal.required()
        return literals_of(*self.model[action].required, self._n)

    def state_mask(self, state: Seq[bool]) -> int:
        """The bitmask (bit i = condition i) of a state."""
        return self._mask(state)

    def labelled_masks(self) -> KeysView[int]:
        """The labelled states as bitmasks (bit i = condition i), in the order they were labelled."""
        return self._situations.keys()

    def state_of(self, mask: int) -> State:
        """The state a bitmask (bit i = condition i) stands for."""
        return self._state(mask)

    def shown_states(self) -> dict[str, State]:
        """For each action, the first labelled state in which it is to be done."""
        shown: dict[str, State] = {}
        for situation in self._situations.values():
            if situation.answer is not None:
                shown.setdefault(situation.answer, situation.state)
        return shown

    def planned_for_goal_bound(self) -> CompiledTree | None:
        """The plan as it would be if the goal were its over-specific bound (every literal that
        held in all goal states): where it acts otherwise than the tree, an answer tells which
        of those literals the task needs."""
        return goal_bound_plan(self._current_view(), sorted(self.goal.candidates(), key=self._ranks.rank), self.names)

    def goal_holds(self, state: State) -> bool:
        """Does the learned goal hold in ``state`` (never before a goal state was shown)? The safe
        learner's goal is every literal not ruled out."""
        mask = self._mask(state)
        return self.goal.required_holds(mask) if self.safe else self.goal.holds(mask)

    def answer_in(self, state: State) -> Answer | bool:
        """What the tree does in ``state``: an action, None for SUCCESS, False for FAILURE."""
        return self._output(self._mask(state))

    def why(self, uid: int) -> Explanation:
        """Why the node ``uid`` of the current tree exists, as data (``teach.learn.explain``)."""
        if self._tree is None:
            self._tree = self._assemble()
        return explain_node(uid, self._root_uid, [*self._exceptions, *self._later], self._roles, self._plan is not None,
                            self.model, self.goal, self.names)

    def explain(self, uid: int) -> str:
        return self.why(uid).text

    # --- labels -------------------------------------------------------------------------------

    def _label(self, mask: int, state: State, answer: Answer, source: str) -> bool:
        """Record a label (``teach.learn.labels``); True if it starts (or extends) a conflict."""
        return self._labels.label(mask, state, answer, source)

    # --- the tree: when to replan, repair and add exceptions ----------------------------------

    def _finish(self, source: str, touched: list[int], new_conflicts: list[int]) -> Update:
        # what a demonstration or an answer ruled out may leave one literal of a group the teacher
        # refused before: that one is needed (snacks: "no" to taking the tray where neither a request
        # nor a partner was, then "yes" where a partner was: the request is needed)
        self._refusals.infer_needed()
        before = self._tree if self._tree is not None else self._assemble()
        view = self._view
        if self._current_view() != view:
            self._replan()
        # after a replan every situation the plan gets wrong, else the new ones the tree gets wrong
        if self._view != view:
            wrong = [m for m, s in self._situations.items() if self._plan_does(s.state) not in s.allowed]
        else:
            wrong = [m for m in dict.fromkeys(touched) if self._output(m) not in self._situations[m].allowed]
        if wrong:
            self._repair_model(wrong)
        if self._view != view:
            self._rebuild_exceptions()
        else:
            self._fix(touched)
        self._tree = None
        after = self.tree
        changed = after != before
        conflicts = tuple(Conflict(self._state(m), tuple(self._labels.conflicts[m]))
                          for m in dict.fromkeys(new_conflicts) if m in self._labels.conflicts)
        parts = [f"{source}: " + ("the tree changed" if changed else "the tree already does this")]
        if conflicts:
            parts.append(f"{len(conflicts)} state(s) now labelled two ways (the latest label is used until "
                         f"the teacher decides)")
        return Update(source, changed, conflicts, "; ".join(parts))

    def plan_if_ruled_out(self, out: Mapping[str | None, Collection[Lit]]) -> CompiledTree | None:
        """The safe plan as it would be if the literals ``out[action]`` were ruled out for each action
        (None: for the goal), the rest of the model as it is: what the robot would do after those
        yeses (``teach.learn.safe_inquiry`` predicts answers by it, in domains small enough for the
        rules to act only where the plan does nothing). Without the regressed rules, which cost most
        of a replan."""
        return ruled_out_plan(self._current_view(), out, self.names)

    def _current_view(self) -> PlanView:
        return plan_view(self.model, self.goal, self._ranks.rank, self._n, self.safe)

    def _replan(self) -> None:
        self._view = self._current_view()
        self._plan, self._roles = plan(self._view, self.names)
        self._compiled = compile_tree(self._plan, self.names) if self._plan is not None else None
        if self._compiled is not None and self._view.regression:
            self._compiled = with_rules(self._view, self._compiled, self._n, self.model.lifted)
        self._tree = None

    def _plan_output(self, mask: int) -> Answer | str:
        return self._plan_does(self._state(mask))

    def _plan_does(self, state: State) -> Answer | str:
        if self._compiled is None:
            return FAILED
        return _answer(*self._compiled(state))

    def _output(self, mask: int) -> Answer | bool:
        for exception in self._exceptions:
            if mask & exception.mask == exception.value:
                return exception.answer
        both = self._rules_first()
        if both is not None:
            decided = both.decided(mask)
            if decided is None:
                later = next((e for e in self._later if mask & e.mask == e.value), None)
                return False if later is None else later.answer
            answer = _answer(*decided)
            return False if answer == FAILED else answer
        result = self._plan_output(mask)
        return False if result == FAILED else result

    def _plan_errors(self, limit: int | None = None) -> int:
        """How many situations the plan gets wrong; counting stops at ``limit`` (the caller
        only needs to know whether it beats a count it has). A complete count is kept for the
        plan and updated label by label, so an update that keeps the plan does not count again."""
        compiled = self._compiled
        if self._counted is not None and self._counted[0] is compiled:
            return self._counted[1]
        wrong = 0
        for situation in self._situations.values():
            if self._plan_does(situation.state) not in situation.allowed:
                wrong += 1
                if wrong == limit:
                    return wrong
        if compiled is not None:
            self._counted = (compiled, wrong)
        return wrong

    def _recount(self, state: State, old: frozenset[Answer], new: frozenset[Answer]) -> None:
        """Keep the plan's error count right after a situation's allowed answers changed."""
        if self._counted is None:
            return
        compiled, wrong = self._counted
        if compiled is not self._compiled:
            self._counted = None
            return
        does = self._plan_does(state)
        if old:
            wrong -= does not in old
        self._counted = (compiled, wrong + (does not in new))

    def _repair_model(self, wrong: list[int]) -> None:
        """Repair the action model where the plan runs the wrong action (``teach.learn.repair``)."""
        repair_model(wrong, self._situations, self.model, self._ranks.rank, self._restored, self._n, self._trials)

    def _keep_plan(self) -> Callable[[], None]:
        """A way back to the current plan (repair tries others)."""
        kept = (self._view, self._plan, self._roles, self._compiled)

        def back() -> None:
            self._view, self._plan, self._roles, self._compiled = kept
        return back

    def _rebuild_exceptions(self) -> None:
        """Exceptions for a new plan: one for each situation the plan gets wrong and no
        exception built so far covers (an exception is right wherever it fires on a situation,
        so covered situations need no check)."""
        self._exceptions = []
        self._later = []
        self._tree = None
        if self._rules_first() is not None:
            self._fix(list(self._situations))
            return
        covered = 0
        position = self._labels.columns.position
        for mask, situation in self._situations.items():
            if covered >> position[mask] & 1 or self._plan_does(situation.state) in situation.allowed:
                continue
            exception = self._exception(mask, situation)
            self._exceptions.insert(0, exception)
            covered |= self._labels.columns.firing(exception.mask, exception.value)

    def _fix(self, masks: Seq[int]) -> None:
        """Add an exception for every given situation the tree gets wrong."""
        for mask in dict.fromkeys(masks):
            situation = self._situations[mask]
            if self._output(mask) in situation.allowed:
                continue
            both = self._rules_first()
            if both is not None:
                self._add_behind_rules(mask, situation, both)
            else:
                self._exceptions.insert(0, self._exception(mask, situation))
            self._tree = None

    def _rules_first(self) -> PlanWithRules | None:
        """The regressed rules, if they come before the plan (``teach.learn.regress``)."""
        both = self._compiled
        return both if isinstance(both, PlanWithRules) and both.rules_first else None

    def _add_behind_rules(self, mask: int, situation: Situation, both: PlanWithRules) -> None:
        """In a rules-first tree an exception never overrides the goal check or a rule except in its
        own state: there the teacher's step is done (a rule that tests every condition, in front),
        elsewhere only where no rule fits (a general one, behind the rules). A general one in front
        would turn the robot away from the rules' way to the goal in states nobody showed, and could
        lead it round in circles (logistics, 2 demonstrations: 13–25% of runs). Where the rules are
        complete (the model knows every way to the goal), the one behind them is exact too: a step
        from a state the model knows no way from, generalised by what set that state apart, is a
        guess about where else it helps, and two such guesses flew logistics' plane back and forth
        (5% of runs after 2 demonstrations and 5 answers; 74% reached without them, 76% with)."""
        if both.decided(mask) is not None:
            self._exceptions.insert(0, self._exception(mask, situation, exact=True))
            if both.complete:
                return  # an exact one behind it would never fire
        self._later.insert(0, self._exception(mask, situation, exact=both.complete))

    def _exception(self, mask: int, situation: Situation, exact: bool = False) -> ExceptionRule:
        return exception_rule(mask, situation.answer, situation.sources[-1], self._labels.columns, self.names,
                              self.goal, self.model, self.safe, exact)

    def _assemble(self) -> Node:
        kids = [e.node for e in self._exceptions]
        if self._plan is not None:
            kids.append(self._plan_node())
        if not kids:
            first = Condition(self.names[0])
            root: Node = Sequence((first, Inverter(Condition(self.names[0]))))
        elif len(kids) == 1:
            root = kids[0]
        else:
            root = Fallback(tuple(kids))
        self._root_uid = root.uid if len(kids) > 1 else -1
        return root

    def _plan_node(self) -> Node:
        """The plan, followed by its regressed rules if it has any (``teach.learn.regress``); built
        once per plan, so assembling the tree after an update costs nothing more."""
        assert self._plan is not None
        both = self._compiled
        if not isinstance(both, PlanWithRules) or not both.rules:
            return self._plan
        if both.rules_first:
            later = tuple(e.node for e in self._later)
            if both.node is None or both.node_later != later:
                if both.rule_nodes is None:
                    both.rule_nodes = (goal_node(both.goal, self.names, self._roles),
                                       *rule_nodes(both.rules, self.names, self._roles))
                both.node, both.node_later = Fallback((*both.rule_nodes, *later)), later
                self._roles[both.node.uid] = Role("regression-complete" if both.complete else "regression-first")
        elif both.node is None:
            both.node = Fallback((self._plan, *rule_nodes(both.rules, self.names, self._roles)))
            self._roles[both.node.uid] = Role("regression")
        return both.node

    # --- helpers ------------------------------------------------------------------------------

    def _literals(self, mask: int, value: int) -> list[Lit]:
        return mask_literals(mask, value, self._n)

    def _checked_mask(self, state: Seq[bool], source: str) -> int:
        if len(state) != self._n:
            raise LearnError(f"a state needs {self._n} truth values, got {len(state)}", source)
        return self._mask(state)

    def _mask(self, state: Seq[bool]) -> int:
        return state_mask(state)

    def _state(self, mask: int) -> State:
        return mask_state(mask, self._n)


def _answer(status: Status, action: str | None) -> Answer | str:
    """What a tick says to do: the action it left running, None for SUCCESS, ``FAILED`` for FAILURE."""
    if status is Status.RUNNING:
        return action
    return None if status is Status.SUCCESS else FAILED


def learn_online(domain: Domain, demos: Seq[Demonstration], safe: bool = True) -> Learner:
    """A learner after every demonstration in turn."""
    learner = Learner(domain, safe)
    for demo in demos:
        learner.update(demo)
    return learner


def learn(domain: Domain, demos: Seq[Demonstration], safe: bool = True) -> Node:
    """The batch helper for ``teach learn`` and the benchmarks: the tree after all demonstrations."""
    return learn_online(domain, demos, safe).tree
