"""The study tabs of the web application as plain functions (no NiceGUI).

Each takes the current computation (:class:`~.project.Computed`) and the project's
settings (texts as typed), parses the settings it needs and calls the API. A bad setting
raises :class:`~crankbalance.errors.InputError` whose ``field`` is the setting's key, so
that the page shows the message beside that input.
"""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np

from ..errors import InputError
from ..units import parse_quantity
from .project import Computed

#: settings of the study tabs: key -> (label, quantity kind | "float" | "int" | "text", hint)
SETTING_FIELDS: dict[str, tuple[str, str, str]] = {
    "orders": ("Highest order", "int", "1..16"),
    "cw_density": ("Density", "density", "e.g. 8000 kg/m^3"),
    "cw_max_mass": ("Largest mass", "mass", "optional, e.g. 400 g"),
    "cw_max_radius": ("Largest radial space", "length", "optional, e.g. 80 mm"),
    "cw_min_balance": ("Smallest balance [%]", "float", "e.g. 100"),
    "cw_iterations": ("Iterations", "int", "0..200"),
    "cw_population": ("Population", "int", "16..100000"),
    "cw_seed": ("Random seed", "int", "repeatable runs"),
    "sc_cylinder": ("Cylinder", "int", "1..number of cylinders"),
    "sc_balance_factor": ("Balance factor", "float", "0..2"),
    "sc_grade": ("ISO 21940-11 grade", "text", "e.g. G6.3"),
    "sc_rotor_mass": ("Rotor mass", "mass", "empty: the crank's rotating masses"),
    "sc_residual": ("Measured residual unbalance", "unbalance", "optional, e.g. 8 g*mm"),
    "rb_new_reciprocating": ("New reciprocating mass", "mass", "empty: unchanged"),
    "rb_new_rotating": ("New rotating mass", "mass", "empty: unchanged"),
    "rb_cw_mass": (
        "Counterweight mass (webs incl.)",
        "mass",
        "empty: what the balance factor needs at the CG radius",
    ),
    "rb_cw_radius": ("Counterweight CG radius", "length", "empty: crank radius"),
    "rb_hole_diameter": ("Drill diameter", "length", "e.g. 8 mm"),
    "rb_hole_radius": ("Hole radius", "length", "empty: counterweight CG radius"),
    "bs_length": ("Shaft length (between bearings)", "length", "e.g. 300 mm"),
    "bs_diameter": ("Shaft diameter", "length", "e.g. 25 mm"),
    "bs_weight": ("Objective weight w", "float", "e.g. 2"),
    "pf_bore": ("Bore", "length", "empty: square engine (bore = stroke)"),
    "pf_balance_factors": ("Balance factors", "list", "e.g. 0, 0.25, 0.5, 0.75, 1"),
    "pf_crank_inertia": ("Crank + flywheel inertia", "inertia", "e.g. 0.006 kg*m^2"),
    "pf_friction_coefficient": ("Bearing friction coefficient", "float", "e.g. 0.005"),
    "pf_journal_diameter": ("Main journal diameter", "length", "e.g. 30 mm"),
}
INT_LIMITS = {
    "orders": (1, 16),
    "cw_iterations": (0, 200),
    "cw_population": (16, 100_000),
    "cw_seed": (0, 2**31 - 1),
}


