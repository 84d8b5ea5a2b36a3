"""The teaching dialogue: phrases, questions, the session manager and its two front-ends."""
