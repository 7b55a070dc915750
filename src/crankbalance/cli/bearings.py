"""``crankbalance bearings ENGINE``: main-bearing loads and crank bending over the engine
cycle, both crank models (docs/main_bearings.md)."""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import json_text, number
from ._common import echo_table, format_option, refuse_unused, run_study, study_options
from .plot import check_figure, write_figure


@click.command()
@click.argument("engine")
@format_option(("table", "json"))
@study_options("bearings")
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
