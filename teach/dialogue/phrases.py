"""Everyday teacher language → actions, events and commands, in English or German.

"Ball finden, zum Ball gehen, Ball greifen" is three actions. Phrases come from the domain's
phrase lists and the world's perturbations; matching ignores case, accents, punctuation,
articles, fillers and politeness, splits on commas and "and/then/und/dann", and segments a
run of phrases without separators. Pronouns ("grab it", "leg ihn in den Eimer") are tried
with every object the phrases name, preferring the one named last.

Safety first: an event (a perturbation of the world) is produced only by its exact phrase,
by ``parse(..., perturb=True)`` (the teacher said "perturb", so events may be matched
loosely there), or by confirming a ``Suggestion``. Typos are tolerated for actions: a clear
one is accepted and its token marked ``guessed``; an unclear one, or a pronoun that could
mean two things, raises ``UnknownPhrase`` carrying a ``Suggestion`` the session can ask
about ("Did you mean …?") and ``confirm``.
"""

from __future__ import annotations

import difflib
import re
import unicodedata
from collections.abc import Iterable, Mapping
from collections.abc import Set as AbstractSet
from dataclasses import dataclass, replace
from itertools import pairwise

from teach.dialogue.reports import report_key
from teach.domain import Domain, Literal
from teach.errors import TeachError
from teach.messages import Lang

MAX_LINE_CHARS = 500  # longer lines are refused: nobody types that much at once
_SHOWN_CHARS = 60  # an unknown part is quoted at most this long

# normalize() drops these (other modules compare command and answer words with it)
_FILLERS = {"the", "a", "an", "please", "now", "bitte", "jetzt", "mal", "den", "die", "das", "dem", "der",
            "des", "ein", "eine", "einen", "to", "zu"}
# phrase matching drops these; "to" and "zu" stay, so "move the bin" and "move to the bin" differ
INTERJECTIONS = frozenset({"oh", "ah", "ach", "hmm", "hm", "um", "uh", "erm", "ahm", "sorry", "naja", "tja"})
"""The sounds of a teacher catching up or hesitating, set aside before a step, a command or an
answer is read ("ach so, erst hinfahren", "sorry, undo", "hmm, I think so")."""
_IGNORED = (_FILLERS - {"to", "zu"}) | INTERJECTIONS | {"ok", "okay", "also", "just", "pls", "can", "could", "would",
                                                        "you", "einem", "einer", "einfach", "doch", "kannst",
                                                        "konntest", "du", "dir", "yourself", "again", "once", "more",
                                                        "nochmal", "noch", "einmal", "wieder", "erneut", "else", "so",
                                        "i", "think", "should", "must", "maybe", "perhaps", "first", "ich",
                                        "glaube", "denke", "solltest", "musst", "vielleicht", "erst", "zuerst",
                                        "d", "instead", "better", "stattdessen", "lieber", "besser", "for", "me", "us",
                                        "fur", "mich", "uns"}
"""Phrase matching drops these too: politeness and hedging ("I think you should go to the ball
first", "I'd go to the bin instead", "besser zum Eimer", "can you find the ball for me?", "such
ihn für mich"), and "again" (a step shown once more after a slip is the same step: "grab it
again", "such den Ball nochmal"), "else" ("find someone else" is finding someone), and the sounds
of a teacher catching up ("ach so, erst hinfahren" was "I don't know “ach so”")."""
_PRONOUNS = {"it", "him", "her", "them", "this", "that", "ihn", "sie", "es", "ihm", "ihr", "ihnen"}
PRONOUN = re.compile(r"\b(?:" + "|".join(sorted(_PRONOUNS)) + r")\b", re.IGNORECASE)
"""The first pronoun of a line (what an object named before may stand for)."""
_PERSONS = frozenset({"person", "people", "someone", "somebody", "caregiver", "resident", "partner", "patient",
                      "nurse", "guest", "visitor", "man", "woman", "child", "friend"})
"""English words for people: what "him", "her" and "them" may stand for ("go to her" was "go back
to the office", the one phrase a pronoun made; "them" also stands for a plural, "put them away")."""
_PERSONS_DE = frozenset({"person", "leute", "jemand", "pflegekraft", "bewohner", "bewohnerin", "partner",
                         "gesprachspartner", "patient", "patientin", "gast", "besucher", "kind", "freund"})
"""German words for people, normalized: a domain naming one has people to do things for."""
_RECEIVERS = frozenset({"him", "her", "them", "ihm", "ihr", "ihnen"})
"""Pronouns for whom something is done ("offer her a drink"), left out where the phrase needs none."""
_PLACES = {"there": ("to", "it"), "hin": ("zu", "ihm"), "dahin": ("zu", "ihm"), "dorthin": ("zu", "ihm")}
"""Words for the place of the object named last, read as "to it" ("go there", "geh hin")."""
_THERE_DE = frozenset({"da", "dort"})
"""German "there", said apart from its "hin" ("geh da hin")."""
_RUN_TOGETHER = ("dorthin", "dahin", "hin")
"""Place words German runs together with the verb after them ("hinfahren"), longest first."""
_NAMING_A_PLACE = {"zum", "zur", "ins", "im"}
"""Besides the linking words: what, after a word for a place, names the place itself ("hin zum Ball")."""
_PARTICLES = {"up", "down", "away", "off", "out", "back"}
"""Particles of phrasal verbs, which people put after the object ("pick b up", "put c down")."""
_ERRAND = ("go", "and", "geh", "gehe", "und")
"""Words before a step that only say the robot should set off to do it ("go get the ball", "go
and grab it", "geh und hol ihn"): one step, not a "go" of its own."""
_LINKS = {"on", "onto", "top", "of", "from", "off", "to", "into", "in", "at", "with", "auf", "von", "an", "mit", "zu"}
"""Words that link a step's objects ("stack b on a", "on top of a"), left out where a line reads no
other way."""
# the word after one of these in a phrase names an object a pronoun may stand for
_ARTICLES = {"the", "a", "an", "this", "that", "den", "die", "das", "dem", "der", "des", "ein", "eine",
             "einen", "einem", "einer", "zum", "zur", "im", "ins", "am", "vom", "beim"}
