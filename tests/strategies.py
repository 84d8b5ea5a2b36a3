"""Hypothesis strategies for random behaviour trees over a fixed vocabulary."""

from __future__ import annotations

from hypothesis import strategies as st

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence


def trees(conditions: list[str], actions: list[str], max_leaves: int = 25) -> st.SearchStrategy[Node]:
    leaves = st.one_of(st.sampled_from(conditions).map(Condition), st.sampled_from(actions).map(Action))

    def extend(inner: st.SearchStrategy[Node]) -> st.SearchStrategy[Node]:
        kids = st.lists(inner, min_size=1, max_size=4).map(tuple)
        return st.one_of(
            kids.map(Sequence), kids.map(Fallback), inner.map(Inverter),
            kids.flatmap(lambda k: st.integers(1, len(k)).map(lambda m: Parallel(k, m))),
        )

    return st.recursive(leaves, extend, max_leaves=max_leaves)
