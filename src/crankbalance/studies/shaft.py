"""The balance-shaft studies of the registry (Kim 2018): the unbalance-mass placement of a
shaft on end bearings (``shaft-inline4``), the second-mass placement of the inline-3's
primary-couple shaft for its three rotor types (``shaft-inline3``), and the state variables
and design checks of one given layout (``shaft-check``).

The unbalance a shaft must carry is given (``unbalance`` and ``speed``) or comes from the
balancing of the study's engine
(:func:`crankbalance.studies.requirements.shaft_requirement`).
"""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np

from ..errors import InputError
from ..output.format import keyed
from ..physics.balance_shaft import (
    BalanceShaft,
    DesignChecks,
    HoldMode,
    PlacementStudy,
    RotorType,
    SecondaryMeasure,
    ShaftResponse,
)
from ..physics.beam import BeamTheory, ShaftSection
from ..records import record
from ..results import ResultMixin, to_jsonable
from ..schema.settings import ShaftCheckOptions, ShaftSectionOptions, ShaftStudyOptions, given
from .engine import EngineLike, engine_label

SCHEMA = "crankbalance.shaft/2"

_DEG = 180.0 / math.pi
#: JSON keys of ``shaft check`` (unit in a suffix, angles in degrees)
SHAFT_KEYS: dict[str, str | tuple[str, float]] = {
    "length": "length_m",
    "bearing_positions": "bearing_positions_m",
    "mass_positions": "mass_positions_m",
    "unbalances": "unbalances_kg_m",
    "speed": "speed_rad_s",
    "phases": ("phases_deg", _DEG),
    "unbalance_radius": "unbalance_radius_m",
    "bearing_stiffness": "bearing_stiffness_N_per_m",
}
SECTION_KEYS: dict[str, str | tuple[str, float]] = {
    "outer_diameter": "outer_diameter_m",
    "inner_diameter": "inner_diameter_m",
    "youngs_modulus": "youngs_modulus_Pa",
    "density": "density_kg_m3",
}
RESPONSE_KEYS: dict[str, str | tuple[str, float]] = {
    "reactions": "reactions_N",
    "reaction_phases": ("reaction_phases_deg", _DEG),
    "reaction_difference": "reaction_difference_N",
    "x": "x_m",
    "deflection": "deflection_m",
    "bending_measure": "bending_measure_m2",
    "max_deflection": "max_deflection_m",
    "max_moment": "max_moment_Nm",
    "max_stress": "max_stress_Pa",
    "first_frequency": "first_frequency_hz",
    "first_critical_speed": "first_critical_speed_rad_s",
    "speed": "speed_rad_s",
}
CHECK_KEYS: dict[str, str | tuple[str, float]] = {
    "max_bearing_load": "max_bearing_load_N",
    "bearing_capacity": "bearing_capacity_N",
    "max_deflection": "max_deflection_m",
    "deflection_limit": "deflection_limit_m",
}
#: what Kim (2018) found for the inline-4 shaft (Sect. 3.1, Fig. 7)
PAPER_INLINE4 = {"optimum_position": 0.67, "weight": 2.0, "source": "Kim (2018), Sect. 3.1, Fig. 7"}
#: what Kim (2018) reports for the inline-3 shaft (Sect. 3.2, Fig. 9)
PAPER_INLINE3 = {
    "optimum_position": 0.69,
    "weight": 2.0,
    "rotor_type": "III",
    "source": "Kim (2018), Sect. 3.2, Fig. 9",
    "note": "not reproducible from the text: geometry not given, Eqs. 14-16 "
    "and 22-25 garbled (docs/references.md)",
}


def section(o: ShaftSectionOptions) -> ShaftSection:
    """The shaft section of the settings."""
    return ShaftSection(
        outer_diameter=o.diameter,
        inner_diameter=o.bore,
        youngs_modulus=o.modulus,
        density=o.density,
        poisson_ratio=o.poisson,
    )


