"""Replay demonstrations against a tree (the thesis's sanity check, §5).

Example:
    teach test demos/ball/reference/colledanchise.xml demos/ball/delta2
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

NAME = "test"
HELP = "replay demonstrations against a tree and report which it reproduces"
ORDER = 20


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("tree", type=Path, help="behaviour tree (BehaviorTree.CPP v4 XML)")
    parser.add_argument("demos", type=Path, help="folder of CSV demonstrations")
    parser.add_argument("--domain", type=Path, help="domain.toml (default: in the folder or its parent)")
    parser.add_argument("--lenient", action="store_true",
                        help="the thesis's reading: SUCCESS before the goal line is not a failure")
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON")


def run(args: argparse.Namespace) -> int:
    from teach.bt.nodes import action_names, condition_names
    from teach.bt.xml import read_tree
    from teach.demos import read_demo_set
    from teach.domain import check_tree_fits, load_domain
    from teach.replay import replay

    domain = load_domain(args.domain) if args.domain else None
    domain, demos = read_demo_set(args.demos, domain)
    tree = read_tree(args.tree)
    check_tree_fits(domain, condition_names(tree), action_names(tree), args.tree)
    report = replay(tree, domain, demos, lenient=args.lenient)
    if args.json:
        print(json.dumps(_as_json(report, domain), indent=2))
        return 0
    for result in report.results:
        if result.reproduced:
            print(f"  ok    {result.name}")
            continue
        d = result.divergence
        assert d is not None
        executed = d.executed if d.status.name == "RUNNING" else d.status.name
        print(f"  FAIL  {result.name}: line {d.line}: expected {d.expected}, tree gave {executed}"
              f"  [{domain.describe(d.state)}]")
    mode = "lenient" if args.lenient else "strict"
    print(f"{report.summary()} ({mode})")
    return 0


def _as_json(report, domain) -> dict:  # type: ignore[no-untyped-def]
    return {
        "reproduced": report.reproduced,
        "total": report.total,
        "mode": "lenient" if report.lenient else "strict",
        "demonstrations": [
            {"name": r.name, "reproduced": r.reproduced,
             **({"line": r.divergence.line, "expected": r.divergence.expected,
                 "status": r.divergence.status.name, "executed": r.divergence.executed,
                 "state": dict(zip(domain.condition_names, map(int, r.divergence.state), strict=True))}
                if r.divergence else {})}
            for r in report.results
        ],
    }
