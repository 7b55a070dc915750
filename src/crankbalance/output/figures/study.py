"""The figures of a study's result, for a notebook: :func:`plot` (also
``crankbalance.plot``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ...errors import InputError
from .balancing import residuals_bar
from .counterweight import counterweight_profile, pareto_front
from .crank3d import crank_3d
from .engine import curves_figure, orders_bar, polar_figure
from .explore import explore_candidate, explore_points, explore_scatter
from .loads import bearing_loads_figure, bearing_sweep_figure
from .mounts import mode_shapes_figure, mounts_figure, mounts_layout_figure
from .performance import bench_figure, engine_torque_figure, sensitivity_figure
from .shaft import shaft_response_figure, shaft_study
from .shop import bob_weights_figure, hole_plan, matched_sets, scatter_histograms
from .single import (
    balance_factor_sweep,
    drilling_plan,
    rebalance_unbalance,
    single_cylinder_forces,
    single_cylinder_polar,
)
from .torsional import torsional_figure


def _drilling_plans(study: Any) -> list[Any]:
    """The drilling plan of every case of a rebalancing drilled with holes (a face removal
    has no plan to draw)."""
    from ...physics.rebalancing import DrilledHoles

    if study.crank_radius is None:
        return []
    return [
        drilling_plan(case, study.crank_radius)
        for case in study.cases
        if isinstance(case.correction, DrilledHoles)
    ]


def _shaft_note(result: Any) -> str | None:
    """What a shaft of ``shaft-inline4``/``shaft-inline3`` balances: its order (from the
    engine), none when the unbalance was given."""
    order = result.requirement.order
    return f"order-{order} shaft" if order else None


def _explore_scatter(result: Any) -> Any:
    """The candidates over the first two objectives, the Pareto set highlighted (the
    figure of ``crankbalance explore --plot``): the rows of the run's figure when it kept
    them (``figure_points``), else its top-N and Pareto set."""
    if len(result.objectives) < 2:
        return None
    run = result.figure or result.run
    shown = explore_points(run.top, run.pareto)
    x, y = result.objectives[0], result.objectives[1]
    return explore_scatter(shown, run.pareto, x, y, total=run.rows)


def _explore_best(result: Any) -> Any:
    """The free forces and moments of the best candidate by the top-N key."""
    top = result.run.top
    if not top or not len(next(iter(top.values()))):
        return None
    return explore_candidate({name: column[:1] for name, column in top.items()})


#: a study result's figure key (:func:`figure_key`: its class name, a shop result's with
#: the class of what it holds) -> the builders of its figures (each takes the result and
#: gives one figure, a list of figures, or none)
FIGURES: dict[str, tuple[Callable[[Any], Any], ...]] = {
    "Analysis": (
        orders_bar,
        curves_figure,
        lambda r: curves_figure(r, quantity="moment"),
        polar_figure,
        crank_3d,
    ),
    "BalanceStudy": (residuals_bar, crank_3d),
    "BalanceFactorResult": (
        lambda r: None if r.study is None else balance_factor_sweep(r.study),
        lambda r: None if r.study is None else single_cylinder_forces(r.study),
        lambda r: None if r.study is None else single_cylinder_polar(r.study),
    ),
    "RebalanceResult": (lambda r: rebalance_unbalance(r.study), lambda r: _drilling_plans(r.study)),
    "OptimizeResult": (lambda r: pareto_front(r.optimum),),
    "DesignResult": (lambda r: counterweight_profile(r.design, r.crank),),
    "PlacementResult": (
        lambda r: [shaft_study(s, r.requirement.engine, _shaft_note(r)) for s in r.studies],
    ),
    "CheckResult": (lambda r: shaft_response_figure(r.response, r.design),),
    "BenchStudy": (lambda r: [bench_figure(run) for run in r.runs],),
    "CycleStudy": (lambda r: engine_torque_figure(r.result),),
    "SensitivityStudy": (lambda r: sensitivity_figure(r.result),),
    "BearingStudy": (bearing_loads_figure,),
    "SweepStudy": (bearing_sweep_figure,),
    "TorsionalResult": (lambda r: torsional_figure(r.study),),
    "MountsResult": (mounts_figure, mounts_layout_figure, mode_shapes_figure),
    "ExploreResult": (_explore_scatter, _explore_best),
    "ShopResult.HolePlan": (lambda r: hole_plan(r.result),),
    "ShopResult.PartsStudy": (lambda r: matched_sets(r.result),),
    "ShopResult.BobWeights": (
        lambda r: bob_weights_figure(r.result, None if r.parts is None else r.parts.engine),
    ),
    "ShopResult.ScatterStudy": (lambda r: scatter_histograms(r.result),),
}

#: the results that have no figure, by figure key, and why (:func:`plot` says so)
NO_FIGURES: dict[str, str] = {
    "ToleranceResult": "the permissible unbalance of a grade, its split between two planes "
    "and the verdict on a residual are a few numbers, no curve (its display)",
    "FrictionResult": "the friction torque and power of one load case are a table (its "
    "display); the bench study draws them over time",
}


def figure_key(result: Any) -> str:
    """The key of ``result`` in :data:`FIGURES` and :data:`NO_FIGURES`: its class name, a
    shop result's with the class of what it holds (``ShopResult.HolePlan``)."""
    name = type(result).__name__
    if name == "ShopResult":
        return f"{name}.{type(result.result).__name__}"
    return name


def plot(result: Any) -> list[Any]:
    """The plotly figures of a study's result, as the command line and the web draw them;
    each displays itself in a notebook: ``crankbalance.plot(crankbalance.analyze("inline4"))``.

    Parameters
    ----------
    result : study result
        What a study returned: :class:`~crankbalance.studies.engine.Analysis` (orders,
        force and moment curves, polar diagram, 3-D crank), a balancing study (residuals,
        3-D crank with its counterweights), a balance-factor study, a rebalancing (the
        drilling plan of each target), a counterweight optimisation or design, a shaft
        check or placement, a bench study (one figure per speed), a cycle, a sensitivity,
        the bearing loads or their sweep, a torsional study, an explorer run (the
        candidates over two objectives with the Pareto set, the best candidate's orders),
        a mount study, a shop's matched sets (and the journals' bob-weights), its
        bob-weights, its scatter (the histograms with the quantiles and the tolerance),
        its hole plan.

    Returns
    -------
    list of plotly.graph_objects.Figure
        The result's figures.

    Raises
    ------
    InputError
        For a result without figures, saying why (:data:`NO_FIGURES`), or not a study's.
    """
    key = figure_key(result)
    if key in NO_FIGURES:
        raise InputError("result", key, f"has no figure: {NO_FIGURES[key]}")
    if key not in FIGURES:
        raise InputError("result", key, "a study result with figures: " + ", ".join(FIGURES))
    figures: list[Any] = []
    for build in FIGURES[key]:
        made = build(result)
        figures += made if isinstance(made, list) else [] if made is None else [made]
    return figures
