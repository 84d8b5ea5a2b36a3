"""The commands a teacher can type, each declared once: its words in both languages, its usage
and its help line. ``Verb.X`` is the command; the session's handler for it is the method
``cmd_x`` (``teach.session.machine`` refuses to load when one is missing). A new command is one
member here and its handler."""

from __future__ import annotations

import difflib
import functools
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from enum import Enum

from teach.dialogue.phrases import INTERJECTIONS, normalize
from teach.errors import TeachError
from teach.messages import Lang, Text
from teach.session.arguments import says_full, step_number, whole_number


@dataclass(frozen=True)
class _Declared:
    en: tuple[str, ...]
    """English words, as typed: one word also starts a line ("run 3"), several words are a
    whole line only ("take that back")."""
    de: tuple[str, ...]
    usage: Text
    help: Text
    argued: bool = False
    """It reads words after it (a number, steps, conditions, a name): a line of a misspelt word
    and more words may be it ("rset 3"); for any other the more words say it was not meant."""
    alone: tuple[str, ...] = ()
    """Words (either language) that name it only as the whole line: "go" is 'run', "go to the
    ball" a step."""


class Verb(Enum):
    HELP = _Declared(("help", "h"), ("hilfe",), Text("help", "hilfe"), Text("show this help", "diese Hilfe zeigen"))
    DEMONSTRATE = _Declared(("demonstrate", "demo"), ("vorführen", "vormachen"),
                            Text("demonstrate [steps]", "vorführen [Schritte]"),
                            Text("start a demonstration", "eine Vorführung beginnen"), argued=True)
    DONE = _Declared(("done", "finished", "that's it", "that is it", "all done", "i'm finished", "that's all",
                      "that is all", "task complete", "task completed", "task done", "job done", "complete",
                      "completed"),
                     ("fertig", "das war's", "das war es", "das wärs", "erledigt", "ich bin fertig", "das war alles",
                      "das war's dann", "das wars dann", "aufgabe erledigt", "alles erledigt"),
                     Text("done", "fertig"),
                     Text("the task is finished: learn this demonstration; also 'that's it'",
                          "die Aufgabe ist erledigt: diese Vorführung lernen; auch 'das war's'"))
    CANCEL = _Declared(("cancel",), ("abbrechen",), Text("cancel", "abbrechen"),
                       Text("discard the open demonstration ('undo' right after brings it back); also "
                            "'forget it'",
                            "die Vorführung verwerfen ('zurück' gleich danach holt sie wieder); auch 'vergiss es'"),
                       alone=("forget it", "forget about it", "vergiss es", "vergiss es einfach"))
    UNDO = _Declared(("undo", "wrong", "that was wrong", "no that was wrong", "no that's wrong", "take that back",
                      "take it back", "oops take that back", "oops", "that's wrong", "that is wrong",
                      "that's not right", "that is not right", "that was not right", "my mistake", "go back",
                      "step back", "one step back", "go back one step"),
                     ("rückgängig", "zurück", "falsch", "das war falsch", "nein das war falsch", "nein falsch",
                      "nimm das zurück", "hoppla", "das ist falsch", "das stimmt nicht", "das war nicht richtig",
                      "mein fehler", "geh zurück", "einen schritt zurück", "schritt zurück"),
                     Text("undo [N] / undo to step N", "zurück [N] / zurück bis Schritt N"),
                     Text("take back the last step (N: steps N to the end), demonstration or answer; "
                          "also 'that was wrong', 'go back'",
                          "letzten Schritt (N: ab Schritt N), Vorführung oder Antwort zurücknehmen; "
                          "auch 'das war falsch', 'geh zurück'"), argued=True, alone=("back",))
    REDO = _Declared(("redo",), ("wiederholen", "wiederherstellen"), Text("redo", "wiederherstellen"),
                     Text("take back the last undo (steps, a demonstration or an answer)",
                          "das letzte Zurücknehmen rückgängig machen (Schritte, eine Vorführung oder eine Antwort)"))
    STEPS = _Declared(("steps",), ("schritte",), Text("steps", "schritte"),
                      Text("list the steps of the open demonstration", "die Schritte der offenen Vorführung zeigen"))
    GUIDE = _Declared(("guide",), ("führen",),
                      Text("guide [forward M|turn [left|right] DEG|lift M|open|close|wait S]",
                           "führen [vor M|drehen [links|rechts] GRAD|heben M|öffnen|schließen|warten S]"),
                      Text("move the robot yourself (MuJoCo world); alone: steer it with the keys "
                           "(↑/↓ move, ←/→ turn, PgUp/PgDn lift, space hand, Esc ends)",
                           "den Roboter selbst bewegen (MuJoCo-Welt); allein: mit den Tasten lenken "
                           "(↑/↓ fahren, ←/→ drehen, Bild↑/Bild↓ heben, Leertaste Hand, Esc Ende)"), argued=True)
    PERTURB = _Declared(("perturb",), ("stören", "ereignis"), Text("perturb EVENT", "stören EREIGNIS"),
                        Text("something happens (an external action)", "etwas passiert (äußeres Ereignis)"),
                        argued=True)
    RUN = _Declared(("run", "now you try", "you try", "your turn", "try it", "try it yourself", "try again",
                     "continue", "keep going", "go on", "carry on", "go ahead", "off you go", "go now", "you do it",
                     "let's see", "can you do it", "can you do it now", "show me what you can do"),
                    ("los", "ausführen", "jetzt du", "du bist dran", "mach du", "versuch es", "versuch es nochmal",
                     "probier es", "probier", "mach weiter", "weitermachen", "leg los", "fang an", "mach mal",
                     "mach du mal", "lass sehen", "lass mal sehen"),
                    Text("run [N]", "los [N]"),
                    Text("let the robot do the task (N: stop after N actions); also 'now you try'",
                         "den Roboter die Aufgabe machen lassen (N: nach N Handlungen anhalten); auch 'jetzt du'"),
                    argued=True, alone=("go", "try"))
    STOP = _Declared(("stop",), ("halt",), Text("stop / Ctrl-C", "halt / Strg-C"),
                     Text("interrupt the robot", "den Roboter anhalten"))
    SHOW = _Declared(("show", "tree", "what did you learn", "what have you learned", "what have you learnt"),
                     ("baum", "zeige", "was hast du gelernt", "was kannst du jetzt"),
                     Text("show [full]", "baum [ganz]"),
                     Text("show the learned tree; also 'what did you learn?'",
                          "den gelernten Baum zeigen; auch 'was hast du gelernt?'"))
    STATE = _Declared(("state", "status", "what do you see", "what can you see", "where are you", "where are we",
                       "what's going on", "what is going on", "what's the situation", "what is the situation",
                       "what are you doing", "what's happening", "what is happening"),
                      ("zustand", "status", "was siehst du", "wo bist du", "wo sind wir", "wie ist die lage",
                       "was ist los", "was machst du", "was machst du gerade"),
                      Text("state [full]", "zustand [ganz]"),
                      Text("show the current situation; also 'what do you see?'",
                           "die aktuelle Lage zeigen; auch 'was siehst du?'"))
    START = _Declared(("start",), ("situation",), Text("start COND ...", "start BEDINGUNG ..."),
                      Text("put the world in a situation (named conditions true)",
                           "die Welt in eine Lage bringen (die genannten Bedingungen gelten)"), argued=True)
    RESET = _Declared(("reset", "start over", "start again", "begin again", "from the beginning",
                       "start from the beginning", "from the start"),
                      ("neu", "von vorn", "von vorne", "nochmal von vorn", "nochmal von vorne", "neu anfangen",
                       "neu beginnen", "von vorn anfangen", "von vorne anfangen"),
                      Text("reset [N]", "neu [N]"),
                      Text("a new start (random in MuJoCo; N: start number N, the same each time); "
                           "also 'start over'",
                           "ein neuer Start (in MuJoCo zufällig; N: Start Nummer N, jedes Mal derselbe); "
                           "auch 'von vorn'"), argued=True)
    ASK = _Declared(("ask", "any questions", "do you have any questions", "do you have questions",
                     "have you got any questions", "questions", "ask me"),
                    ("frag", "frage", "hast du fragen", "hast du noch fragen", "noch fragen",
                     "irgendwelche fragen", "fragen", "frag mich"),
                    Text("ask", "frag"),
                    Text("let the robot ask a question; also 'any questions?'",
                         "den Roboter fragen lassen; auch 'hast du Fragen?'"))
    MODEL = _Declared(("model",), ("modell",), Text("model FILE", "modell DATEI"),
                      Text("load action definitions (pre/ram) and plan with them",
                           "Handlungsbeschreibungen laden und damit planen"), argued=True)
    PLAN = _Declared(("plan",), ("planen",), Text("plan", "planen"),
                     Text("show what the action definitions give", "zeigen, was die Beschreibungen ergeben"))
    SKIP = _Declared(("skip",), ("weiter",), Text("skip", "weiter"),
                     Text("leave a question unanswered", "eine Frage offen lassen (ohne Frage: weitermachen)"))
    WHY = _Declared(("why",), ("warum",), Text("why NAME", "warum NAME"),
                    Text("why a step or a condition is in the tree (why {example})",
                         "warum ein Schritt oder eine Bedingung im Baum ist (warum {example})"), argued=True)
    SAVE = _Declared(("save",), ("speichern",), Text("save", "speichern"),
                     Text("save everything now", "alles jetzt speichern"))
    QUIT = _Declared(("quit", "exit", "good bye", "bye bye", "see you", "see you later"),
                     ("beenden", "tschüss", "auf wiedersehen", "bis dann", "bis später"),
                     Text("quit / Ctrl-D", "beenden / Strg-D"),
                     Text("save and leave (--resume goes on later); also 'bye'",
                          "speichern und beenden (--resume macht später weiter); auch 'tschüss'"),
                     alone=("bye", "goodbye", "ciao", "tschau", "feierabend"))

    @property
    def names(self) -> tuple[str, ...]:
        """The words and sayings that name it in either language, normalized (see ``normalize``), each
        also without its apostrophes, as people type them ("thats it", "das wars")."""
        sayings = (*self.value.en, *self.value.de, *self.value.alone)
        return tuple(dict.fromkeys(normalize(spelled) for word in sayings
                                   for spelled in (word, word.replace("'", ""))))

    def words(self, lang: Lang) -> tuple[str, ...]:
        """Its words in ``lang``, as declared."""
        return self.value.de if lang == Lang.DE else self.value.en

    @property
    def usage(self) -> Text:
        return self.value.usage

    @property
    def help(self) -> Text:
        return self.value.help

    @property
    def handler(self) -> str:
        """The name of the session's method that carries it out."""
        return f"cmd_{self.name.lower()}"


