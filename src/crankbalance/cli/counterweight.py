"""``crankbalance counterweight``: design, optimise, export and check counterweights.

Subcommands: ``optimize`` (constraints and parameter ranges -> feasible designs, Pareto
front, least-mass and least-radius designs), ``show`` (one design's mass properties),
``export`` (SVG, DXF, STL, STEP) and ``check`` (mass properties of an STL/STEP part).
JSON output is one object with ``"schema": "crankbalance.counterweight/2"`` (docs/json.md).
"""

from __future__ import annotations

from typing import Any

import click

from ..output.format import json_text, number
from ..output.format import text as unit_text
from ..physics.counterweight import SYMBOLS as SYMBOL
from ..studies.counterweight import PARAMETERS
from ._common import (
    SuggestingGroup,
    echo_table,
    format_option,
    option_name,
    parse_settings,
    refuse_unused,
    require_extra,
    run_study,
    study_options,
    typed,
)
from .plot import check_figure, write_figure


def _engine_option(f: Any) -> Any:
    return click.option(
        "--engine",
        default=None,
        help="Engine file or preset: the requirement is its balancing's largest "
        "crank counterweight m_c*r_c.",
    )(f)


def _table_rows(rows: list[dict[str, float]], labels: list[str]) -> None:
    header = ["design", "mass g", "R true mm", "R_min mm", "balance %", "r_c mm", "J kg·m²"]
    header += [f"{SYMBOL[n]} {PARAMETERS[n][2]}" for n in PARAMETERS]
    table = []
    for label, r in zip(labels, rows, strict=True):
        cells = [
            label,
            f"{r['mass'] * 1e3:.2f}",
            f"{r['outer_radius'] * 1e3:.2f}",
            f"{r['radius_bound'] * 1e3:.2f}",
            f"{r['balance']:.2f}",
            f"{r['cg_radius'] * 1e3:.2f}",
            number(r["inertia"]),
        ]
        cells += [f"{r[n] * PARAMETERS[n][1]:.2f}" for n in PARAMETERS]
        table.append(cells)
    echo_table(header, table)


@click.group(cls=SuggestingGroup)
def counterweight() -> None:
    """Counterweight shape: optimise, show a design, export it, check a CAD part.

    The profile is the one of the 2021 crankshaft-balancing paper (Sec. 4): web circle
    r_cw, rectangle h_R, trapezoid of angle delta, circular segment R_cw, alpha; thickness
    t_cw. Units go with every quantity ('20 mm', '30 deg', '7880 g*mm').
    """


@counterweight.command()
@_engine_option
@study_options("counterweight-optimize")
@click.option("--quiet", is_flag=True, help="No progress on stderr.")
@format_option(("table", "json"))
def optimize(engine: str | None, quiet: bool, fmt: str, **values: Any) -> None:
    """Feasible counterweights, Pareto front, least-mass and least-radius designs."""

    def progress(state: Any) -> None:
        if not quiet:
            least = "-" if state.least_mass is None else f"{state.least_mass * 1e3:.2f} g"
            click.echo(
                f"\riteration {state.iteration}/{state.n_iterations}  designs "
                f"{state.nfev}  feasible {state.n_feasible}  front {state.n_pareto}  "
                f"least mass {least}",
                err=True,
                nl=False,
            )

    result = run_study("counterweight-optimize", engine, values, progress=progress)
    res = result.optimum
    if not quiet:
        click.echo(
            f"\n{len(res.designs)} feasible designs, {len(res.pareto)} on the front, "
            f"{res.nfev} evaluated in {res.elapsed:.2f} s",
            err=True,
        )
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    click.echo(
        f"required first moment {unit_text(result.required, 'first_moment', 5)}, "
        f"density {number(res.density)} kg/m³,"
        f" free: {', '.join(SYMBOL[n] for n in res.free) or 'none'}"
    )
    labels = ["least mass", "least radius"] + [f"front {k + 1}" for k in range(len(result.listed))]
    _table_rows(result.rows(), labels)


