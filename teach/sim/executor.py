"""Running a learned tree in the simulation.

The tree is ticked at a fixed rate of simulated time (``tick_hz``) with the conditions read
from physics; the action that returns RUNNING drives its skill until the next tick, and
switching to another action halts the previous skill. A run ends on SUCCESS, FAILURE, the
tick limit, or the teacher's interrupt. Perturbations can be scheduled at given ticks; each
halts the running skill (the tree decides afresh) and is recorded as an external action. A
slip (the ball leaving the gripper during a skill that keeps hold, ``teach.sim.slip``) is the
world's own external action: it halts the skill the same way.

The returned ``RunTrace`` turns into a demonstration in the thesis's format; an interrupted
run continued with ``Recorder(world, prefix=trace.as_demonstration(domain))`` becomes a
corrective demonstration (§6.4's online-correction idea).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from teach.bt.nodes import Node, Status
from teach.bt.run import Outcome, Ticker
from teach.bt.tick import TickResult, tick
from teach.demos import Demonstration, Step
from teach.domain import EXTERNAL_ACTION, GOAL_ACTION, Domain, State
from teach.errors import DomainError
from teach.observe.hook import Observer
from teach.sim.perturb import PERTURBATIONS
from teach.sim.skills import FrameClock, Skill, skill_for
from teach.sim.slip import SLIP, SlipWatch, let_fall
from teach.sim.world import CONTROL_STEPS, World


@dataclass(frozen=True, slots=True)
class External:
    """An external action before tick ``tick``; ``halted`` names the skill it stopped."""

    tick: int
    name: str
    before: State
    after: State
    halted: str | None = None
    halted_changed: bool = True  # whether the halted skill had changed the state before it stopped


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

    def entries(self, starts: int | None = None) -> list[tuple[State, str] | External]:
        """The run in order: (state, action) for each skill started, each external action; a skill
        an external action halted before it changed anything is left out (it did nothing). With
        ``starts``, only what came before the skill started after that many."""
        entries: list[tuple[State, str] | External] = []
        pending = sorted(self.externals, key=lambda e: e.tick)

        def external(event: External) -> None:
            last = entries[-1] if entries else None
            if event.halted is not None and not event.halted_changed and isinstance(last, tuple) \
                    and last[1] == event.halted:
                entries.pop()
            entries.append(event)

        begun = 0
        for i, state in enumerate(self.states):
            while pending and pending[0].tick <= i:
                external(pending.pop(0))
            action = self.actions[i]
            if action is not None and self.started[i]:
                if starts is not None and begun >= starts:
                    return entries
                begun += 1
                entries.append((state, action))
        for event in pending:
            external(event)
        return entries

    def as_demonstration(self, domain: Domain, name: str = "run") -> Demonstration:
        """One line per skill started and per external action; the goal line after a success."""
        steps: list[Step] = []
        for entry in self.entries():
            if isinstance(entry, External):
                steps.append(Step(entry.before, EXTERNAL_ACTION, len(steps) + 1))
            else:
                steps.append(Step(entry[0], domain.action(entry[1]).id, len(steps) + 1))
        if self.outcome is Outcome.SUCCESS:
            steps.append(Step(self.states[-1], GOAL_ACTION, len(steps) + 1))
        return Demonstration(name, tuple(steps))


def run_tree(world: World, tree: Node, observer: Observer | None = None, max_ticks: int = 600,
             tick_hz: float = 10.0, interrupt: Callable[[], bool] | None = None,
             perturbations: Mapping[int, str] | None = None, after_tick: Callable[[TickResult], None] | None = None,
             on_frame: Callable[[], None] | None = None,
             on_external: Callable[[External], None] | None = None, ticker: Ticker = tick) -> RunTrace:
    """Tick ``tree`` in ``world`` until it finishes, ``max_ticks`` pass, or ``interrupt()`` is true.

    ``perturbations`` maps a tick number to a perturbation name applied just before that tick.
    ``after_tick`` hears each tick's result once the observer has (a caller's run limit);
    ``on_frame`` runs after each scene frame (see ``FrameClock``); ``on_external`` hears of
    each external action (perturbation or slip) once it is over.
    """
    for name in (perturbations or {}).values():
        if name not in PERTURBATIONS:
            raise DomainError(f"unknown perturbation {name!r} (known: {', '.join(PERTURBATIONS)})")
    period = 1.0 / tick_hz
    frames = FrameClock(world, observer, on_frame)
    trace = RunTrace()
    running: list[Skill | None] = [None]
    begun: list[State] = [()]  # the state the running skill started in
    watch: list[SlipWatch | None] = [None]
    fresh = [False]

    def action_status(name: str) -> Status:
        skill = running[0]
        if skill is None or skill.name != name or skill.result is not None:
            if skill is not None:
                skill.halt()
            begun[0], watch[0] = world.state(), SlipWatch(world, name)
            skill = running[0] = skill_for(world, name)(world)
            fresh[0] = True
        return skill.tick()

    def halt() -> tuple[str | None, State]:
        """Halt the running skill for an external action: its name and the state it started in."""
        skill, running[0], watch[0] = running[0], None, None
        if skill is None or skill.result is not None:
            return None, ()
        skill.halt()
        return skill.name, begun[0]

    def external(event: External) -> None:
        trace.externals.append(event)
        if on_external is not None:
            on_external(event)

    def slipped(before_tick: int, at_tick: bool = False) -> bool:
        """Whether the ball has just slipped out of the gripper; if so the skill is halted and the
        slip recorded as an external action before tick ``before_tick``. Between ticks the hold
        counts as lost after a while (contacts flicker), at a tick at once: the tree sees it."""
        skill, slip_watch = running[0], watch[0]
        if slip_watch is None:
            return False
        finished = skill is not None and skill.result is not None
        held = slip_watch.lost() if at_tick or finished else slip_watch.check()
        if held is None:
            return False
        halted, started = halt()
        if observer is not None:
            observer.on_external(SLIP)
        after = let_fall(world, lambda: frames(None))
        external(External(before_tick, SLIP, held, after, halted, held != started))
        return True

    for number in range(max_ticks):
        if interrupt is not None and interrupt():
            trace.outcome = Outcome.INTERRUPTED
            break
        if perturbations and number in perturbations:
            halted, started = halt()
            before = world.state()
            PERTURBATIONS[perturbations[number]].apply(world, world.rng)
            if observer is not None:
                observer.on_external(perturbations[number])
            external(External(number, perturbations[number], before, world.state(), halted, before != started))
        slipped(number, at_tick=True)
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
        while world.sim_time < start + period - 1e-9:  # the rest of the tick period
            skill = running[0]
            if skill is not None and skill.result is None:
                skill.tick()
            else:
                world.step(CONTROL_STEPS)
            if slipped(number + 1):
                continue
            frames(result.action)
    if running[0] is not None:
        running[0].halt()
    return trace
