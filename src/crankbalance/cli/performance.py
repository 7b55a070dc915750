"""``crankbalance friction | bench | cycle | sensitivity``: bearing friction and performance.

Quantities are unit strings (``"20 mm"``, ``"9000 rpm"``); the physics lives in
:mod:`crankbalance.physics.friction`, :mod:`crankbalance.physics.rotor_bench` and
:mod:`crankbalance.physics.engine_cycle`, imported when a command runs; pressure tables are read by
:mod:`crankbalance.io.pressure_csv`.
"""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from ..errors import InputError
from ..output.format import json_text, keyed, number, text
from ..results import require_finite
from ..schema.settings import MAX_BENCH_REVOLUTIONS, MAX_BENCH_RUNS, MAX_SWEEP
from ._common import (
    echo_table,
    format_option,
    given_options,
    named_as_typed,
    option_name,
    parse_settings,
    refuse_unused,
)

if TYPE_CHECKING:
    from ..schema.settings import CycleOptions

FORMATS = ("table", "json", "csv")


def _number_list(text: str, field: str) -> list[float]:
    """``"0,0.28,0.5"`` or ``"start:stop:step"`` (stop included) -> floats (their count and
    range are checked by the options schema)."""
    try:
        if ":" in text:
            start, stop, step = (float(x) for x in text.split(":"))
            span = (stop - start) / step
            if not (step > 0 and 0 <= span < math.inf):
                raise ValueError
            if span > MAX_SWEEP:
                raise InputError(field, text, f"must give at most {MAX_SWEEP} values")
            return [start + k * step for k in range(int(math.floor(span + 1e-9)) + 1)]
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise InputError(
            field, text, "must be numbers separated by commas, or start:stop:step with step > 0"
        ) from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError(field, text, "must hold at least one finite number")
    return values


def _cell(value: float | str) -> str:
    return value if isinstance(value, str) else number(value, 5)


def _emit_json(schema: str, payload: dict[str, Any]) -> None:
    click.echo(json_text({"schema": schema, **payload}))


_RPM = 30.0 / math.pi  # rad/s -> rpm
#: JSON keys of the bench rotor (unit in a suffix)
ROTOR_KEYS: dict[str, str | tuple[str, float]] = {
    "mass": "mass_kg",
    "inertia": "inertia_kg_m2",
    "journal_diameter": "journal_diameter_m",
    "unbalance": "unbalance_kg_m",
    "bearing_positions": "bearing_positions_m",
    "mass_position": "mass_position_m",
    "unbalance_position": "unbalance_position_m",
    "gravity": "gravity_m_s2",
}
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


def _emit_csv(header: Sequence[str], rows: Sequence[Sequence[float | str]]) -> None:
    require_finite([[v for v in row if not isinstance(v, str)] for row in rows], "rows")
    lines = [",".join(header)]
    for row in rows:
        lines.append(",".join(v if isinstance(v, str) else f"{v:.9g}" for v in row))
    click.echo("\n".join(lines))


def _progress(label: str):  # noqa: ANN202
    def report(done: int, total: int) -> None:
        click.echo(f"\r{label}: {done}/{total}", err=True, nl=done == total)

    return report


# --------------------------------------------------------------------------------------
# friction
# --------------------------------------------------------------------------------------


