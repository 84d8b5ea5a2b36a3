"""Teacher language: English and German phrases, several per line, suggestions for unknown words."""

from __future__ import annotations

import pytest

from teach.dialogue.completion import complete
from teach.dialogue.phrases import PhraseBook, UnknownPhrase

EVENTS = {"knock_ball": (("knock the ball away",), ("den Ball wegstoßen",))}


@pytest.fixture()
def book(ball):
    return PhraseBook(ball, EVENTS)


def test_german_sentence_is_five_actions(book):
    tokens = book.parse("Ball finden, zum Ball gehen, Ball greifen, zum Eimer gehen, Ball in den Eimer legen", "de")
    assert [t.name for t in tokens] == ["FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall"]


def test_english_with_and_then_and_without_separators(book):
    tokens = book.parse("find the ball and then go to the ball grasp the ball")
    assert [t.name for t in tokens] == ["FindBall", "ApproachBall", "GraspBall"]


def test_events_and_action_names(book):
    assert [t.kind for t in book.parse("den Ball wegstossen, PlaceBall", "de")] == ["event", "action"]


def test_small_typo_is_understood(book):
    assert [t.name for t in book.parse("grasp teh ball")] == ["GraspBall"]


def test_unknown_words_get_a_suggestion(book):
    with pytest.raises(UnknownPhrase) as info:
        book.parse("Ball greifen und werfen", "de")
    assert info.value.text == "werfen"
    with pytest.raises(UnknownPhrase) as info:
        book.parse("go to the bucket")
    assert "Did you mean" in str(info.value)


def test_completion_is_a_pure_function():
    phrases = ["find the ball", "go to the ball", "go to the bin"]
    assert complete("go to the b", ["help"], phrases) == ["go to the ball", "go to the bin"]
    assert complete("he", ["help", "hello"], phrases) == ["help", "hello"]
    # after a comma only phrases are offered
    assert complete("find the ball, go", ["go"], phrases) == ["go to the ball", "go to the bin"]