# a decimal point or comma between digits ("guide forward 0.2", "vorwärts 0,2") is no break
_SPLIT = re.compile(r"\s*(?:[;!]|[,.](?!\d)|(?<!\d)[,.]|\band then\b|\bafter that\b|\bthen\b|(?<!\bgo )\band\b"
                    r"|\bund dann\b|\bdann\b|\bdanach\b|(?<!\bgeh )(?<!\bgehe )\bund\b)\s*", re.IGNORECASE)

_TYPO_CUTOFF = 0.75  # similarity from which a typo is accepted without asking
_TYPO_MARGIN = 0.1  # ... when nothing else (another action, or an event) comes this close
_SUGGEST_CUTOFF = 0.45  # similarity from which a phrase is offered as "Did you mean"
_SUGGEST_MARGIN = 0.1  # ... when no other action or event comes this close
_EVENT_SUGGEST_CUTOFF = _TYPO_CUTOFF  # outside "perturb" an event is offered only for a typo of it
_WORD_CUTOFF = 0.75  # a misspelt word is corrected to a known word this similar

# words a teacher adds before a command ("ok done", "i'm done", "ich bin fertig") and after it ("help me");
# after it only words no command takes as its argument ("show all" keeps its "all")
_CHAT_BEFORE = INTERJECTIONS | {"ok", "okay", "so", "well", "all", "i", "m", "im", "am", "we", "re", "are", "now",
                                "please", "just", "then", "and", "ich", "bin", "wir", "sind", "also", "na", "gut",
                                "jetzt", "bitte", "mal", "dann", "und", "no", "oops", "wait", "nein", "ups", "hoppla",
                                "warte", "moment", "entschuldigung", "let", "lets", "s", "lass", "lasst", "uns"}
_CHAT_AFTER = {"me", "us", "please", "now", "ok", "okay", "mir", "uns", "bitte", "jetzt", "mal"}
_HELP_MARKS = re.compile(r"^[?¿]+$")

_YES_SAID = {
    "en": ("yes", "y", "yeah", "yep", "yup", "ok", "okay", "sure", "right", "correct", "exactly", "indeed",
           "of course", "that's right", "thats right", "that's it", "thats it", "yes please", "do it", "go ahead",
           "you may", "you can", "absolutely", "definitely", "certainly", "by all means", "please do", "fine"),
    "de": ("ja", "j", "jawohl", "genau", "richtig", "stimmt", "klar", "na klar", "ok", "okay", "gern", "gerne",
           "ja genau", "das stimmt", "mach das", "mach es", "natürlich", "sicher", "darfst du", "du darfst",
           "nur zu", "mach ruhig", "auf jeden fall", "selbstverständlich"),
}
_NO_SAID = {
    "en": ("no", "n", "nope", "nah", "not that", "wrong", "no thanks", "no thank you", "that's wrong", "thats wrong",
           "that is wrong", "not right", "that's not right", "thats not right", "that is not right", "don't",
           "do not", "please don't", "you may not", "you can't", "you cannot", "no way", "never", "absolutely not",
           "certainly not", "better not", "forget it", "forget about it"),
    "de": ("nein", "ne", "nee", "no", "falsch", "nicht das", "nein danke", "das ist falsch", "stimmt nicht",
           "das stimmt nicht", "nicht richtig", "lieber nicht", "bitte nicht", "darfst du nicht", "du darfst nicht",
           "auf keinen fall", "nie", "niemals", "vergiss es"),  # "nö" reads "no"
}


@dataclass(frozen=True, slots=True)
class Token:
    """One recognised unit of teacher input: an action or an event, with the phrase it matched.

    ``said`` is what the teacher typed for it; ``guessed`` is true when it was read through a
    typo (the session may show "I read … as …" or ask before acting on it)."""

    kind: str  # "action" | "event"
    name: str
    text: str
    said: str = ""
    guessed: bool = False
    needs: tuple[Literal, ...] = ()
    """What must hold for the phrase to mean its action ("take the ball to the bin": the ball in hand)."""


@dataclass(frozen=True, slots=True)
class Suggestion:
    """A part of a line I could only guess: the session asks ``question()`` and, on yes, calls
    ``PhraseBook.confirm`` to get the whole line's tokens."""

    said: str  # the teacher's words I am unsure about
    candidate: Token  # what I guess they meant
    before: tuple[Token, ...]  # what the line said before them, understood
    rest: str  # what follows them, not read yet
    lang: Lang
    perturb: bool = False
    topic: str | None = None  # the object named last before them

    def question(self) -> str:
        """The whole reading so far with the guess at its end: a yes confirms what was shown, all of it."""
        reading = ", ".join(t.text for t in (*self.before, self.candidate))
        if self.lang == Lang.DE:
            return f"Meintest du „{reading}“?"
        return f"Did you mean “{reading}”?"


