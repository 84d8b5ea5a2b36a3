"""A session killed with SIGKILL loses nothing: everything taught before the kill is back after
`teach session --resume`."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from teach.bt.xml import read_tree
from teach.session import messages as m
from teach.session.journal import DemoLearned
from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.world.symbolic import SymbolicWorld

SEQUENCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"


def test_sigkill_then_resume(ball, tmp_path):
    script = tmp_path / "long.dialogue"
    lines = ["@world symbolic", "@questions 0", SEQUENCE, "done"]
    for _ in range(400):  # keep the process busy long after the first demonstration
        lines += ["start BallFound", "go to the ball, grasp the ball, go to the bin, put the ball in the bin", "done"]
    script.write_text("\n".join(lines) + "\n", encoding="utf-8")
    journal = tmp_path / "recordings" / "long.journal.json"
    process = subprocess.Popen([sys.executable, "-m", "teach.cli", "replay", str(script), "--no-record",
                                "--base", str(tmp_path)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            if journal.exists() and sum(e["kind"] == "demo" for e in json.loads(journal.read_text())["events"]) >= 3:
                break
            assert process.poll() is None, process.stderr.read().decode()
            time.sleep(0.05)
        os.kill(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    events = [e for e in json.loads(journal.read_text())["events"] if e["kind"] == "demo"]  # valid JSON: atomic
    assert len(events) >= 3
    demos = sorted((tmp_path / "demos" / "long").glob("demo-*.csv"))
    assert len(demos) >= len(events)  # every journalled demonstration is on disk
    settings = Settings("long", lang="en", questions=0, world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    resumed = SessionManager.resume(settings, ball, SymbolicWorld(ball))
    assert len(resumed.demos) == len(events)
    # the resumed learner is the one that was killed: its pruned tree equals the last generation saved
    generations = sorted((tmp_path / "trees" / "long").glob("gen-*.xml"))
    assert resumed.pruned == read_tree(generations[len(events) - 1])
    # and the CLI resumes it too
    result = subprocess.run([sys.executable, "-m", "teach.cli", "session", "--resume", "long", "--world", "symbolic",
                             "--no-record", "--base", str(tmp_path)], input="quit\n", text=True,
                            capture_output=True, timeout=120)
    assert result.returncode == 0 and f"{len(events)} demonstrations" in result.stdout


def test_recording_survives_a_kill_and_a_resume(tmp_path):
    from teach.observe.reader import read_recording

    script = tmp_path / "rec.dialogue"
    lines = ["@world symbolic", "@questions 0", SEQUENCE, "done"]
    for _ in range(400):
        lines += ["start BallFound", "go to the ball, grasp the ball, go to the bin, put the ball in the bin", "done"]
    script.write_text("\n".join(lines) + "\n", encoding="utf-8")
    journal = tmp_path / "recordings" / "rec.journal.json"
    process = subprocess.Popen([sys.executable, "-m", "teach.cli", "replay", str(script), "--base", str(tmp_path)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            if journal.exists() and len(json.loads(journal.read_text())["events"]) >= 3:
                break
            time.sleep(0.05)
        os.kill(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    result = subprocess.run([sys.executable, "-m", "teach.cli", "session", "--resume", "rec", "--base", str(tmp_path)],
                            input="state\nquit\n", text=True, capture_output=True, timeout=120)
    assert result.returncode == 0, result.stderr
    contents = read_recording(tmp_path / "recordings" / "rec.rrd")
    said = [line.text for line in contents.dialogue if line.speaker == "teacher"]
    # what was said before the kill and after the resume are both in the one recording, in order
    # (killed in the middle of a demonstration, the first quit only warns that it is still open)
    assert SEQUENCE in said and said[-1] == "quit" and "state" in said[-3:]
    steps = [line.step for line in contents.dialogue]
    assert steps == sorted(steps)


KILLS = 20


def _acknowledged(transcript: str) -> tuple[int, int]:
    """What the killed process told the teacher was taken: answers thanked for, and the last generation."""
    thanked = sum(line.startswith("Thank you.") for line in transcript.splitlines())
    generations = [int(line.split()[1].rstrip(":")) for line in transcript.splitlines()
                   if line.startswith("Generation ") and line.split()[1].rstrip(":").isdigit()]
    return thanked, max(generations, default=0)


def test_twenty_kills_at_random_moments_lose_nothing_acknowledged(tmp_path):
    """A scripted session answered by an oracle is killed at 20 seeded random moments; each is
    resumed. Every answer it thanked for and every generation it announced is in the resumed
    journal, and the demonstrations folder holds exactly the journalled demonstrations."""
    import random

    from teach.session.setup import opened_session

    script = tmp_path / "kill.dialogue"
    lines = ["@world symbolic", "@questions 5", SEQUENCE, "done"]
    for start in ["BallFound", "BinClose", "BallFound BallClose", ""] * 100:
        lines += [f"start {start}" if start else "reset", SEQUENCE if "BallFound" not in start else
                  "go to the ball, grasp the ball, go to the bin, put the ball in the bin", "done"]
    script.write_text("\n".join(lines) + "\n", encoding="utf-8")
    from conftest import BALL_DOMAIN

    moments = random.Random(14).sample(range(1500, 6000, 50), KILLS)
    checked, most_thanked, set_aside = 0, 0, 0
    for trial, moment in enumerate(moments):
        base = tmp_path / f"trial-{trial}"
        out = base / "transcript.txt"
        base.mkdir()
        with out.open("w") as transcript:
            process = subprocess.Popen([sys.executable, "-m", "teach.cli", "replay", str(script), "--no-record",
                                        "--base", str(base), "--oracle-model", str(BALL_DOMAIN)],
                                       stdout=transcript, stderr=subprocess.DEVNULL,
                                       env={**os.environ, "PYTHONUNBUFFERED": "1", "COLUMNS": "200"})
            time.sleep(moment / 1000)
            os.kill(process.pid, signal.SIGKILL)
            process.wait()
        thanked, generation = _acknowledged(out.read_text(encoding="utf-8"))
        journal = base / "recordings" / "kill.journal.json"
        if not journal.exists():
            assert generation == 0  # killed before the session opened: nothing was acknowledged
            continue
        notes: list[str] = []
        settings = Settings("kill", world=WorldKind.SYMBOLIC, base=base, record=False)
        with opened_session(settings, resume=True, note=notes.append) as resumed:
            events = resumed.journal.events
            answers = [e for e in events if e.kind == "answer" and getattr(e, "answer", "") != "skip"]
            learned = [e for e in events if e.kind in ("demo", "answer")]
            assert len(answers) >= thanked, (trial, moment)
            assert len(learned) >= generation, (trial, moment)
            assert resumed.budget.used >= len(answers)
        demos = base / "demos" / "kill"
        journalled = {e.file for e in events if e.kind == "demo"}  # type: ignore[union-attr]
        assert {p.name for p in demos.glob("demo-*.csv")} == journalled, (trial, moment, notes)
        checked += 1
        most_thanked = max(most_thanked, thanked)
        set_aside += len(notes)
    print(f"{checked} kills resumed, up to {most_thanked} answers thanked for, {set_aside} demonstrations set aside")
    assert most_thanked > 0  # some kills came after answers were thanked for
    assert checked >= KILLS // 2  # most kills hit a running session, not its start-up


def test_kills_of_a_mujoco_session_lose_nothing_acknowledged(tmp_path):
    """The same promise in the MuJoCo world, at two seeded moments of the quickstart dialogue."""
    import random

    from conftest import BALL_DOMAIN, ROOT

    from teach.session.setup import opened_session

    for trial, moment in enumerate(random.Random(15).sample(range(4000, 12000, 100), 2)):
        base = tmp_path / f"trial-{trial}"
        base.mkdir()
        out = base / "transcript.txt"
        with out.open("w") as transcript:
            process = subprocess.Popen([sys.executable, "-m", "teach.cli", "replay",
                                        str(ROOT / "dialogues" / "quickstart.dialogue"), "--session", "mj",
                                        "--no-record", "--base", str(base), "--oracle-model", str(BALL_DOMAIN)],
                                       stdout=transcript, stderr=subprocess.DEVNULL,
                                       env={**os.environ, "PYTHONUNBUFFERED": "1", "COLUMNS": "200"})
            time.sleep(moment / 1000)
            os.kill(process.pid, signal.SIGKILL)
            process.wait()
        thanked, generation = _acknowledged(out.read_text(encoding="utf-8"))
        if not (base / "recordings" / "mj.journal.json").exists():
            assert generation == 0
            continue
        settings = Settings("mj", base=base, record=False)
        with opened_session(settings, resume=True, note=lambda _: None) as resumed:
            events = resumed.journal.events
        assert sum(e.kind == "answer" for e in events) >= thanked
        assert sum(e.kind in ("demo", "answer") for e in events) >= generation
        journalled = {e.file for e in events if e.kind == "demo"}  # type: ignore[union-attr]
        assert {p.name for p in (base / "demos" / "mj").glob("demo-*.csv")} == journalled
        print(f"MuJoCo kill at {moment} ms: {generation} generations and {thanked} answers acknowledged, kept")


def _killed_while_running(command: list[str], base: Path, at_action: int) -> list[str]:
    """Run ``command`` and SIGKILL it as soon as the teacher has seen the ``at_action``-th action
    of a run begin; the whole transcript it printed."""
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                               env={**os.environ, "PYTHONUNBUFFERED": "1", "COLUMNS": "200"})
    assert process.stdout is not None
    lines, seen = [], 0
    for line in process.stdout:
        lines.append(line.rstrip("\n"))
        seen += line.startswith("→ ")
        if seen == at_action:
            os.kill(process.pid, signal.SIGKILL)
            break
    lines += process.stdout.read().splitlines()  # what it printed before it died
    process.wait()
    return lines


def _check_run_resumed(base: Path, session: str, transcript: list[str]) -> bool:
    """Every action the teacher saw the robot begin in the run the kill cut is kept: the finished
    ones as the open correction, the last as the one a resume sets the world up before; or the
    run had ended and its end is on disk. No demonstration file is an orphan. True when the kill
    came during a run."""
    from teach.session.setup import opened_session

    last_prompt = max(i for i, line in enumerate(transcript) if line.startswith("teach> "))
    block = transcript[last_prompt + 1:]
    announced = [line[2:] for line in block if line.startswith("→ ")]
    cut = bool(announced) and not any(line.startswith("I did") for line in block)
    journal = json.loads((base / "recordings" / f"{session}.journal.json").read_text())
    with opened_session(Settings(session, base=base, record=False), resume=True, note=lambda _: None) as resumed:
        kept = resumed.open.words if resumed.open is not None else []
        if cut and journal["open_run"]:
            assert resumed.domain.action(journal["open_run"]).label("en") == announced[-1]
            assert kept == [m.ROBOT_DID_STEP("en", action=action) for action in announced[:-1]]
        elif cut:  # the run had ended, not yet said: the correction holds them all, or the world is at its end
            assert kept == [m.ROBOT_DID_STEP("en", action=action) for action in announced] or \
                journal["events"][-1]["how"] == "run", (announced, journal)
        events = resumed.journal.events
    journalled = {e.file for e in events if isinstance(e, DemoLearned)}
    assert {p.name for p in (base / "demos" / session).glob("demo-*.csv")} == journalled
    return cut


@pytest.mark.parametrize(("world", "kills", "most"), [("symbolic", 6, 40), ("mujoco", 2, 12)])
def test_kills_during_runs_keep_every_step_the_robot_was_seen_to_do(tmp_path, world, kills, most):
    """Runs of the plan the action definitions give, from changing starts, killed at seeded
    moments while the robot acts (MuJoCo and symbolic)."""
    import random

    from conftest import BALL_DOMAIN

    script = tmp_path / "runs.dialogue"
    lines = [f"@world {world}", "@questions 0", f"model {BALL_DOMAIN}"]
    for start in ["start BallFound", "reset 11", "start BinClose", "reset 12"] * 10:
        lines += [start, "run", "cancel"]
    script.write_text("\n".join(lines) + "\n", encoding="utf-8")
    cut = 0
    for trial, at_action in enumerate(random.Random(16).sample(range(2, most), kills)):
        base = tmp_path / f"trial-{trial}"
        base.mkdir()
        transcript = _killed_while_running([sys.executable, "-m", "teach.cli", "replay", str(script), "--no-record",
                                            "--base", str(base)], base, at_action)
        cut += _check_run_resumed(base, "runs", transcript)
    print(f"{world}: {kills} kills during runs, {cut} cut a run the teacher had seen begin")
    assert cut >= 1
