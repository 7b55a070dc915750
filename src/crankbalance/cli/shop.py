"""``crankbalance shop ...``: the balance shop (issue 16, docs/balance_shop.md).

``match`` and ``bobweights`` read a parts file for an engine; ``plan`` turns the two readings
of a balancing machine into holes per correction plane and checks the predicted residual
against ISO 21940-11; ``scatter`` runs the Monte Carlo of the parts file's scatter; ``sheet``
writes the printable shop sheet (HTML or PDF). Every command validates its settings through
:class:`crankbalance.schema.settings.ShopOptions`; an error names the option as typed, exit 2.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import click

from ..output.format import text
from ..schema.settings import ShopOptions
from ._common import default_help, echo_table, option_name, parse_settings, run_study, typed

FORMATS = click.Choice(["table", "json"])


def _engine(required: bool = True) -> Callable[[Any], Any]:
    return click.option(
        "--engine",
        required=required,
        help="Engine file or preset name (e.g. v8-crossplane): cylinders, pins, speed.",
    )


#: the settings of the matching and bob-weights, as click options
_PARTS_OPTIONS = (
    click.option(
        "--method",
        type=click.Choice(["milp", "pairing", "exhaustive", "as-listed"]),
        default=None,
        help="Matching method (default milp: least spread, proven optimal within the time "
        "limit; too large a problem is matched by a local search, said so in the output).",
    ),
    click.option(
        "--time-limit",
        help="Longest matching, the building of the model included, default '60 s'.",
    ),
    click.option(
        "--fraction", help="Share of the reciprocating weight in the bob-weights, default 0.5."
    ),
)

#: the settings of the hole plan and the ISO check, as click options
_PLAN_OPTIONS = (
    click.option(
        "--reading",
        multiple=True,
        help="Machine reading, twice (measuring plane 1, then 2): '12.5 g @ 40 mm, 35 deg'.",
    ),
    click.option(
        "--convention",
        type=click.Choice(["heavy", "light"]),
        default=None,
        help="The readings' angle is the heavy spot (default) or the light spot.",
    ),
    click.option(
        "--measuring-planes", help="Axial positions of the measuring planes: '0 mm, 400 mm'."
    ),
    click.option(
        "--correction-planes", help="Axial positions of the correction planes: '50 mm, 350 mm'."
    ),
    click.option("--hole-diameter", help="Drill diameter, default '8 mm'."),
    click.option("--hole-radius", help="Radius of the axial holes (or of the rim), e.g. '45 mm'."),
    click.option("--max-depth", help="Deepest hole allowed, default '15 mm'."),
    click.option(
        "--web-thickness",
        help="Axial thickness of the web at the holes: the deepest axial hole, the widest "
        "radial one (not given: holes at most 10 drill diameters deep).",
    ),
    click.option(
        "--depth-to",
        type=click.Choice(["shoulder", "tip"]),
        default=None,
        help="What the depths are read to (required with readings).",
    ),
    click.option("--point-angle", help="Drill point angle, default '118 deg' (180: flat)."),
    click.option(
        "--direction", type=click.Choice(["axial", "radial"]), default=None, help="Hole direction."
    ),
    click.option("--spacing", help="Material between holes, default '2 mm'."),
    click.option("--depth-resolution", help="Machining step, default '0.1 mm'."),
    click.option("--density", help="Crank material, default '7850 kg/m^3'."),
    click.option("--slug-density", help="Add heavy metal of this density instead of drilling."),
    click.option("--grade", help="ISO 21940-11 grade, default G6.3."),
    click.option("--rotor-mass", help="Crank mass for the ISO check, e.g. '25 kg'."),
    click.option("--speed", help="Largest service speed, default the engine's."),
    click.option("--bearings", help="Main bearings: '-20 mm, 420 mm' (default the planes)."),
    click.option("--center-of-mass", help="Crank centre of mass (default mid-bearings)."),
)


def _with(options: tuple[Callable[[Any], Any], ...]) -> Callable[[Any], Any]:
    def wrap(func: Any) -> Any:
        for option in reversed(options):
            func = option(func)
        return func

    return wrap


def _echo_json(result: Any) -> None:
    """The JSON of a shop result, every key with its unit (:func:`studies.shop.shop_json`)."""
    from ..output.format import json_text

    click.echo(json_text(result.to_dict()))


def _g(value: float) -> str:
    return text(value, "mass", 5)


@click.group()
def shop() -> None:
    """The balance shop: weighed parts to matched sets, bob-weights, a hole plan and a sheet."""


@shop.command()
@click.argument("parts")
@_engine()
@_with(_PARTS_OPTIONS)
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def match(parts: str, engine: str, fmt: str, **values: Any) -> None:
    """Match the weighed parts of PARTS (CSV or TOML) to the cylinders of the engine."""
    result = run_study("shop-match", engine, {**values, "parts": parts})
    if fmt == "json":
        _echo_json(result)
        return
    study = result.parts
    m = study.matching
    rows = [
        [str(c + 1), *m.ids[c], _g(m.reciprocating[c]), _g(m.rotating[c])]
        + [_g(m.remove_reciprocating[c]), _g(m.remove_rotating[c])]
        for c in range(study.cylinders)
    ]
    echo_table(["cyl", *m.kinds, "recip.", "rotating", "remove recip.", "remove rot."], rows)
    click.echo(
        f"\n{m.method} ({m.status}): spread reciprocating {_g(m.reciprocating_spread)}, rotating "
        f"{_g(m.rotating_spread)}; material to remove {_g(m.removed_total)}"
    )
    listed = study.as_listed
    click.echo(
        f"as listed: spread {_g(listed.reciprocating_spread)}, {_g(listed.rotating_spread)}; "
        f"remove {_g(listed.removed_total)}"
    )
    click.echo(f"every part machined to the lightest: remove {_g(study.machined.removed_total)}")


@shop.command()
@click.argument("parts")
@_engine()
@_with(_PARTS_OPTIONS)
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def bobweights(parts: str, engine: str, fmt: str, **values: Any) -> None:
    """Bob-weight per crankpin from the matched sets of PARTS."""
    result = run_study("shop-bobweights", engine, {**values, "parts": parts})
    if fmt == "json":
        _echo_json(result)
        return
    study = result.parts
    b = study.bob_weights
    echo_table(
        ["pin", "rods", "rotating", "reciprocating", "bob-weight"],
        [
            [str(t + 1), str(b.rods_on_pin[t]), _g(b.rotating[t]), _g(b.reciprocating[t])]
            + [_g(b.bob_weight[t])]
            for t in range(len(b.bob_weight))
        ],
    )
    left = study.remaining
    m = study.matching
    click.echo(f"\nsets matched by {m.method} ({m.status})")
    click.echo(
        f"fraction {b.fraction:g} at {text(study.crank_radius, 'length')}: leaves "
        + "; ".join(
            f"order {k + 1} force {text(f, 'force')}, couple {text(c, 'moment')}"
            for k, (f, c) in enumerate(
                zip(left.force_amplitude, left.couple_amplitude, strict=True)
            )
        )
    )


def echo_hole_plan(result: Any) -> None:
    """The hole plan per correction plane and the ISO verdict, as a table."""
    rows = []
    for j, (plane, holes) in enumerate(
        zip(result.plan.correction_planes, result.holes, strict=True)
    ):
        angles = ", ".join(text(a, "angle", 4) for a in holes.angles) or "–"
        rows.append(
            [
                f"{j + 1} at {text(plane, 'length')}",
                text(result.plan.amount[j], "unbalance", 4),
                text(result.plan.remove_angle[j], "angle", 4),
                str(holes.number),
                angles,
                f"{text(holes.depth, 'length', 4)} to {holes.depth_to}",
                _g(holes.hole_mass),
                text(abs(result.residual[j]), "unbalance", 3),
                text(result.check.tolerance[j], "unbalance", 4),
                "pass" if result.check.verdicts[j].passed else "FAIL",
            ]
        )
    echo_table(
        ["plane", "unbalance", "heavy spot", "holes", "at", "depth", "per hole", "residual"]
        + ["tolerance", "ISO"],
        rows,
    )
    for j, holes in enumerate(result.holes):
        if holes.note:
            click.echo(f"plane {j + 1}: {holes.note}")
    verdict = "PASS" if result.check.passed else "FAIL"
    click.echo(
        f"\nISO 21940-11 {result.grade}, {text(result.rotor_mass, 'mass_kg')}, "
        f"{text(result.speed, 'speed')}: {verdict}"
    )


@shop.command()
@_engine(required=False)
@_with(_PLAN_OPTIONS)
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def plan(engine: str | None, fmt: str, **values: Any) -> None:
    """Two-plane readings to holes per correction plane, and the ISO check."""
    result = run_study("shop-plan", engine, values)
    if fmt == "json":
        _echo_json(result)
        return
    echo_hole_plan(result.result)


@shop.command()
@click.argument("parts")
@_engine()
@click.option(
    "--fraction", help="Share of the reciprocating weight in the bob-weights, default 0.5."
)
@click.option(
    "--correction-planes", required=True, help="From the crank mid-point: '-200 mm, 200 mm'."
)
@click.option("--rotor-mass", help="Crank mass, for the probability of meeting the grade.")
@click.option("--grade", help="ISO 21940-11 grade, default G6.3.")
@click.option("--speed", help="Largest service speed, default the engine's.")
@click.option("--bearings", help="Main bearings (default the planes).")
@click.option(
    "--samples",
    default=None,
    help=default_help(ShopOptions, "samples", "Engines drawn (up to 1e7)."),
)
@click.option(
    "--seed", default=None, help=default_help(ShopOptions, "seed", "Seed of the random numbers.")
)
@click.option(
    "--scale-step",
    default=None,
    help=default_help(ShopOptions, "scale_step", "Resolution of the scale."),
)
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def scatter(parts: str, engine: str, fmt: str, **values: Any) -> None:
    """Monte Carlo of the weight scatter in PARTS: residual per plane, free forces."""
    result = run_study("shop-scatter", engine, {**values, "parts": parts})
    if fmt == "json":
        _echo_json(result)
        return
    study = result.result
    kinds = ("unbalance", "unbalance", "force", "force", "moment", "moment")
    at = list(study.quantile_levels).index(0.95)
    echo_table(
        ["output", "mean", "95 %", "largest share"],
        [
            [name, text(study.mean[k], kinds[k]), text(study.quantiles[k, at], kinds[k])]
            + [study.dominant[k]]
            for k, name in enumerate(study.outputs)
        ],
    )
    if study.p_grade is not None:
        grade = values.get("grade") or ShopOptions.FIELDS["grade"].default
        click.echo(f"\nP(both planes meet {grade}) = {study.p_grade:.4g}")


@shop.command()
@click.argument("parts")
@_engine()
@click.option("-o", "--output", required=True, help="sheet.html or sheet.pdf.")
@click.option("--chromium", default=None, help="Chromium executable for the PDF.")
@_with(_PARTS_OPTIONS + _PLAN_OPTIONS)
def sheet(parts: str, engine: str, output: str, chromium: str | None, **values: Any) -> None:
    """The printable shop sheet of PARTS (and of the readings, when given): HTML or PDF.

    It shows the studies ``shop match`` and ``shop plan`` with the same options."""
    from ..output.shop_sheet import write_sheet
    from ..schema.settings import ShopOptions
    from ..studies.shop import PLAN_NAMES, shop_study
    from ._common import require_extra
    from .plot import check_output

    pdf = check_output(output, (".html", ".htm", ".pdf")).suffix.lower() == ".pdf"
    require_extra("web", "plotly", *(("kaleido",) if pdf else ()))
    from ..studies.registry import named_fields

    given = typed(values)
    options = parse_settings(ShopOptions, given)
    with named_fields(ShopOptions.FIELDS, given, options, option_name):
        study = shop_study(engine, parts, options, PLAN_NAMES)
    path = write_sheet(study, output, chromium)
    click.echo(f"wrote {path}", err=True)
