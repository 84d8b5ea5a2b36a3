"""Model repair on the thesis's study participants (§6.1, Appendix A.2) and on random models:
real PA-BT, real answers parsed from plain strings."""

from __future__ import annotations

import random

import pytest
from conftest import BALL_DOMAIN, ROOT, journal_data

from teach.dialogue.model_repair import KINDS, ModelOracle, ModelQuestion, ModelRepair, RepairReport, repair
from teach.dialogue.phrases import UnknownPhrase
from teach.dialogue.questions import QuestionBudget
from teach.dialogue.script import read_script
from teach.domain import ActionDef, ConditionDef, Domain, Literal, load_domain
from teach.learn.model_gaps import plan_model

STUDY = ROOT / "dialogues" / "study"
RESCUED = (1, 2, 3, 6)


def participant(number: int) -> Domain:
    return load_domain(STUDY / f"participant{number}.toml")


@pytest.fixture(scope="module")
def true_model() -> Domain:
    return load_domain(BALL_DOMAIN)


@pytest.fixture(scope="module")
def reports(true_model: Domain) -> dict[tuple[int, str], RepairReport]:
    return {(n, lang): repair(participant(n), QuestionBudget(5), ModelOracle(true_model), lang)
            for n in range(1, 9) for lang in ("en", "de")}


def test_without_questions_exactly_participants_4_5_7_8_are_usable(true_model):
    from teach.evaluate import participant_result

    outcomes = {n: plan_model(participant(n), true_model=true_model) for n in range(1, 9)}
    # the thesis's result (§6.1), and the same verdict as the evaluation's own check
    assert sorted(n for n, o in outcomes.items() if o.usable) == [4, 5, 7, 8]
    for n, outcome in outcomes.items():
        assert outcome.usable == participant_result(STUDY / f"participant{n}.toml", n).usable
        assert outcome.reason
        assert (outcome.tree is not None) == outcome.usable
    # the four usable tables also work under Table 6.1's model
    assert all(outcomes[n].true_usable for n in (4, 5, 7, 8))


def test_usable_participants_are_asked_nothing(reports):
    for n in (4, 5, 7, 8):
        report = reports[(n, "en")]
        assert report.questions == 0 and report.before.usable and report.after.usable


def test_five_oracle_questions_rescue_all_four_and_three_under_the_true_model(reports):
    for lang in ("en", "de"):
        after = {n: reports[(n, lang)].after for n in RESCUED}
        assert all(not reports[(n, lang)].before.usable for n in RESCUED)
        # measured: every unusable table becomes usable in its own model ...
        assert sorted(n for n, o in after.items() if o.usable) == [1, 2, 3, 6]
        # ... and the trees of 1, 2 and 6 also reach the goal under Table 6.1; participant 3's
        # tree grasps the ball without finding or approaching it (its table has no
        # preconditions for Grasp Ball), which the true model does not allow
        assert sorted(n for n, o in after.items() if o.true_usable) == [1, 2, 6]
        assert {n: reports[(n, lang)].questions for n in RESCUED} == {1: 5, 2: 4, 3: 1, 6: 1}


def test_no_run_spends_more_than_five_questions(true_model):
    for n in range(1, 9):
        budget = QuestionBudget(5)
        report = repair(participant(n), budget, ModelOracle(true_model))
        assert report.questions <= 5
        assert budget.used == report.questions


def test_a_smaller_budget_stops_the_questions(true_model):
    budget = QuestionBudget(2)
    report = repair(participant(1), budget, ModelOracle(true_model))
    assert report.questions == 2 and budget.left == 0
    assert not report.after.usable
    session = ModelRepair(report.model, budget)
    assert session.next_question() is None and session.ask() is None


def test_question_texts_are_non_empty_in_english_and_german(reports, true_model):
    asked = [step.question for report in reports.values() for step in report.steps]
    assert asked and all(text.strip() for text in asked)
    assert any("Was " in text for text in asked) and any("What " in text for text in asked)
    domain = participant(1)
    cond = Literal("BallFound")
    for question in (ModelQuestion("timing", "FindBall", cond), ModelQuestion("effects", "FindBall"),
                     ModelQuestion("achiever", literal=cond), ModelQuestion("order", "FindBall", other="ApproachBall"),
                     ModelQuestion("never", "ApproachBall", cond)):
        for lang in ("en", "de"):
            text = question.text(domain, lang)
            assert text.strip() and "BallFound" not in text  # labels, not condition names
    assert {q.kind for q in (ModelQuestion(k) for k in KINDS)} == set(KINDS)