@click.command()
@click.option(
    "--load",
    "load_text",
    default="0 N",
    show_default=True,
    help="Constant bearing load, e.g. the rotor weight.",
)
@click.option("--rotating-load", help="Rotating load (unbalance force), e.g. '42.2 N'.")
@click.option(
    "--unbalance", help="Unbalance, e.g. '427 g*mm' (with --speed instead of --rotating-load)."
)
@click.option("--speed", help="Shaft speed, e.g. '3000 rpm'.")
@click.option("--journal-diameter", required=True, help="Journal diameter, e.g. '20 mm'.")
@click.option("--friction-coefficient", help="Coulomb friction coefficient (above 0, at most 1).")
@click.option("--torque", help="Measured torque: back-compute the friction coefficient (Eq. 5.1).")
@click.option("--viscosity", help="Oil viscosity for the hydrodynamic bearing, e.g. '0.01 Pa*s'.")
@click.option("--bearing-length", help="Bearing length (hydrodynamic).")
@click.option("--clearance", help="Mean radial clearance (hydrodynamic), e.g. '20 um'.")
@click.option(
    "--eccentricity",
    default="0",
    show_default=True,
    help="Eccentricity ratio, from 0 to below 1 (hydrodynamic).",
)
@click.option(
    "--attitude-angle", default="0 deg", show_default=True, help="Attitude angle (hydrodynamic)."
)
@format_option(FORMATS)
def friction(
    load_text: str,
    rotating_load: str | None,
    unbalance: str | None,
    speed: str | None,
    journal_diameter: str,
    friction_coefficient: str | None,
    torque: str | None,
    viscosity: str | None,
    bearing_length: str | None,
    clearance: str | None,
    eccentricity: str,
    attitude_angle: str,
    fmt: str,
) -> None:
    """Bearing friction torque under a constant plus a rotating load.

    Hoem and Røsholm (2016), Sec. 4.2.1.
    """
    from ..physics import friction as fr
    from ..schema.settings import FrictionOptions

    o = parse_settings(
        FrictionOptions,
        {
            "load": load_text,
            "rotating_load": rotating_load,
            "unbalance": unbalance,
            "speed": speed,
            "journal_diameter": journal_diameter,
            "friction_coefficient": friction_coefficient,
            "torque": torque,
            "viscosity": viscosity,
            "bearing_length": bearing_length,
            "clearance": clearance,
            "eccentricity": eccentricity,
            "attitude_angle": attitude_angle,
        },
    )
    assert o.journal_diameter is not None  # a required option
    if rotating_load is not None and unbalance is not None:
        raise InputError("--unbalance", unbalance, "give either --rotating-load or --unbalance")
    if o.unbalance is not None:
        if o.speed is None:
            raise InputError("--speed", None, "is needed with --unbalance")
        rotating = o.unbalance * o.speed**2
    else:
        rotating = o.rotating_load or 0.0
    constant = o.load
    if o.torque is None and o.friction_coefficient is None and o.viscosity is None:
        raise InputError(
            "--friction-coefficient",
            None,
            "give --friction-coefficient, --torque or the hydrodynamic options",
        )
    hydrodynamic = ("bearing_length", "clearance", "eccentricity", "attitude_angle")
    refuse_unused(
        {name: o.viscosity is not None for name in hydrodynamic}
        | {"speed": o.viscosity is not None or o.unbalance is not None},
        "only acts on the hydrodynamic bearing (with --viscosity), or for --speed with --unbalance",
    )
    if (o.torque is not None or o.friction_coefficient is not None) and not (
        constant > 0 or rotating > 0
    ):
        raise InputError(
            "--load",
            load_text,
            "the bearing carries no load: give --load (e.g. "
            "the rotor weight) and/or --rotating-load or --unbalance",
        )
    rows: list[dict[str, float | str]] = []
    methods: tuple[fr.MeanLoadMethod, ...] = ("approximate", "cubic", "arithmetic")
    for method in methods:
        mean = (
            float(fr.mean_equivalent_load(constant, rotating, method))
            if constant + rotating > 0
            else 0.0
        )
        row: dict[str, float | str] = {"method": method, "mean_load_N": mean}
        if o.friction_coefficient is not None:
            row["torque_Nm"] = float(
                fr.friction_torque(o.friction_coefficient, mean, o.journal_diameter)
            )
        if o.torque is not None:
            with named_as_typed({"torque": torque}):
                mu = fr.friction_coefficient_from_torque(
                    o.torque, constant, rotating, o.journal_diameter, method
                )
            row["friction_coefficient"] = float(mu)
        rows.append(row)
    hydro: dict[str, float] | None = None
    if o.viscosity is not None:
        if o.speed is None or o.bearing_length is None or o.clearance is None:
            raise InputError(
                "--viscosity",
                viscosity,
                "the hydrodynamic bearing needs --speed, --bearing-length, --clearance",
            )
        args = (o.viscosity, o.journal_diameter, o.bearing_length, o.clearance, o.speed)
        hydro = {
            "petroff_torque_Nm": float(fr.petroff_torque(*args)),
            "journal_bearing_torque_Nm": float(
                fr.journal_bearing_torque(
                    *args, o.eccentricity, constant + rotating, o.attitude_angle
                )
            ),
        }
    inputs = {
        "constant_load_N": constant,
        "rotating_load_N": rotating,
        "journal_diameter_m": o.journal_diameter,
    }
    payload = {"inputs": inputs, "coulomb": rows, "hydrodynamic": hydro}
    require_finite(payload)
    if fmt == "json":
        _emit_json("crankbalance.friction/1", payload)
        return
    keys = [k for k in rows[0]]
    if fmt == "csv":
        extra = list(hydro) if hydro else []  # the hydrodynamic torques, same on each row
        _emit_csv(
            keys + extra,
            [
                [r[k] for k in keys] + [hydro[k] for k in extra]  # type: ignore[index]
                for r in rows
            ],
        )
        return
    click.echo(
        f"constant load {text(constant, 'force')}, rotating load {text(rotating, 'force')}, "
        f"journal {text(o.journal_diameter, 'length')}"
    )
    echo_table(keys, [[_cell(r[k]) for k in keys] for r in rows])
    if hydro:
        click.echo(
            f"Petroff torque {text(hydro['petroff_torque_Nm'], 'torque', 5)}; with eccentricity "
            f"{number(o.eccentricity)}: {text(hydro['journal_bearing_torque_Nm'], 'torque', 5)}"
        )


# --------------------------------------------------------------------------------------
# bench
# --------------------------------------------------------------------------------------


