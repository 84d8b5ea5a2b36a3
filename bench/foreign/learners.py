"""The learners compared on the same data, each as "demonstrations in, tree out (None: refused)"."""

from __future__ import annotations

from collections.abc import Callable

from foreign.sam import SamLearner
from teach.bt.nodes import Node
from teach.demos import Demonstration
from teach.domain import Domain
from teach.errors import LearnError
from teach.learn.learner import learn_online
from teach.learn.model import learn_detect
from teach.learn.specialize import specialize


def sam_tree(domain: Domain, demos: list[Demonstration]) -> Node:
    learner = SamLearner(domain)
    for demo in demos:
        learner.update(demo)
    return learner.tree


Learn = Callable[[Domain, list[Demonstration]], Node | None]


def _refusing(learn: Learn) -> Learn:
    """``learn``, with a refusal (``LearnError``) as None."""
    def learned(domain: Domain, demos: list[Demonstration]) -> Node | None:
        try:
            return learn(domain, demos)
        except LearnError:
            return None
    return learned


BATCH: dict[str, Learn] = {
    "learner": lambda domain, demos: learn_online(domain, demos).tree,
    "guessing": lambda domain, demos: learn_online(domain, demos, safe=False).tree,
    "sam": sam_tree,
    "detect": _refusing(lambda domain, demos: learn_detect(domain, demos)[-1]),
    "specialize": _refusing(lambda domain, demos: specialize(domain, demos).tree),
}
"""``learner``: the default online learner (safe); ``guessing``: the same learner guessing
(``safe=False``, the default before issue 18); ``sam``: the SAM-style baseline; ``detect`` and
``specialize``: the thesis's Approaches 2 and 3, which may refuse a set (None)."""
