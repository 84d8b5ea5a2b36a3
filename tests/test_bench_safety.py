"""The safety bench's parts (bench/foreign): grounding, the teacher, the evaluator, the baseline.

The evaluator is checked on hand-made trees whose outcome is known (an action run without its
true preconditions is unsafe, "done" before the goal is false done, ...), and the compiled
ticker it uses against BehaviorTree.CPP itself on the states the bench visits.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from btcpp import btcpp_tick

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "bench"))

import bench_safety  # noqa: E402
from foreign import ipc, strips  # noqa: E402
from foreign.judge import judge, run  # noqa: E402
from foreign.learners import BATCH  # noqa: E402
from foreign.model import Task  # noqa: E402
from foreign.questions import answer_question, ask, may  # noqa: E402
from foreign.sam import SamLearner  # noqa: E402
from foreign.teaching import ceiling, demonstration, safe_ceiling, split_starts  # noqa: E402

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Sequence, walk  # noqa: E402
from teach.bt.tick import compile_tree  # noqa: E402
from teach.demos import Demonstration  # noqa: E402
from teach.learn.inquiry import SituationQuestion, next_question  # noqa: E402
from teach.learn.learner import Learner  # noqa: E402
from teach.replay import count_reproduced  # noqa: E402


@pytest.fixture(scope="module")
def ferry() -> Task:
    return ipc.load("ferry")


def state_with(task: Task, *facts: str) -> int:
    return task.mask(task.domain.state(list(facts)))


START = ("at_ferry_p1", "empty_ferry", "at_c1_p1", "at_c2_p2", "at_c3_p3")


def test_grounding_keeps_the_pddl_model() -> None:
    blocks = ipc.load("blocksworld")
    assert (len(blocks.model.conditions), len(blocks.model.operators)) == (29, 40)
    pick = blocks.model.by_name["pick_up_a"]
    assert blocks.model.literals(pick.pre_true, pick.pre_false) == {("clear_a", True), ("ontable_a", True),
                                                                    ("handempty", True)}
    assert blocks.model.literals(pick.add, pick.delete) == {("holding_a", True), ("clear_a", False),
                                                            ("ontable_a", False), ("handempty", False)}
    assert blocks.domain.goal == () and not blocks.domain.has_model
    assert len(blocks.reachable) == 125  # the 4-block world's states, with or without a block in hand


def test_the_teacher_plans_optimally(ferry: Task) -> None:
    start = state_with(ferry, *START)
    demo = demonstration(ferry, start, "d")
    assert demo.reached_goal and len(demo.actions) == ferry.distance(start) == 9
    assert ferry.model.goal_holds(ferry.mask(demo.steps[-1].state))
    train, tests = split_starts(ferry, 0, 20, 100)
    assert not set(train) & set(tests) and len(tests) == 100


def test_an_action_without_its_preconditions_is_unsafe(ferry: Task) -> None:
    start = state_with(ferry, *START)
    board = compile_tree(Action("board_c2_p2"), ferry.domain.condition_names)  # the ferry is at p1
    assert run(ferry, board, start).outcome == "unsafe"
    # the same action where it may run: it runs, then (still ticked) it is unsafe with a full ferry
    there = state_with(ferry, "at_ferry_p2", "empty_ferry", "at_c1_p1", "at_c2_p2", "at_c3_p3")
    ended = run(ferry, board, there)
    assert (ended.outcome, ended.steps) == ("unsafe", 1)


def test_done_before_the_goal_is_false_done_and_failure_is_stuck(ferry: Task) -> None:
    name = ferry.domain.condition_names[0]
    always = Fallback((Condition(name), Inverter(Condition(name))))
    never = Sequence((Condition(name), Inverter(Condition(name))))
    start = state_with(ferry, *START)
    assert judge(ferry, always, [start]).counts["false done"] == 1
    assert judge(ferry, never, [start]).counts["stuck"] == 1
    goal = state_with(ferry, "at_ferry_p1", "empty_ferry", "at_c1_p2", "at_c2_p3", "at_c3_p1")
    assert run(ferry, compile_tree(always, ferry.domain.condition_names), goal).outcome == "reached"


def test_sailing_back_and_forth_is_a_loop(ferry: Task) -> None:
    back_and_forth = Fallback((Sequence((Condition("at_ferry_p1"), Action("sail_p1_p2"))), Action("sail_p2_p1")))
    assert judge(ferry, back_and_forth, [state_with(ferry, *START)]).counts["loop"] == 1


def test_sam_reproduces_what_it_saw_and_never_acts_unsafely(ferry: Task) -> None:
    train, tests = split_starts(ferry, 1, 5, 60)
    demos = [demonstration(ferry, s, f"d{i}") for i, s in enumerate(train)]
    sam = SamLearner(ferry.domain)
    for demo in demos:
        sam.update(demo)
    assert count_reproduced(sam.tree, ferry.domain, demos) == len(demos)
    assert judge(ferry, sam.tree, train).counts["reached"] == len(train)
    outcomes = judge(ferry, sam.tree, tests)
    assert outcomes.counts["unsafe"] == outcomes.counts["false done"] == 0
    assert 0 < ceiling(ferry, demos, tests) <= 1


@pytest.mark.parametrize("name", ["ferry", "strips-8x6"])
def test_btcpp_picks_the_action_the_compiled_ticker_picks(name: str) -> None:
    """On the states the bench runs through (held-out starts and every state of their runs),
    for each learner's tree."""
    task = ipc.load(name) if name in ipc.DOMAINS else strips.random_task(8, 6, 1)
    train, tests = split_starts(task, 0, 2, 30)
    demos = [demonstration(task, s, f"d{i}") for i, s in enumerate(train)]
    trees = [tree for learn in BATCH.values() if (tree := learn(task.domain, demos)) is not None]
    assert len(trees) >= 3  # the learner, SAM and at least one of the thesis's approaches
    for tree in trees:
        compiled = compile_tree(tree, task.domain.condition_names)
        states = set()
        for start in tests:
            state = start
            for _ in range(20):
                states.add(state)
                _status, action = compiled(task.state(state))
                operator = task.model.by_name.get(action or "")
                if operator is None or not operator.applicable(state):
                    break
                state = operator.apply(state)
        ordered = [task.state(s) for s in sorted(states)]
        assert btcpp_tick(tree, task.domain, ordered) == [compiled(s) for s in ordered]


