"""CLI commands ``balance-factor``, ``rebalance`` and ``tolerance`` (single-cylinder tools).

Quantities are unit strings (``"282.12 g"``, ``"26.9 mm"``, ``"15200 rpm"``); balance factors
are plain numbers (0.28) or percentages (``"28%"``). Heavy imports stay inside the commands.
"""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path
from typing import Any

import click

from ..errors import InputError, check_positive
from ..units import format_quantity as _format_quantity
from ..units import parse_quantity, registry
from ._common import format_table

FORMATS = click.Choice(["table", "json"])
BALANCE_FACTOR_NOTE = (
    "balance factor = share of the reciprocating mass per cylinder balanced by "
    "the crank counterweight, on top of 100 % of the rotating mass"
)


# ---------------------------------------------------------------------------------------
# parsing helpers
# ---------------------------------------------------------------------------------------


def _q(text: Any, kind: str, field: str) -> float | None:
    return None if text is None else parse_quantity(text, kind, field)


def parse_factor(value: Any, field: str) -> float:
    """A balance factor: ``0.28``, ``"0.28"`` or ``"28%"`` -> 0.28 (range checked later)."""
    if isinstance(value, bool):
        raise InputError(field, value, "must be a number such as 0.28 or a percentage '28%'")
    if isinstance(value, (int, float)):
        number = float(value)
    else:
        text = str(value).strip()
        scale = 1.0
        if text.endswith("%"):
            text, scale = text[:-1].strip(), 0.01
        try:
            number = float(text) * scale
        except ValueError:
            raise InputError(
                field, value, "must be a number such as 0.28 or a percentage '28%'"
            ) from None
    if not math.isfinite(number):
        raise InputError(field, value, "must be a finite number")
    return number


def parse_area(value: Any, field: str) -> float:
    """An area string (``"2157 mm^2"``) -> m^2."""
    if not isinstance(value, str):
        raise InputError(field, value, "must be an area with a unit, e.g. '2000 mm^2'")
    ureg = registry()
    try:
        quantity = ureg.Quantity(value.strip().replace("^", "**"))
        area = float(quantity.to("m**2").magnitude)
    except Exception:
        raise InputError(field, value, "must be an area with a unit, e.g. '2000 mm^2'") from None
    if not (area > 0 and math.isfinite(area)):
        raise InputError(field, value, "must be a positive area")
    return area


