"""``crankbalance friction | bench | cycle | sensitivity``: bearing friction and performance.

Quantities are unit strings (``"20 mm"``, ``"9000 rpm"``); the physics lives in
:mod:`crankbalance.friction`, :mod:`crankbalance.rotor_bench` and
:mod:`crankbalance.engine_cycle`, imported when a command runs; pressure tables are read by
:mod:`crankbalance.io.pressure_csv`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import click

from ..errors import InputError
from ..format import json_text, keyed, number, text
from ._common import echo_table, format_option

FORMATS = ("table", "json", "csv")


def _q(text: str, kind: str, field: str) -> float:
    from ..units import parse_quantity

    return parse_quantity(text, kind, field)


def _q_opt(text: str | None, kind: str, field: str) -> float | None:
    return None if text is None else _q(text, kind, field)


def _number_list(text: str, field: str) -> list[float]:
    """``"0,0.28,0.5"`` or ``"start:stop:step"`` (stop included) -> floats."""
    try:
        if ":" in text:
            start, stop, step = (float(x) for x in text.split(":"))
            if not step > 0 or stop < start:
                raise ValueError
            count = int(math.floor((stop - start) / step + 1e-9)) + 1
            if count > 100000:
                raise ValueError
            return [start + k * step for k in range(count)]
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
#: the curves of ``cycle`` in JSON: SI values (the CSV keeps bar and rpm)
CURVE_KEYS: dict[str, str | tuple[str, float]] = {
    "pressure_bar": ("pressure_Pa", 1e5),
    "speed_rpm": ("speed_rad_s", 1.0 / _RPM),
}


def _emit_csv(header: Sequence[str], rows: Sequence[Sequence[float | str]]) -> None:
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
@click.option("--friction-coefficient", type=float, help="Coulomb friction coefficient.")
@click.option("--torque", help="Measured torque: back-compute the friction coefficient (Eq. 5.1).")
@click.option("--viscosity", help="Oil viscosity for the hydrodynamic bearing, e.g. '0.01 Pa*s'.")
@click.option("--bearing-length", help="Bearing length (hydrodynamic).")
@click.option("--clearance", help="Mean radial clearance (hydrodynamic), e.g. '20 um'.")
@click.option(
    "--eccentricity",
    type=float,
    default=0.0,
    show_default=True,
    help="Eccentricity ratio (hydrodynamic).",
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
    friction_coefficient: float | None,
    torque: str | None,
    viscosity: str | None,
    bearing_length: str | None,
    clearance: str | None,
    eccentricity: float,
    attitude_angle: str,
    fmt: str,
) -> None:
    """Bearing friction torque under a constant plus a rotating load.

    Hoem and Røsholm (2016), Sec. 4.2.1.
    """
    from .. import friction as fr
    from ..errors import check_positive

    constant = _q(load_text, "force", "load")
    omega = _q_opt(speed, "speed", "speed")
    if omega is not None:
        check_positive("speed", omega)
    diameter = check_positive(
        "journal_diameter", _q(journal_diameter, "length", "journal_diameter")
    )
    if rotating_load is not None and unbalance is not None:
        raise InputError("unbalance", unbalance, "give either --rotating-load or --unbalance")
    if unbalance is not None:
        if omega is None:
            raise InputError("speed", None, "is needed with --unbalance")
        rotating = _q(unbalance, "unbalance", "unbalance") * omega**2
    else:
        rotating = _q(rotating_load, "force", "rotating_load") if rotating_load else 0.0
    for name, value, given_text in (
        ("load", constant, load_text),
        ("rotating_load", rotating, rotating_load or unbalance),
        ("friction_coefficient", friction_coefficient, friction_coefficient),
    ):
        if value is not None and not (value >= 0 and math.isfinite(value)):
            raise InputError(name, given_text, "must be finite and not negative")
    measured = _q_opt(torque, "torque", "torque")
    if measured is None and friction_coefficient is None and viscosity is None:
        raise InputError(
            "friction_coefficient",
            None,
            "give --friction-coefficient, --torque or the hydrodynamic options",
        )
    if viscosity is None:
        given = _given_options()
        hydrodynamic = ("bearing_length", "clearance", "eccentricity", "attitude_angle")
        unused: list[str] = [name for name in hydrodynamic if name in given]
        if speed is not None and unbalance is None:
            unused.append("speed")
        for name in unused:
            raise InputError(
                name,
                locals()[name],
                "only acts on the hydrodynamic bearing "
                "(with --viscosity), or for --speed with --unbalance",
            )
    if (measured is not None or friction_coefficient is not None) and not (
        constant > 0 or rotating > 0
    ):
        raise InputError(
            "load",
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
        if friction_coefficient is not None:
            row["torque_Nm"] = float(fr.friction_torque(friction_coefficient, mean, diameter))
        if measured is not None:
            row["friction_coefficient"] = float(
                fr.friction_coefficient_from_torque(measured, constant, rotating, diameter, method)
            )
        rows.append(row)
    hydro: dict[str, float] | None = None
    if viscosity is not None:
        if omega is None or bearing_length is None or clearance is None:
            raise InputError(
                "viscosity",
                viscosity,
                "the hydrodynamic bearing needs --speed, --bearing-length, --clearance",
            )
        args = (
            _q(viscosity, "viscosity", "viscosity"),
            diameter,
            _q(bearing_length, "length", "bearing_length"),
            _q(clearance, "length", "clearance"),
            omega,
        )
        hydro = {
            "petroff_torque_Nm": float(fr.petroff_torque(*args)),
            "journal_bearing_torque_Nm": float(
                fr.journal_bearing_torque(
                    *args,
                    eccentricity,
                    constant + rotating,
                    _q(attitude_angle, "angle", "attitude_angle"),
                )
            ),
        }
    inputs = {
        "constant_load_N": constant,
        "rotating_load_N": rotating,
        "journal_diameter_m": diameter,
    }
    if fmt == "json":
        _emit_json(
            "crankbalance.friction/1", {"inputs": inputs, "coulomb": rows, "hydrodynamic": hydro}
        )
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
        f"journal {text(diameter, 'length')}"
    )
    echo_table(keys, [[_cell(r[k]) for k in keys] for r in rows])
    if hydro:
        click.echo(
            f"Petroff torque {text(hydro['petroff_torque_Nm'], 'torque', 5)}; with eccentricity "
            f"{number(eccentricity)}: {text(hydro['journal_bearing_torque_Nm'], 'torque', 5)}"
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
    type=float,
    required=True,
    help="Coulomb friction coefficient of each bearing.",
)
@click.option(
    "--speed",
    "speeds",
    multiple=True,
    default=("3000 rpm",),
    show_default=True,
    help="Set speed; repeat for several runs.",
)
@click.option("--ramp-time", default="2 s", show_default=True)
@click.option("--hold-time", default="1.5 s", show_default=True)
@click.option(
    "--kp", type=float, default=0.2, show_default=True, help="PI proportional gain [N m s/rad]."
)
@click.option(
    "--ki", type=float, default=10.0, show_default=True, help="PI integral gain [N m/rad]."
)
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
    friction_coefficient: float,
    speeds: tuple[str, ...],
    ramp_time: str,
    hold_time: str,
    kp: float,
    ki: float,
    history: str | None,
    fmt: str,
) -> None:
    """Simulated rotor test bench: PI spin-up, hold, required torque.

    Hoem and Røsholm (2016), Sec. 5.2.5.

    Defaults are the thesis' test rotor (Appendix E, balanced case 1).
    """
    from ..rotor_bench import BenchRotor, BenchSettings, run_bench

    rotor = BenchRotor(
        mass=_q(mass, "mass", "mass"),
        inertia=_q(inertia, "inertia", "inertia"),
        journal_diameter=_q(journal_diameter, "length", "journal_diameter"),
        friction_coefficient=friction_coefficient,
        unbalance=_q(unbalance, "unbalance", "unbalance"),
    )
    # everything is checked before the first (slow) run
    runs = [
        BenchSettings(
            speed=_q(text, "speed", "speed"),
            ramp_time=_q(ramp_time, "time", "ramp_time"),
            hold_time=_q(hold_time, "time", "hold_time"),
            proportional_gain=kp,
            integral_gain=ki,
        )
        for text in speeds
    ]
    if history and not Path(history).resolve().parent.is_dir():
        raise InputError("history", history, "must be a file in an existing directory")
    results = []
    report = _progress("bench")
    for k, settings in enumerate(runs):
        results.append(run_bench(rotor, settings))
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
            type=click.IntRange(1),
            default=1,
            show_default=True,
            help="With --engine: the cylinder studied.",
        ),
        click.option("--bore", default="76.8 mm", show_default=True),
        click.option("--stroke", default="53.8 mm", show_default=True),
        click.option("--rod-length", default="103.5 mm", show_default=True),
        click.option("--reciprocating-mass", default="282 g", show_default=True),
        click.option(
            "--crank-inertia",
            default="0.006 kg*m^2",
            show_default=True,
            help="Inertia of all purely rotating parts incl. flywheel.",
        ),
        click.option("--journal-diameter", default="30 mm", show_default=True),
        click.option("--friction-coefficient", type=float, default=0.005, show_default=True),
        click.option("--speed", default="9000 rpm", show_default=True, help="Mean speed."),
        click.option("--strokes", type=click.Choice(["2", "4"]), default="4", show_default=True),
        click.option("--compression-ratio", type=float, default=13.5, show_default=True),
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
            type=click.Path(exists=True, dir_okay=False),
            help="Cylinder pressure table instead of the Wiebe model: columns "
            "crank angle [deg from firing TDC], absolute pressure [bar].",
        ),
    ]
    for option in reversed(options):
        function = option(function)
    return function


def _given_options() -> set[str]:
    """Names of the options the user typed (not defaults) in the running command."""
    context = click.get_current_context(silent=True)
    if context is None:
        return set()
    return {
        name
        for name in context.params
        if context.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE
    }


def _engine_from_options(o: dict[str, Any], balance_factor: float) -> tuple[Any, Any, float, int]:
    from ..engine_cycle import CylinderSpec, WiebeCombustion

    geometry = {
        "crank_radius": _q(o["stroke"], "length", "stroke") / 2,
        "rod_length": _q(o["rod_length"], "length", "rod_length"),
        "reciprocating_mass": _q(o["reciprocating_mass"], "mass", "reciprocating_mass"),
        "offset": 0.0,
    }
    speed, strokes = _q(o["speed"], "speed", "speed"), int(o["strokes"])
    settings = {
        "bore": _q(o["bore"], "length", "bore"),
        "crank_inertia": _q(o["crank_inertia"], "inertia", "crank_inertia"),
        "balance_factor": balance_factor,
        "journal_diameter": _q(o["journal_diameter"], "length", "journal_diameter"),
        "friction_coefficient": o["friction_coefficient"],
    }
    if o["engine"] is None:
        cylinder = CylinderSpec(**settings, **geometry)
    else:
        from ..studies.cylinder import cylinder_of
        from ..studies.engine import as_model
        from ..studies.performance import cycle_cylinder

        model = as_model(o["engine"])
        cylinder_of(model, o["cylinder"], "--cylinder")
        # the engine's values, except where an option was given on the command line
        given = _given_options()
        typed = {
            key: geometry[key]
            for key, option in (
                ("crank_radius", "stroke"),
                ("rod_length", "rod_length"),
                ("reciprocating_mass", "reciprocating_mass"),
            )
            if option in given
        }
        cylinder = cycle_cylinder(model, o["cylinder"], **settings, **typed)
        speed = speed if "speed" in given else float(model.speed)
        strokes = strokes if "strokes" in given else int(model.strokes)
    if o["pressure_csv"]:
        from ..io.pressure_csv import read_pressure_csv

        pressure: Any = read_pressure_csv(o["pressure_csv"])
    else:
        pressure = WiebeCombustion(
            compression_ratio=o["compression_ratio"],
            ignition_angle=_q(o["ignition"], "angle", "ignition"),
            burn_duration=_q(o["burn_duration"], "angle", "burn_duration"),
            intake_pressure=_q(o["intake_pressure"], "pressure", "intake_pressure"),
        )
    return cylinder, pressure, speed, strokes


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


@click.command()
@_engine_options
@click.option(
    "--balance-factor",
    type=float,
    default=0.5,
    show_default=True,
    help="Share of the reciprocating mass on the counterweight, on top of 100 % of "
    "the rotating mass.",
)
@format_option(FORMATS)
def cycle(fmt: str, balance_factor: float, **options: Any) -> None:
    """One engine cycle of a single cylinder: torques, main-bearing loads, speed fluctuation.

    CSV output gives the curves over the crank angle (the polar load diagram is the
    transverse against the in-line main-bearing load).
    """
    import numpy as np

    from ..engine_cycle import engine_cycle

    cylinder, pressure, speed, strokes = _engine_from_options(options, balance_factor)
    result = engine_cycle(cylinder, speed, pressure, strokes)  # type: ignore[arg-type]
    summary = {label: getattr(result, name) for name, label in SUMMARY_KEYS}
    summary["energy_check_ratio"] = (
        result.gas_work / result.indicated_work if (result.indicated_work) else 1.0
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
    if fmt == "json":
        _emit_json(
            "crankbalance.cycle/2",
            {
                "cylinder": keyed(cylinder.to_dict(), CYLINDER_KEYS),
                "speed_rad_s": speed,
                "strokes": strokes,
                "summary": summary,
                "curves": keyed({k: v.tolist() for k, v in curves.items()}, CURVE_KEYS),
            },
        )
    elif fmt == "csv":
        keys = list(curves)
        _emit_csv(keys, list(zip(*(curves[k] for k in keys), strict=True)))
    else:
        click.echo(
            f"single cylinder, {text(speed, 'speed')}, {strokes}-stroke, "
            f"balance factor {number(balance_factor)}"
        )
        echo_table(["quantity", "value"], [[k, number(v, 5)] for k, v in summary.items()])


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
    from ..engine_cycle import balance_sensitivity

    factors = _number_list(balance_factors, "balance_factors")
    scales = _number_list(mass_scales, "mass_scales")
    cylinder, pressure, speed, strokes = _engine_from_options(options, 0.0)
    result = balance_sensitivity(
        cylinder,
        speed,
        pressure,
        factors,
        scales,
        strokes,  # type: ignore[arg-type]
        progress=_progress("sensitivity"),
    )
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
    if fmt == "json":
        _emit_json(
            "crankbalance.sensitivity/2",
            {
                "speed_rad_s": speed,
                "strokes": strokes,
                "points": [dict(zip(header, row, strict=True)) for row in rows],
            },
        )
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
        echo_table(short, [[number(v) for v in row] for row in rows])
