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
from ..schema.settings import MAX_SHAFT_POINTS, ShaftCheckOptions, ShaftStudyOptions
from ._common import default_help, echo_table, format_option, run_study


def _section_options(function: Any) -> Any:
    def shown(name: str, words: str) -> str:
        return default_help(ShaftStudyOptions, name, words)

    options = [
        click.option(
            "--length", default=None, help=shown("length", 'Shaft length, e.g. "300 mm".')
        ),
        click.option(
            "--diameter",
            default=None,
            help=shown("diameter", 'Outer shaft diameter, e.g. "25 mm".'),
        ),
        click.option("--bore", default=None, help=shown("bore", "Bore diameter (hollow shaft).")),
        click.option("--modulus", default=None, help=shown("modulus", "Young's modulus.")),
        click.option("--density", default=None, help=shown("density", "Density.")),
        click.option("--poisson", default=None, help=shown("poisson", "Poisson's ratio.")),
        click.option(
            "--unbalance-radius",
            default=None,
            help=shown(
                "unbalance_radius",
                "Centre-of-gravity radius of the unbalance masses (their mass m = U / e).",
            ),
        ),
        click.option(
            "--bearing-stiffness",
            default=None,
            help='Radial bearing stiffness, e.g. "2e8 N/m" (default: rigid).',
        ),
        click.option(
            "--theory",
            type=click.Choice(["euler-bernoulli", "timoshenko"]),
            default=None,
            help=shown("theory", "Beam theory."),
        ),
    ]
    for option in reversed(options):
        function = option(function)
    return function


def _study_options(function: Any) -> Any:
    options = [
        click.option(
            "--engine",
            default=None,
            help="Engine file or preset: the balancing solver gives --unbalance and --speed.",
        ),
        click.option(
            "--unbalance",
            default=None,
            help='Required first moment m*e of the shaft, e.g. "3.3 g*m".',
        ),
        click.option(
            "--speed",
            default=None,
            help='Shaft speed (twice crank speed for second order), e.g. "12000 rpm".',
        ),
        click.option(
            "--weight",
            default=None,
            help=default_help(ShaftStudyOptions, "weight", "w of the objective (0 to 1000)."),
        ),
        click.option(
            "--weights",
            default=None,
            help="Comma-separated weights of the sweep (default 20 values 0.2 ... 4).",
        ),
        click.option(
            "--points",
            default=None,
            help=default_help(
                ShaftStudyOptions,
                "points",
                f"Design points along the shaft (3 to {MAX_SHAFT_POINTS}).",
            ),
        ),
        click.option(
            "--secondary",
            type=click.Choice(["reaction-difference", "inverse-frequency"]),
            default=None,
            help="B of the objective (default: reaction-difference for inline4, "
            "inverse-frequency for inline3).",
        ),
    ]
    for option in reversed(options):
        function = option(function)
    return _section_options(function)


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


@click.group()
def shaft() -> None:
    """Balance-shaft bearing and unbalance-mass layout (beam model, Kim 2018)."""


@shaft.command()
@_study_options
@click.option(
    "--order",
    default=None,
    help="With --engine: the order of the shaft, 1 or 2 (default: 2 when the engine has a free "
    "second-order force or moment, else 1).",
)
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
@_study_options
@click.option(
    "--type",
    type=click.Choice(["I", "II", "III", "all"]),
    default=None,
    help=default_help(ShaftStudyOptions, "type", "Rotor type (order of masses and bearings)."),
)
@click.option(
    "--hold",
    type=click.Choice(["couple", "unbalance"]),
    default=None,
    help=default_help(
        ShaftStudyOptions, "hold", "Keep the couple (physical) or each mass's unbalance (paper)."
    ),
)
@click.option("--bearing-offset", default=None, help="Bearing-to-mass distance (default 0.1 L).")
@click.option(
    "--z-min",
    default=None,
    help=default_help(
        ShaftStudyOptions,
        "z_min",
        "Smallest second-mass position z / L of the sweep (0 to below 1).",
    ),
)
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
@click.option(
    "--bearing",
    multiple=True,
    help="Bearing position from the shaft end (repeat, at least two).",
)
@click.option(
    "--mass",
    multiple=True,
    help="Unbalance-mass position (repeat; match with --unbalance).",
)
@click.option(
    "--unbalance",
    multiple=True,
    help='First moment m*e of each mass, e.g. "3.3 g*m" (one for all, or one per mass).',
)
@click.option(
    "--phase",
    multiple=True,
    help='Angular position of each mass on the shaft, e.g. "180 deg" (default 0).',
)
@click.option("--speed", default=None, help="Shaft speed of the evaluation (required).")
@click.option(
    "--max-speed", default=None, help="Maximum shaft speed for the checks (default --speed)."
)
@click.option(
    "--margin",
    default=None,
    help=default_help(
        ShaftCheckOptions,
        "margin",
        "Required separation of the first critical speed above the maximum speed.",
    ),
)
@click.option("--bearing-capacity", default=None, help='Allowed bearing load, e.g. "5 kN".')
@click.option("--deflection-limit", default=None, help='Allowed deflection, e.g. "50 um".')
@_section_options
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
