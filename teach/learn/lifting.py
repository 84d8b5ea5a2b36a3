"""What one action's demonstrations say about the other instances of the same parameterised action.

A domain written from a planning domain (PDDL) declares each action as an instance of a kind with
objects (``form = ["unstack", "a", "b"]``) and each condition as a predicate over objects
(``form = ["on", "a", "b"]``); see README's domain format. Under PDDL's own semantics, which such a
domain declares by giving forms:

- an action's preconditions and effects mention only its own objects (and conditions without
  objects): a condition about other objects (``on_c_d`` before ``unstack_a_b``) is never one of its
  preconditions, however often it held;
- every instance of a kind has the same preconditions and effects up to renaming its objects
  (``unstack_a_b`` needs ``clear_a`` exactly when ``unstack_c_d`` needs ``clear_c``).

So a transition of ``unstack_a_b`` is, renamed, a transition of ``unstack_c_d``, and the safe
bounds (``teach.learn.action_model``) of every instance learn from it: this is lifted SAM (Juba,
Le & Stern, KR 2021; Juba & Stern, 2022), which learns the action models of standard planning
domains from a few trajectories and stays safe. Instances are of one kind only when their objects
repeat in the same pattern (``move_a_a`` is not renamed into ``move_a_b``). An action without a
form learns only from itself, as before. A condition without a form (``teach.domain`` refuses one
where actions have forms; a domain built in code may still have one) could be about any object:
it may be any action's precondition and is never renamed, so only an action's own applications
say anything about it.

An object is one of the action's parameters: a PDDL constant belongs in the predicate's name
(``lit_switch``), or a precondition about it would fall outside every action's own conditions.
"""

from __future__ import annotations

from dataclasses import dataclass

from teach.domain import Domain
from teach.learn.bits import Lit


@dataclass(frozen=True)
class Renaming:
    """From one action's conditions to a sibling's: ``pairs`` maps a bit of the shown action's
    conditions (one of its own objects only) to the sibling's; ``image`` is the sibling's bits
    reached, the only ones this renaming says anything about."""

    sibling: str
    pairs: tuple[tuple[int, int], ...]
    image: int

    def mask(self, mask: int) -> int:
        """The bits of ``mask`` renamed (bits without a pair are dropped)."""
        renamed = 0
        for mine, theirs in self.pairs:
            if mask >> mine & 1:
                renamed |= 1 << theirs
        return renamed

    def literal(self, literal: Lit) -> Lit | None:
        index, value = literal
        return next(((theirs, value) for mine, theirs in self.pairs if mine == index), None)


@dataclass(frozen=True)
class Lifting:
    """Per action: the conditions that can be its preconditions (``own``: every condition for an
    action without a form) and the renamings onto its siblings."""

    own: dict[str, int]
    renamings: dict[str, tuple[Renaming, ...]]


def lifting_of(domain: Domain) -> Lifting | None:
    """The domain's lifting; None when no action declares a form (nothing is shared)."""
    if not any(action.form for action in domain.actions):
        return None
    forms = [condition.form for condition in domain.conditions]
    index = {form: i for i, form in enumerate(forms) if form}
    everything = (1 << len(forms)) - 1
    formless = sum(1 << i for i, form in enumerate(forms) if not form)
    own: dict[str, int] = {}
    kinds: dict[tuple[object, ...], list[str]] = {}
    objects: dict[str, tuple[str, ...]] = {}
    for action in domain.actions:
        if not action.form:
            own[action.name] = everything
            continue
        mine = action.form[1:]
        objects[action.name] = mine
        own[action.name] = formless | sum(1 << i for i, form in enumerate(forms) if form and set(form[1:]) <= set(mine))
        pattern = tuple(mine.index(o) for o in mine)
        kinds.setdefault((action.form[0], pattern), []).append(action.name)
    renamings: dict[str, tuple[Renaming, ...]] = {}
    for names in kinds.values():
        for name in names:
            found = []
            for sibling in names:
                if sibling == name:
                    continue
                rename = dict(zip(objects[name], objects[sibling], strict=True))
                pairs = []
                for i, form in enumerate(forms):
                    if form and own[name] >> i & 1:
                        theirs = index.get((form[0], *(rename[o] for o in form[1:])))
                        if theirs is not None:
                            pairs.append((i, theirs))
                found.append(Renaming(sibling, tuple(pairs), sum(1 << theirs for _mine, theirs in pairs)))
            renamings[name] = tuple(found)
    return Lifting(own, renamings)
