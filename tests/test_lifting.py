"""Parameterised actions (``form`` in domain.toml, ``teach.learn.lifting``): what one instance shows
is learned for its siblings, and only conditions about an action's own objects can be its
preconditions. Judged in the true blocksworld model (bench/foreign/pddl) from every reachable state."""

from __future__ import annotations

import dataclasses
import itertools
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "bench"))

from foreign import ipc  # noqa: E402
from foreign.judge import judge  # noqa: E402
from foreign.model import Task  # noqa: E402
from foreign.sam import SamLearner  # noqa: E402

from teach.demos import parse_demonstration, read_demo_set  # noqa: E402
from teach.dialogue.questions import Question, describe_situation  # noqa: E402
from teach.domain import Domain, load_domain  # noqa: E402
from teach.errors import FormatError, TeachError  # noqa: E402
from teach.learn.learner import learn_online  # noqa: E402
from teach.learn.lifting import lifting_of  # noqa: E402
from teach.messages import Lang  # noqa: E402
from teach.replay import count_reproduced  # noqa: E402
from teach.session.arguments import condition_named, condition_names  # noqa: E402
from teach.symbolic import missing_preconditions  # noqa: E402

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


GO = '''name = "go"

[[condition]]
name = "ready_a"
form = ["ready", "a"]

[[condition]]
name = "ready_b"
form = ["ready", "b"]

[[condition]]
name = "lamp_a"
form = ["lamp", "a"]

[[condition]]
name = "lamp_b"
form = ["lamp", "b"]

[[condition]]
name = "there_a"
form = ["there", "a"]

[[condition]]
name = "there_b"
form = ["there", "b"]

[[action]]
id = 1
name = "go_a"
form = ["go", "a"]

[[action]]
id = 2
name = "go_b"
form = ["go", "b"]
'''


def test_an_answer_about_one_instance_is_one_about_its_siblings(tmp_path: Path) -> None:
    """go_a was shown only with its lamp on; "yes, go to b" where b's lamp is off says a lamp is
    not needed, for go_a too."""
    path = tmp_path / "domain.toml"
    path.write_text(GO)
    domain = load_domain(path)
    learner = learn_online(domain, [parse_demonstration("1;0;1;0;0;0;1\n1;0;1;0;1;0;0\n", domain, "d01.csv")])
    lamp_a, lamp_b = domain.index("lamp_a"), domain.index("lamp_b")
    assert learner.model["go_a"].required[0] >> lamp_a & 1 and learner.model["go_b"].required[0] >> lamp_b & 1
    learner.teach_step(domain.state(["ready_b"]), "go_b", "question 1")
    assert not learner.model["go_b"].required[0] >> lamp_b & 1
    assert not learner.model["go_a"].required[0] >> lamp_a & 1
    assert learner.model["go_a"].required[0] >> domain.index("ready_a") & 1


ROOT = Path(__file__).resolve().parent.parent
PICK = '''name = "pick"
goal = ["held_cup"]

[[condition]]
name = "reach_ball"

[[condition]]
name = "reach_cup"

[[condition]]
name = "held_ball"

[[condition]]
name = "held_cup"

[[action]]
id = 1
name = "pick_ball"
form = ["pick", "ball"]
pre = ["reach_ball", "!held_ball"]
ram = ["held_ball"]

[[action]]
id = 2
name = "pick_cup"
form = ["pick", "cup"]
pre = ["reach_cup", "!held_cup"]
ram = ["held_cup"]

[[action]]
id = 3
name = "go_cup"
pre = ["!reach_cup"]
ram = ["reach_cup"]
'''


def test_actions_with_forms_need_conditions_with_forms(tmp_path: Path) -> None:
    path = tmp_path / "domain.toml"
    path.write_text(PICK)
    with pytest.raises(FormatError, match="condition reach_ball has no 'form' but action pick_ball has one") as caught:
        load_domain(path)
    assert caught.value.line == 4


