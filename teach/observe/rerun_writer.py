"""Every step of a session recorded with rerun (``teach.observe.reader`` reads it back).

``RerunLogger`` is the session's ``Observer``: it writes ``recordings/<session>.rrd`` (no viewer,
no display needed) and, with ``spawn=True``, also streams to a live viewer. Like
BehaviorTree.CPP's file logger it writes what explains the rest first (blueprint, domain,
tree), then the events. Entity paths are namespaced: ``scene/...`` and ``camera/image`` (the
world), ``state`` (symbolic state and running action), ``state/external``, ``tree/graph`` (the
tree, coloured by each tick, with the tick's trace), ``tree/xml``, ``dialogue``, ``learner/...``,
``demos``, and ``study/...`` (what a study leader plots afterwards: tree size and reproduced share
per generation, the questions and what each changed, run outcomes). Each event row carries
``AnyValues`` with plain fields, so ``read_recording`` gets the session back without parsing
display text; rows are put back in order by their rerun row ids, which increase monotonically
within the logging process.

rerun costs 50-270 µs per ``log`` call, so the scene is throttled to ``scene_hz`` and each camera
(``camera/image``: the room's overview, ``robot_camera/image``: the robot's own) to ``camera_hz``
frames per second of simulated time, and each shape kind is one batched call.
"""

from __future__ import annotations

import atexit
import dataclasses
import io
import json
import os
from collections.abc import Callable, Mapping
from collections.abc import Sequence as Seq
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import PIL.Image
import rerun as rr

from teach.bt.nodes import Node
from teach.display import has_display
from teach.errors import TeachError
from teach.observe.encode import SHAPE_ENTITIES, Batch, SceneLayout, plain_values, shape_batch, step_label, tick_columns
from teach.observe.hook import Observer, SessionEvent
from teach.observe.layout import APPLICATION_ID, GENERATION_PANEL, blueprint, default_recording_path
from teach.observe.legend import legend_document
from teach.observe.markdown import demonstration_document, domain_document, state_document
from teach.observe.merge import keep_earlier, merge_into_place, print_note, put_back
from teach.observe.moments import Moments, Opened
from teach.observe.panels import Panels
from teach.observe.tree_view import IDLE_COLOUR, READABLE, TreeView, phrases

if TYPE_CHECKING:
    from teach.bt.tick import TickResult
    from teach.demos import Demonstration
    from teach.domain import Domain
    from teach.observe.scene import SceneShape


CAMERA_ENTITIES = {"overview": "camera/image", "robot": "robot_camera/image"}
"""The room's overview is the main image (``camera/image``); the robot's own camera is beside it."""