def _echo_json(payload: dict[str, Any]) -> None:
    from ..results import to_jsonable

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
@click.option(
    "--cylinder", default=1, show_default=True, type=int, help="Cylinder of --engine (1-based)."
)
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
    cylinder: int,
    fmt: str,
) -> None:
    """Balance factor of a crank, its bob-weight, and the single-cylinder force study.

    The balance factor is the share of the reciprocating mass per cylinder balanced by the
    crank counterweight, on top of 100 % of the rotating mass.
    """
    from .. import single_cylinder as sc

    m_rec = _q(reciprocating_mass, "mass", "reciprocating_mass")
    r = _q(crank_radius, "length", "crank_radius")
    m_rot = _q(rotating_mass, "mass", "rotating_mass")
    l_rod = _q(rod_length, "length", "rod_length")
    w = _q(speed, "speed", "speed")
    e = _q(offset, "length", "offset") or 0.0
    if engine is not None:
        eng = _engine_cylinder(engine, cylinder)
        m_rec = eng["reciprocating_mass"] if m_rec is None else m_rec
        r = eng["crank_radius"] if r is None else r
        l_rod = eng["rod_length"] if l_rod is None else l_rod
        w = eng["speed"] if w is None else w
        e = eng["offset"] if offset is None else e
        m_rot = eng["rotating_mass"] if m_rot is None else m_rot
    if m_rec is None:
        raise InputError("reciprocating_mass", None, "is required, e.g. '282.12 g'")
    if r is None:
        raise InputError("crank_radius", None, "is required, e.g. '26.9 mm'")
    check_positive("reciprocating_mass", m_rec)
    check_positive("crank_radius", r)
    if w is None:
        for name, value in (
            ("rod_length", rod_length),
            ("offset", offset),
            ("kinematics", kinematics),
        ):
            if value is not None:
                raise InputError(name, value, "only acts on the force study: give --speed too")
    if target is not None and m_rot is None:
        raise InputError("target", target, "sizes the bob-weight: give --rotating-mass too")
    given = [x is not None for x in (cw_mass, cw_radius)]
    mass_properties = None
    if any(given):
        if not all(given) or m_rot is None:
            raise InputError(
                "cw_mass",
                cw_mass,
                "the crank's balance factor needs --cw-mass, "
                "--cw-radius and --rotating-mass together",
            )
        m_cw = parse_quantity(cw_mass, "mass", "cw_mass")
        r_cw = parse_quantity(cw_radius, "length", "cw_radius")
        fb_crank = sc.balance_factor_from_mass_properties(m_cw, r_cw, r, m_rot, m_rec)
        mass_properties = {
            "counterweight_mass_kg": m_cw,
            "counterweight_radius_m": r_cw,
            "rotating_mass_kg": m_rot,
            "balance_factor": fb_crank,
            "counterweight_moment_kgm": m_cw * r_cw,
        }
    if balance_factor is not None:
        fb = sc.check_balance_factor(parse_factor(balance_factor, "balance_factor"))
    elif mass_properties is not None:
        fb = mass_properties["balance_factor"]
        low, high = sc.BALANCE_FACTOR_RANGE
        if not low <= fb <= high:
            raise InputError(
                "cw_mass",
                cw_mass,
                f"with --cw-radius and --rotating-mass gives the crank a balance "
                f"factor of {fb:.4f}, outside [{low:g}, {high:g}]; check the mass "
                "properties, or give --balance-factor for the study",
            )
    else:
        fb = 0.5
    fb_target = (
        fb if target is None else sc.check_balance_factor(parse_factor(target, "target"), "target")
    )
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
        "schema": "crankbalance.balance_factor/1",
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
    if fmt == "json":
        _echo_json(payload)
        return
    rows = [("balance factor studied", f"{fb:.4f}")]
    if mass_properties:
        rows.append(
            ("balance factor of the crank (Eq. 6.2)", f"{mass_properties['balance_factor']:.4f}")
        )
        rows.append(
            ("counterweight moment m_cw r'", _gmm(mass_properties["counterweight_moment_kgm"]))
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


def _engine_cylinder(engine: str, cylinder: int) -> dict[str, float]:
    """Single-cylinder data of one cylinder of an engine file (needs crankbalance.io/model)."""
    try:
        from ..io.engine_file import load_engine
        from ..studies.build import build_model
    except ImportError:
        raise InputError(
            "engine",
            engine,
            "engine files are not available in this "
            "version; give the masses and geometry as options",
        ) from None
    model = build_model(load_engine(engine))
    count = len(model.reciprocating_mass)
    if not 1 <= cylinder <= count:
        raise InputError("cylinder", cylinder, f"must lie between 1 and {count}")
    k = cylinder - 1
    throw = int(model.cylinder_throw[k])
    sharing = sum(1 for t in model.cylinder_throw if int(t) == throw)
    return {
        "reciprocating_mass": float(model.reciprocating_mass[k]),
        "crank_radius": float(model.crank_radius),
        "rod_length": float(model.rod_length),
        "speed": float(model.speed),
        "offset": float(model.offset),
        # rotating mass of the throw shared among the rods on its pin
        "rotating_mass": float(model.throw_rotating_mass[throw]) / sharing,
    }


# ---------------------------------------------------------------------------------------
# rebalance
# ---------------------------------------------------------------------------------------

_TOP_KEYS = {
    "name",
    "crank_radius",
    "targets",
    "counterweight",
    "old",
    "new",
    "correction",
    "tolerance",
}
_PART_KEYS = {"label", "rotating", "reciprocating", "rotating_mass", "reciprocating_mass"}
_CW_KEYS = {"mass", "cg_radius"}
_CORRECTION_KEYS = {
    "method",
    "radius",
    "area",
    "orientation",
    "diameter",
    "number",
    "direction",
    "webs",
    "density",
    "depth_resolution",
}
_TOL_KEYS = {"grade", "rotor_mass", "speed", "unbalance"}
#: [correction] keys that belong to one method only
_METHOD_KEYS = {"face": ("area", "orientation"), "holes": ("diameter", "number", "direction")}


def _check_keys(table: Any, allowed: set[str], where: str) -> dict[str, Any]:
    if not isinstance(table, dict):
        raise InputError(where, table, "must be a table")
    for key in table:
        if key not in allowed:
            raise InputError(
                f"{where}.{key}" if where else key,
                table[key],
                f"unknown key; allowed: {', '.join(sorted(allowed))}",
            )
    return table


def _masses(table: dict[str, Any], where: str) -> tuple[float, float, str, dict[str, Any]]:
    from ..single_cylinder import sum_parts

    _check_keys(table, _PART_KEYS, where)
    out: dict[str, Any] = {}
    totals = []
    for kind in ("rotating", "reciprocating"):
        if f"{kind}_mass" in table:
            totals.append(parse_quantity(table[f"{kind}_mass"], "mass", f"{where}.{kind}_mass"))
        elif kind in table:
            parts = {
                name: parse_quantity(text, "mass", f"{where}.{kind}.{name}")
                for name, text in _check_keys(
                    table[kind], set(table[kind]), f"{where}.{kind}"
                ).items()
            }
            out[kind] = parts
            totals.append(sum_parts(parts, f"{where}.{kind}"))
        else:
            raise InputError(
                f"{where}.{kind}", None, f"give [{where}.{kind}] part masses or {kind}_mass"
            )
    return totals[0], totals[1], str(table.get("label", where)), out


def load_rebalance_file(path: str | Path) -> dict[str, Any]:
    """Read a rebalancing TOML file into SI values (see ``examples/crf250r_rebalance.toml``)."""
    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError("parts", str(path), "file not found") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
        raise InputError("parts", str(path), f"is not valid TOML: {error}") from None
    _check_keys(data, _TOP_KEYS, "")
    out: dict[str, Any] = {"name": data.get("name", Path(path).stem)}
    if "crank_radius" in data:
        out["crank_radius"] = parse_quantity(data["crank_radius"], "length", "crank_radius")
    if "targets" in data:
        targets = data["targets"]
        out["targets"] = targets if isinstance(targets, list) else [targets]
    if "counterweight" in data:
        cw = _check_keys(data["counterweight"], _CW_KEYS, "counterweight")
        if "mass" in cw:
            out["cw_mass"] = parse_quantity(cw["mass"], "mass", "counterweight.mass")
        if "cg_radius" in cw:
            out["cw_radius"] = parse_quantity(cw["cg_radius"], "length", "counterweight.cg_radius")
    for side in ("old", "new"):
        if side in data:
            rot, rec, label, parts = _masses(data[side], side)
            out[side] = {
                "rotating_mass": rot,
                "reciprocating_mass": rec,
                "label": label,
                "parts": parts,
            }
    if "correction" in data:
        out["correction"] = dict(_check_keys(data["correction"], _CORRECTION_KEYS, "correction"))
    if "tolerance" in data:
        out["tolerance"] = dict(_check_keys(data["tolerance"], _TOL_KEYS, "tolerance"))
    return out


def build_correction(spec: dict[str, Any]) -> Any:
    """DrilledHoles or FaceRemoval from a ``[correction]`` table of unit strings."""
    from ..single_cylinder import STEEL_DENSITY, DrilledHoles, FaceRemoval

    method = spec.get("method", "face")
    if "radius" not in spec:
        raise InputError(
            "correction.radius", None, "is required: radius of the correction, e.g. '40 mm'"
        )
    radius = parse_quantity(spec["radius"], "length", "correction.radius")
    density = (
        parse_quantity(spec["density"], "density", "correction.density")
        if "density" in spec
        else STEEL_DENSITY
    )
    resolution = (
        parse_quantity(spec["depth_resolution"], "length", "correction.depth_resolution")
        if "depth_resolution" in spec
        else 1e-6
    )
    webs = spec.get("webs", 2)
    other = [key for name, keys in _METHOD_KEYS.items() if name != method for key in keys]
    for key in other:
        if key in spec:
            raise InputError(
                f"correction.{key}",
                spec[key],
                f"does not apply to method {method!r}; remove it or set the "
                "method (--method face|holes)",
            )
    if method == "face":
        if "area" not in spec:
            raise InputError(
                "correction.area", None, "is required for method 'face', e.g. '2000 mm^2'"
            )
        return FaceRemoval(
            area=parse_area(spec["area"], "correction.area"),
            radius=radius,
            orientation=spec.get("orientation", "radial"),
            webs=webs,
            density=density,
            depth_resolution=resolution,
        )
    if method == "holes":
        if "diameter" not in spec:
            raise InputError(
                "correction.diameter", None, "is required for method 'holes', e.g. '8 mm'"
            )
        return DrilledHoles(
            diameter=parse_quantity(spec["diameter"], "length", "correction.diameter"),
            radius=radius,
            number=spec.get("number", 1),
            direction=spec.get("direction", "axial"),
            webs=webs,
            density=density,
            depth_resolution=resolution,
        )
    raise InputError("correction.method", method, "must be 'face' or 'holes'")


def tolerance_from_spec(spec: dict[str, Any]) -> tuple[float, str]:
    """Permissible residual unbalance [kg m] from ``[tolerance]`` (grade or unbalance)."""
    from ..tolerance import balance_grade, permissible_unbalance

    if "unbalance" in spec:
        value = parse_quantity(spec["unbalance"], "unbalance", "tolerance.unbalance")
        return value, "given"
    missing = [k for k in ("grade", "rotor_mass", "speed") if k not in spec]
    if missing:
        raise InputError(
            f"tolerance.{missing[0]}",
            None,
            "give tolerance.unbalance, or grade, rotor_mass and speed",
        )
    grade = balance_grade(spec["grade"], "tolerance.grade")
    mass = parse_quantity(spec["rotor_mass"], "mass", "tolerance.rotor_mass")
    speed = parse_quantity(spec["speed"], "speed", "tolerance.speed")
    return permissible_unbalance(grade.name, mass, speed), (
        f"ISO 21940-11 {grade.name}, {spec['rotor_mass']}, {spec['speed']}"
    )


def run_rebalance(spec: dict[str, Any], targets: list[Any]) -> list[Any]:
    """Rebalance for each target (a number, a percentage or ``"factory"``)."""
    from ..single_cylinder import rebalance

    for key, hint in (
        ("crank_radius", "'26.9 mm'"),
        ("cw_mass", "'2020.40 g'"),
        ("cw_radius", "'6.16 mm'"),
    ):
        if key not in spec:
            raise InputError(key, None, f"is required, e.g. {hint}")
    for side in ("old", "new"):
        if side not in spec:
            raise InputError(
                side,
                None,
                f"the {side} parts are required ([{side}] table "
                f"or --{side}-rotating-mass/--{side}-reciprocating-mass)",
            )
    correction = build_correction(spec.get("correction", {}))
    tol, _source = tolerance_from_spec(spec.get("tolerance", {}))
    results = []
    for target in targets or ["factory"]:
        fb = (
            None
            if isinstance(target, str) and target.strip().lower() == "factory"
            else parse_factor(target, "target")
        )
        results.append(
            rebalance(
                spec["old"]["rotating_mass"],
                spec["old"]["reciprocating_mass"],
                spec["new"]["rotating_mass"],
                spec["new"]["reciprocating_mass"],
                spec["cw_mass"],
                spec["cw_radius"],
                spec["crank_radius"],
                correction,
                tol,
                target_balance_factor=fb,
            )
        )
    return results


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
@click.option("--holes", type=int, default=None, help="Holes per web.")
@click.option("--hole-direction", type=click.Choice(["axial", "radial"]), default=None)
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
    holes: int | None,
    hole_direction: str | None,
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
    spec: dict[str, Any] = load_rebalance_file(parts_file) if parts_file else {"name": "options"}
    if crank_radius:
        spec["crank_radius"] = parse_quantity(crank_radius, "length", "crank_radius")
    if cw_mass:
        spec["cw_mass"] = parse_quantity(cw_mass, "mass", "cw_mass")
    if cw_radius:
        spec["cw_radius"] = parse_quantity(cw_radius, "length", "cw_radius")
    for side, rot, rec in (
        ("old", old_rotating_mass, old_reciprocating_mass),
        ("new", new_rotating_mass, new_reciprocating_mass),
    ):
        entry = spec.setdefault(side, {"label": side}) if (rot or rec or side in spec) else None
        if entry is None:
            continue
        if rot:
            entry["rotating_mass"] = parse_quantity(rot, "mass", f"{side}_rotating_mass")
        if rec:
            entry["reciprocating_mass"] = parse_quantity(rec, "mass", f"{side}_reciprocating_mass")
        for key in ("rotating_mass", "reciprocating_mass"):
            if key not in entry:
                raise InputError(f"{side}_{key}", None, "is required (option or file)")
    corr = spec.setdefault("correction", {})
    if method is not None and method != corr.get("method", "face"):
        # --method switches the file's correction: its keys of the other method no longer apply
        for key in _METHOD_KEYS[corr.get("method", "face")]:
            corr.pop(key, None)
    for key, value in (
        ("method", method),
        ("radius", correction_radius),
        ("area", face_area),
        ("orientation", face_orientation),
        ("diameter", hole_diameter),
        ("number", holes),
        ("direction", hole_direction),
        ("density", density),
        ("depth_resolution", depth_resolution),
    ):
        if value is not None:
            corr[key] = value
    tol = spec.setdefault("tolerance", {})
    if tolerance_text:
        tol.clear()
        tol["unbalance"] = tolerance_text
    for key, value in (("grade", grade), ("rotor_mass", rotor_mass), ("speed", speed)):
        if value is not None:
            tol.pop("unbalance", None)
            tol[key] = value
    tolerance_value, tolerance_source = tolerance_from_spec(tol)
    target_list = list(targets) or spec.get("targets", ["factory"])
    results = run_rebalance(spec, target_list)
    if fmt == "json":
        _echo_json(
            {
                "schema": "crankbalance.rebalance/1",
                "name": spec["name"],
                "definition": BALANCE_FACTOR_NOTE,
                "tolerance": {"unbalance_kgm": tolerance_value, "source": tolerance_source},
                "old": spec["old"],
                "new": spec["new"],
                "cases": [res.to_dict() for res in results],
            }
        )
        return
    click.echo(f"{spec['name']}")
    click.echo(
        f"old parts: m_rot = {format_quantity(spec['old']['rotating_mass'], 'mass')}, "
        f"m_rec = {format_quantity(spec['old']['reciprocating_mass'], 'mass')}; "
        f"new parts: m_rot = {format_quantity(spec['new']['rotating_mass'], 'mass')}, "
        f"m_rec = {format_quantity(spec['new']['reciprocating_mass'], 'mass')}"
    )
    click.echo(f"tolerance: {_gmm(tolerance_value)} ({tolerance_source})")
    for res in results:
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
                "depth [mm]",
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


# ---------------------------------------------------------------------------------------
# tolerance
# ---------------------------------------------------------------------------------------


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
    from .. import tolerance as tl

    if list_grades:
        if fmt == "json":
            _echo_json(
                {"schema": "crankbalance.grades/1", "grades": [g.to_dict() for g in tl.GRADES]}
            )
        else:
            click.echo(
                format_table(
                    ("grade", "example rotor types"), [(g.name, g.examples) for g in tl.GRADES]
                )
            )
        return
    for name, value in (("grade", grade), ("rotor_mass", rotor_mass), ("speed", speed)):
        if value is None:
            raise InputError(name, None, "is required (or use --list)")
    item = tl.balance_grade(grade)  # type: ignore[arg-type]
    mass = parse_quantity(rotor_mass, "mass", "rotor_mass")
    omega = parse_quantity(speed, "speed", "speed")
    u_per = tl.permissible_unbalance(item.name, mass, omega)
    allocation = None
    positions = [bearing_a, bearing_b, center_of_mass]
    if any(p is not None for p in positions + [plane_1, plane_2]):
        if any(p is None for p in positions):
            raise InputError(
                "bearing_a",
                bearing_a,
                "the split between planes needs --bearing-a, --bearing-b and --center-of-mass",
            )
        allocation = tl.allocate_to_planes(
            u_per,
            parse_quantity(bearing_a, "length", "bearing_a"),
            parse_quantity(bearing_b, "length", "bearing_b"),
            parse_quantity(center_of_mass, "length", "center_of_mass"),
            _q(plane_1, "length", "plane_1"),
            _q(plane_2, "length", "plane_2"),
        )
    verdict = None
    if residual is not None:
        verdict = tl.check_residual(parse_quantity(residual, "unbalance", "residual"), u_per)
    if fmt == "json":
        _echo_json(
            {
                "schema": "crankbalance.tolerance/1",
                "grade": item.to_dict(),
                "rotor_mass_kg": mass,
                "speed_rad_s": omega,
                "permissible_unbalance_kgm": u_per,
                "permissible_unbalance_gmm": u_per * 1e6,
                "eccentricity_m": u_per / mass,
                "planes": None if allocation is None else allocation.to_dict(),
                "verdict": None if verdict is None else verdict.to_dict(),
            }
        )
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
