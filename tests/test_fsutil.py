"""The one reader and the one writer: special files, bounds, encodings, nesting, typed JSON,
writes that refuse to destroy and a real full disk."""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from conftest import ROOT

from teach.errors import FormatError, TeachError
from teach.fsutil import (
    atomic_write_bytes,
    atomic_write_text,
    check_nesting,
    check_output,
    check_output_folder,
    parse_json,
    read_bytes,
    read_json,
    read_text,
    validate,
)

# --- reading ------------------------------------------------------------------------------------


def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path: Path) -> None:
    fifo = tmp_path / "tree.xml"
    os.mkfifo(fifo)
    # no process ever opens the FIFO for writing: a blocking open would hang here for ever
    with pytest.raises(FormatError, match="named pipe"):
        read_bytes(fifo, "tree file", 100)


def test_a_session_file_that_is_a_link_is_refused_on_read(tmp_path: Path) -> None:
    """A session's own files (the journal) are never read through a link, as they are never
    written through one; other inputs may be links, but never to a special file."""
    (tmp_path / "real.json").write_text("{}")
    (tmp_path / "journal.json").symlink_to("real.json")
    with pytest.raises(FormatError, match="is a symbolic link, not a session journal"):
        read_bytes(tmp_path / "journal.json", "session journal", 100, links=False)
    assert read_bytes(tmp_path / "journal.json", "session journal", 100) == b"{}"
    os.mkfifo(tmp_path / "pipe")
    (tmp_path / "to-pipe").symlink_to("pipe")
    with pytest.raises(FormatError, match="named pipe"):
        read_bytes(tmp_path / "to-pipe", "run log", 100)


@pytest.mark.parametrize(("path", "kind"), [("/dev/zero", "character device"), ("/dev/null", "character device")])
def test_devices_are_refused_before_any_byte_is_read(path: str, kind: str) -> None:
    with pytest.raises(FormatError, match=kind):
        read_bytes(path, "domain file", 100)


def test_folders_and_sockets_are_refused(tmp_path: Path) -> None:
    with pytest.raises(FormatError, match="a folder, not a dialogue"):
        read_text(tmp_path, "dialogue")
    address = tmp_path / "s.sock"
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(address))
        with pytest.raises(FormatError, match="a socket"):
            read_text(address, "dialogue")


def test_the_limit_holds_whatever_st_size_says(tmp_path: Path) -> None:
    # /proc files are regular files that report st_size 0 and still hold bytes
    status = Path("/proc/self/status")
    assert status.stat().st_size == 0
    with pytest.raises(FormatError, match="more than the 16 bytes"):
        read_bytes(status, "demonstration", 16)
    exact = tmp_path / "exact.csv"
    exact.write_bytes(b"x" * 16)
    assert read_bytes(exact, "demonstration", 16) == b"x" * 16
    exact.write_bytes(b"x" * 17)
    with pytest.raises(FormatError, match="more than the 16 bytes"):
        read_bytes(exact, "demonstration", 16)


def test_missing_files_name_what_was_expected(tmp_path: Path) -> None:
    with pytest.raises(FormatError) as caught:
        read_text(tmp_path / "nope.toml", "domain file")
    assert str(caught.value) == f"{tmp_path / 'nope.toml'}: cannot read domain file: No such file or directory"


def test_text_loses_its_bom_and_bad_bytes_name_their_line(tmp_path: Path) -> None:
    path = tmp_path / "a.dialogue"
    path.write_bytes(b"\xef\xbb\xbfhello\n")
    assert read_text(path, "dialogue") == "hello\n"
    path.write_bytes(b"one\ntwo\n\xc3(\n")
    with pytest.raises(FormatError) as caught:
        read_text(path, "dialogue")
    assert caught.value.line == 3 and "not a UTF-8 text file" in caught.value.message
    path.write_bytes(b"one\nt\x00wo\n")
    with pytest.raises(FormatError) as caught:
        read_text(path, "dialogue")
    assert caught.value.line == 2 and "NUL" in caught.value.message


@pytest.mark.parametrize("text", [
    "x = " + "[" * 500 + "]" * 500,
    "x = " + "{a = " * 500 + "1" + "}" * 500,
    "a" + ".a" * 500 + " = 1",
    '"a"' + '."a"' * 500 + " = 1",
])
def test_deep_toml_is_refused_before_parsing(text: str) -> None:
    with pytest.raises(FormatError, match="more than 32 levels") as caught:
        check_nesting("# fine\n" + text + "\n", "d.toml", "toml")
    assert caught.value.line == 2


