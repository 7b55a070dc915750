"""Torsional vibration of an engine's crank train as a study of the registry
(``torsional``, docs/torsional.md).

The lumped chain (damper ring, front end, one inertia per throw, flywheel, load) of
:mod:`crankbalance.physics.torsional`, excited by the gas and inertia torque harmonics of
every cylinder from one run of the whole-engine cycle
(:func:`~crankbalance.physics.engine_cycle_all.engine_cycle_all`): natural frequencies and
mode shapes, the resonances in the speed range with the response there, the damper check,
and the sweep. Crank dimensions not given are those every study assumes
(:func:`crankbalance.studies.crank.crank_dimensions`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import InputError
from ..physics import torsional as tv
from ..physics.model import EngineModel
from ..records import record
from ..results import ResultMixin, to_jsonable
from ..schema.settings import TorsionalOptions, default_text, given
from .engine import EngineLike, engine_label
from .performance import WIEBE_OPTIONS, arithmetic_checked

SCHEMA = "crankbalance.torsional/1"
_RPM = 30.0 / math.pi  # rad/s -> rpm
#: the crank dimensions of Carter's formula: unused when ``throw_stiffness`` is given
CARTER_SETTINGS = (
    "journal_diameter",
    "pin_diameter",
    "journal_length",
    "pin_length",
    "web_thickness",
    "web_width",
    "shear_modulus",
)


def _shown(o: TorsionalOptions, name: str) -> Any:
    """A setting as a message shows it: its value when given, else its default as one would
    type it."""
    if name in given(o):
        return getattr(o, name)
    return default_text(TorsionalOptions, name)


@record(repr=False)
class TorsionalResult(ResultMixin):
    """The torsional study of one engine.

    Attributes
    ----------
    study : TorsionalStudy
        The physics' result (modes, resonances, sweep).
    model : EngineModel
    speeds : ndarray
        The speeds of the sweep [rad/s].
    crank : dict
        What was assumed of the crank (its dimensions, rotating inertia) and the combustion.
    """

    study: tv.TorsionalStudy
    model: EngineModel
    speeds: np.ndarray
    crank: dict[str, Any]

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.torsional/1`` (SI units in the keys)."""
        out = to_jsonable({"schema": SCHEMA, **payload(self.study, self.model, self.crank)})
        assert isinstance(out, dict)
        return out


def torsional(engine: EngineLike, settings: TorsionalOptions) -> TorsionalResult:
    """Torsional vibration of the crank train of ``engine``: one inertia per throw (the
    throw with its big ends, plus its pistons' mean share), the stiffness between throws
    (given, or Carter's formula from the crank's dimensions: an approximation), front end,
    flywheel, an optional tuned damper and driven load; the natural frequencies and mode
    shapes, every resonance of an engine order with a mode in the speed range with the
    response there, and the damper check. Its work is counted and bounded before any is
    done (:func:`check_size`) and its arithmetic checked
    (:func:`crankbalance.studies.performance.arithmetic_checked`)."""
    o = settings
    typed = given(o)
    for name in WIEBE_OPTIONS:
        if name in typed and o.pressure_csv:
            raise InputError(
                name,
                getattr(o, name),
                "only acts on the Wiebe combustion model, not with --pressure-csv",
            )
    for name in CARTER_SETTINGS:
        if name in typed and o.throw_stiffness is not None:
            raise InputError(
                name,
                getattr(o, name),
                "only acts through Carter's formula, not with --throw-stiffness",
            )
    inputs = " ".join(
        [f"--engine {engine_label(engine)}", *(f"--pressure-csv {p}" for p in o.pressure_csv)]
    )
    with arithmetic_checked("torsional", inputs):
        result = _torsional(engine, o)
    result.to_dict()  # checked finite
    return result


