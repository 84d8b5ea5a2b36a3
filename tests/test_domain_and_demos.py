"""domain.toml and CSV demonstrations: valid files load, bad ones give one `path:line:` error."""

from __future__ import annotations

import pytest
from hostile_corpus import TINY

from teach.demos import Step, parse_demonstration, read_demo_set, write_demonstration
from teach.domain import Literal, load_domain
from teach.errors import FormatError


def test_ball_domain(ball):
    assert ball.condition_names[0] == "BallFound"
    assert ball.action(3).name == "GraspBall"
    assert Literal("BallGrasped", False) in ball.action("GraspBall").pre
    assert ball.goal == (Literal("BallPlaced"),)


def test_demo_round_trip(ball, tmp_path):
    text = "0;0;0;0;0;1\n1;0;0;0;0;-1\n0;0;0;0;0;1\n1;0;0;0;0;0\n"
    demo = parse_demonstration(text, ball, "x.csv")
    assert demo.actions == (1, 1) and demo.reached_goal
    write_demonstration(tmp_path / "d" / "a.csv", demo)
    (tmp_path / "domain.toml").write_text((ball.path).read_text())
    _, [again] = read_demo_set(tmp_path / "d")
    assert again.steps == tuple(Step(s.state, s.action, s.line) for s in demo.steps)


def test_a_set_is_read_in_name_order_and_one_too_many_files_is_refused_before_any_is_read(ball, tmp_path):
    from teach import limits

    folder = tmp_path / "d"
    folder.mkdir()
    for name in ["b.csv", "a.csv", "c.csv"]:
        (folder / name).write_text("0;0;0;0;0;1\n1;0;0;0;0;0\n", encoding="utf-8")
    (folder / "sub.csv").mkdir()  # a folder is no demonstration; nor are .csv and notes.txt
    (folder / ".csv").write_text("junk", encoding="utf-8")
    (folder / "notes.txt").write_text("junk", encoding="utf-8")
    _, demos = read_demo_set(folder, ball)
    assert [d.name for d in demos] == ["a", "b", "c"]
    for number in range(limits.MAX_DEMOS + 1 - 3):  # empty: reading any of them would be an error
        (folder / f"e{number:05d}.csv").touch()
    with pytest.raises(FormatError) as caught:
        read_demo_set(folder, ball)
    assert caught.value.message == f"more than {limits.MAX_DEMOS} demonstrations: a set may hold at most " \
                                   f"{limits.MAX_DEMOS}"




@pytest.mark.parametrize("text, line, words", [
    ("0;0;0;0;1\n", 1, "expected 6 fields"),
    ("0;0;2;0;0;1\n", 1, "must be 0 or 1"),
    ("0;0;0;0;0;9\n", 1, "unknown action ID 9"),
    ("0;0;0;0;0;0\n0;0;0;0;0;1\n", 2, "after the goal line"),
    ("0;0;0;0;0;1\n0;0;0;0;0;-1\n", 2, "no following state"),
    ("0;0;0;0;0;x\n", 1, "must be an integer"),
    ("", None, "empty demonstration"),
    ("0;0;0;0;0;1\u20281;0;0;0;0;0\n", 1, "character U+2028 at column 12 is not allowed"),
    ("0;0;0;0;0;1\n1;0;0;0;0;2\x0c\n1;1;0;0;0;0\n", 2, "character U+000C at column 12"),
    ("0;0;0;0;0;1\x85\n1;0;0;0;0;0\n", 1, "character U+0085"),
    ("0;0;0;0;0;1\u00a0\n1;0;0;0;0;0\n", 1, "character U+00A0"),
    ("\u00a00;0;0;0;0;1\n1;0;0;0;0;0\n", 1, "character U+00A0 at column 1"),
    ("0;0;0;0;0;1\r1;0;0;0;0;0\n", 1, "character U+000D"),
])
def test_bad_demonstrations(ball, text, line, words):
    with pytest.raises(FormatError) as info:
        parse_demonstration(text, ball, "bad.csv")
    assert info.value.line == line and words in str(info.value)
    assert str(info.value).startswith("bad.csv:")