@click.command()
@click.option("--mass", default="2.5464 kg", show_default=True, help="Rotor mass.")
@click.option(
    "--inertia", default="2847.335 kg*mm^2", show_default=True, help="Rotor moment of inertia."
)
@click.option("--unbalance", default="0 g*mm", show_default=True, help="Rotor unbalance.")
@click.option("--journal-diameter", default="20 mm", show_default=True)
@click.option(
    "--friction-coefficient",
    required=True,
    help="Coulomb friction coefficient of each bearing (above 0, at most 1).",
)
@click.option(
    "--speed",
    "speeds",
    multiple=True,
    default=("3000 rpm",),
    show_default=True,
    help=f"Set speed; repeat for several runs (at most {MAX_BENCH_RUNS}).",
)
@click.option(
    "--ramp-time",
    default="2 s",
    show_default=True,
    help="Duration of the speed ramp (at most 600 s).",
)
@click.option(
    "--hold-time",
    default="1.5 s",
    show_default=True,
    help=f"Duration of the hold (at most 600 s; a run simulates at most "
    f"{MAX_BENCH_REVOLUTIONS} revolutions).",
)
@click.option("--kp", default="0.2", show_default=True, help="PI proportional gain [N m s/rad].")
@click.option("--ki", default="10", show_default=True, help="PI integral gain [N m/rad].")
@click.option(
    "--history",
    type=click.Path(dir_okay=False, writable=True),
    help="Write the time histories of the last run to this CSV file.",
)
@format_option(FORMATS)
def bench(
    mass: str,
    inertia: str,
    unbalance: str,
    journal_diameter: str,
    friction_coefficient: str,
    speeds: tuple[str, ...],
    ramp_time: str,
    hold_time: str,
    kp: str,
    ki: str,
    history: str | None,
    fmt: str,
) -> None:
    """Simulated rotor test bench: PI spin-up, hold, required torque.

    Hoem and Røsholm (2016), Sec. 5.2.5.

    Defaults are the thesis' test rotor (Appendix E, balanced case 1).
    """
    from ..physics.rotor_bench import BenchRotor, BenchSettings, run_bench
    from ..schema.settings import BenchOptions

    o = parse_settings(
        BenchOptions,
        {
            "mass": mass,
            "inertia": inertia,
            "unbalance": unbalance,
            "journal_diameter": journal_diameter,
            "friction_coefficient": friction_coefficient,
            "speed": list(speeds),
            "ramp_time": ramp_time,
            "hold_time": hold_time,
            "kp": kp,
            "ki": ki,
        },
    )
    assert o.friction_coefficient is not None  # a required option
    with named_as_typed({"mass": mass, "inertia": inertia, "unbalance": unbalance}):
        rotor = BenchRotor(
            mass=o.mass,
            inertia=o.inertia,
            journal_diameter=o.journal_diameter,
            friction_coefficient=o.friction_coefficient,
            unbalance=o.unbalance,
        )
    # everything is checked before the first (slow) run
    runs = [
        BenchSettings(
            speed=speed,
            ramp_time=o.ramp_time,
            hold_time=o.hold_time,
            proportional_gain=o.kp,
            integral_gain=o.ki,
        )
        for speed in o.speed
    ]
    if history and not Path(os.path.realpath(history)).parent.is_dir():
        raise InputError("history", history, "must be a file in an existing directory")
    results = []
    report = _progress("bench")
    for k, settings in enumerate(runs):
        results.append(run_bench(rotor, settings))
        require_finite(results[-1], f"runs[{k}]")  # before any output, the history too
        report(k + 1, len(runs))
    if history:
        from ..io.files import atomic_open

        last = results[-1]
        with atomic_open(history) as handle:
            handle.write(
                "time_s,speed_rpm,motor_torque_Nm,friction_torque_Nm,"
                "bearing_load_a_N,bearing_load_b_N\n"
            )
            for row in zip(
                last.time,
                last.speed * 30 / math.pi,
                last.motor_torque,
                last.friction_torque,
                last.bearing_load_a,
                last.bearing_load_b,
                strict=True,
            ):
                handle.write(",".join(f"{v:.9g}" for v in row) + "\n")
    rows = [
        {
            "speed_rpm": r.settings.speed * _RPM,
            "required_torque_Nm": r.required_torque,
            "mean_friction_torque_Nm": r.mean_friction_torque,
            "friction_power_W": r.friction_power,
            "final_speed_rpm": r.final_speed * _RPM,
        }
        for r in results
    ]
    keys = list(rows[0])
    if fmt == "json":
        run_rows = [
            {
                "speed_rad_s": r.settings.speed,
                "required_torque_Nm": r.required_torque,
                "mean_friction_torque_Nm": r.mean_friction_torque,
                "friction_power_W": r.friction_power,
                "final_speed_rad_s": r.final_speed,
            }
            for r in results
        ]
        _emit_json(
            "crankbalance.bench/2", {"rotor": keyed(rotor.to_dict(), ROTOR_KEYS), "runs": run_rows}
        )
    elif fmt == "csv":
        _emit_csv(keys, [[r[k] for k in keys] for r in rows])
    else:
        echo_table(keys, [[number(r[k], 5) for k in keys] for r in rows])


