"""Every message a teacher sees, in English and German: the one catalogue.

A message is a ``Text`` with both languages and ``{name}`` fields filled in when it is said:
``HELLO("de", actions=...)``. ``tests/test_messages.py`` fails when one lacks a language or
the two disagree on their fields.
"""

from __future__ import annotations

import string
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from teach.errors import FormatError


class Lang(StrEnum):
    """The languages the session speaks. A ``StrEnum``: ``Lang.DE == "de"``, so a language read
    as a string anywhere still compares equal; it is parsed once where it enters (the command
    line's settings, a dialogue's ``@lang``, a journal's header), so an unknown one is an error."""

    EN = "en"
    DE = "de"

    @classmethod
    def parse(cls, text: str, path: str | Path | None = None, line: int | None = None) -> Lang:
        """``text`` as a language, or one line naming the file (and line) it came from."""
        try:
            return cls(text)
        except ValueError:
            known = ", ".join(cls)
            raise FormatError(f"unknown language {str(text)[:40]!r} (known: {known})", path, line) from None


@dataclass(frozen=True)
class Text:
    en: str
    de: str

    def __call__(self, lang: str, **fields: object) -> str:
        """The text in ``lang`` (a ``Lang``; a plain "en"/"de" from outside the session works too)."""
        return (self.de if lang == Lang.DE else self.en).format(**fields)

    def fields(self, lang: Lang) -> set[str]:
        """The ``{name}`` fields the text in ``lang`` fills in."""
        text = self.de if lang == Lang.DE else self.en
        return {name for _, name, _, _ in string.Formatter().parse(text) if name}


# --- greeting, help, the state -----------------------------------------------------------------
HELLO = Text("Hello! Show me how to do the task, one step at a time. I can: {actions}. "
             "Say 'done' when the task is finished, 'help' for more.",
             "Hallo! Zeig mir die Aufgabe Schritt für Schritt. Ich kann: {actions}. "
             "Sag 'fertig', wenn die Aufgabe erledigt ist, 'hilfe' für mehr.")
WHAT_I_CAN = Text("I can: {actions}. Say 'help' for what else you can type.",
                  "Ich kann: {actions}. Sag 'hilfe' für alles, was du eingeben kannst.")
WHAT_CAN_HAPPEN = Text(" What can happen meanwhile (say it when it does): {events}.",
                       " Was dabei passieren kann (sag es, wenn es passiert): {events}.")
HELP_INTRO = Text("Type what the robot should do, e.g. “{examples}”.",
                  "Schreib, was der Roboter tun soll, z. B. „{examples}“.")
HELP_ASK = Text("You can also ask me: 'what now?', 'why did you do that?', 'are you sure?', 'is it done?', "
                "'what is the task?', and say 'again' for the last step once more.",
                "Du kannst mich auch fragen: 'was jetzt?', 'warum hast du das gemacht?', 'bist du sicher?', "
                "'ist es fertig?', 'was ist die Aufgabe?', und 'nochmal' sagen für den letzten Schritt noch einmal.")
MORE_ACTIONS = Text("{count} more like them (Tab)", "{count} weitere solche (Tab)")
AND_MORE = Text(" and {count} more like them", " und {count} weitere solche")
AND = Text(" and ", " und ")
OR = Text(" or ", " oder ")

# --- demonstrations ----------------------------------------------------------------------------
NEW_DEMONSTRATION = Text("New demonstration. Show me the steps.", "Neue Vorführung. Zeig mir die Schritte.")
NO_STEPS_YET = Text("You have not shown me any steps yet.", "Du hast mir noch keine Schritte gezeigt.")
NOT_FINISHED = Text("The task is not finished yet: {unmet}. Show me more, or say 'cancel'.",
                    "Die Aufgabe ist noch nicht erledigt: {unmet}. Zeig mir mehr, oder sag 'abbrechen'.")
DISCARDED = Text("Demonstration discarded ('undo' right away brings it back).",
                 "Vorführung verworfen ('zurück' gleich danach holt sie wieder).")
DISCARDED_EMPTY = Text("Demonstration discarded (it had no steps).", "Vorführung verworfen (sie hatte keine Schritte).")
NOT_BACK = Text("The demonstration you discarded cannot come back: something happened since. Nothing was undone.",
                "Die verworfene Vorführung kann nicht wiederkommen: seitdem ist etwas passiert. Nichts wurde "
                "rückgängig gemacht.")
BROUGHT_BACK = Text("Back again: the demonstration you discarded ({steps}). Go on showing me.",
                    "Wieder da: die verworfene Vorführung ({steps}). Zeig mir weiter.")
NOTHING_TO_UNDO = Text("Nothing to undo.", "Nichts rückgängig zu machen.")
UNDONE_LEARNING = Text("Undone: the last demonstration or answer.", "Rückgängig: die letzte Vorführung oder Antwort.")
NOTHING_TO_REDO = Text("Nothing to redo: 'redo' brings back what the last 'undo' took, until you do something new.",
                       "Nichts wiederherzustellen: 'wiederherstellen' bringt zurück, was das letzte 'zurück' "
                       "genommen hat, solange du nichts Neues tust.")
REDONE_ONE_STEP = Text("Back again: step {first} ({steps}).", "Wieder da: Schritt {first} ({steps}).")
REDONE_STEPS = Text("Back again: steps {first} to {last} ({steps}).",
                    "Wieder da: Schritte {first} bis {last} ({steps}).")
REDONE_DEMONSTRATION = Text("Back again: your demonstration {name}, learned again.",
                            "Wieder da: deine Vorführung {name}, wieder gelernt.")
REDONE_LEARNING = Text("Back again: what the last undo took.", "Wieder da: was das letzte Zurücknehmen genommen hat.")
REDONE_ANSWER = Text("Back again: your answer to “{question}”.", "Wieder da: deine Antwort auf „{question}“.")
UNDONE_DEMONSTRATION = Text("Undone: your demonstration {name} (set aside, not learned).",
                            "Rückgängig: deine Vorführung {name} (beiseitegelegt, nicht gelernt).")
UNDONE_ANSWER = Text("Undone: your answer to “{question}”.", "Rückgängig: deine Antwort auf „{question}“.")
WHICH_EVENT = Text("Which event? I know: {names}.", "Welches Ereignis? Ich kenne: {names}.")
EVENT = Text("Event: {event}.", "Ereignis: {event}.")
EVENT_NOT_NOW = Text("“{event}” cannot happen now (nothing changed, not recorded).",
                     "„{event}“ kann jetzt nicht passieren (nichts hat sich geändert, nicht aufgezeichnet).")
NOT_WITHOUT = Text("“{said}”: {reason}", "„{said}“: {reason}")
"""A step said by a phrase that needs more than the step ("bring it to the bin" with nothing in hand)."""
COULD_NOT = Text("I could not {action}: {reason}", "„{action}“ ging nicht: {reason}")
WHAT_NOW = Text("From here I can: {actions}. Tell me the next step, or say 'done' when the task is finished "
                "('help' for more).",
                "Von hier aus kann ich: {actions}. Sag mir den nächsten Schritt, oder 'fertig', wenn die Aufgabe "
                "erledigt ist ('hilfe' für mehr).")
