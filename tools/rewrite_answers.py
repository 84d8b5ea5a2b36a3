"""Write a dialogue's answers anew for the questions the robot asks today.

    .venv/bin/python tools/rewrite_answers.py dialogues/quickstart.dialogue [--check]

A scripted dialogue holds the teacher's answers to the robot's questions as plain lines
(dialogues/README.md), so a change of the learner or its questions leaves answers that answer
other questions. This replays the dialogue twice in its own world: once as written, to find
the lines that were taken as answers, and once without them, answering each question the robot
asks as the Table 6.1 behaviour would (demos/ball/reference/table61.xml): "yes" to "may I still
do X here?" where that behaviour does X there (and to "is the task done here?" where it is
done), otherwise what it does there. The dialogue is rewritten in place (atomically) with the
old answer lines removed and the new ones after the line that made the robot ask; comments and
settings stay. ``--check`` only says whether the answers are current (exit 1 if not).

    .venv/bin/python tools/rewrite_answers.py DIALOGUE --before ../main

``--before CHECKOUT``: the answers were written for the questions of the code in CHECKOUT (a
checkout of an earlier commit, safe learner), not for the guessing learner: the first replay
runs there, in a child process, so a change of the questions can be answered anew.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from rich.console import Console

ROOT = Path(__file__).resolve().parent.parent
CODE = Path(os.environ.get("TEACH_CODE", ROOT))
"""Whose ``teach`` is imported: this checkout's, or (in the child of ``--before``) the earlier one's."""
sys.path.insert(0, str(CODE))

from teach.dialogue.oracle import SKIP, Oracle, oracle_from_tree  # noqa: E402
from teach.dialogue.script import Script, read_script  # noqa: E402
from teach.fsutil import atomic_write_text  # noqa: E402
from teach.messages import Lang  # noqa: E402
from teach.session.machine import SessionManager  # noqa: E402
from teach.session.settings import Settings, WorldKind  # noqa: E402
from teach.session.setup import opened_session, session_domain  # noqa: E402

TABLE61 = ROOT / "demos" / "ball" / "reference" / "table61.xml"
YES = {"en": "yes", "de": "ja"}


def settings_of(script: Script, path: Path, base: Path, safe: bool) -> Settings:
    chosen = script.settings
    return Settings(session=path.stem, domain=Path(str(chosen["domain"])) if "domain" in chosen else None,
                    lang=Lang.parse(str(chosen.get("lang", "en"))), questions=int(str(chosen.get("questions", 5))),
                    seed=int(str(chosen.get("seed", 0))), world=WorldKind.parse(str(chosen.get("world", "mujoco"))),
                    base=base, record=False, safe=safe)


def answer_lines(script: Script, path: Path, base: Path, safe: bool = False) -> set[int]:
    """The file lines the code in use takes as answers: with the guessing learner (``safe`` False),
    the one the answers were written for before issue 18."""
    taken: set[int] = set()
    settings = settings_of(script, path, base / "old", safe=safe)
    with opened_session(settings, fresh=True, domain=session_domain(settings)) as manager:
        _quiet(manager)
        for number, line in script.lines:
            if manager.pending is not None:
                taken.add(number)
            manager.handle(line)
    return taken


def honest(manager: SessionManager, oracle: Oracle) -> str:
    """What the Table 6.1 behaviour answers to the open question."""
    question = manager.pending
    assert question is not None
    does = oracle.answer(question.state)
    lang = manager.lang
    if question.kind == "must-precondition" and does == question.action:
        return YES[lang]
    if question.kind == "must-goal" and does is None:
        return YES[lang]
    if does == SKIP:
        return "skip" if lang == "en" else "weiter"
    return ("done" if lang == "en" else "fertig") if does is None else manager.domain.action(does).label(lang)


def new_answers(script: Script, path: Path, base: Path, dropped: set[int]) -> dict[int, list[str]]:
    """For each file line, the answers to the questions its handling raised (safe learner)."""
    settings = settings_of(script, path, base / "new", safe=True)
    domain = session_domain(settings)
    oracle = oracle_from_tree(TABLE61, domain)
    answers: dict[int, list[str]] = {}
    with opened_session(settings, fresh=True, domain=domain) as manager:
        _quiet(manager)
        for number, line in script.lines:
            if number in dropped:
                continue
            manager.handle(line)
            while manager.pending is not None and len(answers.get(number, [])) < 20:
                said = honest(manager, oracle)
                answers.setdefault(number, []).append(said)
                manager.handle(said)
    return answers


def answer_lines_before(dialogue: Path, checkout: Path) -> set[int]:
    """The file lines the code in ``checkout`` takes as answers (safe learner), found in a child
    process that imports that checkout's ``teach``."""
    child = subprocess.run([sys.executable, __file__, str(dialogue), "--print-taken"], capture_output=True,
                           text=True, check=True, env={**os.environ, "TEACH_CODE": str(checkout.resolve())})
    return set(json.loads(child.stdout))


def _quiet(manager: SessionManager) -> None:
    manager.live = None
    manager.greet()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dialogue", type=Path)
    parser.add_argument("--check", action="store_true", help="only say whether the answers are current")
    parser.add_argument("--before", type=Path, metavar="CHECKOUT",
                        help="the answers were written for the code in this checkout (safe learner)")
    parser.add_argument("--print-taken", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    script = read_script(args.dialogue)
    with tempfile.TemporaryDirectory() as scratch:
        base = Path(scratch)
        if args.print_taken:
            print(json.dumps(sorted(answer_lines(script, args.dialogue, base, safe=True))))
            return 0
        if args.before is not None:
            dropped = answer_lines_before(args.dialogue, args.before)
        else:
            dropped = answer_lines(script, args.dialogue, base)
        answers = new_answers(script, args.dialogue, base, dropped)
    text = args.dialogue.read_text(encoding="utf-8").splitlines()
    out: list[str] = []
    for number, line in enumerate(text, start=1):
        if number in dropped:
            continue
        out.append(line)
        out += answers.get(number, [])
    rewritten = "\n".join(out) + "\n"
    current = rewritten == args.dialogue.read_text(encoding="utf-8")
    Console(stderr=True).print(f"{args.dialogue}: {len(dropped)} old answer line(s), "
                               f"{sum(map(len, answers.values()))} new; {'current' if current else 'rewritten'}")
    if args.check:
        return 0 if current else 1
    if not current:
        atomic_write_text(args.dialogue, rewritten)
    return 0


if __name__ == "__main__":
    sys.exit(main())
