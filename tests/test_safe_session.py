"""A session with the safe learner (``--safe``): its questions ask whether it may still act (or is
done) where something it always saw does not hold; a yes answers them, "that cannot happen"
costs nothing and survives a resume."""

from __future__ import annotations

from teach.session.machine import SessionManager
from teach.session.replies import ReplyKind
from teach.session.settings import Settings, WorldKind
from teach.symbolic import possible_actions
from teach.world.symbolic import SymbolicWorld

SEQUENCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"


def safe_session(ball, tmp_path, questions=5):
    settings = Settings("t", questions=questions, world=WorldKind.SYMBOLIC, base=tmp_path, record=False, safe=True)
    return SessionManager(settings, ball, SymbolicWorld(ball))


def two_demonstrations(session):
    session.handle(SEQUENCE)
    session.handle("done")
    session.handle("start BinClose")
    session.handle("find the ball, go to the ball, grasp the ball, put the ball in the bin")
    return session.handle("done")


def skip_all(session):
    while session.pending is not None:
        session.handle("skip")


def stopped_with_the_bin_close(session):
    """One demonstration, its questions skipped, then a run where the bin is close by: it stops
    ("may I still find the ball?"). The run's replies."""
    session.handle(SEQUENCE)
    session.handle("done")
    skip_all(session)
    session.handle("start BinClose")
    return session.handle("run")


def shown_once_in_mujoco(ball, tmp_path, seed):
    """A safe session in real MuJoCo that was shown the whole task once, its questions skipped."""
    from teach.world.mujoco_world import MujocoWorld

    settings = Settings("t", questions=5, world=WorldKind.MUJOCO, base=tmp_path, record=False, safe=True, seed=seed)
    session = SessionManager(settings, ball, MujocoWorld(ball, seed))
    session.handle(SEQUENCE)
    session.handle("done")
    skip_all(session)
    return session


def resumed(ball, tmp_path):
    return SessionManager.resume(Settings("t", questions=5, world=WorldKind.SYMBOLIC, base=tmp_path, record=False,
                                          safe=True), ball, SymbolicWorld(ball))


def question_text(replies):
    return next(r.text for r in replies if r.kind is ReplyKind.QUESTION)


def test_a_declared_goal_is_the_goal_and_never_asked_about(ball, tmp_path):
    session = safe_session(ball, tmp_path)
    text = question_text(two_demonstrations(session))
    assert text.startswith("So far, every time I did") and "may I still do it?" in text
    assert session.learning.learner.goal.required() == [(4, True)]  # only the ball in the bin, as the domain says
    replies = session.handle("yes")
    assert any(r.text.startswith("Thank you") for r in replies)


def test_an_answer_says_what_it_changed(ball, tmp_path):
    """"Thank you. I changed what I do in some situations." said nothing about which: a yes says
    what it now allows (the conditions the question named, as they are there), another action
    that the robot does it there now."""
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    question = session.pending
    assert question is not None and question.action is not None
    replies = session.handle("yes")
    action = ball.action(question.action).label()
    there = " and ".join(ball.condition(name).label("en", not value) for name, value in question.settles)
    assert replies[0].text == f"Thank you. Now I may also {action} when {there}."
    question = session.pending
    assert question is not None and question.action is not None
    other = ball.action(next(name for name in possible_actions(ball, question.state) if name != question.action))
    replies = session.handle(other.label())
    assert replies[0].text == f"Thank you. Now I {other.label()} there."


def test_a_no_with_words_not_understood_is_taken_as_a_no(ball, tmp_path):
    """"no, the ball must be in my hand" was "I don't know …" and nothing else: the no is clear,
    so it is taken, and what to do instead is asked; a hedged answer reads ("I think you should
    find the ball first")."""
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    asked = session.pending
    replies = session.handle("no, the ball must be in my hand")
    assert [r.text for r in replies] == ["I take that as a no (I don't know “the ball must be in my hand”).",
                                         "Then what should I do there instead?"]
    assert session.pending is asked
    assert asked is not None
    other = ball.action(next(name for name in possible_actions(ball, asked.state) if name != asked.action))
    replies = session.handle(f"I think you should {other.label()} first")
    assert replies[0].text == f"Thank you. Now I {other.label()} there." and session.pending is not asked


def test_why_alone_says_what_to_ask(ball, tmp_path):
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    session.handle("skip")
    replies = session.handle("why")
    assert replies[0].text == "Why what? Name a step or a condition of the tree, e.g. 'why find the ball'."


