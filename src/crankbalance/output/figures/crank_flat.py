"""The 3-D crank (:func:`crankbalance.output.figures.crank3d.crank_3d`) drawn flat, seen from
three sides, for print: a WebGL scene does not print from a browser, plotly's 2-D traces
(SVG) do.

:func:`crank_views` takes the 3-D figure's own traces (lines and markers in mm, the scene's
x the crank axis y, its y the engine's x, its z the engine's z) and draws each in three
orthographic views side by side, with equal scales on both axes of a view:

- *side*: the crank axis y across, z up (the 3-D view's default look, from the front);
- *top*: the crank axis y across, x up;
- *end*: x across, z up, looking along the crank axis (the throws' star and the
  counterweights' directions).

Nothing is computed here: every point is one of the 3-D figure's, so both drawings agree.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .common import TEMPLATE, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.model import EngineModel
    from ...studies.engine import Analysis, BalanceStudy

#: the three views: (subplot title, the 3-D trace's coordinate across, the one up)
VIEWS: tuple[tuple[str, str, str], ...] = (
    ("side: crank axis y across, z up", "x", "z"),
    ("top: crank axis y across, x up", "x", "y"),
    ("end: along the crank axis, x across, z up", "y", "z"),
)
#: the axis titles of the 3-D trace's coordinates (mm)
AXIS_TITLES = {"x": "y, crank axis [mm]", "y": "x [mm]", "z": "z [mm]"}
#: the title of the figure (the 3-D figure's, with what the drawing is)
TITLE = "Crankshaft at crank angle 0, seen from three sides"


def crank_views(
    model: EngineModel | Analysis | BalanceStudy, balance_study: BalanceStudy | None = None
) -> go.Figure:
    """The 3-D crank of :func:`~crankbalance.output.figures.crank3d.crank_3d` (same
    arguments) as three 2-D orthographic views (side, top, end; lengths in mm), for print."""
    from plotly.subplots import make_subplots

    from .crank3d import crank_3d

    plotly_go()  # plotly installed, or the project's message
    solid = crank_3d(model, balance_study)
    fig = make_subplots(
        rows=1,
        cols=len(VIEWS),
        subplot_titles=[title for title, _, _ in VIEWS],
        horizontal_spacing=0.1,
    )
    go = plotly_go()
    for col, (_, across, up) in enumerate(VIEWS, start=1):
        for trace in solid.data:
            style: dict[str, Any] = {}
            if trace.mode == "lines":
                line = trace.line
                style["line"] = {
                    "color": line.color,
                    "width": max(1.0, (line.width or 2) / 2.5),
                    "dash": line.dash,
                }
            else:
                marker = trace.marker
                style["marker"] = {
                    "color": marker.color,
                    "size": [0.6 * size for size in marker.size or ()] or None,
                    "opacity": marker.opacity,
                }
            fig.add_trace(
                go.Scatter(
                    x=getattr(trace, across),
                    y=getattr(trace, up),
                    mode=trace.mode,
                    name=trace.name,
                    legendgroup=trace.legendgroup,
                    showlegend=bool(trace.showlegend) and col == 1,
                    hoverinfo="skip",
                    **style,
                ),
                row=1,
                col=col,
            )
        suffix = "" if col == 1 else str(col)
        fig.update_xaxes(title_text=AXIS_TITLES[across], row=1, col=col)
        fig.update_yaxes(
            title_text=AXIS_TITLES[up], scaleanchor=f"x{suffix}", scaleratio=1, row=1, col=col
        )
    title = solid.layout.title.text.replace("Crankshaft at crank angle 0", TITLE, 1)
    fig.update_layout(
        template=TEMPLATE,
        title={"text": title},
        height=420,
        legend={"orientation": "h", "y": -0.25},
        margin={"l": 50, "r": 20, "t": 80, "b": 40},
    )
    fig.update_annotations(font_size=12)  # the subplot titles under the figure's title
    return fig
