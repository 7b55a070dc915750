"""``crankbalance shaft ...``: balance-shaft bearing and unbalance-mass layout (Kim 2018).

Sub-commands:

* ``inline4``: optimum unbalance-mass position of a second-order shaft on end bearings,
* ``inline3``: optimum second-mass position for the three inline-3 rotor types,
* ``check``: state variables and design checks of one given layout.
"""

from __future__ import annotations

from typing import Any

import click

from ..output.format import json_text, text
from ._common import SuggestingGroup, echo_table, format_option, run_study, study_options


def _engine_option(function: Any) -> Any:
    return click.option(
        "--engine",
        default=None,
        help="Engine file or preset: the balancing solver gives --unbalance and --speed.",
    )(function)


def _verdict(limit: float | None, ok: bool) -> str:
    return "" if limit is None else ("ok" if ok else "FAIL")


def _echo_input(result: Any) -> None:
    need = result.requirement
    source = f" (from the balancing solver of {need.engine})" if need.engine else ""
    click.echo(
        f"Unbalance {text(need.unbalance, 'unbalance', 6)} at "
        f"{text(need.speed, 'speed', 6)}{source}"
    )


def _echo_study(study: Any, every: int) -> None:
    click.echo(f"{study.case}: {study.design_variable}")
    click.echo(
        f"  optimum at {100 * study.optimum_position:.1f} % of the length "
        f"(w = {study.weight:g}, J = {study.optimum_objective:.4f}, B = {study.secondary})"
    )
    rows = []
    n = study.positions.size
    for i in sorted(set(range(0, n, max(1, every))) | {n - 1}):
        rows.append(
            [
                f"{100 * study.positions[i]:.1f}",
                f"{study.reactions[i].max():.4g}",
                f"{study.reaction_difference[i]:.4g}",
                f"{1e6 * study.bending_measure[i]:.4g}",
                f"{1e6 * study.max_deflection[i]:.4g}",
                f"{study.max_stress[i] / 1e6:.4g}",
                f"{study.first_frequency[i]:.5g}",
                f"{study.objective[i]:.4f}",
            ]
        )
    echo_table(["x/L %", "max R N", "dR N", "∫w mm²", "w max µm", "σ MPa", "f1 Hz", "J"], rows)
    click.echo("  weight sweep:")
    echo_table(
        ["w", "optimum %"],
        [
            [f"{w:.3g}", f"{100 * x:.1f}"]
            for w, x in zip(study.weights, study.optimum_positions, strict=True)
        ],
    )


@click.group(cls=SuggestingGroup)
def shaft() -> None:
    """Balance-shaft bearing and unbalance-mass layout (beam model, Kim 2018)."""


@shaft.command()
@_engine_option
@study_options("shaft-inline4")
@format_option(("table", "json"))
def inline4(fmt: str, engine: str | None, **values: Any) -> None:
    """Optimum unbalance-mass position of an inline-4 second-order shaft on end bearings."""
    result = run_study("shaft-inline4", engine, values)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    _echo_input(result)
    _echo_study(result.studies[0], max(1, result.points // 10))
    click.echo("Kim (2018), Fig. 7: 67 % with w = 2.")


@shaft.command()
@_engine_option
@study_options("shaft-inline3")
@format_option(("table", "json"))
def inline3(fmt: str, engine: str | None, **values: Any) -> None:
    """Optimum second-mass position of an inline-3 primary-couple shaft, per rotor type.

    --unbalance is the first moment of each mass when the two masses are the shaft
    length apart (Kim (2018), Eq. 12).
    """
    result = run_study("shaft-inline3", engine, values)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    _echo_input(result)
    for s in result.studies:
        _echo_study(s, max(1, result.points // 10))
        click.echo("")
    echo_table(
        ["type", "model optimum %", "paper %"],
        [
            [
                s.case.split("-")[1],
                f"{100 * s.optimum_position:.1f}",
                "69 (type III, not reproducible)" if s.case.endswith("-III") else "-",
            ]
            for s in result.studies
        ],
    )


@shaft.command()
@study_options("shaft-check")
@format_option(("table", "json"))
def check(fmt: str, **values: Any) -> None:
    """State variables and design checks of one shaft layout."""
    result = run_study("shaft-check", None, values)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    design, response, checks = result.design, result.response, result.checks
    rows = [
        [f"bearing {i + 1} at {1000 * x:.1f} mm", f"{r:.4g} N"]
        for i, (x, r) in enumerate(zip(design.bearing_positions, response.reactions, strict=True))
    ]
    rows += [
        ["bearing-load difference", f"{response.reaction_difference:.4g} N"],
        ["integral of deflection", f"{1e6 * response.bending_measure:.4g} mm²"],
        ["max deflection", f"{1e6 * response.max_deflection:.4g} µm"],
        ["max bending stress", f"{response.max_stress / 1e6:.4g} MPa"],
        ["first bending frequency", f"{response.first_frequency:.5g} Hz"],
        [
            "critical speed / max speed",
            f"{checks.critical_speed_ratio:.3f} "
            f"(need >= {checks.required_ratio:.3f}) "
            f"{'ok' if checks.critical_speed_ok else 'FAIL'}",
        ],
        [
            "max bearing load",
            f"{checks.max_bearing_load:.4g} N "
            + _verdict(checks.bearing_capacity, checks.bearing_ok),
        ],
        [
            "max deflection at max speed",
            f"{1e6 * checks.max_deflection:.4g} µm "
            + _verdict(checks.deflection_limit, checks.deflection_ok),
        ],
        ["dynamic amplification (1 mode)", f"{checks.dynamic_amplification:.3f}"],
        ["all checks", "ok" if checks.ok else "FAIL"],
    ]
    echo_table(["quantity", "value"], rows)
