"""The open demonstration in the session's words: how steps, events, 'undo N' and 'redo' of
the demonstration being shown are recorded, said and journalled.

The steps themselves are built by ``teach.open_demonstration`` (the one builder, which the
MuJoCo recorder uses too); the session record holds the demonstration open now and journals
it. Named steps, guided ones (``teach.session.guiding``) and the hand follower's moves all go
through one ``Showing``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from teach import messages as m
from teach.dialogue.phrases import Token
from teach.domain import Literal, State
from teach.errors import TeachError
from teach.messages import Lang
from teach.open_demonstration import OpenDemonstration, TakenBack, WorldEventStep
from teach.session.journal import Situated
from teach.session.record import SessionRecord
from teach.session.replies import Reply, ReplyKind
from teach.session.run_report import already_so, phrase_said, untrue_now, way_steps, why_not
from teach.session.turn import Turn
from teach.session.vocabulary import Vocabulary
from teach.world.protocol import ActResult, RunResult, TeachingWorld, WorldEvent


@dataclass(frozen=True)
class _StepsTakenBack:
    """What 'undo N' took from the open demonstration, so 'redo' can put it back while nothing
    happened since: the open demonstration still ends where they began and the world is as the
    undo left it."""

    taken: TakenBack
    world_after: State
    """The world when the undo was said (after the steps): a redo puts it back there."""
    arranged: State
    """The world the undo left (before the steps)."""


@dataclass(frozen=True)
class _Discarded:
    """What 'cancel' discarded, so an 'undo' straight after it brings it back (it was lost: "Nothing
    to undo"): the demonstration, the world it left, and how much the journal held then."""

    demonstration: OpenDemonstration
    world: State
    journalled: int


MAX_REPLANS = 2
"""How often a way the teacher said yes to is planned again where one of its steps turned out
impossible (each way is at most ``WAY_STEPS`` long)."""


class Showing:
    """The demonstration being shown: opened by its first step, each step said and journalled."""

    def __init__(self, record: SessionRecord, turn: Turn, world: TeachingWorld, vocabulary: Vocabulary,
                 lang: Lang):
        self.record, self.turn, self.world, self.vocabulary = record, turn, world, vocabulary
        self.lang = lang
        self._taken_back: _StepsTakenBack | None = None
        self._discarded: _Discarded | None = None
        self.offered: str | None = None
        """After a refused step, the line that does the way to it and the step ("go to the ball, grasp
        the ball"): the session does it on the teacher's yes to the next line, and forgets it then."""
        self.just_done: str | None = None
        """The last step the line before did (an action's name): "again" on the next line does it once
        more; the session forgets it after that line."""

    @property
    def open(self) -> OpenDemonstration | None:
        return self.record.open

    @property
    def has_steps(self) -> bool:
        return self.record.open is not None and bool(self.record.open.steps)

    def begin(self) -> list[Reply]:
        """Open a demonstration if none is (said: "New demonstration")."""
        if self.record.open is not None:
            return []
        self._discarded = None  # a new one: 'undo' no longer means the discarded one
        self.record.open = OpenDemonstration()
        return [Reply(ReplyKind.INFO, m.NEW_DEMONSTRATION(self.lang))]

    def for_step(self) -> OpenDemonstration:
        """The open demonstration, opened when its first step has happened (a failed first step opens none)."""
        self.turn.say(self.begin())
        assert self.record.open is not None
        return self.record.open

    def close(self) -> None:
        """The demonstration is finished or discarded: none is open."""
        self.record.open = None

    def discard(self) -> None:
        """'cancel': the open demonstration is dropped, kept only for an 'undo' straight after."""
        assert self.record.open is not None
        kept = self.record.open.steps
        self._discarded = _Discarded(self.record.open, self.world.state(), self._taught()) if kept else None
        self.close()

    def _taught(self) -> int:
        """How many things the journal holds, not counting where the world was left."""
        return sum(not isinstance(event, Situated) for event in self.record.journal.events)

    def bring_back(self) -> str | None:
        """Reopen what 'cancel' discarded, while nothing happened since (no demonstration open, the
        world as it was left, nothing journalled), said once it is on disk. Where something did, it
        says that it cannot come back, and nothing else is undone (the 'undo' was meant for it, not
        for the last learned demonstration). None where nothing was discarded."""
        discarded, self._discarded = self._discarded, None
        if discarded is None or self.record.open is not None:
            return None
        if self.world.state() != discarded.world or self._taught() != discarded.journalled:
            return m.NOT_BACK(self.lang)
        self.record.open = discarded.demonstration
        self.record.save_open()
        return m.BROUGHT_BACK(self.lang, steps=steps_said(len(discarded.demonstration.steps), self.lang))

    # --- steps -----------------------------------------------------------------------------

    def step(self, before: State, action: str, words: str) -> None:
        """The robot did ``action`` in ``before``; journalled before the teacher sees its "✓"."""
        self.for_step().add(before, self.vocabulary.domain.action(action).id, words)
        self.record.save_open()

    def event(self, event: WorldEvent) -> None:
        """An event of the world as an external step (-1) of the open demonstration."""
        self.external(event.before, self.said(event))

    def external(self, before: State, said: str) -> None:
        """Something changed in ``before`` that the robot did not do (``said``: what happened)."""
        self.for_step().add_event(WorldEventStep(before, m.EVENT_STEP(self.lang, event=said)))

    def said(self, event: WorldEvent) -> str:
        return m.Text(event.en, event.de)(self.lang)

    def event_reply(self, event: WorldEvent) -> Reply:
        return Reply(ReplyKind.INFO, m.EVENT(self.lang, event=self.said(event)))

    def halted(self, action: str, result: ActResult) -> list[Reply]:
        """An action the world's events halted: its own part kept as a step if it changed
        anything (else dropped: said which), then each event as an external step (-1)."""
        label = self.vocabulary.domain.action(action).label(self.lang)
        events = [WorldEventStep(e.before, m.EVENT_STEP(self.lang, event=self.said(e))) for e in result.events]
        kept = self.for_step().halted(result.before, self.vocabulary.domain.action(action).id, result.action_after,
                                      m.HALTED_STEP(self.lang, action=label), events)
        replies = [Reply(ReplyKind.INFO, (m.HALTED_KEPT if kept else m.HALTED_DROPPED)(self.lang, action=label))]
        replies += [self.event_reply(event) for event in result.events]
        self.record.save_open()  # on disk before the teacher sees the event
        return replies

    def act(self, tokens: list[Token], facilitator: bool, interrupted: Callable[[], bool] | None = None,
            reaching: bool = False) -> list[Reply]:
        """Do the parsed steps in the world, each recorded in the open demonstration (opened by
        the first that happens) and said as it happens; one whose effects hold already is passed
        over, one that cannot be done ends the line
        (``facilitator``: with the world's own words why), and so does Ctrl-C (``interrupted``,
        polled between steps: the step under way is finished, the rest said as not done).
        ``reaching``: the line is an offered way and its step, which the teacher said yes to: where
        a step of it cannot be done (in MuJoCo going to the ball takes a near bin out of reach, which
        the domain's model does not say), the way to the last step is planned again from there
        (``MAX_REPLANS`` times) instead of stopping one step short of what was promised."""
        domain = self.vocabulary.domain
        replies: list[Reply] = []
        queue, index, replanned = list(tokens), 0, 0
        while index < len(queue):
            token = queue[index]
            if index and interrupted is not None and interrupted():
                self.just_done = None
                replies += self.turn.say(self._not_done(queue[index:]))
                break
            if token.kind == "event":
                result = self.world.perturb(token.name)
                if not result.ok:  # it was said to have happened and written as a step of the demonstration
                    replies.append(Reply(ReplyKind.ERROR, m.EVENT_NOT_NOW(self.lang, event=token.text)))
                    if facilitator and result.message:
                        replies.append(Reply(ReplyKind.INFO, m.DETAILS(self.lang, details=result.message)))
                    break
                self.external(result.before, token.text)
                self.record.observer.on_external(token.name)
                self.record.save_open()
                replies += self.turn.say([Reply(ReplyKind.INFO, m.EVENT(self.lang, event=token.text))])
                index += 1
                continue
            label = domain.action(token.name).label(self.lang)
            before = self.world.state() if token.needs else None  # read only for a phrase that needs something
            if before is not None and any(not domain.holds(p, before) for p in token.needs):
                # "take the ball to the bin" without the ball: going there empty-handed would teach
                # that step where the teacher meant another, so it is refused with what is missing
                self.just_done = None
                reason = why_not(domain, token.name, before, self.lang, token.needs)
                said = phrase_said(domain, token, self.lang)
                replies.append(Reply(ReplyKind.ERROR, m.NOT_WITHOUT(self.lang, said=said, reason=reason)))
                replies += self._way_offered(token.name, token.text, before, token.needs)
                break
            result = self.world.act(token.name)
            so = "" if result.ok else already_so(domain, token.name, result.before, self.lang)
            if so:  # "find the ball" where it is seen was "I could not find the ball: first this must be
                # true: I cannot see the ball"; like a step that changed nothing, it is passed over
                replies += self.turn.say([Reply(ReplyKind.INFO, m.ALREADY_SO(self.lang, action=label, so=so))])
                index += 1
                continue
            if not result.ok:
                reason = why_not(domain, token.name, result.before, self.lang)
                way = way_steps(domain, queue[-1].name, self.world.state(), queue[-1].needs) \
                    if reaching and replanned < MAX_REPLANS and queue[-1].kind == "action" else []
                if way:  # the promised step, by a way planned again from where the robot is now
                    replanned += 1
                    queue[index:] = [*(self._token(step) for step in way), queue[-1]]
                    untrue = untrue_now(domain, token.name, result.before, self.lang) or reason
                    labels = [domain.action(step.name).label(self.lang) for step in queue[index:]]
                    said = m.WAY_AGAIN(self.lang, untrue=untrue, steps=", ".join(labels[:-1]), action=labels[-1])
                    replies += self.turn.say([Reply(ReplyKind.INFO, said)])
                    continue
                self.just_done = None  # "again" after a refusal: which step is meant?
                replies.append(Reply(ReplyKind.ERROR, m.COULD_NOT(self.lang, action=label, reason=reason)))
                if facilitator and result.message:  # the world's own words are for the facilitator
                    replies.append(Reply(ReplyKind.INFO, m.DETAILS(self.lang, details=result.message)))
                replies += self._way_offered(token.name, label, result.before, token.needs)
                break
            if result.events:  # the world stopped it: the rest of the line no longer fits
                self.just_done = None
                replies += self.turn.say(self.halted(token.name, result) + self._not_done(queue[index + 1:]))
                break
            index += 1
            if result.after == result.before:
                # a step that changes nothing would teach two different actions in one state; where all it
                # makes so was so already (MuJoCo runs "find the ball" on a seen ball), it is said as in
                # the symbolic world, not ticked ("✓ find the ball (nothing changed)" read as done)
                so = already_so(domain, token.name, result.before, self.lang)
                said = m.ALREADY_SO(self.lang, action=label, so=so) if so \
                    else m.NOTHING_CHANGED(self.lang, action=label)
                replies += self.turn.say([Reply(ReplyKind.INFO, said)])
                continue
            self.step(result.before, token.name, label)
            self.just_done = token.name
            replies += self.turn.say([Reply(ReplyKind.INFO, m.DID_STEP(self.lang, action=label))])
        return replies

    def _token(self, action: str) -> Token:
        """A step the robot planned itself, as if the teacher had named it."""
        return Token("action", action, self.vocabulary.domain.action(action).label(self.lang))

    def _way_offered(self, action: str, label: str, state: State, needs: tuple[Literal, ...] = ()) -> list[Reply]:
        """The way to a refused step, offered: a yes does it and then the step ("grab it" before the
        ball was within reach: "To get there: go to the ball. Say 'yes' and I do that, then grasp the
        ball." — it took two more lines). ``needs``: what the teacher's phrase for it needs too."""
        domain = self.vocabulary.domain
        labels = [domain.action(step).label(self.lang) for step in way_steps(domain, action, state, needs)]
        if not labels:
            return []
        self.offered = ", ".join([*labels, label])
        return [Reply(ReplyKind.INFO, m.WAY_THERE_OFFER(self.lang, steps=", ".join(labels), action=label))]

    def _not_done(self, tokens: list[Token]) -> list[Reply]:
        """The rest of a line the world stopped, said as not done."""
        if not tokens:
            return []
        domain = self.vocabulary.domain
        words = [t.text if t.kind == "event" else domain.action(t.name).label(self.lang) for t in tokens]
        return [Reply(ReplyKind.INFO, m.REST_NOT_DONE(self.lang, actions=", ".join(words)))]

    def from_run(self, result: RunResult, stopped_midway: bool = False) -> None:
        """What a run that did not finish did (and the world's events in it, a slip) opens the
        correction the teacher's next steps continue. ``stopped_midway``: the tree stopped the last
        step before its effects came about; what it changed is kept as an event (-1), as a slip
        is, not learned as its effect (a grasp stopped as the bin came within reach was "why
        grasp the ball: to make the bin within reach true")."""
        domain = self.vocabulary.domain
        steps = [(state, domain.action(action).id,
                  m.ROBOT_DID_STEP(self.lang, action=domain.action(action).label(self.lang)))
                 for state, action in result.steps]
        events = [(after, WorldEventStep(event.before, m.EVENT_STEP(self.lang, event=self.said(event))))
                  for after, event in result.events]
        if stopped_midway:
            state, action = result.steps[-1]
            steps.pop()
            stopped = m.STOPPED_MIDWAY(self.lang, action=domain.action(action).label(self.lang))
            events.append((len(steps), WorldEventStep(state, m.EVENT_STEP(self.lang, event=stopped))))
        self.record.open = OpenDemonstration.from_run(steps, events)

    def save_run(self, started: list[tuple[State, str]]) -> None:
        """A run's progress on disk before the teacher sees it: a kill mid-run keeps the steps done."""
        domain = self.vocabulary.domain
        done = [(state, domain.action(action).id,
                 m.ROBOT_DID_STEP(self.lang, action=domain.action(action).label(self.lang)))
                for state, action in started[:-1]]
        self.record.save_run(done, started[-1][0], started[-1][1])

    # --- 'steps', 'undo N', 'redo' ---------------------------------------------------------

    def listing(self) -> list[Reply]:
        if not self.has_steps:
            return [Reply(ReplyKind.INFO, m.NO_OPEN_STEPS(self.lang))]
        assert self.record.open is not None
        lines = [f"  {number}. {words}" for number, words in enumerate(self.record.open.words, 1)]
        return [Reply(ReplyKind.INFO, m.OPEN_STEPS(self.lang) + "\n" + "\n".join(lines))]

    def take_back(self, first: int | None) -> str:
        """Take back steps ``first``.. (the last one when None): the world goes back to the state
        before them. Returns what was said of it."""
        opened = self.record.open
        assert opened is not None
        count = len(opened.steps)
        if first is None:
            first = count
        if not 1 <= first <= count:
            raise TeachError(m.NO_SUCH_STEP(self.lang, number=first, count=count))
        world_after = self.world.state()
        taken = opened.take_back(first)
        self.world.arrange(taken.steps[0].state)
        self._taken_back = _StepsTakenBack(taken, world_after, self.world.state())
        if not opened.steps:
            self.record.open = None
        text = m.UNDONE_ONE_STEP if first == count else m.UNDONE_STEPS
        return text(self.lang, first=first, last=count, steps="; ".join(taken.words))

    def put_back(self) -> str | None:
        """Bring back the steps the last 'undo N' took, while nothing happened since (the open
        demonstration ends where they began, the world is as the undo left it); None otherwise."""
        back, self._taken_back = self._taken_back, None
        open_steps = len(self.record.open.steps) if self.record.open is not None else 0
        if back is None or open_steps != back.taken.first - 1 or self.world.state() != back.arranged:
            return None
        if self.record.open is None:
            self.record.open = OpenDemonstration()
        self.record.open.put_back(back.taken)
        self.world.arrange(back.world_after)
        self.record.save_open()
        first, last = back.taken.first, len(self.record.open.steps)
        return (m.REDONE_ONE_STEP if last == first else m.REDONE_STEPS)(
            self.lang, first=first, last=last, steps="; ".join(back.taken.words))


def steps_said(count: int, lang: Lang) -> str:
    """How many steps, in words: "1 step", "3 steps"."""
    return (m.STEP_COUNT if count == 1 else m.STEPS_COUNT)(lang, count=count)
