"""CLI commands ``balance-factor``, ``rebalance`` and ``tolerance`` (single-cylinder tools).

Quantities are unit strings (``"282.12 g"``, ``"26.9 mm"``, ``"15200 rpm"``); balance factors
are plain numbers (0.28) or percentages (``"28%"``). Heavy imports stay inside the commands.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import click

from ..errors import InputError
from ..results import require_finite, to_jsonable
from ..units import format_quantity as _format_quantity
from ._common import format_table, option_name, parse_settings, refuse_unused

FORMATS = click.Choice(["table", "json"])
BALANCE_FACTOR_NOTE = (
    "balance factor = share of the reciprocating mass per cylinder balanced by "
    "the crank counterweight, on top of 100 % of the rotating mass"
)


# ---------------------------------------------------------------------------------------
# parsing helpers
# ---------------------------------------------------------------------------------------


def _echo_json(payload: dict[str, Any]) -> None:
    click.echo(json.dumps(to_jsonable(payload), indent=2))


def format_quantity(value: float, kind: str) -> str:
    return _format_quantity(value, kind, digits=5)


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
@click.option("--cylinder", default="1", show_default=True, help="Cylinder of --engine (1-based).")
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
    cylinder: str,
    fmt: str,
) -> None:
    """Balance factor of a crank, its bob-weight, and the single-cylinder force study.

    The balance factor is the share of the reciprocating mass per cylinder balanced by the
    crank counterweight, on top of 100 % of the rotating mass.
    """
    from ..physics import single_cylinder as sc
    from ..schema.settings import BalanceFactorOptions

    o = parse_settings(
        BalanceFactorOptions,
        {
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
            "engine": engine,
            "cylinder": cylinder,
        },
    )
    refuse_unused({"cylinder": engine is not None}, "only acts with --engine")
    m_rec, r, m_rot, l_rod, w = (
        o.reciprocating_mass,
        o.crank_radius,
        o.rotating_mass,
        o.rod_length,
        o.speed,
    )
    e = o.offset or 0.0
    if engine is not None:
        from ..io.engine_file import load_engine
        from ..studies.build import build_model
        from ..studies.cylinder import cylinder_of

        one = cylinder_of(build_model(load_engine(engine)), o.cylinder, "--cylinder")
        m_rec = one.reciprocating_mass if m_rec is None else m_rec
        r = one.crank_radius if r is None else r
        l_rod = one.rod_length if l_rod is None else l_rod
        w = one.speed if w is None else w
        e = one.offset if offset is None else e
        m_rot = one.rotating_mass if m_rot is None else m_rot
    if m_rec is None:
        raise InputError("--reciprocating-mass", None, "is required, e.g. '282.12 g'")
    if r is None:
        raise InputError("--crank-radius", None, "is required, e.g. '26.9 mm'")
    if w is None:
        refuse_unused(
            {name: False for name in ("rod_length", "offset", "kinematics")},
            "only acts on the force study: give --speed too",
        )
    refuse_unused(
        {"rod_length": kinematics != "first-order"},
        "the first-order kinematics does not use the conrod length",
    )
    if target is not None and m_rot is None:
        raise InputError("--target", target, "sizes the bob-weight: give --rotating-mass too")
    mass_properties = None
    if o.cw_mass is not None or o.cw_radius is not None:
        if o.cw_mass is None or o.cw_radius is None or m_rot is None:
            raise InputError(
                "--cw-mass",
                cw_mass,
                "the crank's balance factor needs --cw-mass, "
                "--cw-radius and --rotating-mass together",
            )
        m_cw, r_cw = o.cw_mass, o.cw_radius
        fb_crank = sc.balance_factor_from_mass_properties(m_cw, r_cw, r, m_rot, m_rec)
        mass_properties = {
            "counterweight_mass_kg": m_cw,
            "counterweight_radius_m": r_cw,
            "rotating_mass_kg": m_rot,
            "balance_factor": fb_crank,
            "counterweight_moment_kg_m": m_cw * r_cw,
        }
    if o.balance_factor is not None:
        fb = o.balance_factor
    elif mass_properties is not None:
        fb = mass_properties["balance_factor"]
        low, high = sc.BALANCE_FACTOR_RANGE
        if not low <= fb <= high:
            raise InputError(
                "--cw-mass",
                cw_mass,
                f"with --cw-radius and --rotating-mass gives the crank a balance "
                f"factor of {fb:.4f}, outside [{low:g}, {high:g}]; check the mass "
                "properties, or give --balance-factor for the study",
            )
    else:
        fb = 0.5
    fb_target = fb if o.target is None else o.target
    bob = None
    if m_rot is not None:
        bob = sc.bob_weight(m_rot, m_rec, fb_target)
    study = None
    if w is not None:
        model = kinematics or ("exact" if l_rod is not None else "first-order")
        study = sc.balance_factor_study(
            m_rec,
            r,
            w,
            fb,
            rod_length=l_rod,
            offset=e,
            model=model,  # type: ignore[arg-type]
        )
    payload: dict[str, Any] = {
        "schema": "crankbalance.balance_factor/2",
        "definition": BALANCE_FACTOR_NOTE,
        "balance_factor": fb,
        "reciprocating_mass_kg": m_rec,
        "crank_radius_m": r,
        "mass_properties": mass_properties,
        "bob_weight": None if bob is None else {"target_balance_factor": fb_target, "mass_kg": bob},
        "study": None
        if study is None
        else {
            "model": study.model,
            "speed_rad_s": w,
            "primary_force_N": study.primary_force,
            "in_line_amplitude_N": study.in_line_amplitude,
            "transverse_amplitude_N": study.transverse_amplitude,
            "peak_resultant_N": study.peak_resultant,
            "optimum_balance_factor": study.optimum_balance_factor,
            "optimum_peak_resultant_N": study.optimum_peak_resultant,
            "sweep": [
                {"balance_factor": f, "peak_resultant_N": p}
                for f, p in zip(study.sweep_balance_factor, study.sweep_peak_resultant, strict=True)
            ],
            "curve": {
                "crank_angle_deg": study.crank_angle * 180 / math.pi,
                "in_line_N": study.in_line,
                "transverse_N": study.transverse,
            },
        },
    }
    require_finite(payload)
    if fmt == "json":
        _echo_json(payload)
        return
    rows = [("balance factor studied", f"{fb:.4f}")]
    if mass_properties:
        rows.append(
            ("balance factor of the crank (Eq. 6.2)", f"{mass_properties['balance_factor']:.4f}")
        )
        rows.append(
            ("counterweight moment m_cw r'", _gmm(mass_properties["counterweight_moment_kg_m"]))
        )
    if bob is not None:
        rows.append((f"bob-weight for f_b = {fb_target:.4f}", format_quantity(bob, "mass")))
    if study is not None:
        rows += [
            ("kinematics", study.model),
            ("primary force P", format_quantity(study.primary_force, "force")),
            ("in-line amplitude", format_quantity(study.in_line_amplitude, "force")),
            ("transverse amplitude", format_quantity(study.transverse_amplitude, "force")),
            ("peak resultant", format_quantity(study.peak_resultant, "force")),
            ("optimum balance factor", f"{study.optimum_balance_factor:.4f}"),
            ("peak resultant at optimum", format_quantity(study.optimum_peak_resultant, "force")),
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
    from ..io.rebalance_file import METHOD_KEYS, read_rebalance_data, rebalance_file_from_dict
    from ..schema.settings import RebalancePartsOptions
    from ..studies.rebalance import rebalance_parts

    # the typed values in their physical ranges; the file's schema then checks how they
    # combine with the file
    typed = parse_settings(
        RebalancePartsOptions,
        {
            "crank_radius": crank_radius,
            "cw_mass": cw_mass,
            "cw_radius": cw_radius,
            "old_rotating_mass": old_rotating_mass,
            "old_reciprocating_mass": old_reciprocating_mass,
            "new_rotating_mass": new_rotating_mass,
            "new_reciprocating_mass": new_reciprocating_mass,
            "target": list(targets),
            "correction_radius": correction_radius,
            "face_area": face_area,
            "hole_diameter": hole_diameter,
            "holes": holes,
            "point_angle": point_angle,
            "depth_to": depth_to,
            "web_thickness": web_thickness,
            "density": density,
            "depth_resolution": depth_resolution,
            "grade": grade,
            "rotor_mass": rotor_mass,
            "speed": speed,
            "tolerance": tolerance_text,
        },
    )

    data: dict[str, Any] = {}
    source = "parts"
    if parts_file:
        data = read_rebalance_data(parts_file)
        data.setdefault("name", Path(parts_file).stem)
        source = str(parts_file)
        rebalance_file_from_dict(data, source)  # the file's own errors name its keys
    else:
        data["name"] = "options"
    # options override the file: set them at their key of the file, remember the option
    origin: dict[str, str] = {}

    def put(key: str, value: Any, option: str) -> None:
        if value is None:
            return
        *tables, last = key.split(".")
        table = data
        for name in tables:
            table = table.setdefault(name, {})
        table[last] = value
        origin[key] = option_name(option)

    put("crank_radius", crank_radius, "crank_radius")
    put("counterweight.mass", cw_mass, "cw_mass")
    put("counterweight.cg_radius", cw_radius, "cw_radius")
    for side, rot, rec in (
        ("old", old_rotating_mass, old_reciprocating_mass),
        ("new", new_rotating_mass, new_reciprocating_mass),
    ):
        for kind, value in (("rotating", rot), ("reciprocating", rec)):
            if value is not None:
                data.get(side, {}).pop(kind, None)  # the total replaces the file's parts
                put(f"{side}.{kind}_mass", value, f"{side}_{kind}_mass")
    if targets:
        put("targets", list(targets), "target")
    corr = data.get("correction", {})
    if method is not None and method != corr.get("method", "face"):
        # --method switches the file's correction: its keys of the other method no longer apply
        for key in METHOD_KEYS[corr.get("method", "face")]:
            corr.pop(key, None)
    corrections: tuple[tuple[str, Any, str], ...] = (
        ("method", method, "method"),
        ("radius", correction_radius, "correction_radius"),
        ("area", face_area, "face_area"),
        ("orientation", face_orientation, "face_orientation"),
        ("diameter", hole_diameter, "hole_diameter"),
        ("number", typed.holes, "holes"),
        ("direction", hole_direction, "hole_direction"),
        ("point_angle", point_angle, "point_angle"),
        ("depth_to", depth_to, "depth_to"),
        ("web_thickness", web_thickness, "web_thickness"),
        ("density", density, "density"),
        ("depth_resolution", depth_resolution, "depth_resolution"),
    )
    for key, given, option in corrections:
        put(f"correction.{key}", given, option)
    if tolerance_text is not None:
        if grade is not None or rotor_mass is not None or speed is not None:
            raise InputError(
                "--tolerance",
                tolerance_text,
                "give either --tolerance or --grade with --rotor-mass and --speed",
            )
        data["tolerance"] = {}
        put("tolerance.unbalance", tolerance_text, "tolerance")
    for key, text in (("grade", grade), ("rotor_mass", rotor_mass), ("speed", speed)):
        if text is not None:
            data.get("tolerance", {}).pop("unbalance", None)
            put(f"tolerance.{key}", text, key)
    try:
        parts = rebalance_file_from_dict(data, source)
        _drill_point_used(parts, typed, point_angle, depth_to)
        study = rebalance_parts(parts, names=_plan_names(parts, origin))
    except InputError as error:
        named = origin.get(error.field.split("[")[0])
        if named is None:
            raise
        raise InputError(named, error.value, error.allowed) from None
    payload = {
        "schema": "crankbalance.rebalance/2",
        "name": study.name,
        "definition": BALANCE_FACTOR_NOTE,
        "tolerance": {
            "unbalance_kg_m": study.tolerance,
            "source": study.tolerance_source,
        },
        "old": _parts_json(study.old),
        "new": _parts_json(study.new),
        "cases": [_case_json(res) for res in study.cases],
    }
    require_finite(payload)
    if fmt == "json":
        _echo_json(payload)
        return
    click.echo(study.name)
    click.echo(
        f"old parts: m_rot = {format_quantity(study.old.rotating_mass, 'mass')}, "
        f"m_rec = {format_quantity(study.old.reciprocating_mass, 'mass')}; "
        f"new parts: m_rot = {format_quantity(study.new.rotating_mass, 'mass')}, "
        f"m_rec = {format_quantity(study.new.reciprocating_mass, 'mass')}"
    )
    click.echo(f"tolerance: {_gmm(study.tolerance)} ({study.tolerance_source})")
    for res in study.cases:
        click.echo("")
        click.echo(
            f"target f_b = {res.target_balance_factor:.4f} (crank now "
            f"{res.original_balance_factor:.4f}): unbalance to correct "
            f"{_gmm(res.unbalance)}, bob-weight "
            f"{format_quantity(res.bob_weight, 'mass')}"
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


def _plan_names(parts: Any, origin: dict[str, str]) -> dict[str, str]:
    """How the messages of a correction plan name its quantities: the option that set a
    key, the file's key, or both when neither gave it (``--holes or correction.number``)."""
    names = dict(origin)
    correction = parts.correction
    for key, option in (
        ("correction.number", "--holes"),
        ("correction.web_thickness", "--web-thickness"),
    ):
        given = correction is not None and getattr(correction, key.split(".")[1]) is not None
        if key not in names and not given:
            names[key] = f"{option} or {key}"
    return names


