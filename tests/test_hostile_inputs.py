"""Malformed and hostile files through the real command line: exit status 2, one line on
stderr naming the file (and line), no traceback, nothing written, nothing expanded."""

from __future__ import annotations

import random
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import BALL_DOMAIN, ROOT, colledanchise_tree

from teach.bt.xml import MAX_BYTES, tree_to_xml

GOOD_DEMO = "0;0;0;0;0;1\n1;0;0;0;0;2\n1;1;0;0;0;3\n1;1;1;0;0;4\n1;1;1;1;0;5\n1;1;1;1;1;0\n"
GOOD_TREE = tree_to_xml(colledanchise_tree())
DOMAIN_TEXT = BALL_DOMAIN.read_text()
TINY = """\
name = "tiny"
goal = ["Done"]

[[condition]]
name = "Ready"

[[condition]]
name = "Done"

[[action]]
id = 1
name = "Work"
pre = ["Ready"]
ram = ["Done"]
"""
ERROR_LINE = re.compile(r"^teach: (?P<path>[^:\n]+?)(?::(?P<line>\d+))?: (?P<message>\S[^\n]*)\n$")


def tree_file(body: str, model: str = "") -> str:
    return (f'<root BTCPP_format="4" main_tree_to_execute="MainTree">\n<BehaviorTree ID="MainTree">\n{body}\n'
            f"</BehaviorTree>\n<TreeNodesModel>{model}</TreeNodesModel>\n</root>\n")


BILLION_LAUGHS = ('<?xml version="1.0"?>\n<!DOCTYPE lolz [\n <!ENTITY lol "lol">\n'
                  + "".join(f' <!ENTITY lol{i} "{("&lol" + str(i - 1) + ";") * 10 if i > 1 else "&lol;" * 10}">\n'
                            for i in range(1, 10))
                  + "]>\n<root>&lol9;</root>\n")
XXE = ('<?xml version="1.0"?>\n<!DOCTYPE root [\n<!ENTITY xxe SYSTEM "file:///etc/passwd">\n]>\n'
       '<root BTCPP_format="4"><BehaviorTree ID="M"><Action ID="&xxe;"/></BehaviorTree></root>\n')
EXTERNAL_DTD = ('<?xml version="1.0"?>\n\n<!DOCTYPE root SYSTEM "http://127.0.0.1:9/evil.dtd">\n'
                '<root BTCPP_format="4"/>\n')
ENTITY_ONLY = '<root>\n<!ENTITY x "y">\n</root>\n'


@dataclass(frozen=True)
class Case:
    """One bad input: files to create, the command, and the error we expect."""

    name: str
    files: dict[str, str | bytes]
    command: tuple[str, ...]
    path: str
    line: int | None
    message: str


def show(content: str | bytes) -> dict[str, str | bytes]:
    return {"tree.xml": content}


def demo_set(csv: str | bytes = GOOD_DEMO, domain: str = DOMAIN_TEXT) -> dict[str, str | bytes]:
    return {"tree.xml": GOOD_TREE, "demos/domain.toml": domain, "demos/d1.csv": csv}


SHOW = ("show", "tree.xml")
TEST = ("test", "tree.xml", "demos")
CSV = "demos/d1.csv"
TOML = "demos/domain.toml"

