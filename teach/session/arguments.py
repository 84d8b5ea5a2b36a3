"""What a command's argument names: a whole number ("run 3"), a step ("undo to step 3"), the
conditions of 'start' and the action or condition of 'why', in either language, by label or
by name in any case."""

from __future__ import annotations

import functools
import re
from collections.abc import Callable
from fractions import Fraction

from teach import messages as m
from teach.dialogue.phrases import PhraseBook, UnknownPhrase, normalize, plain
from teach.dialogue.questions import join_words
from teach.domain import ConditionDef, Domain
from teach.errors import TeachError
from teach.messages import Lang

_FULL_WORDS = ("full", "ganz", "all", "alles")
_PARTS = re.compile(r"(\s*(?:,|;|\band\b|\bund\b|\bbut\b|\baber\b)\s*)", re.IGNORECASE)
_LINKING = {"is", "ist", "are", "sind", "i", "ich", "my", "mein", "meiner", "of", "in", "im"}
"""Words nearly every condition's label has: sharing them says nothing about which one is meant."""
MAX_LIKE = 4
"""The most conditions a phrase that names none is said to perhaps mean (beyond: all are listed)."""
_STEP_WORDS = {"step", "steps", "schritt", "schritte", "bis", "ab", "from", "back", "zuruck",
               # "undo that", "undo the last one", "nimm das zurück": the last step, as with no number
               "that", "it", "this", "last", "das", "es", "letzten", "letzte"}


_NARRATING = {"now", "already", "still", "yet", "again", "jetzt", "nun", "schon", "noch", "wieder", "ok", "okay",
              "look", "see", "schau", "guck"}
"""Words a teacher telling the robot how things are adds around a condition ("the tray is empty now")."""


def stated_condition(domain: Domain, text: str) -> tuple[str, bool] | None:
    """The condition and value a whole line states as one of its labels, in either language ("the tray
    is empty now": TrayEmpty true; "ich sehe den Ball nicht": BallFound false), or None."""
    words = normalize(text).split()
    while words and words[0] in _NARRATING:
        words.pop(0)
    while words and words[-1] in _NARRATING:
        words.pop()
    return _condition_labels(domain).get(" ".join(words)) if words else None


@functools.cache
def _condition_labels(domain: Domain) -> dict[str, tuple[str, bool]]:
    """Each condition label of ``domain`` in either language, normalized, with what it states (the
    first condition a label names wins): built once per domain, not for every line."""
    labels: dict[str, tuple[str, bool]] = {}
    for condition in domain.conditions:
        for value in (True, False):
            for lang in ("en", "de"):
                labels.setdefault(normalize(condition.label(lang, value)), (condition.name, value))
    return labels


def says_full(text: str) -> bool:
    """Whether 'show' or 'state' asks for everything ("show full", "zeige alles")."""
    return normalize(text) in _FULL_WORDS


_NUMBER_WORDS = {word: value for words in (
    ("zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve"),
    ("null", "eins", "zwei", "drei", "vier", "funf", "sechs", "sieben", "acht", "neun", "zehn", "elf", "zwolf"))
    for value, word in enumerate(words)} | {"ein": 1, "einen": 1, "eine": 1, "einem": 1}
"""Numbers said in words ("undo to step one", "bis Schritt zwei": "expected a whole number")."""


def whole_number(text: str, lang: Lang) -> int | None:
    """An optional whole number argument ("run 3", "reset 7", "run three")."""
    if not text.strip():
        return None
    said = _NUMBER_WORDS.get(normalize(text))
    try:
        value = int(text.strip()) if said is None else said
    except ValueError:
        raise TeachError(m.WHOLE_NUMBER(lang, text=text.strip())) from None
    if value < 0:
        raise TeachError(m.NOT_NEGATIVE(lang))
    return value


def step_number(text: str, lang: Lang) -> int | None:
    """The step an undo goes back to: "3", "to step 3", "bis Schritt 3"; None when none is named."""
    said = normalize(text).replace("last one", "last")  # "the last one", not step one
    return whole_number(" ".join(w for w in said.split() if w not in _STEP_WORDS), lang)


