"""``crankbalance bearings ENGINE``: main-bearing loads and crank bending over the engine
cycle, both crank models (docs/main_bearings.md)."""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import json_text, number
from ..schema.settings import BearingOptions
from ._common import default_help, echo_table, format_option, refuse_unused, run_study
from .plot import check_figure, write_figure


def _shown(name: str, words: str) -> str:
    return default_help(BearingOptions, name, words)


@click.command()
@click.argument("engine")
@format_option(("table", "json"))
@click.option("--speed", default=None, help="Mean crank speed, e.g. '6000 rpm' (default: engine).")
@click.option(
    "--samples", default=None, help=_shown("samples", "Crank-angle samples per revolution.")
)
@click.option(
    "--gas/--no-gas",
    default=None,
    help=_shown(
        "gas", "Gas forces from the Wiebe model (or --pressure-csv); --no-gas: inertia only."
    ),
)
@click.option("--bore", default=None, help="Bore (default: square engine, bore = stroke).")
@click.option(
    "--compression-ratio",
    default=None,
    help=_shown("compression_ratio", "Compression ratio, as every study."),
)
@click.option(
    "--ignition",
    default=None,
    help=_shown("ignition", "Start of combustion from firing TDC, as every study."),
)
@click.option("--burn-duration", default=None, help=_shown("burn_duration", "Burn duration."))
@click.option(
    "--intake-pressure",
    default=None,
    help=_shown("intake_pressure", "Pressure at the start of compression (load)."),
)
@click.option(
    "--pressure-csv",
    type=click.Path(exists=True, dir_okay=False),
    multiple=True,
    help="Cylinder pressure table instead of the Wiebe model (as 'cycle': crank angle [deg "
    "from firing TDC], absolute pressure [bar]); one for every cylinder, or repeated once "
    "per cylinder in cylinder order.",
)
@click.option(
    "--crank-inertia",
    default=None,
    help="Inertia of the purely rotating parts (crank, flywheel): the speed fluctuation "
    "(default: the engine's, front end + throws + flywheel as 'torsional' and 'cycle "
    "--engine').",
)
@click.option(
    "--balance-factor", default=None, help="Balance factor of the counterweights (default: file)."
)
@click.option(
    "--webs",
    default=None,
    help="Counterweight pattern, 0/1 per web, two per throw: '1,0,0,1,1,0,0,1' "
    "(default: the engine file's, else every web).",
)
@click.option("--journal-diameter", default=None, help="Main-journal diameter (default 1.3 r).")
@click.option("--pin-diameter", default=None, help="Crankpin diameter (default 1.1 r).")
@click.option(
    "--web-thickness", default=None, help="Axial web thickness (default 0.75 web offset)."
)
@click.option("--web-width", default=None, help="Web width across the arm (default 2.2 r).")
@click.option("--modulus", default=None, help=_shown("modulus", "Young's modulus."))
@click.option("--poisson", default=None, help=_shown("poisson", "Poisson's ratio."))
@click.option(
    "--bearing",
    multiple=True,
    help="Main-bearing position along the crank from its mid-point (repeat; default: one "
    "between neighbouring throws and one at each end).",
)
@click.option(
    "--bearing-stiffness",
    default=None,
    help="Radial stiffness of each main bearing, e.g. '5e8 N/m' (default: rigid).",
)
@click.option(
    "--friction-coefficient",
    default=None,
    help=_shown("friction_coefficient", "Coulomb friction coefficient."),
)
@click.option("--viscosity", default=None, help="Oil viscosity, for the Petroff friction.")
@click.option("--bearing-length", default=None, help="Bearing length, for the Petroff friction.")
@click.option(
    "--clearance",
    default=None,
    help="Radial clearance of the main bearings: in the contact model with "
    "--bearing-stiffness, in the Petroff friction with --viscosity and --bearing-length.",
)
@click.option(
    "--curves",
    is_flag=True,
    default=None,
    help="JSON: add the load and moment curves over the cycle.",
)
@click.option(
    "--plot",
    default=None,
    help="Write the polar load diagrams and the journal bending moments: .png, .svg, .html.",
)
def bearings(engine: str, fmt: str, plot: str | None, **values: Any) -> None:
    """Main-bearing loads and crank bending of ENGINE over one working cycle.

    Every cylinder fires in turn (gas and reciprocating inertia through the rods); the
    throws' rotating masses and the counterweights load the crank too. Two crank models:
    determinate (each throw on its two neighbouring bearings) and indeterminate (a
    continuous beam on all bearings; its stiffness is an equivalent-stiffness
    approximation, docs/main_bearings.md).
    """
    refuse_unused({"curves": fmt == "json"}, "only acts with --format json")
    if plot is not None:
        check_figure(plot)
    study = run_study("bearings", engine, values, engine_option=False)
    data = study.to_dict()  # checked finite by to_jsonable
    if plot is not None:
        from ..output import figures

        write_figure(plot, figures.bearing_loads_figure(study))
    if fmt == "json":
        click.echo(json_text(data))
        return
    print_table(data)


def print_table(data: dict[str, Any]) -> None:
    """The bearing table of both crank models and the crankpin bending."""
    e, s = data["engine"], data["settings"]
    cw = data["counterweights"]
    click.echo(
        f"{e['name']}: {number(s['speed_rad_s'] * 30 / math.pi, 5)} rpm, "
        f"{'gas and inertia' if s['gas'] else 'inertia only'}, "
        f"{'no counterweights' if cw is None else str(cw['count']) + ' counterweights'}, "
        + (
            "rigid bearings"
            if s["bearing_stiffness_N_per_m"] is None
            else "elastic bearings" + (" with clearance" if s["clearance_in_contact_model"] else "")
        )
    )
    from ..studies.loads import assumed_text

    click.echo(assumed_text(s))
    det, ind = data["models"]["determinate"], data["models"]["indeterminate"]
    header = [
        "bearing",
        "y mm",
        "max N det",
        "max N ind",
        "mean N det",
        "mean N ind",
        "|M| N·m ind",
        "friction W ind",
    ]
    rows = [
        [
            str(a["bearing"]),
            f"{a['position_m'] * 1e3:.1f}",
            number(a["max_load_N"], 5),
            number(b["max_load_N"], 5),
            number(a["mean_load_N"], 5),
            number(b["mean_load_N"], 5),
            number(b["max_journal_moment_Nm"], 5),
            number(b["coulomb_friction_power_W"], 4),
        ]
        for a, b in zip(det["bearings"], ind["bearings"], strict=True)
    ]
    echo_table(header, rows)
    click.echo("")
    echo_table(
        ["throw", "y mm", "pin |M| N·m det", "pin |M| N·m ind"],
        [
            [
                str(a["throw"]),
                f"{a['position_m'] * 1e3:.1f}",
                number(a["max_pin_moment_Nm"], 5),
                number(b["max_pin_moment_Nm"], 5),
            ]
            for a, b in zip(det["throws"], ind["throws"], strict=True)
        ],
    )
    click.echo(
        f"\nCoulomb friction of all main bearings: {number(det['coulomb_friction_power_W'], 4)} W "
        f"(determinate), {number(ind['coulomb_friction_power_W'], 4)} W (indeterminate)"
    )
    if ind["petroff_friction_power_W"] is not None:
        petroff = number(ind["petroff_friction_power_W"], 4)
        click.echo(f"Petroff friction of all main bearings: {petroff} W")
    click.echo(f"note: indeterminate model: {data['stiffness']['note']}")
