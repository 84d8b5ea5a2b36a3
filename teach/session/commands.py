"""The commands a teacher can type, in both languages, and how a line names one."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum, auto

from teach import messages as m
from teach.dialogue.phrases import normalize
from teach.messages import Text


class Verb(Enum):
    HELP = auto()
    DEMONSTRATE = auto()
    DONE = auto()
    CANCEL = auto()
    UNDO = auto()
    REDO = auto()
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
    GUIDE = auto()


@dataclass(frozen=True)
class Command:
    verb: Verb
    names: tuple[str, ...]
    """The words that name it, normalized (see ``teach.dialogue.phrases.normalize``)."""
    usage: Text
    help: Text


COMMANDS: tuple[Command, ...] = (
    Command(Verb.HELP, ("help", "hilfe", "h"), m.USAGE_HELP, m.HELP_HELP),
    Command(Verb.DEMONSTRATE, ("demonstrate", "demo", "zeigen", "vorfuhren"), m.USAGE_DEMONSTRATE,
            m.HELP_DEMONSTRATE),
    Command(Verb.DONE, ("done", "fertig"), m.USAGE_DONE, m.HELP_DONE),
    Command(Verb.CANCEL, ("cancel", "abbrechen"), m.USAGE_CANCEL, m.HELP_CANCEL),
    Command(Verb.UNDO, ("undo", "ruckgangig", "zuruck"), m.USAGE_UNDO, m.HELP_UNDO_TO_STEP),
    Command(Verb.REDO, ("redo", "wiederholen", "wiederherstellen"), m.USAGE_REDO, m.HELP_REDO),
    Command(Verb.STEPS, ("steps", "schritte"), m.USAGE_STEPS, m.HELP_STEPS),
    Command(Verb.GUIDE, ("guide", "fuhren"), m.USAGE_GUIDE, m.HELP_GUIDE),
    Command(Verb.PERTURB, ("perturb", "storen", "ereignis"), m.USAGE_PERTURB, m.HELP_PERTURB),
    Command(Verb.RUN, ("run", "los", "ausfuhren"), m.USAGE_RUN, m.HELP_RUN),
    Command(Verb.STOP, ("stop", "halt"), m.USAGE_STOP, m.HELP_STOP),
    Command(Verb.SHOW, ("show", "zeige", "baum"), m.USAGE_SHOW, m.HELP_SHOW),
    Command(Verb.STATE, ("state", "zustand"), m.USAGE_STATE, m.HELP_STATE),
    Command(Verb.START, ("start", "situation"), m.USAGE_START, m.HELP_START),
    Command(Verb.RESET, ("reset", "neu"), m.USAGE_RESET, m.HELP_RESET),
    Command(Verb.ASK, ("ask", "frag", "frage"), m.USAGE_ASK, m.HELP_ASK),
    Command(Verb.MODEL, ("model", "modell"), m.USAGE_MODEL, m.HELP_MODEL),
    Command(Verb.PLAN, ("plan", "planen"), m.USAGE_PLAN, m.HELP_PLAN),
    Command(Verb.SKIP, ("skip", "weiter"), m.USAGE_SKIP, m.HELP_SKIP),
    Command(Verb.WHY, ("why", "warum"), m.USAGE_WHY, m.HELP_WHY),
    Command(Verb.SAVE, ("save", "speichern"), m.USAGE_SAVE, m.HELP_SAVE),
    Command(Verb.QUIT, ("quit", "exit", "beenden", "tschuss"), m.USAGE_QUIT, m.HELP_QUIT),
)

COMMAND_WORDS = tuple(name for command in COMMANDS for name in command.names)
"""Every word that names a command, in both languages (``command_hint`` finds them in chatty lines)."""

BLOCKED_WHILE_ASKING = frozenset({Verb.GUIDE, Verb.DEMONSTRATE, Verb.RUN, Verb.START, Verb.RESET, Verb.PERTURB,
                                  Verb.MODEL, Verb.ASK})
"""Commands that would change what an open question is about."""
ANSWERING = frozenset({Verb.DONE, Verb.SKIP})
"""Commands that are also answers to an open question."""
LOOKING = frozenset({Verb.HELP, Verb.STATE, Verb.SHOW, Verb.STEPS, Verb.WHY, Verb.SAVE, Verb.QUIT})
"""Commands that only look (or leave), allowed while a labelling question is open."""

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