@record
class Requirement:
    """The unbalance a shaft carries [kg m] at its speed [rad/s], its order, and the engine
    it comes from (None when given)."""

    unbalance: float
    speed: float
    order: int
    engine: str | None

    def to_dict(self) -> dict[str, Any]:
        return {
            "unbalance_kg_m": self.unbalance,
            "shaft_speed_rad_s": self.speed,
            "from_engine": self.engine,
        }


def _requirement(engine: EngineLike | None, o: ShaftStudyOptions, order: int | None) -> Requirement:
    """The unbalance and speed of the shaft: given, or from the engine's balancing at
    ``order`` (None: the engine's, 2 when it has a free second-order force or moment)."""
    if engine is None:
        if "order" in given(o):
            raise InputError("order", o.order, "only acts with --engine")
        if o.unbalance is None or o.speed is None:
            raise InputError(
                "unbalance" if o.unbalance is None else "speed",
                None,
                "is required (or give --engine to take it from the balancing solver)",
            )
        return Requirement(o.unbalance, o.speed, order or 0, None)
    if o.unbalance is not None or o.speed is not None:
        raise InputError(
            "engine", engine_label(engine), "give --engine or --unbalance/--speed, not both"
        )
    from .requirements import default_shaft_order, shaft_requirement

    try:
        if order is None:
            from .engine import analyze

            order = default_shaft_order(analyze(engine))
        need = shaft_requirement(engine, order, o.length, o.unbalance_radius)
    except InputError as error:
        if error.field != "engine":
            raise
        raise InputError("engine", engine_label(engine), error.allowed) from None
    return Requirement(need.unbalance, need.speed, order, engine_label(engine))


def _common(o: ShaftStudyOptions, need: Requirement) -> dict[str, Any]:
    """The keyword arguments of the placement studies common to inline4 and inline3."""
    kwargs: dict[str, Any] = {
        "unbalance": need.unbalance,
        "speed": need.speed,
        "length": o.length,
        "section": section(o),
        "weight": o.weight,
        "weights": None if o.weights is None else np.array(o.weights),
        "unbalance_radius": o.unbalance_radius,
        "bearing_stiffness": o.bearing_stiffness,
        "theory": cast("BeamTheory", o.theory),
    }
    if o.secondary is not None:
        kwargs["secondary"] = cast("SecondaryMeasure", o.secondary)
    return kwargs


def study_json(study: PlacementStudy) -> dict[str, Any]:
    """The JSON block of one placement study (optimum, weight sweep, curves)."""
    d = study.to_dict()
    return {
        "case": d["case"],
        "design_variable": d["design_variable"],
        "secondary": d["secondary"],
        "optimum": {
            "position": d["optimum_position"],
            "objective": d["optimum_objective"],
            "weight": d["weight"],
        },
        "weight_sweep": [
            {"weight": w, "position": x}
            for w, x in zip(d["weights"], d["optimum_positions"], strict=True)
        ],
        "curves": {
            "position": d["positions"],
            "bearing_positions_m": d["bearing_positions"],
            "mass_positions_m": d["mass_positions"],
            "unbalances_kg_m": d["unbalances"],
            "reactions_N": d["reactions"],
            "reaction_difference_N": d["reaction_difference"],
            "bending_measure_m2": d["bending_measure"],
            "max_deflection_m": d["max_deflection"],
            "max_stress_Pa": d["max_stress"],
            "first_frequency_hz": d["first_frequency"],
            "normalised_bending": d["normalised_bending"],
            "normalised_secondary": d["normalised_secondary"],
            "objective": d["objective"],
        },
    }


