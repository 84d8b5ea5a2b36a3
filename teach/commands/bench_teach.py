"""Teaching from few demonstrations: learn, ask up to N questions of an oracle, replay a test set.

Example:
    teach bench-teach demos/ball/delta4 demos/ball/delta5 --oracle demos/ball/reference/table61.xml --questions 5
    teach bench-teach demos/ball/delta4 demos/ball/delta5 --oracle-model demos/ball/domain.toml -o learned.xml

Learns with the session's own learner and question selector, answers every question from
the oracle, then replays TEST_DIR: ends with `reproduced K/N` under the strict replay (the
lenient figure beside it). `-o TREE.xml` writes the tree learned after the questions (the
one replayed), as `teach learn -o` does: an existing file is replaced, atomically, but never one
the command reads (the oracle, a domain, anything in either set).

`--oracle-model` answers each question with the first step of a shortest plan from the
question's own situation in that model; a question in a situation from which the model's
goal cannot be reached is refused (one line, exit status 2, nothing written).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

NAME = "bench-teach"
HELP = "learn from demonstrations plus oracle-answered questions, then replay a test set"
ORDER = 40


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("train", type=Path, help="folder of training demonstrations")
    parser.add_argument("test", type=Path, help="folder of test demonstrations")
    oracle = parser.add_mutually_exclusive_group(required=True)
    oracle.add_argument("--oracle", type=Path, metavar="TREE.xml", help="reference tree answering the questions")
    oracle.add_argument("--oracle-model", type=Path, metavar="DOMAIN.toml", help="true action model answering them")
    parser.add_argument("--questions", type=int, default=5, help="question budget (default 5)")
    parser.add_argument("--domain", type=Path, help="domain.toml (default: found beside the demonstrations)")
    parser.add_argument("--lang", choices=("en", "de"), default="en")
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON")
    parser.add_argument("-o", "--output", type=Path, metavar="TREE.xml",
                        help="write the tree learned after the questions")


def outputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command writes, checked and locked before it runs (teach.lock.claim_outputs)."""
    return [("file", args.output)] if args.output else []


def inputs(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """What this command reads, which no output may replace (teach.protect)."""
    named = [("tree file", args.oracle), ("domain file", args.oracle_model), ("domain file", args.domain)]
    return [("set", args.train), ("set", args.test)] + [(what, path) for what, path in named if path]


def run(args: argparse.Namespace) -> int:
    import tempfile

    from teach.bt.xml import write_tree
    from teach.demos import read_demo_set
    from teach.dialogue.oracle import answer_open_questions, oracle_from_model, oracle_from_tree
    from teach.domain import load_domain
    from teach.errors import TeachError
    from teach.messages import Lang
    from teach.observe.hook import Observer
    from teach.replay import replay
    from teach.session.machine import SessionManager
    from teach.session.settings import Settings, WorldKind
    from teach.world.offline import OfflineWorld

    if args.questions < 0:
        raise TeachError("--questions must be 0 or more")
    domain = load_domain(args.domain) if args.domain else None
    domain, train = read_demo_set(args.train, domain)
    _, test = read_demo_set(args.test, domain)
    oracle = oracle_from_tree(args.oracle, domain) if args.oracle else oracle_from_model(args.oracle_model, domain)
    asked: list[dict] = []

    class Questions(Observer):
        def on_question(self, question: str, budget_left: int) -> None:
            asked.append({"question": question})

        def on_answer(self, question: str, answer: str, change: str) -> None:
            asked[-1].update(answer=answer, change=change)

    with tempfile.TemporaryDirectory(prefix="teach-bench-") as scratch:
        settings = Settings("bench", lang=Lang.parse(args.lang), questions=args.questions, world=WorldKind.OFFLINE,
                            base=Path(scratch), record=False)
        manager = SessionManager(settings, domain, OfflineWorld(domain), Questions())
        manager.import_demonstrations(train)
        while manager.view().questions_left > 0:
            manager.handle("ask")
            if manager.pending is None:  # no situation question (nothing else can open here)
                break
            answer_open_questions(manager, oracle)
        tree = manager.pruned
    if tree is None:
        raise TeachError("the training demonstrations show no action, so there is nothing to learn", args.train)
    strict = replay(tree, domain, test)
    lenient = replay(tree, domain, test, lenient=True)
    if args.output:
        write_tree(args.output, tree)  # checked before learning (see outputs)
    if args.json:
        summary = {"questions": asked, "reproduced": strict.reproduced, "total": strict.total,
                   "lenient": lenient.reproduced}
        print(json.dumps(summary | ({"tree": str(args.output)} if args.output else {}), indent=2, ensure_ascii=False))
        return 0
    for number, item in enumerate(asked, start=1):
        print(f"Q{number}: {item['question']}")
        print(f"    answer: {item.get('answer', '-')}  ->  {item.get('change', '')}")
    print(f"{len(asked)} question{'' if len(asked) == 1 else 's'} asked (budget {args.questions})")
    print(f"reproduced {strict.reproduced}/{strict.total} (strict); lenient {lenient.reproduced}/{lenient.total}")
    if args.output:
        print(f"tree learned after the questions -> {args.output}")
    return 0
