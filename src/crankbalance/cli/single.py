"""CLI commands ``balance-factor``, ``rebalance`` and ``tolerance`` (single-cylinder tools).

Quantities are unit strings (``"282.12 g"``, ``"26.9 mm"``, ``"15200 rpm"``); balance factors
are plain numbers (0.28) or percentages (``"28%"``). Heavy imports stay inside the commands.
"""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import json_text
from ..units import format_quantity
from ._common import format_table, run_study

FORMATS = click.Choice(["table", "json"])


def _quantity(value: float, kind: str) -> str:
    return format_quantity(value, kind, digits=5)


def _gmm(value: float) -> str:
    return f"{value * 1e6:.4g} g*mm"


# ---------------------------------------------------------------------------------------
# balance-factor
# ---------------------------------------------------------------------------------------


@click.command("balance-factor")
@click.option("--reciprocating-mass", help="m_rec per cylinder, e.g. '282.12 g'.")
@click.option("--crank-radius", help="Crank throw radius (half the stroke), e.g. '26.9 mm'.")
@click.option(
    "--rotating-mass",
    help="m_rot: crankpin + big end + big-end bearing, e.g. "
    "'282.69 g' (with --engine: the model's throw mass, webs included, so "
    "--cw-mass/--cw-radius then mean the counterweights alone).",
)
@click.option("--cw-mass", help="m_cw: counterweights + webs, e.g. '2020.40 g'.")
@click.option("--cw-radius", help="r': CG radius of counterweights + webs, e.g. '6.16 mm'.")
@click.option(
    "--balance-factor",
    "balance_factor",
    help="f_b studied (0.5 or '50%'); "
    "default: the crank's own factor if its mass properties are given, else 0.5.",
)
@click.option("--target", help="f_b the bob-weight is sized for; default: the studied f_b.")
@click.option("--speed", help="Crank speed for the force study, e.g. '15200 rpm'.")
@click.option("--rod-length", help="Conrod length (exact kinematics), e.g. '105 mm'.")
@click.option("--offset", default=None, help="Wrist-pin path offset, e.g. '0 mm'.")
@click.option(
    "--kinematics",
    type=click.Choice(["exact", "series", "first-order"]),
    default=None,
    help="Piston kinematics; default exact with --rod-length, else first-order.",
)
@click.option(
    "--engine",
    "engine",
    default=None,
    help="Engine file or preset: take masses and geometry of one cylinder from it.",
)
@click.option("--cylinder", default=None, help="Cylinder of --engine (1-based). [default: 1]")
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def balance_factor(
    reciprocating_mass: str | None,
    crank_radius: str | None,
    rotating_mass: str | None,
    cw_mass: str | None,
    cw_radius: str | None,
    balance_factor: str | None,
    target: str | None,
    speed: str | None,
    rod_length: str | None,
    offset: str | None,
    kinematics: str | None,
    engine: str | None,
    cylinder: str | None,
    fmt: str,
) -> None:
    """Balance factor of a crank, its bob-weight, and the single-cylinder force study.

    The balance factor is the share of the reciprocating mass per cylinder balanced by the
    crank counterweight, on top of 100 % of the rotating mass.
    """
    from ..studies.single import BALANCE_FACTOR_NOTE

    values = {
        "reciprocating_mass": reciprocating_mass,
        "crank_radius": crank_radius,
        "rotating_mass": rotating_mass,
        "cw_mass": cw_mass,
        "cw_radius": cw_radius,
        "balance_factor": balance_factor,
        "target": target,
        "speed": speed,
        "rod_length": rod_length,
        "offset": offset,
        "kinematics": kinematics,
        "cylinder": cylinder,
    }
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
@click.option(
    "--parts",
    "parts_file",
    default=None,
    help="TOML file with old/new parts, counterweight, correction and tolerance.",
)
@click.option("--crank-radius", help="e.g. '26.9 mm'.")
@click.option("--cw-mass", help="m_cw (counterweights + webs), e.g. '2020.40 g'.")
@click.option("--cw-radius", help="r', e.g. '6.16 mm'.")
@click.option("--old-rotating-mass", help="m_rot with the old parts, e.g. '282.69 g'.")
@click.option("--old-reciprocating-mass", help="m_rec with the old parts, e.g. '282.12 g'.")
@click.option("--new-rotating-mass", help="m_rot with the new parts, e.g. '248.69 g'.")
@click.option("--new-reciprocating-mass", help="m_rec with the new parts, e.g. '261.50 g'.")
@click.option(
    "--target",
    "targets",
    multiple=True,
    help="Target balance factor (0.28, '28%' or 'factory'); repeatable.",
)
@click.option("--method", type=click.Choice(["face", "holes"]), default=None)
@click.option("--correction-radius", help="Radius of the correction, e.g. '40 mm'.")
@click.option("--face-area", help="Face area ground per web, e.g. '2157 mm^2'.")
@click.option("--face-orientation", type=click.Choice(["radial", "axial"]), default=None)
@click.option("--hole-diameter", help="Drill diameter, e.g. '8 mm'.")
@click.option("--holes", default=None, help="Holes per web (1 to 1000).")
@click.option("--hole-direction", type=click.Choice(["axial", "radial"]), default=None)
@click.option(
    "--web-thickness",
    help="Axial thickness of the web at the holes, e.g. '14 mm' (the deepest axial hole; "
    "not given: 10 drill diameters).",
)
@click.option(
    "--point-angle",
    help="Drill point included angle, e.g. '118 deg' (default 180 deg: flat-bottomed holes).",
)
@click.option(
    "--depth-to",
    type=click.Choice(["shoulder", "tip"]),
    default=None,
    help="What the depths of pointed holes are read to (required with --point-angle).",
)
@click.option("--density", help="Crank material density, default '7850 kg/m^3'.")
@click.option("--depth-resolution", help="Machining step, default '0.001 mm'.")
@click.option("--grade", help="ISO 21940-11 grade for the tolerance, e.g. G6.3.")
@click.option("--rotor-mass", help="Crank mass for the tolerance, e.g. '2.7 kg'.")
@click.option("--speed", help="Largest service speed for the tolerance, e.g. '15200 rpm'.")
@click.option(
    "--tolerance",
    "tolerance_text",
    help="Permissible residual, e.g. '10.69 g*mm' (instead of --grade/--rotor-mass/--speed).",
)
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def rebalance_command(
    parts_file: str | None,
    crank_radius: str | None,
    cw_mass: str | None,
    cw_radius: str | None,
    old_rotating_mass: str | None,
    old_reciprocating_mass: str | None,
    new_rotating_mass: str | None,
    new_reciprocating_mass: str | None,
    targets: tuple[str, ...],
    method: str | None,
    correction_radius: str | None,
    face_area: str | None,
    face_orientation: str | None,
    hole_diameter: str | None,
    holes: str | None,
    hole_direction: str | None,
    web_thickness: str | None,
    point_angle: str | None,
    depth_to: str | None,
    density: str | None,
    depth_resolution: str | None,
    grade: str | None,
    rotor_mass: str | None,
    speed: str | None,
    tolerance_text: str | None,
    fmt: str,
) -> None:
    """Rebalance a single-cylinder crank after new parts (Hoem and Røsholm (2016), Sec. 6.4, eight
    steps).

    Options override the values of the --parts file.
    """
    from ..studies.single import BALANCE_FACTOR_NOTE

    values = {
        "parts": parts_file,
        "crank_radius": crank_radius,
        "cw_mass": cw_mass,
        "cw_radius": cw_radius,
        "old_rotating_mass": old_rotating_mass,
        "old_reciprocating_mass": old_reciprocating_mass,
        "new_rotating_mass": new_rotating_mass,
        "new_reciprocating_mass": new_reciprocating_mass,
        "target": targets,
        "method": method,
        "correction_radius": correction_radius,
        "face_area": face_area,
        "face_orientation": face_orientation,
        "hole_diameter": hole_diameter,
        "holes": holes,
        "hole_direction": hole_direction,
        "web_thickness": web_thickness,
        "point_angle": point_angle,
        "depth_to": depth_to,
        "density": density,
        "depth_resolution": depth_resolution,
        "grade": grade,
        "rotor_mass": rotor_mass,
        "speed": speed,
        "tolerance": tolerance_text,
    }
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
                "residual [g*mm]",
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
@click.option("--grade", help="Balance quality grade, e.g. G6.3.")
@click.option("--rotor-mass", help="Rotor mass, e.g. '2.7 kg'.")
@click.option("--speed", help="Largest service speed, e.g. '15200 rpm'.")
@click.option("--residual", help="Measured residual unbalance, e.g. '7.39 g*mm' (verdict).")
@click.option("--bearing-a", help="Axial position of bearing A, e.g. '0 mm'.")
@click.option("--bearing-b", help="Axial position of bearing B, e.g. '120 mm'.")
@click.option("--center-of-mass", help="Axial position of the centre of mass, e.g. '60 mm'.")
@click.option("--plane-1", help="Axial position of correction plane I (default bearing A).")
@click.option("--plane-2", help="Axial position of correction plane II (default bearing B).")
@click.option("--list", "list_grades", is_flag=True, default=None, help="List the grades and exit.")
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def tolerance_command(fmt: str, engine: str | None, **values: Any) -> None:
    """ISO 21940-11 permissible residual unbalance U_per = 1000 G m / Omega [g*mm]."""
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
        ("permissible eccentricity", f"{u_per / result.rotor_mass * 1e6:.4g} um"),
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
