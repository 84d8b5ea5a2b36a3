"""Write one of the safety bench's planning domains as a demonstration set teach reads.

    .venv/bin/python tools/export_planning_demos.py blocksworld demos/blocksworld --demos 2 --held-out 20

Writes FOLDER/domain.toml (every fact a condition and every operator an action, each with its
``form``, and the true model as ``pre``/``ram``; no goal, so it is learned), FOLDER/true-model.toml
(the same with the instance's goal: an oracle for ``teach bench-teach --oracle-model``), FOLDER/two/
(or the count given) with the optimal plans from random reachable starts as CSV files, and
FOLDER/held-out/ with plans from other starts. The learner reads neither ``pre`` nor ``ram``;
tests judge its tree against them.
"""

from __future__ import annotations

import argparse
import random
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT))

from foreign import ipc  # noqa: E402
from foreign.model import Task  # noqa: E402
from foreign.teaching import demonstration  # noqa: E402

from teach.demos import write_demonstration  # noqa: E402

COUNT_WORDS = {1: "one", 2: "two", 3: "three", 5: "five", 20: "twenty"}


def action_phrase(form: tuple[str, ...]) -> str:
    """``("stack", "b", "a")`` -> ``"stack b a"``: a phrase book keeps the words a domain's forms
    name as objects, filler words ("a") too, so no two actions read the same."""
    return " ".join([form[0].replace("_", " "), *form[1:]])


SAID_ALSO = {"stack": ("put {0} on {1}", "place {0} on {1}", "put {0} onto {1}", "move {0} onto {1}"),
             "unstack": ("take {0} off {1}", "take {0} from {1}", "remove {0} from {1}"),
             "pick_up": ("lift {0}", "grab {0}"),
             "put_down": ("put {0} on the table", "drop {0}", "set down {0}", "lay down {0}", "place {0} on the table")}
"""How people also say some IPC actions (blocksworld's), beside the form read out: "put a on c" was
"I don't know" (and, before typos had to name the objects typed, done as "put down c"); "lift a" was
"I don't know" too, and so were "place a on b", "put a onto b", "take a from b", "set a down"."""


def action_phrases(form: tuple[str, ...]) -> list[str]:
    """The form read out first (the action's label), then the other ways people say it."""
    return [action_phrase(form), *(said.format(*form[1:]) for said in SAID_ALSO.get(form[0], ()))]


SAID_DE = {"stack": ("leg {0} auf {1}", "stapel {0} auf {1}", "setz {0} auf {1}", "stell {0} auf {1}"),
           "unstack": ("nimm {0} von {1}", "heb {0} von {1}"),
           "pick_up": ("heb {0} auf", "nimm {0}", "nimm {0} auf"),
           "put_down": ("leg {0} ab", "stell {0} ab", "leg {0} auf den Tisch")}
"""German for blocksworld's actions: a German session showed "pick_up_a" and knew no German step."""
CONDITION_DE = {"clear": "{0} ist frei", "holding": "ich halte {0}", "on": "{0} liegt auf {1}",
                "ontable": "{0} liegt auf dem Tisch", "handempty": "meine Hand ist leer"}
"""German for blocksworld's conditions (the robot speaks of itself: "ich halte a")."""


def domain_toml(task: Task, with_goal: bool = False) -> str:
    model, domain = task.model, task.domain

    def strings(values: list[str] | tuple[str, ...]) -> str:
        return "[" + ", ".join(f'"{v}"' for v in values) + "]"

    def literals(true: int, false: int) -> list[str]:
        return [name if value else f"!{name}" for name, value in sorted(model.literals(true, false))]

    out = [f"# {task.name}, grounded from bench/foreign/pddl by tools/export_planning_demos.py.",
           f'name = "{task.name}"']
    if with_goal:
        out.append(f"goal = {strings(literals(model.goal_true, model.goal_false))}")
    out.append("")
    for condition in domain.conditions:
        german = CONDITION_DE.get(condition.form[0]) if condition.form else None
        out += ["[[condition]]", f'name = "{condition.name}"', f'en = "{condition.en}"',
                *([f'de = "{german.format(*condition.form[1:])}"'] if german else []),
                f"form = {strings(condition.form)}", ""]
    for action in domain.actions:
        operator = model.by_name[action.name]
        german_phrases = [said.format(*action.form[1:]) for said in SAID_DE.get(action.form[0], ())]
        out += ["[[action]]", f"id = {action.id}", f'name = "{action.name}"',
                f"en = {strings(action_phrases(action.form))}",
                *([f"de = {strings(german_phrases)}"] if german_phrases else []), f"form = {strings(action.form)}",
                f"pre = {strings(literals(operator.pre_true, operator.pre_false))}",
                f"ram = {strings(literals(operator.add, operator.delete))}", ""]
    return "\n".join(out)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("domain", choices=ipc.DOMAINS)
    parser.add_argument("folder", type=Path)
    parser.add_argument("--demos", type=int, default=2, help="how many demonstrations (default 2)")
    parser.add_argument("--held-out", type=int, default=20, help="how many held-out demonstrations (default 20)")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    task = ipc.load(args.domain)
    args.folder.mkdir(parents=True, exist_ok=True)
    (args.folder / "domain.toml").write_text(domain_toml(task))
    (args.folder / "true-model.toml").write_text(domain_toml(task, with_goal=True))
    starts = task.starts()
    random.Random(args.seed).shuffle(starts)
    for folder, chosen in ((COUNT_WORDS.get(args.demos, str(args.demos)), starts[:args.demos]),
                           ("held-out", starts[args.demos:args.demos + args.held_out])):
        (args.folder / folder).mkdir(exist_ok=True)
        for i, start in enumerate(chosen):
            write_demonstration(args.folder / folder / f"d{i + 1:02d}.csv", demonstration(task, start, f"d{i + 1:02d}"))
        print(f"{len(chosen)} demonstrations in {args.folder / folder}")


if __name__ == "__main__":
    main()
