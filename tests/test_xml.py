"""BehaviorTree.CPP v4 XML: exact round trips, the written form, and errors that name the line."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import colledanchise_tree
from hypothesis import given, settings
from strategies import trees

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Parallel, Sequence, walk
from teach.bt.xml import MAX_BYTES, MAX_NODES, read_tree, tree_from_xml, tree_to_xml, write_tree
from teach.errors import FormatError

CONDITIONS = ["BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced"]
ACTIONS = ["FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall"]

COLLEDANCHISE_XML = """\
<?xml version="1.0" encoding="UTF-8"?>
<root BTCPP_format="4" main_tree_to_execute="MainTree">
  <BehaviorTree ID="MainTree">
    <ReactiveSequence>
      <ReactiveFallback>
        <BallFound/>
        <FindBall/>
      </ReactiveFallback>
      <ReactiveFallback>
        <BallClose/>
        <ApproachBall/>
      </ReactiveFallback>
      <ReactiveFallback>
        <BallGrasped/>
        <GraspBall/>
      </ReactiveFallback>
      <ReactiveFallback>
        <BinClose/>
        <ApproachBin/>
      </ReactiveFallback>
      <ReactiveFallback>
        <BallPlaced/>
        <PlaceBall/>
      </ReactiveFallback>
    </ReactiveSequence>
  </BehaviorTree>
  <TreeNodesModel>
    <Action ID="ApproachBall"/>
    <Action ID="ApproachBin"/>
    <Action ID="FindBall"/>
    <Action ID="GraspBall"/>
    <Action ID="PlaceBall"/>
    <Condition ID="BallClose"/>
    <Condition ID="BallFound"/>
    <Condition ID="BallGrasped"/>
    <Condition ID="BallPlaced"/>
    <Condition ID="BinClose"/>
  </TreeNodesModel>
