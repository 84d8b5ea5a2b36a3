"""The headline benchmark as a test: few demonstrations plus at most five oracle-answered
questions must reproduce the thesis's Δ5 under the strict replay."""

from __future__ import annotations

import json

import pytest
from conftest import ROOT

from teach.cli import main

BALL = ROOT / "demos" / "ball"


@pytest.mark.parametrize("train, at_least", [("delta4", 43), ("delta3", 43)])
def test_few_demonstrations_and_five_questions(train, at_least, capsys):
    status = main(["bench-teach", str(BALL / train), str(BALL / "delta5"),
                   "--oracle", str(BALL / "reference" / "table61.xml"), "--questions", "5", "--json"])
    result = json.loads(capsys.readouterr().out)
    assert status == 0 and result["total"] == 43
    assert len(result["questions"]) <= 5
    assert result["reproduced"] >= at_least
    assert all("answer" in q for q in result["questions"])


def test_no_questions_means_the_plain_learner(capsys):
    main(["bench-teach", str(BALL / "delta4"), str(BALL / "delta5"),
          "--oracle", str(BALL / "reference" / "table61.xml"), "--questions", "0", "--json"])
    result = json.loads(capsys.readouterr().out)
    # the thesis's specialization reproduced 35/43 from Δ4; the model-based learner must not do worse
    assert result["questions"] == [] and result["reproduced"] >= 35