@counterweight.command()
@_engine_option
@study_options("counterweight-show")
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    help="The design's profile to scale, with the crankpin, journal and radial limit of "
    "--engine (.png, .svg or .html).",
)
@format_option(("table", "json"))
def show(engine: str | None, fmt: str, plot: str | None, **values: Any) -> None:
    """Mass properties of one counterweight design."""
    if plot is not None:
        check_figure(plot)
    result = run_study("counterweight-show", engine, values)
    if plot is not None:
        from ..output.figures.study import plot as figures_of

        write_figure(plot, figures_of(result)[0])
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    props, design = result.properties, result.design
    echo_table(
        ["quantity", "value"],
        [
            ["mass", unit_text(props.mass, "mass", 6)],
            ["volume", f"{number(props.volume * 1e9, 6)} mm³"],
            ["centre of gravity r_c", unit_text(props.cg_radius, "length", 6)],
            ["first moment m r_c", unit_text(props.first_moment, "first_moment", 6)],
            ["balance", "-" if props.balance is None else unit_text(props.balance, "percent", 5)],
            ["inertia about crank axis", unit_text(props.inertia, "inertia", 5)],
            ["true outer radius", unit_text(props.outer_radius, "length", 6)],
            ["paper R_min (bound)", unit_text(props.radius_bound, "length", 6)],
            ["overhang l_c", unit_text(props.overhang, "length", 6)],
            [
                "gamma, lambda",
                f"{unit_text(props.gamma, 'angle')}, {unit_text(props.lam, 'angle')}",
            ],
            ["thickness t_cw", unit_text(design.thickness, "length", 6)],
        ],
    )


@counterweight.command()
@_engine_option
@study_options("counterweight-show")
@click.option("--output", "-o", required=True, help="File: .svg, .dxf, .stl or .step (mm).")
def export(engine: str | None, output: str, **values: Any) -> None:
    """Write a design as SVG/DXF profile, STL solid or STEP (needs crankbalance[cad]).

    The design is the one of ``counterweight show`` with the same options."""
    from ..io.cad import export_counterweight

    if output.lower().endswith((".step", ".stp")):
        require_extra("cad")
    if values["thickness"] is not None:
        refuse_unused(
            {name: False for name in ("first_moment", "cw_mass", "cg_radius", "engine")},
            "only sizes the thickness of an export: give it or --thickness, not both",
        )
    result = run_study("counterweight-show", engine, values)
    path = export_counterweight(result.design, output)
    click.echo(f"wrote {path}", err=True)


@counterweight.command()
@click.argument("part")
@_engine_option
@study_options("counterweight-show", only=("first_moment", "cw_mass", "cg_radius", "density"))
@click.option("--unit", default=None, help="Length unit of the file. [default: mm]")
@format_option(("table", "json"))
def check(part: str, engine: str | None, unit: str | None, fmt: str, **values: Any) -> None:
    """Mass properties of an STL/STEP PART about the crank axis (the file's z axis), against
    the requirement of ``counterweight show`` with the same options."""
    from ..schema.settings import CounterweightDesignOptions
    from ..studies.counterweight import part as part_study
    from ..studies.registry import named, study

    require_extra("geometry", "trimesh")
    if str(part).lower().endswith((".step", ".stp")):
        require_extra("cad")
    given = typed(values)
    if unit is not None:
        given["unit"] = f"1 {unit}"
    settings = parse_settings(CounterweightDesignOptions, given)
    naming = {"engine": "--engine"}
    with named(
        study("counterweight-show"), given, settings, lambda f: naming.get(f, option_name(f))
    ):
        result = part_study(engine, settings, part)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    m = result.properties
    echo_table(
        ["quantity", "value"],
        [
            ["volume", f"{number(m.volume * 1e9, 6)} mm³"],
            ["mass", unit_text(m.mass, "mass", 6)],
            [
                "centre of gravity",
                " ".join(number(v * 1e3, 6) for v in m.centre_of_gravity) + " mm",
            ],
            ["distance from crank axis", unit_text(m.cg_radius, "length", 6)],
            ["first moment", unit_text(m.first_moment, "first_moment", 6)],
            ["balance", "-" if m.balance is None else unit_text(m.balance, "percent", 5)],
            ["inertia about crank axis", unit_text(m.inertia, "inertia", 5)],
            ["watertight", "yes" if m.watertight else "NO (numbers unreliable)"],
        ],
    )
