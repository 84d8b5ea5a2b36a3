"""A recorded session as a rich summary: what was demonstrated, asked, learned and replayed.

Pure functions over ``teach.observe.reader.RecordingContents`` (which ``read_recording`` reads
back with rerun) and the session's runs as ``.btlog`` files (``RunRecord``, read with
``read_runs``), so the terminal prints them and tests compare their text.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from rich.console import Group, RenderableType
from rich.panel import Panel
from rich.table import Table
from rich.text import Text
from rich.tree import Tree

from teach.bt.btcpp_status import BtStatus
from teach.bt.btlog import read_btlog
from teach.bt.nodes import Action, Status, walk
from teach.bt.render import STYLES, render_tree
from teach.bt.xml import tree_from_xml
from teach.errors import TeachError
from teach.observe.btlog_writer import run_logs
from teach.observe.reader import DemoRecord, GenerationRecord, GraphRecord, QuestionRecord, RecordingContents


@dataclass(frozen=True)
class RunRecord:
    """One run of the learned tree as its ``.btlog`` file tells it."""

    path: Path
    outcome: str
    """"success" or "failure" (the root finished so), "stopped" (halted while running)."""
    actions: tuple[str, ...]
    """The actions started, in order."""
    seconds: float
    changes: int


def read_runs(recording: Path) -> list[RunRecord]:
    """The runs the session wrote beside ``recording`` (``recordings/<session>/run-NNN.btlog``)."""
    return [_run(path) for path in run_logs(recording.parent / recording.stem)]


def _run(path: Path) -> RunRecord:
    log = read_btlog(path)
    nodes = list(walk(tree_from_xml(log.xml, path)))
    actions = {uid for uid, node in enumerate(nodes, 1) if isinstance(node, Action)}
    outcome = "stopped"
    started = []
    for transition in log.transitions:
        if transition.uid == 1 and transition.status in (BtStatus.SUCCESS, BtStatus.FAILURE):
            outcome = transition.status.name.lower()
        elif transition.uid in actions and transition.status is BtStatus.RUNNING:
            started.append(log.names[transition.uid])
    seconds = log.transitions[-1].time_us / 1e6 if log.transitions else 0.0
    return RunRecord(path, outcome, tuple(started), seconds, len(log.transitions))


def summary(contents: RecordingContents, runs: Sequence[RunRecord] = (), step: int | None = None,
            tick: int | None = None, dialogue: bool = False) -> Group:
    """Everything a researcher reviews, in session order within each section, each event with
    its place on the recording's timelines ("step 5 · tick 20": ``--step 5`` or ``--tick 20``
    shows the tree there); with ``step`` or ``tick``, also the tree there coloured by each node's
    status; with ``dialogue``, every line said, last (a study reads what the teacher typed)."""
    parts: list[RenderableType] = [_header(contents)]
    parts += [Text("\nDemonstrations", style="bold underline")]
    parts += [_demonstration(d, contents.conditions) for d in contents.demonstrations] or [Text("  none")]
    parts += [Text("\nQuestions", style="bold underline"), _questions(contents)]
    parts += [Text("\nTree generations", style="bold underline"), _generations(contents)]
    if contents.learner_events:
        parts += [Text("\nLearner events", style="bold underline"), _learner_events(contents)]
    if contents.ticks:
        parts += [Text("\nTicks", style="bold underline"), _ticks(contents)]
    if step is not None:
        parts += [Text(f"\nTree at step {step}", style="bold underline"), step_tree(contents, step)]
    if tick is not None:
        parts += [Text(f"\nTree at tick {tick}", style="bold underline"), tick_tree(contents, tick)]
    parts += [Text("\nRuns (.btlog files for Groot2)", style="bold underline"), _runs(runs)]
    parts += [Text("\nFinal tree", style="bold underline"), _final_tree(contents)]
    parts += [Text("\nReplay", style="bold underline"), _replay(contents)]
    parts += [Text("\nStudy figures", style="bold underline"), study_figures(contents, runs)]
    if dialogue:
        parts += [Text("\nDialogue", style="bold underline"), _dialogue(contents)]
    return Group(*parts)


def _header(contents: RecordingContents) -> Panel:
    steps = [line.step for line in contents.dialogue if line.step is not None] + \
        [t.step for t in contents.ticks if t.step is not None]
    counts = [_count(len(contents.demonstrations), "demonstration"), _count(len(contents.questions), "question"),
              _count(len(contents.generations), "tree generation"), _count(len(contents.ticks), "tick"),
              _count(len(contents.externals), "external action")]
    lines = [f"session {contents.session} · domain {contents.domain_name or '(not recorded)'}", " · ".join(counts),
             f"{_count(contents.scene_frames, 'scene frame')} · {_count(contents.camera_frames, 'camera image')}"
             + (f" · timelines step {min(steps)}–{max(steps)}" if steps else "")
             + (f", tick 0–{contents.last_moment}" if contents.last_moment else "")]
    return Panel("\n".join(lines), title=str(contents.path), expand=False)


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}{'' if number == 1 else 's'}"


def where(step: int | None, moment: int | None) -> str:
    """An event's place on the timelines, as ``--step`` and ``--tick`` take them."""
    return " · ".join(part for part in ("" if step is None else f"step {step}",
                                        "" if moment is None else f"tick {moment}") if part)


