"""Question selection: situation questions about doubtful guards, phrasing, the budget."""

from __future__ import annotations

import pytest

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Sequence
from teach.dialogue.questions import (BudgetExhausted, QuestionBudget, describe_situation, guard_key,
                                      select_question)


def test_budget_is_never_exceeded():
    budget = QuestionBudget(2)
    budget.spend()
    budget.spend()
    with pytest.raises(BudgetExhausted):
        budget.spend()
    assert budget.left == 0


def test_guard_keys():
    assert guard_key(Inverter(Condition("A"))) == "!A"
    assert guard_key(Sequence((Condition("A"), Inverter(Condition("B"))))) == "A&!B"


def test_situation_in_words(ball):
    state = ball.state(["BallGrasped"])
    assert describe_situation(ball, state) == ("the ball is in your hand, but you cannot see the ball, the ball is "
                                               "out of reach, the bin is out of reach and the ball is not in the bin")
    assert describe_situation(ball, state, "de").startswith("du hast den Ball in der Hand, aber du siehst den Ball nicht")


def test_asks_about_the_guard_with_most_doubt(ball):
    # PlaceBall is guarded by !BallFound (it was only shown while the ball was visible) and by !BinClose.
    tree = Sequence((Fallback((Inverter(Condition("BallFound")), Inverter(Condition("BinClose")),
                               Condition("BallPlaced"), Action("PlaceBall"))),))
    shown = {"PlaceBall": [ball.state(["BallFound", "BallClose", "BallGrasped", "BinClose"])]}
    question = select_question(tree, ball, [shown["PlaceBall"][0]], set(), shown)
    assert question is not None and question.action == "PlaceBall"
    # dropping either guard lets PlaceBall run in 4 more unseen states; the first in tree order wins the tie
    assert question.guard_key == "!BallFound" and question.impact == 4
    # the situation is the shown one with only the doubtful condition changed
    assert question.state == ball.state(["BallClose", "BallGrasped", "BinClose"])
    # once settled, the other guard is asked about
    again = select_question(tree, ball, [shown["PlaceBall"][0]], {("PlaceBall", "!BallFound")}, shown)
    assert again is not None and again.guard_key == "!BinClose"
    assert "what should I do?" in question.text(ball)
