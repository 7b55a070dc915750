"""The main-bearing load study: from an engine, its counterweights and a cycle setting to the
loads of every main bearing and the bending of the crank (docs/main_bearings.md).

The chain: the engine file's counterweights (with the study's overrides of the pattern and
the balance factor) from :func:`crankbalance.studies.engine.balance_engine`; the whole
engine over one working cycle (gas and reciprocating inertia through the rods, every
cylinder at its firing phase) from :func:`crankbalance.physics.engine_cycle_all.engine_cycle_all`;
then the loads on the crank and both crank models of :mod:`crankbalance.physics.main_bearings`.
The CLI (``crankbalance bearings``) and the example ``examples/inline4_counterweights.py``
call :func:`bearing_loads`.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..output.format import text
from ..physics.main_bearings import (
    CRANK_MODELS,
    MAX_CONTACT_SIZE,
    CrankSection,
    CrankStiffness,
    MainBearingLoads,
    bearing_friction,
    crank_loads,
    crank_stiffness,
    default_bearing_positions,
    main_bearing_loads,
)
from ..physics.model import EngineModel
from ..records import record
from ..results import ResultMixin, to_jsonable
from ..schema.engine import EngineSpec
from ..schema.settings import MIN_SAMPLES, BearingOptions, given, parse_options
from .build import build_model
from .crank import (
    DEFAULT_PROPORTIONS,
    CrankDimensions,
    crank_dimensions,
    rotating_inertia,
    web_offset,
)
from .engine import BalanceStudy, balance_engine, engine_summary
from .performance import (
    WIEBE_OPTIONS,
    arithmetic_checked,
    assumption_text,
    combustion_summary,
    combustion_text,
    engine_estimate,
    pressure_source,
)

if TYPE_CHECKING:  # pragma: no cover
    from ..physics.balancing import BalanceResult
    from ..physics.engine_cycle import PressureSource
    from ..physics.engine_cycle_all import EngineCycleResult

SCHEMA = "crankbalance.bearings/1"

#: what every output says of the indeterminate model's stiffness
STIFFNESS_NOTE = (
    "equivalent-stiffness approximation: the crank as a straight stepped beam (journals, "
    "webs, crankpins); checked against finite elements of the same beam, not of a real crank"
)


@record(repr=False)
class BearingStudy(ResultMixin):
    """Main-bearing loads of one engine over its cycle, both crank models (see
    :func:`bearing_loads`).

    Attributes
    ----------
    model : EngineModel
        The engine.
    balance : balancing.BalanceResult
        Its counterweights (the pattern and balance factor studied).
    cycle : engine_cycle_all.EngineCycleResult
        The whole engine over one working cycle (pin forces, speed).
    options : BearingOptions
        The study's settings.
    section : CrankSection
        Crank dimensions used (given or from the default proportions).
    dimensions : CrankDimensions
        The same, with the lengths and which were typed
        (:func:`crankbalance.studies.crank.crank_dimensions`).
    crank_inertia : float
        Crank + flywheel inertia used [kg m^2] (given, or
        :func:`crankbalance.studies.crank.rotating_inertia`).
    web_offset : float
        Axial distance of a web from its throw mid-plane [m].
    stiffness : CrankStiffness
        EI along the crank.
    bore : float
        Bore [m].
    results : dict of str to MainBearingLoads
        ``"determinate"`` and ``"indeterminate"``, with friction.
    """

    model: EngineModel
    balance: BalanceResult
    cycle: EngineCycleResult
    options: BearingOptions
    section: CrankSection
    dimensions: CrankDimensions
    crank_inertia: float
    web_offset: float
    stiffness: CrankStiffness
    bore: float
    results: dict[str, MainBearingLoads]

    @property
    def bearing_positions(self) -> NDArray[np.float64]:
        """Main-bearing positions [m]."""
        return self.results["indeterminate"].bearing_position

    def to_dict(self, curves: bool | None = None) -> dict[str, Any]:
        """The JSON contract ``crankbalance.bearings/1`` (docs/json.md); ``curves`` (default:
        the setting ``curves``) adds the polar load and bending-moment curves over the
        cycle."""
        o, s = self.options, self.section
        curves = o.curves if curves is None else curves
        cw = self.balance.counterweights
        models: dict[str, Any] = {}
        for name, r in self.results.items():
            fr = r.friction
            assert fr is not None
            models[name] = {
                "bearings": [
                    {
                        "bearing": k + 1,
                        "position_m": float(r.bearing_position[k]),
                        "max_load_N": float(r.max_load[k]),
                        "mean_load_N": float(r.mean_load[k]),
                        "equivalent_load_N": float(r.equivalent_load[k]),
                        "peak_load_crank_angle_rad": float(
                            r.angle[int(np.argmax(np.abs(r.load[k])))]
                        ),
                        "max_journal_moment_Nm": float(r.max_journal_moment[k]),
                        "coulomb_friction_torque_Nm": float(fr.coulomb_torque[k]),
                        "coulomb_friction_power_W": float(fr.coulomb_power[k]),
                        "petroff_friction_torque_Nm": None
                        if fr.petroff_torque is None
                        else float(fr.petroff_torque[k]),
                    }
                    for k in range(r.bearing_position.size)
                ],
                "throws": [
                    {
                        "throw": t + 1,
                        "position_m": float(r.throw_position[t]),
                        "max_pin_moment_Nm": float(r.max_pin_moment[t]),
                    }
                    for t in range(r.throw_position.size)
                ],
                "largest_load_N": float(r.max_load.max()),
                "largest_journal_moment_Nm": float(r.max_journal_moment.max()),
                "largest_pin_moment_Nm": float(r.max_pin_moment.max()),
                "coulomb_friction_power_W": float(fr.coulomb_power.sum()),
                "petroff_friction_power_W": None
                if fr.petroff_power is None
                else float(fr.petroff_power.sum()),
            }
            if curves:
                models[name]["curves"] = {
                    "load_z_N": r.load.real,
                    "load_x_N": r.load.imag,
                    "journal_moment_z_Nm": r.journal_moment.real,
                    "journal_moment_x_Nm": r.journal_moment.imag,
                    "pin_moment_z_Nm": r.pin_moment.real,
                    "pin_moment_x_Nm": r.pin_moment.imag,
                }
        out: dict[str, Any] = {
            "schema": SCHEMA,
            "engine": engine_summary(self.model),
            "settings": {
                "speed_rad_s": float(self.cycle.speed_mean),
                "strokes": int(self.cycle.strokes),
                "gas": o.gas,
                "bore_m": self.bore,
                "bore_from": "engine" if o.bore is None else "typed",
                "peak_pressure_Pa": float(self.cycle.pressure.max()) if o.gas else None,
                "crank_inertia_kg_m2": self.crank_inertia,
                "crank_inertia_from": "engine" if o.crank_inertia is None else "typed",
                "combustion": combustion_summary(o) if o.gas else None,
                "speed_fluctuation": float(self.cycle.speed_fluctuation),
                "journal_diameter_m": s.journal_diameter,
                "pin_diameter_m": s.pin_diameter,
                "web_thickness_m": s.web_thickness,
                "web_width_m": s.web_width,
                "web_offset_m": self.web_offset,
                "dimensions_typed": list(self.dimensions.typed),
                "youngs_modulus_Pa": s.youngs_modulus,
                "poisson_ratio": s.poisson_ratio,
                "bearing_stiffness_N_per_m": o.bearing_stiffness,
                "friction_coefficient": o.friction_coefficient,
                "viscosity_Pa_s": o.viscosity,
                "bearing_length_m": o.bearing_length,
                "clearance_m": o.clearance,
                "clearance_in_contact_model": bool(o.clearance and o.bearing_stiffness),
            },
            "counterweights": None
            if cw is None
            else {
                "count": cw.count,
                "webs": cw.web,
                "total_mass_kg": float(cw.mass.sum()),
                "cg_radius_m": cw.cg_radius,
                "mass_kg": cw.mass,
                "direction_deg": np.degrees(cw.direction),
            },
            "stiffness": {
                "edges_m": self.stiffness.edges,
                "bending_stiffness_Nm2": self.stiffness.stiffness,
                "note": STIFFNESS_NOTE,
            },
            "bearing_position_m": self.bearing_positions,
            "models": models,
        }
        if curves:
            out["crank_angle_rad"] = self.results["indeterminate"].angle
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def _counterweight_arrays(balance: BalanceResult) -> dict[str, Any]:
    """The counterweights (and the extra crank masses of a single counter-rotating primary
    shaft) as the arrays of :func:`crankbalance.physics.main_bearings.crank_loads`: first moments
    at one common radius."""
    parts = [c for c in (balance.counterweights, balance.extra_counterweights) if c is not None]
    if not parts:
        return {}
    radius = parts[0].cg_radius
    return {
        "counterweight_mass": np.concatenate([c.mass * c.cg_radius / radius for c in parts]),
        "counterweight_radius": radius,
        "counterweight_direction": np.concatenate([c.direction for c in parts]),
        "counterweight_position": np.concatenate([c.position for c in parts]),
        "counterweight_throw": np.concatenate([c.throw - 1 for c in parts]),
    }


def _pressure(
    o: BearingOptions, cylinders: int, strokes: int
) -> PressureSource | list[PressureSource]:
    """The cylinder pressure source: Wiebe or tables (:func:`.performance.pressure_source`),
    or the crankcase pressure alone (no gas)."""
    if not o.gas:
        return (np.radians([-300.0, -100.0, 100.0, 300.0]), np.full(4, 1e5))
    return pressure_source(o, cylinders, strokes)


def crank_section(dimensions: CrankDimensions, o: BearingOptions) -> CrankSection:
    """The bending section of the crank's dimensions (:func:`.crank.crank_dimensions`:
    as given, else :data:`DEFAULT_PROPORTIONS` of the crank radius and the web offset)."""
    return CrankSection(
        **{name: getattr(dimensions, name) for name in DEFAULT_PROPORTIONS},
        youngs_modulus=o.modulus,
        poisson_ratio=o.poisson,
    )


def bearing_loads(
    engine: str | os.PathLike[str] | EngineSpec,
    options: BearingOptions | Mapping[str, Any] | None = None,
    balance: BalanceStudy | None = None,
) -> BearingStudy:
    """Main-bearing loads and crank bending of an engine over one working cycle.

    Parameters
    ----------
    engine : str, path or EngineSpec
        Preset name, engine file or validated spec (its [counterweights] table sets the
        pattern, overridden by ``options.webs`` and ``options.balance_factor``).
    options : BearingOptions or mapping, optional
        The study's settings (:class:`crankbalance.schema.settings.BearingOptions`).
    balance : BalanceStudy, optional
        Counterweights already solved for this engine
        (:func:`crankbalance.studies.engine.balance_engine`); then ``options.webs`` and
        ``options.balance_factor`` must be left empty.

    Returns
    -------
    BearingStudy
        Both crank models with friction.
    """
    from ..io.engine_file import load_engine

    o = (
        options
        if isinstance(options, BearingOptions)
        else parse_options(BearingOptions, dict(options or {}))
    )
    spec = engine if isinstance(engine, EngineSpec) else load_engine(engine)
    tables = f", pressure tables {', '.join(o.pressure_csv)}" if o.gas and o.pressure_csv else ""
    with arithmetic_checked("the bearing-load study", f"engine {spec.name!r}{tables}"):
        return _bearing_loads(spec, o, balance)


#: the fields of the physics' errors that are settings of the bearing studies under
#: another name
PHYSICS_FIELDS = {"bearing_positions": "bearing", "counterweights.webs": "webs"}


def refuse_without_gas(o: BearingOptions) -> None:
    """Refuse a combustion setting given where it does not act: the Wiebe model's without
    gas forces or beside pressure tables, the tables and the bore without gas forces."""
    typed = given(o)
    for name in WIEBE_OPTIONS:
        if name in typed and not (o.gas and not o.pressure_csv):
            raise InputError(
                name,
                getattr(o, name),
                "only acts on the Wiebe combustion model (not with --pressure-csv or --no-gas)",
            )
    for name in ("pressure_csv", "bore"):
        if name in typed and not o.gas:
            raise InputError(name, getattr(o, name), "only acts with gas forces")


def named_setting(o: BearingOptions, error: InputError) -> InputError:
    """An error of the physics about a setting of the bearing studies, named by its
    setting with the value given (``bearing_positions`` is ``bearing``); another error, or
    one about the engine file's own counterweight pattern, as it is."""
    name = PHYSICS_FIELDS.get(error.field, error.field)
    if name not in BearingOptions.FIELDS or (name == "webs" and o.webs is None):
        return error
    value = getattr(o, name) if name in given(o) else error.value
    return InputError(name, value, error.allowed)


