"""Whether a dialogue file is a dialogue: every input line a command, something the robot can
do or the world can undergo, or an answer word, read as the session reads it (its command words,
its guide lines, its answers). It lives beside the session, since the session's words decide."""

from __future__ import annotations

from teach import messages as m
from teach.dialogue.phrases import PhraseBook, command_hint, is_no, is_yes, normalize
from teach.dialogue.script import Script
from teach.domain import Domain
from teach.errors import FormatError, TeachError
from teach.messages import Lang
from teach.session.arguments import stated_condition
from teach.session.commands import (
    ANSWER_SAYINGS,
    COMMAND_NAMES,
    WHERE_STARTS,
    Verb,
    after_courtesy,
    after_holding_on,
    is_greeting,
    is_holding_on,
    is_praise,
    parse_command,
    without_hesitation,
)
from teach.session.guiding import STOP_WORDS, is_new_action_answer


def check_lines(script: Script, domain: Domain, phrases: PhraseBook, language: str) -> None:
    """Refuse a file that is not a dialogue (XML, a README, a CSV): every input line must be a
    command, something the robot can do or the world can undergo, or an answer word; the
    first line that is none of these is named with its number."""
    lang = Lang.parse(language)
    answers = ANSWER_SAYINGS | {normalize(word(each)) for word in m.ANSWER_WORDS for each in Lang}
    topic: str | None = None  # "it" names what the line before named, as in the session
    for number, said in script.lines:
        if is_praise(said) or is_greeting(said) or is_holding_on(said) or normalize(said).startswith(WHERE_STARTS) \
                or stated_condition(domain, said) is not None:  # "well done", "hmm", "the bin is within reach"
            continue
        found = False
        for line in dict.fromkeys((after_courtesy(said), after_courtesy(after_holding_on(said)))):
            # "good, now go to the ball"; "wait, no" (but snacks' "wait until someone asks" as it is)
            found, topic = _reads(line, phrases, lang, answers, topic, script, number)
            if found:
                break
        if not found:
            shown = repr(said) if len(said) <= 40 else repr(said[:37]) + "..."
            raise FormatError(f"{shown} is neither a command nor something the robot can do or the world can undergo "
                              "(is this a dialogue? --lenient types such lines anyway)", script.path, number)


def _reads(line: str, phrases: PhraseBook, lang: Lang, answers: set[str], topic: str | None, script: Script,
           number: int) -> tuple[bool, str | None]:
    """Whether the session reads ``line`` as a command, an answer or steps (and the topic after it)."""
    command, rest = parse_command(command_hint(line, lang, COMMAND_NAMES) or line)  # "ok done", as the session
    if command is Verb.GUIDE and rest.strip() and normalize(rest) not in STOP_WORDS:
        from teach.sim.guide import parse_guide_line

        parse_guide_line(f"guide {rest}", script.path, number)  # a bad amount names its line
    if command is not None or is_new_action_answer(line) or without_hesitation(normalize(line)) in answers \
            or is_yes(line, lang) or is_no(line, lang):
        return True, topic
    return _names_actions_or_events(line, phrases, lang, topic)


def _names_actions_or_events(line: str, phrases: PhraseBook, lang: Lang, topic: str | None) -> tuple[bool, str | None]:
    for perturb in (False, True):
        try:
            tokens = phrases.parse(line, lang, perturb=perturb, topic=topic)
        except TeachError:
            continue
        return True, phrases.topic(tokens) or topic
    return False, topic