Command = Verb
"""What a line names: one of the verbs, each with its words, usage and help."""
COMMANDS: tuple[Verb, ...] = tuple(Verb)
COMMAND_NAMES = tuple(name for command in COMMANDS for name in command.names if name not in command.value.alone)
"""Every word and saying that names a command, in both languages (``command_hint`` finds them in chatty
lines), but those that name it only alone ("go to the bin please" is no chatty 'go')."""

NUMBERED: dict[Verb, Callable[[str, Lang], int | None]] = {Verb.RUN: whole_number, Verb.RESET: whole_number,
                                                          Verb.UNDO: step_number}
"""The commands whose argument is a number, and how it is read."""

BLOCKED_WHILE_ASKING = frozenset({Verb.GUIDE, Verb.DEMONSTRATE, Verb.RUN, Verb.START, Verb.RESET, Verb.PERTURB,
                                  Verb.MODEL, Verb.ASK})
"""Commands that would change what an open question is about."""
ANSWERING = frozenset({Verb.DONE, Verb.SKIP})
"""Commands that are also answers to an open question."""
LOOKING = frozenset({Verb.HELP, Verb.STATE, Verb.SHOW, Verb.STEPS, Verb.WHY, Verb.SAVE, Verb.QUIT})
"""Commands that only look (or leave), allowed while a labelling question is open."""

