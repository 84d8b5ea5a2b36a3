"""Summarise a recorded teaching session, or open it in the rerun viewer.

Example:
    teach review recordings/quickstart.rrd
    teach review recordings/quickstart.rrd --open

Prints the demonstrations (action sequences with their states), the questions with their
answers, each tree generation with its node count, the final tree and the replay result.
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


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    from teach.observe.reader import read_recording
    from teach.observe.viewer import open_viewer
    from teach.review import summary

    contents = read_recording(args.recording)
    Console().print(summary(contents))
    if args.open:
        open_viewer(args.recording)
    return 0