def condition_names(domain: Domain, text: str, lang: Lang) -> list[str]:
    """The conditions a teacher names, as labels in either language ("the bin is within reach,
    ich sehe den Ball") or names in any case ("BallFound binclose"), parts split at commas, "and"
    and "but". A state line reads as it is said: its untrue labels ("the ball is out of reach"),
    "and nothing else" and "none of the N conditions holds" name what is false anyway."""
    names: list[str] = []
    untrue: list[str] = []
    for part in _parts(domain, text):
        if normalize(part) in _NOTHING_ELSE or any(pattern.fullmatch(plain(part)) for pattern in _NOTHING_HOLDS):
            continue
        negated = _untrue_label(domain, part)
        if negated is not None:  # false, as every condition not named is: a state line reads as said
            untrue.append(negated)
            continue
        whole = condition_named(domain, part)
        words = part.split()
        if whole is None and len(words) > 1 and not any(condition_named(domain, word) for word in words):
            # a phrase, not names side by side: "the bin is near" was "which condition is 'the'?"
            raise _unknown_phrase(domain, part.strip(), lang)
        for word in [part] if whole is not None else words:  # else names side by side
            found = condition_named(domain, word)
            if found is None:
                family = _begun_by(domain, word)
                if len(family) > 1:
                    raise TeachError(m.WHICH_CONDITION(lang, name=word.strip(), some=", ".join(
                        m.QUOTED(lang, text=domain.condition(name).label(lang)) for name in family)))
                known = ", ".join(c.label(lang) for c in domain.conditions)
                raise TeachError(m.UNKNOWN_CONDITION(lang, name=word.strip(), known=known))
            names.append(found)
    both = [name for name in untrue if name in names]
    if both:
        raise TeachError(m.TRUE_AND_UNTRUE(lang, label=domain.condition(both[0]).label(lang)))
    return names


_NOTHING_ELSE = {normalize(said) for said in ("nothing else", "sonst nichts")}
"""How a state line ends where it names only what holds (``teach.dialogue.questions.only_these``)."""
_NOTHING_HOLDS = [re.compile(re.escape(plain(said.replace("{count}", "0"))).replace("0", r"\d+"))
                  for said in (m.NOTHING_HOLDS.en, m.NOTHING_HOLDS.de)]
"""A state line where nothing holds ("none of the 29 conditions holds")."""


def _parts(domain: Domain, text: str) -> list[str]:
    """``text`` split at commas, "and" and "but", but a label with a comma in it kept whole ("eine
    Pflegekraft hat mich gebeten, Snacks anzubieten" was two unknown conditions)."""
    pieces = _PARTS.split(text)  # parts at even places, the separators between them
    labels = {plain(c.label(lang, value))
              for c in domain.conditions for lang in ("en", "de") for value in (True, False)}
    parts: list[str] = []
    index = 0
    while index < len(pieces):
        part, end = pieces[index], index
        for later in range(index + 2, len(pieces), 2):  # the longest run of pieces that is one label
            joined = "".join(pieces[index:later + 1])
            if plain(joined) in labels:
                part, end = joined, later
        if part.strip():
            parts.append(part)
        index = end + 2
    return parts


def _untrue_label(domain: Domain, text: str) -> str | None:
    """The condition ``text`` says is untrue, as a state line says it ("the bin is out of reach",
    "not: on a b"), or None."""
    said = plain(text)  # every word: "not: on a b" is not "not: on b a"
    for condition in domain.conditions:
        if said in {plain(condition.label(lang, False)) for lang in ("en", "de")}:
            return condition.name
    return None


class ConditionGuess(TeachError):
    """A phrase that names no condition but is most like one: "did you mean …?", and a yes to it
    reads the line again with that condition's label in place of ``said``."""

    def __init__(self, message: str, said: str, meant: str):
        super().__init__(message)
        self.said = said
        self.meant = meant


def _unknown_phrase(domain: Domain, text: str, lang: Lang) -> TeachError:
    """No condition reads as ``text``: the few whose labels share the most telling words with it
    (a word counts less the more labels have it: "table" names 4 of blocksworld's conditions, "on"
    20; a word of 4 letters or more also counts inside a longer one: "table" in "ontable a");
    one alone is a ``ConditionGuess``."""
    said = set(normalize(text).split()) - _LINKING
    labels = {c.name: normalize(c.label(lang)).split() + _name_words(c.name) for c in domain.conditions}
    score: dict[str, Fraction] = {}
    for word in sorted(said):
        having = [name for name, words in labels.items()
                  if any(word == w or len(word) >= 4 and word in w for w in words)]
        for name in having:
            score[name] = score.get(name, Fraction(0)) + Fraction(1, len(having))
    best = max(score.values(), default=Fraction(0))
    labels_like = [domain.condition(name).label(lang) for name, value in score.items() if value == best]
    like = [m.QUOTED(lang, text=label) for label in labels_like]
    if best and len(like) == 1:
        return ConditionGuess(m.UNKNOWN_CONDITION_LIKE(lang, name=text, some=like[0]), text, labels_like[0])
    if best and len(like) <= MAX_LIKE:
        return TeachError(m.UNKNOWN_CONDITION_LIKE(lang, name=text, some=join_words(like, lang, m.OR)))
    return TeachError(m.UNKNOWN_CONDITION(lang, name=text, known=", ".join(c.label(lang) for c in domain.conditions)))


def _name_words(name: str) -> list[str]:
    """A condition's name as words ("BallFound": ball, found; "on_a_b": on, a, b): a teacher may say
    it so ("the ball is found")."""
    return [word.lower() for word in re.findall(r"[A-Z]?[a-z]+|[A-Z]+(?![a-z])|[0-9]+", name)]


