"""Model repair: a few plain questions that make a teacher's own action model usable for PA-BT.

The thesis's study (§6.1) asked eight people for the preconditions and ramifications of the
five ball-task actions; PA-BT (Approach 1) built a usable tree from only four of the tables.
The others fail in a handful of typical ways: the same condition as precondition and
ramification of one action (the temporal order was the hardest part of the concept), a
condition the plan needs that no action makes true (an action given without ramifications),
or actions that wait for each other. People think in actions, not preconditions, and accept
about five questions, so each question here is about one concrete action or a pair of them,
phrased from the domain's own labels:

- ``timing``: "When I find the ball: must “I can see the ball” hold before I start, or
  does it only hold afterwards?" (one condition both before and after one action);
- ``effects``: "What is different after I go to the ball?" (an action with several such
  conditions, or the only action that changes nothing while a needed condition has no cause);
- ``achiever``: "What should I do so that “the ball is within reach”?" (a needed condition that
  no action makes true);
- ``order``: "What should I do first: find the ball or go to the ball?" (actions that wait for
  each other's results);
- ``never``: "Can I find the ball while “the ball is out of reach”?" (a precondition that
  can never become true, once the teacher has said no action makes it true).

Which question comes first follows only the structure of the model (contradictions first,
then the needed conditions nearest the goal), never the ball task. ``ModelOracle`` answers
them as a teacher who knows the true model would type them; ``repair`` runs the loop.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from enum import StrEnum

from teach import messages as m
from teach.dialogue.phrases import PhraseBook, UnknownPhrase, normalize
from teach.dialogue.questions import QuestionBudget
from teach.domain import ActionDef, Domain, Literal
from teach.learn.model_gaps import (
    PlanOutcome,
    achievers,
    depends_on,
    needed,
    needs_actions,
    plan_model,
    reachable,
    requires,
)
from teach.messages import Lang, Text


class QuestionKind(StrEnum):
    TIMING = "timing"
    EFFECTS = "effects"
    ACHIEVER = "achiever"
    ORDER = "order"
    NEVER = "never"


KINDS = tuple(QuestionKind)

# Answer words, compared after ``normalize`` (lower case, no accents, no filler words).
_WORDS: dict[str, frozenset[str]] = {
    "before": frozenset({"before", "already", "already before", "before you start", "first", "vorher",
                         "davor", "schon vorher", "schon", "bevor", "zuvor", "vor dem start"}),
    "after": frozenset({"after", "afterwards", "only after", "only afterwards", "later", "it makes it true",
                        "makes it true", "nachher", "danach", "hinterher", "erst danach", "erst nachher",
                        "macht es wahr", "spater"}),
    "both": frozenset({"both", "before and after", "beides", "beide", "vorher und nachher"}),
    "neither": frozenset({"neither", "neither nor", "none", "nothing", "weder noch", "keins", "keines",
                          "nichts", "weder vorher noch nachher"}),
    "nothing": frozenset({"nothing", "none", "no action", "nothing changes", "nothing is different",
                          "nichts", "keine", "keins", "keine handlung", "nichts andert sich",
                          "nichts ist anders"}),
    "yes": frozenset({"yes", "y", "yeah", "yes i can", "yes you can", "ja", "j", "ja kann ich", "doch"}),
    "no": frozenset({"no", "n", "nope", "no i cannot", "no you cannot", "nein", "nein kann ich nicht"}),
    "either": frozenset({"either", "any", "does not matter", "doesn t matter", "either order", "egal",
                         "beliebig", "ist egal"}),
}
_SHOWN: dict[str, Text] = {  # how an answer word is offered
    "before": m.WORD_BEFORE, "after": m.WORD_AFTER, "both": m.WORD_BOTH, "neither": m.WORD_NEITHER,
    "nothing": m.WORD_NOTHING, "yes": m.WORD_YES, "no": m.WORD_NO, "either": m.WORD_EITHER,
}
_LIST_SPLIT = re.compile(r"\s*(?:[,;]|\band\b|\bund\b)\s*", re.IGNORECASE)


def _q(text: str, lang: Lang) -> str:
    """A label in the language's quotation marks."""
    return m.QUOTED(lang, text=text)


def _literal_label(domain: Domain, literal: Literal, lang: Lang) -> str:
    return domain.condition(literal.name).label(lang, literal.value)