def test_a_condition_without_a_form_is_never_renamed(tmp_path: Path) -> None:
    """Built in code (the loader refuses it): a formless condition may be any action's precondition
    and only the action's own steps say anything about it, so the tree stays safe."""
    path = tmp_path / "domain.toml"
    path.write_text(PICK.replace('form = ["pick", "ball"]\n', "").replace('form = ["pick", "cup"]\n', ""))
    plain = load_domain(path)
    domain = dataclasses.replace(plain, actions=tuple(
        dataclasses.replace(a, form=("pick", a.name.removeprefix("pick_"))) if a.name.startswith("pick") else a
        for a in plain.actions))
    lifting = lifting_of(domain)
    assert lifting is not None and lifting.own["pick_ball"] == 0b1111
    assert all(not r.pairs for r in lifting.renamings["pick_ball"])
    demos = [parse_demonstration("1;0;0;0;1\n1;0;1;0;3\n1;1;1;0;2\n1;1;1;1;0\n", domain, "d01.csv"),
             parse_demonstration("0;1;0;0;2\n0;1;0;1;0\n", domain, "d02.csv")]
    learner = learn_online(domain, demos)
    for bits in itertools.product((False, True), repeat=4):
        action = learner.answer_in(bits)
        if isinstance(action, str):
            assert not missing_preconditions(domain, bits, action), (bits, action)


def test_a_pddl_constant_goes_into_the_name() -> None:
    assert ipc.form("(lit switch)", frozenset({"switch"})) == ("lit_0_switch",)
    assert ipc.form("(move a home b)", frozenset({"home"})) == ("move_1_home", "a", "b")
    assert ipc.form("(on a b)") == ("on", "a", "b")


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


def test_a_question_about_an_action_never_done_says_which_step_it_is_known_from() -> None:
    domain, demos = read_demo_set(BLOCKS / "two")
    learner = learn_online(domain, demos)
    done = {domain.action(a).name for d in demos for a in d.actions}
    for action in domain.action_names:
        known_from = learner.model[action].known_from
        assert (known_from == "") == (action in done or learner.model[action].like == ""), action
        assert known_from == "" or (known_from in done and known_from.split("_")[0] == action.split("_")[0])
    never = next(a for a in domain.action_names if learner.model[a].known_from)
    question = Question(domain.state(), 1.0, kind="must-precondition", action=never, settles=(("clear_a", True),),
                        like=learner.model[never].known_from)
    text = question.text(domain)
    assert text.startswith(f"I have not done “{domain.action(never).label()}” yet, but every time I did a step like it")
    assert "So far, every time I did" not in text


def test_a_condition_named_by_its_name_is_that_condition_word_for_word() -> None:
    """Dropping filler words read "on_b_a" ("on b a" without its "a") as "on_a_b", so
    `start on_b_a` put a on b; word for word first, and a loose reading only where it names one."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    assert [condition_named(domain, text) for text in ("on_b_a", "On B A", "on_a_b", "on a b")] == \
        ["on_b_a", "on_b_a", "on_a_b", "on_a_b"]
    ball = load_domain(ROOT / "demos" / "ball" / "domain.toml")
    assert condition_named(ball, "ballfound") == condition_named(ball, "Ball Found") == "BallFound"


def test_the_first_words_of_several_conditions_name_none_of_them() -> None:
    """"clear" without the filler "a" of "clear a" read as clear_a; it begins clear b, c and d too,
    so 'start clear' asks which one is meant."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    assert condition_named(domain, "clear") is None
    assert condition_named(domain, "clear a") == "clear_a"
    with pytest.raises(TeachError, match=r"^which condition is 'clear': “clear a”, “clear b”, “clear c”, “clear d”\?$"):
        condition_names(domain, "handempty, clear", Lang.EN)
    with pytest.raises(TeachError, match=r"^unknown condition 'cleer'"):
        condition_names(domain, "cleer", Lang.EN)
    ball = load_domain(ROOT / "demos" / "ball" / "domain.toml")
    assert condition_names(ball, "the ball is in my hand, BinClose", Lang.EN) == ["BallGrasped", "BinClose"]


def test_a_situation_with_many_objects_says_what_holds_and_nothing_else() -> None:
    """Blocksworld's questions listed 25 false conditions ("not: on a a, not: on a b, …"); what holds
    and "and nothing else" is what a person can read. The ball's five conditions are all named."""
    domain = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    state = domain.state(["clear_a", "handempty", "on_a_b", "ontable_b"])
    assert describe_situation(domain, state) == "clear a, handempty, on a b and ontable b, and nothing else"
    assert describe_situation(domain, state, Lang.DE) == ("a ist frei, meine Hand ist leer, a liegt auf b und b liegt "
                                                          "auf dem Tisch, sonst nichts")  # it was "… und ontable_b"
    assert describe_situation(domain, domain.state()) == "none of the 29 conditions holds"  # 29 times "not: …" before
    ball = load_domain(ROOT / "demos" / "ball" / "domain.toml")
    assert " but " in describe_situation(ball, ball.state(["BallFound"]))
