"""The thesis's evaluation (§6.2–6.4) recomputed from our learners, next to its published figures.

Pure computation: ``evaluate`` returns data (cross-evaluation tables under both replay
readings, node counts before and after pruning, Approach 1 on each study participant's
action model); ``teach table`` renders it. The thesis's numbers below are data to compare
with, copied from its Tables 6.2 and 6.3 and the text of §6.1–6.4.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from teach.bt.nodes import Node, size
from teach.demos import Demonstration, read_demo_set
from teach.domain import Domain, Literal, State, load_domain
from teach.errors import FormatError, LearnError
from teach.replay import count_reproduced
from teach.symbolic import MAX_RUN_STEPS, goal_verdict

SETS = ("delta1", "delta2", "delta3", "delta4", "delta5")
SET_LABELS = {name: f"Δ{name[-1]}" for name in SETS}
PARTICIPANTS = tuple(range(1, 9))

# Table 6.2 (Approach 2, PA-BT with action detection) and Table 6.3 (Approach 3, specialization):
# generated from (row) -> reproduced demonstrations of each tested-on set (columns Δ1..Δ5).
THESIS_TABLE_6_2 = {
    "delta1": (32, 13, 8, 2, 21), "delta2": (26, 34, 8, 2, 43), "delta3": (11, 13, 8, 2, 21),
    "delta4": (6, 8, 5, 2, 13), "delta5": (26, 34, 8, 2, 43),
}
THESIS_TABLE_6_3 = {
    "delta1": (32, 13, 8, 2, 21), "delta2": (26, 34, 8, 2, 43), "delta3": (26, 34, 8, 2, 43),
    "delta4": (21, 29, 5, 2, 35), "delta5": (26, 34, 8, 2, 43),
}
THESIS_SET_SIZES = {"delta1": 32, "delta2": 34, "delta3": 8, "delta4": 2, "delta5": 43}
# Node counts (before, after pruning) from §6.2–6.4; None where the thesis gives none.
THESIS_NODES: dict[tuple[str, str], tuple[int | None, int | None]] = {
    ("approach1", "all five goals"): (24, 16),
    ("approach2", "delta1"): (41, 16), ("approach2", "delta2"): (44, 17),
    ("approach2", "delta3"): (53, 32), ("approach2", "delta4"): (57, 36),
    ("approach2", "delta5"): (44, 17),
    ("approach3", "delta1"): (36, 16), ("approach3", "delta2"): (34, 22),
    ("approach3", "delta3"): (42, 22), ("approach3", "delta4"): (44, 24),
    ("approach3", "delta5"): (34, 22),
}
# Pruned trees the thesis says equal Colledanchise & Ögren's (Fig. 6.8, 6.15, 6.19).
THESIS_EQUALS_COLLEDANCHISE = {("approach1", "all five goals"), ("approach2", "delta1"), ("approach3", "delta1")}
# §6.1: Approach 1 on each participant's table.
THESIS_PARTICIPANTS: dict[int, tuple[bool, str]] = {
    1: (False, "the same condition is precondition and ramification of one action"),
    2: (False, "the same condition is precondition and ramification of one action"),
    3: (False, "actions without ramifications: crucial atomic BTs cannot be generated"),
    4: (True, "usable (Fig. A.2)"),
    5: (True, "usable (Fig. A.3)"),
    6: (False, "actions without ramifications: crucial atomic BTs cannot be generated"),
    7: (True, "usable (Fig. A.4)"),
    8: (True, "usable (Fig. A.5)"),
}

Progress = Callable[[str], None]


@dataclass(frozen=True)
class Cell:
    """One tree tested on one demonstration set, under both replay readings."""

    generated_from: str
    tested_on: str
    strict: int | None   # None: the learner could not learn from ``generated_from``
    lenient: int | None
    total: int
    thesis: int


@dataclass(frozen=True)
class CrossTable:
    """Table 6.2 or 6.3: trees learned from each set, replayed on every set."""

    key: str
    title: str
    cells: tuple[Cell, ...]
    errors: tuple[tuple[str, str], ...] = ()   # (set, why the learner failed on it)

    def cell(self, generated_from: str, tested_on: str) -> Cell:
        return next(c for c in self.cells if c.generated_from == generated_from and c.tested_on == tested_on)

    def matches(self, lenient: bool) -> int:
        """How many cells equal the thesis's under one reading."""
        return sum((c.lenient if lenient else c.strict) == c.thesis for c in self.cells)

    def error(self, generated_from: str) -> str | None:
        return dict(self.errors).get(generated_from)


