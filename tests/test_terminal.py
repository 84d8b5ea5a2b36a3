"""The terminal front-end driven through prompt_toolkit's pipe input, as a person would type."""

from __future__ import annotations

import io
import os
import signal
from pathlib import Path

from conftest import journal_data
from prompt_toolkit.input import create_pipe_input
from prompt_toolkit.output import DummyOutput
from rich.console import Console

from teach.session.machine import SessionManager
from teach.session.settings import Settings, WorldKind
from teach.terminal.app import Terminal
from teach.world.symbolic import SymbolicWorld


def drive(ball, tmp_path, keys: str, lang: str = "de") -> tuple[str, SessionManager]:
    settings = Settings("term", lang=lang, world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    manager = SessionManager(settings, ball, SymbolicWorld(ball))
    buffer = io.StringIO()
    console = Console(file=buffer, width=100, color_system=None)
    with create_pipe_input() as pipe:
        pipe.send_text(keys)
        pipe.close()  # the input ends there, as a closed terminal's does (Ctrl-D again after a warning)
        Terminal(manager, console=console, input=pipe, output=DummyOutput()).run()
    return buffer.getvalue(), manager


def test_german_sentence_teaches_a_tree_and_ctrl_d_saves(ball, tmp_path):
    keys = ("Ball finden, zum Ball gehen, Ball greifen, zum Eimer gehen, Ball in den Eimer legen\r"
            "fertig\r"
            "\x04")  # Ctrl-D
    out, manager = drive(ball, tmp_path, keys)
    assert "Generation 1" in out and "was ich tue" in out
    assert "Ich bin fertig, sobald gilt: der Ball ist im Eimer" in out
    assert "(BallPlaced)" not in out  # the symbols are for 'zeige ganz' and the facilitator
    assert "Auf Wiedersehen" in out  # Ctrl-D leaves after saving
    assert manager.finished and (tmp_path / "recordings" / "term.journal.json").is_file()
    assert (tmp_path / "demos" / "term" / "demo-001.csv").is_file()


def test_tab_completion_and_help(ball, tmp_path):
    # "Ball fi" + Tab completes to "Ball finden"
    keys = "Ball fi\t\rhilfe\rquit\r"
    out, manager = drive(ball, tmp_path, keys)
    assert "✓ Ball finden" in out
    assert "vorführen [Schritte]" in out  # the help lists the commands, in German
    assert manager.finished


def test_run_and_unknown_words(ball, tmp_path):
    keys = ("find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin\r"
            "done\rstart\rrun\rfly away\rquit\r")
    out, _ = drive(ball, tmp_path, keys, lang="en")
    assert "Done! The task is finished." in out
    assert "I don't know “fly away”" in out


def recorded_drive(ball, tmp_path, keys: str) -> tuple[str, SessionManager, Path]:
    """Like ``drive``, in English, with a real rerun recording written and closed."""
    from teach.observe.rerun_writer import RerunLogger

    rrd = tmp_path / "recordings" / "term.rrd"
    rrd.parent.mkdir(parents=True)
    settings = Settings("term", lang="en", world=WorldKind.SYMBOLIC, base=tmp_path, record=True)
    manager = SessionManager(settings, ball, SymbolicWorld(ball), RerunLogger(rrd, "term"))
    buffer = io.StringIO()
    console = Console(file=buffer, width=100, color_system=None)
    with create_pipe_input() as pipe:
        pipe.send_text(keys)
        pipe.close()  # the input ends there, as a closed terminal's does (Ctrl-D again after a warning)
        Terminal(manager, console=console, input=pipe, output=DummyOutput()).run()
    manager.close()
    return buffer.getvalue(), manager, rrd


TEACH_ONCE = "find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin\rdone\r"


def test_a_bad_run_argument_is_an_error_reply_and_the_session_goes_on(ball, tmp_path):
    out, manager = drive(ball, tmp_path, TEACH_ONCE + "run abc\rstate\rquit\r", lang="en")
    assert "! expected a whole number, not 'abc'" in out
    assert out.index("expected a whole number") < out.index("Goodbye!")  # the session went on to 'quit'
    assert manager.finished


def test_a_run_in_the_terminal_reaches_the_recording_the_clock_and_the_journal(ball, tmp_path):
    from teach.observe.reader import read_recording

    out, manager, rrd = recorded_drive(ball, tmp_path, TEACH_ONCE + "start\rrun\r\x04")
    assert "Done! The task is finished." in out
    lines = [(d.speaker, d.text, d.step) for d in read_recording(rrd).dialogue if d.kind == "line"]
    run_step = next(step for speaker, text, step in lines if speaker == "teacher" and text == "run")
    said = [text for speaker, text, step in lines if speaker == "robot" and step == run_step]
    assert "Done! The task is finished." in said and any(t.startswith("I did: ") for t in said)
    # 'run' had a step of its own on the clock, and the journal was saved with it
    steps = [step for speaker, _, step in lines if speaker == "teacher"]
    assert steps == sorted(set(steps)) and run_step == steps[-2]
    journal = journal_data(tmp_path / "recordings" / "term.journal.json")
    assert journal["step"] == manager.step == steps[-1]


def test_run_before_learning_is_refused_without_the_running_notice(ball, tmp_path):
    out, _ = drive(ball, tmp_path, "run\rquit\r", lang="en")
    assert "I have not learned anything yet" in out and "robot running" not in out


def test_question_mark_and_ok_done_are_commands(ball, tmp_path):
    keys = ("?\rfind the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin\r"
            "ok done\rquit\r")
    out, manager = drive(ball, tmp_path, keys, lang="en")
    assert "demonstrate" in out and "Generation 1" in out and len(manager.demos) == 1
    assert out.index("demonstrate") < out.index("New demonstration")  # "?" started nothing


def test_the_state_line_is_plain_words_unless_asked_for_in_full(ball, tmp_path):
    out, _ = drive(ball, tmp_path, "Ball finden\rzustand ganz\rquit\r")
    before_full = out.split("Zustand: BallFound=1", 1)[0]
    assert "Zustand: ich sehe den Ball" in before_full and "BallFound=" not in before_full
    assert "Zustand: BallFound=1" in out


def test_help_lists_german_usage_in_a_german_session(ball, tmp_path):
    out, _ = drive(ball, tmp_path, "hilfe\rquit\r")
    assert "zurück [N]" in out and "warum NAME" in out and "undo [N]" not in out


def test_tab_completes_labels_after_why_and_start(ball, tmp_path):
    from prompt_toolkit.completion import CompleteEvent
    from prompt_toolkit.document import Document

    settings = Settings("tab", lang="de", world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    with create_pipe_input() as pipe:
        terminal = Terminal(SessionManager(settings, ball, SymbolicWorld(ball)), input=pipe, output=DummyOutput())
    completer = terminal.prompt.completer
    assert completer is not None

    def offered(text):
        return [c.text for c in completer.get_completions(Document(text), CompleteEvent(completion_requested=True))]

    assert offered("warum Ball g") == ["Ball greifen"]
    assert offered("start ich s") == ["ich sehe den Ball"]
    assert offered("start ich sehe den Ball, der E") == ["der Eimer ist in Reichweite"]
    assert offered("warum der Ball ist i") == ["der Ball ist in Reichweite", "der Ball ist im Eimer"]


def test_ctrl_c_during_a_run_starts_what_follows_on_a_new_line(ball, tmp_path):
    settings = Settings("intr", lang="en", world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    buffer = io.StringIO()
    with create_pipe_input() as pipe:
        terminal = Terminal(SessionManager(settings, ball, SymbolicWorld(ball)),
                            console=Console(file=buffer, width=100, color_system=None), input=pipe,
                            output=DummyOutput())
    terminal._on_interrupt()
    terminal._on_interrupt()  # a second Ctrl-C adds no second empty line
    assert buffer.getvalue() == "\n" and terminal._interrupt.is_set()


def test_a_chatty_run_is_recognised_as_a_run(ball, tmp_path):
    keys = ("find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin\r"
            "done\rstart\rok run\rquit\r")
    out, _ = drive(ball, tmp_path, keys, lang="en")
    assert "robot running" in out and "Done! The task is finished." in out


def test_the_toolbar_fits_80_columns_and_names_conditions_only_for_a_facilitator(ball, tmp_path):
    from teach.terminal.view import toolbar

    settings = Settings("bar", lang="de", world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    manager = SessionManager(settings, ball, SymbolicWorld(ball))
    manager.handle("start BallFound BallClose BallGrasped BinClose")
    assert "BallFound" not in toolbar(manager.view()) and len(toolbar(manager.view())) <= 80
    manager.facilitator = True
    assert "BallFound, BallClose" in toolbar(manager.view())


def test_the_running_notice_is_shown_only_once_the_robot_moves(ball, tmp_path):
    # a safe run stops at once where the bin is close by; a yes lets the robot find the ball; 'run'
    # then says it tries again from there and stops at once again. The notice came before "I try
    # again", and for runs in which the robot never moved
    keys = ("find the ball, go to the ball, grasp the ball, go to the bin, put the ball in the bin\r"
            "done\r" + "skip\r" * 4 + "start BinClose\rrun\ryes\r" + "skip\r" * 4 + "run\rquit\r")
    out, _ = drive(ball, tmp_path, keys, lang="en")
    assert "I try again from here" in out and out.count("I got stuck") == 2
    assert "robot running" not in out


class _CtrlCAfterFirstStep(SymbolicWorld):
    """The symbolic world, with the teacher pressing Ctrl-C (a real SIGINT) during its first step."""

    pressed = False

    def act(self, action: str):  # type: ignore[no-untyped-def]
        if not self.pressed:
            self.pressed = True
            os.kill(os.getpid(), signal.SIGINT)
        return super().act(action)


def test_ctrl_c_during_a_line_of_steps_stops_after_the_step_under_way(ball, tmp_path):
    """Ctrl-C while the robot did "find the ball, go to the ball, grasp the ball" ended the program
    ("teach: interrupted"); now the step under way is finished and the rest said as not done."""
    settings = Settings("intr", lang="en", world=WorldKind.SYMBOLIC, base=tmp_path, record=False)
    manager = SessionManager(settings, ball, _CtrlCAfterFirstStep(ball))
    buffer = io.StringIO()
    with create_pipe_input() as pipe:
        pipe.send_text("find the ball, go to the ball, grasp the ball\rsteps\rcancel\rquit\r")
        pipe.close()
        Terminal(manager, console=Console(file=buffer, width=100, color_system=None), input=pipe,
                 output=DummyOutput()).run()
    out = buffer.getvalue()
    assert "I stopped there. Not done: go to the ball, grasp the ball." in out
    assert "1. find the ball" in out and manager.finished  # 'steps', 'cancel' and 'quit' still read
