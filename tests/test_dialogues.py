"""Every dialogue in dialogues/ replays through the real session: the quickstart in MuJoCo with
a rerun recording read back, the eight study participants with and without an oracle."""

from __future__ import annotations

import pytest
from conftest import ROOT, journal_data

from teach.cli import main

STUDY = sorted((ROOT / "dialogues" / "study").glob("participant*.dialogue"))
TRUE_MODEL = ROOT / "demos" / "ball" / "domain.toml"


def replay(args, capsys) -> str:
    assert main(["replay", *map(str, args)]) == 0
    return capsys.readouterr().out


def participant(path) -> int:
    return int(path.stem.removeprefix("participant"))


def test_quickstart_in_mujoco_with_a_recording(tmp_path, capsys):
    out = replay([ROOT / "dialogues" / "quickstart.dialogue", "--base", tmp_path], capsys)
    assert "robot asks:" in out and "Thank you." in out
    demos = sorted((tmp_path / "demos" / "quickstart").glob("demo-*.csv"))
    trees = sorted((tmp_path / "trees" / "quickstart").glob("gen-*.xml"))
    assert len(demos) >= 3 and len(trees) >= len(demos)
    journal = journal_data(tmp_path / "recordings" / "quickstart.journal.json")
    assert [e["kind"] for e in journal["events"]].count("demo") == len(demos)
    recording = tmp_path / "recordings" / "quickstart.rrd"
    assert recording.stat().st_size > 0
    # the recording explains the session: review reads it back
    assert main(["review", str(recording)]) == 0
    review = capsys.readouterr().out
    assert "demonstration" in review.lower() and "question" in review.lower()


@pytest.mark.parametrize("path", STUDY, ids=lambda p: p.stem)
def test_study_without_questions_reproduces_the_thesis(path, tmp_path, capsys):
    out = replay([path, "--base", tmp_path, "--no-record", "--questions", "0"], capsys)
    usable = "I can build a behaviour" in out or "Aus diesen Beschreibungen kann ich ein Verhalten" in out
    # thesis §6.1: only participants 4, 5, 7 and 8 gave usable definitions
    assert usable == (participant(path) in (4, 5, 7, 8))


def test_study_with_five_oracle_questions(tmp_path, capsys):
    rescued, asked = [], {}
    for path in STUDY:
        base = tmp_path / path.stem
        out = replay([path, "--base", base, "--no-record", "--oracle-model", TRUE_MODEL], capsys)
        journal = journal_data(base / "recordings" / f"{path.stem}.journal.json")
        asked[participant(path)] = [e for e in journal["events"] if e["kind"] == "model_answer"]
        finished = "The task is finished" in out or "Die Aufgabe ist erledigt" in out
        if finished and participant(path) not in (4, 5, 7, 8):
            rescued.append(participant(path))
    assert all(len(q) <= 5 for q in asked.values())
    assert all(not asked[n] for n in (4, 5, 7, 8))
    # with at most five questions, three of the four unusable definitions make the robot finish the
    # task in the world of Table 6.1; participant 3's becomes plannable but grasps without approaching
    assert rescued == [1, 2, 6]


def test_german_dialogue_teaches_the_task(tmp_path, capsys):
    out = replay([ROOT / "dialogues" / "deutsch.dialogue", "--base", tmp_path, "--no-record"], capsys)
    assert "Roboter fragt:" in out and "Danke." in out
    # the last run, after a correction, finishes the task in MuJoCo
    assert out.rstrip().count("Fertig! Die Aufgabe ist erledigt.") == 1
    # the first start has the ball in view: "Ball finden" changes nothing and is not recorded,
    # so the first demonstration does not contradict itself
    assert "nicht aufgezeichnet" in out
    assert len(list((tmp_path / "demos" / "deutsch").glob("demo-*.csv"))) == 3