</root>
"""


def wrap(body: str, model: str = "") -> str:
    return (f'<root BTCPP_format="4" main_tree_to_execute="MainTree">\n<BehaviorTree ID="MainTree">\n{body}\n'
            f"</BehaviorTree>\n<TreeNodesModel>{model}</TreeNodesModel>\n</root>\n")


def test_colledanchise_tree_is_written_in_the_documented_form() -> None:
    assert tree_to_xml(colledanchise_tree()) == COLLEDANCHISE_XML


@settings(max_examples=200, deadline=None)
@given(trees(CONDITIONS, ACTIONS))
def test_write_then_read_gives_the_same_tree(tree) -> None:  # type: ignore[no-untyped-def]
    text = tree_to_xml(tree)
    back = tree_from_xml(text)
    # equality compares structure: kinds, names, order, Parallel thresholds
    assert back == tree
    assert tree_to_xml(back) == text


def test_equal_trees_give_identical_text_whatever_their_uids() -> None:
    first, second = colledanchise_tree(), colledanchise_tree()
    assert [n.uid for n in walk(first)] != [n.uid for n in walk(second)]
    assert tree_to_xml(first) == tree_to_xml(second)


def test_read_tree_numbers_uids_in_pre_order(tmp_path: Path) -> None:
    path = tmp_path / "t.xml"
    write_tree(path, colledanchise_tree())
    assert path.read_text() == COLLEDANCHISE_XML
    tree = read_tree(path)
    assert [n.uid for n in walk(tree)] == list(range(1, 17))
    assert not list(tmp_path.glob(".*tmp"))


def test_parallel_counts_follow_table_2_2() -> None:
    tree = Parallel((Condition("A"), Action("B"), Inverter(Condition("C"))), 2)
    text = tree_to_xml(tree)
    # fails once more than N-M = 1 children fail, i.e. at failure_count = N-M+1 = 2
    assert '<Parallel success_count="2" failure_count="2">' in text
    assert tree_from_xml(text) == tree


def test_reading_accepts_long_leaves_and_plain_sequence_and_fallback() -> None:
    text = wrap('<Sequence><Fallback><Condition ID="A"/><Action ID="Go"/></Fallback>'
                '<ReactiveFallback><A/><Go/></ReactiveFallback></Sequence>',
                '<Condition ID="A"/><Action ID="Go"/>')
    pair = Fallback((Condition("A"), Action("Go")))
    assert tree_from_xml(text) == Sequence((pair, pair))


def test_parallel_defaults_and_negative_counts_mean_all_children() -> None:
    kids = "<Action ID='X'/><Action ID='Y'/><Action ID='Z'/>"
    expected = Parallel((Action("X"), Action("Y"), Action("Z")), 3)
    assert tree_from_xml(wrap(f"<Parallel>{kids}</Parallel>")) == expected
    assert tree_from_xml(wrap(f"<Parallel success_count='-1' failure_count='1'>{kids}</Parallel>")) == expected


def test_comments_and_a_single_tree_without_main_attribute_are_fine() -> None:
    text = '<root BTCPP_format="4"><!-- hi --><BehaviorTree ID="T"><!-- c --><Action ID="Go"/></BehaviorTree></root>'
    assert tree_from_xml(text) == Action("Go")


def test_the_writer_refuses_trees_bt_cpp_would_misread() -> None:
    with pytest.raises(FormatError, match="BehaviorTree.CPP node type"):
        tree_to_xml(Sequence((Condition("Sleep"), Action("Go"))))
    with pytest.raises(FormatError, match="both as a condition and as an action"):
        tree_to_xml(Sequence((Condition("Go"), Action("Go"))))
    with pytest.raises(FormatError, match="without children"):
        tree_to_xml(Sequence(()))
    with pytest.raises(FormatError, match="not an identifier"):
        tree_to_xml(Action("a b"))


ERRORS = [
    ("", None, "empty tree file"),
    ("   \n  ", None, "empty tree file"),
    (b"\x89PNG\r\n\x1a\n\xff\xfe", 1, "not a UTF-8 text file"),
    ("<root>\x00</root>", 1, "NUL bytes"),
    ("hello", 1, "not well-formed XML"),
    ("<root><BehaviorTree ID='M'>\n<ReactiveSequence>", 2, "not well-formed XML"),
    ("<tree/>", 1, "root element is <tree>"),
    ('<root BTCPP_format="3"><BehaviorTree ID="M"><Action ID="a"/></BehaviorTree></root>', 1, "BTCPP_format"),
    ("<root/>", 1, "no <BehaviorTree>"),
    ("<root>\n<BehaviorTree><Action ID='a'/></BehaviorTree></root>", 2, "without an ID"),
    ("<root>\n<BehaviorTree ID='A'><Action ID='a'/></BehaviorTree>\n<BehaviorTree ID='A'><Action ID='a'/>"
     "</BehaviorTree></root>", 3, "duplicate BehaviorTree ID 'A'"),
    ("<root main_tree_to_execute='B'><BehaviorTree ID='A'><Action ID='a'/></BehaviorTree></root>", 1,
     "main tree 'B' not found"),
    ("<root><BehaviorTree ID='A'><Action ID='a'/></BehaviorTree><BehaviorTree ID='B'><Action ID='a'/>"
     "</BehaviorTree></root>", 1, "no main_tree_to_execute"),
    (wrap(""), 2, "exactly one root node, found 0"),
    (wrap("<Action ID='a'/><Action ID='b'/>"), 2, "exactly one root node, found 2"),
    (wrap("<ReactiveSequence>\n<Frobnicate/></ReactiveSequence>"), 4, "unknown node type <Frobnicate>"),
    (wrap("<ForceFailure><Action ID='a'/></ForceFailure>"), 3, "unsupported node type <ForceFailure>"),
    (wrap("<SubTree ID='Other'/>"), 3, "SubTree> is not supported"),
    (wrap("<Inverter><Action ID='a'/><Action ID='b'/></Inverter>"), 3, "exactly one child, found 2"),
    (wrap("<ReactiveFallback/>"), 3, "<ReactiveFallback> has no children"),
    (wrap("<Action ID='a'><Action ID='b'/></Action>"), 3, "leaf but has child elements"),
    (wrap("<Go><Stop/></Go>", "<Action ID='Go'/><Action ID='Stop'/>"), 3, "leaf but has child elements"),
    (wrap("<Action/>"), 3, "<Action> without an ID"),
    (wrap("<Parallel success_count='x'><Action ID='a'/></Parallel>"), 3, "is not an integer"),
    (wrap("<Parallel success_count='3' failure_count='1'><Action ID='a'/></Parallel>"), 3, "not between 1 and"),
    (wrap("<Parallel success_count='1' failure_count='1'><Action ID='a'/><Action ID='b'/></Parallel>"), 3,
     "need failure_count=2"),
    (wrap("<Sequence><Condition ID='a'/><Action ID='a'/></Sequence>"), 3, "both as a Condition and as an Action"),
    (wrap("<A/>", "<Condition ID='A'/>\n<Action ID='A'/>"), 6, "declared both as a Condition and as an Action"),
    (wrap("<A/>", "<Port ID='A'/>"), 5, "unexpected element <Port>"),
    ("<root><include path='x.xml'/></root>", 1, "<include> is not supported"),
    ("<root><Thing/></root>", 1, "unexpected element <Thing>"),
    ('<?xml version="1.0"?>\n<!DOCTYPE root [\n<!ENTITY xxe SYSTEM "file:///etc/passwd">\n]>\n'
     "<root>&xxe;</root>", 2, "DOCTYPE declarations are not allowed"),
    (wrap("<ReactiveSequence>" * 210 + "<Action ID='a'/>" + "</ReactiveSequence>" * 210), None, "levels deep"),
    (wrap("<ReactiveSequence _skipIf='a'><Action ID='a'/></ReactiveSequence>"), 3, "has attribute '_skipIf'"),
    (wrap("<ReactiveSequence>\n<Action ID='a' _onSuccess='x:=1'/></ReactiveSequence>"), 4,
     "<Action> has attribute '_onSuccess'"),
    (wrap("<Parallel success_count='" + "9" * 5000 + "'><Action ID='a'/></Parallel>"), 3, "is not an integer"),
]


@pytest.mark.parametrize(("text", "line", "message"), ERRORS, ids=[e[2] + str(i) for i, e in enumerate(ERRORS)])
def test_malformed_trees_raise_format_errors_with_their_line(text, line, message) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(FormatError) as caught:
        tree_from_xml(text, "tree.xml")
    error = caught.value
    assert message in error.message
    assert error.path == "tree.xml"
    if line is not None:
        assert error.line == line
    assert "\n" not in str(error)


def test_node_metadata_bt_cpp_writes_itself_is_read() -> None:
    """``_uid`` and ``_fullpath`` (Groot2 logs) change no behaviour; every other '_' attribute does."""
    text = wrap("<ReactiveSequence name='s' _uid='1'><Action ID='a' _uid='2' _fullpath='x'/></ReactiveSequence>")
    assert tree_from_xml(text, "tree.xml") == tree_from_xml(wrap("<ReactiveSequence><Action ID='a'/>"
                                                                 "</ReactiveSequence>"), "tree.xml")


def test_oversized_files_are_refused_before_parsing(tmp_path: Path) -> None:
    path = tmp_path / "big.xml"
    path.write_bytes(b"<root>" + b" " * MAX_BYTES + b"</root>")
    with pytest.raises(FormatError, match="more than the"):
        read_tree(path)


def test_unreadable_paths_are_format_errors(tmp_path: Path) -> None:
    with pytest.raises(FormatError, match="cannot read"):
        read_tree(tmp_path / "missing.xml")
    with pytest.raises(FormatError, match="folder"):
        read_tree(tmp_path)


def test_a_tree_too_large_to_read_back_is_not_written(tmp_path: Path) -> None:
    path = tmp_path / "big.xml"
    with pytest.raises(FormatError, match=f"more than a tree file may hold \\({MAX_NODES} elements"):
        write_tree(path, Fallback(tuple(Action("A") for _ in range(MAX_NODES))))
    assert not path.exists()
    write_tree(path, Fallback(tuple(Action("A") for _ in range(MAX_NODES - 10))))
    assert path.exists()
