"""Oracle teachers for replays and benchmarks: they answer situation questions the way a
teacher who knows what they want would, from a reference tree or a true action model."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from teach.bt.nodes import Node, Status, action_names, condition_names
from teach.bt.tick import compile_tree
from teach.domain import Domain, Literal, State, load_domain
from teach.errors import DomainError

if TYPE_CHECKING:
    from teach.dialogue.model_repair import ModelOracle, ModelQuestion
    from teach.dialogue.questions import Question
    from teach.messages import Lang

SKIP = "skip"


class Oracle:
    """Answers "what should I do in state s?" with what a reference tree does there:
    an action name, None when the task is done (SUCCESS), or ``SKIP`` when it fails."""

    def __init__(self, reference: Node, domain: Domain, source: str = "reference"):
        unknown = sorted(condition_names(reference) - set(domain.condition_names)) + \
            sorted(action_names(reference) - set(domain.action_names))
        if unknown:
            raise DomainError(f"the oracle's {source} uses names the domain does not know: {', '.join(unknown)}")
        self._tree = compile_tree(reference, domain.condition_names)
        self.source = source

    def answer(self, state: State) -> str | None:
        status, action = self._tree(state)
        if status is Status.RUNNING:
            return action
        return None if status is Status.SUCCESS else SKIP


def oracle_from_tree(path: str | Path, domain: Domain) -> Oracle:
    from teach.bt.xml import read_tree

    return Oracle(read_tree(path), domain, str(path))


def oracle_from_model(path: str | Path, domain: Domain) -> PlanningOracle:
    """The teacher knows the true action model: they would do what an optimal plan from the
    question's own situation does (see ``PlanningOracle``)."""
    model = load_domain(path)
    if model.condition_names != domain.condition_names:
        raise DomainError("the model's conditions differ from the session's domain", path)
    return PlanningOracle(model, domain, str(path))


class PlanningOracle:
    """Answers "what should I do in state s?" from a true action model: the first action of
    the shortest plan from s to the model's goal (ties: the first in the model's action order,
    searched breadth-first), or None where the goal holds. Only the situation asked about
    matters, so a model whose goal some states cannot reach answers every other state; a
    question in a state from which the goal cannot be reached is answered ``SKIP`` (the teacher
    cannot show a way either): the safe learner's "may I still …?" situations are often such."""

    def __init__(self, model: Domain, domain: Domain, source: str = "model"):
        if not model.goal:
            raise DomainError("the model has no goal, so no question can be answered from it "
                              "(goal = [...] in the domain file)", model.path)
        unknown = sorted(set(model.action_names) - set(domain.action_names))
        if unknown:
            raise DomainError(f"the model has actions the domain does not know: {', '.join(unknown)}", model.path)
        self.model, self.source = model, source
        self._goal = _masks(model, model.goal)
        self._actions = [(a.name, _masks(model, a.pre), _masks(model, a.ram)) for a in model.actions]
        self._answers: dict[int, str | None] = {}

    def answer(self, state: State) -> str | None:
        start = sum(1 << i for i, value in enumerate(state) if value)
        if start not in self._answers:
            self._answers[start] = self._plan_from(start)
        return self._answers[start]

    def _plan_from(self, start: int) -> str | None:
        def reached(mask: int) -> bool:
            return mask & self._goal[0] == self._goal[0] and not mask & self._goal[1]

        if reached(start):
            return None
        first: dict[int, str] = {}
        frontier = [start]
        seen = {start}
        while frontier:
            following: list[int] = []
            for mask in frontier:
                for name, (need, forbid), (make, clear) in self._actions:
                    if mask & need != need or mask & forbid:
                        continue
                    after = (mask | make) & ~clear
                    if after in seen:
                        continue
                    seen.add(after)
                    first[after] = first.get(mask, name)
                    if reached(after):
                        return first[after]
                    following.append(after)
            frontier = following
        return SKIP


def _masks(model: Domain, literals: Iterable[Literal]) -> tuple[int, int]:
    """(the conditions that must be true, those that must be false) as bitmasks."""
    true = false = 0
    for literal in literals:
        bit = 1 << model.index(literal.name)
        if literal.value:
            true |= bit
        else:
            false |= bit
    return true, false


SituationOracle = Oracle | PlanningOracle
"""Either kind of oracle: ``answer(state)`` gives an action, None (done) or ``SKIP``."""


class AskingSession(Protocol):
    """What answering a session's open questions needs of it (``teach.session.machine.SessionManager``
    is one): said here, so the dialogue layer never imports the session above it."""

    @property
    def pending(self) -> Question | None: ...
    @property
    def pending_model(self) -> ModelQuestion | None: ...
    @property
    def domain(self) -> Domain: ...
    @property
    def lang(self) -> Lang: ...
    def handle(self, line: str) -> object: ...


def answer_open_questions(manager: AskingSession, oracle: SituationOracle | None,
                          model_oracle: ModelOracle | None = None, said: Callable[[str], None] | None = None) -> None:
    """Answer the session's open questions through ``handle`` until none is open (each answer
    may raise another); ``said`` hears each answer before the session does."""
    while True:
        if manager.pending_model is not None and model_oracle is not None:
            line = model_oracle.answer(manager.pending_model, manager.lang)
        elif manager.pending is not None and oracle is not None:
            answer = oracle.answer(manager.pending.state)
            if answer == SKIP:
                line = "skip"
            elif answer is None:
                line = "done"
            else:
                line = manager.domain.action(answer).label(manager.lang)
        else:
            return
        if said is not None:
            said(line)
        manager.handle(line)
