"""Figures of the main-bearing loads (:mod:`crankbalance.studies.loads`) and of those
loads against balance (:mod:`crankbalance.studies.balance_loads`, the sweep).

Public functions
----------------
- ``bearing_loads_figure(studies, model="indeterminate", labels=None) -> Figure``
    (studies.loads.BearingStudy, one or several overlaid): polar load diagram per main
    bearing, bending moment per journal.
- ``bearing_sweep_figure(sweep) -> Figure``         (studies.balance_loads.SweepStudy)
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ...errors import InputError
from .common import (
    COLORS,
    ORDER_COLORS,
    TEMPLATE,
    figure_title,
    make_subplots,
    note_if_zero,
    plotly_go,
)

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...studies.balance_loads import SweepStudy
    from ...studies.loads import BearingStudy


#: line styles of the studies a bearing-load figure overlays (first: solid)
STUDY_DASHES = ("solid", "dash", "dot", "dashdot")


def bearing_loads_figure(
    studies: BearingStudy | list[BearingStudy] | tuple[BearingStudy, ...],
    model: str = "indeterminate",
    labels: tuple[str, ...] | None = None,
) -> go.Figure:
    """Polar load diagram of every main bearing (top row: the force of the crank on the
    bearing over the cycle, x across horizontally, z along the cylinder axis vertically)
    and the bending moment at every journal over the cycle (bottom) of one crank model
    (:class:`~crankbalance.studies.loads.BearingStudy`, or a sequence of them overlaid,
    e.g. 4 and 8 counterweights; ``labels`` names each)."""
    if model not in ("determinate", "indeterminate"):
        raise InputError("model", model, "'determinate' or 'indeterminate'")
    go = plotly_go()
    many: list[BearingStudy] = list(studies) if isinstance(studies, (list, tuple)) else [studies]
    names = (
        list(labels)
        if labels is not None
        else [
            "no counterweights"
            if s.balance.counterweights is None
            else f"{s.balance.counterweights.count} counterweights"
            for s in many
        ]
    )
    if len(names) != len(many):
        raise InputError("labels", labels, f"needs one label per study ({len(many)})")
    bearings = many[0].results[model].bearing_position.size
    cols = max(bearings, 1)
    fig = make_subplots(
        rows=2,
        cols=cols,
        specs=[[{} for _ in range(cols)], [{"colspan": cols}] + [None] * (cols - 1)],
        row_heights=[0.45, 0.55],
        vertical_spacing=0.14,
        horizontal_spacing=0.03,
        subplot_titles=[f"bearing {k + 1}" for k in range(cols)]
        + ["bending moment at the journals"],  # the crank model is in the title
    )
    reach = max(float(np.abs(s.results[model].load).max()) for s in many) * 1.1 or 1.0
    for n, (study, name) in enumerate(zip(many, names, strict=True)):
        r = study.results[model]
        dash = STUDY_DASHES[n % len(STUDY_DASHES)]
        deg = np.degrees(r.angle)
        for k in range(r.bearing_position.size):
            fig.add_trace(
                go.Scatter(
                    x=r.load[k].imag,
                    y=r.load[k].real,
                    mode="lines",
                    name=name,
                    legendgroup=name,
                    showlegend=k == 0,
                    line={"color": COLORS["total"], "dash": dash},
                    text=[f"{a:.0f} deg" for a in deg],
                    hovertemplate="crank %{text}<br>x %{x:.4g} N<br>z %{y:.4g} N<extra></extra>",
                ),
                row=1,
                col=k + 1,
            )
            fig.add_trace(
                go.Scatter(
                    x=deg,
                    y=np.abs(r.journal_moment[k]),
                    mode="lines",
                    name=f"journal {k + 1}",
                    legendgroup=f"journal {k + 1}",
                    showlegend=n == 0,
                    line={"color": ORDER_COLORS[k % len(ORDER_COLORS)], "dash": dash},
                    hovertemplate=f"{name}, journal {k + 1}<br>crank %{{x:.0f}} deg<br>"
                    "|M| %{y:.4g} N·m<extra></extra>",
                ),
                row=2,
                col=1,
            )
    for k in range(cols):
        axis = "x" if k == 0 else f"x{k + 1}"
        fig.update_xaxes(range=[-reach, reach], title_text="x [N]", row=1, col=k + 1)
        fig.update_yaxes(
            range=[-reach, reach],
            scaleanchor=axis,
            scaleratio=1,
            title_text="z [N]" if k == 0 else None,
            showticklabels=k == 0,
            row=1,
            col=k + 1,
        )
    fig.update_xaxes(title_text="crank angle of throw 1 [deg]", row=2, col=1)
    fig.update_yaxes(title_text="|M| [N·m]", row=2, col=1)
    first = many[0]
    fig.update_layout(
        template=TEMPLATE,
        height=700,
        width=max(900, 220 * cols),
        legend={"orientation": "h", "y": -0.12},
        title=figure_title(
            f"Main-bearing loads over the cycle ({model} crank)",
            first.model.name,
            f"{first.cycle.speed_mean * 30 / math.pi:.0f} rpm",
        ),
    )
    return fig


#: the panels of :func:`bearing_sweep_figure`: key of a case's metrics, axis title
SWEEP_PANELS = (
    ("largest_load_N", "largest bearing load [N]"),
    ("coulomb_friction_power_W", "friction, all main bearings [W]"),
    ("largest_journal_moment_Nm", "largest journal |M| [N·m]"),
    ("counterweight_mass_kg", "counterweight mass [kg]"),
    ("first_order_force_N", "free first-order force left [N]"),
    ("first_order_moment_Nm", "free first-order couple left [N·m]"),
)
#: the legend's heading of the lines of :func:`bearing_sweep_figure` (one per counterweight
#: pattern), apart from the bars' "peak load of" bearing 1, 2, ...
PATTERN_HEADING = "counterweight pattern (lines)"


def bearing_sweep_figure(sweep: SweepStudy) -> go.Figure:
    """Bearing loads against balance
    (:class:`~crankbalance.studies.balance_loads.SweepStudy`): the largest bearing load, the
    friction of all main bearings, the largest bending moment at a journal, the
    counterweight mass and the free first-order force and couple left against the balance
    factor, one line per pattern (``none`` a dotted
    level), and the peak load of every main bearing per balance factor (the factors on the
    axis, under their pattern when there are several: :func:`peak_axis`; one bar per
    bearing, each bearing in the legend), all of the sweep's crank model."""
    go = plotly_go()
    model = sweep.options.crank_model
    data = sweep.to_dict()
    fig = make_subplots(
        rows=4,
        cols=2,
        specs=[[{}, {}], [{}, {}], [{}, {}], [{"colspan": 2}, None]],
        row_heights=[0.2, 0.2, 0.2, 0.4],
        vertical_spacing=0.1,
        horizontal_spacing=0.1,
        # one line each: stacked on a phone, a second line ran into the x-axis title
        # ("balance factor") of the panel above; the crank model is in the figure's title,
        # the balance factor on the axis
        subplot_titles=[title for _, title in SWEEP_PANELS] + ["peak load of each main bearing"],
    )
    factors = [float(f) for f in sweep.options.balance_factors]
    span = [min(factors), max(factors)] if factors else [0.0, 1.0]
    patterns = list(dict.fromkeys(case["pattern"] for case in data["cases"]))
    drawn: list[list[float]] = [[] for _ in SWEEP_PANELS]  # every value of each panel
    for n, pattern in enumerate(patterns):
        cases = [c for c in data["cases"] if c["pattern"] == pattern]
        color = ORDER_COLORS[n % len(ORDER_COLORS)]
        none = pattern == "none"
        for p, (key, title) in enumerate(SWEEP_PANELS):
            values = [
                c[key] if key in c else c["free_forces"].get(key, c["models"][model].get(key))
                for c in cases
            ]
            drawn[p] += values
            fig.add_trace(
                go.Scatter(
                    x=span if none else [c["balance_factor"] for c in cases],
                    y=values * 2 if none else values,
                    mode="lines" if none else "lines+markers",
                    name=pattern,
                    legendgroup=pattern,
                    # the lines' entries under their own heading, apart from the bearings'
                    legendgrouptitle_text=PATTERN_HEADING if n == 0 else None,
                    showlegend=p == 0,
                    line={"color": color, "dash": "dot" if none else "solid"},
                    hovertemplate=f"{pattern}<br>balance factor %{{x:.3g}}<br>"
                    f"{title.split(' [')[0]} %{{y:.4g}}<extra></extra>",
                ),
                row=1 + p // 2,
                col=1 + p % 2,
            )
    # the peaks grouped per balance factor (the user compares factors): the factor on the
    # axis (under its pattern when the sweep has several), one bar per bearing
    x = peak_axis(data["cases"], several=len(patterns) > 1)
    bearings = data["cases"][0]["models"][model]["bearings"]
    for k, bearing in enumerate(bearings):
        name = f"bearing {bearing['bearing']}"
        fig.add_trace(
            go.Bar(
                x=x,
                y=[c["models"][model]["bearings"][k]["max_load_N"] for c in data["cases"]],
                name=name,
                legendgroup="peak",
                legendgrouptitle_text="peak load of" if k == 0 else None,
                marker={"color": ORDER_COLORS[k % len(ORDER_COLORS)]},
                hovertemplate=f"{name}<br>%{{x}}<br>peak %{{y:.4g}} N<extra></extra>",
            ),
            row=4,
            col=1,
        )
    for p, (_, title) in enumerate(SWEEP_PANELS):
        fig.update_xaxes(title_text="balance factor", row=1 + p // 2, col=1 + p % 2)
        unit = title.split(" [")[-1].rstrip("]")
        fig.update_yaxes(title_text=unit, row=1 + p // 2, col=1 + p % 2)
        # a flat 0 (no first-order force on an inline-4) says so, not an empty -1..1 axis
        note_if_zero(fig, drawn[p], unit, 1 + p // 2, 1 + p % 2, "" if p == 0 else str(p + 1))
    fig.update_xaxes(
        title_text="balance factor f_b [-]"
        + ("<br>under its counterweight pattern" if len(patterns) > 1 else ""),
        row=4,
        col=1,
    )
    fig.update_yaxes(title_text="peak bearing load [N]", row=4, col=1)
    speed = data["settings"]["speed_rad_s"] * 30 / math.pi
    fig.update_layout(
        template=TEMPLATE,
        barmode="group",
        height=1150,
        width=1000,
        legend={"orientation": "h", "y": -0.06},
        title=figure_title(
            f"Main-bearing loads against balance ({model} crank)",
            data["engine"]["name"],
            f"{speed:.0f} rpm",
        ),
    )
    return fig


def peak_axis(cases: list[dict[str, Any]], several: bool) -> list[Any]:
    """The category axis of the sweep's peak-load bars: each case's balance factor
    (``f_b 0.5``; ``no counterweights`` for the pattern ``none``), under its pattern (a
    two-level axis, plotly's multicategory) when the sweep has ``several`` patterns."""
    factors = [
        "no counterweights" if c["balance_factor"] is None else f"f_b {c['balance_factor']:.3g}"
        for c in cases
    ]
    if not several:
        return factors
    return [[c["pattern"] for c in cases], factors]