class UnknownPhrase(TeachError):
    """A part of the input matched nothing for sure; ``suggestions`` are the closest known phrases,
    ``suggestion`` (when there is one) the structured first of them, ready to be confirmed."""

    def __init__(self, text: str, suggestions: list[str], lang: Lang = Lang.EN, suggestion: Suggestion | None = None):
        self.text = text
        self.suggestion = suggestion
        self.suggestions = [suggestion.candidate.text] + suggestions if suggestion is not None else suggestions
        shown = _shorten(text)
        if suggestion is not None:
            hint = " " + suggestion.question()
            message = f"Das kenne ich nicht: „{shown}“.{hint}" if lang == Lang.DE else f"I don't know “{shown}”.{hint}"
        elif lang == Lang.DE:
            hint = f" Meintest du „{self.suggestions[0]}“?" if self.suggestions else ""
            message = f"Das kenne ich nicht: „{shown}“.{hint}"
        else:
            hint = f" Did you mean “{self.suggestions[0]}”?" if self.suggestions else ""
            message = f"I don't know “{shown}”.{hint}"
        super().__init__(message)


class LineTooLong(TeachError):
    """A line longer than ``MAX_LINE_CHARS``: refused in one short sentence, never echoed."""

    def __init__(self, length: int, lang: Lang = Lang.EN):
        if lang == Lang.DE:
            message = (f"Die Zeile ist zu lang ({length} Zeichen, höchstens {MAX_LINE_CHARS}). "
                       "Bitte schreib einen Schritt nach dem anderen.")
        else:
            message = (f"That line is too long ({length} characters, at most {MAX_LINE_CHARS}). "
                       "Please type one step at a time.")
        super().__init__(message)


def check_length(line: str, lang: Lang = Lang.EN) -> None:
    """Raise ``LineTooLong`` for a line nobody could have meant as one instruction."""
    if len(line) > MAX_LINE_CHARS:
        raise LineTooLong(len(line), lang)


def _shorten(text: str) -> str:
    """The teacher's words as quoted back: one line, no control characters, at most ``_SHOWN_CHARS``."""
    text = " ".join("".join(c if c.isprintable() else " " for c in text).split())
    return text if len(text) <= _SHOWN_CHARS else text[:_SHOWN_CHARS - 1].rstrip() + "…"


def _words(text: str) -> list[str]:
    """Lower case, no accents (ä → a, ß → ss), no punctuation."""
    text = text.lower().replace("ß", "ss")
    text = "".join(c for c in unicodedata.normalize("NFKD", text) if not unicodedata.combining(c))
    return re.findall(r"[a-z0-9]+", text)


def plain(text: str) -> str:
    """Lower case, no accents, no punctuation, every word kept (``normalize`` drops filler words)."""
    return " ".join(_words(text))


def normalize(text: str) -> str:
    """Lower case, no accents (ä → a, ß → ss), no punctuation, no filler words."""
    return " ".join(w for w in _words(text) if w not in _FILLERS)


_YES = {lang: {normalize(said) for said in sayings} for lang, sayings in _YES_SAID.items()}
_NO = {lang: {normalize(said) for said in sayings} for lang, sayings in _NO_SAID.items()}
"""Yes and no, normalized: a reply made only of them is one ("sure, go ahead", "nein, lieber nicht")."""


def _ratio(a: str, b: str) -> float:
    return difflib.SequenceMatcher(None, a, b).ratio()


# --- yes, no and commands in disguise -------------------------------------------------------------


def _says(text: str, words: set[str]) -> bool:
    """Whether a reply is made only of ``words``, fillers aside: "ok ok", "ja genau", "sure, go ahead",
    "no you may not" (each saying matched whole, the longest first)."""
    key = normalize(text)
    said = key.split()
    known = sorted(words, key=lambda saying: -len(saying.split()))
    while said:
        for saying in known:
            length = len(saying.split())
            if " ".join(said[:length]) == saying:
                del said[:length]
                break
        else:
            return False
    return key != ""


def _answer_sets(table: dict[str, set[str]], lang: Lang) -> set[str]:
    """The session language's words, and English ones in any language (many people say "ok", "no")."""
    return table.get(lang, set()) | table["en"]


def is_yes(text: str, lang: Lang = Lang.EN) -> bool:
    """Whether a reply to "Did you mean …?" says yes; an empty reply (Enter) does."""
    if not text.strip():
        return True
    return _says(text, _answer_sets(_YES, lang))


def is_no(text: str, lang: Lang = Lang.EN) -> bool:
    """Whether a reply to "Did you mean …?" says no."""
    return _says(text, _answer_sets(_NO, lang))


def after_no(text: str, lang: Lang = Lang.EN) -> str | None:
    """What follows a leading no ("no, find someone": "find someone"), or None when the reply does
    not begin with one or is nothing but it: how people answer "may I …?" with what to do instead."""
    no = _answer_sets(_NO, lang)
    if _says(text, no):
        return None
    # the words as typed, fillers set aside, each with where it ends: what follows the no is
    # returned as typed ("no, go to the bin": "go to the bin"; read as "go bin" it was unknown)
    words = [(said, found.end()) for found in re.finditer(r"\w+", text)
             for said in [" ".join(_words(found.group()))] if said and said not in _FILLERS]
    for length in range(min(3, len(words) - 1), 0, -1):
        if " ".join(said for said, _end in words[:length]) in no:
            return text[words[length - 1][1]:].lstrip(" \t,;:.!-–—").rstrip() or None
    return None


