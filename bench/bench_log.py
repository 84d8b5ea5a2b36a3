"""Logging overhead and recording size of a ten-minute session.

Run: .venv/bin/python bench/bench_log.py [--minutes 10] [--sim-minutes 2]

Feeds the event stream of a session at realistic rates (per second of simulated time: 10
scene frames of 15 shapes, 10 states, 10 ticks of a 16-node tree, 2 overview camera images of
400x300 and 1 robot camera image of 320x240; a dialogue line, a question, a learner event or a
new generation every 30 s) once
to a ``RerunLogger`` and once to the no-op ``Observer``, side by side, and prints:
- the logging time, and its share of a live session's wall time (a live session runs in
  simulated real time, so ten minutes of simulated time take ten minutes);
- the ratio against the bare event loop with no physics or rendering in it (an upper bound:
  a real session's loop also steps the physics and renders the camera);
- the size of the recording for the whole run.
Then it runs the real MuJoCo world fast-forward (the five skills of the ball task, again and
again, as a scripted session does) with and without the logger, alternating, and prints the
best-of-three ratio of wall and CPU time (CPU includes rerun's background encoder thread): the overhead of
a session that runs faster than real time, physics and camera rendering included.
Targets (issue 5): overhead at most 20% of a session's wall time, at most 50 MB for ten minutes.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from teach.bt.nodes import Action, Condition, Fallback, Sequence  # noqa: E402
from teach.bt.tick import tick_state  # noqa: E402
from teach.bt.xml import tree_to_xml  # noqa: E402
from teach.domain import load_domain  # noqa: E402
from teach.observe.hook import Observer  # noqa: E402
from teach.observe.rerun_writer import RerunLogger  # noqa: E402
from teach.observe.scene import SceneShape  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
FRAME_HZ = 10
CAMERA_HZ = 2  # the overview camera; the robot's own at half that


def reference_tree() -> Sequence:
    pairs = [("BallFound", "FindBall"), ("BallClose", "ApproachBall"), ("BallGrasped", "GraspBall"),
             ("BinClose", "ApproachBin"), ("BallPlaced", "PlaceBall")]
    return Sequence(tuple(Fallback((Condition(c), Action(a))) for c, a in pairs))


def shapes(t: float) -> list[SceneShape]:
    """Fifteen shapes: a floor, a table, a bin, a ball and an eleven-part robot that moves."""
    identity = (1.0, 0.0, 0.0, 0.0)
    turn = (float(np.cos(t / 4)), 0.0, 0.0, float(np.sin(t / 4)))
    scene = [SceneShape("floor", "box", (3.0, 3.0, 0.01), (0.0, 0.0, -0.01), identity, (0.8, 0.8, 0.8, 1.0)),
             SceneShape("table", "box", (0.4, 0.3, 0.02), (1.0, 0.0, 0.4), identity, (0.6, 0.4, 0.2, 1.0)),
             SceneShape("bin", "cylinder", (0.15, 0.12), (-1.0, 0.5, 0.12), identity, (0.2, 0.6, 0.2, 1.0)),
             SceneShape("ball", "sphere", (0.04,), (1.0, 0.1 * np.sin(t), 0.46), identity, (1.0, 0.2, 0.2, 1.0))]
    base = (0.3 * np.sin(t / 10), 0.3 * np.cos(t / 10), 0.1)
    scene.append(SceneShape("base", "box", (0.25, 0.2, 0.1), base, turn, (0.3, 0.3, 0.3, 1.0)))
    for i in range(4):
        scene.append(SceneShape(f"wheel{i}", "cylinder", (0.05, 0.02), (base[0] + 0.2 * (i % 2) - 0.1,
                                base[1] + 0.2 * (i // 2) - 0.1, 0.05), turn, (0.1, 0.1, 0.1, 1.0)))
    for i in range(5):
        scene.append(SceneShape(f"arm{i}", "capsule", (0.03, 0.1), (base[0], base[1], 0.25 + 0.2 * i), turn,
                                (0.3, 0.3, 0.9, 1.0)))
    scene.append(SceneShape("hand", "sphere", (0.05,), (base[0], base[1], 1.3), turn, (0.9, 0.9, 0.9, 1.0)))
    return scene


def camera_image(t: float, width: int = 320, height: int = 240) -> np.ndarray:
    """A smooth synthetic view (floor, wall, a moving ball), compressible like a render."""
    y, x = np.mgrid[0:height, 0:width]
    image = np.zeros((height, width, 3), dtype=np.uint8)
    image[..., 0] = 120 + (y * 240 // height // 4)
    image[..., 1] = 130 + (x * 320 // width // 8)
    image[..., 2] = np.where(y < height * 5 // 12, 200, 90)
    cx, cy = width / 2 + width / 4 * np.sin(t), height * 5 // 8
    ball = (x - cx) ** 2 + (y - cy) ** 2 < 20 ** 2
    image[ball] = (230, 40, 40)
    return image


def run(observer: Observer, minutes: float) -> float:
    """One session's event stream; returns the seconds spent inside observer calls."""
    domain = load_domain(ROOT / "demos" / "ball" / "domain.toml")
    names = domain.condition_names
    tree = reference_tree()
    states = [domain.state(names[:k]) for k in range(len(names) + 1)]
    images = [camera_image(i / CAMERA_HZ) for i in range(8)]  # rendering is not what we measure
    overviews = [camera_image(i / CAMERA_HZ, 400, 300) for i in range(8)]
    frames = int(minutes * 60 * FRAME_HZ)
    spent = 0.0
    start = time.perf_counter()
    observer.set_time(0, 0.0)
    observer.on_domain(domain)
    observer.on_tree(0, tree, tree_to_xml(tree), "start")
    spent += time.perf_counter() - start
    for frame in range(frames):
        t = frame / FRAME_HZ
        state = states[(frame // 50) % len(states)]
        scene = shapes(t)
        result = tick_state(tree, names, state)
        mapping = dict(zip(names, state, strict=True))
        start = time.perf_counter()
        observer.set_time(frame, t)
        observer.on_scene(scene)
        observer.on_tick(tree, result)
        observer.on_state(mapping, result.action)
        if frame % (FRAME_HZ // CAMERA_HZ) == 0:
            observer.on_camera(overviews[frame % len(overviews)], "overview")
        if frame % (2 * FRAME_HZ // CAMERA_HZ) == 0:
            observer.on_camera(images[frame % len(images)])
        if frame % 300 == 0:
            observer.on_dialogue("teacher", "grasp the ball")
            observer.on_question("Must the ball be within reach before you grasp it?", 3)
            observer.on_answer("Must the ball be within reach before you grasp it?", "yes", "kept (BallClose)")
            observer.on_learner("specialize", "one more demonstration", removed=["(BinClose)"])
            observer.on_tree(frame // 300, tree, tree_to_xml(tree), "demonstration")
            observer.on_replay(frame // 300, frame // 300 + 1)
        spent += time.perf_counter() - start
    start = time.perf_counter()
    observer.close()
    return spent + time.perf_counter() - start


def sim_session(observer: Observer, minutes: float) -> tuple[float, float, float]:
    """Run the ball task's skills in the MuJoCo world for ``minutes`` of simulated time:
    (wall seconds, CPU seconds, simulated seconds)."""
    from teach.sim.skills import run_skill
    from teach.sim.world import World

    domain = load_domain(ROOT / "demos" / "ball" / "domain.toml")
    world = World(seed=0, domain=domain)
    simulated, seed = 0.0, 0
    wall, cpu = time.perf_counter(), time.process_time()
    while simulated < minutes * 60:
        world.reset(seed=seed)
        seed += 1
        start = world.sim_time
        for action in domain.action_names:
            run_skill(world, action, observer)
        simulated += world.sim_time - start
    observer.close()
    return time.perf_counter() - wall, time.process_time() - cpu, simulated


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0, help="simulated session length")
    parser.add_argument("--sim-minutes", type=float, default=2.0,
                        help="simulated minutes of the MuJoCo fast-forward comparison (0 skips it)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "bench.rrd"
        wall = time.perf_counter()
        bare_calls = run(Observer(), args.minutes)
        bare = time.perf_counter() - wall
        wall = time.perf_counter()
        logged_calls = run(RerunLogger(path, "bench"), args.minutes)
        logged = time.perf_counter() - wall
        size_mb = path.stat().st_size / 1e6
    session = args.minutes * 60
    logging = logged_calls - bare_calls
    print(f"simulated session: {args.minutes:g} min, {int(session * FRAME_HZ)} frames")
    print(f"bare event loop:   {bare:7.2f} s wall")
    print(f"with RerunLogger:  {logged:7.2f} s wall (ratio {logged / bare:.2f} of the bare loop; "
          "an upper bound: no physics or rendering in it)")
    print(f"logging cost:      {logging:7.2f} s = {100 * logging / session:.1f}% of a live session's "
          f"{session:.0f} s wall time (target <= 20%)")
    print(f"recording size:    {size_mb:7.1f} MB for {args.minutes:g} min "
          f"(= {size_mb * 10 / args.minutes:.1f} MB per ten minutes, target <= 50 MB)")
    if args.sim_minutes > 0:
        with tempfile.TemporaryDirectory() as folder:
            runs: dict[str, list[tuple[float, float, float]]] = {"bare": [], "logged": []}
            for round_ in range(3):  # alternating, and the best of three, against other load on the machine
                runs["bare"].append(sim_session(Observer(), args.sim_minutes / 3))
                runs["logged"].append(sim_session(RerunLogger(Path(folder) / f"sim{round_}.rrd", "sim"),
                                                  args.sim_minutes / 3))
            sim_mb = sum((Path(folder) / f"sim{r}.rrd").stat().st_size for r in range(3)) / 1e6
            sim_seconds = sum(r[2] for r in runs["logged"])
        bare_wall, bare_cpu = (min(r[i] for r in runs["bare"]) for i in (0, 1))
        log_wall, log_cpu = (min(r[i] for r in runs["logged"]) for i in (0, 1))
        print(f"MuJoCo fast-forward, best of 3 x {args.sim_minutes / 3:.2g} simulated min: bare {bare_wall:.2f} s wall "
              f"{bare_cpu:.2f} s CPU, logged {log_wall:.2f} s wall {log_cpu:.2f} s CPU: overhead "
              f"{100 * (log_wall / bare_wall - 1):.0f}% wall, {100 * (log_cpu / bare_cpu - 1):.0f}% CPU "
              "(target <= 20%)")
        print(f"MuJoCo recordings (rendered camera images): {sim_mb:.1f} MB for {sim_seconds:.0f} simulated s "
              f"= {sim_mb * 600 / sim_seconds:.1f} MB per ten minutes (target <= 50 MB)")


if __name__ == "__main__":
    main()
