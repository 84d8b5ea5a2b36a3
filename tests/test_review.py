"""`teach review` summarises a real recording read back with rerun, and refuses damaged ones."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from conftest import BALL_DOMAIN
from rich.console import Console
from rich.text import Text
from test_log import record_session

from teach.cli import main
from teach.domain import load_domain
from teach.observe.reader import read_recording
from teach.review import summary


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("review") / "session.rrd"
    record_session(path, load_domain(BALL_DOMAIN))
    return path


def _text(path: Path) -> str:
    console = Console(record=True, width=160, color_system=None)
    console.print(summary(read_recording(path)))
    return console.export_text()


def test_summary_lists_everything_in_order(recording: Path) -> None:
    text = _text(recording)
    # each section appears once, in the order a researcher reads them
    headings = ["Demonstrations", "Questions", "Tree generations", "Learner events", "Ticks", "Final tree", "Replay"]
    assert [text.index(h) for h in headings] == sorted(text.index(h) for h in headings)
    # demonstrations as action sequences, in order, with their states and the external action marked
    first = text.index("demo-001: FindBall → ApproachBall → GraspBall → GraspBall → ApproachBin → PlaceBall")
    assert first < text.index("demo-002: ApproachBall → GraspBall → ApproachBin → PlaceBall (goal reached)")
    assert re.search(r"4 +BallFound BallClose BallGrasped +external", text)
    # questions with their answers and the budget left
    assert text.index("Must the ball be in your hand") < text.index("Do you need to see the ball")
    assert "kept (BallGrasped)" in text
    # generations with node counts: 0 has 5 nodes, 1 and 2 the 16-node reference tree
    rows = [line.split() for line in text.splitlines() if line.strip()[:1].isdigit() and "nodes" not in line]
    assert ["0", "5", "0", "0", "the", "first", "tree,", "start"] in rows
    assert ["2", "16"] == next(r[:2] for r in rows if r[:1] == ["2"] and r[-1] == "(no)")
    assert "removed: (BallFound), FindBall" in text
    # the ticks, run-length encoded: generation 0 runs FindBall until the ball is found, then ApproachBall in
    # the other seven states of demo-001; the final tree approaches the ball it sees
    assert "9 ticks: FindBall (tick 3) → ApproachBall ×8 (tick 4)" in text
    # the final tree rendered with the thesis's symbols, and the replay result
    tree = text[text.index("Final tree"):text.index("Replay")]
    assert "→" in tree and "(BallPlaced)" in tree and "PlaceBall" in tree
    assert "reproduced 2/2 demonstrations (lenient); over the session: 1/1 → 2/2" in text


def test_cli_prints_summary(recording: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["review", str(recording)]) == 0
    out = capsys.readouterr().out
    assert "session test-session" in out and "demo-002" in out


def test_the_dialogue_is_printed_on_request_in_order(recording: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The summary listed demonstrations, questions and trees, not what was said: a study reads
    what the teacher typed (`--dialogue`)."""
    assert main(["review", str(recording)]) == 0
    assert "Dialogue" not in capsys.readouterr().out
    assert main(["review", str(recording), "--dialogue"]) == 0
    out = capsys.readouterr().out
    said = out[out.index("Dialogue"):]
    assert re.search(r"\[step 1 · tick \d+\] teacher: find the ball", said)
    assert said.index("teacher: find the ball") < said.index("robot: I find the ball.")


def test_what_the_robot_was_asked_to_tell_is_in_the_dialogue(tmp_path: Path) -> None:
    """ "what do you see?" got the situation on screen, but the recording's dialogue showed the
    question unanswered (the state line after each step is status, not dialogue)."""
    dialogue = tmp_path / "asking.dialogue"
    dialogue.write_text("find the ball\nwhat do you see?\n", encoding="utf-8")
    assert main(["replay", str(dialogue), "--world", "symbolic", "--base", str(tmp_path)]) == 0
    said = [(d.speaker, d.text) for d in read_recording(tmp_path / "recordings" / "asking.rrd").dialogue]
    asked = said.index(("teacher", "what do you see?"))
    assert said[asked + 1][0] == "robot" and "I can see the ball" in said[asked + 1][1]
    assert not any(text.startswith("I can see the ball") for _, text in said[:asked])  # after a step: status only


