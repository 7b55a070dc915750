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
from ._common import (
    SuggestingGroup,
    echo_table,
    option_name,
    parse_settings,
    run_study,
    study_options,
    typed,
)

FORMATS = click.Choice(["table", "json"])


def _engine(required: bool = True) -> Callable[[Any], Any]:
    return click.option(
        "--engine",
        required=required,
        help="Engine file or preset name (e.g. v8-crossplane): cylinders, pins, speed.",
    )


def _echo_json(result: Any) -> None:
    """The JSON of a shop result, every key with its unit (:func:`studies.shop.shop_json`)."""
    from ..output.format import json_text

    click.echo(json_text(result.to_dict()))


def _g(value: float) -> str:
    return text(value, "mass", 5)


@click.group(cls=SuggestingGroup)
def shop() -> None:
    """The balance shop: weighed parts to matched sets, bob-weights, a hole plan and a sheet."""


@shop.command()
@study_options("shop-match")
@_engine()
@click.option(
    "--format", "fmt", type=FORMATS, default="table", show_default=True, help="Output format."
)
def match(engine: str, fmt: str, **values: Any) -> None:
    """Match the weighed parts of PARTS (CSV or TOML) to the cylinders of the engine."""
    result = run_study("shop-match", engine, values)
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
    _echo_journals(study)
    _echo_spares(study)


def _echo_spares(study: Any) -> None:
    """The parts in no set, when the parts file lists more than the engine's cylinders
    (:func:`studies.shop.spares_words`, the web's words)."""
    from ..studies.shop import spares_words

    spares = spares_words(study)
    if spares:
        click.echo(spares)


def _echo_journals(study: Any) -> None:
    """Which cylinders share each journal, and the spread of the journals' bob-weights."""
    from ..output.shop_sheet import journal_cylinders, journals_words

    j = study.journals
    pins = "; ".join(
        f"pin {t + 1}: cylinders {journal_cylinders(j, t)}" for t in range(len(j.bob_weight))
    )
    click.echo(
        f"{journals_words(j)}: {pins}; spread of the journals' bob-weights {_g(j.spread)} "
        f"(as listed {_g(j.as_listed_spread)})"
    )


@shop.command()
@study_options("shop-bobweights")
@_engine()
@click.option(
    "--format", "fmt", type=FORMATS, default="table", show_default=True, help="Output format."
)
def bobweights(engine: str, fmt: str, **values: Any) -> None:
    """Bob-weight per crankpin from the matched sets of PARTS."""
    result = run_study("shop-bobweights", engine, values)
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
    _echo_journals(study)
    _echo_spares(study)
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
@study_options("shop-plan")
@click.option(
    "--format", "fmt", type=FORMATS, default="table", show_default=True, help="Output format."
)
def plan(engine: str | None, fmt: str, **values: Any) -> None:
    """Two-plane readings to holes per correction plane, and the ISO check."""
    result = run_study("shop-plan", engine, values)
    if fmt == "json":
        _echo_json(result)
        return
    echo_hole_plan(result.result)


@shop.command()
@study_options("shop-scatter")
@_engine()
@click.option(
    "--format", "fmt", type=FORMATS, default="table", show_default=True, help="Output format."
)
def scatter(engine: str, fmt: str, **values: Any) -> None:
    """Monte Carlo of the weight scatter in PARTS: residual per plane, free forces."""
    result = run_study("shop-scatter", engine, values)
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
@study_options("shop-match")
@_engine()
@click.option("-o", "--output", required=True, help="sheet.html or sheet.pdf.")
@click.option("--chromium", default=None, help="Chromium executable for the PDF.")
@study_options("shop-plan")
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