def check_size(o: TorsionalOptions, train: tv.CrankTrain, strokes: int, speeds: np.ndarray) -> None:
    """Refuse, before any work, a study that would compute more than
    :data:`crankbalance.physics.torsional.MAX_RESPONSE_SIZE` amplitudes (speeds of the sweep
    and of the resonances in the range x engine orders x masses), naming the setting that
    drives it: ``speed_points`` or ``highest_order``."""
    orders = tv.engine_orders(strokes, o.highest_order)
    resonances, size = tv.response_size(train, orders, speeds)
    if size <= tv.MAX_RESPONSE_SIZE:
        return
    name = "speed_points" if speeds.size >= resonances else "highest_order"
    raise InputError(
        name,
        _shown(o, name),
        f"the study would compute {speeds.size + resonances} speeds ({speeds.size} of the "
        f"sweep and {resonances} resonances in the speed range) x {orders.size} engine "
        f"orders x {train.inertia.size} masses = {size} amplitudes, more than the "
        f"{tv.MAX_RESPONSE_SIZE} allowed: lower --speed-points or --highest-order, or "
        "narrow --speed-min and --speed-max",
    )


def _torsional(engine: EngineLike, o: TorsionalOptions) -> TorsionalResult:
    """:func:`torsional`, unchecked."""
    from ..io.engine_file import load_engine
    from ..physics.engine_cycle_all import engine_cycle_all
    from ..schema.engine import EngineSpec
    from .build import build_model
    from .crank import DIMENSIONS, crank_dimensions, rotating_inertia, web_offset
    from .performance import combustion_summary, pressure_source

    spec = engine if isinstance(engine, EngineSpec) else load_engine(engine)  # type: ignore[arg-type]
    model = build_model(spec)
    high = o.speed_max if o.speed_max is not None else model.speed
    if high <= o.speed_min:
        raise InputError(
            "speed_min",
            f"{o.speed_min * _RPM:g} rpm",
            f"must be below the engine's speed {high * _RPM:g} rpm (or give --speed-max)",
        )
    speeds = np.linspace(o.speed_min, high, o.speed_points)
    dimensions = None
    if o.throw_stiffness is not None:
        k_throw = o.throw_stiffness
    else:
        # the dimensions bearings uses for the same engine, where not given
        dimensions = crank_dimensions(
            model, web_offset(spec, model), {name: getattr(o, name) for name in DIMENSIONS}
        )
        k_throw = tv.carter_stiffness(
            dimensions.journal_diameter,
            dimensions.pin_diameter,
            dimensions.journal_length,
            dimensions.pin_length,
            dimensions.web_thickness,
            dimensions.web_width,
            model.crank_radius,
            o.shear_modulus,
        )
    damper: dict[str, float] = {}
    if o.damper_inertia is not None:
        assert o.damper_frequency is not None  # the settings give both
        omega_d = 2.0 * math.pi * o.damper_frequency
        damper = {
            "damper_inertia": o.damper_inertia,
            "damper_stiffness": o.damper_inertia * omega_d**2,
            "damper_damping": 2.0 * o.damper_damping_ratio * o.damper_inertia * omega_d,
        }
    train = tv.crank_train(
        tv.throw_inertias(model, o.throw_inertia),
        k_throw,
        o.front_inertia,
        o.front_stiffness if o.front_stiffness is not None else k_throw,
        o.flywheel_inertia,
        o.flywheel_stiffness if o.flywheel_stiffness is not None else k_throw,
        load_inertia=o.load_inertia,
        load_stiffness=o.load_stiffness,
        shaft_damping_ratio=o.shaft_damping_ratio,
        throw_names=tv.crank_stations(model)[1],
        **damper,
    )
    check_size(o, train, model.strokes, speeds)
    # the Wiebe model or the tables of cycle
    pressure = pressure_source(o, model.cylinders, model.strokes)
    # front end + throws + flywheel, what cycle --engine and bearings take when their crank
    # inertia is not given (the cycle adds the pistons' inertia as it varies over the turn)
    inertia = rotating_inertia(model, o.throw_inertia, o.front_inertia, o.flywheel_inertia)
    try:
        cycle = engine_cycle_all(
            model,
            pressure,
            bore=o.bore if o.bore is not None else 2.0 * model.crank_radius,
            crank_inertia=inertia,
        )
    except InputError as error:
        if error.field != "crank_inertia":
            raise
        # the cycle turns the chain's front end, throws and flywheel: the flywheel is the
        # inertia to give
        raise InputError(
            "flywheel_inertia",
            _shown(o, "flywheel_inertia"),
            f"makes front end + throws + flywheel {inertia:.4g} kg*m^2, which {error.allowed}",
        ) from None
    excitation = tv.engine_excitation(cycle, model, o.highest_order)
    study = tv.torsional_study(train, excitation, speeds, o.damper_allowed_power)
    crank = {
        "dimensions": None if dimensions is None else dimensions.to_dict(),
        "rotating_inertia_kg_m2": inertia,
        "combustion": combustion_summary(o),
    }
    return TorsionalResult(study, model, speeds, crank)