def _at(step: int | None, moment: int | None) -> Text:
    shown = where(step, moment)
    return Text(f"[{shown}] " if shown else "", style="cyan")


def _demonstration(demo: DemoRecord, conditions: tuple[str, ...]) -> RenderableType:
    robot = [a for a in demo.actions if a not in ("goal", "external")]
    ending = "goal reached" if demo.reached_goal else "no goal line"
    title = Text.assemble(_at(demo.step, demo.moment), (demo.name, "bold"),
                          f": {' → '.join(robot) or '(no actions)'} ({ending})")
    table = Table(box=None, padding=(0, 2), show_header=True, header_style="dim")
    table.add_column("#", justify="right")
    table.add_column("state (true conditions)")
    table.add_column("action")
    for number, (state, action) in enumerate(zip(demo.states, demo.actions, strict=False), 1):
        true = [name for name, value in zip(conditions, state, strict=False) if value] if conditions else \
            ["".join("1" if v else "0" for v in state)]
        style = "magenta" if action == "external" else "green" if action == "goal" else ""
        table.add_row(str(number), " ".join(true) or "—", Text(action, style=style))
    return Group(title, table)


def _questions(contents: RecordingContents) -> RenderableType:
    """Each question as a paragraph (a table squeezes a long question into a narrow column)."""
    if not contents.questions:
        return Text("  none asked")
    parts: list[RenderableType] = []
    for number, q in enumerate(contents.questions, 1):
        left = f" ({q.budget_left} left)" if q.budget_left >= 0 else ""
        parts.append(Text.assemble(f"  {number}. ", _at(q.step, q.moment), q.question, (left, "dim")))
        if q.answer is None:
            parts.append(Text("     → (unanswered)", style="dim"))
        else:
            parts.append(Text.assemble("     → ", _at(q.answer_step, q.answer_moment), (q.answer, "bold"),
                                       f": {q.change}" if q.change else ""))
    return Group(*parts)


def _dialogue(contents: RecordingContents) -> RenderableType:
    """Every line of the session as it was said, the teacher's and the robot's, in order."""
    if not contents.dialogue:
        return Text("  none recorded")
    return Group(*(Text.assemble("  ", _at(line.step, line.moment),
                                 (f"{line.speaker}: ", "bold" if line.speaker == "teacher" else "dim"), line.text)
                   for line in contents.dialogue))


_EVENTS = {"specialize": "from a demonstration", "answer": "from an answer"}


def generation_reason(contents: RecordingContents, generation: GenerationRecord) -> str:
    """Why a generation was saved, from what the recording shows just before it in its turn: the
    latest demonstration or answer ("the first tree" for the first), else the session's reason."""
    first = "the first tree, " if generation is contents.generations[0] else ""
    if generation.step is None or generation.moment is None:
        return first + generation.reason
    causes: list[tuple[int, int, str]] = []  # (moment, answers after demonstrations at one moment, words)
    for demo in contents.demonstrations:
        if demo.step == generation.step and demo.moment is not None and demo.moment <= generation.moment:
            causes.append((demo.moment, 0, f"from demonstration {demo.name}"))
    for number, q in enumerate(contents.questions, 1):
        if q.answer_step == generation.step and q.answer_moment is not None and q.answer_moment <= generation.moment:
            causes.append((q.answer_moment, 1, f"from the answer to question {number} ({q.answer})"))
    if causes:
        return first + max(causes)[2]
    return first + generation.reason.split(": ", 1)[-1]


def _generations(contents: RecordingContents) -> RenderableType:
    if not contents.generations:
        return Text("  none")
    table = Table(box=None, padding=(0, 2), header_style="dim")
    for column in ("generation", "nodes", "step", "tick", "why"):
        table.add_column(column)
    for g in contents.generations:
        table.add_row(str(g.generation), str(g.nodes), "" if g.step is None else str(g.step),
                      "" if g.moment is None else str(g.moment), generation_reason(contents, g))
    return table


def _learner_events(contents: RecordingContents) -> RenderableType:
    """Which learner learned what, in order, each at its place on the timelines."""
    lines = []
    for number, e in enumerate(contents.learner_events, 1):
        shown = [name for name in e.removed if name not in e.detail]  # the detail often names them already
        removed = f"  removed: {', '.join(shown)}" if shown else ""
        who = f"{e.learner}, {_EVENTS.get(e.event, e.event)}" if e.learner else e.event
        lines.append(Text.assemble(f"  {number}. ", _at(e.step, e.moment), (who, "bold"), f": {e.detail}{removed}"))
    return Group(*lines)


