"""A careless teacher, scripted through the session as a caregiver types (issue 11): typos,
pronouns across lines, imperatives, chatty commands, a guess declined, a wrong step taken back
with 'undo N', a wrong answer undone. The tree must still do the task from all 16 starts."""

from __future__ import annotations

import itertools

import pytest

from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.symbolic import RunEnd, run_to_goal
from teach.world.symbolic import SymbolicWorld

ENGLISH = [
    "fnd the bll, drive to the ball",  # a typo, read as a clear guess
    "go to the bucket",  # a wrong step (the ball is not in hand yet) ...
    "steps",
    "undo to step 3",  # ... taken back by its number
    "grab it",  # "it": the ball
    "chnge smthing",  # a guess at an event: asked, never done
    "no",
    "go to the bin, put it in",
    "ok done",
    "?",
    "start ball found",
    "go to it, take it, take it to the bin, put the ball in",  # "it": the ball, named on the line before
    "i'm done",
]
GERMAN = [
    "Ball fnden, geh zum Ball",
    "zum Eimer gehen",
    "schritte",
    "zurück bis Schritt 3",
    "nimm ihn",
    "etwas andrn",
    "nein",
    "zum Eimer gehen, leg ihn in den Eimer",
    "ok fertig",
    "?",
    "start du siehst den Ball",
    "geh zum Ball, nimm ihn, zum Eimer gehen, Ball in den Eimer legen",
    "fertig",
]
GUESSES = {"chnge smthing", "etwas andrn"}


def sixteen_starts(domain):
    """Every situation in which the goal does not hold yet."""
    others = [n for n in domain.condition_names if n != "BallPlaced"]
    return [domain.state([n for n, v in zip(others, bits, strict=True) if v])
            for bits in itertools.product([False, True], repeat=len(others))]


@pytest.mark.parametrize(("lang", "lines"), [("en", ENGLISH), ("de", GERMAN)])
def test_a_careless_teacher_still_teaches_the_task(ball, tmp_path, lang, lines):
    settings = Settings("careless", lang=lang, questions=3, world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    session = SessionManager(settings, ball, SymbolicWorld(ball))
    session.greet()
    for line in lines:
        replies = session.handle(line)
        assert session.open is None or -1 not in [s.action for s in session.open.steps]  # no event was guessed
        if session.pending is not None:  # a wrong answer, then taken back
            asked = session.pending.state
            answered = session.handle("go to the bin" if asked[ball.index("BinClose")] else "put the ball in the bin")
            assert answered[0].kind.name != "ERROR" and session.learning.labels[asked] in ("ApproachBin", "PlaceBall")
            if session.pending is not None:  # undo at answer> takes nothing back: leave the next question first
                session.handle("skip")
                session.handle("undo")
            session.handle("undo")
            assert asked not in session.learning.labels
        errors = [r.text for r in replies if r.kind.name == "ERROR"]
        assert bool(errors) == (line in GUESSES), (line, errors)
    assert len(session.demos) == 2
    assert [s.action for s in session.demos[0].steps] == [1, 2, 3, 4, 5, 0]
    for start in sixteen_starts(ball):
        assert run_to_goal(ball, session.learning.tree, start, 20).end is RunEnd.SUCCESS, start
