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
from typing import Any

import click

from ..output.format import text
from ._common import echo_table, format_option, run_study, study_options
from .plot import check_figure, write_figure

_RPM = 30.0 / math.pi  # rad/s -> rpm
FORMATS = ("table", "json", "csv")
#: most resonances the table shows (JSON has all)
TABLE_RESONANCES = 12


@click.command()
@click.option("--engine", default=None, help="Engine file or preset (required).")
@study_options("torsional")
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    help="Campbell diagram and forced response (.png, .svg or .html).",
)
@format_option(FORMATS)
def torsional(fmt: str, plot: str | None, engine: str | None, **values: Any) -> None:
    """Torsional vibration of the crank train of --engine.

    One inertia per throw (the throw with its big ends, default m_rot r², plus its
    pistons' mean share), the stiffness between throws (given, or Carter's formula from
    the journal, pin and web dimensions: an approximation), front end, flywheel, an
    optional tuned damper (--damper-inertia and --damper-frequency) and driven load.
    Prints the natural frequencies and mode shapes (free-free and with the load), every
    resonance of an engine order with a mode in the speed range with the response there,
    and the damper check. CSV: the sweep over the speed range.
    """
    if plot is not None:
        check_figure(plot)
    result = run_study("torsional", engine, values)
    data = result.to_dict()
    if plot is not None:
        from ..output import figures

        write_figure(plot, figures.torsional_figure(result.study))
    if fmt == "json":
        from ..output.format import json_text

        click.echo(json_text(data))
    elif fmt == "csv":
        sweep = data["sweep"]
        keys = list(sweep)
        click.echo(",".join(keys))
        for row in zip(*(sweep[k] for k in keys), strict=True):
            click.echo(",".join(f"{v:.9g}" for v in row))
    else:
        _echo(data)


def _echo(payload: dict[str, Any]) -> None:
    e = payload["engine"]
    click.echo(
        f"{e['name']}: {e['cylinders']} cylinders, {e['strokes']}-stroke, firing order "
        + "-".join(map(str, e["firing_order"]))
    )
    _echo_assumed(payload["crank"])
    echo_table(
        ["mass", "inertia [kg·m²]", "stiffness to next [N·m/rad]"],
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
    # the power of a damper: a column only with a damper (without one it is all zero)
    damped = payload["damper"] is not None
    header = [
        "mode",
        "order",
        "speed [rpm]",
        "rel. excitation",
        "front [°]",
        "twist [°]",
        "torque [N·m]",
    ]
    rows = [
        [
            str(r["mode"]),
            f"{r['order']:g}",
            f"{r['speed_rad_s'] * _RPM:.0f}",
            f"{r['relative_excitation']:.3f}",
            f"{math.degrees(r['front_amplitude_rad']):.4f}",
            f"{math.degrees(r['crank_twist_rad']):.4f}",
            f"{r['max_section_torque_Nm']:.1f}",
        ]
        + ([f"{r['damper_power_W']:.2f}"] if damped else [])
        for r in shown
    ]
    echo_table(header + (["damper [W]"] if damped else []), rows)
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
    parts = [f"front + throws + flywheel {text(crank['rotating_inertia_kg_m2'], 'inertia')}"]
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
