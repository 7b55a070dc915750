"""The figure of the balance shop (:mod:`crankbalance.studies.shop`): the hole plan of a
two-plane correction.

Public functions
----------------
- ``hole_plan(result) -> Figure``                   (studies.shop.HolePlan)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .common import COLORS, TEMPLATE, figure_title, make_subplots, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...studies.shop import HolePlan


#: font size of the hole plan's panel titles [px]
HOLE_TITLE_SIZE = 12


def hole_plan(result: HolePlan) -> go.Figure:
    """The holes of a two-plane correction to scale (mm), one panel per correction plane,
    seen along the crank axis: 0° (crankpin 1) straight up, angles counterclockwise as the
    crank's throw angles; the hole circle, the heavy spot, each hole with its angle and the
    depth (:class:`~crankbalance.studies.shop.HolePlan`)."""
    go = plotly_go()
    # two short lines per panel, so that the two titles stay apart on a phone (a panel is
    # about 180 px wide there: tests/web/test_web_shop.py measures them at 390 px)
    titles = [
        f"plane {j + 1} at {p * 1e3:.4g} mm<br>{h.number} × Ø{h.diameter * 1e3:.3g} mm, "
        f"{h.depth * 1e3:.4g} mm to {h.depth_to}"
        for j, (p, h) in enumerate(zip(result.plan.correction_planes, result.holes, strict=True))
    ]
    fig = make_subplots(rows=1, cols=2, subplot_titles=titles, horizontal_spacing=0.14)
    fig.update_annotations(font={"size": HOLE_TITLE_SIZE})
    ring = np.linspace(0.0, 2 * np.pi, 91)
    for j, holes in enumerate(result.holes):
        col = j + 1
        r, d = holes.radius * 1e3, holes.diameter * 1e3
        reach = 1.3 * (r + d)
        fig.add_trace(
            go.Scatter(
                x=r * np.sin(ring),
                y=r * np.cos(ring),
                mode="lines",
                name="hole circle",
                line={"color": COLORS["crank"], "dash": "dot", "width": 1},
                showlegend=j == 0,
                hoverinfo="skip",
            ),
            row=1,
            col=col,
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
            row=1,
            col=col,
        )
        fig.add_trace(
            go.Scatter(
                x=[0.0],
                y=[reach * 0.95],
                mode="text",
                text=["0° (crankpin 1)"],
                showlegend=False,
                hoverinfo="skip",
            ),
            row=1,
            col=col,
        )
        for k, phi in enumerate(holes.angles):
            cx, cy = r * np.sin(phi), r * np.cos(phi)
            label = f"{np.degrees(phi) % 360:.1f}°"
            fig.add_trace(
                go.Scatter(
                    x=cx + d / 2 * np.sin(ring),
                    y=cy + d / 2 * np.cos(ring),
                    mode="lines",
                    fill="toself",
                    fillcolor="white",
                    name="hole",
                    legendgroup="holes",
                    showlegend=j == 0 and k == 0,
                    line={"color": COLORS["forward"], "width": 2},
                    hovertext=label,
                ),
                row=1,
                col=col,
            )
            # neighbouring labels on two radii between the hole circle and the panel's
            # edge, so that holes a pitch apart do not print their angles on one another
            at = r + (reach - r) * (0.45 if k % 2 == 0 else 0.85)
            fig.add_trace(
                go.Scatter(
                    x=[at * np.sin(phi)],
                    y=[at * np.cos(phi)],
                    mode="text",
                    text=[label],
                    showlegend=False,
                    hoverinfo="skip",
                ),
                row=1,
                col=col,
            )
        fig.update_xaxes(title_text="x [mm]", range=[-reach, reach], row=1, col=col)
        fig.update_yaxes(
            range=[-reach, reach],
            scaleanchor=f"x{col if col > 1 else ''}",
            scaleratio=1,
            row=1,
            col=col,
        )
    fig.update_layout(
        template=TEMPLATE,
        height=560,
        margin={"t": 150},  # the figure's title, then two lines of panel titles
        legend={"orientation": "h", "y": -0.2},
        title=figure_title("Hole plan", note="along the crank axis; angles as the throw angles"),
    )
    return fig
