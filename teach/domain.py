"""Domains: conditions, actions and their optional action model, read from ``domain.toml``.

A state is a tuple of booleans, one per condition in file order (condition ID = position + 1).
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import NoReturn

from teach import limits
from teach.bt.builtins import BTCPP_BUILTINS
from teach.errors import DomainError, FormatError, shown
from teach.fsutil import check_nesting, read_text

State = tuple[bool, ...]

GOAL_ACTION = 0
EXTERNAL_ACTION = -1
MAX_ACTION_ID = 999_999
"""Largest action ID: IDs are written in every CSV line, so they stay short."""
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_RESERVED_NAMES = BTCPP_BUILTINS | {"Condition", "Action", "root", "BehaviorTree", "TreeNodesModel"}


@dataclass(frozen=True, slots=True, order=True)
class Literal:
    """A condition with the truth value it must have; written ``Name`` or ``!Name``."""

    name: str
    value: bool = True

    @classmethod
    def parse(cls, text: str) -> Literal:
        text = text.strip()
        if text.startswith("!"):
            return cls(text[1:].strip(), False)
        return cls(text, True)

    def negated(self) -> Literal:
        return Literal(self.name, not self.value)

    def __str__(self) -> str:
        return self.name if self.value else f"!{self.name}"


@dataclass(frozen=True, slots=True)
class ConditionDef:
    """A condition with its labels; ``en_false``/``de_false`` optionally phrase it as untrue."""

    name: str
    en: str = ""
    de: str = ""
    en_false: str = ""
    de_false: str = ""
    form: tuple[str, ...] = ()
    """Optional ``(predicate, object, ...)``, e.g. ``("on", "a", "b")``: see ``teach.learn.lifting``."""

    def label(self, lang: str = "en", value: bool = True) -> str:
        if not value:
            negative = self.de_false if lang == "de" else self.en_false
            if negative:
                return negative
            positive = self.label(lang)
            return f"nicht: {positive}" if lang == "de" else f"not: {positive}"
        return (self.de if lang == "de" else self.en) or self.name


@dataclass(frozen=True, slots=True)
class ActionDef:
    id: int
    name: str
    en: tuple[str, ...] = ()
    de: tuple[str, ...] = ()
    pre: tuple[Literal, ...] = ()
    ram: tuple[Literal, ...] = ()
    form: tuple[str, ...] = ()
    """Optional ``(kind, object, ...)``, e.g. ``("unstack", "a", "b")``: an instance of a parameterised
    action; instances of one kind share what is learned about them (``teach.learn.lifting``)."""
    when: tuple[Literal, ...] = ()
    en_when: tuple[str, ...] = ()
    de_when: tuple[str, ...] = ()
    """Phrases that mean this step only while ``when`` holds: "take the ball to the bin" is going
    to the bin with the ball in hand; said without it, the step is refused, not done empty-handed."""

    def label(self, lang: str = "en") -> str:
        phrases = self.de if lang == "de" else self.en
        return phrases[0] if phrases else self.name

    def said(self, lang: str | None = None) -> tuple[str, ...]:
        """Every phrase a teacher may say for it, in ``lang`` (None: both), those that need ``when`` too."""
        english, german = (*self.en, *self.en_when), (*self.de, *self.de_when)
        return english if lang == "en" else german if lang == "de" else (*english, *german)


@dataclass(frozen=True)
class Domain:
    """The vocabulary of one task: conditions (by position) and actions (by ID)."""

    name: str
    conditions: tuple[ConditionDef, ...]
    actions: tuple[ActionDef, ...]
    goal: tuple[Literal, ...] = ()
    path: Path | None = None
    _cond_index: dict[str, int] = field(init=False, repr=False, compare=False)
    _by_id: dict[int, ActionDef] = field(init=False, repr=False, compare=False)
    _by_name: dict[str, ActionDef] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_cond_index", {c.name: i for i, c in enumerate(self.conditions)})
        object.__setattr__(self, "_by_id", {a.id: a for a in self.actions})
        object.__setattr__(self, "_by_name", {a.name: a for a in self.actions})

    @property
    def condition_names(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.conditions)

    @property
    def action_names(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.actions)

    def index(self, condition: str) -> int:
        """Position of a condition in a state tuple."""
        try:
            return self._cond_index[condition]
        except KeyError:
            raise DomainError(f"unknown condition {condition!r}", self.path) from None

    def has_condition(self, name: str) -> bool:
        return name in self._cond_index

    def condition(self, name: str) -> ConditionDef:
        return self.conditions[self.index(name)]

    def action(self, key: int | str) -> ActionDef:
        """An action by ID or by name."""
        found = self._by_id.get(key) if isinstance(key, int) else self._by_name.get(key)
        if found is None:
            raise DomainError(f"unknown action {key!r}", self.path)
        return found

    def has_action(self, key: int | str) -> bool:
        return (key in self._by_id) if isinstance(key, int) else (key in self._by_name)

    def holds(self, literal: Literal, state: State) -> bool:
        return state[self.index(literal.name)] == literal.value

    def goal_holds(self, state: State) -> bool:
        """Whether the declared goal holds in ``state`` (never, when none is declared)."""
        return bool(self.goal) and all(self.holds(literal, state) for literal in self.goal)

    def state(self, true_conditions: list[str] | tuple[str, ...] | set[str] = ()) -> State:
        """A state in which exactly the named conditions are true."""
        for name in true_conditions:
            self.index(name)
        return tuple(c.name in true_conditions for c in self.conditions)

    def describe(self, state: State) -> str:
        return " ".join(f"{c.name}={int(v)}" for c, v in zip(self.conditions, state, strict=False))

    @property
    def has_model(self) -> bool:
        return any(a.pre or a.ram for a in self.actions)


def check_tree_fits(domain: Domain, conditions: set[str], actions: set[str], path: str | Path | None) -> None:
    """A tree (given by its condition and action names) may only use the domain's names."""
    for name in sorted(conditions - set(domain.condition_names)):
        raise DomainError(f"the tree tests condition {name!r}, which {domain.path} does not define", path)
    for name in sorted(actions - set(domain.action_names)):
        raise DomainError(f"the tree runs action {name!r}, which {domain.path} does not define", path)


