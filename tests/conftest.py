"""Shared fixtures: the ball-in-bin domain and small trees built from it."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from teach import evaluate
from teach.bt.nodes import Node
from teach.domain import Domain, load_domain
from teach.session.journal import Journal

ROOT = Path(__file__).resolve().parent.parent
BALL_DOMAIN = ROOT / "demos" / "ball" / "domain.toml"


@pytest.fixture(scope="session")
def ball() -> Domain:
    return load_domain(BALL_DOMAIN)


def journal_data(path: Path) -> dict[str, Any]:
    """A session journal file as one JSON object (its snapshot with every later save applied),
    read as a resume reads it."""
    return Journal.from_bytes(path.read_bytes(), path).to_json()


def colledanchise_tree() -> Node:
    """Fig. 2.5 without AskForHelp: the 16-node reference tree of Colledanchise & Ögren."""
    return evaluate.colledanchise_tree(load_domain(BALL_DOMAIN))