# --------------------------------------------------------------------------------------
# cycle and sensitivity
# --------------------------------------------------------------------------------------


def _engine_options(function: Any) -> Any:
    options = [
        click.option(
            "--engine",
            default=None,
            help="Engine file or preset: stroke, rod length, offset, reciprocating "
            "mass (of --cylinder), speed and stroke count come from it unless "
            "given as options.",
        ),
        click.option(
            "--cylinder",
            default=None,
            help="With --engine: the cylinder studied alone ('cycle': default all cylinders "
            "at once; 'sensitivity': default 1).",
        ),
        click.option("--bore", default="76.8 mm", show_default=True),
        click.option("--stroke", default="53.8 mm", show_default=True),
        click.option("--rod-length", default="103.5 mm", show_default=True),
        click.option("--reciprocating-mass", default="282 g", show_default=True),
        click.option(
            "--crank-inertia",
            default=None,
            help="Inertia of all purely rotating parts incl. flywheel [default: 0.006 kg*m^2, "
            "the thesis' single, without --engine; with --engine the engine's: front end + "
            "throws + flywheel, as 'torsional' and 'bearings'].",
        ),
        click.option("--journal-diameter", default="30 mm", show_default=True),
        click.option("--friction-coefficient", default="0.005", show_default=True),
        click.option("--speed", default="9000 rpm", show_default=True, help="Mean speed."),
        click.option("--strokes", type=click.Choice(["2", "4"]), default="4", show_default=True),
        click.option("--compression-ratio", default="13.5", show_default=True),
        click.option(
            "--ignition",
            default="-25 deg",
            show_default=True,
            help="Start of combustion from firing TDC.",
        ),
        click.option("--burn-duration", default="50 deg", show_default=True),
        click.option(
            "--intake-pressure",
            default="1 bar",
            show_default=True,
            help="Pressure at the start of compression (load).",
        ),
        click.option(
            "--pressure-csv",
            multiple=True,
            type=click.Path(exists=True, dir_okay=False),
            help="Cylinder pressure table instead of the Wiebe model: columns "
            "crank angle [deg from firing TDC], absolute pressure [bar]. 'cycle' of a whole "
            "engine: one for every cylinder, or repeated once per cylinder in cylinder order.",
        ),
    ]
    for option in reversed(options):
        function = option(function)
    return function


def crank_inertia(o: CycleOptions, model: Any = None) -> float:
    """The crank + flywheel inertia of ``cycle`` and ``sensitivity`` before
    ``--flywheel-inertia`` [kg m^2]: as typed; else, with an engine (``model``, the engine
    as studied), its rotating inertia (:func:`crankbalance.studies.crank.rotating_inertia`,
    the same as ``bearings`` and ``torsional``); else the thesis' single's."""
    if o.crank_inertia is not None:
        return float(o.crank_inertia)
    if model is None:
        from ..schema.settings import THESIS_CRANK_INERTIA

        return THESIS_CRANK_INERTIA
    from ..studies.crank import rotating_inertia

    return rotating_inertia(model)


def _inertia_from(o: CycleOptions) -> str:
    """Where the crank + flywheel inertia came from: ``typed``, ``engine`` (the engine's
    rotating inertia) or ``thesis`` (the thesis' single, without an engine)."""
    return "typed" if o.crank_inertia is not None else "thesis" if o.engine is None else "engine"


#: the physics' names of options of ``cycle`` and ``sensitivity`` (the cylinder's fields)
PHYSICS_NAMES = {"crank_radius": "stroke", "ignition_angle": "ignition"}


@contextlib.contextmanager
def _named_options(texts: dict[str, Any]) -> Iterator[None]:
    """Within the block, an :class:`InputError` of the physics about a value the user
    typed names its option of ``cycle`` or ``sensitivity`` with the text typed (``texts``:
    parameter name -> text); a rod too short for a typed stroke names ``--stroke``, an
    engine's firing order that a typed stroke count cannot fire names ``--strokes``. The
    crank inertia is named by :func:`_inertia_error`."""
    given = given_options()
    try:
        yield
    except InputError as error:
        name = PHYSICS_NAMES.get(error.field, error.field)
        allowed = error.allowed
        if name == "rod_length" and "rod_length" not in given and "stroke" in given:
            name = "stroke"  # the typed stroke leaves no room for the rod
            allowed = f"is too long for the rod ({error.value:g} m), which {allowed}"
        elif name == "crank_train.firing_order" and "strokes" in given:
            name = "strokes"  # the engine's firing order is of the other cycle
            allowed = f"does not suit the engine's firing order {error.value}: {allowed}"
        if name not in given or name not in texts:
            raise
        raise InputError(option_name(name), texts[name], allowed) from None


