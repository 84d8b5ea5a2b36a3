"""Write a tree as Graphviz DOT (render it with `dot -Tsvg`).

Example:
    teach dot demos/ball/reference/colledanchise.xml -o colledanchise.dot
"""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "dot"
HELP = "convert a behaviour tree to Graphviz DOT"
ORDER = 31


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("tree", type=Path, help="behaviour tree (BehaviorTree.CPP v4 XML)")
    parser.add_argument("-o", "--output", type=Path, help="DOT file to write (default: standard output)")


def outputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command writes, checked and locked before it runs (teach.lock.claim_outputs)."""
    return [("file", args.output)] if args.output else []


def inputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command reads, which no output may replace (teach.protect)."""
    return [("tree file", args.tree)]


def run(args: argparse.Namespace) -> int:
    from teach.bt.render import to_dot
    from teach.bt.xml import read_tree
    from teach.fsutil import atomic_write_text

    text = to_dot(read_tree(args.tree))
    if args.output:
        atomic_write_text(args.output, text)
    else:
        print(text, end="")
    return 0
