"""Every refusal is one line that is safe to print, in real processes: file names with a newline,
ANSI escapes, U+202E or bytes that are not UTF-8; usage errors; an output encoding that cannot
hold German; a closed standard input; a line history that is a folder; a dialogue line too long."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT

from teach.errors import printable

ENV = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "LANG": "C.UTF-8"}


def teach(*args: str | bytes, cwd: Path, env: dict[str, str] | None = None, close: int | None = None,
          ) -> subprocess.CompletedProcess[bytes]:
    """``teach ARGS`` in a fresh process; ``close``: a standard stream's descriptor closed before it starts."""
    return subprocess.run([sys.executable, "-m", "teach.cli", *args], cwd=cwd, capture_output=True,
                          stdin=subprocess.DEVNULL, env={**ENV, **(env or {})},
                          preexec_fn=None if close is None else lambda: os.close(close), check=False)


def one_line(done: subprocess.CompletedProcess[bytes]) -> str:
    """The single error line of a refused command, checked: exit 2, nothing on stdout, no traceback."""
    err = done.stderr.decode("utf-8")
    assert done.returncode == 2, err
    assert not done.stdout and "Traceback" not in err
    assert err.startswith("teach: ") and err.endswith("\n") and err.count("\n") == 1, repr(err)
    return err


def files(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def test_printable_escapes_what_would_break_the_line() -> None:
    assert printable("a\nb\r\t\x1b[31m\u202eZ\u2028\x85") == "a\\nb\\r\\t\\x1b[31m\\u202eZ\\u2028\\x85"
    assert printable("Größe “ok” ✓") == "Größe “ok” ✓"
    assert printable(os.fsdecode(b"bad\xff.xml")) == "bad\\xff.xml"


@pytest.mark.parametrize("name", [b"two\nlines.xml", b"\x1b[31mred\x1b[0m.xml", "evil\u202elmx.xml".encode(),
                                  b"not-utf8-\xff.xml", b"bell\x07.xml"])
def test_a_hostile_file_name_is_escaped_in_one_line(tmp_path: Path, name: bytes) -> None:
    (tmp_path / os.fsdecode(name)).write_bytes(b"<root>")  # a tree that is not one
    for args in ((b"show", name), (b"show", name + b".missing")):
        err = one_line(teach(*args, cwd=tmp_path))
        assert printable(os.fsdecode(name)) in err
        assert not any(char in err for char in "\x1b\u202e\x07")


@pytest.mark.parametrize("args", [("learn",), ("session", "--questions", "x"), ("frobnicate",), ("--frob",),
                                  ("session", "--lang", "\x1b[2J\u202e")])
def test_usage_errors_are_one_line_with_a_hint_to_help(tmp_path: Path, args: tuple[str, ...]) -> None:
    err = one_line(teach(*args, cwd=tmp_path))
    assert "usage:" not in err and "--help)" in err and "\x1b" not in err


def test_an_ascii_terminal_gets_escapes_not_a_traceback(tmp_path: Path) -> None:
    done = teach("replay", str(ROOT / "dialogues" / "deutsch.dialogue"), "--world", "offline", "--no-record",
                 "--base", str(tmp_path), cwd=tmp_path, env={"PYTHONIOENCODING": "ascii"})
    assert done.returncode == 0 and b"Traceback" not in done.stderr, done.stderr[-500:]
    assert b"Sitzung deutsch" in done.stdout and b"sp\\xe4ter" in done.stdout  # "später" as escapes
    done.stdout.decode("ascii")


def test_a_closed_standard_input_is_one_line_and_creates_nothing(tmp_path: Path) -> None:
    err = one_line(teach("session", "--world", "offline", "--no-record", cwd=tmp_path, close=0))
    assert err.startswith("teach: <stdin>: standard input is closed")
    assert files(tmp_path) == []


def test_a_closed_standard_error_keeps_the_error_off_standard_output(tmp_path: Path) -> None:
    done = teach("show", "missing.xml", cwd=tmp_path, close=2)
    assert done.returncode == 2 and done.stdout == b""


def test_a_history_that_is_a_folder_is_refused_in_one_line_before_the_session_opens(tmp_path: Path) -> None:
    first = teach("session", "--session", "s", "--world", "offline", "--no-record", cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    history = tmp_path / "recordings" / ".teach_history"
    history.unlink(missing_ok=True)
    history.mkdir()
    err = one_line(teach("session", "--resume", "s", "--no-record", cwd=tmp_path))
    assert err == "teach: recordings/.teach_history: is a folder: give a file name to write\n", err
    assert history.is_dir() and not any(history.iterdir())


def test_a_dialogue_line_too_long_names_its_file_and_line(tmp_path: Path) -> None:
    (tmp_path / "long.dialogue").write_text("@lang en\nhelp\n" + "help " * 120 + "\n", encoding="utf-8")
    err = one_line(teach("replay", "long.dialogue", "--world", "offline", "--no-record", cwd=tmp_path))
    assert err.startswith("teach: long.dialogue:3: the line is too long (599 characters, at most 500)")
    assert files(tmp_path) == ["long.dialogue"]
