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


def blueprint() -> rrb.Blueprint:
    """Scene and camera, tree graph, state, dialogue: the layout the viewer opens with."""
    return rrb.Blueprint(
        rrb.Horizontal(
            rrb.Vertical(rrb.Spatial3DView(name="Scene", origin="scene"),
                         rrb.Spatial2DView(name="Camera", origin="camera"), row_shares=[3, 2]),
            rrb.Vertical(rrb.GraphView(name="Behaviour tree", origin="tree/graph"),
                         rrb.Tabs(rrb.TextDocumentView(name="State", origin="state"),
                                  rrb.TimeSeriesView(name="State over time", origin="state"),
                                  rrb.TextDocumentView(name="Tree XML", origin="tree/xml"),
                                  rrb.TextDocumentView(name="Demonstration", origin="demos/table"),
                                  rrb.TextDocumentView(name="Domain", origin="domain")),
                         row_shares=[3, 2]),
            rrb.Vertical(rrb.TextLogView(name="Dialogue", origin="dialogue"),
                         rrb.TextLogView(name="Learner and events",
                                         contents=["learner/**", "demos", "state/external"]),
                         rrb.TextLogView(name="Ticks", origin="tree/graph"), row_shares=[3, 2, 1]),
            column_shares=[3, 3, 2]),
        rrb.TimePanel(timeline="step"),
        collapse_panels=True,
    )
