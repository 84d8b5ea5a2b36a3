"""The session manager: a plain state machine that turns teacher lines into replies.

It interleaves demonstrations in a world, online learning after every demonstration,
at most ``budget`` clarifying questions, and runs of the learned tree that the teacher can
interrupt and correct. Every driver (the terminal, scripted replays, bench-teach) feeds lines
to ``handle(line, interrupt)``, which returns every reply of that line in order. A driver that
shows replies while a line is still being handled (steps as they happen, run progress) sets
``live``: it then sees each of those same replies once, as it is produced.

Modes: ``idle`` (waiting for a command or actions), ``demonstrating`` (a demonstration is
open), ``asking`` (a question waits for its answer).
"""

from __future__ import annotations

import shutil
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from teach.bt.nodes import Node, size
from teach.demos import Demonstration, Step, next_demo_path, read_demonstration, write_demonstration
from teach.session.journal import Journal, parse_state_text, state_text
from teach.dialogue.phrases import PhraseBook, UnknownPhrase, normalize
from teach.dialogue.questions import Answer, Question, QuestionBudget, describe_situation, select_question
from teach.world.protocol import TeachingWorld
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, Literal, State
from teach.errors import FormatError, LearnError, TeachError
from teach.observe.hook import Observer

if TYPE_CHECKING:
    from teach.dialogue.model_repair import ModelQuestion, ModelRepair
    from teach.learn.specialize import Update

QUESTIONS_PER_TURN = 2
BLOCKED_WHILE_ASKING = {"demonstrate", "run", "start", "reset", "perturb", "model", "ask"}
MIN_DEMOS_BEFORE_ASKING = 2


@dataclass
class Reply:
    """Something to show: ``kind`` is say, info, error, tree, state or question."""

    kind: str
    text: str = ""
    tree: Node | None = None
    state: dict[str, bool] | None = None


@dataclass
class SessionConfig:
    session: str
    domain: Domain
    lang: str = "en"
    questions: int = 5
    seed: int = 0
    world: str = "mujoco"
    base: Path = Path(".")
    recording: Path | None = None  # the rerun recording, when there is one

    @property
    def demo_dir(self) -> Path:
        return self.base / "demos" / self.session

    @property
    def tree_dir(self) -> Path:
        return self.base / "trees" / self.session

    @property
    def journal_path(self) -> Path:
        return self.base / "recordings" / f"{self.session}.journal.json"


@dataclass
class Command:
    names: tuple[str, ...]
    usage: str
    en: str
    de: str
    handler: Callable[["SessionManager", str], list[Reply]]


@dataclass
class _OpenDemo:
    steps: list[Step] = field(default_factory=list)
    source: str = "demonstration"


def _t(lang: str, en: str, de: str) -> str:
    return de if lang == "de" else en