@record(repr=False)
class PlacementResult(ResultMixin):
    """The placement studies of one shaft: one for inline4, one per rotor type for inline3.

    Attributes
    ----------
    case : str
        ``inline4`` or ``inline3``.
    requirement : Requirement
    studies : tuple of PlacementStudy
    hold : str, optional
        inline3: what is kept as the masses move (``couple`` or ``unbalance``).
    points : int
        Design points along the shaft.
    """

    case: str
    requirement: Requirement
    studies: tuple[PlacementStudy, ...]
    hold: str | None
    points: int

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.shaft/2``."""
        if self.case == "inline4":
            out = {
                "schema": SCHEMA,
                "input": self.requirement.to_dict(),
                **study_json(self.studies[0]),
                "paper": PAPER_INLINE4,
            }
        else:
            out = {
                "schema": SCHEMA,
                "input": self.requirement.to_dict(),
                "case": "inline3",
                "hold": self.hold,
                "studies": {s.case.split("-")[1]: study_json(s) for s in self.studies},
                "paper": PAPER_INLINE3,
            }
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def inline4(engine: EngineLike | None, settings: ShaftStudyOptions) -> PlacementResult:
    """The optimum unbalance-mass position of a shaft on end bearings (Kim 2018, Sect. 3.1):
    a second-order pair of an inline-4, or any shaft of the engine's order (``order``)."""
    need = _requirement(engine, settings, settings.order)
    from ..physics.balance_shaft import inline4_study

    study = inline4_study(
        positions=np.linspace(0.0, 1.0, settings.points), **_common(settings, need)
    )
    result = PlacementResult("inline4", need, (study,), None, settings.points)
    result.to_dict()  # checked finite
    return result


def inline3(engine: EngineLike | None, settings: ShaftStudyOptions) -> PlacementResult:
    """The optimum second-mass position of an inline-3 primary-couple shaft for each rotor
    type (``type``: I, II, III or all; Kim 2018, Sect. 3.2); ``unbalance`` is the first
    moment of each mass when the two masses are the shaft length apart (Eq. 12)."""
    from ..physics.balance_shaft import ROTOR_TYPES, inline3_study

    o = settings
    need = _requirement(engine, o, 1)
    types = ROTOR_TYPES if o.type == "all" else (o.type,)
    studies = tuple(
        inline3_study(
            cast("RotorType", t),
            positions=np.linspace(o.z_min, 1.0, o.points),
            bearing_offset=o.bearing_offset,
            hold=cast("HoldMode", o.hold),
            **_common(o, need),
        )
        for t in types
    )
    result = PlacementResult("inline3", need, studies, o.hold, o.points)
    result.to_dict()  # checked finite
    return result


@record(repr=False)
class CheckResult(ResultMixin):
    """One shaft layout, its state variables and its design checks."""

    design: BalanceShaft
    response: ShaftResponse
    checks: DesignChecks

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.shaft/2`` (case ``check``)."""
        shaft = keyed(self.design.to_dict(), SHAFT_KEYS)
        shaft["section"] = keyed(shaft["section"], SECTION_KEYS)
        out = {
            "schema": SCHEMA,
            "case": "check",
            "shaft": shaft,
            "response": keyed(self.response.to_dict(), RESPONSE_KEYS),
            "checks": keyed(self.checks.to_dict(), CHECK_KEYS),
        }
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def check(settings: ShaftCheckOptions) -> CheckResult:
    """The state variables and design checks of one shaft layout: bearings, masses and
    their unbalances (one for all, or one per mass) and phases, at ``speed``, against the
    limits given."""
    from ..physics.balance_shaft import design_checks, shaft_response

    o = settings
    if o.speed is None:
        raise InputError("speed", None, "is required: the shaft speed of the evaluation")
    for name in ("bearing", "mass", "unbalance"):
        if not getattr(o, name):
            raise InputError(name, None, "is required (repeat it for each one)")
    u = o.unbalance * len(o.mass) if len(o.unbalance) == 1 else o.unbalance
    design = BalanceShaft(
        length=o.length,
        section=section(o),
        bearing_positions=tuple(o.bearing),
        mass_positions=tuple(o.mass),
        unbalances=tuple(u),
        speed=o.speed,
        phases=tuple(o.phase),
        unbalance_radius=o.unbalance_radius,
        bearing_stiffness=o.bearing_stiffness,
    )
    response = shaft_response(design, theory=cast("BeamTheory", o.theory))
    checks = design_checks(
        response,
        max_speed=o.max_speed,
        critical_speed_margin=o.margin,
        bearing_capacity=o.bearing_capacity,
        deflection_limit=o.deflection_limit,
    )
    result = CheckResult(design, response, checks)
    result.to_dict()  # checked finite
    return result