def test_that_was_wrong_at_the_next_question_takes_back_the_answer_before_it(ball, tmp_path):
    """A wrong "yes", then the next question at once: "that was wrong" was "Nothing to undo while I
    wait for your answer". It takes back that answer; the open question is put aside, paid for,
    and asked again at no cost."""
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    tree = session.learning.learner.tree
    session.handle("yes")
    aside = session.pending
    assert aside is not None and session.learning.learner.tree != tree
    left = session.budget.left
    replies = session.handle("that was wrong")
    assert replies[0].text == "I put my question aside (if I ask it again, it costs nothing)."
    assert replies[1].text.startswith("Undone: your answer to")
    assert session.pending is None and session.learning.learner.tree == tree and session.budget.left == left
    session.handle("redo")
    session.handle("ask")
    assert session.pending is not None and session.pending.state == aside.state and session.budget.left == left
    session.handle("quit")
    assert resumed(ball, tmp_path).budget.left == left


def test_that_cannot_happen_costs_nothing_and_is_kept_on_resume(ball, tmp_path):
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    session.handle("yes")
    left = session.budget.left
    pending = session.pending
    assert pending is not None
    replies = session.handle("that cannot happen")
    assert "cost no question" in replies[0].text and pending.state in session.learning.asked
    # refunded, and the next question follows at once (it waited for 'ask'), paid for as usual
    assert [r.kind for r in replies[1:]] == [ReplyKind.QUESTION] and session.pending not in (None, pending)
    assert session.budget.left == left
    session.handle("quit")
    back = resumed(ball, tmp_path)
    assert back.budget.left == left
    assert back.learning.learner.state_mask(pending.state) in back.learning.learner.impossible


def test_no_asks_what_to_do_instead_and_keeps_the_question_open(ball, tmp_path):
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    replies = session.handle("no")
    assert replies[0].kind is ReplyKind.QUESTION and "instead" in replies[0].text
    assert session.pending is not None


def test_a_run_that_gets_stuck_asks_about_what_it_was_unsure_of_there(ball, tmp_path):
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    session.handle("skip")  # the first question (where the robot holds the ball and sees nothing else) stays unasked
    session.handle("start BallGrasped BinClose")
    replies = session.handle("run")
    assert any(r.text.startswith("I got stuck") for r in replies)
    text = question_text(replies)
    assert text.startswith("So far, every time I did “") and "may I still do it?" in text
    asked = text.split("“")[1].split("”")[0]
    replies = session.handle("yes")
    said = [r.text for r in replies]
    assert any(text.startswith("Thank you") for text in said)
    assert f"✓ {asked}" in said  # asked where it stopped: the yes is the next step, and the robot takes it
    skip_all(session)
    session.handle("cancel")
    session.handle("start BallGrasped BinClose")
    assert session.handle("run")[0].text == f"→ {asked}"


def test_a_session_started_guessing_resumes_guessing(ball, tmp_path):
    settings = Settings("g", questions=5, world=WorldKind.SYMBOLIC, base=tmp_path, record=False, safe=False)
    session = SessionManager(settings, ball, SymbolicWorld(ball))
    session.handle(SEQUENCE)
    session.handle("done")
    session.handle("quit")
    from teach.session.setup import resumed_settings

    again = resumed_settings(Settings("g", world=WorldKind.SYMBOLIC, base=tmp_path, record=False),
                             session.store.load_journal())
    assert again.safe is False
    assert SessionManager.resume(again, ball, SymbolicWorld(ball)).learning.learner.safe is False


def test_after_a_yes_that_unblocks_it_run_tries_again_from_there(ball, tmp_path):
    session = safe_session(ball, tmp_path)
    replies = stopped_with_the_bin_close(session)
    assert "(yes / find the ball" in question_text(replies)  # a yes answers it
    said = [r.text for r in session.handle("yes")]  # may I still find the ball with the bin close by? yes
    assert "✓ find the ball" in said  # and it does, as the next step of the run it stopped in
    skip_all(session)
    replies = session.handle("run")  # it goes on from there, and stops again: may I still go to the ball?
    said = [r.text for r in replies]
    assert said[0].startswith("I try again from here") and "go to the ball" in question_text(replies)
    assert "✓ go to the ball" in [r.text for r in session.handle("yes")]
    skip_all(session)
    again = session.handle("run")  # only its own steps are open: it goes on from there, to the next unsure step
    assert again[0].text.startswith("I try again from here") and "grasp the ball" in question_text(again)


