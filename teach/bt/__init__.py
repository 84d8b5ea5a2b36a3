"""Behaviour trees: immutable node specs, ticking, XML, rendering."""

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Parallel, Sequence, Status, walk

__all__ = ["Action", "Condition", "Fallback", "Inverter", "Node", "Parallel", "Sequence", "Status", "walk"]
