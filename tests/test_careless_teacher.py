"""A careless teacher, scripted through the session as a caregiver types (issue 11): typos,
pronouns across lines, imperatives, chatty commands, a guess declined, a wrong step taken back
with 'undo N', a wrong answer undone. The tree must still do the task from all 16 starts.

The same teacher is written down as dialogues/careless_en.dialogue and careless_de.dialogue,
with a slip added (the ball knocked out of the hand, grasped again, falls out of the gripper
as the carry begins): replayed in MuJoCo they teach a tree that does the task from all 16
starts there, and replayed in the symbolic world (where the knock is only an unknown line) too."""

from __future__ import annotations

import pytest
from conftest import ROOT
from every_start import mujoco_outcomes, sixteen_starts
from teacher_loop import correct_until_it_works

from teach.bt.nodes import Node
from teach.bt.xml import read_tree
from teach.cli import main
from teach.demos import read_demo_set
from teach.domain import load_domain
from teach.session.machine import SessionManager
from teach.session.replies import ReplyKind
from teach.session.settings import Settings, WorldKind
from teach.sim.world import World
from teach.symbolic import RunEnd, missing_preconditions, run_to_goal
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
    "start ich sehe den Ball",
    "geh zum Ball, nimm ihn, zum Eimer gehen, Ball in den Eimer legen",
    "fertig",
]
GUESSES = {"chnge smthing", "etwas andrn"}


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
            # wrong, but nothing the domain file can tell: an action that can run there
            wrong = next(a for a in ball.actions
                         if not missing_preconditions(ball, asked, a.name) and a.name != "PlaceBall")
            answered = session.handle(wrong.label(lang))
            assert answered[0].kind.name != "ERROR" and session.learning.labels[asked] == wrong.name
            if session.pending is not None:  # undo at answer> takes nothing back: leave the next question first
                session.handle("skip")
            undone = session.handle("undo")  # the wrong answer, not the skip (a skip taught nothing)
            assert any("“" in r.text for r in undone), [r.text for r in undone]
            assert asked not in session.learning.labels
        errors = [r.text for r in replies if r.kind.name == "ERROR"]
        assert bool(errors) == (line in GUESSES), (line, errors)
    assert len(session.demos) == 2
    assert [s.action for s in session.demos[0].steps] == [1, 2, 3, 4, 5, 0]
    # two demonstrations leave the robot unsure in some starts: it stops there, never guesses ...
    stuck = [start for start in sixteen_starts(ball)
             if run_to_goal(ball, session.learning.tree, start, 20).end is not RunEnd.SUCCESS]
    assert stuck and all(run_to_goal(ball, session.learning.tree, start, 20).end is RunEnd.FAILURE for start in stuck)
    # ... and the teacher, running it from each start and answering or showing where it stops, teaches the rest
    corrections = correct_until_it_works(session, ball, sixteen_starts(ball))
    for start in sixteen_starts(ball):
        assert run_to_goal(ball, session.learning.tree, start, 20).end is RunEnd.SUCCESS, start
    assert corrections.shown + corrections.answers <= 16


MUJOCO_REACHED = {"en": 7, "de": 7}
SYMBOLIC_REACHED = 5
"""Starts the careless dialogue's tree does the task from in MuJoCo (measured); from the others it stops."""
SLIPPED = {"en": "Event: the ball fell out of the gripper.", "de": "Ereignis: der Ball ist aus dem Greifer gefallen."}
# fetch, knock (-1), fetch again, the slip (-1) as the carry began, grasp again, carry, place, goal
WITH_SLIP = [1, 2, 3, -1, 1, 2, 3, -1, 3, 4, 5, 0]


@pytest.fixture(scope="module")
def mujoco() -> World:
    """One world for every run from the 16 starts (building one costs more than a run)."""
    return World(seed=0)


def replayed(tmp_path, capsys, lang: str, *options: str) -> tuple[str, Node, list[list[int]]]:
    """Replay the careless dialogue: its transcript, its last tree and its demonstrations' actions."""
    dialogue = ROOT / "dialogues" / f"careless_{lang}.dialogue"
    assert main(["replay", str(dialogue), "--no-record", "--base", str(tmp_path), *options]) == 0
    transcript = capsys.readouterr().out
    last = sorted((tmp_path / "trees" / f"careless_{lang}").glob("gen-*.xml"))[-1]
    _, demos = read_demo_set(tmp_path / "demos" / f"careless_{lang}")
    return transcript, read_tree(last), [[s.action for s in demo.steps] for demo in demos]


