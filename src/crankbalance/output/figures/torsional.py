"""The figure of the torsional vibration study (:mod:`crankbalance.physics.torsional`):
the Campbell diagram and the forced response of the crank train.

Public functions
----------------
- ``torsional_figure(study) -> Figure``             (torsional.TorsionalStudy)
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .common import COLORS, ORDER_COLORS, TEMPLATE, make_subplots, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.torsional import TorsionalStudy


def torsional_figure(study: TorsionalStudy) -> go.Figure:
    """Campbell diagram and forced response of the crank train
    (:class:`~crankbalance.physics.torsional.TorsionalStudy`): top, the natural frequencies [Hz]
    and the engine-order lines f = n · rpm / 60 over the speed range, a marker at every
    resonance sized by its relative excitation; bottom, the front end's amplitude and the
    crank's twist (front end to flywheel) summed over the orders, and the damper power."""
    go = plotly_go()
    rpm = np.asarray(study.response.speed) * 30 / math.pi
    orders = np.asarray(study.excitation.orders)
    fig = make_subplots(
        rows=2,
        cols=1,
        shared_xaxes=True,
        vertical_spacing=0.08,
        subplot_titles=("Campbell diagram", "Forced response (synthesised from all orders)"),
        specs=[[{}], [{"secondary_y": True}]],
    )
    top = float(max(orders.max() * rpm[-1] / 60, 1.0))
    for n in orders:
        major = abs(n - round(n)) < 1e-9
        fig.add_trace(
            go.Scatter(
                x=[rpm[0], rpm[-1]],
                y=[n * rpm[0] / 60, n * rpm[-1] / 60],
                mode="lines",
                name=f"order {n:g}",
                showlegend=False,
                line={
                    "color": COLORS["before"],
                    "width": 1 if major else 0.5,
                    "dash": None if major else "dot",
                },
                hovertemplate=f"order {n:g}<extra></extra>",
            ),
            row=1,
            col=1,
        )
    for m, w in enumerate(study.modes.frequency):
        hz = float(w) / (2 * math.pi)
        if m == 0 or hz > top:
            continue
        fig.add_trace(
            go.Scatter(
                x=[rpm[0], rpm[-1]],
                y=[hz, hz],
                mode="lines",
                name=f"mode {m}: {hz:.0f} Hz",
                line={"color": ORDER_COLORS[(m - 1) % len(ORDER_COLORS)]},
            ),
            row=1,
            col=1,
        )
    if study.resonances:
        excite = np.array([r.relative_excitation for r in study.resonances])
        fig.add_trace(
            go.Scatter(
                x=[r.speed * 30 / math.pi for r in study.resonances],
                y=[r.order * r.speed / (2 * math.pi) for r in study.resonances],
                mode="markers",
                name="resonance",
                marker={
                    "size": 4 + 14 * excite / max(float(excite.max()), 1e-12),
                    "color": COLORS["after"],
                },
                text=[f"mode {r.mode}, order {r.order:g}" for r in study.resonances],
            ),
            row=1,
            col=1,
        )
    for name, values, color in (
        ("front end amplitude", study.front_amplitude, COLORS["forward"]),
        ("crank twist, front to flywheel", study.crank_twist, COLORS["backward"]),
    ):
        fig.add_trace(
            go.Scatter(x=rpm, y=np.degrees(values), name=name, line={"color": color}),
            row=2,
            col=1,
        )
    if study.train.damper_section is not None:
        fig.add_trace(
            go.Scatter(
                x=rpm,
                y=study.response.damper_power,
                name="damper power",
                line={"color": COLORS["counterweight"], "dash": "dash"},
            ),
            row=2,
            col=1,
            secondary_y=True,
        )
        fig.update_yaxes(title_text="[W]", row=2, col=1, secondary_y=True)
    fig.update_yaxes(title_text="frequency [Hz]", range=[0, top], row=1, col=1)
    fig.update_yaxes(title_text="[deg]", row=2, col=1, secondary_y=False)
    fig.update_xaxes(title_text="crank speed [rpm]", row=2, col=1)
    fig.update_layout(
        template=TEMPLATE,
        height=800,
        legend={"orientation": "h", "y": -0.1},
        title="Torsional vibration of the crank train",
    )
    return fig
