"""The one symbolic executor: effects, runs to the goal, loops and failures."""

from __future__ import annotations

from conftest import colledanchise_tree

from teach.bt.nodes import Action, Condition, Fallback, Sequence
from teach.symbolic import RunEnd, apply_action, assign, missing_preconditions, run_to_goal, steps_towards


def test_an_action_makes_its_ramifications_true(ball):
    after = apply_action(ball, ball.state([]), "FindBall")
    assert after == ball.state(["BallFound"])
    assert assign((False, True), [(0, True), (1, False)]) == (True, False)
    assert [str(lit) for lit in missing_preconditions(ball, ball.state([]), "GraspBall")]


def test_the_reference_tree_reaches_the_goal_from_nothing(ball):
    run = run_to_goal(ball, colledanchise_tree(), ball.state([]), max_steps=50)
    assert run.end is RunEnd.SUCCESS
    assert run.actions == ["FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall"]


def test_an_action_that_changes_nothing_is_a_loop_and_a_missing_action_a_failure(ball):
    # FindBall once the ball is found changes nothing: the run comes back to its state
    looping = Fallback((Condition("BallPlaced"), Action("FindBall")))
    run = run_to_goal(ball, looping, ball.state(["BallFound"]), max_steps=50)
    assert run.end is RunEnd.LOOP and run.actions == ["FindBall"]
    failing = Sequence((Condition("BallPlaced"),))
    assert run_to_goal(ball, failing, ball.state([]), max_steps=50).end is RunEnd.FAILURE
    assert run_to_goal(ball, looping, ball.state([]), max_steps=1).end is RunEnd.LIMIT


def test_the_way_to_a_refused_step_is_the_shortest_the_model_knows(ball):
    found = ball.state(["BallFound"])
    assert steps_towards(ball, found, "GraspBall", 3) == ["ApproachBall"]
    assert steps_towards(ball, found, "PlaceBall", 3) == ["ApproachBall", "GraspBall", "ApproachBin"]
    assert steps_towards(ball, found, "PlaceBall", 2) is None  # longer than asked for
    # only the world's events make the ball unseen again: no step of the robot's leads there
    assert steps_towards(ball, found, "FindBall", 3) is None
