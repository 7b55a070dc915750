"""The single-cylinder studies of the registry (Hoem and Røsholm 2016): the balance factor of
a crank with its bob-weight and force study (``balance-factor``), the rebalancing of a crank
after new parts (``rebalance``) and the ISO 21940-11 permissible residual unbalance
(``tolerance``).

Each function takes its settings model of :mod:`crankbalance.schema.settings` (and for
``balance-factor`` and ``tolerance`` an optional engine) and returns one result whose
``to_dict()`` is the JSON contract of docs/json.md; the command line prints it, the API
answers it, the web application shows it.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import InputError
from ..physics import single_cylinder as sc
from ..physics import tolerance as tl
from ..records import record
from ..results import ResultMixin, number, require_finite, to_jsonable
from ..schema.settings import (
    BalanceFactorOptions,
    RebalancePartsOptions,
    ToleranceOptions,
    given,
)
from .engine import EngineLike, as_model
from .rebalance import RebalanceStudy, rebalance_parts

if TYPE_CHECKING:  # pragma: no cover
    from ..io.rebalance_file import RebalanceFile
    from ..physics import rebalancing as rb
    from ..physics.kinematics import KinematicsModel
    from .rebalance import PartsSummary

#: what a balance factor is, as every single-cylinder output says it
BALANCE_FACTOR_NOTE = (
    "balance factor = share of the reciprocating mass per cylinder balanced by "
    "the crank counterweight, on top of 100 % of the rotating mass"
)
BALANCE_FACTOR_SCHEMA = "crankbalance.balance_factor/2"
REBALANCE_SCHEMA = "crankbalance.rebalance/2"
TOLERANCE_SCHEMA = "crankbalance.tolerance/2"
GRADES_SCHEMA = "crankbalance.grades/2"


def _checked(payload: dict[str, Any]) -> dict[str, Any]:
    """A JSON payload, checked finite (:func:`crankbalance.results.to_jsonable`)."""
    out = to_jsonable(payload)
    assert isinstance(out, dict)
    return out


# ---------------------------------------------------------------------------------------
# balance-factor
# ---------------------------------------------------------------------------------------


@record(repr=False)
class BalanceFactorResult(ResultMixin):
    """The balance factor of a crank, its bob-weight and the single-cylinder force study.

    Attributes
    ----------
    balance_factor : float
        The balance factor studied [-].
    reciprocating_mass, crank_radius : float
        [kg], [m].
    mass_properties : dict, optional
        The crank's counterweight (mass [kg], CG radius [m]), rotating mass [kg] and the
        balance factor they give (Eq. 6.2), when given.
    target : float
        The balance factor the bob-weight is sized for [-].
    bob_weight : float, optional
        [kg], with a rotating mass.
    speed : float, optional
        Crank speed of the force study [rad/s].
    study : BalanceFactorStudy, optional
        The force study (with a speed).
    """

    balance_factor: float
    reciprocating_mass: float
    crank_radius: float
    mass_properties: dict[str, float] | None
    target: float
    bob_weight: float | None
    speed: float | None
    study: sc.BalanceFactorStudy | None

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.balance_factor/2``."""
        study = self.study
        return _checked(
            {
                "schema": BALANCE_FACTOR_SCHEMA,
                "definition": BALANCE_FACTOR_NOTE,
                "balance_factor": self.balance_factor,
                "reciprocating_mass_kg": self.reciprocating_mass,
                "crank_radius_m": self.crank_radius,
                "mass_properties": self.mass_properties,
                "bob_weight": None
                if self.bob_weight is None
                else {"target_balance_factor": self.target, "mass_kg": self.bob_weight},
                "study": None
                if study is None
                else {
                    "model": study.model,
                    "speed_rad_s": self.speed,
                    "primary_force_N": study.primary_force,
                    "in_line_amplitude_N": study.in_line_amplitude,
                    "transverse_amplitude_N": study.transverse_amplitude,
                    "peak_resultant_N": study.peak_resultant,
                    "optimum_balance_factor": study.optimum_balance_factor,
                    "optimum_peak_resultant_N": study.optimum_peak_resultant,
                    "sweep": [
                        {"balance_factor": f, "peak_resultant_N": p}
                        for f, p in zip(
                            study.sweep_balance_factor, study.sweep_peak_resultant, strict=True
                        )
                    ],
                    "curve": {
                        "crank_angle_deg": study.crank_angle * 180 / math.pi,
                        "in_line_N": study.in_line,
                        "transverse_N": study.transverse,
                    },
                },
            }
        )