def setting(settings: dict[str, Any], key: str, optional: bool = False) -> Any:
    """Parse one setting; None for an empty optional one; InputError(field=key) if bad."""
    label, kind, hint = SETTING_FIELDS[key]
    text = str(settings.get(key, "")).strip()
    if not text:
        if optional:
            return None
        raise InputError(key, None, f"{label} is required ({hint})")
    if kind == "text":
        return text
    if kind == "int":
        try:
            whole = int(text)
        except ValueError:
            raise InputError(key, text, f"{label} must be a whole number ({hint})") from None
        low, high = INT_LIMITS.get(key, (-(2**31), 2**31))
        if not low <= whole <= high:
            raise InputError(key, whole, f"{label} must lie between {low} and {high}")
        return whole
    if kind == "float":
        try:
            number = float(text)
        except ValueError:
            raise InputError(key, text, f"{label} must be a number ({hint})") from None
        if not math.isfinite(number):
            raise InputError(key, text, f"{label} must be a finite number")
        return number
    if kind == "list":
        try:
            values = [float(p) for p in text.replace(";", ",").split(",") if p.strip()]
        except ValueError:
            raise InputError(key, text, f"{label}: numbers separated by commas ({hint})") from None
        if not values or not all(math.isfinite(v) for v in values):
            raise InputError(key, text, f"{label}: finite numbers separated by commas ({hint})")
        return values
    return parse_quantity(text, kind, key)


def check_settings(settings: dict[str, Any]) -> dict[str, str]:
    """Messages of the settings that do not parse (empty ones are checked when used)."""
    errors: dict[str, str] = {}
    for key in SETTING_FIELDS:
        if str(settings.get(key, "")).strip():
            try:
                setting(settings, key)
            except InputError as error:
                errors[key] = str(error)
    return errors


# --------------------------------------------------------------------------- counterweight
def counterweight_requirement(computed: Computed) -> tuple[float, float, float]:
    """(first moment m_c r_c [kg m], counterweight mass [kg], CG radius [m]) of the heaviest
    crank counterweight found by the balancing solver."""
    cw = computed.study.result.counterweights
    if cw is None or cw.count == 0:
        raise InputError("counterweights", None, "the balancing found no crank counterweight")
    mass = float(cw.mass.max())
    return mass * cw.cg_radius, mass, float(cw.cg_radius)


def run_counterweight(computed: Computed, settings: dict[str, Any], callback: Any = None) -> Any:
    """The counterweight optimiser (2021 paper, Sec. 4-5) for the engine's counterweight."""
    from ..counterweight_optimize import optimize_counterweight

    required, _mass, _radius = counterweight_requirement(computed)
    return optimize_counterweight(
        required,
        density=setting(settings, "cw_density"),
        max_mass=setting(settings, "cw_max_mass", optional=True),
        max_radius=setting(settings, "cw_max_radius", optional=True),
        min_balance=_positive(settings, "cw_min_balance"),
        iterations=setting(settings, "cw_iterations"),
        population=setting(settings, "cw_population"),
        children=setting(settings, "cw_population"),
        rng=setting(settings, "cw_seed"),
        callback=callback,
    )


def pick_design(optimum: Any, choice: str) -> Any:
    """A design of an optimum: "least mass", "least radius" or "front k" (1-based)."""
    if choice == "least radius":
        return optimum.least_radius_design
    if choice.startswith("front "):
        k = int(choice.split()[1]) - 1
        return optimum.design(int(optimum.pareto[k]))
    return optimum.least_mass_design


def design_choices(optimum: Any, count: int = 10) -> list[str]:
    n = len(optimum.pareto)
    return ["least mass", "least radius"] + [f"front {k + 1}" for k in range(min(n, 50))]


# --------------------------------------------------------------------------- single cylinder
def _cylinder(computed: Computed, settings: dict[str, Any]) -> int:
    n = int(computed.analysis.model.cylinders)
    number = setting(settings, "sc_cylinder")
    if not 1 <= number <= n:
        raise InputError("sc_cylinder", number, f"Cylinder must be a number from 1 to {n}")
    return number - 1


def _balance_factor(settings: dict[str, Any]) -> float:
    value = setting(settings, "sc_balance_factor")
    if not 0.0 <= value <= 2.0:
        raise InputError("sc_balance_factor", value, "Balance factor must lie between 0 and 2")
    return float(value)


