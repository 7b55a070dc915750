"""What every figure module shares: the palette, the plotly template, the title style, the
round-off level below which a value is drawn as zero, and a few drawing helpers.

plotly is imported inside :func:`plotly_go` and :func:`make_subplots` only, when a figure
is built, so that importing the figure modules stays cheap (the command line's ``analyze``
never loads plotly).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...results import ROUND_OFF, below_round_off, engine_scales

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.model import EngineModel

Quantity = Literal["force", "moment"]

#: colours used consistently across figures
COLORS = {
    "forward": "#1f77b4",
    "backward": "#ff7f0e",
    "total": "#222222",
    "rotating": "#9467bd",
    "after": "#d62728",
    "before": "#7f7f7f",
    "counterweight": "#2ca02c",
    "shaft1": "#17becf",
    "shaft2": "#bcbd22",
    "crank": "#555555",
}
ORDER_COLORS = [
    "#1f77b4",
    "#ff7f0e",
    "#2ca02c",
    "#d62728",
    "#9467bd",
    "#8c564b",
    "#e377c2",
    "#7f7f7f",
    "#bcbd22",
    "#17becf",
]
TEMPLATE = "plotly_white"


def plotly_go() -> Any:
    """``plotly.graph_objects``, imported on first use."""
    import plotly.graph_objects as go

    return go


def make_subplots(**kwargs: Any) -> go.Figure:
    """``plotly.subplots.make_subplots(**kwargs)``, plotly imported on first use."""
    from plotly import subplots

    return subplots.make_subplots(**kwargs)


def roundoff_levels(model: EngineModel, relative: float = ROUND_OFF) -> tuple[float, float]:
    """Round-off levels of an engine's forces [N] and moments [N·m], the one rule of
    :func:`crankbalance.results.round_off` (its scales, its share); the figures call that
    directly, this name stays for the web's callers (``web/tab_results.py``)."""
    force, length = engine_scales(model)
    return float(relative * force), float(relative * force * length)


def zero_below(values: ArrayLike, tiny: float) -> NDArray[np.float64]:
    """``values`` as floats, those at most ``tiny`` in magnitude set to exactly 0 (round-off
    drawn as zero, not as a bar of 1e-12 N; :func:`crankbalance.results.below_round_off`)."""
    return below_round_off(np.asarray(values, dtype=float), tiny)


#: longest engine name shown under a figure title (longer names end in "…")
TITLE_NAME_CHARS = 70


def figure_title(main: str, engine: str | None = None, note: str | None = None) -> str:
    """A figure title that fits a half-width web panel: what the figure shows on the first
    line, the engine name (shortened to :data:`TITLE_NAME_CHARS`) and a note on a second
    line in smaller type."""
    second = []
    if engine:
        name = " ".join(str(engine).split())
        if len(name) > TITLE_NAME_CHARS:
            name = name[: TITLE_NAME_CHARS - 1].rstrip(" ,;:-") + "…"
        second.append(name)
    if note:
        second.append(note)
    if not second:
        return main
    return f"{main}<br><sup>{' · '.join(second)}</sup>"


def note_if_zero(
    fig: go.Figure, values: ArrayLike, unit: str, row: int, col: int, ref: str
) -> None:
    """Say so in a subplot whose bars are all exactly zero (instead of an empty -1..1 axis)."""
    if np.any(np.asarray(values, dtype=float) != 0.0):
        return
    fig.update_yaxes(range=[0, 1], row=row, col=col)
    fig.add_annotation(
        text=f"0 {unit} everywhere<br>(balanced)",
        showarrow=False,
        xref=f"x{ref} domain",
        yref=f"y{ref} domain",
        x=0.5,
        y=0.5,
        font={"size": 14, "color": COLORS["before"]},
    )


def web_drawing(fig: go.Figure, reach: float, title: str) -> go.Figure:
    """Finish a to-scale drawing of one crank web seen along the crank axis (the
    counterweight profile, the drilling plan): the crank axis marked at the origin, x and
    y in mm on equal scales over ``[-reach, reach]``, the legend below.

    Parameters
    ----------
    fig : plotly.graph_objects.Figure
        The drawing, its traces in mm; changed in place.
    reach : float
        Half the width and height of the drawn square [mm].
    title : str
        Title of the figure.

    Returns
    -------
    plotly.graph_objects.Figure
        ``fig``.
    """
    fig.add_trace(
        plotly_go().Scatter(
            x=[0.0],
            y=[0.0],
            mode="markers",
            name="crank axis",
            marker={"color": "black", "size": 10, "symbol": "cross-thin", "line": {"width": 2}},
        )
    )
    fig.update_xaxes(title_text="x [mm]", range=[-reach, reach])
    fig.update_yaxes(title_text="y [mm]", range=[-reach, reach], scaleanchor="x", scaleratio=1)
    fig.update_layout(template=TEMPLATE, legend={"orientation": "h", "y": -0.2}, title=title)
    return fig
