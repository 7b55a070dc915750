"""One schema for the settings of every study and every command, with one set of limits.

The command line, the web form and the API all validate a study's settings through these
schemas (:mod:`crankbalance.schema.core`), so that a setting has the same default, the
same limits and the same message everywhere. Quantities are unit strings
(``"8000 kg/m^3"``, ``"400 g"``) parsed to SI floats; plain numbers stay numbers. Every
field has a default (``None`` where the study derives the value from the engine when it is
not given), a title (the label of a form and of a help text), a description (what it
means; ``docs/settings.md`` is written from it) and, where a form shows one, a hint.

Limits. Every value is checked *after* unit conversion: it must be a finite number (no
NaN, no infinity, whatever the unit: ``"1e308 km"`` is refused) inside the physical range
of its kind (:data:`RANGES`), which a setting may narrow (a balance factor from 0 to 2, a
friction coefficient up to 1). Counts and indices are whole numbers within stated bounds;
the work of the long studies is capped (:data:`MAX_BENCH_REVOLUTIONS`, the design points
of a shaft sweep, the balance factors of a sensitivity sweep).

An edge names the fields as its users write them: the CLI as ``--max-mass``, the web form
by its setting key; :func:`parse_options` takes that naming as a function, so that an
error names the field the user typed. This module is over 800 lines because it is the
one description of about 250 settings of 26 studies and commands: splitting it would put
a study's settings apart from the limits they share.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from typing import Any, Literal, TypeVar, get_args

from ..errors import InputError
from ..physics.limits import (
    BALANCE_FACTOR_RANGE,
    BURN_DURATION_RANGE,
    BURN_ENDS,
    GAMMA_RANGE,
    IGNITION_RANGE,
    LARGEST_CHUNK,
    MAX_DRAWS,
    MAX_FLUCTUATION_TARGET,
    MIN_FLUCTUATION_TARGET,
)
from ..units import RANGES as units_ranges
from ..units import format_quantity, parse_factor, parse_quantity, range_si
from . import core
from .core import FieldProblem, Schema, entry, field, three_lengths

#: the balance factors every study accepts (share of the reciprocating mass) [-]
BALANCE_FACTOR_LIMITS = BALANCE_FACTOR_RANGE

_RPM = math.pi / 30.0  # 1 rpm in rad/s

#: The signed range of each kind of quantity a setting may take, in SI units (angles in
#: rad, speeds in rad/s), from the one table of physical ranges (:data:`units.RANGES`):
#: positive kinds from its smallest to its largest size, a position or an angle either
#: side of zero, a force, torque or unbalance from zero. A setting may narrow its range.
RANGES: dict[str, tuple[float, float]] = {kind: range_si(kind) for kind in units_ranges}
RANGES["position"] = (-RANGES["length"][1], RANGES["length"][1])  # axial positions, offsets
RANGES["angle"] = (-RANGES["angle"][1], RANGES["angle"][1])
for _kind in ("unbalance", "force", "torque"):
    RANGES[_kind] = (0.0, RANGES[_kind][1])
#: the included angle of a drill point [rad]: above 0 (open), at most 180 deg (a flat bottom)
RANGES["point_angle"] = (0.0, math.pi)
#: the smallest first moment a counterweight or a balance shaft is sized for [kg m]
#: (0.001 g mm; a smaller requirement is zero for any balancing machine)
MIN_UNBALANCE = 1e-9
#: most runs of one ``bench`` call (one per ``--speed``)
MAX_BENCH_RUNS = 10
#: most revolutions one bench run may simulate, ``speed / 2 pi * (ramp_time / 2 +
#: hold_time)``: the explicit solver takes at least 8 steps a revolution, so this caps
#: the work of a run (the thesis' runs: about 130 revolutions)
MAX_BENCH_REVOLUTIONS = 2_000
#: most time constants of the bench's PI controller one run may simulate,
#: ``(kp / inertia + sqrt(ki / inertia)) * (ramp_time + hold_time)``: the explicit solver
#: needs steps shorter than the controller's time constant (the thesis' runs: about 450).
#: :data:`crankbalance.physics.rotor_bench.MAX_BENCH_EVALUATIONS` bounds the work of what is left
MAX_BENCH_CONTROL = 50_000
#: most values of a list setting of a sweep (balance factors, mass scales, weights)
MAX_SWEEP = 21
#: most design points along a balance shaft (each one a beam solve and an eigenproblem)
MAX_SHAFT_POINTS = 2001
#: most bearings, unbalance masses or phases of one balance shaft (``shaft check``)
MAX_SHAFT_ITEMS = 64
#: most holes drilled side by side in one web (one rebalancing)
MAX_HOLES = 12
#: the largest harmonic order any study computes
MAX_ORDER = 64
#: designs the counterweight optimiser breeds in each round after its first sample (the
#: ``children`` of :func:`crankbalance.physics.counterweight_optimize.optimize_counterweight`, its
#: default, which the command line and the web app both use)
COUNTERWEIGHT_CHILDREN = 4096
#: most designs one counterweight optimisation evaluates, population + iterations x
#: :data:`COUNTERWEIGHT_CHILDREN`: the optimiser's work and memory grow with it (every
#: feasible design is kept). At this many, mass and radial space as objectives, one core of
#: the 2-core reference machine takes about 5 s and 650 MB (docs/web.md, "Studies: budget,
#: workers, cancel")
MAX_COUNTERWEIGHT_DESIGNS = 1_000_000
#: the same with the inertia as a third objective: the Pareto front of three objectives is
#: far larger and keeping it grows faster than the designs (measured on the 2-core reference
#: machine, paper-inline3: 168 000 designs 12.6 s against 9.2 s with two objectives, 496 000
#: designs 79 s against 9.8 s), so about 200 000 take as long as the two objectives' budget
MAX_THREE_OBJECTIVE_DESIGNS = 200_000
#: what the depth of a pointed hole is read to: the shoulder (where the cylinder ends) or
#: the tip of the point (the same for a flat bottom); the choices of the web's selects
DepthTo = Literal["shoulder", "tip"]
DEPTH_TO: tuple[str, ...] = get_args(DepthTo)
#: the speed fluctuation a flywheel is sized for, from 1 ppm to 20 % [-] (the energy
#: method's range, :data:`crankbalance.physics.engine_cycle_all.MAX_FLUCTUATION_TARGET`)
FLUCTUATION_TARGET = (MIN_FLUCTUATION_TARGET, MAX_FLUCTUATION_TARGET)
#: most pressure tables of one cycle (one per cylinder)
MAX_PRESSURE_TABLES = 64
#: the crank + flywheel inertia of ``cycle`` of the cylinder typed as options (without
#: ``engine``): the thesis' motorcycle single (Hoem and Røsholm 2016) [kg m^2]
THESIS_CRANK_INERTIA = 0.006
#: what the torsional model and, through :func:`crankbalance.studies.crank.
#: rotating_inertia`, every study of an engine assume of the front end (pulley, timing gear,
#: damper hub) and of the flywheel with clutch when not typed: an automotive engine's
#: [kg m^2] (docs/torsional.md)
DEFAULT_FRONT_INERTIA = 0.010
DEFAULT_FLYWHEEL_INERTIA = 0.15
#: what an empty crank + flywheel inertia means in the option descriptions
ENGINE_INERTIA_TEXT = (
    "empty: the engine's, front end + throws + flywheel as the torsional model "
    f"({DEFAULT_FRONT_INERTIA:g} + throws + {DEFAULT_FLYWHEEL_INERTIA:g} kg*m^2)"
)
#: what an empty crank dimension means in the option descriptions
ENGINE_DIMENSION_TEXT = "empty: from the crank radius and web offset (as every study)"
#: most main bearings one crank may be given (``bearings --bearing``)
MAX_MAIN_BEARINGS = 64
#: the crank-angle samples per revolution of ``bearings`` (the engine cycle's least, and
#: ten per degree; the clearance contact model may allow fewer:
#: :data:`crankbalance.physics.main_bearings.MAX_CONTACT_SIZE`)
MIN_SAMPLES = 36
MAX_SAMPLES = 3600
#: stiffest bearing ring the clearance contact of ``bearings`` is solved for [N/m] (oil
#: films and bearing shells: 1e8-1e9 N/m; docs/main_bearings.md)
MAX_CLEARANCE_STIFFNESS = 1e10
#: the named counterweight patterns of a bearing sweep (``bearings-sweep --pattern``):
#: a counterweight on every web, none at all, or the engine file's own pattern
NAMED_PATTERNS = ("all", "none", "file")
#: most counterweight patterns of one bearing sweep
MAX_PATTERNS = 8
#: most cases (patterns times balance factors; ``none`` counts once) of one bearing sweep:
#: each case is a balance solve and both crank models over the cycle
MAX_SWEEP_CASES = 64
#: most cases x samples per revolution x cylinders of one bearing sweep, checked with the
#: engine before the first case (:func:`crankbalance.studies.balance_loads.bearing_sweep`):
#: its time and memory grow with it. The W16 preset's 61 cases at 3600 samples (3.5
#: million) took 12 s of one core of the 2-core reference machine and 1.4 GB
MAX_SWEEP_WORK = 4_000_000
#: the range of a torsional stiffness [N m/rad] (a model engine's crank to a ship's shafting)
TORSIONAL_STIFFNESS_RANGE = (1.0, 1e11)
_TORSIONAL_EXAMPLE = "5e5 N*m/rad"
#: a balancing-machine reading in words
READING_WORDS = "an amount at a radius and an angle, e.g. '12.5 g @ 40 mm, 35 deg'"
#: the longest engine file or preset name, file name, grade or expression a setting takes
MAX_SETTING_CHARS = 1000
#: most cylinders the explorer enumerates (its index space must fit a 64-bit integer:
#: ``crankbalance.physics.explore.orders.MAX_CYLINDERS``), and so most angles of a fixed crank
MAX_EXPLORE_CYLINDERS = 20


# --------------------------------------------------------------------------------------
# the kinds of setting
# --------------------------------------------------------------------------------------
def quantity(
    kind: str,
    default: Any,
    title: str,
    description: str,
    *,
    within: str | None = None,
    ge: float | None = None,
    gt: float | None = None,
    le: float | None = None,
    lt: float | None = None,
    **options: Any,
) -> Any:
    """A quantity setting of ``kind``, inside the signed range of its kind (or of
    ``within``: ``"position"``, ``"point_angle"``) in :data:`RANGES`, narrowed by the
    bounds given (the tightest of each side applies); a kind without a physical range
    (a frequency, a power) takes the bounds given."""
    low, high = RANGES.get(within or kind, (-math.inf, math.inf))
    if gt is None or gt < low:
        gt, ge = None, low if ge is None else max(ge, low)
    if lt is None or lt > high:
        lt, le = None, high if le is None else min(le, high)
    return field(
        kind,
        default=default,
        title=title,
        description=description,
        ge=ge,
        gt=gt,
        le=le,
        lt=lt,
        **options,
    )


def number(default: Any, title: str, description: str, **options: Any) -> Any:
    """A plain number setting (a ratio, a gain), finite, within the bounds given."""
    return field("number", default=default, title=title, description=description, **options)


def whole(default: Any, title: str, description: str, **options: Any) -> Any:
    """A whole-number setting (a count, an index, a seed), within the bounds given."""
    return field("whole", default=default, title=title, description=description, **options)


def choice(default: Any, choices: Any, title: str, description: str, **options: Any) -> Any:
    """A setting that is one of ``choices``."""
    return field(
        "choice", default=default, choices=choices, title=title, description=description, **options
    )


def factor(
    default: Any,
    title: str,
    description: str,
    *,
    low: float = BALANCE_FACTOR_LIMITS[0],
    high: float = BALANCE_FACTOR_LIMITS[1],
    **options: Any,
) -> Any:
    """A balance factor (or a share): ``0.28`` or ``"28%"``, from ``low`` to ``high``."""
    return field(
        "factor", default=default, ge=low, le=high, title=title, description=description, **options
    )


def text(default: Any, title: str, description: str, **options: Any) -> Any:
    """A text setting (a file name, a preset, a grade, an expression)."""
    return field(
        "text",
        default=default,
        max_chars=MAX_SETTING_CHARS,
        title=title,
        description=description,
        **options,
    )


def _length_or_zero(default: Any, title: str, description: str, **options: Any) -> Any:
    """A length that may be zero (a solid shaft's bore, a profile's rectangle height)."""
    return quantity("length", default, title, description, zero=True, **options)


def _requirement(default: Any, title: str, description: str) -> Any:
    """A first moment a counterweight or a balance shaft is sized for [kg m]."""
    return quantity("unbalance", default, title, description, ge=MIN_UNBALANCE)


def _point_angle(default: Any, title: str, description: str, **options: Any) -> Any:
    """A drill point's included angle: above 0, at most 180 deg (flat-bottomed holes)."""
    return quantity("angle", default, title, description, within="point_angle", gt=0.0, **options)