def command_hint(line: str, lang: Lang, commands: Iterable[str]) -> str | None:
    """The command a conversational line amounts to, as the line to handle instead, or None.

    ``commands`` are the session's command words and sayings (compared after ``normalize``). "ok
    done", "i'm done" and "fertig!" give "done"/"fertig"; "help me" gives "help"; "sorry, undo"
    and "no wait, that was wrong" give "undo" and "that was wrong"; a lone "?" gives the help word
    of ``lang``. Words around the command ("ok", "i'm", "oh", "me", "bitte") are dropped, the
    command's own arguments kept: "please show full" gives "show full"."""
    check_length(line, lang)
    names = {normalize(c) for c in commands}
    if _HELP_MARKS.match(line.strip()):
        for word in (("hilfe", "help") if lang == Lang.DE else ("help", "hilfe")):
            if word in names:
                return word
        return None
    words = line.split()

    def chat(word: str, around: AbstractSet[str]) -> bool:
        return all(w in around for w in _words(word))

    said = len(words)
    while words and chat(words[0], _CHAT_BEFORE):
        words.pop(0)
    if 1 < len(words) < said and normalize(" ".join(words)) in names:  # "no wait, that was wrong"
        return " ".join(words)
    if not words or normalize(words[0]) not in names:
        return None
    while len(words) > 1 and chat(words[-1], _CHAT_AFTER):
        words.pop()
    head = normalize(words[0])
    return " ".join([head, *words[1:]])


# --- the phrase book ---------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class _Entry:
    kind: str
    name: str
    phrase: str
    lang: Lang | None  # None for an internal name
    needs: tuple[Literal, ...] = ()  # an action's phrase that means it only while these hold


@dataclass(frozen=True, slots=True)
class _Piece:
    """A run of the teacher's words read as one phrase; several options when a pronoun is ambiguous."""

    words: tuple[str, ...]
    options: tuple[tuple[_Entry, str | None], ...]  # (entry, the noun a pronoun stood for)


