"""A session killed with SIGKILL loses nothing: everything taught before the kill is back after
`teach session --resume`."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import journal_data
from preloaded_cli import PreloadedCli

from teach import messages as m
from teach.bt.nodes import Node
from teach.bt.xml import read_tree
from teach.errors import TeachError
from teach.session.journal import Answered, DemoLearned
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
            if journal.exists() and sum(e["kind"] == "demo" for e in journal_data(journal)["events"]) >= 3:
                break
            assert process.poll() is None, process.stderr.read().decode()
            time.sleep(0.05)
        os.kill(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    events = [e for e in journal_data(journal)["events"] if e["kind"] == "demo"]  # valid JSON: atomic
    assert len(events) >= 3
    demos = sorted((tmp_path / "demos" / "long").glob("demo-*.csv"))
    assert len(demos) >= len(events)  # every journalled demonstration is on disk
    settings = Settings("long", lang="en", questions=0, world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    resumed = SessionManager.resume(settings, ball, SymbolicWorld(ball))
    assert len(resumed.demos) == len(events)
    # the resumed learner is the one that was killed: its pruned tree equals the last generation saved
    generations = sorted((tmp_path / "trees" / "long").glob("gen-*.xml"))
    # a kill after journalling the last demonstration and before writing (and announcing) its
    # generation leaves the generation before it as the last one on disk
    assert len(generations) in (len(events), len(events) - 1)
    if len(generations) == len(events):
        assert resumed.pruned == read_tree(generations[-1])
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
            if journal.exists() and len(journal_data(journal)["events"]) >= 3:
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


@pytest.fixture(scope="module")
def cli():
    """``teach`` command lines started as forked children of one process that imported teach and
    MuJoCo once (a fresh interpreter pays seconds of imports before its first line)."""
    launcher = PreloadedCli()
    yield launcher
    launcher.close()


def _acknowledged(transcript: str) -> tuple[int, int]:
    """What the killed process told the teacher was taken: answers thanked for, and the last generation."""
    thanked = sum(line.startswith("Thank you.") for line in transcript.splitlines())
    generations = [int(line.split()[1].rstrip(":")) for line in transcript.splitlines()
                   if line.startswith("Generation ") and line.split()[1].rstrip(":").isdigit()]
    return thanked, max(generations, default=0)


KILL_DIALOGUE = """@world mujoco
@questions 5
@seed 3
find the ball
go to the ball
grasp the ball
go to the bin
put the ball in the bin
done
start BinClose
find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin
done
reset 11
run
reset 12
run 3
knock the ball away
find the ball
go to the ball
grasp the ball
go to the bin
put the ball in the bin
done
show
"""


def _taught(manager: SessionManager) -> list[object]:
    """What a session learned from, in order: each demonstration's states and actions, each
    answer's situation and action (the learner is deterministic in these)."""
    from teach.session.journal import effective_events

    taught: list[object] = []
    for event in effective_events(manager.journal.events):
        if isinstance(event, DemoLearned):
            demo = manager.store.read_demonstration(event.file, manager.domain)
            taught.append([(step.state, step.action) for step in demo.steps])
        elif isinstance(event, Answered):
            taught.append((event.state, event.answer))
    return taught


