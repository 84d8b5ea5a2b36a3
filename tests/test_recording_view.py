"""What the viewer's screenshots depend on, checked without a browser: the blueprint's views, the
tree graph's colours and labels at a step, the layout, the camera and study entities, all read
back from real ``.rrd`` files with rerun's own reader."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from conftest import colledanchise_tree

from teach.bt.nodes import Action, Condition, Fallback, Sequence, Status, walk
from teach.bt.tick import tick_state
from teach.bt.xml import tree_to_xml
from teach.domain import Domain
from teach.observe.reader import read_recording
from teach.observe.rerun_writer import RerunLogger
from teach.observe.tree_view import (
    CHAR_WIDTH,
    IDLE_COLOUR,
    NODE_PADDING,
    RUNNING_MARK,
    STATUS_COLOURS,
    TreeView,
    panel_scale,
    phrases,
)


def _chunks(path: Path, blueprint: bool = False) -> list[Any]:
    from rerun.chunk import RrdReader

    reader = RrdReader(path)
    store = (reader.blueprints() if blueprint else reader.recordings())[0]
    return list(reader.stream(store=store).to_chunks())


def _rows(path: Path, entity: str) -> list[dict[str, Any]]:
    rows = []
    for chunk in _chunks(path):
        if chunk.entity_path == entity:
            batch = chunk.to_record_batch()
            names = [n for n in batch.schema.names if n != "log_time"]
            columns = {n: batch.column(n).to_pylist() for n in names}
            rows += [{n: columns[n][i] for n in names} for i in range(batch.num_rows)]
    return sorted(rows, key=lambda row: row["rerun.controls.RowId"])  # row ids increase in logging order


def _rgb(packed: int) -> tuple[int, int, int]:
    return (packed >> 24) & 255, (packed >> 16) & 255, (packed >> 8) & 255


def _session(path: Path, ball: Domain, lang: str = "en") -> None:
    """Two steps of a run: at step 1 the robot looks for the ball, at step 2 it approaches it; then
    the run ends. Both cameras send an image."""
    tree = colledanchise_tree()
    names = ball.condition_names
    logger = RerunLogger(path, "view", lang=lang)
    logger.set_time(0, 0.0)
    logger.on_domain(ball)
    logger.on_tree(1, tree, tree_to_xml(tree), "learned")
    logger.on_replay(1, 2)
    logger.on_answer("What should I do?", "find the ball", "I changed what I do in some situations.")
    logger.on_run_start(tree)
    for step, true in ((1, ()), (2, ("BallFound",))):
        logger.set_time(step, float(step))
        state = ball.state(true)
        result = tick_state(tree, names, state)
        logger.on_tick(tree, result)
        logger.on_state(dict(zip(names, state, strict=True)), result.action)
        logger.on_camera(np.full((36, 48, 3), 90, dtype=np.uint8), "overview")
        logger.on_camera(np.full((24, 32, 3), 40, dtype=np.uint8))
    logger.on_run_end("interrupted", 2)
    logger.close()


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory, ball: Domain) -> Path:
    path = tmp_path_factory.mktemp("view") / "view.rrd"
    _session(path, ball)
    return path


def test_the_blueprint_shows_cameras_trees_documents_and_study_plots(recorded: Path) -> None:
    views = set()
    for chunk in _chunks(recorded, blueprint=True):
        batch = chunk.to_record_batch()
        if chunk.entity_path.startswith("/view/") and "ViewBlueprint:class_identifier" in batch.schema.names:
            for kind, name, origin in zip(*(batch.column(f"ViewBlueprint:{c}").to_pylist()
                                             for c in ("class_identifier", "display_name", "space_origin")),
                                          strict=True):
                views.add((kind[0], name[0], origin[0]))
    for expected in [("2D", "Camera", "camera"), ("2D", "Robot camera", "robot_camera"),
                     ("3D", "Scene", "scene"), ("Graph", "Tree that ran (coloured at each tick)", "tree/graph"),
                     ("Graph", "Current generation (what the robot learned)", "tree/generation"),
                     ("TextDocument", "Dialogue", "dialogue/transcript"),
                     ("TextDocument", "Questions asked", "study/questions_asked"),
                     ("TextDocument", "Learner and events", "learner/document"),
                     ("TextDocument", "Legend", "legend"),
                     ("TimeSeries", "Tree size", "study/tree_size"),
                     ("TimeSeries", "Reproduced", "study/reproduced_share"),
                     ("TimeSeries", "Run outcomes", "study/run_outcomes"),
                     ("TextLog", "Runs", "study/runs"), ("TextLog", "Ticks", "tree/graph")]:
        assert expected in views


def test_the_graph_is_coloured_and_labelled_at_each_step(recorded: Path, ball: Domain) -> None:
    tree = colledanchise_tree()
    view = TreeView.of(tree, phrases(ball, "en"))
    nodes = list(walk(tree))
    rows = _rows(recorded, "/tree/graph")
    ticks = {row["step"]: row for row in rows if row.get("GraphNodes:colors") and row.get("status")}
    assert sorted(ticks) == [1, 2]
    for step, running, failed in ((1, "FindBall", "BallFound"), (2, "ApproachBall", "BallClose")):
        colours = [_rgb(c) for c in ticks[step]["GraphNodes:colors"]]
        labels = ticks[step]["GraphNodes:labels"]
        assert len(colours) == len(labels) == len(nodes)
        action = next(i for i, n in enumerate(nodes) if isinstance(n, Action) and n.name == running)
        condition = next(i for i, n in enumerate(nodes) if isinstance(n, Condition) and n.name == failed)
        assert colours[action] == STATUS_COLOURS[Status.RUNNING]
        assert labels[action] == RUNNING_MARK + view.labels[action]
        assert colours[condition] == STATUS_COLOURS[Status.FAILURE]
        assert colours[0] == STATUS_COLOURS[Status.RUNNING]  # the root keeps running
        assert IDLE_COLOUR in colours  # the nodes after the running action were not ticked
        assert sum(label.startswith(RUNNING_MARK) for label in labels) == 1
    found = next(i for i, n in enumerate(nodes) if isinstance(n, Condition) and n.name == "BallFound")
    assert _rgb(ticks[2]["GraphNodes:colors"][found]) == STATUS_COLOURS[Status.SUCCESS]


def test_a_folded_view_draws_what_a_tick_reached_and_counts_the_rest(ball: Domain) -> None:
    """Runs of siblings the tick did not reach become one node labelled with their size (in the
    session's language); a lone leaf stays itself; only drawn nodes are indexed."""
    grasp = Sequence((Condition("BallClose"), Action("GraspBall")))
    tree = Fallback((Condition("BallPlaced"), Sequence((Condition("BallFound"), Action("ApproachBall"))),
                     grasp, Sequence((Condition("BinClose"), Action("PlaceBall"))), Action("FindBall")))
    root, placed, approach = tree, tree.children[0], tree.children[1]
    reached = {root.uid, placed.uid, approach.uid, *(n.uid for n in approach.children)}
    view = TreeView.of(tree, phrases(ball, "de"), reached=reached, lang="de")
    assert view.labels[-1] == "… 7 Knoten" and len(view.labels) == 6
    assert view.edges == [("0", "1"), ("0", "2"), ("0", "5"), ("2", "3"), ("2", "4")]
    assert set(view.index) == reached and view.index[approach.children[1].uid] in view.actions
    lone = TreeView.of(tree, reached={root.uid, placed.uid, approach.uid, grasp.uid, *(n.uid for n in grasp.children),
                                      tree.children[3].uid, *(n.uid for n in tree.children[3].children)})
    assert lone.labels[-1] == "FindBall" and "… 2 nodes" in lone.labels  # approach's two children folded
    assert TreeView.of(tree).labels == TreeView.of(tree, reached={n.uid for n in walk(tree)}).labels


def test_labels_are_the_sessions_language(tmp_path: Path, ball: Domain) -> None:
    path = tmp_path / "de.rrd"
    _session(path, ball, lang="de")
    graph = next(row for row in _rows(path, "/tree/graph") if row.get("GraphNodes:node_ids"))
    labels = [label.replace("\n", " ") for label in graph["GraphNodes:labels"]]
    assert "Ball finden" in labels
    assert "ich sehe den Ball?" in labels
    assert not any("find the ball" in label for label in labels)
    assert graph["GraphNodes:positions"] is not None and graph["GraphNodes:show_labels"] == [True]
    # the legend explains the symbols and colours in the session's language
    legend = next(row for row in _rows(path, "/legend"))["TextDocument:text"][0]
    assert "`?` | Fallback" in legend and "`→` | Sequenz" in legend and "nicht getickt" in legend
    english = next(row for row in _rows(recorded_en(tmp_path, ball), "/legend"))["TextDocument:text"][0]
    assert "`?` | fallback" in english and "not ticked" in english


def recorded_en(tmp_path: Path, ball: Domain) -> Path:
    path = tmp_path / "en.rrd"
    _session(path, ball)
    return path


def test_counts_are_drawn_as_steps_from_zero(recorded: Path) -> None:
    """The tree size and the questions answered are whole numbers: drawn as steps (not sloping
    lines) from a first point at 0, so the plot's axis runs over whole nodes and questions;
    each run outcome's count starts from 0 where its first run started."""
    for entity in ("/study/tree_size", "/study/questions_answered", "/study/run_outcomes/interrupted"):
        rows = _rows(recorded, entity)
        modes = [row["SeriesLines:interpolation_mode"] for row in rows if row.get("SeriesLines:interpolation_mode")]
        assert modes == [[2]], entity  # StepAfter
        values = [row["Scalars:scalars"][0] for row in rows if row.get("Scalars:scalars")]
        assert values[0] == 0.0 and values == sorted(values) and all(v == int(v) for v in values), entity


def test_the_layout_is_top_down_and_compact_for_35_nodes(ball: Domain) -> None:
    """A 35-node tree: no two boxes on a level overlap, children sit below their parent, and the
    drawing fits the tree panel of a 1600x900 viewer at no less than 0.43 of its size: its 15
    leaves side by side are the widest a top-down tree of this shape gets, so its labels wrap narrow
    (0.43, not 0.45, since the robot speaks of itself: "I can see\nthe ball?" wraps wider than
    "you can\nsee the\nball?")."""
    pairs = [("BallFound", "FindBall"), ("BallClose", "ApproachBall"), ("BallGrasped", "GraspBall"),
             ("BinClose", "ApproachBin"), ("BallPlaced", "PlaceBall")]
    guarded = [Fallback((Condition(c), Sequence((Condition("BallFound"), Condition(c), Action(a)))))
               for c, a in pairs]
    tree = Fallback((Condition("BallPlaced"), Sequence(tuple(guarded)), Condition("BallGrasped"), Action("PlaceBall")))
    nodes = list(walk(tree))
    assert len(nodes) == 35
    view = TreeView.of(tree, phrases(ball, "en"))
    x, y = view.positions[:, 0], view.positions[:, 1]
    for parent, child in view.edges:
        assert y[int(child)] > y[int(parent)]
    widths = [max(map(len, label.split("\n"))) * CHAR_WIDTH + NODE_PADDING for label in view.labels]
    for level in set(y.tolist()):
        row = sorted((x[i] - widths[i] / 2, x[i] + widths[i] / 2) for i in range(len(nodes)) if y[i] == level)
        assert all(left[1] <= right[0] + 1e-3 for left, right in zip(row, row[1:], strict=False))
    assert panel_scale(view.positions, view.labels) >= 0.43  # 0.37 with every leaf wrapped at 14 characters


def test_camera_and_study_entities_are_recorded(recorded: Path) -> None:
    entities = {chunk.entity_path for chunk in _chunks(recorded)}
    assert {"/camera/image", "/robot_camera/image", "/study/tree_size", "/study/reproduced_share",
            "/study/questions", "/study/questions_answered", "/study/runs",
            "/study/run_outcomes/interrupted"} <= entities
    assert read_recording(recorded).camera_frames == 2  # the overview images, the main camera
    runs = [row for row in _rows(recorded, "/study/runs") if row.get("TextLog:text")]
    assert ["run 1: interrupted after 2 actions"] in [row["TextLog:text"] for row in runs]
    share = [row["Scalars:scalars"] for row in _rows(recorded, "/study/reproduced_share")]
    assert share == [[0.5]]


def test_nothing_shows_as_running_after_a_run(recorded: Path) -> None:
    """Neither the state panel nor the graph keeps the last tick's running action once the run ends."""
    contents = read_recording(recorded)
    assert contents.states[-2].action == "ApproachBall"
    assert contents.states[-1].action is None and contents.states[-1].state == contents.states[-2].state
    assert len(contents.ticks) == 2  # the idle graph is no tick
    graph = [row for row in _rows(recorded, "/tree/graph") if row.get("GraphNodes:colors")]
    after_run = [row for row in graph if row["step"] == 2][-1]
    assert {_rgb(c) for c in after_run["GraphNodes:colors"]} == {IDLE_COLOUR}
    assert not any(label.startswith(RUNNING_MARK) for label in after_run["GraphNodes:labels"])


def test_the_overview_camera_sees_ball_and_bin() -> None:
    """The MuJoCo overview camera looks at the room: the orange ball and the green bin are in its image."""
    from teach.sim.world import World

    with World(seed=0) as world:
        image = world.camera_image(400, 300, "overview")
        if image is None:
            pytest.skip("no offscreen OpenGL rendering here")
        robot = world.camera_image(320, 240)
    assert image.shape == (300, 400, 3) and robot is not None and robot.shape == (240, 320, 3)
    r, g, b = (image[..., i].astype(int) for i in range(3))
    ball = (r > 180) & (g > 50) & (g < 150) & (b < 60)
    bin_ = (g > r + 40) & (g > b + 40)
    assert ball.sum() >= 4 and bin_.sum() >= 50


def test_text_panels_keep_whole_messages_newest_first_as_text() -> None:
    from teach.observe.panels import KEEP, Panels

    panels = Panels()
    long = "If the ball is within reach, but you cannot see the ball, " * 4 + "what should I do?"
    panels.line(3, "teacher", "find the ball")
    document = panels.line(4, "robot", f"- I find the ball *first*\n{long}")
    assert document.index("`#4`") < document.index("`#3` **teacher:** find the ball")  # the newest on top
    assert "\\- I find the ball \\*first\\*" in document and long in document  # as text, and whole
    for moment in range(KEEP + 5):
        document = panels.line(10 + moment, "robot", f"line {moment}")
    assert "`#3`" not in document and document.count("robot:") == KEEP  # a panel costs the same at any length
    asked = panels.question(50, "Which one?", 2)
    assert "*not answered yet*" in asked
    assert "→ **left**: I changed it." in panels.answer("left", "I changed it.")