_KEYS = {
    "": ("name", "goal", "condition", "action"),
    "condition": ("name", "en", "de", "en_false", "de_false", "form"),
    "action": ("id", "name", "en", "de", "pre", "ram", "form", "when", "en_when", "de_when"),
}
"""The keys each part of a domain file may hold: any other is a typo that would be ignored."""


class TomlLines:
    """Where things are in a TOML text, so every error names its line. Lines end only at
    ``\\n`` (TOML's own rule), never at the other characters ``str.splitlines`` breaks at."""

    def __init__(self, text: str):
        self.lines = text.split("\n")

    def tables(self, kind: str) -> list[int]:
        """The header line of every ``[[kind]]`` table."""
        return [n for n, line in enumerate(self.lines, 1) if line.strip().startswith(f"[[{kind}]]")]

    def table(self, kind: str, index: int) -> int | None:
        """The header line of the ``index``-th ``[[kind]]`` table."""
        headers = self.tables(kind)
        return headers[index] if index < len(headers) else None

    def key(self, key: str, start: int | None) -> int | None:
        """The line that sets ``key`` in the table whose header is line ``start`` (top level:
        None); the header itself when the key is not written there."""
        for number in range((start or 0) + 1, len(self.lines) + 1):
            stripped = self.lines[number - 1].strip()
            if stripped.startswith("["):
                break
            if re.match(rf"{re.escape(key)}\s*=", stripped):
                return number
        return start

    def header(self, key: str) -> int | None:
        """The first table header ``[key]``, ``[[key]]`` or ``[key.…]`` (a top-level key written as a table)."""
        pattern = re.compile(rf"\[\[?\s*{re.escape(key)}\s*[\].]")
        return next((n for n, line in enumerate(self.lines, 1) if pattern.match(line.strip())), None)

    def find(self, needle: str, after_line: int = 1) -> int | None:
        """The first line at or after ``after_line`` that contains ``needle``."""
        for number in range(max(after_line, 1), len(self.lines) + 1):
            if needle in self.lines[number - 1]:
                return number
        return None

    def check_keys(self, raw: dict, allowed: tuple[str, ...], table: str, start: int | None, path: Path) -> None:
        """Refuse a key that is not ``allowed`` in a table (``table`` as written, "" for the top level)."""
        for key in raw:
            if key not in allowed:
                where = f" in {table}" if table else " at the top level"
                line = self.key(key, start) or self.header(key)  # a top-level key written as a table
                raise FormatError(f"unknown key {shown(key)}{where} (allowed: {', '.join(allowed)})", path, line)


