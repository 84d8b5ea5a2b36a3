"""Rendering is pure: golden text of the reference tree, DOT, and the show/dot commands."""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path

from conftest import ROOT, colledanchise_tree
from rich.console import Console

from teach.bt.nodes import Action, Condition, Inverter, Parallel, Status
from teach.bt.render import render_text, render_tree, to_dot
from teach.bt.tick import tick_state
from teach.bt.xml import write_tree
from teach.domain import Domain

COLLEDANCHISE_TEXT = """\
→
├── ?
│   ├── (BallFound)
│   └── FindBall
├── ?
│   ├── (BallClose)
│   └── ApproachBall
├── ?
│   ├── (BallGrasped)
│   └── GraspBall
├── ?
│   ├── (BinClose)
│   └── ApproachBin
└── ?
    ├── (BallPlaced)
    └── PlaceBall
"""

TICKED_TEXT = """\
→ [RUNNING]
├── ? [SUCCESS]
│   ├── (BallFound) [SUCCESS]
│   └── FindBall
├── ? [RUNNING]
│   ├── (BallClose) [FAILURE]
│   └── ApproachBall [RUNNING]
├── ?
│   ├── (BallGrasped)
│   └── GraspBall
├── ?
│   ├── (BinClose)
│   └── ApproachBin
└── ?
    ├── (BallPlaced)
    └── PlaceBall
"""


def test_colledanchise_tree_renders_with_the_thesis_symbols() -> None:
    assert render_text(colledanchise_tree()) == COLLEDANCHISE_TEXT


def test_statuses_of_the_last_tick_are_shown(ball: Domain) -> None:
    tree = colledanchise_tree()
    result = tick_state(tree, ball.condition_names, ball.state(["BallFound"]))
    assert render_text(tree, result.statuses()) == TICKED_TEXT


def test_parallel_inverter_and_labels() -> None:
    tree = Parallel((Inverter(Condition("Door")), Action("Open")), 1)
    text = render_text(tree, labels={"Door": "the door is open"})
    assert text == "⇉ 1/2\n├── ◇\n│   └── (Door) · the door is open\n└── Open\n"


def test_rich_tree_draws_the_same_lines_and_colours_by_status(ball: Domain) -> None:
    tree = colledanchise_tree()
    plain = Console(file=io.StringIO(), width=120, color_system=None)
    plain.print(render_tree(tree))
    assert plain.file.getvalue() == COLLEDANCHISE_TEXT  # type: ignore[attr-defined]

    result = tick_state(tree, ball.condition_names, ball.state(["BallFound"]))
    coloured = Console(file=io.StringIO(), width=120, color_system="standard", force_terminal=True)
    coloured.print(render_tree(tree, result.statuses()))
    lines = coloured.file.getvalue().splitlines()  # type: ignore[attr-defined]
    # expectation: the running action yellow (33), the failed condition red (31), unvisited dim (2)
    assert "\x1b[33mApproachBall" in lines[6]
    assert "\x1b[31m(BallClose)" in lines[5]
    assert "\x1b[2mGraspBall" in lines[9]


def test_dot_is_deterministic_with_pre_order_ids(ball: Domain) -> None:
    dot = to_dot(colledanchise_tree())
    assert dot == to_dot(colledanchise_tree())
    assert dot.startswith("digraph BehaviorTree {\n")
    assert '  n1 [label="→", shape=box];' in dot
    assert '  n3 [label="(BallFound)", shape=ellipse];' in dot
    assert '  n4 [label="FindBall", shape=box, style="rounded"];' in dot
    assert dot.count(" -> ") == 15 and "  n1 -> n2;\n  n2 -> n3;\n" in dot
    tree = colledanchise_tree()
    ticked = to_dot(tree, tick_state(tree, ball.condition_names, ball.state([])).statuses())
    assert 'n4 [label="FindBall", shape=box, fillcolor="#f7e07a", style="rounded,filled"];' in ticked
    assert 'n5 [label="?", shape=box, fontcolor="gray50", color="gray70"];' in ticked


def test_dot_escapes_quotes_in_labels() -> None:
    assert 'label="Go · say \\"hi\\""' in to_dot(Action("Go"), labels={"Go": 'say "hi"'})


def teach(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "teach.cli", *args], capture_output=True, text=True, cwd=ROOT)


def test_show_and_dot_commands(tmp_path: Path) -> None:
    path = tmp_path / "tree.xml"
    write_tree(path, colledanchise_tree())
    shown = teach("show", str(path))
    assert shown.returncode == 0 and shown.stdout == COLLEDANCHISE_TEXT
    ticked = teach("show", str(path), "--state", "BallFound", "--domain", str(ROOT / "demos/ball/domain.toml"))
    assert ticked.returncode == 0, ticked.stderr
    assert "(BallFound) · I can see the ball [SUCCESS]" in ticked.stdout
    assert ticked.stdout.endswith("status RUNNING, running ApproachBall\n")
    out = tmp_path / "tree.dot"
    assert teach("dot", str(path), "-o", str(out)).returncode == 0
    assert out.read_text() == to_dot(colledanchise_tree())
    assert Status.RUNNING.name in teach("show", str(path), "--state", "").stdout


def test_compact_rendering_writes_leaf_groups_inline():
    from rich.console import Console

    from teach.bt.nodes import Action, Condition, Fallback, Inverter, Sequence
    from teach.bt.render import render_tree

    tree = Sequence((Fallback((Condition("A"), Inverter(Condition("B")), Action("X"))),
                     Fallback((Condition("C"), Sequence((Condition("A"), Action("Y")))))))
    console = Console(width=80, color_system=None, record=True)
    console.print(render_tree(tree, compact=True))
    lines = console.export_text().splitlines()
    # a Fallback of leaves is one line; a Fallback with a Sequence child keeps its branches
    assert lines[1].endswith("? (A) ◇(B) X")
    assert lines[2].endswith("?") and lines[4].endswith("→ (A) Y") and len(lines) == 5