def test_the_first_question_for_participant_1_asks_about_timing_in_plain_words():
    session = ModelRepair(participant(1), QuestionBudget(5))
    question = session.ask()
    assert question == ModelQuestion("timing", "FindBall", Literal("BallFound"))
    assert session.text(question) == ("When I “find the ball”: must “I can see the ball” already hold before "
                                      "I start, or does it only hold afterwards? (before / after / both / neither)")
    assert session.text(question, "de").startswith("Bei „Ball finden“: muss „ich sehe den Ball“ schon vorher")


def test_nonsense_answers_give_one_line_with_a_suggestion_and_change_nothing():
    session = ModelRepair(participant(1), QuestionBudget(5))
    question = session.ask()
    model = session.model
    with pytest.raises(UnknownPhrase) as caught:
        session.apply(question, "purple elephant")
    message = caught.value.message
    assert "\n" not in message and "purple elephant" in message and "Did you mean" in message
    assert session.model is model
    with pytest.raises(UnknownPhrase):
        session.apply(ModelQuestion("effects", "FindBall"), "the moon is made of cheese")
    with pytest.raises(UnknownPhrase) as german:
        ModelRepair(participant(1), QuestionBudget(5), lang="de").apply(question, "vielleicht")
    assert "Meintest du" in german.value.message
    assert session.model is model


@pytest.mark.parametrize("answer", ["after", "Afterwards.", "nachher", "danach", "it makes it true"])
def test_timing_answers_in_either_language(answer):
    session = ModelRepair(participant(1), QuestionBudget(5))
    session.apply(ModelQuestion("timing", "FindBall", Literal("BallFound")), answer)
    find = session.model.action("FindBall")
    assert Literal("BallFound") not in find.pre and Literal("BallFound") in find.ram


def test_effects_answers_name_conditions_true_or_untrue():
    session = ModelRepair(participant(3), QuestionBudget(5), lang="de")
    change = session.apply(ModelQuestion("effects", "PlaceBall"),
                           "der Ball ist im Eimer und ich habe den Ball nicht in der Hand")
    assert session.model.action("PlaceBall").ram == (Literal("BallGrasped", False), Literal("BallPlaced"))
    assert change.startswith("Also gilt nach „Ball in den Eimer legen“")
    session.apply(ModelQuestion("effects", "ApproachBall"), "nothing")
    assert session.model.action("ApproachBall").ram == ()
    with pytest.raises(UnknownPhrase):  # both true and untrue at once
        session.apply(ModelQuestion("effects", "ApproachBall"),
                      "the ball is in my hand, the ball is not in my hand")


def test_a_condition_nothing_makes_true_leads_to_asking_whether_it_is_needed():
    # Go needs B, nothing makes B true: ask for an action, then whether Go really needs B
    domain = Domain("tiny", (ConditionDef("A", "the door is open", "die Tür ist offen", "the door is shut"),
                             ConditionDef("B", "the key is in hand", "der Schlüssel ist da", "the key is missing")),
                    (ActionDef(1, "Go", ("open the door",), ("Tür öffnen",), (Literal("B"),), (Literal("A"),)),),
                    (Literal("A"),))
    session = ModelRepair(domain, QuestionBudget(5))
    first = session.ask()
    assert first == ModelQuestion("achiever", literal=Literal("B"))
    assert session.apply(first, "nothing") == "So nothing makes “the key is in hand” true."
    second = session.ask()
    assert second == ModelQuestion("never", "Go", Literal("B"))
    assert session.text(second) == "Can I “open the door” while “the key is missing”? (yes / no)"
    assert session.apply(second, "ja") == "So “open the door” does not need “the key is in hand”."
    assert session.plan().usable and session.ask() is None and session.budget.used == 2


def test_order_answers_break_a_waiting_cycle_and_either_breaks_both_sides():
    session = ModelRepair(participant(1), QuestionBudget(5))
    for question, answer in ((ModelQuestion("timing", "FindBall", Literal("BallFound")), "after"),
                             (ModelQuestion("timing", "ApproachBall", Literal("BallClose")), "after")):
        session.apply(question, answer)
    order = ModelQuestion("order", "FindBall", other="ApproachBall")
    with pytest.raises(UnknownPhrase):
        session.apply(order, "grasp the ball")  # not one of the two
    either = ModelRepair(session.model, QuestionBudget(0))
    either.apply(order, "egal")
    assert Literal("BallClose") not in either.model.action("FindBall").pre
    assert Literal("BallFound") not in either.model.action("ApproachBall").pre
    session.apply(order, "find the ball")
    assert Literal("BallClose") not in session.model.action("FindBall").pre
    assert Literal("BallFound") in session.model.action("ApproachBall").pre


def test_same_questions_twice(true_model):
    def run() -> list[tuple[str, str, str]]:
        return [(s.question, s.answer, s.change) for n in RESCUED
                for s in repair(participant(n), QuestionBudget(5), ModelOracle(true_model), "de").steps]

    assert run() == run()


