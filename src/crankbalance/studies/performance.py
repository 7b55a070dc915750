"""The engine as the engine-cycle models see it (Hoem and Røsholm 2016, Sec. 2.3 and 5).

* one cylinder (:func:`cycle_cylinder`): the engine's geometry and the cylinder's
  reciprocating mass, with the bearing and inertia settings of the study; the CLI
  (``cycle --cylinder``, ``sensitivity``) and the web application's performance tab build
  their cylinder here; its flywheel sizing (:func:`size_cylinder_flywheel`);
* the whole engine (:func:`cycle_model`, :func:`whole_engine_cycle`): every cylinder
  firing (:mod:`crankbalance.physics.engine_cycle_all`), for ``cycle --engine``;
* :func:`engine_estimate`, the bore and main journal a study takes for an engine whose
  setting is left empty (``cycle --cylinder``, ``sensitivity``, the web's Performance tab,
  ``bearings`` and the web's Crank loads: one answer), :func:`peak_pressure` and
  :func:`assumption_text`, the bore, peak pressure and journal a study assumed in words;
* :func:`arithmetic_checked`, the last net of every study of an engine cycle (``cycle``,
  ``sensitivity``, ``bearings``, ``bearings-sweep``, ``torsional``): a floating-point
  overflow, invalid operation or division by zero becomes one :class:`InputError` naming
  the study and its inputs, never a warning and never a wrong field.
"""

from __future__ import annotations

import contextlib
import dataclasses
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any

import numpy as np

from ..physics import kinematics
from ..physics.engine_cycle import CycleResult, CylinderSpec, PressureSource, engine_cycle
from ..physics.engine_cycle_all import EngineCycleResult, engine_cycle_all, flywheel_inertia
from ..physics.model import EngineModel
from ..records import record
from .cylinder import cylinder_of

if TYPE_CHECKING:  # pragma: no cover
    from ..schema.settings import CombustionOptions


@record
class EngineEstimate:
    """What a study takes for an engine where its setting is left empty.

    Attributes
    ----------
    bore : float
        Cylinder bore: a square engine, bore = stroke = 2 r [m].
    journal_diameter : float
        Main journal diameter: the automotive proportion of the crank radius r
        (:data:`crankbalance.studies.crank.DEFAULT_PROPORTIONS`, 1.3 r) [m].
    """

    bore: float
    journal_diameter: float


def engine_estimate(model: EngineModel) -> EngineEstimate:
    """The engine's estimate of its bore and main journal diameter (:class:`EngineEstimate`),
    the one every study takes for a setting left empty: ``bearings``, ``bearings-sweep``
    and ``torsional`` (the crank's journal), ``cycle`` and ``sensitivity`` with an engine."""
    from .crank import DEFAULT_PROPORTIONS

    r = float(model.crank_radius)
    return EngineEstimate(
        bore=2.0 * r, journal_diameter=DEFAULT_PROPORTIONS["journal_diameter"] * r
    )


def peak_pressure(cylinder: CylinderSpec, pressure: PressureSource, strokes: int) -> float:
    """The largest absolute cylinder pressure of one working cycle of ``cylinder`` with its
    gas ``pressure`` (the Wiebe model or a table), sampled every half degree [Pa]."""
    from ..physics.engine_cycle import cylinder_pressure

    angle = np.linspace(0.0, strokes * np.pi, 360 * strokes, endpoint=False)
    return float(cylinder_pressure(angle, cylinder, pressure, strokes).max())


