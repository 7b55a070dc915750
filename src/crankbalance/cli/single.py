"""CLI commands ``balance-factor``, ``rebalance`` and ``tolerance`` (single-cylinder tools).

Quantities are unit strings (``"282.12 g"``, ``"26.9 mm"``, ``"15200 rpm"``); balance factors
are plain numbers (0.28) or percentages (``"28%"``). Heavy imports stay inside the commands.
"""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import in_output_style, json_text, text
from ..units import format_quantity
from ._common import format_table, run_study, study_options

FORMATS = click.Choice(["table", "json"])


def _quantity(value: float, kind: str) -> str:
    return in_output_style(format_quantity(value, kind, digits=5))


def _gmm(value: float) -> str:
    return text(value, "unbalance")


# ---------------------------------------------------------------------------------------
# balance-factor
# ---------------------------------------------------------------------------------------


@click.command("balance-factor")
@study_options("balance-factor")
@click.option(
    "--engine",
    "engine",
    default=None,
    help="Engine file or preset: take masses and geometry of one cylinder from it.",
)
@click.option(
    "--format", "fmt", type=FORMATS, default="table", show_default=True, help="Output format."
)
def balance_factor(engine: str | None, fmt: str, **values: Any) -> None:
    """Balance factor of a crank, its bob-weight, and the single-cylinder force study.

    The balance factor is the share of the reciprocating mass per cylinder balanced by the
    crank counterweight, on top of 100 % of the rotating mass.
    """
    from ..studies.single import BALANCE_FACTOR_NOTE

    result = run_study("balance-factor", engine, values)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    fb, mass_properties, study = result.balance_factor, result.mass_properties, result.study
    rows = [("balance factor studied", f"{fb:.4f}")]
    if mass_properties:
        rows.append(
            ("balance factor of the crank (Eq. 6.2)", f"{mass_properties['balance_factor']:.4f}")
        )
        rows.append(
            ("counterweight moment m_cw r'", _gmm(mass_properties["counterweight_moment_kg_m"]))
        )
    if result.bob_weight is not None:
        rows.append(
            (f"bob-weight for f_b = {result.target:.4f}", _quantity(result.bob_weight, "mass"))
        )
    if study is not None:
        rows += [
            ("kinematics", study.model),
            ("primary force P", _quantity(study.primary_force, "force")),
            ("in-line amplitude", _quantity(study.in_line_amplitude, "force")),
            ("transverse amplitude", _quantity(study.transverse_amplitude, "force")),
            ("peak resultant", _quantity(study.peak_resultant, "force")),
            ("optimum balance factor", f"{study.optimum_balance_factor:.4f}"),
            ("peak resultant at optimum", _quantity(study.optimum_peak_resultant, "force")),
        ]
    click.echo(format_table(None, rows))
    click.echo(f"({BALANCE_FACTOR_NOTE})")


# ---------------------------------------------------------------------------------------
# rebalance
# ---------------------------------------------------------------------------------------


@click.command("rebalance")
@study_options("rebalance")
@click.option(
    "--format", "fmt", type=FORMATS, default="table", show_default=True, help="Output format."
)
def rebalance_command(fmt: str, **values: Any) -> None:
    """Rebalance a single-cylinder crank after new parts (Hoem and Røsholm (2016), Sec. 6.4, eight
    steps).

    Options override the values of the --parts file.
    """
    from ..studies.single import BALANCE_FACTOR_NOTE

    result = run_study("rebalance", None, values)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    study = result.study
    click.echo(study.name)
    click.echo(
        f"old parts: m_rot = {_quantity(study.old.rotating_mass, 'mass')}, "
        f"m_rec = {_quantity(study.old.reciprocating_mass, 'mass')}; "
        f"new parts: m_rot = {_quantity(study.new.rotating_mass, 'mass')}, "
        f"m_rec = {_quantity(study.new.reciprocating_mass, 'mass')}"
    )
    click.echo(f"tolerance: {_gmm(study.tolerance)} ({study.tolerance_source})")
    for res in study.cases:
        click.echo("")
        click.echo(
            f"target f_b = {res.target_balance_factor:.4f} (crank now "
            f"{res.original_balance_factor:.4f}): unbalance to correct "
            f"{_gmm(res.unbalance)}, bob-weight "
            f"{_quantity(res.bob_weight, 'mass')}"
        )
        rows = [
            (
                str(it.iteration),
                f"{it.correction_radius * 1e3:.3f}",
                f"{it.correction_mass * 1e3:.3f}",
                f"{it.depth * 1e3:.3f}",
                f"{it.removed_mass * 1e3:.3f}",
                f"{it.residual * 1e6:.3f}",
                "yes" if it.within_tolerance else "no",
            )
            for it in res.iterations
        ]
        if rows:
            header = (
                "iter",
                "r_corr [mm]",
                "m_corr [g]",
                _depth_header(res.correction),
                "removed [g]",
                "residual [g·mm]",
                "within",
            )
            click.echo(format_table(header, rows))
        click.echo(
            f"status {res.status}; residual {_gmm(abs(res.residual))} "
            f"{'<=' if res.passed else '>'} {_gmm(res.tolerance)}: "
            f"{'PASS' if res.passed else 'FAIL'}; achieved f_b = "
            f"{res.achieved_balance_factor:.4f}"
        )
    click.echo(f"({BALANCE_FACTOR_NOTE})")


def _depth_header(correction: Any) -> str:
    """The depth column's header: what the depth of pointed holes is read to."""
    if correction.kind == "holes" and correction.point_angle != math.pi:
        return f"depth to {correction.depth_to} [mm]"
    return "depth [mm]"


# ---------------------------------------------------------------------------------------
# tolerance
# ---------------------------------------------------------------------------------------


@click.command("tolerance")
@click.option(
    "--engine",
    default=None,
    help="Engine file or preset: the rotor mass (its crank's rotating masses, a stand-in "
    "for the crank's mass) and the speed default to the engine's.",
)
@study_options("tolerance")
@click.option(
    "--format", "fmt", type=FORMATS, default="table", show_default=True, help="Output format."
)
def tolerance_command(fmt: str, engine: str | None, **values: Any) -> None:
    """ISO 21940-11 permissible residual unbalance U_per = 1000 G m / Omega [g·mm]."""
    result = run_study("tolerance", engine, values)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    if result.grade is None:
        click.echo(
            format_table(
                ("grade", "example rotor types"), [(g.name, g.examples) for g in result.grades]
            )
        )
        return
    item, u_per, allocation, verdict = (
        result.grade,
        result.permissible,
        result.planes,
        result.verdict,
    )
    rows = [
        ("grade", item.name),
        ("permissible residual U_per", _gmm(u_per)),
        ("permissible eccentricity", text(u_per / result.rotor_mass, "deflection")),
    ]
    if allocation is not None:
        rows += [
            ("bearing plane A", _gmm(allocation.bearing_a)),
            ("bearing plane B", _gmm(allocation.bearing_b)),
            ("correction plane I", _gmm(allocation.plane_1)),
            ("correction plane II", _gmm(allocation.plane_2)),
        ]
    if verdict is not None:
        rows += [
            ("residual", _gmm(verdict.residual)),
            (
                "verdict",
                f"{'PASS' if verdict.passed else 'FAIL'} ({verdict.ratio * 100:.1f} % of U_per)",
            ),
        ]
    click.echo(format_table(None, rows))
    click.echo(f"({item.name}: {item.examples})")
    if allocation is not None:
        click.echo(f"(rule: {allocation.rule})")
