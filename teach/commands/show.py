"""Show a tree in the terminal, optionally ticked once in a given state.

Example:
    teach show demos/ball/reference/colledanchise.xml --state BallFound,BallClose --domain demos/ball/domain.toml
"""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "show"
HELP = "draw a behaviour tree; with --state, tick it once and colour each node by its status"
ORDER = 30


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("tree", type=Path, help="behaviour tree (BehaviorTree.CPP v4 XML)")
    parser.add_argument("--state", metavar="NAMES",
                        help="comma-separated conditions that are true (all others are false); "
                             "'' for none")
    parser.add_argument("--domain", type=Path, help="domain.toml: checks names and adds their labels")
    parser.add_argument("--lang", choices=("en", "de"), default="en", help="label language (with --domain)")


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    from teach.bt.nodes import Status, action_names, condition_names
    from teach.bt.render import render_text, render_tree
    from teach.bt.tick import tick
    from teach.bt.xml import read_tree
    from teach.domain import check_tree_fits, load_domain
    from teach.errors import DomainError

    tree = read_tree(args.tree)
    labels: dict[str, str] = {}
    known = sorted(condition_names(tree))
    if args.domain:
        domain = load_domain(args.domain)
        check_tree_fits(domain, condition_names(tree), action_names(tree), args.tree)
        labels = {c.name: c.label(args.lang) for c in domain.conditions}
        labels.update({a.name: a.label(args.lang) for a in domain.actions})
        known = list(domain.condition_names)
    console = Console(highlight=False)

    def draw(statuses: dict[int, Status] | None) -> None:
        if console.is_terminal:
            console.print(render_tree(tree, statuses, labels))
        else:  # piped or logged: statuses as words, since colours are lost
            print(render_text(tree, statuses, labels), end="")

    if args.state is None:
        draw(None)
        return 0
    true = [name.strip() for name in args.state.split(",") if name.strip()]
    for name in true:
        if name not in known:
            where = f"the domain {args.domain}" if args.domain else "the tree"
            raise DomainError(f"--state names {name!r}, which is not a condition of {where} "
                              f"(known: {', '.join(known) or 'none'})")
    result = tick(tree, {name: name in true for name in known})
    draw(result.statuses())
    ran = f", running {result.action}" if result.action else ""
    print(f"status {result.status.name}{ran}")
    return 0
