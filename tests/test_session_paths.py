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
