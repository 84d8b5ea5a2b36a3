"""Question selection: situation questions about doubtful guards, phrasing, the budget."""

from __future__ import annotations

import pytest
from conftest import ROOT

from teach.demos import read_demo_set
from teach.dialogue.questions import (
    BudgetExhausted,
    QuestionBudget,
    describe_situation,
    effects_from,
    prior_real,
    select_question,
)
from teach.learn.specialize import specialize


def test_budget_is_never_exceeded():
    budget = QuestionBudget(2)
    budget.spend()
    budget.spend()
    with pytest.raises(BudgetExhausted):
        budget.spend()
    assert budget.left == 0


def test_situation_in_words(ball):
    state = ball.state(["BallGrasped"])
    assert describe_situation(ball, state) == ("the ball is in my hand, but I cannot see the ball, the ball is "
                                               "out of reach, the bin is out of reach and the ball is not in the bin")
    german = describe_situation(ball, state, "de")
    assert german.startswith("ich habe den Ball in der Hand, aber ich sehe den Ball nicht")


def test_causal_prior_from_demonstrations(ball):
    _, demos = read_demo_set(ROOT / "demos" / "ball" / "delta4")
    effects = effects_from(ball, demos)
    # GraspBall's own effect, the effect of ApproachBall just before it, the task's last effect
    assert prior_real(ball, "GraspBall", [("BallGrasped", True)], False, effects) > 0.9
    assert prior_real(ball, "GraspBall", [("BallClose", False)], False, effects) > 0.8
    assert prior_real(ball, "FindBall", [("BallPlaced", True)], False, effects) > 0.8
    # a guard only there because both demonstrations happened to have the bin far away
    assert prior_real(ball, "GraspBall", [("BinClose", True)], False, effects) < 0.5
    # a guard a demonstration needs is certain
    assert prior_real(ball, "GraspBall", [("BinClose", True)], True, effects) == 1.0


def test_first_question_targets_an_accidental_guard(ball):
    _, demos = read_demo_set(ROOT / "demos" / "ball" / "delta4")
    learner = specialize(ball, demos)
    labels = {}
    for demo in demos:
        for step in demo.steps:
            labels[step.state] = None if step.action == 0 else ball.action(step.action).name
    question = select_question(learner, demos, labels)
    assert question is not None and question.state not in labels
    # in the asked situation the robot now does nothing, yet some committee members would act
    assert any(answer != "done" for answer, _ in question.expected)
    # deterministic: the same inputs give the same question
    assert select_question(learner, demos, labels) == question
    # nothing is asked about a situation already asked
    other = select_question(learner, demos, labels, asked=[question.state])
    assert other is None or other.state != question.state