def _friction(default: Any, title: str, description: str, **options: Any) -> Any:
    """A Coulomb friction coefficient [-]: above 0, at most 1."""
    return number(default, title, description, gt=0, le=1, **options)


def _weight(default: Any, title: str, description: str, **options: Any) -> Any:
    """The weight w of the balance-shaft placement objective [-]."""
    return number(default, title, description, ge=0, le=1000, **options)


def _number_sweep(value: str, where: str) -> Any:
    """A list of numbers typed as one text: ``"0,0.28,0.5"``, or ``"start:stop:step"`` (stop
    included, at most :data:`MAX_SWEEP` values); the entries are then checked by the
    list's field."""
    if ":" not in value:
        return value  # comma-separated: read by the list
    words = "must be numbers separated by commas, or start:stop:step with step > 0"
    try:
        start, stop, step = (float(x) for x in value.split(":"))
    except ValueError:
        raise InputError(where, value, words) from None
    span = (stop - start) / step if step > 0 else math.nan
    if not (math.isfinite(start) and 0 <= span < math.inf):
        raise InputError(where, value, words)
    if span > MAX_SWEEP:
        raise InputError(where, value, f"must give at most {MAX_SWEEP} values")
    return [start + k * step for k in range(int(math.floor(span + 1e-9)) + 1)]


def _angle_list(value: str, where: str) -> Any:
    """A list of angles typed as one text with one unit at its end, ``"0,90,270,180 deg"``:
    the unit is given to every number; any other text is read as a list of its own."""
    match = re.fullmatch(r"\s*([-+0-9.eE,\s]+?)\s*(deg|rad)\s*", value)
    if match is None:
        return value
    return [f"{number.strip()} {match.group(2)}" for number in match.group(1).split(",")]


def _balance_factors(default: Any, title: str, description: str, **options: Any) -> Any:
    """The balance factors of a sweep: a list, or a text "0,0.25,0.5" or "start:stop:step"."""
    return field(
        "list",
        default=default,
        item=entry("factor", ge=BALANCE_FACTOR_LIMITS[0], le=BALANCE_FACTOR_LIMITS[1]),
        min_items=1,
        max_items=MAX_SWEEP,
        parse=_number_sweep,
        title=title,
        description=description,
        **options,
    )


def _damping(default: Any, title: str, description: str) -> Any:
    """A damping ratio [-], from 0 to 0.5."""
    return number(default, title, description, ge=0, le=0.5)


def _angle_or_optimal(value: Any, where: str) -> Any:
    """``"optimal"`` or an angle with a unit, in :data:`RANGES` ``["angle"]``."""
    if isinstance(value, str) and value.strip().lower() == "optimal":
        return "optimal"
    low, high = RANGES["angle"]
    words = f"'optimal' or {core.allowed(entry('angle', ge=low, le=high))}"
    try:
        angle = core.parse_in_range(value, "angle", where)
    except InputError as error:
        if isinstance(value, str) and not any(c.isdigit() for c in value):
            raise InputError(where, value, f"must be {words}") from None
        raise InputError(where, value, error.allowed) from None
    if not low <= angle <= high:
        raise InputError(where, value, f"must be {words}")
    return angle


def _target(value: Any, where: str) -> Any:
    """A target balance factor: 0.28, "28%" or "factory" (the crank's own)."""
    if isinstance(value, str) and value.strip().lower() == "factory":
        return "factory"
    low, high = BALANCE_FACTOR_LIMITS
    words = f"must be 'factory' or a number from {low:g} to {high:g}"
    try:
        number = parse_factor(value, where)
    except InputError:
        raise InputError(where, value, words) from None
    if not low <= number <= high:
        raise InputError(where, value, words)
    return number


def _web_pattern(value: Any, where: str) -> str:
    """A counterweight pattern as written: ``all``, ``none``, ``file`` or 0/1 per web,
    ``1,0,0,1``; returned in one spelling (lower-case name, or the digits joined by commas)."""
    shown = value
    if isinstance(value, (list, tuple)):
        value = ",".join(str(v) for v in value)
    words = "must be all, none, file or 0/1 per web (two per throw) such as 1,0,0,1"
    if not isinstance(value, str):
        raise InputError(where, shown, words)
    text = value.strip().lower()
    if text in NAMED_PATTERNS:
        return text
    items = [item.strip() for item in text.split(",")]
    if len(items) < 2 or any(item not in ("0", "1") for item in items):
        raise InputError(where, shown, words)
    if len(items) > 2 * MAX_MAIN_BEARINGS:
        raise InputError(where, shown, f"must list at most {2 * MAX_MAIN_BEARINGS} webs")
    if "1" not in items:
        raise InputError(where, shown, "has no counterweight (all zeros): write none")
    return ",".join(items)


def _reading(value: Any, where: str) -> Any:
    """A balancing-machine reading as typed, ``"12.5 g @ 40 mm, 35 deg"``: the amount (a
    mass, 0 or more) at a radius, and the angle; -> (mass [kg], radius [m], angle [rad])."""
    if isinstance(value, (tuple, list)) and len(value) == 3:
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            return tuple(float(v) for v in value)  # as the settings hold it (SI)
    if not isinstance(value, str):
        raise InputError(where, value, f"must be {READING_WORDS}")
    amount, _at, rest = value.partition("@")
    radius, _comma, angle = rest.partition(",")
    if not (_at and _comma):
        raise InputError(where, value, f"must be {READING_WORDS}")
    mass = parse_quantity(amount, "mass", where)
    size = parse_quantity(radius, "length", where)
    turn = parse_quantity(angle, "angle", where)
    inside = [(mass, "mass", 0.0), (size, "length", RANGES["length"][0])]
    for number_, kind, low in (*inside, (turn, "angle", RANGES["angle"][0])):
        if not low <= number_ <= RANGES[kind][1]:
            raise InputError(where, value, f"must be {READING_WORDS}, in range")
    return (mass, size, turn)


def parse_torsional_stiffness(value: Any, where: str = "") -> float:
    """A torsional stiffness written with its unit per radian: ``"5e5 N*m/rad"`` [N m/rad]."""
    low, high = TORSIONAL_STIFFNESS_RANGE
    words = (
        f"a torsional stiffness such as {_TORSIONAL_EXAMPLE!r}, from {low:g} to {high:g} N*m/rad"
    )
    if not isinstance(value, str) or "rad" not in value:
        raise InputError(where, value, f"must be {words}")
    stiffness = parse_quantity(value.replace("/rad", "").replace("/ rad", ""), "torque", where)
    if not low <= stiffness <= high:
        raise InputError(where, value, f"must be {words}")
    return stiffness


def _stiffness(title: str, description: str) -> Any:
    """A torsional stiffness [N m/rad], not given by default."""
    low, high = TORSIONAL_STIFFNESS_RANGE
    return field(
        "any",
        default=None,
        parse=parse_torsional_stiffness,
        words=f"a torsional stiffness with its unit per radian, e.g. {_TORSIONAL_EXAMPLE!r}, "
        f"from {low:g} to {high:g} N*m/rad",
        title=title,
        description=description,
        metavar="STIFFNESS [N·m/rad]",
    )


def _plot_order(value: Any, where: str) -> Any:
    """A harmonic order from 1 to :data:`MAX_ORDER`, or ``"rotating"``."""
    if isinstance(value, str) and value.strip().lower() == "rotating":
        return "rotating"
    words = f"a harmonic order from 1 to {MAX_ORDER}, or 'rotating'"
    try:
        number = float(value) if not isinstance(value, bool) else math.nan
    except (TypeError, ValueError):
        raise InputError(where, value, f"must be {words}") from None
    if not (math.isfinite(number) and number == int(number) and 1 <= number <= MAX_ORDER):
        raise InputError(where, value, f"must be {words}")
    return int(number)


def _slender(length: float, diameter: float) -> None:
    """A shaft the beam model can describe: at least as long as its diameter."""
    if length < diameter:
        raise FieldProblem(
            "length",
            f"must be at least the diameter ({format_quantity(diameter, 'length', 6)}): the "
            "beam model needs a shaft longer than it is thick",
        )


class StudyOptions(Schema):
    """Base of the study settings: unknown keys are errors, values are frozen and finite."""

    UNKNOWN = ("unknown setting", "known")


# --------------------------------------------------------------------------------------
# the studies of the web form and the command line
# --------------------------------------------------------------------------------------


class AnalysisOptions(StudyOptions):
    """Free forces and moments: how many harmonic orders, and about which point."""

    orders: int = whole(
        8,
        "Highest order",
        "The highest harmonic order of the free forces and moments computed.",
        ge=1,
        le=MAX_ORDER,
    )
    moment_point: list[float] | None = three_lengths(
        "Moment point",
        "The point the moments (the roll moment included) are taken about, x, y, z: y along "
        "the crank from its mid-point, x across, z along the cylinder axis of an in-line "
        "engine (e.g. a mount centre or the engine's centre of mass); empty: the engine "
        "file's (crank_train.moment_point or moment_reference).",
    )


def counterweight_designs(population: int, iterations: int) -> int:
    """The designs a counterweight optimisation evaluates: its first sample and
    :data:`COUNTERWEIGHT_CHILDREN` per round."""
    return population + iterations * COUNTERWEIGHT_CHILDREN


class CounterweightOptions(StudyOptions):
    """Counterweight shape optimisation (Appl. Sci. 2021, Sec. 4-5)."""

    density: float = quantity(
        "density",
        8000.0,
        "Density",
        "Density of the counterweight's material.",
        hint="e.g. 8000 kg/m^3",
    )
    max_mass: float | None = quantity(
        "mass",
        None,
        "Largest mass",
        "The heaviest counterweight a design may have; empty: no limit.",
        hint="e.g. 400 g",
    )
    max_radius: float | None = quantity(
        "length",
        None,
        "Largest radial space",
        "The radial space a design may take from the crank axis; empty: no limit.",
        hint="e.g. 80 mm",
    )
    min_balance: float = number(
        100.0,
        "Smallest balance [%]",
        "The smallest first moment a design must reach, in per cent of the required one.",
        ge=1,
        le=1000,
    )
    iterations: int = whole(
        40,
        "Iterations",
        "Rounds of the optimiser after its first sample, each breeding "
        f"{COUNTERWEIGHT_CHILDREN} designs.",
        ge=0,
        le=1000,
    )
    population: int = whole(
        4096, "Population", "Designs of the optimiser's first sample.", ge=16, le=100_000
    )
    seed: int | None = whole(
        None,
        "Random seed",
        "Seed of the optimiser's random numbers, for repeatable runs; empty: a new seed each run.",
        ge=0,
        le=2**32 - 1,
    )

    def check(self) -> None:
        problem = self.budget_problem(2)
        if problem is not None:
            raise FieldProblem("iterations", problem)

    def check_budget(self, objectives: int) -> None:
        """Refuse more designs than the budget of ``objectives`` objectives (2: mass and
        radial space, 3: with the inertia), naming ``iterations``."""
        problem = self.budget_problem(objectives)
        if problem is not None:
            raise InputError("iterations", self.iterations, problem)

    def budget_problem(self, objectives: int) -> str | None:
        """What is wrong with the designs' budget of ``objectives`` objectives, or None."""
        designs = counterweight_designs(self.population, self.iterations)
        budget = MAX_COUNTERWEIGHT_DESIGNS if objectives < 3 else MAX_THREE_OBJECTIVE_DESIGNS
        if designs <= budget:
            return None
        return (
            f"must keep population + iterations x {COUNTERWEIGHT_CHILDREN} at most "
            f"{budget:,} designs, the optimiser's work budget with {objectives} objectives "
            f"(here {self.population:,} + {self.iterations:,} x {COUNTERWEIGHT_CHILDREN} = "
            f"{designs:,}): lower the iterations or the population"
        )


