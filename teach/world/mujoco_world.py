"""The MuJoCo ball-in-bin world behind the session's ``TeachingWorld`` interface.

Demonstrated actions run as skills in physics and every state is read from physics; runs of
the learned tree go through the simulation's executor. No mujoco call lives here: this only
adapts ``teach.sim`` to the session.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from teach.bt.nodes import Node, Status
from teach.bt.run import Outcome, Ticker
from teach.bt.tick import TickResult, tick
from teach.display import has_display
from teach.domain import Domain, State
from teach.errors import TeachError
from teach.observe.hook import Observer
from teach.sim.executor import External, run_tree
from teach.sim.guide import Guide, Sample
from teach.sim.guided_skill import GuidedMotion, guided_skill
from teach.sim.perturb import PERTURBATIONS
from teach.sim.skills import FrameClock, register, run_skill
from teach.sim.slip import SLIP, SLIP_DE, SLIP_EN, SlipWatch, let_fall
from teach.sim.world import World
from teach.world.protocol import ActResult, RunResult, WorldEvent

TICK_HZ = 10.0
SECONDS_PER_ACTION = 30.0


class _RunLimit:
    """Counts the actions a run starts (so ``run N`` can stop after N) and announces each."""

    def __init__(self, on_action: Callable[[str], None] | None, stop_after: int | None) -> None:
        self.started = 0
        self._last: str | None = None
        self._on_action = on_action
        self._stop_after = stop_after

    def after_tick(self, result: TickResult) -> None:
        if result.action is not None and result.action != self._last:
            self.started += 1
            if self._on_action is not None and (self._stop_after is None or self.started <= self._stop_after):
                self._on_action(result.action)
        self._last = result.action

    def reached(self) -> bool:
        return self._stop_after is not None and self.started > self._stop_after


class _Pacer:
    """Holds simulated time to at most ``pace`` times wall time, so a person can watch a run
    (and press Ctrl-C in time); scripted replays run unpaced."""

    def __init__(self, world: World, pace: float):
        self.world, self.pace = world, pace
        self._origin: tuple[float, float] | None = None

    def __call__(self) -> None:
        now, sim = time.monotonic(), self.world.sim_time
        if self._origin is None or now - self._origin[0] > 1.0 + (sim - self._origin[1]) / self.pace:
            self._origin = (now, sim)  # first frame, or after a pause at the prompt: start afresh
            return
        ahead = (sim - self._origin[1]) / self.pace - (now - self._origin[0])
        if ahead > 0:
            time.sleep(ahead)


class MujocoWorld:
    def __init__(self, domain: Domain, seed: int = 0, observer: Observer | None = None, viewer: bool = False,
                 pace: float = 0.0, cameras: bool | None = None):
        """``cameras``: render the camera images the observer is shown (default: when there is an
        observer); off where nothing records them, since rendering costs more than the physics."""
        self.world = World(seed, domain, cameras=observer is not None if cameras is None else cameras)
        self.domain = self.world.domain
        self.observer = observer or Observer()
        self.ticker: Ticker = tick
        self._frame_steps: list[Callable[[], None]] = []  # after each scene frame: pace, redraw
        self.viewer: Any = None  # the MuJoCo viewer's handle with --viewer: the teacher's hand drags in it
        if pace > 0:
            self._frame_steps.append(_Pacer(self.world, pace))
        if viewer:
            if not has_display():
                raise TeachError("--viewer needs a display (DISPLAY is not set); recordings still show the scene")
            self.viewer = self.world.open_viewer()
            self._frame_steps.append(self.viewer.sync)
        self._on_frame = self._after_frame if self._frame_steps else None
        self.frames = FrameClock(self.world, self.observer, self._on_frame)
        self.events = {name: (p.en, p.de) for name, p in PERTURBATIONS.items()}

    def after_each_frame(self, step: Callable[[], None]) -> None:
        """Run ``step`` after every scene frame too (a scripted mouse in the viewer, a screenshot)."""
        self._frame_steps.append(step)
        self._on_frame = self.frames.on_frame = self._after_frame

    def _after_frame(self) -> None:
        for step in self._frame_steps:
            step()

    def state(self) -> State:
        return self.world.state()

    def arrange(self, state: State) -> None:
        self.world.arrange(state)
        self.frames(None)

    def can_happen(self, state: State) -> bool:
        return self.world.can_arrange(state)

    def reset(self, seed: int | None = None) -> None:
        self.world.reset(seed)
        self.frames(None)

    def act(self, action: str) -> ActResult:
        """Run the skill; a slip halts it and comes back as the result's event."""
        before = self.world.state()
        watch = SlipWatch(self.world, action)
        status = run_skill(self.world, action, self.observer, frames=self.frames,
                           halt_when=lambda: watch.check() is not None)
        held = watch.lost()
        if held is not None:
            self.observer.on_external(SLIP)
            after = let_fall(self.world, lambda: self.frames(None))
            slip = WorldEvent(SLIP, held, after, SLIP_EN, SLIP_DE, action, held != before)
            return ActResult(True, before, after, f"halted: {SLIP_EN}", (slip,))
        after = self.world.state()
        if status is Status.SUCCESS:
            return ActResult(True, before, after)
        return ActResult(False, before, after, "the robot could not finish it in the simulation")

    def perturb(self, event: str) -> ActResult:
        before = self.world.state()
        PERTURBATIONS[event].apply(self.world, self.world.rng)
        self.frames(None)
        return ActResult(True, before, self.world.state())

    def run(self, tree: Node, max_actions: int = 20, interrupt: Callable[[], bool] | None = None,
            stop_after: int | None = None, on_action: Callable[[str], None] | None = None,
            on_event: Callable[[WorldEvent], None] | None = None) -> RunResult:
        limit = _RunLimit(on_action, stop_after)

        def stop() -> bool:
            return (interrupt is not None and interrupt()) or limit.reached()

        def heard(external: External) -> None:
            if on_event is not None:
                on_event(_world_event(external))

        trace = run_tree(self.world, tree, self.observer, max_ticks=int(max_actions * SECONDS_PER_ACTION * TICK_HZ),
                         tick_hz=TICK_HZ, interrupt=stop, after_tick=limit.after_tick, on_frame=self._on_frame,
                         on_external=heard, ticker=self.ticker)
        result = RunResult(trace.outcome, final_state=self.world.state())
        # nothing from the action that reached the 'run N' limit: it was stopped as it started
        for entry in trace.entries(stop_after if trace.outcome is Outcome.INTERRUPTED else None):
            if isinstance(entry, External):
                result.events.append((len(result.steps), _world_event(entry)))
            else:
                result.steps.append(entry)
        last = result.steps[-1] if result.steps else None
        if trace.outcome is Outcome.INTERRUPTED and last is not None and last[0] == result.final_state \
                and not any(after == len(result.steps) for after, _ in result.events):
            result.steps.pop()  # stopped before it changed anything: the teacher's next step replaces it
        return result

    def close(self) -> None:
        if self.viewer is not None:
            self.viewer.close()
        self.world.close()

    # --- guiding (issue 12): the teacher moves the robot's body ----------------------------

    def start_guiding(self, listener: Callable[[Sample], object]) -> Guide:
        """A guide on this world whose samples go to ``listener`` and whose frames go to the
        recording through this world's clock (pacing and viewer redraws included)."""
        return Guide(self.world, listener, self.observer, self.frames)

    def learn_skill(self, motion: GuidedMotion) -> None:
        """Make a motion taught by guidance runnable under its action name, like any skill."""
        register(self.world, guided_skill(motion))

    def adopt_domain(self, domain: Domain) -> None:
        """The session's domain grew an action taught by guidance (the conditions are the same)."""
        self.domain = self.world.domain = domain


def _world_event(external: External) -> WorldEvent:
    """An external action of a run in the session's terms (a perturbation's words are its phrases)."""
    if external.name == SLIP:
        en, de = SLIP_EN, SLIP_DE
    else:
        perturbation = PERTURBATIONS[external.name]
        en, de = perturbation.en[0], perturbation.de[0]
    return WorldEvent(external.name, external.before, external.after, en, de, external.halted,
                      external.halted_changed)
