"""Teach the robot live in the terminal.

Example:
    teach session                      # English, ball-in-bin world in MuJoCo, 5 questions
    teach session --lang de --questions 3
    teach session --label-questions 3  # guide the robot: `guide forward 0.4`, or `guide` alone for the keys
    teach session --resume session-20261122-101500

Type what the robot should do ("find the ball, go to the ball, ..."), `done` when the task
is finished, `help` for all commands. Ctrl-C interrupts a robot run, Ctrl-D saves and leaves.
"""

from __future__ import annotations

import argparse
import os
import stat
import sys
import time
from pathlib import Path

from teach.errors import TeachError

NAME = "session"
HELP = "teach the robot live in the terminal"
ORDER = 10


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--session", help="session name (default: session-<date>-<time>)")
    parser.add_argument("--resume", metavar="SESSION", help="continue a saved or crashed session")
    parser.add_argument("--domain", type=Path, help="domain.toml (default: the ball-in-bin domain)")
    parser.add_argument("--lang", choices=("en", "de"), default="en", help="language of the dialogue")
    parser.add_argument("--questions", type=int, default=5, help="most questions the robot may ask (default 5)")
    parser.add_argument("--label-questions", type=int, default=5, metavar="N",
                        help="most labelling questions about guided motion (default 5; apart from --questions)")
    parser.add_argument("--world", choices=("mujoco", "symbolic", "offline"), default="mujoco",
                        help="where demonstrations happen (default mujoco)")
    parser.add_argument("--seed", type=int, default=0, help="random seed of the world")
    parser.add_argument("--spawn", action="store_true", help="also stream to a live rerun viewer")
    parser.add_argument("--no-record", action="store_true", help="do not write a rerun recording")
    parser.add_argument("--groot", type=int, nargs="?", const=1667, metavar="PORT",
                        help="run trees through BehaviorTree.CPP, watched live by Groot2 on PORT (default 1667)")
    parser.add_argument("--viewer", action="store_true", help="show the MuJoCo viewer (needs a display)")
    parser.add_argument("--pace", type=float, default=1.0,
                        help="simulated seconds per wall-clock second, so you can watch and interrupt "
                             "(default 1: real time; 0 = as fast as possible)")
    parser.add_argument("--guess", action="store_true",
                        help="learn as the earlier model learner did, generalising by guessing (it may act where a "
                             "precondition does not hold; for comparison only: the default never acts on a guess)")
    parser.add_argument("--facilitator", action="store_true",
                        help="show identifiers as well: conditions by name, the symbolic tree (default: plain words)")
    parser.add_argument("--voice", "--stimme", action="store_true",
                        help="the robot says its lines aloud (offline; English or German) and writes them to "
                             "recordings/<session>/speech/")
    parser.add_argument("--listen", action="store_true",
                        help="push-to-talk: F5 or the line 'listen' records what you say (English only, offline)")
    parser.add_argument("--base", type=Path, default=Path("."), help="folder holding demos/, trees/, recordings/")


def run(args: argparse.Namespace) -> int:
    from teach import messages as m
    from teach.fsutil import check_output
    from teach.messages import Lang
    from teach.session.settings import Settings
    from teach.session.setup import opened_session
    from teach.session.store import session_root
    from teach.terminal.app import Terminal

    if not args.pace >= 0 or args.pace == float("inf"):  # also refuses nan
        raise TeachError("--pace must be a number of 0 or more (0: as fast as the simulation goes)")
    if args.label_questions < 0:
        raise TeachError("--label-questions must be 0 or more")
    if args.listen:
        from teach.voice.listen import check_language

        check_language(args.lang)
    if _stdin_is_a_file():  # the terminal would read nothing from it and quit as if all was done
        raise TeachError(m.STDIN_IS_A_FILE(args.lang), "<stdin>")
    name = args.resume or args.session or time.strftime("session-%Y%m%d-%H%M%S")
    settings = Settings(session=name, domain=args.domain, lang=Lang.parse(args.lang), questions=args.questions,
                        seed=args.seed, world=args.world, base=args.base, record=not args.no_record, spawn=args.spawn,
                        viewer=args.viewer, pace=args.pace, label_questions=args.label_questions,
                        facilitator=args.facilitator, groot=args.groot, voice=args.voice, safe=not args.guess)
    history = args.base / "recordings" / ".teach_history"
    check_output(history, session_root(args.base))  # read at the first prompt: never a FIFO, folder or link
    with opened_session(settings, resume=bool(args.resume)) as manager:
        listen = None
        if args.listen:
            from teach.voice.listen import Listener

            view = manager.view()
            listen = Listener(view.domain, view.lang, print).listen
        try:
            if not settings.voice:
                Terminal(manager, history=history, listen=listen).run()
                return 0
            from teach.voice.session import spoken_session

            with spoken_session(manager) as on_shown:
                Terminal(manager, history=history, on_shown=on_shown, listen=listen).run()
        except OSError as error:
            if error.filename:
                raise
            # prompt_toolkit's line history names no file when writing it fails (a full disk)
            raise TeachError(f"cannot write: {error.strerror or error}", history) from None
    return 0


def _stdin_is_a_file() -> bool:
    try:
        return stat.S_ISREG(os.fstat(sys.stdin.fileno()).st_mode)
    except (OSError, ValueError):  # no standard input at all
        return False
