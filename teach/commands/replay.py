"""Replay a scripted dialogue through the teaching session, headless.

Example:
    teach replay dialogues/quickstart.dialogue
    teach replay dialogues/study/participant3.dialogue --oracle-model demos/ball/domain.toml

The transcript is printed as the terminal would show it. Demonstrations go to
demos/<session>/, tree generations to trees/<session>/, the recording and the journal to
recordings/. The session is named after the dialogue file; replaying the same dialogue again
starts afresh. Everything is read and checked (dialogue, domain, oracles) before anything of an
earlier session is touched, and a session that was not made by replaying this dialogue is only
replaced with --overwrite.
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
    parser.add_argument("--label-questions", type=int, default=5, metavar="N",
                        help="most labelling questions about guided motion (default 5)")
    parser.add_argument("--world", choices=("mujoco", "symbolic", "offline"),
                        help="where demonstrations happen (default: @world or mujoco)")
    parser.add_argument("--seed", type=int, help="random seed of the world (default: @seed or 0)")
    oracle = parser.add_mutually_exclusive_group()
    oracle.add_argument("--oracle", type=Path, metavar="TREE.xml", help="answer questions as this tree would act")
    oracle.add_argument("--oracle-model", type=Path, metavar="DOMAIN.toml",
                        help="answer questions from this true action model")
    parser.add_argument("--no-record", action="store_true", help="do not write a rerun recording")
    parser.add_argument("--groot", type=int, nargs="?", const=1667, metavar="PORT",
                        help="run trees through BehaviorTree.CPP, watched live by Groot2 on PORT (default 1667)")
    parser.add_argument("--pace", type=float,
                        help="simulated seconds per wall-clock second in MuJoCo, so a run can be watched "
                             "(default: 1 with --groot, else 0 = as fast as possible)")
    parser.add_argument("--base", type=Path, default=Path("."), help="folder holding demos/, trees/, recordings/")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace a session of the same name that was not made by replaying this dialogue")
    parser.add_argument("--guess", action="store_true",
                        help="learn as the earlier model learner did, generalising by guessing (it may act where a "
                             "precondition does not hold; for comparison only: the default never acts on a guess)")
    parser.add_argument("--facilitator", action="store_true",
                        help="show identifiers as well: conditions by name, the symbolic tree (default: plain words)")
    parser.add_argument("--lenient", action="store_true",
                        help="type lines the session does not know at the prompt anyway (default: refuse the file)")


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    from teach import messages as m
    from teach.dialogue.model_repair import ModelOracle
    from teach.dialogue.oracle import SituationOracle, oracle_from_model, oracle_from_tree
    from teach.dialogue.phrases import PhraseBook
    from teach.dialogue.script import AUDIO, read_script
    from teach.domain import load_domain
    from teach.errors import TeachError
    from teach.messages import Lang
    from teach.session.dialogue_check import check_lines
    from teach.session.settings import Settings, WorldKind
    from teach.session.setup import dialogue_events, opened_session, session_domain
    from teach.session.store import SessionStore
    from teach.terminal.scripted import run_script

    # everything the replay needs is read and checked first: a bad input leaves the session as it was
    pace = args.pace if args.pace is not None else 1.0 if args.groot is not None else 0.0
    if not pace >= 0 or pace == float("inf"):  # also refuses nan
        raise TeachError("--pace must be a number of 0 or more (0: as fast as the simulation goes)")
    script = read_script(args.dialogue)
    chosen = script.settings
    domain_path = args.domain or (Path(str(chosen["domain"])) if "domain" in chosen else None)
    settings = Settings(
        session=args.session or args.dialogue.stem, domain=domain_path,
        lang=Lang.parse(args.lang or str(chosen.get("lang", "en"))),
        questions=args.questions if args.questions is not None else int(str(chosen.get("questions", 5))),
        seed=args.seed if args.seed is not None else int(str(chosen.get("seed", 0))),
        world=WorldKind.parse(args.world or str(chosen.get("world", "mujoco"))),
        base=args.base, record=not args.no_record, label_questions=args.label_questions,
        facilitator=args.facilitator, groot=args.groot, safe=not args.guess, pace=pace)
    if args.label_questions < 0:
        raise TeachError("--label-questions must be 0 or more")
    domain = session_domain(settings)
    heard = [("audio file", script.path.parent / line[len(AUDIO):].strip())
             for _, line in script.lines if line.startswith(AUDIO)]
    if heard:
        from teach.voice.script import heard_script

        script = heard_script(script, domain, settings.lang)
    if not args.lenient:
        check_lines(script, domain, PhraseBook(domain, dialogue_events(settings, domain)), settings.lang)
    oracle: SituationOracle | None = None
    model_oracle: ModelOracle | None = None
    if args.oracle:
        oracle = oracle_from_tree(args.oracle, domain)
    elif args.oracle_model:
        oracle = oracle_from_model(args.oracle_model, domain)
        model_oracle = ModelOracle(load_domain(args.oracle_model))
    origin = f"replay:{args.dialogue.resolve()}"

    def replaceable(store: SessionStore) -> None:
        """A replay replaces an earlier session of its name only when that session was a replay
        of the same dialogue, or when asked to with ``--overwrite``."""
        if args.overwrite or not store.exists():
            return
        try:
            same = store.load_journal().origin == origin
        except TeachError:
            same = False
        if not same:
            raise TeachError(m.REPLAY_NEEDS_OVERWRITE("en", session=settings.session, dialogue=args.dialogue),
                             store.journal_path if store.has_journal() else store.demo_dir)

    console = Console(highlight=False)
    reads = [("dialogue", args.dialogue), ("tree file", args.oracle), ("domain file", args.oracle_model), *heard]
    with opened_session(settings, fresh=True, domain=domain, origin=origin, before_clearing=replaceable,
                        inputs=[(what, path) for what, path in reads if path is not None]) as manager:
        run_script(script, manager, console, oracle, model_oracle)
    return 0
