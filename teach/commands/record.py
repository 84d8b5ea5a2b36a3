"""Record a demonstration in the MuJoCo world by guiding the robot (headless, scripted).

Example:
    teach record --set ball/sim --start BallFound,BinClose --seed 0 ApproachBall GraspBall ApproachBin PlaceBall

Each argument is an action (name or phrase, e.g. "grasp the ball") or a perturbation
(knock_ball, take_ball, move_bin, push_robot). The state before and after every step is read
from physics; the goal line is added when the goal holds at the end. The demonstration is
printed and written atomically as the next demo-NNN.csv in demos/<set>/.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NAME = "record"
HELP = "record a demonstration in the simulation from a list of actions and perturbations"
ORDER = 40


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("steps", nargs="+", metavar="ACTION_OR_PERTURBATION",
                        help="actions (name or phrase) and perturbations, in order")
    parser.add_argument("--set", required=True, dest="demo_set", help="demonstration set: written to ROOT/SET/")
    parser.add_argument("--root", type=Path, default=Path("demos"), help="folder of demonstration sets (demos)")
    parser.add_argument("--start", default="", help="comma-separated conditions true at the start "
                                                    "(default: a random start pose)")
    parser.add_argument("--seed", type=int, default=0, help="random seed for start poses and perturbations")
    parser.add_argument("--viewer", action="store_true", help="show the MuJoCo viewer (needs a display)")


def outputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """The set recorded into, checked and locked before the simulation starts (teach.lock.claim_outputs)."""
    return [("set", _set_folder(args.root, args.demo_set))]


def run(args: argparse.Namespace) -> int:
    from teach.demos import format_demonstration
    from teach.display import has_display
    from teach.errors import TeachError
    from teach.sim.perturb import PERTURBATIONS
    from teach.sim.recorder import Recorder, resolve_action, save_demonstration
    from teach.sim.world import World

    if args.viewer and not has_display():
        raise TeachError("--viewer needs a display (DISPLAY is not set); leave it out to record headless")
    with World(seed=args.seed) as world:
        for step in args.steps:  # check the whole script before moving anything
            if step not in PERTURBATIONS:
                resolve_action(world.domain, step)
        start = [name.strip() for name in args.start.split(",") if name.strip()]
        if start:
            world.arrange(dict.fromkeys(start, True), seed=args.seed)
        viewer = world.open_viewer() if args.viewer else None
        recorder = Recorder(world)
        for step in args.steps:
            result = recorder.perturb(step) if step in PERTURBATIONS else recorder.step(step)
            if result.status is not None and result.status.name == "FAILURE":
                print(f"teach: note: {result.name} failed in the simulation (recorded as observed)", file=sys.stderr)
            if viewer is not None:
                viewer.sync()
        demo = recorder.done()
        path = save_demonstration(demo, _set_folder(args.root, args.demo_set), world.domain)
    sys.stdout.write(format_demonstration(demo))
    print(f"written {path}", file=sys.stderr)
    return 0



def _set_folder(root: Path, name: str) -> Path:
    """ROOT/SET, refusing names that would leave ROOT or write into it directly."""
    from teach.errors import TeachError

    parts = Path(name).parts
    if not parts or any(p in ("..", ".") for p in parts) or Path(name).is_absolute():
        raise TeachError(f"--set must name a folder under {root} (like ball/sim)", name or "''")
    return root / name