# --- questions ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class ModelQuestion:
    """One question about the action model: ``kind`` is one of ``KINDS``; ``action`` is the
    action asked about (the first of the pair for ``order``), ``other`` the second action of
    an ``order`` question, ``literal`` the condition asked about."""

    kind: QuestionKind
    action: str = ""
    literal: Literal | None = None
    other: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", QuestionKind(self.kind))  # ValueError for an unknown kind

    def to_json(self) -> dict[str, str]:
        """As the session journal stores it."""
        return {"kind": self.kind, "action": self.action, "other": self.other,
                "literal": str(self.literal) if self.literal is not None else ""}

    @classmethod
    def from_json(cls, data: dict[str, str]) -> ModelQuestion:
        literal = data.get("literal")
        return cls(QuestionKind(data["kind"]), data.get("action", ""), Literal.parse(literal) if literal else None,
                   data.get("other", ""))

    def text(self, domain: Domain, lang: Lang = Lang.EN) -> str:
        """The question in plain words from the domain's labels, with the expected answers."""
        act = _q(domain.action(self.action).label(lang), lang) if self.action else ""
        cond = _q(_literal_label(domain, self.literal, lang), lang) if self.literal is not None else ""
        if self.kind is QuestionKind.TIMING:
            return m.ASK_TIMING(lang, act=act, cond=cond)
        if self.kind is QuestionKind.EFFECTS:
            return m.ASK_EFFECTS(lang, act=act)
        if self.kind is QuestionKind.ACHIEVER:
            return m.ASK_ACHIEVER(lang, cond=cond)
        if self.kind is QuestionKind.ORDER:
            return m.ASK_ORDER(lang, act=act, other=_q(domain.action(self.other).label(lang), lang))
        if self.kind is QuestionKind.NEVER:
            assert self.literal is not None
            return m.ASK_NEVER(lang, act=act, opposite=_q(_literal_label(domain, self.literal.negated(), lang), lang))
        raise ValueError(f"unknown question kind {self.kind!r}")


@dataclass(frozen=True)
class RepairStep:
    question: str
    answer: str
    change: str


@dataclass(frozen=True)
class RepairReport:
    """A repair run: the outcome before any question, each question with its answer and what
    it changed, the outcome after, and the repaired model."""

    before: PlanOutcome
    steps: tuple[RepairStep, ...]
    after: PlanOutcome
    model: Domain

    @property
    def questions(self) -> int:
        return len(self.steps)


def _candidates(domain: Domain, goal: Sequence[Literal], refused: set[Literal]) -> list[ModelQuestion]:
    """Every question that could help, most useful first (see the module docstring)."""
    result: list[ModelQuestion] = []
    for action in domain.actions:  # PA-BT refuses a model with any of these, so they come first
        both = [lit for lit in action.pre if lit in action.ram]
        if len(both) == 1:
            result.append(ModelQuestion(QuestionKind.TIMING, action.name, both[0]))
        elif both:
            result.append(ModelQuestion(QuestionKind.EFFECTS, action.name))
    reached = reachable(domain)
    unreached = {Literal(n, v) for n in domain.condition_names for v in (True, False)} - reached
    idle = [a for a in domain.actions if not a.ram]
    for literal, consumer in needed(domain, goal):
        if literal in reached:
            continue
        makers = achievers(domain, literal)
        if not makers:
            if literal in refused:
                if consumer:
                    result.append(ModelQuestion(QuestionKind.NEVER, consumer, literal))
                continue
            if len(idle) == 1:
                result.append(ModelQuestion(QuestionKind.EFFECTS, idle[0].name))
            result.append(ModelQuestion(QuestionKind.ACHIEVER, literal=literal))
            continue
        circular = [a for a in makers if literal in requires(domain, a, unreached)]
        if len(circular) < len(makers):
            continue  # some achiever is blocked by another gap, which is asked about on its own
        if idle and literal not in refused:
            result.append(ModelQuestion(QuestionKind.ACHIEVER, literal=literal))
        for achiever in circular:
            for pre in achiever.pre:
                if pre not in unreached:
                    continue
                for other in achievers(domain, pre):
                    if other.name != achiever.name and literal in requires(domain, other, unreached):
                        pair = sorted((achiever, other), key=lambda a: a.id)
                        result.append(ModelQuestion(QuestionKind.ORDER, pair[0].name, other=pair[1].name))
    if not result:  # PA-BT fails for a reason not seen above (effects undoing each other): ask what each does
        result = [ModelQuestion(QuestionKind.EFFECTS, a.name) for a in domain.actions]
    return result


# --- answers -----------------------------------------------------------------------------------


def _word(answer: str, kinds: Sequence[str]) -> str | None:
    """Which of the answer words ``kinds`` the answer is, None if none."""
    key = normalize(answer)
    for kind in kinds:
        if key in _WORDS[kind]:
            return kind
    return None


