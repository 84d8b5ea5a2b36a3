"""Nothing taught is ever lost (issue 14, the session side): one process per session, nothing
touched before everything is checked, nothing acknowledged before it is on disk, a journal
read against its schema, recordings that are not silently damaged."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT, journal_data
from teacher_loop import honest_answer

from teach import messages as m
from teach.cli import main
from teach.session.replies import Reply
from teach.session.settings import Settings, WorldKind
from teach.session.setup import opened_session

SEQUENCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin"
SECOND = "go to the ball, grasp the ball, go to the bin, put the ball in the bin"
DIALOGUE = f"@world symbolic\n@questions 2\n{SEQUENCE}\ndone\nstart BallFound\n{SECOND}\ndone\n"
HOLD_LOCK = ("import sys, time\nfrom teach.lock import session_lock\n"
             "with session_lock(sys.argv[1], sys.argv[2]):\n    print('held', flush=True)\n    time.sleep(120)\n")


def snapshot(base: Path) -> dict[str, bytes]:
    """Every file under ``base`` with its bytes: "changes nothing" compared exactly."""
    return {str(p.relative_to(base)): p.read_bytes() for p in sorted(base.rglob("*")) if p.is_file()}


def replayed(tmp_path: Path, name: str = "keep", text: str = DIALOGUE, *extra: str) -> Path:
    """A session made by replaying a small symbolic dialogue (the oracle answers its questions)."""
    dialogue = tmp_path / f"{name}.dialogue"
    dialogue.write_text(text, encoding="utf-8")
    assert main(["replay", str(dialogue), "--no-record", "--base", str(tmp_path), "--oracle-model",
                 str(ROOT / "demos" / "ball" / "domain.toml"), *extra]) == 0
    return dialogue


def one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


# --- 1. one session, one process ---------------------------------------------------------------

@pytest.fixture
def holder(tmp_path):
    """Another process holding the lock of session "keep"."""
    process = subprocess.Popen([sys.executable, "-c", HOLD_LOCK, str(tmp_path), "keep"], stdout=subprocess.PIPE,
                               text=True)
    assert process.stdout is not None and process.stdout.readline().strip() == "held"
    yield process
    process.kill()
    process.wait()


def test_a_locked_session_is_neither_replayed_nor_resumed(tmp_path, capsys, holder):
    dialogue = tmp_path / "keep.dialogue"
    dialogue.write_text(DIALOGUE, encoding="utf-8")
    (tmp_path / "recordings").mkdir(exist_ok=True)  # the holder made it, for its lock
    before = snapshot(tmp_path)
    assert main(["replay", str(dialogue), "--no-record", "--base", str(tmp_path)]) == 2
    assert f"process {holder.pid}" in one_line(capsys.readouterr().err)
    assert main(["session", "--resume", "keep", "--no-record", "--base", str(tmp_path)]) == 2
    assert f"process {holder.pid}" in one_line(capsys.readouterr().err)
    assert snapshot(tmp_path) == before


def test_two_new_sessions_of_one_name(tmp_path):
    """The second is refused in one line while the first runs, and "exists already" after it."""
    command = [sys.executable, "-m", "teach.cli", "session", "--session", "twin", "--world", "symbolic",
               "--base", str(tmp_path)]
    first = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True)
    journal = tmp_path / "recordings" / "twin.journal.json"
    try:
        assert first.stdin is not None
        first.stdin.write("state\n")
        first.stdin.flush()
        while not journal.exists():
            assert first.poll() is None, first.communicate()
        second = subprocess.run(command, input="quit\n", capture_output=True, text=True, timeout=120)
        assert second.returncode == 2 and f"process {first.pid}" in one_line(second.stderr)
    finally:
        out, err = first.communicate("quit\n", timeout=120)
    assert first.returncode == 0, err
    third = subprocess.run(command, input="quit\n", capture_output=True, text=True, timeout=120)
    assert third.returncode == 2 and "exists already" in one_line(third.stderr)
    assert ".part" not in third.stderr


# --- 2. validate before touching ---------------------------------------------------------------

BAD_INPUTS = {
    "oracle": lambda bad: ["--oracle", str(bad)],
    "oracle-model": lambda bad: ["--oracle-model", str(bad)],
    "domain": lambda bad: ["--domain", str(bad)],
}


@pytest.mark.parametrize("option", sorted(BAD_INPUTS))
def test_a_bad_input_leaves_an_existing_session_exactly_as_it_was(tmp_path, capsys, option):
    dialogue = replayed(tmp_path)
    bad = tmp_path / "bad.file"
    bad.write_text("<root><unclosed>\n[[[[\n", encoding="utf-8")
    capsys.readouterr()
    before = snapshot(tmp_path)
    assert main(["replay", str(dialogue), "--no-record", "--base", str(tmp_path), *BAD_INPUTS[option](bad)]) == 2
    assert "bad.file" in one_line(capsys.readouterr().err)
    assert snapshot(tmp_path) == before


def test_a_file_that_is_not_a_dialogue_is_refused_with_its_line(tmp_path, capsys):
    readme = tmp_path / "README.md"
    readme.write_text("# A title\n\nThis project teaches robots.\n", encoding="utf-8")
    assert main(["replay", str(readme), "--world", "symbolic", "--no-record", "--base", str(tmp_path)]) == 2
    assert one_line(capsys.readouterr().err).startswith(f"teach: {readme}:3: ")
    assert not (tmp_path / "demos").exists()
    assert main(["replay", str(readme), "--world", "symbolic", "--no-record", "--base", str(tmp_path),
                 "--lenient"]) == 0


@pytest.mark.parametrize("args", [("learn", "{ball}/delta22", "-o", "{out}"),
                                  ("learn", "{ball}/delta22", "--approach", "pabt", "-o", "{out}"),
                                  ("test", "{ball}/reference/table61.xml", "{ball}/delta55")])
def test_a_mistyped_folder_is_said_to_be_missing(tmp_path, capsys, args):
    """`teach learn demos/ball/delta22 --approach pabt` learned from the domain file of the folder
    above and wrote a tree; without pabt, and for `teach test`, a missing folder was "needs a folder
    of CSV demonstrations" / "not a folder of demonstrations"."""
    out = tmp_path / "out.xml"
    filled = [arg.format(ball=ROOT / "demos" / "ball", out=out) for arg in args]
    assert main(filled) == 2
    assert one_line(capsys.readouterr().err).endswith(("no such file or folder", "no such folder"))
    assert not out.exists()


