"""A symbolic world with hidden state: what the robot cannot see decides what its actions do.

Some tasks repeat an action until something unseen runs out ("offer snacks until the tray is
empty") and are disturbed by people ("the request is withdrawn"). A ``world.toml`` beside the
domain describes that part of the world, and ``HiddenStateWorld`` runs it behind the same
interface as ``SymbolicWorld``:

    start = ["AtOffice"]                 # conditions true after a reset (the others false)
    random_start = ["Requested"]         # conditions a reset makes true or false at random

    [[variable]]                         # a hidden integer, kept within [min, max]
    name = "snacks"
    min = 0
    max = 3
    start = [1, 3]                       # a reset draws it from this range (or one integer)

    [[derived]]                          # a condition computed from a variable
    condition = "TrayEmpty"
    when = "snacks == 0"                 # ==, !=, <, <=, >, >= and an integer

    [[effect]]                           # what an action does to the hidden variables,
    action = "OfferSnack"                # after the domain's visible ``ram``
    add = { snacks = -1 }                # set = { snacks = 3 } or { snacks = [1, 3] } (drawn)

    [[event]]                            # something people do: in a run, between two actions
    name = "request_withdrawn"           # with this probability; in a demonstration, when
    en = ["the request is withdrawn"]    # the teacher says so
    de = ["der Auftrag wird zurückgezogen"]
    pre = ["Requested"]
    ram = ["!Requested"]
    probability = 0.05

A derived condition is never set directly (not by a ``ram``, not by ``start``): it always
follows its variable. Everything random comes from one seeded generator, so the same seed
and the same inputs give the same world.
"""

from __future__ import annotations

import operator
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from teach import limits
from teach.bt.nodes import Node
from teach.domain import Domain, Literal, State, TomlLines, parse_toml
from teach.errors import DomainError, FormatError, shown
from teach.fsutil import read_text
from teach.observe.hook import Observer
from teach.world.protocol import ActResult, RunResult, WorldEvent
from teach.world.symbolic import SymbolicWorld