def _inputs(o: CycleOptions) -> str:
    """What a cycle was computed of, as typed: the engine and cylinder, the tables."""
    parts = [f"--engine {o.engine}" if o.engine else "the cylinder of the options"]
    if o.engine and o.cylinder:
        parts.append(f"--cylinder {o.cylinder}")
    return " ".join([*parts, *(f"--pressure-csv {path}" for path in o.pressure_csv)])


def _inertia_error(o: CycleOptions, inertia: float, error: InputError, hint: str) -> InputError:
    """The physics' refusal of a crank inertia too small for the cycle (``crank_inertia``),
    naming the option that sets it: ``--flywheel-inertia`` when one was added, else
    ``--crank-inertia``, shown as the crank + flywheel ``inertia`` taken [kg m^2] and where
    it came from; ``hint`` says what else may be typed. Another error is returned as it is."""
    if error.field != "crank_inertia":
        return error
    origin = {"typed": "", "engine": " (the engine's)", "thesis": " (the thesis' single's)"}
    return InputError(
        "--crank-inertia" if o.flywheel_inertia is None else "--flywheel-inertia",
        f"{inertia:.4g} kg*m^2 of crank and flywheel{origin[_inertia_from(o)]}",
        f"{error.allowed}; {hint}",
    )


def _engine_from_options(o: CycleOptions) -> tuple[Any, Any, float, int, float]:
    """The cylinder, its pressure source, speed, stroke count and crank + flywheel inertia
    (before ``--flywheel-inertia``) of ``cycle`` and ``sensitivity`` from their validated
    options (:class:`~crankbalance.schema.settings.CycleOptions`); an option that would be ignored
    is refused."""
    from ..physics.engine_cycle import CylinderSpec
    from ..studies.performance import WIEBE_OPTIONS, pressure_source

    given = given_options()
    refuse_unused({"cylinder": o.engine is not None}, "only acts with --engine", given)
    refuse_unused(
        {name: not o.pressure_csv for name in WIEBE_OPTIONS},
        "only acts on the Wiebe combustion model, not with --pressure-csv",
        given,
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
    if o.engine is None:
        inertia = crank_inertia(o)
        cylinder = CylinderSpec(
            **settings, **geometry, crank_inertia=inertia + (o.flywheel_inertia or 0.0)
        )
    else:
        from ..studies.cylinder import cylinder_of
        from ..studies.engine import as_model
        from ..studies.performance import cycle_cylinder, cycle_model

        model = as_model(o.engine)
        cylinder_of(model, number, "--cylinder")
        # the engine's values, except where an option was given on the command line
        typed = {
            key: geometry[key]
            for key, option in (
                ("crank_radius", "stroke"),
                ("rod_length", "rod_length"),
                ("reciprocating_mass", "reciprocating_mass"),
            )
            if option in given
        }
        # the whole engine's inertia turns with this cylinder (its crank as typed; a typed
        # reciprocating mass is this cylinder's alone)
        inertia = crank_inertia(
            o,
            cycle_model(
                model,
                crank_radius=typed.get("crank_radius"),
                rod_length=typed.get("rod_length"),
            ),
        )
        cylinder = cycle_cylinder(
            model,
            number,
            **settings,
            **typed,
            crank_inertia=inertia + (o.flywheel_inertia or 0.0),
        )
        speed = speed if "speed" in given else float(model.speed)
        strokes = strokes if "strokes" in given else int(model.strokes)
    return cylinder, pressure_source(o, 1, strokes), speed, strokes, inertia


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


#: the summary of ``cycle`` of a whole engine: result attribute -> JSON key
ENGINE_SUMMARY_KEYS = (
    ("mean_torque", "mean_torque_Nm"),
    ("indicated_work", "indicated_work_J"),
    ("indicated_power", "indicated_power_W"),
    ("peak_torque", "peak_torque_Nm"),
    ("min_torque", "min_torque_Nm"),
    ("speed_fluctuation", "speed_fluctuation"),
    ("energy_excursion", "energy_excursion_J"),
)


@click.command()
@_engine_options
@click.option(
    "--balance-factor",
    default="0.5",
    show_default=True,
    help="One cylinder: share of the reciprocating mass on the counterweight, on top of "
    "100 % of the rotating mass.",
)
@click.option(
    "--flywheel-inertia",
    default=None,
    help="Flywheel inertia, added to --crank-inertia, e.g. '0.05 kg*m^2'.",
)
@click.option(
    "--speed-fluctuation-target",
    default=None,
    help="Size the flywheel for this speed fluctuation (max - min)/mean, e.g. '0.01' or "
    "'1%' (from 1e-6 to 0.2).",
)
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    help="Figure of the torque over the cycle with each cylinder's share (.png, .svg or .html).",
)
@format_option(FORMATS)
def cycle(
    fmt: str,
    balance_factor: str,
    flywheel_inertia: str | None,
    speed_fluctuation_target: str | None,
    plot: str | None,
    **options: Any,
) -> None:
    """One engine cycle: torques, speed fluctuation, flywheel sizing.

    With --engine, every cylinder fires in its turn (firing order, bank angles, shared
    crankpins): crank torque of each cylinder and of the engine, speed fluctuation, and
    the flywheel for --speed-fluctuation-target. With --cylinder N (or without --engine,
    the cylinder typed as options), one cylinder alone, with its main-bearing loads and
    friction at --balance-factor.

    CSV output gives the curves over the crank angle (for one cylinder, the polar load
    diagram is the transverse against the in-line main-bearing load).
    """
    from ..schema.settings import CycleOptions
    from ..studies.performance import arithmetic_checked

    o = parse_settings(
        CycleOptions,
        {
            **options,
            "pressure_csv": list(options["pressure_csv"]),
            "balance_factor": balance_factor,
            "flywheel_inertia": flywheel_inertia,
            "speed_fluctuation_target": speed_fluctuation_target,
        },
    )
    if plot is not None:
        from ._common import require_extra
        from .plot import check_output

        check_output(plot, (".png", ".svg", ".html"), "--plot")
        require_extra("web", "plotly", *(() if plot.lower().endswith(".html") else ("kaleido",)))
    texts = {
        **options,
        "balance_factor": balance_factor,
        "flywheel_inertia": flywheel_inertia,
        "speed_fluctuation_target": speed_fluctuation_target,
    }
    with _named_options(texts), arithmetic_checked("cycle", _inputs(o)):
        if o.engine is not None and o.cylinder is None:
            result, payload, curves = _whole_engine_cycle(o)
        else:
            result, payload, curves = _one_cylinder_cycle(o)
    require_finite(payload)
    if plot is not None:
        _write_cycle_plot(plot, result)
    if fmt == "json":
        _emit_json("crankbalance.cycle/3", payload)
    elif fmt == "csv":
        keys = list(curves)
        _emit_csv(keys, list(zip(*(curves[k] for k in keys), strict=True)))
    else:
        _echo_cycle(payload, o.flywheel_inertia or 0.0)


