"""Oracle teachers for replays and benchmarks: they answer situation questions the way a
teacher who knows what they want would, from a reference tree or a true action model."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from teach.bt.nodes import Node, Status, action_names, condition_names
from teach.bt.tick import compile_tree
from teach.domain import Domain, State, load_domain
from teach.errors import DomainError

if TYPE_CHECKING:
    from teach.dialogue.model_repair import ModelOracle
    from teach.session.machine import SessionManager

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


def oracle_from_model(path: str | Path, domain: Domain) -> Oracle:
    """The teacher knows the true action model: they would do what planning on it does."""
    from teach.learn.pabt import expand

    model = load_domain(path)
    if model.condition_names != domain.condition_names:
        raise DomainError("the model's conditions differ from the session's domain", path)
    return Oracle(expand(model)[-1], domain, str(path))


def answer_open_questions(manager: SessionManager, oracle: Oracle | None, model_oracle: ModelOracle | None = None,
                          said: Callable[[str], None] | None = None) -> None:
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