DONE_WORDS = set(Verb.DONE.names) | {"nothing", "nothing task is done", "nichts", "ziel erreicht"}
IMPOSSIBLE_WORDS = {normalize(said) for said in (
    "that cannot happen", "that can't happen", "that cant happen", "cannot happen", "impossible", "that is impossible",
    "that's impossible", "that's not possible", "that is not possible", "not possible", "that can't be",
    "that cannot be", "das gibt es nicht", "gibt es nicht", "das geht nicht", "unmöglich", "das ist unmöglich",
    "das kann nicht sein", "das ist nicht möglich", "nicht möglich")}
"""Answers saying the asked-about situation cannot happen: free, and never asked again."""
PUZZLED_WORDS = {normalize(said) for said in (
    "huh", "what", "pardon", "sorry what", "come again", "say that again", "say again", "repeat", "repeat that",
    "repeat the question", "what was the question", "what do you mean", "i don't understand", "i do not understand",
    "i don't get it", "wie bitte", "was", "hä", "bitte was", "was meinst du", "versteh ich nicht",
    "ich verstehe nicht", "ich verstehe das nicht", "nochmal bitte", "was war die frage", "wiederhol das")}
"""Answers that did not follow the question ("huh?", "wie bitte?"): it is asked again, as it was."""
NONSENSE_WORDS = {normalize(said) for said in (
    "that makes no sense", "makes no sense", "that doesn't make sense", "that does not make sense", "how can that be",
    "how is that possible", "that's silly", "that is silly", "nonsense", "das ergibt keinen sinn",
    "das macht keinen sinn", "wie soll das gehen", "unsinn", "quatsch", "so ein quatsch")}