WHAT_NOW_FINISHED = Text("The task is finished here: say 'done' if this is how it should end, or 'reset' for a new "
                         "start ('help' for more).",
                         "Die Aufgabe ist hier erledigt: sag 'fertig', wenn sie so enden soll, oder 'neu' für einen "
                         "neuen Start ('hilfe' für mehr).")
WAY_THERE = Text("To get there: {steps}.", "Der Weg dahin: {steps}.")
WAY_THERE_OFFER = Text("To get there: {steps}. Say 'yes' and I do that, then {action}.",
                       "Der Weg dahin: {steps}. Sag 'ja', dann tue ich das und danach „{action}“.")
WAY_AGAIN = Text("Now {untrue}: first {steps}, then {action}.",
                 "Jetzt gilt: {untrue}. Also erst {steps}, dann „{action}“.")
DID_STEP = Text("✓ {action}", "✓ {action}")
ALREADY_SO = Text("– {action}: {so} already (nothing to do, not recorded)",
                  "– {action}: schon so – {so} (nichts zu tun, nicht aufgezeichnet)")
NOTHING_CHANGED = Text("✓ {action} (nothing changed: not recorded)",
                       "✓ {action} (nichts hat sich geändert: nicht aufgezeichnet)")
CANNOT_LEARN = Text("I cannot learn this demonstration: {why} Say 'undo' to take back steps, or 'cancel'.",
                    "Diese Vorführung kann ich nicht lernen: {why} "
                    "Sag 'zurück', um Schritte zurückzunehmen, oder 'abbrechen'.")
DETAILS = Text("({details})", "({details})")
FINISH_FIRST = Text("Finish or cancel the open demonstration first.",
                    "Beende oder verwirf zuerst die laufende Vorführung.")
WHICH_CONDITION = Text("which condition is {name!r}: {some}?",
                       "welche Bedingung ist {name!r}: {some}?")
UNKNOWN_CONDITION_LIKE = Text("I know no condition {name!r}; did you mean {some}?",
                              "ich kenne keine Bedingung {name!r}; meintest du {some}?")
UNKNOWN_CONDITION = Text("unknown condition {name!r} (known: {known})",
                         "unbekannte Bedingung {name!r} (bekannt: {known})")

# --- runs --------------------------------------------------------------------------------------
NOTHING_LEARNED = Text("I have not learned anything yet: show me first.",
                       "Ich habe noch nichts gelernt: zeig es mir zuerst.")
FINISH_BEFORE_RUN = Text("Finish ('done') or cancel the open demonstration first.",
                         "Beende ('fertig') oder verwirf zuerst die laufende Vorführung.")
RUNNING_ACTION = Text("→ {action}", "→ {action}")
NOT_DONE_YET = Text("Not yet: {unmet}.", "Noch nicht: {unmet}.")
WHICH_STEP = Text("Which one: {steps}?", "Welchen davon: {steps}?")
TASK_LEARNED = Text("From what you showed me: {done}", "Nach dem, was du mir gezeigt hast: {done}")
TASK_DECLARED = Text("The task is finished when {goal} (my domain file says so). Show me how to get there.",
                     "Die Aufgabe ist erledigt, sobald gilt: {goal} (so steht es in meiner Domänendatei). Zeig mir, "
                     "wie ich dahin komme.")
TASK_SHOWN = Text("You show me: I learn from your steps what the task is. Say 'done' when it is finished.",
                  "Du zeigst es mir: an deinen Schritten lerne ich, was die Aufgabe ist. Sag 'fertig', wenn sie "
                  "erledigt ist.")
ONLY_YOU_TELL_DONE = Text("You tell me: say 'done' when the task is finished.",
                          "Das sagst du mir: sag 'fertig', wenn die Aufgabe erledigt ist.")
NOTHING_TO_DO = Text("There is nothing to do: the task is already finished. Say 'reset' for a new start.",
                     "Es gibt nichts zu tun: die Aufgabe ist schon erledigt. Sag 'neu' für einen neuen Start.")
STARTED_AS_SHOWN = Text("Where nothing holds, nothing can be done in this world, so I begin where {demo} begins "
                        "('start' sets up another situation).",
                        "Wo nichts gilt, lässt sich in dieser Welt nichts tun; ich beginne deshalb dort, wo {demo} "
                        "beginnt ('situation' stellt eine andere Lage her).")
NO_STEP_POSSIBLE = Text("Nothing can be done from here in this world. Set up a situation with 'start' and "
                        "what holds; 'reset' then starts anew from there.",
                        "Von hier aus lässt sich in dieser Welt nichts tun. Stell mit 'situation' und dem, was "
                        "gilt, eine Lage her; 'neu' beginnt dann von dort aus neu.")
I_DID = Text("I did: {actions}.", "Ich habe gemacht: {actions}.")
STOPPED_MIDWAY = Text("I stopped “{action}” midway", "ich habe „{action}“ mittendrin angehalten")
STEP_NOT_FINISHED = Text("{action} (not finished: {unmet})", "{action} (nicht fertig: {unmet})")
TASK_FINISHED = Text("Done! The task is finished.", "Fertig! Die Aufgabe ist erledigt.")
STOPPED = Text("Stopped. Show me how to go on from here, then say 'done'.",
               "Angehalten. Zeig mir, wie es von hier weitergeht, dann sag 'fertig'.")
THOUGHT_DONE = Text("I thought I was done, but {unmet}. Show me how to go on, then say 'done'.",
                    "Ich dachte, ich bin fertig, aber {unmet}. Zeig mir, wie es weitergeht, dann sag 'fertig'.")
STUCK = Text("I got stuck ({outcome}). Show me how to go on, then say 'done'.",
             "Ich komme nicht weiter ({outcome}). Zeig mir, wie es weitergeht, dann sag 'fertig'.")
TRIED_FAILED = Text("I tried to {action}, but it did not work: {reason}.",
                    "Ich habe „{action}“ versucht, aber es ging nicht: {reason}.")
TRIED_FAILED_TIMES = Text("I tried to {action} {times} times, but it did not work: {reason}.",
                          "Ich habe „{action}“ {times}-mal versucht, aber es ging nicht: {reason}.")
STOPPED_DURING = Text("Stopped (the last thing I began was “{action}”). Show me how to go on from here, then say "
                      "'done'.",
                      "Angehalten (zuletzt hatte ich „{action}“ begonnen). Zeig mir, wie es von hier weitergeht, "
                      "dann sag 'fertig'.")
STUCK_AFTER_TRYING = Text("I got stuck. Show me how to go on, then say 'done'.",
                          "Ich komme nicht weiter. Zeig mir, wie es weitergeht, dann sag 'fertig'.")
NOT_RUNNING = Text("The robot is not running.", "Der Roboter läuft gerade nicht.")
WAIT_OR_CTRL_C = Text("! I am running: wait until I finish, or press Ctrl-C to stop me (“{line}” is not kept).",
                      "! Ich laufe gerade: warte, bis ich fertig bin, oder drück Strg-C, um mich anzuhalten "
                      "(„{line}“ wird nicht aufgehoben).")
