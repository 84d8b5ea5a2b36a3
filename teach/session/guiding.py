"""Guiding in a session: the teacher moves the robot's body and the session finds the steps.

A ``guide …`` line (``führen …``) drives the MuJoCo robot by one primitive (``teach.sim.guide``)
inside the open demonstration, the one named steps go to. While the teacher guides, the
segmenter cuts the motion where the symbolic state changes; every finished segment is
recognised (``teach.learn.recognise``): one clear fit becomes that action's step at once, and
anything else waits for the teacher's word in a labelling question. Labelling questions have
their own cap (``Settings.label_questions``), apart from the precondition questions' budget.

Guidance ends with the first line that is not a guiding one: a change still inside its hold
time then counts (the robot ends in it), and what is still unlabelled is asked about before
that line is carried out (it is carried out once the last question is answered).

An answer names a known action, says yes to the one proposed, says "something new: push the
ball" (``etwas Neues: den Ball schieben``), which adds a new action to the session's own domain
copy with the segment's change as its effect and the segment's motion as its skill, or skips.
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Protocol, runtime_checkable

from teach import messages as m
from teach.dialogue.phrases import is_no, is_yes, normalize
from teach.dialogue.questions import QuestionBudget
from teach.domain import Domain
from teach.errors import FormatError, TeachError
from teach.learn.recognise import Recognition, changed_literals, describe_change, explain, question, recognise
from teach.session.commands import SKIP_WORDS
from teach.session.journal import GuidedActionTaught
from teach.session.record import SessionRecord
from teach.session.replies import Reply, ReplyKind
from teach.session.showing import Showing
from teach.session.turn import Turn

if TYPE_CHECKING:
    from teach.session.hand import HandFollower
    from teach.sim.guide import Guide, Sample
    from teach.sim.guided_skill import GuidedMotion
    from teach.sim.segment import Segment, Segmenter


@runtime_checkable
class GuidableWorld(Protocol):
    """A world whose robot a teacher can guide (the MuJoCo world)."""

    def start_guiding(self, listener: Callable[[Sample], object]) -> Guide: ...

    def learn_skill(self, motion: GuidedMotion) -> None: ...

    def adopt_domain(self, domain: Domain) -> None: ...


@dataclass(frozen=True)
class _Due:
    """A guided action waiting for its label: its (joined) segment, what was recognised, and
    how many of the segmenter's segments it spans."""

    segment: Segment
    recognition: Recognition
    spans: int


