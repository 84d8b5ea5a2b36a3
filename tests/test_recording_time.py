"""The quickstart recording's ``tick`` timeline, read back with rerun's own reader: every tick of
a run and every step of a demonstration its own moment, the run view coloured by exactly the
tick under the cursor and grey everywhere else, the recording opening at its end, and the
committed screenshots showing what their captions claim."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from teach.bt.nodes import Status, walk
from teach.bt.xml import read_tree
from teach.cli import main
from teach.observe.moments import Moments
from teach.observe.pictures import Picture, pictures, wrong_at
from teach.observe.reader import RecordingContents, read_recording
from teach.observe.tree_view import IDLE_COLOUR, READABLE, STATUS_COLOURS, layout, panel_scale

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def quickstart_base(tmp_path_factory: pytest.TempPathFactory) -> Path:
    base = tmp_path_factory.mktemp("quickstart")
    assert main(["replay", str(ROOT / "dialogues" / "quickstart.dialogue"), "--base", str(base)]) == 0
    return base


@pytest.fixture(scope="module")
def quickstart(quickstart_base: Path) -> RecordingContents:
    return read_recording(quickstart_base / "recordings" / "quickstart.rrd")


def test_every_tick_is_its_own_moment_and_runs_are_contiguous(quickstart: RecordingContents) -> None:
    moments = [t.moment for t in quickstart.ticks]
    assert None not in moments and len(set(moments)) == len(moments) == 151
    assert moments == sorted(moments)  # type: ignore[type-var]
    for run in quickstart.runs:  # a run's ticks are the moments between its start and its end, one after another
        assert run.started is not None and run.ended is not None
        inside = [m for m in moments if run.started < m < run.ended]  # type: ignore[operator]
        assert inside == list(range(run.started + 1, run.ended))
    assert [r.outcome for r in quickstart.runs] == ["success", "interrupted"]


def test_the_run_view_shows_exactly_the_tick_under_the_cursor(quickstart: RecordingContents) -> None:
    """Walk every moment of the recording: at a tick the run view's colours are that tick's
    statuses (grey for nodes it did not tick), at any other moment every node is grey."""
    checked = 0
    for moment in range(quickstart.last_moment + 1):
        colours = quickstart.colours_at(moment)
        tick = quickstart.tick_at(moment)
        if tick is None:
            assert set(colours) <= {IDLE_COLOUR}, f"moment {moment}: colour left from another tick"
            continue
        graph = quickstart.graphs[quickstart.tick_graphs[quickstart.ticks.index(tick)]]
        expected = [IDLE_COLOUR] * len(graph.labels)
        for node, (_label, status) in zip(tick.nodes, tick.trace, strict=True):
            expected[node] = STATUS_COLOURS[Status[status]]
        assert list(colours) == expected, f"moment {moment}"
        running = [i for i, c in enumerate(colours) if c == STATUS_COLOURS[Status.RUNNING] and i not in
                   {parent for parent, _ in graph.edges}]
        assert len(running) == (1 if tick.action else 0)
        checked += 1
    assert checked == len(quickstart.ticks)


def test_the_large_tree_that_ran_is_drawn_readable_at_every_tick(quickstart: RecordingContents,
                                                                  quickstart_base: Path) -> None:
    """The safe learner's run trees (over 300 nodes) would be drawn at a sixth of their size: each
    tick's drawing is the nodes it reached, the rest folded into labelled nodes, readable at
    1600x900, and every node of the tree that ran is drawn or counted in a fold exactly once."""
    sizes = [len(list(walk(read_tree(path)))) for path in sorted((quickstart_base / "trees" / "quickstart")
                                                                   .glob("run-*.xml"))]
    assert len(sizes) == len(quickstart.runs) and min(sizes) > 300
    for tick, at in zip(quickstart.ticks, quickstart.tick_graphs, strict=True):
        run = next(number for number, r in enumerate(quickstart.runs)
                   if r.started is not None and r.ended is not None and r.started < tick.moment < r.ended)
        graph = quickstart.graphs[at]
        kids: list[list[int]] = [[] for _ in graph.labels]
        for parent, child in graph.edges:
            kids[parent].append(child)
        assert panel_scale(layout(kids, list(graph.labels)), list(graph.labels)) >= READABLE
        folds = [int(label.split()[1]) for label in graph.labels if label.startswith("… ")]
        assert len(graph.labels) - len(folds) + sum(folds) == sizes[run] and folds
        assert not set(tick.nodes) & {i for i, label in enumerate(graph.labels) if label.startswith("… ")}


def test_each_demonstration_step_and_line_is_a_moment(quickstart: RecordingContents) -> None:
    said = [d.moment for d in quickstart.dialogue if d.kind == "line" and d.speaker == "teacher"]
    assert len(set(said)) == len(said)  # no two lines of the teacher share a moment
    steps = [d for d in quickstart.dialogue if d.text.startswith("✓ ")]
    assert len(steps) == 15 and len({d.moment for d in steps}) == 15
    # in MuJoCo a step's moment is opened by its action moving: the state panel shows it running there
    for line in steps:
        running = {s.action for s in quickstart.states if s.moment == line.moment and s.action}
        assert len(running) == 1, line
    # a generation sits at the moment of the line that made it ('done', the answer's thanks), never at a tick
    lines = {d.moment for d in quickstart.dialogue}
    ticks = {t.moment for t in quickstart.ticks}
    assert all(g.moment in lines and g.moment not in ticks for g in quickstart.generations)


def test_the_recording_opens_following_its_tick_timeline(quickstart: RecordingContents) -> None:
    from rerun.chunk import RrdReader

    reader = RrdReader(quickstart.path)
    panel = [chunk for chunk in reader.stream(store=reader.blueprints()[0]).to_chunks()
             if chunk.entity_path == "/time_panel"]
    columns = {name: chunk.to_record_batch().column(name).to_pylist() for chunk in panel
               for name in chunk.to_record_batch().schema.names if name.startswith("TimePanelBlueprint:")}
    assert columns["TimePanelBlueprint:timeline"] == [["tick"]]
    assert columns["TimePanelBlueprint:play_state"] == [[3]]  # following: the viewer goes to the last moment


def test_moments_rules() -> None:
    moments = Moments()
    assert moments.line(teacher=True) and moments.now == 1
    assert moments.action("FindBall") and not moments.line(teacher=False)  # the step's line joins its action
    assert not moments.action("FindBall") and moments.action("ApproachBall") and moments.now == 3
    assert moments.line(teacher=True) and moments.now == 4
    moments.run_starts()
    assert moments.tick() and not moments.line(teacher=False) and not moments.action("X") and moments.tick()
    assert moments.run_ends() and moments.now == 7


def test_each_committed_screenshot_shows_what_its_caption_claims(quickstart: RecordingContents) -> None:
    """docs/screenshots/pictures.json names each picture's moment (``make screenshots`` took it
    where the viewer's own state read back that moment): the replayed recording shows there what
    the caption says (the grasp picture where GraspBall runs, the end with the run view grey)."""
    listing = json.loads((ROOT / "docs" / "screenshots" / "pictures.json").read_text())
    assert set(listing) == {p.name for p in pictures(quickstart)}
    for name, taken in listing.items():
        picture = Picture(name, taken["moment"], taken["caption"])
        assert wrong_at(quickstart, picture) is None
        assert picture.caption == next(p.caption for p in pictures(quickstart) if p.name == name)
        assert (ROOT / "docs" / "screenshots" / f"{name}.png").stat().st_size > 50_000


def test_a_picture_at_another_moment_is_refused(quickstart: RecordingContents) -> None:
    grasp = next(p for p in pictures(quickstart) if p.name == "grasp")
    found = next(t for t in quickstart.ticks if t.action == "FindBall")
    assert found.moment is not None
    wrong = wrong_at(quickstart, Picture("grasp", found.moment, grasp.caption))
    assert wrong is not None and "the recording's is" in wrong
    end = next(p for p in pictures(quickstart) if p.name == "end")
    assert wrong_at(quickstart, Picture("end", grasp.moment, end.caption)) is not None