def balance_factor(
    engine: EngineLike | None, settings: BalanceFactorOptions
) -> BalanceFactorResult:
    """The balance factor of a crank, its bob-weight and the single-cylinder force study.

    The crank is given by its settings, or is one cylinder of ``engine`` (``cylinder``: its
    reciprocating mass, crank radius, conrod, offset, speed and its share of the throw's
    rotating mass, :func:`crankbalance.studies.cylinder.cylinder_of`), a setting given
    replacing the engine's value. The studied balance factor is the one given, else the
    crank's own (from its counterweight, CG radius and rotating mass), else 0.5; the
    bob-weight is sized for ``target`` (default: the studied factor); the force study runs
    with a speed, in the kinematics given, else the engine's, else exact with a conrod
    length and first-order without.
    """
    o = settings
    typed = given(o)
    if "cylinder" in typed and engine is None:
        raise InputError("cylinder", o.cylinder, "only acts with --engine")
    m_rec, r, m_rot, l_rod, w = (
        o.reciprocating_mass,
        o.crank_radius,
        o.rotating_mass,
        o.rod_length,
        o.speed,
    )
    e = o.offset or 0.0
    kinematics: KinematicsModel | None = o.kinematics
    if engine is not None:
        from .cylinder import cylinder_of

        model = as_model(engine)
        one = cylinder_of(model, o.cylinder, "cylinder")
        m_rec = one.reciprocating_mass if m_rec is None else m_rec
        r = one.crank_radius if r is None else r
        l_rod = one.rod_length if l_rod is None else l_rod
        w = one.speed if w is None else w
        e = one.offset if o.offset is None else e
        m_rot = one.rotating_mass if m_rot is None else m_rot
        kinematics = kinematics or model.kinematics
    if m_rec is None:
        raise InputError("reciprocating_mass", None, "is required, e.g. '282.12 g'")
    if r is None:
        raise InputError("crank_radius", None, "is required, e.g. '26.9 mm'")
    if w is None:
        for name in ("rod_length", "offset", "kinematics"):
            if name in typed:
                raise InputError(
                    name, getattr(o, name), "only acts on the force study: give --speed too"
                )
    if "rod_length" in typed and o.kinematics == "first-order":
        raise InputError(
            "rod_length", o.rod_length, "the first-order kinematics does not use the conrod length"
        )
    if o.target is not None and m_rot is None:
        raise InputError("target", o.target, "sizes the bob-weight: give --rotating-mass too")
    mass_properties = None
    if o.cw_mass is not None or o.cw_radius is not None:
        if o.cw_mass is None or o.cw_radius is None or m_rot is None:
            raise InputError(
                "cw_mass",
                o.cw_mass,
                "the crank's balance factor needs --cw-mass, "
                "--cw-radius and --rotating-mass together",
            )
        m_cw, r_cw = o.cw_mass, o.cw_radius
        mass_properties = {
            "counterweight_mass_kg": m_cw,
            "counterweight_radius_m": r_cw,
            "rotating_mass_kg": m_rot,
            "balance_factor": sc.balance_factor_from_mass_properties(m_cw, r_cw, r, m_rot, m_rec),
            "counterweight_moment_kg_m": m_cw * r_cw,
        }
    if o.balance_factor is not None:
        fb = o.balance_factor
    elif mass_properties is not None:
        fb = mass_properties["balance_factor"]
        low, high = sc.BALANCE_FACTOR_RANGE
        if not low <= fb <= high:
            raise InputError(
                "cw_mass",
                o.cw_mass,
                f"with --cw-radius and --rotating-mass gives the crank a balance "
                f"factor of {fb:.4f}, outside [{low:g}, {high:g}]; check the mass "
                "properties, or give --balance-factor for the study",
            )
    else:
        fb = 0.5
    fb_target = fb if o.target is None else o.target
    bob = None if m_rot is None else sc.bob_weight(m_rot, m_rec, fb_target)
    study = None
    if w is not None:
        model_name: KinematicsModel = kinematics or (
            "exact" if l_rod is not None else "first-order"
        )
        study = sc.balance_factor_study(
            m_rec,
            r,
            w,
            fb,
            rod_length=l_rod,
            offset=e,
            model=model_name,
        )
    result = BalanceFactorResult(fb, m_rec, r, mass_properties, fb_target, bob, w, study)
    require_finite(result.to_dict())
    return result


# ---------------------------------------------------------------------------------------
# rebalance
# ---------------------------------------------------------------------------------------


