"""Use Case 2 (snacks and drinks, thesis §3.2.2): the data, its reference tree and its dialogues."""

from __future__ import annotations

import importlib.util
import itertools
from pathlib import Path
from types import ModuleType
from typing import cast

import pytest
from btcpp import assert_matches_btcpp
from conftest import ROOT

from teach import messages as m
from teach.bt.nodes import Node
from teach.bt.xml import read_tree
from teach.demos import Demonstration, read_demo_set
from teach.dialogue.phrases import PhraseBook, UnknownPhrase
from teach.dialogue.script import read_script
from teach.domain import EXTERNAL_ACTION, Domain, load_domain
from teach.messages import Lang
from teach.replay import replay
from teach.session.machine import SessionManager
from teach.session.settings import Settings
from teach.world.hidden import HiddenStateWorld, load_world
from teach.world.protocol import TeachingWorld

SNACKS = ROOT / "demos" / "snacks"
DIALOGUES = [ROOT / "dialogues" / "snacks_en.dialogue", ROOT / "dialogues" / "snacks_de.dialogue"]


def _generator() -> ModuleType:
    spec = importlib.util.spec_from_file_location("snacks_generate", SNACKS / "generate.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def domain() -> Domain:
    return load_domain(SNACKS / "domain.toml")


@pytest.fixture(scope="module")
def reference() -> Node:
    return read_tree(SNACKS / "reference" / "reference.xml")


@pytest.fixture(scope="module")
def sets(domain) -> dict[str, list[Demonstration]]:
    return {name: read_demo_set(SNACKS / name, domain)[1] for name in ("train", "heldout")}


def world(domain: Domain, seed: int = 0) -> HiddenStateWorld:
    return HiddenStateWorld(domain, load_world(SNACKS / "world.toml", domain), seed)


def session(name: str, domain: Domain, place: HiddenStateWorld, base: Path, lang: str = "en") -> SessionManager:
    """A real session in the hidden-state world."""
    settings = Settings(name, lang=lang, base=base, world="symbolic", record=False)
    return SessionManager(settings, domain, cast(TeachingWorld, place))


def test_the_generator_writes_the_committed_files_byte_for_byte(tmp_path):
    assert _generator().main([str(tmp_path)]) == 0
    written = {p.relative_to(tmp_path): p.read_bytes() for p in sorted(tmp_path.rglob("*")) if p.is_file()}
    committed = {p.relative_to(SNACKS): p.read_bytes() for folder in ("train", "heldout", "reference")
                 for p in sorted((SNACKS / folder).rglob("*")) if p.is_file()}
    assert written == committed
    assert len([p for p in written if p.parts[0] == "train"]) == 11


def test_the_reference_tree_is_the_generators_and_loads_in_behaviortree_cpp(domain, reference):
    assert reference == _generator().reference_tree()
    assert_matches_btcpp(reference, domain)


@pytest.mark.parametrize("folder", ["train", "heldout"])
def test_the_reference_tree_replays_every_demonstration_strictly(domain, reference, sets, folder):
    report = replay(reference, domain, sets[folder])
    assert report.reproduced == report.total, [r for r in report.results if not r.reproduced]


def test_training_has_repeats_both_orders_and_events(domain, sets):
    train = sets["train"]
    assert all(demo.reached_goal for demo in train)
    repeated = [demo.name for demo in train if any(demo.actions.count(a) > 1 for a in set(demo.actions))]
    assert len(repeated) >= 7
    with_events = [demo for demo in train if any(step.action == EXTERNAL_ACTION for step in demo.steps)]
    assert len(with_events) >= 5

    def somewhere_before(demo: Demonstration, a: str, b: str) -> bool:
        ids = demo.actions
        first = ids.index(domain.action(a).id) if domain.action(a).id in ids else len(ids)
        return domain.action(b).id in ids[first + 1:]

    # each of these pairs appears in both orders (no single action order holds them all)
    for a, b in (("WaitForRequest", "TakeTray"), ("WaitForRequest", "FindPartner"), ("TakeTray", "OfferSnack")):
        assert any(somewhere_before(d, a, b) for d in train) and any(somewhere_before(d, b, a) for d in train), (a, b)
    # every kind of event the world knows is shown once at least, told apart by what it changed
    changed = {tuple((domain.conditions[i].name, y) for i, (x, y) in enumerate(zip(s.state, t.state, strict=True))
                     if x != y)
               for demo in with_events for s, t in itertools.pairwise(demo.steps) if s.action == EXTERNAL_ACTION}
    assert changed == {(("Requested", False),), (("Requested", True),), (("TrayTaken", False),),
                       (("TrayEmpty", True),), (("PartnerFound", False),)}

def test_heldout_starts_in_every_other_state(domain, sets):
    starts = [demo.steps[0].state for demo in sets["train"] + sets["heldout"]]
    everything = set(itertools.product((False, True), repeat=len(domain.conditions)))
    assert set(starts) == everything
    assert len(set(d.steps[0].state for d in sets["heldout"])) == len(sets["heldout"]) == 32 - len(
        {d.steps[0].state for d in sets["train"]})


def test_the_reference_tree_reaches_the_goal_from_every_start_in_the_hidden_state_world(domain, reference):
    runs = 0
    for index, state in enumerate(itertools.product((False, True), repeat=len(domain.conditions))):
        empty = state[domain.index("TrayEmpty")]
        for snacks in (0,) if empty else (1, 2, 3):
            for seed in range(4):  # events happen in the runs: requests withdrawn, people leaving, ...
                place = world(domain, seed=1000 * index + seed)
                place.arrange(state, {"snacks": snacks})
                run = place.run(reference, max_actions=60)
                assert run.outcome == "success", (domain.describe(state), snacks, seed, run)
                assert all(domain.holds(goal, run.final_state) for goal in domain.goal)
                runs += 1
    assert runs == 4 * (16 * 3 + 16)


def test_every_phrase_names_its_action_or_event_and_is_no_command(domain, tmp_path):
    place = world(domain)
    book = PhraseBook(domain, place.events)
    manager = session("phrases", domain, place, tmp_path)
    named = [(a.name, lang, phrase) for a in domain.actions for lang in ("en", "de") for phrase in getattr(a, lang)]
    named += [(name, lang, phrase) for name, (en, de) in place.events.items()
              for lang, phrases in (("en", en), ("de", de)) for phrase in phrases]
    for name, lang, phrase in named:
        assert manager.command(phrase)[0] is None, phrase
        assert [token.name for token in book.parse(phrase, lang)] == [name], phrase


def walk_dialogue(path: Path, tree: Node, tmp_path: Path) -> list[str]:
    """Do in the hidden-state world what the session would do for each line of a dialogue, with
    ``tree`` standing in for what the robot has learned; returns the problems found."""
    script = read_script(path)
    assert script.settings["world"] == "symbolic" and script.settings["domain"] == "demos/snacks/domain.toml"
    domain = load_domain(ROOT / str(script.settings["domain"]))
    lang = str(script.settings["lang"])
    place = world(domain, int(script.settings["seed"]))  # type: ignore[call-overload]
    manager = session(path.stem, domain, place, tmp_path, lang)
    problems, shown = [], 0
    for number, line in script.lines:
        command, rest = manager.command(line)
        name = command.names[0] if command is not None else "actions"
        if name == "start":
            place.arrange(domain.state(rest.split()))
        elif name == "reset":
            place.reset(int(rest) if rest.strip() else None)
        elif name == "done":
            if not shown or not all(domain.holds(goal, place.state()) for goal in domain.goal):
                problems.append(f"{number}: 'done' but the task is not finished: {domain.describe(place.state())}")
            shown = 0
        elif name == "run":
            result = place.run(tree, 4 * len(domain.actions) + 4, stop_after=int(rest) if rest.strip() else None)
            if not rest.strip() and result.outcome != "success":
                problems.append(f"{number}: the run ends with {result.outcome}")
            shown = len(result.steps)
        elif name in ("actions", "demonstrate", "perturb"):
            for token in manager.phrases.parse(rest, lang):
                done = place.perturb(token.name) if token.kind == "event" else place.act(token.name)
                if not done.ok or done.after == done.before:
                    problems.append(f"{number}: {token.text}: {done.message or 'changes nothing visible'}")
                shown += 1
        elif name not in ("show", "state", "why", "help", "save"):
            problems.append(f"{number}: unexpected command {line!r}")
    return problems


@pytest.mark.parametrize("path", DIALOGUES, ids=lambda p: p.stem)
def test_dialogues_teach_the_task_when_the_robot_learns_the_reference_behaviour(path, reference, tmp_path):
    assert walk_dialogue(path, reference, tmp_path) == []


@pytest.mark.parametrize("path", DIALOGUES, ids=lambda p: p.stem)
def test_dialogues_show_repeats_events_runs_and_a_correction(path, domain, tmp_path):
    script = read_script(path)
    manager = session(path.stem, domain, world(domain), tmp_path)
    kinds = [manager.command(line) for _, line in script.lines]
    tokens = [token for command, rest in kinds if command is None
              for token in manager.phrases.parse(rest, str(script.settings["lang"]))]
    assert sum(1 for token in tokens if token.kind == "event") >= 3
    assert sum(1 for token in tokens if token.name == "OfferSnack") >= 8
    runs = [rest.strip() for command, rest in kinds if command is not None and command.names[0] == "run"]
    assert "" in runs and any(runs)  # a whole run, and one stopped early and corrected


def test_every_possible_action_changes_something_the_session_can_see(domain):
    # the session drops a step that changes no condition; here every action needs the negation
    # of one of its own visible effects, so whenever it can run it is recorded
    for action in domain.actions:
        assert any(literal.negated() in action.pre for literal in action.ram), action.name


@pytest.mark.parametrize(("lang", "line", "action"), [
    ("en", "wait until someone asks", "WaitForRequest"),  # was offered as "find someone"
    ("de", "warte auf eine Bitte", "WaitForRequest"),  # was offered as the bare "warte"
    ("en", "head back to the office", "ReturnToOffice"),
    ("de", "geh zurück ins Büro", "ReturnToOffice"),  # was unknown
    ("de", "biete einen Keks an", "OfferSnack"),  # was "Meintest du „biete etwas an“?"
    ("en", "offer them a cookie", "OfferSnack"),  # was "Did you mean “offer a snack”?"
])
def test_everyday_sayings_name_their_step(domain, lang, line, action):
    tokens = PhraseBook(domain).parse(line, lang)
    assert [(t.kind, t.name) for t in tokens] == [("action", action)]


@pytest.mark.parametrize(("lang", "line"), [("en", "ask if they want something"), ("de", "frag ob sie etwas möchten")])
def test_a_step_beginning_with_a_command_word_is_the_step(domain, tmp_path, lang, line):
    """ "ask if they want something" was 'ask' ("I have no question right now"): a line that is one
    of the domain's phrases is that step though its first word is a command that takes no words."""
    manager = session("asking", domain, world(domain), tmp_path, lang=lang)
    manager.handle("wait for a request, take the tray, find someone" if lang == "en"
                   else "warte, Tablett nehmen, such jemanden")
    manager.handle(line)
    assert manager.open is not None and domain.action(manager.open.steps[-1].action).name == "OfferSnack"
    assert manager.handle("ask" if lang == "en" else "frag")[0].text == m.NO_QUESTION_NOW(Lang(lang))


def test_an_event_that_cannot_happen_now_is_not_recorded(domain, tmp_path):
    """ "someone takes a snack" with no tray carried was "Event: someone takes a snack." and written
    into the demonstration as something that happened, though the world refused it."""
    manager = session("events", domain, world(domain), tmp_path)
    replies = manager.handle("someone takes a snack")
    assert [r.kind.name for r in replies] == ["ERROR", "STATE"] and "cannot happen now" in replies[0].text
    assert manager.open is None
    manager.handle("wait for a request, take the tray")
    assert [r.kind.name for r in manager.handle("someone takes a snack")][0] == "INFO"
    assert manager.open is not None and manager.open.steps[-1].action == EXTERNAL_ACTION


@pytest.mark.parametrize(("line", "event"), [("she walked away", "partner_leaves"),
                                             ("the person left", "partner_leaves"), ("he left", "partner_leaves"),
                                             ("someone took a snack", "snack_taken"),
                                             ("she took one", "snack_taken"),
                                             ("jemand hat sich gerade einen Snack genommen", "snack_taken")])
def test_an_event_reported_in_the_past_is_offered_and_happens_once_confirmed(domain, tmp_path, line, event):
    """ "she walked away" was "Did you mean 'they walk away'?" only by chance of spelling, "he took a
    snack" unknown: a report of an event is offered as that event (never run on a guess: "hid
    ball" may be a slip of "hide ball"), and a yes makes it happen."""
    manager = session("reports", domain, world(domain), tmp_path)
    manager.handle("wait for a request, take the tray, find someone")
    replies = manager.handle(line)
    assert [r.kind.name for r in replies] == ["ERROR"] and "Did you mean" in replies[0].text
    assert manager.suggestion is not None and manager.suggestion.candidate.name == event
    steps = len(manager.open.steps)
    manager.handle("yes")
    assert len(manager.open.steps) == steps + 1 and manager.open.steps[-1].action == EXTERNAL_ACTION


def test_a_report_two_phrases_share_is_no_reading(domain, tmp_path):
    """ "someone took the tray" reports "take the tray" (an action) and "someone takes the tray" (an
    event) alike: it is not read as the step (only offered, as the near spelling of the event)."""
    manager = session("shared", domain, world(domain), tmp_path)
    with pytest.raises(UnknownPhrase):
        manager.phrases.parse("someone took the tray", "en")


def test_what_is_not_done_yet_is_said_as_a_list(domain, tmp_path):
    """ "is it done?" was "Not yet: I am not carrying the tray and the tray is not empty yet and I am
    away from the office."; "sie hat sich einen genommen" was not known."""
    manager = session("done-yet", domain, world(domain), tmp_path)
    manager.handle("find someone")
    assert manager.handle("is it done?")[0].text == ("Not yet: I am not carrying the tray, the tray is not empty yet "
                                                     "and I am away from the office.")
    german = session("events-de", domain, world(domain), tmp_path, "de")
    german.handle("warte, Tablett nehmen, such jemanden")
    assert german.handle("sie hat sich einen genommen")[0].text == "Ereignis: sie hat sich einen genommen."


def test_offering_with_nobody_there_is_refused_not_already_done(domain, tmp_path):
    """ "offer a snack" after the person had left was "– offer a snack: nobody is there to talk to
    already (nothing to do, not recorded)": the person leaving is what offering costs, not what it
    is for. It is refused with what it needs; a second "find someone" is still already so."""
    manager = session("offer-again", domain, world(domain), tmp_path)
    manager.handle("wait for a request, take the tray, find someone, offer a snack")
    said = [r.text for r in manager.handle("offer a snack")]
    assert said[0].startswith("I could not offer a snack: first this must be true:") and "already" not in said[0]
    manager.handle("find someone")
    assert manager.handle("find someone")[0].text.startswith("– find someone: someone is there to talk to")


def test_bringing_the_tray_back_needs_the_tray(domain, tmp_path):
    """ "bring the tray back" with no tray went back to the office and taught "go back" there."""
    manager = session("tray-back", domain, world(domain), tmp_path)
    manager.handle("find someone")
    said = [r.text for r in manager.handle("bring the tray back")]
    assert said[0] == "“bring the tray back”: first this must be true: I am carrying the tray"
    assert manager.open is not None and [s.action for s in manager.open.steps] == [3]
    german = session("tray-back-de", domain, world(domain), tmp_path, "de")
    german.handle("warte, Tablett nehmen, such jemanden")
    assert german.handle("bring das Tablett zurück")[0].text == "✓ ins Büro zurückfahren"


@pytest.mark.parametrize(("lang", "lines", "steps"), [
    ("en", ["wait for a request, take the tray", "go to the residents", "ask if anyone wants a cookie"], [1, 2, 3, 4]),
    ("de", ["warte, Tablett nehmen", "geh zu den Leuten", "frag ob jemand einen Keks will"], [1, 2, 3, 4])])
def test_asking_someone_is_offering_not_the_ask_command(domain, tmp_path, lang, lines, steps):
    """ "frag ob jemand einen Keks will" was the command 'frag' ("Ich habe gerade keine Frage"), and
    "geh zu den Leuten" was not known."""
    manager = session(f"ask-{lang}", domain, world(domain), tmp_path, lang)
    for line in lines:
        manager.handle(line)
    assert manager.open is not None and [s.action for s in manager.open.steps] == steps
    said = manager.handle("ask whether she wants a drink" if lang == "en" else "frag ob sie Tee will")[0].text
    assert "question" not in said and "Frage" not in said  # the step offered or not known, never 'ask'
