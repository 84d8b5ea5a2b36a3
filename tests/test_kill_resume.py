"""A session killed with SIGKILL loses nothing: everything taught before the kill is back after
`teach session --resume`."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

from teach.bt.xml import read_tree
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
            if journal.exists() and len(json.loads(journal.read_text())["events"]) >= 3:
                break
            assert process.poll() is None, process.stderr.read().decode()
            time.sleep(0.05)
        os.kill(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    events = json.loads(journal.read_text())["events"]  # still valid JSON: written atomically
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
    assert SEQUENCE in said and said[-2:] == ["state", "quit"]
    steps = [line.step for line in contents.dialogue]
    assert steps == sorted(steps)
