"""The generality benches' smallest cases (bench/bench_ball_pairs.py, bench/bench_snacks_draws.py,
bench/bench_may_i_ceiling.py)
and the parts they are built from: task outcomes in the true model, and answers from a reference tree."""

from __future__ import annotations

import sys

from conftest import ROOT

sys.path.insert(0, str(ROOT / "bench"))

import bench_ball_pairs  # noqa: E402
import bench_may_i_ceiling  # noqa: E402
import bench_snacks_draws  # noqa: E402
from foreign import strips  # noqa: E402
from foreign.judge import judge  # noqa: E402
from foreign.teaching import demonstration  # noqa: E402
from oracle_answers import DONE, ReferenceTeacher, answer  # noqa: E402
from question_ceiling import idle_states, knowing_the_answers  # noqa: E402
from task_outcomes import from_every_state, tally  # noqa: E402

from teach.bt.nodes import Action, Condition, Fallback  # noqa: E402
from teach.bt.xml import read_tree  # noqa: E402
from teach.demos import read_demo_set  # noqa: E402
from teach.domain import load_domain  # noqa: E402
from teach.learn.inquiry import SituationQuestion  # noqa: E402
from teach.learn.learner import learn_online  # noqa: E402
from teach.learn.situations import tree_does  # noqa: E402
from teach.replay import count_reproduced  # noqa: E402

BALL = ROOT / "demos" / "ball"
SNACKS = ROOT / "demos" / "snacks"


def test_outcomes_in_the_true_ball_model():
    model = load_domain(BALL / "domain.toml")
    assert from_every_state(read_tree(BALL / "reference" / "table61.xml"), model)[0] == {"reached": 32}
    # place the ball unless it is placed: right in the 16 placed states and the 4 ready to place;
    # elsewhere the hand is empty or the bin out of reach
    careless = Fallback((Condition("BallPlaced"), Action("PlaceBall")))
    assert from_every_state(careless, model) == ({"reached": 20, "unsafe": 12},
                                                 {"PlaceBall without BallGrasped": 8, "PlaceBall without BinClose": 4})
    assert from_every_state(Condition("BallClose"), model)[0] == {"reached": 8, "false done": 8, "stuck": 16}
    # finding the ball is all it knows: done once the ball is seen, placed or not
    assert from_every_state(Fallback((Condition("BallFound"), Action("FindBall"))), model)[0] == \
        {"reached": 16, "false done": 16}
    # FindBall where the ball is already seen is unsafe (Table 6.1: pre !BallFound)
    assert from_every_state(Action("FindBall"), model) == ({"unsafe": 32}, {"FindBall without !BallFound": 32})


def test_may_i_questions_of_the_safe_learner_are_answered_as_a_teacher_does():
    domain, delta4 = read_demo_set(BALL / "delta4")
    teacher = ReferenceTeacher(read_tree(BALL / "reference" / "table61.xml"), domain)
    learner = learn_online(domain, delta4, safe=True)
    # "is the task done once the ball is in the bin, whatever else holds?": yes
    done = SituationQuestion((False, False, False, False, True), "must-goal", settles=(("BallFound", True),))
    assert answer(learner, done, teacher, "question 1").answer == "yes"
    assert learner.goal_holds((False, False, False, False, True))
    # "may I go to the bin without the ball in view?": Table 6.1 does, with the ball in hand
    state = (False, False, True, False, False)
    going = SituationQuestion(state, "must-precondition", action="ApproachBin",
                              settles=(("BallFound", True), ("BallClose", True)))
    assert answer(learner, going, teacher, "question 2").answer == "yes"
    assert learner.answer_in(state) == "ApproachBin"
    # "may I grasp the ball when it is out of reach?": no, Table 6.1 goes to it first
    grasping = SituationQuestion((True, False, False, False, False), "must-precondition", action="GraspBall",
                                 settles=(("BallClose", True),))
    assert answer(learner, grasping, teacher, "question 3").answer == "ApproachBall"
    assert (1, True) in learner.model["GraspBall"].confirmed


def test_a_situation_answer_is_taught_and_says_whether_the_tree_changed():
    domain, delta2 = read_demo_set(BALL / "delta2")
    teacher = ReferenceTeacher(read_tree(BALL / "reference" / "table61.xml"), domain)
    learner = learn_online(domain, delta2[:1])
    state = (False, False, True, False, False)  # the ball in hand, nothing else: go to the bin
    before = learner.answer_in(state)
    answered = answer(learner, SituationQuestion(state, "gap"), teacher, "question 1")
    assert answered.answer == teacher.does[state] == "ApproachBin" != DONE
    assert learner.answer_in(state) == "ApproachBin"
    assert answered.tree_changed == (before != "ApproachBin")


