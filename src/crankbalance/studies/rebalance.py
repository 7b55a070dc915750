"""Rebalancing a single-cylinder crank after new parts, from a rebalance parts file
(Hoem and Røsholm (2016), Sec. 6.4, eight steps).

The derivations from the file's content to the input of
:func:`crankbalance.physics.rebalancing.rebalance` live here: the correction object, the
permissible residual (given, or from an ISO 21940-11 grade), and one run per target
balance factor. The ``rebalance`` command merges its options over the file and calls
:func:`rebalance_parts`; nothing else derives these quantities.
"""

from __future__ import annotations

import math

from ..errors import InputError
from ..io.rebalance_file import Correction, Parts, RebalanceFile, Tolerance
from ..physics.rebalancing import DrilledHoles, FaceRemoval, RebalanceResult, rebalance
from ..physics.shop.holes import FLAT_BOTTOM, STEEL_DENSITY
from ..records import record
from ..results import ResultMixin


@record
class PartsSummary(ResultMixin):
    """One side (old or new parts) of a rebalancing, in SI.

    Attributes
    ----------
    label : str
    rotating_mass, reciprocating_mass : float
        Totals [kg].
    rotating_parts, reciprocating_parts : dict of str to float
        The named parts [kg] (empty when the file gives totals).
    """

    label: str
    rotating_mass: float
    reciprocating_mass: float
    rotating_parts: dict[str, float]
    reciprocating_parts: dict[str, float]


@record(repr=False)
class RebalanceStudy(ResultMixin):
    """The rebalancing of one crank for each target balance factor.

    Attributes
    ----------
    name : str
    old, new : PartsSummary
    tolerance : float
        Permissible residual unbalance [kg m].
    tolerance_source : str
        Where it comes from ("given", or the ISO grade, rotor mass and speed).
    cases : list of RebalanceResult
        One per target, in the order given.
    crank_radius : float, optional
        The crank radius [m] (the drilling plan's figure draws the crankpin with it).
    """

    name: str
    old: PartsSummary
    new: PartsSummary
    tolerance: float
    tolerance_source: str
    cases: list[RebalanceResult]
    crank_radius: float | None = None


def correction_of(table: Correction | None) -> DrilledHoles | FaceRemoval:
    """DrilledHoles or FaceRemoval from a ``[correction]`` table."""
    table = table or Correction()
    if table.radius is None:
        raise InputError(
            "correction.radius", None, "is required: radius of the correction, e.g. '40 mm'"
        )
    density = STEEL_DENSITY if table.density is None else table.density
    resolution = 1e-6 if table.depth_resolution is None else table.depth_resolution
    if table.method == "face":
        if table.area is None:
            raise InputError(
                "correction.area", None, "is required for method 'face', e.g. '2000 mm^2'"
            )
        return FaceRemoval(
            area=table.area,
            radius=table.radius,
            orientation=table.orientation or "radial",
            webs=table.webs,
            density=density,
            depth_resolution=resolution,
        )
    if table.diameter is None:
        raise InputError("correction.diameter", None, "is required for method 'holes', e.g. '8 mm'")
    return DrilledHoles(
        diameter=table.diameter,
        radius=table.radius,
        number=table.number or 1,
        direction=table.direction or "axial",
        webs=table.webs,
        density=density,
        depth_resolution=resolution,
        point_angle=FLAT_BOTTOM if table.point_angle is None else table.point_angle,
        depth_to=table.depth_to or "shoulder",
        web_thickness=table.web_thickness,
        drill_length=table.drill_length,
    )


#: the keys of ``[correction]`` that name the quantities of a correction plan's messages
#: (:func:`crankbalance.physics.rebalancing.rebalance`, ``names``)
PLAN_KEYS = {
    "hole_diameter": "correction.diameter",
    "holes": "correction.number",
    "web_thickness": "correction.web_thickness",
    "drill_length": "correction.drill_length",
    "correction_radius": "correction.radius",
}