def bearings(engine: str | os.PathLike[str] | EngineSpec, settings: BearingOptions) -> BearingStudy:
    """The main-bearing loads and crank bending of an engine over one working cycle, both
    crank models (the ``bearings`` study of the registry, :func:`bearing_loads`); a
    combustion setting that would not act is refused."""
    refuse_without_gas(settings)
    try:
        study = bearing_loads(engine, settings)
    except InputError as error:
        raise named_setting(settings, error) from None
    study.to_dict()  # checked finite
    return study


def _bearing_loads(
    spec: EngineSpec, o: BearingOptions, balance: BalanceStudy | None
) -> BearingStudy:
    """:func:`bearing_loads` of a validated spec and settings."""
    from ..physics.engine_cycle_all import engine_cycle_all

    overrides: dict[str, Any] = {}
    if o.balance_factor is not None:
        overrides["balance_factor"] = o.balance_factor
    if o.webs is not None:
        overrides["webs"] = tuple(o.webs)
    if balance is None:
        balance = balance_engine(spec, halves_if_balanced=True, **overrides)
    elif overrides:
        name = next(iter(overrides))
        raise InputError(
            name, getattr(o, name), "is set by the balancing result given; leave it empty"
        )
    model, solved = balance.model, balance.result
    if model.throws != build_model(spec).throws:
        raise InputError(
            "balance", model.name, f"must be a balancing result of the engine {spec.name!r}"
        )
    offset = web_offset(spec, model)
    dimensions = crank_dimensions(
        model, offset, {name: getattr(o, name) for name in DEFAULT_PROPORTIONS}
    )
    section = crank_section(dimensions, o)
    inertia = o.crank_inertia if o.crank_inertia is not None else rotating_inertia(model)
    bore = o.bore if o.bore is not None else engine_estimate(model).bore
    bearings = (
        np.asarray(o.bearing, dtype=float)
        if o.bearing is not None
        else default_bearing_positions(model.throw_position, 2.0 * offset)
    )
    if o.clearance is not None and o.bearing_stiffness is not None:
        _check_contact_size(o.samples, model.strokes, bearings.size)
    try:
        cycle = engine_cycle_all(
            model,
            _pressure(o, model.cylinders, model.strokes),
            bore=bore,
            crank_inertia=inertia,
            speed=o.speed,
            samples_per_revolution=o.samples,
        )
    except InputError as error:
        if error.field != "crank_inertia" or o.crank_inertia is not None:
            raise
        raise InputError(
            "crank_inertia",
            f"{inertia:.4g} kg*m^2 of crank and flywheel (the engine's)",
            error.allowed,
        ) from None
    loads = crank_loads(
        cycle.crank_angle,
        cycle.throw_force,
        model.throw_angle,
        model.throw_position,
        model.throw_rotating_mass,
        model.crank_radius,
        cycle.speed,
        cycle.crank_acceleration,
        **_counterweight_arrays(solved),
    )
    ends = np.concatenate([bearings, loads.position])
    stiffness = crank_stiffness(
        model.throw_position,
        offset,
        model.crank_radius,
        section,
        float(ends.min()),
        float(ends.max()),
    )
    results: dict[str, MainBearingLoads] = {}
    for name in CRANK_MODELS:
        r = main_bearing_loads(
            loads,
            bearings,
            model.throw_position,
            name,  # type: ignore[arg-type]
            stiffness,
            o.bearing_stiffness if name == "indeterminate" else None,
            o.clearance if name == "indeterminate" and o.bearing_stiffness else None,
        )
        fr = bearing_friction(
            r.load,
            cycle.speed_mean,  # the time mean: angle-mean torque x it is the mean power
            section.journal_diameter,
            o.friction_coefficient,
            o.viscosity,
            o.bearing_length,
            o.clearance if o.viscosity is not None else None,  # Petroff takes all three
        )
        results[name] = dataclasses.replace(r, friction=fr)
    return BearingStudy(
        model=model,
        balance=solved,
        cycle=cycle,
        options=o,
        section=section,
        dimensions=dimensions,
        crank_inertia=float(inertia),
        web_offset=offset,
        stiffness=stiffness,
        bore=float(bore),
        results=results,
    )


