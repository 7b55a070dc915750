"""The settings of the crank studies: crank dimensions, main bearings and their sweep,
torsional vibration and the mounts.

Part of :mod:`crankbalance.schema.settings`, imported when one of its schemas is first
asked for (see there)."""

from __future__ import annotations

import math
from typing import Any, Literal, TypeVar

from ...errors import InputError
from ...units import parse_quantity
from ..core import FieldProblem, entry, field, three_lengths
from .common import (
    DEFAULT_FLYWHEEL_INERTIA,
    DEFAULT_FRONT_INERTIA,
    ENGINE_DIMENSION_TEXT,
    ENGINE_INERTIA_TEXT,
    MAX_CLEARANCE_STIFFNESS,
    MAX_MAIN_BEARINGS,
    MAX_ORDER,
    MAX_PATTERNS,
    MAX_SAMPLES,
    MAX_SWEEP_CASES,
    MIN_SAMPLES,
    NAMED_PATTERNS,
    RANGES,
    RPM,
    TORSIONAL_EXAMPLE,
    TORSIONAL_STIFFNESS_RANGE,
    StudyOptions,
    balance_factors,
    choice,
    factor,
    friction,
    number,
    quantity,
    whole,
)
from .cycle import CombustionOptions


def _damping(default: Any, title: str, description: str) -> Any:
    """A damping ratio [-], from 0 to 0.5."""
    return number(default, title, description, ge=0, le=0.5)


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


def parse_torsional_stiffness(value: Any, where: str = "") -> float:
    """A torsional stiffness written with its unit per radian: ``"5e5 N*m/rad"`` [N m/rad]."""
    low, high = TORSIONAL_STIFFNESS_RANGE
    words = f"a torsional stiffness such as {TORSIONAL_EXAMPLE!r}, from {low:g} to {high:g} N*m/rad"
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
        words=f"a torsional stiffness with its unit per radian, e.g. {TORSIONAL_EXAMPLE!r}, "
        f"from {low:g} to {high:g} N*m/rad",
        title=title,
        description=description,
        metavar="STIFFNESS [N·m/rad]",
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
    friction_coefficient: float = friction(
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
    balance_factors: list[float] = balance_factors(
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


class TorsionalOptions(CombustionOptions, CrankDimensionOptions):
    """``torsional``: the crank train's lumped torsional model (docs/torsional.md): the
    speed range and orders, the throws' inertia and stiffness (given, or Carter's formula
    from the dimensions), front end, flywheel, damper, load, and the Wiebe combustion.
    Crank dimensions left empty are those ``bearings`` uses
    (:func:`crankbalance.studies.crank.crank_dimensions`)."""

    speed_min: float = quantity("speed", 600 * RPM, "Lowest speed", "The sweep's lowest speed.")
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

    speed_min: float = quantity("speed", 600 * RPM, "Lowest speed", "The sweep's lowest speed.")
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
    compare_balance_factors: list[float] | None = balance_factors(
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