def _drill_point_used(
    parts: Any, typed: Any, point_angle: str | None, depth_to: str | None
) -> None:
    """Refuse the drill-point options where they would be ignored or leave the depth
    unstated: ``--depth-to`` for flat-bottomed holes (one depth, nothing to read it to),
    ``--point-angle`` below 180 deg without the depth reference (the point changes the depth
    by a third to two thirds of its height, docs/balance_shop.md). With the face method the
    file's schema refuses both (``METHOD_KEYS``)."""
    correction = parts.correction
    if correction is None or correction.method != "holes":
        if point_angle is not None or depth_to is not None:
            option = "--point-angle" if point_angle is not None else "--depth-to"
            raise InputError(
                option,
                point_angle if point_angle is not None else depth_to,
                "applies to drilled holes only: give --method holes (or method = "
                '"holes" in the [correction] of the parts file)',
            )
        return
    pointed = correction.point_angle is not None and correction.point_angle < math.pi
    if depth_to is not None and not pointed:
        raise InputError(
            "--depth-to",
            depth_to,
            "applies to pointed holes only: give --point-angle below 180 deg (flat-bottomed "
            "holes have one depth)",
        )
    if typed.point_angle is not None and pointed and correction.depth_to is None:
        raise InputError(
            "--point-angle",
            point_angle,
            "needs --depth-to shoulder|tip: what the depths are read to (with a point the "
            "depth to the tip is the depth to the shoulder plus the point's height)",
        )