def test_ball_pairs_smallest_case_the_thesis_pair():
    ball = bench_ball_pairs.load()
    pair = tuple(d for d in ball.delta2 if d.name in ("d01", "d33"))
    runs = bench_ball_pairs.run_pair(ball, pair)  # type: ignore[arg-type]
    assert runs[0].shows_all and runs[0].questions == 0 and 1 < len(runs) <= 6  # at most 5 questions
    assert all(r.training_kept and sum(r.outcomes.values()) == 32 for r in runs)
    assert all(r.outcomes["unsafe"] == r.outcomes["false done"] == 0 for r in runs)  # the safe learner
    assert [len(r.answers) for r in runs] == list(range(len(runs)))
    assert runs[-1].reproduced > runs[0].reproduced  # the answers pay
    assert len(runs) == 6 or runs[-1].reproduced == 43  # fewer questions only when nothing is left to ask
    # the thesis's specialization reproduced 35/43 from this pair; the guessing learner does not do worse
    assert bench_ball_pairs.run_pair(ball, pair, budget=0, safe=False)[0].reproduced >= 35  # type: ignore[arg-type]


def test_snacks_smallest_draw_is_the_generator_s_own_behaviour():
    domain = load_domain(SNACKS / "domain.toml")
    world = bench_snacks_draws.HiddenStateWorld(domain, bench_snacks_draws.load_world(SNACKS / "world.toml", domain))
    data = bench_snacks_draws.draw(1, domain, world, bench_snacks_draws.generator())
    assert len(data.train) == 10 and len(data.held_out) == 40
    assert any(step.action == -1 for demo in data.train for step in demo.steps)  # events happen
    reference = read_tree(SNACKS / "reference" / "reference.xml")
    assert count_reproduced(reference, domain, data.train) == 10
    assert count_reproduced(reference, domain, data.held_out) == 40
    goalless = bench_snacks_draws.dataclasses.replace(domain, goal=())
    quiet = bench_snacks_draws.HiddenStateWorld(domain, world.spec, events_in_runs=False)
    rows = bench_snacks_draws.measure(goalless, ReferenceTeacher(reference, goalless), data, quiet, domain.goal)
    assert [(r.demonstrations, r.budget, r.total) for r in rows] == [(10, 0, 40), (10, 5, 40), (3, 0, 40), (3, 5, 40)]
    assert all(sum(r.outcomes.values()) == 64 for r in rows)
    # the reference behaviour reaches the goal from every start, whatever is on the tray
    starts = bench_snacks_draws.starts(domain)
    assert tally(reference, quiet, domain.goal, starts) == ({"reached": 64}, {})
    learner = learn_online(goalless, data.train)
    assert count_reproduced(learner.tree, goalless, data.train) == 10  # every training demonstration, strictly
    # no learner that never acts on a guess reproduces more of the held-out set than the safe
    # ceiling; ours reproduces exactly that much (27 of 40 on this draw), the guessing one more
    ceiling = bench_snacks_draws.safe_ceiling(data.train, data.held_out)
    assert count_reproduced(learner.tree, goalless, data.held_out) == round(ceiling * 40) == 27
    guessing = learn_online(goalless, data.train, safe=False)
    assert count_reproduced(guessing.tree, goalless, data.held_out) > 27
    assert bench_snacks_draws.safe_ceiling(data.train, data.train) == 1.0


def test_questions_chosen_knowing_their_answers_reach_what_the_chooser_does_not():
    # the worst pair of the ball bench (the chooser's 5 questions reproduced 29 of Δ5 when this
    # was written): the same budget chosen knowing the answers reproduces all 43
    ball = bench_ball_pairs.load()
    pair = [d for d in ball.delta2 if d.name in ("d03", "d05")]
    learner = learn_online(ball.domain, pair)
    before = count_reproduced(learner.tree, ball.domain, ball.delta5)
    best = knowing_the_answers(learner, ball.teacher, 5)
    assert count_reproduced(learner.tree, ball.domain, ball.delta5) == before  # the argument is left as it was
    assert len(best.situations) <= len(learner.situations) + 5
    assert count_reproduced(best.tree, ball.domain, ball.delta5) == 43
    assert idle_states(best, list(ball.teacher.does)) == 0


def test_may_i_questions_chosen_knowing_their_answers_in_a_random_strips_domain():
    """The "may I" ceiling's candidates are where the robot does nothing, each testing unsure literals
    only; five chosen knowing their answers take the robot to the goal from more starts."""
    task = strips.random_task(6, 5, 1)
    learner = learn_online(task.domain, [demonstration(task, start, f"d{i}")
                                         for i, start in enumerate(task.starts()[:2])])
    before = judge(task, learner.tree, task.starts()).share("reached")
    candidates = list(bench_may_i_ceiling.may_i_questions(learner, task))
    assert candidates and all(tree_does(learner, q.state) == "nothing" and q.settles for q in candidates)
    kept: list[str] = []
    best = bench_may_i_ceiling.knowing(learner, task, bench_may_i_ceiling.may_i_questions, kept)
    assert judge(task, learner.tree, task.starts()).share("reached") == before  # the argument is left as it was
    assert len(kept) == 5 and judge(task, best.tree, task.starts()).share("reached") > before
