"""Replay a scripted dialogue through the teaching session, headless.

Example:
    teach replay dialogues/quickstart.dialogue
    teach replay dialogues/study/participant3.dialogue --oracle-model demos/ball/domain.toml

The transcript is printed as the terminal would show it. Demonstrations go to
demos/<session>/, tree generations to trees/<session>/, the recording and the journal to
recordings/. The session is named after the dialogue file; replaying it again starts afresh.
"""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "replay"
HELP = "run a scripted dialogue through the teaching session (headless)"
ORDER = 11


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("dialogue", type=Path, help="dialogue file (see dialogues/README.md)")
    parser.add_argument("--session", help="session name (default: the dialogue file's name)")
    parser.add_argument("--domain", type=Path, help="domain.toml (default: the ball-in-bin domain)")
    parser.add_argument("--lang", choices=("en", "de"), help="language (default: the dialogue's @lang or en)")
    parser.add_argument("--questions", type=int, help="question budget (default: @questions or 5)")
    parser.add_argument("--world", choices=("mujoco", "symbolic", "offline"),
                        help="where demonstrations happen (default: @world or mujoco)")
    parser.add_argument("--seed", type=int, help="random seed of the world (default: @seed or 0)")
    oracle = parser.add_mutually_exclusive_group()
    oracle.add_argument("--oracle", type=Path, metavar="TREE.xml", help="answer questions as this tree would act")
    oracle.add_argument("--oracle-model", type=Path, metavar="DOMAIN.toml",
                        help="answer questions from this true action model")
    parser.add_argument("--no-record", action="store_true", help="do not write a rerun recording")
    parser.add_argument("--base", type=Path, default=Path("."), help="folder holding demos/, trees/, recordings/")


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    from teach.dialogue.model_repair import ModelOracle
    from teach.dialogue.oracle import oracle_from_model, oracle_from_tree
    from teach.dialogue.script import read_script
    from teach.domain import load_domain
    from teach.session.settings import Settings, WorldKind
    from teach.session.setup import open_session
    from teach.terminal.scripted import run_script

    script = read_script(args.dialogue)
    chosen = script.settings
    domain = args.domain or (Path(str(chosen["domain"])) if "domain" in chosen else None)
    settings = Settings(
        session=args.session or args.dialogue.stem, domain=domain,
        lang=args.lang or str(chosen.get("lang", "en")),
        questions=args.questions if args.questions is not None else int(str(chosen.get("questions", 5))),
        seed=args.seed if args.seed is not None else int(str(chosen.get("seed", 0))),
        world=WorldKind.parse(args.world or str(chosen.get("world", "mujoco"))),
        base=args.base, record=not args.no_record)
    manager = open_session(settings, fresh=True)
    oracle, model_oracle = None, None
    if args.oracle:
        oracle = oracle_from_tree(args.oracle, manager.domain)
    elif args.oracle_model:
        oracle = oracle_from_model(args.oracle_model, manager.domain)
        model_oracle = ModelOracle(load_domain(args.oracle_model))
    console = Console(highlight=False)
    try:
        run_script(script, manager, console, oracle, model_oracle)
    finally:
        manager.close()
    return 0