class PhraseBook:
    """All phrases a teacher may type for the domain's actions and the world's events."""

    def __init__(self, domain: Domain, events: Mapping[str, tuple[Iterable[str], Iterable[str]]] = {}):
        self._entries: dict[tuple[str, ...], list[_Entry]] = {}
        self._display: dict[str, dict[str, str]] = {"en": {}, "de": {}}
        self._labels: dict[tuple[str, str], str] = {}
        self._nouns: list[str] = []
        # an object the domain names by a word a line otherwise drops ("a" of "stack b a") is kept
        forms = [c.form for c in domain.conditions] + [a.form for a in domain.actions]
        objects = list(dict.fromkeys(word for form in forms for thing in form[1:] for word in _words(thing)))
        self._objects = frozenset(objects)
        self._ignored = _IGNORED - self._objects
        for action in domain.actions:
            self._add("action", action.name, action.en, action.de)
            self._add("action", action.name, action.en_when, action.de_when, action.when)
        # a form's objects are what "it" may mean too, block "a" among them (an article to _note_nouns)
        self._nouns += [word for word in objects if word not in self._nouns]
        self._handles = {action.name: _words(action.form[1])[-1] for action in domain.actions
                         if len(action.form) > 1 and _words(action.form[1])}
        for name, (english, german) in sorted(events.items()):
            self._add("event", name, tuple(english), tuple(german))
        self._vocabulary = {kind: sorted({w for key, entries in self._entries.items()
                                          if any(e.kind == kind for e in entries) for w in key} | _PRONOUNS)
                            for kind in ("action", "event")}
        self._reports: dict[tuple[str, ...], dict[tuple[str, str], _Entry]] = {}
        for key, entries in self._entries.items():
            for entry in entries:
                if entry.lang is not None:  # the phrases people say, not internal names
                    self._reports.setdefault(report_key(key), {}).setdefault((entry.kind, entry.name), entry)
        self._longest = max((len(key) for key in self._entries), default=1)
        self._ranking: tuple[str | None, list[tuple[float, _Entry]]] = (None, [])

    @property
    def words(self) -> frozenset[str]:
        """Every word of the action and event phrases (both languages): what a typo of a command
        is weighed against, so "tke the tray" is not read as a command."""
        return frozenset((*self._vocabulary["action"], *self._vocabulary["event"]))

    def _add(self, kind: str, name: str, english: tuple[str, ...], german: tuple[str, ...],
             needs: tuple[Literal, ...] = ()) -> None:
        """``needs``: the phrases mean the action only while these hold (never its label)."""
        spelled = re.sub(r"(?<!^)(?=[A-Z])", " ", name)  # FindBall → "Find Ball"
        for lang, phrases in ((Lang.EN, english), (Lang.DE, german)):
            if phrases and not needs:
                self._labels.setdefault((name, lang), phrases[0])
            for phrase in phrases:
                self._enter(_Entry(kind, name, phrase, lang, needs))
                self._note_nouns(phrase)
                self._display[lang].setdefault(phrase, name)
        for internal in () if needs else (name, spelled):
            self._enter(_Entry(kind, name, internal, None))

    def _enter(self, entry: _Entry) -> None:
        """The first phrase of each kind keeps a key: an action and an event may share one."""
        key = self.key(entry.phrase)
        if key:
            entries = self._entries.setdefault(key, [])
            if all(e.kind != entry.kind for e in entries):
                entries.append(entry)

    def _note_nouns(self, phrase: str) -> None:
        """Objects the phrases name (the word after an article), in order of first mention."""
        for article, noun in pairwise(_words(phrase)):
            if article in _ARTICLES and noun not in self._ignored | _ARTICLES | _PRONOUNS and noun not in self._nouns:
                self._nouns.append(noun)

    def phrases(self, lang: Lang = Lang.EN) -> list[str]:
        """Phrases shown for completion, in the given language."""
        return sorted(self._display[lang])

    @property
    def objects(self) -> list[str]:
        """The objects the domain's forms name ("a", "b" in blocksworld), in a fixed order."""
        return sorted(self._objects)

    def topic_in(self, text: str) -> str | None:
        """The one object a line names ("start ball found": the ball), or None: where it names
        several ("start clear b, holding a, ontable d"), which one "it" then means cannot be told
        (it was the last: "put it on b" was "stack d b")."""
        named = {word for word in self.key(text) if word in self._nouns}
        return named.pop() if len(named) == 1 else None

    def topic(self, tokens: Iterable[Token]) -> str | None:
        """What "it" means in the next line: the object the last of ``tokens`` handles, its form's
        first (after "unstack a c" the block held is a, not c), or else the object it names last."""
        topic = None
        for token in tokens:
            topic = self._about(token.name, self.key(token.text)) or topic
        return topic

    # --- parsing ------------------------------------------------------------------------------------

    def parse(self, line: str, lang: Lang = Lang.EN, *, perturb: bool = False, topic: str | None = None) -> list[Token]:
        """All actions and events in a line, in order.

        ``perturb``: the teacher said "perturb": every part names an event, typos tolerated.
        ``topic``: the object a pronoun means when the line itself names none (see ``topic``).
        Raises ``UnknownPhrase`` for the first part that is unknown or only a guess, or for a
        line of only fillers or marks ("ok", "?": nothing to do, so nothing may start), and
        ``LineTooLong`` for a line over ``MAX_LINE_CHARS``."""
        check_length(line, lang)
        chunks = [c.strip() for c in _SPLIT.split(line) if c and c.strip()]
        tokens = self._read(chunks, lang, perturb, topic, [])
        if not tokens and line.strip():
            raise UnknownPhrase(line.strip(), [], lang)
        return tokens

    def confirm(self, suggestion: Suggestion) -> list[Token]:
        """The teacher said yes to ``suggestion``: the whole line's tokens (may raise again for a
        later part of the line)."""
        candidate = replace(suggestion.candidate, guessed=False)
        tokens = [*suggestion.before, candidate]
        topic = self._about(candidate.name, self.key(candidate.text)) or suggestion.topic
        chunks = [c.strip() for c in _SPLIT.split(suggestion.rest) if c and c.strip()]
        return self._read(chunks, suggestion.lang, suggestion.perturb, topic, tokens)

    def _read(self, chunks: list[str], lang: Lang, perturb: bool, topic: str | None,
              tokens: list[Token]) -> list[Token]:
        for index, chunk in enumerate(chunks):
            words = _place_said(self._separated(self.key(chunk)))
            if not words:
                continue
            later = ", ".join(chunks[index + 1:])
            pieces = self._segment(words, perturb)
            for other in () if pieces is not None else self._rephrased(words):  # only where it reads no other way
                pieces = self._segment(other, perturb)
                if pieces is not None:
                    break
            if pieces is None:
                pieces = self._reported(words, perturb)  # "someone took the ball away", "the bin was moved"
            guessed = False
            for other in (words, *self._rephrased(words)) if pieces is None else ():
                pieces = self._corrected(other, perturb)  # "unstak a from c": "unstack a c"
                guessed = True
                if pieces is not None:
                    break
            if pieces is None:
                typo = self._clear_typo(chunk, words, lang, perturb)
                if typo is None:
                    raise self._unknown(chunk, words, lang, perturb, topic, tokens, later)
                tokens.append(typo)
                topic = self._about(typo.name, self.key(typo.text)) or topic
                continue
            for number, piece in enumerate(pieces):
                said = chunk if len(pieces) == 1 else " ".join(piece.words)
                entry, noun = self._choose(piece, topic)
                if entry is None:
                    rest = ", ".join(filter(None, [" ".join(w for p in pieces[number + 1:] for w in p.words), later]))
                    first, alternatives = self._candidates(piece, lang)
                    suggestion = Suggestion(said, replace(first, said=said, guessed=True), tuple(tokens), rest, lang,
                                            perturb, topic)
                    raise UnknownPhrase(said, alternatives, lang, suggestion)
                tokens.append(self._token(entry, lang, said, guessed))
                topic = self._handles.get(entry.name) or noun or self._last_noun(piece.words) or topic
        return tokens

    def _segment(self, words: tuple[str, ...], perturb: bool, typed: bool = True) -> list[_Piece] | None:
        """Split a run of words into known phrases: fewest pieces, then fewest pronouns; None if impossible.
        ``typed``: the words are the teacher's own, not corrected ones (only those reach an event exactly)."""
        best: list[tuple[tuple[int, int], list[_Piece]] | None] = [((0, 0), [])] + [None] * len(words)
        for end in range(1, len(words) + 1):
            for start in range(max(0, end - self._longest), end):
                reached = best[start]
                if reached is None:
                    continue
                piece = self._piece(words[start:end], perturb, typed)
                if piece is None:
                    continue
                pronoun = 1 if piece.options[0][1] is not None else 0
                cost = (reached[0][0] + 1, reached[0][1] + pronoun)
                current = best[end]
                if current is None or cost < current[0]:
                    best[end] = (cost, reached[1] + [piece])
        found = best[-1]
        return None if found is None else found[1]

    def _piece(self, words: tuple[str, ...], perturb: bool, typed: bool) -> _Piece | None:
        exact = self._exact(words, perturb, typed)
        if exact is not None:
            return _Piece(words, ((exact, None),))
        options = self._resolved(words, perturb, places=typed)
        return _Piece(words, tuple(options)) if options else None

    def _exact(self, words: tuple[str, ...], perturb: bool, typed: bool) -> _Entry | None:
        """An action's phrase before an event's: an event needs the teacher's own words of one of
        its phrases (its internal name only after "perturb"), or "perturb"."""
        entries = self._entries.get(words, [])
        for kind in ("event",) if perturb else ("action", "event") if typed else ("action",):
            for entry in entries:
                if entry.kind == kind and (entry.lang or kind == "action" or perturb):
                    return entry
        return None

    def _resolved(self, words: tuple[str, ...], perturb: bool, places: bool = True) -> list[tuple[_Entry, str]]:
        """Each object a pronoun in ``words`` may stand for, with the phrase it makes (never an event
        outside "perturb": a pronoun is a guess); never one the words name themselves ("put b on it"
        was "stack b b")."""
        if not any(w in _PRONOUNS or places and w in _PLACES for w in words):
            return []
        kind = "event" if perturb else "action"
        options = []
        for noun in self._nouns:
            if noun in words or not _may_stand_for(words, noun):
                continue
            for variant in _substituted(words, noun, places):
                entry = next((e for e in self._entries.get(variant, []) if e.kind == kind), None)
                if entry is not None:
                    options.append((entry, noun))
                    break
        if not options:
            options = self._without_receiver(words, kind)
        return options

    def _reported(self, words: tuple[str, ...], perturb: bool) -> list[_Piece] | None:
        """The action (after "perturb": the event) ``words`` report, as one piece. An event reported
        outside "perturb" is only offered (``_unknown``): "hid ball" may be a slip of "hide ball"."""
        meant = self._report_of(words)
        if meant is None or (meant.kind == "event") != perturb:
            return None
        return [_Piece(words, ((meant, None),))]

    def _report_of(self, words: tuple[str, ...]) -> _Entry | None:
        """The one action or event whose phrase ``words`` report (``teach.dialogue.reports``); None
        where none or several do ("b stacked on a": "stack a b" and "stack b a")."""
        found = self._reports.get(report_key(words), {})
        return next(iter(found.values())) if len(found) == 1 else None

    def _without_receiver(self, words: tuple[str, ...], kind: str) -> list[tuple[_Entry, str]]:
        """The phrase ``words`` make without a pronoun for the person something is done for, in a domain
        with people: "offer her a drink" is "offer a drink", "biete ihm einen Snack an" "biete einen Snack an"."""
        people = [noun for noun in self._nouns if noun in _PERSONS or noun in _PERSONS_DE]
        if not people or not any(word in _RECEIVERS for word in words[1:]):
            return []
        left = tuple(word for word in words if word not in _RECEIVERS)
        entry = next((e for e in self._entries.get(left, []) if e.kind == kind), None)
        return [] if entry is None else [(entry, people[0])]

    def _choose(self, piece: _Piece, topic: str | None) -> tuple[_Entry | None, str | None]:
        """The one meaning of a piece: unique, or the one about the topic; (None, None) if ambiguous."""
        names = {entry.name for entry, _ in piece.options}
        if len(names) == 1:
            return piece.options[0]
        about_topic = [(entry, noun) for entry, noun in piece.options if noun == topic]
        if about_topic and len({entry.name for entry, _ in about_topic}) == 1:
            return about_topic[0]
        return None, None

    def _candidates(self, piece: _Piece, lang: Lang) -> tuple[Token, list[str]]:
        """An ambiguous piece's readings: the first as a token, the others' texts."""
        seen: dict[str, Token] = {}
        for entry, _ in piece.options:
            seen.setdefault(entry.name, self._token(entry, lang))
        first, *others = seen.values()
        return first, [t.text for t in others]

    def _corrected(self, words: tuple[str, ...], perturb: bool) -> list[_Piece] | None:
        """Misspelt words corrected to known ones, when every correction is clear and (outside
        "perturb") the line is not closer to an event than to the corrected reading."""
        kind = "event" if perturb else "action"
        vocabulary = self._vocabulary[kind]
        fixed = []
        for word in words:
            if word in vocabulary:
                fixed.append(word)
                continue
            close = difflib.get_close_matches(word, vocabulary, n=2, cutoff=_WORD_CUTOFF)
            ratios = [_ratio(word, c) for c in close]
            if not close or (len(close) > 1 and ratios[1] > ratios[0] - _TYPO_MARGIN):
                return None
            fixed.append(close[0])
        corrected = tuple(fixed)
        if corrected == words:
            return None
        pieces = self._segment(corrected, perturb, typed=False)
        if pieces is None:
            return None
        other = "action" if perturb else "event"
        if self._best(" ".join(words), other)[0] >= _ratio(" ".join(words), " ".join(corrected)):
            return None
        return pieces

    def _best(self, said: str, kind: str, other_than: str | None = None,
              objects: list[str] | None = None) -> tuple[float, _Entry | None]:
        """The phrase of ``kind`` most similar to ``said`` (skipping the name ``other_than``; with
        ``objects``, only one naming those objects in that order)."""
        for ratio, entry in self._ranked(said):
            if entry.kind == kind and entry.name != other_than and \
                    (objects is None or self._objects_named(self.key(entry.phrase)) == objects):
                return ratio, entry
        return 0.0, None

    def _ranked(self, said: str) -> list[tuple[float, _Entry]]:
        """Every phrase by similarity to ``said``, most similar first; the last chunk's ranking is
        kept, since reading one chunk asks for it several times."""
        if self._ranking[0] != said:
            matcher = difflib.SequenceMatcher(None, "", said)  # said is the side the matcher indexes
            scored = []
            for key, entries in self._entries.items():
                matcher.set_seq1(" ".join(key))
                ratio = matcher.ratio()
                scored += [(ratio, entry) for entry in entries if entry.lang or entry.kind == "action"]
            self._ranking = (said, sorted(scored, key=lambda pair: -pair[0]))
        return self._ranking[1]

    def _clear_typo(self, chunk: str, words: tuple[str, ...], lang: Lang, perturb: bool) -> Token | None:
        """The phrase a chunk is a clear typo of: close, and nothing else (another phrase of its
        kind, or any phrase of the other kind: events outside "perturb", actions in it) comes near."""
        said = " ".join(words)
        kind, other = ("event", "action") if perturb else ("action", "event")
        ratio, entry = self._best(said, kind)
        if entry is None or ratio < _TYPO_CUTOFF:
            return None
        rival = max(self._best(said, kind, other_than=entry.name)[0], self._best(said, other)[0])
        if rival > ratio - _TYPO_MARGIN:
            return None
        key = self.key(entry.phrase)
        if self._objects_named(words) != self._objects_named(key):
            return None  # it names other things than typed: no typo ("put a on c" was done as "put down c")
        if not all(_misspelt(word, (*key, *self._ignored)) for word in words):
            return None  # a word of its own, not a slip of one ("put a by c" was done as "put a on c")
        return self._token(entry, lang, chunk, True)

    def _objects_named(self, words: Iterable[str]) -> list[str]:
        """The objects of the domain's forms among ``words``, in order (none in a domain without forms)."""
        return [word for word in words if word in self._objects]

    def _unknown(self, chunk: str, words: tuple[str, ...], lang: Lang, perturb: bool, topic: str | None,
                 tokens: list[Token], later: str) -> UnknownPhrase:
        """The error for a chunk read neither exactly nor as a clear typo, with the closest phrase
        as a confirmable suggestion. Outside "perturb" an event is offered only for a pronoun
        ("hide it"), a report of it ("someone took the ball away") or a typo of one of its phrases,
        and it runs only once the teacher says yes;
        after "perturb" no event is offered for words closer to an action."""
        said = " ".join(words)
        ratio, entry = self._best(said, "event" if perturb else "action", objects=self._objects_named(words))
        if not perturb:
            events = self._resolved(words, perturb=True)
            events = [option for option in events if option[1] == topic] or events
            reported = self._report_of(words)  # "someone took the ball away"
            if not events and reported is not None and reported.kind == "event":
                events = [(reported, "")]  # no pronoun stood for anything
            event_ratio, event = (1.0, events[0][0]) if events else self._best(said, "event")
            if event_ratio >= _EVENT_SUGGEST_CUTOFF and event_ratio > ratio:
                ratio, entry = event_ratio, event
        elif self._best(said, "action")[0] >= ratio:
            entry = None  # an action's words after "perturb": no event to offer
        pronoun_event = entry is not None and entry.kind == "event" and ratio == 1.0
        if entry is None or ratio < _SUGGEST_CUTOFF \
                or not (pronoun_event or self._clearly_nearest(said, entry, ratio, lang)):
            return UnknownPhrase(chunk, [], lang)
        candidate = self._token(entry, lang, chunk, True)
        return UnknownPhrase(chunk, [], lang, Suggestion(chunk, candidate, tuple(tokens), later, lang, perturb, topic))

    def _clearly_nearest(self, said: str, entry: _Entry, ratio: float, lang: Lang) -> bool:
        """Whether ``entry`` is the one phrase ``said`` is near: a word of it is one the teacher
        typed, or nearly ("werfen" in "einwerfen", "bi" for "bin"), and every phrase of another
        action or event in the session's language within ``_SUGGEST_MARGIN`` of it has fewer
        such words ("Ball fahren" is "zum Ball fahren", not "den Ball aufheben"): "go get it" is
        not "go to the bin", and "the ball" names no step. Nor is it offered when a word it leaves
        unexplained is one of another step's: "wait until someone asks" is not "find someone"."""
        shared = self._shared(said, entry.phrase)
        if not shared:
            return False
        mine = self.key(entry.phrase)
        left_over = [word for word in said.split() if len(word) > 3 and word not in _LINKS
                     and not any(_alike(word, theirs) for theirs in mine)]  # a little word says little
        return all(self._shared(said, other.phrase) < shared for r, other in self._ranked(said)
                   if r > ratio - _SUGGEST_MARGIN and other.name != entry.name and other.lang in (lang, None)) \
            and not any(self._shared(" ".join(left_over), other.phrase) for _r, other in self._ranked(said)
                        if left_over and other.name != entry.name and other.kind == entry.kind and other.lang == lang)

    def _shared(self, said: str, phrase: str) -> int:
        """How many of the teacher's words stand for a word of ``phrase`` (articles aside)."""
        theirs = [w for w in self.key(phrase) if w not in _ARTICLES]
        return sum(any(_alike(mine, word) for word in theirs) for mine in said.split())

    def _token(self, entry: _Entry, lang: Lang, said: str = "", guessed: bool = False) -> Token:
        return Token(entry.kind, entry.name, self._text(entry, lang), said, guessed, entry.needs)

    def _text(self, entry: _Entry, lang: Lang) -> str:
        """The phrase to show for an entry: the one matched if it is a phrase of ``lang``, else the label."""
        if entry.lang == lang:
            return entry.phrase
        return self._labels.get((entry.name, lang)) or self._labels.get((entry.name, "en")) or entry.phrase

    def key(self, text: str) -> tuple[str, ...]:
        """The words of a phrase that matter for matching (two phrases with one key read the same):
        fillers dropped, but not the words this domain's forms name as objects (block "a")."""
        return tuple(w for w in _words(text) if w not in self._ignored)

    def _separated(self, words: tuple[str, ...]) -> tuple[str, ...]:
        """A German verb run together with its place word ("hinfahren", "hingehen") as the two words
        ("hin fahren": to what was named last), where the phrases know the verb."""
        known = self._vocabulary["action"]
        split: list[str] = []
        for word in words:
            place = next((p for p in _RUN_TOGETHER if word.startswith(p) and word[len(p):] in known), None)
            split += [place, word[len(place):]] if place else [word]
        return tuple(split)

    def _rephrased(self, words: tuple[str, ...]) -> list[tuple[str, ...]]:
        """Other orders of ``words`` people use for a step, tried where the line reads no other way:
        without linking words before objects ("stack b on a"), the particle of a phrasal verb after
        its object moved back ("put c down": "put down c"), without the "go (and)" of an errand ("go
        get the ball": "get the ball"; not "go back", "go there")."""
        unlinked = self._unlinked(words)
        found = [unlinked] if unlinked != words else []
        errand = words
        while errand and errand[0] in _ERRAND:
            errand = errand[1:]
        if errand != words and errand and errand[0] not in _LINKS | _PARTICLES | _PLACES.keys():
            found.append(errand)
        linked_once = self._linked_once(words)
        if linked_once != words:
            found.append(linked_once)
        for said in (words, unlinked):
            if len(said) >= 3 and said[-1] in _PARTICLES and said[1] not in _PARTICLES:
                found.append((said[0], said[-1], *said[1:-1]))
        return found

    def _unlinked(self, words: tuple[str, ...]) -> tuple[str, ...]:
        """``words`` without the linking words before an object the domain's forms name ("stack b
        on top of a": "stack b a"), or a pronoun standing for one ("stack b on it"): how people say
        a step whose phrase lists its objects bare."""
        kept: list[str] = []
        for word in reversed(words):
            if not (word in _LINKS and kept and self._objects and kept[-1] in self._objects | _PRONOUNS):
                kept.append(word)
        return tuple(reversed(kept))

    def _linked_once(self, words: tuple[str, ...]) -> tuple[str, ...]:
        """``words`` with a run of linking words before an object cut to its first ("put b on top of
        a": "put b on a"), how a phrase that links its objects says it."""
        kept: list[str] = []
        for word in reversed(words):
            if word in _LINKS and len(kept) > 1 and kept[-1] in _LINKS and self._objects \
                    and kept[-2] in self._objects | _PRONOUNS:
                kept[-1] = word
            else:
                kept.append(word)
        return tuple(reversed(kept))

    def _about(self, name: str, words: Iterable[str]) -> str | None:
        """What a step called ``name``, said as ``words``, is about: the object its form handles
        first, or the object it names last."""
        return self._handles.get(name) or self._last_noun(words)

    def _last_noun(self, words: Iterable[str]) -> str | None:
        found = [w for w in words if w in self._nouns]
        return found[-1] if found else None


