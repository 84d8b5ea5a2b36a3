"""Recognising which known action a change of state was, and the labelling questions."""

from __future__ import annotations

from teach.domain import Domain, Literal
from teach.learn.recognise import explain, question, recognise


def test_each_declared_action_is_recognised_from_its_change(ball: Domain) -> None:
    s = ball.state
    cases = [(s([]), s(["BallFound"]), "FindBall"),
             (s(["BallFound"]), s(["BallFound", "BallClose"]), "ApproachBall"),
             (s(["BallFound", "BallClose"]), s(["BallFound", "BallClose", "BallGrasped"]), "GraspBall"),
             (s(["BallFound", "BallClose", "BallGrasped"]), s(["BallFound", "BallClose", "BallGrasped", "BinClose"]),
              "ApproachBin"),
             (s(["BallFound", "BallClose", "BallGrasped", "BinClose"]),
              s(["BallFound", "BallClose", "BinClose", "BallPlaced"]), "PlaceBall")]
    for before, after, name in cases:
        found = recognise(ball, before, after)
        assert found.best == name and not found.needs_question


def test_preconditions_must_hold(ball: Domain) -> None:
    # the ball ends in the bin without ever being grasped: PlaceBall's effect, not its precondition
    before = ball.state(["BallFound", "BallClose", "BinClose"])
    after = ball.state(["BallFound", "BallClose", "BinClose", "BallPlaced"])
    found = recognise(ball, before, after)
    assert not found.fits and found.needs_question and found.best is None
    assert found.changes == (Literal("BallPlaced"),)


def test_a_change_nobody_declares_fits_nothing(ball: Domain) -> None:
    found = recognise(ball, ball.state(["BallFound", "BallClose"]), ball.state(["BallFound"]))
    assert not found.fits and found.changes == (Literal("BallClose", False),)


def test_learned_effects_rank_and_tie(ball: Domain) -> None:
    before, after = ball.state(["BallFound"]), ball.state(["BallFound", "BallClose"])
    # a learned action with the same effect: two explain the change equally, the teacher decides
    tied = recognise(ball, before, after, effects={"PushBall": [Literal("BallClose")]})
    assert [c.action for c in tied.candidates] == ["ApproachBall", "PushBall"] and tied.ambiguous
    # learned effects replace the declared ones: ApproachBall now also loses the bin
    moved = recognise(ball, ball.state(["BallFound", "BinClose"]), after,
                      effects={"ApproachBall": [Literal("BallClose"), Literal("BinClose", False)],
                               "PushBall": [Literal("BallClose")]})
    assert [c.action for c in moved.candidates] == ["ApproachBall", "PushBall"] and not moved.ambiguous
    assert moved.candidates[1].unexplained == (Literal("BinClose", False),)


def test_learned_preconditions_count(ball: Domain) -> None:
    before, after = ball.state(["BallFound"]), ball.state(["BallFound", "BallClose"])
    learned = {"PushBall": [Literal("BallClose")]}
    assert [c.action for c in recognise(ball, before, after, learned, {"PushBall": [Literal("BinClose")]}).candidates] \
        == ["ApproachBall"]
    assert [c.action for c in recognise(ball, before, after, learned, {"PushBall": []}).candidates] \
        == ["ApproachBall", "PushBall"]


def test_a_gain_left_unexplained_asks_a_loss_does_not(ball: Domain) -> None:
    # leaving the bin behind on the way to the ball: a side effect, no question
    lost = recognise(ball, ball.state(["BallFound", "BinClose"]), ball.state(["BallFound", "BallClose"]))
    assert lost.best == "ApproachBall" and not lost.needs_question
    # the ball ended in the hand too: maybe a second thing the teacher did, so the robot asks
    gained = recognise(ball, ball.state(["BallFound"]), ball.state(["BallFound", "BallClose", "BallGrasped"]))
    assert gained.best == "ApproachBall" and not gained.ambiguous and gained.needs_question
    # reach and the bin at once: going to the ball and going to the bin explain it equally
    both = recognise(ball, ball.state(["BallFound"]), ball.state(["BallFound", "BallClose", "BinClose"]))
    assert both.ambiguous and question(ball, both).endswith("Was that 'go to the ball' or 'go to the bin'?")


def test_a_side_effect_before_the_change_joins_it(ball: Domain) -> None:
    # driving to the ball first leaves the bin behind, then reaches the ball: one ApproachBall
    s = ball.state
    changes = [(s(["BallFound", "BinClose"]), s(["BallFound"])),
               (s(["BallFound"]), s(["BallFound", "BallClose"])),
               (s(["BallFound", "BallClose"]), s(["BallFound", "BallClose", "BallGrasped"]))]
    groups = explain(ball, changes)
    assert [(list(r), g.best) for r, g in groups] == [([0, 1], "ApproachBall"), ([2], "GraspBall")]
    # nothing after it explains a lost ball: it stays on its own, recognised as nothing
    alone = explain(ball, [(s(["BallFound", "BallClose"]), s(["BallFound"]))])
    assert [(list(r), g.fits) for r, g in alone] == [([0], False)]


def test_questions_in_plain_words(ball: Domain) -> None:
    found = recognise(ball, ball.state(["BallFound"]), ball.state(["BallFound", "BallClose"]))
    assert question(ball, found) == "You moved me so that now the ball is within reach. Was that 'go to the ball'?"
    assert question(ball, found, "de") == \
        "Du hast mich so bewegt, dass jetzt gilt: der Ball ist in Reichweite. War das „zum Ball gehen“?"
    tied = recognise(ball, ball.state(["BallFound"]), ball.state(["BallFound", "BallClose"]),
                     effects={"PushBall": [Literal("BallClose")]})
    assert question(ball, tied, labels={"PushBall": "push the ball"}).endswith(
        "Was that 'go to the ball' or 'push the ball'?")
    none = recognise(ball, ball.state(["BallFound", "BallClose"]), ball.state(["BallFound"]))
    assert question(ball, none) == ("You moved me so that now the ball is out of reach. "
                                    "None of the actions I know does that. What should I call what you did?")
    assert question(ball, none, "de").startswith("Du hast mich so bewegt, dass jetzt gilt: der Ball ist nicht in "
                                                 "Reichweite. Das kann keine Aktion")