ROBOT_RUNNING = Text("robot running, Ctrl-C interrupts ...", "Roboter läuft, Strg-C hält ihn an ...")
WHOLE_NUMBER = Text("expected a whole number, not {text!r}", "erwartet eine ganze Zahl, nicht {text!r}")
NOT_NEGATIVE = Text("the number cannot be negative", "die Zahl darf nicht negativ sein")

# --- trees and learning ------------------------------------------------------------------------
NO_TREE = Text("I have not learned anything yet: show me the task step by step, then say 'done'.",
               "Ich habe noch nichts gelernt: zeig mir die Aufgabe Schritt für Schritt, dann sag 'fertig'.")
WHY_WHAT = Text("Why what? Name a step or a condition of the tree, e.g. 'why {example}'.",
               "Warum was? Nenn einen Schritt oder eine Bedingung des Baums, z. B. 'warum {example}'.")
NO_SUCH_NODE = Text("No action or condition named {name!r} in the tree.",
                    "Keine Handlung oder Bedingung namens {name!r} im Baum.")
GOAL_ONLY = Text("I have seen the finished task, but no steps yet.",
                 "Ich habe die erledigte Aufgabe gesehen, aber noch keine Schritte.")
GENERATION = Text("Generation {generation}: {nodes} nodes ({unpruned} before pruning), saved as {path}. "
                  "I reproduce {reproduced} of {total} demonstrations.",
                  "Generation {generation}: {nodes} Knoten ({unpruned} vor dem Beschneiden), gespeichert als {path}. "
                  "Ich kann {reproduced} von {total} Vorführungen nachmachen.")
GENERATION_PLAIN = Text("Generation {generation} saved: I can do {reproduced} of your {total} demonstrations just "
                        "as you showed them.",
                        "Generation {generation} gespeichert: ich kann {reproduced} von deinen {total} Vorführungen so "
                        "nachmachen, wie du sie gezeigt hast.")
GENERATION_PLAIN_ALL = Text("Generation {generation} saved: I can do all {total} of your demonstrations just as you "
                            "showed them.",
                            "Generation {generation} gespeichert: ich kann alle {total} Vorführungen so nachmachen, "
                            "wie du sie gezeigt hast.")
GENERATION_PLAIN_BOTH = Text("Generation {generation} saved: I can do both of your demonstrations just as you showed "
                             "them.",
                             "Generation {generation} gespeichert: ich kann beide Vorführungen so nachmachen, wie du "
                             "sie gezeigt hast.")
GENERATION_PLAIN_THE_ONE = Text("Generation {generation} saved: I can do your demonstration just as you showed it.",
                                "Generation {generation} gespeichert: ich kann deine Vorführung so nachmachen, wie du "
                                "sie gezeigt hast.")
GENERATION_PLAIN_NOT_THE_ONE = Text("Generation {generation} saved: I cannot yet do your demonstration just as you "
                                    "showed it.",
                                    "Generation {generation} gespeichert: deine Vorführung kann ich noch nicht so "
                                    "nachmachen, wie du sie gezeigt hast.")
LEARNED_STEPS = Text("I learned the steps {steps}", "ich habe die Schritte {steps} gelernt")
LEARNED_STEP = Text("I learned the step {steps}", "ich habe den Schritt {steps} gelernt")
ALSO_WHEN = Text("now I will {action} also when {when}", "jetzt mache ich „{action}“ auch, wenn gilt: {when}")
NOT_WHEN = Text("I will not {action} when {when}", "ich mache „{action}“ nicht, wenn gilt: {when}")
ANYWAY = Text("That is what I would have done anyway.", "Das hätte ich sowieso getan.")
CHANGED = Text("I changed what I do in some situations", "ich mache jetzt in manchen Lagen etwas anderes")
NOW_MAY_TOO = Text("now I may also {action} when {conditions}",
                   "jetzt darf ich „{action}“ auch tun, wenn gilt: {conditions}")
NOW_DONE_TOO = Text("now the task is done also when {conditions}",
                    "jetzt ist die Aufgabe auch erledigt, wenn gilt: {conditions}")
NOW_THERE = Text("now I {action} there", "jetzt mache ich dort „{action}“")
NOW_DONE_THERE = Text("now I know the task is done there", "jetzt weiß ich: dort ist die Aufgabe erledigt")
CONFLICT_NOTED = Text("in one situation you have shown me two different things; for now I do the last one, "
                      "and I will ask you which is right",
                      "in einer Lage hast du mir zwei verschiedene Dinge gezeigt; vorerst mache ich das letzte, "
                      "und ich frage dich, was richtig ist")
CONFLICT_QUESTION = Text("Here you have shown me two different things ({shown}). If {situation}, what should I do?",
                         "Hier hast du mir zwei verschiedene Dinge gezeigt ({shown}). Angenommen, {situation}. "
                         "Was soll ich dann tun?")
# why a node is in the tree, from the learner's explanation
WHY_GOAL = Text("“{condition}” is part of the task: it held at the end of every demonstration, "
                "and you kept going while it did not ({sources})",
                "„{condition}“ gehört zur Aufgabe: es galt am Ende jeder Vorführung, und du hast "
                "weitergemacht, solange es nicht galt ({sources})")
SOURCE_DEMO = Text("demonstration {number}", "Vorführung {number}")
SOURCE_DEMO_STEP = Text("demonstration {number}, step {step}", "Vorführung {number}, Schritt {step}")
SOURCE_ANSWER = Text("your answer to question {number}", "deine Antwort auf Frage {number}")
WHY_PRE = Text("I {action} only when {condition}: that held every time you showed it ({sources})",
               "Ich mache „{action}“ nur, wenn gilt: {condition}; das galt jedes Mal, als du es gezeigt hast "
               "({sources})")
WHY_EFFECT = Text("I {action} to make “{condition}” true: doing it made that true when it was shown or named "
                  "({sources})",
                  "Ich mache „{action}“, damit gilt: {condition}; das hat es bewirkt, als es gezeigt oder genannt "
                  "wurde ({sources})")
WHY_LAST_RESORT = Text("if nothing else works, I still try to {action} to make “{condition}” true",
                       "wenn nichts anderes geht, versuche ich trotzdem „{action}“, damit gilt: {condition}")
WHY_EXCEPTION = Text("in one situation you showed me something else, so there I {action} ({sources})",
                     "in einer Lage hast du mir etwas anderes gezeigt, deshalb mache ich dort „{action}“ ({sources})")
WHY_DONE_HERE = Text("the task is done", "die Aufgabe ist erledigt")
WHY_CONTRADICTION = Text("in the same situation you once showed one thing and once another.",
                         "in derselben Lage hast du einmal das eine und einmal etwas anderes gezeigt.")
WHY_REPEATED = Text("it does the same step twice; I can only learn each step once in a task.",
                    "darin kommt ein Schritt zweimal vor; ich kann jeden Schritt nur einmal lernen.")
WHY_ORDER = Text("it does the steps in another order than before.",
                 "darin kommen die Schritte in einer anderen Reihenfolge vor als vorher.")

