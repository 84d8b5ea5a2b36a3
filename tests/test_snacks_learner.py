"""The model-based learner on Use Case 2 (demos/snacks): hidden state, repeats, events."""

from __future__ import annotations

from pathlib import Path

from teach.bt.nodes import Status
from teach.bt.tick import compile_tree
from teach.bt.xml import read_tree
from teach.demos import read_demo_set
from teach.learn.inquiry import next_question
from teach.learn.learner import learn_online
from teach.replay import replay
from tests.btcpp import assert_matches_btcpp

SNACKS = Path(__file__).resolve().parent.parent / "demos" / "snacks"


def test_training_and_held_out_snacks_are_reproduced_strictly() -> None:
    domain, train = read_demo_set(SNACKS / "train")
    _domain, held_out = read_demo_set(SNACKS / "heldout", domain)
    learner = learn_online(domain, train, safe=False)
    assert replay(learner.tree, domain, train).reproduced == len(train)
    # issue 10's target: at least 95% of the scenarios from every other start state
    assert replay(learner.tree, domain, held_out).reproduced >= 0.95 * len(held_out)
    assert_matches_btcpp(learner.tree, domain)


def test_an_offer_that_empties_the_tray_only_sometimes_achieves_an_empty_tray() -> None:
    domain, train = read_demo_set(SNACKS / "train")
    learner = learn_online(domain, train, safe=False)
    empty = (domain.condition_names.index("TrayEmpty"), True)
    # most offers leave something on the tray: that does not contradict the effect
    assert learner.model.achievers(empty) == ["OfferSnack"]


def test_a_condition_the_teacher_restores_after_every_event_is_kept_for_every_step() -> None:
    domain, train = read_demo_set(SNACKS / "train")
    learner = learn_online(domain, train, safe=False)
    requested = (domain.condition_names.index("Requested"), True)
    # the request was withdrawn twice (d04, d09) and the teacher waited for a new one at once;
    # d04 shows OfferSnack needs it, so ReturnToOffice (never shown without it) needs it too
    back = learner.model["ReturnToOffice"]
    assert requested in back.maintained
    assert "restores it at once" in back.reason(requested)
    without_request = (False, True, True, False, False)  # an empty tray carried, away, no request
    assert learner.answer_in(without_request) == "WaitForRequest"


def test_precondition_questions_start_with_the_step_shown_most_often() -> None:
    domain, train = read_demo_set(SNACKS / "train")
    learner = learn_online(domain, train[:3], safe=False)  # OfferSnack shown 7 times, WaitForRequest once
    asked: list[tuple[bool, ...]] = []
    question = next_question(learner, asked)
    while question is not None and question.kind != "possible-precondition":
        asked.append(question.state)
        question = next_question(learner, asked)
    assert question is not None and question.action == "OfferSnack"


def test_three_snack_demonstrations_and_five_answers_reproduce_most_held_out_scenarios() -> None:
    domain, train = read_demo_set(SNACKS / "train")
    _domain, held_out = read_demo_set(SNACKS / "heldout", domain)
    reference = compile_tree(read_tree(SNACKS / "reference" / "reference.xml"), domain.condition_names)
    learner = learn_online(domain, train[:3], safe=False)
    asked: list[tuple[bool, ...]] = []
    for number in range(5):
        question = next_question(learner, asked)
        assert question is not None
        asked.append(question.state)
        status, action = reference(question.state)
        learner.teach_step(question.state, action if status is Status.RUNNING else None, f"question {number + 1}")
    # issue 10's target: at least 80% of the held-out scenarios (the 3 demonstrations alone: 8 of 26)
    assert replay(learner.tree, domain, held_out).reproduced >= 0.8 * len(held_out)
    assert replay(learner.tree, domain, train[:3]).reproduced == 3
