"""Learners that turn demonstrations into behaviour trees (thesis §4)."""