def single_study(computed: Computed, settings: dict[str, Any]) -> Any:
    """Balance-factor study of one cylinder (Hoem and Røsholm (2016), Sec. 4.1)."""
    from ..single_cylinder import cylinder_balance_factor_study

    return cylinder_balance_factor_study(
        computed.analysis.model, _cylinder(computed, settings), _balance_factor(settings)
    )


def _rotor_mass(computed: Computed, settings: dict[str, Any]) -> float:
    value = setting(settings, "sc_rotor_mass", optional=True)
    if value is None:
        return float(np.sum(computed.analysis.model.throw_rotating_mass))
    if value <= 0:
        raise InputError("sc_rotor_mass", value, "Rotor mass must be greater than zero")
    return float(value)


def iso_check(computed: Computed, settings: dict[str, Any]) -> dict[str, Any]:
    """ISO 21940-11 permissible residual unbalance at the engine speed and the verdict."""
    from ..tolerance import balance_grade, check_residual, permissible_unbalance

    grade_text = setting(settings, "sc_grade")
    try:
        grade = balance_grade(grade_text.replace(" ", ""), field="sc_grade")
    except InputError as error:
        raise InputError("sc_grade", grade_text, error.allowed) from None
    mass = _rotor_mass(computed, settings)
    speed = float(computed.analysis.model.speed)
    permissible = permissible_unbalance(grade_text.replace(" ", ""), mass, speed)
    residual = setting(settings, "sc_residual", optional=True)
    verdict = None
    if residual is not None:
        if residual < 0:
            raise InputError("sc_residual", residual, "the residual unbalance is a magnitude >= 0")
        verdict = check_residual(residual, permissible)
    return {
        "grade": grade,
        "rotor_mass": mass,
        "speed": speed,
        "permissible": permissible,
        "verdict": verdict,
    }


def rebalance_study(computed: Computed, settings: dict[str, Any]) -> Any:
    """Rebalance the cylinder's throw after new parts (Hoem and Røsholm (2016), Sec. 4.1.3, eight steps)."""
    from ..single_cylinder import DrilledHoles, rebalance

    model = computed.analysis.model
    c = _cylinder(computed, settings)
    throw = int(model.cylinder_throw[c])
    old_rec = float(model.reciprocating_mass[c])
    old_rot = float(model.throw_rotating_mass[throw])
    new_rec = setting(settings, "rb_new_reciprocating", optional=True)
    new_rot = setting(settings, "rb_new_rotating", optional=True)
    radius = setting(settings, "rb_cw_radius", optional=True) or float(model.crank_radius)
    fb = _balance_factor(settings)
    cw_mass = setting(settings, "rb_cw_mass", optional=True)
    if cw_mass is None:
        cw_mass = (old_rot + fb * old_rec) * model.crank_radius / radius
    hole_radius = setting(settings, "rb_hole_radius", optional=True) or radius
    try:
        holes = DrilledHoles(diameter=setting(settings, "rb_hole_diameter"), radius=hole_radius)
    except InputError as error:
        key = "rb_hole_diameter" if "diameter" in error.field else "rb_hole_radius"
        raise InputError(key, error.value, error.allowed) from None
    tolerance = iso_check(computed, settings)["permissible"]
    return rebalance(
        old_rot,
        old_rec,
        old_rot if new_rot is None else new_rot,
        old_rec if new_rec is None else new_rec,
        cw_mass,
        radius,
        float(model.crank_radius),
        holes,
        tolerance,
    )


