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
from .loads import bearing_loads_figure, bearing_sweep_figure
from .performance import engine_torque_figure, sensitivity_figure
from .shaft import shaft_response_figure, shaft_study
from .shop import hole_plan
from .single import balance_factor_sweep, single_cylinder_forces, single_cylinder_polar
from .torsional import torsional_figure

#: a study result's class name -> the builders of its figures (each takes the result and
#: gives one figure or none); a result of another class has no figure
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
    "OptimizeResult": (lambda r: pareto_front(r.optimum),),
    "DesignResult": (lambda r: counterweight_profile(r.design),),
    "CheckResult": (lambda r: shaft_response_figure(r.response, r.design),),
    "CycleStudy": (lambda r: engine_torque_figure(r.result),),
    "SensitivityStudy": (lambda r: sensitivity_figure(r.result),),
    "BearingStudy": (bearing_loads_figure,),
    "SweepStudy": (bearing_sweep_figure,),
    "TorsionalResult": (lambda r: torsional_figure(r.study),),
    "ShopResult": (
        lambda r: hole_plan(r.result) if type(r.result).__name__ == "HolePlan" else None,
    ),
}


def plot(result: Any) -> list[Any]:
    """The plotly figures of a study's result, as the command line and the web draw them;
    each displays itself in a notebook: ``crankbalance.plot(crankbalance.analyze("inline4"))``.

    Parameters
    ----------
    result : study result
        What a study returned: :class:`~crankbalance.studies.engine.Analysis` (orders,
        force and moment curves, polar diagram, 3-D crank), a balancing study (residuals,
        3-D crank with its counterweights), a balance-factor study, a counterweight
        optimisation or design, a shaft check or placement, a cycle, a sensitivity, the
        bearing loads or their sweep, a torsional study, a hole plan.

    Returns
    -------
    list of plotly.graph_objects.Figure
        The result's figures.
    """
    name = type(result).__name__
    if name == "PlacementResult":
        return [shaft_study(s) for s in result.studies]
    if name not in FIGURES:
        raise InputError("result", name, "a study result with figures: " + ", ".join(FIGURES))
    figures = (build(result) for build in FIGURES[name])
    return [f for f in figures if f is not None]