_MAX_RUNS = 20


def _ticks(contents: RecordingContents) -> RenderableType:
    """What the ticks did, run-length encoded: the action that ran (or the root's status), how
    often, and from which tick on (``--tick N`` shows the tree there)."""
    runs: list[list] = []
    for tick in contents.ticks:
        what = tick.action or tick.status
        if runs and runs[-1][0] == what:
            runs[-1][1] += 1
        else:
            runs.append([what, 1, tick.moment])
    shown = " → ".join((f"{what} ×{count}" if count > 1 else what) + ("" if at is None else f" (tick {at})")
                       for what, count, at in runs[:_MAX_RUNS])
    more = f" → … ({len(runs) - _MAX_RUNS} more)" if len(runs) > _MAX_RUNS else ""
    return Text(f"  {_count(len(contents.ticks), 'tick')}: {shown}{more}")


def _final_tree(contents: RecordingContents) -> RenderableType:
    xml = contents.final_tree_xml
    if not xml:
        return Text("  no tree was recorded")
    return render_tree(tree_from_xml(xml, contents.path))


def _replay(contents: RecordingContents) -> RenderableType:
    if not contents.replays:
        return Text("  no replay was recorded")
    last = contents.replays[-1]
    mode = "lenient" if last.lenient else "strict"
    history = " → ".join(f"{r.reproduced}/{r.total}" for r in contents.replays)
    return Text(f"  reproduced {last.reproduced}/{last.total} demonstrations ({mode}); over the session: {history}")


# --- the tree at one step ---------------------------------------------------------------------

_STATUS_STYLES = {status.name: style for status, style in STYLES.items()}
_RUNNING_ACTION = "bold black on yellow"


def tick_tree(contents: RecordingContents, moment: int) -> RenderableType:
    """The tree at ``moment`` of the ``tick`` timeline as the viewer shows it: at a tick, the tree
    that ran coloured by that tick; at any other moment, the current generation, nothing ticked."""
    last = contents.last_moment
    if not 0 <= moment <= last:
        raise TeachError(f"--tick {moment} is outside the recording (its ticks: 0–{last})", contents.path)
    tick = contents.tick_at(moment)
    if tick is not None:
        index = contents.ticks.index(tick)
        statuses = {node: status for node, (_, status) in zip(tick.nodes, tick.trace, strict=True)}
        note = Text(f"  tick {moment} (step {tick.step}): the tree that ran, root {tick.status}"
                    + (f", running {tick.action}" if tick.action else ""))
        graph_at = contents.tick_graphs[index]
        if graph_at >= 0:
            return Group(note, _graph_tree(contents.graphs[graph_at], statuses), _legend())
    earlier = [g for g in contents.generation_graphs if g.moment is not None and g.moment <= moment]
    if not earlier:
        return Text(f"  no tree yet at tick {moment}", style="dim")
    generation = [g for g in contents.generations if g.moment is not None and g.moment <= moment]
    name = f"generation {generation[-1].generation}" if generation else "the current generation"
    return Group(Text(f"  no tick at tick {moment}: {name} as it stood, nothing ticked", style="dim"),
                 _graph_tree(earlier[-1], {}), _legend())


def session_steps(contents: RecordingContents) -> list[int]:
    """Every step something was logged at, in order."""
    steps = {line.step for line in contents.dialogue} | {t.step for t in contents.ticks} | \
        {g.step for g in contents.generations}
    return sorted(s for s in steps if s is not None)


def step_tree(contents: RecordingContents, step: int) -> RenderableType:
    """The tree at ``step`` as the viewer's graph shows it, each node coloured by its status in
    the step's last tick (success green, failure red, running yellow, not ticked dim; the
    running action highlighted); labels as the session logged them, in its language."""
    steps = session_steps(contents)
    if not steps or not steps[0] <= step <= steps[-1]:
        shown = f"{steps[0]}–{steps[-1]}" if steps else "none"
        raise TeachError(f"--step {step} is outside the recording (its steps: {shown})", contents.path)
    ticked = [i for i, tick in enumerate(contents.ticks) if tick.step == step]
    if ticked:
        tick = contents.ticks[ticked[-1]]
        graph_at = contents.tick_graphs[ticked[-1]]
        statuses = {node: status for node, (_, status) in zip(tick.nodes, tick.trace, strict=True)}
        note = Text(f"  last of {len(ticked)} tick{'s' if len(ticked) != 1 else ''} at step {step}: "
                    f"root {tick.status}" + (f", running {tick.action}" if tick.action else ""))
    else:
        earlier = [g for g in contents.generation_graphs if g.step is not None and g.step <= step]
        if not earlier:
            return Text(f"  no tree yet at step {step}", style="dim")
        return Group(Text(f"  no tick at step {step}: the tree as it stood, nothing ticked", style="dim"),
                     _graph_tree(earlier[-1], {}), _legend())
    if graph_at < 0:
        return Text(f"  no tree yet at step {step}", style="dim")
    return Group(note, _graph_tree(contents.graphs[graph_at], statuses), _legend())


