"""One cylinder of an engine, for the single-cylinder studies (Hoem and Røsholm 2016).

The one definition of "the masses of one cylinder" lives here; the command line, the web
application and the report all call :func:`cylinder_of`.

Shared crankpins (V, W, radial engines; ``docs/single_cylinder.md``): the throw's
rotating mass (crankpin, webs reduced to the crank radius and every big end on the pin) is
shared equally among the rods on the pin. A cylinder's rotating mass is its share, so the
shares of the cylinders on a pin add up to the throw, and the bob-weight and counterweight
of a throw are the sums of those of its cylinders. The reciprocating mass is the
cylinder's own.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import InputError
from ..physics.kinematics import KinematicsModel
from ..physics.model import EngineModel
from ..physics.rebalancing import DrilledHoles, RebalanceResult, rebalance
from ..physics.single_cylinder import (
    BalanceFactorStudy,
    balance_factor_study,
    counterweight_moment,
)
from ..physics.tolerance import BalanceGrade, ToleranceVerdict
from ..records import record
from ..results import ResultMixin
from ..schema.settings import RebalanceOptions, SingleCylinderOptions


@record
class Cylinder(ResultMixin):
    """The masses and geometry of one cylinder of an engine, in SI.

    Attributes
    ----------
    number : int
        Cylinder number (1-based, ``docs/engine_file.md``).
    throw : int
        Throw the cylinder sits on (1-based).
    rods_on_pin : int
        Cylinders sharing that throw's crankpin.
    reciprocating_mass : float
        The cylinder's reciprocating mass [kg].
    rotating_mass : float
        The cylinder's share of its throw's rotating mass [kg at the crank radius].
    crank_radius, rod_length, offset : float
        [m].
    speed : float
        Crank speed [rad/s].
    """

    number: int
    throw: int
    rods_on_pin: int
    reciprocating_mass: float
    rotating_mass: float
    crank_radius: float
    rod_length: float
    offset: float
    speed: float


def cylinder_of(model: EngineModel, number: int, field: str = "cylinder") -> Cylinder:
    """Cylinder ``number`` (1-based) of an engine; ``field`` names the input in errors."""
    count = model.cylinders
    if isinstance(number, bool) or not isinstance(number, int | np.integer):
        raise InputError(field, number, f"must be a whole number from 1 to {count}")
    if not 1 <= number <= count:
        raise InputError(field, number, f"must be a cylinder number from 1 to {count}")
    k = int(number) - 1
    _check_not_link(model, k, field)
    throw = int(model.cylinder_throw[k])
    rods = int(np.count_nonzero(model.cylinder_throw == throw))
    return Cylinder(
        number=int(number),
        throw=throw + 1,
        rods_on_pin=rods,
        reciprocating_mass=float(model.reciprocating_mass[k]),
        rotating_mass=float(model.throw_rotating_mass[throw]) / rods,
        crank_radius=float(model.crank_radius),
        rod_length=float(model.rod_length),
        offset=float(model.cylinder_offset[k]),
        speed=float(model.speed),
    )


def _check_not_link(model: EngineModel, k: int, field: str) -> None:
    """A link rod's cylinder of an articulated radial is no slider-crank: refused."""
    art = model.articulation
    if art is not None and k != art.master:
        raise InputError(
            field,
            k + 1,
            "is driven by a link rod of the master-and-link rods "
            "(crank_train.articulated), not a plain slider-crank; the single-cylinder "
            f"studies take the master cylinder ({art.master + 1}), the engine's free forces "
            "include every link (analyze)",
        )


def cylinder_study(
    model: EngineModel,
    number: int,
    balance_factor: float,
    kinematics: KinematicsModel | None = None,
    **options: Any,
) -> BalanceFactorStudy:
    """The single-cylinder balance-factor study of one cylinder of an engine.

    For a multi-cylinder engine the forces of the other cylinders are not included: this
    is the per-cylinder view of Hoem and Røsholm (2016), Sec. 4.1.2, not the engine's free
    force (:func:`crankbalance.studies.engine.analyze` gives that).

    ``options`` go to :func:`crankbalance.physics.single_cylinder.balance_factor_study`
    (``samples``, ``sweep``).
    """
    cylinder = cylinder_of(model, number)
    return balance_factor_study(
        cylinder.reciprocating_mass,
        cylinder.crank_radius,
        cylinder.speed,
        balance_factor,
        rod_length=cylinder.rod_length,
        offset=cylinder.offset,
        model=kinematics or model.kinematics,
        **options,
    )


@record
class IsoCheck(ResultMixin):
    """ISO 21940-11 permissible residual unbalance of an engine's crank at its speed."""

    grade: BalanceGrade
    rotor_mass: float
    speed: float
    permissible: float
    verdict: ToleranceVerdict | None


def iso_check(model: EngineModel, options: SingleCylinderOptions) -> IsoCheck:
    """Permissible residual unbalance [kg m] at the engine speed, and the verdict on a
    measured residual when one is given. The rotor mass defaults to the crank's rotating
    masses (every throw)."""
    from ..physics.tolerance import balance_grade, check_residual, permissible_unbalance

    grade = balance_grade(options.grade.replace(" ", ""), field="grade")
    mass = options.rotor_mass
    if mass is None:
        mass = float(np.sum(model.throw_rotating_mass))
    speed = float(model.speed)
    permissible = permissible_unbalance(grade.name, mass, speed)
    verdict = None
    if options.residual is not None:
        verdict = check_residual(options.residual, permissible)
    return IsoCheck(grade, mass, speed, permissible, verdict)


def rebalance_cylinder(
    model: EngineModel, single: SingleCylinderOptions, options: RebalanceOptions
) -> RebalanceResult:
    """Rebalance one cylinder's share of its throw after new parts, by drilled holes (of
    ``options.point_angle``, flat-bottomed at 180 deg, their depths read to
    ``options.depth_to``; no deeper than ``options.web_thickness`` and the drill's length
    ``options.drill_length``, else refused with split holes proposed), to the balance
    factor ``single.balance_factor`` and the ISO tolerance of :func:`iso_check`.

    Without a counterweight mass the crank is taken to be balanced to that factor with the
    old parts (the counterweight is what the factor needs at the CG radius).
    """
    cylinder = cylinder_of(model, single.cylinder)
    old_rec, old_rot = cylinder.reciprocating_mass, cylinder.rotating_mass
    r = cylinder.crank_radius
    radius = options.cw_radius or r
    cw_mass = options.cw_mass
    if cw_mass is None:
        cw_mass = counterweight_moment(old_rot, old_rec, single.balance_factor, r) / radius
    holes = DrilledHoles(
        diameter=options.hole_diameter,
        radius=options.hole_radius or radius,
        number=options.holes,
        point_angle=options.point_angle,
        depth_to=options.depth_to,
        web_thickness=options.web_thickness,
        drill_length=options.drill_length,
    )
    return rebalance(
        old_rot,
        old_rec,
        old_rot if options.new_rotating is None else options.new_rotating,
        old_rec if options.new_reciprocating is None else options.new_reciprocating,
        cw_mass,
        radius,
        r,
        holes,
        iso_check(model, single).permissible,
    )