def test_a_stopped_run_still_open_when_the_session_ends_may_be_tried_again_after_a_resume(ball, tmp_path):
    # 'run' after a stop tries again from there while the teacher has added no step; after a
    # resume it said "finish or cancel the open demonstration first", the run's steps taken for
    # the teacher's own
    session = safe_session(ball, tmp_path)
    stopped_with_the_bin_close(session)
    session.handle("yes")  # may I still find the ball with the bin close by? the robot does
    skip_all(session)
    assert session.open is not None and session.open.robot_steps == len(session.open.steps) == 1
    session.handle("quit")
    back = resumed(ball, tmp_path)
    assert back.open is not None and back.open.robot_steps == 1
    again = back.handle("run")
    assert again[0].text.startswith("I try again from here")
    back.handle("quit")
    # a step of the teacher's own is theirs after a resume too: 'run' asks to finish it first
    back = resumed(ball, tmp_path)
    skip_all(back)
    back.handle("go to the ball")
    back.handle("quit")
    back = resumed(ball, tmp_path)
    assert "Finish" in back.handle("run")[0].text


def test_no_followed_by_an_action_is_that_action(ball, tmp_path):
    # "no, go to the ball" was "I don't know 'no'"; a bare "no" still asks what to do instead
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    question = session.pending
    assert question is not None and question.action is not None
    instead = next(a for a in possible_actions(ball, question.state) if a != question.action)
    said = ball.action(instead).en[0]
    replies = session.handle(f"no, {said}")
    assert any(r.text.startswith("Thank you") for r in replies)
    assert session.learning.learner.situations[question.state] == {instead}


def test_a_question_open_when_the_session_ends_is_asked_again_on_resume_at_no_cost(ball, tmp_path):
    # it was paid for and then lost: a resume greeted without it, and the budget stayed spent
    session = safe_session(ball, tmp_path)
    two_demonstrations(session)
    pending = session.pending
    assert pending is not None
    left = session.budget.left
    session.handle("quit")
    back = resumed(ball, tmp_path)
    greeting = back.greet()
    assert back.pending is not None and back.pending.state == pending.state
    assert (back.pending.kind, back.pending.action) == (pending.kind, pending.action)  # found again as chosen
    assert any("costs no second question" in r.text for r in greeting)
    assert question_text(greeting) == question_text([session.asking._question_reply(pending)])
    assert back.budget.left == left
    replies = back.handle("yes")
    assert any(r.text.startswith("Thank you") for r in replies) and back.budget.left <= left


def test_after_a_resume_the_step_an_answer_names_where_a_run_stopped_is_still_taken(ball, tmp_path):
    # a run that did nothing before it stopped leaves an empty correction, which a journal does
    # not keep: after a resume the answer was learned but the robot stayed where it was
    session = safe_session(ball, tmp_path)
    replies = stopped_with_the_bin_close(session)
    assert "I did nothing" in " ".join(r.text for r in replies)
    session.handle("quit")
    back = resumed(ball, tmp_path)
    back.greet()
    assert back.pending is not None and back.pending.action == "FindBall"
    assert "✓ find the ball" in [r.text for r in back.handle("yes")]
    skip_all(back)
    assert back.handle("run")[0].text.startswith("I try again from here")


def test_no_and_another_step_with_linking_words_is_that_step(ball, tmp_path):
    # "no, go to the bin" was read as "go bin": refused in MuJoCo ("I don't know 'go bin'"), whose
    # events ("move the bin") make a guess at it unsure
    session = shown_once_in_mujoco(ball, tmp_path, seed=3)
    session.handle("start BallFound BallGrasped")
    assert "may I still do it?" in question_text(session.handle("run"))  # go to the ball, with it in hand?
    said = [r.text for r in session.handle("no, go to the bin")]
    assert said[0].startswith("Thank you") and "✓ go to the bin" in said


def test_a_step_the_tree_stopped_midway_is_said_not_finished_and_its_change_is_no_effect(ball, tmp_path):
    # in MuJoCo the tree stops a skill when what it checks changes: the grasp began with the bin out
    # of reach, the bin came within reach while it grasped, and "grasp the ball" (known only with
    # the bin away) stopped with the ball not in hand. It was said as done: "I did: …, grasp the ball."
    session = shown_once_in_mujoco(ball, tmp_path, seed=0)
    session.handle("reset")
    said = [r.text for r in session.handle("run")]
    assert "I did: find the ball, go to the ball, grasp the ball (not finished: the ball is not in my hand)." in said
    # and what it changed is an event, not its effect: it was "why grasp the ball: to make the bin
    # within reach true" once the correction was learned
    assert session.handle("steps")[0].text.endswith("3. something happened: I stopped “grasp the ball” midway")
    for line in ("yes", "put the ball in the bin", "done"):  # may I still grasp the ball with the bin near? yes
        session.handle(line)
    why = " ".join(r.text for r in session.handle("why grasp the ball"))
    assert "“the ball is in my hand”" in why and "bin" not in why