WORLD_FILE = "world.toml"
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_WHEN = re.compile(r"^[ \t]*([A-Za-z_][A-Za-z0-9_]*)[ \t]*(==|!=|<=|>=|<|>)[ \t]*(-?[0-9]{1,18})[ \t]*$")
"""A derived condition's test: a variable, a comparison and an integer of at most 18 digits, with
ASCII blanks between (no other script's digits or spaces, no parser limit)."""
_COMPARE: dict[str, Callable[[int, int], bool]] = {
    "==": operator.eq, "!=": operator.ne, "<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge}
_KEYS = {
    "": ("start", "random_start", "variable", "derived", "effect", "event"),
    "variable": ("name", "min", "max", "start"),
    "derived": ("condition", "when"),
    "effect": ("action", "set", "add"),
    "event": ("name", "en", "de", "pre", "ram", "set", "add", "probability"),
}


@dataclass(frozen=True)
class Variable:
    """A hidden integer: its range and the range a reset draws it from."""

    name: str
    low: int
    high: int
    start: tuple[int, int]


@dataclass(frozen=True)
class Derived:
    """A visible condition that holds exactly when ``variable op value``."""

    condition: str
    variable: str
    op: str
    value: int

    def holds(self, value: int) -> bool:
        return _COMPARE[self.op](value, self.value)


@dataclass(frozen=True)
class Change:
    """``add``: the variable changes by ``low``; ``set``: it takes a value drawn from [low, high]."""

    variable: str
    kind: str
    low: int
    high: int


@dataclass(frozen=True)
class Event:
    """Something that happens without the robot: visible ``ram``, hidden changes, when ``pre`` holds."""

    name: str
    en: tuple[str, ...]
    de: tuple[str, ...]
    pre: tuple[Literal, ...]
    ram: tuple[Literal, ...]
    changes: tuple[Change, ...]
    probability: float


@dataclass(frozen=True)
class WorldSpec:
    """A ``world.toml``, checked against its domain."""

    path: Path
    start: tuple[str, ...] = ()
    random_start: tuple[str, ...] = ()
    variables: tuple[Variable, ...] = ()
    derived: tuple[Derived, ...] = ()
    effects: Mapping[str, tuple[Change, ...]] = field(default_factory=dict)
    events: tuple[Event, ...] = ()

    def variable(self, name: str) -> Variable:
        return next(v for v in self.variables if v.name == name)


# --- reading world.toml --------------------------------------------------------------------


def load_world(path: str | Path, domain: Domain) -> WorldSpec:
    """Read and check a ``world.toml`` against ``domain``; every error names the file and line."""
    path = Path(path)
    text = read_text(path, "world file", limits.MAX_DOMAIN_BYTES)
    return _Reader(path, TomlLines(text), domain).world(parse_toml(text, path))


class _Reader:
    def __init__(self, path: Path, lines: TomlLines, domain: Domain):
        self.path, self.lines, self.domain = path, lines, domain

    def fail(self, message: str, line: int | None) -> FormatError:
        return FormatError(message, self.path, line)

    def world(self, data: dict) -> WorldSpec:
        self._known_keys(data, "", None)
        variables: list[Variable] = []
        for index, raw in enumerate(self._tables(data, "variable")):
            variables.append(self._variable(raw, index, variables))
        derived = self._all_derived(data, {v.name: v for v in variables})
        derived_names = {d.condition for d in derived}
        by_name = {v.name: v for v in variables}
        start = self._condition_list(data, "start", derived_names)
        random_start = self._condition_list(data, "random_start", derived_names)
        for name in sorted(set(start) & set(random_start)):
            raise self.fail(f"{name} is in both 'start' and 'random_start'", self.lines.key("random_start", None))
        for definition in self.domain.actions:
            for literal in definition.ram:
                if literal.name in derived_names:
                    line = self.lines.table("derived", [d.condition for d in derived].index(literal.name))
                    raise self.fail(f"{literal.name} follows a variable, but action {definition.name} sets it in its "
                                    f"'ram' in {self.domain.path}: remove one of the two", line)
        effects: dict[str, tuple[Change, ...]] = {}
        for index, raw in enumerate(self._tables(data, "effect")):
            line = self.lines.table("effect", index)
            self._known_keys(raw, "effect", line)
            action = raw.get("action")
            if not isinstance(action, str) or not self.domain.has_action(action):
                raise self.fail(f"'action' must name an action of {self.domain.path}, got {shown(action)}",
                                self.lines.key("action", line))
            if action in effects:
                raise self.fail(f"a second [[effect]] for {action}: put all its changes in one table", line)
            effects[action] = self._changes(raw, by_name, line)
            if not effects[action]:
                raise self.fail(f"the [[effect]] for {action} changes nothing: give 'set' or 'add'", line)
        events = self._events(data, by_name, derived_names)
        return WorldSpec(self.path, start, random_start, tuple(variables), derived, effects, events)

    def _tables(self, data: dict, kind: str) -> list[dict]:
        raw = data.get(kind, [])
        if not isinstance(raw, list) or not all(isinstance(item, dict) for item in raw):
            raise self.fail(f"'{kind}' must be written as [[{kind}]] tables", self.lines.key(kind, None))
        return raw

    def _known_keys(self, raw: dict, kind: str, line: int | None) -> None:
        self.lines.check_keys(raw, _KEYS[kind], f"[[{kind}]]" if kind else "", line, self.path)

    def _integer(self, raw: dict, key: str, line: int | None) -> int:
        value = raw.get(key)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(f"'{key}' must be an integer, got {shown(value)}", self.lines.key(key, line))
        return value

    def _range(self, value: object, what: str, line: int | None) -> tuple[int, int]:
        """An integer or an inclusive ``[low, high]`` range."""
        if isinstance(value, int) and not isinstance(value, bool):
            return value, value
        if (isinstance(value, list) and len(value) == 2 and all(isinstance(v, int) and not isinstance(v, bool)
                                                                for v in value) and value[0] <= value[1]):
            return value[0], value[1]
        raise self.fail(f"{what} must be an integer or a range [low, high] with low <= high, got {shown(value)}", line)

    def _variable(self, raw: dict, index: int, seen: list[Variable]) -> Variable:
        line = self.lines.table("variable", index)
        self._known_keys(raw, "variable", line)
        name = raw.get("name")
        if not isinstance(name, str) or not _NAME.match(name):
            raise self.fail(f"variable {index + 1}: 'name' must be an identifier, got {shown(name)}",
                            self.lines.key("name", line))
        if any(v.name == name for v in seen) or self.domain.has_condition(name) or self.domain.has_action(name):
            raise self.fail(f"variable name {shown(name)} is taken already", self.lines.key("name", line))
        low, high = self._integer(raw, "min", line), self._integer(raw, "max", line)
        if low > high:
            raise self.fail(f"variable {name}: 'min' ({low}) is above 'max' ({high})", self.lines.key("max", line))
        start_line = self.lines.key("start", line)
        start = self._range(raw.get("start", [low, high]), f"variable {name}: 'start'", start_line)
        if start[0] < low or start[1] > high:
            raise self.fail(f"variable {name}: 'start' {list(start)} leaves [{low}, {high}]", start_line)
        return Variable(name, low, high, start)

    def _all_derived(self, data: dict, variables: dict[str, Variable]) -> tuple[Derived, ...]:
        result: list[Derived] = []
        for index, raw in enumerate(self._tables(data, "derived")):
            line = self.lines.table("derived", index)
            self._known_keys(raw, "derived", line)
            condition = raw.get("condition")
            if not isinstance(condition, str) or not self.domain.has_condition(condition):
                raise self.fail(f"'condition' must name a condition of {self.domain.path}, got {shown(condition)}",
                                self.lines.key("condition", line))
            if any(d.condition == condition for d in result):
                raise self.fail(f"{condition} is derived twice", line)
            when = raw.get("when")
            match = _WHEN.match(when) if isinstance(when, str) else None
            if match is None:
                raise self.fail(f"'when' must read like \"snacks == 0\" (a variable, one of "
                                f"{' '.join(_COMPARE)}, an integer), got {shown(when)}", self.lines.key("when", line))
            if match.group(1) not in variables:
                raise self.fail(f"'when' names unknown variable {match.group(1)!r}", self.lines.key("when", line))
            result.append(Derived(condition, match.group(1), match.group(2), int(match.group(3))))
        return tuple(result)

    def _condition_list(self, data: dict, key: str, derived: set[str]) -> tuple[str, ...]:
        raw = data.get(key, [])
        line = self.lines.key(key, None)
        if not isinstance(raw, list) or not all(isinstance(name, str) for name in raw):
            raise self.fail(f"'{key}' must be a list of condition names", line)
        for name in raw:
            if not self.domain.has_condition(name):
                raise self.fail(f"'{key}' names unknown condition {shown(name)}", line)
            if name in derived:
                raise self.fail(f"'{key}' names {name}, which follows its variable", line)
        return tuple(dict.fromkeys(raw))

    def _literals(self, raw: dict, key: str, derived: set[str], line: int | None) -> tuple[Literal, ...]:
        value = raw.get(key, [])
        where = self.lines.key(key, line)
        if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
            raise self.fail(f"'{key}' must be a list of literals like \"Requested\" or \"!Requested\"", where)
        literals = tuple(Literal.parse(item) for item in value)
        for literal in literals:
            if not self.domain.has_condition(literal.name):
                raise self.fail(f"'{key}' names unknown condition {shown(literal.name)}", where)
            if key == "ram" and literal.name in derived:
                raise self.fail(f"'ram' sets {literal.name}, which follows its variable: change the variable", where)
            if literal.negated() in literals:
                raise self.fail(f"'{key}' asks for both {literal.name} and !{literal.name}", where)
        return literals

    def _changes(self, raw: dict, variables: dict[str, Variable], line: int | None) -> tuple[Change, ...]:
        changes: list[Change] = []
        for kind in ("set", "add"):
            table = raw.get(kind, {})
            where = self.lines.key(kind, line)
            if not isinstance(table, dict):
                raise self.fail(f"'{kind}' must be a table like {{ snacks = 1 }}", where)
            for name, value in table.items():
                if name not in variables:
                    raise self.fail(f"'{kind}' names unknown variable {shown(name)}", where)
                if any(c.variable == name for c in changes):
                    raise self.fail(f"variable {name} is both set and changed", where)
                if kind == "add" and (isinstance(value, bool) or not isinstance(value, int)):
                    raise self.fail(f"'add' needs an integer for {name}, got {shown(value)}", where)
                low, high = self._range(value, f"'{kind}' for {name}", where)
                changes.append(Change(name, kind, low, high))
        return tuple(changes)

    def _events(self, data: dict, variables: dict[str, Variable], derived: set[str]) -> tuple[Event, ...]:
        events: list[Event] = []
        for index, raw in enumerate(self._tables(data, "event")):
            line = self.lines.table("event", index)
            self._known_keys(raw, "event", line)
            name = raw.get("name")
            if not isinstance(name, str) or not _NAME.match(name) or any(e.name == name for e in events):
                raise self.fail(f"event {index + 1}: 'name' must be a new identifier, got {shown(name)}",
                                self.lines.key("name", line))
            phrases = {}
            for lang in ("en", "de"):
                value = raw.get(lang)
                if not isinstance(value, list) or not value or not all(isinstance(p, str) and p for p in value):
                    raise self.fail(f"event {name}: '{lang}' must be a list of phrases a teacher may type",
                                    self.lines.key(lang, line))
                phrases[lang] = tuple(value)
            probability = raw.get("probability", 0.0)
            if isinstance(probability, bool) or not isinstance(probability, int | float) or not 0 <= probability <= 1:
                raise self.fail(f"event {name}: 'probability' must be a number from 0 to 1, got {shown(probability)}",
                                self.lines.key("probability", line))
            pre = self._literals(raw, "pre", derived, line)
            ram = self._literals(raw, "ram", derived, line)
            changes = self._changes(raw, variables, line)
            if not ram and not changes:
                raise self.fail(f"event {name} changes nothing: give 'ram', 'set' or 'add'", line)
            events.append(Event(name, phrases["en"], phrases["de"], pre, ram, changes, float(probability)))
        return tuple(events)


# --- the world -----------------------------------------------------------------------------


@dataclass
class _RunLog:
    """What a run has done so far, for the events between its actions: each event with the
    number of robot actions before it, told at once to whoever listens (the session shows it)."""

    on_event: Callable[[WorldEvent], None] | None = None
    actions: int = 0
    events: list[tuple[int, WorldEvent]] = field(default_factory=list)


class HiddenStateWorld(SymbolicWorld):
    """``SymbolicWorld`` (the domain's visible ``pre``/``ram``) with hidden variables, derived
    conditions and events from a ``world.toml``."""

    walks_to_a_start = False  # the world.toml declares its start

    def __init__(self, domain: Domain, spec: WorldSpec, seed: int = 0, observer: Observer | None = None,
                 events_in_runs: bool = True):
        super().__init__(domain, seed, observer)
        self.spec = spec
        self.events = {e.name: (e.en, e.de) for e in spec.events}
        self.events_in_runs = events_in_runs
        self._hidden: dict[str, int] = {}
        self._run: _RunLog | None = None  # while a run is going on
        self.reset(seed)

    def hidden(self) -> dict[str, int]:
        """The hidden variables' current values."""
        return dict(self._hidden)

    def reset(self, seed: int | None = None) -> None:
        """The declared start: ``start`` true, ``random_start`` drawn, variables drawn from their start ranges."""
        super().reset(seed)
        values = list(self._state)
        for name in self.spec.start:
            values[self.domain.index(name)] = True
        for name in self.spec.random_start:
            values[self.domain.index(name)] = self._rng.random() < 0.5
        self._hidden = {v.name: self._rng.randint(*v.start) for v in self.spec.variables}
        self._state = self._derive(tuple(values))

    def arrange(self, state: State, hidden: Mapping[str, int] | None = None) -> None:
        """Put the world in ``state``. Variables take the ``hidden`` values given; the others keep
        their value when it fits the state's derived conditions, else get one that does."""
        given = dict(hidden or {})
        for name, value in given.items():
            if not any(v.name == name for v in self.spec.variables):
                raise DomainError(f"unknown hidden variable {shown(name)}", self.spec.path)
            variable = self.spec.variable(name)
            if not variable.low <= value <= variable.high:
                raise DomainError(f"{name} = {value} leaves its range [{variable.low}, {variable.high}]",
                                  self.spec.path)
        for variable in self.spec.variables:
            wanted = tuple((d, state[self.domain.index(d.condition)]) for d in self.spec.derived
                           if d.variable == variable.name)
            if variable.name in given:
                if not _fits(given[variable.name], wanted):
                    raise DomainError(f"{variable.name} = {given[variable.name]} does not fit "
                                      f"[{self.domain.describe(state)}]", self.spec.path)
                self._hidden[variable.name] = given[variable.name]
            elif not _fits(self._hidden[variable.name], wanted):
                self._hidden[variable.name] = self._fitting_value(variable, wanted, state)
        self._state = self._derive(tuple(state))

    def can_happen(self, state: State) -> bool:
        """Whether some value of every hidden variable gives ``state``'s derived conditions."""
        for variable in self.spec.variables:
            wanted = tuple((d, state[self.domain.index(d.condition)]) for d in self.spec.derived
                           if d.variable == variable.name)
            # every derived condition compares with a constant: its truth changes only next to one
            edges = {variable.low, variable.high} | {d.value + step for d, _truth in wanted for step in (-1, 0, 1)}
            if not any(_fits(value, wanted) for value in edges if variable.low <= value <= variable.high):
                return False
        return True

    def _fitting_value(self, variable: Variable, wanted: tuple[tuple[Derived, bool], ...], state: State) -> int:
        """A value for ``variable`` that fits, drawn from its start range if one does there."""
        for low, high in (variable.start, (variable.low, variable.high)):
            candidates = [value for value in range(low, high + 1) if _fits(value, wanted)]
            if candidates:
                return self._rng.choice(candidates)
        raise DomainError(f"no value of {variable.name} in [{variable.low}, {variable.high}] fits "
                          f"[{self.domain.describe(state)}]", self.spec.path)

    def act(self, action: str) -> ActResult:
        result = super().act(action)
        if not result.ok:
            return result
        self._change(self.spec.effects.get(action, ()))
        self._state = self._derive(self._state)
        after = self._state
        if self._run is not None:
            self._run.actions += 1
            if self.events_in_runs:
                self._random_events(self._run)
        return ActResult(True, result.before, after)

    def perturb(self, event: str) -> ActResult:
        """The named event happens now, if its ``pre`` holds."""
        before = self._state
        found = next((e for e in self.spec.events if e.name == event), None)
        if found is None:
            return ActResult(False, before, before, f"unknown event {shown(event)} (known: {', '.join(self.events)})")
        missing = [lit for lit in found.pre if not self.domain.holds(lit, before)]
        if missing:
            return ActResult(False, before, before, "not possible now: needs " + ", ".join(map(str, missing)))
        values = list(before)
        for literal in found.ram:
            values[self.domain.index(literal.name)] = literal.value
        self._change(found.changes)
        self._state = self._derive(tuple(values))
        return ActResult(True, before, self._state, event)

    def run(self, tree: Node, max_actions: int = 20, interrupt: Callable[[], bool] | None = None,
            stop_after: int | None = None, on_action: Callable[[str], None] | None = None,
            on_event: Callable[[WorldEvent], None] | None = None) -> RunResult:
        """``SymbolicWorld.run``; after every action each event may happen (``events_in_runs``):
        told through ``on_event`` as it happens and kept in the result's ``events``, so the
        session shows it and writes it as an external step (-1)."""
        log = self._run = _RunLog(on_event)
        try:
            plain = super().run(tree, max_actions, interrupt, stop_after, on_action, on_event)
        finally:
            self._run = None
        return RunResult(plain.outcome, plain.steps, plain.final_state, events=log.events)

    def _random_events(self, log: _RunLog) -> None:
        """Each event in file order happens with its probability when its ``pre`` holds."""
        for event in self.spec.events:
            draw = self._rng.random()
            if draw < event.probability and all(self.domain.holds(lit, self._state) for lit in event.pre):
                before = self._state
                self.perturb(event.name)
                happened = WorldEvent(event.name, before, self._state, event.en[0] if event.en else event.name,
                                      event.de[0] if event.de else event.name)
                log.events.append((log.actions, happened))
                self.observer.on_external(event.name)
                if log.on_event is not None:
                    log.on_event(happened)

    def _change(self, changes: tuple[Change, ...]) -> None:
        for change in changes:
            variable = self.spec.variable(change.variable)
            if change.kind == "add":
                value = self._hidden[change.variable] + change.low
            else:
                value = self._rng.randint(change.low, change.high)
            self._hidden[change.variable] = max(variable.low, min(variable.high, value))

    def _derive(self, state: State) -> State:
        values = list(state)
        for derived in self.spec.derived:
            values[self.domain.index(derived.condition)] = derived.holds(self._hidden[derived.variable])
        return tuple(values)


def _fits(value: int, wanted: tuple[tuple[Derived, bool], ...]) -> bool:
    """Whether ``value`` gives every derived condition the truth value wanted for it."""
    return all(derived.holds(value) == truth for derived, truth in wanted)


def world_file(domain: Domain) -> Path | None:
    """The ``world.toml`` beside a domain file, if anything of that name is there."""
    if domain.path is None:
        return None
    candidate = Path(domain.path).parent / WORLD_FILE
    return candidate if os.path.lexists(candidate) else None  # a folder or a FIFO there is refused, not ignored


def symbolic_world(domain: Domain, seed: int = 0, observer: Observer | None = None) -> SymbolicWorld:
    """The symbolic world for a domain: with hidden state when a ``world.toml`` sits beside it."""
    path = world_file(domain)
    if path is None:
        return SymbolicWorld(domain, seed, observer)
    return HiddenStateWorld(domain, load_world(path, domain), seed, observer)
