"""A recorded session as a rich summary: what was demonstrated, asked, learned and replayed.

Pure functions over ``teach.observe.reader.RecordingContents`` (which ``read_recording`` reads
back with rerun), so the terminal prints them and tests compare their text.
"""

from __future__ import annotations

from rich.console import Group, RenderableType
from rich.panel import Panel
from rich.table import Table
from rich.text import Text

from teach.bt.render import render_tree
from teach.bt.xml import tree_from_xml
from teach.observe.reader import DemoRecord, RecordingContents


def summary(contents: RecordingContents) -> Group:
    """Everything a researcher reviews, in session order within each section."""
    parts: list[RenderableType] = [_header(contents)]
    parts += [Text("\nDemonstrations", style="bold underline")]
    parts += [_demonstration(d, contents.conditions) for d in contents.demonstrations] or [Text("  none")]
    parts += [Text("\nQuestions", style="bold underline"), _questions(contents)]
    parts += [Text("\nTree generations", style="bold underline"), _generations(contents)]
    if contents.learner_events:
        parts += [Text("\nLearner events", style="bold underline"), _learner_events(contents)]
    if contents.ticks:
        parts += [Text("\nTicks", style="bold underline"), _ticks(contents)]
    parts += [Text("\nFinal tree", style="bold underline"), _final_tree(contents)]
    parts += [Text("\nReplay", style="bold underline"), _replay(contents)]
    return Group(*parts)


def _header(contents: RecordingContents) -> Panel:
    steps = [line.step for line in contents.dialogue if line.step is not None] + \
        [t.step for t in contents.ticks if t.step is not None]
    counts = [_count(len(contents.demonstrations), "demonstration"), _count(len(contents.questions), "question"),
              _count(len(contents.generations), "tree generation"), _count(len(contents.ticks), "tick"),
              _count(len(contents.externals), "external action")]
    lines = [f"session {contents.session} · domain {contents.domain_name or '(not recorded)'}", " · ".join(counts),
             f"{_count(contents.scene_frames, 'scene frame')} · {_count(contents.camera_frames, 'camera image')}"
             + (f" · steps {min(steps)}–{max(steps)}" if steps else "")]
    return Panel("\n".join(lines), title=str(contents.path), expand=False)


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}{'' if number == 1 else 's'}"


def _demonstration(demo: DemoRecord, conditions: tuple[str, ...]) -> RenderableType:
    robot = [a for a in demo.actions if a not in ("goal", "external")]
    ending = "goal reached" if demo.reached_goal else "no goal line"
    title = Text.assemble((demo.name, "bold"), f": {' → '.join(robot) or '(no actions)'} ({ending})")
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
    if not contents.questions:
        return Text("  none asked")
    table = Table(box=None, padding=(0, 2), header_style="dim")
    for column in ("#", "question", "left", "answer", "what it changed"):
        table.add_column(column)
    for number, q in enumerate(contents.questions, 1):
        table.add_row(str(number), q.question, str(q.budget_left) if q.budget_left >= 0 else "",
                      q.answer if q.answer is not None else Text("(unanswered)", style="dim"), q.change or "")
    return table


def _generations(contents: RecordingContents) -> RenderableType:
    if not contents.generations:
        return Text("  none")
    table = Table(box=None, padding=(0, 2), header_style="dim")
    for column in ("generation", "nodes", "step", "why"):
        table.add_column(column)
    for g in contents.generations:
        table.add_row(str(g.generation), str(g.nodes), "" if g.step is None else str(g.step), g.reason)
    return table


def _learner_events(contents: RecordingContents) -> RenderableType:
    lines = []
    for e in contents.learner_events:
        shown = [name for name in e.removed if name not in e.detail]  # the detail often names them already
        removed = f"  removed: {', '.join(shown)}" if shown else ""
        lines.append(Text.assemble(("  " + e.event, "bold"), f": {e.detail}{removed}"))
    return Group(*lines)


_MAX_RUNS = 20


def _ticks(contents: RecordingContents) -> RenderableType:
    """What the ticks did, run-length encoded: the action that ran (or the root's status) and how often."""
    runs: list[list] = []
    for tick in contents.ticks:
        what = tick.action or tick.status
        if runs and runs[-1][0] == what:
            runs[-1][1] += 1
        else:
            runs.append([what, 1])
    shown = " → ".join(f"{what} ×{count}" if count > 1 else what for what, count in runs[:_MAX_RUNS])
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
