"""Guiding feedback in words: where the ball and the bin are from the robot's hand, the lift,
the hand, and what the last key (or guide line) did, so a person can steer by it alone."""

from __future__ import annotations

from typing import TYPE_CHECKING

from teach import messages as m
from teach.messages import Lang

if TYPE_CHECKING:
    from teach.sim.guide import Feedback

AHEAD_DEGREES = 8.0     # this close to straight ahead is "ahead"
BEHIND_DEGREES = 150.0  # this far round is "behind me"
LEVEL = 0.03            # m: the ball this close to the hand's height is "at hand height"
STILL = 0.005           # m (or 0.5 degree, 5 mm of lift or finger): the command moved nothing
HELD_BY_TOP = 0.045     # m: a ball held with its centre this far below the hand is held by its top only
# (closed round a centred ball with the lift 4 cm up it stayed in the hand on the way to the bin; 5 cm up it
# fell out at the first move, and the teacher who guided that grasp saw "✓ grasp the ball")
ON_THE_BALL = 0.12      # m: an open hand stopped this near the ball on its way down rests on it


def feedback_line(feedback: Feedback, lang: Lang) -> str:
    """One line: "ball 34 cm, 20° to my left, 5 cm below my hand · bin 1.2 m ahead · lift 26 cm ·
    hand open · last: ↑ moved me 10 cm"."""
    hand = m.FEEDBACK_OPEN if feedback.hand_open else m.FEEDBACK_CLOSED
    ball = m.FEEDBACK_UNDER_ARM(lang, distance=_length(feedback.ball_distance, lang)) if feedback.ball_under_arm \
        else _where(feedback.ball_distance, feedback.ball_bearing, lang)
    return m.GUIDE_FEEDBACK(lang, ball=ball,
                            ball_height=_height(feedback.ball_height, feedback.ball_held, lang),
                            bin=_where(feedback.bin_distance, feedback.bin_bearing, lang),
                            lift=_length(feedback.lift, lang), hand=hand(lang), last=_last(feedback, lang))


def _length(metres: float, lang: Lang) -> str:
    if abs(metres) < 1.0:
        return m.FEEDBACK_CM(lang, cm=round(abs(metres) * 100))
    tenths = round(abs(metres) * 10)
    return m.FEEDBACK_M(lang, whole=tenths // 10, tenth=tenths % 10)


def _where(distance: float, bearing: float, lang: Lang) -> str:
    length = _length(distance, lang)
    if abs(bearing) <= AHEAD_DEGREES:
        return m.FEEDBACK_AHEAD(lang, distance=length)
    if abs(bearing) >= BEHIND_DEGREES:
        return m.FEEDBACK_BEHIND(lang, distance=length)
    side = m.FEEDBACK_LEFT if bearing > 0 else m.FEEDBACK_RIGHT
    return side(lang, distance=length, degrees=round(abs(bearing)))


def _height(height: float, held: bool, lang: Lang) -> str:
    if held and height < -HELD_BY_TOP:
        return m.FEEDBACK_HELD_BY_TOP(lang, distance=_length(height, lang))
    if abs(height) <= LEVEL:
        return m.FEEDBACK_AT_HAND_HEIGHT(lang)
    return (m.FEEDBACK_ABOVE if height > 0 else m.FEEDBACK_BELOW)(lang, distance=_length(height, lang))


def _last(feedback: Feedback, lang: Lang) -> str:
    did = _last_did(feedback, lang)
    return m.FEEDBACK_STOPPED(lang, did=did) if feedback.stopped else did


def _last_did(feedback: Feedback, lang: Lang) -> str:
    command = feedback.last
    if command is None:
        return m.FEEDBACK_NOTHING_YET(lang)
    if command.verb == "forward":
        key = "↑" if command.amount >= 0 else "↓"
        if feedback.moved < STILL:
            return m.FEEDBACK_BLOCKED(lang, key=key)
        return m.FEEDBACK_MOVED(lang, key=key, distance=_length(feedback.moved, lang))
    if command.verb == "turn":
        key = "←" if command.amount >= 0 else "→"
        if abs(feedback.turned) < 0.5:
            return m.FEEDBACK_BLOCKED(lang, key=key)
        turned = m.FEEDBACK_TURNED_LEFT if feedback.turned > 0 else m.FEEDBACK_TURNED_RIGHT
        return turned(lang, key=key, degrees=round(abs(feedback.turned)))
    if command.verb == "lift":
        key = (m.KEY_PAGE_UP if command.amount >= feedback.lift - feedback.lifted else m.KEY_PAGE_DOWN)(lang)
        if _rests_on_ball(feedback, command.amount):
            return m.FEEDBACK_ON_THE_BALL(lang, key=key)
        if abs(feedback.lifted) < STILL:
            return m.FEEDBACK_BLOCKED(lang, key=key)
        lifted = m.FEEDBACK_LIFTED if feedback.lifted > 0 else m.FEEDBACK_LOWERED
        return lifted(lang, key=key, distance=_length(feedback.lifted, lang))
    if command.verb in ("open", "close"):
        key = m.KEY_SPACE(lang)
        if abs(feedback.gripped) < STILL:
            return m.FEEDBACK_BLOCKED(lang, key=key)
        return (m.FEEDBACK_CLOSED_HAND if feedback.gripped > 0 else m.FEEDBACK_OPENED)(lang, key=key)
    return m.FEEDBACK_WAITED(lang, key=m.KEY_WAIT(lang))



def _rests_on_ball(feedback: Feedback, target: float) -> bool:
    """Lowering an open hand stopped short of ``target`` just above the ball: its fingers sit on
    the ball instead of round it, and closing them would hold it by its top."""
    return (feedback.hand_open and feedback.lifted < 0 and feedback.lift - target > STILL
            and feedback.ball_distance < ON_THE_BALL and feedback.ball_height < 0)