class Guiding:
    """The guiding side of one session: the guide, its segments, and the labelling questions.

    It adds its steps to the open demonstration (``showing``), speaks through the turn, journals
    and writes a new action through the session record, and hands a grown domain to ``adopted``
    (the machine learns again in it)."""

    def __init__(self, showing: Showing, record: SessionRecord, turn: Turn, label_questions: int,
                 adopted: Callable[[Domain], None]):
        self.showing, self.record, self.turn = showing, record, turn
        self.world = showing.world
        self.vocabulary = showing.vocabulary
        self.lang = showing.lang
        self.adopted = adopted
        self.budget = QuestionBudget(label_questions)
        self.guide: Guide | None = None
        self.segmenter: Segmenter | None = None
        self.labelled = 0          # segments of the segmenter already turned into steps (or left out)
        self.pending: _Due | None = None  # the labelling question open now
        self.deferred: str | None = None  # the line that ended guidance, carried out after the answers
        self.used = False          # guiding happened in this session (the toolbar then shows both budgets)
        self.hand: HandFollower | None = None  # following the teacher's hand in the viewer (``guide hand``)

    @property
    def domain(self) -> Domain:
        return self.vocabulary.domain

    @property
    def active(self) -> bool:
        return self.guide is not None

    # --- guiding ---------------------------------------------------------------------------

    def can_guide(self) -> bool:
        return isinstance(self.world, GuidableWorld)

    def refusal(self) -> list[Reply]:
        return [Reply(ReplyKind.ERROR, m.GUIDING_NEEDS_MUJOCO(self.lang))]

    def begin(self) -> list[Reply]:
        """Start guiding (if not yet): the open demonstration is opened if need be."""
        from teach.sim.segment import Segmenter

        world = self.world
        assert isinstance(world, GuidableWorld)
        replies = self.showing.begin()
        if self.guide is None:
            self.segmenter, self.labelled = Segmenter(), 0
            self.guide = world.start_guiding(self._feed)
            self.used = True
        return replies

    def command(self, rest: str, interrupted: Callable[[], bool] | None = None) -> list[Reply]:
        """``guide`` alone: guiding begins (the terminal's guide mode); ``guide stop``: it ends;
        otherwise one primitive (``interrupted``: Ctrl-C, which stops it where it is)."""
        if not rest.strip():
            return self.turn.say(self.begin()) + [Reply(ReplyKind.INFO, m.GUIDE_MODE_ON(self.lang))]
        if normalize(rest) in STOP_WORDS:
            return self.end() + [Reply(ReplyKind.INFO, m.GUIDE_MODE_OFF(self.lang))]
        return self.line(rest, interrupted)

    def reads_as_move(self, line: str) -> bool:
        """While guiding, a line that begins with a move's word, without 'guide' ("forward 0.3",
        "turn -30" were "I don't know “forward 0.3”" and ended guiding); a wrong number is then
        said as the move's ("takes -5 to 5 metres")."""
        from teach.sim.guide import VERBS

        words = line.split()
        if not self.active or not words or words[0].lower() not in VERBS:
            return False
        # a word alone only where it is a whole move ("open"; "wait" alone is holding on)
        return len(words) > 1 or _whole_move(line)

    def back_line(self) -> str:
        """The move one ↓ key makes, as a line ("back 0.1"): what "step back" means while guiding."""
        from teach.sim.guide import KEY_STEP

        return f"back {KEY_STEP}"

    def offered_move(self, line: str) -> str | None:
        """Not guiding, in a world that can be guided: a line that is a whole move without 'guide'
        ("forward 0.3", "lift 0.1", "turn right 40"), as the guide line a yes would do; None
        otherwise. ("lift 0.1" was offered as "lift the ball", a grasp.)"""
        from teach.sim.guide import VERBS

        words = line.split()
        if self.active or not self.can_guide() or not words or words[0].lower() not in VERBS or not _whole_move(line):
            return None
        return f"{m.GUIDE_WORD(self.lang)} {line.strip()}"

    def line(self, rest: str, interrupted: Callable[[], bool] | None = None) -> list[Reply]:
        """One ``guide …`` line: begin guiding if need be, carry out the primitive, label what it finished."""
        from teach.sim.guide import parse_guide_line

        try:
            command = parse_guide_line(f"guide {rest}")
        except FormatError as error:
            raise TeachError(error.message) from None
        if command.verb == "hand":
            return self.follow_hand(command.amount)
        replies = self.turn.say(self.begin())
        assert self.guide is not None
        before = self.guide.stop_when
        self.guide.stop_when = interrupted or before
        try:
            self.guide.run(command)
        finally:
            self.guide.stop_when = before
        self._settle()
        return replies + self.label(final=False)

    def _settle(self) -> None:
        """A change the command made counts once it has held (the segmenter's hold time): wait
        that long now, so its ✓ comes with this command, not only after the next one."""
        assert self.guide is not None and self.segmenter is not None
        tail = self.segmenter.tail()
        if tail and tail[-1].state != tail[0].state:
            self.guide.wait(self.segmenter.hold)

    def feedback(self) -> Reply | None:
        """Where the ball and the bin are from the hand, the lift, the hand and what the last
        command did (``teach.session.feedback``); None when nobody is guiding."""
        from teach.session.feedback import feedback_line

        if self.guide is None:
            return None
        return Reply(ReplyKind.INFO, feedback_line(self.guide.feedback(), self.lang))

    def _feed(self, sample: Sample) -> None:
        """A guided sample to the segmenter, unless the teacher's hand is moving the ball or the
        bin: that change is theirs (an external step), not the robot's."""
        if self.segmenter is not None and (self.hand is None or not self.hand.holds_segmenting):
            self.segmenter.add(sample)

    def follow_hand(self, seconds: float) -> list[Reply]:
        """``guide hand``: follow the teacher's drag in the MuJoCo viewer (``teach.session.hand``)."""
        from teach.session.hand import HandFollower  # it imports MuJoCo's hand contact code

        if getattr(self.world, "viewer", None) is None:
            return [Reply(ReplyKind.ERROR, m.HAND_NEEDS_VIEWER(self.lang))]
        replies = self.turn.say(self.begin())
        assert self.guide is not None and self.segmenter is not None
        if self.hand is None or self.hand.guide is not self.guide:
            self.hand = HandFollower(self, self.guide, self.showing, self.record.observer, self.turn)
        return replies + self.hand.follow(seconds)

    def line_for_key(self, name: str) -> str | None:
        """The ``guide …`` line a key of the terminal's guide mode stands for (``Guide.key``
        names the keys; it knows where the lift and the fingers are going); None for other keys."""
        if self.guide is None:
            return None
        command = self.guide.key(name)
        return str(command) if command is not None else None

    def end(self) -> list[Reply]:
        """Guidance is over: a change within its hold time counts, and everything is labelled."""
        if self.guide is None or self.segmenter is None:
            return []
        if self.hand is not None:
            self.hand.finish()
        self.segmenter.finish()
        self.guide = None
        return self.label(final=True)

    # --- labelling -------------------------------------------------------------------------

    def label(self, final: bool) -> list[Reply]:
        """Turn the finished segments into steps while they are clear; ask about the first that is not.

        While guiding goes on, a change no action explains waits: the next one may complete it
        (driving to the ball leaves the bin behind first)."""
        replies: list[Reply] = []
        while self.pending is None:
            due = self._next_due(final)
            if due is None:
                break
            if not due.recognition.needs_question:
                replies += self._record(due, due.recognition.best or "", "robot")
            elif self.budget.left > 0:
                replies += self._ask(due)
            elif due.recognition.best is not None:
                action = due.recognition.best
                replies += self._record(due, action, "robot (no labelling questions left)",
                                        m.LABEL_ASSUMED(self.lang, change=self._change(due),
                                                        action=self._label_of(action)))
            else:
                self._leave_out(due, "robot (no labelling questions left)")
                replies.append(Reply(ReplyKind.INFO, m.LABEL_DROPPED(self.lang, change=self._change(due))))
        if self.pending is None and self.hand is not None:
            replies += self.hand.after_labels()
        if self.pending is None and not self.active and self.segmenter is not None:
            self.segmenter = None
        return self.turn.say(replies)

    def _next_due(self, final: bool) -> _Due | None:
        from teach.sim.segment import join_all

        if self.segmenter is None:
            return None
        segments = self.segmenter.segments[self.labelled:]
        if not segments:
            return None
        groups = explain(self.domain, [(s.before, s.after) for s in segments])
        span, recognition = groups[0]
        if recognition.fits:
            return _Due(join_all(segments[span.start:span.stop]), recognition, len(span))
        if not final:
            return None  # a later change may complete it (driving to the ball leaves the bin behind first)
        # a stretch of motion that no known action explains is asked about as one
        unknown = next((g.start for g, r in groups if r.fits), len(segments))
        joined = join_all(segments[:unknown])
        return _Due(joined, recognise(self.domain, joined.before, joined.after), unknown)

    def _record(self, due: _Due, action: str, who: str, text: str | None = None) -> list[Reply]:
        opened = self.showing.open
        assert opened is not None
        definition = self.domain.action(action)
        label = definition.label(self.lang)
        opened.add(due.segment.before, definition.id, m.GUIDED_WORDS(self.lang, action=label))
        self.labelled += due.spans
        self._observe(due, action, who)
        return [Reply(ReplyKind.INFO, text or m.GUIDED_STEP(self.lang, change=self._change(due), action=label))]

    def _leave_out(self, due: _Due, who: str) -> None:
        self.labelled += due.spans
        self._observe(due, "", who)

    def _observe(self, due: _Due, action: str, who: str) -> None:
        """The segment's boundaries and label, and who gave it, for the recording."""
        segment = due.segment
        change = ", ".join(str(lit) for lit in due.recognition.changes)
        self.record.observer.on_learner(
            "guided segment", f"{segment.start_time:.2f}-{segment.end_time:.2f} s: {change} → "
                              f"{action or 'left out'} (labelled by {who})")

    def _ask(self, due: _Due) -> list[Reply]:
        self.budget.spend()
        self.pending = due
        text = self._question(due)
        self.record.observer.on_learner("labelling question", text)
        options = m.LABEL_OPTIONS(self.lang, used=self.budget.used, total=self.budget.total)
        return [Reply(ReplyKind.QUESTION, f"{text}\n   {options}")]

    def _question(self, due: _Due) -> str:
        return question(self.domain, due.recognition, self.lang)

    def _change(self, due: _Due) -> str:
        return describe_change(self.domain, due.recognition, self.lang)

    def _label_of(self, action: str) -> str:
        return self.domain.action(action).label(self.lang)

    # --- answers ---------------------------------------------------------------------------

    def answer(self, line: str) -> list[Reply]:
        """The teacher's answer to the open labelling question; then the next question, if any."""
        due = self.pending
        assert due is not None
        said = line.strip()
        new_name = _new_action_phrase(said)
        if normalize(said) in SKIP_WORDS:
            self.pending = None
            self._leave_out(due, "teacher (skipped)")
            replies = [Reply(ReplyKind.INFO, m.LABEL_SKIPPED(self.lang))]
        elif new_name is not None:
            replies = self._new_action(due, new_name)
            if self.pending is due:
                return replies
        else:
            action = self._answered_action(due, said)
            if action is None:
                if is_no(said, self.lang):
                    return [Reply(ReplyKind.INFO, m.LABEL_WHICH(self.lang))]
                return [Reply(ReplyKind.ERROR, m.LABEL_ONE_ACTION(self.lang))]
            self.pending = None
            replies = self._record(due, action, "teacher",
                                   m.LABEL_THANKS(self.lang, action=self._label_of(action)))
        self.record.observer.on_answer(self._question(due), said, replies[-1].text)
        return self.turn.say(replies) + self.label(final=not self.active)

    def _answered_action(self, due: _Due, said: str) -> str | None:
        if is_yes(said, self.lang) and due.recognition.fits:
            return due.recognition.best
        try:
            tokens = [t for t in self.vocabulary.phrases.parse(said, self.lang) if t.kind == "action"]
        except TeachError:
            return None
        return tokens[0].name if len(tokens) == 1 else None

    def take_deferred(self) -> str | None:
        """The line that ended guidance, once every question about it is answered."""
        if self.pending is not None:
            return None
        line, self.deferred = self.deferred, None
        return line

    # --- a new action from guidance --------------------------------------------------------

    def _new_action(self, due: _Due, phrase: str) -> list[Reply]:
        from teach.sim.guided_skill import motion_from_segment

        name = action_name(phrase)
        domain = self.domain
        if domain.has_action(name) or any(normalize(phrase) == normalize(p) for a in domain.actions
                                          for p in a.said()):
            return [Reply(ReplyKind.ERROR, m.NEW_ACTION_TAKEN(self.lang, action=phrase))]
        phrases: dict[str, tuple[str, ...]] = {"en": (), "de": ()}
        phrases[self.lang] = (phrase,)  # in the session's language only: it is the teacher's word
        changes = changed_literals(domain, due.segment.before, due.segment.after)
        # what became true is what it is for; a condition lost on the way is a side effect (unless that is all)
        effects = tuple(lit for lit in changes if lit.value) or changes
        motion = replace(motion_from_segment(name, due.segment, domain, phrases["en"], phrases["de"]), effects=effects)
        grown = self.record.store.add_action(action_block(domain, name, phrases, effects))
        file = self.record.store.write_motion(motion)
        self.adopt(grown, [motion])
        self.record.add(GuidedActionTaught(name, file))
        self.pending = None
        return self._record(due, name, "teacher (a new action)",
                            m.NEW_ACTION_LEARNED(self.lang, action=phrase, change=self._change(due)))

    def adopt(self, domain: Domain, motions: Sequence[GuidedMotion]) -> None:
        """Teach from now on in ``domain`` (the session's copy with new actions), their motions runnable."""
        world = self.world
        assert isinstance(world, GuidableWorld)
        for motion in motions:
            world.learn_skill(motion)
        world.adopt_domain(domain)
        self.vocabulary.adopt(domain)
        self.adopted(domain)

    def restore(self, events: Sequence[object]) -> None:
        """On resume: the actions taught by guidance are back in the domain and runnable."""
        taught = [e for e in events if isinstance(e, GuidedActionTaught)]
        if not taught or not self.can_guide():
            return
        domain = self.record.store.session_domain()
        self.adopt(domain, [self.record.store.read_motion(e.motion, domain) for e in taught])


