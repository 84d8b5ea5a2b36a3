"""Simulation speed: physics against real time, a recorded five-action demonstration, camera frames.

Example:
    .venv/bin/python bench/bench_sim.py

Targets (issue 4): physics at least 50x real time headless; a five-action demonstration
recorded in under 3 s of wall time with rendering off.
"""

from __future__ import annotations

import time

from teach.sim.recorder import record
from teach.sim.skills import run_skill
from teach.sim.world import World

FIVE = ["FindBall", "ApproachBall", "GraspBall", "ApproachBin", "PlaceBall"]


def physics_ratio(world: World, seconds: float = 10.0) -> float:
    """Simulated seconds per wall second, the robot carrying the ball (contacts active)."""
    world.arrange({"BallFound": True, "BallGrasped": True}, seed=1)
    steps = round(seconds / world.model.opt.timestep)
    start = time.perf_counter()
    world.step(steps)
    return seconds / (time.perf_counter() - start)


def reference_ratio(seconds: float = 10.0) -> float:
    """The same measure for a plain 9-body scene (boxes on a floor), run side by side, so the
    machine's load shows in both numbers."""
    import mujoco  # the bench may import it: it only measures teach.sim

    bodies = "".join(f'<body pos="{i % 3 - 1} {i // 3 - 1} 0.2"><freejoint/>'
                     f'<geom type="box" size=".05 .05 .05"/></body>'
                     for i in range(9))
    model = mujoco.MjModel.from_xml_string(f'<mujoco><worldbody><geom type="plane" size="3 3 .1"/>{bodies}'
                                           f'</worldbody></mujoco>')
    data = mujoco.MjData(model)
    start = time.perf_counter()
    mujoco.mj_step(model, data, nstep=round(seconds / model.opt.timestep))
    return seconds / (time.perf_counter() - start)


def skills_ratio(world: World) -> float:
    """Simulated over wall time while skills run (physics + perception + control)."""
    sim = wall = 0.0
    for seed in range(5):
        world.arrange({}, seed=seed)
        start, t0 = time.perf_counter(), world.sim_time
        for name in FIVE:
            run_skill(world, name)
        wall += time.perf_counter() - start
        sim += world.sim_time - t0
    return sim / wall


def demo_seconds(world: World) -> tuple[float, float]:
    """Wall and simulated seconds to record one five-action demonstration (worst of five)."""
    worst = (0.0, 0.0)
    for seed in range(5):
        world.arrange({}, seed=seed)
        t0, start = world.sim_time, time.perf_counter()
        demo = record(world, FIVE)
        assert demo.reached_goal
        worst = max(worst, (time.perf_counter() - start, world.sim_time - t0))
    return worst


def camera_fps(world: World, frames: int = 20) -> float | None:
    world.reset(seed=0)
    if world.camera_image() is None:
        return None
    start = time.perf_counter()
    for _ in range(frames):
        world.step(10)
        world.camera_image()
    return frames / (time.perf_counter() - start)


def main() -> None:
    with World(seed=0) as world:
        ratio, reference = physics_ratio(world), reference_ratio()
        print(f"physics: {ratio:.0f}x real time (target >= 50x); a plain 9-body scene: {reference:.0f}x "
              f"(ours at {ratio / reference:.2f} of it)")
        print(f"skills running: {skills_ratio(world):.0f}x real time")
        wall, sim = demo_seconds(world)
        print(f"five-action demonstration: {wall:.2f} s wall for {sim:.1f} s simulated (target < 3 s)")
        fps = camera_fps(world)
        print("camera 320x240: " + ("unavailable (no offscreen OpenGL)" if fps is None else f"{fps:.1f} frames/s"))


if __name__ == "__main__":
    main()