def test_cli_truncated_recording_is_one_line_status_2(recording: Path, tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    broken = tmp_path / "broken.rrd"
    broken.write_bytes(recording.read_bytes()[:-200])
    assert main(["review", str(broken)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"teach: {broken}: ") and "Traceback" not in err


def test_open_without_display_is_a_clear_error(recording: Path, monkeypatch: pytest.MonkeyPatch,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert main(["review", str(recording), "--open"]) == 2
    assert "no display" in capsys.readouterr().err


def test_a_recording_with_wrong_value_types_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A recording whose values have the wrong types (here a replay result logged as text) is
    refused in one line, never summarised as "reproduced many/None" or a TypeError. It is
    written in a process of its own: rerun keeps the first type logged under a name for the
    rest of a process."""
    import subprocess
    import sys

    path = tmp_path / "typed.rrd"
    writer = ("import sys\nfrom teach.domain import load_domain\nfrom teach.observe.rerun_writer import RerunLogger\n"
              "logger = RerunLogger(sys.argv[1], 'typed')\nlogger.on_domain(load_domain(sys.argv[2]))\n"
              "logger.set_time(1)\nlogger.on_replay('many', 3)\nlogger.close()\n")
    subprocess.run([sys.executable, "-c", writer, str(path), str(BALL_DOMAIN)], check=True, timeout=120)
    assert main(["review", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith(f"teach: {path}: ") and "reproduced is 'many', not int" in err


# --- the tree at a step, the runs and the study figures -------------------------------------------

def _styles(renderable: object) -> dict[str, set[str]]:
    """Every label of a rich tree with the styles it is drawn in."""
    from rich.tree import Tree

    found: dict[str, set[str]] = {}
    stack = [renderable]
    while stack:
        item = stack.pop()
        if isinstance(item, Tree):
            label = item.label
            assert isinstance(label, Text)
            found.setdefault(label.plain.strip(), set()).add(str(label.style))
            stack.extend(item.children)
        elif hasattr(item, "renderables"):
            stack.extend(item.renderables)
    return found


def test_the_tree_at_a_step_is_coloured_by_each_nodes_status_there(recording: Path) -> None:
    from teach.review import step_tree

    contents = read_recording(recording)
    last = contents.ticks[-1]
    assert last.action == "ApproachBall" and last.step is not None
    styles = _styles(step_tree(contents, last.step))
    assert styles["go to the ball"] == {"bold black on yellow"}  # the running action, in the session's words
    assert styles["I can see the ball?"] == {"green"} and styles["the ball is within reach?"] == {"red"}
    assert styles["→"] == {"yellow"} and styles["?"] == {"green", "yellow", "dim"}
    assert styles["put the ball in the bin"] == styles["the ball is in the bin?"] == {"dim"}  # not ticked
    # the first tick, on generation 0's tree: it finds the ball
    first = contents.ticks[0]
    assert first.step is not None
    early = _styles(step_tree(contents, first.step))
    assert early["find the ball"] == {"bold black on yellow"} and early["I can see the ball?"] == {"red"}
    assert "go to the ball" in early and early["go to the ball"] == {"dim"}


def test_a_step_without_ticks_shows_the_tree_as_it_stood(recording: Path) -> None:
    from teach.review import step_tree

    contents = read_recording(recording)
    text = _plain(step_tree(contents, 1))
    assert "no tick at step 1" in text and "find the ball" in text and "put the ball in the bin" not in text


def test_a_tick_shows_the_tree_that_ran_there_and_other_moments_the_generation(recording: Path) -> None:
    from teach.review import tick_tree

    contents = read_recording(recording)
    last = contents.ticks[-1]
    assert last.moment is not None
    text = _plain(tick_tree(contents, last.moment))
    assert f"tick {last.moment} (step {last.step}): the tree that ran, root RUNNING, running ApproachBall" in text
    before = contents.generations[0].moment
    assert before is not None
    text = _plain(tick_tree(contents, before))
    assert f"no tick at tick {before}: generation 0 as it stood, nothing ticked" in text


def test_cli_tick_outside_the_recording_is_one_line(recording: Path, capsys: pytest.CaptureFixture[str]) -> None:
    last = read_recording(recording).last_moment
    assert main(["review", str(recording), "--tick", str(last + 1)]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert f"--tick {last + 1} is outside the recording (its ticks: 0–{last})" in captured.err


def _plain(renderable: object) -> str:
    console = Console(record=True, width=160, color_system=None)
    console.print(renderable)
    return console.export_text()


def test_cli_step_outside_the_recording_is_one_line(recording: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["review", str(recording), "--step", "999"]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert "--step 999 is outside the recording (its steps: 0–12)" in captured.err


def test_cli_step_shows_the_tree_there(recording: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["review", str(recording), "--step", "12"]) == 0
    out = capsys.readouterr().out
    assert "Tree at step 12" in out and "last of 1 tick at step 12: root RUNNING, running ApproachBall" in out


def test_study_figures_give_share_and_size_per_generation_and_what_each_answer_did(recording: Path) -> None:
    text = _text(recording)
    figures = text[text.index("Study figures"):]
    rows = [line.split() for line in figures.splitlines()[2:] if line.strip()[:1].isdigit()]
    # generation, step, nodes, reproduced, share: generation 0 came before any replay
    assert rows[0][:3] == ["0", "0", "5"] and rows[-1] == ["2", "12", "16", "2/2", "100%"]
    assert "question 1: kept (BallGrasped) → no new generation" in figures
    assert "question 2: no → tree unchanged (generation 2, 16 nodes)" in figures


def test_a_damaged_run_log_beside_the_recording_is_one_line(recording: Path, tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    copy = tmp_path / "copy.rrd"
    copy.write_bytes(recording.read_bytes())
    (tmp_path / "copy").mkdir()
    (tmp_path / "copy" / "run-001.btlog").write_bytes(b"BTCPP4-FileLogger2\x01")
    assert main(["review", str(copy)]) == 2
    captured = capsys.readouterr()
    bad = tmp_path / "copy" / "run-001.btlog"
    assert captured.out == "" and captured.err == f"teach: {bad}: the log ends inside its header\n"


def test_questions_read_as_paragraphs_at_80_columns(recording: Path) -> None:
    """A question is a paragraph across the whole width (a table squeezed it into 10 lines at 80
    columns), numbered with its step and tick, its answer on the next line."""
    console = Console(record=True, width=80, color_system=None)
    console.print(summary(read_recording(recording)))
    text = console.export_text()
    questions = text[text.index("\nQuestions"):text.index("\nTree generations")].strip().splitlines()[1:]
    assert questions[0] == "  1. [step 10 · tick 11] Must the ball be in your hand before you go to the bin?"
    assert questions[1:3] == ["(4 left)", "     → [step 11 · tick 11] yes: kept (BallGrasped)"]
    assert len(questions) == 5
