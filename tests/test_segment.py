"""Segmentation of guided motion: debounced changes of state become segments."""

from __future__ import annotations

from collections.abc import Sequence

import pytest

from teach.demos import format_demonstration
from teach.domain import Domain, State
from teach.errors import DomainError, TeachError
from teach.sim.guide import Sample
from teach.sim.segment import Segmenter, guided_demonstration, join_all, segment

A, B, C = (False, False), (True, False), (True, True)


def samples(states: Sequence[State], period: float = 0.02) -> list[Sample]:
    """A stream of samples 20 ms apart with the given states (poses are irrelevant here)."""
    zero = (0.0, 0.0, 0.0)
    return [Sample(i * period, state, zero, 0.0, 0.0, zero, zero, (0.0, 0.0, 0.0, 0.0))
            for i, state in enumerate(states)]


def test_a_held_change_makes_a_segment_that_ends_where_it_began() -> None:
    stream = samples([A] * 10 + [B] * 20)
    found = segment(stream, hold=0.3)
    assert len(found) == 1
    only = found[0]
    assert (only.before, only.after) == (A, B)
    # the segment runs from the start to the first sample of the new state
    assert only.samples[0] is stream[0] and only.samples[-1] is stream[10]
    assert (only.start_time, only.end_time) == (0.0, stream[10].time)


def test_a_glimpse_shorter_than_the_hold_makes_no_step() -> None:
    # B for 0.28 s, then back to A: a sweep past the bin, not a change
    assert segment(samples([A] * 10 + [B] * 14 + [A] * 30), hold=0.3) == []
    # the same glimpse with no debouncing is two changes
    assert [(s.before, s.after) for s in segment(samples([A] * 10 + [B] * 14 + [A] * 30), hold=0.0)] == \
        [(A, B), (B, A)]


def test_a_flicker_on_the_way_restarts_the_wait() -> None:
    # A, then B flickering with A, then B for good: one change, starting where B settled
    stream = samples([A] * 5 + [B, A, B, A] + [B] * 20)
    found = segment(stream, hold=0.3)
    assert [(s.before, s.after) for s in found] == [(A, B)]
    assert found[0].samples[-1] is stream[9]


def test_two_quick_changes_are_one_step() -> None:
    # B lasts 0.1 s before C: the change that holds is A -> C
    found = segment(samples([A] * 5 + [B] * 5 + [C] * 20), hold=0.3)
    assert [(s.before, s.after) for s in found] == [(A, C)]


def test_online_segments_and_tail() -> None:
    stream = samples([A] * 5 + [B] * 20 + [C] * 20 + [A] * 3)
    segmenter = Segmenter(hold=0.3)
    confirmed = [s for s in map(segmenter.add, stream) if s is not None]
    assert [(s.before, s.after) for s in confirmed] == [(A, B), (B, C)]
    assert segmenter.segments == confirmed
    # after the last confirmed change: C held, then an unconfirmed flip back to A
    assert segmenter.tail()[0] is stream[25] and segmenter.tail()[-1] is stream[-1]
    whole = join_all(confirmed)
    assert (whole.before, whole.after) == (A, C) and whole.samples == tuple(stream[:26])


def test_the_end_of_guidance_confirms_the_state_it_ends_in() -> None:
    stream = samples([A] * 10 + [B] * 5)  # B for 0.08 s when the teacher says done
    segmenter = Segmenter(hold=0.3)
    for sample in stream:
        assert segmenter.add(sample) is None
    ended = segmenter.finish()
    assert ended is not None and (ended.before, ended.after) == (A, B) and ended.samples[-1] is stream[10]
    assert segmenter.finish() is None and segmenter.segments == [ended]
    # ending back where it was: the flicker is no change
    assert segment(samples([A] * 10 + [B] * 5 + [A] * 2)) == []


def test_the_hold_must_be_a_duration() -> None:
    with pytest.raises(TeachError, match="hold time"):
        Segmenter(hold=-1.0)


def test_labelled_segments_become_csv_lines(ball: Domain) -> None:
    s = ball.state
    stream = samples([s([])] * 5 + [s(["BallFound"])] * 20 + [s(["BallFound", "BallClose"])] * 20)
    found = segment(stream)
    demo = guided_demonstration(ball, [(found[0], "FindBall"), (found[1], "ApproachBall")], stream[-1].state)
    assert format_demonstration(demo) == "0;0;0;0;0;1\n1;0;0;0;0;2\n"  # no goal line: the ball is not in the bin
    with pytest.raises(DomainError, match="Dance"):
        guided_demonstration(ball, [(found[0], "Dance")], stream[-1].state)
