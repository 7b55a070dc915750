"""``crankbalance torsional``: torsional vibration of an engine's crank train.

The lumped chain (damper ring, front end, one inertia per throw, flywheel, load) of
:mod:`crankbalance.physics.torsional`, excited by the gas and inertia torque harmonics of every
cylinder from one run of the whole-engine cycle
(:func:`~crankbalance.physics.engine_cycle_all.engine_cycle_all`): natural frequencies and mode
shapes, the resonances in the speed range with the response there, the damper check, and
the sweep. ``docs/torsional.md``.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click

from ..errors import InputError
from ._common import (
    echo_table,
    format_option,
    given_options,
    named_as_typed,
    option_name,
    parse_settings,
)

_RPM = 30.0 / math.pi  # rad/s -> rpm
FORMATS = ("table", "json", "csv")
#: most resonances the table shows (JSON has all)
TABLE_RESONANCES = 12
#: the options of the command: every field of TorsionalOptions but the engine
_FIELDS = (
    "speed_min",
    "speed_max",
    "speed_points",
    "highest_order",
    "throw_inertia",
    "throw_stiffness",
    "journal_diameter",
    "pin_diameter",
    "journal_length",
    "pin_length",
    "web_thickness",
    "web_width",
    "shear_modulus",
    "front_inertia",
    "front_stiffness",
    "flywheel_inertia",
    "flywheel_stiffness",
    "damper_inertia",
    "damper_frequency",
    "damper_damping_ratio",
    "damper_allowed_power",
    "load_inertia",
    "load_stiffness",
    "shaft_damping_ratio",
    "bore",
    "compression_ratio",
    "ignition",
    "burn_duration",
    "intake_pressure",
)

#: the crank dimensions of Carter's formula: unused when --throw-stiffness is given
CARTER_OPTIONS = (
    "journal_diameter",
    "pin_diameter",
    "journal_length",
    "pin_length",
    "web_thickness",
    "web_width",
    "shear_modulus",
)


def _options(function: Any) -> Any:
    from ..schema.settings import TorsionalOptions, default_text

    for name in reversed(_FIELDS):
        spec = TorsionalOptions.FIELDS[name]
        default = default_text(TorsionalOptions, name)
        shown = f" [default: {default}]" if default else ""
        if not default and spec.hint:
            shown = f" [{spec.hint}]"
        if name.endswith("_stiffness") and name != "damper_stiffness":
            shown += " E.g. '5e5 N*m/rad'."
        function = click.option(option_name(name), default=None, help=f"{spec.title}.{shown}")(
            function
        )
    return function


@click.command()
@click.option("--engine", default=None, help="Engine file or preset (required).")
@_options
@click.option(
    "--pressure-csv",
    multiple=True,
    type=click.Path(exists=True, dir_okay=False),
    help="Cylinder pressure table instead of the Wiebe model (as 'cycle': crank angle [deg "
    "from firing TDC], absolute pressure [bar]); one for every cylinder, or one per cylinder "
    "in cylinder order.",
)
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    help="Campbell diagram and forced response (.png, .svg or .html).",
)
@format_option(FORMATS)
def torsional(fmt: str, plot: str | None, **options: Any) -> None:
    """Torsional vibration of the crank train of --engine.

    One inertia per throw (the throw with its big ends, default m_rot r^2, plus its
    pistons' mean share), the stiffness between throws (given, or Carter's formula from
    the journal, pin and web dimensions: an approximation), front end, flywheel, an
    optional tuned damper (--damper-inertia and --damper-frequency) and driven load.
    Prints the natural frequencies and mode shapes (free-free and with the load), every
    resonance of an engine order with a mode in the speed range with the response there,
    and the damper check. CSV: the sweep over the speed range.
    """
    from ..results import require_finite
    from ..schema.settings import TorsionalOptions
    from ..studies.performance import WIEBE_OPTIONS
    from ._common import refuse_unused

    o = parse_settings(TorsionalOptions, {**options, "pressure_csv": list(options["pressure_csv"])})
    refuse_unused(
        {name: not o.pressure_csv for name in WIEBE_OPTIONS},
        "only acts on the Wiebe combustion model, not with --pressure-csv",
    )
    refuse_unused(
        {name: o.throw_stiffness is None for name in CARTER_OPTIONS},
        "only acts through Carter's formula, not with --throw-stiffness",
    )
    if plot is not None:
        from ._common import require_extra
        from .plot import check_output

        check_output(plot, (".png", ".svg", ".html"), "--plot")
        require_extra("web", "plotly", *(() if plot.lower().endswith(".html") else ("kaleido",)))
    typed = {name: options[name] for name in _FIELDS if options.get(name) is not None}
    with named_as_typed(typed):
        study, model, speeds, crank = run_study(o)
    payload = study_payload(study, model, crank)
    require_finite(payload)
    if plot is not None:
        _write_plot(plot, study)
    if fmt == "json":
        from ..output.format import json_text

        click.echo(json_text({"schema": "crankbalance.torsional/1", **payload}))
    elif fmt == "csv":
        sweep = payload["sweep"]
        keys = list(sweep)
        click.echo(",".join(keys))
        for row in zip(*(sweep[k] for k in keys), strict=True):
            click.echo(",".join(f"{v:.9g}" for v in row))
    else:
        _echo(payload)


def run_study(o: Any) -> tuple[Any, Any, Any, dict[str, Any]]:
    """The study of the validated options: (TorsionalStudy, EngineModel, speeds [rad/s],
    what was assumed of the crank: the JSON's ``crank``). Its work is counted and bounded
    before any is done (:func:`check_size`), and its arithmetic checked
    (:func:`crankbalance.studies.performance.arithmetic_checked`)."""
    from ..studies.performance import arithmetic_checked

    inputs = " ".join([f"--engine {o.engine}", *(f"--pressure-csv {p}" for p in o.pressure_csv)])
    with arithmetic_checked("torsional", inputs):
        return _run_study(o)


def check_size(o: Any, train: Any, strokes: int, speeds: Any) -> None:
    """Refuse, before any work, a study that would compute more than
    :data:`crankbalance.physics.torsional.MAX_RESPONSE_SIZE` amplitudes (speeds of the sweep and of
    the resonances in the range x engine orders x masses), naming the option that drives
    it: ``--speed-points`` or ``--highest-order``."""
    from ..physics import torsional as tv

    orders = tv.engine_orders(strokes, o.highest_order)
    resonances, size = tv.response_size(train, orders, speeds)
    if size <= tv.MAX_RESPONSE_SIZE:
        return
    name = "speed_points" if speeds.size >= resonances else "highest_order"
    raise InputError(
        option_name(name),
        _typed(name),
        f"the study would compute {speeds.size + resonances} speeds ({speeds.size} of the "
        f"sweep and {resonances} resonances in the speed range) x {orders.size} engine "
        f"orders x {train.inertia.size} masses = {size} amplitudes, more than the "
        f"{tv.MAX_RESPONSE_SIZE} allowed: lower --speed-points or --highest-order, or "
        "narrow --speed-min and --speed-max",
    )


def _typed(name: str) -> str:
    """An option of the running command as typed, else its default as one would type it."""
    from ..schema.settings import TorsionalOptions, default_text

    if name in given_options():
        return str(click.get_current_context().params[name])
    return default_text(TorsionalOptions, name)


def _run_study(o: Any) -> tuple[Any, Any, Any, dict[str, Any]]:
    """:func:`run_study`, unchecked."""
    import numpy as np

    from ..io.engine_file import load_engine
    from ..physics import torsional as tv
    from ..physics.engine_cycle_all import engine_cycle_all
    from ..studies.build import build_model
    from ..studies.crank import DIMENSIONS, crank_dimensions, rotating_inertia, web_offset
    from ..studies.performance import combustion_summary, pressure_source

    spec = load_engine(o.engine)
    model = build_model(spec)
    high = o.speed_max if o.speed_max is not None else model.speed
    if high <= o.speed_min:
        raise InputError(
            "--speed-min",
            f"{o.speed_min * _RPM:g} rpm",
            f"must be below the engine's speed {high * _RPM:g} rpm (or give --speed-max)",
        )
    speeds = np.linspace(o.speed_min, high, o.speed_points)
    dimensions = None
    if o.throw_stiffness is not None:
        k_throw = o.throw_stiffness
    else:
        # the dimensions bearings uses for the same engine, where not typed
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
    # inertia is not typed (the cycle adds the pistons' inertia as it varies over the turn)
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
        # inertia to type
        raise InputError(
            "--flywheel-inertia",
            _typed("flywheel_inertia"),
            f"makes front end + throws + flywheel {inertia:.4g} kg*m^2, which {error.allowed}",
        ) from None
    excitation = tv.engine_excitation(cycle, model, o.highest_order)
    study = tv.torsional_study(train, excitation, speeds, o.damper_allowed_power)
    crank = {
        "dimensions": None if dimensions is None else dimensions.to_dict(),
        "rotating_inertia_kg_m2": inertia,
        "combustion": combustion_summary(o),
    }
    return study, model, speeds, crank


def _modes(modes: Any, names: list[str]) -> list[dict[str, Any]]:
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


def study_payload(study: Any, model: Any, crank: dict[str, Any]) -> dict[str, Any]:
    """The JSON of ``torsional`` (``crankbalance.torsional/1``, SI units in the keys);
    ``crank`` is what :func:`run_study` assumed of the crank and the combustion."""
    import numpy as np

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


def _echo(payload: dict[str, Any]) -> None:
    e = payload["engine"]
    click.echo(
        f"{e['name']}: {e['cylinders']} cylinders, {e['strokes']}-stroke, firing order "
        + "-".join(map(str, e["firing_order"]))
    )
    _echo_assumed(payload["crank"])
    echo_table(
        ["mass", "inertia [kg m^2]", "stiffness to next [N m/rad]"],
        [
            [m["name"], f"{m['inertia_kg_m2']:.5g}", f"{s['stiffness_Nm_rad']:.4g}" if s else ""]
            for m, s in zip(payload["masses"], [*payload["sections"], None], strict=True)
        ],
    )
    for key, title in (("modes_free", "free-free engine"), ("modes", "with the load")):
        if key == "modes" and len(payload["modes"]) == len(payload["modes_free"]):
            continue
        click.echo(f"Natural frequencies ({title}):")
        echo_table(
            ["mode", "frequency [Hz]", "nodes", "shape (front .. rear)"],
            [
                [
                    str(m["mode"]),
                    f"{m['frequency_Hz']:.1f}",
                    str(m["nodes"]),
                    " ".join(f"{v:+.2f}" for v in m["shape"].values()),
                ]
                for m in payload[key]
            ],
        )
    shown = payload["resonances"]
    if len(shown) > TABLE_RESONANCES:
        shown = sorted(
            sorted(shown, key=lambda r: -r["crank_twist_rad"])[:TABLE_RESONANCES],
            key=lambda r: r["speed_rad_s"],
        )
    if not shown:
        click.echo("No resonance of an engine order with a mode in the speed range.")
    click.echo(
        f"Resonances in the speed range: {len(shown)} of {len(payload['resonances'])} "
        "(those of largest crank twist; all in --format json); the response is synthesised "
        "from all orders:"
    )
    echo_table(
        [
            "mode",
            "order",
            "speed [rpm]",
            "rel. excitation",
            "front [deg]",
            "twist [deg]",
            "torque [N m]",
            "damper [W]",
        ],
        [
            [
                str(r["mode"]),
                f"{r['order']:g}",
                f"{r['speed_rad_s'] * _RPM:.0f}",
                f"{r['relative_excitation']:.3f}",
                f"{math.degrees(r['front_amplitude_rad']):.4f}",
                f"{math.degrees(r['crank_twist_rad']):.4f}",
                f"{r['max_section_torque_Nm']:.1f}",
                f"{r['damper_power_W']:.2f}",
            ]
            for r in shown
        ],
    )
    d = payload["damper"]
    if d is None:
        click.echo("No damper (give --damper-inertia and --damper-frequency).")
        return
    line = (
        f"Damper: largest power {d['max_power_W']:.2f} W at "
        f"{d['max_power_speed_rad_s'] * _RPM:.0f} rpm in the sweep"
    )
    if d["allowed_power_W"] is None:
        click.echo(line + "; no allowed power given (--damper-allowed-power).")
    else:
        verdict = "within" if d["within_allowed"] else "ABOVE"
        click.echo(line + f"; {verdict} the allowed {d['allowed_power_W']:.1f} W.")


def _echo_assumed(crank: dict[str, Any]) -> None:
    """One line of the crank dimensions and combustion the study took (typed, or the
    engine's: the same for every study, docs/torsional.md)."""
    parts = [f"front + throws + flywheel {crank['rotating_inertia_kg_m2']:.4g} kg m^2"]
    d = crank["dimensions"]
    if d is not None:
        typed = set(d["typed"])

        def mm(name: str) -> str:
            return f"{d[name + '_m'] * 1e3:.4g}" + ("" if name in typed else "*")

        parts.append(
            f"journal {mm('journal_diameter')} x {mm('journal_length')}, pin "
            f"{mm('pin_diameter')} x {mm('pin_length')}, web {mm('web_thickness')} x "
            f"{mm('web_width')} mm (* the engine's, as every study assumes)"
        )
    from ..studies.performance import combustion_text

    parts.append(combustion_text(crank["combustion"]))
    click.echo("; ".join(parts))


def _write_plot(plot: str, study: Any) -> None:
    from ..io.files import write_atomic
    from ..output import render
    from ..output.figures.torsional import torsional_figure

    fig = torsional_figure(study)
    fmt = Path(plot).suffix.lower().lstrip(".")
    write_atomic(plot, render.to_html(fig) if fmt == "html" else render.to_image(fig, fmt))  # type: ignore[arg-type]
    click.echo(f"wrote {plot}", err=True)
