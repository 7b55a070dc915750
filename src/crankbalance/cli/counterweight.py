"""``crankbalance counterweight``: design, optimise, export and check counterweights.

Subcommands: ``optimize`` (constraints and parameter ranges -> feasible designs, Pareto
front, least-mass and least-radius designs), ``show`` (one design's mass properties),
``export`` (SVG, DXF, STL, STEP) and ``check`` (mass properties of an STL/STEP part).
JSON output is one object with ``"schema": "crankbalance.counterweight/2"`` (docs/json.md).
"""

from __future__ import annotations

import math
import re
from typing import Any

import click

from ..errors import InputError
from ..output.format import json_text, keyed, number
from ..output.format import text as unit_text
from ..physics.counterweight import SYMBOLS as _SYMBOL
from ..results import require_finite
from ..schema.settings import (
    CounterweightDesignOptions,
    CounterweightOptions,
    allowed,
    parse_options,
)
from ._common import (
    echo_table,
    format_option,
    option_name,
    parse_settings,
    refuse_unused,
    require_extra,
)


def _limits(field: str) -> str:
    """What a counterweight setting accepts (the one options schema's limits)."""
    return allowed(CounterweightOptions, field)


SCHEMA = "crankbalance.counterweight/2"

# parameter -> (option, quantity kind, display unit factor, display unit)
_PARAMS: dict[str, tuple[str, str, float, str]] = {
    "web_radius": ("--web-radius", "length", 1e3, "mm"),
    "rectangle_height": ("--rectangle-height", "length", 1e3, "mm"),
    "trapezoid_angle": ("--trapezoid-angle", "angle", 180 / math.pi, "°"),
    "segment_radius": ("--segment-radius", "length", 1e3, "mm"),
    "segment_angle": ("--segment-angle", "angle", 180 / math.pi, "°"),
    "thickness": ("--thickness", "length", 1e3, "mm"),
}
_SI_UNIT = {"length": "m", "angle": "deg"}
#: factor from the SI value of a parameter to its JSON value (angles in degrees)
_JSON_FACTOR = {"length": 1.0, "angle": 180.0 / math.pi}
#: JSON keys of a part's mass properties (``counterweight check``)
_PART_KEYS: dict[str, str | tuple[str, float]] = {
    "volume": "volume_m3",
    "mass": "mass_kg",
    "centre_of_gravity": "centre_of_gravity_m",
    "cg_radius": "cg_radius_m",
    "first_moment": "first_moment_kg_m",
    "inertia": "inertia_kg_m2",
    "balance": "balance_percent",
}


def _value(field: str, text: str) -> float:
    """One value of a counterweight option (``field`` as in
    :class:`~crankbalance.schema.settings.CounterweightDesignOptions`), in SI and in its physical
    range; 'LOW..HIGH' is refused here. Ranges go through :func:`_value_or_range`."""
    value = getattr(parse_settings(CounterweightDesignOptions, {field: text}), field)
    assert isinstance(value, float)
    return value


def _param_options(help_suffix: str):
    def decorate(f):
        for name, (opt, kind, _k, unit) in reversed(_PARAMS.items()):
            f = click.option(
                opt,
                name,
                default=None,
                help=f"{_SYMBOL[name]} ({kind}, e.g. '20 {unit}'){help_suffix}",
            )(f)
        return f

    return decorate


