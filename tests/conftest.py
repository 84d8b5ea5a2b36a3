"""Shared fixtures: the ball-in-bin domain and small trees built from it."""

from __future__ import annotations

from pathlib import Path

import pytest

from teach import evaluate
from teach.bt.nodes import Node
from teach.domain import Domain, load_domain

ROOT = Path(__file__).resolve().parent.parent
BALL_DOMAIN = ROOT / "demos" / "ball" / "domain.toml"


@pytest.fixture(scope="session")
def ball() -> Domain:
    return load_domain(BALL_DOMAIN)


def colledanchise_tree() -> Node:
    """Fig. 2.5 without AskForHelp: the 16-node reference tree of Colledanchise & Ögren."""
    return evaluate.colledanchise_tree(load_domain(BALL_DOMAIN))