def _parts_json(side: Any) -> dict[str, Any]:
    return {
        "label": side.label,
        "rotating_mass_kg": side.rotating_mass,
        "reciprocating_mass_kg": side.reciprocating_mass,
        "rotating_parts_kg": side.rotating_parts,
        "reciprocating_parts_kg": side.reciprocating_parts,
    }


def _depth_header(correction: Any) -> str:
    """The depth column's header: what the depth of pointed holes is read to."""
    if correction.kind == "holes" and correction.point_angle != math.pi:
        return f"depth to {correction.depth_to} [mm]"
    return "depth [mm]"


def _correction_json(correction: Any) -> dict[str, Any]:
    out: dict[str, Any] = {"kind": correction.kind, "radius_m": correction.radius}
    if correction.kind == "face":
        out |= {"area_m2": correction.area, "orientation": correction.orientation}
    else:
        out |= {
            "diameter_m": correction.diameter,
            "number": correction.number,
            "direction": correction.direction,
        }
        if correction.point_angle != math.pi:  # flat-bottomed holes: no point to state
            out |= {
                "point_angle_deg": math.degrees(correction.point_angle),
                "depth_to": correction.depth_to,
            }
        if correction.web_thickness is not None:
            out["web_thickness_m"] = correction.web_thickness
    return out | {
        "webs": correction.webs,
        "density_kg_m3": correction.density,
        "depth_resolution_m": correction.depth_resolution,
    }