class SessionManager:
    """One teaching session. Not thread-safe: one driver feeds it lines."""

    def __init__(self, config: SessionConfig, world: TeachingWorld, observer: Observer | None = None,
                 journal: Journal | None = None):
        from teach.learn.specialize import Specializer

        self.config = config
        self.domain = config.domain
        self.world = world
        self.observer = observer or Observer()
        self.lang = config.lang
        self.phrases = PhraseBook(self.domain, world.events)
        self.learner = Specializer(self.domain)
        self.budget = QuestionBudget(config.questions)
        self.demos: list[Demonstration] = []
        self.labels: dict[State, Answer] = {}
        self.asked: set[State] = set()
        self.generation = 0
        self.pruned: Node | None = None
        self.pending: Question | None = None
        self.model_repair: "ModelRepair | None" = None
        self.pending_model: "ModelQuestion | None" = None
        self.planned: Node | None = None
        self.open: _OpenDemo | None = None
        self.finished = False
        self.step = 0
        self.live: Callable[[Reply], None] | None = None  # a driver that shows replies as they are produced
        self._turn: list[Reply] = []
        self._interrupt: Callable[[], bool] | None = None
        self._turn_questions = 0
        self.last_learn_ms = 0.0
        self.journal = journal or Journal(config.session, str(config.domain.path or ""), config.lang,
                                          config.questions, config.world, config.seed)
        config.demo_dir.mkdir(parents=True, exist_ok=True)
        config.tree_dir.mkdir(parents=True, exist_ok=True)
        if self.domain.path is not None and not (config.demo_dir / "domain.toml").exists():
            shutil.copyfile(self.domain.path, config.demo_dir / "domain.toml")
        self.observer.on_domain(self.domain)

    # --- the driver's interface -----------------------------------------------------------

    @property
    def mode(self) -> str:
        if self.pending is not None or self.pending_model is not None:
            return "asking"
        return "demonstrating" if self.open is not None else "idle"

    def greet(self) -> list[Reply]:
        actions = ", ".join(a.label(self.lang) for a in self.domain.actions)
        replies = [Reply("say", _t(self.lang,
                                   f"Hello! Show me how to do the task, one step at a time. I can: {actions}. "
                                   "Say 'done' when the task is finished, 'help' for more.",
                                   f"Hallo! Zeig mir die Aufgabe Schritt für Schritt. Ich kann: {actions}. "
                                   "Sag 'fertig', wenn die Aufgabe erledigt ist, 'hilfe' für mehr."))]
        if self.demos:
            replies.insert(0, Reply("info", _t(self.lang,
                                               f"Resumed session {self.config.session}: {len(self.demos)} demonstrations, "
                                               f"{self.budget.used} questions asked, generation {self.generation}.",
                                               f"Sitzung {self.config.session} fortgesetzt: {len(self.demos)} Vorführungen, "
                                               f"{self.budget.used} Fragen gestellt, Generation {self.generation}.")))
            if self.pruned is not None:
                replies.append(Reply("tree", tree=self.pruned))
        replies.append(self._state_reply())
        self._turn = []
        return self._end_turn(replies)

    def handle(self, line: str, interrupt: Callable[[], bool] | None = None) -> list[Reply]:
        """One teacher line in, every reply to it out, in order. Never raises for bad input.
        ``interrupt`` is polled while the robot runs (the terminal's Ctrl-C)."""
        line = line.strip()
        if not line:
            return []
        self._turn = []
        self._interrupt = interrupt
        self._tick_clock()
        self.observer.on_dialogue("teacher", line, self.budget.left)
        try:
            command, rest = self.command(line)
            answering = command is None or command.names[0] in ("done", "skip")
            if self.pending_model is not None and answering:
                replies = self._answer_model(line)
            elif self.pending is not None and answering:
                replies = self._answer(line)
            elif command is not None and self.mode == "asking" and command.names[0] in BLOCKED_WHILE_ASKING:
                replies = [Reply("error", _t(self.lang, "Please answer my question first (an action, 'done' or 'skip').",
                                             "Bitte beantworte zuerst meine Frage (eine Handlung, 'fertig' oder 'weiter')."))]
            elif command is not None:
                self._turn_questions = 0
                replies = command.handler(self, rest)
            else:
                self._turn_questions = 0
                replies = self._teach_actions(line)
        except UnknownPhrase as unknown:
            replies = [Reply("error", unknown.message)]
        except TeachError as error:
            replies = [Reply("error", str(error))]
        finally:
            self._interrupt = None
        turn = self._end_turn(replies)
        self.observer.checkpoint()
        self.journal.save(self.config.journal_path)  # the step clock too, so a resume goes on from it
        return turn

    def close(self) -> None:
        self.journal.save(self.config.journal_path)
        self.world.close()
        self.observer.close()

    # --- commands --------------------------------------------------------------------------

    def command(self, line: str) -> tuple[Command | None, str]:
        words = line.split(maxsplit=1)
        head = normalize(words[0]) if words else ""
        for command in COMMANDS:
            if head in command.names:
                return command, words[1] if len(words) > 1 else ""
        whole = normalize(line)
        for command in COMMANDS:
            if whole in command.names:
                return command, ""
        return None, line

    def cmd_help(self, rest: str) -> list[Reply]:
        lines = [f"  {c.usage:<28} {_t(self.lang, c.en, c.de)}" for c in COMMANDS]
        actions = "; ".join(self.phrases.phrases(self.lang)[:12])
        intro = _t(self.lang, "Type what the robot should do, e.g. ", "Schreib, was der Roboter tun soll, z. B. ")
        return [Reply("info", intro + f"“{actions}”.\n" + "\n".join(lines))]

    def cmd_demonstrate(self, rest: str) -> list[Reply]:
        replies = []
        if self.open is None:
            self.open = _OpenDemo()
            replies.append(Reply("info", _t(self.lang, "New demonstration. Show me the steps.",
                                            "Neue Vorführung. Zeig mir die Schritte.")))
        if rest.strip():
            replies += self._teach_actions(rest)
        return replies

    def cmd_done(self, rest: str) -> list[Reply]:
        if self.open is None or not self.open.steps:
            return [Reply("error", _t(self.lang, "You have not shown me any steps yet.",
                                      "Du hast mir noch keine Schritte gezeigt."))]
        state = self.world.state()
        unmet = self._unmet_goal(state)
        if unmet:
            return [Reply("error", _t(self.lang, f"The task is not finished yet: {unmet}. Show me more, or say 'cancel'.",
                                      f"Die Aufgabe ist noch nicht erledigt: {unmet}. Zeig mir mehr, oder sag 'abbrechen'."))]
        self.open.steps.append(Step(state, GOAL_ACTION, len(self.open.steps) + 1))
        return self._finish_demo()

    def cmd_cancel(self, rest: str) -> list[Reply]:
        self.open = None
        return [Reply("info", _t(self.lang, "Demonstration discarded.", "Vorführung verworfen."))]

    def cmd_undo(self, rest: str) -> list[Reply]:
        if self.open is not None and self.open.steps:
            last = self.open.steps.pop()
            self.world.arrange(last.state)
            if not self.open.steps:
                self.open = None
            return [Reply("info", _t(self.lang, "Undone: the last step.", "Rückgängig: der letzte Schritt.")),
                    self._state_reply()]
        if not self.demos:
            return [Reply("error", _t(self.lang, "Nothing to undo.", "Nichts rückgängig zu machen."))]
        self.pending = self.pending_model = None  # a question stays paid for, but it is about what is undone
        self.journal.add(self.config.journal_path, kind="undo")
        self._rebuild_from_journal()
        head = self._flush([Reply("info", _t(self.lang, "Undone: the last demonstration or answer.",
                                             "Rückgängig: die letzte Vorführung oder Antwort."))])
        return head + self._after_learning(ask=False)

    def cmd_perturb(self, rest: str) -> list[Reply]:
        tokens = self.phrases.parse(rest, self.lang) if rest.strip() else []
        events = [t for t in tokens if t.kind == "event"]
        if not events:
            names = ", ".join(en[0] for en, _ in self.world.events.values())
            return [Reply("error", _t(self.lang, f"Which event? I know: {names}.", f"Welches Ereignis? Ich kenne: {names}."))]
        return self._teach_actions(rest)

    def cmd_run(self, rest: str) -> list[Reply]:
        # the unpruned tree runs: pruning assumes actions have only the effects seen so far
        tree = self.learner.tree if self.learner.order else self.planned
        if tree is None:
            return [Reply("error", _t(self.lang, "I have not learned anything yet: show me first.",
                                      "Ich habe noch nichts gelernt: zeig es mir zuerst."))]
        stop_after = _number(rest, self.lang)
        if self.open is not None and self.open.steps:
            return [Reply("error", _t(self.lang, "Finish ('done') or cancel the open demonstration first.",
                                      "Beende ('fertig') oder verwirf zuerst die laufende Vorführung."))]
        self.open = None
        result = self.world.run(tree, max_actions=4 * len(self.domain.actions) + 4, interrupt=self._interrupt,
                                stop_after=stop_after,
                                on_action=lambda a: self._flush([Reply("info", f"→ {self.domain.action(a).label(self.lang)}")]))
        unmet = self._unmet_goal(self.world.state())
        if not result.steps and result.outcome == "success" and not unmet:
            return [Reply("say", _t(self.lang, "There is nothing to do: the task is already finished. "
                                    "Say 'reset' for a new start.",
                                    "Es gibt nichts zu tun: die Aufgabe ist schon erledigt. Sag 'neu' für einen neuen Start."))]
        done = ", ".join(self.domain.action(a).label(self.lang) for _, a in result.steps) or "-"
        replies = [Reply("info", _t(self.lang, f"I did: {done}.", f"Ich habe gemacht: {done}."))]
        if result.outcome == "success" and not unmet:
            replies.append(Reply("say", _t(self.lang, "Done! The task is finished.", "Fertig! Die Aufgabe ist erledigt.")))
            return replies + [self._state_reply()]
        if result.outcome == "interrupted":
            message = _t(self.lang, "Stopped. Show me how to go on from here, then say 'done'.",
                         "Angehalten. Zeig mir, wie es von hier weitergeht, dann sag 'fertig'.")
        elif result.outcome == "success":
            message = _t(self.lang, f"I thought I was done, but {unmet}. Show me how to go on, then say 'done'.",
                         f"Ich dachte, ich bin fertig, aber {unmet}. Zeig mir, wie es weitergeht, dann sag 'fertig'.")
        else:
            message = _t(self.lang, f"I got stuck ({result.outcome}). Show me how to go on, then say 'done'.",
                         f"Ich komme nicht weiter ({result.outcome}). Zeig mir, wie es weitergeht, dann sag 'fertig'.")
        # what the robot did so far and what the teacher shows next become one corrective demonstration
        self.open = _OpenDemo([Step(s, self.domain.action(a).id, i + 1) for i, (s, a) in enumerate(result.steps)],
                              source="correction")
        return replies + [Reply("say", message), self._state_reply()]

    def cmd_stop(self, rest: str) -> list[Reply]:
        return [Reply("info", _t(self.lang, "The robot is not running.", "Der Roboter läuft gerade nicht."))]

    def cmd_show(self, rest: str) -> list[Reply]:
        if self.pruned is None and self.planned is not None:
            return [Reply("tree", tree=self.planned)]
        if self.pruned is None:
            return [Reply("info", _t(self.lang, "No tree yet.", "Noch kein Baum."))]
        tree = self.learner.tree if normalize(rest) in ("full", "ganz", "all") else self.pruned
        return [Reply("tree", tree=tree)]

    def cmd_state(self, rest: str) -> list[Reply]:
        return [self._state_reply()]

    def cmd_start(self, rest: str) -> list[Reply]:
        if self.open is not None and self.open.steps:
            return [Reply("error", _t(self.lang, "Finish or cancel the open demonstration first.",
                                      "Beende oder verwirf zuerst die laufende Vorführung."))]
        names = [w for w in rest.replace(",", " ").split() if w]
        for name in names:
            if not self.domain.has_condition(name):
                raise TeachError(f"unknown condition {name!r} (known: {', '.join(self.domain.condition_names)})")
        self.world.arrange(self.domain.state(names))
        return [self._state_reply()]

    def cmd_reset(self, rest: str) -> list[Reply]:
        if self.open is not None and self.open.steps:
            return [Reply("error", _t(self.lang, "Finish or cancel the open demonstration first.",
                                      "Beende oder verwirf zuerst die laufende Vorführung."))]
        self.open = None
        self.world.reset(_number(rest, self.lang))
        return [self._state_reply()]

    def cmd_ask(self, rest: str) -> list[Reply]:
        if self.model_repair is not None and not self.model_repair.plan().usable:
            return self._ask_model()
        replies = self._maybe_ask(force=True)
        return replies or [Reply("info", self._no_question_text())]

    def cmd_skip(self, rest: str) -> list[Reply]:
        return [Reply("info", _t(self.lang, "No question is open.", "Es ist keine Frage offen."))]

    def cmd_why(self, rest: str) -> list[Reply]:
        name = rest.strip()
        if self.pruned is None:
            return [Reply("info", _t(self.lang, "No tree yet.", "Noch kein Baum."))]
        from teach.bt.nodes import Action, Condition, walk
        if self.domain.has_action(name) and name in self.learner.order:
            action = next(n for n in walk(self.learner.tree) if isinstance(n, Action) and n.name == name)
            lines = [self.learner.explain(action.uid)]
            for guard in self.learner.guards(name):
                lines.append(f"({_literals_label(str(guard), self.domain, self.lang)}): "
                             f"{self.learner.explain(guard.uid)}")
            return [Reply("info", "\n".join(f"- {line}" for line in lines))]
        matches = [n for n in walk(self.learner.tree) if isinstance(n, Condition) and n.name == name]
        if not matches:
            return [Reply("error", _t(self.lang, f"No action or condition named {name!r} in the tree.",
                                      f"Keine Handlung oder Bedingung namens {name!r} im Baum."))]
        return [Reply("info", "\n".join(f"- {self.learner.explain(n.uid)}" for n in matches))]

    def cmd_save(self, rest: str) -> list[Reply]:
        self.journal.save(self.config.journal_path)
        self.observer.checkpoint()
        places = [self.config.demo_dir, self.config.tree_dir, self.config.journal_path]
        if self.config.recording is not None:
            places.append(self.config.recording)
        where = ", ".join(map(str, places))
        return [Reply("info", _t(self.lang, f"Saved: {where}.", f"Gespeichert: {where}."))]

    def cmd_quit(self, rest: str) -> list[Reply]:
        self.finished = True
        replies = self.cmd_save(rest)
        return replies + [Reply("say", _t(self.lang, "Goodbye! Resume with: teach session --resume "
                                          f"{self.config.session}", "Auf Wiedersehen! Weiter mit: teach session "
                                          f"--resume {self.config.session}"))]

    # --- action definitions (the thesis's Approach 1, repaired by questions) ---------------

    def cmd_model(self, rest: str) -> list[Reply]:
        from teach.dialogue.model_repair import ModelRepair
        from teach.domain import load_domain

        path = Path(rest.strip())
        if not rest.strip():
            return [Reply("error", _t(self.lang, "Which file? model FILE.toml", "Welche Datei? model DATEI.toml"))]
        model = load_domain(path)
        if model.condition_names != self.domain.condition_names or \
                not set(model.action_names) <= set(self.domain.action_names):
            raise TeachError(f"its conditions and actions must be those of {self.domain.path}", path)
        self.model_repair = ModelRepair(model, self.budget, lang=self.lang)
        self.pending_model = None
        self.journal.add(self.config.journal_path, kind="model", file=str(path.resolve()))
        return self._show_plan(ask=True)

    def cmd_plan(self, rest: str) -> list[Reply]:
        if self.model_repair is None:
            return [Reply("error", _t(self.lang, "No action definitions yet: load them with 'model FILE'.",
                                      "Noch keine Handlungsbeschreibungen: lade sie mit 'model DATEI'."))]
        return self._show_plan(ask=False)

    def _show_plan(self, ask: bool) -> list[Reply]:
        """What the action definitions give; after a change (``ask``) the tree is saved as a
        generation and, while it is not usable, the next repair question is asked."""
        assert self.model_repair is not None
        outcome = self.model_repair.plan()
        if outcome.usable and outcome.tree is not None:
            self.planned = outcome.tree
            if ask:
                self._save_generation(outcome.tree, "planned from the action definitions")
            return [Reply("say", _t(self.lang, "I can build a behaviour from these definitions.",
                                    "Aus diesen Beschreibungen kann ich ein Verhalten bauen.")),
                    Reply("tree", tree=outcome.tree)]
        replies = [Reply("say", _t(self.lang, f"I cannot build a behaviour from these definitions yet: {outcome.reason}",
                                   f"Aus diesen Beschreibungen kann ich noch kein Verhalten bauen: {outcome.reason}"))]
        return replies + (self._ask_model() if ask else [])

    def _ask_model(self) -> list[Reply]:
        assert self.model_repair is not None
        if self.budget.left <= 0:
            return [Reply("info", self._no_question_text())]
        question = self.model_repair.ask()
        if question is None:
            return [Reply("info", _t(self.lang, "I do not know what else to ask.", "Ich weiß nicht, was ich noch fragen soll."))]
        self.pending_model = question
        self.journal.add(self.config.journal_path, kind="asked", model_question=_question_data(question))
        text = self.model_repair.text(question, self.lang)
        self.observer.on_question(text, self.budget.left)
        return [Reply("question", text)]

    def _answer_model(self, line: str) -> list[Reply]:
        assert self.model_repair is not None and self.pending_model is not None
        question = self.pending_model
        text = self.model_repair.text(question, self.lang)
        if normalize(line) in SKIP_WORDS:
            self.pending_model = None
            self.observer.on_answer(text, line, "nothing (skipped)")
            self.journal.add(self.config.journal_path, kind="model_answer", question=_question_data(question), answer="skip")
            return [Reply("info", _t(self.lang, "All right. Say 'ask' for another question.",
                                     "In Ordnung. Sag 'frag' für eine andere Frage."))]
        change = self.model_repair.apply(question, line)  # UnknownPhrase keeps the question open
        self.pending_model = None
        self.observer.on_answer(text, line, change)
        self.journal.add(self.config.journal_path, kind="model_answer", question=_question_data(question), answer=line)
        return [Reply("info", _t(self.lang, f"Thank you. {change}", f"Danke. {change}"))] + self._show_plan(ask=True)

    # --- demonstrations ---------------------------------------------------------------------

    def _teach_actions(self, text: str) -> list[Reply]:
        tokens = self.phrases.parse(text, self.lang)
        replies: list[Reply] = []
        if self.open is None:
            replies += self._flush(self.cmd_demonstrate(""))
        assert self.open is not None
        for token in tokens:
            if token.kind == "event":
                result = self.world.perturb(token.name)
                self.open.steps.append(Step(result.before, EXTERNAL_ACTION, len(self.open.steps) + 1))
                self.observer.on_external(token.name)
                replies += self._flush([Reply("info", _t(self.lang, f"Event: {token.text}.", f"Ereignis: {token.text}."))])
                continue
            result = self.world.act(token.name)
            label = self.domain.action(token.name).label(self.lang)
            if not result.ok:
                replies.append(Reply("error", _t(self.lang, f"I could not {label}: {result.message}",
                                                 f"„{label}“ ging nicht: {result.message}")))
                break
            if result.after == result.before:
                # a step that changes nothing would teach two different actions in one state
                replies += self._flush([Reply("info", _t(self.lang, f"✓ {label} (nothing changed: not recorded)",
                                                         f"✓ {label} (nichts hat sich geändert: nicht aufgezeichnet)"))])
                continue
            self.open.steps.append(Step(result.before, self.domain.action(token.name).id, len(self.open.steps) + 1))
            replies += self._flush([Reply("info", f"✓ {label}")])
        replies.append(self._state_reply())
        return replies

    def _finish_demo(self) -> list[Reply]:
        assert self.open is not None
        started = time.perf_counter()
        path = next_demo_path(self.config.demo_dir)
        demo = Demonstration(path.stem, tuple(self.open.steps), path)
        source = path.name
        try:
            update = self.learner.update(demo, source=source)
        except LearnError as error:
            self.open.steps.pop()  # the goal line: the demonstration stays open to be mended
            return [Reply("error", _t(self.lang, f"I cannot learn this demonstration: {_why(error, 'en')} "
                                      "Say 'undo' to take back steps, or 'cancel'.",
                                      f"Diese Vorführung kann ich nicht lernen: {_why(error, 'de')} "
                                      "Sag 'zurück', um Schritte zurückzunehmen, oder 'abbrechen'.")),
                    Reply("info", f"({error.message})")]
        write_demonstration(path, demo)
        self.open = None
        self._remember(demo)
        self.observer.on_demonstration(demo.name, demo, self.domain)
        self.observer.on_learner("specialize", _describe_update(update, self.domain, self.lang), _removed_names(update))
        replies = self._after_learning(ask=True, started=started,
                                       events=[{"kind": "demo", "file": path.name, "source": source}])
        return replies

    def import_demonstrations(self, demos: list[Demonstration]) -> list[Reply]:
        """Learn demonstrations recorded elsewhere (one generation for all of them)."""
        self._turn = []
        started = time.perf_counter()
        events = []
        for demo in demos:
            path = next_demo_path(self.config.demo_dir)
            source = f"imported {demo.name} ({path.name})"
            self.learner.update(demo, source=source)
            write_demonstration(path, demo)
            self._remember(demo)
            events.append({"kind": "demo", "file": path.name, "source": source})
            self.observer.on_demonstration(demo.name, demo, self.domain)
        return self._end_turn(self._after_learning(ask=False, started=started, events=events))

    # --- questions --------------------------------------------------------------------------

    def _maybe_ask(self, force: bool = False) -> list[Reply]:
        """Ask the best question if the budget allows; unforced, at most QUESTIONS_PER_TURN in a row."""
        if self.budget.left <= 0 or self.pending is not None:
            return []
        if not force and (len(self.demos) < MIN_DEMOS_BEFORE_ASKING or self._turn_questions >= QUESTIONS_PER_TURN):
            return []
        question = self.next_question()
        if question is None:
            return []
        self.budget.spend()
        self._turn_questions += 1
        self.pending = question
        self.asked.add(question.state)
        self.journal.add(self.config.journal_path, kind="asked", state=state_text(question.state))
        text = question.text(self.domain, self.lang)
        self.observer.on_question(text, self.budget.left)
        options = " / ".join([a.label(self.lang) for a in self.domain.actions] +
                             [_t(self.lang, "done", "fertig"), _t(self.lang, "skip", "weiter")])
        return [Reply("question", f"{text}\n   ({options})")]

    def next_question(self) -> Question | None:
        return select_question(self.learner, self.demos, self.labels, self.asked, self.config.seed)

    def _answer(self, line: str) -> list[Reply]:
        question = self.pending
        assert question is not None
        key = normalize(line)
        if key in SKIP_WORDS:
            self.pending = None
            self.journal.add(self.config.journal_path, kind="answer", state=state_text(question.state),
                             answer="skip", question=question.text(self.domain, self.lang))
            self.observer.on_answer(question.text(self.domain, self.lang), line, "nothing (skipped)")
            return [Reply("info", _t(self.lang, "All right, I keep being careful there.",
                                     "In Ordnung, da bleibe ich vorsichtig."))]
        if key in DONE_WORDS:
            answer: str | None = None
        else:
            tokens = [t for t in self.phrases.parse(line, self.lang) if t.kind == "action"]
            if len(tokens) != 1:
                return [Reply("error", _t(self.lang, "Please answer with one action, 'done' or 'skip'.",
                                          "Bitte antworte mit einer Handlung, 'fertig' oder 'weiter'."))]
            answer = tokens[0].name
        return self.apply_answer(answer, line)

    def apply_answer(self, answer: str | None, said: str) -> list[Reply]:
        """Learn from the answer to the pending question (None: the task is done there)."""
        question = self.pending
        assert question is not None
        started = time.perf_counter()
        text = question.text(self.domain, self.lang)
        source = f"answer to question {self.budget.used}"
        self.pending = None
        try:
            update = self.learner.teach_step(question.state, answer, source=source)
        except LearnError as error:
            return [Reply("error", _t(self.lang, f"That contradicts what you showed me: {_why(error, 'en')}",
                                      f"Das widerspricht dem Gezeigten: {_why(error, 'de')}")),
                    Reply("info", f"({error.message})")]
        self.labels[question.state] = answer
        change = _describe_update(update, self.domain, self.lang)
        self.observer.on_answer(text, said, change)
        self.observer.on_learner("answer", change, _removed_names(update))
        head = self._flush([Reply("info", _t(self.lang, f"Thank you. {change}", f"Danke. {change}"))])
        event = {"kind": "answer", "state": state_text(question.state), "answer": answer or "done", "question": text}
        return head + self._after_learning(ask=True, started=started, events=[event])

    def _no_question_text(self) -> str:
        if self.budget.left <= 0:
            return _t(self.lang, "I have used all my questions.", "Ich habe alle meine Fragen gestellt.")
        return _t(self.lang, "I have no question right now.", "Ich habe gerade keine Frage.")

    # --- learning results -------------------------------------------------------------------

    def _after_learning(self, ask: bool, started: float | None = None, events: Sequence[dict] = ()) -> list[Reply]:
        """Prune, save the generation, then commit ``events`` to the journal (so a journalled
        event always has its generation on disk), then show, replay and maybe ask."""
        from teach.replay import replay

        if not self.learner.order:  # only goal states so far: there is no behaviour to show yet
            if events:
                self.journal.events.extend(events)
                self.journal.save(self.config.journal_path)
            return self._flush([Reply("info", _t(self.lang, "I have seen the finished task, but no steps yet.",
                                                 "Ich habe die erledigte Aufgabe gesehen, aber noch keine Schritte."))])
        self.pruned = self._prune()
        path = self._save_generation(self.pruned, "learned from demonstrations and answers")
        if events:
            self.journal.events.extend(events)
            self.journal.save(self.config.journal_path)
        report = replay(self.pruned, self.domain, self.demos)
        self.observer.on_replay(report.reproduced, report.total)
        summary = _t(self.lang,
                     f"Generation {self.generation}: {size(self.pruned)} nodes "
                     f"({size(self.learner.tree)} before pruning), saved as {path}. "
                     f"I reproduce {report.reproduced} of {report.total} demonstrations.",
                     f"Generation {self.generation}: {size(self.pruned)} Knoten "
                     f"({size(self.learner.tree)} vor dem Beschneiden), gespeichert als {path}. "
                     f"Ich kann {report.reproduced} von {report.total} Vorführungen nachmachen.")
        replies = self._flush([Reply("tree", tree=self.pruned), Reply("info", summary)])
        if started is not None:
            self.last_learn_ms = (time.perf_counter() - started) * 1000
        if ask:
            replies += self._maybe_ask()
        return replies

    def _prune(self) -> Node:
        """The learner's tree pruned for display, using the effects the demonstrations show
        (it behaves as the unpruned tree in every state)."""
        from teach.learn.model import detect_model
        from teach.learn.prune import prune, ramifications_of

        return prune(self.learner.tree, ramifications_of(detect_model(self.domain, self.demos)))

    def _save_generation(self, tree: Node, reason: str) -> Path:
        """Write the next ``gen-NN.xml`` atomically and report it to the observer."""
        from teach.bt.xml import tree_to_xml, write_tree

        self.generation = _last_generation(self.config.tree_dir) + 1  # never overwrite a kept generation
        path = self.config.tree_dir / f"gen-{self.generation:02d}.xml"
        write_tree(path, tree)
        self.observer.on_tree(self.generation, tree, tree_to_xml(tree), f"generation {self.generation}: {reason}")
        return path

    # --- resume -----------------------------------------------------------------------------

    def _rebuild_from_journal(self) -> None:
        """Re-learn everything in the journal (after an undo or on resume), deterministically."""
        try:
            self._replay_journal()
        except (KeyError, TypeError, ValueError, AttributeError) as error:
            raise FormatError(f"the session journal is damaged ({type(error).__name__}: {error})",
                              self.config.journal_path) from None

    def _replay_journal(self) -> None:
        from teach.learn.specialize import Specializer

        self.learner = Specializer(self.domain)
        self.demos, self.labels, self.asked = [], {}, set()
        self.model_repair, self.pending_model, self.planned = None, None, None
        # every question asked stays paid for, even when what it was about is undone
        self.budget = QuestionBudget(self.config.questions,
                                     sum(1 for e in self.journal.events if e["kind"] == "asked"))
        self.generation = _last_generation(self.config.tree_dir)
        answered = 0
        for event in _effective_events(self.journal.events):
            if event["kind"] == "demo":
                demo = read_demonstration(self.config.demo_dir / event["file"], self.domain)
                self.learner.update(demo, source=event.get("source"))
                self._remember(demo)
            elif event["kind"] == "model":
                from teach.dialogue.model_repair import ModelRepair
                from teach.domain import load_domain

                self.model_repair = ModelRepair(load_domain(event["file"]), self.budget, lang=self.lang)
            elif event["kind"] == "model_answer" and self.model_repair is not None:
                from teach.dialogue.model_repair import ModelQuestion

                if event["answer"] != "skip":
                    data = dict(event["question"])
                    literal = Literal.parse(data.pop("literal")) if data.get("literal") else None
                    self.model_repair.apply(ModelQuestion(literal=literal, **data), event["answer"])
            elif event["kind"] == "answer":
                answered += 1
                state = parse_state_text(event["state"])
                if len(state) != len(self.domain.conditions):
                    raise ValueError(f"an answered state has {len(state)} values, not {len(self.domain.conditions)}")
                self.asked.add(state)
                if event["answer"] != "skip":
                    answer = None if event["answer"] == "done" else event["answer"]
                    try:
                        self.learner.teach_step(state, answer, source=f"answer to question {answered}")
                        self.labels[state] = answer
                    except LearnError:
                        pass  # it was rejected when it was given, too
        self.pruned = self._prune() if self.learner.order else None
        if self.model_repair is not None:
            outcome = self.model_repair.plan()
            self.planned = outcome.tree if outcome.usable else None

    @classmethod
    def resume(cls, config: SessionConfig, world: TeachingWorld, observer: Observer | None = None) -> "SessionManager":
        journal = Journal.load(config.journal_path)
        manager = cls(config, world, observer, journal)
        manager._rebuild_from_journal()
        manager.step = journal.step + 1  # a step of its own: the kill may have come before the save
        manager.observer.set_time(manager.step)
        current = manager.pruned or manager.planned
        if current is not None:
            from teach.bt.xml import tree_to_xml

            manager.observer.on_tree(manager.generation, current, tree_to_xml(current), "resumed")
        if manager.demos:
            last = manager.demos[-1].steps[-1].state
            world.arrange(last)
        return manager

    # --- helpers ---------------------------------------------------------------------------

    def _remember(self, demo: Demonstration) -> None:
        """Keep a learned demonstration and what it says about each of its situations."""
        self.demos.append(demo)
        for step in demo.steps:
            if step.action == GOAL_ACTION:
                self.labels[step.state] = None
            elif step.action != EXTERNAL_ACTION:
                self.labels[step.state] = self.domain.action(step.action).name

    def _unmet_goal(self, state: State) -> str:
        """The domain's goal conditions that do not hold, in words ("" when the goal holds)."""
        missing = [lit for lit in self.domain.goal if not self.domain.holds(lit, state)]
        return _t(self.lang, " and ", " und ").join(self.domain.condition(lit.name).label(self.lang, not lit.value)
                                                    for lit in missing)

    def _state_reply(self) -> Reply:
        state = self.world.state()
        return Reply("state", describe_situation(self.domain, state, self.lang),
                     state=dict(zip(self.domain.condition_names, state)))

    def _tick_clock(self) -> None:
        self.step += 1
        self.journal.step = self.step
        self.observer.set_time(self.step)

    def _flush(self, replies: list[Reply]) -> list[Reply]:
        """The one way a reply leaves the session: told to the observer, added to the line's
        replies and shown by a live driver at once (the tree appears before a question is
        chosen). Returns nothing left to hand back."""
        self._say_all(replies)
        self._turn.extend(replies)
        if self.live is not None:
            for reply in replies:
                self.live(reply)
        return []

    def _end_turn(self, replies: list[Reply]) -> list[Reply]:
        """Send the last replies and hand back all of this turn's, in the order they were sent."""
        self._flush(replies)
        turn, self._turn = self._turn, []
        return turn

    def _say_all(self, replies: list[Reply]) -> None:
        for reply in replies:
            if reply.kind in ("say", "info", "error") and reply.text:  # questions go to on_question
                self.observer.on_dialogue("robot", reply.text, self.budget.left)


