"""Summarise a recorded teaching session, or open it in the rerun viewer.

Example:
    teach review recordings/quickstart.rrd
    teach review recordings/quickstart.rrd --open
    teach review recordings/quickstart.rrd --step 12
    teach review recordings/quickstart.rrd --tick 40
    teach review recordings/quickstart.rrd --dialogue

Prints the demonstrations (action sequences with their states), the questions with their
answers, each tree generation with its node count, the runs (their .btlog files beside the
recording, for Groot2), the final tree, the replay result and the study figures, each event
with its place on the recording's timelines ("step 5 · tick 20"); ``--step N`` adds the tree at
step N (a typed line) coloured by each node's status there, ``--tick N`` the tree at moment N of
the viewer's ``tick`` timeline (a tick of a run, a step of a demonstration or a line),
``--dialogue`` every line the teacher and the robot said, each with its place.
"""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "review"
HELP = "summarise a session recording (.rrd), or open it in the rerun viewer"
ORDER = 12


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("recording", type=Path, help="a recording written by a session (recordings/*.rrd)")
    parser.add_argument("--open", action="store_true", help="also start the rerun viewer on it (needs a display)")
    parser.add_argument("--step", type=_step, metavar="N", help="also show the tree at step N, coloured by status")
    parser.add_argument("--tick", type=_step, metavar="N",
                        help="also show the tree at moment N of the viewer's tick timeline, coloured by status")
    parser.add_argument("--dialogue", action="store_true",
                        help="also print every line the teacher and the robot said, with its step and tick")


def _step(text: str) -> int:
    if not text.isdecimal() or not text.isascii():
        raise argparse.ArgumentTypeError(f"{text!r} is not a step number (0, 1, 2, ...)")
    return int(text)


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    from teach.observe.reader import read_recording
    from teach.observe.viewer import open_viewer
    from teach.review import read_runs, summary

    contents = read_recording(args.recording)
    runs = read_runs(args.recording)
    shown = summary(contents, runs, args.step, args.tick, args.dialogue)  # all checked before anything is printed
    Console().print(shown)
    if args.open:
        open_viewer(args.recording)
    return 0
