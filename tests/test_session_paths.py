"""A session's own files are its own: never read back through a link (issue 23: a journal that
was a link to a file outside was read through it and the whole session ran before a save failed)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT

from teach.errors import TeachError
from teach.session.settings import Settings, WorldKind
from teach.session.setup import opened_session

SEQUENCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"


@pytest.fixture
def taught(tmp_path: Path) -> Path:
    """A base folder holding one finished symbolic session ``own`` with one demonstration."""
    script = tmp_path / "own.dialogue"
    script.write_text(f"@world symbolic\n@questions 0\n{SEQUENCE}\ndone\n", encoding="utf-8")
    subprocess.run([sys.executable, "-m", "teach.cli", "replay", str(script), "--no-record", "--base", str(tmp_path)],
                   check=True, capture_output=True, cwd=ROOT, timeout=300)
    return tmp_path


@pytest.mark.parametrize("own", ["demos/own/demo-001.csv", "demos/own/domain.toml", "recordings/own.journal.json"])
def test_a_session_file_replaced_by_a_link_is_refused_on_resume(taught: Path, own: str) -> None:
    path = taught / own
    outside = taught / "outside" / path.name
    outside.parent.mkdir()
    shutil.move(path, outside)
    path.symlink_to(outside)
    with pytest.raises(TeachError, match="symbolic link") as caught:
        with opened_session(Settings("own", world=WorldKind.SYMBOLIC, base=taught, record=False), resume=True,
                            note=lambda _: None):
            pass
    assert caught.value.path == str(path) and "\n" not in str(caught.value)
    assert path.is_symlink() and outside.is_file()


def test_an_audio_line_heard_from_the_sessions_own_folder_is_refused(tmp_path: Path,
                                                                    capsys: pytest.CaptureFixture[str]) -> None:
    """A replay forgets its session's earlier folders: a dialogue's ``@audio`` file inside them
    would be deleted after it was heard, so the replay is refused before it starts."""
    from teach.cli import main

    speech = tmp_path / "recordings" / "said" / "speech"
    speech.mkdir(parents=True)
    assert main(["speak", "find the ball", "-o", str(speech / "001.wav")]) == 0
    dialogue = tmp_path / "said.dialogue"
    dialogue.write_text("@world symbolic\n@audio recordings/said/speech/001.wav\n", encoding="utf-8")
    before = sorted(tmp_path.rglob("*"))
    assert main(["replay", str(dialogue), "--base", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err == (f"teach: {tmp_path / 'recordings' / 'said'}: holds {speech / '001.wav'}, which this command "
                   "reads: write into another folder\n")
    assert sorted(tmp_path.rglob("*")) == before


def test_the_resume_hint_names_the_base_folder_where_it_is_not_the_working_one(tmp_path, monkeypatch):
    """ "Resume with: teach session --resume x2" after `--base /elsewhere`, run again from the same
    folder, found no journal: the hint says the base where it is needed."""
    monkeypatch.chdir(tmp_path)
    assert Settings("x2", base=Path(".")).resume_words == "x2"
    assert Settings("x2", base=tmp_path).resume_words == "x2"  # the working folder, named
    elsewhere = tmp_path / "my sessions"
    assert Settings("x2", base=elsewhere).resume_words == f"x2 --base '{elsewhere}'"