def _unknown(answer: str, offered: Sequence[str], lang: Lang) -> UnknownPhrase:
    close = difflib.get_close_matches(answer.strip().lower(), offered, n=1, cutoff=0.0)
    return UnknownPhrase(answer.strip(), close or list(offered[:1]), lang)


def _offered(kinds: Sequence[str], lang: Lang) -> list[str]:
    return [_SHOWN[k](lang) for k in kinds]


class _Conditions:
    """Condition phrases a teacher may type: the labels (true and untrue, en and de) and names."""

    def __init__(self, domain: Domain):
        self._map: dict[str, Literal] = {}
        self._shown: dict[str, list[str]] = {"en": [], "de": []}
        for cond in domain.conditions:
            spelled = re.sub(r"(?<!^)(?=[A-Z])", " ", cond.name)
            for value in (True, False):
                for lang in ("en", "de"):
                    label = cond.label(lang, value)
                    self._shown[lang].append(label)
                    self._add(label, Literal(cond.name, value))
                for prefix in ("",) if value else ("not ", "nicht "):
                    self._add(prefix + cond.name, Literal(cond.name, value))
                    self._add(prefix + spelled, Literal(cond.name, value))

    def _add(self, phrase: str, literal: Literal) -> None:
        key = normalize(phrase)
        if key:
            self._map.setdefault(key, literal)

    def parse(self, text: str, lang: Lang) -> list[Literal]:
        """All conditions in an answer like "the ball is in the bin and the ball is not in my hand"."""
        whole = self._one(text)
        if whole is not None:
            return [whole]
        literals: list[Literal] = []
        for chunk in _LIST_SPLIT.split(text):
            if not normalize(chunk):
                continue
            literal = self._one(chunk)
            if literal is None:
                key = normalize(chunk)
                close = difflib.get_close_matches(key, self._map, n=1, cutoff=0.45)
                suggestion = [self.pretty(self._map[close[0]], lang)] if close else self._shown[lang][:1]
                raise UnknownPhrase(chunk.strip(), suggestion, lang)
            literals.append(literal)
        return literals

    def _one(self, text: str) -> Literal | None:
        key = normalize(text)
        if key in self._map:
            return self._map[key]
        close = difflib.get_close_matches(key, self._map, n=2, cutoff=0.85)
        if close and (len(close) == 1 or self._map[close[0]] == self._map[close[1]]):
            return self._map[close[0]]  # a clear typo
        return None

    def pretty(self, literal: Literal, lang: Lang) -> str:
        for label in self._shown[lang]:
            if self._map.get(normalize(label)) == literal:
                return label
        return str(literal)


# --- the repair itself -------------------------------------------------------------------------


