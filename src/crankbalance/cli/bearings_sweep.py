"""``crankbalance bearings-sweep ENGINE``: main-bearing loads, friction and crank bending
against the counterweight pattern and the balance factor (docs/main_bearings.md).

The loads' settings are those of ``crankbalance bearings`` (the same options, taken from
that command, one vocabulary); ``--balance-factors`` is written as in ``sensitivity``
(``0.4,0.5,0.6`` or ``start:stop:step``) and ``--pattern`` (repeated) replaces
``--webs``."""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import json_text, number
from ..studies.balance_loads import COLUMNS, case_rows
from ..studies.loads import assumed_text
from ..studies.performance import WIEBE_OPTIONS
from ._common import (
    echo_table,
    format_option,
    given_options,
    option_name,
    refuse_unused,
    require_extra,
)
from .bearings import PHYSICS_FIELDS, bearings
from .performance import _number_list

#: options of ``bearings`` that this command does not take (swept, or a single run's)
NOT_SHARED = ("balance_factor", "webs", "curves", "fmt", "plot", "engine")


def _name(field: str) -> str:
    """The option of a settings field (``patterns`` is typed as ``--pattern``)."""
    return "--pattern" if field == "patterns" else option_name(field)


@click.command("bearings-sweep")
@click.argument("engine")
@format_option(("table", "json", "csv"))
@click.option(
    "--pattern",
    "patterns",
    multiple=True,
    help="Counterweight pattern (repeat): all, none, file (the engine file's) or 0/1 per "
    "web, two per throw, '1,0,0,1,1,0,0,1' (default: all).",
)
@click.option(
    "--balance-factors",
    default="0:1:0.25",
    show_default=True,
    help="Balance factors: '0.4,0.5,0.6' or start:stop:step.",
)
@click.option(
    "--crank-model",
    type=click.Choice(["indeterminate", "determinate"]),
    default="indeterminate",
    show_default=True,
    help="Crank model of the table, the CSV and the figure (the JSON has both).",
)
@click.option(
    "--plot",
    default=None,
    help="Write the metrics against the balance factor (one line per pattern) and the peak "
    "load of every bearing per case: .png, .svg, .html.",
)
def bearings_sweep(
    engine: str,
    fmt: str,
    patterns: tuple[str, ...],
    balance_factors: str,
    crank_model: str,
    plot: str | None,
    bearing: tuple[str, ...],
    **options: Any,
) -> None:
    """Main-bearing loads, friction and crank bending of ENGINE for every counterweight
    pattern at every balance factor.

    Each case is a full balance solve and then the loads of ``crankbalance bearings`` with
    the same settings (both crank models); ``none`` is the crank without counterweights,
    one case. At most 64 cases.
    """
    from ..errors import InputError
    from ..schema.settings import BearingOptions, BearingSweepOptions, parse_options
    from ..studies.balance_loads import bearing_sweep

    given = given_options()
    sweep = parse_options(
        BearingSweepOptions,
        {
            "patterns": list(patterns) or None,
            "balance_factors": _number_list(balance_factors, "--balance-factors"),
            "crank_model": crank_model,
        },
        _name,
    )
    o = parse_options(
        BearingOptions,
        {
            **options,
            "bearing": list(bearing) or None,
            "pressure_csv": list(options["pressure_csv"]),
        },
        option_name,
    )
    refuse_unused(
        {name: o.gas and not o.pressure_csv for name in WIEBE_OPTIONS},
        "only acts on the Wiebe combustion model (not with --pressure-csv or --no-gas)",
        given,
    )
    refuse_unused({"pressure_csv": o.gas, "bore": o.gas}, "only acts with gas forces", given)
    if plot is not None:
        from .plot import check_output

        check_output(plot, (".png", ".svg", ".html"), "--plot")
        require_extra("web", "plotly", *(() if plot.lower().endswith(".html") else ("kaleido",)))
    typed: dict[str, Any] = {**options, "bearing": list(bearing) or None}
    try:
        study = bearing_sweep(engine, sweep, o)
    except InputError as error:
        # an error of the physics about a setting names its option, with what was typed
        name = PHYSICS_FIELDS.get(error.field, error.field)
        if name == "patterns":
            raise InputError("--pattern", error.value, error.allowed) from None
        if name not in BearingOptions.FIELDS or name == "webs":
            raise
        shown = typed.get(name) if name in given or name == "bearing" else None
        raise InputError(
            option_name(name), error.value if shown is None else shown, error.allowed
        ) from None
    data = study.to_dict()  # checked finite by to_jsonable
    if plot is not None:
        _write_plot(plot, study)
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


def _write_plot(plot: str, study: Any) -> None:
    from pathlib import Path

    from ..io.files import write_atomic
    from ..output import render
    from ..output.figures.loads import bearing_sweep_figure

    fig = bearing_sweep_figure(study)
    fmt = Path(plot).suffix.lower().lstrip(".")
    write_atomic(plot, render.to_html(fig) if fmt == "html" else render.to_image(fig, fmt))  # type: ignore[arg-type]
    click.echo(f"wrote {plot}", err=True)


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
        "mean N: the largest mean load; friction: Coulomb, all main bearings; free: the "
        "first-order force and moment and the rotating moment left after balancing"
    )


# the loads' options are those of ``bearings`` (one vocabulary, one set of help texts)
bearings_sweep.params.extend(p for p in bearings.params if p.name not in NOT_SHARED)