#: the profile parameters of a counterweight (the 2021 paper, Sec. 4), in the order of
#: :class:`crankbalance.physics.counterweight.CounterweightDesign`
PROFILE_PARAMETERS = (
    "web_radius",
    "rectangle_height",
    "trapezoid_angle",
    "segment_radius",
    "segment_angle",
    "thickness",
)


class CounterweightRequirementOptions(StudyOptions):
    """The first moment a counterweight must carry, m_c r_c: given, or from a mass and its
    CG radius (or from the engine's balancing, the study's engine)."""

    first_moment: float | None = _requirement(
        None,
        "Required first moment m_c r_c",
        "The first moment the counterweight must carry; empty: from the mass and CG radius, "
        "or from the engine's balancing.",
    )
    cw_mass: float | None = quantity(
        "mass", None, "Counterweight mass m_c", "The counterweight's mass, with its CG radius."
    )
    cg_radius: float | None = quantity(
        "length", None, "Counterweight CG radius r_c", "The radius of its centre of gravity."
    )


def _profile(title: str, metavar: str) -> Any:
    """A profile parameter of ``counterweight optimize``: a value fixes it, ``LOW..HIGH``
    leaves it free in that range (read by the study), empty: the optimiser's range;
    ``metavar`` its kind and unit in the command's help."""
    return text(
        None,
        f"{title} (value or LOW..HIGH)",
        "A value fixes the parameter, LOW..HIGH leaves it free in that range; empty: the "
        "optimiser's range.",
        metavar=metavar,
    )


class CounterweightOptimizeOptions(CounterweightOptions, CounterweightRequirementOptions):
    """``counterweight optimize``: the requirement, the profile parameters, the radial
    measure, the objectives and how many Pareto designs are listed."""

    web_radius: str | None = _profile("Web circle radius r_cw", "LENGTH [mm]")
    rectangle_height: str | None = _profile("Rectangle height h_R", "LENGTH [mm]")
    trapezoid_angle: str | None = _profile("Trapezoid angle delta", "ANGLE [°]")
    segment_radius: str | None = _profile("Segment radius R_cw", "LENGTH [mm]")
    segment_angle: str | None = _profile("Segment angle alpha", "ANGLE [°]")
    thickness: str | None = _profile("Thickness t_cw", "LENGTH [mm]")
    journal_diameter: float | None = quantity(
        "length",
        None,
        "Main journal diameter",
        "The web circle r_cw must clear the main journal: r_cw is searched from half this "
        "diameter up; empty: the engine's journal (1.3 x crank radius) with an engine, else "
        "no limit.",
        hint="e.g. 52 mm",
    )
    radius_measure: Literal["true", "paper"] = choice(
        "true",
        ("true", "paper"),
        "Radial space",
        "How the radial space is measured: true, the outer radius; paper, the 2021 paper's "
        "R_min bound.",
    )
    inertia: bool = field(
        "flag",
        default=False,
        title="Inertia as a third objective",
        description="Minimise the counterweight's moment of inertia too.",
    )
    pareto: int = whole(
        10,
        "Pareto designs listed",
        "How many designs of the Pareto front are listed, evenly spread along it.",
        ge=0,
        le=10**6,
    )

    def check(self) -> None:
        problem = self.budget_problem(3 if self.inertia else 2)
        if problem is not None:
            raise FieldProblem("iterations", problem)


class SingleCylinderOptions(StudyOptions):
    """One cylinder of an engine: balance factor study and the ISO 21940-11 check."""

    cylinder: int = whole(
        1,
        "Cylinder",
        "The cylinder of the engine studied alone (1-based).",
        ge=1,
        hint="1..number of cylinders",
    )
    balance_factor: float = number(
        0.5,
        "Balance factor",
        "Share of the cylinder's reciprocating mass balanced by its counterweight.",
        ge=BALANCE_FACTOR_LIMITS[0],
        le=BALANCE_FACTOR_LIMITS[1],
    )
    grade: str = text(
        "G6.3",
        "ISO 21940-11 grade",
        "The balance quality grade of the ISO check.",
        hint="e.g. G6.3",
    )
    rotor_mass: float | None = quantity(
        "mass",
        None,
        "Rotor mass",
        "The rotor's mass for the permissible residual unbalance.",
        hint="empty: the crank's rotating masses",
    )
    residual: float | None = quantity(
        "unbalance",
        None,
        "Measured residual unbalance",
        "A measured residual unbalance, checked against the permissible one.",
        hint="optional, e.g. 8 g*mm",
    )


class RebalanceOptions(StudyOptions):
    """Rebalancing one cylinder's throw after new parts (Hoem and Røsholm 2016, Sec. 6.4)."""

    new_reciprocating: float | None = quantity(
        "mass",
        None,
        "New reciprocating mass",
        "The cylinder's reciprocating mass with the new parts.",
        hint="empty: unchanged",
    )
    new_rotating: float | None = quantity(
        "mass",
        None,
        "New rotating mass",
        "The throw's rotating mass with the new parts.",
        hint="empty: unchanged",
    )
    cw_mass: float | None = quantity(
        "mass",
        None,
        "Counterweight mass (webs incl.)",
        "Mass of the counterweights with their webs.",
        hint="empty: what the balance factor needs at the CG radius",
    )
    cw_radius: float | None = quantity(
        "length",
        None,
        "Counterweight CG radius",
        "Radius of the centre of gravity of the counterweights with their webs.",
        hint="empty: crank radius",
    )
    hole_diameter: float = quantity(
        "length",
        0.008,
        "Drill diameter",
        "Diameter of the drill that takes material off the counterweights.",
        hint="e.g. 8 mm",
    )
    point_angle: float = _point_angle(
        math.pi,
        "Drill point angle",
        "The drill point's included angle (180 deg: flat-bottomed holes).",
        hint="e.g. 118 deg (180 deg: flat-bottomed)",
    )
    depth_to: DepthTo = choice(
        "tip",
        DEPTH_TO,
        "Depth read to the",
        "What the depth of a pointed hole is read to: the tip of the point or "
        "the shoulder where the cylinder ends.",
        hint="tip or shoulder",
    )
    holes: int = whole(
        1,
        "Holes per web",
        "Holes drilled side by side in each web.",
        ge=1,
        le=MAX_HOLES,
        hint="side by side, e.g. 2",
    )
    hole_radius: float | None = quantity(
        "length",
        None,
        "Hole radius",
        "Radius at which the holes are drilled.",
        hint="empty: counterweight CG radius",
    )
    web_thickness: float | None = quantity(
        "length",
        None,
        "Web thickness at the holes",
        "Axial thickness of the web at the holes: the deepest axial hole, to the tip.",
        hint="e.g. 14 mm (empty: the drill's reach alone)",
    )
    drill_length: float | None = quantity(
        "length",
        None,
        "Drill length",
        "Usable length of the drill: the deepest hole it makes, to the tip.",
        hint="empty: 10 drill diameters (a jobber drill)",
    )


class ShaftPlacementOptions(StudyOptions):
    """Unbalance-mass placement on a balance shaft with end bearings (Kim 2018, Sec. 3.1)."""

    length: float = quantity(
        "length",
        0.3,
        "Shaft length (between bearings)",
        "Length of the balance shaft between its end bearings.",
        hint="e.g. 300 mm",
    )
    diameter: float = quantity(
        "length", 0.025, "Shaft diameter", "Outer diameter of the balance shaft.", hint="e.g. 25 mm"
    )
    weight: float = _weight(
        2.0,
        "Objective weight w",
        "Weight w of the bearing-load difference against the bending in the "
        "placement objective (Kim 2018).",
        hint="e.g. 2",
    )
    points: int = whole(
        41,
        "Design points along the shaft",
        "Positions of the second mass tried along the shaft.",
        ge=3,
        le=MAX_SHAFT_POINTS,
    )

    def check(self) -> None:
        _slender(self.length, self.diameter)


class PerformanceOptions(StudyOptions):
    """Friction, bearing loads and shaking against the balance factor (Hoem and Røsholm
    2016, Sec. 5)."""

    bore: float | None = quantity(
        "length",
        None,
        "Bore",
        "Cylinder bore, for the gas force; empty: the engine's estimate, a square engine "
        "(bore = stroke), as Crank loads and bearings take it.",
        hint="empty: the engine's estimate, bore = stroke",
    )
    balance_factors: list[float] = _balance_factors(
        [0.0, 0.25, 0.5, 0.75, 1.0],
        "Balance factors",
        "The balance factors the study compares.",
        hint="e.g. 0, 0.25, 0.5, 0.75, 1",
    )
    crank_inertia: float | None = quantity(
        "inertia",
        None,
        "Crank + flywheel inertia",
        "Inertia of the purely rotating parts, which sets the speed fluctuation.",
        hint="empty: the engine's (front end, throws and flywheel)",
    )
    friction_coefficient: float = _friction(
        0.005,
        "Bearing friction coefficient",
        "Coulomb friction coefficient of the main bearings.",
        hint="e.g. 0.005",
    )
    journal_diameter: float | None = quantity(
        "length",
        None,
        "Main journal diameter",
        "Diameter of the main journals, the friction's lever arm; empty: the engine's "
        "estimate, 1.3 x crank radius, as Crank loads and bearings take it.",
        hint="empty: the engine's estimate, 1.3 x crank radius",
    )


# --------------------------------------------------------------------------------------
# the commands of the command line (crankbalance COMMAND --option ...)
# --------------------------------------------------------------------------------------


class BalanceOptions(StudyOptions):
    """``balance`` and ``report``: overrides of the engine file's counterweights."""

    angle: float | str | None = field(
        "angle",
        default=None,
        parse=_angle_or_optimal,
        words="'optimal' or "
        + core.allowed(entry("angle", ge=RANGES["angle"][0], le=RANGES["angle"][1])),
        title="Counterweight angle",
        description="Angle of the counterweights from the position opposite the crankpin, "
        "or optimal (least mass); empty: the engine file's, else optimal.",
        hint="'optimal' or e.g. 30 deg",
    )
    balance_factor: float | None = factor(
        None,
        "Balance factor",
        "Share of the pin's reciprocating mass put on the crank counterweights; "
        "empty: the engine file's.",
    )
    method: Literal["pattern", "individual"] | None = choice(
        None,
        ("pattern", "individual"),
        "Counterweight method",
        "pattern: equal counterweights (2021 paper); individual: each its own mass and "
        "angle; empty: the engine file's.",
    )
    scope: Literal["auto", "whole", "halves"] | None = choice(
        None,
        ("auto", "whole", "halves"),
        "Whole crank or halves",
        "Balance the whole crank or each half on its own; empty: the engine file's.",
    )
    verify: bool = field(
        "flag",
        default=False,
        title="Verify in the time domain",
        description="Also check the residuals in the time domain (every mass over a "
        "revolution, then a Fourier transform) and report how well the two agree.",
    )


class CounterweightDesignOptions(StudyOptions):
    """``counterweight optimize|show|export|check``: the requirement and the profile
    parameters (each a value, or for ``optimize`` both ends of a range)."""

    first_moment: float | None = _requirement(
        None, "Required first moment m_c r_c", "The first moment the counterweight must carry."
    )
    cw_mass: float | None = quantity(
        "mass",
        None,
        "Counterweight mass m_c",
        "Counterweight mass from the balancing (with the CG radius: the requirement).",
    )
    cg_radius: float | None = quantity(
        "length",
        None,
        "Counterweight CG radius r_c",
        "Radius of the counterweight's centre of gravity from the balancing.",
    )
    web_radius: float | None = quantity(
        "length", None, "Web circle radius r_cw", "Radius of the web's circle about the crank axis."
    )
    rectangle_height: float | None = _length_or_zero(
        None, "Rectangle height h_R", "Height of the profile's rectangle."
    )
    trapezoid_angle: float | None = quantity(
        "angle",
        None,
        "Trapezoid angle delta",
        "Angle delta of the profile's trapezoid flanks.",
        ge=0,
    )
    segment_radius: float | None = quantity(
        "length", None, "Segment radius R_cw", "Radius of the profile's outer circular segment."
    )
    segment_angle: float | None = quantity(
        "angle",
        None,
        "Segment angle alpha",
        "Angle alpha of the profile's outer circular segment.",
        gt=0,
    )
    thickness: float | None = quantity(
        "length", None, "Thickness t_cw", "Axial thickness of the counterweight."
    )
    density: float = quantity(
        "density", 8000.0, "Density", "Density of the counterweight's material."
    )
    unit: float = quantity(
        "length",
        1e-3,
        "Length unit of a CAD file",
        "The length one unit of a checked CAD file stands for.",
    )


