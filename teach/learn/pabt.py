"""Approach 1 (thesis §4.1): Planning and Acting with Behavior Trees from a given action model.

Generation 0 is the goal: one condition, or a Sequence of the goal literals (Fig. 4.3). Each
later generation replaces one failing literal by its atomic BT (Fig. 2.8)::

    Fallback(literal, Sequence(pre_1, ..., pre_k, action), ...)   # one Sequence per achiever

An achiever without preconditions stands directly under the Fallback (a one-child Sequence
ticks the same; this is what makes the thesis's all-goals tree 24 nodes, Fig. 6.7).
A negative literal ``!C`` is ``Inverter(Condition(C))``.

Which literal fails: the thesis *executes* the tree from the all-false state (reset every
generation) and replaces "the last failing condition". Executing in the symbolic world means
ticking, and when an action is left RUNNING, applying its ramifications to the state and
ticking again (§5: actions return RUNNING and change the state by their ramifications). The
execution ends with SUCCESS, FAILURE, or when a state repeats (the tree would loop). The
literal expanded next is the last literal node that returned FAILURE and has not been
expanded yet, searched from the last tick of the execution backwards. So with several goals
a RUNNING tree is executed on until a later goal fails (Figs. 6.3-6.7 expand BallFound,
BallClose, ... in turn), and inside an atomic BT the failing precondition is expanded (Fig.
6.1). Every literal is expanded at most once; expansion stops at SUCCESS.
"""

from __future__ import annotations

from collections.abc import Sequence as Seq
from pathlib import Path

from teach.bt.nodes import Action, Condition, Fallback, Inverter, Node, Sequence, Status, replace_node, walk
from teach.bt.tick import tick
from teach.domain import ActionDef, Domain, Literal, State
from teach.errors import LearnError


def literal_node(literal: Literal) -> Node:
    """``C`` as a Condition, ``!C`` as an Inverter over it."""
    condition = Condition(literal.name)
    return condition if literal.value else Inverter(condition)


def atomic_bt(literal_leaf: Node, achievers: Seq[ActionDef]) -> Node:
    """The atomic BT of Fig. 2.8 around an existing literal node (which keeps its uid)."""
    branches: list[Node] = []
    for action in achievers:
        if action.pre:
            branches.append(Sequence(tuple(literal_node(p) for p in action.pre) + (Action(action.name),)))
        else:
            branches.append(Action(action.name))
    return Fallback((literal_leaf, *branches))


def expand(domain: Domain, goal: Seq[Literal] | None = None) -> list[Node]:
    """Every generation of PA-BT on the domain's action model, generation 0 first.

    Raises ``LearnError`` with a plain-words reason when the model cannot give a tree that
    reaches the goal from the state where nothing holds.
    """
    goal = tuple(domain.goal if goal is None else goal)
    if not goal:
        raise LearnError("no goal: give the goal conditions (goal = [...] in the domain file, or --goal)",
                         domain.path)
    for literal in goal:
        domain.index(literal.name)
    _check_model(domain)

    leaves = [literal_node(g) for g in goal]
    tree: Node = leaves[0] if len(leaves) == 1 else Sequence(tuple(leaves))
    needed_by = {leaf.uid: "the goal needs it" for leaf in leaves}
    generations = [tree]
    expanded: set[Literal] = set()
    start: State = (False,) * len(domain.conditions)
    while True:
        outcome, failing, note = _execute(domain, tree, start)
        if outcome is Status.SUCCESS:
            return generations
        candidate = next(((uid, lit) for uid, lit in failing if lit not in expanded), None)
        if candidate is None:
            raise LearnError(f"the model cannot reach the goal {_conjunction(goal)} from the state where "
                             f"nothing holds: {note}", domain.path)
        uid, literal = candidate
        achievers = [a for a in domain.actions if literal in a.ram]
        if not achievers:
            idle = [a.name for a in domain.actions if not a.ram]
            hint = f" (actions without any ramification: {', '.join(idle)})" if idle else ""
            raise LearnError(f"no action makes {literal} true (none has it among its ramifications), "
                             f"but {needed_by[uid]}{hint}", domain.path)
        leaf = next(n for n in walk(tree) if n.uid == uid)
        atomic = atomic_bt(leaf, achievers)
        assert isinstance(atomic, Fallback)
        for branch in atomic.children[1:]:  # each achiever: the action, or Sequence(pre..., action)
            steps = branch.children if isinstance(branch, Sequence) else (branch,)
            action = steps[-1]
            assert isinstance(action, Action)
            for pre in steps[:-1]:
                needed_by[pre.uid] = f"{action.name} needs it as a precondition"
        expanded.add(literal)
        tree = replace_node(tree, uid, atomic)  # type: ignore[assignment]
        generations.append(tree)