def tolerance_of(table: Tolerance | None) -> tuple[float, str]:
    """Permissible residual unbalance [kg m] from ``[tolerance]`` and where it comes from:
    ``unbalance`` as given, or ISO 21940-11 ``grade`` at ``rotor_mass`` and ``speed``."""
    from ..physics.tolerance import balance_grade, permissible_unbalance

    table = table or Tolerance()
    if table.unbalance is not None:
        return table.unbalance, "given"
    missing = [k for k in ("grade", "rotor_mass", "speed") if getattr(table, k) is None]
    if missing:
        raise InputError(
            f"tolerance.{missing[0]}",
            None,
            "give tolerance.unbalance, or grade, rotor_mass and speed",
        )
    grade = balance_grade(str(table.grade), "tolerance.grade")
    mass, speed = float(table.rotor_mass or 0.0), float(table.speed or 0.0)
    source = f"ISO 21940-11 {grade.name}, {mass:g} kg, {speed * 30 / math.pi:g} rpm"
    return permissible_unbalance(grade.name, mass, speed), source


def _summary(parts: Parts, side: str) -> PartsSummary:
    return PartsSummary(
        label=parts.label or side,
        rotating_mass=parts.rotating_total,
        reciprocating_mass=parts.reciprocating_total,
        rotating_parts=dict(parts.rotating or {}),
        reciprocating_parts=dict(parts.reciprocating or {}),
    )


def rebalance_parts(
    parts: RebalanceFile,
    targets: list[float | str] | None = None,
    names: dict[str, str] | None = None,
) -> RebalanceStudy:
    """Rebalance for each target balance factor (a number, or ``"factory"`` for the crank's
    own); ``targets`` default to the file's, else ``["factory"]``. A correction plan the
    drill cannot make is refused naming the file's keys (``correction.diameter``,
    ``correction.web_thickness``), or what ``names`` gives for a key (the option that set
    it: ``{"correction.diameter": "--hole-diameter"}``)."""
    from ..io.rebalance_file import rebalance_file_from_dict

    if targets is not None:
        # validated like the file's targets (numbers, percentages, "factory")
        targets = rebalance_file_from_dict({"targets": list(targets)}).targets
    targets = targets or parts.targets or ["factory"]
    for value, key, hint in (
        (parts.crank_radius, "crank_radius", "'26.9 mm'"),
        (parts.counterweight and parts.counterweight.mass, "counterweight.mass", "'2020.40 g'"),
        (
            parts.counterweight and parts.counterweight.cg_radius,
            "counterweight.cg_radius",
            "'6.16 mm'",
        ),
    ):
        if value is None:
            raise InputError(key, None, f"is required, e.g. {hint}")
    sides = {}
    for side, given in (("old", parts.old), ("new", parts.new)):
        if given is None:
            raise InputError(
                side,
                None,
                f"the {side} parts are required ([{side}] table "
                f"or --{side}-rotating-mass/--{side}-reciprocating-mass)",
            )
        sides[side] = _summary(given, side)
    correction = correction_of(parts.correction)
    tolerance, source = tolerance_of(parts.tolerance)
    typed = names or {}
    plan_names = {name: typed.get(key, key) for name, key in PLAN_KEYS.items()}
    assert parts.counterweight is not None and parts.crank_radius is not None
    cases = [
        rebalance(
            sides["old"].rotating_mass,
            sides["old"].reciprocating_mass,
            sides["new"].rotating_mass,
            sides["new"].reciprocating_mass,
            float(parts.counterweight.mass or 0.0),
            float(parts.counterweight.cg_radius or 0.0),
            parts.crank_radius,
            correction,
            tolerance,
            target_balance_factor=None if target == "factory" else float(target),
            names=plan_names,
        )
        for target in targets
    ]
    return RebalanceStudy(
        name=parts.name or "rebalance",
        old=sides["old"],
        new=sides["new"],
        tolerance=tolerance,
        tolerance_source=source,
        cases=cases,
        crank_radius=parts.crank_radius,
    )