@record(repr=False)
class RebalanceResult(ResultMixin):
    """The rebalancing of one crank for each target balance factor
    (:class:`~crankbalance.studies.rebalance.RebalanceStudy`)."""

    study: RebalanceStudy

    def headline(self) -> tuple[str, ...]:
        """Per target: the balance factor reached, the residual against the tolerance."""
        study = self.study
        return tuple(
            f"target {number(c.target_balance_factor)}: balance factor "
            f"{number(c.achieved_balance_factor)} reached, residual "
            f"{number(abs(c.residual) * 1e6)} g·mm "
            f"{'within' if c.passed else 'OVER'} the tolerance "
            f"{number(study.tolerance * 1e6)} g·mm ({c.status})"
            for c in study.cases
        )

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.rebalance/2``."""
        study = self.study
        return _checked(
            {
                "schema": REBALANCE_SCHEMA,
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
        )


#: the settings of a correction and the key of ``[correction]`` each overrides
CORRECTION_KEYS = (
    ("method", "method"),
    ("radius", "correction_radius"),
    ("area", "face_area"),
    ("orientation", "face_orientation"),
    ("diameter", "hole_diameter"),
    ("number", "holes"),
    ("direction", "hole_direction"),
    ("point_angle", "point_angle"),
    ("depth_to", "depth_to"),
    ("web_thickness", "web_thickness"),
    ("drill_length", "drill_length"),
    ("density", "density"),
    ("depth_resolution", "depth_resolution"),
)


def rebalance(settings: RebalancePartsOptions) -> RebalanceResult:
    """Rebalance a single-cylinder crank after new parts (Hoem and Røsholm (2016), Sec. 6.4,
    eight steps): the parts file (``parts``), each setting given replacing the value of its
    key in the file (a total mass the file's named parts, ``method`` the correction's keys
    of the other method, ``tolerance`` the grade and the other way round). The file's
    schema (:mod:`crankbalance.io.rebalance_file`) then checks how they combine; an error
    names the setting that gave the value, or the file's key."""
    from ..io.rebalance_file import METHOD_KEYS, read_rebalance_data, rebalance_file_from_dict

    o = settings
    typed = given(o)
    data: dict[str, Any] = {}
    source = "parts"
    if o.parts:
        data = read_rebalance_data(o.parts)
        data.setdefault("name", Path(o.parts).stem)
        source = str(o.parts)
        rebalance_file_from_dict(data, source)  # the file's own errors name its keys
    else:
        data["name"] = "options"
    # settings override the file: put them at their key of the file, remember the setting
    origin: dict[str, str] = {}

    def put(key: str, value: Any, name: str) -> None:
        if name not in typed:
            return
        value = _file_value(name, value)
        *tables, last = key.split(".")
        table = data
        for part in tables:
            table = table.setdefault(part, {})
        table[last] = value
        origin[key] = name

    put("crank_radius", o.crank_radius, "crank_radius")
    put("counterweight.mass", o.cw_mass, "cw_mass")
    put("counterweight.cg_radius", o.cw_radius, "cw_radius")
    for side in ("old", "new"):
        for kind in ("rotating", "reciprocating"):
            name = f"{side}_{kind}_mass"
            if name in typed:
                data.get(side, {}).pop(kind, None)  # the total replaces the file's parts
                put(f"{side}.{kind}_mass", getattr(o, name), name)
    if o.target:
        put("targets", list(o.target), "target")
    corr = data.get("correction", {})
    if o.method is not None and o.method != corr.get("method", "face"):
        # the method switches the file's correction: its keys of the other method go
        for key in METHOD_KEYS[corr.get("method", "face")]:
            corr.pop(key, None)
    for key, name in CORRECTION_KEYS:
        put(f"correction.{key}", getattr(o, name), name)
    if "tolerance" in typed:
        if {"grade", "rotor_mass", "speed"} & typed:
            raise InputError(
                "tolerance",
                o.tolerance,
                "give either --tolerance or --grade with --rotor-mass and --speed",
            )
        data["tolerance"] = {}
        put("tolerance.unbalance", o.tolerance, "tolerance")
    for key in ("grade", "rotor_mass", "speed"):
        if key in typed:
            data.get("tolerance", {}).pop("unbalance", None)
            put(f"tolerance.{key}", getattr(o, key), key)
    try:
        parts = rebalance_file_from_dict(data, source)
        _drill_point_used(parts, o)
        study = rebalance_parts(parts, names=_plan_names(parts, origin))
    except InputError as error:
        named = origin.get(error.field.split("[")[0])
        if named is None:
            raise
        raise InputError(named, getattr(o, named), error.allowed) from None
    result = RebalanceResult(study)
    require_finite(result.to_dict())
    return result