"""Answers doubting the asked-about situation ("that makes no sense"): asked whether it cannot
happen at all, never taken as 'that cannot happen' on a guess."""
SKIP_WORDS = set(Verb.SKIP.names) | {"dont know", "don t know", "i dont know", "i don t know", "weiss nicht",
                                     "ich weiss nicht", "keine ahnung", "uberspringen", "forget it",
                                     "forget about it", "vergiss es"}
"""Answers that pass a question by ("forget it" to one was "What should I do there instead?")."""
HESITATIONS = INTERJECTIONS | {"well", "na", "also"}
"""Sounds and words a hesitant answer starts with, set aside before it is compared ("hmm, I think so")."""


UNSURE_WORDS = {normalize(said) for said in ("maybe", "perhaps", "depends", "it depends", "not sure", "i'm not sure",
                                             "i am not sure", "no idea", "hard to say", "sometimes", "vielleicht",
                                             "kommt darauf an", "kommt drauf an", "nicht sicher",
                                             "ich bin nicht sicher", "schwer zu sagen", "manchmal")}
"""Answers that neither allow nor forbid: the question stays open, and 'skip' is offered."""
LIKELY_WORDS = {normalize(said) for said in ("i think so", "i guess so", "i suppose so", "probably", "should be",
                                             "ich glaube schon", "ich denke schon", "glaube schon", "denke schon",
                                             "wahrscheinlich", "vermutlich")}
"""A yes with a doubt: asked again as "is that a yes?" (a care robot does not act on a guess)."""
WHY_ASKING = {normalize(said) for said in ("", "do you ask", "are you asking", "you ask", "ask", "that", "this",
                                           "is that", "fragst du", "fragst du das", "das", "diese frage")}
