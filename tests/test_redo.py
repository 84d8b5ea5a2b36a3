"""'redo' takes back the last 'undo': steps of the open demonstration, or the last demonstration
or answer an undo took, while nothing new came after it; in files and on resume too."""

from __future__ import annotations

from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.world.symbolic import SymbolicWorld

SEQUENCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"


def session_in(ball, tmp_path, lang="en"):
    settings = Settings("r", lang=lang, world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    return SessionManager(settings, ball, SymbolicWorld(ball))


def texts(replies):
    return "\n".join(r.text for r in replies)


def test_redo_puts_undone_steps_and_the_world_back(ball, tmp_path):
    session = session_in(ball, tmp_path)
    session.handle("find the ball, go to the ball, grasp the ball")
    before = session.world.state()
    session.handle("undo to step 2")
    assert len(session.open.steps) == 1 and session.world.state() != before
    said = texts(session.handle("redo"))
    assert "steps 2 to 3" in said and "go to the ball; grasp the ball" in said
    assert [s.action for s in session.open.steps] == [1, 2, 3] and session.world.state() == before
    session.handle("go to the bin, put the ball in the bin")
    session.handle("done")
    assert [s.action for s in session.demos[0].steps] == [1, 2, 3, 4, 5, 0]


def test_nothing_to_redo_once_something_new_happened(ball, tmp_path):
    session = session_in(ball, tmp_path)
    session.handle("find the ball, go to the ball")
    session.handle("undo")
    session.handle("find the ball")  # changes nothing (the ball is seen): not a step
    session.handle("go to the ball")  # a new step where the undone one was
    replies = session.handle("redo")
    assert replies[0].kind.name == "ERROR" and "Nothing to redo" in replies[0].text
    assert [s.action for s in session.open.steps] == [1, 2]


def test_redo_brings_back_an_undone_demonstration_and_its_file(ball, tmp_path):
    session = session_in(ball, tmp_path)
    session.handle(SEQUENCE)
    session.handle("done")
    session.handle("start BallFound")
    session.handle("go to the ball, grasp the ball, go to the bin, put the ball in the bin")
    session.handle("done")
    folder = tmp_path / "demos" / "r"
    if session.pending is not None:
        session.handle("skip")  # a skipped question taught nothing: the undo takes the demonstration
    session.handle("undo")
    assert len(session.demos) == 1 and (folder / "undone" / "demo-002.csv").is_file()
    said = texts(session.handle("redo"))
    assert "your demonstration 2," in said and "Generation" in said
    assert len(session.demos) == 2 and (folder / "demo-002.csv").is_file()
    assert not (folder / "undone" / "demo-002.csv").exists()
    assert "Nothing to redo" in texts(session.handle("redo"))  # one undo, one redo
    session.close()
    resumed = SessionManager.resume(session.settings, ball, SymbolicWorld(ball))
    assert len(resumed.demos) == 2  # the journal holds the redo


def test_an_undo_after_new_learning_cannot_be_redone(ball, tmp_path):
    session = session_in(ball, tmp_path, lang="de")
    session.handle("Ball finden, zum Ball gehen, Ball greifen, zum Eimer gehen, Ball in den Eimer legen")
    session.handle("fertig")
    if session.pending is not None:
        session.handle("weiter")
    session.handle("zurück")
    session.handle("start BallFound")
    session.handle("zum Ball gehen, Ball greifen, zum Eimer gehen, Ball in den Eimer legen")
    session.handle("fertig")  # something new was learned: the undone demonstration stays undone
    replies = session.handle("wiederherstellen")
    assert replies[0].kind.name == "ERROR" and "Nichts wiederherzustellen" in replies[0].text
    assert len(session.demos) == 1