# --------------------------------------------------------------------------- balance shaft
def shaft_requirement(computed: Computed) -> tuple[float, float, str]:
    """(first moment of one shaft's mass [kg m], shaft speed [rad/s], which) for the
    placement study: the engine's secondary shaft if it has one, else its primary shaft,
    else the inline-4 closed form Kim (2018), Eq. 4 for its first cylinder."""
    from ..balance_shaft import inline4_secondary_unbalance

    result, model = computed.study.result, computed.analysis.model
    for group, label in ((result.secondary, "secondary"), (result.primary, "primary")):
        if group is not None and group.shafts:
            shaft = max(group.shafts, key=lambda s: s.mass)
            moment = max((x.mass for x in shaft.masses), default=0.0) * shaft.cg_radius
            if moment > 0:
                return moment, group.order * float(model.speed), f"{label} shaft of the engine"
    moment = inline4_secondary_unbalance(
        float(model.reciprocating_mass[0]), float(model.crank_radius), float(model.rod_length)
    )
    return moment, 2 * float(model.speed), "inline-4 secondary shaft (Kim (2018), Eq. 4)"


def shaft_placement(computed: Computed, settings: dict[str, Any]) -> tuple[Any, str]:
    """Unbalance-mass placement on a shaft with end bearings (Kim (2018), Sec. 3.1)."""
    from ..balance_shaft import ShaftSection, inline4_study

    moment, speed, which = shaft_requirement(computed)
    try:
        section = ShaftSection(outer_diameter=setting(settings, "bs_diameter"))
    except InputError as error:
        raise InputError("bs_diameter", error.value, error.allowed) from None
    length = setting(settings, "bs_length")
    if length <= 0:
        raise InputError("bs_length", length, "Shaft length must be greater than zero")
    weight = setting(settings, "bs_weight")
    if weight < 0:
        raise InputError("bs_weight", weight, "the objective weight must not be negative")
    study = inline4_study(
        moment, speed, length, section, weight=weight, positions=np.linspace(0.0, 1.0, 41)
    )
    return study, which


# --------------------------------------------------------------------------- performance
def performance_study(computed: Computed, settings: dict[str, Any]) -> Any:
    """Friction, bearing loads and shaking against the balance factor (Hoem and Røsholm (2016), Sec. 5) for one
    cylinder of the engine (its reciprocating mass, crank radius, rod length, speed)."""
    from ..dynamics import CylinderSpec, WiebeCombustion, balance_sensitivity

    model = computed.analysis.model
    bore = setting(settings, "pf_bore", optional=True) or 2 * float(model.crank_radius)
    factors = setting(settings, "pf_balance_factors")
    if len(factors) > 21 or any(not 0 <= f <= 2 for f in factors):
        raise InputError("pf_balance_factors", factors, "up to 21 values between 0 and 2")
    fields = {
        "bore": "pf_bore",
        "crank_inertia": "pf_crank_inertia",
        "journal_diameter": "pf_journal_diameter",
        "friction_coefficient": "pf_friction_coefficient",
    }
    try:
        cylinder = CylinderSpec(
            bore=bore,
            crank_radius=float(model.crank_radius),
            rod_length=float(model.rod_length),
            reciprocating_mass=float(model.reciprocating_mass[0]),
            crank_inertia=setting(settings, "pf_crank_inertia"),
            journal_diameter=setting(settings, "pf_journal_diameter"),
            friction_coefficient=setting(settings, "pf_friction_coefficient"),
        )
        pressure = WiebeCombustion(
            compression_ratio=10.0, ignition_angle=math.radians(-25), burn_duration=math.radians(50)
        )
        return balance_sensitivity(
            cylinder,
            float(model.speed),
            pressure,
            factors,
            strokes=_strokes(model.strokes),
            samples_per_revolution=180,
        )
    except InputError as error:
        raise InputError(fields.get(error.field, error.field), error.value, error.allowed) from None


def _strokes(value: Any) -> Literal[2, 4]:
    """The engine's strokes per cycle as the Literal the dynamics API takes."""
    strokes = int(value)
    if strokes == 2:
        return 2
    if strokes == 4:
        return 4
    raise InputError("strokes", value, "2 or 4 strokes per cycle")


def _positive(settings: dict[str, Any], key: str) -> float:
    value = setting(settings, key)
    if not value > 0:
        raise InputError(key, value, "must be greater than zero")
    return float(value)