# --- questions ---------------------------------------------------------------------------------
ANSWER_FIRST = Text("Please answer my question first (an action, 'done' or 'skip').",
                    "Bitte beantworte zuerst meine Frage (eine Handlung, 'fertig' oder 'weiter').")
DONE_WORD = Text("done", "fertig")
YES_WORD = Text("yes", "ja")
SKIP_WORD = Text("skip", "weiter")
ANSWER_ONE_OF = Text("Please answer with one of: {options} (or 'that cannot happen').",
                     "Bitte antworte mit einem von: {options} (oder 'das gibt es nicht').")
NOT_SURE = Text("Not sure? Then say 'skip': I will not do anything there on a guess. Or tell me what to do there.",
                "Nicht sicher? Dann sag 'weiter': Dort tue ich nichts auf Verdacht. Oder sag mir, was ich dort tun "
                "soll.")
IS_THAT_A_YES = Text("Is that a yes? Say 'yes' if I may, or 'skip' if you are not sure.",
                     "Ist das ein Ja? Sag 'ja', wenn ich darf, oder 'weiter', wenn du nicht sicher bist.")
WHY_I_ASK = Text("I was never shown this situation, and I do nothing on a guess: your answer tells me what to do "
                 "there (and where it is like this). Not sure? Say 'skip'.",
                 "Diese Lage wurde mir nie gezeigt, und ich tue nichts auf Verdacht: Deine Antwort sagt mir, was "
                 "ich dort tun soll (und wo es genauso ist). Nicht sicher? Sag 'weiter'.")
KEEP_CAREFUL = Text("All right, I keep being careful there.", "In Ordnung, da bleibe ich vorsichtig.")
ONE_ACTION = Text("Please answer with one action, 'done' or 'skip'.",
                  "Bitte antworte mit einer Handlung, 'fertig' oder 'weiter'.")
CONTRADICTS = Text("That contradicts what you showed me: {why}", "Das widerspricht dem Gezeigten: {why}")
THANKS = Text("Thank you. {change}", "Danke. {change}")
NO_TO_WHAT = Text("No question is open. If my last step was wrong, say 'undo' (or 'that was wrong').",
                  "Es ist keine Frage offen. War mein letzter Schritt falsch, sag 'zurück' (oder 'das war falsch').")
STATED_HOLDS = Text("Yes, I know: {condition}.", "Ja, ich weiß: {condition}.")
STATED_UNTRUE = Text("That is not what I see: {condition}.", "Das sehe ich anders: {condition}.")
STATED_WHAT_HAPPENED = Text(" If something happened, say what: {events}.",
                            " Wenn etwas passiert ist, sag was: {events}.")
PRAISED = Text("Thank you!", "Danke!")
HELLO_AGAIN = Text("Hello!", "Hallo!")
TAKE_YOUR_TIME = Text("Take your time.", "Lass dir Zeit.")
TAKE_YOUR_TIME_ASKED = Text("Take your time: my question is still open ('skip' leaves it).",
                            "Lass dir Zeit: meine Frage ist noch offen ('weiter' lässt sie offen).")
ALL_RIGHT = Text("All right.", "In Ordnung.")
GO_ON = Text("Tell me the next step, or say 'done' when the task is finished.",
             "Sag mir den nächsten Schritt, oder 'fertig', wenn die Aufgabe erledigt ist.")
AGAIN_WHAT = Text("Do what again? Name the step ('{example}').", "Was nochmal? Sag mir den Schritt ('{example}').")
DID_AS_ASKED = Text("I did “{action}” because you asked me to. Not what you meant? Say 'undo'.",
                   "Ich habe „{action}“ gemacht, weil du mich darum gebeten hast. Nicht gemeint? Sag 'zurück'.")
DID_AS_LEARNED = Text("I did “{action}” because of what I have learned:",
                     "Ich habe „{action}“ gemacht, weil ich gelernt habe:")
NO_STEP_JUST_NOW = Text("I did no step just now.", "Ich habe gerade keinen Schritt gemacht.")
WHY_A_STEP = Text(" 'why {example}' says why I would do a step.",
                  " 'warum {example}' sagt, warum ich einen Schritt tun würde.")
NO_QUESTION_OPEN = Text("No question is open.", "Es ist keine Frage offen.")
ALL_QUESTIONS_USED = Text("I have used all my questions.", "Ich habe alle meine Fragen gestellt.")
NO_QUESTION_NOW = Text("I have no question right now.", "Ich habe gerade keine Frage.")

# --- action definitions ------------------------------------------------------------------------
WHICH_FILE = Text("Which file? model FILE.toml", "Welche Datei? model DATEI.toml")
MODEL_MISMATCH = Text("its conditions and actions must be those of {domain}",
                      "ihre Bedingungen und Handlungen müssen die von {domain} sein")
NO_DEFINITIONS = Text("No action definitions yet: load them with 'model FILE'.",
                      "Noch keine Handlungsbeschreibungen: lade sie mit 'model DATEI'.")
CAN_BUILD = Text("I can build a behaviour from these definitions.",
                 "Aus diesen Beschreibungen kann ich ein Verhalten bauen.")
CANNOT_BUILD = Text("I cannot build a behaviour from these definitions yet: {reason}",
                    "Aus diesen Beschreibungen kann ich noch kein Verhalten bauen: {reason}")
NOTHING_TO_ASK = Text("I do not know what else to ask.", "Ich weiß nicht, was ich noch fragen soll.")
ASK_ANOTHER = Text("All right. Say 'ask' for another question.", "In Ordnung. Sag 'frag' für eine andere Frage.")

# --- saving and leaving ------------------------------------------------------------------------
SAVED = Text("Saved: {places}.", "Gespeichert: {places}.")
GOODBYE = Text("Goodbye! Resume with: teach session --resume {resume}",
               "Auf Wiedersehen! Weiter mit: teach session --resume {resume}")

# --- the terminal ------------------------------------------------------------------------------
PROMPT = Text("teach> ", "teach> ")
ANSWER_PROMPT = Text("answer> ", "Antwort> ")
TREE_TITLE = Text("learned tree", "gelernter Baum")
SAY_PREFIX = Text("robot: ", "Roboter: ")
QUESTION_PREFIX = Text("robot asks: ", "Roboter fragt: ")
ERROR_PREFIX = Text("! ", "! ")
STATE_PREFIX = Text("  state: ", "  Zustand: ")
TOOLBAR = Text(" {mode} │ true: {holds} │ questions left: {left} │ generation {generation} │ Ctrl-D: quit",
               " {mode} │ wahr: {holds} │ Fragen übrig: {left} │ Generation {generation} │ Strg-D: Ende")
MODE_IDLE = Text("idle", "bereit")
MODE_DEMONSTRATING = Text("demonstrating", "Vorführung")
MODE_ASKING = Text("asking", "Frage offen")

# --- situation questions (teach/dialogue/questions.py) -----------------------------------------
MUST_ACTION_QUESTION = Text("So far, every time I did “{action}”, this was true: {held}. If {situation}, may I still "
                            "do it? (yes, or tell me what to do there)",
                            "Bisher galt jedes Mal, wenn ich „{action}“ getan habe: {held}. Angenommen, {situation}. "
                            "Darf ich es dann trotzdem tun? (ja, oder sag mir, was ich dort tun soll)")
