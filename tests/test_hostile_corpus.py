"""The hostile corpus (tests/hostile_corpus.py) through every command that reads each kind of file,
and every hostile output path through every command that writes one: each run must end with
exit status 2 and one line ``teach: FILE[:LINE]: what is wrong`` naming the bad file, no
traceback, no hang (each run has an alarm), nothing on standard output, no file changed and no
process left running.

The runs go through ``teach.cli.main`` in forked processes (tests/cli_batch.py); a sample (one
run of every special file and output path, and every 60th run) also through fresh
``python -m teach.cli`` processes, which must give byte-identical results.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import stat
import subprocess
import sys
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from conftest import ROOT
from hostile_corpus import (
    GOOD_DEMO,
    GOOD_DIALOGUE,
    GOOD_DOMAIN,
    GOOD_TREE,
    MOTION_SESSION,
    SESSION_KINDS,
    corpus,
    materialise,
    outputs,
)

ERROR_LINE = re.compile(r"^teach: (?P<path>.+?)(?::(?P<line>\d+))?: (?P<message>\S[^\n]*)\n$")
TIMEOUT = 30
PARALLEL = 2
ENV = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "LANG": "C.UTF-8"}

READERS = {
    "tree": [("show", "{P}"), ("dot", "{P}", "-o", "out.dot"), ("prune", "{P}", "-o", "out.xml"),
             ("test", "{P}", "{SET}"), ("bench-teach", "{SET}", "{SET}", "--oracle", "{P}", "--questions", "1")],
    "domain": [("learn", "{SET}", "--domain", "{P}", "-o", "out.xml"), ("learn", "{P}", "--approach", "pabt", "-o",
                                                                          "out.xml"),
               ("test", "{TREE}", "{SET}", "--domain", "{P}"), ("show", "{TREE}", "--domain", "{P}"),
               ("prune", "{TREE}", "--domain", "{P}", "-o", "out.xml"),
               ("bench-teach", "{SET}", "{SET}", "--oracle-model", "{P}", "--questions", "1"),
               ("replay", "{DIALOGUE}", "--domain", "{P}", "--no-record"),
               ("session", "--domain", "{P}", "--world", "offline", "--no-record"),
               ("table", "--demos", "{PDIR}", "--json"),
               ("table", "--demos", "{BALL}", "--study", "{PSTUDY}", "--json")],
    "csv": [("test", "{TREE}", "{P}"), ("learn", "{P}", "-o", "out.xml"),
            ("learn", "{P}", "--approach", "detect", "-o", "out.xml"),
            ("bench-teach", "{P}", "{SET}", "--oracle", "{TREE}", "--questions", "1"),
            ("bench-teach", "{SET}", "{P}", "--oracle", "{TREE}", "--questions", "1")],
    "dialogue": [("replay", "{P}", "--world", "offline", "--no-record"),
                 ("replay", "{P}", "--world", "offline", "--no-record", "--oracle", "{TREE}")],
}
READERS["set"] = READERS["csv"]
READERS["world"] = [("session", "--domain", "{PBASE}/domain.toml", "--world", "symbolic", "--no-record"),
                    ("replay", "{DIALOGUE}", "--domain", "{PBASE}/domain.toml", "--world", "symbolic", "--no-record")]
READERS["journal"] = READERS["motion"] = [("session", "--base", "{PBASE}", "--resume", MOTION_SESSION, "--no-record")]
READERS["recording"] = [("review", "{P}"), ("review", "{P}", "--step", "3")]
READERS["btlog"] = [("review", "{P}")]


@dataclass(frozen=True)
class Run:
    name: str
    argv: tuple[str, ...]
    cwd: Path
    expect: str  # the path the error must name (or a folder the named file lies in)
    special: bool


def snapshot(folder: Path) -> dict[str, str]:
    """Every entry under ``folder`` with its type and content (file hash, link target)."""
    seen = {}
    for top, folders, files in os.walk(folder):
        for name in folders + files:
            path = Path(top) / name
            info = os.lstat(path)
            if stat.S_ISREG(info.st_mode):
                seen[str(path)] = "file " + hashlib.sha256(path.read_bytes()).hexdigest()
            elif stat.S_ISLNK(info.st_mode):
                seen[str(path)] = "link " + os.readlink(path)
            else:
                seen[str(path)] = f"mode {stat.S_IFMT(info.st_mode):o}"
    return seen


def build(tmp_path: Path) -> list[Run]:
    """Materialise the corpus and the good inputs, and list every run with its own empty folder."""
    inputs = tmp_path / "corpus"
    inputs.mkdir()
    good = inputs / "good"
    (good / "set").mkdir(parents=True)
    (good / "set" / "domain.toml").write_bytes(GOOD_DOMAIN)
    (good / "set" / "d1.csv").write_bytes(GOOD_DEMO)
    (good / "tree.xml").write_bytes(GOOD_TREE)
    (good / "good.dialogue").write_bytes(GOOD_DIALOGUE)
    fill = {"SET": str(good / "set"), "TREE": str(good / "tree.xml"), "DIALOGUE": str(good / "good.dialogue"),
            "BALL": str(ROOT / "demos" / "ball")}
    runs: list[Run] = []

    def folder() -> Path:
        path = tmp_path / "runs" / f"{len(runs):04d}"
        path.mkdir(parents=True)
        return path

    for entry in corpus():
        path = str(inputs / materialise(entry, inputs))
        places = {"P": path}
        if entry.kind == "csv" and not entry.special:  # the set holding the bad file is read; the error names the file
            places["P"] = str(Path(path).parent)
        if entry.kind in SESSION_KINDS:  # found by name in a folder of good files: the domain's, the session's
            places["PBASE"] = str(Path(path).parents[SESSION_KINDS[entry.kind]])
        if entry.kind == "domain":  # `teach table` finds domains by name: DIR/domain.toml, STUDY/participantN.toml
            for key, file in (("PDIR", "domain.toml"), ("PSTUDY", "participant1.toml")):
                where = inputs / f"as-{file}" / entry.name
                where.mkdir(parents=True)
                (where / file).symlink_to(os.path.abspath(path))
                places[key] = str(where)
        for command in READERS[entry.kind]:
            if entry.kind == "set" and "domain" in entry.special and command[2] == "{P}":
                continue  # a test set is read with the training set's domain, never its own
            argv = tuple(part.format(**places, **fill) for part in command)
            expect = next((places[key] for key in ("PDIR", "PSTUDY") if "{" + key + "}" in command), path)
            if entry.kind == "btlog":  # the bad log lies in the recording's run folder
                expect = str(Path(path).with_suffix(""))
            runs.append(Run(f"{entry.kind}/{entry.name}: {command[0]}", argv, folder(), expect,
                            bool(entry.special)))
    for case in outputs(fill["TREE"], fill["SET"], fill["DIALOGUE"]):
        cwd = folder()
        case.setup(cwd)
        runs.append(Run(f"output/{case.name}", case.args, cwd, case.expect, True))
    return runs


def through_batch(runs: list[Run], logs: Path) -> list[tuple[int, str, str]]:
    jobs = [{"argv": list(run.argv), "cwd": str(run.cwd), "stdout": str(logs / f"{i}.out"),
             "stderr": str(logs / f"{i}.err"), "timeout": TIMEOUT} for i, run in enumerate(runs)]
    done = subprocess.run([sys.executable, str(ROOT / "tests" / "cli_batch.py"), str(PARALLEL)],
                          input=json.dumps(jobs), capture_output=True, text=True, env=ENV, check=True)
    statuses = [result["status"] for result in json.loads(done.stdout)]
    return [(status, (logs / f"{i}.out").read_text(errors="replace"), (logs / f"{i}.err").read_text(errors="replace"))
            for i, status in enumerate(statuses)]


def through_processes(runs: list[Run]) -> list[tuple[int, str, str]]:
    def one(run: Run) -> tuple[int, str, str]:
        try:
            done = subprocess.run([sys.executable, "-m", "teach.cli", *run.argv], cwd=run.cwd, capture_output=True,
                                  stdin=subprocess.DEVNULL, env=ENV, timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            return -14, "", "hang"
        return done.returncode, done.stdout.decode(errors="replace"), done.stderr.decode(errors="replace")

    with ThreadPoolExecutor(PARALLEL) as pool:
        return list(pool.map(one, runs))


def problem(run: Run, status: int, stdout: str, stderr: str) -> str | None:
    """What is wrong with one run's result, or None."""
    if status == -14:
        return "hangs (killed after the timeout)"
    if "Traceback" in stderr:
        return "traceback: " + stderr.strip().splitlines()[-1]
    if status != 2:
        return f"exit status {status}: {stderr.strip()[:200]!r}"
    if stdout:
        return f"printed {stdout[:100]!r}"
    match = ERROR_LINE.match(stderr)
    if not match:
        return f"not one 'teach: FILE[:LINE]: message' line: {stderr[:300]!r}"
    named = match["path"]
    if named != run.expect and not named.startswith(run.expect.rstrip("/") + "/"):
        return f"names {named!r}, not {run.expect!r}: {stderr.strip()!r}"
    return None