"""What follows 'why' while a question is open when it asks about the question itself ("why do you ask?")."""
WHY_ASKING_LINES = {normalize(f"{why} {said}") for why in ("why", "warum", "wieso") for said in WHY_ASKING}
"""Whole lines asking why a question is asked ("why?", "warum das?") while one is open."""
WHAT_NOW_WORDS = {normalize(said) for said in ("what now", "now what", "what next", "what should i do",
                                               "what do i do", "what shall i do", "what can you do",
                                               "what's next", "whats next", "what comes next", "what is next",
                                               "what do we do", "what should we do", "wie geht es weiter",
                                               "wie weiter", "was als nächstes", "was kommt jetzt",
                                               "was jetzt", "was nun", "und jetzt", "was soll ich tun",
                                               "was soll ich machen", "was mache ich jetzt", "was kannst du")}
"""Whole lines asking what to do next (also, with no question open, the "I don't know"s of
``SKIP_WORDS``): answered with the steps the domain's model allows from here."""
PRAISE_WORDS = frozenset(normalize(said) for said in (
    "thanks", "thank you", "thanks a lot", "good job", "great job", "nice job", "well done", "good", "very good",
    "great", "perfect", "nice", "nice one", "excellent", "awesome", "cool", "yay", "bravo", "thumbs up", "good robot",
    "good boy", "good girl", "danke", "danke schön", "dankeschön", "vielen dank", "gut gemacht", "sehr gut", "gut",
    "prima", "toll", "super", "klasse", "perfekt", "brav", "spitze", "wunderbar", "daumen hoch"))
"""Praise and thanks (with no question open): thanked back, with the next step to take, never
read as 'done' ("well done" after a run was "You have not shown me any steps")."""
_COURTESY_AROUND = frozenset({"robot", "roboter", "ok", "okay", "very much", "so much", "really", "that was",
                              "that s", "thats", "das war", "das hast du", "hast du", "gemacht"})
"""Words that go with praise or a greeting ("thank you very much, robot", "das hast du gut gemacht")."""
GREETINGS = frozenset(normalize(said) for said in (
    "hello", "hi", "hey", "hi there", "hello there", "good morning", "good afternoon", "good evening", "hallo",
    "guten morgen", "guten tag", "guten abend", "servus", "moin", "grüß gott", "grüß dich"))
"""Whole lines greeting the robot: greeted back with what it can do, as at the start ("hallo" was
"Did you mean 'halt'?")."""
APPROVING_MARKS = ("👍", "👏", "👌", "🙂", "😊", "😀", "😃", "😄", "😁", "❤️", "❤", "♥", "💪", "🎉",
                   ":-)", ":)", ":D", "+1")
"""Emoji and marks people praise with ("👍" was "I don't know '👍'"); to a "may I …?" question they
are asked back as "is that a yes?" (a care robot does not act on a thumb)."""
HOLD_ON_WORDS = frozenset(normalize(said) for said in (
    "wait", "wait a moment", "wait a second", "wait a minute", "hold on", "hang on", "one moment", "just a moment",
    "a moment", "moment", "one second", "one sec", "just a second", "let me think", "give me a moment", "warte",
    "warte mal", "moment mal", "einen moment", "augenblick", "sekunde", "lass mich überlegen",
    "lass mich nachdenken")) | (INTERJECTIONS - {"sorry"})
"""Lines asking the robot to wait, or only hesitating ("hmm", "wait", "einen Moment"): it waits and
says so, a question staying open ("wait" was "I don't know 'wait'", "wait, no" too)."""
_WAITING_AROUND = frozenset({"robot", "roboter", "ok", "okay", "please", "bitte"})
"""Words that go with a "wait" ("hold on, robot"); not "that's", which begins "that's not right"."""
_COURTESY = PRAISE_WORDS | GREETINGS
"""What ``after_courtesy`` sets aside before a step or a command."""


@functools.cache
def _longest_first(sayings: frozenset[str], around: frozenset[str]) -> tuple[str, ...]:
    """``sayings`` and the words around them, the longest first (read greedily by ``_only``)."""
    return tuple(sorted(sayings | around | HESITATIONS, key=lambda saying: -len(saying.split())))