def _check_when_phrases(actions: list[ActionDef], lines: TomlLines,
                        fail: Callable[[str, int | None], NoReturn]) -> None:
    """A phrase that needs ``when`` may not also be a plain phrase (one of the two would be read,
    which one is unclear): "head to the bin" in both ``en`` and ``en_when`` is refused."""
    def key(phrase: str) -> str:
        return " ".join(phrase.lower().split())

    plain = {(lang, key(phrase)): action.name for action in actions
             for lang, phrases in (("en", action.en), ("de", action.de)) for phrase in phrases}
    for action in actions:
        for lang, phrases in (("en", action.en_when), ("de", action.de_when)):
            for phrase in phrases:
                other = plain.get((lang, key(phrase)))
                if other is not None:
                    fail(f"action {action.name}: {shown(phrase)} is in '{lang}_when' and a plain phrase of {other}",
                         lines.find(f'"{phrase}"'))


def check_numbers(text: str, path: str | Path, syntax: str) -> None:
    """Refuse a JSON or TOML text with an integer too long to convert (teach.limits), naming its line."""
    line = limits.too_long_number(text, syntax)
    if line is not None:
        raise FormatError(f"a number with more than {limits.MAX_NUMBER_DIGITS} digits", path, line)


def parse_toml(text: str, path: Path) -> dict:
    """TOML with bounded nesting and integer size, parse errors as one line naming the line."""
    check_nesting(text, path, "toml")
    check_numbers(text, path, "toml")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        match = re.search(r"\(at line (\d+), column \d+\)", str(exc))
        line = int(match.group(1)) if match else max(1, text.count("\n"))  # else: at the end
        message = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", str(exc)) or "invalid TOML"
        raise FormatError(f"invalid TOML: {message}", path, line) from None


def load_domain(path: str | Path) -> Domain:
    """Read and validate a ``domain.toml``; every error names the file and line."""
    path = Path(path)
    text = read_text(path, "domain file", limits.MAX_DOMAIN_BYTES)
    lines = TomlLines(text)
    for kind, most in (("condition", limits.MAX_CONDITIONS), ("action", limits.MAX_ACTIONS)):
        headers = lines.tables(kind)
        if len(headers) > most:  # before parsing: a huge domain costs no parsing time
            raise FormatError(f"{len(headers)} [[{kind}]] tables: a domain may have at most {most}", path,
                              headers[most])
    return _domain_from_data(parse_toml(text, path), lines, path)