def test_study_dialogues_ask_what_repair_asks(true_model, tmp_path, capsys):
    """Each participantN.dialogue (settings, ``model FILE``, ``plan``, a run) replayed with the
    true model as oracle asks exactly the questions ``repair`` asks, in order."""
    from teach.cli import main

    for n in range(1, 9):
        path = STUDY / f"participant{n}.dialogue"
        script = read_script(path)
        lang = str(script.settings.get("lang", "en"))
        lines = [line for _, line in script.lines]
        assert script.settings["questions"] == 5 and lines[:2] == [f"model dialogues/study/participant{n}.toml", "plan"]
        base = tmp_path / str(n)
        assert main(["replay", str(path), "--base", str(base), "--no-record", "--oracle-model",
                     str(ROOT / "demos" / "ball" / "domain.toml")]) == 0
        capsys.readouterr()
        journal = journal_data(base / "recordings" / f"participant{n}.journal.json")
        answered = [e["answer"] for e in journal["events"] if e["kind"] == "model_answer"]
        report = repair(load_domain(ROOT / lines[0].split()[1]), QuestionBudget(5), ModelOracle(true_model), lang)
        assert answered == [step.answer for step in report.steps]


def _random_case(rng: random.Random) -> tuple[Domain, Domain]:
    """A plannable true model (a chain of conditions, each made true by one action that needs
    some earlier ones) and a teacher's garbled copy of it."""
    size = rng.randint(3, 6)
    conditions = tuple(ConditionDef(f"C{i}", f"c{i} holds", f"c{i} gilt", f"c{i} fails") for i in range(size))
    true_actions, told = [], []
    for i in range(size):
        pre = tuple(Literal(f"C{j}") for j in sorted(rng.sample(range(i), min(i, rng.randint(0, 2)))))
        ram = (Literal(f"C{i}"),)
        true_actions.append(ActionDef(i + 1, f"Do{i}", (f"do thing {i}",), (f"Ding {i} tun",), pre, ram))
        garble = rng.choice(("keep", "keep", "both", "no_effect", "extra_pre"))
        if garble == "both":
            pre = pre + ram
        elif garble == "no_effect":
            ram = ()
        elif garble == "extra_pre" and i + 1 < size:
            pre = pre + (Literal(f"C{rng.randint(i + 1, size - 1)}"),)
        told.append(ActionDef(i + 1, f"Do{i}", (f"do thing {i}",), (f"Ding {i} tun",), pre, ram))
    goal = (Literal(f"C{size - 1}"),)
    return (Domain("random", conditions, tuple(true_actions), goal),
            Domain("random-told", conditions, tuple(told), goal))


def test_random_models_never_break_the_budget_and_are_often_rescued():
    rescued = unusable = 0
    for seed in range(60):
        true, told = _random_case(random.Random(seed))
        assert plan_model(true).usable
        budget = QuestionBudget(5)
        report = repair(told, budget, ModelOracle(true), "en" if seed % 2 else "de")
        assert report.questions == budget.used <= 5
        assert all(step.question.strip() and step.change.strip() for step in report.steps)
        if not report.before.usable:
            unusable += 1
            rescued += report.after.usable
    assert unusable >= 20
    assert rescued >= unusable * 3 // 4


def test_a_confirmed_impossible_precondition_ends_the_questions():
    domain = Domain("tiny", (ConditionDef("A", "the door is open"), ConditionDef("B", "the key is in hand")),
                    (ActionDef(1, "Go", ("open the door",), (), (Literal("B"),), (Literal("A"),)),), (Literal("A"),))
    session = ModelRepair(domain, QuestionBudget(5))
    session.apply(session.ask(), "none")
    assert session.apply(session.ask(), "no").endswith("the task cannot be done.")
    assert session.ask() is None and session.budget.used == 2 and not session.plan().usable


def test_effects_that_undo_each_other_are_asked_about_action_by_action():
    # each action's effect undoes the other's, so PA-BT loops although every condition has a cause
    conditions = (ConditionDef("X", "x holds", "x gilt"), ConditionDef("Y", "y holds", "y gilt"))
    told = Domain("undo", conditions, (ActionDef(1, "MakeX", ("make x",), (), (), (Literal("X"), Literal("Y", False))),
                                       ActionDef(2, "MakeY", ("make y",), (), (), (Literal("Y"), Literal("X", False)))),
                  (Literal("X"), Literal("Y")))
    true = Domain("undo", conditions, (ActionDef(1, "MakeX", ("make x",), (), (), (Literal("X"),)),
                                       ActionDef(2, "MakeY", ("make y",), (), (), (Literal("Y"),))), told.goal)
    report = repair(told, QuestionBudget(5), ModelOracle(true))
    assert not report.before.usable and report.after.usable and report.after.true_usable
    assert [(s.question, s.answer) for s in report.steps] == [
        ("What is different after I “make x”? (what is true then, or “nothing”)", "x holds")]
