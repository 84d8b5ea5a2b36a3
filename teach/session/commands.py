"""The commands a teacher can type, in both languages, and how a line names one."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum, auto

from teach.dialogue.phrases import normalize
from teach.session import messages as m
from teach.session.messages import Text


class Verb(Enum):
    HELP = auto()
    DEMONSTRATE = auto()
    DONE = auto()
    CANCEL = auto()
    UNDO = auto()
    PERTURB = auto()
    RUN = auto()
    STOP = auto()
    SHOW = auto()
    STATE = auto()
    START = auto()
    RESET = auto()
    ASK = auto()
    MODEL = auto()
    PLAN = auto()
    SKIP = auto()
    WHY = auto()
    SAVE = auto()
    QUIT = auto()
    STEPS = auto()


@dataclass(frozen=True)
class Command:
    verb: Verb
    names: tuple[str, ...]
    """The words that name it, normalized (see ``teach.dialogue.phrases.normalize``)."""
    usage: str
    help: Text


COMMANDS: tuple[Command, ...] = (
    Command(Verb.HELP, ("help", "hilfe", "h"), "help", m.HELP_HELP),
    Command(Verb.DEMONSTRATE, ("demonstrate", "demo", "zeigen", "vorfuhren"), "demonstrate [steps]",
            m.HELP_DEMONSTRATE),
    Command(Verb.DONE, ("done", "fertig"), "done", m.HELP_DONE),
    Command(Verb.CANCEL, ("cancel", "abbrechen"), "cancel", m.HELP_CANCEL),
    Command(Verb.UNDO, ("undo", "ruckgangig", "zuruck"), "undo [N]", m.HELP_UNDO_TO_STEP),
    Command(Verb.STEPS, ("steps", "schritte"), "steps", m.HELP_STEPS),
    Command(Verb.PERTURB, ("perturb", "storen", "ereignis"), "perturb EVENT", m.HELP_PERTURB),
    Command(Verb.RUN, ("run", "los", "ausfuhren"), "run [N]", m.HELP_RUN),
    Command(Verb.STOP, ("stop", "halt"), "stop / Ctrl-C", m.HELP_STOP),
    Command(Verb.SHOW, ("show", "zeige", "baum"), "show [full]", m.HELP_SHOW),
    Command(Verb.STATE, ("state", "zustand"), "state", m.HELP_STATE),
    Command(Verb.START, ("start", "situation"), "start COND ...", m.HELP_START),
    Command(Verb.RESET, ("reset", "neu"), "reset [SEED]", m.HELP_RESET),
    Command(Verb.ASK, ("ask", "frag", "frage"), "ask", m.HELP_ASK),
    Command(Verb.MODEL, ("model", "modell"), "model FILE", m.HELP_MODEL),
    Command(Verb.PLAN, ("plan", "planen"), "plan", m.HELP_PLAN),
    Command(Verb.SKIP, ("skip", "weiter"), "skip", m.HELP_SKIP),
    Command(Verb.WHY, ("why", "warum"), "why NAME", m.HELP_WHY),
    Command(Verb.SAVE, ("save", "speichern"), "save", m.HELP_SAVE),
    Command(Verb.QUIT, ("quit", "exit", "beenden", "tschuss"), "quit / Ctrl-D", m.HELP_QUIT),
)

COMMAND_WORDS = tuple(name for command in COMMANDS for name in command.names)
"""Every word that names a command, in both languages (``command_hint`` finds them in chatty lines)."""

BLOCKED_WHILE_ASKING = frozenset({Verb.DEMONSTRATE, Verb.RUN, Verb.START, Verb.RESET, Verb.PERTURB, Verb.MODEL,
                                  Verb.ASK})
"""Commands that would change what an open question is about."""
ANSWERING = frozenset({Verb.DONE, Verb.SKIP})
"""Commands that are also answers to an open question."""

DONE_WORDS = {"done", "finished", "nothing", "nothing task is done", "fertig", "nichts", "ziel erreicht"}
SKIP_WORDS = {"skip", "dont know", "don t know", "i dont know", "i don t know", "weiter", "weiss nicht",
              "ich weiss nicht", "keine ahnung", "uberspringen"}


def parse_command(line: str) -> tuple[Command | None, str]:
    """The command a line starts with (or is, as a whole phrase) and the rest of the line;
    ``(None, line)`` when it names none."""
    words = line.split(maxsplit=1)
    head = normalize(words[0]) if words else ""
    for command in COMMANDS:
        if head in command.names:
            return command, words[1] if len(words) > 1 else ""
    whole = normalize(line)
    for command in COMMANDS:
        if whole in command.names:
            return command, ""
    return None, line
