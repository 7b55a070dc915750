"""The figures of the mount study (:mod:`crankbalance.physics.mounts`): the Campbell diagram
of the six rigid-body modes and the force every mount transmits over speed.

Public functions
----------------
- ``mounts_figure(result) -> Figure``               (studies.mounts.MountsResult)
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .common import COLORS, ORDER_COLORS, TEMPLATE, make_subplots, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...studies.mounts import MountsResult

_DASHES = ("solid", "dash", "dot", "dashdot", "longdash", "longdashdot")


def mounts_figure(result: MountsResult) -> go.Figure:
    """Top, the Campbell diagram: the six natural frequencies [Hz] of the powertrain on its
    mounts and the engine-order lines f = n · rpm / 60 over the speed range, a marker at
    every crossing; middle, the largest force of each mount over a cycle [N] against speed,
    one line per mount (dash) and order (colour); with a comparison of balancing choices or
    an optimisation, a third row: the largest force of any mount and order against speed,
    for the mounts as given, each choice and the optimised mounts."""
    go = plotly_go()
    response, modes = result.response, result.modes
    rpm = np.asarray(response.speeds) * 30 / math.pi
    extra = bool(result.comparison) or result.optimum_response is not None
    fig = make_subplots(
        rows=3 if extra else 2,
        cols=1,
        shared_xaxes=True,
        vertical_spacing=0.08,
        subplot_titles=(
            "Campbell diagram: rigid-body modes",
            "Force transmitted by each mount",
            *(["Largest mount force (every mount and order)"] if extra else []),
        ),
    )
    for n in response.orders:
        fig.add_trace(
            go.Scatter(
                x=[rpm[0], rpm[-1]],
                y=[n * rpm[0] / 60, n * rpm[-1] / 60],
                mode="lines",
                name=f"order {n}",
                showlegend=False,
                line={"color": COLORS["before"], "width": 1},
                hovertemplate=f"order {n}<extra></extra>",
            ),
            row=1,
            col=1,
        )
    for r, f in enumerate(modes.frequencies):
        fig.add_trace(
            go.Scatter(
                x=[rpm[0], rpm[-1]],
                y=[f, f],
                mode="lines",
                name=f"mode {r + 1}",
                showlegend=False,
                line={"color": COLORS["after"], "width": 1.5},
                hovertemplate=f"mode {r + 1}: {f:.2f} Hz<extra></extra>",
            ),
            row=1,
            col=1,
        )
    if result.crossings:
        fig.add_trace(
            go.Scatter(
                x=[c.speed * 30 / math.pi for c in result.crossings],
                y=[modes.frequencies[c.mode] for c in result.crossings],
                mode="markers",
                name="crossings",
                showlegend=False,
                marker={"color": COLORS["after"], "size": 8},
                text=[f"mode {c.mode + 1}, order {c.order}" for c in result.crossings],
                hovertemplate="%{text}: %{x:.0f} rpm<extra></extra>",
            ),
            row=1,
            col=1,
        )
    top = float(max(modes.frequencies.max(), 1.0)) * 1.6
    fig.update_yaxes(title_text="frequency [Hz]", range=[0, top], row=1, col=1)
    for k, n in enumerate(response.orders):
        color = ORDER_COLORS[k % len(ORDER_COLORS)]
        for i, mount in enumerate(result.powertrain.mounts):
            fig.add_trace(
                go.Scatter(
                    x=rpm,
                    y=response.mount_peak[:, k, i],
                    mode="lines",
                    name=f"{mount.name}, order {n}",
                    line={"color": color, "dash": _DASHES[i % len(_DASHES)]},
                ),
                row=2,
                col=1,
            )
    fig.update_yaxes(title_text="force [N]", row=2, col=1)
    if extra:
        _largest(fig, result, rpm)
    fig.update_xaxes(title_text="speed [rpm]", row=3 if extra else 2, col=1)
    fig.update_layout(template=TEMPLATE, title=f"{result.name}: the powertrain on its mounts")
    return fig


def _largest(fig: go.Figure, result: MountsResult, rpm: np.ndarray) -> None:
    """Third row: the largest force of any mount and order over speed, for the mounts as
    given, each balancing choice compared and the optimised mounts."""
    go = plotly_go()
    lines = [("mounts as given", result.response.mount_peak, "solid")]
    lines += [(label, r.response.mount_peak, "solid") for label, r in result.comparison]
    if result.optimum_response is not None:
        lines.append(("optimised mounts", result.optimum_response.mount_peak, "dash"))
    for k, (label, peak, dash) in enumerate(lines):
        fig.add_trace(
            go.Scatter(
                x=rpm,
                y=peak.max(axis=(1, 2)),
                mode="lines",
                name=label,
                line={"color": ORDER_COLORS[k % len(ORDER_COLORS)], "dash": dash},
            ),
            row=3,
            col=1,
        )
    fig.update_yaxes(title_text="force [N]", row=3, col=1)
