"""Parameterised actions (``form`` in domain.toml, ``teach.learn.lifting``): what one instance shows
is learned for its siblings, and only conditions about an action's own objects can be its
preconditions. Judged in the true blocksworld model (bench/foreign/pddl) from every reachable state."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "bench"))

from foreign import ipc  # noqa: E402
from foreign.judge import judge  # noqa: E402
from foreign.model import Task  # noqa: E402
from foreign.sam import SamLearner  # noqa: E402

from teach.demos import read_demo_set  # noqa: E402
from teach.domain import Domain, load_domain  # noqa: E402
from teach.errors import FormatError  # noqa: E402
from teach.learn.learner import learn_online  # noqa: E402
from teach.learn.lifting import lifting_of  # noqa: E402
from teach.replay import count_reproduced  # noqa: E402

BLOCKS = Path(__file__).resolve().parent.parent / "demos" / "blocksworld"


@pytest.fixture(scope="module")
def blocks() -> Task:
    return ipc.load("blocksworld")


def without_forms(domain: Domain) -> Domain:
    return dataclasses.replace(domain, conditions=tuple(dataclasses.replace(c, form=()) for c in domain.conditions),
                               actions=tuple(dataclasses.replace(a, form=()) for a in domain.actions))


def test_the_shipped_domain_declares_the_pddl_forms(blocks: Task) -> None:
    domain = load_domain(BLOCKS / "domain.toml")
    assert domain.condition_names == blocks.domain.condition_names
    assert domain.condition("on_a_b").form == ("on", "a", "b")
    assert domain.action("unstack_a_b").form == ("unstack", "a", "b")
    assert domain.condition("handempty").form == ("handempty",)


def test_a_renaming_maps_an_instance_onto_its_sibling(blocks: Task) -> None:
    lifting = lifting_of(blocks.domain)
    assert lifting is not None
    names = blocks.domain.condition_names
    own = {names[i] for i in range(len(names)) if lifting.own["unstack_a_b"] >> i & 1}
    assert own == {"clear_a", "clear_b", "handempty", "holding_a", "holding_b", "on_a_a", "on_a_b", "on_b_a",
                   "on_b_b", "ontable_a", "ontable_b"}
    renaming = next(r for r in lifting.renamings["unstack_a_b"] if r.sibling == "unstack_c_d")
    assert renaming.literal((names.index("clear_a"), True)) == (names.index("clear_c"), True)
    assert renaming.literal((names.index("on_a_b"), False)) == (names.index("on_c_d"), False)
    assert renaming.literal((names.index("handempty"), True)) == (names.index("handempty"), True)
    assert not any(r.sibling.startswith("pick_up") for r in lifting.renamings["unstack_a_b"])


def test_no_form_no_lifting() -> None:
    domain, _demos = read_demo_set(BLOCKS / "two")
    assert lifting_of(without_forms(domain)) is None
    assert lifting_of(load_domain(Path(__file__).resolve().parent.parent / "demos" / "ball" / "domain.toml")) is None


def test_two_demonstrations_reach_the_goal_safely_from_every_state(blocks: Task) -> None:
    domain, demos = read_demo_set(BLOCKS / "two")
    learner = learn_online(domain, demos)
    assert count_reproduced(learner.tree, domain, demos) == len(demos)
    starts = [s for s, distance in blocks.reachable.items() if distance >= 0]
    outcomes = judge(blocks, learner.tree, starts)
    assert outcomes.counts["unsafe"] == outcomes.counts["false done"] == 0
    assert outcomes.share("reached") >= 0.95
    # the same demonstrations without the forms: the grounded learner is safe, and stuck nearly everywhere
    grounded = judge(blocks, learn_online(without_forms(domain), demos).tree, starts)
    assert grounded.counts["unsafe"] == grounded.counts["false done"] == 0
    assert grounded.share("reached") < 0.5


def test_lifted_sam_shares_the_same_evidence(blocks: Task) -> None:
    domain, demos = read_demo_set(BLOCKS / "two")
    sam = SamLearner(domain)
    for demo in demos:
        sam.update(demo)
    shown = {domain.action(a).name for d in demos for a in d.actions}
    assert set(sam.known) > shown  # siblings never shown are known
    starts = [s for s, distance in blocks.reachable.items() if distance >= 0]
    outcomes = judge(blocks, sam.tree, starts)
    assert outcomes.counts["unsafe"] == outcomes.counts["false done"] == 0


def test_an_answer_about_one_instance_rules_out_its_siblings(blocks: Task) -> None:
    domain, demos = read_demo_set(BLOCKS / "two")
    learner = learn_online(domain, demos)
    names = domain.condition_names
    learner.model.rule_out("pick_up_a", (names.index("clear_a"), True), "question 1")
    assert (names.index("clear_c"), True) in learner.model["pick_up_c"].ruled_out
    assert (names.index("clear_a"), True) not in learner.model["pick_up_c"].ruled_out


@pytest.mark.parametrize(("form", "message"), [
    ('"on"', "'form' must be a list"),
    ('["on", "a b"]', "'form' must be a list"),
    ("[]", "'form' must be a list"),
    ('["on", "a", "b", "c", "d", "e", "f", "g", "h", "i"]', "up to 8 objects"),
])
def test_a_bad_form_is_one_line_naming_its_line(tmp_path: Path, form: str, message: str) -> None:
    path = tmp_path / "domain.toml"
    path.write_text(f'[[condition]]\nname = "On"\nform = {form}\n\n[[action]]\nid = 1\nname = "Go"\n')
    with pytest.raises(FormatError, match=message) as caught:
        load_domain(path)
    assert caught.value.line == 3


def test_two_conditions_of_the_same_form_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "domain.toml"
    path.write_text('[[condition]]\nname = "A"\nform = ["on", "a"]\n\n[[condition]]\nname = "B"\nform = ["on", "a"]\n\n'
                    '[[action]]\nid = 1\nname = "Go"\nform = ["on", "a"]\n')
    with pytest.raises(FormatError, match="condition B has the same 'form' as condition A") as caught:
        load_domain(path)
    assert caught.value.line == 7