def test_a_dialogue_may_say_what_a_session_understands(tmp_path, capsys):
    """ "what now?", doubtful answers and "that cannot happen" are understood by a session, but a
    scripted replay refused them as "neither a command nor something the robot can do"."""
    dialogue = tmp_path / "everyday.dialogue"
    dialogue.write_text("find the ball\nwhat now?\nhmm, maybe\nI think so\nthat cannot happen\nhuh?\n"
                        "that makes no sense\n", encoding="utf-8")
    assert main(["replay", str(dialogue), "--world", "symbolic", "--no-record", "--base", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "From here I can" in out and out.count("No question is open.") == 4


def test_a_dialogue_may_praise_and_ask_where_things_are(tmp_path, capsys):
    """Greetings, praise, "where is …?" and how things are ("I can see the ball now") are understood
    by a session, so a scripted replay reads them too; praise before a step is set aside, as in the
    session."""
    dialogue = tmp_path / "kind.dialogue"
    dialogue.write_text("hello\nfind the ball\nwhere is the ball?\nI can see the ball now\nhmm\nwait, no\nok\n"
                        "good, now go to the ball\nGreat, well done!\n👍\n", encoding="utf-8")
    assert main(["replay", str(dialogue), "--world", "symbolic", "--no-record", "--base", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "✓ go to the ball" in out and "Thank you! Tell me the next step" in out and "Yes, I know" in out
    assert "Take your time." in out and "If my last step was wrong" in out


def test_replacing_another_session_needs_overwrite(tmp_path, capsys):
    dialogue = replayed(tmp_path)
    other = tmp_path / "other.dialogue"
    other.write_text(f"@world symbolic\n{SEQUENCE}\ndone\n", encoding="utf-8")
    capsys.readouterr()
    before = snapshot(tmp_path)
    assert main(["replay", str(other), "--session", "keep", "--no-record", "--base", str(tmp_path)]) == 2
    assert "--overwrite" in one_line(capsys.readouterr().err)
    assert snapshot(tmp_path) == before
    replayed(tmp_path)  # the same dialogue again replaces its own session
    assert snapshot(tmp_path).keys() == before.keys()
    assert main(["replay", str(other), "--session", "keep", "--no-record", "--base", str(tmp_path),
                 "--overwrite"]) == 0
    assert journal_data(tmp_path / "recordings" / "keep.journal.json")["origin"] == \
        f"replay:{other.resolve()}"
    assert dialogue.exists()


# --- 3. acknowledge after durable --------------------------------------------------------------

def test_every_thanks_and_generation_is_on_disk_when_it_is_shown(tmp_path):
    settings = Settings("ack", questions=3, world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    journal = tmp_path / "recordings" / "ack.journal.json"
    seen: list[tuple[str, list[str]]] = []

    def shown(reply: Reply) -> None:
        kinds = [e["kind"] for e in journal_data(journal)["events"]] if journal.exists() else []
        seen.append((reply.text, kinds))

    with opened_session(settings) as manager:
        manager.live = shown
        for line in [SEQUENCE, "done", "start BallFound", SECOND, "done"]:
            manager.handle(line)
        for _ in range(2):  # two questions, answered as a teacher who knows the task would
            manager.handle(honest_answer(manager, manager.domain))
    thanks = [kinds for text, kinds in seen if text.startswith(m.THANKS("en", change=""))]
    generations = [kinds for text, kinds in seen if text.startswith("Generation ")]
    assert len(thanks) == 2 and len(generations) >= 4
    for number, kinds in enumerate(thanks, start=1):
        assert kinds.count("answer") == number  # the answer thanked for is in the journal
    for number, kinds in enumerate(generations, start=1):
        assert sum(k in ("demo", "answer") for k in kinds) >= number


def test_an_orphaned_demonstration_is_set_aside_on_resume(tmp_path, capsys):
    replayed(tmp_path)
    demos = tmp_path / "demos" / "keep"
    orphan = demos / "demo-099.csv"
    orphan.write_bytes((demos / "demo-001.csv").read_bytes())
    result = subprocess.run([sys.executable, "-m", "teach.cli", "session", "--resume", "keep", "--no-record",
                             "--base", str(tmp_path)], input="quit\n", capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "demo-099.csv" in result.stderr and "orphaned" in result.stderr
    assert not orphan.exists() and (demos / "orphaned" / "demo-099.csv").is_file()
    journalled = {e["file"] for e in journal_data(tmp_path / "recordings" / "keep.journal.json")["events"]
                  if e["kind"] == "demo"}
    assert {p.name for p in demos.glob("demo-*.csv")} == journalled


def test_a_session_refuses_a_regular_file_as_standard_input(tmp_path):
    typed = tmp_path / "typed.txt"
    typed.write_text(f"{SEQUENCE}\ndone\n", encoding="utf-8")
    with typed.open() as stdin:
        result = subprocess.run([sys.executable, "-m", "teach.cli", "session", "--world", "symbolic", "--no-record",
                                 "--base", str(tmp_path)], stdin=stdin, capture_output=True, text=True, timeout=120)
    assert result.returncode == 2 and "teach replay" in one_line(result.stderr)
    assert not (tmp_path / "recordings").exists()


# --- 4. the journal's schema -------------------------------------------------------------------

def _journal(**changes: object) -> dict[str, object]:
    data: dict[str, object] = {"session": "j", "domain": "", "lang": "en", "questions": 5, "world": "symbolic",
                               "seed": 0, "step": 3, "events": [], "version": 1}
    data.update(changes)
    return data


DAMAGED_JOURNALS = {
    "domain is a number": (json.dumps(_journal(domain=5)), "domain: must be a string"),
    "questions in words": (json.dumps(_journal(questions="five")), "questions: must be an integer"),
    "step is null": (json.dumps(_journal(step=None)), "step: must be an integer"),
    "step is NaN": (json.dumps(_journal()).replace('"step": 3', '"step": NaN'), "NaN"),
    "seed is a string": (json.dumps(_journal(seed="x")), "seed: must be an integer"),
    "unknown world": (json.dumps(_journal(world="mars")), "world: must be one of"),
    "deep nesting": (json.dumps(_journal()).replace('"events": []', '"events": ' + "[" * 1200 + "]" * 1200),
                     "nest"),
    "unknown event kind": (json.dumps(_journal(events=[{"kind": "teleport"}])), "events[0]: kind: unknown event"),
    "event with a wrong type": (json.dumps(_journal(events=[{"kind": "demo", "file": 3, "source": "x"}])),
                                "events[0]: file: must be a string"),
    "demonstration outside its folder": (json.dumps(_journal(events=[{"kind": "demo", "file": "../x.csv",
                                                                      "source": "x"}])), "events[0]: file"),
    "unknown key": (json.dumps(_journal(extra=1)), "extra: unknown key"),
    "unknown action answered": (json.dumps(_journal(events=[
        {"kind": "asked", "state": "00000"},
        {"kind": "answer", "state": "00000", "answer": "Teleport", "question": "?"}])), "'Teleport' is not an action"),
}


@pytest.mark.parametrize("case", sorted(DAMAGED_JOURNALS))
def test_a_damaged_journal_is_one_line_naming_the_journal(tmp_path, capsys, case):
    text, expected = DAMAGED_JOURNALS[case]
    path = tmp_path / "recordings" / "j.journal.json"
    path.parent.mkdir()
    path.write_text(text, encoding="utf-8")
    before = snapshot(tmp_path)
    assert main(["session", "--resume", "j", "--no-record", "--base", str(tmp_path)]) == 2
    line = one_line(capsys.readouterr().err)
    assert line.startswith(f"teach: {path}") and expected in line, line
    assert "domain.toml" not in line
    assert snapshot(tmp_path) == before


# --- 5. recordings ----------------------------------------------------------------------------

def test_a_failed_resume_leaves_the_recording_as_it_was(tmp_path, capsys):
    dialogue = tmp_path / "rec.dialogue"
    dialogue.write_text(f"@world symbolic\n@questions 0\n{SEQUENCE}\ndone\n", encoding="utf-8")
    assert main(["replay", str(dialogue), "--base", str(tmp_path)]) == 0
    (tmp_path / "demos" / "rec" / "demo-001.csv").unlink()  # the journal now names a missing demonstration
    capsys.readouterr()
    before = snapshot(tmp_path)
    assert main(["session", "--resume", "rec", "--base", str(tmp_path)]) == 2
    assert "demo-001.csv" in one_line(capsys.readouterr().err)
    assert snapshot(tmp_path) == before


def test_a_damaged_earlier_recording_is_kept_aside_not_merged(tmp_path, capsys):
    dialogue = tmp_path / "rec.dialogue"
    dialogue.write_text(f"@world symbolic\n@questions 0\n{SEQUENCE}\ndone\n", encoding="utf-8")
    assert main(["replay", str(dialogue), "--base", str(tmp_path)]) == 0
    recording = tmp_path / "recordings" / "rec.rrd"
    damaged = recording.read_bytes()[: len(recording.read_bytes()) // 2] + b"\x00garbage" * 64
    recording.write_bytes(damaged)
    result = subprocess.run([sys.executable, "-m", "teach.cli", "session", "--resume", "rec", "--base",
                             str(tmp_path)], input="quit\n", capture_output=True, text=True, timeout=120,
                            env={**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"})
    assert result.returncode == 0, result.stderr
    assert "damaged" in result.stderr and "rec.damaged.rrd" in result.stderr
    assert (tmp_path / "recordings" / "rec.damaged.rrd").read_bytes() == damaged
    assert recording.is_file()


# --- 6. a full disk ---------------------------------------------------------------------------

@pytest.fixture
def small_disk(tmp_path):
    """A 300 KiB tmpfs (needs root; skipped otherwise, with the reason)."""
    if os.geteuid() != 0:
        pytest.skip("the disk-full test mounts a small tmpfs, which needs root")
    disk = tmp_path / "disk"
    disk.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=300k", "tmpfs", str(disk)], capture_output=True,
                             text=True)
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.strip()}")
    yield disk
    subprocess.run(["umount", str(disk)], check=True)


def test_a_full_disk_ends_a_live_session_in_one_line_and_it_resumes(small_disk):
    lines = [SEQUENCE, "done", "start BallFound", SECOND, "done"] * 60 + ["quit"]
    command = [sys.executable, "-m", "teach.cli", "session", "--world", "symbolic", "--questions", "0",
               "--no-record", "--base", str(small_disk)]
    full = subprocess.run([*command, "--session", "full"], input="\n".join(lines) + "\n", capture_output=True,
                          text=True, timeout=300)
    assert full.returncode == 2 and "Traceback" not in full.stderr
    last = full.stderr.strip().splitlines()[-1]
    assert last.startswith(f"teach: {small_disk}/") and last.endswith("No space left on device"), full.stderr
    subprocess.run(["mount", "-o", "remount,size=8m", str(small_disk)], check=True)
    resumed = subprocess.run([*command, "--resume", "full"], input="quit\n", capture_output=True, text=True,
                             timeout=300)
    assert resumed.returncode == 0, resumed.stderr
    journal = journal_data(small_disk / "recordings" / "full.journal.json")
    journalled = {e["file"] for e in journal["events"] if e["kind"] == "demo"}
    assert f"Resumed session full: {len(journalled)} demonstrations" in resumed.stdout
    assert {p.name for p in (small_disk / "demos" / "full").glob("demo-*.csv")} == journalled