@pytest.mark.parametrize("lang", ["en", "de"])
def test_the_careless_dialogue_teaches_the_task_in_mujoco(tmp_path, capsys, mujoco, lang):
    transcript, tree, demos = replayed(tmp_path, capsys, lang)
    assert transcript.count(SLIPPED[lang]) == 1 and "cannot learn" not in transcript.lower()
    assert demos == [WITH_SLIP, [2, 3, 4, 5, 0]]
    ends = mujoco_outcomes(mujoco, tree)
    # never done wrongly, never anything but done or "show me": where two demonstrations leave it unsure it stops
    assert set(ends) <= {"reached", "stuck"} and ends["reached"] >= MUJOCO_REACHED[lang], ends


@pytest.mark.parametrize("lang", ["en", "de"])
def test_the_careless_dialogue_teaches_the_task_in_the_symbolic_world(tmp_path, capsys, ball, lang):
    transcript, tree, demos = replayed(tmp_path, capsys, lang, "--world", "symbolic")
    assert SLIPPED[lang] not in transcript  # no physics, no slip: the knock is a line it does not know
    assert demos == [[1, 2, 3, 4, 5, 0], [2, 3, 4, 5, 0]]
    runs = [run_to_goal(ball, tree, start, 20) for start in sixteen_starts(ball)]
    reached = [run.end is RunEnd.SUCCESS and run.state[ball.index("BallPlaced")] for run in runs]
    # done only with the ball in the bin; elsewhere it stops and asks to be shown (measured: 5 of 16
    # done; the answers are written for the questions asked in MuJoCo)
    assert all(ok or run.end is RunEnd.FAILURE for ok, run in zip(reached, runs, strict=True))
    assert sum(reached) >= SYMBOLIC_REACHED


def test_a_new_start_in_blocksworld_is_one_the_world_can_be_in(tmp_path):
    """Blocksworld's state where nothing holds (no block on the table, the hand neither empty nor
    full) allows no action: a session there was a dead end, and 'reset' always went back to it.
    The session begins where a demonstration beside the domain file begins (a careless teacher did
    not get past the first line: every step refused, "what now?" told to type a whole situation);
    without one it says how to leave it. After a 'start' a new start walks from there, 'reset N'
    the same each time; the ball's start (where nothing holds and it can look for the ball) stays."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    settings = Settings("blocks", base=tmp_path, world="symbolic", record=False)
    manager = SessionManager(settings, domain, SymbolicWorld(domain))
    told = "\n".join(r.text for r in manager.greet())
    assert "I begin where held-out/d01.csv begins" in told
    first = read_demo_set(ROOT / "demos" / "blocksworld" / "held-out", domain)[1][0].steps[0].state
    assert manager.world.state() == first
    alone = tmp_path / "alone" / "domain.toml"  # no demonstration beside it
    alone.parent.mkdir()
    alone.write_bytes((ROOT / "demos" / "blocksworld" / "domain.toml").read_bytes())
    domain = load_domain(alone)
    manager = SessionManager(Settings("blocks2", base=tmp_path, world="symbolic", record=False), domain,
                             SymbolicWorld(domain))
    told = "\n".join(r.text for r in manager.greet())
    assert "none of the 29 conditions holds" in told and "Set up a situation with 'start'" in told
    manager.handle("start clear a, clear b, clear c, clear d, handempty, ontable a, ontable b, ontable c, ontable d")
    starts = []
    for line in ("reset 2", "reset 3", "reset 2"):
        replies = manager.handle(line)
        assert not any("Set up a situation" in r.text for r in replies)
        state = manager.world.state()
        assert any(not missing_preconditions(domain, state, a.name) for a in domain.actions)
        starts.append(state)
    assert starts[0] == starts[2]
    ball = load_domain(ROOT / "demos" / "ball" / "domain.toml")
    world = SymbolicWorld(ball)
    world.arrange(ball.state(["BallFound", "BallClose"]))
    world.reset(2)
    assert world.state() == ball.state([])


def test_no_way_is_offered_that_the_refused_step_would_only_undo(tmp_path):
    """ "take d off a" with d on the table was offered "To get there: put down a, pick up d, stack d
    a." (to take it off again); a way the step does more than undo is still offered."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    manager = SessionManager(Settings("blocks", base=tmp_path, world="symbolic", record=False), domain,
                             SymbolicWorld(domain))
    manager.handle("start clear b, clear c, clear d, holding a, ontable b, ontable c, ontable d")
    assert [r.kind for r in manager.handle("take d off a")] == [ReplyKind.ERROR, ReplyKind.STATE]
    assert [r.kind for r in manager.handle("put d on the table")] == [ReplyKind.ERROR, ReplyKind.STATE]
    assert manager.handle("put b on c")[1].text == ("To get there: put down a, pick up b. Say 'yes' and I do that, "
                                                   "then stack b c.")