class FrictionOptions(StudyOptions):
    """``friction``: bearing friction torque under a constant plus a rotating load."""

    load: float = quantity(
        "force",
        0.0,
        "Constant bearing load",
        "The constant part of the bearing load (weight, belt pull).",
    )
    rotating_load: float | None = quantity(
        "force",
        None,
        "Rotating load",
        "The rotating part of the bearing load (an unbalance force).",
    )
    unbalance: float | None = quantity(
        "unbalance",
        None,
        "Unbalance",
        "An unbalance whose force at the shaft speed is the rotating load.",
    )
    speed: float | None = quantity(
        "speed",
        None,
        "Shaft speed",
        "Shaft speed, for the rotating load of an unbalance and for the hydrodynamic bearing.",
    )
    journal_diameter: float | None = quantity(
        "length", None, "Journal diameter", "Diameter of the bearing journal."
    )
    friction_coefficient: float | None = _friction(
        None, "Friction coefficient", "Coulomb friction coefficient of the bearing."
    )
    torque: float | None = quantity(
        "torque",
        None,
        "Measured torque",
        "A measured friction torque, to back-compute the friction coefficient.",
    )
    viscosity: float | None = quantity(
        "viscosity",
        None,
        "Oil viscosity",
        "Dynamic viscosity of the oil of a hydrodynamic bearing.",
    )
    bearing_length: float | None = quantity(
        "length", None, "Bearing length", "Axial length of a hydrodynamic bearing."
    )
    clearance: float | None = quantity(
        "length", None, "Radial clearance", "Mean radial clearance of a hydrodynamic bearing."
    )
    eccentricity: float = number(
        0.0,
        "Eccentricity ratio",
        "Eccentricity of the journal in the bearing over the clearance.",
        ge=0,
        lt=1,
    )
    attitude_angle: float = quantity(
        "angle", 0.0, "Attitude angle", "Angle of the journal's eccentricity from the load."
    )


class BenchOptions(StudyOptions):
    """``bench``: the simulated rotor test bench (Hoem and Røsholm 2016, Sec. 5.2.5)."""

    mass: float = quantity("mass", 2.5464, "Rotor mass", "Mass of the rotor on the bench.")
    inertia: float = quantity(
        "inertia",
        2.847335e-3,
        "Rotor moment of inertia",
        "Moment of inertia of the rotor about its axis.",
    )
    unbalance: float = quantity("unbalance", 0.0, "Rotor unbalance", "Unbalance of the rotor.")
    journal_diameter: float = quantity(
        "length",
        0.02,
        "Journal diameter",
        "Diameter of the rotor's journals in the bench's bearings.",
    )
    friction_coefficient: float | None = _friction(
        None, "Friction coefficient", "Coulomb friction coefficient of each bearing."
    )
    speed: list[float] = field(
        "list",
        default=[3000 * _RPM],
        item=entry("speed", ge=RANGES["speed"][0], le=RANGES["speed"][1]),
        min_items=1,
        max_items=MAX_BENCH_RUNS,
        single=True,
        title="Set speeds",
        description="The speed each run ramps to and holds, one run per speed.",
    )
    ramp_time: float = quantity("time", 2.0, "Ramp time", "Duration of the speed ramp.")
    hold_time: float = quantity(
        "time",
        1.5,
        "Hold time",
        f"Duration of the hold (a run simulates at most {MAX_BENCH_REVOLUTIONS} revolutions).",
    )
    kp: float = number(
        0.2,
        "PI proportional gain [N m s/rad]",
        "Proportional gain of the bench's speed controller.",
        gt=0,
        le=1e4,
    )
    ki: float = number(
        10.0,
        "PI integral gain [N m/rad]",
        "Integral gain of the bench's speed controller.",
        ge=0,
        le=1e6,
    )

    def check(self) -> None:
        fastest = max(self.speed)
        turns = fastest / (2 * math.pi) * (self.ramp_time / 2 + self.hold_time)
        if turns > MAX_BENCH_REVOLUTIONS:
            raise FieldProblem(
                "hold_time",
                f"the run at {format_quantity(fastest, 'speed', 6)} would simulate "
                f"{turns:.3g} revolutions, at most {MAX_BENCH_REVOLUTIONS} are allowed: "
                "shorten the ramp and hold times or lower the speed",
            )
        proportional, integral = self.kp / self.inertia, math.sqrt(self.ki / self.inertia)
        rate = proportional + integral
        if rate * (self.ramp_time + self.hold_time) > MAX_BENCH_CONTROL:
            gain = "kp" if proportional >= integral else "ki"
            raise FieldProblem(
                gain,
                f"the controller (time constant {1 / rate:.3g} s against the rotor's inertia) "
                f"would need more than {MAX_BENCH_CONTROL} steps over the run: lower --kp "
                "and --ki, raise the inertia or shorten the run",
            )


class CombustionOptions(StudyOptions):
    """The gas pressure of a cycle: the Wiebe model (Hoem and Røsholm 2016) or pressure
    tables, one for every cylinder or one per cylinder; shared by ``cycle``,
    ``sensitivity``, ``bearings`` and ``torsional`` with the same defaults (the thesis'
    combustion, docs/engine_cycle.md)."""

    compression_ratio: float = number(
        13.5,
        "Compression ratio",
        "Geometric compression ratio of the Wiebe model's cylinder.",
        gt=1,
        le=100,
    )
    # the Wiebe model's own ranges (engine_cycle.IGNITION_RANGE, BURN_DURATION_RANGE)
    ignition: float = quantity(
        "angle",
        math.radians(-25.0),
        "Start of combustion from firing TDC",
        "Crank angle of the start of combustion from firing top dead centre (negative: before it).",
        ge=IGNITION_RANGE[0],
        le=IGNITION_RANGE[1],
    )
    burn_duration: float = quantity(
        "angle",
        math.radians(50.0),
        "Burn duration",
        "Crank angle over which the Wiebe model burns the charge.",
        ge=BURN_DURATION_RANGE[0],
        le=BURN_DURATION_RANGE[1],
    )
    intake_pressure: float = quantity(
        "pressure",
        1e5,
        "Pressure at the start of compression",
        "Cylinder pressure at the start of compression: the engine's load.",
    )
    heat_release: float | None = quantity(
        "energy",
        None,
        "Heat released per cycle",
        "Heat the charge releases in one cylinder per cycle (not with fuel_mass).",
        hint="empty: from the charge (pressure at the start of compression, 320 K, "
        "air/fuel 14.7, heating value, combustion efficiency)",
        gt=0,
        le=1e7,
    )
    fuel_mass: float | None = quantity(
        "mass",
        None,
        "Fuel per cycle",
        "Fuel burnt in one cylinder per cycle; the heat released is combustion_efficiency x "
        "fuel_mass x heating_value (not with heat_release).",
        hint="empty: from the charge",
        gt=0,
        le=10.0,
    )
    heating_value: float = quantity(
        "specific_energy",
        44e6,
        "Heating value of the fuel",
        "Lower heating value of the fuel (the heat released from the charge or from fuel_mass).",
        ge=1e6,
        le=2e8,
    )
    combustion_efficiency: float = number(
        0.8,
        "Combustion efficiency",
        "Share of the fuel's energy released as heat in the cylinder (lumps the heat lost to "
        "the walls); not with heat_release.",
        gt=0,
        le=1,
    )
    gamma: float = number(
        1.3,
        "Ratio of specific heats",
        "Ratio of specific heats of the charge, cp/cv, in compression, combustion and expansion.",
        ge=GAMMA_RANGE[0],
        le=GAMMA_RANGE[1],
    )
    exhaust_pressure: float | None = quantity(
        "pressure",
        None,
        "Exhaust back-pressure",
        "Cylinder pressure during the exhaust stroke of a four-stroke (a two-stroke is "
        "scavenged at bottom dead centre).",
        hint="empty: the pressure at the start of compression",
    )
    burn_end: str = choice(
        "complete",
        BURN_ENDS,
        "End of the burn",
        "The Wiebe burn's end: complete (its exponential tail runs on past the burn duration "
        "to a complete burn) or stop (it ends at the burn duration, 99.3 % burnt).",
    )
    pressure_csv: list[str] = field(
        "list",
        default=[],
        item=entry("text", max_chars=MAX_SETTING_CHARS),
        max_items=MAX_PRESSURE_TABLES,
        single=True,
        words=f"at most {MAX_PRESSURE_TABLES} files, the option given once for each",
        title="Cylinder pressure tables",
        description="Cylinder pressure tables instead of the Wiebe model (crank angle [° "
        "from firing TDC], absolute pressure [bar]): one for every cylinder, or one per "
        "cylinder in cylinder order.",
    )

    def check(self) -> None:
        typed = self.given()
        if "heat_release" in typed and "fuel_mass" in typed:
            raise FieldProblem(
                "fuel_mass", "cannot be given with heat_release: give the one or the other"
            )
        if "heat_release" in typed:
            for name in ("heating_value", "combustion_efficiency"):
                if name in typed:
                    raise FieldProblem(
                        name, "cannot act with heat_release (the heat released is given)"
                    )


class CycleOptions(CombustionOptions):
    """``cycle`` and ``sensitivity``: one cylinder (typed, or of the study's engine) or the
    whole engine (an engine without ``cylinder``: every cylinder firing), its gas pressure
    (the Wiebe model, or tables: one for every cylinder or one per cylinder) and the
    flywheel. With an engine, stroke, conrod length, reciprocating mass, speed and strokes
    are the engine's unless given (:meth:`~crankbalance.schema.core.Schema.given`), and so
    are the bore and main journal (the engine's estimate,
    :func:`crankbalance.studies.performance.engine_estimate`: bore = stroke, journal 1.3 x
    crank radius, as ``bearings``); without an engine they are the thesis' single's."""

    cylinder: int | None = whole(
        None,
        "Cylinder of the engine (none: all cylinders)",
        "With an engine: the cylinder studied alone; empty: every cylinder firing.",
        ge=1,
        le=10_000,
    )
    bore: float = quantity(
        "length",
        0.0768,
        "Bore",
        "Cylinder bore; not given: with an engine its estimate (bore = stroke, as "
        "bearings), else the thesis' 76.8 mm.",
    )
    stroke: float = quantity("length", 0.0538, "Stroke", "Piston stroke, twice the crank radius.")
    rod_length: float = quantity(
        "length", 0.1035, "Conrod length", "Centre distance of the conrod."
    )
    reciprocating_mass: float = quantity(
        "mass", 0.282, "Reciprocating mass", "Reciprocating mass of the cylinder."
    )
    crank_inertia: float | None = quantity(
        "inertia",
        None,
        "Crank + flywheel inertia",
        "Inertia of all purely rotating parts, which sets the speed fluctuation.",
        hint=f"empty: {THESIS_CRANK_INERTIA:g} kg*m^2 (the thesis' single) without "
        f"an engine; with one, {ENGINE_INERTIA_TEXT.removeprefix('empty: ')}",
    )
    journal_diameter: float = quantity(
        "length",
        0.03,
        "Main journal diameter",
        "Diameter of the main journal, the friction's lever arm; not given: with an engine "
        "its estimate (1.3 x crank radius, as bearings), else the thesis' 30 mm.",
    )
    friction_coefficient: float = _friction(
        0.005, "Friction coefficient", "Coulomb friction coefficient of the main bearing."
    )
    speed: float = quantity("speed", 9000 * _RPM, "Mean speed", "Mean crank speed of the cycle.")
    strokes: int = whole(4, "Strokes per cycle", "2 or 4 strokes per working cycle.", ge=2, le=4)
    balance_factor: float = factor(
        0.5,
        "Balance factor",
        "One cylinder: share of the reciprocating mass on the counterweight, on "
        "top of the rotating mass.",
    )
    flywheel_inertia: float | None = quantity(
        "inertia",
        None,
        "Flywheel inertia (added to the crank)",
        "A flywheel's inertia, added to the crank inertia.",
    )
    speed_fluctuation_target: float | None = factor(
        None,
        "Speed fluctuation to size the flywheel for",
        "Size the flywheel for this speed fluctuation (max - min) / mean.",
        low=FLUCTUATION_TARGET[0],
        high=FLUCTUATION_TARGET[1],
    )


