"""What every study's settings share: the limits and ranges, the kinds of setting, the base
schema, the settings of ``analyze`` and ``balance``, and the parsing and words by field.

Imported through :mod:`crankbalance.schema.settings` (see there), whose other modules
build on it."""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from typing import Any, Literal, TypeVar, get_args

from ...errors import InputError
from ...physics.limits import (
    BALANCE_FACTOR_RANGE,
    MAX_FLUCTUATION_TARGET,
    MIN_FLUCTUATION_TARGET,
)
from ...units import RANGES as units_ranges
from ...units import range_si
from .. import core
from ..core import Schema, entry, field, three_lengths

#: the balance factors every study accepts (share of the reciprocating mass) [-]
BALANCE_FACTOR_LIMITS = BALANCE_FACTOR_RANGE

RPM = math.pi / 30.0  # 1 rpm in rad/s

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
TORSIONAL_EXAMPLE = "5e5 N*m/rad"
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


def length_or_zero(default: Any, title: str, description: str, **options: Any) -> Any:
    """A length that may be zero (a solid shaft's bore, a profile's rectangle height)."""
    return quantity("length", default, title, description, zero=True, **options)


def requirement(default: Any, title: str, description: str) -> Any:
    """A first moment a counterweight or a balance shaft is sized for [kg m]."""
    return quantity("unbalance", default, title, description, ge=MIN_UNBALANCE)


def point_angle(default: Any, title: str, description: str, **options: Any) -> Any:
    """A drill point's included angle: above 0, at most 180 deg (flat-bottomed holes)."""
    return quantity("angle", default, title, description, within="point_angle", gt=0.0, **options)


def friction(default: Any, title: str, description: str, **options: Any) -> Any:
    """A Coulomb friction coefficient [-]: above 0, at most 1."""
    return number(default, title, description, gt=0, le=1, **options)


def number_sweep(value: str, where: str) -> Any:
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


def balance_factors(default: Any, title: str, description: str, **options: Any) -> Any:
    """The balance factors of a sweep: a list, or a text "0,0.25,0.5" or "start:stop:step"."""
    return field(
        "list",
        default=default,
        item=entry("factor", ge=BALANCE_FACTOR_LIMITS[0], le=BALANCE_FACTOR_LIMITS[1]),
        min_items=1,
        max_items=MAX_SWEEP,
        parse=number_sweep,
        title=title,
        description=description,
        **options,
    )


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