def _only(line: str, sayings: frozenset[str], around: frozenset[str] = _COURTESY_AROUND) -> bool:
    """Whether a line says nothing but some of ``sayings`` and the words ``around`` them ("great,
    well done!", "thank you robot", "super, das hast du gut gemacht")."""
    words = normalize(line).split()
    known = _longest_first(sayings, around)
    said = False
    while words:
        for saying in known:
            length = len(saying.split())
            if " ".join(words[:length]) == saying:
                said = said or saying in sayings
                del words[:length]
                break
        else:
            return False
    return said


def is_praise(line: str) -> bool:
    """Whether a whole line only praises or thanks the robot, in words or marks ("👍", "great :)")."""
    return only_marks(line) or _only(_without_marks(line), PRAISE_WORDS)


def only_marks(line: str) -> bool:
    """Whether a line is approving marks and nothing else that says anything ("👍", "👍👍!")."""
    unmarked = _without_marks(line)
    return unmarked != line.strip() and not normalize(unmarked)


def _without_marks(line: str) -> str:
    for mark in APPROVING_MARKS:
        line = line.replace(mark, " ")
    return line.strip()


def is_holding_on(line: str) -> bool:
    """Whether a whole line only asks the robot to wait or hesitates ("hmm", "hold on, robot")."""
    return _only(line, HOLD_ON_WORDS, _WAITING_AROUND)


def after_holding_on(line: str) -> str:
    """The line without the words asking to wait it starts or ends with ("wait, no" and "no, wait":
    "no"); the line itself where it has none there, "" where it is nothing else."""
    words = line.split()
    start = next((cut for cut in range(len(words), 0, -1) if is_holding_on(" ".join(words[:cut]))), 0)
    end = next((cut for cut in range(start, len(words)) if is_holding_on(" ".join(words[cut:]))), len(words))
    return line if (start, end) == (0, len(words)) else " ".join(words[start:end])


def is_greeting(line: str) -> bool:
    """Whether a whole line only greets the robot ("hello robot", "guten Morgen")."""
    return _only(line, GREETINGS)


def after_courtesy(line: str) -> str:
    """The line without the praise or greeting it starts with ("good, now go to the ball" is "now
    go to the ball", "hallo, such den Ball" "such den Ball"); the line itself if it starts with none."""
    words = line.split()
    for cut in range(len(words) - 1, 0, -1):
        if _only(" ".join(words[:cut]), _COURTESY):
            return " ".join(words[cut:])
    return line


WHERE_STARTS = ("where is ", "where s ", "where are ", "wo ist ", "wo sind ", "wo liegt ")
"""How a line asking where something is starts ("where is the ball?"): answered with the situation."""
_MEANT = re.compile(r"^(?:(?:oops|sorry|no|nein|hoppla|ups|entschuldigung)\W+)*"
                    r"(?:i meant to say|i meant|i mean|i wanted|meant|ich meinte|ich meine|ich wollte|gemeint war)"
                    r"\W+(?P<steps>.+)$", re.IGNORECASE)


def meant_instead(line: str) -> str | None:
    """The steps a line says were meant instead of the last one ("oops, I meant go to the ball",
    "nein, ich meinte zum Ball"), or None: it was "expected a whole number" ('oops' is an undo)."""
    said = _MEANT.match(line.strip())
    return said.group("steps").strip() if said else None


AGAIN_WORDS = {normalize(said) for said in ("again", "and again", "again please", "once more", "one more time",
                                            "do it again", "do that again", "same again", "the same again",
                                            "can you do it again", "could you do that again",
                                            "nochmal", "noch mal", "noch einmal", "nochmals", "und nochmal",
                                            "wieder", "mach das nochmal", "mach es nochmal", "das gleiche nochmal",
                                            "kannst du das nochmal machen", "nochmal machen")}
