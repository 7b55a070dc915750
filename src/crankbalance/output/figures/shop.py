"""The figures of the balance shop (:mod:`crankbalance.studies.shop`): the matched sets,
the bob-weights, the scatter's histograms and the hole plan of a two-plane correction.
Masses are drawn in g, unbalances in g·mm.

Public functions
----------------
- ``matched_sets(study) -> Figure``                 (studies.shop.PartsStudy)
- ``bob_weights_figure(bob_weights) -> Figure``     (physics.shop.bobweights.BobWeights)
- ``scatter_histograms(study) -> Figure``           (physics.shop.scatter.ScatterStudy)
- ``hole_plan(result) -> Figure``                   (studies.shop.HolePlan)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .common import COLORS, TEMPLATE, circle, figure_title, make_subplots, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go
    from numpy.typing import NDArray

    from ...physics.shop.bobweights import BobWeights
    from ...physics.shop.scatter import ScatterStudy
    from ...studies.shop import HolePlan, PartsStudy


#: font size of the hole plan's panel titles [px]
HOLE_TITLE_SIZE = 12
#: points of each circle of the hole plan (the hole circle and every hole)
RING_POINTS = 91

#: the hole plan's panel spans this many times the hole circle's outer edge (radius plus
#: half a hole) each way from the axis [-]
HOLE_MARGIN = 1.25
#: height of the hole plan, its two panels stacked [px]
HOLE_PLAN_HEIGHT = 900
#: hole angles per line of a hole plan panel's title
ANGLES_PER_LINE = 4

#: the journals' pairings drawn beside the matched sets (a pairing chosen, not as listed)
PAIRED = ("milp", "exhaustive", "joint")


def _band(
    go: Any, x: tuple[float, float], low: float, high: float, name: str, show: bool
) -> list[Any]:
    """Two traces filling ``[low, high]`` over ``x``: the spread of a set of masses [g]."""
    common = {"mode": "lines", "hoverinfo": "skip", "legendgroup": "spread", "line": {"width": 0}}
    return [
        go.Scatter(x=list(x), y=[low, low], showlegend=False, **common),
        go.Scatter(
            x=list(x),
            y=[high, high],
            fill="tonexty",
            fillcolor="rgba(127, 127, 127, 0.2)",
            name=name,
            showlegend=show,
            **common,
        ),
    ]


def _grams(values: NDArray[np.float64] | float) -> list[float]:
    return [float(v) * 1e3 for v in np.atleast_1d(values)]


def matched_sets(study: PartsStudy) -> go.Figure:
    """The matched sets of a shop match, one panel per share: each cylinder's
    reciprocating and rotating set [g] (the sets as listed beside them), the target every
    set is machined to (the lightest) and the spread of the sets; with the sets paired on
    the journals (``journals`` ``paired`` or ``joint``), a third panel with the journals'
    bob-weights and their spread (:class:`~crankbalance.studies.shop.PartsStudy`)."""
    go = plotly_go()
    m, listed, pairing = study.matching, study.as_listed, study.journals
    paired = pairing.method in PAIRED
    shares = (
        (
            "reciprocating",
            m.reciprocating,
            m.remove_reciprocating,
            listed.reciprocating,
            m.reciprocating_spread,
        ),
        ("rotating", m.rotating, m.remove_rotating, listed.rotating, m.rotating_spread),
    )
    titles = [f"{name} sets: spread {spread * 1e3:.4g} g" for name, *_, spread in shares]
    if paired:
        titles.append(
            f"journals' bob-weights: spread {pairing.spread * 1e3:.4g} g "
            f"(as listed {pairing.as_listed_spread * 1e3:.4g} g)"
        )
    fig = make_subplots(rows=1, cols=len(titles), subplot_titles=titles, horizontal_spacing=0.08)
    fig.update_annotations(font={"size": HOLE_TITLE_SIZE})
    cylinders = list(range(1, study.cylinders + 1))
    edge = (0.5, study.cylinders + 0.5)
    for j, (name, sets, remove, as_listed, spread) in enumerate(shares):
        col = j + 1
        target = _grams(sets - remove)  # every set machined to the lightest
        for trace in _band(go, edge, target[0], target[0] + spread * 1e3, "spread", j == 0):
            fig.add_trace(trace, row=1, col=col)
        fig.add_trace(
            go.Scatter(
                x=cylinders,
                y=target,
                mode="lines",
                name="target (the lightest set)",
                line={"color": COLORS["after"], "dash": "dash"},
                showlegend=j == 0,
                legendgroup="target",
            ),
            row=1,
            col=col,
        )
        fig.add_trace(
            go.Scatter(
                x=cylinders,
                y=_grams(as_listed),
                mode="markers",
                name="as listed",
                marker={"color": COLORS["before"], "symbol": "circle-open", "size": 9},
                showlegend=j == 0,
                legendgroup="as listed",
            ),
            row=1,
            col=col,
        )
        fig.add_trace(
            go.Scatter(
                x=cylinders,
                y=_grams(sets),
                mode="markers",
                name=f"matched ({m.method})",
                marker={"color": COLORS["forward"], "size": 10},
                showlegend=j == 0,
                legendgroup="matched",
                customdata=[", ".join(ids) for ids in m.ids],
                hovertemplate="cylinder %{x}: %{y:.4g} g<br>%{customdata}<extra></extra>",
            ),
            row=1,
            col=col,
        )
        fig.update_xaxes(title_text="cylinder", dtick=1, row=1, col=col)
        fig.update_yaxes(title_text=f"{name} set [g]", row=1, col=col)
    if paired:
        col = 3
        pins = list(range(1, len(pairing.bob_weight) + 1))
        weights = _grams(pairing.bob_weight)
        low = min(weights)
        span = (0.5, len(pins) + 0.5)
        for trace in _band(go, span, low, low + pairing.spread * 1e3, "spread", False):
            fig.add_trace(trace, row=1, col=col)
        fig.add_trace(
            go.Scatter(
                x=pins,
                y=weights,
                mode="markers",
                name="journal's bob-weight",
                marker={"color": COLORS["rotating"], "size": 10, "symbol": "diamond"},
                customdata=[
                    ", ".join(str(c + 1) for c, t in enumerate(pairing.cylinder_throw) if t == k)
                    for k in range(len(pins))
                ],
                hovertemplate="crankpin %{x}: %{y:.5g} g<br>cylinders %{customdata}<extra></extra>",
            ),
            row=1,
            col=col,
        )
        fig.update_xaxes(title_text="crankpin", dtick=1, row=1, col=col)
        fig.update_yaxes(title_text="bob-weight [g]", row=1, col=col)
    fig.update_layout(
        template=TEMPLATE,
        height=460,
        margin={"t": 110},
        legend={"orientation": "h", "y": -0.22},
        title=figure_title("Matched sets", study.engine, f"{m.method}, {m.status}"),
    )
    return fig


def bob_weights_figure(bob_weights: BobWeights, engine: str | None = None) -> go.Figure:
    """The bob-weight of every crankpin [g] against their mean, each marked with its
    difference from the mean, its rotating and reciprocating shares in the hover text
    (:class:`~crankbalance.physics.shop.bobweights.BobWeights`)."""
    go = plotly_go()
    b = bob_weights
    pins = list(range(1, len(b.bob_weight) + 1))
    weights = _grams(b.bob_weight)
    mean = float(np.mean(weights))
    fig = go.Figure()
    fig.add_trace(
        go.Scatter(
            x=[0.5, len(pins) + 0.5],
            y=[mean, mean],
            mode="lines",
            name=f"mean {mean:.5g} g",
            line={"color": COLORS["before"], "dash": "dash"},
        )
    )
    fig.add_trace(
        go.Scatter(
            x=pins,
            y=weights,
            mode="markers+text",
            name="bob-weight",
            marker={"color": COLORS["forward"], "size": 11},
            text=[f"{w - mean:+.3g} g" for w in weights],
            textposition="top center",
            customdata=np.column_stack(
                [_grams(b.rotating), _grams(b.reciprocating), b.rods_on_pin]
            ),
            hovertemplate="crankpin %{x}: %{y:.5g} g<br>rotating %{customdata[0]:.5g} g, "
            "reciprocating %{customdata[1]:.5g} g, %{customdata[2]} rods<extra></extra>",
        )
    )
    spread = max(weights) - min(weights)
    fig.update_xaxes(title_text="crankpin", dtick=1)
    fig.update_yaxes(title_text="bob-weight [g]")
    fig.update_layout(
        template=TEMPLATE,
        height=440,
        legend={"orientation": "h", "y": -0.2},
        title=figure_title(
            "Bob-weights",
            engine,
            f"rotating + {b.fraction:g} × reciprocating; spread {spread:.3g} g",
        ),
    )
    return fig


#: the scatter's panels, one per output of
#: :data:`crankbalance.physics.shop.scatter.OUTPUTS` (in its order): title, unit, factor
#: from SI, and the name of its limit
SCATTER_PANELS = (
    ("residual, correction plane 1", "g·mm", 1e6, "tolerance"),
    ("residual, correction plane 2", "g·mm", 1e6, "tolerance"),
    ("free force, order 1", "N", 1.0, "limit"),
    ("free force, order 2", "N", 1.0, "limit"),
    ("free moment, order 1", "N·m", 1.0, "limit"),
    ("free moment, order 2", "N·m", 1.0, "limit"),
)
#: most bars a histogram of the scatter draws over the bins that hold samples: its bins
#: (:data:`crankbalance.physics.shop.scatter.BINS` over ten RMS) are drawn merged in
#: groups of as many as this needs (:func:`merged_bins`)
SCATTER_BARS = 100


def merged_bins(counts: NDArray[np.int64], group: int) -> NDArray[np.int64]:
    """The samples of every ``group`` neighbouring bins of a histogram, summed (the last
    group padded with empty bins)."""
    padded = np.concatenate([counts, np.zeros(-counts.size % group, dtype=counts.dtype)])
    return padded.reshape(-1, group).sum(axis=1)


#: the dash of each quantile's line, in the order of the levels (round again after five)
QUANTILE_DASH = ("dot", "dashdot", "dash", "longdash", "solid")


def scatter_histograms(study: ScatterStudy) -> go.Figure:
    """The histograms of a shop scatter, one panel per output (residual per correction
    plane, free force and moment of orders 1 and 2): the samples per bin, the quantiles as
    vertical lines, and the tolerance of the grade or the limit where one was given (bins
    merged into at most :data:`SCATTER_BARS` bars); a panel's title counts the samples
    beyond its histogram
    (:class:`~crankbalance.physics.shop.scatter.ScatterStudy`)."""
    go = plotly_go()
    limits: list[float | None] = []
    for given in (study.plane_tolerance, study.force_limit, study.moment_limit):
        limits += [None, None] if given is None else [float(v) for v in given]
    titles = [
        title + (f" ({int(over)} beyond)" if over else "")
        for (title, *_), over in zip(SCATTER_PANELS, study.overflow, strict=True)
    ]
    fig = make_subplots(rows=3, cols=2, subplot_titles=titles, vertical_spacing=0.1)
    fig.update_annotations(font={"size": HOLE_TITLE_SIZE})
    bins = study.histogram.shape[1]
    for k, (_title, unit, factor, limit_name) in enumerate(SCATTER_PANELS):
        row, col = k // 2 + 1, k % 2 + 1
        filled = (
            int(np.flatnonzero(study.histogram[k]).max()) + 1 if study.histogram[k].any() else 1
        )
        group = -(-filled // SCATTER_BARS)  # bins per bar
        counts = merged_bins(study.histogram[k], group)
        width = float(study.histogram_upper[k]) * factor / bins * group
        fig.add_trace(
            go.Bar(
                x=(np.arange(counts.size) + 0.5) * width,
                y=counts,
                width=width,
                name="engines per bin",
                marker={"color": COLORS["forward"], "line": {"width": 0}},
                showlegend=k == 0,
                legendgroup="histogram",
            ),
            row=row,
            col=col,
        )
        top = float(counts.max()) if counts.size else 0.0
        reach = width * (int(np.flatnonzero(counts).max()) + 1) if counts.any() else width
        for q, (level, value) in enumerate(
            zip(study.quantile_levels, study.quantiles[k], strict=True)
        ):
            fig.add_trace(
                go.Scatter(
                    x=[value * factor] * 2,
                    y=[0.0, top],
                    mode="lines",
                    name=f"{level * 100:g} % quantile",
                    line={"color": COLORS["crank"], "dash": QUANTILE_DASH[q % 5], "width": 1},
                    showlegend=k == 0,
                    legendgroup=f"q{level}",
                ),
                row=row,
                col=col,
            )
        limit = limits[k]
        if limit is not None and np.isfinite(limit):
            fig.add_trace(
                go.Scatter(
                    x=[limit * factor] * 2,
                    y=[0.0, top],
                    mode="lines",
                    name=limit_name,
                    line={"color": COLORS["after"], "width": 2},
                    showlegend=limit_name not in {t.name for t in fig.data[:-1]},
                    legendgroup=limit_name,
                ),
                row=row,
                col=col,
            )
            reach = max(reach, limit * factor)
        fig.update_xaxes(title_text=f"[{unit}]", range=[0.0, 1.05 * reach], row=row, col=col)
        fig.update_yaxes(title_text=f"engines per {width:.3g} {unit}", row=row, col=col)
    p = "" if study.p_grade is None else f"; P(both planes meet the grade) = {study.p_grade:.4g}"
    fig.update_layout(
        template=TEMPLATE,
        height=900,
        bargap=0,
        legend={"orientation": "h", "y": -0.08},
        title=figure_title("Scatter of the parts", note=f"{study.samples} engines drawn{p}"),
    )
    return fig


def hole_angles(angles: NDArray[np.float64]) -> str:
    """The angles of a plane's holes [rad] as the hole plan lists them: "at 21.0°, 33.8°",
    :data:`ANGLES_PER_LINE` to a line."""
    words = [f"{np.degrees(phi) % 360:.1f}°" for phi in angles]
    lines = [
        ", ".join(words[k : k + ANGLES_PER_LINE]) for k in range(0, len(words), ANGLES_PER_LINE)
    ]
    return "at " + ",<br>".join(lines)


def hole_plan(result: HolePlan) -> go.Figure:
    """The holes of a two-plane correction to scale (mm), one panel per correction plane
    (stacked, so that a phone shows each at its width), seen along the crank axis: 0°
    (crankpin 1) straight up, angles counterclockwise as the crank's throw angles; the hole
    circle, the heavy spot and each hole (its angle in the hover). The panel's title lists
    the holes' angles: holes a pitch apart are closer than their labels are long. Each
    panel spans the hole circle and the holes plus a margin (:data:`HOLE_MARGIN`) at equal
    scale in x and y: the panel shrinks to a square, the range stays
    (:class:`~crankbalance.studies.shop.HolePlan`)."""
    go = plotly_go()
    titles = [
        f"plane {j + 1} at {p * 1e3:.4g} mm: {h.number} × Ø{h.diameter * 1e3:.3g} mm, "
        f"{h.depth * 1e3:.4g} mm to {h.depth_to}<br>{hole_angles(h.angles)}"
        for j, (p, h) in enumerate(zip(result.plan.correction_planes, result.holes, strict=True))
    ]
    fig = make_subplots(rows=2, cols=1, subplot_titles=titles, vertical_spacing=0.16)
    # a title's last line clear of the "0° (crankpin 1)" at the top of a full-height panel
    fig.update_annotations(font={"size": HOLE_TITLE_SIZE}, yshift=8)
    for j, holes in enumerate(result.holes):
        row = j + 1
        r, d = holes.radius * 1e3, holes.diameter * 1e3
        reach = HOLE_MARGIN * (r + d / 2)
        x, y = circle(r, points=RING_POINTS, from_top=True)
        fig.add_trace(
            go.Scatter(
                x=x,
                y=y,
                mode="lines",
                name="hole circle",
                line={"color": COLORS["crank"], "dash": "dot", "width": 1},
                showlegend=j == 0,
                hoverinfo="skip",
            ),
            row=row,
            col=1,
        )
        spot = float(result.plan.remove_angle[j])
        fig.add_trace(
            go.Scatter(
                x=[0.0, reach * 0.9 * np.sin(spot)],
                y=[0.0, reach * 0.9 * np.cos(spot)],
                mode="lines+markers",
                name="heavy spot",
                showlegend=j == 0,
                line={"color": COLORS["after"], "width": 2},
                marker={"symbol": ["cross-thin", "triangle-up"], "size": 10},
            ),
            row=row,
            col=1,
        )
        fig.add_trace(
            go.Scatter(
                x=[0.0],
                y=[reach * 0.93],
                mode="text",
                text=["0° (crankpin 1)"],
                showlegend=False,
                hoverinfo="skip",
            ),
            row=row,
            col=1,
        )
        for k, phi in enumerate(holes.angles):
            x, y = circle(d / 2, (r * np.sin(phi), r * np.cos(phi)), RING_POINTS, from_top=True)
            fig.add_trace(
                go.Scatter(
                    x=x,
                    y=y,
                    mode="lines",
                    fill="toself",
                    fillcolor="white",
                    name="hole",
                    legendgroup="holes",
                    showlegend=j == 0 and k == 0,
                    line={"color": COLORS["forward"], "width": 2},
                    hovertext=f"{np.degrees(phi) % 360:.1f}°",
                    hoverinfo="text",
                ),
                row=row,
                col=1,
            )
        # equal scale: the panel's domain shrinks to a square, the range stays the drawing's
        fig.update_xaxes(
            title_text="x [mm]", range=[-reach, reach], constrain="domain", row=row, col=1
        )
        fig.update_yaxes(
            title_text="y [mm]",
            range=[-reach, reach],
            constrain="domain",
            scaleanchor=f"x{row if row > 1 else ''}",
            scaleratio=1,
            row=row,
            col=1,
        )
    fig.update_layout(
        template=TEMPLATE,
        height=HOLE_PLAN_HEIGHT,
        margin={"t": 110},  # the figure's title, then the first panel's two title lines
        legend={"orientation": "h", "y": -0.08},
        title=figure_title("Hole plan", note="along the crank axis; angles as the throw angles"),
    )
    return fig
