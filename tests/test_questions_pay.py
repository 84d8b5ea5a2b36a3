"""Questions that pay (issue 11): a run that ends "done" with the goal unmet asks about it at
once, 'done' is refused where the goal visibly does not hold, undo at answer> takes nothing
back, and no situation is paid for twice. Symbolic world, real learner."""

from __future__ import annotations

from test_session import SEQUENCE, new_session, possible_answers, settings, teach_two_demonstrations

from teach.learn.inquiry import next_question
from teach.session.machine import Mode, SessionManager
from teach.world.symbolic import SymbolicWorld


def wrongly_done_session(ball, tmp_path, lang="en"):
    """A session whose tree says "done" with the ball out of the bin where the ball is seen and
    the bin is close (an answer of an older session that did not check answers)."""
    session = new_session(ball, tmp_path, lang=lang)
    session.handle(SEQUENCE)
    session.handle("done")
    state = ball.state(["BallFound", "BinClose"])
    session.learning.learn_answer(state, None, "an unchecked answer")
    return session, state


def test_a_run_that_thinks_it_is_done_asks_about_where_it_ended(ball, tmp_path):
    session, state = wrongly_done_session(ball, tmp_path)
    session.handle("start BallFound BinClose")
    replies = session.handle("run")
    assert any("I thought I was done" in r.text for r in replies)
    assert replies[-1].kind.name == "QUESTION" and session.pending is not None
    assert session.pending.state == state and session.budget.left == 4


def test_ask_finds_the_situation_where_the_tree_would_stop_short(ball, tmp_path):
    session, state = wrongly_done_session(ball, tmp_path)
    question = next_question(session.learning.learner, session.learning.asked)
    assert question is not None and question.kind == "unmet-goal" and question.tree_does == "done"
    assert session.handle("ask")[0].kind.name == "QUESTION" and session.pending is not None


def test_done_where_the_goal_does_not_hold_is_refused_and_asked_again(ball, tmp_path):
    for lang, done, reason in (("en", "done", "the ball is not in the bin"),
                               ("de", "fertig", "der Ball ist nicht im Eimer")):
        session, state = wrongly_done_session(ball, tmp_path / lang, lang)
        session.handle("start BallFound BinClose")
        session.handle("run" if lang == "en" else "los")
        left = session.budget.left
        replies = session.handle(done)
        assert [r.kind.name for r in replies] == ["ERROR", "QUESTION"] and reason in replies[0].text
        assert session.pending is not None and session.pending.state == state and session.budget.left == left


def test_undo_at_the_answer_prompt_takes_nothing_back(ball, tmp_path):
    session, _ = wrongly_done_session(ball, tmp_path)
    session.handle("start BallFound BinClose")
    session.handle("run")
    demos, left = len(session.demos), session.budget.left
    replies = session.handle("undo")
    assert [r.kind.name for r in replies] == ["INFO"] and "skip" in replies[0].text
    assert session.mode is Mode.ASKING and len(session.demos) == demos and session.budget.left == left


def test_a_question_asked_again_after_an_undo_is_not_paid_twice(ball, tmp_path):
    session = new_session(ball, tmp_path)
    teach_two_demonstrations(session)
    asked = session.pending
    assert asked is not None
    session.handle(ball.action(possible_answers(ball, asked.state)[0]).label("en"))  # raises the next question
    assert session.pending is not None
    left = session.budget.left
    session.handle("skip")
    session.handle("undo")  # takes back the skip
    session.handle("undo")  # and the answer
    session.handle("ask")
    assert session.pending is not None and session.pending.state == asked.state and session.budget.left == left
    session.handle("skip")
    resumed = SessionManager.resume(settings(tmp_path), ball, SymbolicWorld(ball))
    assert resumed.budget.left == left  # the journal asks it twice; it was paid for once