def processes_in(folder: Path) -> list[str]:
    """Processes (a child a command started, like ``rerun rrd verify``) still running with their
    working folder or a command-line argument under ``folder``."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdecimal():
            continue
        try:
            where = os.readlink(entry / "cwd")
            argv = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:  # ended meanwhile, or another user's
            continue
        if where.startswith(str(folder)) or any(arg.startswith(str(folder).encode()) for arg in argv):
            found.append(f"{entry.name}: {b' '.join(argv).decode(errors='replace')[:200]}")
    return found


def test_every_hostile_input_and_output_path_gives_one_line_and_changes_nothing(tmp_path: Path) -> None:
    runs = build(tmp_path)
    kinds = Counter(run.name.split("/")[0] for run in runs)
    entries = {run.name.split(":")[0] for run in runs}
    assert len(entries) >= 600, f"only {len(entries)} hostile files and paths"
    logs = tmp_path.parent / f"{tmp_path.name}-logs"
    logs.mkdir()
    before = snapshot(tmp_path)

    results = through_batch(runs, logs)
    failures = [f"{run.name}: {what}" for run, result in zip(runs, results, strict=True)
                if (what := problem(run, *result)) is not None]

    sample = sorted({run.name.split(":")[0]: i for i, run in enumerate(runs) if run.special}.values())
    sample += [i for i in range(0, len(runs), 60) if i not in sample]
    fresh = through_processes([runs[i] for i in sample])
    differ = [f"{runs[i].name}: batch gave {results[i]!r}, a fresh process {again!r}"
              for i, again in zip(sample, fresh, strict=True) if again != results[i]]

    after = snapshot(tmp_path)
    changed = sorted(set(before.items()) ^ set(after.items()))
    left = processes_in(tmp_path)
    print(f"\nhostile corpus: {len(entries)} files and paths ({dict(sorted(kinds.items()))} runs), "
          f"{len(runs)} runs, {len(runs) - len(failures)} one-line errors with exit 2; "
          f"{len(sample)} also in fresh processes")
    assert not failures, f"{len(failures)} of {len(runs)} runs broke the promise:\n" + "\n".join(failures[:60])
    assert not differ, "\n".join(differ[:20])
    assert not changed, f"files changed: {changed[:20]}"
    assert not left, f"processes left running in the runs' folders: {left}"