def _one_cylinder_cycle(o: CycleOptions) -> tuple[Any, dict[str, Any], dict[str, Any]]:
    """``cycle`` of one cylinder: the result, the JSON payload and the CSV curves."""
    import numpy as np

    from ..physics.engine_cycle import engine_cycle
    from ..studies.performance import combustion_summary, size_cylinder_flywheel

    cylinder, pressure, speed, strokes, inertia = _engine_from_options(o)
    try:
        result = engine_cycle(cylinder, speed, pressure, strokes)  # type: ignore[arg-type]
    except InputError as error:
        hint = "" if o.speed_fluctuation_target else " (or size it: --speed-fluctuation-target)"
        raise _inertia_error(
            o, cylinder.crank_inertia, error, f"add a flywheel with --flywheel-inertia{hint}"
        ) from None
    summary = {label: getattr(result, name) for name, label in SUMMARY_KEYS}
    summary["energy_check_ratio"] = (
        result.gas_work / result.indicated_work if (result.indicated_work) else 1.0
    )
    flywheel = None
    if o.speed_fluctuation_target is not None:
        sizing = size_cylinder_flywheel(cylinder, result, pressure, o.speed_fluctuation_target)
        flywheel = _flywheel_keys(
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
        "crank_inertia_from": _inertia_from(o),
        "combustion": combustion_summary(o),
        "speed_rad_s": speed,
        "strokes": strokes,
        "summary": summary,
        **({"flywheel": flywheel} if flywheel else {}),
        "curves": keyed({k: v.tolist() for k, v in curves.items()}, CURVE_KEYS),
    }
    return result, payload, curves


def _flywheel_keys(
    o: CycleOptions, crank: float, required: float, excursion: float, achieved: float
) -> dict[str, float]:
    """The ``flywheel`` part of the JSON of ``cycle`` (``crank``: the crank + flywheel
    inertia used before ``--flywheel-inertia`` [kg m^2])."""
    return {
        "speed_fluctuation_target": float(o.speed_fluctuation_target or 0.0),
        "energy_excursion_J": excursion,
        "required_inertia_kg_m2": required,
        "required_flywheel_inertia_kg_m2": max(required - crank, 0.0),
        "check_speed_fluctuation": achieved,
    }