def test_it_before_anything_was_named_is_offered_as_the_one_object_it_can_be(tmp_path):
    """ "put it on b" while holding a, with no block named yet, was "Did you mean “put c on b”?"
    (a typo of the words); the one block that makes the step possible is offered, and a yes does it."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    manager = SessionManager(Settings("blocks", base=tmp_path, world="symbolic", record=False), domain,
                             SymbolicWorld(domain))
    manager.greet()  # nothing can be done where nothing holds: it begins where held-out/d01.csv does, holding a
    assert manager.handle("put it on b")[0].text == "I don't know “put it on b”. Did you mean “put a on b”?"
    manager.handle("yes")
    assert manager.open is not None and [domain.action(s.action).name for s in manager.open.steps] == ["stack_a_b"]
    assert manager.handle("pick it up")[0].text.startswith("I could not pick up a")  # "it" is a now


def test_a_start_naming_several_blocks_leaves_it_to_the_one_that_fits(tmp_path, ball):
    """After "start …, holding a, …, ontable d", "put it on b" was "stack d b" (the last block the
    start line named); "it" there is the block the step can be about, as before anything was named.
    A start naming one object still makes it the topic ("start ball found", "go to it")."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    manager = SessionManager(Settings("blocks", base=tmp_path, world="symbolic", record=False), domain,
                             SymbolicWorld(domain))
    manager.handle("start clear b, clear c, clear d, holding a, ontable b, ontable c, ontable d")
    assert manager.handle("put it on b")[0].text == "I don't know “put it on b”. Did you mean “put a on b”?"
    manager = SessionManager(Settings("ball", base=tmp_path, world="symbolic", record=False), ball,
                             SymbolicWorld(ball))
    manager.handle("start ball found")
    manager.handle("go to it")
    assert manager.open is not None and [ball.action(s.action).name for s in manager.open.steps] == ["ApproachBall"]


def test_blocksworld_conditions_said_in_a_persons_order(tmp_path):
    """"start a on b, b on the table, hand empty, a clear" was "unknown condition 'a on b'": a condition
    with a form is read from its objects in order and its other words run together ("on the table":
    ontable; "hand empty": handempty); "b on a" is on b a, never on a b."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    manager = SessionManager(Settings("blocks", base=tmp_path, world="symbolic", record=False), domain,
                             SymbolicWorld(domain))
    replies = manager.handle("start a on b, b on the table, c is on the table, d on the table, hand empty, "
                             "a clear, c clear, the d is clear")
    assert [r.kind for r in replies] != [ReplyKind.ERROR]
    assert manager.world.state() == domain.state(["on_a_b", "ontable_b", "ontable_c", "ontable_d", "handempty",
                                                   "clear_a", "clear_c", "clear_d"])
    manager.handle("start b on a")
    assert manager.world.state() == domain.state(["on_b_a"])


def test_a_question_in_blocksworld_offers_one_action_of_each_kind(tmp_path):
    """The answers offered under a question listed all 40 blocksworld actions, "stack a a" and
    "unstack d d" among them, over five lines; now one of each kind and how many more (Tab)."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    settings = Settings("blocks", base=tmp_path, world="symbolic", record=False, questions=5)
    manager = SessionManager(settings, domain, SymbolicWorld(domain))
    manager.greet()
    manager.handle("start clear a, clear b, clear c, handempty, on a d, ontable b, ontable c, ontable d")
    for line in ("pick up b", "stack b on a", "done"):
        manager.handle(line)
    asked = [r.text for r in manager.handle("ask") if r.kind is ReplyKind.QUESTION]
    assert asked, "the robot asks something after one demonstration"
    options = asked[0].splitlines()[-1]
    assert "36 more like them (Tab)" in options and "stack a a" not in options and "skip" in options