MUST_KIN_QUESTION = Text("I have not done “{action}” yet, but every time I did a step like it (“{like}”), the same "
                         "held for its things; for “{action}” that is: {held}. If {situation}, may I do it? (yes, or "
                         "tell me what to do there)",
                         "„{action}“ habe ich noch nie getan, aber jedes Mal, wenn ich einen Schritt wie diesen getan "
                         "habe („{like}“), galt dasselbe für seine Dinge; für „{action}“ heißt das: {held}. "
                         "Angenommen, {situation}. Darf ich es dann tun? (ja, oder sag mir, was ich dort tun soll)")
MUST_GOAL_QUESTION = Text("So far, every time the task was done, this was true: {held}. If {situation}, is the task "
                          "done? (yes, or tell me what to do there)",
                          "Bisher galt jedes Mal, wenn die Aufgabe erledigt war: {held}. Angenommen, {situation}. "
                          "Ist die Aufgabe dann erledigt? (ja, oder sag mir, was ich dort tun soll)")
RUN_AGAIN = Text("I try again from here (the steps of the last run are not kept as a demonstration; "
                 "whatever you answered is learned already).",
                 "Ich versuche es von hier aus noch einmal (die Schritte des letzten Laufs werden keine "
                 "Vorführung; was du geantwortet hast, ist schon gelernt).")
WHAT_INSTEAD = Text("Then what should I do there instead?", "Was soll ich dort dann stattdessen tun?")
NO_TAKEN = Text("I take that as a no (I don't know “{rest}”).", "Ich verstehe das als Nein („{rest}“ kenne ich nicht).")
QUESTION_AGAIN = Text("My question again ('why do you ask?' says why I ask, 'skip' leaves it):",
                      "Noch einmal meine Frage ('warum fragst du?' sagt, warum ich frage, 'weiter' lässt sie offen):")
CANNOT_HAPPEN_THEN = Text("Can that situation not happen at all? Then say 'that cannot happen' (I will not ask "
                          "about it again). Otherwise answer, or say 'skip'.",
                          "Kann es diese Lage gar nicht geben? Dann sag 'das gibt es nicht' (dann frage ich nicht mehr "
                          "danach). Sonst antworte, oder sag 'weiter'.")
CANNOT_HAPPEN = Text("Thank you: I will not ask about that situation again, and it cost no question.",
                     "Danke: Nach dieser Lage frage ich nicht mehr, und die Frage zählt nicht.")
SITUATION_QUESTION = Text("If {situation}, what should I do?", "Angenommen, {situation}. Was soll ich dann tun?")
BUT = Text(" but ", " aber ")
TRUE_AND_UNTRUE = Text("'{label}' cannot be both true and untrue: name it once.",
                       "„{label}“ kann nicht zugleich gelten und nicht gelten: nenne es nur einmal.")
NOTHING_ELSE = Text(", and nothing else", ", sonst nichts")
NOTHING_ELSE_BUT_MAYBE = Text(", and nothing else but maybe {conditions}",
                              ", sonst nichts, außer vielleicht {conditions}")
NONE_OF = Text("none of: {conditions}", "keine von: {conditions}")
NOTHING_HOLDS = Text("none of the {count} conditions holds", "keine der {count} Bedingungen gilt")

# --- questions about the action definitions (teach/dialogue/model_repair.py) -------------------
QUOTED = Text("“{text}”", "„{text}“")
ASK_TIMING = Text("When I {act}: must {cond} already hold before I start, or does it only hold afterwards? "
                  "(before / after / both / neither)",
                  "Bei {act}: muss {cond} schon vorher gelten, oder gilt es erst danach? "
                  "(vorher / nachher / beides / keins)")
ASK_EFFECTS = Text("What is different after I {act}? (what is true then, or “nothing”)",
                   "Was ist anders nach {act}? (was dann gilt, oder „nichts“)")
ASK_ACHIEVER = Text("What should I do so that {cond}? (an action, or “nothing”)",
                    "Was soll ich tun, damit gilt: {cond}? (eine Handlung, oder „nichts“)")
ASK_ORDER = Text("What should I do first: {act} or {other}? (one of them, or “either”)",
                 "Was soll ich zuerst tun: {act} oder {other}? (eins davon, oder „egal“)")
ASK_NEVER = Text("Can I {act} while {opposite}? (yes / no)", "Kann ich {act}, wenn {opposite}? (ja / nein)")
SO_MAKES_TRUE_NOT_BEFORE = Text("So {act} makes {cond} true; it need not hold before.",
                                "Also macht {act} {cond} wahr; es muss vorher nicht gelten.")
SO_UNRELATED = Text("So {cond} has nothing to do with {act}.", "Also hat {cond} nichts mit {act} zu tun.")
SO_BEFORE_AND_STAYS = Text("So {cond} must hold before {act} and stays true; {act} does not make it true.",
                           "Also muss {cond} vor {act} gelten und bleibt so; {act} macht es nicht wahr.")
SO_BEFORE = Text("So {cond} must hold before {act}; {act} does not make it true.",
                 "Also muss {cond} vor {act} gelten; {act} macht es nicht wahr.")
SO_CHANGES_NOTHING = Text("So {act} changes nothing.", "Also ändert {act} nichts.")
SO_AFTER = Text("So after {act}: {made}.", "Also gilt nach {act}: {made}.")
NEED_NOT_HOLD_BEFORE = Text(" It need not hold before: {conds}.", " Vorher muss nicht gelten: {conds}.")
SO_NOTHING_MAKES = Text("So nothing makes {cond} true.", "Also macht nichts {cond} wahr.")
SO_MAKES_TRUE = Text("So {act} makes {cond} true.", "Also macht {act} {cond} wahr.")
IT_NEED_NOT_HOLD_BEFORE = Text(" It need not hold before.", " Es muss vorher nicht gelten.")
CHANGES_NOTHING_KNOWN = Text("That does not change what I know.", "Das ändert nichts an dem, was ich weiß.")
DOES_NOT_NEED = Text("{act} does not need {cond}", "{act} braucht nicht {cond}")
SO_LIST = Text("So {parts}.", "Also: {parts}.")
SO_CANNOT_BE_DONE = Text("So {act} really needs {cond}, and nothing makes it true: the task cannot be done.",
                         "Also braucht {act} wirklich {cond}, und nichts macht es wahr: die Aufgabe geht so nicht.")
SO_DOES_NOT_NEED = Text("So {act} does not need {cond}.", "Also braucht {act} nicht {cond}.")
WORD_BEFORE = Text("before", "vorher")
WORD_AFTER = Text("after", "nachher")
WORD_BOTH = Text("both", "beides")
WORD_NEITHER = Text("neither", "keins")
WORD_NOTHING = Text("nothing", "nichts")
WORD_YES = Text("yes", "ja")
WORD_NO = Text("no", "nein")
WORD_EITHER = Text("either", "egal")

