"""Recognition: which known action a guided change of state was.

An action fits a change (state before, state after) when its preconditions held before, all its
effects hold after, and at least one of them was new. Effects are the domain's declared
``ram`` or, for actions named in ``effects``, what was learned for them (a mapping wins over
the file, so a session can pass what its learner knows so far). Candidates are ranked by how
much of the change they explain: an action whose effects cover every change beats one that
leaves a side effect unexplained; ties keep the domain's order. A question is due when nothing
fits, when two fit equally, or when the best leaves a gained condition unexplained.

Guided motion often loses a condition on the way to the one it is after (driving to the ball
leaves the bin behind). ``explain`` therefore joins a change that no action explains with the
changes after it, as long as the joined change is explained: one action with a side effect,
as a named-skill demonstration would record it.

The questions are plain sentences in English or German built from the domain's labels:
"You moved me so that now the ball is within reach. Was that 'go to the ball'?"
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from teach.domain import Domain, Literal, State

Effects = Mapping[str, Sequence[Literal]]


@dataclass(frozen=True, slots=True)
class Candidate:
    """An action that fits a change; ``unexplained`` are changed literals its effects do not name."""

    action: str
    unexplained: tuple[Literal, ...]


@dataclass(frozen=True, slots=True)
class Recognition:
    """The change of one segment (or of joined segments) and the actions that fit it, best first."""

    before: State
    after: State
    changes: tuple[Literal, ...]
    candidates: tuple[Candidate, ...]

    @property
    def fits(self) -> bool:
        return bool(self.candidates)

    @property
    def best(self) -> str | None:
        return self.candidates[0].action if self.candidates else None

    @property
    def ambiguous(self) -> bool:
        """Two or more actions explain the change equally well: only the teacher can tell."""
        return len(self.candidates) > 1 and \
            len(self.candidates[1].unexplained) == len(self.candidates[0].unexplained)

    @property
    def needs_question(self) -> bool:
        """Nothing fits, two fit, or the best leaves a condition that became true unexplained.

        A condition lost on the way (the bin left behind) is a side effect and asks nothing; one
        gained that the action does not promise may be a second thing the teacher did."""
        return not self.fits or self.ambiguous or any(lit.value for lit in self.candidates[0].unexplained)


def changed_literals(domain: Domain, before: State, after: State) -> tuple[Literal, ...]:
    """The literals that became true, in domain order (``!X`` for a condition that became false)."""
    return tuple(Literal(c.name, bool(b)) for c, a, b in zip(domain.conditions, before, after, strict=True)
                 if a != b)


def effects_of(domain: Domain, action: str, effects: Effects | None = None) -> tuple[Literal, ...]:
    if effects is not None and action in effects:
        return tuple(effects[action])
    return domain.action(action).ram if domain.has_action(action) else ()


def recognise(domain: Domain, before: State, after: State, effects: Effects | None = None,
              preconditions: Effects | None = None) -> Recognition:
    """The actions (known to the domain or in ``effects``) that fit ``before`` → ``after``, ranked."""
    changes = changed_literals(domain, before, after)
    names = list(domain.action_names) + sorted(set(effects or {}) - set(domain.action_names))
    found: list[tuple[int, int, Candidate]] = []
    for order, name in enumerate(names):
        wanted = effects_of(domain, name, effects)
        if not wanted or not all(domain.holds(lit, after) for lit in wanted):
            continue
        if all(domain.holds(lit, before) for lit in wanted):
            continue  # it would have changed nothing
        pre = preconditions[name] if preconditions is not None and name in preconditions else \
            (domain.action(name).pre if domain.has_action(name) else ())
        if not all(domain.holds(lit, before) for lit in pre):
            continue
        unexplained = tuple(lit for lit in changes if lit not in wanted)
        found.append((len(unexplained), order, Candidate(name, unexplained)))
    found.sort(key=lambda item: (item[0], item[1]))
    return Recognition(before, after, changes, tuple(candidate for _, _, candidate in found))


def explain(domain: Domain, changes: Sequence[tuple[State, State]], effects: Effects | None = None,
            preconditions: Effects | None = None) -> list[tuple[range, Recognition]]:
    """Group consecutive changes into actions: each group's index range and its recognition.

    A change no action fits is joined with the following ones up to the first joined change an
    action fits; when no such join exists it stays on its own, recognised as nothing known.
    """
    groups: list[tuple[range, Recognition]] = []
    start = 0
    while start < len(changes):
        alone = recognise(domain, changes[start][0], changes[start][1], effects, preconditions)
        group = (range(start, start + 1), alone)
        if not alone.fits:
            for end in range(start + 1, len(changes)):
                joined = recognise(domain, changes[start][0], changes[end][1], effects, preconditions)
                if joined.fits:
                    group = (range(start, end + 1), joined)
                    break
        groups.append(group)
        start = group[0].stop
    return groups


# --- questions -----------------------------------------------------------------------------

def describe_change(domain: Domain, recognition: Recognition, lang: str = "en") -> str:
    """What now holds that did not before, in the teacher's words ("the ball is within reach")."""
    labels = [domain.condition(lit.name).label(lang, lit.value) for lit in recognition.changes]
    joiner = " und " if lang == "de" else " and "
    if len(labels) <= 2:
        return joiner.join(labels)
    return ", ".join(labels[:-1]) + joiner + labels[-1]


def _quoted(text: str, lang: str) -> str:
    return f"„{text}“" if lang == "de" else f"'{text}'"


def question(domain: Domain, recognition: Recognition, lang: str = "en",
             labels: Mapping[str, str] | None = None) -> str:
    """The labelling question for a segment: a confirmation, a choice, or a request for a name.

    ``labels`` gives the phrase for actions the domain does not know (learned by guidance).
    """
    def label(name: str) -> str:
        if labels is not None and name in labels:
            return labels[name]
        return domain.action(name).label(lang) if domain.has_action(name) else name

    change = describe_change(domain, recognition, lang)
    if lang == "de":
        moved = f"Du hast mich so bewegt, dass jetzt gilt: {change}."
    else:
        moved = f"You moved me so that now {change}."
    if not recognition.fits:
        if lang == "de":
            return f"{moved} Das kann keine Aktion, die ich kenne. Wie heißt das, was du gemacht hast?"
        return f"{moved} None of the actions I know does that. What should I call what you did?"
    tied = [c.action for c in recognition.candidates
            if len(c.unexplained) == len(recognition.candidates[0].unexplained)]
    options = [_quoted(label(name), lang) for name in tied]
    if len(options) == 1:
        return f"{moved} War das {options[0]}?" if lang == "de" else f"{moved} Was that {options[0]}?"
    listed = ", ".join(options[:-1]) + (" oder " if lang == "de" else " or ") + options[-1]
    return f"{moved} War das {listed}?" if lang == "de" else f"{moved} Was that {listed}?"
