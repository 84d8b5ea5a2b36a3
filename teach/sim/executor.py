"""Running a learned tree in the simulation.

The tree is ticked at a fixed rate of simulated time (``tick_hz``) with the conditions read
from physics; the action that returns RUNNING drives its skill until the next tick, and
switching to another action halts the previous skill. A run ends on SUCCESS, FAILURE, the
tick limit, or the teacher's interrupt. Perturbations can be scheduled at given ticks; each
halts the running skill (the tree decides afresh) and is recorded as an external action.

The returned ``RunTrace`` turns into a demonstration in the thesis's format; an interrupted
run continued with ``Recorder(world, prefix=trace.as_demonstration(domain))`` becomes a
corrective demonstration (§6.4's online-correction idea).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from teach.bt.nodes import Node, Status
from teach.bt.tick import TickResult, tick
from teach.demos import Demonstration, Step
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State
from teach.errors import DomainError
from teach.observe.hook import Observer
from teach.sim.perturb import PERTURBATIONS
from teach.sim.skills import FrameClock, Skill, skill_for
from teach.sim.world import CONTROL_STEPS, World
from teach.world.protocol import Outcome, Ticker


@dataclass(frozen=True, slots=True)
class External:
    tick: int
    name: str
    before: State
    after: State


@dataclass
class RunTrace:
    """What happened in a run, tick by tick (``states[i]`` is the state ticked at tick i)."""

    outcome: Outcome = Outcome.TIMEOUT
    states: list[State] = field(default_factory=list)
    actions: list[str | None] = field(default_factory=list)
    statuses: list[Status] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    started: list[bool] = field(default_factory=list)  # a fresh skill started at this tick
    externals: list[External] = field(default_factory=list)

    @property
    def ticks(self) -> int:
        return len(self.states)

    def as_demonstration(self, domain: Domain, name: str = "run") -> Demonstration:
        """One line per skill started and per perturbation; the goal line after a success."""
        steps: list[Step] = []
        pending = sorted(self.externals, key=lambda e: e.tick)
        for i, state in enumerate(self.states):
            while pending and pending[0].tick <= i:
                steps.append(Step(pending.pop(0).before, EXTERNAL_ACTION, len(steps) + 1))
            action = self.actions[i]
            if action is not None and self.started[i]:
                steps.append(Step(state, domain.action(action).id, len(steps) + 1))
        for external in pending:
            steps.append(Step(external.before, EXTERNAL_ACTION, len(steps) + 1))
        if self.outcome is Outcome.SUCCESS:
            steps.append(Step(self.states[-1], GOAL_ACTION, len(steps) + 1))
        return Demonstration(name, tuple(steps))


def run_tree(world: World, tree: Node, observer: Observer | None = None, max_ticks: int = 600,
             tick_hz: float = 10.0, interrupt: Callable[[], bool] | None = None,
             perturbations: Mapping[int, str] | None = None, after_tick: Callable[[TickResult], None] | None = None,
             on_frame: Callable[[], None] | None = None, ticker: Ticker = tick) -> RunTrace:
    """Tick ``tree`` in ``world`` until it finishes, ``max_ticks`` pass, or ``interrupt()`` is true.

    ``perturbations`` maps a tick number to a perturbation name applied just before that tick.
    ``after_tick`` hears each tick's result once the observer has (a caller's run limit);
    ``on_frame`` runs after each scene frame (see ``FrameClock``).
    """
    for name in (perturbations or {}).values():
        if name not in PERTURBATIONS:
            raise DomainError(f"unknown perturbation {name!r} (known: {', '.join(PERTURBATIONS)})")
    period = 1.0 / tick_hz
    frames = FrameClock(world, observer, on_frame)
    trace = RunTrace()
    running: list[Skill | None] = [None]
    fresh = [False]

    def action_status(name: str) -> Status:
        skill = running[0]
        if skill is None or skill.name != name or skill.result is not None:
            if skill is not None:
                skill.halt()
            skill = running[0] = skill_for(name)(world)
            fresh[0] = True
        return skill.tick()

    for number in range(max_ticks):
        if interrupt is not None and interrupt():
            trace.outcome = Outcome.INTERRUPTED
            break
        if perturbations and number in perturbations:
            if running[0] is not None:
                running[0].halt()
                running[0] = None
            before = world.state()
            PERTURBATIONS[perturbations[number]].apply(world, world.rng)
            trace.externals.append(External(number, perturbations[number], before, world.state()))
            if observer is not None:
                observer.on_external(perturbations[number])
        state, conditions, start = world.state(), world.conditions(), world.sim_time
        fresh[0] = False
        result = ticker(tree, conditions, action_status)
        trace.states.append(state)
        trace.actions.append(result.action)
        trace.statuses.append(result.status)
        trace.times.append(start)
        trace.started.append(fresh[0] and result.action is not None)
        frames(result.action, force=True)
        if observer is not None:
            observer.on_tick(tree, result)
        if after_tick is not None:
            after_tick(result)
        if result.status is not Status.RUNNING:
            trace.outcome = Outcome.SUCCESS if result.status is Status.SUCCESS else Outcome.FAILURE
            break
        skill = running[0]
        while world.sim_time < start + period - 1e-9:  # the rest of the tick period
            if skill is not None and skill.result is None:
                skill.tick()
            else:
                world.step(CONTROL_STEPS)
            frames(result.action)
    if running[0] is not None:
        running[0].halt()
    return trace
