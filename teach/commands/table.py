"""Recompute the thesis's evaluation tables next to its published figures.

Example:
    teach table
    teach table --json > evaluation.json

Tables 6.2 and 6.3 (trees learned from each demonstration set, replayed on every set) under
both replay readings, node counts before and after pruning, and Approach 1 on each study
participant's action model. Each cell shows our figure and, after it, the thesis's; cells
that differ are explained in docs/reproduction.md.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from teach.evaluate import Evaluation

NAME = "table"
HELP = "recompute the thesis's Tables 6.2 and 6.3, node counts and the study, next to its figures"
ORDER = 60


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--demos", type=Path, default=Path("demos/ball"),
                        help="folder with domain.toml and delta1..delta5 (default: demos/ball)")
    parser.add_argument("--study", type=Path, default=Path("dialogues/study"),
                        help="folder with participant1..8.toml (default: dialogues/study)")
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON (no progress bar)")


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    from teach.evaluate import as_json, evaluate, work_units

    show_progress = not args.json and sys.stderr.isatty()
    if show_progress:
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                      console=Console(stderr=True), transient=True) as bar:
            task = bar.add_task("learning", total=work_units())
            evaluation = evaluate(args.demos, args.study,
                                  lambda label: bar.update(task, advance=1, description=label))
    else:
        evaluation = evaluate(args.demos, args.study)
    if args.json:
        print(json.dumps(as_json(evaluation), indent=2, ensure_ascii=False))
        return 0
    console = Console()
    for renderable in render(evaluation):
        console.print(renderable)
        console.print()
    return 0


def render(evaluation: Evaluation) -> list[object]:
    """Rich renderables for every table, in the thesis's order."""
    from rich.table import Table

    from teach.evaluate import SET_LABELS, SETS

    out: list[object] = []
    for cross in (evaluation.table_6_2, evaluation.table_6_3):
        for lenient in (False, True):
            reading = "lenient reading" if lenient else "strict reading"
            caption = f"{cross.matches(lenient)}/{len(cross.cells)} cells equal the thesis's"
            for source, error in cross.errors:
                caption += f"\n{SET_LABELS[source]}: no tree: {error}"
            table = Table(title=f"{cross.title}, {reading}: ours (thesis)", caption=caption)
            table.add_column("generated from \\ tested on")
            for target in SETS:
                table.add_column(SET_LABELS[target], justify="right")
            for source in SETS:
                row = [SET_LABELS[source]]
                for target in SETS:
                    cell = cross.cell(source, target)
                    ours = cell.lenient if lenient else cell.strict
                    if ours is None:
                        row.append(f"[red]—[/] ({cell.thesis})")
                        continue
                    style = "green" if ours == cell.thesis else "yellow"
                    row.append(f"[{style}]{ours}/{cell.total}[/] ({cell.thesis})")
                table.add_row(*row)
            out.append(table)

    nodes = Table(title="Node counts before → after pruning: ours (thesis)")
    for column in ("approach", "learned from", "before", "after", "= Colledanchise & Ögren"):
        nodes.add_column(column, justify="left" if column in ("approach", "learned from") else "right")
    for n in evaluation.nodes:
        source = SET_LABELS.get(n.source, n.source)
        same = ("yes" if n.equals_colledanchise else "no") + (
            " (yes)" if n.thesis_equals_colledanchise else "")
        if n.error is not None:
            nodes.add_row(n.approach.replace("approach", "Approach "), source, "[red]—[/]", "[red]—[/]",
                          f"no tree: {n.error}")
            continue
        assert n.before is not None and n.after is not None  # a learner that did not fail counted both
        nodes.add_row(n.approach.replace("approach", "Approach "), source,
                      _vs(n.before, n.thesis_before), _vs(n.after, n.thesis_after), same)
    out.append(nodes)

    study = Table(title="Approach 1 on the study participants' action models (§6.1, Tables A.2–A.9)")
    for column in ("participant", "usable", "why", "thesis"):
        study.add_column(column)
    for p in evaluation.participants:
        style = "green" if p.usable == p.thesis_usable else "yellow"
        verdict = f"[{style}]{'yes' if p.usable else 'no'}[/]"
        thesis = f"{'yes' if p.thesis_usable else 'no'}: {p.thesis_reason}"
        study.add_row(str(p.participant), verdict, p.reason, thesis)
    out.append(study)
    return out


def _vs(ours: int, thesis: int | None) -> str:
    if thesis is None:
        return str(ours)
    style = "green" if ours == thesis else "yellow"
    return f"[{style}]{ours}[/] ({thesis})"
