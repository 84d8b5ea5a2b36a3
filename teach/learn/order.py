"""The action order of Approach 3 (thesis §4.3.1): a topological order of demonstrated sequences.

Every demonstration gives edges a_i -> a_(i+1) between its consecutive robot actions. An
external action (-1) ends the chain: it may undo what the robot did (a dropped ball is grasped
again), so the actions after it start a new sequence rather than follow the ones before it;
this is what lets Δ5's perturbed demonstrations keep the order of Δ2 (§6.4). Ties are broken by
first appearance (demonstrations in the order given, steps in file order), so the same
demonstrations always give the same order. When no order exists (a cycle, or an action
repeated), the error names the actions and, for each direction, the demonstration file and line
that shows it.
"""

from __future__ import annotations

from collections.abc import Iterator
from collections.abc import Sequence as Seq

import networkx as nx

from teach.demos import Demonstration, Step
from teach.domain import Domain
from teach.errors import LearnError


def demo_source(demo: Demonstration) -> str:
    """How a demonstration is named in messages: its file, or its name."""
    return str(demo.path) if demo.path is not None else demo.name


def _chain(domain: Domain, demo: Demonstration) -> Iterator[tuple[tuple[str, int] | None, str, Step]]:
    """Each robot action of a demonstration with the one right before it ((name, line), or None
    at the start and after an external action, which ends a chain)."""
    previous: tuple[str, int] | None = None
    for step in demo.steps:
        if step.action < 0:
            previous = None
        if step.action <= 0:
            continue
        name = domain.action(step.action).name
        yield previous, name, step
        previous = (name, step.line)


class OrderGraph:
    """The order edges seen so far, where each was first seen, and each action's first appearance."""

    def __init__(self) -> None:
        self.graph: nx.DiGraph = nx.DiGraph()
        self.first_seen: dict[str, int] = {}
        self.evidence: dict[tuple[str, str], str] = {}

    def copy(self) -> OrderGraph:
        other = OrderGraph()
        other.graph = self.graph.copy()
        other.first_seen = dict(self.first_seen)
        other.evidence = dict(self.evidence)
        return other

    def add_action(self, name: str) -> bool:
        """Add an action without edges; True if it is new."""
        if name in self.first_seen:
            return False
        self.first_seen[name] = len(self.first_seen)
        self.graph.add_node(name)
        return True

    def is_new(self, domain: Domain, demo: Demonstration) -> bool:
        """True if the demonstration shows an action or an edge not seen yet (cheap, no copy)."""
        return any(name not in self.first_seen or (previous is not None and (previous[0], name) not in self.evidence)
                   for previous, name, _step in _chain(domain, demo))

    def add_demo(self, domain: Domain, demo: Demonstration, source: str | None = None) -> bool:
        """Add a demonstration's actions and edges; True if anything was new. Raises
        ``LearnError`` (leaving the graph possibly changed: call it on a copy) if no order fits."""
        where = source or demo_source(demo)
        changed = False
        for previous, name, _step in _chain(domain, demo):
            changed |= self.add_action(name)
            if previous is not None:
                edge = (previous[0], name)
                if edge not in self.evidence:
                    self.evidence[edge] = f"{where}:{previous[1]}"
                    self._check_edge(*edge)
                    self.graph.add_edge(*edge)
                    changed = True
        return changed

    def _check_edge(self, a: str, b: str) -> None:
        """Refuse the edge a -> b if b already leads back to a (the edge would close a cycle)."""
        if a == b:
            raise LearnError(f"no action order fits the demonstrations: {a} follows itself "
                             f"({self.evidence[(a, a)]}), and an order cannot repeat an action", kind="repeated")
        if not nx.has_path(self.graph, b, a):
            return
        path = nx.shortest_path(self.graph, b, a)
        cycle = [*zip(path, path[1:], strict=False), (a, b)]
        shown = ", ".join(f"{u} before {v} ({self.evidence[(u, v)]})" for u, v in cycle)
        names = sorted({u for u, _v in cycle})
        raise LearnError(f"no action order fits the demonstrations: {', '.join(names)} appear in "
                         f"contradicting orders: {shown}", kind="order")

    def order(self) -> list[str]:
        """The topological order, ties broken by first appearance."""
        return list(nx.lexicographical_topological_sort(self.graph, key=self.first_seen.__getitem__))

    def violated_by(self, order: Seq[str]) -> bool:
        """True if ``order`` (covering every action) puts some edge backwards."""
        position = {name: i for i, name in enumerate(order)}
        return any(position[u] > position[v] for u, v in self.graph.edges)


def action_order(domain: Domain, demos: Seq[Demonstration]) -> list[str]:
    """The demonstrated actions in one order consistent with every demonstration."""
    graph = OrderGraph()
    for demo in demos:
        graph.add_demo(domain, demo)
    return graph.order()
