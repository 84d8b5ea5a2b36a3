"""The moments of a recording worth a picture, and what each picture claims to show.

``tools/screenshots.py`` photographs these moments in rerun's web viewer and commits their
moments and captions beside the pictures (``docs/screenshots/pictures.json``); a test replays
the session and checks, at each committed moment, that the recording shows what the caption says.
"""

from __future__ import annotations

from dataclasses import dataclass

from teach.bt.nodes import Status
from teach.observe.reader import RecordingContents
from teach.observe.tree_view import IDLE_COLOUR, STATUS_COLOURS


@dataclass(frozen=True)
class Picture:
    name: str
    moment: int
    """The moment on the recording's ``tick`` timeline."""
    caption: str


def pictures(contents: RecordingContents) -> list[Picture]:
    """The first tick of the first run, the middle of its grasp, the answer to the last question
    and the end of the session (the pictures a recording offers)."""
    shots: list[Picture] = []
    first_run = [t for t in contents.ticks if contents.runs and t.moment is not None
                 and contents.runs[0].started is not None and contents.runs[0].ended is not None
                 and contents.runs[0].started < t.moment < contents.runs[0].ended]
    if first_run and first_run[0].moment is not None:
        tick = first_run[0]
        shots.append(Picture("first-tick", first_run[0].moment,
                             f"Tick {tick.moment}, the first tick of run 1: the robot starts with "
                             f"{tick.action or 'nothing'} (orange in the tree that ran; red: conditions that failed)."))
    grasps = [t for t in first_run if t.action == "GraspBall"]
    if grasps:
        middle = grasps[len(grasps) // 2]
        assert middle.moment is not None
        shots.append(Picture("grasp", middle.moment,
                             f"Tick {middle.moment}, run 1: the robot grasps the ball (GraspBall running, "
                             f"tick {grasps.index(middle) + 1} of its {len(grasps)})."))
    answered = [q.answer_moment for q in contents.questions if q.answer_moment is not None]
    if answered and len(answered) == len(contents.questions):
        shots.append(Picture("questions", max(answered),
                             f"Tick {max(answered)}: the answer to the last of the {len(answered)} questions; "
                             "every question and answer in full in Questions asked."))
    if contents.generations:
        shots.append(Picture("end", contents.last_moment,
                             f"Tick {contents.last_moment}, the end of the session: generation "
                             f"{contents.generations[-1].generation} as learned, the tree that ran grey "
                             "(no run at this moment)."))
    return shots


def wrong_at(contents: RecordingContents, picture: Picture) -> str | None:
    """What is wrong with ``picture``'s claim at its moment in ``contents`` (None: it holds)."""
    chosen = {p.name: p for p in pictures(contents)}
    if picture.name not in chosen:
        return f"{picture.name}: the recording offers no such picture"
    if chosen[picture.name].moment != picture.moment:
        return f"{picture.name}: taken at tick {picture.moment}, the recording's is {chosen[picture.name].moment}"
    tick = contents.tick_at(picture.moment)
    colours = contents.colours_at(picture.moment)
    if picture.name in ("first-tick", "grasp"):
        if tick is None:
            return f"{picture.name}: no tick at {picture.moment}"
        if picture.name == "grasp" and tick.action != "GraspBall":
            return f"grasp: the action running at tick {picture.moment} is {tick.action}"
        running = [node for node, (_, status) in zip(tick.nodes, tick.trace, strict=True)
                   if status == Status.RUNNING.name and colours[node] == STATUS_COLOURS[Status.RUNNING]]
        if not running:
            return f"{picture.name}: nothing is drawn running at tick {picture.moment}"
    elif set(colours) - {IDLE_COLOUR}:
        return f"{picture.name}: the tree that ran is coloured at tick {picture.moment}"
    if picture.name == "questions" and any(q.answer_moment is None or q.answer_moment > picture.moment
                                           for q in contents.questions):
        return f"questions: a question is not answered by tick {picture.moment}"
    return None
