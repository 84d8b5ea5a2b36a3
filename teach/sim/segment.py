"""Segmentation: guided motion cut where the symbolic state changes, debounced.

A change counts only once the new state has held for ``hold`` simulated seconds (default
0.3 s): a sweep of the gripper past the bin, or a wobble at the edge of reach, flips a
condition for a moment and makes no step. The segment ends where the new state first
appeared, so the motion that made the change belongs to it and the dithering after it does
not. What follows the last change (lifting the arm after placing, say) is the tail: motion
without a change, which no transition describes. When guidance ends (``finish``), a change
still inside its hold time counts: the robot ends in that state.

The segmenter works online, one sample per control period, at a few microseconds each.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from teach.demos import Demonstration, Step
from teach.domain import GOAL_ACTION, Domain, State
from teach.errors import TeachError
from teach.learn.recognise import Effects, Recognition, explain
from teach.sim.guide import Sample

HOLD_SECONDS = 0.3


@dataclass(frozen=True, slots=True)
class Segment:
    """One change of the symbolic state and the motion that made it: a transition."""

    before: State
    after: State
    samples: tuple[Sample, ...]  # from the segment's start up to the sample where ``after`` began

    @property
    def start_time(self) -> float:
        return self.samples[0].time

    @property
    def end_time(self) -> float:
        return self.samples[-1].time

    def joined(self, later: Segment) -> Segment:
        """This segment followed by ``later`` as one: from this one's state to the later one's."""
        return Segment(self.before, later.after, self.samples + later.samples[1:])


class Segmenter:
    """Turns a stream of samples into segments, one per debounced change of state."""

    def __init__(self, hold: float = HOLD_SECONDS):
        if not hold >= 0:
            raise TeachError(f"the hold time must be a non-negative number of seconds, got {hold!r}")
        self.hold = hold
        self.segments: list[Segment] = []
        self._samples: list[Sample] = []      # since the current segment began
        self._stable: State | None = None
        self._candidate = -1                  # index in _samples where an unconfirmed new state began

    def add(self, sample: Sample) -> Segment | None:
        """Take the next sample; the segment it completes, if the change it confirms is one."""
        samples = self._samples
        samples.append(sample)
        if self._stable is None:
            self._stable = sample.state
            return None
        if sample.state == self._stable:
            self._candidate = -1
            return None
        if self._candidate < 0 or samples[self._candidate].state != sample.state:
            self._candidate = len(samples) - 1
        if sample.time - samples[self._candidate].time + 1e-9 < self.hold:
            return None
        start = self._candidate
        segment = Segment(self._stable, sample.state, tuple(samples[: start + 1]))
        self.segments.append(segment)
        self._stable = sample.state
        self._samples = samples[start:]
        self._candidate = -1
        return segment

    def finish(self) -> Segment | None:
        """End of guidance: a change still within its hold time counts, as the robot ends in it
        (a wobble the teacher stopped in the middle of is not undone by anyone)."""
        samples = self._samples
        if self._stable is None or self._candidate < 0 or samples[-1].state != samples[self._candidate].state:
            return None
        segment = Segment(self._stable, samples[-1].state, tuple(samples[: self._candidate + 1]))
        self.segments.append(segment)
        self._stable, self._samples, self._candidate = segment.after, samples[self._candidate:], -1
        return segment

    def tail(self) -> tuple[Sample, ...]:
        """The motion after the last confirmed change (a pending, unconfirmed change included)."""
        return tuple(self._samples)


def segment(samples: Iterable[Sample], hold: float = HOLD_SECONDS) -> list[Segment]:
    """All segments of a finished recording, the state it ends in included."""
    segmenter = Segmenter(hold)
    for sample in samples:
        segmenter.add(sample)
    segmenter.finish()
    return segmenter.segments


def join_all(segments: Sequence[Segment]) -> Segment:
    """Consecutive segments as one."""
    whole = segments[0]
    for later in segments[1:]:
        whole = whole.joined(later)
    return whole


def explain_segments(domain: Domain, segments: Sequence[Segment], effects: Effects | None = None,
                     preconditions: Effects | None = None) -> list[tuple[Segment, Recognition]]:
    """Each guided action: its (possibly joined) segment and what it was recognised as."""
    groups = explain(domain, [(s.before, s.after) for s in segments], effects, preconditions)
    return [(join_all(segments[group.start:group.stop]), recognition) for group, recognition in groups]


def guided_demonstration(domain: Domain, labelled: Sequence[tuple[Segment, str]], final: State,
                         name: str = "demo") -> Demonstration:
    """The labelled segments as CSV lines (one per segment, by action name), then the goal line
    when the domain's goal holds in ``final``, as ``Recorder.done`` writes a named-skill one."""
    steps = [Step(seg.before, domain.action(label).id, number) for number, (seg, label) in enumerate(labelled, 1)]
    if domain.goal_holds(final):
        steps.append(Step(final, GOAL_ACTION, len(steps) + 1))
    return Demonstration(name, tuple(steps))
