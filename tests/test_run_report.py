"""Runs that say what happened (issue 21, item 4): each action the tree tried and that failed,
with what it lacked, and the action a Ctrl-C stopped, in both languages."""

from __future__ import annotations

import pytest

from teach.session.machine import SessionManager
from teach.session.settings import Settings
from teach.world.symbolic import SymbolicWorld

ALL = {"en": "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin",
       "de": "Ball finden, zum Ball gehen, Ball greifen, zum Eimer gehen, Ball in den Eimer legen"}


def taught(ball, tmp_path, lang, safe=True):
    settings = Settings("runs", lang=lang, questions=0, base=tmp_path, world="symbolic", record=False, safe=safe)
    manager = SessionManager(settings, ball, SymbolicWorld(ball))
    manager.handle(ALL[lang])
    manager.handle("done")
    return manager


@pytest.mark.parametrize(("lang", "tried"), [
    ("en", "I tried to put the ball in the bin, but it did not work: first this must be true: the ball is in my "
           "hand."),
    ("de", "Ich habe „Ball in den Eimer legen“ versucht, aber es ging nicht: dafür muss erst gelten: ich habe den "
           "Ball in der Hand."),
])
def test_an_action_that_failed_in_a_run_is_named_with_what_it_lacked(ball, tmp_path, lang, tried):
    # the guessing learner (--guess) tries actions where their preconditions do not hold: the safe one never does
    manager = taught(ball, tmp_path, lang, safe=False)
    manager.handle("start BinClose")  # the one demonstration went to the bin carrying the ball
    said = [r.text for r in manager.handle("run")]
    assert tried in said
    assert not any("nothing I know fits" in text or "hier passt nichts" in text for text in said)


def test_a_ctrl_c_names_the_action_it_stopped(ball, tmp_path):
    manager = taught(ball, tmp_path, "en")
    manager.handle("reset")
    polls = iter([False, False, True])  # Ctrl-C once the robot has begun its second action
    said = [r.text for r in manager.handle("run", interrupt=lambda: next(polls, True))]
    assert "→ go to the ball" in said
    assert any(text.startswith("Stopped (the last thing I began was “go to the ball”)") for text in said)


def test_in_mujoco_a_skill_that_fails_is_named_too(ball, tmp_path):
    from teach.bt.nodes import Action
    from teach.world.mujoco_world import MujocoWorld

    settings = Settings("runs", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, ball, MujocoWorld(ball, seed=0))
    manager.definitions.planned = Action("GraspBall")  # a tree that grasps where nothing can be grasped
    said = [r.text for r in manager.handle("run")]
    assert "I tried to grasp the ball, but it did not work: first this must be true: I can see the ball and the ball " \
           "is within reach." in said
    manager.close()


def test_in_mujoco_a_yes_to_an_offered_way_keeps_its_promise_where_the_way_changes(ball, tmp_path):
    """With the bin near, "put the ball in the bin" offered "find the ball, go to the ball, grasp the
    ball"; going to the ball takes the bin out of reach (the domain's model does not say so), and
    after the yes the step was refused one step short, with a second offer. The way is planned
    again from there."""
    from teach.world.mujoco_world import MujocoWorld

    settings = Settings("runs", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, ball, MujocoWorld(ball, seed=0))
    manager.handle("start bin close")
    assert "Say 'yes' and I do that" in "\n".join(r.text for r in manager.handle("put the ball in the bin"))
    said = [r.text for r in manager.handle("yes")]
    assert "Now the bin is out of reach: first go to the bin, then put the ball in the bin." in said
    assert manager.open is not None and [s.action for s in manager.open.steps] == [1, 2, 3, 4, 5]
    assert ball.goal_holds(manager.world.state())
    manager.close()
