"""``crankbalance friction | bench | cycle | sensitivity``: bearing friction and performance.

Each command parses its options into its study's settings and runs the study
(:mod:`crankbalance.studies.friction`, :mod:`crankbalance.studies.cycle`, through
:mod:`crankbalance.studies.registry`); it prints the table, the CSV or the JSON and writes
its output files (``bench --history``, ``cycle --plot``). Quantities are unit strings
(``"20 mm"``, ``"9000 rpm"``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import click

from ..errors import InputError
from ..output.format import json_text, number, text
from ..results import require_finite
from ._common import echo_table, format_option, run_study, study_options
from .plot import check_figure, write_figure

FORMATS = ("table", "json", "csv")
_RPM = 30.0 / math.pi  # rad/s -> rpm


def _cell(value: float | str) -> str:
    return value if isinstance(value, str) else number(value, 5)


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
@study_options("friction")
@format_option(FORMATS)
def friction(fmt: str, **values: Any) -> None:
    """Bearing friction torque under a constant plus a rotating load.

    Hoem and Røsholm (2016), Sec. 4.2.1.
    """
    result = run_study("friction", None, values)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    rows, hydro = result.coulomb, result.hydrodynamic
    keys = [k for k in rows[0]]
    if fmt == "csv":
        extra = list(hydro) if hydro else []  # the hydrodynamic torques, same on each row
        _emit_csv(
            keys + extra,
            [[r[k] for k in keys] + [hydro[k] for k in extra] for r in rows],
        )
        return
    click.echo(
        f"constant load {text(result.constant_load, 'force')}, rotating load "
        f"{text(result.rotating_load, 'force')}, journal {text(result.journal_diameter, 'length')}"
    )
    echo_table(keys, [[_cell(r[k]) for k in keys] for r in rows])
    if hydro:
        click.echo(
            f"Petroff torque {text(hydro['petroff_torque_Nm'], 'torque', 5)}; with eccentricity "
            f"{number(result.eccentricity)}: "
            f"{text(hydro['journal_bearing_torque_Nm'], 'torque', 5)}"
        )


# --------------------------------------------------------------------------------------
# bench
# --------------------------------------------------------------------------------------


@click.command()
@study_options("bench")
@click.option(
    "--history",
    type=click.Path(dir_okay=False, writable=True),
    help="Write the time histories of the last run to this CSV file.",
)
@format_option(FORMATS)
def bench(history: str | None, fmt: str, **values: Any) -> None:
    """Simulated rotor test bench: PI spin-up, hold, required torque.

    Hoem and Røsholm (2016), Sec. 5.2.5.

    Defaults are the thesis' test rotor (Appendix E, balanced case 1).
    """
    if history and not Path(os.path.realpath(history)).parent.is_dir():
        raise InputError("history", history, "must be a file in an existing directory")
    study = run_study("bench", None, values, progress=_progress("bench"))
    if history:
        from ..io.files import atomic_open

        last = study.runs[-1]
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
    if fmt == "json":
        click.echo(json_text(study.to_dict()))
        return
    rows = [
        {
            "speed_rpm": r.settings.speed * _RPM,
            "required_torque_Nm": r.required_torque,
            "mean_friction_torque_Nm": r.mean_friction_torque,
            "friction_power_W": r.friction_power,
            "final_speed_rpm": r.final_speed * _RPM,
        }
        for r in study.runs
    ]
    keys = list(rows[0])
    if fmt == "csv":
        _emit_csv(keys, [[r[k] for k in keys] for r in rows])
    else:
        echo_table(keys, [[number(r[k], 5) for k in keys] for r in rows])


# --------------------------------------------------------------------------------------
# cycle and sensitivity
# --------------------------------------------------------------------------------------


def _engine_option(function: Any) -> Any:
    return click.option(
        "--engine",
        default=None,
        help="Engine file or preset: stroke, rod length, offset, reciprocating "
        "mass (of --cylinder), speed and stroke count come from it unless "
        "given as options.",
    )(function)


@click.command()
@_engine_option
@study_options("cycle")
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    help="Figure of the torque over the cycle with each cylinder's share (.png, .svg or .html).",
)
@format_option(FORMATS)
def cycle(fmt: str, plot: str | None, engine: str | None, **values: Any) -> None:
    """One engine cycle: torques, speed fluctuation, flywheel sizing.

    With --engine, every cylinder fires in its turn (firing order, bank angles, shared
    crankpins): crank torque of each cylinder and of the engine, speed fluctuation, and
    the flywheel for --speed-fluctuation-target. With --cylinder N (or without --engine,
    the cylinder typed as options), one cylinder alone, with its main-bearing loads and
    friction at --balance-factor.

    CSV output gives the curves over the crank angle (for one cylinder, the polar load
    diagram is the transverse against the in-line main-bearing load).
    """
    if plot is not None:
        check_figure(plot)
    study = run_study("cycle", engine, values)
    if plot is not None:
        from ..output import figures

        write_figure(plot, figures.engine_torque_figure(study.result))
    if fmt == "json":
        click.echo(json_text(study.to_dict()))
    elif fmt == "csv":
        curves = study.curves
        keys = list(curves)
        _emit_csv(keys, list(zip(*(curves[k] for k in keys), strict=True)))
    else:
        _echo_cycle(study.payload, study.flywheel_inertia)


def _echo_cycle(payload: dict[str, Any], flywheel_inertia: float = 0.0) -> None:
    """The text output of ``cycle``: a header, the summary and the flywheel
    (``flywheel_inertia``: :func:`_assumed_text`)."""
    import math as _math

    speed, strokes = payload["speed_rad_s"], payload["strokes"]
    if "engine" in payload:
        engine = payload["engine"]
        steps = "-".join(number(_math.degrees(a)) for a in engine["firing_interval_rad"])
        click.echo(
            f"{engine['name']}: "
            + (
                f"all {engine['cylinders']} cylinders"
                if engine["cylinders"] > 1
                else "one cylinder"
            )
            + f", {text(speed, 'speed')}, "
            f"{strokes}-stroke, firing order {'-'.join(map(str, engine['firing_order']))} "
            f"(intervals {steps}°)"
        )
    else:
        click.echo(
            f"single cylinder, {text(speed, 'speed')}, {strokes}-stroke, "
            f"balance factor {number(payload['cylinder']['balance_factor'])}"
        )
    click.echo(_assumed_text(payload, flywheel_inertia))
    if "assumed" in payload:  # one cylinder
        from ..studies.cycle import assumption_words

        click.echo(f"Assumed: {assumption_words(payload['assumed'])}")
    values = dict(payload["summary"])
    values.update(payload.get("flywheel") or {})
    echo_table(["quantity", "value"], [summary_row(k, v) for k, v in values.items()])


#: the values of ``cycle``'s summary that are fractions, shown as percentages (as their
#: settings are given: ``--speed-fluctuation-target 1%``)
PERCENT_KEYS = frozenset(
    {"speed_fluctuation", "speed_fluctuation_target", "check_speed_fluctuation"}
)


def summary_row(key: str, value: float) -> list[str]:
    """A row of a summary table in words with its unit: ``mean_torque_Nm`` ->
    ``["mean torque", "236.4 N·m"]``, ``speed_fluctuation`` 0.0144 -> ``["speed
    fluctuation", "1.44 %"]`` (the unit from the JSON key's suffix,
    :func:`crankbalance.results.key_label`)."""
    from ..results import UNITS, key_label

    if key in PERCENT_KEYS:
        label, kind, value = key.replace("_", " "), "percent", 100.0 * value
    else:
        label, kind = key_label(key)
        label = label.split(" [")[0]
    unit = UNITS[kind][0] if kind else ""
    shown = number(value * (UNITS[kind][1] if kind and kind != "percent" else 1.0), 5)
    return [label, f"{shown} {unit}".rstrip()]


def _assumed_text(payload: dict[str, Any], flywheel_inertia: float = 0.0) -> str:
    """One line of the crank + flywheel inertia and the combustion ``cycle`` or
    ``sensitivity`` took (``flywheel_inertia``: that of ``--flywheel-inertia``, in the
    inertia of one cylinder's payload) [kg·m²]."""
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
    extra = f" + flywheel {text(flywheel, 'inertia')}" if flywheel else ""
    return f"crank + flywheel {text(inertia, 'inertia')}{extra} ({source}); " + combustion_text(
        payload["combustion"]
    )


@click.command()
@_engine_option
@study_options("sensitivity")
@format_option(FORMATS)
def sensitivity(fmt: str, engine: str | None, **values: Any) -> None:
    """Sweep the balance factor: friction, bearing loads, torque, acceleration, shaking."""
    study = run_study("sensitivity", engine, values, progress=_progress("sensitivity"))
    if fmt == "json":
        click.echo(json_text(study.to_dict()))
    elif fmt == "csv":
        _emit_csv(study.header, study.rows)
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
        click.echo(_assumed_text(study.payload, study.flywheel_inertia))
        click.echo(f"Assumed: {study.assumption()}")
        echo_table(short, [[number(v) for v in row] for row in study.rows])