def _domain_from_data(data: dict, lines: TomlLines, path: Path) -> Domain:
    def fail(message: str, line: int | None = None) -> NoReturn:
        raise FormatError(message, path, line)

    lines.check_keys(data, _KEYS[""], "", None, path)
    name = data.get("name", path.parent.name)
    if not isinstance(name, str):
        fail("'name' must be a string", lines.key("name", None))
    raw_conditions = data.get("condition", [])
    raw_actions = data.get("action", [])
    if not isinstance(raw_conditions, list) or not raw_conditions:
        fail("no [[condition]] tables: a domain needs at least one condition")
    if not isinstance(raw_actions, list) or not raw_actions:
        fail("no [[action]] tables: a domain needs at least one action")
    cond_lines = lines.tables("condition")
    action_lines = lines.tables("action")
    for what, items, most, headers in (("conditions", raw_conditions, limits.MAX_CONDITIONS, cond_lines),
                                       ("actions", raw_actions, limits.MAX_ACTIONS, action_lines)):
        if len(items) > most:
            fail(f"{len(items)} {what}: a domain may have at most {most}",
                 headers[most] if len(headers) > most else None)

    conditions: list[ConditionDef] = []
    cond_names: set[str] = set()
    condition_forms: dict[tuple[str, ...], str] = {}
    for i, raw in enumerate(raw_conditions):
        line = cond_lines[i] if i < len(cond_lines) else None
        if not isinstance(raw, dict):
            fail("[[condition]] must be a table", line)
        lines.check_keys(raw, _KEYS["condition"], "[[condition]]", line, path)
        cname = raw.get("name")
        if not isinstance(cname, str) or not _NAME.match(cname) or cname in _RESERVED_NAMES:
            fail(f"condition {i + 1}: 'name' must be an identifier (letters, digits, _) and not a "
                 f"BehaviorTree.CPP node type, got {shown(cname)}", line)
        if cname in cond_names:
            fail(f"duplicate condition name {cname!r}", line)
        labels = [raw.get(key, "") for key in ("en", "de", "en_false", "de_false")]
        if not all(isinstance(label, str) for label in labels):
            fail(f"condition {cname}: 'en', 'de', 'en_false' and 'de_false' must be strings", line)
        if any(len(label) > limits.MAX_LABEL_CHARS for label in labels):
            fail(f"condition {cname}: a label is longer than {limits.MAX_LABEL_CHARS} characters", line)
        en, de, en_false, de_false = labels
        form = _form(raw, f"condition {cname}", condition_forms, fail, lines.key("form", line))
        conditions.append(ConditionDef(cname, en, de, en_false, de_false, form))
        cond_names.add(cname)

    def literals(raw: object, what: str, line: int | None) -> tuple[Literal, ...]:
        if not isinstance(raw, list) or not all(isinstance(x, str) for x in raw):
            fail(f"{what} must be a list of strings like \"BallFound\" or \"!BallFound\"", line)
        if len(raw) > limits.MAX_MODEL_LITERALS:  # type: ignore[arg-type]
            fail(f"{what} has {len(raw)} literals, more than the {limits.MAX_MODEL_LITERALS} accepted", line)  # type: ignore[arg-type]
        result: dict[Literal, None] = {}
        for item in raw:  # type: ignore[union-attr]
            literal = Literal.parse(item)
            if literal.name not in cond_names:
                where = lines.find(f'"{item}"', line or 1) or line
                fail(f"{what} names unknown condition {shown(literal.name)}", where)
            if literal.negated() in result:
                fail(f"{what} asks for both {literal.name} and !{literal.name}", line)
            result[literal] = None
        return tuple(result)

    actions: list[ActionDef] = []
    action_forms: dict[tuple[str, ...], str] = {}
    action_names: set[str] = set()
    action_ids: set[int] = set()
    for i, raw in enumerate(raw_actions):
        line = action_lines[i] if i < len(action_lines) else None
        if not isinstance(raw, dict):
            fail("[[action]] must be a table", line)
        lines.check_keys(raw, _KEYS["action"], "[[action]]", line, path)
        aid, aname = raw.get("id"), raw.get("name")
        if not isinstance(aname, str) or not _NAME.match(aname) or aname in _RESERVED_NAMES:
            fail(f"action {i + 1}: 'name' must be an identifier (letters, digits, _) and not a "
                 f"BehaviorTree.CPP node type, got {shown(aname)}", line)
        if isinstance(aid, bool) or not isinstance(aid, int) or not 1 <= aid <= MAX_ACTION_ID:
            fail(f"action {aname}: 'id' must be an integer >= 1 and <= {MAX_ACTION_ID} (0 and -1 are reserved), "
                 f"got {shown(aid)}", line)
        if aname in cond_names:
            fail(f"action {aname} has the same name as a condition", line)
        if aname in action_names:
            fail(f"duplicate action name {aname!r}", line)
        if aid in action_ids:
            fail(f"duplicate action id {aid}", line)
        phrases = {}
        for lang in ("en", "de", "en_when", "de_when"):
            value = raw.get(lang, [])
            if isinstance(value, str):
                value = [value]
            where = lines.key(lang, line)
            if not isinstance(value, list) or not all(isinstance(p, str) for p in value):
                fail(f"action {aname}: '{lang}' must be a list of phrases", where)
            if len(value) > limits.MAX_PHRASES:
                fail(f"action {aname}: {len(value)} '{lang}' phrases, more than the {limits.MAX_PHRASES} accepted",
                     where)
            if any(len(p) > limits.MAX_LABEL_CHARS for p in value):
                fail(f"action {aname}: a '{lang}' phrase is longer than {limits.MAX_LABEL_CHARS} characters", where)
            phrases[lang] = tuple(value)
        pre = literals(raw.get("pre", []), f"action {aname}: 'pre'", line)
        ram = literals(raw.get("ram", []), f"action {aname}: 'ram'", line)
        form = _form(raw, f"action {aname}", action_forms, fail, lines.key("form", line))
        when = literals(raw.get("when", []), f"action {aname}: 'when'", lines.key("when", line))
        if bool(when) != bool(phrases["en_when"] or phrases["de_when"]):
            fail(f"action {aname}: 'when' and the phrases that need it ('en_when', 'de_when') go together",
                 lines.key("when" if when else "en_when" if phrases["en_when"] else "de_when", line))
        actions.append(ActionDef(aid, aname, phrases["en"], phrases["de"], pre, ram, form, when,  # type: ignore[arg-type]
                                 phrases["en_when"], phrases["de_when"]))
        action_names.add(aname)  # type: ignore[arg-type]
        action_ids.add(aid)  # type: ignore[arg-type]

    _check_when_phrases(actions, lines, fail)
    formed = next((a.name for a in actions if a.form), None)
    for i, condition in enumerate(conditions if formed is not None else ()):
        if not condition.form:
            fail(f"condition {condition.name} has no 'form' but action {formed} has one: give every condition "
                 f"its form (form = [\"{condition.name}\"] if it is about no object)",
                 cond_lines[i] if i < len(cond_lines) else None)
    goal = literals(data.get("goal", []), "'goal'", lines.key("goal", None))
    return Domain(name, tuple(conditions), tuple(actions), goal, path)