@pytest.mark.parametrize("body, words", [
    ('name = "x"\n[[condition]]\nname = "A"\n[[condition]]\nname = "A"\n[[action]]\nid = 1\nname = "X"\n',
     "duplicate condition name"),
    ('[[condition]]\nname = "A"\n[[action]]\nid = 0\nname = "X"\n', "'id' must be an integer >= 1"),
    ('[[condition]]\nname = "A"\n[[action]]\nid = 1\nname = "X"\npre = ["B"]\n', "unknown condition 'B'"),
    ('[[condition]]\nname = "A"\n[[action]]\nid = 1\nname = "X"\n[[action]]\nid = 1\nname = "Y"\n',
     "duplicate action id 1"),
    ('[[condition]\nname = "A"\n', "invalid TOML"),
    ('goal = ["Nope"]\n[[condition]]\nname = "A"\n[[action]]\nid = 1\nname = "X"\n', "unknown condition 'Nope'"),
])
def test_bad_domains(tmp_path, body, words):
    path = tmp_path / "domain.toml"
    path.write_text(body)
    with pytest.raises(FormatError) as info:
        load_domain(path)
    assert words in str(info.value) and info.value.line is not None


def test_phrases_that_mean_a_step_only_when_something_holds(tmp_path):
    path = tmp_path / "domain.toml"
    path.write_text(TINY + 'when = ["Ready", "!Done"]\nen_when = ["work hard"]\nde_when = ["arbeite hart"]\n')
    work = load_domain(path).action("Work")
    assert work.when == (Literal("Ready"), Literal("Done", False))
    assert (work.en_when, work.de_when) == (("work hard",), ("arbeite hart",))
    assert work.label("en") == "Work"  # a phrase that needs something is never the step's label


def test_crlf_and_trailing_ascii_blanks_end_a_line_unseen(ball):
    demo = parse_demonstration("0;0;0;0;0;1 \t\r\n1;0;0;0;0;0\r\n\r\n", ball, "ok.csv")
    assert [s.action for s in demo.steps] == [1, 0]


@pytest.mark.parametrize("body, line, message", [
    (TINY.replace('pre = ["Ready"]', 'prex = ["Ready"]'), 13,
     "unknown key 'prex' in [[action]] (allowed: id, name, en, de, pre, ram, form, when, en_when, de_when)"),
    (TINY.replace('name = "Done"', 'name = "Done"\nlabel = "x"'), 9,
     "unknown key 'label' in [[condition]] (allowed: name, en, de, en_false, de_false, form)"),
    ("goals = []\n" + TINY, 1, "unknown key 'goals' at the top level (allowed: name, goal, condition, action)"),
    (TINY + "\n[meta]\nx = 1\n", 16, "unknown key 'meta' at the top level"),
    (TINY.replace("id = 1", "id = " + "9" * 5000), 11, "a number with more than 4300 digits"),
    (TINY.replace("id = 1", "id = 0x" + "f" * 4000), 11, "a number with more than 4300 digits"),
    ("# \u2028 \x85\n" + TINY.replace("ram =", "rma ="), 15, "unknown key 'rma'"),
    (TINY + 'when = ["Ready"]\n', 15, "action Work: 'when' and the phrases that need it ('en_when', 'de_when') go"),
    (TINY + 'en_when = ["work hard"]\n', 15, "action Work: 'when' and the phrases that need it"),
    (TINY + 'when = ["Busy"]\nen_when = ["work hard"]\n', 15, "action Work: 'when' names unknown condition 'Busy'"),
    (TINY + 'when = ["Ready"]\nde_when = 3\n', 16, "action Work: 'de_when' must be a list of phrases"),
    (TINY + 'en = ["work"]\nwhen = ["Ready"]\nen_when = ["Work "]\n', 17,
     "action Work: 'Work ' is in 'en_when' and a plain phrase of Work"),
])
def test_domain_keys_and_numbers_are_strict(tmp_path, body, line, message):
    path = tmp_path / "domain.toml"
    path.write_text(body, encoding="utf-8")
    with pytest.raises(FormatError) as info:
        load_domain(path)
    assert info.value.message.startswith(message) and info.value.line == line, info.value


def test_the_recordings_domain_document_names_what_a_phrase_needs(ball):
    from teach.observe.markdown import domain_document
    row = next(line for line in domain_document(ball).splitlines() if "| ApproachBin |" in line)
    assert "head to the bin, go over to the bin; while BallGrasped: take the ball to the bin" in row