def assumption_text(
    bore: float, peak: float | None, journal: float, estimated: Iterable[str], note: bool = True
) -> str:
    """The bore [m], peak cylinder pressure [Pa] (None: no gas forces) and main journal
    diameter [m] a study assumed, in words, each of ``estimated`` (``"bore"``,
    ``"journal_diameter"``) marked as the engine's estimate (:func:`engine_estimate`) with a
    star, and (``note``) what the star means; the same words for every study that has them
    (``cycle --cylinder``, ``sensitivity`` and the web's Performance tab, ``bearings``,
    ``bearings-sweep`` and the web's Crank loads)."""
    marked = set(estimated)

    def star(name: str) -> str:
        return "*" if name in marked else ""

    pressure = "no gas forces" if peak is None else f"peak pressure {peak / 1e5:.4g} bar"
    from .crank import DEFAULT_PROPORTIONS

    share = DEFAULT_PROPORTIONS["journal_diameter"]
    meaning = (
        f" (* the engine's estimate: bore = stroke, journal {share:g} x crank radius)"
        if marked and note
        else ""
    )
    return (
        f"bore {bore * 1e3:.4g} mm{star('bore')}, {pressure}, main journal "
        f"{journal * 1e3:.4g} mm{star('journal_diameter')}{meaning}"
    )


#: what the one-cylinder studies' peak bearing load is, beside the bearing-load studies'
#: (the web's Performance and Crank loads tabs say it under their tables)
PEAK_BEARING_WORDS = (
    "Peak bearing N: the whole load of one cylinder (gas, inertia and its counterweight) on "
    "one main bearing; Crank loads shares each throw's load among the main bearings on "
    "either side of it (a single cylinder's two bearings carry half each), so its max N is "
    "another quantity"
)


