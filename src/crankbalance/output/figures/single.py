"""Figures of the single-cylinder studies (:mod:`crankbalance.studies.cylinder`): the
shaking force of one cylinder for a balance factor, its polar diagram, the sweep over the
balance factor, and the drilling plan of a rebalancing with holes.

Public functions
----------------
- ``single_cylinder_forces(study) -> Figure``  (physics.single_cylinder.BalanceFactorStudy)
- ``single_cylinder_polar(study) -> Figure``
- ``balance_factor_sweep(study) -> Figure``
- ``drilling_plan(result, crank_radius) -> Figure``  (physics.rebalancing.RebalanceResult)
- ``rebalance_unbalance(study) -> Figure``  (studies.rebalance.RebalanceStudy)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from ...results import number
from ..format import depth_read_to
from .common import COLORS, TEMPLATE, circle, figure_title, plotly_go, web_drawing

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.rebalancing import DrilledHoles, RebalanceResult
    from ...physics.single_cylinder import BalanceFactorStudy
    from ...studies.rebalance import RebalanceStudy


def single_cylinder_forces(study: BalanceFactorStudy) -> go.Figure:
    """In-line, transverse and resultant shaking force of one cylinder versus crank angle
    (:class:`~crankbalance.physics.single_cylinder.BalanceFactorStudy`)."""
    go = plotly_go()
    deg = np.degrees(study.crank_angle)
    fig = go.Figure()
    for name, values, color, dash in (
        ("in-line (cylinder axis)", study.in_line, COLORS["forward"], "solid"),
        ("transverse", study.transverse, COLORS["backward"], "solid"),
        ("resultant", study.resultant, COLORS["total"], "dash"),
    ):
        fig.add_trace(
            go.Scatter(x=deg, y=values, name=name, line={"color": color, "width": 2, "dash": dash})
        )
    fig.update_xaxes(
        title_text="crank angle from top dead centre [deg]",
        tickvals=list(range(0, 361, 45)),
        range=[0, 360],
    )
    fig.update_yaxes(title_text="force [N]")
    fig.update_layout(
        template=TEMPLATE,
        hovermode="x unified",
        title=f"Single cylinder, balance factor {study.balance_factor:.0%}: "
        f"peak resultant {number(study.peak_resultant, 5)} N",
        legend={"orientation": "h", "y": -0.2},
    )
    return fig


def single_cylinder_polar(study: BalanceFactorStudy) -> go.Figure:
    """Polar diagram of the residual shaking force of one cylinder: the tip of the force
    vector over a revolution (transverse horizontal, in-line vertical), with the circle of
    the peak resultant."""
    go = plotly_go()
    fig = go.Figure()
    fig.add_trace(
        go.Scatter(
            x=study.transverse,
            y=study.in_line,
            mode="lines",
            name="residual force",
            line={"color": COLORS["after"], "width": 2.5},
            text=[f"{a:.0f} deg" for a in np.degrees(study.crank_angle)],
            hovertemplate="crank %{text}<br>transverse %{x:.4g} N<br>"
            "in-line %{y:.4g} N<extra></extra>",
        )
    )
    peak = study.peak_resultant
    x, y = circle(peak, from_top=True)
    fig.add_trace(
        go.Scatter(
            x=x,
            y=y,
            mode="lines",
            name=f"peak resultant {number(peak, 5)} N",
            line={"color": COLORS["before"], "dash": "dot"},
        )
    )
    p = study.primary_force
    x, y = circle(p, from_top=True)
    fig.add_trace(
        go.Scatter(
            x=x,
            y=y,
            mode="lines",
            name=f"primary force P = {number(p, 5)} N (no balance)",
            line={"color": COLORS["forward"], "dash": "dash", "width": 1},
        )
    )
    reach = 1.1 * max(peak, p)
    fig.update_xaxes(title_text="transverse [N]", range=[-reach, reach])
    fig.update_yaxes(title_text="in-line [N]", range=[-reach, reach], scaleanchor="x", scaleratio=1)
    fig.update_layout(
        template=TEMPLATE,
        legend={"orientation": "h", "y": -0.2},
        title=f"Residual force, balance factor {study.balance_factor:.0%}",
    )
    return fig


def balance_factor_sweep(study: BalanceFactorStudy) -> go.Figure:
    """Peak resultant shaking force versus balance factor, with the studied factor and the
    optimum marked."""
    go = plotly_go()
    fig = go.Figure()
    fig.add_trace(
        go.Scatter(
            x=100 * np.asarray(study.sweep_balance_factor),
            y=study.sweep_peak_resultant,
            mode="lines",
            name="peak resultant",
            line={"color": COLORS["total"], "width": 2},
        )
    )
    fig.add_trace(
        go.Scatter(
            x=[100 * study.optimum_balance_factor],
            y=[study.optimum_peak_resultant],
            mode="markers",
            name=f"optimum {study.optimum_balance_factor:.1%}: "
            f"{number(study.optimum_peak_resultant, 5)} N",
            marker={"color": COLORS["counterweight"], "size": 12},
        )
    )
    fig.add_trace(
        go.Scatter(
            x=[100 * study.balance_factor],
            y=[study.peak_resultant],
            mode="markers",
            name=f"studied {study.balance_factor:.1%}: {number(study.peak_resultant, 5)} N",
            marker={"color": COLORS["after"], "size": 12, "symbol": "diamond"},
        )
    )
    fig.update_xaxes(title_text="balance factor [%]")
    fig.update_yaxes(title_text="peak resultant force [N]", rangemode="tozero")
    fig.update_layout(
        template=TEMPLATE,
        title="Peak shaking force versus balance factor",
        legend={"orientation": "h", "y": -0.2},
    )
    return fig


def _radial_hole(
    holes: DrilledHoles, depth: float, rim: float, phi: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Outline (x, y) [mm] of a hole drilled inward from the rim at radius ``rim`` [mm],
    at ``phi`` [rad] from straight down, seen from the side: the full diameter down to the
    shoulder, then the drill point to the tip (a flat bottom for a 180° point); ``depth``
    [m] as read (:func:`crankbalance.physics.shop.holes.hole_geometry`)."""
    from ...physics.shop.holes import hole_geometry

    g = hole_geometry(holes.diameter, depth, holes.depth_to, holes.point_angle)
    half, tip = holes.diameter * 1e3 / 2, float(g.tip_depth) * 1e3
    shoulder = float(g.shoulder_depth) * 1e3
    # (depth from the rim, offset from the hole's axis) [mm] around the outline
    outline = [(0.0, half), (tip, half), (tip, -half), (0.0, -half)]  # a flat bottom
    if g.cone_height > 0 and shoulder > 0:
        outline = [(0.0, half), (shoulder, half), (tip, 0.0), (shoulder, -half), (0.0, -half)]
    elif g.cone_height > 0:  # shallower than its point: the point alone, narrower at the rim
        entry = half * min(1.0, tip / (g.cone_height * 1e3))
        outline = [(0.0, entry), (tip, 0.0), (0.0, -entry)]
    inward, across = np.array([np.sin(phi), -np.cos(phi)]), np.array([np.cos(phi), np.sin(phi)])
    points = [(rim - s) * inward + w * across for s, w in [*outline, outline[0]]]
    x, y = np.array(points).T
    return x, y


