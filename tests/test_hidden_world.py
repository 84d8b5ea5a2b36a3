"""The hidden-state world (teach/world/hidden.py): variables, derived conditions, effects, events."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import BALL_DOMAIN, ROOT

from teach.bt.nodes import Action, Condition, Fallback, Sequence
from teach.domain import Domain, Literal, load_domain
from teach.errors import DomainError, FormatError
from teach.world.hidden import HiddenStateWorld, load_world, symbolic_world
from teach.world.symbolic import SymbolicWorld

SNACKS = ROOT / "demos" / "snacks"

# A small domain that is not the snacks task: wash the dishes in the sink until none are left.
DISHES_DOMAIN = """\
name = "dishes"
goal = ["SinkEmpty"]

[[condition]]
name = "AtSink"

[[condition]]
name = "SinkEmpty"

[[condition]]
name = "TapOpen"

[[action]]
id = 1
name = "GoToSink"
pre = ["!AtSink"]
ram = ["AtSink"]

[[action]]
id = 2
name = "WashDish"
pre = ["AtSink", "!SinkEmpty"]
"""

DISHES_WORLD = """\
start = ["TapOpen"]

[[variable]]
name = "dishes"
min = 0
max = 9
start = [2, 4]

[[derived]]
condition = "SinkEmpty"
when = "dishes <= 0"

[[effect]]
action = "WashDish"
add = { dishes = -1 }