"""Whole lines asking for the step just done once more ("offer a snack", "again", "again": "again"
alone was "I don't know “again”"; "can you do it again?")."""
DOUBT_WORDS = {normalize(said) for said in ("why", "why that", "why did you do that", "why did you do it",
                                            "why did you do this", "why that one", "are you sure",
                                            "are you sure about that", "you sure", "is that right", "is that correct",
                                            "warum", "warum das", "warum hast du das gemacht",
                                            "warum hast du das getan",
                                            "wieso", "wieso das", "weshalb", "bist du sicher", "bist du dir sicher",
                                            "stimmt das", "ist das richtig")}
"""Whole lines doubting the step just done ("are you sure?" was "I don't know", "why did you do
that?" "No tree yet."): they are told why it was done."""
DONE_YET_WORDS = {normalize(said) for said in ("is it done", "are you done", "are we done", "is the task done",
                                               "is the task finished", "is it finished", "are you finished",
                                               "have you finished", "is that it", "ist es fertig", "bist du fertig",
                                               "sind wir fertig", "ist die aufgabe erledigt", "ist die aufgabe fertig",
                                               "ist es erledigt", "war es das")}
"""Whole lines asking whether the task is finished ("is it done?" was "I don't know", "are we
done?" ended the demonstration): answered from the domain's goal, nothing ended."""
BACK_WORDS = {normalize(said) for said in ("back", "go back", "step back", "one step back", "go back one step",
                                           "zurück", "geh zurück", "fahr zurück", "einen schritt zurück",
                                           "schritt zurück")}
"""'undo' in everyday words that, while guiding, mean the robot backing up a key's step instead."""
GOING_ON_WORDS = {normalize(said) for said in ("weiter",)}
"""A 'skip' word that, with no question open, means going on: run ("weiter" after an answer was "Es
ist keine Frage offen.")."""
TASK_WORDS = {normalize(said) for said in (
    "what is the task", "what's the task", "whats the task", "what is the goal", "what's the goal", "whats the goal",
    "what is your task", "what's your task", "what is your goal", "what's your goal", "what is your job",
    "what are you supposed to do", "what do you have to do", "what are we trying to do", "what is the task again",
    "was ist die aufgabe", "was ist das ziel", "was ist deine aufgabe", "was ist dein ziel", "was sollst du tun",
    "was sollst du machen", "was musst du tun", "was ist nochmal die aufgabe")}
"""Whole lines asking what the task is ("what is the goal?" was "I don't know"): what the robot has
learned of when it is done, or the domain's declared goal."""
WHO_WORDS = {normalize(said) for said in ("who are you", "what are you", "wer bist du", "was bist du")}
"""Whole lines asking who the robot is ("who are you" was "Did you mean 'why are you'?"): greeted."""
ASKING_SOMEONE = frozenset({"if", "whether", "ob"})
"""After 'ask', a word that makes a line near a domain step that step, not 'ask' ("frag ob jemand
einen Keks will" was "I have no question right now"; snacks offers "frag ob sie etwas möchten";
the ball's "ask if you have a question" stays 'ask')."""
NO_MATTER_WORDS = {normalize(said) for said in ("sorry", "oh sorry", "never mind", "nevermind", "no worries",
                                                "no problem", "all good", "ok", "okay", "ok then", "alright",
                                                "all right", "fine", "got it", "i see", "understood",
                                                "entschuldigung", "egal", "schon gut", "macht nichts", "kein problem",
                                                "alles gut", "alles klar", "verstanden", "ach so", "aha")}
"""Whole lines that ask for nothing (with no question open): "All right.", nothing done ("sorry"
was "I don't know 'sorry'" and a list of what the robot can do; "ok" "No question is open")."""
DOUBTS = UNSURE_WORDS | LIKELY_WORDS
"""The doubtful answers ("maybe", "I think so"): with no question open, said to have nothing to answer."""
ANSWERS_ONLY = DOUBTS | IMPOSSIBLE_WORDS | NONSENSE_WORDS
"""What only answers a question ("maybe", "that cannot happen"): with none open, said to have nothing to answer."""
ANSWER_SAYINGS = (DONE_WORDS | SKIP_WORDS | IMPOSSIBLE_WORDS | PUZZLED_WORDS | NONSENSE_WORDS | WHAT_NOW_WORDS | DOUBTS
                  | NO_MATTER_WORDS)