def _may_stand_for(words: tuple[str, ...], noun: str) -> bool:
    """The English pronouns among ``words`` may all mean ``noun``: "him" and "her" a person, "them"
    a person or a plural ("it" and the German pronouns anything: German names things "ihn" and "sie")."""
    person = noun in _PERSONS
    return all(person or (word == "them" and noun.endswith("s")) for word in words if word in ("him", "her", "them"))


def _alike(typed: str, word: str) -> bool:
    """A word the teacher typed stands for ``word``: three letters or more inside it or its
    start, five or more also spelled nearly like it; two letters only as the start of a longer
    word ("bi" for "bin", never "go" for "go": words that short say nothing about which phrase
    was meant)."""
    if len(typed) < 3:
        return len(typed) == 2 and len(word) > 2 and word.startswith(typed)
    return typed in word or (len(typed) >= 5 and _ratio(typed, word) >= _WORD_CUTOFF)  # "nein" is not "rein"


def _misspelt(typed: str, words: tuple[str, ...]) -> bool:
    """``typed`` is one of ``words`` or a slip of one: spelled nearly like it, two letters swapped
    ("teh"), run together with it ("pickup"), or cut short ("sta"); never another word ("by" is not "on")."""
    return any(typed == word or _ratio(typed, word) >= _WORD_CUTOFF or sorted(typed) == sorted(word)
               or (len(word) > 1 and word in typed) or (len(typed) > 1 and typed in word) for word in words)