class SensitivityOptions(CycleOptions):
    """``sensitivity``: the cycle swept over balance factors and reciprocating-mass scales."""

    cylinder: int = whole(
        1, "Cylinder of the engine", "With an engine: the cylinder studied.", ge=1, le=10_000
    )
    pressure_csv: list[str] = field(
        "list",
        default=[],
        item=entry("text", max_chars=MAX_SETTING_CHARS),
        max_items=1,
        single=True,
        words="at most 1 file, the option given once for each",
        title="Cylinder pressure table",
        description="A cylinder pressure table instead of the Wiebe model (crank angle [° "
        "from firing TDC], absolute pressure [bar]).",
    )
    balance_factors: list[float] = _balance_factors(
        [0.1 * k for k in range(11)], "Balance factors", "The balance factors of the sweep."
    )
    mass_scales: list[float] = field(
        "list",
        default=[1.0],
        item=entry("number", gt=0, le=10),
        min_items=1,
        max_items=MAX_SWEEP,
        parse=_number_sweep,
        title="Reciprocating-mass scales",
        description="Factors on the reciprocating mass (lighter parts below 1).",
    )


class CrankDimensionOptions(StudyOptions):
    """The crank's dimensions ``bearings`` and ``torsional`` may be given; empty ones are
    the engine's, from its crank radius and web offset
    (:func:`crankbalance.studies.crank.crank_dimensions`), the same for both."""

    journal_diameter: float | None = quantity(
        "length",
        None,
        "Main journal diameter",
        "Diameter of the main journals.",
        hint=ENGINE_DIMENSION_TEXT,
    )
    pin_diameter: float | None = quantity(
        "length",
        None,
        "Crankpin diameter",
        "Diameter of the crankpins.",
        hint=ENGINE_DIMENSION_TEXT,
    )
    web_thickness: float | None = quantity(
        "length",
        None,
        "Web thickness (axial)",
        "Axial thickness of a crank web.",
        hint=ENGINE_DIMENSION_TEXT,
    )
    web_width: float | None = quantity(
        "length",
        None,
        "Web width (across the arm)",
        "Width of a crank web across its arm.",
        hint=ENGINE_DIMENSION_TEXT,
    )


class BearingOptions(CombustionOptions, CrankDimensionOptions):
    """``bearings``: main-bearing loads and crank bending over the engine cycle
    (docs/main_bearings.md). Crank dimensions left empty are taken from the crank radius
    and the web offset (proportions of an automotive crank,
    :func:`crankbalance.studies.crank.crank_dimensions`), an empty crank + flywheel inertia
    is the engine's (:func:`crankbalance.studies.crank.rotating_inertia`) and the combustion
    is :class:`CombustionOptions`': the same as ``cycle --engine`` and ``torsional``."""

    speed: float | None = quantity(
        "speed", None, "Mean speed", "Mean crank speed of the cycle.", hint="empty: the engine's"
    )
    samples: int = whole(
        360,
        "Samples per revolution",
        "Crank-angle samples per revolution of the cycle.",
        ge=MIN_SAMPLES,
        le=MAX_SAMPLES,
    )
    gas: bool = field(
        "flag",
        default=True,
        title="Gas forces",
        description="Gas forces from the Wiebe model or the pressure tables; off: inertia "
        "forces only.",
        hint="off: inertia forces only",
    )
    bore: float | None = quantity(
        "length",
        None,
        "Bore",
        "Cylinder bore, for the gas force.",
        hint="empty: square engine (bore = stroke)",
    )
    crank_inertia: float | None = quantity(
        "inertia",
        None,
        "Crank + flywheel inertia",
        "Inertia of the purely rotating parts, which sets the speed fluctuation.",
        hint=ENGINE_INERTIA_TEXT,
    )
    balance_factor: float | None = factor(
        None,
        "Balance factor",
        "Balance factor of the counterweights.",
        hint="empty: the engine file's",
    )
    webs: list[int] | None = field(
        "list",
        default=None,
        item=entry("whole", ge=0, le=1),
        min_items=2,
        max_items=2 * MAX_MAIN_BEARINGS,
        title="Counterweight webs (0/1, two per throw)",
        description="The counterweight pattern, 0/1 per web, two per throw.",
        hint="empty: the engine file's",
    )
    modulus: float = quantity(
        "modulus", 210e9, "Young's modulus of the crank", "Young's modulus of the crank's material."
    )
    poisson: float = number(
        0.3, "Poisson's ratio", "Poisson's ratio of the crank's material.", gt=-1, lt=0.5
    )
    bearing: list[float] | None = field(
        "list",
        default=None,
        item=entry("length", ge=RANGES["position"][0], le=RANGES["position"][1]),
        min_items=2,
        max_items=MAX_MAIN_BEARINGS,
        single=True,
        title="Main-bearing positions",
        description="Main-bearing positions along the crank from its mid-point; empty: "
        "one between neighbouring throws and one at each end.",
    )
    bearing_stiffness: float | None = quantity(
        "stiffness",
        None,
        "Radial bearing stiffness",
        "Radial stiffness of each main bearing.",
        hint="empty: rigid bearings",
    )
    friction_coefficient: float = _friction(
        0.005, "Friction coefficient", "Coulomb friction coefficient of the main bearings."
    )
    viscosity: float | None = quantity(
        "viscosity", None, "Oil viscosity (Petroff)", "Oil viscosity, for the Petroff friction."
    )
    bearing_length: float | None = quantity(
        "length",
        None,
        "Bearing length (Petroff)",
        "Axial length of the main bearings, for the Petroff friction.",
    )
    clearance: float | None = quantity(
        "length",
        None,
        "Radial clearance",
        "Radial clearance of the main bearings: in the contact model with a "
        "bearing stiffness, in the Petroff friction with viscosity and bearing length.",
        hint="Petroff friction; contact with a stiffness",
    )
    curves: bool = field(
        "flag",
        default=False,
        title="Curves in the JSON",
        description="The load and moment curves over the cycle in the JSON result.",
    )

    def check(self) -> None:
        CombustionOptions.check(self)
        trio = ("viscosity", "bearing_length", "clearance")
        given = [name for name in trio if getattr(self, name) is not None]
        if given and given != ["clearance"] and len(given) < 3:
            missing = next(name for name in trio if getattr(self, name) is None)
            raise FieldProblem(
                given[0],
                f"needs {missing.replace('_', ' ')} too: the Petroff friction takes "
                "viscosity, bearing length and clearance together",
            )
        if (
            self.clearance is not None
            and self.bearing_stiffness is not None
            and self.bearing_stiffness > MAX_CLEARANCE_STIFFNESS
        ):
            raise FieldProblem(
                "bearing_stiffness",
                f"must be at most {MAX_CLEARANCE_STIFFNESS:g} N/m with a clearance (the "
                "contact solution converges up to there; stiffer rings are the model "
                "without clearance)",
            )
        if given == ["clearance"] and self.bearing_stiffness is None:
            raise FieldProblem(
                "clearance",
                "needs a bearing stiffness (the rings' contact) or viscosity and bearing "
                "length (Petroff friction) to act",
            )


class BearingSweepOptions(StudyOptions):
    """``bearings-sweep``: the main-bearing loads over counterweight patterns and balance
    factors (docs/main_bearings.md); the loads' own settings are :class:`BearingOptions`.
    ``none`` is one case whatever the balance factors."""

    patterns: list[str] = field(
        "list",
        default=["all"],
        item=entry("any", parse=_web_pattern, words="all, none, file or 0/1 per web"),
        min_items=1,
        max_items=MAX_PATTERNS,
        single=True,
        title="Counterweight patterns",
        description="The counterweight patterns compared: all, none, file (the engine "
        "file's) or 0/1 per web, two per throw.",
        hint="all, none, file or 0/1 per web: 1,0,0,1,1,0,0,1",
    )
    balance_factors: list[float] = _balance_factors(
        [0.0, 0.25, 0.5, 0.75, 1.0],
        "Balance factors",
        "The balance factors of the patterns with counterweights.",
        hint="e.g. 0.4, 0.5, 0.6",
    )
    crank_model: Literal["indeterminate", "determinate"] = choice(
        "indeterminate",
        ("indeterminate", "determinate"),
        "Crank model of the table and the figure",
        "The crank model the table and the figure show (the JSON has both).",
    )

    def check(self) -> None:
        if len(set(self.patterns)) < len(self.patterns):
            twice = next(p for p in self.patterns if self.patterns.count(p) > 1)
            raise FieldProblem("patterns", f"must give each pattern once ({twice} twice)")
        if len(set(self.balance_factors)) < len(self.balance_factors):
            again = next(f for f in self.balance_factors if self.balance_factors.count(f) > 1)
            raise FieldProblem(
                "balance_factors", f"must give each balance factor once ({again:g} twice)"
            )
        swept = sum(p != "none" for p in self.patterns)
        cases = swept * len(self.balance_factors) + ("none" in self.patterns)
        if cases > MAX_SWEEP_CASES:
            raise FieldProblem(
                "patterns",
                f"must make at most {MAX_SWEEP_CASES} cases (patterns other than none times "
                f"balance factors, and none once): here {cases}",
            )


#: the settings of ``bearings`` that ``bearings-sweep`` does not take: it sweeps the
#: balance factor and the counterweight pattern, and has no curves
NOT_SWEPT = ("balance_factor", "webs", "curves")


class BearingSweepStudyOptions(BearingSweepOptions, BearingOptions):
    """``bearings-sweep`` as one study: the sweep (:class:`BearingSweepOptions`) and the
    loads' settings of every case (:class:`BearingOptions`, but for :data:`NOT_SWEPT`)."""

    def check(self) -> None:
        for name in NOT_SWEPT:
            if name in self.given():
                raise FieldProblem(
                    name,
                    "is not a setting of the sweep: it sweeps the balance factors and the "
                    "counterweight patterns (balance_factors, patterns) and has no curves",
                )
        BearingSweepOptions.check(self)
        BearingOptions.check(self)

    def loads(self) -> BearingOptions:
        """The settings of the loads of every case (the given ones still given)."""
        return _part(self, BearingOptions)

    def sweep(self) -> BearingSweepOptions:
        """The sweep's own settings."""
        return _part(self, BearingSweepOptions)


Part = TypeVar("Part", bound="StudyOptions")


def _part(settings: StudyOptions, model: type[Part]) -> Part:
    """The settings of ``model`` within ``settings`` (a schema made of several), its given
    fields still given."""
    given = settings.given()
    part = model(**{name: getattr(settings, name) for name in model.FIELDS if name in given})
    part.__dict__.update({name: getattr(settings, name) for name in model.FIELDS})
    return part


class ShaftSectionOptions(StudyOptions):
    """``shaft ...``: the shaft's section and material, the masses' radius, the bearings."""

    length: float = quantity("length", 0.3, "Shaft length", "Length of the balance shaft.")
    diameter: float = quantity("length", 0.025, "Outer diameter", "Outer diameter of the shaft.")
    bore: float = _length_or_zero(
        0.0, "Bore diameter (hollow shaft)", "Bore of a hollow shaft; 0 for a solid one."
    )
    modulus: float = quantity(
        "modulus", 210e9, "Young's modulus", "Young's modulus of the shaft's material."
    )
    density: float = quantity("density", 7850.0, "Density", "Density of the shaft's material.")
    poisson: float = number(
        0.3, "Poisson's ratio", "Poisson's ratio of the shaft's material.", gt=-1, lt=0.5
    )
    unbalance_radius: float = quantity(
        "length",
        0.02,
        "CG radius of the unbalance masses",
        "Radius of the unbalance masses' centres of gravity (their mass is the unbalance over it).",
    )
    bearing_stiffness: float | None = quantity(
        "stiffness",
        None,
        "Radial bearing stiffness",
        "Radial stiffness of the shaft's bearings; empty: rigid.",
    )
    theory: Literal["euler-bernoulli", "timoshenko"] = choice(
        "euler-bernoulli",
        ("euler-bernoulli", "timoshenko"),
        "Beam theory",
        "The beam theory of the shaft: euler-bernoulli, or timoshenko (shear and rotary inertia).",
    )

    def check(self) -> None:
        _slender(self.length, self.diameter)


