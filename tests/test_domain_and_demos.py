"""domain.toml and CSV demonstrations: valid files load, bad ones give one `path:line:` error."""

from __future__ import annotations

import pytest

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
