"""``crankbalance balance``: counterweights and balance shafts of an engine."""

from __future__ import annotations

from typing import Any

import click

from ..output.format import json_text, number, plural, text
from ._common import echo_notes, echo_table, format_option, run_study, study_options


@click.command()
@click.argument("engine")
@format_option(("table", "json"))
@study_options("balance")
def balance(engine: str, fmt: str, **values: Any) -> None:
    """Counterweights and balance shafts of ENGINE (an engine file or a preset name).

    The [counterweights] and [balance_shafts] tables of the engine file set what is
    solved; without them the crank gets counterweights on every web at the crank radius.
    """
    data = run_study("balance", engine, values, engine_option=False).to_dict()
    if fmt == "json":
        click.echo(json_text(data))
        return
    print_table(data)
    echo_notes(engine)


def print_table(data: dict[str, Any]) -> None:
    e = data["engine"]
    click.echo(f"{e['name']} ({text(e['speed_rad_s'], 'speed')}, kinematics: {e['kinematics']})")
    cw = data["counterweight"]
    if cw is not None:
        angle = (
            "individual angles"
            if cw["angle_deg"] is None
            else f"alpha = {text(cw['angle_deg'], 'angle_deg', 6)}"
        )
        click.echo(
            f"\nCrank counterweights ({cw['method']}, {cw['scope']} crank, {angle}, "
            f"CG radius {text(cw['cg_radius_m'], 'length')}): "
            f"{plural(cw['count'], 'counterweight')}, "
            f"{text(cw['total_mass_kg'], 'mass_kg')} in all"
        )
        if cw["total_mass_kg"] > 0:
            echo_table(
                ["web", "throw", "y mm", "mass kg", "direction °"],
                [
                    [
                        str(w["web"]),
                        str(w["throw"]),
                        f"{w['position_m'] * 1e3:.2f}",
                        f"{w['mass_kg']:.4f}",
                        number(w["direction_deg"], 5),
                    ]
                    for w in cw["webs"]
                ],
            )
        elif cw["note"]:
            click.echo(f"none: {cw['note']}")
    extra = data["extra_counterweights"]
    if extra is not None:
        click.echo("\nExtra crank counterweight masses replacing the co-rotating primary shaft:")
        echo_table(
            ["web", "mass kg", "direction °"],
            [
                [str(w["web"]), f"{w['mass_kg']:.4f}", number(w["direction_deg"], 5)]
                for w in extra["webs"]
            ],
        )
    for key, title in (
        ("primary_shafts", "Primary balance shafts (crank speed)"),
        ("secondary_shafts", "Secondary balance shafts (twice crank speed)"),
    ):
        group = data[key]
        if group is None:
            continue
        click.echo(
            f"\n{title}, {group['arrangement']}, length {text(group['length_m'], 'length')}:"
        )
        rows = []
        for shaft in group["shafts"]:
            if not shaft["masses"]:
                rows.append([shaft["rotation"], "-", "0", "-"])
            for mass in shaft["masses"]:
                rows.append(
                    [
                        shaft["rotation"],
                        f"{mass['position_m'] * 1e3:.1f}",
                        f"{mass['mass_kg']:.4f}",
                        number(mass["phase_deg"], 5),
                    ]
                )
        echo_table(["shaft", "y mm", "mass kg", "phase °"], rows)
    click.echo("\nResiduals (amplitudes before -> after):")
    echo_table(
        ["component", "targeted", "force N", "after", "moment N·m", "after"],
        [
            [
                c["component"],
                "yes" if c["targeted"] else "no",
                number(c["force_before_N"]),
                number(c["force_after_N"]),
                number(c["moment_before_Nm"]),
                number(c["moment_after_Nm"]),
            ]
            for c in data["components"]
            if c["force_before_N"] > 1e-9 or c["moment_before_Nm"] > 1e-9 or c["targeted"]
        ],
    )
    for note in data["notes"]:
        click.echo(f"note: {note}")
    left = data["remaining"]
    click.echo("\nWhat is left, and what would remove it:" if left else "\nNothing is left.")
    for item in left:
        click.echo(f"  {item['text']}: {item['next_step']}")
    check = data.get("verification")
    if check is not None:
        verdict = "agree" if check["agrees"] else "DO NOT agree"
        click.echo(
            f"\nTime-domain verification ({check['samples']} crank angles, Fourier transform): "
            f"the residuals {verdict} to round-off; largest differences "
            f"{text(check['force_difference_N'], 'force')} "
            f"(round-off {text(check['force_round_off_N'], 'force')}) and "
            f"{text(check['moment_difference_Nm'], 'moment')} "
            f"(round-off {text(check['moment_round_off_Nm'], 'moment')})"
        )
