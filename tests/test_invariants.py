"""Questions only about situations that can happen (issue 21, item 5): the world says which states
it can be in, and "that cannot happen" rules out the states that share its reason."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from conftest import ROOT

from teach.demos import read_demo_set
from teach.dialogue.oracle import oracle_from_tree
from teach.domain import load_domain
from teach.errors import DomainError
from teach.learn.inquiry import next_question
from teach.learn.invariants import Invariants
from teach.learn.learner import Learner, learn_online
from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.sim.world import World
from teach.world.hidden import HiddenStateWorld, load_world
from teach.world.offline import OfflineWorld
from teach.world.symbolic import SymbolicWorld

SNACKS = ROOT / "demos" / "snacks"
TABLE61 = ROOT / "demos" / "ball" / "reference" / "table61.xml"


def every_state(width: int) -> list[tuple[bool, ...]]:
    return list(itertools.product((False, True), repeat=width))


def arranges(arrange, state) -> bool:
    try:
        arrange(state)
    except DomainError:
        return False
    return True


def chain(ball) -> Learner:
    """One demonstration of the whole task from nothing: only the states along one chain seen."""
    _, demos = read_demo_set(ROOT / "demos" / "ball" / "delta2", ball)
    return learn_online(ball, [demos[0]])


def test_a_pair_never_seen_together_is_the_reason_and_rules_out_every_state_with_it():
    seen_states = {0b0011, 0b0101}
    invariants = Invariants(4)

    def seen(care: int, value: int) -> bool:
        return any(mask & care == value for mask in seen_states)

    invariants.rule_out(0b0111, "answer 1", seen)  # bits 1 and 2 never held together
    assert not invariants.possible(0b0111)
    assert not invariants.possible(0b1110)  # shares the pair
    assert invariants.possible(0b1011) and invariants.possible(0b0001)
    invariants.saw(0b0110)  # a demonstration shows the pair together: the reason was wrong
    assert invariants.possible(0b1110)
    assert not invariants.possible(0b0111)  # itself still said to be impossible


def test_that_cannot_happen_keeps_later_questions_off_the_states_sharing_its_reason(ball):
    learner = chain(ball)
    first = next_question(learner)
    assert first is not None
    mask = learner.state_mask(first.state)
    learner.rule_out(first.state, "answer 1")
    reasons = learner.invariants.nogoods
    assert reasons, "a state off the one chain seen has a pair of literals never seen together"
    for _ in range(8):
        question = next_question(learner, [first.state])
        if question is None:
            break
        probe = learner.state_mask(question.state)
        assert probe != mask and not any(reason.holds_in(probe) for reason in reasons)
        learner.rule_out(question.state, "answer")
        reasons = learner.invariants.nogoods


def test_the_mujoco_world_can_be_in_exactly_the_states_it_can_arrange():
    world = World(cameras=False)
    states = every_state(len(world.domain.conditions))
    assert [world.can_arrange(s) for s in states] == [arranges(world.arrange, s) for s in states]
    assert sum(map(world.can_arrange, states)) == 32 - 8 - 2  # in the bin and in the hand; near it, far from the bin


LEVELS_DOMAIN = """\
name = "levels"
goal = ["Done"]

[[condition]]
name = "Low"

[[condition]]
name = "High"

[[condition]]
name = "Done"

[[action]]
id = 1
name = "Fill"
pre = ["Low"]
ram = ["Done"]
"""
LEVELS_WORLD = """\
[[variable]]
name = "water"
min = 0
max = 10
start = [0, 10]

[[derived]]
condition = "Low"
when = "water < 3"

[[derived]]
condition = "High"
when = "water > 7"
"""


def levels(tmp_path: Path) -> HiddenStateWorld:
    """A hidden water level seen as two conditions that cannot both hold."""
    (tmp_path / "domain.toml").write_text(LEVELS_DOMAIN)
    (tmp_path / "world.toml").write_text(LEVELS_WORLD)
    domain = load_domain(tmp_path / "domain.toml")
    return HiddenStateWorld(domain, load_world(tmp_path / "world.toml", domain))


def test_the_hidden_world_can_be_in_exactly_the_states_it_can_arrange(tmp_path: Path):
    for world in (levels(tmp_path), snacks()):
        states = every_state(len(world.domain.conditions))
        assert [world.can_happen(s) for s in states] == [arranges(world.arrange, s) for s in states]
    assert not levels(tmp_path).can_happen((True, True, False))  # low and high at once


def snacks() -> HiddenStateWorld:
    domain = load_domain(SNACKS / "domain.toml")
    return HiddenStateWorld(domain, load_world(SNACKS / "world.toml", domain))


def test_no_question_is_about_a_state_the_mujoco_world_cannot_be_in(ball):
    world = World(cameras=False)
    oracle = oracle_from_tree(TABLE61, ball)
    _, demos = read_demo_set(ROOT / "demos" / "ball" / "delta2", ball)
    for pair in itertools.islice(itertools.combinations(demos, 2), 0, 60, 6):
        learner = learn_online(ball, list(pair))
        learner.invariants = Invariants(len(ball.conditions), world.can_arrange)
        asked: list = []
        for number in range(5):
            question = next_question(learner, asked)
            if question is None:
                break
            assert world.can_arrange(question.state), question
            asked.append(question.state)
            does = oracle.answer(question.state)
            about = question.action if question.kind == "must-precondition" else None
            if question.kind.startswith("must-"):
                learner.answer_question(question.state, about, does, f"question {number}")
            else:
                learner.teach_step(question.state, does, f"question {number}")


def test_a_session_asks_only_about_states_its_world_can_be_in(tmp_path: Path):
    world = levels(tmp_path)
    domain = world.domain
    settings = Settings("t", world=WorldKind.SYMBOLIC, base=tmp_path, record=False, safe=True)
    session = SessionManager(settings, domain, world)
    learner = session.learning.learner
    impossible = [s for s in every_state(len(domain.conditions)) if not world.can_happen(s)]
    assert impossible and not any(learner.possible(learner.state_mask(s)) for s in impossible)
    session.learning.restart()  # as an undo or a resume does: the new learner keeps the world's word
    assert not any(session.learning.learner.possible(learner.state_mask(s)) for s in impossible)


@pytest.mark.parametrize("world", ["symbolic", "offline"])
def test_a_world_of_conditions_only_can_be_in_every_state(ball, world):
    made = SymbolicWorld(ball) if world == "symbolic" else OfflineWorld(ball)
    assert all(made.can_happen(s) for s in every_state(len(ball.conditions)))


def test_only_states_whose_every_two_literals_were_seen_together_pass_in_a_large_domain():
    invariants = Invariants(3)
    for mask in (0b001, 0b010):  # the ferry is at one of two places: never both, never neither
        invariants.saw(mask)
    assert invariants.pairs_seen(0b001) and invariants.pairs_seen(0b010)
    assert not invariants.pairs_seen(0b011)  # at both places: never seen together
    assert not invariants.pairs_seen(0b000)  # at neither
    assert not invariants.pairs_seen(0b111)
    invariants.saw(0b011)
    assert invariants.pairs_seen(0b011)
