"""Figures of the performance studies: the test bench (:mod:`crankbalance.physics.rotor_bench`),
the single-cylinder cycle and the sensitivity to the balance factor
(:mod:`crankbalance.physics.engine_cycle`), and the whole engine's cycle
(:mod:`crankbalance.physics.engine_cycle_all`).

Public functions
----------------
- ``sensitivity_figure(result, indicators=None) -> Figure``  (engine_cycle.SensitivityResult)
- ``bench_figure(result) -> Figure``                (rotor_bench.BenchResult)
- ``cycle_figure(result) -> Figure``                (engine_cycle.CycleResult)
- ``engine_torque_figure(result) -> Figure``        (engine_cycle_all.EngineCycleResult)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from ...errors import InputError
from .common import (
    COLORS,
    ORDER_COLORS,
    PERFORMANCE_MIN_SPAN_SHARE,
    TEMPLATE,
    make_subplots,
    min_span,
    plotly_go,
)

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.engine_cycle import CycleResult, SensitivityResult
    from ...physics.engine_cycle_all import EngineCycleResult
    from ...physics.rotor_bench import BenchResult


SENSITIVITY_LABELS = {
    "mean_friction_torque": ("mean friction torque", "N·m", 1.0),
    "friction_power": ("friction power", "W", 1.0),
    "peak_bearing_load": ("peak bearing load", "N", 1.0),
    "mean_bearing_load": ("mean bearing load", "N", 1.0),
    "peak_net_torque": ("peak net torque", "N·m", 1.0),
    "max_crank_acceleration": ("max crank acceleration", "rad/s²", 1.0),
    "speed_fluctuation": ("speed fluctuation", "%", 100.0),
    "peak_shaking_force": ("peak shaking force", "N", 1.0),
}


def sensitivity_figure(
    result: SensitivityResult, indicators: tuple[str, ...] | None = None
) -> go.Figure:
    """Performance indicators versus balance factor, one line per reciprocating-mass scale
    (:class:`~crankbalance.physics.engine_cycle.SensitivityResult`); each panel's value axis
    spans at least :data:`~crankbalance.output.figures.common.PERFORMANCE_MIN_SPAN_SHARE`
    (1 %) of its largest value (:func:`~crankbalance.output.figures.common.min_span`)."""
    go = plotly_go()
    names = indicators or (
        "mean_friction_torque",
        "peak_bearing_load",
        "friction_power",
        "peak_shaking_force",
        "speed_fluctuation",
        "peak_net_torque",
    )
    for name in names:
        if name not in SENSITIVITY_LABELS:
            raise InputError("indicators", name, f"one of {sorted(SENSITIVITY_LABELS)}")
    cols = 2
    rows = math.ceil(len(names) / cols)
    fig = make_subplots(
        rows=rows,
        cols=cols,
        horizontal_spacing=0.12,
        vertical_spacing=0.12,
        subplot_titles=[SENSITIVITY_LABELS[n][0] for n in names],
    )
    bf = 100 * np.asarray(result.balance_factors)
    scales = np.asarray(result.mass_scales)
    for k, name in enumerate(names):
        label, unit, factor = SENSITIVITY_LABELS[name]
        values = np.atleast_2d(np.asarray(getattr(result, name))) * factor
        row, col = k // cols + 1, k % cols + 1
        for j, scale in enumerate(scales):
            fig.add_trace(
                go.Scatter(
                    x=bf,
                    y=values[j],
                    mode="lines+markers",
                    name=f"reciprocating mass x {scale:g}",
                    legendgroup=f"scale{j}",
                    showlegend=k == 0,
                    line={"color": ORDER_COLORS[j % len(ORDER_COLORS)]},
                ),
                row=row,
                col=col,
            )
        fig.update_yaxes(title_text=f"[{unit}]", row=row, col=col)
        fig.update_xaxes(title_text="balance factor [%]", row=row, col=col)
    fig.update_layout(
        template=TEMPLATE,
        height=320 * rows,
        legend={"orientation": "h", "y": -0.08},
        title=f"Performance versus balance factor at {result.speed * 30 / math.pi:.0f} rpm",
    )
    return min_span(fig, PERFORMANCE_MIN_SPAN_SHARE)


def _stacked_figure(
    x: ArrayLike,
    panels: Sequence[tuple[str, str, Sequence[dict[str, Any]]]],
    x_title: str,
    title: str,
    height: int,
    **subplots: Any,
) -> go.Figure:
    """Histories stacked in rows over one shared x axis (the bench and engine-cycle figures).

    Parameters
    ----------
    x : array_like
        The shared abscissa of every trace that gives none of its own (time [s], crank
        angle [deg]).
    panels : sequence of (str, str, sequence of dict)
        One per row, top to bottom: its subplot title, its y-axis title (the unit, e.g.
        ``"[N]"``) and its traces, each the keyword arguments of a
        ``plotly.graph_objects.Scatter`` (``name``, ``y``, ``line``, ...; ``x`` when not
        the shared one).
    x_title : str
        Title of the x axis, written under the bottom row.
    title : str
        Title of the figure.
    height : int
        Height of the figure [px].
    **subplots
        Further arguments of ``plotly.subplots.make_subplots`` (e.g. ``row_heights``).

    Returns
    -------
    plotly.graph_objects.Figure
        The rows in order, the traces of a row in order, the legend below the figure.
    """
    go = plotly_go()
    fig = make_subplots(
        rows=len(panels),
        cols=1,
        shared_xaxes=True,
        vertical_spacing=0.06,
        subplot_titles=tuple(panel[0] for panel in panels),
        **subplots,
    )
    for row, (_, _, traces) in enumerate(panels, start=1):
        for trace in traces:
            fig.add_trace(go.Scatter(**{"x": x, **trace}), row=row, col=1)
    for row, (_, y_title, _) in enumerate(panels, start=1):
        fig.update_yaxes(title_text=y_title, row=row, col=1)
    fig.update_xaxes(title_text=x_title, row=len(panels), col=1)
    fig.update_layout(
        template=TEMPLATE,
        height=height,
        legend={"orientation": "h", "y": -0.08},
        title=title,
    )
    return fig


def bench_figure(result: BenchResult) -> go.Figure:
    """Rotor test bench time histories: speed, motor and friction torque, bearing loads
    (:class:`~crankbalance.physics.rotor_bench.BenchResult`)."""
    speed = {
        "name": "speed",
        "y": np.asarray(result.speed) * 30 / math.pi,
        "line": {"color": COLORS["total"]},
    }
    torques = [
        {"name": "motor torque", "y": result.motor_torque, "line": {"color": COLORS["forward"]}},
        {
            "name": "friction torque",
            "y": result.friction_torque,
            "line": {"color": COLORS["backward"]},
        },
    ]
    loads = [
        {
            "name": "bearing A",
            "y": result.bearing_load_a,
            "line": {"color": COLORS["counterweight"]},
        },
        {"name": "bearing B", "y": result.bearing_load_b, "line": {"color": COLORS["after"]}},
    ]
    return _stacked_figure(
        np.asarray(result.time),
        (
            ("Speed", "[rpm]", [speed]),
            ("Torque", "[N·m]", torques),
            ("Bearing loads", "[N]", loads),
        ),
        "time [s]",
        f"Test bench: required torque {result.required_torque:.4g} N·m, "
        f"friction power {result.friction_power:.4g} W",
        750,
    )


def cycle_figure(result: CycleResult) -> go.Figure:
    """Engine-cycle histories versus crank angle: torques, bearing load and shaking forces
    (:class:`~crankbalance.physics.engine_cycle.CycleResult`)."""
    torques = [
        {"name": f"{name} torque", "y": values, "line": {"color": color}}
        for name, values, color in (
            ("gas", result.gas_torque, COLORS["backward"]),
            ("inertia", result.inertia_torque, COLORS["forward"]),
            ("friction", result.friction_torque, COLORS["rotating"]),
            ("net", result.net_torque, COLORS["total"]),
        )
    ]
    load = {"name": "bearing load", "y": result.bearing_load, "line": {"color": COLORS["after"]}}
    shaking = [
        {
            "name": "shaking in-line",
            "y": result.shaking_inline,
            "line": {"color": COLORS["forward"], "dash": "dash"},
        },
        {
            "name": "shaking transverse",
            "y": result.shaking_transverse,
            "line": {"color": COLORS["backward"], "dash": "dash"},
        },
    ]
    return _stacked_figure(
        np.degrees(np.asarray(result.angle)),
        (
            ("Torques", "[N·m]", torques),
            ("Main-bearing load", "[N]", [load]),
            ("Shaking forces", "[N]", shaking),
        ),
        "crank angle [deg]",
        f"Engine cycle at {result.speed_mean * 30 / math.pi:.0f} rpm: "
        f"friction power {result.friction_power:.4g} W",
        750,
    )


def engine_torque_figure(result: EngineCycleResult | CycleResult) -> go.Figure:
    """The whole engine's torque over the cycle, each cylinder's share, and the speed
    (:class:`~crankbalance.physics.engine_cycle_all.EngineCycleResult`); a single-cylinder
    :class:`~crankbalance.physics.engine_cycle.CycleResult` gets :func:`cycle_figure`."""
    from ...physics.engine_cycle_all import EngineCycleResult

    if not isinstance(result, EngineCycleResult):
        return cycle_figure(result)
    deg = np.degrees(np.asarray(result.angle))
    torques = [
        {"name": f"{name} torque", "y": values, "line": {"color": color}}
        for name, values, color in (
            ("gas", result.gas_torque, COLORS["backward"]),
            ("inertia", result.inertia_torque, COLORS["forward"]),
            ("total", result.torque, COLORS["total"]),
        )
    ]
    torques.append(
        {
            "x": [deg[0], deg[-1]],
            "y": [result.mean_torque] * 2,
            "mode": "lines",
            "name": "mean torque",
            "line": {"color": COLORS["after"], "dash": "dash"},
        }
    )
    shares = np.asarray(result.cylinder_gas_torque) + np.asarray(result.cylinder_inertia_torque)
    cylinders = [
        {
            "name": f"cylinder {c + 1}",
            "y": values,
            "line": {"color": ORDER_COLORS[c % len(ORDER_COLORS)], "width": 1},
        }
        for c, values in enumerate(shares)
    ]
    speed = {
        "name": "speed",
        "y": np.asarray(result.speed) * 30 / math.pi,
        "line": {"color": COLORS["total"]},
    }
    return _stacked_figure(
        deg,
        (
            ("Crank torque", "[N·m]", torques),
            ("Torque of each cylinder (gas + inertia)", "[N·m]", cylinders),
            ("Speed", "[rpm]", [speed]),
        ),
        "crank angle from the first firing TDC [deg]",
        f"Engine cycle at {result.speed_mean * 30 / math.pi:.0f} rpm: mean torque "
        f"{result.mean_torque:.4g} N·m, speed fluctuation {100 * result.speed_fluctuation:.3g} %",
        800,
        row_heights=[0.4, 0.4, 0.2],
    )