def _check_model(domain: Domain) -> None:
    """A literal both required and produced by one action can never be produced by it (§6.1)."""
    conflicts = [(a.name, [str(lit) for lit in a.pre if lit in a.ram]) for a in domain.actions]
    conflicts = [(name, both) for name, both in conflicts if both]
    if conflicts:
        (name, both), rest = conflicts[0], conflicts[1:]
        literals = ", ".join(both)
        problems = [f"{literals} {'is' if len(both) == 1 else 'are'} both a precondition and a ramification "
                    f"of {name}: {name} can only start when {literals} already holds, so it can never be "
                    f"what makes {literals} true"]
        if rest:
            problems.append("the same in " + ", ".join(f"{n} ({', '.join(b)})" for n, b in rest))
        idle = [a.name for a in domain.actions if not a.ram]
        if idle:
            problems.append(f"{', '.join(idle)} {'has' if len(idle) == 1 else 'have'} no ramifications")
        raise LearnError("; ".join(problems), domain.path)


def _literal_leaves(tree: Node) -> dict[int, tuple[int, Literal]]:
    """uid of the node whose status is the literal's -> (uid of the literal node, literal)."""
    result: dict[int, tuple[int, Literal]] = {}
    inverted: set[int] = set()
    for node in walk(tree):
        if isinstance(node, Inverter) and isinstance(node.child, Condition):
            result[node.uid] = (node.uid, Literal(node.child.name, False))
            inverted.add(node.child.uid)
        elif isinstance(node, Condition) and node.uid not in inverted:
            result[node.uid] = (node.uid, Literal(node.name))
    return result


def _execute(domain: Domain, tree: Node, start: State) -> tuple[Status, list[tuple[int, Literal]], str]:
    """Run the tree in the symbolic world; returns the outcome, the failing literal nodes (most
    recent first) and a sentence on how the run ended."""
    leaves = _literal_leaves(tree)
    names = domain.condition_names
    state, seen = start, {start}
    failing: list[tuple[int, Literal]] = []
    while True:
        result = tick(tree, dict(zip(names, state, strict=True)))
        failing[:0] = [leaves[uid] for uid, status in reversed(result.trace)
                       if status is Status.FAILURE and uid in leaves]
        if result.status is not Status.RUNNING or result.action is None:
            return result.status, failing, f"the tree returns {result.status.name} in {_true(domain, state)}"
        values = list(state)
        for literal in domain.action(result.action).ram:
            values[domain.index(literal.name)] = literal.value
        after = tuple(values)
        if after in seen:
            return Status.RUNNING, failing, (f"running {result.action} in {_true(domain, state)} leads back to "
                                             f"an earlier state, so the robot would loop")
        seen.add(after)
        state = after


def _true(domain: Domain, state: State) -> str:
    names = [n for n, v in zip(domain.condition_names, state, strict=True) if v]
    return "{" + ", ".join(names) + "}" if names else "the state where nothing holds"


def _conjunction(literals: Seq[Literal]) -> str:
    return " and ".join(str(lit) for lit in literals)


def write_generations(folder: str | Path, generations: Seq[Node]) -> list[Path]:
    """Write each generation as ``gen-NN.xml`` (atomically) and return the paths; generations
    an earlier run left in the folder are removed, so the highest number is this run's result."""
    from teach.bt.xml import write_tree

    folder = Path(folder)
    if folder.is_dir():
        for stale in folder.glob("gen-*.xml"):
            stale.unlink()
    paths = []
    for number, tree in enumerate(generations):
        path = folder / f"gen-{number:02d}.xml"
        write_tree(path, tree)
        paths.append(path)
    return paths