def _graph_tree(graph: GraphRecord, statuses: dict[int, str]) -> Tree:
    kids: dict[int, list[int]] = {}
    parents: set[int] = set()
    for parent, child in graph.edges:
        kids.setdefault(parent, []).append(child)
        parents.add(child)
    root = next((i for i in range(len(graph.labels)) if i not in parents), 0)

    def line(node: int) -> Text:
        status = statuses.get(node)
        label = " ".join(graph.labels[node].split())  # the viewer's labels are wrapped to fit its boxes
        if status == Status.RUNNING.name and node not in kids:  # a running leaf: the action the robot does
            return Text(f" {label} ", style=_RUNNING_ACTION)
        return Text(label, style=_STATUS_STYLES.get(status or "", "dim"))

    top = Tree(line(root), guide_style="bright_black")
    stack, seen = [(root, top)], {root}
    while stack:  # each node's children are added in order when it is reached; no cycle is followed
        node, into = stack.pop()
        for kid in kids.get(node, []):
            if kid not in seen:
                seen.add(kid)
                stack.append((kid, into.add(line(kid))))
    return top


def _legend() -> Text:
    return Text.assemble("  ", ("success", "green"), " · ", ("failure", "red"), " · ", ("running", "yellow"),
                         " · ", ("not ticked", "dim"), " · ", (" running action ", _RUNNING_ACTION))


# --- runs and study figures -------------------------------------------------------------------

def _runs(runs: Sequence[RunRecord]) -> RenderableType:
    if not runs:
        return Text("  no run was written")
    table = Table(box=None, padding=(0, 2), header_style="dim")
    for column in ("file", "outcome", "sim s", "changes", "actions started"):
        table.add_column(column)
    for run in runs:
        style = {"success": "green", "failure": "red"}.get(run.outcome, "yellow")
        table.add_row(f"{run.path.parent.name}/{run.path.name}", Text(run.outcome, style=style),
                      f"{run.seconds:.1f}", str(run.changes),
                      " → ".join(run.actions) or "—")
    return table


def _question_effect(contents: RecordingContents, question: QuestionRecord) -> str:
    """Whether the answer gave the tree a new shape: the generation saved at the answer's step
    compared with the one before it."""
    if question.answer is None:
        return "unanswered"
    made = [i for i, g in enumerate(contents.generations) if question.answer_step is not None
            and g.step == question.answer_step]
    if not made:
        return "no new generation"
    new = contents.generations[made[-1]]
    old = contents.generations[made[0] - 1] if made[0] > 0 else None
    if old is not None and old.xml == new.xml:
        return f"tree unchanged (generation {new.generation}, {new.nodes} nodes)"
    before = f"{old.nodes} → " if old is not None else ""
    return f"generation {new.generation}: {before}{new.nodes} nodes"


def study_figures(contents: RecordingContents, runs: Sequence[RunRecord] = ()) -> RenderableType:
    """What a study leader asks afterwards: how the tree grew and how much of what was shown it
    reproduces, generation by generation; which question changed what; how the runs ended."""
    table = Table(box=None, padding=(0, 2), header_style="dim", title_justify="left")
    for column in ("generation", "step", "nodes", "reproduced", "share"):
        table.add_column(column, justify="right")
    for g in contents.generations:
        replay = next((r for r in reversed(contents.replays) if r.step == g.step), None)
        share = f"{100 * replay.reproduced / replay.total:.0f}%" if replay is not None and replay.total else ""
        table.add_row(str(g.generation), "" if g.step is None else str(g.step), str(g.nodes),
                      f"{replay.reproduced}/{replay.total}" if replay is not None else "", share)
    lines: list[RenderableType] = [table if contents.generations else Text("  no tree generation")]
    for number, q in enumerate(contents.questions, 1):
        lines.append(Text(f"  question {number}: {q.change or q.answer or '—'} → {_question_effect(contents, q)}"))
    if runs:
        counts = {outcome: sum(r.outcome == outcome for r in runs) for outcome in ("success", "failure", "stopped")}
        lines.append(Text(f"  runs: {len(runs)} — " + ", ".join(f"{n} {o}" for o, n in counts.items() if n)
                          + f"; over time: {' '.join(r.outcome for r in runs)}"))
    return Group(*lines)
