"""Words mean one thing: a phrase names one action or one event, never both and never two of
them, in every domain file and the worlds' event tables; the words of commands that undo,
finish or skip say so in both languages (issue 21)."""

from __future__ import annotations

from collections import defaultdict

import pytest
from conftest import ROOT

from teach.dialogue.phrases import PhraseBook
from teach.domain import load_domain
from teach.sim.perturb import PERTURBATIONS
from teach.world.hidden import load_world, world_file
from teach.world.symbolic import SymbolicWorld

DOMAIN_FILES = sorted([*ROOT.glob("demos/*/domain.toml"), *ROOT.glob("dialogues/study/*.toml"),
                       ROOT / "demos/ball/reference/table41.toml", ROOT / "teach/sim/assets/ball_in_bin.toml"])


def _events(path):
    """Every event table a world for this domain can have: its world.toml's, MuJoCo's perturbations
    (a ball domain) and the plain symbolic world's."""
    domain = load_domain(path)
    tables = [SymbolicWorld.events]
    found = world_file(domain)
    if found is not None:
        tables.append({e.name: (e.en, e.de) for e in load_world(found, domain).events})
    if "BallGrasped" in domain.condition_names:
        tables.append({name: (p.en, p.de) for name, p in PERTURBATIONS.items()})
    return domain, tables


@pytest.mark.parametrize("path", DOMAIN_FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_each_phrase_names_one_action_or_one_event(path):
    domain, tables = _events(path)
    for events in tables:
        key = PhraseBook(domain, events).key  # as the session reads a line (block "a" is kept)
        meanings: dict[tuple[str, ...], set[str]] = defaultdict(set)
        for action in domain.actions:
            for phrase in action.said():
                meanings[key(phrase)].add(f"action {action.name}")
        for name, (english, german) in events.items():
            for phrase in (*english, *german):
                meanings[key(phrase)].add(f"event {name}")
        twice = {" ".join(key): sorted(names) for key, names in meanings.items() if len(names) > 1}
        assert twice == {}

