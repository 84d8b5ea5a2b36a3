"""The session's learner, and everything the session does with what it learns: the tree pruned
for display, the generation files, the next question, updates described in words.

This is the one module that knows which learner the session uses: ``teach.learn.learner``'s
model-based learner (an action model and a goal learned from the transitions, a reactive
tree planned from them). It never refuses a demonstration: a situation shown two ways is a
conflict the robot asks about.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from teach.bt.nodes import Action, Condition, Node, walk
from teach.bt.xml import tree_to_xml
from teach.demos import Demonstration
from teach.dialogue.questions import Answer, Question
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State
from teach.learn.inquiry import next_question
from teach.learn.learner import Learner, Update
from teach.learn.safe_inquiry import unsure_here
from teach.messages import Lang
from teach.observe.hook import Observer
from teach.session.describe import describe_update, explain_node
from teach.session.store import SessionStore

LEARNER_NAMES = {True: "model-based learner (safe)", False: "model-based learner (guessing)"}
"""How the recording names the learner below, by ``safe`` (``teach review`` says which learner learned what)."""
DONE_ABOUT = "done"
"""``asked_about`` of an "is the task done here?" question."""


def make_learner(domain: Domain, safe: bool = True, can_happen: Callable[[State], bool] | None = None) -> Learner:
    return Learner(domain, safe, can_happen)


class Learning:
    """One session's learner with the demonstrations and labels it learned from."""

    def __init__(self, domain: Domain, store: SessionStore, observer: Observer, safe: bool = True,
                 can_happen: Callable[[State], bool] | None = None):
        """``can_happen``: the world's word on which states it can be in; no question is about another."""
        self.domain = domain
        self.safe = safe
        self.can_happen = can_happen
        self.store = store
        self.observer = observer
        self.restart()

    def restart(self) -> None:
        """Forget everything learned (an undo or a resume then learns the journal again)."""
        self.learner = make_learner(self.domain, self.safe, self.can_happen)
        self.demos: list[Demonstration] = []
        self.labels: dict[State, Answer] = {}
        self.asked: set[State] = set()
        self.pruned: Node | None = None
        self.generation = self.store.last_generation()
        self._learned_actions: list[str] = []

    @property
    def knows_goal(self) -> bool:
        """Whether a demonstration has shown where the task ends (the tree's "done" is learned)."""
        return self.learner.goal.known

    @property
    def has_behaviour(self) -> bool:
        """Whether the tree does anything yet (only goal states shown: it does not)."""
        return any(isinstance(node, Action) for node in walk(self.learner.tree))

    @property
    def tree(self) -> Node:
        """The unpruned tree: what runs (pruning assumes actions have only the effects seen so far)."""
        return self.learner.tree

    # --- learning -------------------------------------------------------------------------

    def learn_demonstration(self, demo: Demonstration, source: str | None) -> Update:
        """Learn and keep a demonstration (never refused: contradictions become conflicts)."""
        before = self._actions()
        update = self.learner.update(demo, source=source)
        shown = [self.domain.action(s.action).name for s in demo.steps
                 if s.action not in (GOAL_ACTION, EXTERNAL_ACTION)]
        self._learned_actions = _in_order(self._actions() - before, shown)
        self.demos.append(demo)
        for step in demo.steps:
            if step.action == GOAL_ACTION:
                self.labels[step.state] = None
            elif step.action != EXTERNAL_ACTION:
                self.labels[step.state] = self.domain.action(step.action).name
        return update

    def learn_answer(self, state: State, answer: str | None, source: str, asked_about: str | None = None) -> Update:
        """Learn what to do in an asked-about situation; an answer about a conflict settles it.
        ``asked_about``: the action a "may I still …?" question asked about ("done": "is the task
        done here?"); an answer naming something else says no to it."""
        before = self._actions()
        if any(conflict.state == state for conflict in self.learner.conflicts):
            update = self.learner.resolve(state, answer, source)
        elif asked_about is not None:
            update = self.learner.answer_question(state, None if asked_about == DONE_ABOUT else asked_about, answer,
                                                  source)
        else:
            update = self.learner.teach_step(state, answer, source=source)
        self._learned_actions = _in_order(self._actions() - before, [answer] if answer else [])
        self.labels[state] = answer
        return update

    def next_question(self, seed: int) -> Question | None:
        """The learner's most decisive open situation not asked about yet (``seed``: unused, the
        choice is a pure function of what was learned)."""
        question = next_question(self.learner, self.asked)
        if question is None:
            return None
        shown: tuple[str, ...] = ()
        if question.kind == "conflict":
            conflict = next(c for c in self.learner.conflicts if c.state == question.state)
            shown = tuple(dict.fromkeys("" if answer is None else answer for answer, _ in conflict.labels))
        return Question(question.state, 1.0, expected=((question.tree_does, 1.0),), shown=shown, kind=question.kind,
                        action=question.action, settles=question.settles, like=self._known_from(question.action))

    def question_where_stuck(self, state: State) -> Question | None:
        """The safe learner, stopped in ``state``: what it was unsure of there, as a question."""
        question = unsure_here(self.learner, state) if self.learner.safe else None
        if question is None:
            return None
        return Question(state, 1.0, expected=(("nothing", 1.0),), kind=question.kind, action=question.action,
                        settles=question.settles, like=self._known_from(question.action))

    def _known_from(self, action: str | None) -> str:
        """The step of its kind an action asked about is known from, if it was never done itself."""
        return "" if action is None else self.learner.model[action].known_from

    def rule_out(self, state: State, source: str) -> None:
        """The teacher said the asked-about situation cannot happen: it is never asked again."""
        self.learner.rule_out(state, source)
        self.asked.add(state)

    def _actions(self) -> set[str]:
        return {node.name for node in walk(self.learner.tree) if isinstance(node, Action)}

    # --- results --------------------------------------------------------------------------

    def prune(self) -> Node:
        """The learner's tree pruned for display, using the effects the demonstrations show
        (it behaves as the unpruned tree in every state)."""
        from teach.learn.model import detect_model
        from teach.learn.prune import prune, ramifications_of

        self.pruned = prune(self.learner.tree, ramifications_of(detect_model(self.domain, self.demos)))
        return self.pruned

    def save_generation(self, tree: Node, reason: str) -> Path:
        """Write the next ``gen-NN.xml`` (never overwriting a kept one) and report it."""
        self.generation = self.store.last_generation() + 1
        path = self.store.write_generation(self.generation, tree)
        self.observer.on_tree(self.generation, tree, tree_to_xml(tree), f"generation {self.generation}: {reason}")
        return path

    def describe(self, update: Update, lang: Lang, answered: tuple[Question, str | None] | None = None) -> str:
        return describe_update(update, self._learned_actions, self.domain, lang, answered)

    def report(self, event: str, update: Update, lang: Lang) -> str:
        """Tell the observer what an update changed; returns it in words."""
        change = self.describe(update, lang)
        self.observer.on_learner(event, change, [], learner=LEARNER_NAMES[self.learner.safe])
        return change

    def why(self, name: str, lang: Lang) -> list[str] | None:
        """Why an action or condition is in the tree, one line per reason (None: it is not)."""
        nodes = [n for n in walk(self.learner.tree) if isinstance(n, Action | Condition) and n.name == name]
        lines = [explain_node(self.learner.why(node.uid), self.domain, lang) for node in nodes]
        return list(dict.fromkeys(line for line in lines if line)) or None


def _in_order(new: set[str], shown: list[str]) -> list[str]:
    """The actions new in the tree in the order they were shown (any others after, by name)."""
    ordered = [name for name in dict.fromkeys(shown) if name in new]
    return ordered + sorted(new - set(ordered))