def _check_contact_size(samples: int, strokes: int, bearings: int) -> None:
    """Refuse, before any work, a clearance contact model larger than
    :data:`crankbalance.physics.main_bearings.MAX_CONTACT_SIZE` (the samples of one cycle times
    (2 x bearings)^2), naming the samples per revolution it allows."""
    per_sample = (2 * bearings) ** 2 * strokes // 2  # samples of a cycle per revolution
    allowed = MAX_CONTACT_SIZE // per_sample
    if samples <= allowed:
        return
    if allowed < MIN_SAMPLES:
        raise InputError(
            "clearance",
            None,
            f"the contact model of {bearings} bearings is too large at any number of samples "
            f"(samples of a cycle x (2 x bearings)^2 at most {MAX_CONTACT_SIZE}): fewer "
            "bearings, or leave out the clearance",
        )
    raise InputError(
        "samples",
        samples,
        f"must be at most {allowed} with the clearance contact model of {bearings} bearings "
        f"(samples of a cycle x (2 x bearings)^2 at most {MAX_CONTACT_SIZE})",
    )


def assumed_text(s: dict[str, Any]) -> str:
    """One line of what the study took for the crank, the flywheel, the bore, the peak
    cylinder pressure and the combustion (typed, or the engine's: the same for every study,
    docs/main_bearings.md; the bore, pressure and journal in the words of
    :func:`~crankbalance.studies.performance.assumption_text`, as the Performance tab)."""
    typed = set(s["dimensions_typed"])

    def mm(name: str) -> str:
        return f"{s[name + '_m'] * 1e3:.4g} mm" + ("" if name in typed else "*")

    combustion = f"; {combustion_text(s['combustion'])}" if s["gas"] else ""
    estimated = [name for name in ("journal_diameter",) if name not in typed]
    if s["bore_from"] == "engine":
        estimated.append("bore")
    cylinder = assumption_text(
        s["bore_m"], s["peak_pressure_Pa"], s["journal_diameter_m"], estimated, note=False
    )
    return (
        f"crank + flywheel {text(s['crank_inertia_kg_m2'], 'inertia')}"
        + ("*" if s["crank_inertia_from"] == "engine" else "")
        + f"; {cylinder}, pin {mm('pin_diameter')}, web "
        f"{mm('web_thickness')} x {mm('web_width')}{combustion} "
        "(* the engine's, as every study assumes: bore = stroke, journal "
        f"{DEFAULT_PROPORTIONS['journal_diameter']:g} x crank radius)"
    )