class ShaftStudyOptions(ShaftSectionOptions):
    """``shaft inline4|inline3``: the required unbalance (given, or from the study's
    engine) and the placement sweep; ``order`` is inline4's, ``type``, ``hold``,
    ``bearing_offset`` and ``z_min`` inline3's."""

    unbalance: float | None = _requirement(
        None,
        "Required first moment",
        "The first moment m e the shaft must carry (without an engine).",
    )
    speed: float | None = quantity(
        "speed", None, "Shaft speed", "The shaft's speed (without an engine)."
    )
    weight: float = _weight(
        2.0,
        "Objective weight w",
        "Weight w of the bearing-load difference against the bending in the "
        "placement objective (Kim 2018).",
    )
    weights: list[float] | None = field(
        "list",
        default=None,
        item=entry("number", ge=0, le=1000),
        min_items=1,
        max_items=MAX_SWEEP,
        title="Weights of the sweep",
        description="The weights w of the sweep; empty: 20 values from 0.2 to 4.",
    )
    points: int = whole(
        200, "Design points", "Positions tried along the shaft.", ge=3, le=MAX_SHAFT_POINTS
    )
    secondary: Literal["reaction-difference", "inverse-frequency"] | None = choice(
        None,
        ("reaction-difference", "inverse-frequency"),
        "B of the objective",
        "The second term B of the placement objective; empty: reaction-difference for "
        "inline4, inverse-frequency for inline3.",
    )
    order: int | None = whole(
        None,
        "Order of the shaft the engine needs (1 or 2)",
        "The order of the balance shaft; empty: 2 when the engine has a free second-order "
        "force or moment, else 1.",
        ge=1,
        le=2,
    )
    type: Literal["I", "II", "III", "all"] = choice(
        "all", ("I", "II", "III", "all"), "Rotor type", "The inline3 rotor types studied."
    )
    hold: Literal["couple", "unbalance"] = choice(
        "couple",
        ("couple", "unbalance"),
        "Keep the couple or each unbalance",
        "What the inline3 sweep keeps: the couple (physical) or each mass's unbalance "
        "(the paper's).",
    )
    bearing_offset: float | None = quantity(
        "length",
        None,
        "Bearing-to-mass distance",
        "Distance of a bearing from its nearest mass; empty: 0.1 of the length.",
    )
    z_min: float = number(
        0.3,
        "Smallest second-mass position z/L",
        "The smallest position of the second mass in the sweep, as a share of the length.",
        ge=0,
        lt=1,
    )


class ShaftCheckOptions(ShaftSectionOptions):
    """``shaft check``: one layout (bearings, masses, unbalances, phases) and its limits."""

    bearing: list[float] = field(
        "list",
        default=[],
        item=entry("length", ge=RANGES["position"][0], le=RANGES["position"][1]),
        min_items=2,
        max_items=MAX_SHAFT_ITEMS,
        single=True,
        title="Bearing positions",
        description="Bearing positions from the shaft's end, at least two.",
    )
    mass: list[float] = field(
        "list",
        default=[],
        item=entry("length", ge=RANGES["position"][0], le=RANGES["position"][1]),
        min_items=1,
        max_items=MAX_SHAFT_ITEMS,
        single=True,
        title="Mass positions",
        description="Positions of the unbalance masses from the shaft's end.",
    )
    unbalance: list[float] = field(
        "list",
        default=[],
        item=entry("unbalance", ge=RANGES["unbalance"][0], le=RANGES["unbalance"][1]),
        min_items=1,
        max_items=MAX_SHAFT_ITEMS,
        single=True,
        title="Unbalances",
        description="The unbalance of each mass, in the order of the masses.",
    )
    phase: list[float] = field(
        "list",
        default=[],
        item=entry("angle", ge=RANGES["angle"][0], le=RANGES["angle"][1]),
        max_items=MAX_SHAFT_ITEMS,
        single=True,
        title="Phases",
        description="The angle of each mass about the shaft; empty: all at 0.",
    )
    speed: float | None = quantity("speed", None, "Shaft speed", "The shaft's running speed.")
    max_speed: float | None = quantity(
        "speed",
        None,
        "Maximum shaft speed",
        "The highest speed of the checks; empty: the shaft speed.",
    )
    margin: float = number(
        0.25,
        "Critical-speed separation",
        "Required separation of the first critical speed above the maximum "
        "speed, as a share of it.",
        ge=0,
        le=10,
    )
    bearing_capacity: float | None = quantity(
        "force", None, "Bearing load", "The load a bearing may carry.", gt=0
    )
    deflection_limit: float | None = quantity(
        "length", None, "Allowed deflection", "The largest deflection the shaft may have."
    )


class BalanceFactorOptions(StudyOptions):
    """``balance-factor``: one crank's balance factor, bob-weight and force study."""

    reciprocating_mass: float | None = quantity(
        "mass", None, "Reciprocating mass", "Reciprocating mass m_rec."
    )
    crank_radius: float | None = quantity(
        "length", None, "Crank radius", "Crank throw radius, half the stroke."
    )
    rotating_mass: float | None = quantity(
        "mass", None, "Rotating mass", "Rotating mass m_rot: crankpin, big end and its bearing."
    )
    cw_mass: float | None = quantity(
        "mass",
        None,
        "Counterweight mass (webs incl.)",
        "Mass of the counterweights with their webs.",
    )
    cw_radius: float | None = quantity(
        "length",
        None,
        "Counterweight CG radius",
        "Radius of the centre of gravity of the counterweights with their webs.",
    )
    balance_factor: float | None = factor(
        None,
        "Balance factor studied",
        "The balance factor f_b studied; empty: the crank's own if its mass "
        "properties are given, else 0.5.",
    )
    target: float | None = factor(
        None,
        "Balance factor of the bob-weight",
        "The balance factor the bob-weight is sized for; empty: the one studied.",
    )
    speed: float | None = quantity("speed", None, "Crank speed", "Crank speed for the force study.")
    rod_length: float | None = quantity(
        "length", None, "Conrod length", "Conrod length, for the exact kinematics."
    )
    offset: float | None = quantity(
        "length",
        None,
        "Wrist-pin offset",
        "Offset of the wrist-pin path from the crank axis.",
        within="position",
    )
    kinematics: Literal["exact", "series", "first-order"] | None = choice(
        None,
        ("exact", "series", "first-order"),
        "Piston kinematics",
        "The piston kinematics of the force study; empty: the engine's, without an engine "
        "exact with a conrod length, else first-order.",
    )
    cylinder: int = whole(
        1, "Cylinder of the engine", "The engine's cylinder studied (1-based).", ge=1, le=10_000
    )


class RebalancePartsOptions(StudyOptions):
    """``rebalance``: a parts file and the settings that override its values (the file's
    own schema, :mod:`crankbalance.io.rebalance_file`, then checks how they combine)."""

    parts: str | None = text(None, "Parts file (TOML)", "The parts file of the rebalancing.")
    crank_radius: float | None = quantity("length", None, "Crank radius", "Crank throw radius.")
    cw_mass: float | None = quantity(
        "mass",
        None,
        "Counterweight mass (webs incl.)",
        "Mass of the counterweights with their webs.",
    )
    cw_radius: float | None = quantity(
        "length",
        None,
        "Counterweight CG radius",
        "Radius of the centre of gravity of the counterweights with their webs.",
    )
    old_rotating_mass: float | None = quantity(
        "mass", None, "Rotating mass, old parts", "The rotating mass with the old parts."
    )
    old_reciprocating_mass: float | None = quantity(
        "mass", None, "Reciprocating mass, old parts", "The reciprocating mass with the old parts."
    )
    new_rotating_mass: float | None = quantity(
        "mass", None, "Rotating mass, new parts", "The rotating mass with the new parts."
    )
    new_reciprocating_mass: float | None = quantity(
        "mass", None, "Reciprocating mass, new parts", "The reciprocating mass with the new parts."
    )
    target: list[float | str] = field(
        "list",
        default=[],
        item=entry(
            "any",
            parse=_target,
            words="'factory' or a number from 0 to 2 (or a percentage)",
        ),
        max_items=50,
        single=True,
        title="Target balance factors",
        description="The balance factors to rebalance to; factory: the crank's own.",
    )
    method: Literal["face", "holes"] | None = choice(
        None, ("face", "holes"), "Correction method", "Grind a face or drill holes."
    )
    correction_radius: float | None = quantity(
        "length", None, "Radius of the correction", "Radius at which material comes off."
    )
    face_area: float | None = quantity(
        "area", None, "Face area ground per web", "Area of the face ground off each web."
    )
    face_orientation: Literal["radial", "axial"] | None = choice(
        None,
        ("radial", "axial"),
        "Face ground radially or axially",
        "Whether the face is ground radially or axially.",
    )
    hole_diameter: float | None = quantity(
        "length", None, "Drill diameter", "Diameter of the drill."
    )
    holes: int | None = whole(
        None, "Holes per web", "Holes drilled side by side in each web.", ge=1, le=1000
    )
    hole_direction: Literal["axial", "radial"] | None = choice(
        None, ("axial", "radial"), "Hole direction", "The direction of the holes."
    )
    point_angle: float | None = _point_angle(
        None,
        "Drill point angle (180 deg: flat)",
        "The drill point's included angle (180 deg: flat-bottomed holes).",
    )
    depth_to: DepthTo | None = choice(
        None,
        DEPTH_TO,
        "Depth read to",
        "What the depths of pointed holes are read to: tip or shoulder.",
    )
    web_thickness: float | None = quantity(
        "length",
        None,
        "Web thickness at the holes",
        "Axial thickness of the web at the holes: the deepest axial hole.",
    )
    drill_length: float | None = quantity(
        "length",
        None,
        "Drill length",
        "Usable length of the drill: the deepest hole it makes, to the tip.",
    )
    density: float | None = quantity(
        "density", None, "Crank material density", "Density of the crank's material."
    )
    depth_resolution: float | None = _length_or_zero(
        None, "Machining step", "The step the depths are rounded to."
    )
    grade: str | None = text(
        None, "ISO 21940-11 grade", "The balance quality grade for the tolerance."
    )
    rotor_mass: float | None = quantity(
        "mass", None, "Crank mass", "The crank's mass, for the tolerance."
    )
    speed: float | None = quantity(
        "speed", None, "Largest service speed", "The largest service speed, for the tolerance."
    )
    tolerance: float | None = _requirement(
        None,
        "Permissible residual unbalance",
        "The permissible residual unbalance, instead of a grade.",
    )


def _positions(title: str, description: str) -> Any:
    """Two axial positions (measuring or correction planes, bearings) [m]."""
    return field(
        "list",
        default=None,
        item=entry("length", ge=RANGES["position"][0], le=RANGES["position"][1]),
        min_items=2,
        max_items=2,
        title=title,
        description=description,
    )


#: most engines one ``shop scatter`` draws
MAX_SCATTER_SAMPLES = 10_000_000
#: the coarsest resolution of the scale of ``shop scatter`` [kg]
MAX_SCALE_STEP = 0.01


def _scale_step(value: Any, where: str) -> float:
    """The resolution of a scale: 0 (exact), or a mass up to :data:`MAX_SCALE_STEP`."""
    if isinstance(value, str) and value.strip() == "0":
        return 0.0
    if isinstance(value, int | float) and not isinstance(value, bool) and value == 0:
        return 0.0
    step = core.parse_in_range(value, "mass", where)
    if not 0 <= step <= MAX_SCALE_STEP:
        raise InputError(where, value, "must be a mass from 0 to 10 g")
    return step