class ModelRepair:
    """A teacher's action model, a goal and a question budget: plans with PA-BT, picks the
    most useful question about what keeps the model from giving a usable tree, and changes
    the model by the answer. Only ``ask`` spends the budget, and it never asks beyond it."""

    def __init__(self, model: Domain, budget: QuestionBudget, goal: Sequence[Literal] | None = None,
                 true_model: Domain | None = None, lang: Lang = Lang.EN):
        self.model = model
        self.budget = budget
        self.goal = tuple(model.goal if goal is None else goal)
        self.true_model = true_model
        self.lang = lang
        self.asked: list[ModelQuestion] = []
        self._refused: set[Literal] = set()  # conditions the teacher said no action makes true
        self._conditions = _Conditions(model)
        self._phrases = PhraseBook(model)
        self._outcome: PlanOutcome | None = None

    def plan(self) -> PlanOutcome:
        """PA-BT on the current model; see ``PlanOutcome``."""
        if self._outcome is None:
            self._outcome = plan_model(self.model, self.goal, self.true_model)
        return self._outcome

    def next_question(self) -> ModelQuestion | None:
        """The most useful question not asked yet, or None when the model is usable, the budget
        is spent or nothing is left to ask. Asks nothing by itself (see ``ask``)."""
        if self.budget.left <= 0 or self.plan().usable:
            return None
        return next((q for q in _candidates(self.model, self.goal, self._refused) if q not in self.asked), None)

    def ask(self) -> ModelQuestion | None:
        """Ask the next question: spends one question of the budget."""
        question = self.next_question()
        if question is not None:
            self.budget.spend()
            self.asked.append(question)
        return question

    def text(self, question: ModelQuestion, lang: Lang | None = None) -> str:
        return question.text(self.model, lang or self.lang)

    def apply(self, question: ModelQuestion, answer: str) -> str:
        """Change the model as the answer says and return a sentence saying what changed.
        Raises ``UnknownPhrase`` (one line, with a suggestion) for an answer it cannot read,
        leaving the model as it was."""
        change = _APPLIERS[question.kind](self, question, answer)
        self._outcome = None
        if question not in self.asked:
            self.asked.append(question)
        return change

    # --- one method per kind of question: parse the answer, change the model, say what changed

    def _apply_timing(self, question: ModelQuestion, answer: str) -> str:
        word = _word(answer, ("before", "after", "both", "neither"))
        if word is None:
            raise _unknown(answer, _offered(("before", "after", "both", "neither"), self.lang), self.lang)
        action, literal = self.model.action(question.action), question.literal
        assert literal is not None
        act, cond = self._act(action.name), self._cond(literal)
        if word == "after":
            self._set(action, pre=_without(action.pre, literal))
            return m.SO_MAKES_TRUE_NOT_BEFORE(self.lang, act=act, cond=cond)
        if word == "neither":
            self._set(action, pre=_without(action.pre, literal), ram=_without(action.ram, literal))
            return m.SO_UNRELATED(self.lang, act=act, cond=cond)
        self._set(action, ram=_without(action.ram, literal))
        if word == "both":
            return m.SO_BEFORE_AND_STAYS(self.lang, act=act, cond=cond)
        return m.SO_BEFORE(self.lang, act=act, cond=cond)

    def _apply_effects(self, question: ModelQuestion, answer: str) -> str:
        action = self.model.action(question.action)
        literals = [] if _word(answer, ("nothing",)) else self._conditions.parse(answer, self.lang)
        effects = tuple(dict.fromkeys(literals))
        clash = next((lit for lit in effects if lit.negated() in effects), None)
        if clash is not None:
            raise UnknownPhrase(answer.strip(), [self._conditions.pretty(clash, self.lang)], self.lang)
        effects = tuple(sorted(effects, key=lambda lit: self.model.index(lit.name)))
        dropped = [p for p in action.pre if p in effects]
        self._set(action, pre=tuple(p for p in action.pre if p not in effects), ram=effects)
        act = self._act(action.name)
        if not effects:
            return m.SO_CHANGES_NOTHING(self.lang, act=act)
        said = m.SO_AFTER(self.lang, act=act, made=self._list(effects))
        if dropped:
            said += m.NEED_NOT_HOLD_BEFORE(self.lang, conds=self._list(dropped))
        return said

    def _apply_achiever(self, question: ModelQuestion, answer: str) -> str:
        literal = question.literal
        assert literal is not None
        cond = self._cond(literal)
        if _word(answer, ("nothing",)):
            self._refused.add(literal)
            return m.SO_NOTHING_MAKES(self.lang, cond=cond)
        action = self.model.action(self._one_action(answer))
        ram = tuple(r for r in action.ram if r != literal.negated())
        self._set(action, pre=_without(action.pre, literal), ram=ram if literal in ram else ram + (literal,))
        self._refused.discard(literal)
        said = m.SO_MAKES_TRUE(self.lang, act=self._act(action.name), cond=cond)
        if literal in action.pre:
            said += m.IT_NEED_NOT_HOLD_BEFORE(self.lang)
        return said

    def _apply_order(self, question: ModelQuestion, answer: str) -> str:
        pair = (question.action, question.other)
        if _word(answer, ("either",)):
            firsts = list(pair)
        else:
            first = self._one_action(answer)
            if first not in pair:
                raise UnknownPhrase(answer.strip(), [self._act_plain(n) for n in pair], self.lang)
            firsts = [first]
        unreached = {Literal(n, v) for n in self.model.condition_names for v in (True, False)} - \
            reachable(self.model)
        dropped: list[tuple[str, Literal]] = []
        for first in firsts:
            second = pair[1] if first == pair[0] else pair[0]
            action = self.model.action(first)
            gone = [p for p in action.pre if p in unreached and second in needs_actions(self.model, p, unreached)]
            if gone:
                self._set(action, pre=tuple(p for p in action.pre if p not in gone))
                dropped += [(first, p) for p in gone]
        if not dropped:
            return m.CHANGES_NOTHING_KNOWN(self.lang)
        parts = [m.DOES_NOT_NEED(self.lang, act=self._act(a), cond=self._cond(p)) for a, p in dropped]
        return m.SO_LIST(self.lang, parts="; ".join(parts))

    def _apply_never(self, question: ModelQuestion, answer: str) -> str:
        word = _word(answer, ("yes", "no"))
        if word is None:
            raise _unknown(answer, _offered(("yes", "no"), self.lang), self.lang)
        action, literal = self.model.action(question.action), question.literal
        assert literal is not None
        act, cond = self._act(action.name), self._cond(literal)
        if word == "no":
            return m.SO_CANNOT_BE_DONE(self.lang, act=act, cond=cond)
        self._set(action, pre=_without(action.pre, literal))
        return m.SO_DOES_NOT_NEED(self.lang, act=act, cond=cond)

    # --- helpers

    def _one_action(self, answer: str) -> str:
        tokens = [t for t in self._phrases.parse(answer, self.lang) if t.kind == "action"]
        if len(tokens) != 1:
            raise UnknownPhrase(answer.strip(), [a.label(self.lang) for a in self.model.actions][:1], self.lang)
        return tokens[0].name

    def _set(self, action: ActionDef, pre: tuple[Literal, ...] | None = None,
             ram: tuple[Literal, ...] | None = None) -> None:
        changed = replace(action, pre=action.pre if pre is None else pre, ram=action.ram if ram is None else ram)
        actions = tuple(changed if a.name == action.name else a for a in self.model.actions)
        self.model = Domain(self.model.name, self.model.conditions, actions, self.model.goal, self.model.path)

    def _act(self, name: str) -> str:
        return _q(self._act_plain(name), self.lang)

    def _act_plain(self, name: str) -> str:
        return self.model.action(name).label(self.lang)

    def _cond(self, literal: Literal) -> str:
        return _q(_literal_label(self.model, literal, self.lang), self.lang)

    def _list(self, literals: Iterable[Literal]) -> str:
        return m.AND(self.lang).join(self._cond(lit) for lit in literals)


