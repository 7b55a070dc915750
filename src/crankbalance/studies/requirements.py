"""What the counterweight and balance-shaft designers need from an engine: the first
moment one crank counterweight must carry, and the unbalance one balance shaft must carry.

Both come from the balancing solver (:func:`crankbalance.studies.engine.balance_engine`),
so the command line, the web application and the report size the same parts.
"""

from __future__ import annotations

from typing import Literal

import numpy as np

from ..errors import InputError
from ..physics.balancing import ShaftOptions
from ..physics.counterweight import required_first_moment
from ..records import record
from ..results import ResultMixin
from ..schema.engine import EngineSpec
from .engine import Analysis, BalanceStudy, EngineLike, balance_engine


def counterweight_requirement(study: BalanceStudy, web: int | None = None) -> float:
    """First moment m_c r_c [kg m] of the heaviest crank counterweight of a balanced engine
    (or of counterweight ``web``, 1-based)."""
    counterweights = study.result.counterweights
    if counterweights is None or counterweights.count == 0:
        raise InputError(
            "engine",
            study.model.name,
            "its balancing has no crank counterweight (give it a [counterweights] table)",
        )
    return required_first_moment(counterweights, web)


@record
class ShaftRequirement(ResultMixin):
    """The unbalance one balance shaft must carry.

    Attributes
    ----------
    order : int
        1 (primary) or 2 (secondary).
    unbalance : float
        Largest first moment of one shaft mass [kg m].
    speed : float
        Shaft speed [rad/s] (order times crank speed).
    arrangement : str
        "counter-rotating" (order 1: a single shaft, its co-rotating half on the crank, the
        inline-3 module of Kim 2018) or "pair" (order 2: two shafts at twice crank speed,
        the inline-4 Lanchester module).
    """

    order: int
    unbalance: float
    speed: float
    arrangement: str


def default_shaft_order(analysis: Analysis) -> int:
    """The order a balance shaft of this engine is for: 2 when the engine has a free
    second-order force or moment, else 1 (a free first-order one), else an error."""
    f = analysis.to_dict()
    for order in (2, 1):
        row_f = f["free_forces"][order - 1]
        row_m = f["free_moments"][order - 1]
        if row_f["amplitude_N"] > 0 or row_m["amplitude_Nm"] > 0:
            return order
    raise InputError(
        "engine",
        analysis.model.name,
        "has no free first- or second-order force or moment for a balance shaft to carry",
    )


def shaft_requirement(
    engine: EngineLike, order: int, length: float, cg_radius: float = 0.02
) -> ShaftRequirement:
    """The unbalance one balance shaft of an engine must carry, from the balancing solver.

    Parameters
    ----------
    engine : str, path or EngineSpec
        Preset name, engine file or validated spec.
    order : {1, 2}
        1: a single counter-rotating shaft, its co-rotating half on the crank; 2: a pair of
        shafts at twice crank speed.
    length : float
        Distance between the outer masses of the shaft [m].
    cg_radius : float
        Radius of the shaft masses' centre of gravity [m]; the first moment returned does
        not depend on it.
    """
    if order not in (1, 2):
        raise InputError("order", order, "must be 1 (primary) or 2 (secondary)")
    if not isinstance(engine, EngineSpec | str) and not hasattr(engine, "__fspath__"):
        raise InputError("engine", type(engine).__name__, "a preset, an engine file or a spec")
    arrangement: Literal["counter-rotating", "pair"] = "counter-rotating" if order == 1 else "pair"
    shafts = ShaftOptions(cg_radius, length, arrangement)
    if order == 1:
        study = balance_engine(engine, primary=shafts, secondary=None)
    else:
        study = balance_engine(engine, primary=None, secondary=shafts)
    group = study.result.primary if order == 1 else study.result.secondary
    masses = [] if group is None else [m.mass for s in group.shafts for m in s.masses]
    unbalance = float(np.max(masses, initial=0.0)) * cg_radius
    if unbalance <= 0.0:
        raise InputError(
            "engine",
            study.model.name,
            f"has no order-{order} unbalance for a balance shaft to carry",
        )
    return ShaftRequirement(order, unbalance, order * study.model.speed, arrangement)
