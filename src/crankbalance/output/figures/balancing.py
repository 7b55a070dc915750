"""Figures of the engine after balancing (:func:`crankbalance.studies.engine.balance_engine`):
the residual of every component before and after balancing, and the numbers behind the
"after balancing" curves of :func:`crankbalance.output.figures.engine.curves_figure`.

Public functions
----------------
- ``residuals_bar(balance_study) -> Figure``
    Amplitude of every component before and after balancing (force and moment).
- ``balanced_curves(analysis, balance_study, angle=None) -> BalancedCurves``
    Whole-engine force and moment versus crank angle before and after balancing (also
    for CSV export).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError
from ...records import record
from ...results import ResultMixin, round_off
from .common import (
    COLORS,
    TEMPLATE,
    figure_title,
    make_subplots,
    note_if_zero,
    plotly_go,
    zero_below,
)

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...studies.engine import Analysis, BalanceStudy


@record
class BalancedCurves(ResultMixin):
    """Whole-engine force [N] and moment [N·m] versus crank angle [rad], before and after
    balancing: reciprocating masses (exact or series, as the model says), rotating masses,
    and, after, every counterweight and balance-shaft mass as a point mass."""

    angle: NDArray[np.float64]
    before_fx: NDArray[np.float64]
    before_fz: NDArray[np.float64]
    before_mx: NDArray[np.float64]
    before_mz: NDArray[np.float64]
    after_fx: NDArray[np.float64]
    after_fz: NDArray[np.float64]
    after_mx: NDArray[np.float64]
    after_mz: NDArray[np.float64]


def balanced_curves(
    analysis: Analysis, balance_study: BalanceStudy, angle: ArrayLike | None = None
) -> BalancedCurves:
    """Whole-engine force and moment versus crank angle before and after balancing.

    "Before" is the reciprocating total of ``analysis`` plus the rotating masses of the
    bare crank; "after" adds every counterweight and shaft mass of ``balance_study``, as
    point masses (:func:`crankbalance.physics.balancing.point_mass_history`, the history the
    time-domain verification of a balance uses, :mod:`crankbalance.physics.balance_check`).
    Moments about the crankshaft mid-point, :math:`M = iC` (``M_x = y F_z``,
    ``M_z = -y F_x``).
    """
    _check_same_engine(analysis, balance_study)
    c = analysis.curves(angle)
    from ...physics.balancing import point_mass_history

    res = balance_study.result
    force, couple = point_mass_history(
        balance_study.model.speed,
        c.angle,
        [
            (cw.moments, cw.position)
            for cw in (res.counterweights, res.extra_counterweights)
            if cw is not None
        ],
        (res.primary, res.secondary),
    )
    moment = 1j * couple
    bfx = c.total_fx + c.rotating_fx
    bfz = c.total_fz + c.rotating_fz
    bmx = c.total_mx + c.rotating_mx
    bmz = c.total_mz + c.rotating_mz
    return BalancedCurves(
        angle=c.angle,
        before_fx=bfx,
        before_fz=bfz,
        before_mx=bmx,
        before_mz=bmz,
        after_fx=bfx + force.imag,
        after_fz=bfz + force.real,
        after_mx=bmx + moment.imag,
        after_mz=bmz + moment.real,
    )


def _check_same_engine(analysis: Analysis, balance_study: BalanceStudy) -> None:
    a, b = analysis.model, balance_study.model
    same = (
        a.throws == b.throws
        and a.cylinders == b.cylinders
        and math.isclose(a.speed, b.speed, rel_tol=1e-9)
        and np.allclose(a.throw_angle, b.throw_angle)
        and np.allclose(a.throw_position, b.throw_position)
    )
    if not same:
        raise InputError(
            "balance_study", b.name, f"a balancing study of the analysed engine ({a.name})"
        )


def residuals_bar(balance_study: BalanceStudy) -> go.Figure:
    """Amplitude of every component (rotating masses, orders 1..K) before and after
    balancing, force and moment, from the solver (``balance_study.result.residuals``: every
    balancing mass added back to the free forces); values at most the round-off of the
    engine's force
    scale (:func:`crankbalance.results.round_off`) are drawn as zero."""
    go = plotly_go()
    res = balance_study.result.residuals
    tiny = dict(zip(("force", "moment"), round_off(balance_study.model), strict=True))
    names = [
        ("rotating" if c.component == "rotating" else c.component.replace("order", "order "))
        + (" *" if c.targeted else "")
        for c in res
    ]
    fig = make_subplots(rows=1, cols=2, subplot_titles=("Force", "Moment"), horizontal_spacing=0.12)
    for col, attr, unit in ((1, "force", "N"), (2, "moment", "N·m")):
        note_if_zero(
            fig,
            zero_below(
                [getattr(c, f"{attr}_{when}") for c in res for when in ("before", "after")],
                tiny[attr],
            ),
            unit,
            1,
            col,
            "" if col == 1 else "2",
        )
        for when, color in (("before", COLORS["before"]), ("after", COLORS["after"])):
            fig.add_trace(
                go.Bar(
                    x=names,
                    y=zero_below([getattr(c, f"{attr}_{when}") for c in res], tiny[attr]),
                    name=f"{when} balancing",
                    marker_color=color,
                    legendgroup=when,
                    showlegend=col == 1,
                    hovertemplate="%{x}<br>" + when + " %{y:.4g} " + unit + "<extra></extra>",
                ),
                row=1,
                col=col,
            )
        fig.update_yaxes(title_text=f"amplitude [{unit}]", row=1, col=col)
        fig.update_xaxes(type="category", row=1, col=col)
    fig.update_layout(
        barmode="group",
        template=TEMPLATE,
        title=figure_title(
            "Residuals before and after balancing",
            balance_study.model.name,
            "* targeted by counterweights or shafts",
        ),
        legend={"orientation": "h", "y": -0.2},
    )
    return fig
