"""The tree in plain sentences (teach/session/tree_words.py): the reference tree word for word in
both languages, learned trees, and random trees of any shape."""

from __future__ import annotations

from pathlib import Path

from hypothesis import given, settings
from strategies import trees

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Sequence, walk
from teach.bt.xml import read_tree
from teach.demos import read_demo_set
from teach.domain import load_domain
from teach.learn.learner import learn_online
from teach.session.tree_words import tree_lines

BALL = Path(__file__).resolve().parent.parent / "demos" / "ball"


def test_table_6_1_in_english_and_german(ball):
    tree = read_tree(BALL / "reference" / "table61.xml")
    assert tree_lines(tree, ball, "en") == [
        "When the ball is in the bin, I am done.",
        "Otherwise I do the first that fits:",
        "  – if the ball is not in my hand and I cannot see the ball, I find the ball",
        "  – if the ball is not in my hand and the ball is out of reach, I go to the ball",
        "  – if the ball is not in my hand, I grasp the ball",
        "  – if the bin is out of reach, I go to the bin",
        "  – otherwise, I put the ball in the bin",
    ]
    assert tree_lines(tree, ball, "de") == [
        "Ich bin fertig, sobald gilt: der Ball ist im Eimer.",
        "Sonst tue ich das Erste, was passt:",
        "  – wenn gilt: ich habe den Ball nicht in der Hand und ich sehe den Ball nicht, dann: „Ball finden“",
        "  – wenn gilt: ich habe den Ball nicht in der Hand und der Ball ist nicht in Reichweite, "
        "dann: „zum Ball gehen“",
        "  – wenn gilt: ich habe den Ball nicht in der Hand, dann: „Ball greifen“",
        "  – wenn gilt: der Eimer ist nicht in Reichweite, dann: „zum Eimer gehen“",
        "  – sonst: „Ball in den Eimer legen“",
    ]


def test_a_learned_tree_says_its_goal_and_every_step_without_identifiers(ball):
    domain, demos = read_demo_set(BALL / "delta4")
    tree = learn_online(domain, demos).tree
    for lang in ("en", "de"):
        text = "\n".join(tree_lines(tree, ball, lang))
        assert ball.condition("BallPlaced").label(lang) in text.splitlines()[0]
        assert all(action.label(lang) in text for action in ball.actions)
        assert not any(name in text for name in (*ball.condition_names, *ball.action_names))


def test_a_tree_of_nothing_but_checks_does_nothing(ball):
    tree = read_tree(BALL / "reference" / "table61.xml")
    goal_only = tree.children[0]  # type: ignore[union-attr]
    assert tree_lines(goal_only, ball, "en") == ["When the ball is in the bin, I am done.",
                                                 "Otherwise I do nothing yet."]


@settings(max_examples=150, deadline=None)
@given(trees(["BallFound", "BallClose", "BallGrasped", "BinClose", "BallPlaced"],
             ["FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall"]))
def test_any_tree_is_said_in_words_naming_every_action(tree):
    from teach.domain import load_domain

    ball = load_domain(BALL / "domain.toml")
    for lang in ("en", "de"):
        lines = tree_lines(tree, ball, lang)
        assert lines and lines == tree_lines(tree, ball, lang)  # deterministic
        text = "\n".join(lines)
        assert all(ball.action(n.name).label(lang) in text for n in walk(tree) if isinstance(n, Action))
        assert not any(name in text for name in (*ball.condition_names, *ball.action_names))


def test_a_rule_an_earlier_one_always_comes_before_is_not_said(ball):
    # "if the bin is out of reach, I go to the bin" comes first: a later rule that goes to the
    # bin when it checks the same and more ("... and I cannot see the ball") says nothing new
    out_of_reach = Inverter(Condition("BinClose"))
    tree = Fallback((Sequence((out_of_reach, Action("ApproachBin"))),
                     Sequence((out_of_reach, Inverter(Condition("BallFound")), Action("ApproachBin"))),
                     Action("PlaceBall")))
    assert tree_lines(tree, ball, "en") == [
        "I do the first that fits:",
        "  – if the bin is out of reach, I go to the bin",
        "  – otherwise, I put the ball in the bin",
    ]


def test_rules_of_a_domain_with_many_conditions_name_what_holds():
    """Blocksworld's rules tested 25 false conditions each, said as "not: on a a and not: on a b …"."""
    blocks = load_domain(BALL.parent / "blocksworld" / "domain.toml")
    exact = Sequence((*(Condition(c.name) if c.name in ("clear_a", "handempty", "ontable_a") else
                        Inverter(Condition(c.name)) for c in blocks.conditions), Action("pick_up_a")))
    some = Sequence((Condition("clear_a"), *(Inverter(Condition(f"on_{x}_a")) for x in "abcd"),
                     *(Inverter(Condition(f"holding_{x}")) for x in "abcd"), Inverter(Condition("on_a_b")),
                     Action("pick_up_a")))
    assert tree_lines(exact, blocks, "en")[1].endswith(
        "if clear a, handempty and ontable a, and nothing else, I pick up a")
    assert "none of: on a a, on b a, on c a, on d a, holding a, holding b, holding c, holding d, on a b" in \
        tree_lines(some, blocks, "en")[1]
    assert "not: " not in "\n".join(tree_lines(exact, blocks, "en") + tree_lines(some, blocks, "en"))
