"""One cylinder of an engine as the engine-cycle model sees it (Hoem and Røsholm 2016,
Sec. 2.3 and 5): the engine's geometry and the cylinder's reciprocating mass, with the
bearing and inertia settings of the study. The CLI (``cycle``, ``sensitivity``) and the
web application's performance tab both build their cylinder here.
"""

from __future__ import annotations

from typing import Any

from ..engine_cycle import CylinderSpec
from ..model import EngineModel
from .cylinder import cylinder_of


def cycle_cylinder(
    model: EngineModel,
    number: int,
    *,
    crank_inertia: float,
    journal_diameter: float,
    friction_coefficient: float,
    bore: float | None = None,
    balance_factor: float = 0.0,
    **geometry: Any,
) -> CylinderSpec:
    """The :class:`~crankbalance.engine_cycle.CylinderSpec` of cylinder ``number`` (1-based).

    Crank radius, rod length, offset and the cylinder's reciprocating mass come from the
    engine unless ``geometry`` gives them (``crank_radius``, ``rod_length``,
    ``reciprocating_mass``, ``offset`` [m, kg]); without a bore the engine is taken as
    square (bore = stroke).
    """
    cylinder = cylinder_of(model, number)
    values = {
        "crank_radius": cylinder.crank_radius,
        "rod_length": cylinder.rod_length,
        "reciprocating_mass": cylinder.reciprocating_mass,
        "offset": cylinder.offset,
    } | geometry
    return CylinderSpec(
        bore=bore if bore is not None else 2.0 * values["crank_radius"],
        crank_inertia=crank_inertia,
        balance_factor=balance_factor,
        journal_diameter=journal_diameter,
        friction_coefficient=friction_coefficient,
        **values,
    )
