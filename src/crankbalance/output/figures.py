r"""Figure builders: one function per figure, shared by the web app, the report and
``crankbalance plot``. Each takes a result object (compute apart from plot) and returns a
``plotly.graph_objects.Figure``; plotly is imported inside the functions.

This module owns how results look (traces, axes, titles, colours) and nothing else: the
numbers come from the result objects and the physics modules (the balancing masses' time
histories from :func:`crankbalance.physics.balancing.point_mass_history`), and turning a figure
into a PNG, SVG or HTML file is :mod:`crankbalance.output.render`'s job.

It is longer than the ~800 lines the layout aims at because it holds one builder per
figure of every study (eighteen builders, 30-190 lines each) around one shared palette and title
style; splitting it by study would spread that style over several modules for no gain in
cohesion (each builder depends only on the palette and helpers at the top).

Public functions
----------------
Engine analysis and balancing (:mod:`crankbalance.studies.engine`):

- ``orders_bar(analysis) -> Figure``
    Force and moment amplitudes per order, forward/backward phasor magnitudes stacked.
- ``curves_figure(analysis, balance_study=None, quantity="force") -> Figure``
    x and z components versus crank angle: reciprocating total, each order, rotating
    masses, and the whole engine after balancing when a BalanceStudy is given.
    ``quantity`` in {"force", "moment"}.
- ``balanced_curves(analysis, balance_study, angle=None) -> BalancedCurves``
    The numbers behind the "after balancing" traces (also for CSV export).
- ``polar_figure(analysis, order, quantity="force") -> Figure``
    Rotating-vector diagram of one order: locus and the forward/backward phasors at
    crank angle 0.
- ``crank_3d(model, balance_study=None) -> Figure``
    3-D view of the crankshaft: journals, throws, webs, cylinder axes, counterweights
    (marker size from mass), balance shafts with their masses (schematic positions).
- ``residuals_bar(balance_study) -> Figure``
    Amplitude of every component before and after balancing (force and moment).

Other studies:

- ``single_cylinder_forces(study) -> Figure``       (single_cylinder.BalanceFactorStudy)
- ``single_cylinder_polar(study) -> Figure``
- ``balance_factor_sweep(study) -> Figure``
- ``pareto_front(optimum) -> Figure``               (counterweight.CounterweightOptimum)
- ``counterweight_profile(design) -> Figure``       (counterweight.CounterweightDesign)
- ``drilling_plan(result, crank_radius) -> Figure`` (single_cylinder.RebalanceResult)
- ``shaft_study(study) -> Figure``                  (balance_shaft placement studies)
- ``shaft_response_figure(response) -> Figure``     (balance_shaft.ShaftResponse)
- ``sensitivity_figure(result) -> Figure``          (engine_cycle.SensitivityResult)
- ``bench_figure(result) -> Figure``                (rotor_bench.BenchResult)
- ``cycle_figure(result) -> Figure``                (engine_cycle.CycleResult)
- ``engine_torque_figure(result) -> Figure``        (engine_cycle_all.EngineCycleResult)
- ``bearing_loads_figure(studies, model) -> Figure`` (studies.loads.BearingStudy, one or
    several overlaid): polar load diagram per main bearing, bending moment per journal

Design-space explorer (:mod:`crankbalance.physics.explore`, rows of its run):

- ``explore_scatter(rows, pareto, x, y) -> Figure`` candidates over two objectives, the
    Pareto set highlighted, hover text per candidate
- ``explore_candidate(row) -> Figure``              one candidate's free forces and moments

Conventions
-----------
Vectors across the crank axis are complex ``z + i x`` (:mod:`crankbalance.physics.shaking`); the
diagrams draw x horizontally and z (cylinder axis of an in-line engine) vertically. The 3-D
view puts the crank axis y horizontally. Angles are shown in degrees, forces in N,
moments in N·m, lengths in mm, masses in kg.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..results import ResultMixin
from .format import depth_read_to, moment_point

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ..physics.model import EngineModel
    from ..studies.engine import Analysis, BalanceStudy

Quantity = Literal["force", "moment"]

#: colours used consistently across figures
COLORS = {
    "forward": "#1f77b4",
    "backward": "#ff7f0e",
    "total": "#222222",
    "rotating": "#9467bd",
    "after": "#d62728",
    "before": "#7f7f7f",
    "counterweight": "#2ca02c",
    "shaft1": "#17becf",
    "shaft2": "#bcbd22",
    "crank": "#555555",
}
ORDER_COLORS = [
    "#1f77b4",
    "#ff7f0e",
    "#2ca02c",
    "#d62728",
    "#9467bd",
    "#8c564b",
    "#e377c2",
    "#7f7f7f",
    "#bcbd22",
    "#17becf",
]
TEMPLATE = "plotly_white"


def _go() -> Any:
    import plotly.graph_objects as go

    return go


def _subplots(**kwargs: Any) -> Any:
    from plotly.subplots import make_subplots

    return make_subplots(**kwargs)


def _check_quantity(quantity: str) -> None:
    if quantity not in ("force", "moment"):
        raise InputError("quantity", quantity, "'force' or 'moment'")


def roundoff_levels(model: EngineModel, relative: float = 1e-10) -> tuple[float, float]:
    """Round-off levels of an engine's forces [N] and moments [N·m]: values below are
    drawn as zero (sums of phasors that cancel leave ~1e-12 N of noise)."""
    mass = float(np.sum(model.reciprocating_mass) + np.sum(model.throw_rotating_mass))
    force = mass * model.crank_radius * model.speed**2
    length = max(float(np.ptp(model.throw_position)), model.crank_radius)
    return relative * force, relative * force * length


def _clean(values: ArrayLike, tiny: float) -> NDArray[np.float64]:
    out = np.array(values, dtype=float)
    out[np.abs(out) < tiny] = 0.0
    return out


def _unit(quantity: str) -> str:
    return "N" if quantity == "force" else "N·m"


#: longest engine name shown under a figure title (longer names end in "…")
TITLE_NAME_CHARS = 70


def figure_title(main: str, engine: str | None = None, note: str | None = None) -> str:
    """A figure title that fits a half-width web panel: what the figure shows on the first
    line, the engine name (shortened to :data:`TITLE_NAME_CHARS`) and a note on a second
    line in smaller type."""
    second = []
    if engine:
        name = " ".join(str(engine).split())
        if len(name) > TITLE_NAME_CHARS:
            name = name[: TITLE_NAME_CHARS - 1].rstrip(" ,;:-") + "…"
        second.append(name)
    if note:
        second.append(note)
    if not second:
        return main
    return f"{main}<br><sup>{' · '.join(second)}</sup>"


def leading_quantity(analysis: Analysis) -> Quantity:
    """The quantity a user should see first: ``"moment"`` when every free force (every
    order and the bare crank's rotating masses) is below round-off but a moment is not
    (e.g. an in-line 3), else ``"force"``."""
    f = analysis.forces
    tf, tm = roundoff_levels(analysis.model, 1e-12)
    forces = np.append(np.asarray(f.force_amplitude, dtype=float), abs(f.rotating_force))
    moments = np.append(np.asarray(f.moment_amplitude, dtype=float), abs(f.rotating_couple))
    if np.all(forces < tf) and np.any(moments >= tm):
        return "moment"
    return "force"


def _note_if_zero(fig: Any, values: ArrayLike, unit: str, row: int, col: int, ref: str) -> None:
    """Say so in a subplot whose bars are all exactly zero (instead of an empty -1..1 axis)."""
    if np.any(np.asarray(values, dtype=float) != 0.0):
        return
    fig.update_yaxes(range=[0, 1], row=row, col=col)
    fig.add_annotation(
        text=f"0 {unit} everywhere<br>(balanced)",
        showarrow=False,
        xref=f"x{ref} domain",
        yref=f"y{ref} domain",
        x=0.5,
        y=0.5,
        font={"size": 14, "color": COLORS["before"]},
    )


# --------------------------------------------------------------------------- orders
def orders_bar(analysis: Analysis) -> go.Figure:
    """Force and moment amplitudes per order, forward and backward phasors stacked.

    The stacked bar height is the amplitude :math:`|F_n^+| + |F_n^-|` (the largest
    magnitude over a revolution, ``analysis.forces.force_amplitude``); the rotating masses
    of the bare crank are shown as an extra forward bar labelled "rot".
    """
    f = analysis.forces
    fig = _subplots(
        rows=1, cols=2, subplot_titles=("Free forces", "Free moments"), horizontal_spacing=0.12
    )
    labels = [str(int(n)) for n in f.orders] + ["rot"]
    tf, tm = roundoff_levels(analysis.model, 1e-12)  # as Analysis.to_dict
    parts = (
        (
            1,
            _clean(np.abs(f.force_forward), tf),
            _clean(np.abs(f.force_backward), tf),
            _clean([abs(f.rotating_force)], tf)[0],
        ),
        (
            2,
            _clean(np.abs(f.couple_forward), tm),
            _clean(np.abs(f.couple_backward), tm),
            _clean([abs(f.rotating_couple)], tm)[0],
        ),
    )
    for col, fwd, bwd, rot in parts:
        unit = "N" if col == 1 else "N·m"
        _note_if_zero(fig, np.append(fwd + bwd, rot), unit, 1, col, "" if col == 1 else "2")
        fig.add_trace(
            _go().Bar(
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
            _go().Bar(
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
        fig.update_yaxes(title_text=f"amplitude [{unit}]", row=1, col=col)
        fig.update_xaxes(title_text="order", type="category", row=1, col=col)
    fig.update_layout(
        barmode="stack",
        template=TEMPLATE,
        title=figure_title("Free forces and moments by order", analysis.model.name),
        legend={"orientation": "h", "y": -0.2},
    )
    return fig


# --------------------------------------------------------------------------- curves
@dataclass(frozen=True)
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
    solver's own time-domain check uses).
    Moments about the crankshaft mid-point, :math:`M = iC` (``M_x = y F_z``,
    ``M_z = -y F_x``).
    """
    _check_same_engine(analysis, balance_study)
    c = analysis.curves(angle)
    from ..physics.balancing import point_mass_history

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
    go = _go()
    c = analysis.curves()
    deg = np.degrees(c.angle)
    unit = _unit(quantity)
    key = "f" if quantity == "force" else "m"
    fig = _subplots(
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
    tiny = roundoff_levels(analysis.model)[0 if quantity == "force" else 1]

    def y(source: Any, name: str, k: int | None = None) -> NDArray[np.float64]:
        values = getattr(source, name)
        return _clean(values if k is None else values[k], tiny)

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
        name = f"moments about {moment_point(analysis.model.moment_reference)}".replace(
            "the crankshaft mid-point", "the mid-point"
        )
    fig.update_layout(
        template=TEMPLATE,
        title=figure_title(f"Free {name}", analysis.model.name),
        legend={"orientation": "h", "y": -0.15},
        hovermode="x unified",
    )
    return fig


# --------------------------------------------------------------------------- polar
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
    go = _go()
    fwd, bwd, n, label = _order_phasors(analysis, order, quantity)
    tiny = roundoff_levels(analysis.model, 1e-12)[0 if quantity == "force" else 1]
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

    arrow(0j, fwd, f"forward |F+| = {abs(fwd):.4g} {unit}", COLORS["forward"])
    arrow(fwd, fwd + bwd, f"backward |F-| = {abs(bwd):.4g} {unit}", COLORS["backward"])
    arrow(0j, fwd + bwd, f"at crank angle 0: {abs(fwd + bwd):.4g} {unit}", COLORS["after"])
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
    size = f"{amplitude:.4g} {unit}" if amplitude > 0 else f"0 {unit} (balanced)"
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


# --------------------------------------------------------------------------- 3-D crank
#: the 3-D crank's frame: room around the drawing on every side, as a share of its largest
#: extent; the shortest axis drawn at least this share of the longest (a single's crank is
#: a few mm long, a radial's cylinders reach 400 mm: the short axis keeps its scale and
#: gets empty room, so its tick labels do not crowd); tick labels per axis of full length;
#: the camera's direction (from the front, a little from the right and above)
SCENE_MARGIN = 0.08
SCENE_MIN_ASPECT = 0.4
SCENE_TICKS = 8
SCENE_EYE = (0.7, -1.9, 0.6)
#: the view the camera's distance is fitted to: plotly's vertical field of view [rad], the
#: width / height of the scene it must fit (a half-width web card; a wider figure only
#: gains room), and the share of that view the box may fill
SCENE_FOV = math.pi / 4
SCENE_VIEW_ASPECT = 1.25
SCENE_FILL = 0.7


def scene_box_fits(ratios: ArrayLike, eye: ArrayLike) -> bool:
    """Whether the eight corners of a plotly scene box (sides ``ratios``, the aspect
    ratios, centred on the origin) seen in perspective from ``eye`` (looking at the
    centre, z up, vertical field of view :data:`SCENE_FOV`) lie within
    :data:`SCENE_FILL` of a view :data:`SCENE_VIEW_ASPECT` times as wide as high."""
    position = np.asarray(eye, dtype=float)
    forward = -position / np.linalg.norm(position)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half = np.asarray(ratios, dtype=float) / 2
    corners = np.array(np.meshgrid(*[(-h, h) for h in half])).reshape(3, -1).T
    relative = corners - position
    depth = relative @ forward
    if np.any(depth <= 0):
        return False
    tangent = math.tan(SCENE_FOV / 2) * SCENE_FILL
    across = np.abs(relative @ right) / depth
    high = np.abs(relative @ up) / depth
    return bool(np.all(across <= tangent * SCENE_VIEW_ASPECT) and np.all(high <= tangent))


def _fitted_eye(ratios: Sequence[float]) -> NDArray[np.float64]:
    """The camera along :data:`SCENE_EYE` at the least distance (to 1 %) from which the
    box of ``ratios`` fits the view (:func:`scene_box_fits`)."""
    direction = np.asarray(SCENE_EYE, dtype=float)
    direction /= np.linalg.norm(direction)
    near, far = 0.1, 50.0
    while far / near > 1.01:
        middle = math.sqrt(near * far)
        near, far = (near, middle) if scene_box_fits(ratios, middle * direction) else (middle, far)
    return far * direction


#: no tick label within this share of an axis' length from its ends, where three axes meet
#: and their labels would run into each other
SCENE_TICK_EDGE = 0.1


def _scene_ticks(span: Sequence[float], count: int) -> list[float]:
    """At most about ``count`` round tick values (1, 2 or 5 times a power of ten apart) in
    ``span``, none within :data:`SCENE_TICK_EDGE` of its ends."""
    low, high = float(span[0]), float(span[1])
    edge = SCENE_TICK_EDGE * (high - low)
    raw = (high - low) / max(count, 1)
    power = 10.0 ** math.floor(math.log10(raw))
    step = next(f * power for f in (1.0, 2.0, 5.0, 10.0) if f * power >= raw)
    first = math.ceil((low + edge) / step)
    last = math.floor((high - edge) / step)
    return [clean_tick(k * step) for k in range(first, last + 1)]


def clean_tick(value: float) -> float:
    """A tick value without float noise (``3 * 0.1`` -> ``0.3``, no ``-0.0``)."""
    return float(f"{value:.12g}") + 0.0


def crank_3d_scene(traces: list[dict[str, Any]]) -> dict[str, Any]:
    """The scene of the 3-D crank that frames every trace: per axis a range holding every
    point of ``traces`` (plotly ``scatter3d`` dictionaries, ``None`` breaks skipped) with
    :data:`SCENE_MARGIN` of room, widened about its centre to at least
    :data:`SCENE_MIN_ASPECT` of the longest; the box to scale (aspect ratio of the
    ranges), at most :data:`SCENE_TICKS` tick labels on the longest axis and fewer on the
    shorter ones, and the camera along :data:`SCENE_EYE` as near as the whole box fits
    the view (:func:`scene_box_fits`)."""
    lows, highs = [], []
    for key in ("x", "y", "z"):
        values = [float(v) for t in traces for v in t.get(key, []) if v is not None]
        lows.append(min(values, default=-1.0))
        highs.append(max(values, default=1.0))
    largest = max(max(h - lo for lo, h in zip(lows, highs, strict=True)), 1.0)
    pad = SCENE_MARGIN * largest
    ranges = []
    for lo, h in zip(lows, highs, strict=True):
        half = max((h - lo) / 2 + pad, SCENE_MIN_ASPECT * (largest / 2 + pad))
        centre = (lo + h) / 2
        ranges.append([centre - half, centre + half])
    longest = max(h - lo for lo, h in ranges)
    ratios = [(h - lo) / longest for lo, h in ranges]
    eye = _fitted_eye(ratios)
    # tick labels by the length an axis shows: its share of the box, foreshortened by the
    # angle it makes with the line of sight (an axis seen end-on would crowd its labels)
    sight = eye / np.linalg.norm(eye)
    shown = [ratio * math.sqrt(max(0.0, 1.0 - sight[k] ** 2)) for k, ratio in enumerate(ratios)]
    axes = {
        f"{key}axis": {
            "range": span,
            "tickmode": "array",
            "tickvals": _scene_ticks(span, max(2, round(SCENE_TICKS * length))),
        }
        for key, span, length in zip(("x", "y", "z"), ranges, shown, strict=True)
    }
    return {
        **axes,
        "aspectmode": "manual",
        "aspectratio": dict(zip(("x", "y", "z"), ratios, strict=True)),
        "camera": {"eye": dict(zip(("x", "y", "z"), (float(v) for v in eye), strict=True))},
    }


def crank_3d(
    model: EngineModel | Analysis | BalanceStudy, balance_study: BalanceStudy | None = None
) -> go.Figure:
    """3-D view of the crankshaft at crank angle 0 (lengths in mm).

    Crank axis y drawn horizontally. Main journals on the axis, each throw's crankpin at
    the crank radius in its direction, two webs per throw (a quarter pitch from the throw
    mid-plane, as the balancing solver assumes), the cylinder axes as thin lines, and with
    ``balance_study`` the counterweights (at their CG radius and direction; marker size
    grows with the square root of the mass) and the balance-shaft masses. Shafts are drawn
    beside the crank at a schematic distance (their position across the crank does not
    enter the balance).
    """
    from ..physics.balancing import default_web_offset

    go = _go()
    m: Any = model
    if hasattr(m, "model"):
        if balance_study is None and hasattr(m, "result"):
            balance_study = m
        m = m.model
    mm = 1e3
    r = m.crank_radius
    web = default_web_offset(m)
    pos = m.throw_position
    span = float(np.ptp(pos)) if m.throws > 1 else 0.0
    end = span / 2 + 2 * web
    middle = -m.moment_reference  # the crank's mid-point, from the moment reference point
    # one trace per legend entry, kind (lines or markers) and style: segments joined with
    # None breaks, hover text and marker size per point (a few traces build and draw much
    # faster than one per segment: plotly validates every trace)
    traces: dict[tuple[str, str, str], dict[str, Any]] = {}

    def trace(mode: str, name: str, show: bool, **style: Any) -> dict[str, Any]:
        key = (mode, name, repr(style))
        if key not in traces:
            traces[key] = {
                "type": "scatter3d",
                "mode": mode,
                "name": name,
                "legendgroup": style.pop("group", name),
                "showlegend": show,
                "x": [],
                "y": [],
                "z": [],
                "text": [],
                **style,
            }
        t = traces[key]
        t["showlegend"] = t["showlegend"] or show
        return t

    def line(
        ys: tuple[float, float],
        xs: tuple[float, float],
        zs: tuple[float, float],
        name: str,
        color: str,
        width: float,
        group: str,
        show: bool,
        dash: str = "solid",
        text: str | None = None,
    ) -> None:
        t = trace(
            "lines",
            name,
            show,
            group=group,
            line={"color": color, "width": width, "dash": dash},
            hoverinfo="text" if text else "name",
        )
        for out, values in ((t["x"], ys), (t["y"], xs), (t["z"], zs)):
            if out:
                out.append(None)
            out.extend(v * mm for v in values)
        t["text"].extend(([None] if len(t["text"]) else []) + [text, text])

    def marker(
        y: float, x: float, z: float, name: str, color: str, size: float, show: bool, text: str
    ) -> None:
        t = trace("markers", name, show, marker={"color": color, "opacity": 0.9}, hoverinfo="text")
        t["marker"].setdefault("size", []).append(size)
        for out, v in ((t["x"], y), (t["y"], x), (t["z"], z)):
            out.append(v * mm)
        t["text"].append(text)

    # main journals: the crank axis between and beyond the throws
    line(
        (middle - end, middle + end),
        (0, 0),
        (0, 0),
        "crank axis / main journals",
        COLORS["crank"],
        8,
        "axis",
        True,
    )
    for t in range(m.throws):
        phi = m.throw_angle[t]
        px, pz = r * math.sin(phi), r * math.cos(phi)
        y0, y1 = pos[t] - web, pos[t] + web
        text = (
            f"throw {t + 1}: angle {math.degrees(phi) % 360:.1f} deg, y {pos[t] * mm:.1f} mm,"
            f" rotating mass {m.throw_rotating_mass[t]:.3f} kg"
        )
        line((y0, y1), (px, px), (pz, pz), "crankpins", "#1f3b73", 12, "pin", True, text=text)
        for yw in (y0, y1):
            line((yw, yw), (0, px), (0, pz), "webs", "#6b6b6b", 6, "web", True)
    # cylinder axes from the crankpin's top-dead-centre circle outward
    for c in range(m.cylinders):
        beta = m.cylinder_bank[c]
        y = m.cylinder_position[c]
        r0, r1 = r + m.rod_length, r + m.rod_length + 2 * r
        line(
            (y, y),
            (r0 * math.sin(beta), r1 * math.sin(beta)),
            (r0 * math.cos(beta), r1 * math.cos(beta)),
            "cylinder axes (stroke)",
            "#c7c7c7",
            10,
            "cyl",
            True,
            text=f"cylinder {c + 1}: bank {math.degrees(beta):.1f} deg",
        )
    if balance_study is not None:
        res = balance_study.result
        masses = [
            cw.mass for cw in (res.counterweights, res.extra_counterweights) if cw is not None
        ]
        for group in (res.primary, res.secondary):
            if group is not None:
                masses += [np.array([x.mass for s in group.shafts for x in s.masses])]
        biggest = max((float(np.max(a, initial=0.0)) for a in masses), default=0.0)

        def size(mass: float) -> float:
            return 4.0 + 14.0 * math.sqrt(mass / biggest) if biggest > 0 else 4.0

        for label, cw, color in (
            ("counterweights", res.counterweights, COLORS["counterweight"]),
            ("extra counterweights (Eq. 17)", res.extra_counterweights, "#98df8a"),
        ):
            if cw is None or cw.count == 0:
                continue
            for j in range(cw.count):
                d, rho = float(cw.direction[j]), cw.cg_radius
                cx, cz, y = rho * math.sin(d), rho * math.cos(d), float(cw.position[j])
                line((y, y), (0, cx), (0, cz), label, color, 5, label, False)
                marker(
                    y,
                    cx,
                    cz,
                    label,
                    color,
                    size(float(cw.mass[j])),
                    True,
                    f"{label}: web {int(cw.web[j])}, {cw.mass[j]:.4g} kg at "
                    f"{rho * mm:.1f} mm, {math.degrees(d) % 360:.1f} deg",
                )
        # balance shafts beside the crank (schematic): primary left/right of the crank at
        # the height of the axis, secondary below; co-rotating on one side
        gap = 2.5 * r + 0.02
        for group, zc, color in (
            (res.primary, 0.0, COLORS["shaft1"]),
            (res.secondary, -(r + 0.5 * m.rod_length), COLORS["shaft2"]),
        ):
            if group is None:
                continue
            half = group.length / 2
            for s in group.shafts:
                xc = -gap if s.sense > 0 else gap
                sense = "co-rotating" if s.sense > 0 else "counter-rotating"
                label = f"order-{group.order} shaft, {sense}"
                line(
                    (-half, half),
                    (xc, xc),
                    (zc, zc),
                    label,
                    color,
                    6,
                    label,
                    True,
                    dash="solid" if s.sense > 0 else "dash",
                )
                for x in s.masses:
                    rho = s.cg_radius
                    mx, mz = xc + rho * math.sin(x.phase), zc + rho * math.cos(x.phase)
                    arm = (x.position, x.position), (xc, mx), (zc, mz)
                    line(*arm, label, color, 4, label, False)
                    marker(
                        x.position,
                        mx,
                        mz,
                        label,
                        color,
                        size(x.mass),
                        False,
                        f"{label}: {x.mass:.4g} kg at {rho * mm:.1f} mm, y "
                        f"{x.position * mm:.1f} mm, phase {math.degrees(x.phase):.1f} deg",
                    )
    for drawn in traces.values():
        if not any(drawn["text"]):
            del drawn["text"]
    scene = crank_3d_scene(list(traces.values()))
    scene["xaxis"]["title"] = {"text": "y, crank axis [mm]"}
    scene["yaxis"]["title"] = {"text": "x [mm]"}
    scene["zaxis"]["title"] = {"text": "z [mm]"}
    layout = {
        "template": TEMPLATE,
        "title": {"text": figure_title("Crankshaft at crank angle 0", m.name)},
        "scene": scene,
        "legend": {"orientation": "h", "y": -0.05},
        "margin": {"l": 0, "r": 0, "t": 50, "b": 0},
    }
    # one validated construction (update_layout afterwards would validate the template twice)
    return go.Figure(data=list(traces.values()), layout=layout)


# --------------------------------------------------------------------------- residuals
def residuals_bar(balance_study: BalanceStudy) -> go.Figure:
    """Amplitude of every component (rotating masses, orders 1..K) before and after
    balancing, force and moment, from the solver's time-domain check
    (``balance_study.result.residuals``); values below round-off of the engine's force
    scale (:func:`roundoff_levels`) are drawn as zero."""
    go = _go()
    res = balance_study.result.residuals
    tiny = dict(zip(("force", "moment"), roundoff_levels(balance_study.model), strict=True))
    names = [
        ("rotating" if c.component == "rotating" else c.component.replace("order", "order "))
        + (" *" if c.targeted else "")
        for c in res
    ]
    fig = _subplots(rows=1, cols=2, subplot_titles=("Force", "Moment"), horizontal_spacing=0.12)
    for col, attr, unit in ((1, "force", "N"), (2, "moment", "N·m")):
        _note_if_zero(
            fig,
            _clean(
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
                    y=_clean([getattr(c, f"{attr}_{when}") for c in res], tiny[attr]),
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


# --------------------------------------------------------------------------- single cylinder
def single_cylinder_forces(study: Any) -> go.Figure:
    """In-line, transverse and resultant shaking force of one cylinder versus crank angle
    (:class:`~crankbalance.physics.single_cylinder.BalanceFactorStudy`)."""
    go = _go()
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
        f"peak resultant {study.peak_resultant:.4g} N",
        legend={"orientation": "h", "y": -0.2},
    )
    return fig


def single_cylinder_polar(study: Any) -> go.Figure:
    """Polar diagram of the residual shaking force of one cylinder: the tip of the force
    vector over a revolution (transverse horizontal, in-line vertical), with the circle of
    the peak resultant."""
    go = _go()
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
    ring = np.linspace(0, 2 * np.pi, 181)
    peak = study.peak_resultant
    fig.add_trace(
        go.Scatter(
            x=peak * np.sin(ring),
            y=peak * np.cos(ring),
            mode="lines",
            name=f"peak resultant {peak:.4g} N",
            line={"color": COLORS["before"], "dash": "dot"},
        )
    )
    p = study.primary_force
    fig.add_trace(
        go.Scatter(
            x=p * np.sin(ring),
            y=p * np.cos(ring),
            mode="lines",
            name=f"primary force P = {p:.4g} N (no balance)",
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


def balance_factor_sweep(study: Any) -> go.Figure:
    """Peak resultant shaking force versus balance factor, with the studied factor and the
    optimum marked."""
    go = _go()
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
            f"{study.optimum_peak_resultant:.4g} N",
            marker={"color": COLORS["counterweight"], "size": 12},
        )
    )
    fig.add_trace(
        go.Scatter(
            x=[100 * study.balance_factor],
            y=[study.peak_resultant],
            mode="markers",
            name=f"studied {study.balance_factor:.1%}: {study.peak_resultant:.4g} N",
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


# --------------------------------------------------------------------------- counterweight
def _web_drawing(fig: go.Figure, reach: float, title: str) -> go.Figure:
    """Finish a to-scale drawing of one crank web seen along the crank axis (the
    counterweight profile, the drilling plan): the crank axis marked at the origin, x and
    y in mm on equal scales over ``[-reach, reach]``, the legend below.

    Parameters
    ----------
    fig : plotly.graph_objects.Figure
        The drawing, its traces in mm; changed in place.
    reach : float
        Half the width and height of the drawn square [mm].
    title : str
        Title of the figure.

    Returns
    -------
    plotly.graph_objects.Figure
        ``fig``.
    """
    fig.add_trace(
        _go().Scatter(
            x=[0.0],
            y=[0.0],
            mode="markers",
            name="crank axis",
            marker={"color": "black", "size": 10, "symbol": "cross-thin", "line": {"width": 2}},
        )
    )
    fig.update_xaxes(title_text="x [mm]", range=[-reach, reach])
    fig.update_yaxes(title_text="y [mm]", range=[-reach, reach], scaleanchor="x", scaleratio=1)
    fig.update_layout(template=TEMPLATE, legend={"orientation": "h", "y": -0.2}, title=title)
    return fig


def pareto_front(optimum: Any, max_points: int = 4000) -> go.Figure:
    """Counterweight designs: every feasible design found (a sample of at most
    ``max_points``), the Pareto front of mass versus radial space, and the least-mass and
    least-radius designs (:class:`~crankbalance.physics.counterweight.CounterweightOptimum`)."""
    go = _go()
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
    fig.add_trace(
        go.Scatter(
            x=radius[front],
            y=mass[front],
            mode="lines+markers",
            name=f"Pareto front ({front.size})",
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


def counterweight_profile(design: Any) -> go.Figure:
    """The counterweight profile drawn to scale (mm): the outline, the web circle it sits on,
    the crank axis and the centre of gravity
    (:class:`~crankbalance.physics.counterweight.CounterweightDesign`)."""
    go = _go()
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
    ring = np.linspace(0, 2 * np.pi, 181)
    r = design.web_radius * 1e3
    fig.add_trace(
        go.Scatter(
            x=r * np.cos(ring),
            y=r * np.sin(ring),
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
    return _web_drawing(
        fig,
        1.1 * max(float(props.outer_radius) * 1e3, r),
        f"Counterweight: {float(props.mass) * 1e3:.1f} g, thickness "
        f"{design.thickness * 1e3:.2f} mm, outer radius "
        f"{float(props.outer_radius) * 1e3:.2f} mm",
    )


def _radial_hole(holes: Any, depth: float, rim: float, phi: float) -> tuple[Any, Any]:
    """Outline (x, y) [mm] of a hole drilled inward from the rim at radius ``rim`` [mm],
    at ``phi`` [rad] from straight down, seen from the side: the full diameter down to the
    shoulder, then the drill point to the tip (a flat bottom for a 180° point); ``depth``
    [m] as read (:func:`crankbalance.physics.shop.holes.hole_geometry`)."""
    from ..physics.shop.holes import hole_geometry

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


def drilling_plan(result: Any, crank_radius: float) -> go.Figure:
    """The drilled holes of a rebalancing to scale (mm), one web seen along the crank axis:
    the crank axis, the crankpin centre straight up, the holes on the counterweight side
    (180 deg from the crankpin) and a schematic counterweight outline
    (:class:`~crankbalance.physics.single_cylinder.RebalanceResult` with a
    :class:`~crankbalance.physics.single_cylinder.DrilledHoles` correction; ``crank_radius``
    [m])."""
    go = _go()
    holes = result.correction
    if getattr(holes, "kind", "") != "holes":
        raise InputError("correction", getattr(holes, "kind", None), "the plan draws holes")
    depth = result.iterations[-1].depth if result.iterations else 0.0
    to = depth_read_to(holes.point_angle, holes.depth_to)
    d, rh, r = holes.diameter * 1e3, holes.radius * 1e3, crank_radius * 1e3
    fig = go.Figure()
    outer = rh + 1.5 * d
    arc = np.radians(np.linspace(120.0, 240.0, 61)) + np.pi / 2  # around straight down
    ring = np.linspace(0, 2 * np.pi, 73)
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
                x, y = cx + d / 2 * np.cos(ring), cy + d / 2 * np.sin(ring)
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
    return _web_drawing(fig, 1.15 * max(outer, r), figure_title("Drilling plan", note=what))


# --------------------------------------------------------------------------- balance shaft
def shaft_study(study: Any) -> go.Figure:
    """Balance-shaft placement study (Kim 2018, Figs. 6-9): bearing loads, bending measure
    and first bending frequency along the design variable, and the normalised measures with
    the objective J and its optimum
    (:class:`~crankbalance.physics.balance_shaft.PlacementStudy`)."""
    go = _go()
    x = 100 * np.asarray(study.positions)
    fig = _subplots(
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
        title=f"Balance-shaft placement study ({study.case})",
    )
    return fig


def shaft_response_figure(response: Any, shaft: Any = None) -> go.Figure:
    """Deflection amplitude along a balance shaft
    (:class:`~crankbalance.physics.balance_shaft.ShaftResponse`); with ``shaft``
    (:class:`~crankbalance.physics.balance_shaft.BalanceShaft`) the bearings and masses are
    marked."""
    go = _go()
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


# --------------------------------------------------------------------------- performance
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


def sensitivity_figure(result: Any, indicators: tuple[str, ...] | None = None) -> go.Figure:
    """Performance indicators versus balance factor, one line per reciprocating-mass scale
    (:class:`~crankbalance.physics.engine_cycle.SensitivityResult`)."""
    go = _go()
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
    fig = _subplots(
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
    return fig


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
    go = _go()
    fig = _subplots(
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


def bench_figure(result: Any) -> go.Figure:
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


def cycle_figure(result: Any) -> go.Figure:
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


# ------------------------------------------------------------------ main-bearing loads
#: line styles of the studies a bearing-load figure overlays (first: solid)
STUDY_DASHES = ("solid", "dash", "dot", "dashdot")


def bearing_loads_figure(
    studies: Any, model: str = "indeterminate", labels: tuple[str, ...] | None = None
) -> go.Figure:
    """Polar load diagram of every main bearing (top row: the force of the crank on the
    bearing over the cycle, x across horizontally, z along the cylinder axis vertically)
    and the bending moment at every journal over the cycle (bottom) of one crank model
    (:class:`~crankbalance.studies.loads.BearingStudy`, or a sequence of them overlaid,
    e.g. 4 and 8 counterweights; ``labels`` names each)."""
    if model not in ("determinate", "indeterminate"):
        raise InputError("model", model, "'determinate' or 'indeterminate'")
    go = _go()
    many = list(studies) if isinstance(studies, (list, tuple)) else [studies]
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
    fig = _subplots(
        rows=2,
        cols=cols,
        specs=[[{} for _ in range(cols)], [{"colspan": cols}] + [None] * (cols - 1)],
        row_heights=[0.45, 0.55],
        vertical_spacing=0.14,
        horizontal_spacing=0.03,
        subplot_titles=[f"bearing {k + 1}" for k in range(cols)]
        + [f"bending moment at the journals ({model} crank)"],
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
)


def bearing_sweep_figure(sweep: Any) -> go.Figure:
    """Bearing loads against balance (:class:`~crankbalance.studies.balance_loads.
    SweepStudy`): the largest bearing load, the friction of all main bearings, the largest
    bending moment at a journal and the counterweight mass against the balance factor, one
    line per pattern (``none`` a dotted level), and the peak load of every bearing per case
    (bars), all of the sweep's crank model."""
    go = _go()
    model = sweep.options.crank_model
    data = sweep.to_dict()
    fig = _subplots(
        rows=3,
        cols=2,
        specs=[[{}, {}], [{}, {}], [{"colspan": 2}, None]],
        row_heights=[0.3, 0.3, 0.4],
        vertical_spacing=0.1,
        horizontal_spacing=0.1,
        subplot_titles=[title for _, title in SWEEP_PANELS]
        + [f"peak load of each bearing per case ({model} crank)"],
    )
    factors = [float(f) for f in sweep.options.balance_factors]
    span = [min(factors), max(factors)] if factors else [0.0, 1.0]
    patterns = list(dict.fromkeys(case["pattern"] for case in data["cases"]))
    for n, pattern in enumerate(patterns):
        cases = [c for c in data["cases"] if c["pattern"] == pattern]
        color = ORDER_COLORS[n % len(ORDER_COLORS)]
        none = pattern == "none"
        for p, (key, title) in enumerate(SWEEP_PANELS):
            values = [c[key] if key in c else c["models"][model][key] for c in cases]
            fig.add_trace(
                go.Scatter(
                    x=span if none else [c["balance_factor"] for c in cases],
                    y=values * 2 if none else values,
                    mode="lines" if none else "lines+markers",
                    name=pattern,
                    legendgroup=pattern,
                    showlegend=p == 0,
                    line={"color": color, "dash": "dot" if none else "solid"},
                    hovertemplate=f"{pattern}<br>balance factor %{{x:.3g}}<br>"
                    f"{title.split(' [')[0]} %{{y:.4g}}<extra></extra>",
                ),
                row=1 + p // 2,
                col=1 + p % 2,
            )
    bearings = [b["bearing"] for b in data["cases"][0]["models"][model]["bearings"]]
    for case in data["cases"]:
        label = case["pattern"] + (
            "" if case["balance_factor"] is None else f", f_b {case['balance_factor']:.3g}"
        )
        fig.add_trace(
            go.Bar(
                x=[f"bearing {k}" for k in bearings],
                y=[b["max_load_N"] for b in case["models"][model]["bearings"]],
                name=label,
                showlegend=False,
                marker={"color": ORDER_COLORS[patterns.index(case["pattern"]) % len(ORDER_COLORS)]},
                hovertemplate=f"{label}<br>%{{x}}<br>peak %{{y:.4g}} N<extra></extra>",
            ),
            row=3,
            col=1,
        )
    for p, (_, title) in enumerate(SWEEP_PANELS):
        fig.update_xaxes(title_text="balance factor", row=1 + p // 2, col=1 + p % 2)
        unit = title.split(" [")[-1].rstrip("]")
        fig.update_yaxes(title_text=unit, row=1 + p // 2, col=1 + p % 2)
    fig.update_yaxes(title_text="N", row=3, col=1)
    speed = data["settings"]["speed_rad_s"] * 30 / math.pi
    fig.update_layout(
        template=TEMPLATE,
        barmode="group",
        height=900,
        width=1000,
        legend={"orientation": "h", "y": -0.08},
        title=figure_title(
            f"Main-bearing loads against balance ({model} crank)",
            data["engine"]["name"],
            f"{speed:.0f} rpm",
        ),
    )
    return fig


def engine_torque_figure(result: Any) -> go.Figure:
    """The whole engine's torque over the cycle, each cylinder's share, and the speed
    (:class:`~crankbalance.physics.engine_cycle_all.EngineCycleResult`); a single-cylinder
    :class:`~crankbalance.physics.engine_cycle.CycleResult` gets :func:`cycle_figure`."""
    if not hasattr(result, "cylinder_gas_torque"):
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


def torsional_figure(study: Any) -> go.Figure:
    """Campbell diagram and forced response of the crank train
    (:class:`~crankbalance.physics.torsional.TorsionalStudy`): top, the natural frequencies [Hz]
    and the engine-order lines f = n · rpm / 60 over the speed range, a marker at every
    resonance sized by its relative excitation; bottom, the front end's amplitude and the
    crank's twist (front end to flywheel) summed over the orders, and the damper power."""
    go = _go()
    rpm = np.asarray(study.response.speed) * 30 / math.pi
    orders = np.asarray(study.excitation.orders)
    fig = _subplots(
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


# ------------------------------------------------------------------ design-space explorer
#: most candidates an explorer scatter draws (the best by the top-N key and the Pareto set)
EXPLORE_POINTS = 50_000


def _column_label(name: str) -> str:
    """An explorer column as an axis title: ``F2_N`` -> ``F2 [N]``, ``M1_Nm`` -> ``M1 [N·m]``."""
    for suffix, unit in (("_Nm", "N·m"), ("_N", "N"), ("_kg", "kg"), ("_rad", "rad")):
        if name.endswith(suffix):
            return f"{name[: -len(suffix)]} [{unit}]"
    return name


def explore_points(*parts: dict[str, Any]) -> dict[str, NDArray[Any]]:
    """The rows of explorer results (a run's top-N list, its Pareto set), each candidate
    once (by its enumeration index), by increasing index: the points of
    :func:`explore_scatter`."""
    parts = tuple(p for p in parts if p and np.asarray(p["index"]).size)
    if not parts:
        return {}
    joined = {name: np.concatenate([np.asarray(p[name]) for p in parts]) for name in parts[0]}
    _, first = np.unique(joined["index"], return_index=True)
    return {name: values[first] for name, values in joined.items()}


def explore_hover(rows: dict[str, Any], names: tuple[str, ...]) -> list[str]:
    """One hover text per row: the firing order, the throw angles [deg], the values of
    ``names``."""
    out = []
    for i in range(np.asarray(rows["index"]).size):
        order = "-".join(str(int(c)) for c in rows["firing_order"][i])
        throws = ", ".join(f"{math.degrees(a) % 360:.0f}" for a in rows["throw_angle_rad"][i])
        values = "<br>".join(f"{n} = {float(rows[n][i]):.5g}" for n in names)
        out.append(f"firing order {order}<br>throws [deg]: {throws}<br>{values}")
    return out


def explore_scatter(
    rows: dict[str, Any],
    pareto: dict[str, Any],
    x: str,
    y: str,
    title: str = "Candidates",
    total: int | None = None,
) -> go.Figure:
    """Explorer candidates over two objectives (columns of
    :func:`crankbalance.physics.explore.merit.merit`), the Pareto set highlighted.

    ``rows`` are the candidates drawn (each with ``index``, ``firing_order``,
    ``throw_angle_rad`` and the columns ``x`` and ``y``), ``pareto`` the run's Pareto set
    (drawn over them), ``total`` the candidates the run kept (said in the legend when more
    than drawn). Each point carries its enumeration index as ``customdata`` (what a click
    gives) and a hover text with its firing order, throw angles and values.
    """
    go = _go()
    fig = go.Figure()
    names = tuple(dict.fromkeys((x, y)))
    for part, label, color, size in (
        (rows, "candidates", COLORS["before"], 6),
        (pareto, "Pareto set", COLORS["after"], 10),
    ):
        n = np.asarray(part.get("index", ())).size if part else 0
        if not n:
            continue
        shown = f"{label} ({n}" + (f" of {total})" if label == "candidates" and total else ")")
        scatter = go.Scattergl if n > 5000 else go.Scatter  # SVG slows down past that
        fig.add_trace(
            scatter(
                x=np.asarray(part[x], dtype=float),
                y=np.asarray(part[y], dtype=float),
                mode="markers",
                name=shown,
                customdata=np.asarray(part["index"], dtype=np.int64),
                hovertext=explore_hover(part, names),
                hoverinfo="text",
                marker={"color": color, "size": size, "line": {"width": 0}},
            )
        )
    fig.update_xaxes(title_text=_column_label(x))
    fig.update_yaxes(title_text=_column_label(y))
    fig.update_layout(
        template=TEMPLATE,
        legend={"orientation": "h", "y": -0.2},
        title=figure_title(title, note=f"{x} against {y}, both minimised"),
    )
    return fig


def explore_candidate(row: dict[str, Any], orders: int = 4) -> go.Figure:
    """One explorer candidate's leading figures: free force and free moment of orders 1 to
    ``orders`` (forward and backward stacked), the firing order in the title. ``row`` is one
    row of the explorer's columns (scalars, or arrays of one element)."""
    go = _go()
    fig = _subplots(rows=1, cols=2, subplot_titles=("free force [N]", "free moment [N·m]"))

    def value(name: str) -> float:
        return float(np.asarray(row.get(name, np.nan)).reshape(-1)[0])

    found = [n for n in range(1, orders + 1) if f"F{n}f_N" in row]
    labels = [str(n) for n in found]
    for col, (letter, unit) in enumerate((("F", "N"), ("M", "Nm")), start=1):
        for part, name in (("f", "forward"), ("b", "backward")):
            fig.add_trace(
                go.Bar(
                    x=labels,
                    y=[value(f"{letter}{n}{part}_{unit}") for n in found],
                    name=name,
                    marker_color=COLORS[name],
                    showlegend=col == 1,
                ),
                row=1,
                col=col,
            )
    fig.update_xaxes(title_text="order")
    order = "-".join(str(int(c)) for c in np.asarray(row["firing_order"]).reshape(-1))
    fig.update_layout(
        template=TEMPLATE,
        barmode="stack",
        legend={"orientation": "h", "y": -0.2},
        title=figure_title("Leading figures of merit", note=f"firing order {order}"),
    )
    return fig


# --------------------------------------------------------------------------- balance shop
#: font size of the hole plan's panel titles [px]
HOLE_TITLE_SIZE = 12


def hole_plan(result: Any) -> go.Figure:
    """The holes of a two-plane correction to scale (mm), one panel per correction plane,
    seen along the crank axis: 0° (crankpin 1) straight up, angles counterclockwise as the
    crank's throw angles; the hole circle, the heavy spot, each hole with its angle and the
    depth (:class:`~crankbalance.studies.shop.HolePlan`)."""
    go = _go()
    # two short lines per panel, so that the two titles stay apart on a phone (a panel is
    # about 180 px wide there: tests/web/test_web_shop.py measures them at 390 px)
    titles = [
        f"plane {j + 1} at {p * 1e3:.4g} mm<br>{h.number} × Ø{h.diameter * 1e3:.3g} mm, "
        f"{h.depth * 1e3:.4g} mm to {h.depth_to}"
        for j, (p, h) in enumerate(zip(result.plan.correction_planes, result.holes, strict=True))
    ]
    fig = _subplots(rows=1, cols=2, subplot_titles=titles, horizontal_spacing=0.14)
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