def test_answers_come_from_the_true_model(ferry: Task) -> None:
    learner = Learner(ferry.domain)
    learner.update(demonstration(ferry, state_with(ferry, *START), "d"))
    impossible = ferry.domain.state(["at_ferry_p1", "at_ferry_p2", "empty_ferry"])
    said = answer_question(learner, SituationQuestion(impossible, "gap"), ferry, "q1")
    assert said.said.startswith("impossible") and not said.changed
    there = ferry.domain.state(["at_ferry_p2", "empty_ferry", "at_c1_p1", "at_c2_p2", "at_c3_p3"])
    said = answer_question(learner, SituationQuestion(there, "gap"), ferry, "q2")
    assert said.said == ferry.best(ferry.mask(there)).name  # type: ignore[union-attr]
    assert learner.answer_in(there) == said.said
    answers = ask(learner, ferry, 3)
    assert sum(a.charged for a in answers) <= 3


def test_may_i_answers_read_the_true_preconditions_and_goal(ferry: Task) -> None:
    there = ferry.mask(ferry.domain.state(["at_ferry_p1", "empty_ferry", "at_c1_p1", "at_c2_p2", "at_c3_p3"]))
    assert may(ferry, "board_c1_p1", there)
    assert not may(ferry, "board_c2_p2", there)  # the ferry is not where that car is
    assert not may(ferry, None, there) and may(ferry, None, ferry.model.goal_true)
    learner = Learner(ferry.domain)
    learner.update(demonstration(ferry, state_with(ferry, *START), "d"))
    for number in range(1, 6):
        question = next_question(learner)
        if question is None:
            break
        said = answer_question(learner, question, ferry, f"q{number}")
        assert said.said in ("yes", "no", "done", "impossible") or said.said in ferry.domain.action_names


def test_random_strips_preconditions_are_positive_and_negative_alike() -> None:
    operators = [o for seed in range(20) for o in strips.random_task(8, 6, seed).model.operators]
    positive = sum(o.pre_true.bit_count() for o in operators)
    negative = sum(o.pre_false.bit_count() for o in operators)
    assert 0.35 < negative / (positive + negative) < 0.65
    assert sum(o.delete != 0 for o in operators) > len(operators) / 4


@pytest.mark.parametrize("k", [2, 5, 20])
def test_no_safe_learner_passes_the_safe_ceiling_without_questions(k: int) -> None:
    """The safe ceiling is what acting only on what the demonstrations prove can reach: the safe
    learner and SAM reach no more (and, in this formless domain, no less), the information
    ceiling counts more."""
    task = strips.random_task(8, 6, 0)
    train, tests = split_starts(task, 0, k, 100)
    demos = [demonstration(task, s, f"d{i}") for i, s in enumerate(train)]
    safe = safe_ceiling(task, demos, tests)
    for learn in (BATCH["learner"], BATCH["sam"]):
        outcomes = judge(task, learn(task.domain, demos), tests)
        assert outcomes.share("unsafe") == 0 and outcomes.share("false done") == 0
        assert outcomes.share("reached") <= safe
        assert outcomes.share("reached") >= safe - 0.1
    assert safe <= ceiling(task, demos, tests)