_WHY = {
    "contradiction": ("in the same situation you once showed one thing and once another.",
                      "in derselben Lage hast du einmal das eine und einmal etwas anderes gezeigt."),
    "repeated": ("it does the same step twice; I can only learn each step once in a task.",
                 "darin kommt ein Schritt zweimal vor; ich kann jeden Schritt nur einmal lernen."),
    "order": ("it does the steps in another order than before.",
              "darin kommen die Schritte in einer anderen Reihenfolge vor als vorher."),
}


def _why(error: LearnError, lang: str) -> str:
    """A learner's refusal in the teacher's words (the details follow for the facilitator)."""
    if error.kind in _WHY:
        en, de = _WHY[error.kind]
        return de if lang == "de" else en
    return error.message


def _last_generation(folder: Path) -> int:
    """The highest ``gen-NN.xml`` number in a folder (0 when there is none)."""
    numbers = [int(p.stem[4:]) for p in folder.glob("gen-*.xml") if p.stem[4:].isdecimal()]
    return max(numbers, default=0)


def _number(text: str, lang: str) -> int | None:
    """An optional whole number argument ("run 3", "reset 7")."""
    if not text.strip():
        return None
    try:
        value = int(text.strip())
    except ValueError:
        raise TeachError(_t(lang, f"expected a whole number, not {text.strip()!r}",
                            f"erwartet eine ganze Zahl, nicht {text.strip()!r}")) from None
    if value < 0:
        raise TeachError(_t(lang, "the number cannot be negative", "die Zahl darf nicht negativ sein"))
    return value