def _file_value(name: str, value: Any) -> Any:
    """A setting's value as the parts file writes it: a quantity as its SI value with its
    unit (``"0.0269 m"``, read back to the same number), anything else as it is."""
    from ..schema.settings import field_kind
    from ..units import KINDS

    kind, quantity = field_kind(RebalancePartsOptions, name)
    if kind == "quantity" and quantity is not None and isinstance(value, float):
        return f"{value!r} {KINDS[quantity][0]}"
    return value


def _plan_names(parts: RebalanceFile, origin: dict[str, str]) -> dict[str, str]:
    """How the messages of a correction plan name its quantities: the option that set a
    key, the file's key, or both when neither gave it (``--holes or correction.number``)."""
    names = {key: "--" + name.replace("_", "-") for key, name in origin.items()}
    correction = parts.correction
    for key, option in (
        ("correction.number", "--holes"),
        ("correction.web_thickness", "--web-thickness"),
    ):
        present = correction is not None and getattr(correction, key.split(".")[1]) is not None
        if key not in names and not present:
            names[key] = f"{option} or {key}"
    return names


def _drill_point_used(parts: RebalanceFile, o: RebalancePartsOptions) -> None:
    """Refuse the drill-point settings where they would be ignored or leave the depth
    unstated: ``depth_to`` for flat-bottomed holes (one depth, nothing to read it to),
    ``point_angle`` below 180 deg without the depth reference (the point changes the depth
    by a third to two thirds of its height, docs/balance_shop.md). With the face method the
    file's schema refuses both (``METHOD_KEYS``)."""
    typed = given(o)
    correction = parts.correction
    if correction is None or correction.method != "holes":
        for name in ("point_angle", "depth_to"):
            if name in typed:
                raise InputError(
                    name,
                    getattr(o, name),
                    "applies to drilled holes only: give --method holes (or method = "
                    '"holes" in the [correction] of the parts file)',
                )
        return
    pointed = correction.point_angle is not None and correction.point_angle < math.pi
    if "depth_to" in typed and not pointed:
        raise InputError(
            "depth_to",
            o.depth_to,
            "applies to pointed holes only: give --point-angle below 180 deg (flat-bottomed "
            "holes have one depth)",
        )
    if "point_angle" in typed and pointed and correction.depth_to is None:
        raise InputError(
            "point_angle",
            o.point_angle,
            "needs --depth-to shoulder|tip: what the depths are read to (with a point the "
            "depth to the tip is the depth to the shoulder plus the point's height)",
        )


def _parts_json(side: PartsSummary) -> dict[str, Any]:
    return {
        "label": side.label,
        "rotating_mass_kg": side.rotating_mass,
        "reciprocating_mass_kg": side.reciprocating_mass,
        "rotating_parts_kg": side.rotating_parts,
        "reciprocating_parts_kg": side.reciprocating_parts,
    }


def _correction_json(correction: rb.DrilledHoles | rb.FaceRemoval) -> dict[str, Any]:
    from ..physics.rebalancing import FaceRemoval

    out: dict[str, Any] = {"kind": correction.kind, "radius_m": correction.radius}
    if isinstance(correction, FaceRemoval):
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
        if correction.drill_length is not None:
            out["drill_length_m"] = correction.drill_length
    return out | {
        "webs": correction.webs,
        "density_kg_m3": correction.density,
        "depth_resolution_m": correction.depth_resolution,
    }


def _case_json(res: rb.RebalanceResult) -> dict[str, Any]:
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


#: the settings of the split between the correction planes
PLANE_SETTINGS = ("bearing_a", "bearing_b", "center_of_mass", "plane_1", "plane_2")


