"""The journal file (issue 20): a save appends what it adds, fsynced, so its cost does not grow with
the session; a save a kill cut short is left out; a resume compacts the file to one line; a
journal of version 1 (one JSON document, as teach wrote before) still resumes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from conftest import journal_data

from teach.cli import main
from teach.errors import FormatError
from teach.session.journal import VERSION, Journal
from teach.session.settings import Settings, WorldKind
from teach.session.setup import opened_session

SEQUENCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"
LATER = ["start BallFound", "go to the ball, grasp the ball, go to the bin, put the ball in the bin", "done"]


def settings(base: Path) -> Settings:
    return Settings("j", questions=0, world=WorldKind.SYMBOLIC, base=base, record=False)


def taught(base: Path, demos: int) -> Path:
    """A closed session of ``demos`` demonstrations; its journal file."""
    with opened_session(settings(base)) as manager:
        for number in range(demos):
            for line in [SEQUENCE, "done"] if number == 0 else LATER:
                manager.handle(line)
    return base / "recordings" / "j.journal.json"


def test_a_save_appends_one_line_of_what_it_adds_whatever_the_session_holds(tmp_path):
    journal = taught(tmp_path, 1)
    with opened_session(settings(tmp_path), resume=True) as manager:
        compacted = journal.read_bytes()
        assert compacted.count(b"\n") == 1  # the resume's first save wrote the journal whole, as one line
        grown: list[int] = []
        for _ in range(30):
            for line in LATER:
                before = journal.stat().st_size
                manager.handle(line)
                after = journal.read_bytes()
                assert after.startswith(compacted) or len(grown) == 0  # the snapshot is never rewritten
                grown.append(len(after) - before)
        assert len(manager.demos) == 31
    assert max(grown[-9:]) <= max(grown[:9])  # the 30th demonstration costs a save what the 1st did
    assert journal_data(journal)["events"] == Journal.from_text(journal.read_text(), journal).to_json()["events"]
    with opened_session(settings(tmp_path), resume=True) as resumed:
        assert len(resumed.demos) == 31


def test_a_save_a_kill_cut_short_is_left_out(tmp_path):
    journal = taught(tmp_path, 2)
    whole = journal_data(journal)
    cut = b'{"events": [{"kind": "demo", "file": "demo-009.csv", "sou'
    journal.write_bytes(journal.read_bytes() + cut)
    assert journal_data(journal) == whole
    journal.write_bytes(journal.read_bytes()[:-len(cut)] + b"\x00\x00\x00")  # what a lost page leaves
    assert journal_data(journal) == whole
    with opened_session(settings(tmp_path), resume=True) as manager:
        assert len(manager.demos) == 2
    assert journal.read_bytes().count(b"\n") == 1 and b"\x00" not in journal.read_bytes()


def test_a_damaged_line_inside_the_journal_is_one_line_naming_it(tmp_path, capsys):
    journal = taught(tmp_path, 2)
    with opened_session(settings(tmp_path), resume=True) as manager:
        manager.handle("reset 3")
        manager.handle("state")
    lines = journal.read_text(encoding="utf-8").splitlines(keepends=True)
    assert len(lines) >= 3
    lines[1] = '{"events": [{"kind": "teleport"}]}\n'
    journal.write_text("".join(lines), encoding="utf-8")
    assert main(["session", "--resume", "j", "--no-record", "--base", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"teach: {journal}:2: the session journal is damaged: events[{len(journal_data_until(lines, 1))}]: " \
                  "kind: unknown event kind 'teleport' (known: demo, undo, redo, model, asked, answer, " \
                  "model_answer, guided_action, situation)"


def journal_data_until(lines: list[str], count: int) -> list[object]:
    """The events of the journal's first ``count`` lines."""
    return Journal.from_text("".join(lines[:count]), Path("j")).to_json()["events"]


def test_a_version_1_journal_resumes_and_is_rewritten_as_version_2(tmp_path):
    journal = taught(tmp_path, 3)
    data = journal_data(journal)
    data["version"] = 1
    journal.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")  # as teach wrote it
    with opened_session(settings(tmp_path), resume=True) as manager:
        assert len(manager.demos) == 3
        manager.handle("reset 2")
    lines = journal.read_bytes().splitlines()
    assert json.loads(lines[0])["version"] == VERSION and len(lines) >= 1
    assert len(journal_data(journal)["events"]) > len(data["events"])


@pytest.mark.parametrize(("change", "expected"), [
    ('{"open_kept": 4, "open_steps": []}', "open_kept: 4, but only 0 steps are open"),
    ('{"step": -1}', "step: must be 0 or more"),
    ('{"teleport": 1}', "teleport: unknown key"),
    ('[1, 2]', "must be an object"),
])
def test_a_damaged_save_line_names_its_line(change, expected):
    snapshot = Journal("j", "").snapshot_text()
    with pytest.raises(FormatError) as caught:
        Journal.from_text(snapshot + change + "\n", Path("j.journal.json"))
    assert caught.value.line == 2 and expected in caught.value.message