def condition_named(domain: Domain, text: str) -> str | None:
    """The condition ``text`` names: first word for word (so "on_b_a" is never "on_a_b"), else
    without filler words if that reading names one condition only ("the ball is found"; "on b a"
    without its "a" reads "on a b" too: then None), and ``text`` is not the first words of several
    ("clear" without the "a" of "clear a" would read as "clear a", but "clear b" begins so too)."""
    exact = _conditions_read(domain, text, plain)
    if exact:
        return exact[0]
    if len(_begun_by(domain, text)) > 1:
        return None
    loose = _conditions_read(domain, text, normalize)
    return loose[0] if len(loose) == 1 else _by_form(domain, text)


def _by_form(domain: Domain, text: str) -> str | None:
    """The condition with a form (a predicate and its objects, ``teach.learn.lifting``) that ``text``
    names in a person's order: "a on b" is "on a b", "b is on the table" "ontable b", "hand empty"
    "handempty": its objects in the form's order, and its other words, filler words and then
    linking ones aside, run together into the predicate."""
    objects = {word for c in domain.conditions for thing in c.form[1:] for word in plain(thing).split()}
    words = plain(text).split()
    named = [w for w in words if w in objects]
    rest = [w for w in words if w not in objects and normalize(w)]
    said = {"".join(rest), "".join(w for w in rest if w not in _LINKING)}
    found = [c.name for c in domain.conditions if c.form and [w for thing in c.form[1:] for w in plain(thing).split()]
             == named and plain(c.form[0]).replace(" ", "") in said]
    return found[0] if len(found) == 1 else None


def _begun_by(domain: Domain, text: str) -> list[str]:
    """The conditions whose name or label, word for word, begins with ``text``'s words and goes on."""
    key = plain(text).split()
    if not key:
        return []
    return [c.name for c in domain.conditions
            if any(words[:len(key)] == key and len(words) > len(key)
                   for words in (plain(r).split() for r in _readings(c)))]


def _conditions_read(domain: Domain, text: str, read: Callable[[str], str]) -> list[str]:
    """The conditions whose name, name spelled out or label reads as ``text`` does."""
    key = read(text)
    return [c.name for c in domain.conditions if key in {read(r) for r in _readings(c)}]


def _readings(condition: ConditionDef) -> tuple[str, str, str, str]:
    """What a teacher may call a condition: its name, the name spelled out, its labels."""
    return condition.name, _spelled(condition.name), condition.en, condition.de


def node_named(domain: Domain, phrases: PhraseBook, text: str, lang: Lang, topic: str | None) -> str:
    """The action or condition ``why`` asks about: its label, its name in any case, or any
    words the prompt would take as that one step ("grab it", a typo; "it" is ``topic``), also a
    verb alone ("why grab", "warum greifen": read as "grab it", "ihn greifen")."""
    condition = condition_named(domain, text) or _condition_said(domain, text)
    if condition is not None:
        return condition
    key = normalize(text)
    for action in domain.actions:
        if key in {normalize(action.name), normalize(_spelled(action.name))}:
            return action.name
    for words in (text, f"{text} it", f"it {text}"):
        try:
            tokens = phrases.parse(words, lang, topic=topic)
        except UnknownPhrase:
            continue
        if len(tokens) == 1 and tokens[0].kind == "action":
            return tokens[0].name
    return text.strip()


def untrue_asked(domain: Domain, name: str, text: str) -> bool:
    """Whether ``text`` names condition ``name`` by its untrue label ("why is the bin out of reach"),
    so the reasons about it being untrue come first."""
    if not domain.has_condition(name):
        return False
    condition = domain.condition(name)
    return any(label and _same_words(label, text) for label in (condition.en_false, condition.de_false))


def _condition_said(domain: Domain, text: str) -> str | None:
    """The condition whose label, true or untrue, has ``text``'s words in any order: the tree in
    words says "the bin is out of reach", a teacher asks "why is the bin out of reach" (it was "No
    condition named 'the bin is out of reach' in the tree"). Never for 'start': there an untrue
    label would set the condition true."""
    found = {c.name for c in domain.conditions
             for label in (c.en, c.de, c.en_false, c.de_false) if label and _same_words(label, text)}
    return found.pop() if len(found) == 1 else None


def _same_words(label: str, text: str) -> bool:
    """Whether ``text`` has the words of ``label`` in any order, filler words aside ("is the bin out of
    reach" and "the bin is out of reach")."""
    return sorted(normalize(label).split()) == sorted(normalize(text).split())


def _spelled(name: str) -> str:
    """An identifier as words: BallFound → "Ball Found"."""
    return re.sub(r"(?<!^)(?=[A-Z])", " ", name)
