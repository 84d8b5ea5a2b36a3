"""A corpus of hostile and malformed inputs and output paths, for every kind of file teach reads.

    python tests/hostile_corpus.py OUT_DIR     # writes the corpus there and prints the counts

Every entry must be refused by every command that reads its kind with one line
``teach: FILE[:LINE]: what is wrong`` and exit status 2 (tests/test_hostile_corpus.py runs them).
Kinds: ``tree``, ``domain``, ``csv`` (one bad file in an otherwise good set), ``set`` (a whole
demonstration folder), ``dialogue``, ``world`` (a world.toml beside a good domain), ``motion`` (a
guided action's motion file in a good session), ``journal`` (a session journal), ``recording``
(rerun files with values missing or of the wrong type, written by rerun itself), ``btlog`` (a run
log beside a good recording); ``output`` cases are paths a command must refuse to write, among
them what the command reads and a session's own paths.
Special files (FIFOs, sockets, devices, symlinks, folders, missing files) are made by
``materialise``; nothing here knows the ball task beyond using its files as the good inputs.
"""

from __future__ import annotations

import functools
import json
import os
import random
import socket
import subprocess
import sys
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from teach.limits import MAX_TREE_NODES

ROOT = Path(__file__).resolve().parent.parent
GOOD_DOMAIN = (ROOT / "demos" / "ball" / "domain.toml").read_bytes()
GOOD_TREE = (ROOT / "demos" / "ball" / "reference" / "colledanchise.xml").read_bytes()
GOOD_DEMO = b"0;0;0;0;0;1\n1;0;0;0;0;2\n1;1;0;0;0;3\n1;1;1;0;0;4\n1;1;1;1;0;5\n1;1;1;1;1;0\n"
GOOD_DIALOGUE = b"@world offline\nask\nquit\n"

MIB = 1024 * 1024


@dataclass(frozen=True)
class Hostile:
    """One bad input: its bytes, or a special file ``special`` names, or a fixed ``path``."""

    kind: str
    name: str
    content: bytes | None = None
    special: str = ""
    path: str = ""


@dataclass(frozen=True)
class OutputCase:
    """A command whose output path must be refused: ``setup`` builds the hostile target in the
    run folder, ``expect`` is the path the error must name."""

    name: str
    args: tuple[str, ...]
    expect: str
    setup: Callable[[Path], None] = field(default=lambda folder: None)


# --- trees --------------------------------------------------------------------------------------

def tree_file(body: str, model: str = "") -> bytes:
    return (f'<root BTCPP_format="4" main_tree_to_execute="MainTree">\n<BehaviorTree ID="MainTree">\n{body}\n'
            f"</BehaviorTree>\n<TreeNodesModel>{model}</TreeNodesModel>\n</root>\n").encode()


def _balanced(depth: int) -> str:
    if depth == 0:
        return "<A/>"
    inner = _balanced(depth - 1)
    return f"<ReactiveSequence>{inner}{inner}</ReactiveSequence>"


def trees() -> list[Hostile]:
    good = GOOD_TREE.decode()
    rng = random.Random(14)
    cases: dict[str, bytes] = {
        "xxe": b'<?xml version="1.0"?>\n<!DOCTYPE root [\n<!ENTITY xxe SYSTEM "file:///etc/passwd">\n]>\n'
               b'<root BTCPP_format="4"><BehaviorTree ID="M"><Action ID="&xxe;"/></BehaviorTree></root>\n',
        "billion-laughs": ('<?xml version="1.0"?>\n<!DOCTYPE lolz [\n <!ENTITY lol "lol">\n'
                           + "".join(f' <!ENTITY lol{i} "{("&lol" + str(i - 1) + ";") * 10}">\n'
                                     for i in range(2, 10))
                           + "]>\n<root>&lol9;</root>\n").encode(),
        "external-dtd": b'<?xml version="1.0"?>\n<!DOCTYPE root SYSTEM "http://127.0.0.1:9/evil.dtd">\n<root/>\n',
        "parameter-entity": b'<!DOCTYPE r [<!ENTITY % p SYSTEM "http://127.0.0.1:9/p.dtd"> %p;]>\n<root/>\n',
        "entity-in-body": b'<root>\n<!ENTITY x "y">\n</root>\n',
        "xinclude": b'<root xmlns:xi="http://www.w3.org/2001/XInclude" BTCPP_format="4">\n'
                    b'<xi:include href="/etc/passwd" parse="text"/>\n</root>\n',
        "oversized": b"<root>" + b" " * (5 * MIB) + b"</root>",
        "deep-5000": tree_file("<Inverter>" * 5000 + "<A/>" + "</Inverter>" * 5000, "<Action ID='A'/>"),
        "deep-201": tree_file("<Inverter>" * 201 + "<A/>" + "</Inverter>" * 201, "<Action ID='A'/>"),
        "wide-200k-leaves": tree_file("<ReactiveFallback>\n" + "<A/>\n" * 200_000 + "</ReactiveFallback>",
                                      "<Action ID='A'/>"),
        "balanced-depth-16": tree_file(_balanced(16), "<Action ID='A'/>"),
        f"nodes-{MAX_TREE_NODES + 1}": tree_file("<ReactiveFallback>\n" + "<A/>\n" * (MAX_TREE_NODES + 1)
                                                 + "</ReactiveFallback>", "<Action ID='A'/>"),
        "binary-1": bytes(rng.randrange(256) for _ in range(4096)),
        "binary-2": b"\x89PNG\r\n\x1a\n" + bytes(rng.randrange(256) for _ in range(512)),
        "binary-3": bytes(range(256)) * 4,
        "utf16": good.encode("utf-16"),
        "utf16-le-no-bom": good.encode("utf-16-le"),
        "utf32": good.encode("utf-32"),
        "latin1": tree_file("<Äktion/>", "<Action ID='Äktion'/>").decode().encode("latin-1"),
        "nul-inside": good[:200].encode() + b"\x00" + good[200:].encode(),
        "empty": b"",
        "whitespace": b"  \n\t\n",
        "bom-only": b"\xef\xbb\xbf",
        "comment-only": b"<!-- nothing -->\n",
        "text-only": b"hello tree\n",
        "wrong-root": b"<BehaviorTree ID='M'><Action ID='a'/></BehaviorTree>\n",
        "no-behaviortree": b"<root BTCPP_format='4'/>\n",
        "btcpp-format-3": b'<root BTCPP_format="3"><BehaviorTree ID="M"><Action ID="a"/></BehaviorTree></root>\n',
        "unknown-node": tree_file("<ReactiveSequence>\n<Dance/>\n</ReactiveSequence>"),
        "unsupported-builtin": tree_file("<ForceFailure><Action ID='a'/></ForceFailure>"),
        "subtree": tree_file("<SubTree ID='Other'/>"),
        "include": b"<root><include path='other.xml'/></root>\n",
        "inverter-two-children": tree_file("<Inverter><Action ID='a'/><Action ID='b'/></Inverter>"),
        "inverter-no-children": tree_file("<Inverter/>"),
        "sequence-no-children": tree_file("<ReactiveSequence/>"),
        "parallel-counts": tree_file("<Parallel success_count='2' failure_count='2'><Action ID='a'/>"
                                     "<Action ID='b'/></Parallel>"),
        "parallel-not-int": tree_file("<Parallel success_count='x'><Action ID='a'/></Parallel>"),
        "parallel-plus": tree_file("<Parallel success_count='+1x'><Action ID='a'/></Parallel>"),
        "parallel-zero": tree_file("<Parallel success_count='0'><Action ID='a'/></Parallel>"),
        "parallel-huge": tree_file("<Parallel success_count='99999999999999999999'><Action ID='a'/></Parallel>"),
        "duplicate-tree-ids": b'<root main_tree_to_execute="A">\n<BehaviorTree ID="A"><Action ID="a"/></BehaviorTree>'
                              b'\n<BehaviorTree ID="A"><Action ID="b"/></BehaviorTree>\n</root>\n',
        "missing-main": b'<root main_tree_to_execute="Main"><BehaviorTree ID="Other"><Action ID="a"/>'
                        b"</BehaviorTree></root>\n",
        "two-trees-no-main": b"<root><BehaviorTree ID='A'><Action ID='a'/></BehaviorTree>"
                             b"<BehaviorTree ID='B'><Action ID='a'/></BehaviorTree></root>\n",
        "tree-without-id": b"<root>\n<BehaviorTree><Action ID='a'/></BehaviorTree></root>\n",
        "two-roots": tree_file("<Action ID='a'/><Action ID='b'/>"),
        "no-root-node": tree_file(""),
        "leaf-with-children": tree_file("<Action ID='a'><Action ID='b'/></Action>"),
        "action-without-id": tree_file("<Action/>"),
        "name-with-space": tree_file("<Action ID='a b'/>"),
        "name-path": tree_file("<Action ID='../../etc/passwd'/>"),
        "condition-and-action": tree_file("<ReactiveSequence><Condition ID='a'/><Action ID='a'/></ReactiveSequence>"),
        "declared-twice": tree_file("<A/>", "<Condition ID='A'/>\n<Action ID='A'/>"),
        "model-unknown-element": tree_file("<A/>", "<Port ID='A'/>"),
        "model-without-id": tree_file("<A/>", "<Action/>"),
        "unexpected-under-root": b"<root><Thing/></root>\n",
        "cdata-only": b"<root><![CDATA[<BehaviorTree/>]]></root>\n",
        "unclosed-attribute": b"<root BTCPP_format='4><BehaviorTree/></root>\n",
        "mismatched-tags": b"<root><BehaviorTree ID='M'><Action ID='a'/></Tree></root>\n",
        "two-documents": GOOD_TREE + GOOD_TREE,
        "processing-instruction-only": b'<?xml version="1.0"?>\n<?teach run?>\n',
    }
    big = "9" * 5000
    cases.update({  # BehaviorTree.CPP's '_' attributes teach does not implement, and counts past any parser
        f"attribute-{name}": tree_file(f"<ReactiveSequence {name}='A'><A/><A/></ReactiveSequence>", "<Action ID='A'/>")
        for name in ("_skipIf", "_successIf", "_failureIf", "_while", "_onSuccess", "_onFailure", "_onHalted",
                     "_post", "_autoremap", "_description", "_")})
    cases.update({
        "attribute-on-leaf": tree_file("<ReactiveSequence><A _skipIf='x'/></ReactiveSequence>", "<Action ID='A'/>"),
        "attribute-on-long-leaf": tree_file("<Action ID='A' _onSuccess='x:=1'/>"),
        "attribute-on-inverter": tree_file("<Inverter _while='x'><A/></Inverter>", "<Condition ID='A'/>"),
        "attribute-on-parallel": tree_file("<Parallel success_count='1' failure_count='2' _post='x'><A/><A/>"
                                           "</Parallel>", "<Action ID='A'/>"),
        "attribute-on-good-tree": good.replace("<BallFound/>", "<BallFound _failureIf='true'/>", 1).encode(),
        "parallel-5000-digits": tree_file(f"<Parallel success_count='{big}'><A/></Parallel>", "<Action ID='A'/>"),
        "parallel-underscore": tree_file("<Parallel success_count='1_0'><A/></Parallel>", "<Action ID='A'/>"),
        "parallel-space": tree_file("<Parallel success_count=' 1'><A/></Parallel>", "<Action ID='A'/>"),
    })
    for percent in range(5, 100, 5):  # truncated at 19 places
        cut = len(good) * percent // 100
        cases[f"truncated-{percent:02d}"] = good[:cut].encode()
    lines = good.splitlines(keepends=True)
    for number in range(1, len(lines) - 1):  # one line of the tree left out (each is an element)
        if lines[number].strip().startswith(("<BehaviorTree", "</BehaviorTree", "<Reactive", "</Reactive",
                                             "<root", "</root", "<Inverter", "</Inverter")):
            cases[f"line-{number + 1}-dropped"] = "".join(lines[:number] + lines[number + 1:]).encode()
    for number, tag in enumerate(("Frobnicate", "Sequence ID='x'", "Parallel success_count='9'", "Inverter")):
        cases[f"replaced-root-node-{number}"] = good.replace("<ReactiveSequence>", f"<{tag}>", 1).encode()
    entries = [Hostile("tree", name, content) for name, content in cases.items()]
    return entries + _special("tree")