def _whole_engine_cycle(o: CycleOptions) -> tuple[Any, dict[str, Any], dict[str, Any]]:
    """``cycle`` of every cylinder of ``--engine``: the result, the JSON payload and the CSV
    curves; an option that acts on one cylinder only is refused."""
    import numpy as np

    from ..studies.engine import as_model
    from ..studies.performance import (
        WIEBE_OPTIONS,
        combustion_summary,
        cycle_model,
        pressure_source,
        whole_engine_cycle,
    )

    given = given_options()
    refuse_unused(
        {name: False for name in ("balance_factor", "journal_diameter", "friction_coefficient")},
        "acts on one cylinder's bearing (give --cylinder N): the whole engine's cycle has "
        "no bearing model",
        given,
    )
    refuse_unused(
        {name: not o.pressure_csv for name in WIEBE_OPTIONS},
        "only acts on the Wiebe combustion model, not with --pressure-csv",
        given,
    )
    assert o.engine is not None
    model = cycle_model(
        as_model(o.engine),
        speed=o.speed if "speed" in given else None,
        strokes=o.strokes if "strokes" in given else None,
        crank_radius=o.stroke / 2 if "stroke" in given else None,
        rod_length=o.rod_length if "rod_length" in given else None,
        reciprocating_mass=o.reciprocating_mass if "reciprocating_mass" in given else None,
    )
    pressure = pressure_source(o, model.cylinders, model.strokes)
    crank = crank_inertia(o, model)
    inertia = crank + (o.flywheel_inertia or 0.0)
    try:
        result = whole_engine_cycle(
            model,
            pressure,
            crank_inertia=inertia,
            bore=o.bore if "bore" in given else None,
            speed_fluctuation_target=o.speed_fluctuation_target,
        )
    except InputError as error:
        hint = "" if o.speed_fluctuation_target else " (or size it: --speed-fluctuation-target)"
        raise _inertia_error(
            o, inertia, error, f"add a flywheel with --flywheel-inertia{hint}"
        ) from None
    summary = {label: getattr(result, name) for name, label in ENGINE_SUMMARY_KEYS}
    summary["max_crank_acceleration_rad_s2"] = float(np.abs(result.crank_acceleration).max())
    summary["energy_check_ratio"] = (
        result.gas_work / result.indicated_work if result.indicated_work else 1.0
    )
    flywheel = None
    if result.required_inertia is not None:
        flywheel = _flywheel_keys(
            o,
            crank,
            result.required_inertia,
            result.energy_excursion,
            float(result.required_inertia_fluctuation or 0.0),
        )
    order = list(model.firing_order)
    fire = result.fire_angle
    sequence = fire[np.array(order) - 1]
    intervals = np.diff(np.append(sequence, sequence[0] + np.pi * model.strokes))
    engine = {
        "name": model.name,
        "cylinders": model.cylinders,
        "throws": model.throws,
        "bore_m": o.bore if "bore" in given else 2.0 * model.crank_radius,
        "crank_radius_m": model.crank_radius,
        "rod_length_m": model.rod_length,
        "offset_m": model.cylinder_offset.tolist(),
        "reciprocating_mass_kg": model.reciprocating_mass.tolist(),
        "crank_inertia_kg_m2": crank,
        "crank_inertia_from": _inertia_from(o),
        "flywheel_inertia_kg_m2": o.flywheel_inertia or 0.0,
        "firing_order": order,
        "fire_angle_rad": fire.tolist(),
        # one cylinder fires once a cycle: its interval is the cycle, not 0
        "firing_interval_rad": (
            np.mod(intervals, np.pi * model.strokes) if model.cylinders > 1 else intervals
        ).tolist(),
    }
    curves: dict[str, Any] = {
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
        "engine": engine,
        "combustion": combustion_summary(o),
        "speed_rad_s": result.speed_mean,
        "strokes": result.strokes,
        "summary": summary,
        **({"flywheel": flywheel} if flywheel else {}),
        "curves": json_curves,
    }
    return result, payload, curves


def _echo_cycle(payload: dict[str, Any], flywheel_inertia: float = 0.0) -> None:
    """The text output of ``cycle``: a header, the summary and the flywheel
    (``flywheel_inertia``: :func:`_assumed_text`)."""
    import math as _math

    speed, strokes = payload["speed_rad_s"], payload["strokes"]
    if "engine" in payload:
        engine = payload["engine"]
        steps = "/".join(f"{_math.degrees(a):.4g}" for a in engine["firing_interval_rad"])
        click.echo(
            f"{engine['name']}: "
            + (
                f"all {engine['cylinders']} cylinders"
                if engine["cylinders"] > 1
                else "one cylinder"
            )
            + f", {text(speed, 'speed')}, "
            f"{strokes}-stroke, firing order {'-'.join(map(str, engine['firing_order']))} "
            f"(intervals {steps} deg)"
        )
    else:
        click.echo(
            f"single cylinder, {text(speed, 'speed')}, {strokes}-stroke, "
            f"balance factor {number(payload['cylinder']['balance_factor'])}"
        )
    click.echo(_assumed_text(payload, flywheel_inertia))
    rows = [[k, number(v, 5)] for k, v in payload["summary"].items()]
    if "flywheel" in payload:
        rows += [
            [k, number(v, 5)] for k, v in payload["flywheel"].items() if k not in payload["summary"]
        ]
    echo_table(["quantity", "value"], rows)