MAX_FORM_OBJECTS = 8
"""Objects a condition's or an action's ``form`` may name."""


def _form(raw: dict, what: str, seen: dict[tuple[str, ...], str], fail: Callable[[str, int | None], NoReturn],
          line: int | None) -> tuple[str, ...]:
    """The optional ``form = ["kind", "object", ...]`` of a condition or action, checked: identifiers,
    at most ``MAX_FORM_OBJECTS`` objects, none the same as one in ``seen`` (the forms of the other
    conditions, or of the other actions, so far)."""
    value = raw.get("form")
    if value is None:
        return ()
    if (not isinstance(value, list) or not value or len(value) > MAX_FORM_OBJECTS + 1
            or not all(isinstance(part, str) and _NAME.match(part) for part in value)):
        fail(f"{what}: 'form' must be a list of a kind and up to {MAX_FORM_OBJECTS} objects, each an identifier "
             f"(letters, digits, _), like [\"on\", \"a\", \"b\"]; got {shown(value)}", line)
    form = tuple(value)
    if form in seen:
        fail(f"{what} has the same 'form' as {seen[form]}", line)
    seen[form] = what
    return form


def find_domain_file(folder: str | Path) -> Path:
    """The ``domain.toml`` of a demonstration folder: in the folder itself or its parent."""
    folder = Path(folder)
    start = folder if folder.is_dir() else folder.parent
    for candidate in (start / "domain.toml", start.parent / "domain.toml"):
        if candidate.is_file():
            return candidate
    raise FormatError("no domain.toml in this folder or its parent (pass --domain FILE)", folder)