def _modes(modes: tv.TorsionalModes, names: list[str]) -> list[dict[str, Any]]:
    return [
        {
            "mode": m,
            "frequency_rad_s": float(w),
            "frequency_Hz": float(w) / (2 * math.pi),
            "nodes": int(modes.nodes[m]),
            "shape": dict(zip(names, modes.mode_shape[:, m].tolist(), strict=True)),
        }
        for m, w in enumerate(modes.frequency)
        if m > 0
    ]


def payload(study: tv.TorsionalStudy, model: EngineModel, crank: dict[str, Any]) -> dict[str, Any]:
    """The JSON of ``torsional`` without its schema; ``crank`` is what the study assumed of
    the crank and the combustion."""
    train = study.train
    names = list(train.names)
    response = study.response
    damper = None
    if train.damper_section is not None:
        allowed = study.damper_allowed_power
        worst = max(study.resonances, key=lambda r: r.damper_power, default=None)
        damper = {
            "allowed_power_W": allowed,
            "max_power_W": study.damper_max_power,
            "max_power_speed_rad_s": float(response.speed[int(np.argmax(response.damper_power))]),
            "worst_resonance": None
            if worst is None
            else {
                "mode": worst.mode,
                "order": worst.order,
                "speed_rad_s": worst.speed,
                "power_W": worst.damper_power,
                "front_amplitude_rad": worst.front_amplitude,
            },
            "within_allowed": None if allowed is None else bool(study.damper_max_power <= allowed),
        }
    return {
        "engine": {
            "name": model.name,
            "cylinders": model.cylinders,
            "strokes": model.strokes,
            "firing_order": list(model.firing_order),
            "fire_angle_rad": study.excitation.fire_angle.tolist(),
            "mean_torque_Nm": study.excitation.mean_torque,
        },
        "crank": crank,
        "masses": [
            {"name": n, "inertia_kg_m2": float(j)}
            for n, j in zip(names, train.inertia, strict=True)
        ],
        "sections": [
            {
                "from": names[s],
                "to": names[s + 1],
                "stiffness_Nm_rad": float(train.stiffness[s]),
                "damping_Nms_rad": float(train.damping[s]),
            }
            for s in range(train.stiffness.size)
        ],
        "modes": _modes(study.modes, names),
        "modes_free": _modes(study.modes_free, names[: study.modes_free.frequency.size]),
        "resonances": [
            {
                "mode": r.mode,
                "order": r.order,
                "speed_rad_s": r.speed,
                "relative_excitation": r.relative_excitation,
                "front_amplitude_rad": r.front_amplitude,
                "crank_twist_rad": r.crank_twist,
                "max_section_torque_Nm": r.max_section_torque,
                "damper_power_W": r.damper_power,
            }
            for r in study.resonances
        ],
        "damper": damper,
        "sweep": {
            "speed_rad_s": response.speed.tolist(),
            "front_amplitude_rad": study.front_amplitude.tolist(),
            "crank_twist_rad": study.crank_twist.tolist(),
            "max_section_torque_Nm": response.torque_peak.max(axis=1).tolist(),
            "damper_power_W": response.damper_power.tolist(),
        },
    }