def _assumed_text(payload: dict[str, Any], flywheel_inertia: float = 0.0) -> str:
    """One line of the crank + flywheel inertia and the combustion ``cycle`` or
    ``sensitivity`` took (``flywheel_inertia``: that of ``--flywheel-inertia``, in the
    inertia of one cylinder's payload) [kg m^2]."""
    from ..studies.performance import combustion_text

    if "engine" in payload:
        e = payload["engine"]
        inertia, flywheel = e["crank_inertia_kg_m2"], e["flywheel_inertia_kg_m2"]
        origin = e["crank_inertia_from"]
    else:  # one cylinder (cycle) or the sweep of one cylinder (sensitivity)
        flywheel, origin = flywheel_inertia, payload["crank_inertia_from"]
        inertia = payload.get("cylinder", payload)["crank_inertia_kg_m2"] - flywheel
    source = {
        "typed": "typed",
        "engine": "the engine's: front end + throws + flywheel, as 'torsional' and 'bearings'",
        "thesis": "the thesis' single",
    }[origin]
    extra = f" + flywheel {flywheel:.4g}" if flywheel else ""
    return f"crank + flywheel {inertia:.4g}{extra} kg m^2 ({source}); " + combustion_text(
        payload["combustion"]
    )


def _write_cycle_plot(plot: str, result: Any) -> None:
    """The torque figure of ``cycle``, written atomically (png, svg or html by suffix)."""
    from ..io.files import write_atomic
    from ..output import render
    from ..output.figures.performance import engine_torque_figure

    fig = engine_torque_figure(result)
    fmt = Path(plot).suffix.lower().lstrip(".")
    write_atomic(plot, render.to_html(fig) if fmt == "html" else render.to_image(fig, fmt))  # type: ignore[arg-type]
    click.echo(f"wrote {plot}", err=True)


@click.command()
@_engine_options
@click.option(
    "--balance-factors",
    default="0:1:0.1",
    show_default=True,
    help="Balance factors: '0,0.28,0.5' or start:stop:step.",
)
@click.option(
    "--mass-scales",
    default="1",
    show_default=True,
    help="Factors on the reciprocating mass (lighter parts < 1), comma separated.",
)
@format_option(FORMATS)
def sensitivity(fmt: str, balance_factors: str, mass_scales: str, **options: Any) -> None:
    """Sweep the balance factor: friction, bearing loads, torque, acceleration, shaking."""
    from ..physics.engine_cycle import balance_sensitivity
    from ..schema.settings import SensitivityOptions
    from ..studies.performance import arithmetic_checked, combustion_summary

    values = {
        **options,
        "pressure_csv": list(options["pressure_csv"]),
        "balance_factor": 0.0,  # swept: the cylinder's own factor is not used
        "balance_factors": _number_list(balance_factors, "--balance-factors"),
        "mass_scales": _number_list(mass_scales, "--mass-scales"),
    }
    if values["cylinder"] is None:  # the schema's default: cylinder 1
        del values["cylinder"]
    o = parse_settings(SensitivityOptions, values)
    with _named_options(options), arithmetic_checked("sensitivity", _inputs(o)):
        cylinder, pressure, speed, strokes, _inertia = _engine_from_options(o)
        try:
            result = balance_sensitivity(
                cylinder,
                speed,
                pressure,
                o.balance_factors,
                o.mass_scales,
                strokes,  # type: ignore[arg-type]
                progress=_progress("sensitivity"),
            )
        except InputError as error:
            raise _inertia_error(
                o, cylinder.crank_inertia, error, "give a larger --crank-inertia"
            ) from None
    labels = [
        label for name, label in SUMMARY_KEYS if name not in ("load_torque", "indicated_work")
    ]
    names = [name for name, _ in SUMMARY_KEYS if name not in ("load_torque", "indicated_work")]
    rows = []
    for i, scale in enumerate(result.mass_scales):
        for k, factor in enumerate(result.balance_factors):
            rows.append(
                [float(scale), float(factor)] + [float(getattr(result, n)[i, k]) for n in names]
            )
    header = ["mass_scale", "balance_factor", *labels]
    payload = {
        "speed_rad_s": speed,
        "strokes": strokes,
        "crank_inertia_kg_m2": cylinder.crank_inertia,
        "crank_inertia_from": _inertia_from(o),
        "combustion": combustion_summary(o),
        "points": [dict(zip(header, row, strict=True)) for row in rows],
    }
    require_finite(payload)
    if fmt == "json":
        _emit_json("crankbalance.sensitivity/2", payload)
    elif fmt == "csv":
        _emit_csv(header, rows)
    else:
        short = [
            "scale",
            "f_b",
            "T_f N·m",
            "P_f W",
            "F_max N",
            "F_mean N",
            "T_net,max",
            "acc_max",
            "dω/ω",
            "shake_z N",
            "shake_x N",
            "shake N",
        ]
        click.echo(_assumed_text(payload, o.flywheel_inertia or 0.0))
        echo_table(short, [[number(v) for v in row] for row in rows])