@dataclass(frozen=True)
class NodeCount:
    approach: str
    source: str
    before: int | None   # None: the learner failed (see ``error``)
    after: int | None
    equals_colledanchise: bool
    thesis_before: int | None
    thesis_after: int | None
    thesis_equals_colledanchise: bool
    error: str | None = None


@dataclass(frozen=True)
class ParticipantResult:
    participant: int
    usable: bool
    reason: str
    nodes: int | None
    thesis_usable: bool
    thesis_reason: str


@dataclass(frozen=True)
class Evaluation:
    table_6_2: CrossTable
    table_6_3: CrossTable
    nodes: tuple[NodeCount, ...]
    participants: tuple[ParticipantResult, ...]


@dataclass(frozen=True)
class Learned:
    """A learner's last generation and its pruned form."""

    tree: Node
    pruned: Node


def work_units() -> int:
    """How many ``progress`` calls ``evaluate`` makes (for a progress bar)."""
    return 1 + 2 * len(SETS) + len(PARTICIPANTS)


def evaluate(demos_root: str | Path = "demos/ball", study: str | Path = "dialogues/study",
             progress: Progress | None = None) -> Evaluation:
    """Recompute the thesis's evaluation from the sets in ``demos_root`` (``delta1``..``delta5``,
    ``domain.toml``, and ``reference/table41.toml``, the action model Approach 1 was run with)
    and the participant files in ``study``."""
    tell = progress or (lambda _label: None)
    demos_root, study = Path(demos_root), Path(study)
    domain = load_domain(demos_root / "domain.toml")
    sets = {name: read_demo_set(demos_root / name, domain)[1] for name in SETS}
    reference = colledanchise_tree(domain)
    nodes: list[NodeCount] = []

    tell("Approach 1 with all five goal conditions")
    hard_coded = load_domain(demos_root / "reference" / "table41.toml")
    every_goal = tuple(Literal(name) for name in hard_coded.condition_names)
    nodes.append(_count("approach1", "all five goals", approach1(hard_coded, every_goal), reference))

    learned: dict[str, dict[str, Learned | str]] = {"approach2": {}, "approach3": {}}
    for approach, learner in (("approach2", approach2), ("approach3", approach3)):
        for name in SETS:
            tell(f"Approach {approach[-1]} on {SET_LABELS[name]}")
            try:
                learned[approach][name] = learner(domain, sets[name])
            except LearnError as error:  # an outcome to report, as the thesis reports unusable tables
                learned[approach][name] = str(error)
            nodes.append(_count(approach, name, learned[approach][name], reference))

    participants = []
    for number in PARTICIPANTS:
        tell(f"Approach 1 on participant {number}")
        participants.append(participant_result(study / f"participant{number}.toml", number))

    return Evaluation(
        cross_table("table_6_2", "Table 6.2: Approach 2 (PA-BT with action and goal detection)",
                    domain, sets, learned["approach2"], THESIS_TABLE_6_2),
        cross_table("table_6_3", "Table 6.3: Approach 3 (action order and BT specialization)",
                    domain, sets, learned["approach3"], THESIS_TABLE_6_3),
        tuple(nodes), tuple(participants))


def colledanchise_tree(domain: Domain) -> Node:
    """Colledanchise & Ögren's tree (Fig. 2.5 without AskForHelp) over ``domain``'s conditions,
    each achieved by the action whose ramification it is, in condition order."""
    from teach.bt.nodes import Action, Condition, Fallback, Sequence

    pairs = []
    for name in domain.condition_names:
        achiever = next((a for a in domain.actions if Literal(name) in a.ram), None)
        if achiever is None:
            raise FormatError(f"no action makes {name} true, so there is no Colledanchise & Ögren tree",
                              domain.path)
        pairs.append(Fallback((Condition(name), Action(achiever.name))))
    return Sequence(tuple(pairs))


def approach1(domain: Domain, goal: tuple[Literal, ...] | None = None) -> Learned:
    """§4.1: PA-BT from the domain's own action model."""
    from teach.learn.pabt import expand
    from teach.learn.prune import prune, ramifications_of

    tree = expand(domain, goal)[-1]
    return Learned(tree, prune(tree, ramifications_of(domain)))


