"""Golden transcripts: every dialogue in dialogues/ replays to exactly the text, trees and
demonstrations it gave before (byte for byte), so a restructuring cannot change behaviour
unnoticed.

Each case replays in a scratch folder that sees the repository's demos/ball/ and dialogues/
under their usual relative names, with ``--base .``, so printed paths are the same everywhere.
The quickstart and the German dialogue are pinned in MuJoCo (with their tree generations and
demonstration CSVs, as ``make run`` leaves them) and in the symbolic world, which has no
physics at all; the study participants in the world their dialogues name, with and without
the oracle answering from the true action model.

To accept a deliberate behaviour change, regenerate the files and review the diff:

    TEACH_UPDATE_GOLDEN=1 .venv/bin/python -m pytest tests/test_golden.py
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from conftest import ROOT

from teach.cli import main

GOLDEN = ROOT / "tests" / "golden"
UPDATE = os.environ.get("TEACH_UPDATE_GOLDEN") == "1"
TRUE_MODEL = "demos/ball/domain.toml"
STUDY = sorted(p.stem for p in (ROOT / "dialogues" / "study").glob("participant*.dialogue"))

CASES: dict[str, list[str]] = {
    "quickstart-mujoco": ["dialogues/quickstart.dialogue"],
    "quickstart-symbolic": ["dialogues/quickstart.dialogue", "--world", "symbolic"],
    "deutsch-mujoco": ["dialogues/deutsch.dialogue"],
    "deutsch-symbolic": ["dialogues/deutsch.dialogue", "--world", "symbolic"],
    "messy-mujoco": ["dialogues/messy.dialogue"],
    "snacks-en": ["dialogues/snacks_en.dialogue"],
    "snacks-de": ["dialogues/snacks_de.dialogue"],
    **{name: [f"dialogues/study/{name}.dialogue"] for name in STUDY},
    **{f"{name}-oracle": [f"dialogues/study/{name}.dialogue", "--oracle-model", TRUE_MODEL] for name in STUDY},
}


def _scratch(tmp_path: Path) -> Path:
    """A working folder with the repository's inputs linked in and nothing else."""
    (tmp_path / "demos").mkdir()
    for domain in ("ball", "snacks"):
        (tmp_path / "demos" / domain).symlink_to(ROOT / "demos" / domain, target_is_directory=True)
    (tmp_path / "dialogues").symlink_to(ROOT / "dialogues", target_is_directory=True)
    return tmp_path


def _outputs(folder: Path) -> dict[str, bytes]:
    """Every tree generation and demonstration under a folder, by relative path."""
    files = sorted([*folder.glob("trees/*/gen-*.xml"), *folder.glob("demos/*/demo-*.csv")])
    return {str(path.relative_to(folder)): path.read_bytes() for path in files}


def _write_golden(case: Path, transcript: str, outputs: dict[str, bytes]) -> None:
    shutil.rmtree(case, ignore_errors=True)
    case.mkdir(parents=True)
    (case / "transcript.txt").write_text(transcript, encoding="utf-8")
    for name, data in outputs.items():
        (case / name).parent.mkdir(parents=True, exist_ok=True)
        (case / name).write_bytes(data)


@pytest.mark.parametrize("name", sorted(CASES))
def test_replay_is_byte_identical_to_the_golden_files(name, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(_scratch(tmp_path))
    monkeypatch.setenv("COLUMNS", "80")  # rich wraps at the console width
    assert main(["replay", *CASES[name], "--base", ".", "--no-record"]) == 0
    transcript = capsys.readouterr().out
    outputs = _outputs(tmp_path)
    case = GOLDEN / name
    if UPDATE:
        _write_golden(case, transcript, outputs)
    assert transcript == (case / "transcript.txt").read_text(encoding="utf-8")
    golden = _outputs(case)
    assert sorted(outputs) == sorted(golden)
    for file, data in outputs.items():
        assert data == golden[file], file



def test_the_readmes_session_is_the_german_golden_abridged() -> None:
    """README's "A session" shows ``dialogues/deutsch.dialogue`` as it replays: every line of it
    but the "…" that mark cuts is a line of the golden transcript, in the same order (it had kept
    trees and answers of an earlier learner). The terminal's wrapping may leave a space at a line's
    end, which README does not keep."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    start = readme.index("```\nSitzung deutsch")
    shown = readme[start + 4:readme.index("```", start + 4)].splitlines()
    golden = iter((GOLDEN / "deutsch-mujoco" / "transcript.txt").read_text(encoding="utf-8").splitlines())
    cuts = {"…", "│   …                                                                         │"}
    for line in shown:
        if line not in cuts:
            assert any(line.rstrip() == later.rstrip() for later in golden), \
                f"README session line not in the golden, in order: {line!r}"
