"""The phrase book inside today's session manager (symbolic world): a careless teacher's
everyday lines, pronouns and imperatives in both languages, teach a whole demonstration."""

from __future__ import annotations

import pytest

from teach.demos import read_demo_set
from teach.session.machine import SessionManager
from teach.session.settings import Settings
from teach.world.symbolic import SymbolicWorld


def session(ball, tmp_path, lang):
    settings = Settings("careless", lang=lang, questions=0, base=tmp_path, world="symbolic", record=False)
    return SessionManager(settings, ball, SymbolicWorld(ball))


@pytest.mark.parametrize("lang,lines", [
    ("en", ["please find the ball, then drive to it", "grab it", "ok, go to the bucket and put it in", "done"]),
    ("de", ["such den Ball und dann fahr zum Ball", "nimm ihn", "fahr zum Eimer", "leg ihn in den Eimer",
            "fertig"]),
    ("en", ["find the ball", "go to the ball", "pick it up", "take it to the bin", "drop it in", "done"]),
    ("de", ["Ball finden", "zum Ball", "nimm ihn", "ab zum Eimer damit", "räum ihn weg", "fertig"]),
])
def test_everyday_lines_teach_the_whole_task(ball, tmp_path, lang, lines):
    manager = session(ball, tmp_path, lang)
    for line in lines:
        replies = manager.handle(line)
        assert all(r.kind != "error" for r in replies), (line, [r.text for r in replies])
    _, [demo] = read_demo_set(tmp_path / "demos" / "careless")
    assert [step.action for step in demo.steps] == [1, 2, 3, 4, 5, 0]


def test_in_mujoco_only_the_exact_phrase_perturbs(ball, tmp_path):
    from teach.world.mujoco_world import MujocoWorld

    settings = Settings("mujoco", lang="en", questions=0, base=tmp_path, world="mujoco", record=False)
    manager = SessionManager(settings, ball, MujocoWorld(ball, seed=3))
    replies = manager.handle("take the ball to the bin")  # not the event "take the ball away"
    assert not any(r.text.startswith("Event") for r in replies)
    # and not done with nothing in hand: that would teach "go to the bin" where the teacher meant the ball
    assert replies[0].text == "“take the ball to the bin”: first this must be true: the ball is in my hand"
    assert manager.open is None
    manager.handle("go to the bin")
    replies = manager.handle("move the bin")
    assert [r.text for r in replies if r.text.startswith("Event")] == ["Event: move the bin."]
    assert manager.open is not None and [s.action for s in manager.open.steps] == [4, -1]
    manager.close()