def _case_json(res: Any) -> dict[str, Any]:
    """One rebalancing result with the SI unit in every key that carries one."""
    return {
        "original_balance_factor": res.original_balance_factor,
        "target_balance_factor": res.target_balance_factor,
        "original_moment_kg_m": res.original_moment,
        "required_moment_kg_m": res.required_moment,
        "unbalance_kg_m": res.unbalance,
        "correction": _correction_json(res.correction),
        "iterations": [
            {
                "iteration": it.iteration,
                "unbalance_to_correct_kg_m": it.unbalance_to_correct,
                "correction_radius_m": it.correction_radius,
                "correction_mass_kg": it.correction_mass,
                "depth_m": it.depth,
                "removed_mass_kg": it.removed_mass,
                "removed_unbalance_kg_m": it.removed_unbalance,
                "residual_kg_m": it.residual,
                "within_tolerance": it.within_tolerance,
            }
            for it in res.iterations
        ],
        "residual_kg_m": res.residual,
        "achieved_balance_factor": res.achieved_balance_factor,
        "tolerance_kg_m": res.tolerance,
        "passed": res.passed,
        "status": res.status,
        "bob_weight_kg": res.bob_weight,
    }


# ---------------------------------------------------------------------------------------
# tolerance
# ---------------------------------------------------------------------------------------


#: the options of the split between the correction planes
PLANE_OPTIONS = ("bearing_a", "bearing_b", "center_of_mass", "plane_1", "plane_2")


