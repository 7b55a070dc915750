"""``crankbalance shaft ...``: balance-shaft bearing and unbalance-mass layout (Kim 2018).

Sub-commands:

* ``inline4``: optimum unbalance-mass position of a second-order shaft on end bearings,
* ``inline3``: optimum second-mass position for the three inline-3 rotor types,
* ``check``: state variables and design checks of one given layout.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, cast

import click
import numpy as np

from ..errors import InputError
from ..output.format import json_text, keyed, text
from ..results import require_finite
from ..schema.settings import MAX_SHAFT_POINTS
from ._common import echo_table, format_option, parse_settings

if TYPE_CHECKING:
    from ..physics.balance_shaft import HoldMode, RotorType, SecondaryMeasure
    from ..physics.beam import BeamTheory
    from ..schema.settings import ShaftSectionOptions, ShaftStudyOptions

SCHEMA = "crankbalance.shaft/2"

_DEG = 180.0 / math.pi
#: JSON keys of ``shaft check`` (unit in a suffix, angles in degrees)
SHAFT_KEYS: dict[str, str | tuple[str, float]] = {
    "length": "length_m",
    "bearing_positions": "bearing_positions_m",
    "mass_positions": "mass_positions_m",
    "unbalances": "unbalances_kg_m",
    "speed": "speed_rad_s",
    "phases": ("phases_deg", _DEG),
    "unbalance_radius": "unbalance_radius_m",
    "bearing_stiffness": "bearing_stiffness_N_per_m",
}
SECTION_KEYS: dict[str, str | tuple[str, float]] = {
    "outer_diameter": "outer_diameter_m",
    "inner_diameter": "inner_diameter_m",
    "youngs_modulus": "youngs_modulus_Pa",
    "density": "density_kg_m3",
}
RESPONSE_KEYS: dict[str, str | tuple[str, float]] = {
    "reactions": "reactions_N",
    "reaction_phases": ("reaction_phases_deg", _DEG),
    "reaction_difference": "reaction_difference_N",
    "x": "x_m",
    "deflection": "deflection_m",
    "bending_measure": "bending_measure_m2",
    "max_deflection": "max_deflection_m",
    "max_moment": "max_moment_Nm",
    "max_stress": "max_stress_Pa",
    "first_frequency": "first_frequency_hz",
    "first_critical_speed": "first_critical_speed_rad_s",
    "speed": "speed_rad_s",
}
CHECK_KEYS: dict[str, str | tuple[str, float]] = {
    "max_bearing_load": "max_bearing_load_N",
    "bearing_capacity": "bearing_capacity_N",
    "max_deflection": "max_deflection_m",
    "deflection_limit": "deflection_limit_m",
}


def _section_options(function: Any) -> Any:
    options = [
        click.option("--length", required=True, help='Shaft length, e.g. "300 mm".'),
        click.option("--diameter", required=True, help='Outer shaft diameter, e.g. "25 mm".'),
        click.option(
            "--bore", default="0 mm", show_default=True, help="Bore diameter (hollow shaft)."
        ),
        click.option("--modulus", default="210 GPa", show_default=True, help="Young's modulus."),
        click.option("--density", default="7850 kg/m^3", show_default=True, help="Density."),
        click.option("--poisson", default="0.3", show_default=True, help="Poisson's ratio."),
        click.option(
            "--unbalance-radius",
            default="20 mm",
            show_default=True,
            help="Centre-of-gravity radius of the unbalance masses (their mass m = U / e).",
        ),
        click.option(
            "--bearing-stiffness",
            default=None,
            help='Radial bearing stiffness, e.g. "2e8 N/m" (default: rigid).',
        ),
        click.option(
            "--theory",
            type=click.Choice(["euler-bernoulli", "timoshenko"]),
            default="euler-bernoulli",
            show_default=True,
            help="Beam theory.",
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
            "--weight", default="2", show_default=True, help="w of the objective (0 to 1000)."
        ),
        click.option(
            "--weights",
            default=None,
            help="Comma-separated weights of the sweep (default 20 values 0.2 ... 4).",
        ),
        click.option(
            "--points",
            default="200",
            show_default=True,
            help=f"Design points along the shaft (3 to {MAX_SHAFT_POINTS}).",
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


def _section(o: ShaftSectionOptions) -> Any:
    """The shaft section of the validated options."""
    from ..physics.beam import ShaftSection

    return ShaftSection(
        outer_diameter=o.diameter,
        inner_diameter=o.bore,
        youngs_modulus=o.modulus,
        density=o.density,
        poisson_ratio=o.poisson,
    )


def _study_setup(
    order: int, options: dict[str, Any]
) -> tuple[ShaftStudyOptions, dict[str, Any], dict[str, Any]]:
    """Validate the options shared by ``inline4`` and ``inline3``.

    Returns the options, the requirement block (unbalance and shaft speed, from --engine or
    --unbalance/--speed, in SI) and the keyword arguments common to
    :func:`inline4_study` and :func:`inline3_study` (length and section included).
    """
    from ..schema.settings import ShaftStudyOptions

    values = {k: v for k, v in options.items() if k in ShaftStudyOptions.FIELDS}
    if options["weights"] is not None:
        values["weights"] = options["weights"].split(",")
    o = parse_settings(ShaftStudyOptions, values)
    if o.engine is not None:
        if o.unbalance is not None or o.speed is not None:
            raise InputError("--engine", o.engine, "give --engine or --unbalance/--speed, not both")
        from ..studies.requirements import shaft_requirement

        need = shaft_requirement(o.engine, order, o.length, o.unbalance_radius)
        required, shaft_speed = need.unbalance, need.speed
    elif o.unbalance is None or o.speed is None:
        raise InputError(
            "--unbalance" if o.unbalance is None else "--speed",
            None,
            "is required (or give --engine to take it from the balancing solver)",
        )
    else:
        required, shaft_speed = o.unbalance, o.speed
    c = {"unbalance": required, "speed": shaft_speed}
    kwargs: dict[str, Any] = {
        "unbalance": required,
        "speed": shaft_speed,
        "length": o.length,
        "section": _section(o),
        "weight": o.weight,
        "weights": None if o.weights is None else np.array(o.weights),
        "unbalance_radius": o.unbalance_radius,
        "bearing_stiffness": o.bearing_stiffness,
        "theory": cast("BeamTheory", options["theory"]),
    }
    if options["secondary"] is not None:
        kwargs["secondary"] = cast("SecondaryMeasure", options["secondary"])
    return o, c, kwargs


def _input_json(engine: str | None, c: dict[str, Any]) -> dict[str, Any]:
    return {
        "unbalance_kg_m": c["unbalance"],
        "shaft_speed_rad_s": c["speed"],
        "from_engine": engine,
    }


def _echo_input(engine: str | None, c: dict[str, Any]) -> None:
    source = f" (from the balancing solver of {engine})" if engine else ""
    click.echo(
        f"Unbalance {text(c['unbalance'], 'unbalance', 6)} at "
        f"{text(c['speed'], 'speed', 6)}{source}"
    )


def _verdict(limit: float | None, ok: bool) -> str:
    return "" if limit is None else ("ok" if ok else "FAIL")


def study_json(study: Any) -> dict[str, Any]:
    """The JSON block of one placement study (optimum, weight sweep, curves)."""
    d = study.to_dict()
    return {
        "case": d["case"],
        "design_variable": d["design_variable"],
        "secondary": d["secondary"],
        "optimum": {
            "position": d["optimum_position"],
            "objective": d["optimum_objective"],
            "weight": d["weight"],
        },
        "weight_sweep": [
            {"weight": w, "position": x}
            for w, x in zip(d["weights"], d["optimum_positions"], strict=True)
        ],
        "curves": {
            "position": d["positions"],
            "bearing_positions_m": d["bearing_positions"],
            "mass_positions_m": d["mass_positions"],
            "unbalances_kg_m": d["unbalances"],
            "reactions_N": d["reactions"],
            "reaction_difference_N": d["reaction_difference"],
            "bending_measure_m2": d["bending_measure"],
            "max_deflection_m": d["max_deflection"],
            "max_stress_Pa": d["max_stress"],
            "first_frequency_hz": d["first_frequency"],
            "normalised_bending": d["normalised_bending"],
            "normalised_secondary": d["normalised_secondary"],
            "objective": d["objective"],
        },
    }


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
@format_option(("table", "json"))
def inline4(fmt: str, **options: Any) -> None:
    """Optimum unbalance-mass position of an inline-4 second-order shaft on end bearings."""
    from ..physics.balance_shaft import inline4_study

    o, c, kwargs = _study_setup(2, options)
    study = inline4_study(positions=np.linspace(0.0, 1.0, o.points), **kwargs)
    out = {
        "schema": SCHEMA,
        "input": _input_json(o.engine, c),
        **study_json(study),
        "paper": {
            "optimum_position": 0.67,
            "weight": 2.0,
            "source": "Kim (2018), Sect. 3.1, Fig. 7",
        },
    }
    require_finite(out)
    if fmt == "json":
        click.echo(json_text(out))
        return
    _echo_input(o.engine, c)
    _echo_study(study, max(1, o.points // 10))
    click.echo("Kim (2018), Fig. 7: 67 % with w = 2.")


@shaft.command()
@_study_options
@click.option(
    "--type",
    "rotor_type",
    type=click.Choice(["I", "II", "III", "all"]),
    default="all",
    show_default=True,
    help="Rotor type (order of masses and bearings).",
)
@click.option(
    "--hold",
    type=click.Choice(["couple", "unbalance"]),
    default="couple",
    show_default=True,
    help="Keep the couple (physical) or each mass's unbalance (paper).",
)
@click.option("--bearing-offset", default=None, help="Bearing-to-mass distance (default 0.1 L).")
@click.option(
    "--z-min",
    default="0.3",
    show_default=True,
    help="Smallest second-mass position z / L of the sweep (0 to below 1).",
)
@format_option(("table", "json"))
def inline3(
    rotor_type: str,
    hold: str,
    bearing_offset: str | None,
    z_min: str,
    fmt: str,
    **options: Any,
) -> None:
    """Optimum second-mass position of an inline-3 primary-couple shaft, per rotor type.

    --unbalance is the first moment of each mass when the two masses are the shaft
    length apart (Kim (2018), Eq. 12).
    """
    from ..physics.balance_shaft import ROTOR_TYPES, inline3_study

    o, c, kwargs = _study_setup(1, {**options, "bearing_offset": bearing_offset, "z_min": z_min})
    types = ROTOR_TYPES if rotor_type == "all" else (rotor_type,)
    studies = [
        inline3_study(
            cast("RotorType", t),
            positions=np.linspace(o.z_min, 1.0, o.points),
            bearing_offset=o.bearing_offset,
            hold=cast("HoldMode", hold),
            **kwargs,
        )
        for t in types
    ]
    out = {
        "schema": SCHEMA,
        "input": _input_json(o.engine, c),
        "case": "inline3",
        "hold": hold,
        "studies": {s.case.split("-")[1]: study_json(s) for s in studies},
        "paper": {
            "optimum_position": 0.69,
            "weight": 2.0,
            "rotor_type": "III",
            "source": "Kim (2018), Sect. 3.2, Fig. 9",
            "note": "not reproducible from the text: geometry not given, Eqs. 14-16 "
            "and 22-25 garbled (docs/references.md)",
        },
    }
    require_finite(out)
    if fmt == "json":
        click.echo(json_text(out))
        return
    _echo_input(o.engine, c)
    for s in studies:
        _echo_study(s, max(1, o.points // 10))
        click.echo("")
    echo_table(
        ["type", "model optimum %", "paper %"],
        [
            [
                s.case.split("-")[1],
                f"{100 * s.optimum_position:.1f}",
                "69 (type III, not reproducible)" if s.case.endswith("-III") else "-",
            ]
            for s in studies
        ],
    )


@shaft.command()
@click.option(
    "--bearing",
    "bearings",
    multiple=True,
    required=True,
    help="Bearing position from the shaft end (repeat, at least two).",
)
@click.option(
    "--mass",
    "masses",
    multiple=True,
    required=True,
    help="Unbalance-mass position (repeat; match with --unbalance).",
)
@click.option(
    "--unbalance",
    "unbalances",
    multiple=True,
    required=True,
    help='First moment m*e of each mass, e.g. "3.3 g*m" (one for all, or one per mass).',
)
@click.option(
    "--phase",
    "phases",
    multiple=True,
    help='Angular position of each mass on the shaft, e.g. "180 deg" (default 0).',
)
@click.option("--speed", required=True, help="Shaft speed of the evaluation.")
@click.option(
    "--max-speed", default=None, help="Maximum shaft speed for the checks (default --speed)."
)
@click.option(
    "--margin",
    default="0.25",
    show_default=True,
    help="Required separation of the first critical speed above the maximum speed.",
)
@click.option("--bearing-capacity", default=None, help='Allowed bearing load, e.g. "5 kN".')
@click.option("--deflection-limit", default=None, help='Allowed deflection, e.g. "50 um".')
@_section_options
@format_option(("table", "json"))
def check(
    bearings: tuple[str, ...],
    masses: tuple[str, ...],
    unbalances: tuple[str, ...],
    phases: tuple[str, ...],
    speed: str,
    max_speed: str | None,
    margin: str,
    bearing_capacity: str | None,
    deflection_limit: str | None,
    length: str,
    diameter: str,
    bore: str,
    modulus: str,
    density: str,
    poisson: str,
    unbalance_radius: str,
    bearing_stiffness: str | None,
    theory: str,
    fmt: str,
) -> None:
    """State variables and design checks of one shaft layout."""
    from ..physics.balance_shaft import BalanceShaft, design_checks, shaft_response
    from ..schema.settings import ShaftCheckOptions

    o = parse_settings(
        ShaftCheckOptions,
        {
            "bearing": list(bearings),
            "mass": list(masses),
            "unbalance": list(unbalances),
            "phase": list(phases),
            "speed": speed,
            "max_speed": max_speed,
            "margin": margin,
            "bearing_capacity": bearing_capacity,
            "deflection_limit": deflection_limit,
            "length": length,
            "diameter": diameter,
            "bore": bore,
            "modulus": modulus,
            "density": density,
            "poisson": poisson,
            "unbalance_radius": unbalance_radius,
            "bearing_stiffness": bearing_stiffness,
        },
    )
    assert o.speed is not None  # a required option
    u = o.unbalance * len(o.mass) if len(o.unbalance) == 1 else o.unbalance
    design = BalanceShaft(
        length=o.length,
        section=_section(o),
        bearing_positions=tuple(o.bearing),
        mass_positions=tuple(o.mass),
        unbalances=tuple(u),
        speed=o.speed,
        phases=tuple(o.phase),
        unbalance_radius=o.unbalance_radius,
        bearing_stiffness=o.bearing_stiffness,
    )
    response = shaft_response(design, theory=cast("BeamTheory", theory))
    checks = design_checks(
        response,
        max_speed=o.max_speed,
        critical_speed_margin=o.margin,
        bearing_capacity=o.bearing_capacity,
        deflection_limit=o.deflection_limit,
    )
    shaft_dict = keyed(design.to_dict(), SHAFT_KEYS)
    shaft_dict["section"] = keyed(shaft_dict["section"], SECTION_KEYS)
    out = {
        "schema": SCHEMA,
        "case": "check",
        "shaft": shaft_dict,
        "response": keyed(response.to_dict(), RESPONSE_KEYS),
        "checks": keyed(checks.to_dict(), CHECK_KEYS),
    }
    require_finite(out)
    if fmt == "json":
        click.echo(json_text(out))
        return
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