def cycle_cylinder(
    model: EngineModel,
    number: int,
    *,
    crank_inertia: float,
    journal_diameter: float,
    friction_coefficient: float,
    bore: float | None = None,
    balance_factor: float = 0.0,
    **geometry: float,
) -> CylinderSpec:
    """The :class:`~crankbalance.physics.engine_cycle.CylinderSpec` of cylinder ``number``
    (1-based).

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


def cycle_model(
    model: EngineModel,
    *,
    speed: float | None = None,
    strokes: int | None = None,
    crank_radius: float | None = None,
    rod_length: float | None = None,
    reciprocating_mass: float | None = None,
) -> EngineModel:
    """The engine of the whole-engine cycle: ``model`` with the values given here (the
    options typed on the command line) in place of its own: speed [rad/s], strokes, crank
    radius [m], rod length [m], and one reciprocating mass [kg] for every cylinder."""
    changes: dict[str, Any] = {}
    if speed is not None:
        changes["speed"] = float(speed)
    if strokes is not None:
        changes["strokes"] = int(strokes)
    if crank_radius is not None:
        changes["crank_radius"] = float(crank_radius)
    if rod_length is not None:
        changes["rod_length"] = float(rod_length)
    if reciprocating_mass is not None:
        changes["reciprocating_mass"] = np.full(model.cylinders, float(reciprocating_mass))
    return dataclasses.replace(model, **changes)


@contextlib.contextmanager
def arithmetic_checked(study: str, inputs: str) -> Iterator[None]:
    """Within the block, numpy's floating-point overflow, invalid operation (NaN) and
    division by zero raise instead of warning, and are refused as one
    :class:`~crankbalance.errors.InputError` naming ``study`` (``"the torsional
    study"``) and its ``inputs`` as the user gave them (``"--engine inline4"``).

    The inputs are checked at the edge (every option against its range, every pressure
    table value against :data:`crankbalance.io.pressure_csv.PRESSURE_RANGE_BAR`), so this
    is a net for a combination of extreme values that no single check sees. Underflow
    (a result below the smallest double, rounded to zero) is not an error: it is how
    a vanishing term of a sum is computed.
    """
    from ..errors import InputError

    try:
        with np.errstate(over="raise", divide="raise", invalid="raise"):
            yield
    except FloatingPointError as error:
        raise InputError(
            study,
            inputs,
            f"cannot be computed for these inputs ({error}): their extreme values together "
            "take the arithmetic beyond floating point; bring the most extreme of them "
            "closer to an engine's",
        ) from None


def whole_engine_cycle(
    model: EngineModel,
    pressure: PressureSource | list[PressureSource],
    *,
    crank_inertia: float,
    bore: float | None = None,
    speed_fluctuation_target: float | None = None,
) -> EngineCycleResult:
    """All cylinders of ``model`` over one working cycle
    (:func:`~crankbalance.physics.engine_cycle_all.engine_cycle_all`); without a bore the engine is
    taken as square (bore = stroke), as :func:`cycle_cylinder` does; its arithmetic is
    checked (:func:`arithmetic_checked`)."""
    with arithmetic_checked("the engine cycle", f"engine {model.name!r}"):
        return engine_cycle_all(
            model,
            pressure,
            bore=bore if bore is not None else 2.0 * model.crank_radius,
            crank_inertia=crank_inertia,
            speed_fluctuation_target=speed_fluctuation_target,
        )


@record
class FlywheelSizing:
    """The rotating inertia one cylinder's cycle needs for a target speed fluctuation.

    ``required_inertia`` [kg m^2] is the purely rotating inertia (crank and flywheel) from
    :func:`~crankbalance.physics.engine_cycle_all.flywheel_inertia` on the cylinder's net torque
    (gas, inertia, friction), less the mean inertia of its reciprocating parts;
    ``achieved_fluctuation`` [-] is the fluctuation of the cycle re-run with it (the
    check); ``energy_excursion`` [J].
    """

    target: float
    required_inertia: float
    energy_excursion: float
    achieved_fluctuation: float


def size_cylinder_flywheel(
    cylinder: CylinderSpec,
    result: CycleResult,
    pressure: PressureSource,
    target: float,
) -> FlywheelSizing:
    """Flywheel sizing of the single-cylinder cycle ``result`` of ``cylinder`` (run by
    :func:`~crankbalance.physics.engine_cycle.engine_cycle`), checked by re-running that cycle with
    the inertia found."""
    total, excursion = flywheel_inertia(result.angle, result.net_torque, result.speed_mean, target)
    slope = kinematics.piston_velocity(
        result.angle, cylinder.crank_radius, cylinder.rod_length, cylinder.offset
    )
    required = max(total - float(np.mean(cylinder.reciprocating_mass * slope**2)), 0.0)
    check = engine_cycle(
        dataclasses.replace(cylinder, crank_inertia=required),
        result.speed_mean,
        pressure,
        result.strokes,  # type: ignore[arg-type]
        samples_per_revolution=result.angle.size * 2 // result.strokes,
    )
    return FlywheelSizing(
        target=float(target),
        required_inertia=required,
        energy_excursion=excursion,
        achieved_fluctuation=check.speed_fluctuation,
    )


#: the options of the Wiebe combustion model (a pressure table replaces them)
WIEBE_OPTIONS = (
    "compression_ratio",
    "ignition",
    "burn_duration",
    "intake_pressure",
    "heat_release",
    "fuel_mass",
    "heating_value",
    "combustion_efficiency",
    "gamma",
    "exhaust_pressure",
    "burn_end",
)

#: the end-of-burn conventions in words (:data:`~crankbalance.physics.engine_cycle.BURN_ENDS`)
BURN_END_WORDS = {
    "complete": "burn complete (the Wiebe tail runs on past the duration)",
    "stop": "burn stopped at the end of the duration (99.3 % burnt)",
}


def combustion_summary(o: CombustionOptions) -> dict[str, Any] | None:
    """The Wiebe combustion of :class:`~crankbalance.schema.settings.CombustionOptions` as the JSON
    of ``cycle``, ``torsional`` and ``bearings`` shows it (SI units in the keys), the same
    defaults for all; None with pressure tables. The heat released is stated as given
    (``heat_release_J``), or by the fuel (``fuel_mass_kg``) or the charge (both null), with
    the heating value and combustion efficiency those use."""
    if o.pressure_csv:
        return None
    return {
        "compression_ratio": float(o.compression_ratio),
        "ignition_rad": float(o.ignition),
        "burn_duration_rad": float(o.burn_duration),
        "intake_pressure_Pa": float(o.intake_pressure),
        "heat_release_J": o.heat_release,
        "fuel_mass_kg": o.fuel_mass,
        "heating_value_J_kg": float(o.heating_value),
        "combustion_efficiency": float(o.combustion_efficiency),
        "gamma": float(o.gamma),
        "exhaust_pressure_Pa": float(
            o.intake_pressure if o.exhaust_pressure is None else o.exhaust_pressure
        ),
        "burn_end": o.burn_end,
    }


def combustion_text(summary: dict[str, Any] | None) -> str:
    """The combustion of :func:`combustion_summary` in words, for the text outputs."""
    import math

    if summary is None:
        return "combustion: pressure tables"
    if summary["heat_release_J"] is not None:
        heat = f"heat released {summary['heat_release_J']:g} J per cycle"
    else:
        source = (
            "the charge"
            if summary["fuel_mass_kg"] is None
            else f"{1e3 * summary['fuel_mass_kg']:g} g of fuel per cycle"
        )
        heat = (
            f"heat from {source} ({summary['heating_value_J_kg'] / 1e6:g} MJ/kg, "
            f"efficiency {summary['combustion_efficiency']:g})"
        )
    return (
        f"Wiebe combustion: compression {summary['compression_ratio']:g}, ignition "
        f"{math.degrees(summary['ignition_rad']):g}°, burn "
        f"{math.degrees(summary['burn_duration_rad']):g}°, "
        f"{BURN_END_WORDS[summary['burn_end']]}; {heat}, gamma {summary['gamma']:g}, "
        f"exhaust {summary['exhaust_pressure_Pa'] / 1e5:g} bar"
    )


#: the columns of a pressure table named by the model's checks of a table
_TABLE_COLUMNS = {"pressure table angle": "angle_deg", "pressure table pressure": "pressure_bar"}


def pressure_source(
    o: CombustionOptions, cylinders: int = 1, strokes: int | None = None
) -> PressureSource | list[PressureSource]:
    """The gas pressure of ``cycle``, ``sensitivity``, ``torsional`` and ``bearings`` from
    their :class:`~crankbalance.schema.settings.CombustionOptions`: the pressure tables (one for
    every cylinder, or one per cylinder), else the Wiebe model of the options. With the
    cycle's ``strokes`` each table is checked by the model
    (:func:`~crankbalance.physics.engine_cycle.tabulated_pressure`: less than one cycle) and an
    error names its file."""
    from ..errors import InputError
    from ..physics.engine_cycle import WiebeCombustion, tabulated_pressure

    if o.pressure_csv:
        from ..io.pressure_csv import read_pressure_csv

        if len(o.pressure_csv) not in (1, cylinders):
            raise InputError(
                "pressure_csv",
                f"{len(o.pressure_csv)} files",
                f"give one table for every cylinder, or one per cylinder ({cylinders})",
            )
        tables = []
        for path in o.pressure_csv:
            try:
                tables.append(read_pressure_csv(path))
            except InputError as error:
                if error.field != "pressure_csv":  # a line of the table names file and line
                    raise
                # the file as a whole (missing, too short, not text): the option and this
                # file, not every file the option was given
                raise InputError("--pressure-csv", path, error.allowed) from None
        for path, (angle, pressure) in zip(o.pressure_csv, tables, strict=True):
            if strokes is None:
                break
            try:
                tabulated_pressure(angle[:1], angle, pressure, strokes)  # type: ignore[arg-type]
            except InputError as error:
                column = _TABLE_COLUMNS.get(error.field)
                where = f"pressure_csv {path}" + (f", {column}" if column else "")
                raise InputError(where, error.value, error.allowed) from None
        sources: list[PressureSource] = [*tables]
        return sources[0] if len(sources) == 1 else sources
    from ..schema.settings import given

    if strokes == 2 and "exhaust_pressure" in given(o):
        raise InputError(
            "exhaust_pressure",
            o.exhaust_pressure,
            "acts on a four-stroke's exhaust stroke only (a two-stroke is scavenged at "
            "bottom dead centre)",
        )
    return WiebeCombustion(
        compression_ratio=o.compression_ratio,
        ignition_angle=o.ignition,
        burn_duration=o.burn_duration,
        intake_pressure=o.intake_pressure,
        heat_release=o.heat_release,
        fuel_mass=o.fuel_mass,
        heating_value=o.heating_value,
        combustion_efficiency=o.combustion_efficiency,
        gamma=o.gamma,
        exhaust_pressure=o.exhaust_pressure,
        burn_end=o.burn_end,
    )
