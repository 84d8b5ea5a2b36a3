"""Shared fixtures: the ball-in-bin domain and small trees built from it."""

from __future__ import annotations

from pathlib import Path

import pytest

from teach.bt.nodes import Action, Condition, Fallback, Node, Sequence
from teach.domain import Domain, load_domain

ROOT = Path(__file__).resolve().parent.parent
BALL_DOMAIN = ROOT / "demos" / "ball" / "domain.toml"


@pytest.fixture(scope="session")
def ball() -> Domain:
    return load_domain(BALL_DOMAIN)


def colledanchise_tree() -> Node:
    """Fig. 2.5 without AskForHelp: the 16-node reference tree of Colledanchise & Ögren."""
    def pair(condition: str, action: str) -> Node:
        return Fallback((Condition(condition), Action(action)))

    return Sequence((pair("BallFound", "FindBall"), pair("BallClose", "ApproachBall"),
                     pair("BallGrasped", "GraspBall"), pair("BinClose", "ApproachBin"),
                     pair("BallPlaced", "PlaceBall")))
