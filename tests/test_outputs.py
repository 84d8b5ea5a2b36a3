"""What the commands write: readable files, one-line errors for unusable output paths, no
stale or half-written results."""

from __future__ import annotations

import os

import pytest
from conftest import ROOT

from teach.cli import main
from teach.demos import Demonstration, Step
from teach.errors import DomainError
from teach.fsutil import atomic_write_text

REFERENCE = ROOT / "demos" / "ball" / "reference" / "colledanchise.xml"


def test_written_files_get_the_umasks_mode(tmp_path):
    old = os.umask(0o022)
    try:
        atomic_write_text(tmp_path / "a.txt", "x")
    finally:
        os.umask(old)
    assert (tmp_path / "a.txt").stat().st_mode & 0o777 == 0o644


@pytest.mark.parametrize("target", ["folder", "under-a-file"])
def test_unusable_output_path_is_one_line(tmp_path, capsys, target):
    (tmp_path / "file").write_text("x")
    out = tmp_path if target == "folder" else tmp_path / "file" / "x.dot"
    assert main(["dot", str(REFERENCE), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("teach: ") and "Traceback" not in err


def test_learn_writes_nothing_when_the_output_path_is_bad(tmp_path, capsys):
    generations = tmp_path / "gens"
    assert main(["learn", str(ROOT / "demos" / "ball" / "delta4"), "-o", str(tmp_path),
                 "--generations", str(generations)]) == 2
    assert not generations.exists()
    capsys.readouterr()


def test_goal_only_demonstrations_are_a_clear_error(tmp_path, capsys):
    (tmp_path / "g").mkdir()
    (tmp_path / "g" / "d.csv").write_text("1;1;1;1;1;0\n")
    (tmp_path / "domain.toml").write_text((ROOT / "demos" / "ball" / "domain.toml").read_text())
    assert main(["learn", str(tmp_path / "g"), "-o", str(tmp_path / "g.xml")]) == 2
    assert "no demonstration shows an action" in capsys.readouterr().err
    assert not (tmp_path / "g.xml").exists()


def test_generations_folder_holds_only_this_runs_generations(tmp_path, capsys):
    folder = tmp_path / "gens"
    for demos, output in (("delta1", "a.xml"), ("delta4", "b.xml")):
        main(["learn", str(ROOT / "demos" / "ball" / demos), "-o", str(tmp_path / output),
              "--generations", str(folder)])
    capsys.readouterr()
    last = sorted(folder.glob("gen-*.xml"))[-1]
    assert last.read_bytes() == (tmp_path / "b.xml").read_bytes()


def test_recording_into_a_set_of_another_domain_is_refused(tmp_path):
    from teach.sim.recorder import save_demonstration

    folder = tmp_path / "other"
    folder.mkdir()
    (folder / "domain.toml").write_text('[[condition]]\nname = "A"\n[[action]]\nid = 1\nname = "FindBall"\n')
    demo = Demonstration("d", (Step((False,) * 5, 1, 1),))
    with pytest.raises(DomainError, match="other conditions or actions"):
        save_demonstration(demo, folder)
    assert not list(folder.glob("*.csv"))


def _sha256s(folder) -> dict[str, str]:
    import hashlib

    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest() if p.is_file() else "folder"
            for p in sorted(folder.rglob("*"))}


@pytest.mark.parametrize("output", ["SET/a-good.csv", "SET/domain.toml", "SET/zz.csv", "tree.xml"])
def test_an_output_that_is_an_input_is_refused_and_nothing_changes(tmp_path, capsys, monkeypatch, output):
    """Issue 23: these commands once exited 0 having replaced a demonstration, the domain, the
    input tree, or added an XML "demonstration" to the set."""
    (tmp_path / "SET").mkdir()
    (tmp_path / "SET" / "a-good.csv").write_bytes((ROOT / "demos" / "ball" / "delta4" / "d01.csv").read_bytes())
    (tmp_path / "SET" / "domain.toml").write_bytes((ROOT / "demos" / "ball" / "domain.toml").read_bytes())
    (tmp_path / "tree.xml").write_bytes(REFERENCE.read_bytes())
    monkeypatch.chdir(tmp_path)
    before = _sha256s(tmp_path)
    argv = ["dot", "tree.xml", "-o", output] if output == "tree.xml" else ["learn", "SET", "-o", output]
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.startswith(f"teach: {output}: ") and captured.err.count("\n") == 1
    assert "this command reads" in captured.err
    assert _sha256s(tmp_path) == before


def test_a_hard_link_to_an_input_is_the_input(tmp_path, capsys):
    tree = tmp_path / "tree.xml"
    tree.write_bytes(REFERENCE.read_bytes())
    (tmp_path / "elsewhere").mkdir()
    os.link(tree, tmp_path / "elsewhere" / "same.xml")
    assert main(["prune", str(tree), "-o", str(tmp_path / "elsewhere" / "same.xml")]) == 2
    assert f"is the tree file {tree} that this command reads" in capsys.readouterr().err
    assert (tmp_path / "elsewhere" / "same.xml").read_bytes() == REFERENCE.read_bytes()


def test_writing_beside_the_inputs_still_works(tmp_path, capsys):
    """The guard refuses only what is read: the same folder, another name, is fine."""
    (tmp_path / "tree.xml").write_bytes(REFERENCE.read_bytes())
    assert main(["dot", str(tmp_path / "tree.xml"), "-o", str(tmp_path / "tree.dot")]) == 0
    assert main(["learn", str(ROOT / "demos" / "ball" / "delta4"), "-o", str(tmp_path / "tree.xml")]) == 0
    capsys.readouterr()


def test_a_session_base_that_is_a_link_creates_nothing_anywhere(tmp_path, capsys, monkeypatch):
    """Issue 23: ``teach session --base LINK`` made ``outside/demos`` and ``outside/trees`` before
    it refused to write through the link."""
    (tmp_path / "outside").mkdir()
    (tmp_path / "project").mkdir()
    (tmp_path / "project" / "LINK").symlink_to(tmp_path / "outside")
    monkeypatch.chdir(tmp_path / "project")
    before = _sha256s(tmp_path)
    for argv in (["session", "--base", "LINK", "--world", "offline"], ["replay", str(ROOT / "dialogues" /
                 "quickstart.dialogue"), "--base", "LINK", "--world", "offline"]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert "the folder LINK is a symbolic link" in err and err.count("\n") == 1
    assert _sha256s(tmp_path) == before and not list((tmp_path / "outside").iterdir())
