"""The readers' schemas are strict: a key nobody reads is refused with the allowed ones, a number
is bounded before it is converted, and a world.toml that is not a file is refused, not ignored."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from conftest import BALL_DOMAIN, ROOT
from hostile_corpus import GOOD_MOTION

from teach.domain import load_domain
from teach.errors import FormatError
from teach.session.journal import Journal, check_open_actions
from teach.sim.guided_skill import load_motion
from teach.world.hidden import symbolic_world

SNACKS = ROOT / "demos" / "snacks"


def snacks_with_world(tmp_path: Path, make: str) -> Path:
    (tmp_path / "domain.toml").write_bytes((SNACKS / "domain.toml").read_bytes())
    world = tmp_path / "world.toml"
    if make == "fifo":
        os.mkfifo(world)
    elif make == "folder":
        world.mkdir()
    else:
        world.write_text(make, encoding="utf-8")
    return tmp_path / "domain.toml"


@pytest.mark.parametrize("make, message", [
    ("fifo", "is a named pipe (FIFO), not a world file"),
    ("folder", "is a folder, not a world file"),
    ('start = ["AtOffice"]\nstrat = []\n', "unknown key 'strat' at the top level (allowed: start, random_start, "),
    ('[[variable]]\nname = "n"\nmin = 0\nmax = 1\n[[derived]]\ncondition = "TrayEmpty"\n'
     f'when = "n == {"9" * 5000}"\n', "'when' must read like"),
    ("[[variable]]\nname = 'n'\nmin = " + "9" * 4301 + "\n", "a number with more than 4300 digits"),
])
def test_a_world_file_that_is_not_a_good_file_is_refused(tmp_path: Path, make: str, message: str) -> None:
    domain = load_domain(snacks_with_world(tmp_path, make))
    with pytest.raises(FormatError) as caught:
        symbolic_world(domain)
    assert caught.value.path == str(tmp_path / "world.toml") and message in caught.value.message
    assert len(str(caught.value)) < 300


def test_the_repository_world_still_loads() -> None:
    assert symbolic_world(load_domain(SNACKS / "domain.toml")).events


@pytest.mark.parametrize("old, new, line, message", [
    ('"lift": 0,', '"lift": 0,\n  "lfit": 1,', 11, "unknown key 'lfit' (allowed: format, version, name, "),
    ('"lift": 0', '"lift": ' + "9" * 400, 10, "'lift' must be a number"),
    ('"lift": 0', '"lift": ' + "9" * 4301, 10, "a number with more than 4300 digits"),
])
def test_motion_files_are_strict(tmp_path: Path, old: str, new: str, line: int, message: str) -> None:
    path = tmp_path / "PushBall.motion.json"
    path.write_text(GOOD_MOTION.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(FormatError) as caught:
        load_motion(path, load_domain(BALL_DOMAIN))
    assert caught.value.line == line and caught.value.message.startswith(message), caught.value


def test_the_corpus_good_motion_loads(tmp_path: Path) -> None:
    path = tmp_path / "PushBall.motion.json"
    path.write_text(GOOD_MOTION, encoding="utf-8")
    assert load_motion(path, load_domain(BALL_DOMAIN)).name == "PushBall"


def journal_text(**changes: object) -> str:
    data = {"session": "S", "domain": str(BALL_DOMAIN), "lang": "en", "questions": 5, "world": "offline",
            "seed": 0, "step": 1, "events": [], "version": 2, **changes}
    return json.dumps(data) + "\n"


def test_open_steps_must_name_the_domains_actions(tmp_path: Path) -> None:
    where = tmp_path / "S.journal.json"
    ball = load_domain(BALL_DOMAIN)
    steps = [["00000", 1, "find"], ["10000", -1, "the ball moved"], ["10000", 0, ""]]
    check_open_actions(Journal.from_text(journal_text(open_steps=steps, open_state="10000"), where), ball, where)
    journal = Journal.from_text(journal_text(open_steps=[["00000", 77, "x"]], open_state="10000"), where)
    with pytest.raises(FormatError, match=r"open_steps\[0\]: action 77 is not an action of the domain"):
        check_open_actions(journal, ball, where)


@pytest.mark.parametrize("text, line", [
    (journal_text().replace('"step": 1', '"step": ' + "9" * 4301), 1),
    (journal_text() + '{"step": ' + "9" * 4301 + "}\n", 2),
    (journal_text(stpe=1), 1),
])
def test_journal_numbers_and_keys_are_bounded_and_named_with_their_line(tmp_path: Path, text: str,
                                                                        line: int) -> None:
    with pytest.raises(FormatError) as caught:
        Journal.from_text(text, tmp_path / "S.journal.json")
    assert caught.value.line == line and "the session journal is damaged" in caught.value.message
