"""`teach table`: the thesis's evaluation recomputed, every table present, run as the CLI runs it."""

from __future__ import annotations

import json

import pytest
from conftest import ROOT

from teach.cli import main
from teach.evaluate import SETS, THESIS_TABLE_6_2, evaluate

BALL = ROOT / "demos" / "ball"
STUDY = ROOT / "dialogues" / "study"


@pytest.fixture(scope="module")
def evaluation():
    return evaluate(BALL, STUDY)


def test_json_contains_every_table(capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    assert main(["table", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) == {"table_6_2", "table_6_3", "nodes", "participants"}
    for key in ("table_6_2", "table_6_3"):
        cells = data[key]["cells"]
        assert len(cells) == 25 and {(c["generated_from"], c["tested_on"]) for c in cells} == {
            (a, b) for a in SETS for b in SETS}
        assert all(0 <= c["strict"] <= c["lenient"] <= c["total"] for c in cells)
    assert {(n["approach"], n["source"]) for n in data["nodes"]} >= {("approach1", "all five goals")} | {
        (a, s) for a in ("approach2", "approach3") for s in SETS}
    assert [p["participant"] for p in data["participants"]] == list(range(1, 9))


def test_trees_reproduce_their_own_demonstrations(evaluation):
    # the thesis's first observation on Table 6.2: a tree always reproduces the set it came from
    for table in (evaluation.table_6_2, evaluation.table_6_3):
        for name in SETS:
            cell = table.cell(name, name)
            assert cell.strict == cell.total, (table.key, name)


def test_approach2_matches_the_thesis_where_the_data_is_pinned_down(evaluation):
    # rows Δ1, Δ3 (both readings) and Δ2, Δ5 (the lenient reading) are the thesis's exactly
    table = evaluation.table_6_2
    for source, lenient in (("delta1", False), ("delta3", False), ("delta2", True), ("delta5", True)):
        ours = tuple(getattr(table.cell(source, t), "lenient" if lenient else "strict") for t in SETS)
        assert ours == THESIS_TABLE_6_2[source], source


def test_pruned_delta1_trees_and_approach1_equal_colledanchise(evaluation):
    counts = {(n.approach, n.source): n for n in evaluation.nodes}
    approach1 = counts[("approach1", "all five goals")]
    assert (approach1.before, approach1.after, approach1.equals_colledanchise) == (24, 16, True)
    assert counts[("approach2", "delta1")].equals_colledanchise
    assert all(n.after <= n.before for n in evaluation.nodes)


def test_study_verdicts(evaluation):
    assert [p.participant for p in evaluation.participants if p.usable] == [4, 5, 7, 8]
    assert all(p.usable == p.thesis_usable for p in evaluation.participants)


def test_missing_data_is_one_clear_error(tmp_path, capsys):
    assert main(["table", "--demos", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("teach: ") and "domain" in err and err.count("\n") == 1