def _question_data(question: "ModelQuestion") -> dict:
    return {"kind": question.kind, "action": question.action, "other": question.other,
            "literal": str(question.literal) if question.literal is not None else ""}


def _effective_events(events: list[dict]) -> list[dict]:
    """The journal's learning events with every undone one removed."""
    kept: list[dict] = []
    for event in events:
        if event["kind"] == "undo":
            if kept:
                kept.pop()
        elif event["kind"] in ("demo", "answer", "model", "model_answer"):
            kept.append(event)
    return kept


def _describe_update(update: "Update", domain: Domain, lang: str) -> str:
    """What an update changed, in the teacher's words."""
    parts: list[str] = []
    if update.inserted:
        steps = " → ".join(domain.action(a).label(lang) for a in update.inserted)
        parts.append(_t(lang, f"I learned the steps {steps}", f"ich habe die Schritte {steps} gelernt"))
    for action in dict.fromkeys(c.action for c in update.removed if c.action not in update.inserted):
        when = [_literals_label(c.text, domain, lang) for c in update.removed if c.action == action]
        label = domain.action(action).label(lang)
        parts.append(_t(lang, f"now I will {label} also when {' or '.join(when)}",
                        f"jetzt mache ich „{label}“ auch, wenn gilt: {' oder '.join(when)}"))
    for change in update.added:
        label = domain.action(change.action).label(lang)
        parts.append(_t(lang, f"I will not {label} when {_literals_label(change.text, domain, lang)}",
                        f"ich mache „{label}“ nicht, wenn gilt: {_literals_label(change.text, domain, lang)}"))
    if not parts:
        return _t(lang, "That is what I would have done anyway.", "Das hätte ich sowieso getan.")
    text = "; ".join(parts)
    return text[0].upper() + text[1:] + "."