@click.command("tolerance")
@click.option("--grade", help="Balance quality grade, e.g. G6.3.")
@click.option("--rotor-mass", help="Rotor mass, e.g. '2.7 kg'.")
@click.option("--speed", help="Largest service speed, e.g. '15200 rpm'.")
@click.option("--residual", help="Measured residual unbalance, e.g. '7.39 g*mm' (verdict).")
@click.option("--bearing-a", help="Axial position of bearing A, e.g. '0 mm'.")
@click.option("--bearing-b", help="Axial position of bearing B, e.g. '120 mm'.")
@click.option("--center-of-mass", help="Axial position of the centre of mass, e.g. '60 mm'.")
@click.option("--plane-1", help="Axial position of correction plane I (default bearing A).")
@click.option("--plane-2", help="Axial position of correction plane II (default bearing B).")
@click.option("--list", "list_grades", is_flag=True, help="List the grades and exit.")
@click.option("--format", "fmt", type=FORMATS, default="table", show_default=True)
def tolerance_command(
    grade: str | None,
    rotor_mass: str | None,
    speed: str | None,
    residual: str | None,
    bearing_a: str | None,
    bearing_b: str | None,
    center_of_mass: str | None,
    plane_1: str | None,
    plane_2: str | None,
    list_grades: bool,
    fmt: str,
) -> None:
    """ISO 21940-11 permissible residual unbalance U_per = 1000 G m / Omega [g*mm]."""
    from ..physics import tolerance as tl
    from ..schema.settings import ToleranceOptions

    o = parse_settings(
        ToleranceOptions,
        {
            "grade": grade,
            "rotor_mass": rotor_mass,
            "speed": speed,
            "residual": residual,
            "bearing_a": bearing_a,
            "bearing_b": bearing_b,
            "center_of_mass": center_of_mass,
            "plane_1": plane_1,
            "plane_2": plane_2,
        },
    )
    if list_grades:
        refuse_unused(
            {name: False for name in ToleranceOptions.FIELDS},
            "does not act with --list (which lists the grades only)",
        )
        if fmt == "json":
            _echo_json(
                {"schema": "crankbalance.grades/2", "grades": [_grade_json(g) for g in tl.GRADES]}
            )
        else:
            click.echo(
                format_table(
                    ("grade", "example rotor types"), [(g.name, g.examples) for g in tl.GRADES]
                )
            )
        return
    if o.grade is None or o.rotor_mass is None or o.speed is None:
        missing = next(n for n in ("grade", "rotor_mass", "speed") if getattr(o, n) is None)
        raise InputError(option_name(missing), None, "is required (or use --list)")
    item = tl.balance_grade(o.grade)
    mass, omega = o.rotor_mass, o.speed
    u_per = tl.permissible_unbalance(item.name, mass, omega)
    allocation = None
    if any(getattr(o, n) is not None for n in PLANE_OPTIONS):
        if o.bearing_a is None or o.bearing_b is None or o.center_of_mass is None:
            raise InputError(
                "--bearing-a",
                bearing_a,
                "the split between planes needs --bearing-a, --bearing-b and --center-of-mass",
            )
        allocation = tl.allocate_to_planes(
            u_per, o.bearing_a, o.bearing_b, o.center_of_mass, o.plane_1, o.plane_2
        )
    verdict = None if o.residual is None else tl.check_residual(o.residual, u_per)
    payload = {
        "schema": "crankbalance.tolerance/2",
        "grade": _grade_json(item),
        "rotor_mass_kg": mass,
        "speed_rad_s": omega,
        "permissible_unbalance_kg_m": u_per,
        "eccentricity_m": u_per / mass,
        "planes": None
        if allocation is None
        else {
            "total_kg_m": allocation.total,
            "bearing_a_kg_m": allocation.bearing_a,
            "bearing_b_kg_m": allocation.bearing_b,
            "plane_1_kg_m": allocation.plane_1,
            "plane_2_kg_m": allocation.plane_2,
            "share_a": allocation.share_a,
            "rule": allocation.rule,
        },
        "verdict": None
        if verdict is None
        else {
            "residual_kg_m": verdict.residual,
            "permissible_kg_m": verdict.permissible,
            "ratio": verdict.ratio,
            "passed": verdict.passed,
        },
    }
    require_finite(payload)
    if fmt == "json":
        _echo_json(payload)
        return
    rows = [
        ("grade", item.name),
        ("permissible residual U_per", _gmm(u_per)),
        ("permissible eccentricity", f"{u_per / mass * 1e6:.4g} um"),
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


def _grade_json(grade: Any) -> dict[str, Any]:
    return {
        "name": grade.name,
        "value_m_s": grade.value,
        "examples": grade.examples,
        "crank_drive": grade.crank_drive,
    }
