"""The engine-cycle studies of the registry (Hoem and Røsholm 2016, Sec. 2.3 and 5): one
working cycle of one cylinder or of the whole engine with its torques, bearing loads,
speed fluctuation and flywheel sizing (``cycle``), and the cycle of one cylinder swept over
balance factors and reciprocating-mass scales (``sensitivity``).

The cylinder is the one typed in the settings (the thesis' motorcycle single by default),
or cylinder ``cylinder`` of the study's engine with the settings given
(:func:`crankbalance.schema.settings.given`) in place of the engine's values; the crank +
flywheel inertia is the one given, else the engine's
(:func:`crankbalance.studies.crank.rotating_inertia`, as ``bearings`` and ``torsional``),
else the thesis' single's. The combustion is the Wiebe model of the settings or pressure
tables (:func:`crankbalance.studies.performance.pressure_source`).
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import InputError
from ..output.format import keyed
from ..physics.model import EngineModel
from ..results import ResultMixin, require_finite, to_jsonable
from ..schema.settings import THESIS_CRANK_INERTIA, CycleOptions, SensitivityOptions, given
from .engine import EngineLike, as_model, engine_label, firing

if TYPE_CHECKING:  # pragma: no cover
    from numpy.typing import NDArray

    from ..physics.engine_cycle import CycleResult, CylinderSpec, PressureSource, SensitivityResult
    from ..physics.engine_cycle_all import EngineCycleResult

from ..records import record
from .performance import (
    WIEBE_OPTIONS,
    arithmetic_checked,
    combustion_summary,
    cycle_cylinder,
    cycle_model,
    engine_estimate,
    peak_pressure,
    pressure_source,
)

CYCLE_SCHEMA = "crankbalance.cycle/3"
SENSITIVITY_SCHEMA = "crankbalance.sensitivity/2"
#: crank-angle samples per revolution of every cycle of these studies (the physics' default,
#: the web's performance tab included)
SAMPLES_PER_REVOLUTION = 360
_RPM = 30.0 / math.pi  # rad/s -> rpm
#: JSON keys of the cylinder of ``cycle``
CYLINDER_KEYS: dict[str, str | tuple[str, float]] = {
    "bore": "bore_m",
    "crank_radius": "crank_radius_m",
    "rod_length": "rod_length_m",
    "reciprocating_mass": "reciprocating_mass_kg",
    "crank_inertia": "crank_inertia_kg_m2",
    "journal_diameter": "journal_diameter_m",
    "offset": "offset_m",
    "crankshaft_weight": "crankshaft_weight_N",
    "crankcase_pressure": "crankcase_pressure_Pa",
}
#: the curves of ``cycle`` in JSON: SI values (the CSV keeps degrees, bar and rpm); the
#: angle over a whole cycle (720 deg for a four-stroke) in rad, not folded into [0, 360)
CURVE_KEYS: dict[str, str | tuple[str, float]] = {
    "angle_deg": ("cycle_angle_rad", math.pi / 180.0),
    "pressure_bar": ("pressure_Pa", 1e5),
    "speed_rpm": ("speed_rad_s", 1.0 / _RPM),
}
#: the summary of one cylinder's cycle: result attribute -> JSON key
SUMMARY_KEYS = (
    ("load_torque", "brake_torque_Nm"),
    ("indicated_work", "indicated_work_J"),
    ("mean_friction_torque", "mean_friction_torque_Nm"),
    ("friction_power", "friction_power_W"),
    ("peak_bearing_load", "peak_bearing_load_N"),
    ("mean_bearing_load", "mean_bearing_load_N"),
    ("peak_net_torque", "peak_net_torque_Nm"),
    ("max_crank_acceleration", "max_crank_acceleration_rad_s2"),
    ("speed_fluctuation", "speed_fluctuation"),
    ("peak_shaking_inline", "peak_shaking_inline_N"),
    ("peak_shaking_transverse", "peak_shaking_transverse_N"),
    ("peak_shaking_force", "peak_shaking_force_N"),
)
#: the summary of a whole engine's cycle: result attribute -> JSON key
ENGINE_SUMMARY_KEYS = (
    ("mean_torque", "mean_torque_Nm"),
    ("indicated_work", "indicated_work_J"),
    ("indicated_power", "indicated_power_W"),
    ("peak_torque", "peak_torque_Nm"),
    ("min_torque", "min_torque_Nm"),
    ("speed_fluctuation", "speed_fluctuation"),
    ("energy_excursion", "energy_excursion_J"),
)
#: the physics' names of settings of one cylinder's cycle
PHYSICS_NAMES = {"crank_radius": "stroke", "ignition_angle": "ignition"}


def crank_inertia(o: CycleOptions, model: EngineModel | None = None) -> float:
    """The crank + flywheel inertia of ``cycle`` and ``sensitivity`` before
    ``flywheel_inertia`` [kg m^2]: as given; else, with an engine (``model``, the engine as
    studied), its rotating inertia (:func:`crankbalance.studies.crank.rotating_inertia`,
    the same as ``bearings`` and ``torsional``); else the thesis' single's."""
    if o.crank_inertia is not None:
        return float(o.crank_inertia)
    if model is None:
        return THESIS_CRANK_INERTIA
    from .crank import rotating_inertia

    return rotating_inertia(model)


def inertia_from(o: CycleOptions, engine: EngineLike | None) -> str:
    """Where the crank + flywheel inertia came from: ``typed``, ``engine`` (the engine's
    rotating inertia) or ``thesis`` (the thesis' single, without an engine)."""
    return "typed" if o.crank_inertia is not None else "thesis" if engine is None else "engine"


def _inputs(o: CycleOptions, engine: EngineLike | None) -> str:
    """What a cycle was computed of, as given: the engine and cylinder, the tables."""
    parts = [f"--engine {engine_label(engine)}" if engine else "the cylinder of the options"]
    if engine and o.cylinder:
        parts.append(f"--cylinder {o.cylinder}")
    return " ".join([*parts, *(f"--pressure-csv {path}" for path in o.pressure_csv)])


@contextlib.contextmanager
def _named(o: CycleOptions) -> Iterator[None]:
    """Within the block, an :class:`InputError` of the physics about a value given names its
    setting: a rod too short for a given stroke names ``stroke``, an engine's firing order
    that a given stroke count cannot fire names ``strokes``. The crank inertia is named by
    :func:`_inertia_error`."""
    typed = given(o)
    try:
        yield
    except InputError as error:
        if isinstance(error, _InertiaError):
            raise
        name = PHYSICS_NAMES.get(error.field, error.field)
        allowed = error.allowed
        if name == "rod_length" and "rod_length" not in typed and "stroke" in typed:
            name = "stroke"  # the given stroke leaves no room for the rod
            allowed = f"is too long for the rod ({error.value:g} m), which {allowed}"
        elif name == "crank_train.firing_order" and "strokes" in typed:
            name = "strokes"  # the engine's firing order is of the other cycle
            allowed = f"does not suit the engine's firing order {error.value}: {allowed}"
        if name not in typed:
            raise
        raise InputError(name, getattr(o, name), allowed) from None


class _InertiaError(InputError):
    """A crank inertia too small for the cycle, already named (:func:`_inertia_error`)."""


def _inertia_error(
    o: CycleOptions, engine: EngineLike | None, inertia: float, error: InputError, hint: str
) -> InputError:
    """The physics' refusal of a crank inertia too small for the cycle (``crank_inertia``),
    naming the setting that sets it: ``flywheel_inertia`` when one was added, else
    ``crank_inertia``, shown as the crank + flywheel ``inertia`` taken [kg m^2] and where it
    came from; ``hint`` says what else may be given. Another error is returned as it is."""
    if error.field != "crank_inertia":
        return error
    origin = {"typed": "", "engine": " (the engine's)", "thesis": " (the thesis' single's)"}
    return _InertiaError(
        "crank_inertia" if o.flywheel_inertia is None else "flywheel_inertia",
        f"{inertia:.4g} kg*m^2 of crank and flywheel{origin[inertia_from(o, engine)]}",
        f"{error.allowed}; {hint}",
    )


def _cylinder(
    engine: EngineLike | None, o: CycleOptions
) -> tuple[CylinderSpec, PressureSource, float, int, float]:
    """The cylinder, its pressure source, speed, stroke count and crank + flywheel inertia
    (before ``flywheel_inertia``) of one cylinder's cycle; a setting that would not act is
    refused."""
    from ..physics.engine_cycle import CylinderSpec

    typed = given(o)
    if "cylinder" in typed and engine is None:
        raise InputError("cylinder", o.cylinder, "only acts with --engine")
    for name in WIEBE_OPTIONS:
        if name in typed and o.pressure_csv:
            raise InputError(
                name,
                getattr(o, name),
                "only acts on the Wiebe combustion model, not with --pressure-csv",
            )
    number = o.cylinder or 1
    geometry = {
        "crank_radius": o.stroke / 2,
        "rod_length": o.rod_length,
        "reciprocating_mass": o.reciprocating_mass,
        "offset": 0.0,
    }
    speed, strokes = o.speed, o.strokes
    settings = {
        "bore": o.bore,
        "balance_factor": o.balance_factor,
        "journal_diameter": o.journal_diameter,
        "friction_coefficient": o.friction_coefficient,
    }
    if engine is None:
        inertia = crank_inertia(o)
        cylinder = CylinderSpec(
            **settings, **geometry, crank_inertia=inertia + (o.flywheel_inertia or 0.0)
        )
    else:
        from .cylinder import cylinder_of

        model = as_model(engine)
        cylinder_of(model, number, "cylinder")
        # the engine's values, except where a setting was given
        own = {
            key: geometry[key]
            for key, name in (
                ("crank_radius", "stroke"),
                ("rod_length", "rod_length"),
                ("reciprocating_mass", "reciprocating_mass"),
            )
            if name in typed
        }
        # the whole engine's inertia turns with this cylinder (its crank as given; a given
        # reciprocating mass is this cylinder's alone)
        inertia = crank_inertia(
            o,
            cycle_model(
                model, crank_radius=own.get("crank_radius"), rod_length=own.get("rod_length")
            ),
        )
        # the bore and journal the engine suggests where the settings are empty (the same
        # as bearings and the web's Crank loads: studies.performance.engine_estimate)
        estimate = engine_estimate(cycle_model(model, crank_radius=own.get("crank_radius")))
        for name in ("bore", "journal_diameter"):
            if name not in typed:
                settings[name] = getattr(estimate, name)
        cylinder = cycle_cylinder(
            model,
            number,
            **settings,
            **own,
            crank_inertia=inertia + (o.flywheel_inertia or 0.0),
        )
        speed = speed if "speed" in typed else float(model.speed)
        strokes = strokes if "strokes" in typed else int(model.strokes)
    pressure = pressure_source(o, 1, strokes)
    assert not isinstance(pressure, list)  # one cylinder: one source
    return cylinder, pressure, speed, strokes, inertia


def estimated(engine: EngineLike | None, o: CycleOptions) -> list[str]:
    """The settings of one cylinder's cycle taken from the engine's estimate
    (:func:`~crankbalance.studies.performance.engine_estimate`): ``bore`` and
    ``journal_diameter`` where an engine is studied and they are not given."""
    typed = given(o)
    if engine is None:
        return []
    return [name for name in ("bore", "journal_diameter") if name not in typed]


def assumption_words(assumed: Mapping[str, Any]) -> str:
    """What :func:`assumed` gives, in words
    (:func:`~crankbalance.studies.performance.assumption_text`): the line of the web's
    Performance tab and of the text output of ``sensitivity`` and ``cycle --cylinder``."""
    from .performance import assumption_text

    a = assumed
    return assumption_text(
        a["bore_m"], a["peak_pressure_Pa"], a["journal_diameter_m"], a["estimated"]
    )


def assumed(
    engine: EngineLike | None,
    o: CycleOptions,
    cylinder: CylinderSpec,
    pressure: PressureSource,
    strokes: int,
) -> dict[str, Any]:
    """The bore, peak cylinder pressure and main journal one cylinder's cycle assumed, with
    the settings among them that are the engine's estimate (``estimated``), as the JSON of
    ``cycle --cylinder`` and ``sensitivity`` shows them (:func:`assumption_words` says
    them in words)."""
    return {
        "bore_m": cylinder.bore,
        "peak_pressure_Pa": peak_pressure(cylinder, pressure, strokes),
        "journal_diameter_m": cylinder.journal_diameter,
        "estimated": estimated(engine, o),
    }


def _flywheel(
    o: CycleOptions, crank: float, required: float, excursion: float, achieved: float
) -> dict[str, float]:
    """The ``flywheel`` part of the JSON of ``cycle`` (``crank``: the crank + flywheel
    inertia before ``flywheel_inertia`` [kg m^2])."""
    return {
        "speed_fluctuation_target": float(o.speed_fluctuation_target or 0.0),
        "energy_excursion_J": excursion,
        "required_inertia_kg_m2": required,
        "required_flywheel_inertia_kg_m2": max(required - crank, 0.0),
        "check_speed_fluctuation": achieved,
    }


@record(repr=False)
class CycleStudy(ResultMixin):
    """One working cycle, of one cylinder or of the whole engine.

    Attributes
    ----------
    result : CycleResult or EngineCycleResult
        The physics' result (the figure of ``cycle --plot`` is drawn from it).
    payload : dict
        The JSON contract without its schema (SI units in the keys).
    curves : dict of str to ndarray
        The curves over the cycle as the CSV writes them (degrees, bar, rpm).
    flywheel_inertia : float
        The flywheel given, added to the crank [kg m^2].
    """

    result: CycleResult | EngineCycleResult
    payload: dict[str, Any]
    curves: dict[str, NDArray[np.float64]]
    flywheel_inertia: float

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.cycle/3``."""
        out = to_jsonable({"schema": CYCLE_SCHEMA, **self.payload})
        assert isinstance(out, dict)
        return out


def cycle(engine: EngineLike | None, settings: CycleOptions) -> CycleStudy:
    """One engine cycle: the cylinder of the settings, or with an engine every cylinder
    firing in its turn (firing order, bank angles, shared crankpins: the torque of each
    cylinder and of the engine, the speed fluctuation, the flywheel for a target
    fluctuation), or with an engine and ``cylinder`` that cylinder alone with its
    main-bearing loads and friction at ``balance_factor``."""
    o = settings
    with _named(o), arithmetic_checked("cycle", _inputs(o, engine)):
        if engine is not None and o.cylinder is None:
            study = _whole_engine(engine, o)
        else:
            study = _one_cylinder(engine, o)
    require_finite(study.payload)
    return study


def _one_cylinder(engine: EngineLike | None, o: CycleOptions) -> CycleStudy:
    from ..physics.engine_cycle import engine_cycle
    from .performance import size_cylinder_flywheel

    cylinder, pressure, speed, strokes, inertia = _cylinder(engine, o)
    try:
        result = engine_cycle(cylinder, speed, pressure, strokes)  # type: ignore[arg-type]
    except InputError as error:
        hint = "" if o.speed_fluctuation_target else " (or size it: --speed-fluctuation-target)"
        raise _inertia_error(
            o,
            engine,
            cylinder.crank_inertia,
            error,
            f"add a flywheel with --flywheel-inertia{hint}",
        ) from None
    summary = {label: getattr(result, name) for name, label in SUMMARY_KEYS}
    summary["energy_check_ratio"] = (
        result.gas_work / result.indicated_work if (result.indicated_work) else 1.0
    )
    flywheel = None
    if o.speed_fluctuation_target is not None:
        sizing = size_cylinder_flywheel(cylinder, result, pressure, o.speed_fluctuation_target)
        flywheel = _flywheel(
            o,
            inertia,
            sizing.required_inertia,
            sizing.energy_excursion,
            sizing.achieved_fluctuation,
        )
    curves = {
        "angle_deg": np.degrees(result.angle),
        "pressure_bar": result.pressure[0] / 1e5,
        "gas_torque_Nm": result.gas_torque,
        "inertia_torque_Nm": result.inertia_torque,
        "friction_torque_Nm": result.friction_torque,
        "net_torque_Nm": result.net_torque,
        "inline_load_N": result.inline_load[0],
        "transverse_load_N": result.transverse_load[0],
        "bearing_load_N": result.bearing_load[0],
        "speed_rpm": result.speed * 30 / np.pi,
        "crank_acceleration_rad_s2": result.crank_acceleration,
    }
    payload = {
        "cylinder": keyed(cylinder.to_dict(), CYLINDER_KEYS),
        "assumed": assumed(engine, o, cylinder, pressure, strokes),
        "crank_inertia_from": inertia_from(o, engine),
        "combustion": combustion_summary(o),
        "speed_rad_s": speed,
        "strokes": strokes,
        "summary": summary,
        **({"flywheel": flywheel} if flywheel else {}),
        "curves": keyed({k: v.tolist() for k, v in curves.items()}, CURVE_KEYS),
    }
    return CycleStudy(result, payload, curves, o.flywheel_inertia or 0.0)


def _whole_engine(engine: EngineLike, o: CycleOptions) -> CycleStudy:
    """``cycle`` of every cylinder of the engine; a setting that acts on one cylinder only
    is refused."""
    from .performance import whole_engine_cycle

    typed = given(o)
    for name in ("balance_factor", "journal_diameter", "friction_coefficient"):
        if name in typed:
            raise InputError(
                name,
                getattr(o, name),
                "acts on one cylinder's bearing (give --cylinder N): the whole engine's cycle "
                "has no bearing model",
            )
    for name in WIEBE_OPTIONS:
        if name in typed and o.pressure_csv:
            raise InputError(
                name,
                getattr(o, name),
                "only acts on the Wiebe combustion model, not with --pressure-csv",
            )
    model = cycle_model(
        as_model(engine),
        speed=o.speed if "speed" in typed else None,
        strokes=o.strokes if "strokes" in typed else None,
        crank_radius=o.stroke / 2 if "stroke" in typed else None,
        rod_length=o.rod_length if "rod_length" in typed else None,
        reciprocating_mass=o.reciprocating_mass if "reciprocating_mass" in typed else None,
    )
    pressure = pressure_source(o, model.cylinders, model.strokes)
    crank = crank_inertia(o, model)
    inertia = crank + (o.flywheel_inertia or 0.0)
    try:
        result = whole_engine_cycle(
            model,
            pressure,
            crank_inertia=inertia,
            bore=o.bore if "bore" in typed else None,
            speed_fluctuation_target=o.speed_fluctuation_target,
        )
    except InputError as error:
        hint = "" if o.speed_fluctuation_target else " (or size it: --speed-fluctuation-target)"
        raise _inertia_error(
            o, engine, inertia, error, f"add a flywheel with --flywheel-inertia{hint}"
        ) from None
    summary = {label: getattr(result, name) for name, label in ENGINE_SUMMARY_KEYS}
    summary["max_crank_acceleration_rad_s2"] = float(np.abs(result.crank_acceleration).max())
    summary["energy_check_ratio"] = (
        result.gas_work / result.indicated_work if result.indicated_work else 1.0
    )
    flywheel = None
    if result.required_inertia is not None:
        flywheel = _flywheel(
            o,
            crank,
            result.required_inertia,
            result.energy_excursion,
            float(result.required_inertia_fluctuation or 0.0),
        )
    order = list(model.firing_order)
    fire = result.fire_angle
    about = {
        "name": model.name,
        "cylinders": model.cylinders,
        "throws": model.throws,
        "bore_m": o.bore if "bore" in typed else 2.0 * model.crank_radius,
        "crank_radius_m": model.crank_radius,
        "rod_length_m": model.rod_length,
        "offset_m": model.cylinder_offset.tolist(),
        "reciprocating_mass_kg": model.reciprocating_mass.tolist(),
        "crank_inertia_kg_m2": crank,
        "crank_inertia_from": inertia_from(o, engine),
        "flywheel_inertia_kg_m2": o.flywheel_inertia or 0.0,
        "firing_order": order,
        "fire_angle_rad": fire.tolist(),
        "firing_interval_rad": firing(model, fire)[1].tolist(),
    }
    curves: dict[str, NDArray[np.float64]] = {
        "angle_deg": np.degrees(result.angle),
        "crank_angle_deg": np.degrees(result.crank_angle),
        "gas_torque_Nm": result.gas_torque,
        "inertia_torque_Nm": result.inertia_torque,
        "torque_Nm": result.torque,
        "speed_rpm": result.speed * 30 / np.pi,
        "crank_acceleration_rad_s2": result.crank_acceleration,
    }
    for c in range(model.cylinders):
        curves[f"cylinder{c + 1}_torque_Nm"] = (
            result.cylinder_gas_torque[c] + result.cylinder_inertia_torque[c]
        )
    for c in range(model.cylinders):
        curves[f"cylinder{c + 1}_pressure_bar"] = result.pressure[c] / 1e5
    for t in range(model.throws):
        curves[f"throw{t + 1}_force_z_N"] = result.throw_force[t].real
        curves[f"throw{t + 1}_force_x_N"] = result.throw_force[t].imag
    json_curves = {
        "cycle_angle_rad": result.angle.tolist(),
        "crank_angle_rad": result.crank_angle.tolist(),
        "gas_torque_Nm": result.gas_torque.tolist(),
        "inertia_torque_Nm": result.inertia_torque.tolist(),
        "torque_Nm": result.torque.tolist(),
        "speed_rad_s": result.speed.tolist(),
        "crank_acceleration_rad_s2": result.crank_acceleration.tolist(),
        "cylinder_torque_Nm": (
            result.cylinder_gas_torque + result.cylinder_inertia_torque
        ).tolist(),
        "cylinder_pressure_Pa": result.pressure.tolist(),
        "throw_force_z_N": result.throw_force.real.tolist(),
        "throw_force_x_N": result.throw_force.imag.tolist(),
    }
    payload = {
        "engine": about,
        "combustion": combustion_summary(o),
        "speed_rad_s": result.speed_mean,
        "strokes": result.strokes,
        "summary": summary,
        **({"flywheel": flywheel} if flywheel else {}),
        "curves": json_curves,
    }
    return CycleStudy(result, payload, curves, o.flywheel_inertia or 0.0)


# --------------------------------------------------------------------------- sensitivity
#: the indicators of the sensitivity sweep: the cycle's summary but the brake torque and
#: the indicated work
SENSITIVITY_KEYS = tuple(
    (name, label) for name, label in SUMMARY_KEYS if name not in ("load_torque", "indicated_work")
)


@record(repr=False)
class SensitivityStudy(ResultMixin):
    """The cycle of one cylinder over balance factors and reciprocating-mass scales.

    Attributes
    ----------
    result : SensitivityResult
        The physics' result: every indicator over (mass scale, balance factor).
    payload : dict
        The JSON contract without its schema.
    header : list of str
        The columns of :attr:`rows`.
    rows : list of list of float
        One row per (mass scale, balance factor): the two, then every indicator.
    flywheel_inertia : float
        The flywheel given [kg m^2] (none: the sweep has no flywheel setting).
    """

    result: SensitivityResult
    payload: dict[str, Any]
    header: list[str]
    rows: list[list[float]]
    flywheel_inertia: float = 0.0

    def assumption(self) -> str:
        """The bore, peak cylinder pressure and main journal the sweep assumed, in words
        (:func:`assumption_words`)."""
        return assumption_words(self.payload["assumed"])

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.sensitivity/2``."""
        out = to_jsonable({"schema": SENSITIVITY_SCHEMA, **self.payload})
        assert isinstance(out, dict)
        return out


def sensitivity(
    engine: EngineLike | None,
    settings: SensitivityOptions,
    *,
    progress: Callable[[int, int], Any] | None = None,
) -> SensitivityStudy:
    """The cycle of one cylinder swept over ``balance_factors`` and ``mass_scales``:
    friction, bearing loads, torque, crank acceleration, speed fluctuation and shaking
    (:func:`~crankbalance.physics.engine_cycle.balance_sensitivity` at
    :data:`SAMPLES_PER_REVOLUTION`); ``progress(done, total)`` after each point."""
    from ..physics.engine_cycle import balance_sensitivity

    o = settings
    with _named(o), arithmetic_checked("sensitivity", _inputs(o, engine)):
        cylinder, pressure, speed, strokes, _inertia = _cylinder(engine, o)
        try:
            result = balance_sensitivity(
                cylinder,
                speed,
                pressure,
                o.balance_factors,
                o.mass_scales,
                strokes,  # type: ignore[arg-type]
                samples_per_revolution=SAMPLES_PER_REVOLUTION,
                progress=progress,
            )
        except InputError as error:
            raise _inertia_error(
                o, engine, cylinder.crank_inertia, error, "give a larger --crank-inertia"
            ) from None
    rows = []
    for i, scale in enumerate(result.mass_scales):
        for k, factor in enumerate(result.balance_factors):
            rows.append(
                [float(scale), float(factor)]
                + [float(getattr(result, name)[i, k]) for name, _ in SENSITIVITY_KEYS]
            )
    header = ["mass_scale", "balance_factor", *(label for _, label in SENSITIVITY_KEYS)]
    payload = {
        "speed_rad_s": speed,
        "strokes": strokes,
        "assumed": assumed(engine, o, cylinder, pressure, strokes),
        "crank_inertia_kg_m2": cylinder.crank_inertia,
        "crank_inertia_from": inertia_from(o, engine),
        "combustion": combustion_summary(o),
        "points": [dict(zip(header, row, strict=True)) for row in rows],
    }
    require_finite(payload)
    return SensitivityStudy(result, payload, header, rows)
