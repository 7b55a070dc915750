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


#: the smallest span of a figure's value axis, as a share of the largest magnitude on it:
#: the resolution of 5 significant digits (the web page's and the reports'); a curve that varies
#: less (0.0004 % in issue 28) is drawn flat in the middle of that span instead of being
#: stretched over the axis, which drew an "optimum" out of round-off
MIN_SPAN_SHARE = 1e-4
#: the key of a figure's ``layout.meta`` (a dict) that gives the figure a larger minimum span
#: share of its own (:func:`min_span`, read by :func:`value_ranges`)
MIN_SPAN_KEY = "min_span_share"
#: the smallest span of the performance studies' trends over the balance factor, as a share
#: of the largest magnitude on the axis: 1 %, below the accuracy of the friction, bearing and
#: gas-force models behind them (a few per cent); a panel whose line crosses its whole
#: height then always means a change of at least 1 %, and the 0.1-0.15 % spreads of an
#: inline-4's speed fluctuation and peak net torque (issue 28's review) are drawn as the
#: near-flat lines they are instead of a slope with an "optimum"
PERFORMANCE_MIN_SPAN_SHARE = 0.01
#: the note over a figure whose every value is 0 (drawn, but nothing to see): the web's
#: figure cards show it above the plot, :func:`readable` adds it to the figure
ALL_ZERO = "0 everywhere: every value of this figure is zero (nothing left to balance)."
#: 2-D traces whose values are ``y`` (cartesian) or ``r`` (polar)
CARTESIAN = ("scatter", "scattergl", "bar")
POLAR = ("scatterpolar", "barpolar")


def _values(trace: Any) -> Any | None:
    """The finite values of a 2-D trace [its unit], None for any other trace (3-D, maps)."""

    kind = trace.type or "scatter"
    data = trace.y if kind in CARTESIAN else trace.r if kind in POLAR else None
    if data is None:
        return None
    try:
        values = np.asarray(data, dtype=float).ravel()
    except (TypeError, ValueError):  # categories on the value axis
        return None
    return values[np.isfinite(values)]


def _scattered(trace: Any) -> Any | None:
    """The finite ``x`` of a scatter of values (markers only: each point a pair of values,
    e.g. the explorer's candidates over two objectives), None for any other trace (a line
    over an independent variable, bars over categories: their x is not a value)."""
    if (trace.type or "scatter") not in ("scatter", "scattergl") or trace.mode != "markers":
        return None
    try:
        values = np.asarray(trace.x, dtype=float).ravel()
    except (TypeError, ValueError):  # categories
        return None
    return values[np.isfinite(values)]


def all_zero(figure: Any) -> bool:
    """Whether every value of the figure's 2-D traces is 0 (and it has only such traces):
    the ``y`` (or ``r``) of each, and the ``x`` of a scatter of values (markers only,
    :func:`_scattered`), so that candidates at M1 = 1974 N·m and M2 = 0 are not "0
    everywhere"."""
    found = []
    for trace in figure.data:
        values = _values(trace)
        if values is None:
            return False
        found.append(values)
        x = _scattered(trace)
        if x is not None:
            found.append(x)
    return any(v.size for v in found) and all(not v.any() for v in found)


def min_span(fig: go.Figure, share: float) -> go.Figure:
    """Give ``fig`` a minimum span share of its own for its value axes (instead of
    :data:`MIN_SPAN_SHARE`; e.g. :data:`PERFORMANCE_MIN_SPAN_SHARE`), kept in its
    ``layout.meta`` so that every edge applying :func:`value_ranges` uses it; ``fig``
    changed in place and returned."""
    meta = fig.layout.meta if isinstance(fig.layout.meta, dict) else {}
    fig.update_layout(meta={**meta, MIN_SPAN_KEY: share})
    return fig


def span_share(layout: dict[str, Any]) -> float:
    """The minimum span share of a figure's value axes: its own (:func:`min_span`) or
    :data:`MIN_SPAN_SHARE`. ``layout`` is the figure's layout as a dict."""
    meta = layout.get("meta")
    own = meta.get(MIN_SPAN_KEY) if isinstance(meta, dict) else None
    return MIN_SPAN_SHARE if own is None else float(own)