def approach2(domain: Domain, demos: list[Demonstration]) -> Learned:
    """§4.2: PA-BT from the action model and goal detected in the demonstrations."""
    from teach.learn.model import detect_model, learn_detect
    from teach.learn.prune import prune, ramifications_of

    tree = learn_detect(domain, demos)[-1]
    return Learned(tree, prune(tree, ramifications_of(detect_model(domain, demos))))


def approach3(domain: Domain, demos: list[Demonstration]) -> Learned:
    """§4.3: topological action order, then specialization on every demonstration."""
    from teach.learn.model import detect_model
    from teach.learn.prune import prune, ramifications_of
    from teach.learn.specialize import specialize

    tree = specialize(domain, demos).tree
    return Learned(tree, prune(tree, ramifications_of(detect_model(domain, demos))))


def _count(approach: str, source: str, learned: Learned | str, reference: Node) -> NodeCount:
    before, after = THESIS_NODES.get((approach, source), (None, None))
    thesis_equal = (approach, source) in THESIS_EQUALS_COLLEDANCHISE
    if isinstance(learned, str):
        return NodeCount(approach, source, None, None, False, before, after, thesis_equal, learned)
    return NodeCount(approach, source, size(learned.tree), size(learned.pruned), learned.pruned == reference,
                     before, after, thesis_equal)


def cross_table(key: str, title: str, domain: Domain, sets: dict[str, list[Demonstration]],
                learned: dict[str, Learned | str], thesis: Mapping[str, tuple[int, ...]]) -> CrossTable:
    """Each set's pruned tree replayed on every set; a set the learner failed on gives a row
    without figures and its error."""
    from teach.bt.tick import compile_tree

    cells, errors = [], []
    for source in SETS:
        result = learned[source]
        if isinstance(result, str):
            errors.append((source, result))
            cells += [Cell(source, target, None, None, len(sets[target]), thesis[source][column])
                      for column, target in enumerate(SETS)]
            continue
        compiled = compile_tree(result.pruned, domain.condition_names)
        for column, target in enumerate(SETS):
            demos = sets[target]
            cells.append(Cell(source, target, count_reproduced(compiled, domain, demos),
                              count_reproduced(compiled, domain, demos, lenient=True), len(demos),
                              thesis[source][column]))
    return CrossTable(key, title, tuple(cells), tuple(errors))


def participant_result(path: Path, number: int) -> ParticipantResult:
    """Approach 1 on one participant's action model: usable when PA-BT builds a tree and that
    tree, run in the participant's own symbolic world from the state where nothing holds,
    reaches the goal."""
    thesis_usable, thesis_reason = THESIS_PARTICIPANTS[number]
    domain = load_domain(path)
    try:
        learned = approach1(domain)
    except LearnError as error:
        return ParticipantResult(number, False, error.message, None, thesis_usable, thesis_reason)
    start = tuple(False for _ in domain.conditions)
    reached, why = run_to_goal(domain, learned.tree, start)
    return ParticipantResult(number, reached, why, size(learned.tree), thesis_usable, thesis_reason)


def run_to_goal(domain: Domain, tree: Node, start: State) -> tuple[bool, str]:
    """Run ``tree`` in the symbolic world of ``domain``'s action model until it succeeds,
    fails or repeats a state; says which."""
    return goal_verdict(domain, tree, start, MAX_RUN_STEPS)


def as_json(evaluation: Evaluation) -> dict:
    """The evaluation as plain JSON-ready data (keys in a fixed order)."""
    def table(t: CrossTable) -> dict:
        return {"title": t.title,
                "matches_thesis": {"strict": t.matches(False), "lenient": t.matches(True), "cells": len(t.cells)},
                "errors": dict(t.errors),
                "cells": [{"generated_from": c.generated_from, "tested_on": c.tested_on, "strict": c.strict,
                           "lenient": c.lenient, "total": c.total, "thesis": c.thesis} for c in t.cells]}

    return {
        "table_6_2": table(evaluation.table_6_2),
        "table_6_3": table(evaluation.table_6_3),
        "nodes": [{"approach": n.approach, "source": n.source, "before": n.before, "after": n.after,
                   "equals_colledanchise": n.equals_colledanchise, "thesis_before": n.thesis_before,
                   "thesis_after": n.thesis_after, "thesis_equals_colledanchise": n.thesis_equals_colledanchise,
                   "error": n.error}
                  for n in evaluation.nodes],
        "participants": [{"participant": p.participant, "usable": p.usable, "reason": p.reason, "nodes": p.nodes,
                          "thesis_usable": p.thesis_usable, "thesis_reason": p.thesis_reason}
                         for p in evaluation.participants],
    }