class RerunLogger(Observer):
    """Records a session to an ``.rrd`` file (and a live viewer with ``spawn``).

    The file is written as ``<name>.rrd.part`` and renamed when the logger closes, so a
    finished recording is never half-written; ``close`` runs at interpreter exit if the
    caller forgot it.
    """


    def __init__(self, path: Path | None, session_name: str, spawn: bool = False, *, resume: bool = False,
                 note: Callable[[str], None] = print_note, scene_hz: float = 10.0, camera_hz: float = 2.0,
                 jpeg_quality: int = 80, batch_rows: int | None = None, lang: str = "en"):
        if spawn and not has_display():
            raise TeachError("--spawn needs a display for the rerun viewer (no DISPLAY or WAYLAND_DISPLAY); "
                             "the recording is written without it, open it later with `teach review FILE --open`")
        self.path = Path(path) if path is not None else default_recording_path(session_name)
        self._part = self.path.with_name(self.path.name + ".part")
        self._earlier: list[Path] = []  # a resumed session's recording so far, merged in on close
        try:  # fail here with a clear line rather than inside rerun's writer
            self.path.parent.mkdir(parents=True, exist_ok=True)
            if resume:
                self._earlier = keep_earlier(self.path, self._part, note)
            self._part.open("wb").close()
        except OSError as exc:
            raise TeachError(f"cannot write the recording: {exc.strerror}", exc.filename or self._part) from None
        self._scene_period = 1.0 / scene_hz
        self._camera_period = 1.0 / camera_hz
        self._jpeg_quality = jpeg_quality
        self._lang = lang
        self._phrases: dict[str, str] = {}  # leaf labels in the session's language, once the domain is known
        self._batch_rows = batch_rows or (3 if spawn else 20)  # a live viewer should lag little
        self._rec = rr.RecordingStream(APPLICATION_ID, recording_id=session_name)
        self._rec.set_log_time_enabled(False)
        self._rec.set_log_tick_enabled(False)
        if spawn:
            self._rec.spawn(connect=False)
            self._rec.set_sinks(rr.FileSink(self._part), rr.GrpcSink(), default_blueprint=blueprint())
        else:
            self._rec.save(self._part, default_blueprint=blueprint())
        self._rec.send_recording_name(session_name)
        self._clock: tuple[int, int, float | None] = (0, 0, None)  # version, step, sim_time
        self._moments = Moments()  # the `tick` timeline: every tick, demonstration step and line its own moment
        self._sim_time: float | None = None  # the last sim_time given: rerun's clocks are sticky too
        self._batches: dict[str, Batch] = {}
        self._last_state: tuple | None = None
        self._stamped = -1  # the clock version rerun was last told
        self._view: TreeView | None = None  # the current generation (the teaching view)
        self._run_view: TreeView | None = None  # the tree that runs as drawn (the run view, coloured by its ticks)
        self._whole: TreeView | None = None  # the whole tree that runs, drawn whole if it reads at that size
        self._folded: dict[frozenset[int], TreeView] = {}  # its drawings folded to what a tick reached
        self._coloured = False  # the run view shows a tick's colours: cleared when the next moment is no tick
        self._generation = -1
        self._last_scene: float | None = None
        self._last_camera: dict[str, float] = {}
        self._questions = 0
        self._panels = Panels()
        self._runs: dict[str, int] = {}
        self._run_started = (0, 0)  # the (step, moment) the current run started at
        self._scene_geometry: tuple = ()  # name, kind, size and colour of each shape, as last logged
        self._scene_columns: Callable[[list[tuple]], list[tuple[str, list[Any]]]] | None = None
        self._closed = False
        atexit.register(self.close)

    # --- clocks -----------------------------------------------------------------------------

    def set_time(self, step: int | None, sim_time: float | None = None) -> None:
        """``step`` None keeps the session's step (a simulation advancing only ``sim_time``)."""
        self._clock = (self._clock[0] + 1, self._clock[1] if step is None else step, sim_time)
        if sim_time is not None:
            self._sim_time = sim_time
        self._stamp()

    def _moment(self, opened: bool) -> None:
        """A new moment on the ``tick`` timeline began (``opened``): the run view's colours belonged
        to the tick before, so a moment that is no tick shows the tree idle."""
        if not opened:
            return
        self._clock = (self._clock[0] + 1, *self._clock[1:])
        if self._coloured and self._moments.opened is not Opened.TICK:
            self._idle_run_view()

    def _idle_run_view(self) -> None:
        self._coloured = False
        if self._run_view is not None:
            self._log("tree/graph", rr.GraphNodes.from_fields(colors=[IDLE_COLOUR] * len(self._run_view.labels),
                                                              labels=self._run_view.labels))

    def _stamp(self) -> None:
        """Bring rerun's clocks up to the session's before logging (once per clock change)."""
        version, step, sim_time = self._clock
        if self._stamped == version:
            return
        self._stamped = version
        self._rec.set_time("step", sequence=step)
        self._rec.set_time("tick", sequence=self._moments.now)
        if sim_time is not None:
            self._rec.set_time("sim_time", duration=sim_time)

    def _log(self, entity: str, *parts: Any, static: bool = False, flush: bool = True) -> None:
        """Log one row now; ``flush`` first sends the batched rows, so row ids keep the calls' order."""
        if self._closed:
            return
        if flush:
            self._flush()
        self._stamp()
        self._rec.log(entity, *parts, static=static)

    def _queue(self, stream: str, columns: Callable[[list[tuple]], list[tuple[str, list[Any]]]], row: tuple) -> None:
        """Batch one row of a high-rate stream (scene poses, ticks); sent as columns, one rerun call per
        entity per batch. ``columns`` turns the rows into (entity, columns) pairs."""
        if self._closed:
            return
        batch = self._batches.get(stream)
        if batch is not None and (batch.times[0] is None) != (self._sim_time is None):
            self._send(stream)
            batch = None
        if batch is None:
            batch = self._batches[stream] = Batch(columns)
        batch.steps.append(self._clock[1])
        batch.moments.append(self._moments.now)
        batch.times.append(self._sim_time)
        batch.rows.append(row)
        if len(batch.rows) >= self._batch_rows:
            self._send(stream)

    def _flush(self, stream: str | None = None) -> None:
        for name in [stream] if stream is not None else sorted(self._batches):
            if name in self._batches:
                self._send(name)

    def _send(self, stream: str) -> None:
        batch = self._batches.pop(stream)
        indexes = [rr.TimeColumn("step", sequence=batch.steps), rr.TimeColumn("tick", sequence=batch.moments)]
        if batch.times[0] is not None:
            indexes.append(rr.TimeColumn("sim_time", duration=[t for t in batch.times if t is not None]))
        for entity, columns in batch.columns(batch.rows):
            self._rec.send_columns(entity, indexes=indexes, columns=columns)

    # --- vocabulary and trees ---------------------------------------------------------------

    def on_domain(self, domain: Domain) -> None:
        self._phrases = phrases(domain, self._lang)
        names = list(domain.condition_names)
        self._log("domain", rr.TextDocument(domain_document(domain), media_type=rr.MediaType.MARKDOWN),
                  plain_values(name=domain.name, conditions=names, actions=list(domain.action_names),
                          action_ids=[a.id for a in domain.actions], goal=[str(g) for g in domain.goal] or None),
                  static=True)
        self._log("state", rr.SeriesLines(names=names, interpolation_mode="StepAfter"), static=True)
        self._log("scene", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)  # MuJoCo's convention
        self._log("legend", rr.TextDocument(legend_document(self._lang), media_type=rr.MediaType.MARKDOWN),
                  static=True)
        for entity in ("study/tree_size", "study/questions_answered"):  # counts: whole numbers, as steps from 0
            self._log(entity, rr.SeriesLines(interpolation_mode="StepAfter"), static=True)
            self._log(entity, rr.Scalars(0.0))
        if self._view is None:  # the tree comes first in every recording, even before there is one
            self._log("tree/xml", rr.TextDocument("No tree yet: the robot learns its first behaviour tree from the "
                                                  "first demonstration.", media_type=rr.MediaType.TEXT))

    def on_tree(self, generation: int, tree: Node, xml: str, reason: str) -> None:
        self._generation = generation
        self._view = TreeView.of(tree, self._phrases, GENERATION_PANEL)
        self._log_graph("tree/generation", self._view)
        nodes = len(self._view.labels)
        self._log("tree/xml", rr.TextDocument(xml, media_type=rr.MediaType.TEXT))
        self._log("learner/generations",
                  rr.TextLog(f"generation {generation}: {nodes} nodes ({reason})", level="generation"),
                  plain_values(generation=generation, reason=reason, nodes=nodes, xml=xml))
        self._log("study/tree_size", rr.Scalars(float(nodes)))
        self._learner_panel(f"generation {generation}: {nodes} nodes ({reason})")

    def _learner_panel(self, text: str) -> None:
        self._log("learner/document", rr.TextDocument(self._panels.learner(self._moments.now, text),
                                                      media_type=rr.MediaType.MARKDOWN))

    def _log_graph(self, entity: str, view: TreeView) -> None:
        self._log(entity,
                  rr.GraphNodes([str(i) for i in range(len(view.labels))], labels=view.labels, show_labels=True,
                                positions=view.positions, colors=[IDLE_COLOUR] * len(view.labels)),
                  rr.GraphEdges(view.edges, graph_type="directed"))

    def _running(self, tree: Node, reached: frozenset[int]) -> TreeView:
        """The run view of a tick of ``tree`` that reached the uids ``reached``: the whole tree if it
        reads at the size the panel draws it, else only what the tick reached, the rest folded. Its
        graph is logged when the drawing changed (the same drawing with other uids only re-indexes)."""
        if self._whole is None or self._whole.tree is not tree:
            self._whole = TreeView.of(tree, self._phrases, lang=self._lang)
            self._folded = {}
        view = self._whole
        if view.scale < READABLE:
            view = self._folded.get(reached) or self._folded.setdefault(
                reached, TreeView.of(tree, self._phrases, reached=reached, lang=self._lang))
        shown = self._run_view
        if shown is None or (shown.labels, shown.edges) != (view.labels, view.edges):
            self._log_graph("tree/graph", view)
        self._run_view = view
        return view

    def on_tick(self, tree: Node, result: TickResult) -> None:
        """Each tick is a moment of its own: the run view coloured by it, cleared at the next moment
        that is no tick."""
        self._moment(self._moments.tick())
        view = self._running(tree, frozenset(uid for uid, _ in result.trace))
        self._coloured = True
        statuses = result.statuses()
        trace = [(view.index[uid], status.name) for uid, status in result.trace if uid in view.index]
        action = result.action or ""
        self._queue("tree/graph", tick_columns,
                    (view.colours(statuses), view.marked_labels(statuses), result.status.name, action,
                     self._generation, [i for i, _ in trace], [view.names[i] for i, _ in trace],
                     [s for _, s in trace]))

    # --- the world --------------------------------------------------------------------------

    def on_state(self, state: Mapping[str, bool], action: str | None) -> None:
        """Logged when the state or the action changes (the viewer holds a value until the next); a
        demonstration's action starting to move opens its moment."""
        self._moment(self._moments.action(action))
        names = list(state)
        values = [bool(state[n]) for n in names]
        key = (tuple(names), tuple(values), action)
        if key == self._last_state:
            return
        self._last_state = key
        self._log("state", rr.TextDocument(state_document(names, values, action), media_type=rr.MediaType.MARKDOWN),
                  *([rr.Scalars(np.asarray(values, dtype=np.float64))] if values else []),
                  plain_values(conditions=names or None, values=values or None, action=action or ""), flush=False)

    def on_external(self, name: str) -> None:
        self._moment(self._moments.action(f"external {name}"))  # the line that reports it joins its moment
        self._log("state/external", rr.TextLog(f"external action: {name}", level="EXTERNAL"),
                  plain_values(external=name))
        self._learner_panel(f"external action: {name}")

    def on_scene(self, shapes: Seq[SceneShape]) -> None:
        sim_time = self._clock[2]
        if not self._due(sim_time, self._last_scene, self._scene_period):
            return
        self._last_scene = sim_time
        geometry = tuple((s.name, s.kind, s.size, s.rgba) for s in shapes)
        positions = np.array([s.pos for s in shapes], dtype=np.float32).reshape(-1, 3)
        rotations = np.array([s.quat for s in shapes], dtype=np.float32).reshape(-1, 4)
        if geometry == self._scene_geometry and self._scene_columns is not None:
            self._queue("scene", self._scene_columns, (positions, rotations))
            return
        # the shapes changed: everything about them once, then poses alone (a seventh of the cost)
        layout = SceneLayout.of(geometry)
        self._flush("scene")
        for kind in sorted({g[1] for g in self._scene_geometry} - layout.kinds.keys()):
            self._log(SHAPE_ENTITIES[kind], rr.Clear(recursive=False), flush=False)
        for kind, index in layout.kinds.items():
            where, xyzw = layout.poses(kind, positions[None], rotations[None])
            self._log(SHAPE_ENTITIES[kind], shape_batch(kind, [geometry[i] for i in index], where, xyzw),
                      flush=False)
        self._scene_geometry, self._scene_columns = geometry, layout.columns

    def on_camera(self, image: Any, camera: str = "robot") -> None:
        sim_time = self._clock[2]
        if not self._due(sim_time, self._last_camera.get(camera), self._camera_period):
            return
        if sim_time is not None:
            self._last_camera[camera] = sim_time
        jpeg = io.BytesIO()  # Pillow directly: a third of the time of rerun's Image(...).compress()
        PIL.Image.fromarray(np.ascontiguousarray(image, dtype=np.uint8)).save(jpeg, format="JPEG",
                                                                              quality=self._jpeg_quality)
        self._log(CAMERA_ENTITIES.get(camera, f"{camera}_camera/image"),
                  rr.EncodedImage(contents=jpeg.getvalue(), media_type="image/jpeg"), flush=False)

    @staticmethod
    def _due(now: float | None, last: float | None, period: float) -> bool:
        """Throttle by simulated time; a clock that went back (a reset world) starts afresh."""
        return now is None or last is None or now < last or now - last >= period - 1e-9

    # --- dialogue, demonstrations, learner --------------------------------------------------

    def _dialogue(self, kind: str, speaker: str, shown: str, level: str, *, text: str = "",
                  budget_left: int | None = None, question: str = "", answer: str = "", change: str = "") -> None:
        if kind != "answer":  # an answer is the teacher's line just logged: it shares its moment
            self._moment(self._moments.line(speaker == "teacher"))
        self._log("dialogue", rr.TextLog(shown, level=level),
                  plain_values(kind=kind, speaker=speaker, text=text,
                               budget_left=-1 if budget_left is None else budget_left,
                          question=question, answer=answer, change=change))

    def on_dialogue(self, speaker: str, text: str, budget_left: int | None = None) -> None:
        shown = text if budget_left is None else f"{text}  [questions left: {budget_left}]"
        self._dialogue("line", speaker, shown, speaker, text=text, budget_left=budget_left)
        self._transcript(speaker, text)

    def _transcript(self, speaker: str, text: str) -> None:
        self._log("dialogue/transcript", rr.TextDocument(self._panels.line(self._moments.now, speaker, text),
                                                         media_type=rr.MediaType.MARKDOWN))

    def on_question(self, question: str, budget_left: int) -> None:
        self._dialogue("question", "robot", f"{question}  [questions left: {budget_left}]", "question",
                       text=question, budget_left=budget_left, question=question)
        self._transcript("robot", f"{question} (questions left: {budget_left})")
        self._log("study/questions_asked", rr.TextDocument(self._panels.question(self._moments.now, question,
                                                                                 budget_left),
                                                           media_type=rr.MediaType.MARKDOWN))

    def on_answer(self, question: str, answer: str, change: str) -> None:
        shown = f"{answer}  → {change}" if change else answer
        self._dialogue("answer", "teacher", shown, "answer", text=answer, question=question, answer=answer,
                       change=change)
        self._questions += 1
        self._log("study/questions", rr.TextLog(f"{self._questions}. {question} → {answer}: {change or '—'}",
                                                level="question"))
        self._log("study/questions_answered", rr.Scalars(float(self._questions)))
        self._log("study/questions_asked", rr.TextDocument(self._panels.answer(answer, change),
                                                           media_type=rr.MediaType.MARKDOWN))

    def on_demonstration(self, name: str, demo: Demonstration, domain: Domain) -> None:
        from teach.demos import format_demonstration

        labels = [step_label(s.action, domain) for s in demo.steps]
        states = ["".join("1" if v else "0" for v in s.state) for s in demo.steps]
        robot = [domain.action(a).name for a in demo.actions]
        ending = "goal reached" if demo.reached_goal else "no goal line"
        self._log("demos", rr.TextLog(f"demonstration {name}: {' → '.join(robot) or '(no actions)'} ({ending})",
                                      level="demonstration"),
                  plain_values(name=name, conditions=list(domain.condition_names), states=states,
                          step_actions=[s.action for s in demo.steps], step_labels=labels,
                          reached_goal=demo.reached_goal, csv=format_demonstration(demo)))
        self._log("demos/table", rr.TextDocument(demonstration_document(name, domain, states, labels),
                                                 media_type=rr.MediaType.MARKDOWN))
        self._learner_panel(f"demonstration {name}: {' → '.join(robot) or '(no actions)'} ({ending})")

    def on_learner(self, event: str, detail: str, removed: Seq[str] = (), learner: str = "") -> None:
        text = (f"{learner} · " if learner else "") + f"{event}: {detail}" + (
            f" (removed {', '.join(removed)})" if removed else "")
        self._log("learner/events", rr.TextLog(text, level=event),
                  plain_values(event=event, detail=detail, removed=list(removed) or None, learner=learner or None))
        self._learner_panel(text)

    def on_session_event(self, event: SessionEvent) -> None:
        """The journal's events at their moment, with their fields as the journal holds them."""
        fields = json.dumps(dataclasses.asdict(event), sort_keys=True, ensure_ascii=False)
        self._log("session/events", rr.TextLog(f"{event.kind}: {fields}", level=event.kind),
                  plain_values(kind=event.kind, fields=fields))

    def on_replay(self, reproduced: int, total: int, lenient: bool = False) -> None:
        mode = "lenient" if lenient else "strict"
        self._log("learner/replay", rr.TextLog(f"replay: reproduced {reproduced}/{total} ({mode})", level="replay"),
                  plain_values(reproduced=reproduced, total=total, lenient=lenient))
        if isinstance(reproduced, int) and isinstance(total, int) and total:  # an observer never fails the session
            self._log("study/reproduced_share", rr.Scalars(reproduced / total))
        self._learner_panel(f"replay: reproduced {reproduced}/{total} ({mode})")

    def _log_at(self, moment: tuple[int, int], entity: str, value: float) -> None:
        """A scalar at an earlier (step, moment)."""
        self._flush()
        self._rec.send_columns(entity, indexes=[rr.TimeColumn("step", sequence=[moment[0]]),
                                                rr.TimeColumn("tick", sequence=[moment[1]])],
                               columns=rr.Scalars.columns(scalars=[value]))

    def on_run_start(self, tree: Node) -> None:
        self._moments.run_starts()
        self._run_started = (self._clock[1], self._moments.now)
        self._running(tree, frozenset({tree.uid}))  # before its first tick a large tree is its root
        number = sum(self._runs.values()) + 1
        self._log("study/runs", rr.TextLog(f"run {number} starts (generation {self._generation})", level="run"),
                  plain_values(run=number))

    def on_run_end(self, outcome: str, actions: int) -> None:
        """The run's outcome, a count per outcome so far, at the moment after its last tick: the run
        view goes idle and the state panel's running action is cleared there (the viewer would hold
        the last tick's until the next)."""
        self._moment(self._moments.run_ends())
        if outcome not in self._runs:  # a count that starts from 0 where the first run started, drawn as steps
            self._log(f"study/run_outcomes/{outcome}", rr.SeriesLines(names=outcome, interpolation_mode="StepAfter"),
                      static=True)
            self._log_at(self._run_started, f"study/run_outcomes/{outcome}", 0.0)
        self._runs[outcome] = self._runs.get(outcome, 0) + 1
        runs = sum(self._runs.values())
        self._log("study/runs", rr.TextLog(f"run {runs}: {outcome} after {actions} actions", level=outcome),
                  plain_values(run=runs, outcome=outcome, run_actions=actions))
        for name, count in sorted(self._runs.items()):
            self._log(f"study/run_outcomes/{name}", rr.Scalars(float(count)))
        self._clear_running()

    def _clear_running(self) -> None:
        """Nothing runs any more: the state panel must not keep the last action."""
        if self._last_state is not None and self._last_state[2]:
            names, values, _action = self._last_state
            self.on_state(dict(zip(names, values, strict=True)), None)

    def checkpoint(self) -> None:
        """Write what is queued to the file now, so a killed session keeps it."""
        if not self._closed:
            self._flush()
            self._rec.flush()

    def close(self) -> None:
        """Flush, finish the file (rerun writes its footer on disconnect) and move it into place."""
        if self._closed:
            return
        self._flush()
        self._closed = True
        atexit.unregister(self.close)
        self._rec.flush()
        self._rec.disconnect()
        if self._earlier:
            merge_into_place(self.path, self._part, self._earlier)
        else:
            os.replace(self._part, self.path)

    def abandon(self) -> None:
        """Stop without keeping anything of this run (a session that failed to open): the
        recording on disk stays exactly as it was."""
        if self._closed:
            return
        self._closed = True
        atexit.unregister(self.close)
        self._rec.disconnect()
        self._part.unlink(missing_ok=True)
        put_back(self.path, self._part, self._earlier)

    def __enter__(self) -> RerunLogger:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.close()