def value_ranges(figure: Any, layout: dict[str, Any] | None = None) -> dict[str, list[float]]:
    """The ranges to give the value axes of ``figure``'s line traces whose values vary by
    less than the figure's minimum span share (:func:`span_share`: :data:`MIN_SPAN_SHARE`
    unless the figure gives its own) of their magnitude (axis key of the layout -> range):
    that span, centred on the values. Axes with bars (their range includes 0), a range or a
    log scale of their own are left as they are. ``layout`` is the figure's layout as a
    dict (by default its own)."""
    if layout is None:
        layout = figure.layout.to_plotly_json()
    share = span_share(layout)

    lines: dict[str, list[Any]] = {}
    bars: set[str] = set()
    for trace in figure.data:
        if (trace.type or "scatter") not in ("scatter", "scattergl"):
            if trace.type == "bar":
                bars.add(f"yaxis{(trace.yaxis or 'y')[1:]}")
            continue
        values = _values(trace)
        if values is not None and values.size:
            lines.setdefault(f"yaxis{(trace.yaxis or 'y')[1:]}", []).append(values)
    out = {}
    for key, parts in lines.items():
        axis = layout.get(key) or {}
        if key in bars or axis.get("range") is not None or axis.get("type") == "log":
            continue
        values = np.concatenate(parts)
        low, high = float(values.min()), float(values.max())
        span = share * max(abs(low), abs(high))
        if span > 0 and high - low < span:
            middle = 0.5 * (low + high)
            out[key] = [middle - 0.5 * span, middle + 0.5 * span]
    return out


def readable(fig: go.Figure) -> go.Figure:
    """The figure as every edge shows it (the command line's and the reports' images and
    HTML through :mod:`crankbalance.output.render`; the web's figure cards apply the same
    :func:`value_ranges` and :func:`all_zero`): a value axis whose lines vary by less than
    the figure's minimum span share (:func:`span_share`) of their magnitude gets that span,
    and a 2-D figure whose every value is 0 says :data:`ALL_ZERO` at its top. ``fig``
    itself is left unchanged (a copy is returned when something changes).
    """
    ranges = value_ranges(fig)
    zero = all_zero(fig) and not any(
        "everywhere" in str(a.text or "") for a in fig.layout.annotations or ()
    )
    if not ranges and not zero:
        return fig
    out = plotly_go().Figure(fig)
    for key, span in ranges.items():
        out.layout[key].update(range=span, autorange=False)
    if zero:
        out.add_annotation(
            text=ALL_ZERO,
            showarrow=False,
            xref="paper",
            yref="paper",
            x=0.5,
            y=1.0,
            yanchor="bottom",
            font={"color": COLORS["before"]},
        )
    return out


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


def circle(
    radius: float,
    centre: tuple[float, float] = (0.0, 0.0),
    points: int = 181,
    from_top: bool = False,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ``x`` and ``y`` of a closed circle of ``radius`` about ``centre`` drawn as a line
    of ``points`` points (the first repeated at the end), in the unit of its arguments.

    Parameters
    ----------
    radius : float
        Radius of the circle [the drawing's unit, e.g. mm or N].
    centre : tuple of float
        Its centre (x, y) [same unit].
    points : int
        Points along it, the first and last the same.
    from_top : bool
        False: from +x, anticlockwise (x = r cos t, y = r sin t); True: from +y, clockwise,
        as a crank angle is drawn from top dead centre (x = r sin t, y = r cos t).

    Returns
    -------
    tuple of numpy.ndarray
        ``x`` and ``y`` [same unit].
    """
    turn = np.linspace(0, 2 * np.pi, points)
    across, along = (np.sin(turn), np.cos(turn)) if from_top else (np.cos(turn), np.sin(turn))
    return centre[0] + radius * across, centre[1] + radius * along


#: the side margins of a to-scale drawing [px] (plotly's default is 80 on each side): room
#: for the y axis's title and tick labels on the left, none needed on the right; on a phone
#: the drawing is then 240 px wide instead of 158 px
DRAWING_MARGIN = {"l": 60, "r": 20}


def web_drawing(fig: go.Figure, reach: float, title: str) -> go.Figure:
    """Finish a to-scale drawing of one crank web seen along the crank axis (the
    counterweight profile, the drilling plan): the crank axis marked at the origin, x and
    y in mm on equal scales over exactly ``[-reach, reach]`` (the plot a square in the space
    the figure has, never a range widened to fill it), narrow side margins
    (:data:`DRAWING_MARGIN`), the legend below.

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
    # constrain="domain": the plot shrinks to a square instead of widening one axis's range
    # (a wide plot drew ±250 mm around a ±112 mm drawing, a narrow one the same upright)
    fig.update_xaxes(title_text="x [mm]", range=[-reach, reach], constrain="domain")
    fig.update_yaxes(
        title_text="y [mm]",
        range=[-reach, reach],
        scaleanchor="x",
        scaleratio=1,
        constrain="domain",
    )
    fig.update_layout(
        template=TEMPLATE,
        legend={"orientation": "h", "y": -0.2},
        title=title,
        margin=DRAWING_MARGIN,
    )
    return fig
