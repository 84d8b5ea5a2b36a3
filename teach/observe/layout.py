"""Where things go in a teach recording: its application id, its default file name and the
viewer layout it opens with."""

from __future__ import annotations

from pathlib import Path

import rerun.blueprint as rrb

APPLICATION_ID = "teach"
RECORDINGS = Path("recordings")

COLUMN_SHARES = (3, 8, 4)  # cameras and scene; the two trees; dialogue, documents and plots
TREE_SHARES = (3, 2)  # the tree that ran above the current generation
# the two tree views of a 1600x900 viewer in pixels (about 830 of its height hold views, each
# with a title bar): the trees' labels are wrapped for these, so they are drawn as large as they can be
_TREE_WIDTH = 1600.0 * COLUMN_SHARES[1] / sum(COLUMN_SHARES) - 16
_TREE_HEIGHT = 830.0 - 2 * 26
RUN_TREE_PANEL = (_TREE_WIDTH, _TREE_HEIGHT * TREE_SHARES[0] / sum(TREE_SHARES))
GENERATION_PANEL = (_TREE_WIDTH, _TREE_HEIGHT * TREE_SHARES[1] / sum(TREE_SHARES))


def default_recording_path(session_name: str) -> Path:
    """``recordings/<session>.rrd``, with characters a file name should not carry replaced."""
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in session_name).strip(".") or "session"
    return RECORDINGS / f"{safe}.rrd"


def blueprint() -> rrb.Blueprint:
    """What a reviewer looks at first: the two trees in the middle (the tree that ran, coloured by
    the tick under the time cursor, above the current generation), the cameras and the state (the
    3D scene in its tab) on the left, the dialogue above the questions asked (the learner's events,
    the legend, the runs, ticks and study plots in their tabs) on the right. Time is the ``tick`` timeline (one
    moment per tick, demonstration step and line); a live viewer follows the session and a
    recording opens at its last moment (the last generation beside the last run's tree)."""
    logs = rrb.TextLogColumns(timeline_columns=["tick"], text_log_columns=["body", "loglevel"])
    return rrb.Blueprint(
        rrb.Horizontal(
            rrb.Vertical(rrb.Spatial2DView(name="Camera", origin="camera"),
                         rrb.Spatial2DView(name="Robot camera", origin="robot_camera"),
                         rrb.Tabs(rrb.TextDocumentView(name="State", origin="state"),
                                  rrb.Spatial3DView(name="Scene", origin="scene"))),
            rrb.Vertical(rrb.GraphView(name="Tree that ran (coloured at each tick)", origin="tree/graph"),
                         rrb.GraphView(name="Current generation (what the robot learned)", origin="tree/generation"),
                         row_shares=list(TREE_SHARES)),
            rrb.Vertical(rrb.TextDocumentView(name="Dialogue", origin="dialogue/transcript"),
                         rrb.Tabs(rrb.TextDocumentView(name="Questions asked", origin="study/questions_asked"),
                                  rrb.TextDocumentView(name="Learner and events", origin="learner/document"),
                                  rrb.TextDocumentView(name="Legend", origin="legend"),
                                  rrb.TextLogView(name="Runs", origin="study/runs", columns=logs),
                                  rrb.TextLogView(name="Ticks", origin="tree/graph", columns=logs),
                                  rrb.TimeSeriesView(name="Tree size", origin="study/tree_size"),
                                  rrb.TimeSeriesView(name="Reproduced", origin="study/reproduced_share"),
                                  rrb.TimeSeriesView(name="Run outcomes", origin="study/run_outcomes"),
                                  rrb.TimeSeriesView(name="Questions", origin="study/questions_answered"),
                                  rrb.TimeSeriesView(name="State over time", origin="state"),
                                  rrb.TextDocumentView(name="Tree XML", origin="tree/xml"),
                                  rrb.TextDocumentView(name="Demonstration", origin="demos/table"),
                                  rrb.TextDocumentView(name="Domain", origin="domain")),
                         row_shares=[1, 2]),  # the questions, each in full, need the room
            column_shares=list(COLUMN_SHARES)),
        rrb.TimePanel(timeline="tick", state="collapsed", play_state="following"),
        collapse_panels=True,
    )
