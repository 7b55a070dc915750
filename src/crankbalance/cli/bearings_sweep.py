"""``crankbalance bearings-sweep ENGINE``: main-bearing loads, friction and crank bending
against the counterweight pattern and the balance factor (docs/main_bearings.md).

The loads' settings are those of ``crankbalance bearings`` (the same settings schema, one
vocabulary); ``--balance-factors`` is written as in ``sensitivity``
(``0.4,0.5,0.6`` or ``start:stop:step``) and ``--pattern`` (repeated) replaces
``--webs``."""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import json_text, number
from ..studies.balance_loads import COLUMNS, case_rows
from ..studies.loads import assumed_text
from ._common import echo_table, format_option, run_study, study_options
from .plot import check_figure, write_figure


@click.command("bearings-sweep")
@click.argument("engine")
@format_option(("table", "json", "csv"))
@study_options("bearings-sweep")
@click.option(
    "--plot",
    default=None,
    help="Write the metrics against the balance factor (one line per pattern) and the peak "
    "load of every bearing per case: .png, .svg, .html.",
)
def bearings_sweep(engine: str, fmt: str, plot: str | None, **values: Any) -> None:
    """Main-bearing loads, friction and crank bending of ENGINE for every counterweight
    pattern at every balance factor.

    Each case is a full balance solve and then the loads of ``crankbalance bearings`` with
    the same settings (both crank models); ``none`` is the crank without counterweights,
    one case. At most 64 cases.
    """
    if plot is not None:
        check_figure(plot)
    study = run_study("bearings-sweep", engine, values, engine_option=False)
    data = study.to_dict()  # checked finite by to_jsonable
    if plot is not None:
        from ..output import figures

        write_figure(plot, figures.bearing_sweep_figure(study))
    if fmt == "json":
        click.echo(json_text(data))
        return
    rows = case_rows(data)
    if fmt == "csv":
        import csv
        import sys

        writer = csv.writer(sys.stdout, lineterminator="\n")
        writer.writerow([key for key, _ in COLUMNS])
        writer.writerows(["" if v is None else v for v in row] for row in rows)
        return
    print_table(data, rows)


def _cell(value: Any) -> str:
    """A table cell: text as it is, a missing balance factor (``none``) as a dash."""
    if value is None:
        return "–"
    if isinstance(value, (str, int)):
        return str(value)
    return number(value, 5)


def print_table(data: dict[str, Any], rows: list[list[Any]]) -> None:
    """One line per case: counterweights, the worst bearing, bending, friction, free forces."""
    e, s = data["engine"], data["settings"]
    click.echo(
        f"{e['name']}: {number(s['speed_rad_s'] * 30 / math.pi, 5)} rpm, "
        f"{'gas and inertia' if s['gas'] else 'inertia only'}, {data['crank_model']} crank, "
        + ("rigid bearings" if s["bearing_stiffness_N_per_m"] is None else "elastic bearings")
    )
    click.echo(assumed_text(s))
    echo_table(
        [label for _, label in COLUMNS],
        [[_cell(v) for v in row] for row in rows],
    )
    click.echo(
        "max N: the largest load of any bearing over the cycle (of the worst bearing); "
        "mean N: the largest mean load; friction: Coulomb, all main bearings; left after "
        "balancing: Frot, Mrot the rotating masses' free force and couple, F1+/F1-, M1+/M1- "
        "the first order's forward/backward-rotating (every order in the JSON)"
    )
    for line in data["summary"]["text"]:  # the study's summary, its warning included
        click.echo(line)