"""Every whole line a session takes as an answer or a plea, not as a step or a command (after
``without_hesitation``): what a dialogue file may say besides steps and commands."""


def without_hesitation(key: str) -> str:
    """A normalized answer without the sounds it starts with ("hmm i think so" is "i think so")."""
    words = key.split()
    while words and words[0] in HESITATIONS:
        words.pop(0)
    return " ".join(words)


def parse_command(line: str) -> tuple[Command | None, str]:
    """The command a line starts with (one of its single words) or is as a whole ("that was
    wrong"), and the rest of the line; ``(None, line)`` when it names none."""
    whole = normalize(line)
    said = whole.split()
    if len(said) > 1 and len(set(said)) == 1:  # "undo undo", "stop stop", "go go": once
        whole = said[0]  # ("undo undo" was "expected a whole number, not 'undo'")
    for command in COMMANDS:
        if whole and whole in command.names:
            return command, ""
    words = line.split(maxsplit=1)
    head = normalize(words[0]) if words else ""
    for command in COMMANDS:
        if head and head in command.names and head not in command.value.alone:
            return command, words[1] if len(words) > 1 else ""
    return None, line


def _reads(command: Verb, rest: str, lang: Lang) -> bool:
    """Whether ``command`` takes ``rest`` as what follows it: "give her a cookie" is no 'guide', "bring
    the tray back" no 'wrong' (undo); they were offered as "Did you mean 'guide her a cookie'?"."""
    if not rest:
        return True
    if command in (Verb.SHOW, Verb.STATE):
        return says_full(rest)
    if not command.value.argued:
        return False
    if command is Verb.MODEL:  # "move a onto b" was "Did you mean 'model a onto b'?"
        return rest.strip().endswith(".toml")
    reads = NUMBERED.get(command)
    try:
        if reads is not None:
            reads(rest, lang)
        elif command is Verb.GUIDE:
            from teach.sim.guide import parse_guide_line  # MuJoCo only where a guide line is asked about

            parse_guide_line(f"guide {rest}")
    except TeachError:
        return False
    return True


TYPO_CUTOFF = 0.6
"""Similarity (``difflib``) from which a first word is read as a typo of a command word: "hlep"
and "yse" (0.75, 0.67) are, "rum" for "run" too; two words that close are not guessed between."""


def typo_of_command(line: str, lang: Lang, answers: Iterable[str] = (),
                    rivals: frozenset[str] = frozenset()) -> str | None:
    """The line with its first word read as the word of ``lang`` (a command's, or one of
    ``answers`` while a question is open) it is a typo of — "hlep" gives "help", "sohw full"
    gives "show full" — or None where no word is close, two are about as close, the first word
    is a known one, or one of ``rivals`` (the phrases' words) is closer."""
    words = line.split(maxsplit=1)
    typed = normalize(words[0]) if words else ""
    if len(typed) < 3:
        return None
    rest = words[1] if len(words) > 1 else ""
    said = {word: command for command in COMMANDS for word in command.words(lang) if " " not in word and len(word) >= 3}
    if typed in said or typed in answers or typed in rivals:  # a word it knows is no typo ("yes xyzzy")
        return None
    # with more words, only a command that reads them ("take a off c" was "did you mean 'state a off c'?")
    known = {word for word, command in said.items() if _reads(command, rest, lang)}
    known.update(answers)
    scored = sorted(((difflib.SequenceMatcher(None, typed, word).ratio(), word) for word in known), reverse=True)
    if not scored or scored[0][0] < TYPO_CUTOFF or (len(scored) > 1 and scored[1][0] > scored[0][0] - 0.05):
        return None
    if any(difflib.SequenceMatcher(None, typed, word).ratio() > scored[0][0] for word in rivals):
        return None
    return " ".join([scored[0][1], *words[1:]])