_APPLIERS: dict[QuestionKind, Callable[[ModelRepair, ModelQuestion, str], str]] = {
    QuestionKind.TIMING: ModelRepair._apply_timing, QuestionKind.EFFECTS: ModelRepair._apply_effects,
    QuestionKind.ACHIEVER: ModelRepair._apply_achiever, QuestionKind.ORDER: ModelRepair._apply_order,
    QuestionKind.NEVER: ModelRepair._apply_never,
}


def _without(literals: tuple[Literal, ...], literal: Literal) -> tuple[Literal, ...]:
    return tuple(x for x in literals if x != literal)


# --- the oracle teacher and the loop ------------------------------------------------------------


class ModelOracle:
    """A teacher who knows the true action model and answers model questions with what they
    would type."""

    def __init__(self, true_domain: Domain):
        self.true_domain = true_domain

    def answer(self, question: ModelQuestion, lang: Lang = Lang.EN) -> str:
        true = self.true_domain
        if question.kind is QuestionKind.TIMING:
            action, literal = true.action(question.action), question.literal
            before, after = literal in action.pre, literal in action.ram
            word = "both" if before and after else "before" if before else "after" if after else "neither"
            return _SHOWN[word](lang)
        if question.kind is QuestionKind.EFFECTS:
            ram = true.action(question.action).ram
            if not ram:
                return m.WORD_NOTHING(lang)
            return m.AND(lang).join(_literal_label(true, lit, lang) for lit in ram)
        if question.kind is QuestionKind.ACHIEVER:
            assert question.literal is not None
            makers = achievers(true, question.literal)
            return makers[0].label(lang) if makers else m.WORD_NOTHING(lang)
        if question.kind is QuestionKind.ORDER:
            everything = {Literal(n, True) for n in true.condition_names}  # what the empty start lacks
            first, second = true.action(question.action), true.action(question.other)
            first_waits = depends_on(true, first, second.name, everything)
            second_waits = depends_on(true, second, first.name, everything)
            if first_waits == second_waits:
                return m.WORD_EITHER(lang)
            return (second if first_waits else first).label(lang)
        if question.kind is QuestionKind.NEVER:
            needed = question.literal in true.action(question.action).pre
            return (m.WORD_NO if needed else m.WORD_YES)(lang)
        raise ValueError(f"unknown question kind {question.kind!r}")


def repair(model_domain: Domain, budget: QuestionBudget, oracle: ModelOracle, lang: Lang = Lang.EN) -> RepairReport:
    """Ask and apply until the model is usable, the budget is spent or nothing is left to ask."""
    session = ModelRepair(model_domain, budget, true_model=oracle.true_domain, lang=lang)
    before = session.plan()
    steps = []
    while (question := session.ask()) is not None:
        text = session.text(question)
        answer = oracle.answer(question, lang)
        steps.append(RepairStep(text, answer, session.apply(question, answer)))
    return RepairReport(before, tuple(steps), session.plan(), session.model)
