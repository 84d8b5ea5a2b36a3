"""``guide hand`` (``führen hand``): the session follows the teacher's drag in the MuJoCo viewer.

The robot follows a hand on any of its bodies, control period by control period
(``Guide.hand_period``), and its motion is segmented and recognised as scripted guide lines
are. A hand on the ball or the bin is the teacher moving that thing: what the robot had done
before counts as finished (it is labelled first), the segmenter waits while the thing moves,
and once it lies still the change is one external step (-1), "you moved the ball"; a move that
changed nothing is said so and not recorded. Segmenting then starts afresh from the new state.

``guide hand 10`` follows for 10 simulated seconds (paced to wall time in a session);
``guide hand`` alone follows until the hand has been off everything for ``LET_GO_SECONDS``
(at most ``MAX_SECONDS``). A labelling question ends the following: the teacher answers at the
prompt, then says ``guide hand`` again.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from teach import messages as m
from teach.observe.hook import Observer
from teach.session.replies import Reply, ReplyKind
from teach.session.showing import Showing
from teach.session.turn import Turn
from teach.sim.hand import PUSH_EPSILON, Moved, ObjectWatch, robot_bodies, robot_wrench
from teach.world.protocol import WorldEvent

if TYPE_CHECKING:
    from teach.sim.guide import Guide
    from teach.sim.segment import Segmenter

LET_GO_SECONDS = 1.5   # the hand is off everything this long: the teacher has let go
MAX_SECONDS = 60.0     # ``guide hand`` alone never follows longer than this
MOVED_EVENT = "moved by hand"  # the external action's name in the recording

_THINGS = {"ball": m.HAND_THE_BALL, "bin": m.HAND_THE_BIN}


class Labelling(Protocol):
    """What the hand follower needs of guiding (``teach.session.guiding.Guiding``): the segments
    of the motion so far and their labelling."""

    segmenter: Segmenter | None
    labelled: int
    """How many of the segmenter's segments are steps (or left out) already."""

    @property
    def pending(self) -> object | None: ...

    @property
    def active(self) -> bool: ...

    def label(self, final: bool) -> list[Reply]: ...


class HandFollower:
    """Follows the hand over one guide; holds back a moved thing's step while a label is asked."""

    def __init__(self, guiding: Labelling, guide: Guide, showing: Showing, observer: Observer, turn: Turn):
        self.guiding, self.guide = guiding, guide
        self.showing, self.observer, self.turn = showing, observer, turn
        self.watch = ObjectWatch(guide.world, guide.period)
        self._robot = robot_bodies(guide.world)
        self._held: list[Moved] = []  # moves that wait for the labels of what came before them

    @property
    def holds_segmenting(self) -> bool:
        """The segmenter waits: a thing is moving, or its step waits for a label before it."""
        return self.watch.busy or bool(self._held)

    def follow(self, seconds: float) -> list[Reply]:
        guiding, guide, watch = self.guiding, self.guide, self.watch
        self.turn.say([Reply(ReplyKind.INFO, m.HAND_FOLLOWING(self.showing.lang))])
        replies: list[Reply] = []
        limit = seconds if seconds > 0 else MAX_SECONDS
        elapsed = off = 0.0
        touched = False
        guide.doing = "guide hand"
        while elapsed + 1e-9 < limit:
            if watch.begins() and not watch.busy and guiding.segmenter is not None:
                guiding.segmenter.finish()  # what the robot did before the hand took the thing is done
                replies += guiding.label(final=True)
            for moved in watch.update():
                self._held.append(moved)
                replies += guiding.label(final=False)  # records the move at once if no label is asked
            guide.hand_period()
            elapsed += guide.period
            on_robot = any(abs(v) > PUSH_EPSILON for v in robot_wrench(guide.world, self._robot))
            hand_on = on_robot or watch.touched()
            touched = touched or hand_on
            off = 0.0 if hand_on or watch.busy else off + guide.period
            if guiding.pending is not None and not watch.busy:
                break  # the teacher answers at the prompt
            if seconds <= 0 and touched and off + 1e-9 >= LET_GO_SECONDS:
                break
        guide.world.drive(0.0, 0.0)  # a thing still moving is watched on by the next 'guide hand'
        return replies + guiding.label(final=False)

    def finish(self) -> None:
        """Guidance ends: a thing still moving is taken where it is now."""
        self._held += self.watch.settle_now()

    def after_labels(self) -> list[Reply]:
        """Everything before the held moves is labelled: record them, and segment afresh."""
        guiding = self.guiding
        segmenter = guiding.segmenter
        if not self._held or (segmenter is not None and guiding.labelled < len(segmenter.segments)):
            return []
        replies = [self._record(moved) for moved in self._held]
        changed = any(moved.before != moved.after for moved in self._held)
        self._held = []
        if changed and guiding.active:
            from teach.sim.segment import Segmenter

            guiding.segmenter, guiding.labelled = Segmenter(), 0
        return self.turn.say(replies)

    def _record(self, moved: Moved) -> Reply:
        lang = self.showing.lang
        thing = _THINGS[moved.thing]
        if moved.before == moved.after:
            return Reply(ReplyKind.INFO, m.HAND_MOVED_NOTHING(lang, thing=thing(lang)))
        en, de = m.HAND_MOVED("en", thing=thing("en")), m.HAND_MOVED("de", thing=thing("de"))
        event = WorldEvent(MOVED_EVENT, moved.before, moved.after, en, de)
        self.showing.event(event)
        self.observer.on_external(MOVED_EVENT)
        self.showing.record.save_open()
        return self.showing.event_reply(event)
