"""The readers at their limits: files with a BOM read like files without, inputs exactly at each
limit in teach.limits are accepted and one more is refused with its line, and values are strict
(digits only, ASCII)."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import BALL_DOMAIN, colledanchise_tree

from teach import limits
from teach.bt.xml import read_tree, tree_to_xml
from teach.demos import parse_demonstration, read_demo_set
from teach.dialogue.script import read_script
from teach.domain import Domain, load_domain
from teach.errors import FormatError

BOM = b"\xef\xbb\xbf"
GOOD_DEMO = "0;0;0;0;0;1\n1;0;0;0;0;2\n1;1;0;0;0;3\n1;1;1;0;0;4\n1;1;1;1;0;5\n1;1;1;1;1;0\n"


def test_a_utf8_bom_changes_nothing(tmp_path: Path, ball: Domain) -> None:
    (tmp_path / "domain.toml").write_bytes(BOM + BALL_DOMAIN.read_bytes())
    (tmp_path / "d1.csv").write_bytes(BOM + GOOD_DEMO.encode())
    domain, demos = read_demo_set(tmp_path)
    assert domain.conditions == ball.conditions and domain.actions == ball.actions
    assert demos[0].steps == parse_demonstration(GOOD_DEMO, ball, "d1.csv").steps
    (tmp_path / "t.xml").write_bytes(BOM + tree_to_xml(colledanchise_tree()).encode())
    assert read_tree(tmp_path / "t.xml") == colledanchise_tree()
    (tmp_path / "a.dialogue").write_bytes(BOM + b"@lang de\nfertig\n")
    assert read_script(tmp_path / "a.dialogue").settings == {"lang": "de"}


def domain_text(conditions: int, actions: int) -> str:
    return ("".join(f'[[condition]]\nname = "C{i}"\n\n' for i in range(conditions))
            + "".join(f'[[action]]\nid = {i + 1}\nname = "A{i}"\nen = ["do {i}"]\n\n' for i in range(actions)))


def test_domains_up_to_the_limits_load_and_one_more_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "domain.toml"
    path.write_text(domain_text(limits.MAX_CONDITIONS, limits.MAX_ACTIONS))
    domain = load_domain(path)
    assert len(domain.conditions) == limits.MAX_CONDITIONS and len(domain.actions) == limits.MAX_ACTIONS
    for conditions, actions, header in ((limits.MAX_CONDITIONS + 1, 1, "[[condition]]"),
                                        (1, limits.MAX_ACTIONS + 1, "[[action]]")):
        path.write_text(domain_text(conditions, actions))
        with pytest.raises(FormatError, match=r"a domain may have at most") as caught:
            load_domain(path)
        assert header in caught.value.message
        assert path.read_text().splitlines()[caught.value.line - 1] == header  # type: ignore[operator]


def wide_tree(leaves: int) -> str:
    """A tree file of exactly ``leaves + 5`` elements."""
    return ('<root BTCPP_format="4">\n<BehaviorTree ID="M">\n<ReactiveFallback>\n' + "<A/>\n" * leaves
            + "</ReactiveFallback>\n</BehaviorTree>\n<TreeNodesModel><Action ID=\"A\"/></TreeNodesModel>\n</root>\n")


def test_trees_up_to_the_node_limit_load_and_one_more_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "t.xml"
    path.write_text(wide_tree(limits.MAX_TREE_NODES - 5))
    read_tree(path)
    text = wide_tree(limits.MAX_TREE_NODES - 4)
    path.write_text(text)
    with pytest.raises(FormatError, match=f"more than {limits.MAX_TREE_NODES} elements") as caught:
        read_tree(path)
    # the element past the limit is the last one, the model's <Action ID="A"/> on the last line but one
    assert caught.value.line == len(text.splitlines()) - 1


def test_demonstrations_up_to_the_line_limit_load_and_one_more_is_refused(ball: Domain) -> None:
    line = "0;0;0;0;0;1\n"
    assert len(parse_demonstration(line * limits.MAX_DEMO_LINES, ball, "d.csv").steps) == limits.MAX_DEMO_LINES
    with pytest.raises(FormatError, match="more than") as caught:
        parse_demonstration(line * (limits.MAX_DEMO_LINES + 1), ball, "d.csv")
    assert caught.value.line == limits.MAX_DEMO_LINES + 1


def test_equal_states_share_one_tuple(ball: Domain) -> None:
    demo = parse_demonstration("0;0;0;0;0;1\n0;0;0;0;0;-1\n0;0;0;0;0;1\n1;0;0;0;0;0\n", ball, "d.csv")
    assert demo.steps[0].state is demo.steps[1].state is demo.steps[2].state


@pytest.mark.parametrize("action", ["+3", "0_3", "３", "٣", " 3", "3.0", "0x3", "-0", "-3", "--1", "1e0", ""])
def test_action_ids_are_ascii_digits_only(ball: Domain, action: str) -> None:
    with pytest.raises(FormatError, match="action ID must be an integer written in digits") as caught:
        parse_demonstration(f"0;0;0;0;0;1\n1;0;0;0;0;{action}\n", ball, "d.csv")
    assert caught.value.line == 2


@pytest.mark.parametrize("value", ["+1", " 1", "１", "true", "01", ""])
def test_condition_values_are_0_or_1_only(ball: Domain, value: str) -> None:
    with pytest.raises(FormatError, match="must be 0 or 1") as caught:
        parse_demonstration(f"0;0;0;0;0;1\n{value};0;0;0;0;0\n", ball, "d.csv")
    assert caught.value.line == 2


def test_the_usual_ids_still_read(ball: Domain) -> None:
    demo = parse_demonstration("0;0;0;0;0;1\n1;0;0;0;0;-1\n1;0;0;0;0;2\n1;1;0;0;0;0\r\n", ball, "d.csv")
    assert [step.action for step in demo.steps] == [1, -1, 2, 0]


@pytest.mark.parametrize(("setting", "words"), [
    ("@lang fr", "unknown language 'fr' (known: en, de)"),
    ("@world mars", "@world must be one of mujoco, symbolic, offline"),
    ("@questions -1", "0 or more"),
    ("@questions +3", "written in digits"),
    ("@questions ３", "written in digits"),
    ("@seed 1_0", "written in digits"),
    ("@domain", "@domain needs a value"),
])
def test_dialogue_settings_are_checked_where_they_are_written(tmp_path: Path, setting: str, words: str) -> None:
    path = tmp_path / "a.dialogue"
    path.write_text(f"# settings\n{setting}\nhelp\n")
    with pytest.raises(FormatError) as caught:
        read_script(path)
    assert words in caught.value.message and caught.value.line == 2 and caught.value.path == str(path)


def test_good_dialogue_settings_read(tmp_path: Path) -> None:
    path = tmp_path / "a.dialogue"
    path.write_text("@lang de\n@world symbolic\n@questions 0\n@seed 7\n@domain d.toml\nhilfe\n")
    assert read_script(path).settings == {"lang": "de", "world": "symbolic", "questions": 0, "seed": 7,
                                          "domain": "d.toml"}