def taught(name: str, seed: int, k: int) -> tuple[Task, list[Demonstration], list[int], Learner]:
    """The planning task, ``k`` demonstrations from its seed's training starts, its held-out starts
    and the learner that learned the demonstrations one by one."""
    task = ipc.load(name)
    train, tests = split_starts(task, seed, k, 100)
    demos = [demonstration(task, start, f"d{i}") for i, start in enumerate(train)]
    learner = Learner(task.domain)
    for demo in demos:
        learner.update(demo)
    return task, demos, tests, learner


def test_visitall_is_reached_goal_literal_by_goal_literal() -> None:
    """Visitall's goal (every cell visited) regresses past the rules' budget; its literals are
    never undone, so they are worked towards one at a time, and the robot gets there from every
    held-out start (before: 72% after 5 demonstrations, stuck elsewhere), never unsafe."""
    task, _demos, tests, learner = taught("visitall", 0, 5)
    assert judge(task, learner.tree, tests).share("reached") == 1.0
    pursued = [why for why in map(learner.why, (node.uid for node in walk(learner.tree))) if why.kind == "pursued"]
    assert pursued and "does not hold yet: the goal needs it and no action undoes it" in pursued[0].text


def test_teachers_steps_outside_complete_rules_do_not_send_the_robot_round_in_circles() -> None:
    """Logistics, 2 demonstrations (one never loads the plane), 5 answers: generalised, a shown
    flight and an answered one flew the plane back and forth from 16 of 100 starts."""
    task, demos, tests, learner = taught("logistics", 1, 2)
    ask(learner, task, 5)
    outcomes = judge(task, learner.tree, tests)
    assert outcomes.share("loop") == 0 and outcomes.share("unsafe") == 0
    assert outcomes.share("reached") >= safe_ceiling(task, demos, tests)  # the answers cost no reach


def test_where_no_rule_fits_the_robot_stops_rather_than_goes_round_in_circles() -> None:
    """Logistics, 5 demonstrations: at 30,000 nodes the goal's regression was cut short, and the plan
    that followed the rules achieved goal literals one at a time: it unloaded a parcel from a truck
    for one goal literal and loaded it back for another, for ever, from 5 of 100 held-out starts.
    Where no rule fits the robot now stops and asks (without the plan at 30,000 nodes: 88 reached,
    12 stuck); the rules' budget of 40,000 nodes holds the whole regression here."""
    task, _demos, tests, learner = taught("logistics", 1, 5)
    outcomes = judge(task, learner.tree, tests)
    assert outcomes.share("loop") == 0 and outcomes.share("unsafe") == 0
    assert outcomes.share("reached") >= 0.95


def test_questions_with_forms_are_about_states_that_can_happen() -> None:
    """With forms only states the learned effects lead to are asked about (before: 50 of 51
    answers in blocksworld were "impossible"), and after 2 demonstrations at most 1 answer in 5
    is what the robot would have done anyway."""
    answers = []
    for name in ("blocksworld", "miconic", "logistics"):
        task, _demos, _tests, learner = taught(name, 0, 2)
        answers += ask(learner, task, 5)
    assert answers and not [a for a in answers if a.said == "impossible"]
    assert sum(not a.changed for a in answers) <= len(answers) / 5, answers


def test_the_bench_prints_its_tables(capsys: pytest.CaptureFixture[str]) -> None:
    bench_safety.main(["--quick", "--domains", "miconic", "--held-out", "10", "--rounds", "4"])
    out = capsys.readouterr().out
    for row in bench_safety.ROWS:
        assert f"miconic        10     2 {row}" in out
    assert "session loop" in out and "miconic      sam" in out


def test_questions_where_the_robot_does_nothing_come_first() -> None:
    """After 20 demonstrations a "may I still …?" asked where the robot acts was mostly answered
    with what it does there (changing nothing: 47% of the answers); where it does nothing any
    answer is new. strips-8x6, seed 2: its second to fourth questions were asked where it acts."""
    task = strips.random_task(8, 6, 2)
    train, _tests = split_starts(task, 2, 20, 100)
    learner = Learner(task.domain)
    for number, start in enumerate(train):
        learner.update(demonstration(task, start, f"d{number}"))
    asked: list[tuple[bool, ...]] = []
    for number in range(4):
        question = next_question(learner, asked)
        assert question is not None and question.tree_does == "nothing"
        asked.append(question.state)
        answer_question(learner, question, task, f"question {number + 1}")