def _whole_move(line: str) -> bool:
    """Whether ``line`` after 'guide' is a move as it stands (its amount right)."""
    from teach.sim.guide import parse_guide_line

    try:
        parse_guide_line(f"guide {line.strip()}")
    except FormatError:
        return False
    return True


STOP_WORDS = ("stop", "end", "ende", "halt", "aus", "esc", "escape")
"""``guide stop``: guidance ends (Esc in the terminal's guide mode says it); while guiding also
one of them alone ("esc" typed after "Esc ends it" was "I don't know “esc”")."""
_NEW_WORDS = ("something new", "a new action", "new action", "etwas neues", "was neues", "eine neue aktion",
              "neue aktion")


def _new_action_phrase(text: str) -> str | None:
    """The name in "something new: push the ball" (either language), or None."""
    key = normalize(text)
    for words in _NEW_WORDS:
        if key == words or key.startswith(words + " "):
            count = len(words.split())
            rest = re.split(r"[\s:,–-]+", text.strip(), maxsplit=count)
            phrase = rest[count].strip(" :,–-") if len(rest) > count else ""
            return phrase or None
    return None


def is_new_action_answer(text: str) -> bool:
    """Whether a dialogue line names a new action for a guided motion."""
    return _new_action_phrase(text) is not None


def action_name(phrase: str) -> str:
    """An identifier for a phrase: "push the ball" → PushTheBall, "den Ball schieben" → DenBallSchieben."""
    plain = unicodedata.normalize("NFKD", phrase.replace("ß", "ss"))
    plain = "".join(c for c in plain if not unicodedata.combining(c))
    words = re.findall(r"[A-Za-z0-9]+", plain)
    name = "".join(w[:1].upper() + w[1:] for w in words)
    return name if name[:1].isalpha() else f"Action{name}"


def action_block(domain: Domain, name: str, phrases: Mapping[str, Sequence[str]], effects: Sequence[object]) -> str:
    """The ``[[action]]`` table of a new action: the next free id, its phrases, its effects."""
    def strings(values: Sequence[object]) -> str:
        return "[" + ", ".join('"' + str(v).replace("\\", "\\\\").replace('"', '\\"') + '"' for v in values) + "]"

    number = max((a.id for a in domain.actions), default=0) + 1
    return (f"# taught by guidance\n[[action]]\nid = {number}\nname = \"{name}\"\nen = {strings(phrases['en'])}\n"
            f"de = {strings(phrases['de'])}\npre = []\nram = {strings(effects)}\n")