class ShopOptions(StudyOptions):
    """The balance shop (issue 16): the parts file, matching, bob-weights, readings to a hole
    plan, the ISO check, and the Monte Carlo of the weight scatter."""

    parts: str | None = text(None, "Parts file (CSV or TOML)", "The parts file of the shop.")
    fraction: float = factor(
        0.5,
        "Reciprocating fraction in the bob-weights",
        "Share of the reciprocating weight in the bob-weights.",
    )
    method: Literal["milp", "pairing", "exhaustive", "as-listed"] = choice(
        "milp",
        ("milp", "pairing", "exhaustive", "as-listed"),
        "Matching method",
        "How the parts are matched: milp (least spread, proven optimal within "
        "the time limit), pairing, exhaustive, or as listed.",
    )
    time_limit: float = quantity(
        "time",
        60.0,
        "Matching time limit",
        "Longest matching, the building of the model included (and again for the "
        "pairing of the sets on the journals).",
        le=3600.0,
    )
    journals: Literal["paired", "joint", "as-listed"] = choice(
        "paired",
        ("paired", "joint", "as-listed"),
        "Sets on the journals",
        "Which matched sets share a journal: paired (the least spread of the journals' "
        "bob-weights, after the matching), joint (the parts matched for that spread at "
        "once; method milp or exhaustive), or as listed (set c in cylinder c).",
    )
    reading: list[tuple[float, float, float]] = field(
        "list",
        default=[],
        item=entry("any", parse=_reading, words=READING_WORDS),
        max_items=2,
        single=True,
        title="Readings, one per measuring plane",
        description="The balancing machine's readings, measuring plane 1 then 2.",
    )
    convention: Literal["heavy", "light"] = choice(
        "heavy",
        ("heavy", "light"),
        "Reading convention",
        "The readings' angle is the heavy spot or the light spot.",
    )
    measuring_planes: list[float] | None = _positions(
        "Measuring planes", "Axial positions of the two measuring planes."
    )
    correction_planes: list[float] | None = _positions(
        "Correction planes", "Axial positions of the two correction planes."
    )
    hole_diameter: float = quantity("length", 0.008, "Drill diameter", "Diameter of the drill.")
    hole_radius: float | None = quantity(
        "length", None, "Radius of the holes", "Radius of the axial holes (or of the rim)."
    )
    max_depth: float = quantity("length", 0.015, "Deepest hole", "The deepest hole allowed.")
    web_thickness: float | None = quantity(
        "length",
        None,
        "Web thickness at the holes",
        "Axial thickness of the web at the holes: the deepest axial hole, the widest radial one.",
    )
    depth_to: DepthTo | None = choice(
        None,
        DEPTH_TO,
        "Depth read to",
        "What the depths are read to: tip or shoulder (required with readings).",
    )
    point_angle: float = _point_angle(
        math.radians(118.0),
        "Drill point angle",
        "The drill point's included angle (180 deg: flat-bottomed holes).",
    )
    direction: Literal["axial", "radial"] = choice(
        "axial",
        ("axial", "radial"),
        "Hole direction",
        "The direction of the holes: axial or radial.",
    )
    spacing: float = _length_or_zero(
        0.002, "Material between holes", "Material left between neighbouring holes."
    )
    depth_resolution: float = _length_or_zero(
        0.0001, "Machining step", "The step the depths are rounded to."
    )
    density: float = quantity(
        "density", 7850.0, "Crank material density", "Density of the crank's material."
    )
    slug_density: float | None = quantity(
        "density",
        None,
        "Heavy-metal density (add instead)",
        "Add heavy metal of this density instead of drilling.",
    )
    grade: str = text("G6.3", "ISO 21940-11 grade", "The balance quality grade of the ISO check.")
    rotor_mass: float | None = quantity(
        "mass", None, "Crank mass", "The crank's mass, for the ISO check."
    )
    speed: float | None = quantity(
        "speed",
        None,
        "Largest service speed",
        "The largest service speed, for the ISO check; empty: the engine's.",
    )
    bearings: list[float] | None = _positions(
        "Main bearings", "Axial positions of the two outer main bearings; empty: the planes."
    )
    center_of_mass: float | None = quantity(
        "length",
        None,
        "Centre of mass",
        "Axial position of the crank's centre of mass; empty: mid-bearings.",
        within="position",
    )
    samples: int = whole(
        100_000,
        "Engines drawn",
        "Engines drawn by the Monte Carlo of the weight scatter.",
        ge=1,
        le=MAX_SCATTER_SAMPLES,
    )
    seed: int = whole(0, "Random seed", "Seed of the random numbers.", ge=0, le=2**63 - 1)
    scale_step: float = field(
        "mass",
        default=1e-4,
        parse=_scale_step,
        words="0 or a mass up to 10 g",
        title="Resolution of the scale",
        description="The resolution of the scale the parts are weighed on; 0: exact.",
    )

    def check(self) -> None:
        if len(self.reading) == 1:
            raise FieldProblem("reading", "must be given twice, one per measuring plane")


class ToleranceOptions(StudyOptions):
    """``tolerance``: ISO 21940-11 permissible residual unbalance and its planes (with an
    engine the rotor mass and the speed default to its crank's rotating masses and its
    speed); ``list_grades`` lists the grades instead."""

    grade: str | None = text(None, "Balance quality grade", "The ISO 21940-11 grade, e.g. G6.3.")
    rotor_mass: float | None = quantity("mass", None, "Rotor mass", "The rotor's mass.")
    speed: float | None = quantity(
        "speed", None, "Largest service speed", "The rotor's largest service speed."
    )
    residual: float | None = quantity(
        "unbalance",
        None,
        "Measured residual unbalance",
        "A measured residual unbalance, for the verdict.",
    )
    bearing_a: float | None = quantity(
        "length", None, "Bearing A", "Axial position of bearing A.", within="position"
    )
    bearing_b: float | None = quantity(
        "length", None, "Bearing B", "Axial position of bearing B.", within="position"
    )
    center_of_mass: float | None = quantity(
        "length",
        None,
        "Centre of mass",
        "Axial position of the rotor's centre of mass.",
        within="position",
    )
    plane_1: float | None = quantity(
        "length",
        None,
        "Correction plane I",
        "Axial position of correction plane I; empty: bearing A.",
        within="position",
    )
    plane_2: float | None = quantity(
        "length",
        None,
        "Correction plane II",
        "Axial position of correction plane II; empty: bearing B.",
        within="position",
    )
    list_grades: bool = field(
        "flag", default=False, title="List the grades", description="List the ISO grades."
    )


class PlotOptions(StudyOptions):
    """``plot``: the settings of the figures that take any."""

    order: int | str = field(
        "any",
        default=1,
        parse=_plot_order,
        metavar="{ORDER|rotating}",
        words=f"a harmonic order from 1 to {MAX_ORDER}, or 'rotating'",
        title="Harmonic order",
        description="The harmonic order of the polar figure, or rotating for the bare "
        "crank's masses.",
    )
    cylinder: int = whole(
        1, "Cylinder", "The cylinder of the single-cylinder figure (1-based).", ge=1, le=10_000
    )
    balance_factor: float = factor(
        0.5, "Balance factor", "The balance factor of the single-cylinder figure."
    )


EXPLORE_LAYOUTS = ("inline", "vee", "boxer", "w", "vr", "radial")


class ExploreOptions(StudyOptions):
    """``explore``: the design-space explorer (docs/explorer.md)."""

    layout: Literal["inline", "vee", "boxer", "w", "vr", "radial"] = choice(
        "inline",
        EXPLORE_LAYOUTS,
        "Layout",
        "The layout explored: inline, vee, boxer, w (broad arrow; a W from VR banks with "
        "its engine file), vr or radial.",
    )
    cylinders: int = whole(4, "Cylinders", "Number of cylinders.", ge=1, le=MAX_EXPLORE_CYLINDERS)
    strokes: int = whole(
        4, "Strokes per cycle (2 or 4)", "2 or 4 strokes per working cycle.", ge=2, le=4
    )
    bank_angle: float | None = quantity(
        "angle", None, "Vee or W bank angle", "The vee angle, or the angle between W banks."
    )
    crank: Literal["any", "flat", "cross", "split"] = choice(
        "any",
        ("any", "flat", "cross", "split"),
        "Crank family",
        "The cranks explored: any, flat, cross or split (split pins).",
    )
    fixed_crank: list[float] | None = field(
        "list",
        default=None,
        item=entry("angle", ge=RANGES["angle"][0], le=RANGES["angle"][1]),
        min_items=1,
        max_items=MAX_EXPLORE_CYLINDERS,
        parse=_angle_list,
        title="Fixed crank",
        description="Only the firing orders this crank allows: one throw angle per throw "
        "(per cylinder with crank split), e.g. '0,90,270,180 deg'.",
        hint="empty: every crank of the family",
    )
    mirror: bool = field(
        "flag",
        default=True,
        title="Mirror image the same engine",
        description="An engine numbered from the other end (its mirror image) counts as the "
        "same; off: a distinct engine.",
        hint="off: the mirror image is a distinct engine",
    )
    reversal: bool = field(
        "flag",
        default=False,
        title="Time reversal the same engine",
        description="An engine run backwards (the reverse firing order on the mirrored "
        "crank) counts as the same.",
    )
    list_orders: bool = field(
        "flag",
        default=False,
        title="List the orders of each engine",
        description="List every firing order each engine of the tables stands for (its "
        "equivalent descriptions).",
    )
    target: Literal["none", "counterweights", "primary", "secondary"] = choice(
        "counterweights",
        ("none", "counterweights", "primary", "secondary"),
        "Balancing target",
        "What each candidate is balanced with: none, counterweights, or "
        "primary or secondary shaft pairs.",
    )
    balance_factor: float = factor(
        0.0, "Balance factor", "The balance factor of the candidates' counterweights."
    )
    mode_shape: str = text(
        "uniform",
        "Torsional mode shape",
        "The torsional mode shape of the excitation merit: uniform, linear, or "
        "one weight per cylinder.",
    )
    orders: int = whole(
        8, "Highest order", "The highest harmonic order of the merits.", ge=1, le=MAX_ORDER
    )
    objectives: str = text(
        "F1,M1,F2,M2",
        "Pareto objectives (comma separated)",
        "The columns of the Pareto front, all minimised.",
    )
    filter: str | None = text(
        None, "Filter", "An expression on the columns that a candidate must meet to be kept."
    )
    top: int = whole(
        20, "Rows of the top-N table", "Rows of the table of the best candidates.", ge=1, le=100_000
    )
    top_key: str | None = text(
        None,
        "Column of the top-N table",
        "The column the top-N table is sorted by; empty: residual_M, the "
        "largest moment left after balancing (with target none the first objective).",
    )
    chunk: int | None = whole(
        None,
        "Indices per task (default: chosen from the problem; bounded by memory)",
        "Candidates per task; empty: chosen from the problem.",
        ge=1,
        le=LARGEST_CHUNK,
    )
    workers: int | None = whole(
        None,
        "Workers of a LocalCluster",
        "Run on a dask LocalCluster of this many worker processes.",
        ge=1,
        le=1024,
    )
    scheduler: str | None = text(
        None, "Address of a dask scheduler", "Run on an existing dask cluster, tcp://HOST:PORT."
    )
    connect_timeout: float = quantity(
        "time",
        5.0,
        "Time a scheduler has to answer",
        "The time the scheduler has to answer.",
        ge=0.1,
        le=120.0,
    )
    sample: int | None = whole(
        None,
        "Random draws (search)",
        "Random search: draw this many indices instead of enumerating all.",
        ge=1,
        le=MAX_DRAWS,
    )
    seed: int = whole(0, "Random seed", "Seed of the random search.", ge=0, le=2**32 - 1)