def drilling_plan(result: RebalanceResult, crank_radius: float) -> go.Figure:
    """The drilled holes of a rebalancing to scale (mm), one web seen along the crank axis:
    the crank axis, the crankpin centre straight up, the holes on the counterweight side
    (180 deg from the crankpin) and a schematic counterweight outline
    (:class:`~crankbalance.physics.rebalancing.RebalanceResult` with a
    :class:`~crankbalance.physics.rebalancing.DrilledHoles` correction; ``crank_radius``
    [m])."""
    from ...physics.rebalancing import DrilledHoles

    go = plotly_go()
    holes = result.correction
    if not isinstance(holes, DrilledHoles):
        raise InputError("correction", getattr(holes, "kind", None), "the plan draws holes")
    depth = result.iterations[-1].depth if result.iterations else 0.0
    to = depth_read_to(holes.point_angle, holes.depth_to)
    d, rh, r = holes.diameter * 1e3, holes.radius * 1e3, crank_radius * 1e3
    fig = go.Figure()
    outer = rh + 1.5 * d
    arc = np.radians(np.linspace(120.0, 240.0, 61)) + np.pi / 2  # around straight down
    fig.add_trace(
        go.Scatter(
            x=np.concatenate([[0.0], outer * np.cos(arc), [0.0]]),
            y=np.concatenate([[0.0], outer * np.sin(arc), [0.0]]),
            mode="lines",
            fill="toself",
            fillcolor="rgba(127,140,141,0.35)",
            name="counterweight (outline schematic)",
            line={"color": COLORS["crank"], "width": 1},
            hoverinfo="skip",
        )
    )
    if depth > 0:
        # the holes of one web, side by side on the circle of radius rh, 1.5 d apart
        spread = 1.5 * d / rh * (np.arange(holes.number) - (holes.number - 1) / 2)
        for k, phi in enumerate(spread):
            cx, cy = rh * np.sin(phi), -rh * np.cos(phi)
            if holes.direction == "axial":
                x, y = circle(d / 2, (cx, cy), points=73)
            else:  # drilled inward from the rim: the hole seen from the side, its point too
                x, y = _radial_hole(holes, depth, rh, phi)
            fig.add_trace(
                go.Scatter(
                    x=x,
                    y=y,
                    mode="lines",
                    fill="toself",
                    fillcolor="white",
                    name=f"hole Ø{d:.3g} mm, {depth * 1e3:.3f} mm deep{to}",
                    legendgroup="holes",
                    showlegend=k == 0,
                    line={"color": COLORS["after"], "width": 2},
                )
            )
    fig.add_trace(
        go.Scatter(
            x=[0.0, 0.0],
            y=[r, -rh],
            mode="markers+text",
            text=[f"crankpin (r = {r:.4g} mm)", f"holes at {rh:.4g} mm"],
            textposition=["top center", "bottom center"],
            name="crankpin centre, hole radius",
            marker={"color": ["black", COLORS["after"]], "size": 8, "symbol": "circle-open"},
        )
    )
    what = (
        f"{holes.number} × Ø{d:.3g} mm, {depth * 1e3:.3f} mm deep{to}, on each of {holes.webs} webs"
        if depth > 0
        else "no hole needed"
    )
    return web_drawing(fig, 1.15 * max(outer, r), figure_title("Drilling plan", note=what))


