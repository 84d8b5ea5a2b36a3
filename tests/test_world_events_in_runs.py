"""Every world records its outside events (issue 21, item 6): in a snacks run the person who
walks away is shown ("Event: the person walks away.") and is an external step (-1) of the
correction the stopped run begins, on disk and in the demonstration learned from it."""

from __future__ import annotations

from conftest import ROOT

from teach.demos import read_demo_set
from teach.domain import EXTERNAL_ACTION, load_domain
from teach.session.machine import SessionManager
from teach.session.settings import Settings
from teach.world.hidden import symbolic_world

SNACKS = ROOT / "demos" / "snacks" / "domain.toml"


def snacks_session(tmp_path, lang="en"):
    domain = load_domain(SNACKS)
    settings = Settings("events", lang=lang, questions=0, base=tmp_path, world="symbolic", record=False)
    manager = SessionManager(settings, domain, symbolic_world(domain, seed=0))
    _, demos = read_demo_set(ROOT / "demos" / "snacks" / "train", domain)
    manager.import_demonstrations(demos)
    return manager


def test_a_snacks_run_shows_the_person_walking_away_and_records_it_as_an_external_step(tmp_path):
    manager = snacks_session(tmp_path)
    for seed in range(60):  # the person walks away with probability 0.1 after each action
        manager.handle(f"reset {seed}")
        said = [r.text for r in manager.handle("run 3")]  # stopped after 3 actions: a correction opens
        if "Event: the person walks away." in said and manager.open is not None:
            break
        manager.handle("cancel")
    else:
        raise AssertionError("no stopped run of 60 had the person walk away")
    steps = manager.open.steps
    leaves = [i for i, step in enumerate(steps) if step.action == EXTERNAL_ACTION]
    assert leaves, [s.action for s in steps]
    partner = manager.domain.index("PartnerFound")
    assert steps[leaves[0]].state[partner]  # before it someone was there to talk to
    after = steps[leaves[0] + 1].state if leaves[0] + 1 < len(steps) else manager.world.state()
    assert not after[partner]  # ... and after it nobody was
    # on disk before the teacher heard of it: a resume reopens it with the -1 step
    journal = manager.store.load_journal()
    assert EXTERNAL_ACTION in [int(action) for _, action, _ in journal.open_steps]
    assert "something happened: the person walks away" in manager.cmd_steps("")[0].text


def test_the_event_is_said_in_german_too(tmp_path):
    manager = snacks_session(tmp_path, "de")
    for seed in range(60):
        manager.handle(f"neu {seed}")
        said = [r.text for r in manager.handle("los 3")]
        if "Ereignis: die Person geht weg." in said:
            return
        manager.handle("abbrechen")
    raise AssertionError("no run of 60 had the person walk away")


def test_a_domain_the_mujoco_world_cannot_compute_is_taught_in_the_symbolic_world(tmp_path):
    from teach.session.settings import WorldKind
    from teach.session.setup import opened_session

    notes: list[str] = []
    settings = Settings("auto", domain=SNACKS, world="mujoco", base=tmp_path, record=False)
    with opened_session(settings, note=notes.append) as manager:
        assert manager.settings.world is WorldKind.SYMBOLIC and manager.journal.world == "symbolic"
    assert notes == ["the MuJoCo world cannot tell whether “a caregiver has asked me to offer snacks”: this session "
                     "uses the symbolic world (--world symbolic)"]
