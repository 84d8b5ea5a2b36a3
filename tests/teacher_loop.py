"""A teacher who corrects the robot in a session until it does the task from every start: the
session loop of issue 18 (item 3), driven through ``SessionManager.handle`` as a person types.

From each start the teacher types ``start …`` and ``run``. When the robot asks "may I still do X
here?" they say yes if X can run there in the true model (``demos/ball/domain.toml`` declares
it), else they name what an optimal plan does there; any other question gets the plan's first
step (or "done"). When it stops without a question, they show the rest of the task from there
and say done. Nothing here knows the learner: only what a person would see and type."""

from __future__ import annotations

from dataclasses import dataclass, field

from teach.dialogue.oracle import SKIP, PlanningOracle
from teach.domain import Domain, State
from teach.session.machine import SessionManager
from teach.symbolic import missing_preconditions


@dataclass
class Corrections:
    """What it took: lines typed, questions answered, demonstrations shown, runs made."""

    lines: list[str] = field(default_factory=list)
    answers: int = 0
    shown: int = 0
    runs: int = 0


def goal_holds(model: Domain, state: State) -> bool:
    return all(state[model.index(lit.name)] == lit.value for lit in model.goal)


def honest_answer(session: SessionManager, model: Domain, teacher: PlanningOracle | None = None) -> str:
    """What a teacher who knows the true model answers to the open question."""
    question = session.pending
    assert question is not None
    if question.kind == "must-precondition" and question.action is not None \
            and not missing_preconditions(model, question.state, question.action):
        return "yes"
    if question.kind == "must-goal" and goal_holds(model, question.state):
        return "yes"
    best = (teacher or PlanningOracle(model, session.domain)).answer(question.state)
    return "skip" if best == SKIP else "done" if best is None else session.domain.action(best).label("en")


def correct_until_it_works(session: SessionManager, model: Domain, starts: list[State],
                           rounds: int = 6) -> Corrections:
    """Run from every start, correcting, until a round needs no correction (at most ``rounds``)."""
    teacher = PlanningOracle(model, session.domain)
    done = Corrections()

    def say(line: str) -> list:
        done.lines.append(line)
        return session.handle(line)

    def answer_all() -> None:
        while session.pending is not None:
            done.answers += 1
            say(honest_answer(session, model, teacher))

    for _ in range(rounds):
        corrected = False
        for start in starts:
            named = [name for name, value in zip(session.domain.condition_names, start, strict=True) if value]
            say("start " + " ".join(named) if named else "start nothing")
            done.runs += 1
            replies = say("run")
            if any(r.text == "Done! The task is finished." for r in replies):
                continue
            corrected = True
            answer_all()
            if session.open is not None or any("Show me how to go on" in r.text for r in replies):
                show_rest(session, teacher, say)
                done.shown += 1
                answer_all()
        if not corrected:
            return done
    return done


def show_rest(session: SessionManager, teacher: PlanningOracle, say) -> None:  # type: ignore[no-untyped-def]
    """Show the optimal plan from where the robot stands, then say done."""
    for _ in range(12):
        state = session.world.state()
        best = teacher.answer(state)
        if best is None or best == SKIP:
            break
        say(session.domain.action(best).label("en"))
    if session.open is not None and session.open.steps:
        say("done")
    elif session.open is not None:
        say("cancel")
