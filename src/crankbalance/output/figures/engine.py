"""Figures of the engine analysis (:func:`crankbalance.studies.engine.analyze`): the free
forces and moments by order, versus crank angle (with the engine before and after
balancing when a :class:`~crankbalance.studies.engine.BalanceStudy` is given) and as the
rotating-vector diagram of one order.

Public functions
----------------
- ``orders_bar(analysis) -> Figure``
    Force and moment amplitudes per order, forward/backward phasor magnitudes stacked.
- ``curves_figure(analysis, balance_study=None, quantity="force", orders=None) -> Figure``
    x and z components versus crank angle: reciprocating total, each order, rotating
    masses, and the whole engine after balancing when a BalanceStudy is given
    (:func:`crankbalance.output.figures.balancing.balanced_curves`). ``quantity`` in
    {"force", "moment"}.
- ``polar_figure(analysis, order=1, quantity="force") -> Figure``
    Rotating-vector diagram of one order: locus and the forward/backward phasors at
    crank angle 0.
- ``leading_quantity(analysis) -> "force" | "moment"``
    The quantity a user should see first.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from ...results import number, round_off
from ..format import moment_point
from .balancing import balanced_curves
from .common import (
    COLORS,
    ORDER_COLORS,
    TEMPLATE,
    Quantity,
    figure_title,
    make_subplots,
    note_if_zero,
    plotly_go,
    zero_below,
)

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ...physics.shaking import Curves
    from ...studies.engine import Analysis, BalanceStudy
    from .balancing import BalancedCurves


def _check_quantity(quantity: str) -> None:
    if quantity not in ("force", "moment"):
        raise InputError("quantity", quantity, "'force' or 'moment'")


def _unit(quantity: str) -> str:
    return "N" if quantity == "force" else "N·m"


def leading_quantity(analysis: Analysis) -> Quantity:
    """The quantity a user should see first: ``"moment"`` when every free force (every
    order and the bare crank's rotating masses) is below round-off but a moment is not
    (e.g. an in-line 3), else ``"force"``."""
    f = analysis.forces
    tf, tm = round_off(analysis.model)
    forces = np.append(np.asarray(f.force_amplitude, dtype=float), abs(f.rotating_force))
    moments = np.append(np.asarray(f.moment_amplitude, dtype=float), abs(f.rotating_couple))
    if np.all(forces < tf) and np.any(moments >= tm):
        return "moment"
    return "force"


#: the gap between the panels of :func:`orders_bar`, a share of the figure's width: room
#: for the value axis's tick labels (the panels have no axis title: the unit is in the
#: panel's title)
ORDERS_BAR_GAP = 0.1
#: the top margin of :func:`orders_bar` [px]: its title (two lines) over its panels'
#: two-line titles
ORDERS_BAR_TOP = 140
#: the titles of :func:`orders_bar`'s panels, each with its unit
ORDERS_BAR_TITLES = (
    "Free forces<br>(x, z) [N]",
    "Free moments<br>(x, z) [N·m]",
    "Roll moment<br>(y) [N·m]",
)


def orders_bar(analysis: Analysis) -> go.Figure:
    """Force and moment amplitudes per order, forward and backward phasors stacked, and the
    roll moment's.

    The stacked bar height is the amplitude :math:`|F_n^+| + |F_n^-|` (the largest
    magnitude over a revolution, ``analysis.forces.force_amplitude``); the rotating masses
    of the bare crank are shown as an extra forward bar labelled "rot". The third panel is
    the sixth component, the roll moment about y (``analysis.forces.roll_amplitude``, a
    real curve of each order: one bar). Each panel's title gives its unit; the value axes
    have no title of their own (no room between three panels in a half-width web card).
    """
    f = analysis.forces
    fig = make_subplots(
        rows=1,
        cols=3,
        # the unit in each panel's title, no value-axis title: three panels side by side in
        # a half-width web card (560 px at 1280) left no room between them for one, and the
        # roll panel's "amplitude [N·m]" was drawn over the moment panel's last bar
        # (two lines each: one line of three titles runs into its neighbours at that width)
        subplot_titles=ORDERS_BAR_TITLES,
        horizontal_spacing=ORDERS_BAR_GAP,
    )
    labels = [str(int(n)) for n in f.orders] + ["rot"]
    tf, tm = round_off(analysis.model)  # as Analysis.to_dict
    parts = (
        (
            1,
            zero_below(np.abs(f.force_forward), tf),
            zero_below(np.abs(f.force_backward), tf),
            zero_below([abs(f.rotating_force)], tf)[0],
        ),
        (
            2,
            zero_below(np.abs(f.couple_forward), tm),
            zero_below(np.abs(f.couple_backward), tm),
            zero_below([abs(f.rotating_couple)], tm)[0],
        ),
    )
    for col, fwd, bwd, rot in parts:
        unit = "N" if col == 1 else "N·m"
        note_if_zero(fig, np.append(fwd + bwd, rot), unit, 1, col, "" if col == 1 else "2")
        fig.add_trace(
            plotly_go().Bar(
                x=labels,
                y=np.append(fwd, rot),
                name="forward (co-rotating)",
                marker_color=COLORS["forward"],
                legendgroup="forward",
                showlegend=col == 1,
                hovertemplate="order %{x}<br>forward %{y:.4g} " + unit + "<extra></extra>",
            ),
            row=1,
            col=col,
        )
        fig.add_trace(
            plotly_go().Bar(
                x=labels,
                y=np.append(bwd, 0.0),
                name="backward (counter-rotating)",
                marker_color=COLORS["backward"],
                legendgroup="backward",
                showlegend=col == 1,
                hovertemplate="order %{x}<br>backward %{y:.4g} " + unit + "<extra></extra>",
            ),
            row=1,
            col=col,
        )
        fig.update_xaxes(title_text="order", type="category", row=1, col=col)
    roll = zero_below(np.append(f.roll_amplitude, abs(f.rotating_roll)), tm)
    note_if_zero(fig, roll, "N·m", 1, 3, "3")
    fig.add_trace(
        plotly_go().Bar(
            x=labels,
            y=roll,
            name="roll (about y)",
            marker_color=COLORS["forward"],
            marker_pattern_shape="/",
            hovertemplate="order %{x}<br>roll %{y:.4g} N·m<extra></extra>",
        ),
        row=1,
        col=3,
    )
    fig.update_xaxes(title_text="order", type="category", row=1, col=3)
    fig.update_layout(
        barmode="stack",
        template=TEMPLATE,
        title=figure_title("Free forces and moments by order", analysis.model.name),
        legend={"orientation": "h", "y": -0.2},
        margin={"t": ORDERS_BAR_TOP},  # room for the title over the panels' two-line titles
    )
    return fig


def curves_figure(
    analysis: Analysis,
    balance_study: BalanceStudy | None = None,
    quantity: Quantity = "force",
    orders: int | None = None,
) -> go.Figure:
    """x and z components of the free force (or moment) versus crank angle.

    Traces: the reciprocating total (exact slider-crank when the model is exact), each
    order (orders above 2 hidden until clicked in the legend), the rotating masses of the
    bare crank and, with ``balance_study``, the whole engine before and after balancing.

    Parameters
    ----------
    analysis : Analysis
    balance_study : BalanceStudy, optional
    quantity : {"force", "moment"}
    orders : int, optional
        Highest order drawn (all computed orders by default).
    """
    _check_quantity(quantity)
    go = plotly_go()
    c = analysis.curves()
    deg = np.degrees(c.angle)
    unit = _unit(quantity)
    key = "f" if quantity == "force" else "m"
    fig = make_subplots(
        rows=2,
        cols=1,
        shared_xaxes=True,
        vertical_spacing=0.08,
        subplot_titles=(f"{quantity} x (across)", f"{quantity} z (cylinder axis)"),
    )
    after = balanced_curves(analysis, balance_study, c.angle) if balance_study else None
    amplitude = (
        analysis.forces.force_amplitude if quantity == "force" else analysis.forces.moment_amplitude
    )
    top = len(c.orders) if orders is None else orders
    tiny = round_off(analysis.model)[0 if quantity == "force" else 1]

    def y(source: Curves | BalancedCurves, name: str, k: int | None = None) -> NDArray[np.float64]:
        values = getattr(source, name)
        return zero_below(values if k is None else values[k], tiny)

    def add(row: int, values: NDArray[np.float64], group: str, **trace: Any) -> None:
        """One curve in ``row``, in the legend (``group``) once, from the top row."""
        scatter = go.Scatter(x=deg, y=values, legendgroup=group, showlegend=row == 1, **trace)
        fig.add_trace(scatter, row=row, col=1)

    for row, comp in ((1, "x"), (2, "z")):
        total = {"color": COLORS["total"], "width": 2.5}
        add(row, y(c, f"total_{key}{comp}"), "total", name="reciprocating total", line=total)
        for k, n in enumerate(c.orders):
            if n > top or amplitude[k] < tiny:
                continue
            add(
                row,
                y(c, f"{key}{comp}", k),
                f"order{n}",
                name=f"order {int(n)}",
                line={
                    "color": ORDER_COLORS[(int(n) - 1) % len(ORDER_COLORS)],
                    "width": 1.2,
                    "dash": "dot",
                },
                visible=True if n <= 2 else "legendonly",
            )
        add(
            row,
            y(c, f"rotating_{key}{comp}"),
            "rotating",
            name="rotating masses (bare crank)",
            line={"color": COLORS["rotating"], "width": 1.5, "dash": "dash"},
            visible=True if after is None else "legendonly",
        )
        if after is not None:
            for when, width in (("before", 2), ("after", 2.5)):
                add(
                    row,
                    y(after, f"{when}_{key}{comp}"),
                    when,
                    name=f"engine {when} balancing",
                    line={"color": COLORS[when], "width": width},
                )
        fig.update_yaxes(title_text=f"{quantity} {comp} [{unit}]", row=row, col=1)
    fig.update_xaxes(
        title_text="crank angle [deg]",
        tickvals=list(range(0, 361, 45)),
        range=[0, 360],
        row=2,
        col=1,
    )
    fig.update_xaxes(tickvals=list(range(0, 361, 45)), range=[0, 360], row=1, col=1)
    name = "forces"
    if quantity == "moment":
        name = f"moments about {moment_point(analysis.model.moment_point)}".replace(
            "the crankshaft mid-point", "the mid-point"
        )
    fig.update_layout(
        template=TEMPLATE,
        title=figure_title(f"Free {name}", analysis.model.name),
        legend={"orientation": "h", "y": -0.15},
        hovermode="x unified",
    )
    return fig


def _order_phasors(
    analysis: Analysis, order: int | str, quantity: str
) -> tuple[complex, complex, int, str]:
    """Forward and backward phasor (complex z + i x, moment as iC) of one order."""
    f = analysis.forces
    if order in ("rotating", "rot", 0):
        if quantity == "force":
            return complex(f.rotating_force), 0j, 1, "rotating masses"
        return 1j * complex(f.rotating_couple), 0j, 1, "rotating masses"
    if isinstance(order, bool) or not isinstance(order, int | np.integer):
        raise InputError("order", order, f"a whole number in {f.orders.tolist()} or 'rotating'")
    try:
        k = f.order(int(order))
    except KeyError:
        raise InputError(
            "order",
            order,
            f"an order computed: {int(f.orders[0])}..{int(f.orders[-1])} or 'rotating'",
        ) from None
    if quantity == "force":
        return (
            complex(f.force_forward[k]),
            complex(f.force_backward[k]),
            int(order),
            f"order {order}",
        )
    return (
        1j * complex(f.couple_forward[k]),
        1j * complex(f.couple_backward[k]),
        int(order),
        f"order {order}",
    )


def polar_figure(
    analysis: Analysis, order: int | str = 1, quantity: Quantity = "force"
) -> go.Figure:
    r"""Rotating-vector diagram of one order: :math:`F_n(\theta) = F^+e^{in\theta} +
    F^-e^{-in\theta}` traced over a revolution (an ellipse; a circle when one phasor is
    zero, a line when both are equal), with the forward and backward phasors drawn at crank
    angle 0 (head to tail) and their resultant.

    x is drawn horizontally, z (cylinder axis of an in-line engine) vertically.
    ``order`` may be ``"rotating"`` for the rotating masses of the bare crank.
    """
    _check_quantity(quantity)
    go = plotly_go()
    fwd, bwd, n, label = _order_phasors(analysis, order, quantity)
    tiny = round_off(analysis.model)[0 if quantity == "force" else 1]
    fwd, bwd = (0j if abs(fwd) < tiny else fwd), (0j if abs(bwd) < tiny else bwd)
    unit = _unit(quantity)
    theta = np.linspace(0.0, 2 * np.pi / max(n, 1), 361)
    locus = fwd * np.exp(1j * n * theta) + bwd * np.exp(-1j * n * theta)
    fig = go.Figure()
    fig.add_trace(
        go.Scatter(
            x=locus.imag,
            y=locus.real,
            mode="lines",
            name="locus",
            line={"color": COLORS["total"], "width": 2},
            hovertemplate="x %{x:.4g}<br>z %{y:.4g}<extra></extra>",
        )
    )

    def arrow(start: complex, end: complex, name: str, color: str) -> None:
        fig.add_trace(
            go.Scatter(
                x=[start.imag, end.imag],
                y=[start.real, end.real],
                mode="lines+markers",
                name=name,
                line={"color": color, "width": 3},
                marker={"size": [0, 10], "symbol": "arrow", "angleref": "previous", "color": color},
            )
        )

    arrow(0j, fwd, f"forward |F+| = {number(abs(fwd), 5)} {unit}", COLORS["forward"])
    arrow(fwd, fwd + bwd, f"backward |F-| = {number(abs(bwd), 5)} {unit}", COLORS["backward"])
    arrow(0j, fwd + bwd, f"at crank angle 0: {number(abs(fwd + bwd), 5)} {unit}", COLORS["after"])
    amplitude = abs(fwd) + abs(bwd)
    reach = 1.15 * amplitude if amplitude > 0 else _zero_reach(analysis, quantity, tiny)
    fig.update_xaxes(title_text=f"x [{unit}]", range=[-reach, reach], zeroline=True)
    fig.update_yaxes(
        title_text=f"z [{unit}]",
        range=[-reach, reach],
        zeroline=True,
        scaleanchor="x",
        scaleratio=1,
    )
    word = "force" if quantity == "force" else "moment"
    size = f"{number(amplitude, 5)} {unit}" if amplitude > 0 else f"0 {unit} (balanced)"
    fig.update_layout(
        template=TEMPLATE,
        width=None,
        title=figure_title(f"{label.capitalize()} {word}: amplitude {size}", analysis.model.name),
        legend={"orientation": "h", "y": -0.15},
    )
    return fig


def _zero_reach(analysis: Analysis, quantity: str, tiny: float) -> float:
    """Axis half-range [N or N·m] of a polar diagram whose order is balanced: the largest
    amplitude of that quantity at any order (so the zero reads against the engine's own
    scale), else 1 N (1 N·m) when the whole quantity is balanced."""
    f = analysis.forces
    if quantity == "force":
        values = np.append(np.asarray(f.force_amplitude, dtype=float), abs(f.rotating_force))
    else:
        values = np.append(np.asarray(f.moment_amplitude, dtype=float), abs(f.rotating_couple))
    largest = float(np.max(values))
    return 1.15 * largest if largest >= tiny else 1.0