# --- domains ------------------------------------------------------------------------------------

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


def _conditions(count: int) -> str:
    return "".join(f'[[condition]]\nname = "C{i}"\n\n' for i in range(count))


def _actions(count: int) -> str:
    return "".join(f'[[action]]\nid = {i + 1}\nname = "A{i}"\n\n' for i in range(count))


def domains() -> list[Hostile]:
    good = GOOD_DOMAIN.decode()
    swap: dict[str, tuple[str, str]] = {
        "name-not-string": ('name = "tiny"', "name = 5"),
        "condition-name-int": ('name = "Ready"', "name = 5"),
        "condition-name-empty": ('name = "Ready"', 'name = ""'),
        "condition-name-space": ('name = "Ready"', 'name = "Re ady"'),
        "condition-name-digit-first": ('name = "Ready"', 'name = "3Ready"'),
        "condition-name-umlaut": ('name = "Ready"', 'name = "Bäll"'),
        "condition-name-path": ('name = "Ready"', 'name = "../../etc/passwd"'),
        "condition-reserved": ('name = "Ready"', 'name = "Sequence"'),
        "condition-reserved-root": ('name = "Ready"', 'name = "root"'),
        "condition-duplicate": ('name = "Done"', 'name = "Ready"'),
        "condition-label-int": ('name = "Ready"', 'name = "Ready"\nen = 5'),
        "condition-label-list": ('name = "Ready"', 'name = "Ready"\nde = ["x"]'),
        "condition-label-long": ('name = "Ready"', 'name = "Ready"\nen = "' + "x" * 501 + '"'),
        "action-id-string": ("id = 1", 'id = "1"'),
        "action-id-float": ("id = 1", "id = 1.0"),
        "action-id-bool": ("id = 1", "id = true"),
        "action-id-zero": ("id = 1", "id = 0"),
        "action-id-minus-one": ("id = 1", "id = -1"),
        "action-id-huge": ("id = 1", "id = 10000000"),
        "action-id-nan": ("id = 1", "id = nan"),
        "action-id-inf": ("id = 1", "id = inf"),
        "action-id-date": ("id = 1", "id = 1979-05-27"),
        "action-id-missing": ("id = 1\n", ""),
        "action-name-missing": ('name = "Work"\n', ""),
        "action-name-reserved": ('name = "Work"', 'name = "Fallback"'),
        "action-same-as-condition": ('name = "Work"', 'name = "Ready"'),
        "phrases-int": ('name = "Work"', 'name = "Work"\nen = 5'),
        "phrases-mixed": ('name = "Work"', 'name = "Work"\nde = ["ok", 1]'),
        "phrases-many": ('name = "Work"', 'name = "Work"\nen = [' + ", ".join(f'"p{i}"' for i in range(65)) + "]"),
        "phrase-long": ('name = "Work"', 'name = "Work"\nen = ["' + "y" * 501 + '"]'),
        "pre-string": ('pre = ["Ready"]', 'pre = "Ready"'),
        "pre-int": ('pre = ["Ready"]', "pre = [1]"),
        "pre-unknown": ('pre = ["Ready"]', 'pre = ["Set"]'),
        "pre-contradiction": ('pre = ["Ready"]', 'pre = ["Ready", "!Ready"]'),
        "pre-table": ('pre = ["Ready"]', "pre = {a = 1}"),
        "pre-too-many": ('pre = ["Ready"]', "pre = [" + ", ".join(['"Ready"'] * 65) + "]"),
        "ram-unknown": ('ram = ["Done"]', 'ram = ["!Nothing"]'),
        "form-string": ('name = "Work"', 'name = "Work"\nform = "work"'),
        "form-empty": ('name = "Work"', 'name = "Work"\nform = []'),
        "form-int": ('name = "Ready"', 'name = "Ready"\nform = ["ready", 1]'),
        "form-space": ('name = "Ready"', 'name = "Ready"\nform = ["ready", "a b"]'),
        "form-path": ('name = "Ready"', 'name = "Ready"\nform = ["ready", "../x"]'),
        "form-too-many-objects": ('name = "Ready"', 'name = "Ready"\nform = [' + ", ".join(['"o"'] * 10) + "]"),
        "form-table": ('name = "Work"', 'name = "Work"\nform = {kind = "work"}'),
        "form-action-without-condition-forms": ('name = "Work"', 'name = "Work"\nform = ["work"]'),
        "goal-unknown": ('goal = ["Done"]', 'goal = ["Finished"]'),
        "goal-string": ('goal = ["Done"]', 'goal = "Done"'),
        "goal-nested": ('goal = ["Done"]', 'goal = [["Done"]]'),
        "goal-nan": ('goal = ["Done"]', "goal = nan"),
        "condition-single-table": ("[[condition]]\nname = \"Ready\"", "[condition]\nname = \"Ready\""),
        "condition-is-int": ('goal = ["Done"]', 'goal = ["Done"]\ncondition = 5'),
        "action-is-string": ('goal = ["Done"]', 'goal = ["Done"]\naction = "Work"'),
        "syntax-error": ("[[condition]]\n", "[[condition]\n"),
        "duplicate-key": ('name = "Ready"', 'name = "Ready"\nname = "Again"'),
        "unterminated-array": ('pre = ["Ready"]', 'pre = ["Ready"'),
        "unterminated-string": ('name = "Work"', 'name = "Work'),
        "unterminated-multiline": ('name = "Work"', 'name = """Work'),
        "bad-escape": ('name = "Work"', 'name = "W\\qork"'),
    }
    cases: dict[str, bytes] = {}
    for name, (old, new) in swap.items():
        assert old in TINY, name
        cases[name] = TINY.replace(old, new, 1).encode()
    cases.update({
        "nested-arrays-500": ("x = " + "[" * 500 + "]" * 500 + "\n" + TINY).encode(),
        "nested-inline-tables-500": ("x = " + "{a = " * 500 + "1" + "}" * 500 + "\n" + TINY).encode(),
        "nested-goal-1200": TINY.replace('goal = ["Done"]', "goal = " + "[" * 1200 + "]" * 1200).encode(),
        "dotted-key-500": ("a" + ".a" * 500 + " = 1\n" + TINY).encode(),
        "dotted-header-500": (TINY + "\n[" + "t." * 500 + "t]\n").encode(),
        "nested-unbalanced": ("x = " + "[" * 5000).encode(),
        "conditions-65": (_conditions(65) + _actions(1)).encode(),
        "actions-65": (_conditions(1) + _actions(65)).encode(),
        "conditions-10000": (_conditions(10_000) + _actions(1)).encode(),
        "oversized": (TINY + "# " + "x" * MIB + "\n").encode(),
        "no-conditions": _actions(2).encode(),
        "no-actions": _conditions(2).encode(),
        "empty": b"",
        "comment-only": b"# a domain\n",
        "duplicate-action-name": (TINY + '\n[[action]]\nid = 2\nname = "Work"\n').encode(),
        "duplicate-action-id": (TINY + '\n[[action]]\nid = 1\nname = "Rest"\n').encode(),
        "utf16": good.encode("utf-16"),
        "utf16-le-no-bom": TINY.encode("utf-16-le"),
        "latin1": TINY.replace('name = "tiny"', 'name = "tiny"\n# Größe').encode("latin-1")
                  .replace(b'name = "Ready"', 'name = "Rädy"'.encode("latin-1")),
        "nul-inside": TINY.encode().replace(b"Work", b"Wo\x00rk", 1),
        "binary": bytes(random.Random(5).randrange(256) for _ in range(2048)),
        "bom-then-utf16": b"\xef\xbb\xbf" + TINY.encode("utf-16"),
        "xml-instead": GOOD_TREE,
        "csv-instead": GOOD_DEMO,
        "json-instead": b'{"name": "tiny", "condition": []}\n',
    })
    big = "9" * 5000
    misspelled: dict[str, tuple[str, str]] = {  # a key nobody reads is a typo: refused, naming it
        "key-prex": ('pre = ["Ready"]', 'prex = ["Ready"]'),
        "key-rams": ('ram = ["Done"]', 'rams = ["Done"]'),
        "key-pre-capital": ('pre = ["Ready"]', 'Pre = ["Ready"]'),
        "key-pre-quoted-space": ('pre = ["Ready"]', '"pre " = ["Ready"]'),
        "key-precondition": ('pre = ["Ready"]', 'precondition = ["Ready"]'),
        "key-action-phrases": ('name = "Work"', 'name = "Work"\nphrases = ["work"]'),
        "key-action-label": ('name = "Work"', 'name = "Work"\nlabel = "work"'),
        "key-condition-id": ('name = "Ready"', 'name = "Ready"\nid = 1'),
        "key-condition-en-dash": ('name = "Ready"', 'name = "Ready"\nen-false = "not ready"'),
        "key-condition-pre": ('name = "Ready"', 'name = "Ready"\npre = ["Done"]'),
        "key-goals": ('goal = ["Done"]', 'goals = ["Done"]'),
        "key-version": ('name = "tiny"', 'name = "tiny"\nversion = 2'),
        "key-table": ('goal = ["Done"]', 'goal = ["Done"]\n\n[meta]\nauthor = "x"'),
        "key-actions-plural": ("[[action]]", "[[actions]]"),
        "key-conditions-plural": ('[[condition]]\nname = "Done"', '[[conditions]]\nname = "Done"'),
        "key-dotted": ('pre = ["Ready"]', 'pre = ["Ready"]\nmodel.pre = ["Ready"]'),
        "action-id-5000-digits": ("id = 1", f"id = {big}"),
        "action-id-minus-5000-digits": ("id = 1", f"id = -{big}"),
        "action-id-underscored-5000": ("id = 1", "id = " + "_".join(["9999"] * 1250)),
        "action-id-hex-huge": ("id = 1", "id = 0x" + "f" * 5000),
        "unknown-number-5000-digits": ('name = "tiny"', f'name = "tiny"\nsize = {big}'),
        "float-5000-digits": ("id = 1", f"id = 1.{big}"),
        "condition-not-a-table": ('goal = ["Done"]', 'goal = ["Done"]\ncondition = [1, 2]'),
        "line-separator-outside-string": ('goal = ["Done"]', 'goal = ["Done"]\u2028'),
    }
    for name, (old, new) in misspelled.items():
        assert old in TINY, name
        cases[name] = TINY.replace(old, new, 1).encode()
    cases["key-prex-in-ball-domain"] = good.replace("pre = ", "prex = ", 1).encode()
    cases["form-duplicate-condition"] = TINY.replace('name = "Ready"', 'name = "Ready"\nform = ["s"]').replace(
        'name = "Done"', 'name = "Done"\nform = ["s"]').encode()
    cases["key-after-separator-lines"] = ("# a\u2028b\u2029c\x85d\n" + TINY.replace('ram = ["Done"]', 'rma = ["Done"]')
                                          ).encode()
    for number, at in enumerate(_opening_quotes(good)[:12]):  # truncated inside a string: never valid TOML
        cases[f"truncated-in-string-{number:02d}"] = good[:at + 1].encode()
    entries = [Hostile("domain", name, content) for name, content in cases.items()]
    return entries + _special("domain")


