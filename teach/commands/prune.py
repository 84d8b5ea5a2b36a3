"""Remove redundant and unreachable nodes from a tree without changing what it does (thesis §4.2.2).

Example:
    teach learn demos/ball/delta1 --approach detect -o delta1.xml
    teach prune delta1.xml -o delta1-pruned.xml --domain demos/ball/domain.toml

With --domain, an action's ramifications count as known once it has succeeded (a condition
right after Fallback(BallFound, FindBall) need not test BallFound again); without it only the
conditions themselves are used. The pruned tree ticks like the original in every state.
"""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "prune"
HELP = "remove redundant nodes from a tree (same behaviour in every state)"
ORDER = 25


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("tree", type=Path, help="behaviour tree (BehaviorTree.CPP v4 XML)")
    parser.add_argument("-o", "--output", type=Path, required=True, help="where to write the pruned tree")
    parser.add_argument("--domain", type=Path,
                        help="domain.toml whose action model (ramifications) the pruning may use")
    parser.add_argument("--verbose", "-v", action="store_true", help="list every removed node")


def outputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command writes, checked and locked before it runs (teach.lock.claim_outputs)."""
    return [("file", args.output)]


def inputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command reads, which no output may replace (teach.protect)."""
    return [("tree file", args.tree)] + ([("domain file", args.domain)] if args.domain else [])


def run(args: argparse.Namespace) -> int:
    from teach.bt.nodes import action_names, condition_names, size
    from teach.bt.xml import read_tree, write_tree
    from teach.domain import check_tree_fits, load_domain
    from teach.learn.prune import prune_with_report, ramifications_of

    tree = read_tree(args.tree)
    ramifications = {}
    if args.domain:
        domain = load_domain(args.domain)
        check_tree_fits(domain, condition_names(tree), action_names(tree), args.tree)
        ramifications = ramifications_of(domain)
    pruned, removed = prune_with_report(tree, ramifications)
    write_tree(args.output, pruned)
    if args.verbose:
        for node in removed:
            print(f"  removed {node}")
    print(f"{args.tree}: {size(tree)} -> {size(pruned)} nodes, written to {args.output}")
    return 0