# --- the careless teacher (issue 11) ----------------------------------------------------------------
SAY_IT_ANOTHER_WAY = Text("Say it another way, please.", "Sag es bitte anders.")
OPEN_STEPS = Text("The steps so far:", "Die Schritte bisher:")
NO_OPEN_STEPS = Text("No demonstration is open: there are no steps yet.",
                     "Keine Vorführung ist offen: es gibt noch keine Schritte.")
EVENT_STEP = Text("something happened: {event}", "etwas ist passiert: {event}")
ROBOT_DID_STEP = Text("{action} (the robot did it)", "{action} (hat der Roboter gemacht)")
UNDONE_ONE_STEP = Text("Undone: step {last} ({steps}).", "Rückgängig: Schritt {last} ({steps}).")
UNDONE_STEPS = Text("Undone: steps {first} to {last} ({steps}).", "Rückgängig: Schritte {first} bis {last} ({steps}).")
NO_SUCH_STEP = Text("There is no step {number}: the steps so far are 1 to {count}.",
                    "Es gibt keinen Schritt {number}: die Schritte bisher sind 1 bis {count}.")
NO_STEPS_TO_UNDO = Text("No demonstration is open, so there are no steps to take back.",
                        "Keine Vorführung ist offen, also gibt es keine Schritte zurückzunehmen.")
I_DID_NOTHING = Text("I did nothing.", "Ich habe nichts gemacht.")
NOTHING_TO_CANCEL = Text("No demonstration is open: there is nothing to cancel.",
                         "Keine Vorführung ist offen: es gibt nichts abzubrechen.")
SESSION_ID = Text("Session {session} (continue it later with: teach session --resume {resume}).",
                  "Sitzung {session} (später weitermachen mit: teach session --resume {resume}).")
IT_NEEDS = Text("first this must be true: {conditions}", "dafür muss erst gelten: {conditions}")
IT_DID_NOT_WORK = Text("it did not work out this time", "es hat diesmal nicht geklappt")
OUTCOME_SUCCESS = Text("it said it was done", "es hieß, ich sei fertig")
OUTCOME_FAILURE = Text("nothing I know fits here", "hier passt nichts, was ich kann")
OUTCOME_TIMEOUT = Text("I kept going round in circles", "ich habe mich im Kreis gedreht")
OUTCOME_INTERRUPTED = Text("I was stopped", "ich wurde angehalten")
RESUMED_COUNTED = Text("Resumed session {session}: {demos}, {asked}, generation {generation}.",
                       "Sitzung {session} fortgesetzt: {demos}, {asked}, Generation {generation}.")
NO_DEMOS = Text("no demonstrations", "keine Vorführungen")
ONE_DEMO = Text("{count} demonstration", "{count} Vorführung")
DEMOS = Text("{count} demonstrations", "{count} Vorführungen")
NO_QUESTIONS_ASKED = Text("no questions asked", "keine Fragen gestellt")
ONE_QUESTION_ASKED = Text("{count} question asked", "{count} Frage gestellt")
QUESTIONS_ASKED = Text("{count} questions asked", "{count} Fragen gestellt")
TOOLBAR_PLAIN = Text(" {mode} │ questions left: {left} │ generation {generation} │ Ctrl-D: quit",
                     " {mode} │ Fragen übrig: {left} │ Generation {generation} │ Strg-D: Ende")

OPEN_ON_QUIT = Text("You have shown me {steps} I have not learned yet: say 'done' to learn them, 'cancel' to "
                    "drop them, or quit again: they stay open, and --resume brings them back.",
                    "Du hast mir {steps} gezeigt, die ich noch nicht gelernt habe: sag 'fertig', um sie zu "
                    "lernen, 'abbrechen', um sie zu verwerfen, oder beende noch einmal: sie bleiben offen, und "
                    "--resume bringt sie zurück.")
OPEN_ON_QUIT_ONE = Text("You have shown me 1 step I have not learned yet: say 'done' to learn it, 'cancel' to drop "
                        "it, or quit again: it stays open, and --resume brings it back.",
                        "Du hast mir 1 Schritt gezeigt, den ich noch nicht gelernt habe: sag 'fertig', um ihn zu "
                        "lernen, 'abbrechen', um ihn zu verwerfen, oder beende noch einmal: er bleibt offen, und "
                        "--resume bringt ihn zurück.")
STEP_COUNT = Text("{count} step", "{count} Schritt")
STEPS_COUNT = Text("{count} steps", "{count} Schritte")

ASKED_BEFORE_YOU_LEFT = Text("Before the session ended I had asked you this (it costs no second question):",
                             "Bevor die Sitzung endete, hatte ich dich das gefragt (es kostet keine zweite Frage):")
OPEN_RESTORED = Text("The demonstration you had started is still open ({steps}): 'steps' lists them, "
                     "'done' learns it, 'cancel' drops it.",
                     "Die Vorführung, die du angefangen hattest, ist noch offen ({steps}): 'schritte' "
                     "zeigt sie, 'fertig' lernt sie, 'abbrechen' verwirft sie.")

# --- durability (issue 14)
ORPHAN_SET_ASIDE = Text("{file} was written just before the session stopped but never learned; moved to {folder}",
                        "{file} wurde kurz vor dem Ende der Sitzung geschrieben, aber nie gelernt; verschoben nach "
                        "{folder}")
REPLAY_NEEDS_OVERWRITE = Text("session {session!r} exists already and was not made by replaying {dialogue}: "
                              "add --overwrite to replace it, or choose another name with --session",
                              "Sitzung {session!r} gibt es schon, und sie stammt nicht aus {dialogue}: "
                              "--overwrite ersetzt sie, oder wähle mit --session einen anderen Namen")
STDIN_IS_A_FILE = Text("standard input is a file, not a terminal: replay it with `teach replay FILE`",
                       "die Standardeingabe ist eine Datei, kein Terminal: spiele sie mit `teach replay DATEI` ab")
UNKNOWN_JOURNAL_ACTION = Text("events[{number}]: answer: {action!r} is not an action of the domain",
                              "events[{number}]: answer: {action!r} ist keine Aktion der Domäne")
SYMBOLIC_INSTEAD = Text("the MuJoCo world cannot tell whether “{condition}”: this session uses the symbolic world "
                        "(--world symbolic)",
                        "die MuJoCo-Welt kann nicht erkennen, ob „{condition}“: diese Sitzung nutzt die symbolische "
                        "Welt (--world symbolic)")
# --- guiding the robot in a session (issue 12, the guide helper)
GUIDING_NEEDS_MUJOCO = Text("Guiding moves the robot's body: it needs the MuJoCo world (start the session with "
                            "--world mujoco).",
                            "Führen bewegt den Körper des Roboters: dafür braucht es die MuJoCo-Welt (starte die "
                            "Sitzung mit --world mujoco).")
GUIDED_STEP = Text("✓ You moved me so that now {change}: that was “{action}”.",
                   "✓ Du hast mich so bewegt, dass jetzt gilt: {change}. Das war „{action}“.")
GUIDED_WORDS = Text("{action} (guided)", "{action} (geführt)")
LABEL_OPTIONS = Text("(name an action, 'yes', 'something new: NAME' or 'skip' · labelling question {used} of {total})",
                     "(nenne eine Aktion, 'ja', 'etwas Neues: NAME' oder 'weiter' · Benennfrage {used} von {total})")