def _opening_quotes(text: str) -> list[int]:
    """Offsets of the opening quote of each one-line string value (``= "``)."""
    return [i + 2 for i in range(len(text) - 2) if text[i:i + 3] == '= "']


# --- demonstrations -----------------------------------------------------------------------------

def csvs() -> list[Hostile]:
    cases: dict[str, bytes] = {
        "fields-too-few": b"0;0;0;0;0;1\n1;0;0;0;2\n",
        "fields-too-many": b"0;0;0;0;0;0;1\n",
        "fields-1000": (";".join(["0"] * 1000) + ";1\n").encode(),
        "value-2": b"0;0;0;0;0;1\n1;0;2;0;0;2\n",
        "value-true": b"true;0;0;0;0;1\n",
        "value-space": b" 1;0;0;0;0;1\n",
        "value-fullwidth": "１;0;0;0;0;1\n".encode(),
        "value-empty": b";0;0;0;0;1\n",
        "action-unknown": b"0;0;0;0;0;1\n1;0;0;0;0;9\n",
        "action-name": b"0;0;0;0;0;FindBall\n",
        "action-plus": b"0;0;0;0;0;+3\n",
        "action-underscore": b"0;0;0;0;0;0_3\n",
        "action-fullwidth": "0;0;0;0;0;３\n".encode(),
        "action-arabic-indic": "0;0;0;0;0;٣\n".encode(),
        "action-leading-space": b"0;0;0;0;0; 3\n",
        "action-trailing-space-inside": b"0;0;0;0;0;3 ;\n",
        "action-float": b"0;0;0;0;0;3.0\n",
        "action-exponent": b"0;0;0;0;0;3e0\n",
        "action-hex": b"0;0;0;0;0;0x3\n",
        "action-minus-two": b"0;0;0;0;0;-2\n",
        "action-double-minus": b"0;0;0;0;0;--1\n",
        "action-minus-zero": b"0;0;0;0;0;-0\n",
        "action-huge": b"0;0;0;0;0;99999999999999999999\n",
        "action-empty": b"0;0;0;0;0;\n",
        "goal-not-last": b"0;0;0;0;0;1\n1;0;0;0;0;0\n1;1;0;0;0;2\n",
        "external-last": b"0;0;0;0;0;1\n1;0;0;0;0;-1\n",
        "empty": b"",
        "blank-lines": b"\n\n\n",
        "empty-line-inside": b"0;0;0;0;0;1\n\n1;0;0;0;0;0\n",
        "comma-separated": b"0,0,0,0,0,1\n",
        "tab-separated": b"0\t0\t0\t0\t0\t1\n",
        "only-separators": b";;;;;\n",
        "truncated-mid-line": GOOD_DEMO[:20],
        "binary": b"\xff\xfe\x00\x01",
        "utf16": GOOD_DEMO.decode().encode("utf-16"),
        "latin1": "0;0;0;0;0;1 # Größe\n".encode("latin-1"),
        "nul-inside": b"0;0;0;0;0;1\n1;0;0\x00;0;0;2\n",
        "lines-10001": b"0;0;0;0;0;1\n" * 10_001,
        "oversized": b"0;0;0;0;0;1\n" * (4 * MIB // 12 + 1),
        "xml-instead": GOOD_TREE,
        "toml-instead": GOOD_DOMAIN,
    }
    hidden = {"line-separator": "\u2028", "paragraph-separator": "\u2029", "next-line": "\x85", "form-feed": "\f",
              "vertical-tab": "\v", "file-separator": "\x1c", "group-separator": "\x1d", "record-separator": "\x1e",
              "lone-cr": "\r", "no-break-space": "\u00a0", "em-space": "\u2003", "ideographic-space": "\u3000",
              "zero-width-space": "\u200b", "bom-inside": "\ufeff", "rtl-override": "\u202e", "escape": "\x1b"}
    for name, char in hidden.items():  # lines end only at \n or \r\n; only ASCII blanks may end a line
        cases[f"{name}-as-line-break"] = f"0;0;0;0;0;1{char}1;0;0;0;0;0\n".encode()
        if char != "\r":  # "\r\n" is a line end
            cases[f"{name}-after-value"] = f"0;0;0;0;0;1{char}\n1;0;0;0;0;0\n".encode()
    cases["no-break-space-before-value"] = "0;0;0;0;0;1\n\u00a01;0;0;0;0;0\n".encode()
    cases["tab-inside-field"] = b"0;0;\t0;0;0;1\n1;0;0;0;0;0\n"
    entries = [Hostile("csv", name, content) for name, content in cases.items()]
    return entries + _special("csv")


def sets() -> list[Hostile]:
    """Whole demonstration folders that are unusable; ``special`` says how to build each."""
    return [Hostile("set", name, special=name) for name in (
        "set-missing", "set-is-a-file", "set-is-a-fifo", "set-without-csv", "set-without-domain",
        "set-domain-is-fifo", "set-domain-is-folder", "set-domain-deep", "set-csv-is-fifo", "set-csv-is-socket",
        "set-csv-symlink-loop", "set-csv-to-dev-zero", "set-csv-dangling-link", "set-csv-is-device")]


# --- dialogues ----------------------------------------------------------------------------------

def dialogues() -> list[Hostile]:
    cases: dict[str, bytes] = {
        "lang-fr": b"@lang fr\nhelp\n",
        "world-mars": b"@world mars\nhelp\n",
        "questions-negative": b"@questions -1\nhelp\n",
        "questions-plus": b"@questions +3\nhelp\n",
        "questions-fullwidth": "@questions ３\nhelp\n".encode(),
        "questions-underscore": b"@questions 1_0\nhelp\n",
        "questions-word": b"@questions many\nhelp\n",
        "questions-empty": b"@questions\nhelp\n",
        "questions-huge": b"@questions 99999999999\nhelp\n",
        "seed-word": b"@seed x\nhelp\n",
        "seed-negative": b"@seed -1\nhelp\n",
        "seed-float": b"@seed 1.5\nhelp\n",
        "domain-empty": b"@domain\nhelp\n",
        "lang-twice": b"@lang en\n@lang de\nhelp\n",
        "unknown-setting": b"@colour red\nhelp\n",
        "setting-after-input": b"help\n@lang de\n",
        "no-input-lines": b"# only a comment\n@lang en\n",
        "empty": b"",
        "blank": b"\n   \n",
        "binary": bytes(random.Random(9).randrange(256) for _ in range(1024)),
        "utf16": "@lang en\nhelp\n".encode("utf-16"),
        "latin1": "@lang en\nBall größer\n".encode("latin-1"),
        "nul-inside": b"@lang en\nhe\x00lp\n",
        "oversized": b"help\n" * (MIB // 5 + 1),
        "lines-20001": b"help\n" * 20_001,
        "line-too-long": b"@lang en\n" + b"help " * 120 + b"\n",
        "line-too-long-one-word": b"x" * 600 + b"\n",
        "questions-5000-digits": b"@questions " + b"9" * 5000 + b"\nhelp\n",
        "seed-5000-digits": b"@seed " + b"9" * 5000 + b"\nhelp\n",
        "form-feed-joins-setting": b"@lang en\x0chelp\n",
        "line-separator-joins-setting": "@lang en\u2028help\n".encode(),
        "escape-in-line": b"\x1b[31mhelp\n",
        "rtl-override-line": "\u202eplehn\n".encode(),
    }
    entries = [Hostile("dialogue", name, content) for name, content in cases.items()]
    return entries + _special("dialogue")


# --- worlds (world.toml beside a domain) ---------------------------------------------------------

GOOD_WORLD_DOMAIN = (ROOT / "demos" / "snacks" / "domain.toml").read_bytes()
GOOD_WORLD = (ROOT / "demos" / "snacks" / "world.toml").read_text(encoding="utf-8")
BIG = "9" * 5000
"""An integer past Python's limit on converting text to int (4300 digits)."""


def worlds() -> list[Hostile]:
    """Bad ``world.toml`` files, each beside a good copy of the snacks domain."""
    swap: dict[str, tuple[str, str]] = {
        "key-top-level": ('start = ["AtOffice"]', 'strat = ["AtOffice"]'),
        "key-random-start": ("random_start = ", "randomstart = "),
        "key-variable": ("min = 0", "mni = 0"),
        "key-derived": ('when = "snacks == 0"', 'wen = "snacks == 0"'),
        "key-effect": ("add = { snacks = -1 }", "ad = { snacks = -1 }"),
        "key-event": ("probability = 0.05", "probabilty = 0.05"),
        "key-event-label": ("probability = 0.2", "probability = 0.2\nlabel = \"x\""),
        "key-table": ("# How many", "[settings]\nseed = 1\n\n# How many"),
        "when-5000-digits": ('when = "snacks == 0"', f'when = "snacks == {BIG}"'),
        "when-19-digits": ('when = "snacks == 0"', 'when = "snacks == 1000000000000000000"'),
        "when-fullwidth-digit": ('when = "snacks == 0"', 'when = "snacks == \uff10"'),
        "when-no-break-space": ('when = "snacks == 0"', 'when = "snacks\u00a0== 0"'),
        "when-unknown-variable": ('when = "snacks == 0"', 'when = "drinks == 0"'),
        "min-5000-digits": ("min = 0", f"min = -{BIG}"),
        "max-5000-digits": ("max = 3", f"max = {BIG}"),
        "start-5000-digits": ("start = [1, 3]", f"start = [1, {BIG}]"),
        "add-5000-digits": ("add = { snacks = -1 }", f"add = {{ snacks = -{BIG} }}"),
        "probability-5000-digits": ("probability = 0.05", f"probability = 0.{BIG}"),
        "min-above-max": ("min = 0", "min = 4"),
        "start-unknown-condition": ('start = ["AtOffice"]', 'start = ["AtHome"]'),
        "derived-unknown-condition": ('condition = "TrayEmpty"', 'condition = "TrayFull"'),
        "effect-unknown-action": ('action = "TakeTray"', 'action = "Fly"'),
        "event-without-phrases": ('en = ["the request is withdrawn", "the caregiver calls it off", '
                                  '"the request is called off"]\n', ""),
        "duplicate-key": ("max = 3", "max = 3\nmax = 4"),
        "syntax-error": ("[[variable]]", "[[variable]"),
        "line-separator-outside-string": ('start = ["AtOffice"]', 'start = ["AtOffice"]\u2028'),
    }
    cases: dict[str, bytes] = {}
    for name, (old, new) in swap.items():
        assert old in GOOD_WORLD, name
        cases[name] = GOOD_WORLD.replace(old, new, 1).encode()
    cases.update({
        "nested-500": ("x = " + "[" * 500 + "]" * 500 + "\n" + GOOD_WORLD).encode(),
        "oversized": (GOOD_WORLD + "# " + "x" * MIB + "\n").encode(),
        "utf16": GOOD_WORLD.encode("utf-16"),
        "nul-inside": GOOD_WORLD.encode().replace(b"snacks", b"sna\x00cks", 1),
        "binary": bytes(random.Random(21).randrange(256) for _ in range(2048)),
        "xml-instead": GOOD_TREE,
    })
    entries = [Hostile("world", name, content) for name, content in cases.items()]
    return entries + _special("world", absent_is_fine=True)


# --- guided motions (a session's *.motion.json, read on resume) -----------------------------------

MOTION_SESSION = "S"
GOOD_MOTION = """{
  "format": "teach-guided-motion",
  "version": 1,
  "name": "PushBall",
  "en": ["push the ball away"],
  "de": ["den Ball wegschieben"],
  "anchor": "ball",
  "effects": ["!BallClose"],
  "offset": [0.3, 0],
  "lift": 0,
  "fingers": 0,
  "points": [
    [0, 0, 0, 0, 0, 0, 0, 0],
    [0.5, 0.1, 0, 0, 0.2, 0, 0, 0]
  ]
}
"""
GUIDED_DOMAIN = GOOD_DOMAIN + b"""
# taught by guidance
[[action]]
id = 6
name = "PushBall"
en = ["push the ball away"]
de = ["den Ball wegschieben"]
"""


def _journal_line(**changes: object) -> str:
    data: dict[str, object] = {"session": MOTION_SESSION, "domain": str(ROOT / "demos" / "ball" / "domain.toml"),
                               "lang": "en", "questions": 5, "world": "offline", "seed": 0, "step": 1, "events": [],
                               "version": 2}
    data.update(changes)
    return json.dumps({k: v for k, v in data.items() if v is not None})


GUIDED_JOURNAL = _journal_line(world="mujoco", events=[{"kind": "guided_action", "name": "PushBall",
                                                        "motion": "PushBall.motion.json"}]) + "\n"


def motions() -> list[Hostile]:
    """Bad motion files of an action taught by guidance, in an otherwise good MuJoCo session."""
    swap: dict[str, tuple[str, str]] = {
        "key-misspelled": ('"lift": 0,', '"lfit": 0,\n  "lift": 0,'),
        "key-capital": ('"fingers": 0,', '"Fingers": 0,\n  "fingers": 0,'),
        "key-comment": ('"version": 1,', '"version": 1,\n  "comment": "by hand",'),
        "key-points-misspelled": ('"points"', '"point"'),
        "format-other": ("teach-guided-motion", "teach-motion"),
        "version-2": ('"version": 1', '"version": 2'),
        "version-string": ('"version": 1', '"version": "1"'),
        "version-5000-digits": ('"version": 1', f'"version": {BIG}'),
        "name-not-identifier": ('"name": "PushBall"', '"name": "push ball"'),
        "anchor-other": ('"anchor": "ball"', '"anchor": "table"'),
        "effects-empty": ('"effects": ["!BallClose"]', '"effects": []'),
        "effects-unknown": ('"effects": ["!BallClose"]', '"effects": ["!BallGone"]'),
        "offset-three": ('"offset": [0.3, 0]', '"offset": [0.3, 0, 1]'),
        "lift-nan": ('"lift": 0', '"lift": NaN'),
        "lift-infinity": ('"lift": 0', '"lift": -Infinity'),
        "lift-overflow": ('"lift": 0', '"lift": 1e999'),
        "lift-400-digits": ('"lift": 0', '"lift": ' + "9" * 400),
        "lift-5000-digits": ('"lift": 0', f'"lift": {BIG}'),
        "fingers-bool": ('"fingers": 0', '"fingers": true'),
        "points-empty": ('[\n    [0, 0, 0, 0, 0, 0, 0, 0],\n    [0.5, 0.1, 0, 0, 0.2, 0, 0, 0]\n  ]', "[]"),
        "point-seven-numbers": ("[0, 0, 0, 0, 0, 0, 0, 0]", "[0, 0, 0, 0, 0, 0, 0]"),
        "point-string": ("[0.5, 0.1, 0,", '[0.5, "0.1", 0,'),
        "point-back-in-time": ("[0.5, 0.1", "[-0.5, 0.1"),
        "point-5000-digits": ("[0.5, 0.1", f"[{BIG}, 0.1"),
        "truncated": ('"points": [', '"points": [\n'),
    }
    cases: dict[str, bytes] = {}
    for name, (old, new) in swap.items():
        assert old in GOOD_MOTION, name
        text = GOOD_MOTION.replace(old, new, 1)
        cases[name] = (text[:text.index('"points": [') + 14] if name == "truncated" else text).encode()
    cases.update({
        "nested-100": ("[" * 100 + "]" * 100).encode(),
        "array": b"[]\n", "null": b"null\n", "empty": b"", "not-json": b"points: none\n",
        "utf16": GOOD_MOTION.encode("utf-16"),
        "nul-inside": GOOD_MOTION.encode().replace(b"PushBall", b"Push\x00Ball", 1),
        "binary": bytes(random.Random(23).randrange(256) for _ in range(1024)),
    })
    entries = [Hostile("motion", name, content) for name, content in cases.items()]
    return entries + _special("motion")


# --- session journals (recordings/S.journal.json, read by --resume) ----------------------------

def journals() -> list[Hostile]:
    """Bad journals of an otherwise good offline session ``S`` (JSON Lines, version 2)."""
    lines: dict[str, str] = {
        "step-5000-digits": _journal_line(step=int("9" * 100)).replace("9" * 100, BIG),
        "seed-5000-digits": _journal_line(seed=int("9" * 100)).replace("9" * 100, BIG),
        "questions-5000-digits": _journal_line(questions=-1).replace("-1", "-" + BIG),
        "step-negative": _journal_line(step=-1),
        "step-string": _journal_line(step="1"),
        "step-float": _journal_line(step=1.5),
        "step-bool": _journal_line(step=True),
        "step-nan": _journal_line().replace('"step": 1', '"step": NaN'),
        "key-header": _journal_line(stpe=1),
        "key-event": _journal_line(events=[{"kind": "undo", "fiel": "x"}]),
        "kind-unknown": _journal_line(events=[{"kind": "dance"}]),
        "demo-file-outside": _journal_line(events=[{"kind": "demo", "file": "../x.csv", "source": "typed"}]),
        "open-steps-unknown-action": _journal_line(open_steps=[["00000", 77, "find"]], open_state="10000"),
        "open-steps-action-5000-digits": _journal_line(open_steps=[["00000", 77, "find"]], open_state="10000")
        .replace("77", BIG),
        "open-steps-action-string": _journal_line(open_steps=[["00000", "1", "find"]], open_state="10000"),
        "open-steps-state-width": _journal_line(open_steps=[["000", 1, "find"]], open_state="10000"),
        "open-state-letters": _journal_line(open_steps=[["00000", 1, "find"]], open_state="ab"),
        "open-run-unknown": _journal_line(open_run="Fly", open_state="00000"),
        "lang-fr": _journal_line(lang="fr"),
        "world-mars": _journal_line(world="mars"),
        "version-3": _journal_line(version=3),
        "version-missing": _journal_line(version=None),
        "session-missing": _journal_line(session=None),
        "nested-100": "[" * 100 + "]" * 100,
        "array": "[]", "null": "null", "not-json": "session: S",
    }
    cases = {name: (line + "\n").encode() for name, line in lines.items()}
    good = _journal_line() + "\n"
    cases.update({
        "save-line-key": (good + '{"stpe": 2}\n').encode(),
        "save-line-5000-digits": (good + f'{{"step": {BIG}}}\n').encode(),
        "save-line-not-json": (good + "{step: 2}\n").encode(),
        "save-line-open-kept-past-end": (good + '{"open_kept": 3, "open_steps": []}\n').encode(),
        "first-line-cut": good[:40].encode(),
        "empty": b"",
        "utf16": good.encode("utf-16"),
        "nul-inside": good.encode().replace(b"offline", b"off\x00line"),
        "binary": bytes(random.Random(25).randrange(256) for _ in range(1024)),
    })
    entries = [Hostile("journal", name, content) for name, content in cases.items()]
    return entries + _special("journal")


def _make_session_kind(entry: Hostile, sub: Path) -> Path:
    """Where a world, motion or journal entry goes, with the good files around it: a folder of the
    snacks domain for a world; a session base folder for a motion (with its journal and domain
    copy) and for a journal."""
    base = sub / entry.name
    if entry.kind == "world":
        base.mkdir()
        (base / "domain.toml").write_bytes(GOOD_WORLD_DOMAIN)
        return base / "world.toml"
    for folder in ("demos", "trees", "recordings"):
        (base / folder / MOTION_SESSION).mkdir(parents=True)
    if entry.kind == "journal":  # a session keeps a copy of its domain from its start on
        (base / "demos" / MOTION_SESSION / "domain.toml").write_bytes(GOOD_DOMAIN)
        return base / "recordings" / f"{MOTION_SESSION}.journal.json"
    (base / "recordings" / f"{MOTION_SESSION}.journal.json").write_text(GUIDED_JOURNAL, encoding="utf-8")
    (base / "demos" / MOTION_SESSION / "domain.toml").write_bytes(GUIDED_DOMAIN)
    return base / "demos" / MOTION_SESSION / "PushBall.motion.json"


def _bind_socket(path: Path) -> None:
    """A socket file at ``path`` (nobody listens on it), bound through its folder's descriptor:
    AF_UNIX takes at most 108 bytes, and a parallel run's temporary folders are deep."""
    where = os.open(path.parent, os.O_RDONLY)
    try:
        with socket.socket(socket.AF_UNIX) as server:
            server.bind(f"/proc/self/fd/{where}/{path.name}")
    finally:
        os.close(where)


def _deep_socket(path: Path, folder: Path) -> str:
    """A socket at a path too long for AF_UNIX to name."""
    _bind_socket(path)
    return str(path.relative_to(folder))


SESSION_KINDS = {"world": 0, "journal": 1, "motion": 2}
"""The kinds that live in a folder of their own, with how many folders up from the file it is
(the folder of the domain for a world, the session's base folder for a journal or a motion)."""


# --- recordings ---------------------------------------------------------------------------------

Row = tuple[str, dict[str, list[object]]]
"""One logged row: the entity and its plain fields (each a list, as the session's writer logs them)."""

LINE = {"speaker": ["robot"], "text": ["hi"], "question": [""], "answer": [""], "change": [""]}
MISSING: dict[str, Row] = {
    "replay-without-reproduced": ("learner/replay", {"total": [3], "lenient": [False]}),
    "replay-with-two-values": ("learner/replay", {"reproduced": [1, 2], "total": [3], "lenient": [False]}),
    "generation-without-xml": ("learner/generations", {"generation": [1], "reason": ["r"], "nodes": [5]}),
    "dialogue-without-kind": ("dialogue", {**LINE, "budget_left": [-1]}),
    "dialogue-without-budget": ("dialogue", {**LINE, "kind": ["line"]}),
    "answer-without-change": ("dialogue", {**LINE, "kind": ["answer"], "budget_left": [-1], "change": []}),
    "demo-without-csv": ("demos", {"name": ["d"], "states": ["00"], "step_labels": ["goal"], "reached_goal": [True]}),
    "demo-states-and-labels-differ": ("demos", {"name": ["d"], "states": ["00", "01"], "step_labels": ["goal"],
                                                "reached_goal": [True], "csv": ["0;0;0\n"]}),
    "tick-without-generation": ("tree/graph", {"status": ["RUNNING"], "action": ["A"]}),
    "tick-without-action": ("tree/graph", {"status": ["RUNNING"], "generation": [0]}),
    "tick-trace-lengths-differ": ("tree/graph", {"status": ["RUNNING"], "action": [""], "generation": [0],
                                                 "trace_nodes": [0, 1], "trace_labels": ["a"],
                                                 "trace_status": ["SUCCESS"]}),
    "tick-trace-without-status": ("tree/graph", {"status": ["RUNNING"], "action": [""], "generation": [0],
                                                 "trace_nodes": [0], "trace_labels": ["a"]}),
    "state-without-action": ("state", {"conditions": ["A"], "values": [True]}),
    "state-values-missing-one": ("state", {"conditions": ["A", "B"], "values": [True], "action": [""]}),
    "external-without-name": ("state/external", {"level": ["EXTERNAL"]}),
    "learner-event-without-detail": ("learner/events", {"event": ["e"]}),
    "domain-without-name": ("domain", {"conditions": ["A"], "actions": ["B"]}),
}
"""Rows with a field missing, or lists that do not fit together (all present fields well typed)."""

WRONG: dict[str, Row] = {
    "replay-reproduced-is-text": ("learner/replay", {"reproduced": ["many"], "total": [3], "lenient": [False]}),
    "generation-nodes-is-text": ("learner/generations", {"generation": [1], "reason": ["r"], "nodes": ["many"],
                                                         "xml": ["<root/>"]}),
    "dialogue-budget-is-text": ("dialogue", {**LINE, "kind": ["line"], "budget_left": ["two"]}),
    "demo-reached-goal-is-text": ("demos", {"name": ["d"], "states": ["00"], "step_labels": ["goal"],
                                            "reached_goal": ["yes"], "csv": ["x"]}),
    "state-values-are-numbers": ("state", {"conditions": ["A"], "values": [0.5], "action": [""]}),
    "tick-status-is-a-number": ("tree/graph", {"status": [3], "action": [""], "generation": [0]}),
    "external-is-a-number": ("state/external", {"external": [7]}),
    "learner-removed-are-numbers": ("learner/events", {"event": ["e"], "detail": ["d"], "removed": [1, 2]}),
    "domain-actions-are-numbers": ("domain", {"name": ["n"], "conditions": ["A"], "actions": [1, 2]}),
}
"""Rows with one field of another type than the session's writer logs. rerun fixes a field's type
the first time a process logs it, so these are written in a process of their own, and no field
appears here with two types."""

_WRITE_RECORDINGS = """
import json, sys
import rerun as rr
from teach.observe.layout import APPLICATION_ID
folder, cases = sys.argv[1], json.loads(sys.argv[2])
for name, (entity, fields) in cases.items():
    app = "other-application" if name == "another-application" else APPLICATION_ID
    rec = rr.RecordingStream(app, recording_id=name)
    rec.save(f"{folder}/{name}.rrd")
    rec.set_time("step", sequence=3)
    parts = [rr.AnyValues(**fields)] if fields else [rr.TextLog("no fields")]
    rec.log(entity, *parts, static=entity == "domain")
    rec.flush()
    rec.disconnect()
"""


def _written(cases: dict[str, Row]) -> dict[str, bytes]:
    """Each case as a one-row recording, written by rerun in a fresh process."""
    with tempfile.TemporaryDirectory() as folder:
        done = subprocess.run([sys.executable, "-c", _WRITE_RECORDINGS, folder, json.dumps(cases)], check=True,
                              cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)}, capture_output=True, timeout=300)
        if b"Inconsistent with previous type" in done.stderr:  # a field given two types: rerun dropped one
            raise RuntimeError(done.stderr.decode(errors="replace"))
        return {name: (Path(folder) / f"{name}.rrd").read_bytes() for name in cases}