def test_twenty_kills_of_a_mujoco_session_lose_nothing_acknowledged(tmp_path, cli):
    """A scripted MuJoCo session (steps one by one and a line at once, runs, a correction, questions
    answered by an oracle) is killed with SIGKILL at 20 seeded moments, placed by the line the
    session printed last before them (so a loaded machine moves them little) and a delay after
    it. Each is resumed and finishes the dialogue. Every "Thank you", "Generation N", "✓" and "→"
    the teacher saw is on disk (journal, CSVs, generation files) and no file is an orphan. Where
    the journal on disk is the one the unkilled session had between two lines, the learner
    rebuilt from it equals the unkilled one's at that point; and when the resumed session learned
    from what the unkilled one did (the same demonstrations and answers: in MuJoCo a resume
    places the objects anew, so the world may go another way), it ends with the same tree."""
    import random
    from collections import Counter
    from concurrent.futures import ThreadPoolExecutor

    from conftest import BALL_DOMAIN
    from killed_session import drive, journal_key, kill_after_marker, run_cut, since_last_prompt

    from teach.dialogue.model_repair import ModelOracle
    from teach.dialogue.oracle import oracle_from_model
    from teach.dialogue.script import read_script
    from teach.domain import load_domain
    from teach.session.setup import opened_session

    script = tmp_path / "kill.dialogue"
    script.write_text(KILL_DIALOGUE, encoding="utf-8")
    lines = [text for _, text in read_script(script).lines]
    oracle = oracle_from_model(BALL_DOMAIN, load_domain(BALL_DOMAIN))
    model_oracle = ModelOracle(load_domain(BALL_DOMAIN))

    # the unkilled session, its journal after every line: where a killed one may go on from
    between: dict[int, str] = {}
    tree_between: dict[int, Node | None] = {}

    def note_between(index: int) -> None:
        if index not in between:
            between[index], tree_between[index] = journal_key(manager.store.journal_path), manager.pruned

    reference = Settings("kill", questions=5, seed=3, world=WorldKind.MUJOCO, base=tmp_path / "reference",
                         record=False)
    with opened_session(reference, note=lambda _: None) as manager:
        drive(manager, lines, 0, oracle, model_oracle, note_between)
        expected_tree, expected_taught = manager.pruned, _taught(manager)
    assert expected_tree is not None and sum(isinstance(t, list) for t in expected_taught) == 3

    # the CLI session unkilled: how long it takes from its first line, on this machine now
    def replay(base: Path) -> list[str]:
        return ["replay", str(script), "--no-record", "--base", str(base), "--oracle-model", str(BALL_DOMAIN)]

    timed = kill_after_marker(cli, replay(tmp_path / "trial-tm"))  # the name as long as each trial's: same lines
    assert timed.started and any(line.startswith("Saved:") for line in timed.transcript), timed.transcript
    duration = timed.times[-1]
    # half the kills one in each tenth of the session's time (steps and runs take most of it), half
    # each in another turn (a line typed or answered and all it does: learning, questions), at a
    # random moment of it
    turns = [i for i, line in enumerate(timed.transcript) if line.startswith(("teach> ", "answer> "))]
    ends = [timed.times[i] for i in turns[1:]] + [duration]
    rng = random.Random(14)
    moments = sorted([(slot + rng.random()) / (KILLS // 2) * duration for slot in range(KILLS // 2)] +
                     [timed.times[turns[turn]] + rng.random() * (ends[turn] - timed.times[turns[turn]])
                      for turn in rng.sample(range(len(turns)), KILLS - KILLS // 2)])
    phases: Counter[str] = Counter()
    resumed_count, rebuilt, compared, retyped, set_aside, interrupted = 0, 0, 0, 0, 0, 0
    thanked_most, generation_most = 0, 0
    bases = [tmp_path / f"trial-{trial:02d}" for trial in range(KILLS)]
    after_lines = [max(i for i, when in enumerate(timed.times) if when <= moment) for moment in moments]
    # the next session is run and killed while this one is resumed and checked (two processes, two cores)
    killer = ThreadPoolExecutor(max_workers=1)
    kills = [killer.submit(kill_after_marker, cli, replay(base), line, moment - timed.times[line])
             for base, line, moment in zip(bases, after_lines, moments, strict=True)]
    try:
        for trial, (moment, base, kill) in enumerate(zip(moments, bases, kills, strict=True)):
            killed = kill.result()
            assert killed.started, killed.transcript
            phases[killed.phase] += 1
            transcript = "\n".join(killed.transcript)
            thanked, generation = _acknowledged(transcript)
            journal = base / "recordings" / "kill.journal.json"
            where = (trial, round(moment, 2), killed.last_seen)
            if not journal.exists():  # killed in the first step: nothing acknowledged, nothing on disk
                assert generation == 0 and "✓" not in transcript, where
                assert not [*base.glob("demos/kill/demo-*"), *base.glob("trees/kill/gen-*")], where
                continue
            interrupted += len(list(base.rglob(".*.tmp")))  # an atomic write the kill cut short
            typed = killed.typed
            on_disk = journal_key(journal)
            go_on = typed if on_disk == between.get(typed - 1) else typed - 1 if on_disk == between.get(typed - 2) \
                else None
            rebuilt += go_on is not None
            after_generation = transcript.rsplit("\nGeneration ", 1)[-1].splitlines()
            seen_steps = [line[2:] for line in after_generation if line.startswith("✓ ") and "(nothing" not in line]
            cut_run = run_cut(killed.transcript)
            notes: list[str] = []
            with opened_session(Settings("kill", base=base, record=False), resume=True, note=notes.append) as resumed:
                events = resumed.journal.events
                answers = [e for e in events if isinstance(e, Answered) and e.answer != "skip"]
                learned = [e for e in events if isinstance(e, DemoLearned) or e in answers]
                assert len(answers) >= thanked, where
                assert len(learned) >= generation and resumed.generation >= generation, where
                if generation:
                    assert (base / "trees" / "kill" / f"gen-{generation:02d}.xml").is_file(), where
                if go_on is not None:  # the learner rebuilt from the journal is the one the kill ended
                    assert resumed.pruned == tree_between[go_on - 1], where
                words = resumed.open.words if resumed.open is not None else []
                if cut_run and resumed.journal.open_run:  # the run's finished actions open the correction
                    did = [m.ROBOT_DID_STEP("en", action=action) for action in cut_run]
                    begun = resumed.domain.action(resumed.journal.open_run).label("en")
                    # the last action seen begun is the one a resume sets the world up before, or it had
                    # ended and the next begun (journalled, killed before its "→" was printed)
                    assert (words, begun) == (did[:-1], cut_run[-1]) or words == did, where
                elif resumed.open is not None:  # the steps shown since the last generation are the open ones
                    # (a step is journalled before its "✓": the kill may have come between the two)
                    shown = [words[len(words) - len(seen_steps):], words[len(words) - 1 - len(seen_steps):-1]]
                    assert seen_steps in shown, where
                elif seen_steps:  # or a demonstration the kill kept from being announced holds them
                    labels = [resumed.domain.actions[s.action - 1].label("en") for s in resumed.demos[-1].steps
                              if s.action > 0]
                    assert labels[len(labels) - len(seen_steps):] == seen_steps, where
                journalled = {e.file for e in events if isinstance(e, DemoLearned)}
                assert {p.name for p in (base / "demos" / "kill").glob("demo-*.csv")} == journalled, (where, notes)
                shown = [line[2:] for line in since_last_prompt(killed.transcript) if line.startswith("✓ ")]
                parts = lines[typed - 1].split(", ")
                if go_on is None and len(parts) > len(shown) > 0 and words == shown:
                    # killed within a line of steps: the teacher types the steps not yet acknowledged
                    resumed.handle(", ".join(parts[len(shown):]))
                    go_on = typed
                    retyped += 1
                drive(resumed, lines, typed if go_on is None else go_on, oracle, model_oracle)
                if _taught(resumed) == expected_taught:  # the world and the questions went as unkilled
                    assert resumed.pruned == expected_tree, where
                    compared += 1
                events = resumed.journal.events
            journalled = {e.file for e in events if isinstance(e, DemoLearned)}
            assert {p.name for p in (base / "demos" / "kill").glob("demo-*.csv")} == journalled, where
            assert not list(base.rglob(".*.tmp")), where  # the resume removed them: no orphans
            resumed_count += 1
            set_aside += len(notes)
            thanked_most, generation_most = max(thanked_most, thanked), max(generation_most, generation)
    finally:  # a failed check stops the kills still to come
        killer.shutdown(cancel_futures=True)
    print(f"{KILLS} kills over {duration:.1f} s of session: {dict(sorted(phases.items()))}; {resumed_count} resumed, "
          f"{rebuilt} rebuilt the unkilled learner of that point, {compared} learned what the unkilled one did "
          f"and ended with its tree ({retyped} after retyping the rest of a line); up to {thanked_most} answers "
          f"and generation {generation_most} acknowledged; {set_aside} unjournalled demonstrations set aside, "
          f"{interrupted} cut-short writes removed")
    assert resumed_count >= KILLS - 4 and thanked_most > 0 and generation_most >= 5
    assert len(phases) >= 4  # the kills spread over steps, runs, learning, questions, the journal's saves


START_UP_KILLS = 8


def test_kills_during_start_up_leave_nothing_a_resume_does_not_explain(tmp_path, cli):
    """A recorded MuJoCo replay killed at seeded moments from its start until just after its first
    line (building the world, writing the journal, opening the recording, copying the domain):
    either the journal is on disk, and ``--resume`` opens the session (no demonstration, nothing
    orphaned, the recording part merged), or nothing but the lock's note is (then a resume says
    there is no such session and a new start goes ahead). The start-up that left a domain copy and
    a recording part without a journal (issue 23) is now impossible, and its leftovers are taken
    over all the same (test_a_start_killed_before_its_journal_is_taken_over)."""
    import random

    from killed_session import kill_after_marker, kill_after_start

    from teach.session.setup import opened_session

    script = tmp_path / "kill.dialogue"
    script.write_text(KILL_DIALOGUE, encoding="utf-8")

    def replay(base: Path) -> list[str]:
        return ["replay", str(script), "--base", str(base)]

    began = time.monotonic()
    timed = kill_after_marker(cli, replay(tmp_path / "trial-tm"), after_line=0)
    to_first_line = time.monotonic() - began
    assert timed.started, timed.transcript
    rng = random.Random(23)
    # one kill at once (before the world is built, surely before the journal), the others anywhere
    moments = [0.0, *sorted(rng.uniform(0.0, 1.2 * to_first_line) for _ in range(START_UP_KILLS - 1))]
    with_journal, open_already = 0, 0
    for trial, moment in enumerate(moments):
        base = tmp_path / f"start-{trial}"
        killed = kill_after_start(cli, replay(base), moment)
        journal = base / "recordings" / "kill.journal.json"
        where = (trial, round(moment, 2), killed.transcript[:1])
        if not journal.exists():  # killed before the journal: nothing of the session's own on disk
            left = {str(p.relative_to(base)) for p in base.rglob("*")}
            assert left <= {"recordings", "recordings/.kill.journal.json.teach-lock"} | \
                {str(p.relative_to(base)) for p in base.glob("recordings/.kill.journal.json.*.tmp")}, where
            with pytest.raises(TeachError, match="no such session journal"):
                with opened_session(Settings("kill", base=base, record=False), resume=True, note=lambda _: None):
                    pass
            continue
        with_journal += 1
        open_already += killed.started
        notes: list[str] = []
        with opened_session(Settings("kill", base=base), resume=True, note=notes.append) as resumed:
            if not killed.started:  # still starting: nothing taught yet
                assert resumed.demos == [] and resumed.open is None and notes == [], (where, notes)
            events = resumed.journal.events
        assert not list(base.rglob("*.part")) and not list(base.rglob(".*.tmp")), where
        assert (base / "recordings" / "kill.rrd").is_file(), where
        journalled = {e.file for e in events if isinstance(e, DemoLearned)}
        assert {p.name for p in (base / "demos" / "kill").glob("demo-*.csv")} == journalled, where
    print(f"{START_UP_KILLS} kills in the first {1.2 * to_first_line:.2f} s of start-up: {with_journal} after the "
          f"journal was written (resumed; {open_already} once the session was open), the others before it "
          "(nothing left)")
    assert with_journal < START_UP_KILLS


def test_a_start_killed_before_its_journal_is_taken_over(tmp_path, ball):
    """What a start killed before its journal used to leave (the domain copy, empty folders, a
    recording part) is taken over by ``--resume`` with one note, or removed by a new start; taught
    data without a journal is refused and left alone."""
    from conftest import BALL_DOMAIN

    from teach.session.setup import opened_session

    def leave(session: str) -> None:
        (tmp_path / "demos" / session).mkdir(parents=True)
        (tmp_path / "trees" / session).mkdir(parents=True)
        (tmp_path / "demos" / session / "domain.toml").write_bytes(BALL_DOMAIN.read_bytes())
        (tmp_path / "recordings").mkdir(exist_ok=True)
        (tmp_path / "recordings" / f"{session}.rrd.part").write_bytes(b"")

    settings = Settings("S", world=WorldKind.OFFLINE, base=tmp_path, record=False)
    for resume, said in ((True, "starting session S anew"), (False, "removing what a start")):
        leave("S")
        notes: list[str] = []
        with opened_session(settings, resume=resume, note=notes.append) as manager:
            assert manager.demos == []
        assert len(notes) == 1 and said in notes[0] and "recordings/S.rrd.part" in notes[0], notes
        assert not (tmp_path / "recordings" / "S.rrd.part").exists()
        assert (tmp_path / "recordings" / "S.journal.json").is_file()
        for path in [tmp_path / "demos" / "S", tmp_path / "trees" / "S", tmp_path / "recordings" / "S.journal.json"]:
            subprocess.run(["rm", "-rf", str(path)], check=True)
    leave("T")
    (tmp_path / "demos" / "T" / "demo-001.csv").write_text("0;0;0;0;0;1\n")
    with pytest.raises(TeachError, match="holds demo-001.csv, but the session has no journal"):
        with opened_session(Settings("T", world=WorldKind.OFFLINE, base=tmp_path, record=False), resume=True):
            pass
    assert (tmp_path / "demos" / "T" / "demo-001.csv").is_file() and (tmp_path / "recordings" / "T.rrd.part").exists()


def _killed_while_running(cli: PreloadedCli, argv: list[str], at_action: int) -> list[str]:
    """Run ``teach`` with ``argv`` and SIGKILL it as soon as the teacher has seen the
    ``at_action``-th action of a run begin; the whole transcript it printed."""
    child = cli.start(argv)
    lines, seen = [], 0
    with child.stdout:
        for line in child.stdout:
            lines.append(line.rstrip("\n"))
            seen += line.startswith("→ ")
            if seen == at_action:
                child.kill()
                break
        lines += child.stdout.read().splitlines()  # what it printed before it died
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
    journal = journal_data(base / "recordings" / f"{session}.journal.json")
    with opened_session(Settings(session, base=base, record=False), resume=True, note=lambda _: None) as resumed:
        kept = resumed.open.words if resumed.open is not None else []
        did = [m.ROBOT_DID_STEP("en", action=action) for action in announced]
        if cut and journal["open_run"]:  # or the last one seen had ended and the next begun, not yet shown
            begun = resumed.domain.action(journal["open_run"]).label("en")
            assert (kept, begun) == (did[:-1], announced[-1]) or kept == did, (announced, journal)
        elif cut:  # the run had ended, not yet said: the correction holds them all, or the world is at its end
            assert kept == did or journal["events"][-1]["how"] == "run", (announced, journal)
        events = resumed.journal.events
    journalled = {e.file for e in events if isinstance(e, DemoLearned)}
    assert {p.name for p in (base / "demos" / session).glob("demo-*.csv")} == journalled
    return cut


@pytest.mark.parametrize(("world", "kills", "most"), [("symbolic", 6, 40), ("mujoco", 2, 12)])
def test_kills_during_runs_keep_every_step_the_robot_was_seen_to_do(tmp_path, cli, world, kills, most):
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
        transcript = _killed_while_running(cli, ["replay", str(script), "--no-record", "--base", str(base)],
                                           at_action)
        cut += _check_run_resumed(base, "runs", transcript)
    print(f"{world}: {kills} kills during runs, {cut} cut a run the teacher had seen begin")
    assert cut >= 1


def test_a_resume_removes_the_writes_a_kill_cut_short(tmp_path):
    """A kill inside the atomic writer leaves its fsynced temporary file (``.NAME.*.tmp``) beside
    the journal or a generation: the resume removes it, and only the session's own."""
    from teach.session.setup import opened_session

    script = tmp_path / "cut.dialogue"
    script.write_text(f"@world symbolic\n@questions 0\n{SEQUENCE}\ndone\n", encoding="utf-8")
    subprocess.run([sys.executable, "-m", "teach.cli", "replay", str(script), "--no-record", "--base", str(tmp_path)],
                   check=True, capture_output=True, timeout=120)
    cut_short = [tmp_path / "recordings" / ".cut.journal.json.a1b2c3.tmp",
                 tmp_path / "trees" / "cut" / ".gen-02.xml.x.tmp", tmp_path / "demos" / "cut" / ".demo-002.csv.y.tmp"]
    others = tmp_path / "recordings" / ".other.journal.json.a1b2c3.tmp"  # another session's write, maybe under way
    for path in [*cut_short, others]:
        path.write_text("half", encoding="utf-8")
    with opened_session(Settings("cut", base=tmp_path, record=False), resume=True, note=lambda _: None) as resumed:
        assert len(resumed.demos) == 1
    assert [path for path in cut_short if path.exists()] == [] and others.exists()