def _literals_label(text: str, domain: Domain, lang: str) -> str:
    """"!BallFound & BinClose" → "you cannot see the ball and the bin is within reach"."""
    labels = []
    for part in text.split("&"):
        literal = Literal.parse(part)
        labels.append(domain.condition(literal.name).label(lang, literal.value) if domain.has_condition(literal.name)
                      else part.strip())
    return _t(lang, " and ", " und ").join(labels)


def _removed_names(update: "Update") -> list[str]:
    return [change.text for change in update.removed]


DONE_WORDS = {"done", "finished", "nothing", "nothing task is done", "fertig", "nichts", "ziel erreicht"}
SKIP_WORDS = {"skip", "dont know", "don t know", "i dont know", "i don t know", "weiter", "weiss nicht",
              "ich weiss nicht", "keine ahnung", "uberspringen"}

COMMANDS: list[Command] = [
    Command(("help", "hilfe", "h"), "help", "show this help", "diese Hilfe zeigen", SessionManager.cmd_help),
    Command(("demonstrate", "demo", "zeigen", "vorfuhren"), "demonstrate [steps]", "start a demonstration",
            "eine Vorführung beginnen", SessionManager.cmd_demonstrate),
    Command(("done", "fertig"), "done", "the task is finished: learn this demonstration",
            "die Aufgabe ist erledigt: diese Vorführung lernen", SessionManager.cmd_done),
    Command(("cancel", "abbrechen"), "cancel", "discard the open demonstration", "die Vorführung verwerfen",
            SessionManager.cmd_cancel),
    Command(("undo", "ruckgangig", "zuruck"), "undo", "undo the last step, demonstration or answer",
            "letzten Schritt, Vorführung oder Antwort zurücknehmen", SessionManager.cmd_undo),
    Command(("perturb", "storen", "ereignis"), "perturb EVENT", "something happens (an external action)",
            "etwas passiert (äußeres Ereignis)", SessionManager.cmd_perturb),
    Command(("run", "los", "ausfuhren"), "run [N]", "let the robot do the task (N: stop after N actions)",
            "den Roboter die Aufgabe machen lassen", SessionManager.cmd_run),
    Command(("stop", "halt"), "stop / Ctrl-C", "interrupt the robot", "den Roboter anhalten", SessionManager.cmd_stop),
    Command(("show", "zeige", "baum"), "show [full]", "show the learned tree", "den gelernten Baum zeigen",
            SessionManager.cmd_show),
    Command(("state", "zustand"), "state", "show the current situation", "die aktuelle Lage zeigen",
            SessionManager.cmd_state),
    Command(("start", "situation"), "start COND ...", "put the world in a situation (named conditions true)",
            "die Welt in eine Lage bringen", SessionManager.cmd_start),
    Command(("reset", "neu"), "reset [SEED]", "new random start", "neuer zufälliger Start", SessionManager.cmd_reset),
    Command(("ask", "frag", "frage"), "ask", "let the robot ask a question", "den Roboter fragen lassen",
            SessionManager.cmd_ask),
    Command(("model", "modell"), "model FILE", "load action definitions (pre/ram) and plan with them",
            "Handlungsbeschreibungen laden und damit planen", SessionManager.cmd_model),
    Command(("plan", "planen"), "plan", "show what the action definitions give", "zeigen, was die Beschreibungen ergeben",
            SessionManager.cmd_plan),
    Command(("skip", "weiter"), "skip", "leave a question unanswered", "eine Frage offen lassen",
            SessionManager.cmd_skip),
    Command(("why", "warum"), "why NAME", "why a node is in the tree", "warum ein Knoten im Baum ist",
            SessionManager.cmd_why),
    Command(("save", "speichern"), "save", "save everything now", "alles jetzt speichern", SessionManager.cmd_save),
    Command(("quit", "exit", "beenden", "tschuss"), "quit / Ctrl-D", "save and leave", "speichern und beenden",
            SessionManager.cmd_quit),
]