@functools.cache
def recordings() -> list[Hostile]:
    written = _written({**MISSING, "good": ("learner/replay", {"reproduced": [1], "total": [1], "lenient": [False]}),
                        "another-application": ("learner/replay", {"total": [1]})})
    written.update(_written(WRONG))
    good = written.pop("good")
    written.update({"empty": b"", "not-rerun": b"RRF2" + bytes(random.Random(13).randrange(256) for _ in range(400)),
                    "truncated": good[:len(good) // 2], "text": b"this is not a recording\n"})
    return [Hostile("recording", name, content) for name, content in written.items()] + _special("recording")


# --- run logs (.btlog) beside a recording ---------------------------------------------------------

BTLOG_MAGIC = b"BTCPP4-FileLogger2"
BTLOG_XML = ('<root BTCPP_format="4">\n<BehaviorTree ID="MainTree" _fullpath="">\n'
             '<ReactiveSequence name="ReactiveSequence" _uid="1">\n<Ready name="Ready" _uid="2"/>\n'
             '<Work name="Work" _uid="3"/>\n</ReactiveSequence>\n</BehaviorTree>\n<TreeNodesModel>\n'
             '<Condition ID="Ready"/>\n<Action ID="Work"/>\n</TreeNodesModel>\n</root>\n')


def btlog_file(xml: str = BTLOG_XML, records: bytes | None = None, protocol: int = 1, size: int | None = None,
               start: bytes = b"\x00" * 8) -> bytes:
    """A FileLogger2 file: magic, protocol, XML size and XML, first timestamp, 9-byte records."""
    raw = xml.encode("utf-8", errors="surrogateescape")
    if records is None:  # root RUNNING, Ready SUCCESS, Work RUNNING
        records = b"".join(_record(t, uid, status) for t, uid, status in ((0, 1, 1), (0, 2, 2), (5, 3, 1)))
    return (BTLOG_MAGIC + bytes([protocol]) + (len(raw) if size is None else size).to_bytes(4, "little", signed=True)
            + raw + start + records)


def _record(time_us: int, uid: int, status: int) -> bytes:
    return time_us.to_bytes(6, "little") + uid.to_bytes(2, "little") + bytes([status])


GOOD_BTLOG = btlog_file()


def btlogs() -> list[Hostile]:
    """Run logs ``teach review`` reads beside a recording: each case is ``run-002.btlog`` after a
    good ``run-001.btlog``, beside a good recording."""
    good_xml = BTLOG_XML
    cases: dict[str, bytes] = {
        "empty": b"",
        "magic-only": BTLOG_MAGIC,
        "magic-and-protocol": BTLOG_MAGIC + b"\x01",
        "wrong-magic": b"BTCPP3-FileLogger2" + GOOD_BTLOG[len(BTLOG_MAGIC):],
        "magic-lower-case": BTLOG_MAGIC.lower() + GOOD_BTLOG[len(BTLOG_MAGIC):],
        "protocol-0": btlog_file(protocol=0),
        "protocol-2": btlog_file(protocol=2),
        "protocol-255": btlog_file(protocol=255),
        "xml-size-0": btlog_file(size=0),
        "xml-size-negative": btlog_file(size=-5),
        "xml-size-huge": btlog_file(size=2**31 - 1),
        "xml-size-past-the-end": btlog_file(size=len(good_xml) + 100, records=b""),
        "no-timestamp": btlog_file(start=b"", records=b""),
        "half-a-timestamp": btlog_file(start=b"\x00" * 4, records=b""),
        "xml-latin1": btlog_file(good_xml.replace("Work", "W\udce4rk")),
        "xml-nul": btlog_file(good_xml.replace("Work", "Wo\x00rk", 1)),
        "xml-malformed": btlog_file(good_xml.replace("</root>", "</rot>")),
        "xml-doctype": btlog_file('<!DOCTYPE root [<!ENTITY x "y">]>\n' + good_xml),
        "xml-external-entity": btlog_file('<!DOCTYPE r [<!ENTITY e SYSTEM "file:///etc/passwd">]>\n<root>&e;</root>'),
        "xml-no-tree": btlog_file('<root BTCPP_format="4"/>', records=b""),
        "xml-not-a-tree": btlog_file("<html><body>hi</body></html>", records=b""),
        "xml-unknown-node": btlog_file(good_xml.replace("ReactiveSequence", "Frobnicate")),
        "xml-uid-not-a-number": btlog_file(good_xml.replace('_uid="3"', '_uid="three"')),
        "xml-uid-negative": btlog_file(good_xml.replace('_uid="3"', '_uid="-3"')),
        "xml-uid-huge": btlog_file(good_xml.replace('_uid="3"', '_uid="99999999999999999999"')),
        "xml-uid-twice": btlog_file(good_xml.replace('_uid="3"', '_uid="2"')),
        "xml-deep-5000": btlog_file('<root BTCPP_format="4"><BehaviorTree ID="MainTree">' + "<Inverter>" * 5000
                                    + '<Work _uid="1"/>' + "</Inverter>" * 5000 + "</BehaviorTree></root>", b""),
        "status-5": btlog_file(records=_record(0, 1, 5)),
        "status-255": btlog_file(records=_record(0, 1, 255)),
        "uid-0": btlog_file(records=_record(0, 0, 1)),
        "uid-unknown": btlog_file(records=_record(0, 9, 1)),
        "uid-65535": btlog_file(records=_record(0, 65535, 1)),
        "tree-file-instead": GOOD_TREE,
        "csv-instead": GOOD_DEMO,
        "domain-instead": GOOD_DOMAIN,
        "text-instead": b"this is not a log\n",
        "binary": bytes(random.Random(23).randrange(256) for _ in range(4096)),
        "utf16": GOOD_BTLOG.decode("latin-1").encode("utf-16"),
    }
    for extra in range(1, RECORD_BYTES):  # a record cut short, by each number of bytes
        cases[f"record-cut-{extra}"] = GOOD_BTLOG + _record(9, 2, 2)[:extra]
    for percent in (3, 10, 25, 50, 75, 90):  # truncated in the header or the XML
        cases[f"truncated-{percent:02d}"] = GOOD_BTLOG[:len(GOOD_BTLOG) * percent // 100]
    entries = [Hostile("btlog", name, content) for name, content in cases.items()]
    return entries + [Hostile("btlog", f"special-{special}", special=special) for special in SPECIALS
                      if special not in ("missing", "dotdot-missing")]  # a run log is only read where one is


RECORD_BYTES = 9


@functools.cache
def good_recording() -> bytes:
    """A teach recording ``teach review`` reads (one replay row), written by rerun."""
    return _written({"good": ("learner/replay", {"reproduced": [1], "total": [1], "lenient": [False]})})["good"]


def _make_btlog(entry: Hostile, sub: Path, folder: Path) -> str:
    """``btlogs/<name>.rrd`` and its runs ``btlogs/<name>/run-001.btlog`` (good), ``run-002.btlog``."""
    recording = sub / f"{entry.name}.rrd"
    recording.write_bytes(good_recording())
    runs = sub / entry.name
    runs.mkdir()
    (runs / "run-001.btlog").write_bytes(GOOD_BTLOG)
    bad = runs / "run-002.btlog"
    if entry.special:
        _make_special(entry.special, bad, folder)
    else:
        assert entry.content is not None
        bad.write_bytes(entry.content)
    return str(recording.relative_to(folder))


# --- special files, the same for every kind -----------------------------------------------------

SPECIALS = ("fifo", "folder", "socket", "missing", "symlink-loop", "symlink-to-fifo", "dangling-symlink",
            "dev-zero", "dev-null", "dev-urandom", "dotdot-missing")


def _special(kind: str, absent_is_fine: bool = False) -> list[Hostile]:
    """Every special file for ``kind``; a kind found by a fixed name gets no '..' path, and one
    that may be absent (world.toml) not the missing file either."""
    skip = {"dotdot-missing", "missing"} if absent_is_fine else {"dotdot-missing"} if kind in SESSION_KINDS else set()
    if kind == "journal":  # no journal beside a session's domain copy: a start killed early, taken over by --resume
        skip.add("missing")
    return [Hostile(kind, f"special-{special}", special=special) for special in SPECIALS if special not in skip]


def materialise(entry: Hostile, folder: Path) -> str:
    """Create ``entry`` under ``folder`` (in ``<kind>s/``) and return the path to pass, relative to
    ``folder``; csv entries become a set ``csvs/<name>/`` with the good domain beside the bad file."""
    sub = folder / f"{entry.kind}s"
    sub.mkdir(exist_ok=True)
    if entry.kind == "set":
        return _make_set(entry.special, sub / entry.name, folder)
    if entry.kind == "btlog":
        return _make_btlog(entry, sub, folder)
    if entry.kind == "csv":
        target = sub / entry.name
        target.mkdir()
        (target / "domain.toml").write_bytes(GOOD_DOMAIN)
        (target / "a-good.csv").write_bytes(GOOD_DEMO)
        path = target / "b-bad.csv"
    elif entry.kind in SESSION_KINDS:
        path = _make_session_kind(entry, sub)
        if entry.special == "socket":
            return _deep_socket(path, folder)
    else:
        path = sub / f"{entry.name}.{_SUFFIX[entry.kind]}"
    if entry.special:
        return _make_special(entry.special, path, folder)
    assert entry.content is not None
    path.write_bytes(entry.content)
    return str(path.relative_to(folder))


_SUFFIX = {"tree": "xml", "domain": "toml", "csv": "csv", "dialogue": "dialogue", "recording": "rrd"}


def _make_special(special: str, path: Path, folder: Path) -> str:
    if special == "fifo":
        os.mkfifo(path)
    elif special == "folder":
        path.mkdir()
    elif special == "socket":
        _bind_socket(path)
    elif special == "symlink-loop":
        path.symlink_to(path.name)
    elif special == "symlink-to-fifo":
        os.mkfifo(path.with_name(path.name + ".fifo"))
        path.symlink_to(path.name + ".fifo")
    elif special == "dangling-symlink":
        path.symlink_to("nowhere/at/all")
    elif special.startswith("dev-"):
        path.symlink_to(f"/dev/{special[4:]}")
    elif special == "dotdot-missing":
        return str(path.relative_to(folder).parent / ".." / ".." / "outside" / path.name)
    elif special != "missing":
        raise ValueError(special)
    return str(path.relative_to(folder))


def _make_set(special: str, target: Path, folder: Path) -> str:
    relative = str(target.relative_to(folder))
    if special == "set-missing":
        return relative
    if special == "set-is-a-file":
        target.write_bytes(GOOD_DEMO)
        return relative
    if special == "set-is-a-fifo":
        os.mkfifo(target)
        return relative
    target.mkdir()
    if special != "set-without-domain":
        if special == "set-domain-is-fifo":
            os.mkfifo(target / "domain.toml")
        elif special == "set-domain-is-folder":
            (target / "domain.toml").mkdir()
        elif special == "set-domain-deep":
            (target / "domain.toml").write_bytes(("x = " + "[" * 500 + "]" * 500 + "\n").encode() + GOOD_DOMAIN)
        else:
            (target / "domain.toml").write_bytes(GOOD_DOMAIN)
    if special != "set-without-csv":
        (target / "a-good.csv").write_bytes(GOOD_DEMO)
    bad = target / "b-bad.csv"
    if special == "set-csv-is-fifo":
        os.mkfifo(bad)
    elif special == "set-csv-is-socket":
        _bind_socket(bad)
    elif special == "set-csv-symlink-loop":
        bad.symlink_to(bad.name)
    elif special == "set-csv-to-dev-zero":
        bad.symlink_to("/dev/zero")
    elif special == "set-csv-dangling-link":
        bad.symlink_to("missing.csv")
    elif special == "set-csv-is-device":
        bad.symlink_to("/dev/null")
    return relative


# --- output paths -------------------------------------------------------------------------------

def _symlink(name: str, to: str) -> Callable[[Path], None]:
    return lambda folder: (folder / name).symlink_to(to)


def _fifo(name: str) -> Callable[[Path], None]:
    return lambda folder: os.mkfifo(folder / name)


def _file(name: str, content: bytes = b"keep me") -> Callable[[Path], None]:
    def make(folder: Path) -> None:
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(content)
    return make


def _socket(name: str) -> Callable[[Path], None]:
    def make(folder: Path) -> None:
        _make_special("socket", folder / name, folder)
    return make


def _both(*steps: Callable[[Path], None]) -> Callable[[Path], None]:
    def make(folder: Path) -> None:
        for step in steps:
            step(folder)
    return make


def _folder(name: str) -> Callable[[Path], None]:
    return lambda folder: (folder / name).mkdir(parents=True)


def outputs(tree: str, demo_set: str, dialogue: str = "good.dialogue") -> list[OutputCase]:
    """Output paths every writing command must refuse before writing anything; ``tree``,
    ``demo_set`` (holding ``domain.toml`` and ``d1.csv``) and ``dialogue`` are good inputs
    (absolute paths)."""
    writers: list[tuple[str, tuple[str, ...]]] = [
        ("learn", ("learn", demo_set, "-o")), ("prune", ("prune", tree, "-o")), ("dot", ("dot", tree, "-o"))]
    targets: list[tuple[str, str, str, Callable[[Path], None]]] = [
        ("symlink-to-file", "out.xml", "out.xml", _both(_file("real.xml"), _symlink("out.xml", "real.xml"))),
        ("dangling-symlink", "out.xml", "out.xml", _symlink("out.xml", "elsewhere.xml")),
        ("symlink-out-of-project", "out.xml", "out.xml", _symlink("out.xml", "/tmp/teach-hostile-never.xml")),
        ("fifo", "out.xml", "out.xml", _fifo("out.xml")),
        ("dev-null", "/dev/null", "/dev/null", lambda folder: None),
        ("dev-stdout", "/dev/stdout", "/dev/stdout", lambda folder: None),
        ("dev-zero", "/dev/zero", "/dev/zero", lambda folder: None),
        ("folder", "out", "out", _folder("out")),
        ("symlinked-folder", "link/out.xml", "link/out.xml", _both(_folder("real"), _symlink("link", "real"))),
        ("symlinked-folder-deep", "link/a/b/out.xml", "link/a/b/out.xml",
         _both(_folder("real"), _symlink("link", "real"))),
        ("under-a-file", "file.xml/out.xml", "file.xml/out.xml", _file("file.xml")),
        ("under-proc", "/proc/teach/out.xml", "/proc/teach/out.xml", lambda folder: None),
        ("socket", "out.xml", "out.xml", _socket("out.xml")),
    ]
    cases = [OutputCase(f"{writer}-{target}", (*command, path), expect, setup)
             for writer, command in writers for target, path, expect, setup in targets]
    generations = [
        ("generations-a-file", ("--generations", "gens"), "gens", _file("gens")),
        ("generations-symlink", ("--generations", "gens"), "gens", _both(_folder("real"), _symlink("gens", "real"))),
        ("generations-under-file", ("--generations", "file/gens"), "file/gens", _file("file")),
        ("generations-under-proc", ("--generations", "/proc/teach-gens"), "/proc/teach-gens", lambda folder: None),
        ("generations-same-as-output", ("--generations", "out/l.xml"), "out/l.xml", lambda folder: None),
    ]
    cases += [OutputCase(name, ("learn", demo_set, "-o", "out/l.xml", *extra), expect, setup)
              for name, extra, expect, setup in generations]
    for name, set_name in (("dotdot", "../x"), ("dotdot-inside", "ball/../../x"), ("absolute", "/tmp/x"),
                           ("dot", "."), ("empty", "")):
        cases.append(OutputCase(f"record-set-{name}", ("record", "--set", set_name, "FindBall"), set_name or "''"))
    cases += [
        OutputCase("record-set-symlinked", ("record", "--set", "ball/sim", "FindBall"), "demos/ball/sim",
                   _both(_folder("elsewhere"), _folder("demos/ball"), _symlink("demos/ball/sim", "../../elsewhere"))),
        OutputCase("record-root-symlinked", ("record", "--set", "sim", "--root", "data", "FindBall"), "data/sim",
                   _both(_folder("elsewhere"), _symlink("data", "elsewhere"))),
        OutputCase("record-set-is-a-file", ("record", "--set", "sim", "FindBall"), "demos/sim",
                   _file("demos/sim")),
    ]
    return cases + inputs_as_outputs(tree, demo_set, dialogue) + session_paths(dialogue)


def _copy(source: str, name: str) -> Callable[[Path], None]:
    return lambda folder: _file(name, Path(source).read_bytes())(folder)


def _hard_link(source: str, name: str) -> Callable[[Path], None]:
    return lambda folder: os.link(source, folder / name)


def inputs_as_outputs(tree: str, demo_set: str, dialogue: str) -> list[OutputCase]:
    """Outputs that are what the command reads (issue 23: ``teach learn SET -o SET/a-good.csv``
    replaced a demonstration, ``teach dot tree.xml -o tree.xml`` the tree): the same path, another
    spelling of it, a hard link, a path through a symbolic link, a file inside a set read whole."""
    demo, domain = f"{demo_set}/d1.csv", f"{demo_set}/domain.toml"
    folder_of_tree = str(Path(tree).parent)
    spelled = f"{demo_set}/../{Path(demo_set).name}/d1.csv"
    learn, bench = ("learn", demo_set), ("bench-teach", demo_set, demo_set, "--oracle", tree, "--questions", "0")
    none: Callable[[Path], None] = lambda folder: None  # noqa: E731 - a setup that makes nothing
    table: list[tuple[str, tuple[str, ...], str, Callable[[Path], None]]] = [
        ("learn-demonstration", (*learn, "-o", demo), demo, none),
        ("learn-domain-of-the-set", (*learn, "-o", domain), domain, none),
        ("learn-new-file-in-the-set", (*learn, "-o", f"{demo_set}/zz.csv"), f"{demo_set}/zz.csv", none),
        ("learn-deep-in-the-set", (*learn, "-o", f"{demo_set}/sub/x.xml"), f"{demo_set}/sub/x.xml", none),
        ("learn-the-set-itself", (*learn, "-o", demo_set), demo_set, none),
        ("learn-demonstration-spelled-with-dotdot", (*learn, "-o", spelled), spelled, none),
        ("learn-hard-link-to-a-demonstration", (*learn, "-o", "hard.csv"), "hard.csv", _hard_link(demo, "hard.csv")),
        ("learn-through-a-link-to-the-set", (*learn, "-o", "alias/zz.xml"), "alias/zz.xml",
         lambda folder: (folder / "alias").symlink_to(demo_set)),
        ("learn-given-domain", (*learn, "--domain", "d.toml", "-o", "d.toml"), "d.toml", _copy(domain, "d.toml")),
        ("learn-pabt-domain", ("learn", "d.toml", "--approach", "pabt", "-o", "d.toml"), "d.toml",
         _copy(domain, "d.toml")),
        ("learn-pabt-domain-hard-link", ("learn", "d.toml", "--approach", "pabt", "-o", "e.toml"), "e.toml",
         _both(_copy(domain, "d.toml"), lambda folder: os.link(folder / "d.toml", folder / "e.toml"))),
        ("learn-generations-into-the-set", (*learn, "-o", "out.xml", "--generations", demo_set), demo_set, none),
        ("learn-generations-into-a-set-folder", (*learn, "-o", "out.xml", "--generations", f"{demo_set}/gens"),
         f"{demo_set}/gens", none),
        ("learn-generations-beside-the-domain", (*learn, "--domain", "d.toml", "-o", "out/l.xml",
                                                 "--generations", "."), ".", _copy(domain, "d.toml")),
        ("prune-tree", ("prune", tree, "-o", tree), tree, none),
        ("prune-tree-hard-link", ("prune", tree, "-o", "hard.xml"), "hard.xml", _hard_link(tree, "hard.xml")),
        ("prune-tree-through-a-link", ("prune", tree, "-o", f"alias/{Path(tree).name}"),
         f"alias/{Path(tree).name}", lambda folder: (folder / "alias").symlink_to(folder_of_tree)),
        ("prune-tree-spelled-with-dot", ("prune", "t.xml", "-o", "./t.xml"), "t.xml", _copy(tree, "t.xml")),
        ("prune-domain", ("prune", tree, "--domain", "d.toml", "-o", "d.toml"), "d.toml", _copy(domain, "d.toml")),
        ("dot-tree", ("dot", tree, "-o", tree), tree, none),
        ("dot-tree-relative", ("dot", "t.xml", "-o", "t.xml"), "t.xml", _copy(tree, "t.xml")),
        ("dot-tree-spelled-with-dotdot", ("dot", "sub/t.xml", "-o", "sub/../sub/t.xml"), "sub/../sub/t.xml",
         _copy(tree, "sub/t.xml")),
        ("dot-tree-hard-link", ("dot", tree, "-o", "hard.dot"), "hard.dot", _hard_link(tree, "hard.dot")),
        ("dot-tree-through-a-link", ("dot", tree, "-o", f"alias/{Path(tree).name}"), f"alias/{Path(tree).name}",
         lambda folder: (folder / "alias").symlink_to(folder_of_tree)),
        ("bench-oracle", (*bench, "-o", tree), tree, none),
        ("bench-training-set", (*bench, "-o", f"{demo_set}/x.xml"), f"{demo_set}/x.xml", none),
        ("bench-test-set", ("bench-teach", demo_set, "test", "--oracle", tree, "--questions", "0", "-o",
                            "test/x.xml"), "test/x.xml",
         _both(_copy(demo, "test/d1.csv"), _copy(domain, "test/domain.toml"))),
        ("bench-oracle-model", ("bench-teach", demo_set, demo_set, "--oracle-model", "m.toml", "--questions", "0",
                                "-o", "m.toml"), "m.toml", _copy(domain, "m.toml")),
        ("bench-domain", (*bench, "--domain", "m.toml", "-o", "m.toml"), "m.toml", _copy(domain, "m.toml")),
        ("bench-domain-hard-link", (*bench, "--domain", "m.toml", "-o", "n.toml"), "n.toml",
         _both(_copy(domain, "m.toml"), lambda folder: os.link(folder / "m.toml", folder / "n.toml"))),
        ("replay-dialogue-in-its-session-folder", ("replay", "demos/good/good.dialogue", "--no-record"),
         "demos/good", _copy(dialogue, "demos/good/good.dialogue")),
        ("replay-dialogue-in-its-trees", ("replay", "trees/good/good.dialogue", "--no-record"), "trees/good",
         _copy(dialogue, "trees/good/good.dialogue")),
        ("replay-dialogue-is-its-recording", ("replay", "recordings/x.rrd", "--session", "x"), "recordings/x.rrd",
         _copy(dialogue, "recordings/x.rrd")),
        ("replay-dialogue-is-its-journal", ("replay", "recordings/j.journal.json", "--session", "j", "--no-record"),
         "recordings/j.journal.json", _copy(dialogue, "recordings/j.journal.json")),
        ("replay-oracle-in-its-trees", ("replay", dialogue, "--oracle", "trees/good/gen-01.xml", "--no-record"),
         "trees/good", _copy(tree, "trees/good/gen-01.xml")),
        ("replay-domain-in-its-demos", ("replay", dialogue, "--domain", "demos/good/domain.toml", "--no-record"),
         "demos/good", _copy(domain, "demos/good/domain.toml")),
        ("replay-oracle-model-in-its-demos", ("replay", dialogue, "--oracle-model", "demos/good/undone/m.toml",
                                              "--no-record"), "demos/good", _copy(domain, "demos/good/undone/m.toml")),
        ("replay-dialogue-in-its-run-folder", ("replay", "recordings/good/good.dialogue"), "recordings/good",
         _copy(dialogue, "recordings/good/good.dialogue")),
        ("replay-dialogue-under-its-base", ("replay", "b/demos/good/good.dialogue", "--base", "b", "--no-record"),
         "b/demos/good", _copy(dialogue, "b/demos/good/good.dialogue")),
        ("session-domain-in-its-demos", ("session", "--session", "S", "--domain", "demos/S/domain.toml", "--world",
                                         "offline", "--no-record"), "demos/S", _copy(domain, "demos/S/domain.toml")),
        ("session-domain-in-its-trees", ("session", "--session", "S", "--domain", "trees/S/domain.toml", "--world",
                                         "offline", "--no-record"), "trees/S", _copy(domain, "trees/S/domain.toml")),
        ("session-domain-is-its-journal", ("session", "--session", "S", "--domain", "recordings/S.journal.json",
                                           "--world", "offline", "--no-record"), "recordings/S.journal.json",
         _copy(domain, "recordings/S.journal.json")),
        ("session-world-file-in-its-demos", ("session", "--session", "S", "--domain", "demos/S/x/domain.toml",
                                             "--world", "offline", "--no-record"), "demos/S",
         _both(_copy(domain, "demos/S/x/domain.toml"), _file("demos/S/x/world.toml", b"# hidden state\n"))),
    ]
    return [OutputCase(f"input-{name}", args, expect, setup) for name, args, expect, setup in table]


def session_paths(dialogue: str) -> list[OutputCase]:
    """A session's own paths that are links, special files or files where folders belong: refused
    before the first folder is made (issue 23: ``teach session --base LINK`` created folders
    outside; a journal that was a link was read through it; a FIFO recording hung ``--resume``)."""
    new = ("--session", "S", "--world", "offline")
    resume = ("--resume", "S", "--world", "offline")
    outside = _folder("elsewhere")
    table: list[tuple[str, tuple[str, ...], str, Callable[[Path], None]]] = [
        ("base-link", ("session", "--base", "LINK", *new), "LINK", _both(outside, _symlink("LINK", "elsewhere"))),
        ("base-under-a-link", ("session", "--base", "LINK/sub", *new), "LINK",
         _both(outside, _symlink("LINK", "elsewhere"))),
        ("base-a-file", ("session", "--base", "b", *new), "b", _file("b")),
        ("journal-link", ("session", *resume), "recordings/S.journal.json",
         _both(_file("elsewhere/j.json", b"{}\n"), _folder("recordings"),
               _symlink("recordings/S.journal.json", "../elsewhere/j.json"))),
        ("journal-link-new", ("session", *new), "recordings/S.journal.json",
         _both(_folder("recordings"), _symlink("recordings/S.journal.json", "nowhere.json"))),
        ("journal-fifo", ("session", *resume), "recordings/S.journal.json",
         _both(_folder("recordings"), _fifo("recordings/S.journal.json"))),
        ("journal-folder", ("session", *resume), "recordings/S.journal.json", _folder("recordings/S.journal.json")),
        ("journal-socket", ("session", *resume), "recordings/S.journal.json",
         _both(_folder("recordings"), _socket("recordings/S.journal.json"))),
        ("recording-fifo", ("session", *resume), "recordings/S.rrd",
         _both(_folder("recordings"), _fifo("recordings/S.rrd"))),
        ("recording-link", ("session", *new), "recordings/S.rrd",
         _both(_file("elsewhere/r.rrd"), _folder("recordings"), _symlink("recordings/S.rrd", "../elsewhere/r.rrd"))),
        ("recording-part-fifo", ("session", *new), "recordings/S.rrd.part",
         _both(_folder("recordings"), _fifo("recordings/S.rrd.part"))),
        ("recording-merge-fifo", ("session", *resume), "recordings/S.rrd.merged",
         _both(_folder("recordings"), _fifo("recordings/S.rrd.merged"))),
        ("history-folder", ("session", *new, "--no-record"), "recordings/.teach_history",
         _folder("recordings/.teach_history")),
        ("history-fifo", ("session", *new, "--no-record"), "recordings/.teach_history",
         _both(_folder("recordings"), _fifo("recordings/.teach_history"))),
        ("history-link", ("session", *new, "--no-record"), "recordings/.teach_history",
         _both(_file("elsewhere/h"), _folder("recordings"), _symlink("recordings/.teach_history", "../elsewhere/h"))),
        ("demos-folder-link", ("session", *new, "--no-record"), "demos/S",
         _both(outside, _folder("demos"), _symlink("demos/S", "../elsewhere"))),
        ("demos-link", ("session", *new, "--no-record"), "demos", _both(outside, _symlink("demos", "elsewhere"))),
        ("trees-folder-a-file", ("session", *new, "--no-record"), "trees/S", _file("trees/S")),
        ("trees-folder-a-fifo", ("session", *new, "--no-record"), "trees/S", _both(_folder("trees"), _fifo("trees/S"))),
        ("run-folder-a-fifo", ("session", *new), "recordings/S", _both(_folder("recordings"), _fifo("recordings/S"))),
        ("demonstration-a-link", ("session", *resume, "--no-record"), "demos/S/demo-001.csv",
         _both(_file("elsewhere/d.csv", GOOD_DEMO), _folder("demos/S"),
               _symlink("demos/S/demo-001.csv", "../../elsewhere/d.csv"))),
        ("generation-a-link", ("session", *resume, "--no-record"), "trees/S/gen-01.xml",
         _both(_file("elsewhere/t.xml", GOOD_TREE), _folder("trees/S"),
               _symlink("trees/S/gen-01.xml", "../../elsewhere/t.xml"))),
        ("undone-a-link", ("session", *resume, "--no-record"), "demos/S/undone",
         _both(outside, _folder("demos/S"), _symlink("demos/S/undone", "../../elsewhere"))),
        ("recordings-link", ("session", *new), "recordings", _both(outside, _symlink("recordings", "elsewhere"))),
        ("replay-demos-link", ("replay", dialogue, "--no-record"), "demos",
         _both(outside, _symlink("demos", "elsewhere"))),
        ("replay-journal-fifo", ("replay", dialogue, "--no-record"), "recordings/good.journal.json",
         _both(_folder("recordings"), _fifo("recordings/good.journal.json"))),
        ("replay-journal-link", ("replay", dialogue, "--no-record"), "recordings/good.journal.json",
         _both(_file("elsewhere/j.json"), _folder("recordings"),
               _symlink("recordings/good.journal.json", "../elsewhere/j.json"))),
        ("replay-recording-link", ("replay", dialogue), "recordings/good.rrd",
         _both(_file("elsewhere/r.rrd"), _folder("recordings"), _symlink("recordings/good.rrd", "../elsewhere/r.rrd"))),
        ("replay-base-link", ("replay", dialogue, "--base", "LINK", "--no-record"), "LINK",
         _both(outside, _symlink("LINK", "elsewhere"))),
        ("replay-trees-a-file", ("replay", dialogue, "--no-record"), "trees", _file("trees")),
    ]
    return [OutputCase(f"session-{name}", args, expect, setup) for name, args, expect, setup in table]


def corpus() -> list[Hostile]:
    return (trees() + domains() + csvs() + sets() + dialogues() + worlds() + motions() + journals() + recordings()
            + btlogs())


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    folder = Path(argv[0])
    folder.mkdir(parents=True, exist_ok=False)
    entries = corpus()
    for entry in entries:
        materialise(entry, folder)
    kinds = sorted({entry.kind for entry in entries})
    print(", ".join(f"{sum(e.kind == kind for e in entries)} {kind}" for kind in kinds)
          + f", {len(outputs('TREE', 'SET'))} output paths")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