[[event]]
name = "more_dishes"
en = ["someone brings more dishes"]
de = ["jemand bringt mehr Geschirr"]
add = { dishes = 1 }
probability = {probability}
"""


def dishes(tmp_path: Path, probability: float = 0.0, world: str | None = None) -> tuple[Domain, Path]:
    (tmp_path / "domain.toml").write_text(DISHES_DOMAIN)
    text = DISHES_WORLD.replace("{probability}", str(probability)) if world is None else world
    (tmp_path / "world.toml").write_text(text)
    return load_domain(tmp_path / "domain.toml"), tmp_path / "world.toml"


def wash_until_empty() -> Sequence:
    return Sequence((Fallback((Condition("AtSink"), Action("GoToSink"))),
                     Fallback((Condition("SinkEmpty"), Action("WashDish")))))


@pytest.fixture(scope="module")
def snacks() -> tuple[Domain, HiddenStateWorld]:
    domain = load_domain(SNACKS / "domain.toml")
    return domain, HiddenStateWorld(domain, load_world(SNACKS / "world.toml", domain))


def test_a_derived_condition_follows_its_variable(tmp_path):
    domain, path = dishes(tmp_path)
    world = HiddenStateWorld(domain, load_world(path, domain))
    world.arrange(domain.state(["AtSink"]), {"dishes": 2})
    # washing changes nothing visible until the last dish is done
    first = world.act("WashDish")
    assert first.ok and first.after == first.before and world.hidden() == {"dishes": 1}
    last = world.act("WashDish")
    assert last.ok and world.state() == domain.state(["AtSink", "SinkEmpty"]) and world.hidden() == {"dishes": 0}
    # the domain's visible precondition (!SinkEmpty) now forbids washing
    refused = world.act("WashDish")
    assert not refused.ok and "!SinkEmpty" in refused.message and world.hidden() == {"dishes": 0}


def test_every_snack_offer_is_visible_and_only_the_last_empties_the_tray(snacks):
    domain, world = snacks
    world.arrange(domain.state(["Requested", "TrayTaken", "PartnerFound"]), {"snacks": 2})
    offer = world.act("OfferSnack")
    assert offer.ok and offer.after != offer.before  # the partner takes one and leaves
    assert world.state() == domain.state(["Requested", "TrayTaken"]) and world.hidden() == {"snacks": 1}
    world.act("FindPartner")
    world.act("OfferSnack")
    assert world.state() == domain.state(["Requested", "TrayTaken", "TrayEmpty"])


def test_taking_a_tray_fills_it_from_the_seeded_generator(snacks):
    domain, world = snacks
    fills = []
    for seed in range(20):
        world.reset(seed)
        world.arrange(domain.state(["Requested"]))
        world.act("TakeTray")
        fills.append(world.hidden()["snacks"])
    assert set(fills) == {1, 2, 3}
    again = []
    for seed in range(20):
        world.reset(seed)
        world.arrange(domain.state(["Requested"]))
        world.act("TakeTray")
        again.append(world.hidden()["snacks"])
    assert again == fills


def test_events_change_visible_and_hidden_state_only_when_possible(snacks):
    domain, world = snacks
    world.arrange(domain.state(["Requested", "TrayTaken"]), {"snacks": 1})
    taken = world.perturb("snack_taken")  # the thesis's case: the last snack goes unnoticed
    assert taken.ok and world.state() == domain.state(["Requested", "TrayTaken", "TrayEmpty"])
    impossible = world.perturb("snack_taken")
    assert not impossible.ok and impossible.after == impossible.before and "!TrayEmpty" in impossible.message
    withdrawn = world.perturb("request_withdrawn")
    assert withdrawn.ok and not domain.holds(Literal("Requested"), world.state())
    unknown = world.perturb("rain")
    assert not unknown.ok and "unknown event" in unknown.message
    assert set(world.events) == {"request_withdrawn", "new_request", "partner_leaves", "snack_taken", "tray_lost"}


def test_arrange_keeps_hidden_values_that_fit_and_replaces_those_that_do_not(snacks):
    domain, world = snacks
    world.arrange(domain.state(["TrayTaken"]), {"snacks": 3})
    world.arrange(domain.state(["TrayTaken", "Requested"]))
    assert world.hidden() == {"snacks": 3}
    world.arrange(domain.state(["TrayTaken", "TrayEmpty"]))
    assert world.hidden() == {"snacks": 0}
    world.arrange(domain.state(["TrayTaken"]))
    assert world.hidden()["snacks"] in (1, 2, 3)  # drawn from the start range
    with pytest.raises(DomainError, match="does not fit"):
        world.arrange(domain.state(["TrayEmpty"]), {"snacks": 2})
    with pytest.raises(DomainError, match="leaves its range"):
        world.arrange(domain.state([]), {"snacks": 7})
    with pytest.raises(DomainError, match="unknown hidden variable"):
        world.arrange(domain.state([]), {"cookies": 1})


def test_reset_is_the_declared_start_and_the_same_for_the_same_seed(snacks):
    domain, world = snacks
    starts = set()
    for seed in range(30):
        world.reset(seed)
        first = (world.state(), world.hidden()["snacks"])
        world.reset(seed)
        assert (world.state(), world.hidden()["snacks"]) == first
        starts.add(first[0])
        assert domain.holds(Literal("AtOffice"), first[0])  # it is in 'start'
    # Requested and TrayTaken are drawn; nothing else is true; the tray is never empty at a reset
    assert starts == {domain.state(s) for s in (["AtOffice"], ["Requested", "AtOffice"], ["TrayTaken", "AtOffice"],
                                                ["Requested", "TrayTaken", "AtOffice"])}


def test_runs_are_disturbed_by_events_and_repeat_for_the_same_seed(tmp_path):
    domain, path = dishes(tmp_path, probability=0.5)
    spec = load_world(path, domain)
    runs, at_start = [], []
    for _ in range(2):
        world = HiddenStateWorld(domain, spec, seed=3)
        at_start.append(world.hidden()["dishes"])
        runs.append(world.run(wash_until_empty(), max_actions=60))
    assert runs[0] == runs[1] and at_start[0] == at_start[1]
    run = runs[0]
    assert run.outcome == "success" and domain.holds(Literal("SinkEmpty"), run.final_state)
    # every dish brought during the run was washed too
    assert run.events and all(event.name == "more_dishes" for _, event in run.events)
    assert sum(1 for _, action in run.steps if action == "WashDish") == at_start[0] + len(run.events)


def test_runs_without_events_do_exactly_what_is_hidden(tmp_path):
    domain, path = dishes(tmp_path, probability=1.0)
    world = HiddenStateWorld(domain, load_world(path, domain), events_in_runs=False)
    world.arrange(domain.state([]), {"dishes": 3})
    run = world.run(wash_until_empty())
    assert run.outcome == "success" and run.events == []
    assert [action for _, action in run.steps] == ["GoToSink", "WashDish", "WashDish", "WashDish"]


def test_symbolic_world_has_hidden_state_only_where_a_world_file_says_so(snacks):
    domain, _ = snacks
    assert isinstance(symbolic_world(domain, 1), HiddenStateWorld)
    plain = symbolic_world(load_domain(BALL_DOMAIN), 1)
    assert isinstance(plain, SymbolicWorld) and not isinstance(plain, HiddenStateWorld)


BAD_WORLDS = [
    ("start = [\n", 1, "invalid TOML"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3 3\n", 4, "invalid TOML"),
    ("colour = 3\n", 1, "unknown key 'colour'"),
    ("start = [\"Nope\"]\n", 1, "unknown condition 'Nope'"),
    ("start = [\"SinkEmpty\"]\n[[variable]]\nname = \"d\"\nmin = 0\nmax = 1\n[[derived]]\ncondition = \"SinkEmpty\"\n"
     "when = \"d == 0\"\n", 1, "follows its variable"),
    ("[[variable]]\nname = \"d\"\nmin = 3\nmax = 1\n", 4, "'min' (3) is above 'max' (1)"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = \"many\"\n", 4, "'max' must be an integer"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3\nstart = [2, 5]\n", 5, "leaves [0, 3]"),
    ("[[variable]]\nname = \"AtSink\"\nmin = 0\nmax = 3\n", 2, "is taken already"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3\n[[derived]]\ncondition = \"SinkEmpty\"\nwhen = \"d ~ 0\"\n", 7,
     "'when' must read like"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3\n[[derived]]\ncondition = \"SinkEmpty\"\nwhen = \"e == 0\"\n", 7,
     "unknown variable 'e'"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3\n[[derived]]\ncondition = \"AtSink\"\nwhen = \"d == 0\"\n", 5,
     "action GoToSink sets it in its 'ram'"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3\n\n[[effect]]\naction = \"Fly\"\nadd = { d = 1 }\n", 7,
     "'action' must name an action"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3\n[[effect]]\naction = \"WashDish\"\nadd = { d = [1, 2] }\n", 7,
     "'add' needs an integer"),
    ("[[variable]]\nname = \"d\"\nmin = 0\nmax = 3\n[[effect]]\naction = \"WashDish\"\nset = { e = 1 }\n", 7,
     "unknown variable 'e'"),
    ("[[effect]]\naction = \"WashDish\"\n", 1, "changes nothing"),
    ("[[event]]\nname = \"e\"\nen = [\"e\"]\nde = [\"e\"]\nram = [\"AtSink\"]\nprobability = 2\n", 6,
     "'probability' must be a number from 0 to 1"),
    ("[[event]]\nname = \"e\"\nen = []\nde = [\"e\"]\nram = [\"AtSink\"]\n", 3, "'en' must be a list of phrases"),
    ("[[event]]\nname = \"e\"\nen = [\"e\"]\nde = [\"e\"]\npre = [\"Wet\"]\nram = [\"AtSink\"]\n", 5,
     "unknown condition 'Wet'"),
    ("[[event]]\nname = \"e\"\nen = [\"e\"]\nde = [\"e\"]\n", 1, "event e changes nothing"),
    ("variable = 3\n", 1, "must be written as [[variable]] tables"),
]


@pytest.mark.parametrize(("text", "line", "message"), BAD_WORLDS)
def test_bad_world_files_give_one_line_with_file_and_line(tmp_path, text, line, message):
    domain, path = dishes(tmp_path, world=text)
    with pytest.raises(FormatError) as error:
        load_world(path, domain)
    assert error.value.line == line and message in error.value.message, str(error.value)
    assert str(error.value).startswith(f"{path}:{line}: ") and "\n" not in str(error.value)

