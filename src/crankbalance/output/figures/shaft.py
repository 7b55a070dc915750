"""Figures of the balance-shaft studies (:mod:`crankbalance.physics.balance_shaft`): the
placement study and the deflection of one shaft.

Public functions
----------------
- ``shaft_study(study, engine=None, note=None) -> Figure``  (balance_shaft placement studies)
- ``shaft_response_figure(response, shaft=None) -> Figure``  (balance_shaft.ShaftResponse)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .common import COLORS, ORDER_COLORS, TEMPLATE, figure_title, make_subplots, plotly_go

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.balance_shaft import BalanceShaft, PlacementStudy, ShaftResponse


def shaft_study(
    study: PlacementStudy, engine: str | None = None, note: str | None = None
) -> go.Figure:
    """Balance-shaft placement study (Kim 2018, Figs. 6-9): bearing loads, bending measure
    and first bending frequency along the design variable, and the normalised measures with
    the objective J and its optimum
    (:class:`~crankbalance.physics.balance_shaft.PlacementStudy`). The subtitle names the
    ``engine`` and ``note`` (what the shaft balances); an inline-3 study names its rotor
    type. The study's internal case (``inline4``: the model of the study) is not the
    engine and is not shown."""
    go = plotly_go()
    x = 100 * np.asarray(study.positions)
    fig = make_subplots(
        rows=2,
        cols=2,
        horizontal_spacing=0.12,
        vertical_spacing=0.1,
        shared_xaxes=True,
        subplot_titles=(
            "Bearing loads",
            "Bending (integral of deflection)",
            "First bending frequency",
            "Objective J",
        ),
    )
    reactions = np.atleast_2d(np.asarray(study.reactions))

    def add(row: int, col: int, **trace: Any) -> None:
        fig.add_trace(go.Scatter(**{"x": x, **trace}), row=row, col=col)

    for b in range(reactions.shape[1]):
        color = ORDER_COLORS[b % len(ORDER_COLORS)]
        add(1, 1, y=reactions[:, b], name=f"bearing {b + 1}", line={"color": color})
    difference = {"color": COLORS["total"], "dash": "dot"}
    add(1, 1, y=study.reaction_difference, name="largest - smallest", line=difference)
    bending = np.asarray(study.bending_measure) * 1e6
    add(1, 2, y=bending, name="bending measure A", line={"color": COLORS["forward"]})
    add(2, 1, y=study.first_frequency, name="first frequency", line={"color": COLORS["rotating"]})
    for y, name, color in (
        (study.normalised_bending, "A / max A", COLORS["forward"]),
        (study.normalised_secondary, f"B / max B ({study.secondary})", COLORS["backward"]),
    ):
        add(2, 2, y=y, name=name, line={"color": color, "dash": "dash"})
    objective = {"color": COLORS["total"], "width": 2.5}
    add(2, 2, y=study.objective, name=f"J (w = {study.weight:g})", line=objective)
    add(
        2,
        2,
        x=[100 * study.optimum_position],
        y=[study.optimum_objective],
        mode="markers",
        name=f"optimum {study.optimum_position:.1%}",
        marker={"color": COLORS["after"], "size": 12},
    )
    fig.update_yaxes(title_text="load [N]", row=1, col=1)
    fig.update_yaxes(title_text="A [mm²]", row=1, col=2)
    fig.update_yaxes(title_text="frequency [Hz]", row=2, col=1)
    fig.update_yaxes(title_text="J [-]", row=2, col=2)
    for col in (1, 2):  # the columns share x: one axis title under each
        fig.update_xaxes(title_text=f"{study.design_variable} [% of length]", row=2, col=col)
    # the legend sits at the bottom of the whole figure, below the axis titles (a legend
    # placed in plot coordinates overlapped the lower-left axis title)
    fig.update_layout(
        template=TEMPLATE,
        height=760,
        margin={"b": 150},
        legend={
            "orientation": "h",
            "yref": "container",
            "y": 0.01,
            "yanchor": "bottom",
            "x": 0.5,
            "xanchor": "center",
        },
        title=figure_title("Balance-shaft placement study", engine, _note(study, note)),
    )
    return fig


def _note(study: PlacementStudy, note: str | None) -> str | None:
    """The subtitle's note: ``note``, with the rotor type of an inline-3 study."""
    rotor = study.case.partition("inline3-")[2]
    words = [w for w in (note, f"rotor type {rotor}" if rotor else None) if w]
    return " · ".join(words) or None


def shaft_response_figure(response: ShaftResponse, shaft: BalanceShaft | None = None) -> go.Figure:
    """Deflection amplitude along a balance shaft
    (:class:`~crankbalance.physics.balance_shaft.ShaftResponse`); with ``shaft``
    (:class:`~crankbalance.physics.balance_shaft.BalanceShaft`) the bearings and masses are
    marked."""
    go = plotly_go()
    x = np.asarray(response.x) * 1e3
    deflection = np.abs(np.asarray(response.deflection)) * 1e6
    fig = go.Figure(
        go.Scatter(
            x=x,
            y=deflection,
            name="deflection amplitude",
            line={"color": COLORS["forward"], "width": 2.5},
        )
    )
    if shaft is not None:
        fig.add_trace(
            go.Scatter(
                x=np.asarray(shaft.bearing_positions) * 1e3,
                y=np.zeros(len(shaft.bearing_positions)),
                mode="markers",
                name="bearings",
                marker={"symbol": "triangle-up", "size": 14, "color": COLORS["total"]},
            )
        )
        fig.add_trace(
            go.Scatter(
                x=np.asarray(shaft.mass_positions) * 1e3,
                y=np.zeros(len(shaft.mass_positions)),
                mode="markers",
                name="unbalance masses",
                marker={"size": 14, "color": COLORS["after"]},
            )
        )
    fig.update_xaxes(title_text="position along the shaft [mm]")
    fig.update_yaxes(title_text="deflection [µm]")
    fig.update_layout(
        template=TEMPLATE,
        legend={"orientation": "h", "y": -0.2},
        title=f"Balance shaft: max deflection {response.max_deflection * 1e6:.1f} µm,"
        f" first bending frequency {response.first_frequency:.0f} Hz",
    )
    return fig