def test_brackets_in_strings_and_comments_do_not_count() -> None:
    brackets = "[" * 100
    check_nesting(f'a = "{brackets}"\nb = \'{brackets}\'\n# {brackets}\nc = """\n{brackets}\n"""\n', "d.toml", "toml")
    check_nesting(f'{{"a": "{brackets}\\"{brackets}"}}', "j.json", "json")
    check_nesting("x = " + "[" * 32 + "]" * 32, "d.toml", "toml")


def test_json_refuses_depth_nan_and_infinity_with_their_line() -> None:
    with pytest.raises(FormatError, match="more than 32 levels"):
        parse_json("[" * 1200 + "]" * 1200, "j.json")
    for constant in ("NaN", "Infinity", "-Infinity"):
        with pytest.raises(FormatError, match=f"holds {constant}") as caught:
            parse_json(f'{{"a": 1,\n "step": {constant}}}', "j.json")
        assert caught.value.line == 2
    assert parse_json('{"text": "NaN and Infinity"}', "j.json") == {"text": "NaN and Infinity"}
    with pytest.raises(FormatError, match="not valid JSON") as caught:
        parse_json('{"a":\n', "j.json")
    assert caught.value.line == 2


def test_read_json_reads_a_bounded_file(tmp_path: Path) -> None:
    path = tmp_path / "j.json"
    path.write_text('{"a": [1, 2]}')
    assert read_json(path) == {"a": [1, 2]}
    with pytest.raises(FormatError, match="more than the 5 bytes"):
        read_json(path, limit=5)


SCHEMA = {"domain": str, "questions": int, "events": list}


@pytest.mark.parametrize(("data", "message"), [
    ({"domain": 5, "questions": 5, "events": []}, "domain: must be a string, got 5"),
    ({"domain": "d", "questions": "five", "events": []}, 'questions: must be an integer, got "five"'),
    ({"domain": "d", "questions": True, "events": []}, "questions: must be an integer, got true"),
    ({"domain": "d", "events": []}, "questions: missing (it must be an integer)"),
    ({"domain": "d", "questions": 5, "events": [], "colour": 1}, "colour: unknown key"),
    ({"domain": "d", "questions": 5, "events": [], "step": None}, "step: must be an integer, got null"),
    ([1, 2], "must be an object, got [1, 2]"),
])
def test_validate_names_the_key_and_what_is_wrong(data: object, message: str) -> None:
    with pytest.raises(FormatError) as caught:
        validate(data, "j.json", SCHEMA, {"step": int}, where="journal")
    assert str(caught.value).startswith("j.json: journal: ")
    assert message in str(caught.value)


def test_validate_accepts_good_data_and_numbers_for_floats() -> None:
    good = {"domain": "d", "questions": 5, "events": [], "x": 2}
    assert validate(good, "j.json", SCHEMA, {"x": float}) is good
    assert validate({"a": 1, "b": 2}, "j.json", {"a": int}, extra=True) == {"a": 1, "b": 2}


# --- writing ------------------------------------------------------------------------------------


def leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def test_a_regular_file_is_replaced_atomically_with_the_umask_mode(tmp_path: Path) -> None:
    target = tmp_path / "a" / "b" / "t.xml"
    atomic_write_text(target, "one", root=tmp_path)
    atomic_write_text(target, "two", root=tmp_path)
    assert target.read_text() == "two"
    mask = os.umask(0)
    os.umask(mask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~mask
    assert leftovers(target.parent) == []


def test_symlinks_fifos_devices_and_folders_are_never_replaced(tmp_path: Path) -> None:
    real = tmp_path / "real.xml"
    real.write_text("keep")
    link = tmp_path / "link.xml"
    link.symlink_to(real)
    fifo = tmp_path / "fifo.xml"
    os.mkfifo(fifo)
    for target, words in ((link, "symbolic link"), (fifo, "named pipe"), (Path("/dev/null"), "character device"),
                          (Path("/dev/stdout"), "symbolic link"), (tmp_path, "is a folder")):
        with pytest.raises(TeachError, match=words):
            atomic_write_text(target, "new", root=tmp_path)
    assert link.is_symlink() and real.read_text() == "keep"
    assert fifo.is_fifo() and Path("/dev/null").is_char_device()
    assert leftovers(tmp_path) == []


def test_no_write_through_a_symlinked_folder_inside_the_project(tmp_path: Path) -> None:
    outside = tmp_path / "outside"
    outside.mkdir()
    project = tmp_path / "project"
    (project / "demos").mkdir(parents=True)
    (project / "demos" / "ball").symlink_to(outside, target_is_directory=True)
    with pytest.raises(TeachError, match="symbolic link: refusing to write through it"):
        atomic_write_text(project / "demos" / "ball" / "sub" / "d.csv", "x", root=project)
    with pytest.raises(TeachError, match="symbolic link"):
        check_output_folder(project / "demos" / "ball", root=project)
    assert list(outside.iterdir()) == []


def test_a_file_in_the_folder_chain_is_refused_before_anything_is_created(tmp_path: Path) -> None:
    (tmp_path / "l.xml").write_text("tree")
    with pytest.raises(TeachError, match="is not a folder"):
        check_output(tmp_path / "l.xml" / "gens" / "gen-00.xml", root=tmp_path)
    with pytest.raises(TeachError, match="cannot write here"):
        check_output_folder("/proc/teach-gens")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["l.xml"]


def test_os_errors_are_one_line_naming_the_file(tmp_path: Path) -> None:
    readonly = tmp_path / "ro"
    readonly.mkdir()
    with _mounted(readonly, "-o", "ro,size=16k") as mounted:
        if not mounted:
            pytest.skip("mounting a read-only tmpfs needs root (not running as root here)")
        with pytest.raises(TeachError) as caught:
            atomic_write_text(readonly / "t.xml", "x", root=tmp_path)
    assert str(caught.value).startswith(f"{readonly / 't.xml'}: cannot write here")
    assert "\n" not in str(caught.value)


@contextlib.contextmanager
def _mounted(folder: Path, *options: str) -> Iterator[bool]:
    """A small tmpfs mounted on ``folder`` while the block runs; False when this user cannot mount."""
    if os.geteuid() != 0 or shutil.which("mount") is None:
        yield False
        return
    done = subprocess.run(["mount", "-t", "tmpfs", *options, "tmpfs", str(folder)], capture_output=True)
    if done.returncode != 0:
        yield False
        return
    try:
        yield True
    finally:
        subprocess.run(["umount", "-l", str(folder)], check=True)


def test_a_full_disk_leaves_the_old_file_and_no_temporary_one(tmp_path: Path) -> None:
    disk = tmp_path / "disk"
    disk.mkdir()
    with _mounted(disk, "-o", "size=64k") as mounted:
        if not mounted:
            pytest.skip("the disk-full test mounts a 64 KiB tmpfs, which needs root (not running as root here)")
        target = disk / "journal.json"
        atomic_write_bytes(target, b"old", root=tmp_path)
        with pytest.raises(TeachError) as caught:
            atomic_write_bytes(target, b"x" * 200_000, root=tmp_path)
        assert str(caught.value) == f"{target}: cannot write: No space left on device"
        assert target.read_bytes() == b"old"
        assert leftovers(disk) == []
        # and through the command line: one line naming the file, exit 2, no traceback
        (disk / "filler").write_bytes(b"f" * (64 * 1024 - 4096 - 100))
        done = subprocess.run([sys.executable, "-m", "teach.cli", "dot", str(ROOT / "demos/ball/reference/table61.xml"),
                               "-o", str(disk / "tree.dot")], cwd=tmp_path, capture_output=True, text=True,
                              env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
        assert done.returncode == 2
        assert done.stderr == f"teach: {disk / 'tree.dot'}: cannot write: No space left on device\n"
        assert sorted(p.name for p in disk.iterdir()) == ["filler", "journal.json"]


def test_the_writers_of_demonstrations_and_trees_take_the_project_root(tmp_path: Path, ball) -> None:  # type: ignore[no-untyped-def]
    from conftest import colledanchise_tree

    from teach.bt.xml import write_tree
    from teach.demos import parse_demonstration, write_demonstration

    outside = tmp_path / "outside"
    outside.mkdir()
    (tmp_path / "demos").symlink_to(outside, target_is_directory=True)
    demo = parse_demonstration("0;0;0;0;0;1\n1;0;0;0;0;0\n", ball, "d.csv")
    with pytest.raises(TeachError, match="symbolic link"):
        write_demonstration(tmp_path / "demos" / "s" / "demo-001.csv", demo, root=tmp_path)
    with pytest.raises(TeachError, match="symbolic link"):
        write_tree(tmp_path / "demos" / "gen-01.xml", colledanchise_tree(), tmp_path)
    assert list(outside.iterdir()) == []