def _place_said(words: tuple[str, ...]) -> tuple[str, ...]:
    """``words`` without a word for a place the next words name ("geh hin zum Ball": "geh zum Ball");
    alone, it stands for the place of what was named last (``_PLACES``), "da hin" and "dort hin" as
    "hin" ("geh da hin" was unknown where "geh dahin" was the step)."""
    return tuple(word for word, after in zip(words, (*words[1:], ""), strict=False)
                 if not (word in _PLACES and (after in _LINKS or after in _NAMING_A_PLACE))
                 and not (word in _THERE_DE and after == "hin"))


def _substituted(words: tuple[str, ...], noun: str, places: bool = True) -> list[tuple[str, ...]]:
    """``words`` with every pronoun replaced by ``noun``; German "zu ihm" also as "zum Ball"/"zur …";
    with ``places``, a word for its place as "to" it ("go there": "go to ball"; not a word a typo was
    corrected to: "thing" is not "hin")."""
    if places:
        words = tuple(part for word in words for part in _PLACES.get(word, (word,)))
    plain = tuple(noun if w in _PRONOUNS else w for w in words)
    variants = [plain]
    for contraction in ("zum", "zur"):
        merged: list[str] = []
        for word in words:
            if word in _PRONOUNS and merged and merged[-1] == "zu":
                merged[-1:] = [contraction, noun]
            else:
                merged.append(noun if word in _PRONOUNS else word)
        if tuple(merged) != plain:
            variants.append(tuple(merged))
    return variants