def rebalance_unbalance(study: RebalanceStudy) -> go.Figure:
    """The unbalance of a rebalancing before and after its correction, per target balance
    factor: the unbalance the new parts leave (to correct) and the residual after the
    correction, against the tolerance [g·mm]."""
    go = plotly_go()
    targets = [f"target {case.target_balance_factor:.4g}" for case in study.cases]
    fig = go.Figure()
    for name, values, color in (
        ("before: unbalance to correct", [c.unbalance for c in study.cases], COLORS["before"]),
        ("after: residual", [c.residual for c in study.cases], COLORS["after"]),
    ):
        grams = [abs(v) * 1e6 for v in values]
        fig.add_trace(go.Bar(x=targets, y=grams, name=name, marker={"color": color}))
    fig.add_hline(
        y=study.tolerance * 1e6,
        line={"dash": "dash", "color": COLORS["total"]},
        annotation_text=f"tolerance {study.tolerance * 1e6:.4g} g·mm",
    )
    fig.update_yaxes(title_text="unbalance [g·mm]", rangemode="tozero")
    fig.update_layout(
        template=TEMPLATE,
        barmode="group",
        title=figure_title("Rebalancing: unbalance before and after", note=study.name),
        legend={"orientation": "h", "y": -0.2},
    )
    return fig