LABEL_THANKS = Text("✓ Thank you: that was “{action}”.", "✓ Danke: das war „{action}“.")
LABEL_WHICH = Text("Then which action was it? Name it, or say 'something new: NAME'.",
                   "Welche Aktion war es dann? Nenne sie, oder sag 'etwas Neues: NAME'.")
LABEL_ONE_ACTION = Text("Please name one action I know, or say 'something new: NAME' (or 'skip').",
                        "Nenne bitte eine Aktion, die ich kenne, oder sag 'etwas Neues: NAME' (oder 'weiter').")
LABEL_SKIPPED = Text("I leave that motion out of the demonstration.", "Diese Bewegung lasse ich in der Vorführung weg.")
LABEL_ASSUMED = Text("✓ You moved me so that now {change}: I take it that was “{action}” (no labelling questions "
                     "left).",
                     "✓ Du hast mich so bewegt, dass jetzt gilt: {change}. Ich nehme an, das war „{action}“ (keine "
                     "Benennfragen mehr übrig).")
LABEL_DROPPED = Text("You moved me so that now {change}, but I know no action for that and have no labelling "
                     "questions left: I leave it out.",
                     "Du hast mich so bewegt, dass jetzt gilt: {change}. Dafür kenne ich keine Aktion und habe keine "
                     "Benennfragen mehr: ich lasse es weg.")
LABEL_GUIDE_FIRST = Text("Please tell me first what your last motion was (an action, 'something new: NAME' or "
                         "'skip').",
                         "Sag mir bitte zuerst, was deine letzte Bewegung war (eine Aktion, 'etwas Neues: NAME' oder "
                         "'weiter').")
NEW_ACTION_LEARNED = Text("✓ New action “{action}”: afterwards {change}. I can do it myself from now on.",
                          "✓ Neue Aktion „{action}“: danach gilt: {change}. Das kann ich jetzt selbst.")
NEW_ACTION_TAKEN = Text("There is already an action called “{action}”: say its name alone, or choose another name.",
                        "Eine Aktion „{action}“ gibt es schon: nenne sie allein, oder wähle einen anderen Namen.")
GUIDE_WORD = Text("guide", "führen")
GUIDE_MODE_ON = Text("Guide mode: ↑/↓ move, ←/→ turn, PgUp/PgDn lift, space opens or closes the hand; Esc ends it.",
                     "Führmodus: ↑/↓ fahren, ←/→ drehen, Bild↑/Bild↓ heben, Leertaste öffnet oder schließt die "
                     "Hand; Esc beendet ihn.")
GUIDE_FEEDBACK = Text("ball {ball}, {ball_height} · bin {bin} · lift {lift} · hand {hand} · last: {last}",
                      "Ball {ball}, {ball_height} · Eimer {bin} · Hub {lift} · Hand {hand} · zuletzt: {last}")
FEEDBACK_CM = Text("{cm} cm", "{cm} cm")
FEEDBACK_M = Text("{whole}.{tenth} m", "{whole},{tenth} m")
FEEDBACK_AHEAD = Text("{distance} ahead", "{distance} geradeaus")
FEEDBACK_LEFT = Text("{distance}, {degrees}° to my left", "{distance}, {degrees}° links von mir")
FEEDBACK_RIGHT = Text("{distance}, {degrees}° to my right", "{distance}, {degrees}° rechts von mir")
FEEDBACK_BEHIND = Text("{distance} behind me", "{distance} hinter mir")
FEEDBACK_UNDER_ARM = Text("{distance} behind my hand, under my arm (↓ backs me up to it)",
                         "{distance} hinter meiner Hand, unter meinem Arm (↓ fährt mich zurück zu ihm)")
FEEDBACK_AT_HAND_HEIGHT = Text("at hand height", "auf Handhöhe")
FEEDBACK_ABOVE = Text("{distance} above my hand", "{distance} über meiner Hand")
FEEDBACK_BELOW = Text("{distance} below my hand", "{distance} unter meiner Hand")
FEEDBACK_HELD_BY_TOP = Text("{distance} below my hand, held by its top only: it will slip out (space opens my hand, "
                            "PgDn lowers it round the ball)",
                            "{distance} unter meiner Hand, nur oben gehalten: er rutscht mir heraus (Leertaste öffnet "
                            "meine Hand, Bild↓ senkt sie um den Ball)")
FEEDBACK_OPEN = Text("open", "offen")
FEEDBACK_CLOSED = Text("closed", "zu")
FEEDBACK_NOTHING_YET = Text("nothing yet", "noch nichts")
FEEDBACK_STOPPED = Text("{did}, then Ctrl-C stopped me", "{did}, dann hat Strg-C mich angehalten")
FEEDBACK_MOVED = Text("{key} moved me {distance}", "{key} hat mich {distance} bewegt")
FEEDBACK_TURNED_LEFT = Text("{key} turned me {degrees}° left", "{key} hat mich {degrees}° nach links gedreht")
FEEDBACK_TURNED_RIGHT = Text("{key} turned me {degrees}° right", "{key} hat mich {degrees}° nach rechts gedreht")
FEEDBACK_LIFTED = Text("{key} moved the lift {distance} up", "{key} hat den Hub {distance} gehoben")
FEEDBACK_ON_THE_BALL = Text("{key} stopped with my hand on the ball: move me until the ball is between my fingers",
                            "{key} hat angehalten, meine Hand sitzt auf dem Ball: fahr mich, bis der Ball zwischen "
                            "meinen Fingern ist")
FEEDBACK_LOWERED = Text("{key} moved the lift {distance} down", "{key} hat den Hub {distance} gesenkt")
FEEDBACK_OPENED = Text("{key} opened my hand", "{key} hat meine Hand geöffnet")
FEEDBACK_CLOSED_HAND = Text("{key} closed my hand", "{key} hat meine Hand geschlossen")
FEEDBACK_BLOCKED = Text("{key} did nothing (something is in the way, or it was there already)",
                        "{key} hat nichts bewirkt (etwas ist im Weg, oder es war schon so)")
FEEDBACK_WAITED = Text("{key}: I waited", "{key}: ich habe gewartet")
KEY_PAGE_UP = Text("PgUp", "Bild↑")
KEY_PAGE_DOWN = Text("PgDn", "Bild↓")
KEY_SPACE = Text("space", "Leertaste")
KEY_WAIT = Text("wait", "warten")
GUIDE_MODE_OFF = Text("Guide mode ended.", "Führmodus beendet.")
TOOLBAR_LABELS = Text(" │ labelling questions left: {left}", " │ Benennfragen übrig: {left}")
# --- slips during a skill (issue 11: the world's events)
HALTED_KEPT = Text("✓ {action} (stopped halfway: recorded up to there)",
                   "✓ {action} (mittendrin angehalten: bis dahin aufgezeichnet)")
HALTED_DROPPED = Text("✗ {action} (stopped before it changed anything: not recorded)",
                      "✗ {action} (angehalten, bevor sich etwas geändert hat: nicht aufgezeichnet)")