def _value_or_range(text: str, field: str) -> float | tuple[float, float]:
    """'20 mm' -> 0.02; '10..20 mm' or '10 mm..20 mm' -> (0.01, 0.02)."""
    if ".." not in text:
        return _value(field, text)
    low, high = (part.strip() for part in text.split("..", 1))
    if ".." in high:
        raise InputError(
            option_name(field), text, "a value or one range 'LOW..HIGH', e.g. '10..20 mm'"
        )
    if re.fullmatch(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", low):
        # a bare lower number takes the unit of the upper value: '10..20 mm'
        unit = high.lstrip("0123456789.eE+- ")
        low = f"{low} {unit}" if unit else low
    return (_value(field, low), _value(field, high))


def _first_moment(
    first_moment: str | None,
    cw_mass: str | None,
    cg_radius: str | None,
    engine: str | None = None,
) -> float:
    given = [
        first_moment is not None,
        cw_mass is not None or cg_radius is not None,
        engine is not None,
    ]
    if sum(given) > 1:
        raise InputError(
            "--first-moment",
            first_moment,
            "give only one of --first-moment, --cw-mass with --cg-radius, or --engine",
        )
    if engine is not None:
        from ..studies.engine import balance_engine
        from ..studies.requirements import counterweight_requirement

        study = balance_engine(engine)
        try:
            return counterweight_requirement(study)
        except InputError as error:
            raise InputError("--engine", engine, error.allowed) from None
    if first_moment is not None:
        return _value("first_moment", first_moment)
    if cw_mass is None or cg_radius is None:
        raise InputError(
            "--first-moment",
            None,
            "required: e.g. --first-moment '7880 g*mm', or --cw-mass '263 g' with "
            "--cg-radius '30 mm', or --engine FILE (the balancing solver's counterweight)",
        )
    return _value("cw_mass", cw_mass) * _value("cg_radius", cg_radius)


def _requirement_options(f):
    f = click.option(
        "--engine",
        default=None,
        help="engine file or preset: the requirement is its balancing's largest "
        "crank counterweight m_c*r_c.",
    )(f)
    f = click.option("--cg-radius", default=None, help="with --cw-mass: r_c, e.g. '30 mm'.")(f)
    f = click.option(
        "--cw-mass",
        default=None,
        help="counterweight mass m_c from the balancing, e.g. '263 g' (with --cg-radius).",
    )(f)
    f = click.option(
        "--first-moment", default=None, help="required first moment m_c*r_c, e.g. '7880 g*mm'."
    )(f)
    return f


def _design_row(values: dict[str, float]) -> dict[str, float]:
    keys = {
        "mass": "mass_kg",
        "outer_radius": "outer_radius_m",
        "radius_bound": "r_min_bound_m",
        "inertia": "inertia_kg_m2",
        "cg_radius": "cg_radius_m",
        "first_moment": "first_moment_kg_m",
        "balance": "balance_percent",
    }
    out: dict[str, float] = {}
    for name, value in values.items():
        if name in _PARAMS:
            kind = _PARAMS[name][1]
            out[f"{name}_{_SI_UNIT[kind]}"] = float(value) * _JSON_FACTOR[kind]
        elif name in keys:
            out[keys[name]] = float(value)
    return out


def _table_rows(rows: list[dict[str, float]], labels: list[str]) -> None:
    header = ["design", "mass g", "R true mm", "R_min mm", "balance %", "r_c mm", "J kg·m²"]
    header += [f"{_SYMBOL[n]} {_PARAMS[n][3]}" for n in _PARAMS]
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
        cells += [f"{r[n] * _PARAMS[n][2]:.2f}" for n in _PARAMS]
        table.append(cells)
    echo_table(header, table)


@click.group()
def counterweight() -> None:
    """Counterweight shape: optimise, show a design, export it, check a CAD part.

    The profile is the one of the 2021 crankshaft-balancing paper (Sec. 4): web circle
    r_cw, rectangle h_R, trapezoid of angle delta, circular segment R_cw, alpha; thickness
    t_cw. Units go with every quantity ('20 mm', '30 deg', '7880 g*mm').
    """


@counterweight.command()
@_requirement_options
@_param_options(": a value fixes it, 'LOW..HIGH' leaves it free in that range.")
@click.option("--density", default="8000 kg/m^3", show_default=True, help="Material density.")
@click.option("--max-mass", default=None, help="Largest counterweight mass, e.g. '400 g'.")
@click.option("--max-radius", default=None, help="Largest radial space, e.g. '80 mm'.")
@click.option(
    "--min-balance",
    default="100",
    show_default=True,
    help="Smallest balance, achieved / required first moment [%].",
)
@click.option(
    "--radius-measure",
    type=click.Choice(["true", "paper"]),
    default="true",
    show_default=True,
    help="Radial space: true outer radius, or the paper's R_min bound.",
)
@click.option("--inertia", "with_inertia", is_flag=True, help="Inertia as a third objective.")
@click.option("--iterations", default="40", show_default=True, help=_limits("iterations"))
@click.option("--population", default="4096", show_default=True, help=_limits("population"))
@click.option("--seed", default=None, help="Random seed (repeatable runs); " + _limits("seed"))
@click.option(
    "--pareto",
    "n_pareto",
    type=click.IntRange(0, 10**6),
    default=10,
    show_default=True,
    help="How many Pareto designs to list (evenly spread along the front).",
)
@click.option("--quiet", is_flag=True, help="No progress on stderr.")
@format_option(("table", "json"))
def optimize(
    first_moment,
    cw_mass,
    cg_radius,
    engine,
    density,
    max_mass,
    max_radius,
    min_balance,
    radius_measure,
    with_inertia,
    iterations,
    population,
    seed,
    n_pareto,
    quiet,
    fmt,
    **params: Any,
) -> None:
    """Feasible counterweights, Pareto front, least-mass and least-radius designs."""
    from ..physics.counterweight_optimize import DEFAULT_BOUNDS, optimize_counterweight

    required = _first_moment(first_moment, cw_mass, cg_radius, engine)
    bounds: dict[str, Any] = {}
    for name, text in params.items():
        if text is not None:
            bounds[name] = _value_or_range(text, name)

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

    settings = parse_options(
        CounterweightOptions,
        {
            "density": density,
            "max_mass": max_mass,
            "max_radius": max_radius,
            "min_balance": min_balance,
            "iterations": iterations,
            "population": population,
            "seed": seed,
        },
        option_name,
    )
    if with_inertia:
        try:
            settings.check_budget(3)
        except InputError as error:
            raise InputError(option_name(error.field), iterations, error.allowed) from None
    res = optimize_counterweight(
        required,
        bounds,
        density=settings.density,
        max_mass=settings.max_mass,
        max_radius=settings.max_radius,
        min_balance=settings.min_balance,
        radius_measure=radius_measure,
        objectives=("mass", "radius", "inertia") if with_inertia else ("mass", "radius"),
        population=settings.population,
        iterations=settings.iterations,
        rng=settings.seed,
        callback=progress,
    )
    if not quiet:
        click.echo(
            f"\n{len(res.designs)} feasible designs, {len(res.pareto)} on the front, "
            f"{res.nfev} evaluated in {res.elapsed:.2f} s",
            err=True,
        )
    pick = [int(i) for i in res.pareto]
    if n_pareto < len(pick):
        pick = [pick[k] for k in sorted({round(x) for x in _spread(len(pick), n_pareto)})]
        pick = pick if n_pareto else []
    if fmt == "json":
        full = {n: DEFAULT_BOUNDS[n] for n in _PARAMS} | bounds
        out = {
            "schema": SCHEMA,
            "mode": "optimize",
            "required_first_moment_kg_m": required,
            "density_kg_m3": res.density,
            "constraints": {
                "max_mass_kg": settings.max_mass,
                "max_radius_m": settings.max_radius,
                "min_balance_percent": settings.min_balance,
                "radius_measure": radius_measure,
            },
            "bounds": {
                f"{n}_{_SI_UNIT[_PARAMS[n][1]]}": keyed(
                    {"v": list(v) if isinstance(v, tuple) else v},
                    {"v": ("v", _JSON_FACTOR[_PARAMS[n][1]])},
                )["v"]
                for n, v in full.items()
            },
            "free": list(res.free),
            "objectives": list(res.objectives),
            "n_feasible": len(res.designs),
            "n_pareto": len(res.pareto),
            "nfev": res.nfev,
            "elapsed_s": res.elapsed,
            "least_mass": _design_row(res.row(res.least_mass)),
            "least_radius": _design_row(res.row(res.least_radius)),
            "pareto": [_design_row(res.row(int(i))) for i in pick],
        }
        click.echo(json_text(out))
        return
    rows = [res.row(res.least_mass), res.row(res.least_radius)] + [res.row(int(i)) for i in pick]
    require_finite({"required_first_moment": required, "designs": rows})
    click.echo(
        f"required first moment {unit_text(required, 'first_moment', 5)}, "
        f"density {number(res.density)} kg/m³,"
        f" free: {', '.join(_SYMBOL[n] for n in res.free) or 'none'}"
    )
    labels = ["least mass", "least radius"] + [f"front {k + 1}" for k in range(len(pick))]
    _table_rows(rows, labels)


def _spread(n: int, k: int) -> list[float]:
    return [0.0] if k == 1 else [i * (n - 1) / (k - 1) for i in range(k)]


def _design_from(params: dict[str, Any], density: str, required: float | None):
    from ..physics.counterweight import CounterweightDesign

    values: dict[str, float] = {}
    for name, text in params.items():
        opt, kind = _PARAMS[name][0], _PARAMS[name][1]
        if text is None:
            if name == "thickness" and required is not None:
                continue
            raise InputError(
                opt,
                None,
                f"required ({kind}, e.g. '20 {_PARAMS[name][3]}')"
                + ("; or give the requirement to size it" if name == "thickness" else ""),
            )
        values[name] = _value(name, text)
    rho = _value("density", density)
    if "thickness" not in values:
        assert required is not None
        probe = CounterweightDesign(**values, thickness=1.0, density=rho)
        return probe.with_thickness_for(required)
    return CounterweightDesign(**values, density=rho)


def _optional_requirement(first_moment, cw_mass, cg_radius, engine) -> float | None:
    if first_moment is None and cw_mass is None and cg_radius is None and engine is None:
        return None
    return _first_moment(first_moment, cw_mass, cg_radius, engine)


@counterweight.command()
@_requirement_options
@_param_options(" (thickness may be left out with a requirement: sized to 100 %).")
@click.option("--density", default="8000 kg/m^3", show_default=True, help="Material density.")
@format_option(("table", "json"))
def show(first_moment, cw_mass, cg_radius, engine, density, fmt, **params: Any) -> None:
    """Mass properties of one counterweight design."""
    required = _optional_requirement(first_moment, cw_mass, cg_radius, engine)
    design = _design_from(params, density, required)
    props = design.properties(required)
    values = {n: getattr(design, n) for n in _PARAMS}
    values.update(
        mass=props.mass,
        outer_radius=props.outer_radius,
        radius_bound=props.radius_bound,
        inertia=props.inertia,
        cg_radius=props.cg_radius,
        first_moment=props.first_moment,
        balance=props.balance if props.balance is not None else math.nan,
    )
    row = _design_row(values)
    if props.balance is None:
        row.pop("balance_percent")
    out = {
        "schema": SCHEMA,
        "mode": "design",
        "density_kg_m3": design.density,
        "required_first_moment_kg_m": required,
        "design": row,
        "area_m2": props.area,
        "volume_m3": props.volume,
        "overhang_m": props.overhang,
        "gamma_deg": math.degrees(props.gamma),
        "lambda_deg": math.degrees(props.lam),
        "hub_protrusion": bool(props.hub_protrusion),
    }
    require_finite(out)
    if fmt == "json":
        click.echo(json_text(out))
        return
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
@_requirement_options
@_param_options(" (thickness may be left out with a requirement: sized to 100 %).")
@click.option("--density", default="8000 kg/m^3", show_default=True, help="Material density.")
@click.option("--output", "-o", required=True, help="File: .svg, .dxf, .stl or .step (mm).")
def export(first_moment, cw_mass, cg_radius, engine, density, output, **params: Any) -> None:
    """Write a design as SVG/DXF profile, STL solid or STEP (needs crankbalance[cad])."""
    from ..io.cad import export_counterweight

    if output.lower().endswith((".step", ".stp")):
        require_extra("cad")
    if params["thickness"] is not None:
        refuse_unused(
            {name: False for name in ("first_moment", "cw_mass", "cg_radius", "engine")},
            "only sizes the thickness of an export: give it or --thickness, not both",
        )
    required = _optional_requirement(first_moment, cw_mass, cg_radius, engine)
    design = _design_from(params, density, required)
    require_finite(design.properties(required), "design")
    path = export_counterweight(design, output)
    click.echo(f"wrote {path}", err=True)


@counterweight.command()
@click.argument("part")
@_requirement_options
@click.option("--density", default="8000 kg/m^3", show_default=True, help="Material density.")
@click.option("--unit", default="mm", show_default=True, help="Length unit of the file.")
@format_option(("table", "json"))
def check(part, first_moment, cw_mass, cg_radius, engine, density, unit, fmt) -> None:
    """Mass properties of an STL/STEP PART about the crank axis (the file's z axis)."""
    from ..io.cad import mesh_mass_properties

    require_extra("geometry", "trimesh")
    if str(part).lower().endswith((".step", ".stp")):
        require_extra("cad")
    required = _optional_requirement(first_moment, cw_mass, cg_radius, engine)
    m = mesh_mass_properties(
        part,
        _value("density", density),
        length_unit=_value("unit", f"1 {unit}"),
        required_first_moment=required,
    )
    out = {
        "schema": SCHEMA,
        "mode": "part",
        "path": str(part),
        **keyed(m.to_dict(), _PART_KEYS),
    }
    require_finite(out)
    if fmt == "json":
        click.echo(json_text(out))
        return
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