CASES = [
    # --- XML -------------------------------------------------------------------------------------
    Case("xxe external entity", show(XXE), SHOW, "tree.xml", 2, "DOCTYPE declarations are not allowed"),
    Case("billion laughs", show(BILLION_LAUGHS), SHOW, "tree.xml", 2, "DOCTYPE declarations are not allowed"),
    Case("external dtd over the network", show(EXTERNAL_DTD), SHOW, "tree.xml", 3, "DOCTYPE"),
    Case("entity declaration in the body", show(ENTITY_ONLY), SHOW, "tree.xml", 2, "ENTITY declarations"),
    Case("oversized", show(b"<root>" + b" " * MAX_BYTES + b"</root>"), SHOW, "tree.xml", None, "more than the"),
    Case("deeply nested", show(tree_file("<Inverter>" * 5000 + "<Action ID='a'/>" + "</Inverter>" * 5000)),
         SHOW, "tree.xml", None, "levels deep"),
    Case("truncated", show(GOOD_TREE[:300]), SHOW, "tree.xml", None, "not well-formed XML"),
    Case("binary junk", show(bytes(random.Random(7).randrange(256) for _ in range(4096))), SHOW, "tree.xml",
         None, "not a UTF-8 text file"),
    Case("utf-16 text", show(GOOD_TREE.encode("utf-16")), SHOW, "tree.xml", 1, "not a UTF-8 text file"),
    Case("empty tree file", show(""), SHOW, "tree.xml", None, "empty tree file"),
    Case("wrong root", show("<BehaviorTree ID='M'><Action ID='a'/></BehaviorTree>\n"), SHOW, "tree.xml", 1,
         "root element is <BehaviorTree>"),
    Case("unknown node", show(tree_file("<ReactiveSequence>\n<Dance/>\n</ReactiveSequence>")), SHOW, "tree.xml",
         4, "unknown node type <Dance>"),
    Case("subtree", show(tree_file("<SubTree ID='Other'/>")), SHOW, "tree.xml", 3, "SubTree"),
    Case("inverter with two children", show(tree_file("<Inverter><Action ID='a'/><Action ID='b'/></Inverter>")),
         SHOW, "tree.xml", 3, "exactly one child"),
    Case("bad parallel counts", show(tree_file("<Parallel success_count='2' failure_count='2'>"
                                               "<Action ID='a'/><Action ID='b'/></Parallel>")),
         SHOW, "tree.xml", 3, "failure_count=1"),
    Case("duplicate tree ids", show('<root main_tree_to_execute="A">\n<BehaviorTree ID="A"><Action ID="a"/>'
                                    '</BehaviorTree>\n<BehaviorTree ID="A"><Action ID="b"/></BehaviorTree>\n</root>'),
         SHOW, "tree.xml", 3, "duplicate BehaviorTree ID"),
    Case("missing main tree", show('<root main_tree_to_execute="Main"><BehaviorTree ID="Other">'
                                   '<Action ID="a"/></BehaviorTree></root>'), SHOW, "tree.xml", 1, "'Main' not found"),
    Case("tree action unknown to the domain", {**demo_set(), "tree.xml": tree_to_xml(colledanchise_tree())
                                                .replace("PlaceBall", "ThrowBall")},
         TEST, "tree.xml", None, "'ThrowBall'"),
    Case("dot output is not written for a bad tree", show(tree_file("<Inverter/>")),
         ("dot", "tree.xml", "-o", "tree.dot"), "tree.xml", 3, "<Inverter> has no children"),
    # --- CSV -------------------------------------------------------------------------------------
    Case("wrong field count", demo_set("0;0;0;0;0;1\n1;0;0;0;2\n"), TEST, CSV, 2, "expected 6 fields"),
    Case("value other than 0/1", demo_set("0;0;0;0;0;1\n1;0;2;0;0;2\n"), TEST, CSV, 2, "must be 0 or 1"),
    Case("unknown action id", demo_set("0;0;0;0;0;1\n1;0;0;0;0;9\n"), TEST, CSV, 2, "unknown action ID 9"),
    Case("action id not a number", demo_set("0;0;0;0;0;FindBall\n"), TEST, CSV, 1, "must be an integer"),
    Case("goal not last", demo_set("0;0;0;0;0;1\n1;0;0;0;0;0\n1;1;0;0;0;2\n"), TEST, CSV, 3,
         "a line after the goal line"),
    Case("external action on the last line", demo_set("0;0;0;0;0;1\n1;0;0;0;0;-1\n"), TEST, CSV, 2,
         "external action"),
    Case("empty demonstration", demo_set(""), TEST, CSV, None, "empty demonstration file"),
    Case("binary demonstration", demo_set(b"\xff\xfe\x00\x01"), TEST, CSV, 1, "not a UTF-8 text file"),
    # --- TOML ------------------------------------------------------------------------------------
    Case("toml syntax error", demo_set(domain="name = \"x\"\n[[condition]\nname = \"A\"\n"), TEST, TOML, 2,
         "invalid TOML"),
    Case("duplicate condition names", demo_set(domain=TINY.replace('name = "Done"', 'name = "Ready"')), TEST, TOML,
         7, "duplicate condition name 'Ready'"),
    Case("unknown literal", demo_set(domain=TINY.replace('pre = ["Ready"]', 'pre = ["Set"]')), TEST, TOML, 13,
         "unknown condition 'Set'"),
    Case("reserved action id", demo_set(domain=TINY.replace("id = 1", "id = 0")), TEST, TOML, 10,
         "0 and -1 are reserved"),
    Case("duplicate action names", demo_set(domain=TINY + '\n[[action]]\nid = 2\nname = "Work"\n'), TEST, TOML,
         16, "duplicate action name 'Work'"),
    Case("reserved condition name", demo_set(domain=TINY.replace('"Ready"', '"Sequence"')), TEST, TOML, 4,
         "must be an identifier"),
]


def snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_bad_input_gives_one_line_and_status_2(case: Case, tmp_path: Path) -> None:
    for name, content in case.files.items():
        target = tmp_path / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8"))
    before = snapshot(tmp_path)
    done = subprocess.run([sys.executable, "-m", "teach.cli", *case.command], cwd=tmp_path, capture_output=True,
                          env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    stderr = done.stderr.decode("utf-8")
    assert done.returncode == 2, stderr
    assert "Traceback" not in stderr
    match = ERROR_LINE.match(stderr)
    assert match, f"not one 'teach: PATH[:LINE]: message' line: {stderr!r}"
    assert match["path"] == case.path
    if case.line is not None:
        assert match["line"] == str(case.line)
    assert case.message in match["message"]
    assert "root:" not in stderr and "lollol" not in stderr  # nothing was expanded
    assert done.stdout == b""
    assert snapshot(tmp_path) == before