HALTED_STEP = Text("{action} (stopped halfway)", "{action} (mittendrin angehalten)")
REST_NOT_DONE = Text("I stopped there. Not done: {actions}.", "Ich habe dort aufgehört. Nicht gemacht: {actions}.")

ANSWER_WORDS = (WORD_BEFORE, WORD_AFTER, WORD_BOTH, WORD_NEITHER, WORD_NOTHING, WORD_YES, WORD_NO, WORD_EITHER)
"""The words that answer a question about action definitions (a dialogue may hold them as lines)."""

# --- questions that pay, the tree in plain sentences (issue 11, job "pay") ------------------------
NOT_DONE_THERE = Text("I would not be done there: {unmet}. What should I do there?",
                      "Dort wäre ich nicht fertig: {unmet}. Was soll ich dort tun?")
QUESTION_ASIDE = Text("I put my question aside (if I ask it again, it costs nothing).",
                     "Ich lege meine Frage beiseite (frage ich sie noch einmal, kostet sie nichts).")
NO_UNDO_WHILE_ASKING = Text("Nothing to undo while I wait for your answer; say 'skip' to leave the question.",
                            "Solange ich auf deine Antwort warte, gibt es nichts zurückzunehmen; "
                            "sag 'weiter', um die Frage offen zu lassen.")
TREE_WORDS_TITLE = Text("what I do", "was ich tue")
WORDS_DONE_WHEN = Text("When {condition}, I am done.", "Ich bin fertig, sobald gilt: {condition}.")
WORDS_OTHERWISE_FIRST_FIT = Text("Otherwise I do the first that fits:", "Sonst tue ich das Erste, was passt:")
WORDS_FIRST_FIT = Text("I do the first that fits:", "Ich tue das Erste, was passt:")
WORDS_OTHERWISE_NOTHING = Text("Otherwise I do nothing yet.", "Sonst tue ich noch nichts.")
WORDS_NOTHING = Text("I do nothing yet.", "Ich tue noch nichts.")
WORDS_BULLET = Text("  – {text}", "  – {text}")
WORDS_IF = Text("if {condition}, {what}", "wenn gilt: {condition}, dann: {what}")
WORDS_FIRST = Text("{what}", "{what}")
WORDS_OTHERWISE = Text("otherwise, {what}", "sonst: {what}")
WORDS_I_DO = Text("I {action}", "„{action}“")
WORDS_I_AM_DONE = Text("I am done", "ich bin fertig")
WORDS_QUOTED = Text("“{action}”", "„{action}“")
WORDS_SOME_OF = Text("I do {actions}, in a way I cannot say simply ('show full' shows how)",
                     "{actions}, auf eine Art, die ich nicht einfach sagen kann ('zeige ganz' zeigt sie)")
WORDS_NOTHING_SIMPLE = Text("I check something I cannot say simply ('show full' shows it)",
                            "ich prüfe etwas, das ich nicht einfach sagen kann ('zeige ganz' zeigt es)")
WORDS_SOME_CHECK = Text("a check I cannot say simply holds", "eine Prüfung gilt, die ich nicht einfach sagen kann")
WORDS_NOT = Text("not {condition}", "nicht {condition}")
# --- resume restores the situation and an unfinished run (issue 14, resume)
SITUATION_RESTORED = Text("I set up the last situation again:", "Ich habe die letzte Situation wieder aufgebaut:")
SITUATION_RESTORED_ANEW = Text("I set up the last situation again (the simulation placed everything anew: what holds "
                               "is the same, the exact positions are not):",
                               "Ich habe die letzte Situation wieder aufgebaut (die Simulation hat alles neu "
                               "hingestellt: was gilt, ist dasselbe, die genauen Positionen nicht):")
SITUATION_NOT_RESTORED = Text("I could not set up the last situation again ({situation}); we go on from here:",
                              "Ich konnte die letzte Situation nicht wieder aufbauen ({situation}); wir machen von "
                              "hier aus weiter:")
RUN_RESTORED = Text("The session ended while I was running ({action} had begun): what I had finished ({steps}) "
                    "is the start of a correction ('steps' lists it, 'done' learns it, 'cancel' drops it); the "
                    "world is set up as it was before {action}.",
                    "Die Sitzung endete, während ich lief ({action} hatte begonnen): was ich fertig hatte "
                    "({steps}), ist der Anfang einer Korrektur ('schritte' zeigt sie, 'fertig' lernt sie, "
                    "'abbrechen' verwirft sie); die Welt ist wieder so wie vor {action}.")
RUN_RESTORED_NO_STEPS = Text("The session ended while I was running ({action} had just begun): the world is set up "
                             "as it was before it.",
                             "Die Sitzung endete, während ich lief ({action} hatte gerade begonnen): die Welt ist "
                             "wieder so wie davor.")
# --- guiding by dragging in the MuJoCo viewer (issue 12, viewer)
HAND_NEEDS_VIEWER = Text("'guide hand' follows your drag in the MuJoCo viewer: start the session with --viewer.",
                         "'führen hand' folgt deinem Ziehen im MuJoCo-Viewer: starte die Sitzung mit --viewer.")
HAND_FOLLOWING = Text("I follow the mouse in the viewer: double-click the robot, then Ctrl + right-drag moves me and "
                      "Ctrl + left-drag turns me; drag the ball or the bin the same way. Let go when you are done.",
                      "Ich folge der Maus im Viewer: doppelklicke auf den Roboter, dann bewegt mich Strg + "
                      "Rechtsziehen und Strg + Linksziehen dreht mich; Ball und Eimer ziehst du genauso. Lass los, "
                      "wenn du fertig bist.")
HAND_THE_BALL = Text("the ball", "den Ball")
HAND_THE_BIN = Text("the bin", "den Eimer")
HAND_MOVED = Text("you moved {thing}", "du hast {thing} bewegt")
HAND_MOVED_NOTHING = Text("You moved {thing}, but nothing changed for me: not recorded.",
                          "Du hast {thing} bewegt, aber für mich hat sich nichts geändert: nicht aufgezeichnet.")
# --- voice (issue 22: the robot speaks, and listens in English)
SPOKEN_NOW = Text("now I {action}", "jetzt: {action}")
VOICE_FILES_ONLY = Text("{reason}: what I say is only written to {folder}.",
                        "{reason}: was ich sage, wird nur nach {folder} geschrieben.")
VOICE_NOT_WRITTEN = Text("What I say is no longer written to files: {error}",
                         "Was ich sage, wird nicht mehr in Dateien geschrieben: {error}")
LISTEN_ENGLISH_ONLY = Text("I listen in English only: German speech recognition is not available offline.",
                           "Ich höre nur Englisch: deutsche Spracherkennung gibt es offline nicht.")
LISTEN_NO_MICROPHONE = Text("I cannot listen: {reason}. Please type instead.",
                            "Ich kann nicht zuhören: {reason}. Bitte tippe stattdessen.")
NOTHING_HEARD = Text("nothing I know is said in {file}", "in {file} wird nichts gesagt, das ich kenne")
THE_MICROPHONE = Text("what the microphone heard", "dem, was das Mikrofon gehört hat")
HEARD_DID_YOU_MEAN = Text("Did you mean “{line}”?", "Meintest du „{line}“?")