@record(repr=False)
class ToleranceResult(ResultMixin):
    """ISO 21940-11 permissible residual unbalance, its split between two correction planes
    and the verdict on a measured residual; or, for ``list_grades``, the grades.

    Attributes
    ----------
    grades : tuple of BalanceGrade
        The grades listed (``list_grades``), else empty.
    grade : BalanceGrade, optional
        The grade checked.
    rotor_mass : float
        [kg].
    speed : float
        Largest service speed [rad/s].
    permissible : float
        Permissible residual unbalance U_per [kg m].
    planes : PlaneAllocation, optional
        U_per split between the bearing and correction planes.
    verdict : ToleranceVerdict, optional
        The measured residual against U_per.
    """

    grades: tuple[tl.BalanceGrade, ...] = ()
    grade: tl.BalanceGrade | None = None
    rotor_mass: float = 0.0
    speed: float = 0.0
    permissible: float = 0.0
    planes: tl.PlaneAllocation | None = None
    verdict: tl.ToleranceVerdict | None = None

    def headline(self) -> tuple[str, ...]:
        """The permissible unbalance of the grade, rotor mass and speed, and the verdict on
        a measured residual."""
        if self.grade is None:
            return (f"{len(self.grades)} balance grades of ISO 21940-11",)
        said = (
            f"permissible unbalance {number(self.permissible * 1e6)} g·mm "
            f"({self.grade.name}, {number(self.rotor_mass)} kg, "
            f"{number(self.speed * 30 / math.pi)} rpm)",
        )
        if self.verdict is None:
            return said
        v = self.verdict
        return (
            *said,
            f"measured residual {number(v.residual * 1e6)} g·mm: "
            f"{'within' if v.passed else 'OVER'} the grade ({number(v.ratio * 100)} %)",
        )

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.tolerance/2`` (``crankbalance.grades/2`` for
        the list of grades)."""
        if self.grade is None:
            return _checked(
                {"schema": GRADES_SCHEMA, "grades": [_grade_json(g) for g in self.grades]}
            )
        planes, verdict = self.planes, self.verdict
        return _checked(
            {
                "schema": TOLERANCE_SCHEMA,
                "grade": _grade_json(self.grade),
                "rotor_mass_kg": self.rotor_mass,
                "speed_rad_s": self.speed,
                "permissible_unbalance_kg_m": self.permissible,
                "eccentricity_m": self.permissible / self.rotor_mass,
                "planes": None
                if planes is None
                else {
                    "total_kg_m": planes.total,
                    "bearing_a_kg_m": planes.bearing_a,
                    "bearing_b_kg_m": planes.bearing_b,
                    "plane_1_kg_m": planes.plane_1,
                    "plane_2_kg_m": planes.plane_2,
                    "share_a": planes.share_a,
                    "rule": planes.rule,
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
        )


def tolerance(engine: EngineLike | None, settings: ToleranceOptions) -> ToleranceResult:
    """ISO 21940-11 permissible residual unbalance U_per = 1000 G m / Omega of a rotor of
    the given grade, mass and largest service speed (with an engine: by default its crank's
    rotating masses, a stand-in for the crank's mass, and its speed), split between two
    correction planes when the bearings and the centre of mass are given, and the verdict on
    a measured residual; ``list_grades`` lists the grades alone."""
    o = settings
    typed = given(o)
    if o.list_grades:
        others = [n for n in ToleranceOptions.FIELDS if n in typed and n != "list_grades"]
        for name in others + (["engine"] if engine is not None else []):
            raise InputError(
                name,
                getattr(o, name, engine),
                "does not act with --list (which lists the grades only)",
            )
        return ToleranceResult(grades=tuple(tl.GRADES))
    mass, omega = o.rotor_mass, o.speed
    if engine is not None:
        import numpy as np

        model = as_model(engine)
        mass = float(np.sum(model.throw_rotating_mass)) if mass is None else mass
        omega = float(model.speed) if omega is None else omega
    if o.grade is None or mass is None or omega is None:
        missing = next(
            n for n, v in (("grade", o.grade), ("rotor_mass", mass), ("speed", omega)) if v is None
        )
        raise InputError(missing, None, "is required (or use --list)")
    item = tl.balance_grade(o.grade)
    u_per = tl.permissible_unbalance(item.name, mass, omega)
    allocation = None
    if any(getattr(o, n) is not None for n in PLANE_SETTINGS):
        if o.bearing_a is None or o.bearing_b is None or o.center_of_mass is None:
            raise InputError(
                "bearing_a",
                o.bearing_a,
                "the split between planes needs --bearing-a, --bearing-b and --center-of-mass",
            )
        allocation = tl.allocate_to_planes(
            u_per, o.bearing_a, o.bearing_b, o.center_of_mass, o.plane_1, o.plane_2
        )
    verdict = None if o.residual is None else tl.check_residual(o.residual, u_per)
    result = ToleranceResult((), item, mass, omega, u_per, allocation, verdict)
    require_finite(result.to_dict())
    return result


def _grade_json(grade: tl.BalanceGrade) -> dict[str, Any]:
    return {
        "name": grade.name,
        "value_m_s": grade.value,
        "examples": grade.examples,
        "crank_drive": grade.crank_drive,
    }