class TorsionalOptions(CombustionOptions, CrankDimensionOptions):
    """``torsional``: the crank train's lumped torsional model (docs/torsional.md): the
    speed range and orders, the throws' inertia and stiffness (given, or Carter's formula
    from the dimensions), front end, flywheel, damper, load, and the Wiebe combustion.
    Crank dimensions left empty are those ``bearings`` uses
    (:func:`crankbalance.studies.crank.crank_dimensions`)."""

    speed_min: float = quantity("speed", 600 * _RPM, "Lowest speed", "The sweep's lowest speed.")
    speed_max: float | None = quantity(
        "speed",
        None,
        "Highest speed (default: the engine's)",
        "The sweep's highest speed; empty: the engine's speed.",
    )
    speed_points: int = whole(
        400, "Speeds of the sweep", "Speeds of the sweep, evenly spaced.", ge=10, le=2001
    )
    highest_order: float = number(
        12.0,
        "Highest engine order",
        "The highest engine order of the excitation (half orders for a four-stroke).",
        ge=0.5,
        le=MAX_ORDER,
    )
    throw_inertia: float | None = quantity(
        "inertia",
        None,
        "Inertia of one throw with its big ends",
        "Inertia of one throw with its big ends; empty: from the engine.",
    )
    throw_stiffness: float | None = _stiffness(
        "Stiffness between throws (default: Carter's formula, an approximation)",
        "Torsional stiffness between neighbouring throws; empty: Carter's "
        "formula from the crank's dimensions.",
    )
    journal_length: float | None = quantity(
        "length",
        None,
        "Main journal length",
        "Axial length of a main journal.",
        hint=ENGINE_DIMENSION_TEXT,
    )
    pin_length: float | None = quantity(
        "length", None, "Crankpin length", "Axial length of a crankpin.", hint=ENGINE_DIMENSION_TEXT
    )
    shear_modulus: float = quantity(
        "modulus", 80e9, "Shear modulus of the crank", "Shear modulus of the crank's material."
    )
    front_inertia: float = quantity(
        "inertia",
        DEFAULT_FRONT_INERTIA,
        "Pulley, timing gear and damper hub",
        "Inertia of the front end: pulley, timing gear and damper hub.",
    )
    front_stiffness: float | None = _stiffness(
        "Front end to throw 1 (default: the throws')",
        "Torsional stiffness from the front end to throw 1; empty: the throws'.",
    )
    flywheel_inertia: float = quantity(
        "inertia",
        DEFAULT_FLYWHEEL_INERTIA,
        "Flywheel and clutch",
        "Inertia of the flywheel with its clutch.",
    )
    flywheel_stiffness: float | None = _stiffness(
        "Last throw to flywheel (default: the throws')",
        "Torsional stiffness from the last throw to the flywheel; empty: the throws'.",
    )
    damper_inertia: float | None = quantity(
        "inertia",
        None,
        "Damper ring (none: no damper)",
        "Inertia of a tuned damper's ring; empty: no damper.",
    )
    damper_frequency: float | None = quantity(
        "frequency", None, "Damper tuning frequency", "The damper's tuning frequency.", gt=0, le=1e5
    )
    damper_damping_ratio: float = _damping(
        0.15, "Damper damping ratio", "The damper's damping ratio."
    )
    damper_allowed_power: float | None = quantity(
        "power",
        None,
        "Power the damper may dissipate",
        "The heat the damper may dissipate, checked against its power.",
        gt=0,
        le=1e9,
    )
    load_inertia: float | None = quantity(
        "inertia",
        None,
        "Driven load (none: free end)",
        "Inertia of the driven load; empty: a free end.",
    )
    load_stiffness: float | None = _stiffness(
        "Flywheel to load", "Torsional stiffness from the flywheel to the load."
    )
    shaft_damping_ratio: float = _damping(
        0.02, "Crank's own damping ratio", "The crank's own damping ratio."
    )
    bore: float | None = quantity(
        "length",
        None,
        "Bore (default: square)",
        "Cylinder bore, for the gas torque; empty: bore = stroke.",
    )

    def check(self) -> None:
        CombustionOptions.check(self)
        if self.speed_max is not None and self.speed_max <= self.speed_min:
            raise FieldProblem("speed_max", "must be above the lowest speed")
        if (self.damper_inertia is None) != (self.damper_frequency is None):
            raise FieldProblem(
                "damper_frequency" if self.damper_inertia is not None else "damper_inertia",
                "the damper needs both its ring inertia and its tuning frequency",
            )
        if self.damper_allowed_power is not None and self.damper_inertia is None:
            raise FieldProblem(
                "damper_allowed_power",
                "needs a damper: give --damper-inertia and --damper-frequency",
            )
        if (self.load_inertia is None) != (self.load_stiffness is None):
            raise FieldProblem(
                "load_stiffness" if self.load_inertia is not None else "load_inertia",
                "the load needs both its inertia and the stiffness to the flywheel",
            )


class MountsOptions(CombustionOptions):
    """``mounts``: the powertrain on its mounts (docs/mounts.md): the speed range and its
    samples, the engine orders, the mean torque of the statics, the rotating masses, a point
    whose motion is shown; the gas torque's reaction when asked (with the combustion of
    :class:`CombustionOptions`); the comparison of balancing choices and the mount
    optimiser."""

    speed_min: float = quantity("speed", 600 * _RPM, "Lowest speed", "The sweep's lowest speed.")
    speed_max: float | None = quantity(
        "speed",
        None,
        "Highest speed (default: the engine's)",
        "The sweep's highest speed; empty: the engine's speed.",
    )
    speed_samples: int = whole(
        400, "Speeds of the sweep", "Speeds of the sweep, evenly spaced.", ge=2, le=10_001
    )
    orders: int = whole(
        4,
        "Engine orders",
        "The orders 1..n of the free forces and moments applied to the powertrain "
        "(speed samples x orders at most 50000: physics.mounts.MAX_RESPONSE_POINTS).",
        ge=1,
        le=MAX_ORDER,
    )
    mean_torque: float = quantity(
        "torque",
        0.0,
        "Mean engine torque",
        "The steady torque of the statics, on the crank in the sense of rotation (the block "
        "takes its reaction about the crank axis).",
    )
    rotating: str = choice(
        "balanced",
        ("balanced", "bare"),
        "Rotating masses",
        "balanced: the crank's counterweights carry the rotating masses (no rotating force "
        "reaches the mounts); bare: the bare crank's rotating force and moment are applied.",
    )
    point: list[float] | None = three_lengths(
        "Point shown",
        "A point of the powertrain (x, y, z from the reference point) whose largest "
        "displacement per order is shown; empty: the centre of gravity.",
    )
    gas_torque: bool = field(
        "flag",
        default=False,
        title="Gas-torque reaction",
        description="Also apply the reaction of the gas torque about the crank axis at every "
        "order (half orders of a four-stroke included) from the engine cycle (the Wiebe "
        "model or the pressure tables); it does not scale with the speed (docs/mounts.md).",
    )
    bore: float | None = quantity(
        "length",
        None,
        "Bore",
        "Cylinder bore, for the gas torque; empty: bore = stroke.",
        gt=0,
    )
    compare_patterns: list[str] | None = field(
        "list",
        default=None,
        item=entry("any", parse=_web_pattern, words="all, none, file or 0/1 per web"),
        min_items=1,
        max_items=MAX_PATTERNS,
        single=True,
        title="Compare counterweight patterns",
        description="Compare these counterweight patterns at the mounts (all, none, file or "
        "0/1 per web, two per throw); empty: the engine file's, if another comparison "
        "setting is given (at most 32 balancing choices: studies.mounts.MAX_CHOICES).",
        hint="all, none, file or 0/1 per web: 1,0,0,1",
    )
    compare_balance_factors: list[float] | None = _balance_factors(
        None,
        "Compare balance factors",
        "Compare these balance factors at the mounts (each pattern with counterweights "
        "takes every one); empty: the engine file's, if another comparison setting is given.",
        hint="e.g. 0, 0.5, 1",
    )
    compare_shafts: bool = field(
        "flag",
        default=False,
        title="Compare balance shafts on and off",
        description="Compare every balancing with and without the engine file's balance "
        "shafts at the mounts (the file needs a [balance_shafts] table).",
    )
    optimize: list[str] | None = field(
        "list",
        default=None,
        item=entry("choice", choices=("stiffness", "position")),
        min_items=1,
        max_items=2,
        title="Optimise the mounts",
        description="What the mount optimiser may change: stiffness (each mount's three "
        "stiffnesses scaled by one factor), position (each mount moved along x, y, z); "
        "empty: no optimisation (docs/mounts.md, 'The mount optimiser').",
        hint="stiffness, position",
    )
    objective: str = choice(
        "force",
        ("force", "change"),
        "Optimiser's objective",
        "force: the least root-mean-square mount force over the speed range; change: the "
        "least change of the mounts that meets the goals.",
    )
    stiffness_range: list[float] = field(
        "list",
        default=[0.5, 2.0],
        item=entry("number", gt=0, le=100),
        min_items=2,
        max_items=2,
        title="Stiffness factors",
        description="The lowest and highest factor on each mount's stiffnesses.",
    )
    position_range: float = quantity(
        "length",
        0.02,
        "Mount movement",
        "How far the optimiser may move each mount along each axis.",
    )
    frequency_band: list[float] | None = field(
        "list",
        default=None,
        item=entry("frequency", ge=0, le=1e4),
        min_items=2,
        max_items=2,
        title="Frequency band",
        description="The optimiser's goal: all six natural frequencies in this band (e.g. "
        "below the firing frequency at idle over the square root of 2); empty: no band.",
        hint="e.g. 5 Hz, 14 Hz",
    )
    roll_energy: float | None = number(
        None,
        "Roll energy",
        "The optimiser's goal: at least this per cent of the roll mode's kinetic energy "
        "in roll; empty: none.",
        ge=0,
        le=100,
    )
    roll_axis_angle: float | None = quantity(
        "angle",
        None,
        "Angle to the torque-roll axis",
        "The optimiser's goal: the roll mode turns at most this far from the torque-roll "
        "axis; empty: none.",
        ge=0,
        le=math.pi / 2,
    )
    optimize_iterations: int = whole(
        40,
        "Optimiser iterations",
        "Generations of the differential evolution (the work is bounded: "
        "physics.mounts_optimize.MAX_OPTIMIZER_EVALUATIONS).",
        ge=1,
        le=500,
    )

    def check(self) -> None:
        if self.speed_max is not None and self.speed_max <= self.speed_min:
            raise FieldProblem("speed_max", "must be above the lowest speed")
        if self.stiffness_range[0] > self.stiffness_range[1]:
            raise FieldProblem("stiffness_range", "must be lowest then highest")
        band = self.frequency_band
        if band is not None and band[0] >= band[1]:
            raise FieldProblem("frequency_band", "must be lowest then highest, apart")
        for name in ("compare_patterns", "compare_balance_factors", "optimize"):
            items = getattr(self, name)
            if items is not None and len(set(items)) < len(items):
                raise FieldProblem(name, "must give each value once")

    def comparing(self) -> bool:
        """Whether a comparison of balancing choices is asked for."""
        return bool(
            self.compare_patterns is not None
            or self.compare_balance_factors is not None
            or self.compare_shafts
        )


# --------------------------------------------------------------------------------------
# parsing and words, by schema and field name
# --------------------------------------------------------------------------------------
Options = TypeVar("Options", bound=StudyOptions)


def given(settings: StudyOptions) -> frozenset[str]:
    """The fields of ``settings`` that were given (typed on the command line, sent to the
    API, passed to the schema), as opposed to left at their defaults: a study takes an
    engine's value where a setting was not given, and refuses a given one that would not
    act."""
    return settings.given()


Kind = Literal["quantity", "number", "whole", "text", "list"]


def field_kind(model: type[StudyOptions], name: str) -> tuple[Kind, str | None]:
    """How a field is written: its kind and, for a quantity, the quantity kind."""
    spec = model.FIELDS[name]
    if spec.quantity is not None:
        return "quantity", spec.quantity
    if spec.kind == "list":
        return "list", None
    if spec.kind == "whole":
        return "whole", None
    if spec.kind in ("number", "factor"):
        return "number", None
    return "text", None


#: what a length that may be zero accepts, in words
ZERO_OR_LENGTH = core.allowed(
    entry("length", zero=True, ge=RANGES["length"][0], le=RANGES["length"][1])
)


def allowed(model: type[StudyOptions], name: str) -> str:
    """What a field accepts, in words: "a whole number from 16 to 100000", ..."""
    return core.allowed(model.FIELDS[name])


def default_text(model: type[StudyOptions], name: str) -> str:
    """A field's default as a user would type it ("" for a default of None)."""
    return core.default_text(model.FIELDS[name])


def parse_options(
    model: type[Options],
    values: Mapping[str, Any],
    name: Callable[[str], str] = str,
) -> Options:
    """Validate a study's settings; raise :class:`InputError` naming the field as the user
    wrote it (``name(field)``), the value given and what is allowed.

    Values that are ``None`` are left out, so that the schema's default applies. Values
    may be typed texts (the command line, the web form) or values of their type (the
    study layer, the API's JSON). A value in a list is named by its list's field and shown
    alone; an unknown setting is named with the closest known one.
    """
    given = {key: value for key, value in values.items() if value is not None}
    try:
        return model.parse(given, source="text", name=lambda path: name(str(path[0])))
    except InputError as error:
        words = error.allowed
        if not words.startswith(("the ", "unknown ", "takes ")):
            words = predicate(words)
        raise InputError(error.field, error.value, words) from None


#: how a message about a value goes on after the value ("'5 kg' has the wrong unit ...")
VERBS = ("must ", "has ", "is ", "needs ", "cannot ")


def predicate(text: str) -> str:
    """A message about a value as what is said of it, so that "FIELD = VALUE: TEXT" and
    "Label: VALUE TEXT" read as sentences: a description of what is allowed ("a number
    from 1 to 64") becomes "must be a number from 1 to 64"; "a density needs a unit, ..."
    becomes "needs a unit, ..."; "must ...", "has the wrong unit ..." stay."""
    if text.startswith(VERBS):
        return text
    found = re.match(r"an? \w+ (needs .*)", text)
    if found:
        return found.group(1)
    return f"must be {text}"
