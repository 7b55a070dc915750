"""Figures of the counterweight design and optimisation (:mod:`crankbalance.physics.counterweight`):
the designs found and their Pareto front, and one counterweight's profile to scale.

Public functions
----------------
- ``pareto_front(optimum, max_points=4000) -> Figure``  (counterweight.CounterweightOptimum)
- ``counterweight_profile(design, crank=None) -> Figure`` (counterweight.CounterweightDesign,
  with the engine's crankpin, journal and radial limit: studies.counterweight.CrankOutline)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .common import COLORS, TEMPLATE, circle, plotly_go, web_drawing

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.counterweight import CounterweightDesign
    from ...physics.counterweight_optimize import CounterweightOptimum
    from ...studies.counterweight import CrankOutline


def pareto_front(optimum: CounterweightOptimum, max_points: int = 4000) -> go.Figure:
    """Counterweight designs: every feasible design found (a sample of at most
    ``max_points``), the Pareto front of mass versus radial space (at most ``max_points`` of
    it, evenly along the front and both its ends: a run of the budget's size has a front of
    about 100 000 designs, which no browser draws as SVG markers in good time), and the
    least-mass and least-radius designs
    (:class:`~crankbalance.physics.counterweight_optimize.CounterweightOptimum`); each
    legend gives the whole number."""
    go = plotly_go()
    radius = np.asarray(optimum.radius) * 1e3
    mass = np.asarray(optimum.mass) * 1e3
    fig = go.Figure()
    n = mass.size
    if n:
        pick = (
            np.arange(n)
            if n <= max_points
            else np.random.default_rng(0).choice(n, max_points, replace=False)
        )
        fig.add_trace(
            go.Scattergl(
                x=radius[pick],
                y=mass[pick],
                mode="markers",
                name=f"feasible designs ({n})",
                marker={"color": "#c7c7c7", "size": 3},
            )
        )
    front = np.asarray(optimum.pareto, dtype=int)
    drawn = front
    if front.size > max_points:  # evenly along the front, its two ends kept
        drawn = front[np.unique(np.linspace(0, front.size - 1, max_points).round().astype(int))]
    fig.add_trace(
        go.Scatter(
            x=radius[drawn],
            y=mass[drawn],
            mode="lines+markers",
            name=f"Pareto front ({front.size}"
            + (f", {drawn.size} drawn)" if drawn.size < front.size else ")"),
            line={"color": COLORS["forward"], "width": 2},
            marker={"size": 5},
        )
    )
    for idx, label, color, symbol in (
        (optimum.least_mass, "least mass", COLORS["counterweight"], "star"),
        (optimum.least_radius, "least radius", COLORS["after"], "diamond"),
    ):
        fig.add_trace(
            go.Scatter(
                x=[radius[idx]],
                y=[mass[idx]],
                mode="markers",
                name=f"{label}: {mass[idx]:.1f} g, {radius[idx]:.2f} mm",
                marker={"color": color, "size": 15, "symbol": symbol},
            )
        )
    measure = "outer radius" if optimum.radius_measure == "true" else "R_min bound (paper)"
    fig.update_xaxes(title_text=f"radial space, {measure} [mm]")
    fig.update_yaxes(title_text="counterweight mass [g]")
    fig.update_layout(
        template=TEMPLATE,
        legend={"orientation": "h", "y": -0.2},
        title=f"Counterweight designs for m r = {optimum.required_first_moment * 1e6:.5g} g·mm",
    )
    return fig


def counterweight_profile(
    design: CounterweightDesign, crank: CrankOutline | None = None
) -> go.Figure:
    """The counterweight profile drawn to scale (mm): the outline, the web circle it sits on,
    the crank axis and the centre of gravity
    (:class:`~crankbalance.physics.counterweight.CounterweightDesign`); with ``crank``
    (:class:`~crankbalance.studies.counterweight.CrankOutline`) also the parts that give it
    its scale: the main journal about the axis, the crankpin opposite the counterweight at
    the crank radius and the radial limit."""
    go = plotly_go()
    props = design.properties()
    fig = go.Figure()
    for k, loop in enumerate(design.outline(tolerance=2e-6)):
        closed = np.vstack([loop, loop[:1]]) * 1e3
        fig.add_trace(
            go.Scatter(
                x=closed[:, 0],
                y=closed[:, 1],
                mode="lines",
                fill="toself",
                fillcolor="rgba(127,140,141,0.6)",
                name="profile",
                legendgroup="profile",
                showlegend=k == 0,
                line={"color": "black", "width": 1.5},
            )
        )
    r = design.web_radius * 1e3
    x, y = circle(r)
    fig.add_trace(
        go.Scatter(
            x=x,
            y=y,
            mode="lines",
            name=f"web circle r_cw = {r:.2f} mm",
            line={"color": "#c0392b", "dash": "dash", "width": 1},
        )
    )
    cg = float(props.cg_radius) * 1e3
    fig.add_trace(
        go.Scatter(
            x=[0.0],
            y=[cg],
            mode="markers",
            name=f"CG at {cg:.2f} mm",
            marker={"color": COLORS["after"], "size": 10, "symbol": "x"},
        )
    )
    reach = max(float(props.outer_radius) * 1e3, r)
    if crank is not None:
        reach = max(reach, _crank_parts(fig, crank))
    return web_drawing(
        fig,
        1.1 * reach,
        f"Counterweight: {float(props.mass) * 1e3:.1f} g, thickness "
        f"{design.thickness * 1e3:.2f} mm, outer radius "
        f"{float(props.outer_radius) * 1e3:.2f} mm",
    )


def _crank_parts(fig: go.Figure, crank: CrankOutline) -> float:
    """Draw the journal, the crankpin (at -y, opposite the counterweight) and the radial
    limit of ``crank`` into ``fig``; the largest radius drawn [mm]."""
    go = plotly_go()
    r = crank.crank_radius * 1e3
    steel = {"color": "#34495e", "width": 1.5}
    for name, radius, centre in (
        (f"main journal ⌀ {crank.journal_diameter * 1e3:.1f} mm", crank.journal_diameter / 2, 0.0),
        (
            f"crankpin ⌀ {crank.pin_diameter * 1e3:.1f} mm at r = {r:.1f} mm",
            crank.pin_diameter / 2,
            -r,
        ),
    ):
        x, y = circle(radius * 1e3, (0.0, centre))
        fig.add_trace(
            go.Scatter(
                x=x,
                y=y,
                mode="lines",
                fill="toself",
                fillcolor="rgba(52,73,94,0.25)",
                name=name,
                line=steel,
            )
        )
    limit = crank.radial_limit * 1e3
    why = "typed" if crank.limit_source == "typed" else "rod length - crank radius"
    x, y = circle(limit)
    fig.add_trace(
        go.Scatter(
            x=x,
            y=y,
            mode="lines",
            name=f"radial limit {limit:.1f} mm ({why})",
            line={"color": COLORS["before"], "dash": "dot", "width": 1.5},
        )
    )
    return max(limit, r + crank.pin_diameter * 1e3 / 2)
