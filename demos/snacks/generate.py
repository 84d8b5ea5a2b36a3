"""Regenerate the snacks-and-drinks demonstrations (thesis §3.2.2, Fig. 3.3) and the reference tree.

Example:
    .venv/bin/python demos/snacks/generate.py           # rewrites train/, heldout/, reference/
    .venv/bin/python demos/snacks/generate.py /tmp/out  # the same files under another folder

The thesis gives the behaviour (Fig. 3.3) but no demonstrations, so they are made here by
running that behaviour, written as ``reference_tree()``, in the hidden-state world of
``world.toml`` (teach/world/hidden.py): ``train/`` holds eleven demonstrations with repeated
actions, both orders of actions and external events; ``heldout/`` one demonstration from
every other start state. Every choice is a named constant below and is explained in
demos/snacks/README.md. The output is deterministic: running this twice gives the same bytes.
"""

from __future__ import annotations

import itertools
import shutil
import sys
from pathlib import Path
from typing import NamedTuple

from teach.bt.nodes import Action, Condition, Fallback, Node, Sequence, Status
from teach.bt.tick import compile_tree
from teach.demos import Demonstration, Step, format_demonstration
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State, load_domain
from teach.fsutil import atomic_write_text
from teach.world.hidden import HiddenStateWorld, load_world

HERE = Path(__file__).resolve().parent
MAX_STEPS = 40  # a reference behaviour that needs more steps than this is looping


class Scenario(NamedTuple):
    """One training demonstration: where it starts, what is hidden, and what people do meanwhile."""

    story: str
    start: tuple[str, ...]              # the conditions true at the start
    seed: int                           # the world's seed (how full a fresh tray is)
    snacks: int | None = None           # snacks on a tray already carried (None: the world draws)
    events: tuple[tuple[int, str], ...] = ()  # (robot actions before it, event name)


TRAINING: tuple[Scenario, ...] = (
    Scenario("a whole round from the office", ("AtOffice",), 1),
    Scenario("the request is there already", ("Requested", "AtOffice"), 3),
    Scenario("out with a tray already", ("Requested", "TrayTaken"), 1, snacks=2),
    Scenario("the request is withdrawn after someone is found", ("AtOffice",), 4,
             events=((3, "request_withdrawn"),)),
    Scenario("the person walks away before the offer", ("AtOffice",), 5, events=((3, "partner_leaves"),)),
    Scenario("someone takes the last snack before it is offered", ("Requested", "TrayTaken", "AtOffice"), 1,
             snacks=2, events=((3, "snack_taken"),)),
    Scenario("the tray is lost after the first offer", ("Requested", "AtOffice"), 5,
             events=((3, "tray_lost"),)),
    Scenario("a request comes before the robot waits", ("AtOffice",), 6, events=((0, "new_request"),)),
    Scenario("the request is withdrawn after the tray is taken", ("Requested", "AtOffice"), 2,
             events=((1, "request_withdrawn"),)),
    Scenario("someone is there at the office already", ("Requested", "TrayTaken", "PartnerFound", "AtOffice"), 1,
             snacks=3),
    Scenario("an empty tray stands in the office", ("Requested", "TrayEmpty", "AtOffice"), 4),
)


def reference_tree() -> Node:
    """Fig. 3.3 with a goal check in front: done when the empty tray is back in the office;
    otherwise wait for a request, take the tray, and offer snacks to whoever is found until
    the tray is empty, then go back to the office."""
    def achieve(condition: str, action: str) -> Node:
        return Fallback((Condition(condition), Action(action)))

    serve = Fallback((Sequence((Condition("TrayEmpty"), Action("ReturnToOffice"))),
                      Sequence((achieve("PartnerFound", "FindPartner"), Action("OfferSnack")))))
    return Fallback((Sequence((Condition("TrayTaken"), Condition("TrayEmpty"), Condition("AtOffice"))),
                     Sequence((achieve("Requested", "WaitForRequest"), achieve("TrayTaken", "TakeTray"), serve))))


def all_states(domain: Domain) -> list[State]:
    """Every state, in counting order with the first condition as the most significant bit."""
    return [tuple(bits) for bits in itertools.product((False, True), repeat=len(domain.conditions))]


def demonstrate(world: HiddenStateWorld, tree: Node, name: str, start: State, seed: int,
                snacks: int | None = None, events: tuple[tuple[int, str], ...] = ()) -> Demonstration:
    """Run ``tree`` in ``world`` from ``start`` until it succeeds, recording every line; the
    events happen after the given number of robot actions (-1 lines)."""
    domain = world.domain
    world.reset(seed)
    world.arrange(start, {} if snacks is None else {"snacks": snacks})
    compiled = compile_tree(tree, domain.condition_names)
    pending = list(events)
    done = 0
    steps: list[Step] = []
    while len(steps) <= MAX_STEPS:
        if pending and pending[0][0] == done:
            event = pending.pop(0)[1]
            happened = world.perturb(event)
            if not happened.ok:
                raise SystemExit(f"{name}: {event} cannot happen in {domain.describe(world.state())}: "
                                 f"{happened.message}")
            steps.append(Step(happened.before, EXTERNAL_ACTION))
            continue
        state = world.state()
        status, action = compiled(state)
        if status is Status.SUCCESS and not pending:
            steps.append(Step(state, GOAL_ACTION))
            return Demonstration(name, tuple(steps))
        if status is not Status.RUNNING or action is None:
            raise SystemExit(f"{name}: the reference behaviour gives {status.name} in {domain.describe(state)}")
        acted = world.act(action)
        if not acted.ok:
            raise SystemExit(f"{name}: {action} is not possible in {domain.describe(state)}: {acted.message}")
        steps.append(Step(state, domain.action(action).id))
        done += 1
    raise SystemExit(f"{name}: the reference behaviour did not reach its goal in {MAX_STEPS} steps")


def build_sets(domain: Domain, world: HiddenStateWorld) -> dict[str, list[Demonstration]]:
    """``train``: the scenarios above; ``heldout``: from every start state no training
    demonstration starts in, without events (the world draws the snacks, seeded by position)."""
    tree = reference_tree()
    train = [demonstrate(world, tree, f"d{i:02d}", domain.state(s.start), s.seed, s.snacks, s.events)
             for i, s in enumerate(TRAINING, 1)]
    seen = {demo.steps[0].state for demo in train}
    others = [state for state in all_states(domain) if state not in seen]
    heldout = [demonstrate(world, tree, f"h{i:02d}", state, i) for i, state in enumerate(others, 1)]
    return {"train": train, "heldout": heldout}


def main(argv: list[str]) -> int:
    from teach.bt.xml import write_tree

    out = Path(argv[0]) if argv else HERE
    domain = load_domain(HERE / "domain.toml")
    world = HiddenStateWorld(domain, load_world(HERE / "world.toml", domain))
    for folder, demos in build_sets(domain, world).items():
        target = out / folder
        if target.exists():
            shutil.rmtree(target)
        for demo in demos:
            atomic_write_text(target / f"{demo.name}.csv", format_demonstration(demo))
        print(f"{folder}: {len(demos)} demonstrations")
    write_tree(out / "reference" / "reference.xml", reference_tree())
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
