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

from ..errors import InputError
from ..format import json_text, keyed, text
from ._common import echo_table, format_option

if TYPE_CHECKING:
    from ..balance_shaft import HoldMode, RotorType, SecondaryMeasure
    from ..beam import BeamTheory

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
        click.option(
            "--poisson", type=float, default=0.3, show_default=True, help="Poisson's ratio."
        ),
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
            "--weight", type=float, default=2.0, show_default=True, help="w of the objective."
        ),
        click.option(
            "--weights",
            default=None,
            help="Comma-separated weights of the sweep (default 20 values 0.2 ... 4).",
        ),
        click.option(
            "--points",
            type=int,
            default=200,
            show_default=True,
            help="Design points along the shaft.",
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


#: Most design points of a sweep (each one is a beam solve and an FE eigenproblem).
MAX_POINTS = 5001


def _quantity(text: str, kind: str, field: str) -> float:
    """:func:`crankbalance.units.parse_quantity` that refuses ranges ('LOW..HIGH').

    The unit parser reads '300..200 mm' as the product 300. x .200 mm; no option of
    this command takes a range, so it is an error here, not a silent 60 mm.
    """
    from ..units import parse_quantity

    if ".." in text:
        raise InputError(field, text, "must be a single quantity, not a range")
    return parse_quantity(text, kind, field)


def _parse_section(
    length: str, diameter: str, bore: str, modulus: str, density: str, poisson: float
) -> tuple[float, Any]:
    from ..beam import ShaftSection

    length_m = _positive(_quantity(length, "length", "length"), "length", length)
    section = ShaftSection(
        outer_diameter=_positive(_quantity(diameter, "length", "diameter"), "diameter", diameter),
        inner_diameter=_quantity(bore, "length", "bore"),
        youngs_modulus=_positive(_quantity(modulus, "modulus", "modulus"), "modulus", modulus),
        density=_positive(_quantity(density, "density", "density"), "density", density),
        poisson_ratio=poisson,
    )
    return length_m, section


def _positive(value: float, name: str, text: str) -> float:
    if not value > 0:
        raise InputError(name, text, "must be greater than zero")
    return value


def _material(unbalance_radius: str, bearing_stiffness: str | None) -> tuple[float, float | None]:
    """Unbalance-mass radius [m] and bearing stiffness [N/m] (None: rigid)."""
    radius = _positive(
        _quantity(unbalance_radius, "length", "unbalance_radius"),
        "unbalance_radius",
        unbalance_radius,
    )
    if bearing_stiffness is None:
        return radius, None
    stiffness = _quantity(bearing_stiffness, "stiffness", "bearing_stiffness")
    return radius, _positive(stiffness, "bearing_stiffness", bearing_stiffness)


def _common(
    engine: str | None,
    order: int,
    length: float,
    unbalance: str | None,
    speed: str | None,
    unbalance_radius: str,
    bearing_stiffness: str | None,
    weights: str | None,
    points: int,
) -> dict[str, Any]:
    """Requirement (from --engine or --unbalance/--speed) and the sweep options, in SI."""
    import numpy as np

    if not 3 <= points <= MAX_POINTS:
        raise InputError("points", points, f"must be an integer from 3 to {MAX_POINTS}")
    radius, stiffness = _material(unbalance_radius, bearing_stiffness)
    if engine is not None:
        if unbalance is not None or speed is not None:
            raise InputError("--engine", engine, "give --engine or --unbalance/--speed, not both")
        from ..studies.requirements import shaft_requirement

        need = shaft_requirement(engine, order, length, radius)
        required, shaft_speed = need.unbalance, need.speed
    else:
        if unbalance is None or speed is None:
            raise InputError(
                "--unbalance" if unbalance is None else "--speed",
                None,
                "is required (or give --engine to take it from the balancing solver)",
            )
        required = _positive(_quantity(unbalance, "unbalance", "unbalance"), "unbalance", unbalance)
        shaft_speed = _positive(_quantity(speed, "speed", "speed"), "speed", speed)
    out: dict[str, Any] = {
        "unbalance": required,
        "speed": shaft_speed,
        "unbalance_radius": radius,
        "bearing_stiffness": stiffness,
        "weights": None,
    }
    if weights is not None:
        try:
            out["weights"] = np.array([float(w) for w in weights.split(",")])
        except ValueError:
            raise InputError(
                "weights", weights, "must be comma-separated numbers >= 0, e.g. 1,2,3"
            ) from None
    return out


def _study_setup(order: int, options: dict[str, Any]) -> tuple[dict[str, Any], Any, dict[str, Any]]:
    """Parse the options shared by ``inline4`` and ``inline3``.

    Returns the requirement block of :func:`_common`, the design-point count and the
    keyword arguments common to :func:`inline4_study` and :func:`inline3_study`
    (length and section included).
    """
    length_m, section = _parse_section(
        options["length"],
        options["diameter"],
        options["bore"],
        options["modulus"],
        options["density"],
        options["poisson"],
    )
    c = _common(
        options["engine"],
        order,
        length_m,
        options["unbalance"],
        options["speed"],
        options["unbalance_radius"],
        options["bearing_stiffness"],
        options["weights"],
        options["points"],
    )
    kwargs: dict[str, Any] = {
        "unbalance": c["unbalance"],
        "speed": c["speed"],
        "length": length_m,
        "section": section,
        "weight": options["weight"],
        "weights": c["weights"],
        "unbalance_radius": c["unbalance_radius"],
        "bearing_stiffness": c["bearing_stiffness"],
        "theory": cast("BeamTheory", options["theory"]),
    }
    if options["secondary"] is not None:
        kwargs["secondary"] = cast("SecondaryMeasure", options["secondary"])
    return c, options["points"], kwargs


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
    import numpy as np

    from ..balance_shaft import inline4_study

    c, points, kwargs = _study_setup(2, options)
    study = inline4_study(positions=np.linspace(0.0, 1.0, points), **kwargs)
    if fmt == "json":
        out = {
            "schema": SCHEMA,
            "input": _input_json(options["engine"], c),
            **study_json(study),
            "paper": {
                "optimum_position": 0.67,
                "weight": 2.0,
                "source": "Kim (2018), Sect. 3.1, Fig. 7",
            },
        }
        click.echo(json_text(out))
        return
    _echo_input(options["engine"], c)
    _echo_study(study, max(1, points // 10))
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
    type=float,
    default=0.3,
    show_default=True,
    help="Smallest second-mass position z / L of the sweep.",
)
@format_option(("table", "json"))
def inline3(
    rotor_type: str,
    hold: str,
    bearing_offset: str | None,
    z_min: float,
    fmt: str,
    **options: Any,
) -> None:
    """Optimum second-mass position of an inline-3 primary-couple shaft, per rotor type.

    --unbalance is the first moment of each mass when the two masses are the shaft
    length apart (Kim (2018), Eq. 12).
    """
    import numpy as np

    from ..balance_shaft import ROTOR_TYPES, inline3_study

    c, points, kwargs = _study_setup(1, options)
    if not (0.0 <= z_min < 1.0):
        raise InputError("z_min", z_min, "must lie in [0, 1)")
    offset = (
        None if bearing_offset is None else _quantity(bearing_offset, "length", "bearing_offset")
    )
    types = ROTOR_TYPES if rotor_type == "all" else (rotor_type,)
    studies = [
        inline3_study(
            cast("RotorType", t),
            positions=np.linspace(z_min, 1.0, points),
            bearing_offset=offset,
            hold=cast("HoldMode", hold),
            **kwargs,
        )
        for t in types
    ]
    if fmt == "json":
        out = {
            "schema": SCHEMA,
            "input": _input_json(options["engine"], c),
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
        click.echo(json_text(out))
        return
    _echo_input(options["engine"], c)
    for s in studies:
        _echo_study(s, max(1, points // 10))
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
    type=float,
    default=0.25,
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
    margin: float,
    bearing_capacity: str | None,
    deflection_limit: str | None,
    length: str,
    diameter: str,
    bore: str,
    modulus: str,
    density: str,
    poisson: float,
    unbalance_radius: str,
    bearing_stiffness: str | None,
    theory: str,
    fmt: str,
) -> None:
    """State variables and design checks of one shaft layout."""
    from ..balance_shaft import BalanceShaft, design_checks, shaft_response

    length_m, section = _parse_section(length, diameter, bore, modulus, density, poisson)
    radius, stiffness = _material(unbalance_radius, bearing_stiffness)
    shaft_speed = _positive(_quantity(speed, "speed", "speed"), "speed", speed)
    u = [_quantity(v, "unbalance", f"unbalances[{i}]") for i, v in enumerate(unbalances)]
    if len(u) == 1:
        u = u * len(masses)
    design = BalanceShaft(
        length=length_m,
        section=section,
        bearing_positions=tuple(
            _quantity(b, "length", f"bearing_positions[{i}]") for i, b in enumerate(bearings)
        ),
        mass_positions=tuple(
            _quantity(m, "length", f"mass_positions[{i}]") for i, m in enumerate(masses)
        ),
        unbalances=tuple(u),
        speed=shaft_speed,
        phases=tuple(_quantity(p, "angle", f"phases[{i}]") for i, p in enumerate(phases)),
        unbalance_radius=radius,
        bearing_stiffness=stiffness,
    )
    response = shaft_response(design, theory=cast("BeamTheory", theory))
    checks = design_checks(
        response,
        max_speed=None if max_speed is None else _quantity(max_speed, "speed", "max_speed"),
        critical_speed_margin=margin,
        bearing_capacity=None
        if bearing_capacity is None
        else _quantity(bearing_capacity, "force", "bearing_capacity"),
        deflection_limit=None
        if deflection_limit is None
        else _quantity(deflection_limit, "length", "deflection_limit"),
    )
    if fmt == "json":
        shaft_dict = keyed(design.to_dict(), SHAFT_KEYS)
        shaft_dict["section"] = keyed(shaft_dict["section"], SECTION_KEYS)
        click.echo(
            json_text(
                {
                    "schema": SCHEMA,
                    "case": "check",
                    "shaft": shaft_dict,
                    "response": keyed(response.to_dict(), RESPONSE_KEYS),
                    "checks": keyed(checks.to_dict(), CHECK_KEYS),
                }
            )
        )
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
