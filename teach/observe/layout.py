"""Where things go in a teach recording: its application id, its default file name and the
viewer layout it opens with."""

from __future__ import annotations

from pathlib import Path

import rerun.blueprint as rrb

APPLICATION_ID = "teach"
RECORDINGS = Path("recordings")


def default_recording_path(session_name: str) -> Path:
    """``recordings/<session>.rrd``, with characters a file name should not carry replaced."""
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in session_name).strip(".") or "session"
    return RECORDINGS / f"{safe}.rrd"


def blueprint(live: bool = False) -> rrb.Blueprint:
    """What a reviewer looks at first: the room's overview camera (the robot's own camera and the 3D
    scene beside it), the behaviour tree coloured by the selected step, state and study plots,
    and the dialogue with the study's questions and runs: the layout the viewer opens with.
    A live viewer follows the session; a recording opens paused, at the step its URL names."""
    return rrb.Blueprint(
        rrb.Horizontal(
            rrb.Vertical(rrb.Spatial2DView(name="Camera", origin="camera"),
                         rrb.Horizontal(rrb.Spatial2DView(name="Robot camera", origin="robot_camera"),
                                        rrb.Spatial3DView(name="Scene", origin="scene")),
                         row_shares=[3, 2]),
            rrb.Vertical(rrb.GraphView(name="Behaviour tree", origin="tree/graph"),
                         rrb.Tabs(rrb.TextDocumentView(name="State", origin="state"),
                                  rrb.TimeSeriesView(name="Tree size", origin="study/tree_size"),
                                  rrb.TimeSeriesView(name="Reproduced", origin="study/reproduced_share"),
                                  rrb.TimeSeriesView(name="Run outcomes", origin="study/run_outcomes"),
                                  rrb.TimeSeriesView(name="Questions", origin="study/questions_answered"),
                                  rrb.TimeSeriesView(name="State over time", origin="state"),
                                  rrb.TextDocumentView(name="Tree XML", origin="tree/xml"),
                                  rrb.TextDocumentView(name="Demonstration", origin="demos/table"),
                                  rrb.TextDocumentView(name="Domain", origin="domain")),
                         row_shares=[3, 2]),
            rrb.Vertical(rrb.Tabs(rrb.TextLogView(name="Dialogue", origin="dialogue"),
                                  rrb.TextLogView(name="Questions asked", origin="study/questions"),
                                  rrb.TextLogView(name="Runs", origin="study/runs")),
                         rrb.TextLogView(name="Learner and events",
                                         contents=["learner/**", "demos", "state/external"]),
                         rrb.TextLogView(name="Ticks", origin="tree/graph"), row_shares=[3, 2, 1]),
            column_shares=[5, 6, 4]),
        rrb.TimePanel(timeline="step", state="collapsed", play_state="following" if live else "paused"),
        collapse_panels=True,
    )
