"""One schema for the settings of every study and every command, with one set of limits.

The command line and the web form both validate a study's settings through these pydantic
models, so that a setting has the same default, the same limits and the same message
everywhere. Quantities are unit strings (``"8000 kg/m^3"``, ``"400 g"``) parsed to SI
floats; plain numbers stay numbers. Every field has a default (``None`` where the study
derives the value from the engine when it is not given).

Limits. Every value is checked *after* unit conversion: it must be a finite number (no
NaN, no infinity, whatever the unit: ``"1e308 km"`` is refused) inside the physical range
of its kind (:data:`RANGES`), which a setting may narrow (a balance factor from 0 to 2, a
friction coefficient up to 1). Counts and indices are whole numbers within stated bounds;
the work of the long studies is capped (:data:`MAX_BENCH_REVOLUTIONS`, the design points
of a shaft sweep, the balance factors of a sensitivity sweep).

An edge names the fields as its users write them: the CLI as ``--max-mass``, the web form
by its setting key; :func:`parse_options` takes that naming as a function, so that an
error names the field the user typed.
"""

from __future__ import annotations

import math
import re
import types
from collections.abc import Callable, Mapping
from functools import partial
from typing import Annotated, Any, Literal, TypeVar, Union, get_args, get_origin

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    ValidationError,
    model_validator,
)
from pydantic.fields import FieldInfo

from ..errors import InputError
from ..physics.engine_cycle import BURN_DURATION_RANGE, IGNITION_RANGE
from ..physics.engine_cycle_all import MAX_FLUCTUATION_TARGET, MIN_FLUCTUATION_TARGET
from ..physics.explore.work import LARGEST_CHUNK, MAX_DRAWS
from ..physics.single_cylinder import BALANCE_FACTOR_RANGE
from ..units import KINDS, format_quantity, parse_factor, parse_quantity, range_si
from ..units import RANGES as units_ranges

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
#: (low, low is open, high, high is open) of a value
Bounds = tuple[float | None, bool, float | None, bool]
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


def _quantity(kind: str) -> Any:
    """A quantity string of ``kind`` parsed to SI."""
    return BeforeValidator(partial(parse_quantity, kind=kind, field=""))


def _range(kind: str) -> Any:
    """The physical range of a kind of quantity (:data:`RANGES`)."""
    low, high = RANGES[kind]
    return Field(ge=low, le=high)


def _number(value: Any) -> Any:
    """A plain number: refuse NaN, infinities and booleans."""
    if isinstance(value, bool):
        raise ValueError("must be a number, not true/false")
    if isinstance(value, str):
        try:
            value = float(value.strip())
        except ValueError:
            raise ValueError("must be a plain number") from None
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


def _factor(value: Any) -> float:
    """A balance factor as written: 0.28, "0.28" or "28%"."""
    return parse_factor(value, "")


def _target(value: Any) -> Any:
    """A target balance factor: 0.28, "28%" or "factory" (the crank's own)."""
    if isinstance(value, str) and value.strip().lower() == "factory":
        return "factory"
    factor = parse_factor(value, "")
    low, high = BALANCE_FACTOR_LIMITS
    if not low <= factor <= high:
        raise InputError("", value, f"must be 'factory' or a number from {low:g} to {high:g}")
    return factor


def _angle_or_optimal(value: Any) -> Any:
    """``"optimal"`` or an angle with a unit, in :data:`RANGES` ``["angle"]``."""
    if isinstance(value, str) and value.strip().lower() == "optimal":
        return "optimal"
    angle = parse_quantity(value, "angle", "")
    low, high = RANGES["angle"]
    if not low <= angle <= high:
        words = _range_words("angle", (low, False, high, False))
        raise InputError("", value, f"must be 'optimal' or {words}")
    return angle


Length = Annotated[float, _quantity("length"), _range("length")]
Area = Annotated[float, _quantity("area"), _range("area")]
Position = Annotated[float, _quantity("length"), _range("position")]
Mass = Annotated[float, _quantity("mass"), _range("mass")]
Density = Annotated[float, _quantity("density"), _range("density")]
Inertia = Annotated[float, _quantity("inertia"), _range("inertia")]
Unbalance = Annotated[float, _quantity("unbalance"), _range("unbalance")]
Speed = Annotated[float, _quantity("speed"), _range("speed")]
Force = Annotated[float, _quantity("force"), _range("force")]
Torque = Annotated[float, _quantity("torque"), _range("torque")]
Time = Annotated[float, _quantity("time"), _range("time")]
Stiffness = Annotated[float, _quantity("stiffness"), _range("stiffness")]
Modulus = Annotated[float, _quantity("modulus"), _range("modulus")]
Pressure = Annotated[float, _quantity("pressure"), _range("pressure")]
Viscosity = Annotated[float, _quantity("viscosity"), _range("viscosity")]
Angle = Annotated[float, _quantity("angle"), _range("angle")]
#: a drill point's included angle: above 0, at most 180 deg (flat-bottomed holes)
PointAngle = Annotated[
    float,
    _quantity("angle"),
    Field(gt=RANGES["point_angle"][0], le=RANGES["point_angle"][1]),
]
#: what the depth of a pointed hole is read to: the shoulder (where the cylinder ends) or
#: the tip of the point (the same for a flat bottom); the choices of the web's selects
DepthTo = Literal["shoulder", "tip"]
DEPTH_TO: tuple[str, ...] = get_args(DepthTo)
Number = Annotated[float, BeforeValidator(_number)]
Whole = Annotated[int, BeforeValidator(_number)]
#: a balance factor: 0.28 or "28%", from 0 to 2
Factor = Annotated[
    float,
    BeforeValidator(_factor),
    Field(ge=BALANCE_FACTOR_LIMITS[0], le=BALANCE_FACTOR_LIMITS[1]),
]
#: a Coulomb friction coefficient [-]
FrictionCoefficient = Annotated[float, BeforeValidator(_number), Field(gt=0, le=1)]
#: a first moment a counterweight or balance shaft is sized for [kg m]
Requirement = Annotated[Unbalance, Field(ge=MIN_UNBALANCE)]


def _zero_or_length(value: float) -> float:
    """Zero, or a length in its physical range (no length of a trillionth of a millimetre)."""
    if value != 0 and value < RANGES["length"][0]:
        raise InputError("", value, f"must be {ZERO_OR_LENGTH}")
    return value


#: a length that may be zero (a solid shaft's bore, a profile's rectangle height) [m]
LengthOrZero = Annotated[Position, Field(ge=0), AfterValidator(_zero_or_length)]
#: the weight w of the balance-shaft placement objective [-]
ShaftWeight = Annotated[float, BeforeValidator(_number), Field(ge=0, le=1000)]


def _number_sweep(value: Any) -> Any:
    """A list of numbers as typed: ``"0,0.28,0.5"`` or ``"start:stop:step"`` (stop included,
    at most :data:`MAX_SWEEP` values); a list is taken as it is. Its count and range are
    checked by the field."""
    if not isinstance(value, str):
        return value
    words = "must be numbers separated by commas, or start:stop:step with step > 0"
    try:
        if ":" in value:
            start, stop, step = (float(x) for x in value.split(":"))
            span = (stop - start) / step
            if not (step > 0 and 0 <= span < math.inf):
                raise ValueError
            if span > MAX_SWEEP:
                raise InputError("", value, f"must give at most {MAX_SWEEP} values")
            return [start + k * step for k in range(int(math.floor(span + 1e-9)) + 1)]
        numbers = [float(x) for x in value.split(",") if x.strip()]
    except ValueError:
        raise InputError("", value, words) from None
    if not numbers or not all(math.isfinite(v) for v in numbers):
        raise InputError("", value, "must hold at least one finite number")
    return numbers


def _comma_list(value: Any) -> Any:
    """A list typed as one text, its items separated by commas (``"1,0,0,1"``); a list is
    taken as it is."""
    if not isinstance(value, str):
        return value
    return [item.strip() for item in value.split(",") if item.strip()] or [value]


def _one_or_many(value: Any) -> Any:
    """The values of a setting that may be given several times (an option repeated on the
    command line, a JSON list): one value alone is a list of one."""
    if isinstance(value, (list, tuple)):
        return list(value)
    return [value]


#: the balance factors of a sweep: a list, or a text "0,0.25,0.5" or "start:stop:step"
BalanceFactors = Annotated[
    list[Factor], BeforeValidator(_number_sweep), Field(min_length=1, max_length=MAX_SWEEP)
]
#: a setting that may be given several times
Many = BeforeValidator(_one_or_many)


class StudyOptions(BaseModel):
    """Base of the study settings: unknown keys are errors, values are frozen and finite."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False, defer_build=True)


# --------------------------------------------------------------------------------------
# the studies of the web form and the command line
# --------------------------------------------------------------------------------------


class AnalysisOptions(StudyOptions):
    """Free forces and moments: how many harmonic orders."""

    orders: Whole = Field(8, ge=1, le=MAX_ORDER, title="Highest order")


class CounterweightOptions(StudyOptions):
    """Counterweight shape optimisation (Appl. Sci. 2021, Sec. 4-5)."""

    density: Density = Field(8000.0, title="Density", description="e.g. 8000 kg/m^3")
    max_mass: Mass | None = Field(None, title="Largest mass", description="e.g. 400 g")
    max_radius: Length | None = Field(None, title="Largest radial space", description="e.g. 80 mm")
    min_balance: Number = Field(100.0, ge=1, le=1000, title="Smallest balance [%]")
    iterations: Whole = Field(40, ge=0, le=1000, title="Iterations")
    population: Whole = Field(4096, ge=16, le=100_000, title="Population")
    seed: Whole | None = Field(None, ge=0, le=2**32 - 1, title="Random seed")

    @model_validator(mode="after")
    def _budget(self) -> CounterweightOptions:
        self.check_budget(2)
        return self

    def check_budget(self, objectives: int) -> None:
        """Refuse more designs than the budget of ``objectives`` objectives (2: mass and
        radial space, 3: with the inertia), naming ``iterations``."""
        designs = counterweight_designs(self.population, self.iterations)
        budget = MAX_COUNTERWEIGHT_DESIGNS if objectives < 3 else MAX_THREE_OBJECTIVE_DESIGNS
        if designs > budget:
            raise InputError(
                "iterations",
                self.iterations,
                f"must keep population + iterations x {COUNTERWEIGHT_CHILDREN} at most "
                f"{budget:,} designs, the optimiser's work budget with {objectives} objectives "
                f"(here {self.population:,} + {self.iterations:,} x {COUNTERWEIGHT_CHILDREN} = "
                f"{designs:,}): lower the iterations or the population",
            )


def counterweight_designs(population: int, iterations: int) -> int:
    """The designs a counterweight optimisation evaluates: its first sample and
    :data:`COUNTERWEIGHT_CHILDREN` per round."""
    return population + iterations * COUNTERWEIGHT_CHILDREN


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

    first_moment: Requirement | None = Field(None, title="Required first moment m_c r_c")
    cw_mass: Mass | None = Field(None, title="Counterweight mass m_c")
    cg_radius: Length | None = Field(None, title="Counterweight CG radius r_c")


class CounterweightOptimizeOptions(CounterweightOptions, CounterweightRequirementOptions):
    """``counterweight optimize``: the requirement, the profile parameters (a value fixes
    one, ``"LOW..HIGH"`` leaves it free in that range, empty: the optimiser's range), the
    radial measure, the objectives and how many Pareto designs are listed."""

    web_radius: str | None = Field(None, title="Web circle radius r_cw (value or LOW..HIGH)")
    rectangle_height: str | None = Field(None, title="Rectangle height h_R (value or LOW..HIGH)")
    trapezoid_angle: str | None = Field(None, title="delta (value or LOW..HIGH)")
    segment_radius: str | None = Field(None, title="Segment radius R_cw (value or LOW..HIGH)")
    segment_angle: str | None = Field(None, title="alpha (value or LOW..HIGH)")
    thickness: str | None = Field(None, title="Thickness t_cw (value or LOW..HIGH)")
    radius_measure: Literal["true", "paper"] = Field(
        "true",
        title="Radial space",
        description="true: the outer radius; paper: the 2021 paper's R_min bound",
    )
    inertia: bool = Field(False, title="Inertia as a third objective")
    pareto: Whole = Field(
        10, ge=0, le=10**6, title="Pareto designs listed (evenly spread along the front)"
    )

    @model_validator(mode="after")
    def _three_objectives(self) -> CounterweightOptimizeOptions:
        if self.inertia:
            self.check_budget(3)
        return self


class SingleCylinderOptions(StudyOptions):
    """One cylinder of an engine: balance factor study and the ISO 21940-11 check."""

    cylinder: Whole = Field(1, ge=1, title="Cylinder", description="1..number of cylinders")
    balance_factor: Number = Field(
        0.5, ge=BALANCE_FACTOR_LIMITS[0], le=BALANCE_FACTOR_LIMITS[1], title="Balance factor"
    )
    grade: str = Field("G6.3", title="ISO 21940-11 grade", description="e.g. G6.3")
    rotor_mass: Mass | None = Field(
        None, title="Rotor mass", description="empty: the crank's rotating masses"
    )
    residual: Unbalance | None = Field(
        None, title="Measured residual unbalance", description="optional, e.g. 8 g*mm"
    )


class RebalanceOptions(StudyOptions):
    """Rebalancing one cylinder's throw after new parts (Hoem and Røsholm 2016, Sec. 6.4)."""

    new_reciprocating: Mass | None = Field(
        None, title="New reciprocating mass", description="empty: unchanged"
    )
    new_rotating: Mass | None = Field(
        None, title="New rotating mass", description="empty: unchanged"
    )
    cw_mass: Mass | None = Field(
        None,
        title="Counterweight mass (webs incl.)",
        description="empty: what the balance factor needs at the CG radius",
    )
    cw_radius: Length | None = Field(
        None, title="Counterweight CG radius", description="empty: crank radius"
    )
    hole_diameter: Length = Field(0.008, title="Drill diameter", description="e.g. 8 mm")
    point_angle: PointAngle = Field(
        math.pi, title="Drill point angle", description="e.g. 118 deg (180 deg: flat-bottomed)"
    )
    depth_to: DepthTo = Field("tip", title="Depth read to the", description="tip or shoulder")
    holes: Whole = Field(
        1, ge=1, le=MAX_HOLES, title="Holes per web", description="side by side, e.g. 2"
    )
    hole_radius: Length | None = Field(
        None, title="Hole radius", description="empty: counterweight CG radius"
    )


def _slender(length: float, diameter: float) -> None:
    """A shaft the beam model can describe: at least as long as its diameter."""
    if length < diameter:
        raise InputError(
            "length",
            length,
            f"must be at least the diameter ({format_quantity(diameter, 'length', 6)}): the "
            "beam model needs a shaft longer than it is thick",
        )


class ShaftPlacementOptions(StudyOptions):
    """Unbalance-mass placement on a balance shaft with end bearings (Kim 2018, Sec. 3.1)."""

    length: Length = Field(0.3, title="Shaft length (between bearings)", description="e.g. 300 mm")
    diameter: Length = Field(0.025, title="Shaft diameter", description="e.g. 25 mm")
    weight: ShaftWeight = Field(2.0, title="Objective weight w", description="e.g. 2")
    points: Whole = Field(41, ge=3, le=MAX_SHAFT_POINTS, title="Design points along the shaft")

    @model_validator(mode="after")
    def _beam(self) -> ShaftPlacementOptions:
        _slender(self.length, self.diameter)
        return self


class PerformanceOptions(StudyOptions):
    """Friction, bearing loads and shaking against the balance factor (Hoem and Røsholm
    2016, Sec. 5)."""

    bore: Length | None = Field(
        None,
        title="Bore",
        description="empty: 76.8 mm, the one-cylinder studies' (cycle, sensitivity)",
    )
    balance_factors: BalanceFactors = Field(
        [0.0, 0.25, 0.5, 0.75, 1.0],
        title="Balance factors",
        description="e.g. 0, 0.25, 0.5, 0.75, 1",
    )
    crank_inertia: Inertia | None = Field(
        None,
        title="Crank + flywheel inertia",
        description="empty: the engine's (front end, throws and flywheel)",
    )
    friction_coefficient: FrictionCoefficient = Field(
        0.005, title="Bearing friction coefficient", description="e.g. 0.005"
    )
    journal_diameter: Length = Field(0.03, title="Main journal diameter", description="e.g. 30 mm")


# --------------------------------------------------------------------------------------
# the commands of the command line (crankbalance COMMAND --option ...)
# --------------------------------------------------------------------------------------


class BalanceOptions(StudyOptions):
    """``balance`` and ``report``: overrides of the engine file's counterweights."""

    angle: Annotated[float | str, BeforeValidator(_angle_or_optimal)] | None = Field(
        None, title="Counterweight angle", description="'optimal' or e.g. 30 deg"
    )
    balance_factor: Factor | None = Field(None, title="Balance factor")
    method: Literal["pattern", "individual"] | None = Field(
        None,
        title="Counterweight method",
        description="pattern: equal counterweights; individual: each its own mass and angle "
        "(empty: the engine file's)",
    )
    scope: Literal["auto", "whole", "halves"] | None = Field(
        None,
        title="Balance the whole crank or each half",
        description="empty: the engine file's",
    )


class CounterweightDesignOptions(StudyOptions):
    """``counterweight optimize|show|export|check``: the requirement and the profile
    parameters (each a value, or for ``optimize`` both ends of a range)."""

    first_moment: Requirement | None = Field(None, title="Required first moment m_c r_c")
    cw_mass: Mass | None = Field(None, title="Counterweight mass m_c")
    cg_radius: Length | None = Field(None, title="Counterweight CG radius r_c")
    web_radius: Length | None = Field(None, title="Web circle radius r_cw")
    rectangle_height: LengthOrZero | None = Field(None, title="Rectangle height h_R")
    trapezoid_angle: Annotated[Angle, Field(ge=0)] | None = Field(None, title="delta")
    segment_radius: Length | None = Field(None, title="Segment radius R_cw")
    segment_angle: Annotated[Angle, Field(gt=0)] | None = Field(None, title="alpha")
    thickness: Length | None = Field(None, title="Thickness t_cw")
    density: Density = Field(8000.0, title="Density")
    unit: Length = Field(1e-3, title="Length unit of a CAD file")


class FrictionOptions(StudyOptions):
    """``friction``: bearing friction torque under a constant plus a rotating load."""

    load: Force = Field(0.0, title="Constant bearing load")
    rotating_load: Force | None = Field(None, title="Rotating load")
    unbalance: Unbalance | None = Field(None, title="Unbalance")
    speed: Speed | None = Field(None, title="Shaft speed")
    journal_diameter: Length | None = Field(None, title="Journal diameter")
    friction_coefficient: FrictionCoefficient | None = Field(None, title="Friction coefficient")
    torque: Torque | None = Field(None, title="Measured torque")
    viscosity: Viscosity | None = Field(None, title="Oil viscosity")
    bearing_length: Length | None = Field(None, title="Bearing length")
    clearance: Length | None = Field(None, title="Radial clearance")
    eccentricity: Number = Field(0.0, ge=0, lt=1, title="Eccentricity ratio")
    attitude_angle: Angle = Field(0.0, title="Attitude angle")


class BenchOptions(StudyOptions):
    """``bench``: the simulated rotor test bench (Hoem and Røsholm 2016, Sec. 5.2.5)."""

    mass: Mass = Field(2.5464, title="Rotor mass")
    inertia: Inertia = Field(2.847335e-3, title="Rotor moment of inertia")
    unbalance: Unbalance = Field(0.0, title="Rotor unbalance")
    journal_diameter: Length = Field(0.02, title="Journal diameter")
    friction_coefficient: FrictionCoefficient | None = Field(None, title="Friction coefficient")
    speed: Annotated[list[Speed], Many] = Field(
        [3000 * _RPM], min_length=1, max_length=MAX_BENCH_RUNS, title="Set speeds"
    )
    ramp_time: Time = Field(2.0, title="Ramp time")
    hold_time: Time = Field(1.5, title="Hold time")
    kp: Number = Field(0.2, gt=0, le=1e4, title="PI proportional gain [N m s/rad]")
    ki: Number = Field(10.0, ge=0, le=1e6, title="PI integral gain [N m/rad]")

    @model_validator(mode="after")
    def _bounded_work(self) -> BenchOptions:
        fastest = max(self.speed)
        turns = fastest / (2 * math.pi) * (self.ramp_time / 2 + self.hold_time)
        if turns > MAX_BENCH_REVOLUTIONS:
            raise InputError(
                "hold_time",
                self.hold_time,
                f"the run at {format_quantity(fastest, 'speed', 6)} would simulate "
                f"{turns:.3g} revolutions, at most {MAX_BENCH_REVOLUTIONS} are allowed: "
                "shorten the ramp and hold times or lower the speed",
            )
        proportional, integral = self.kp / self.inertia, math.sqrt(self.ki / self.inertia)
        rate = proportional + integral
        if rate * (self.ramp_time + self.hold_time) > MAX_BENCH_CONTROL:
            gain = "kp" if proportional >= integral else "ki"
            raise InputError(
                gain,
                getattr(self, gain),
                f"the controller (time constant {1 / rate:.3g} s against the rotor's inertia) "
                f"would need more than {MAX_BENCH_CONTROL} steps over the run: lower --kp "
                "and --ki, raise the inertia or shorten the run",
            )
        return self


#: the speed fluctuation a flywheel is sized for, from 1 ppm to 20 % [-] (the energy
#: method's range, :data:`crankbalance.physics.engine_cycle_all.MAX_FLUCTUATION_TARGET`)
FluctuationTarget = Annotated[
    float,
    BeforeValidator(_factor),
    Field(ge=MIN_FLUCTUATION_TARGET, le=MAX_FLUCTUATION_TARGET),
]
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


class CombustionOptions(StudyOptions):
    """The gas pressure of a cycle: the Wiebe model (Hoem and Røsholm 2016) or pressure
    tables, one for every cylinder or one per cylinder; shared by ``cycle``,
    ``sensitivity``, ``bearings`` and ``torsional`` with the same defaults (the thesis'
    combustion, docs/engine_cycle.md)."""

    compression_ratio: Number = Field(13.5, gt=1, le=100, title="Compression ratio")
    # the Wiebe model's own ranges (engine_cycle.IGNITION_RANGE, BURN_DURATION_RANGE)
    ignition: Angle = Field(
        math.radians(-25.0),
        ge=IGNITION_RANGE[0],
        le=IGNITION_RANGE[1],
        title="Start of combustion from firing TDC",
    )
    burn_duration: Angle = Field(
        math.radians(50.0),
        ge=BURN_DURATION_RANGE[0],
        le=BURN_DURATION_RANGE[1],
        title="Burn duration",
    )
    intake_pressure: Pressure = Field(1e5, title="Pressure at the start of compression")
    pressure_csv: Annotated[list[str], Many] = Field(
        [], max_length=MAX_PRESSURE_TABLES, title="Cylinder pressure tables"
    )


class CycleOptions(CombustionOptions):
    """``cycle`` and ``sensitivity``: one cylinder (typed, or of ``engine``) or the whole
    engine (an engine without ``cylinder``: every cylinder firing), its gas pressure (the
    Wiebe model, or tables: one for every cylinder or one per cylinder) and the flywheel.
    With an engine, stroke, conrod length, reciprocating mass, speed and strokes are the
    engine's unless given (:func:`given`); the bore of one cylinder is the thesis' 76.8 mm
    unless given, that of the whole engine the stroke (a square engine)."""

    cylinder: Whole | None = Field(
        None, ge=1, le=10_000, title="Cylinder of the engine (none: all cylinders)"
    )
    bore: Length = Field(0.0768, title="Bore")
    stroke: Length = Field(0.0538, title="Stroke")
    rod_length: Length = Field(0.1035, title="Conrod length")
    reciprocating_mass: Mass = Field(0.282, title="Reciprocating mass")
    crank_inertia: Inertia | None = Field(
        None,
        title="Crank + flywheel inertia",
        description=f"empty: {THESIS_CRANK_INERTIA:g} kg*m^2 (the thesis' single) without "
        f"an engine; with one, {ENGINE_INERTIA_TEXT.removeprefix('empty: ')}",
    )
    journal_diameter: Length = Field(0.03, title="Main journal diameter")
    friction_coefficient: FrictionCoefficient = Field(0.005, title="Friction coefficient")
    speed: Speed = Field(9000 * _RPM, title="Mean speed")
    strokes: Whole = Field(4, ge=2, le=4, title="Strokes per cycle")
    balance_factor: Factor = Field(0.5, title="Balance factor")
    flywheel_inertia: Inertia | None = Field(None, title="Flywheel inertia (added to the crank)")
    speed_fluctuation_target: FluctuationTarget | None = Field(
        None, title="Speed fluctuation to size the flywheel for"
    )


class SensitivityOptions(CycleOptions):
    """``sensitivity``: the cycle swept over balance factors and reciprocating-mass scales."""

    cylinder: Whole = Field(1, ge=1, le=10_000, title="Cylinder of the engine")
    pressure_csv: Annotated[list[str], Many] = Field(
        [], max_length=1, title="Cylinder pressure table"
    )

    balance_factors: BalanceFactors = Field([0.1 * k for k in range(11)], title="Balance factors")
    mass_scales: Annotated[
        list[Annotated[Number, Field(gt=0, le=10)]], BeforeValidator(_number_sweep)
    ] = Field([1.0], min_length=1, max_length=MAX_SWEEP, title="Reciprocating-mass scales")


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


class CrankDimensionOptions(StudyOptions):
    """The crank's dimensions ``bearings`` and ``torsional`` may be given; empty ones are
    the engine's, from its crank radius and web offset
    (:func:`crankbalance.studies.crank.crank_dimensions`), the same for both."""

    journal_diameter: Length | None = Field(
        None, title="Main journal diameter", description=ENGINE_DIMENSION_TEXT
    )
    pin_diameter: Length | None = Field(
        None, title="Crankpin diameter", description=ENGINE_DIMENSION_TEXT
    )
    web_thickness: Length | None = Field(
        None, title="Web thickness (axial)", description=ENGINE_DIMENSION_TEXT
    )
    web_width: Length | None = Field(
        None, title="Web width (across the arm)", description=ENGINE_DIMENSION_TEXT
    )


class BearingOptions(CombustionOptions, CrankDimensionOptions):
    """``bearings``: main-bearing loads and crank bending over the engine cycle
    (docs/main_bearings.md). Crank dimensions left empty are taken from the crank radius
    and the web offset (proportions of an automotive crank,
    :func:`crankbalance.studies.crank.crank_dimensions`), an empty crank + flywheel inertia
    is the engine's (:func:`crankbalance.studies.crank.rotating_inertia`) and the combustion
    is :class:`CombustionOptions`': the same as ``cycle --engine`` and ``torsional``."""

    speed: Speed | None = Field(None, title="Mean speed", description="empty: the engine's")
    samples: Whole = Field(360, ge=MIN_SAMPLES, le=MAX_SAMPLES, title="Samples per revolution")
    gas: bool = Field(True, title="Gas forces", description="off: inertia forces only")
    bore: Length | None = Field(
        None, title="Bore", description="empty: square engine (bore = stroke)"
    )
    crank_inertia: Inertia | None = Field(
        None, title="Crank + flywheel inertia", description=ENGINE_INERTIA_TEXT
    )
    balance_factor: Factor | None = Field(
        None, title="Balance factor", description="empty: the engine file's"
    )
    webs: (
        Annotated[
            list[Annotated[int, BeforeValidator(_number), Field(ge=0, le=1)]],
            BeforeValidator(_comma_list),
        ]
        | None
    ) = Field(
        None,
        min_length=2,
        max_length=2 * MAX_MAIN_BEARINGS,
        title="Counterweight webs (0/1, two per throw)",
        description="empty: the engine file's",
    )
    modulus: Modulus = Field(210e9, title="Young's modulus of the crank")
    poisson: Number = Field(0.3, gt=-1, lt=0.5, title="Poisson's ratio")
    bearing: Annotated[list[Position], Many] | None = Field(
        None, min_length=2, max_length=MAX_MAIN_BEARINGS, title="Main-bearing positions"
    )
    bearing_stiffness: Stiffness | None = Field(
        None, title="Radial bearing stiffness", description="empty: rigid bearings"
    )
    friction_coefficient: FrictionCoefficient = Field(0.005, title="Friction coefficient")
    viscosity: Viscosity | None = Field(None, title="Oil viscosity (Petroff)")
    bearing_length: Length | None = Field(None, title="Bearing length (Petroff)")
    clearance: Length | None = Field(
        None, title="Radial clearance", description="Petroff friction; contact with a stiffness"
    )
    curves: bool = Field(False, title="The load and moment curves over the cycle in the JSON")

    @model_validator(mode="after")
    def _petroff(self) -> BearingOptions:
        trio = ("viscosity", "bearing_length", "clearance")
        given = [name for name in trio if getattr(self, name) is not None]
        if given and given != ["clearance"] and len(given) < 3:
            missing = next(name for name in trio if getattr(self, name) is None)
            raise InputError(
                given[0],
                getattr(self, given[0]),
                f"needs {missing.replace('_', ' ')} too: the Petroff friction takes "
                "viscosity, bearing length and clearance together",
            )
        if (
            self.clearance is not None
            and self.bearing_stiffness is not None
            and self.bearing_stiffness > MAX_CLEARANCE_STIFFNESS
        ):
            raise InputError(
                "bearing_stiffness",
                self.bearing_stiffness,
                f"must be at most {MAX_CLEARANCE_STIFFNESS:g} N/m with a clearance (the "
                "contact solution converges up to there; stiffer rings are the model "
                "without clearance)",
            )
        if given == ["clearance"] and self.bearing_stiffness is None:
            raise InputError(
                "clearance",
                self.clearance,
                "needs a bearing stiffness (the rings' contact) or viscosity and bearing "
                "length (Petroff friction) to act",
            )
        return self


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


def _web_pattern(value: Any) -> str:
    """A counterweight pattern as written: ``all``, ``none``, ``file`` or 0/1 per web,
    ``1,0,0,1``; returned in one spelling (lower-case name, or the digits joined by commas)."""
    shown = value
    if isinstance(value, (list, tuple)):
        value = ",".join(str(v) for v in value)
    allowed = "must be all, none, file or 0/1 per web (two per throw) such as 1,0,0,1"
    if not isinstance(value, str):
        raise InputError("patterns", shown, allowed)
    text = value.strip().lower()
    if text in NAMED_PATTERNS:
        return text
    items = [item.strip() for item in text.split(",")]
    if len(items) < 2 or any(item not in ("0", "1") for item in items):
        raise InputError("patterns", shown, allowed)
    if len(items) > 2 * MAX_MAIN_BEARINGS:
        raise InputError("patterns", shown, f"must list at most {2 * MAX_MAIN_BEARINGS} webs")
    if "1" not in items:
        raise InputError("patterns", shown, "has no counterweight (all zeros): write none")
    return ",".join(items)


class BearingSweepOptions(StudyOptions):
    """``bearings-sweep``: the main-bearing loads over counterweight patterns and balance
    factors (docs/main_bearings.md); the loads' own settings are :class:`BearingOptions`.
    ``none`` is one case whatever the balance factors."""

    patterns: Annotated[list[Annotated[str, BeforeValidator(_web_pattern)]], Many] = Field(
        ["all"],
        min_length=1,
        max_length=MAX_PATTERNS,
        title="Counterweight patterns",
        description="all, none, file or 0/1 per web: 1,0,0,1,1,0,0,1",
    )
    balance_factors: BalanceFactors = Field(
        [0.0, 0.25, 0.5, 0.75, 1.0], title="Balance factors", description="e.g. 0.4, 0.5, 0.6"
    )
    crank_model: Literal["indeterminate", "determinate"] = Field(
        "indeterminate", title="Crank model of the table and the figure"
    )

    @model_validator(mode="after")
    def _bounded(self) -> BearingSweepOptions:
        if len(set(self.patterns)) < len(self.patterns):
            twice = next(p for p in self.patterns if self.patterns.count(p) > 1)
            raise InputError(
                "patterns", self.patterns, f"must give each pattern once ({twice} twice)"
            )
        if len(set(self.balance_factors)) < len(self.balance_factors):
            again = next(f for f in self.balance_factors if self.balance_factors.count(f) > 1)
            raise InputError(
                "balance_factors",
                self.balance_factors,
                f"must give each balance factor once ({again:g} twice)",
            )
        swept = sum(p != "none" for p in self.patterns)
        cases = swept * len(self.balance_factors) + ("none" in self.patterns)
        if cases > MAX_SWEEP_CASES:
            raise InputError(
                "patterns",
                ", ".join(self.patterns),
                f"must make at most {MAX_SWEEP_CASES} cases (patterns other than none times "
                f"balance factors, and none once): here {cases}",
            )
        return self


#: the settings of ``bearings`` that ``bearings-sweep`` does not take: it sweeps the
#: balance factor and the counterweight pattern, and has no curves
NOT_SWEPT = ("balance_factor", "webs", "curves")


class BearingSweepStudyOptions(BearingSweepOptions, BearingOptions):
    """``bearings-sweep`` as one study: the sweep (:class:`BearingSweepOptions`) and the
    loads' settings of every case (:class:`BearingOptions`, but for :data:`NOT_SWEPT`)."""

    @model_validator(mode="after")
    def _not_swept(self) -> BearingSweepStudyOptions:
        for name in NOT_SWEPT:
            if name in self.model_fields_set:
                raise InputError(
                    name,
                    getattr(self, name),
                    "is not a setting of the sweep: it sweeps the balance factors and the "
                    "counterweight patterns (balance_factors, patterns) and has no curves",
                )
        return self

    def loads(self) -> BearingOptions:
        """The settings of the loads of every case."""
        values = {name: getattr(self, name) for name in BearingOptions.model_fields}
        given_ = {name for name in BearingOptions.model_fields if name in self.model_fields_set}
        return BearingOptions.model_construct(given_, **values)

    def sweep(self) -> BearingSweepOptions:
        """The sweep's own settings."""
        values = {name: getattr(self, name) for name in BearingSweepOptions.model_fields}
        given_ = {
            name for name in BearingSweepOptions.model_fields if name in self.model_fields_set
        }
        return BearingSweepOptions.model_construct(given_, **values)


class ShaftSectionOptions(StudyOptions):
    """``shaft ...``: the shaft's section and material, the masses' radius, the bearings."""

    length: Length = Field(0.3, title="Shaft length")
    diameter: Length = Field(0.025, title="Outer diameter")
    bore: LengthOrZero = Field(0.0, title="Bore diameter (hollow shaft)")
    modulus: Modulus = Field(210e9, title="Young's modulus")
    density: Density = Field(7850.0, title="Density")
    poisson: Number = Field(0.3, gt=-1, lt=0.5, title="Poisson's ratio")
    unbalance_radius: Length = Field(0.02, title="CG radius of the unbalance masses")
    bearing_stiffness: Stiffness | None = Field(None, title="Radial bearing stiffness")
    theory: Literal["euler-bernoulli", "timoshenko"] = Field("euler-bernoulli", title="Beam theory")

    @model_validator(mode="after")
    def _beam(self) -> ShaftSectionOptions:
        _slender(self.length, self.diameter)
        return self


class ShaftStudyOptions(ShaftSectionOptions):
    """``shaft inline4|inline3``: the required unbalance (given, or from the study's
    engine) and the placement sweep; ``order`` is inline4's, ``type``, ``hold``,
    ``bearing_offset`` and ``z_min`` inline3's."""

    unbalance: Requirement | None = Field(None, title="Required first moment")
    speed: Speed | None = Field(None, title="Shaft speed")
    weight: ShaftWeight = Field(2.0, title="Objective weight w")
    weights: Annotated[list[ShaftWeight], BeforeValidator(_comma_list)] | None = Field(
        None, min_length=1, max_length=MAX_SWEEP, title="Weights of the sweep"
    )
    points: Whole = Field(200, ge=3, le=MAX_SHAFT_POINTS, title="Design points")
    secondary: Literal["reaction-difference", "inverse-frequency"] | None = Field(
        None,
        title="B of the objective",
        description="empty: reaction-difference for inline4, inverse-frequency for inline3",
    )
    order: Whole | None = Field(
        None,
        ge=1,
        le=2,
        title="Order of the shaft the engine needs (1 or 2)",
        description="empty: 2 when the engine has a free second-order force or moment, else 1",
    )
    type: Literal["I", "II", "III", "all"] = Field("all", title="Rotor type")
    hold: Literal["couple", "unbalance"] = Field(
        "couple", title="Keep the couple (physical) or each mass's unbalance (paper)"
    )
    bearing_offset: Length | None = Field(None, title="Bearing-to-mass distance")
    z_min: Number = Field(0.3, ge=0, lt=1, title="Smallest second-mass position z/L")


class ShaftCheckOptions(ShaftSectionOptions):
    """``shaft check``: one layout (bearings, masses, unbalances, phases) and its limits."""

    bearing: Annotated[list[Position], Many] = Field([], min_length=2, max_length=MAX_SHAFT_ITEMS)
    mass: Annotated[list[Position], Many] = Field([], min_length=1, max_length=MAX_SHAFT_ITEMS)
    unbalance: Annotated[list[Unbalance], Many] = Field(
        [], min_length=1, max_length=MAX_SHAFT_ITEMS
    )
    phase: Annotated[list[Angle], Many] = Field([], max_length=MAX_SHAFT_ITEMS)
    speed: Speed | None = Field(None, title="Shaft speed")
    max_speed: Speed | None = Field(None, title="Maximum shaft speed")
    margin: Number = Field(0.25, ge=0, le=10, title="Critical-speed separation")
    bearing_capacity: Annotated[Force, Field(gt=0)] | None = Field(None, title="Bearing load")
    deflection_limit: Length | None = Field(None, title="Allowed deflection")


class BalanceFactorOptions(StudyOptions):
    """``balance-factor``: one crank's balance factor, bob-weight and force study."""

    reciprocating_mass: Mass | None = Field(None, title="Reciprocating mass")
    crank_radius: Length | None = Field(None, title="Crank radius")
    rotating_mass: Mass | None = Field(None, title="Rotating mass")
    cw_mass: Mass | None = Field(None, title="Counterweight mass (webs incl.)")
    cw_radius: Length | None = Field(None, title="Counterweight CG radius")
    balance_factor: Factor | None = Field(None, title="Balance factor studied")
    target: Factor | None = Field(None, title="Balance factor of the bob-weight")
    speed: Speed | None = Field(None, title="Crank speed")
    rod_length: Length | None = Field(None, title="Conrod length")
    offset: Position | None = Field(None, title="Wrist-pin offset")
    kinematics: Literal["exact", "series", "first-order"] | None = Field(
        None,
        title="Piston kinematics",
        description="empty: the engine's; without an engine exact with a conrod length, "
        "else first-order",
    )
    cylinder: Whole = Field(1, ge=1, le=10_000, title="Cylinder of the engine")


class RebalancePartsOptions(StudyOptions):
    """``rebalance``: a parts file and the settings that override its values (the file's
    own schema, :mod:`crankbalance.io.rebalance_file`, then checks how they combine)."""

    parts: str | None = Field(None, title="Parts file (TOML)")
    crank_radius: Length | None = Field(None, title="Crank radius")
    cw_mass: Mass | None = Field(None, title="Counterweight mass (webs incl.)")
    cw_radius: Length | None = Field(None, title="Counterweight CG radius")
    old_rotating_mass: Mass | None = Field(None, title="Rotating mass, old parts")
    old_reciprocating_mass: Mass | None = Field(None, title="Reciprocating mass, old parts")
    new_rotating_mass: Mass | None = Field(None, title="Rotating mass, new parts")
    new_reciprocating_mass: Mass | None = Field(None, title="Reciprocating mass, new parts")
    target: Annotated[list[Annotated[float | str, BeforeValidator(_target)]], Many] = Field(
        [], max_length=50, title="Target balance factors"
    )
    method: Literal["face", "holes"] | None = Field(None, title="Correction method")
    correction_radius: Length | None = Field(None, title="Radius of the correction")
    face_area: Area | None = Field(None, title="Face area ground per web")
    face_orientation: Literal["radial", "axial"] | None = Field(
        None, title="Face ground radially or axially"
    )
    hole_diameter: Length | None = Field(None, title="Drill diameter")
    holes: Whole | None = Field(None, ge=1, le=1000, title="Holes per web")
    hole_direction: Literal["axial", "radial"] | None = Field(None, title="Hole direction")
    point_angle: PointAngle | None = Field(None, title="Drill point angle (180 deg: flat)")
    depth_to: DepthTo | None = Field(None, title="Depth read to")
    web_thickness: Length | None = Field(None, title="Web thickness at the holes")
    density: Density | None = Field(None, title="Crank material density")
    depth_resolution: LengthOrZero | None = Field(None, title="Machining step")
    grade: str | None = Field(None, title="ISO 21940-11 grade")
    rotor_mass: Mass | None = Field(None, title="Crank mass")
    speed: Speed | None = Field(None, title="Largest service speed")
    tolerance: Requirement | None = Field(None, title="Permissible residual unbalance")


def _reading(value: Any) -> Any:
    """A balancing-machine reading as typed, ``"12.5 g @ 40 mm, 35 deg"``: the amount (a
    mass, 0 or more) at a radius, and the angle; -> (mass [kg], radius [m], angle [rad])."""
    if not isinstance(value, str):
        return value
    amount, _at, rest = value.partition("@")
    radius, _comma, where = rest.partition(",")
    if not (_at and _comma):
        raise InputError("", value, f"must be {READING_WORDS}")
    mass = parse_quantity(amount, "mass", "")
    size = parse_quantity(radius, "length", "")
    turn = parse_quantity(where, "angle", "")
    inside = [(mass, "mass", 0.0), (size, "length", RANGES["length"][0])]
    for number_, kind, low in (*inside, (turn, "angle", RANGES["angle"][0])):
        if not low <= number_ <= RANGES[kind][1]:
            raise InputError("", value, f"must be {READING_WORDS}, in range")
    return (mass, size, turn)


def _pair(value: Any) -> Any:
    """Two values as typed, ``"0 mm, 400 mm"``, as a list."""
    return [part.strip() for part in value.split(",")] if isinstance(value, str) else value


#: a balancing-machine reading in words
READING_WORDS = "an amount at a radius and an angle, e.g. '12.5 g @ 40 mm, 35 deg'"
Reading = Annotated[tuple[float, float, float], BeforeValidator(_reading)]
#: two axial positions (measuring or correction planes, bearings) [m]
Positions = Annotated[list[Position], BeforeValidator(_pair), Field(min_length=2, max_length=2)]


#: most engines one ``shop scatter`` draws
MAX_SCATTER_SAMPLES = 10_000_000
#: the coarsest resolution of the scale of ``shop scatter`` [kg]
MAX_SCALE_STEP = 0.01


def _scale_step(value: Any) -> float:
    """The resolution of a scale: 0 (exact), or a mass up to :data:`MAX_SCALE_STEP`."""
    if (
        isinstance(value, str)
        and value.strip() == "0"
        or (isinstance(value, int | float) and not isinstance(value, bool) and value == 0)
    ):
        return 0.0
    step = parse_quantity(value, "mass", "")
    if not 0 <= step <= MAX_SCALE_STEP:
        raise InputError("", value, "must be a mass from 0 to 10 g")
    return step


#: the resolution of a scale [kg]
ScaleStep = Annotated[float, BeforeValidator(_scale_step)]


class ShopOptions(StudyOptions):
    """The balance shop (issue 16): the parts file, matching, bob-weights, readings to a hole
    plan, the ISO check, and the Monte Carlo of the weight scatter."""

    parts: str | None = Field(None, title="Parts file (CSV or TOML)")
    fraction: Factor = Field(0.5, title="Reciprocating fraction in the bob-weights")
    method: Literal["milp", "pairing", "exhaustive", "as-listed"] = "milp"
    time_limit: Time = Field(60.0, le=3600.0, title="Matching time limit")
    reading: Annotated[list[Reading], Many] = Field(
        [], max_length=2, title="Readings, one per measuring plane"
    )
    convention: Literal["heavy", "light"] = "heavy"
    measuring_planes: Positions | None = Field(None, title="Measuring planes")
    correction_planes: Positions | None = Field(None, title="Correction planes")
    hole_diameter: Length = Field(0.008, title="Drill diameter")
    hole_radius: Length | None = Field(None, title="Radius of the holes")
    max_depth: Length = Field(0.015, title="Deepest hole")
    web_thickness: Length | None = Field(None, title="Web thickness at the holes")
    depth_to: DepthTo | None = None
    point_angle: PointAngle = Field(math.radians(118.0), title="Drill point angle")
    direction: Literal["axial", "radial"] = "axial"
    spacing: LengthOrZero = Field(0.002, title="Material between holes")
    depth_resolution: LengthOrZero = Field(0.0001, title="Machining step")
    density: Density = Field(7850.0, title="Crank material density")
    slug_density: Density | None = Field(None, title="Heavy-metal density (add instead)")
    grade: str = Field("G6.3", title="ISO 21940-11 grade")
    rotor_mass: Mass | None = Field(None, title="Crank mass")
    speed: Speed | None = Field(None, title="Largest service speed")
    bearings: Positions | None = Field(None, title="Main bearings")
    center_of_mass: Position | None = Field(None, title="Centre of mass")
    samples: Whole = Field(100_000, ge=1, le=MAX_SCATTER_SAMPLES, title="Engines drawn")
    seed: Whole = Field(0, ge=0, le=2**63 - 1, title="Seed of the random numbers")
    scale_step: ScaleStep = Field(1e-4, title="Resolution of the scale")

    @model_validator(mode="after")
    def _two_readings(self) -> ShopOptions:
        if len(self.reading) == 1:
            raise InputError("reading", None, "must be given twice, one per measuring plane")
        return self


class ToleranceOptions(StudyOptions):
    """``tolerance``: ISO 21940-11 permissible residual unbalance and its planes (with an
    engine the rotor mass and the speed default to its crank's rotating masses and its
    speed); ``list_grades`` lists the grades instead."""

    grade: str | None = Field(None, title="Balance quality grade")
    rotor_mass: Mass | None = Field(None, title="Rotor mass")
    speed: Speed | None = Field(None, title="Largest service speed")
    residual: Unbalance | None = Field(None, title="Measured residual unbalance")
    bearing_a: Position | None = Field(None, title="Bearing A")
    bearing_b: Position | None = Field(None, title="Bearing B")
    center_of_mass: Position | None = Field(None, title="Centre of mass")
    plane_1: Position | None = Field(None, title="Correction plane I")
    plane_2: Position | None = Field(None, title="Correction plane II")
    list_grades: bool = Field(False, title="List the grades")


class PlotOptions(StudyOptions):
    """``plot``: the settings of the figures that take any."""

    order: Annotated[int, BeforeValidator(_number)] | Literal["rotating"] = Field(
        1, title="Harmonic order"
    )
    cylinder: Whole = Field(1, ge=1, le=10_000, title="Cylinder")
    balance_factor: Factor = Field(0.5, title="Balance factor")

    @model_validator(mode="after")
    def _order_range(self) -> PlotOptions:
        if self.order != "rotating" and not 1 <= int(self.order) <= MAX_ORDER:
            raise InputError(
                "order", self.order, f"a harmonic order from 1 to {MAX_ORDER}, or 'rotating'"
            )
        return self


def _no_vr_layout(value: Any) -> Any:
    """The explorer's layouts: a VR is refused with the reason (it enumerates no VR)."""
    from ..physics.explore.orders import VR_REFUSED

    if isinstance(value, str) and value.strip() == "vr":
        raise InputError("", value, VR_REFUSED)
    return value


class ExploreOptions(StudyOptions):
    """``explore``: the design-space explorer (docs/explorer.md)."""

    layout: Annotated[Literal["inline", "vee", "boxer", "w"], BeforeValidator(_no_vr_layout)] = (
        Field("inline", title="Layout")
    )
    cylinders: Whole = Field(4, ge=1, le=20, title="Cylinders")
    strokes: Whole = Field(4, ge=2, le=4, title="Strokes per cycle (2 or 4)")
    bank_angle: Angle | None = Field(None, title="Vee or W bank angle")
    crank: Literal["any", "flat", "cross", "split"] = Field("any", title="Crank family")
    target: Literal["none", "counterweights", "primary", "secondary"] = Field(
        "counterweights", title="Balancing target"
    )
    balance_factor: Factor = Field(0.0, title="Balance factor")
    mode_shape: str = Field("uniform", title="Torsional mode shape")
    orders: Whole = Field(8, ge=1, le=MAX_ORDER, title="Highest order")
    objectives: str = Field("F1,M1,F2,M2", title="Pareto objectives (comma separated)")
    filter: str | None = Field(None, title="Filter")
    top: Whole = Field(20, ge=1, le=100_000, title="Rows of the top-N table")
    top_key: str | None = Field(None, title="Column of the top-N table")
    chunk: Whole | None = Field(
        None,
        ge=1,
        le=LARGEST_CHUNK,
        title="Indices per task (default: chosen from the problem; bounded by memory)",
    )
    workers: Whole | None = Field(None, ge=1, le=1024, title="Workers of a LocalCluster")
    scheduler: str | None = Field(None, title="Address of a dask scheduler")
    connect_timeout: Time = Field(5.0, ge=0.1, le=120.0, title="Time a scheduler has to answer")
    sample: Whole | None = Field(None, ge=1, le=MAX_DRAWS, title="Random draws (search)")
    seed: Whole = Field(0, ge=0, le=2**32 - 1, title="Random seed")


#: the range of a torsional stiffness [N m/rad] (a model engine's crank to a ship's shafting)
TORSIONAL_STIFFNESS_RANGE = (1.0, 1e11)
_TORSIONAL_EXAMPLE = "5e5 N*m/rad"


def _torsional_stiffness(value: Any) -> float:
    """A torsional stiffness written with its unit per radian: ``"5e5 N*m/rad"``."""
    low, high = TORSIONAL_STIFFNESS_RANGE
    words = (
        f"a torsional stiffness such as {_TORSIONAL_EXAMPLE!r}, from {low:g} to {high:g} N*m/rad"
    )
    if not isinstance(value, str) or "rad" not in value:
        raise InputError("", value, f"must be {words}")
    stiffness = parse_quantity(value.replace("/rad", "").replace("/ rad", ""), "torque", "")
    if not low <= stiffness <= high:
        raise InputError("", value, f"must be {words}")
    return stiffness


#: a torsional stiffness [N m/rad]
TorsionalStiffness = Annotated[float, BeforeValidator(_torsional_stiffness)]
#: a frequency [Hz] of a torsional system
Frequency = Annotated[float, _quantity("frequency"), Field(gt=0, le=1e5)]
#: a power [W] (the heat a damper may dissipate)
Power = Annotated[float, _quantity("power"), Field(gt=0, le=1e9)]
#: a damping ratio [-]
DampingRatio = Annotated[float, BeforeValidator(_number), Field(ge=0, le=0.5)]


class TorsionalOptions(CombustionOptions, CrankDimensionOptions):
    """``torsional``: the crank train's lumped torsional model (docs/torsional.md): the
    speed range and orders, the throws' inertia and stiffness (given, or Carter's formula
    from the dimensions), front end, flywheel, damper, load, and the Wiebe combustion.
    Crank dimensions left empty are those ``bearings`` uses
    (:func:`crankbalance.studies.crank.crank_dimensions`)."""

    speed_min: Speed = Field(600 * _RPM, title="Lowest speed")
    speed_max: Speed | None = Field(None, title="Highest speed (default: the engine's)")
    speed_points: Whole = Field(400, ge=10, le=2001, title="Speeds of the sweep")
    highest_order: Number = Field(12.0, ge=0.5, le=MAX_ORDER, title="Highest engine order")
    throw_inertia: Inertia | None = Field(None, title="Inertia of one throw with its big ends")
    throw_stiffness: TorsionalStiffness | None = Field(
        None, title="Stiffness between throws (default: Carter's formula, an approximation)"
    )
    journal_length: Length | None = Field(
        None, title="Main journal length", description=ENGINE_DIMENSION_TEXT
    )
    pin_length: Length | None = Field(
        None, title="Crankpin length", description=ENGINE_DIMENSION_TEXT
    )
    shear_modulus: Modulus = Field(80e9, title="Shear modulus of the crank")
    front_inertia: Inertia = Field(
        DEFAULT_FRONT_INERTIA, title="Pulley, timing gear and damper hub"
    )
    front_stiffness: TorsionalStiffness | None = Field(
        None, title="Front end to throw 1 (default: the throws')"
    )
    flywheel_inertia: Inertia = Field(DEFAULT_FLYWHEEL_INERTIA, title="Flywheel and clutch")
    flywheel_stiffness: TorsionalStiffness | None = Field(
        None, title="Last throw to flywheel (default: the throws')"
    )
    damper_inertia: Inertia | None = Field(None, title="Damper ring (none: no damper)")
    damper_frequency: Frequency | None = Field(None, title="Damper tuning frequency")
    damper_damping_ratio: DampingRatio = Field(0.15, title="Damper damping ratio")
    damper_allowed_power: Power | None = Field(None, title="Power the damper may dissipate")
    load_inertia: Inertia | None = Field(None, title="Driven load (none: free end)")
    load_stiffness: TorsionalStiffness | None = Field(None, title="Flywheel to load")
    shaft_damping_ratio: DampingRatio = Field(0.02, title="Crank's own damping ratio")
    bore: Length | None = Field(None, title="Bore (default: square)")

    @model_validator(mode="after")
    def _consistent(self) -> TorsionalOptions:
        if self.speed_max is not None and self.speed_max <= self.speed_min:
            raise InputError("speed_max", self.speed_max, "must be above the lowest speed")
        if (self.damper_inertia is None) != (self.damper_frequency is None):
            raise InputError(
                "damper_frequency" if self.damper_inertia is not None else "damper_inertia",
                None,
                "the damper needs both its ring inertia and its tuning frequency",
            )
        if self.damper_allowed_power is not None and self.damper_inertia is None:
            raise InputError(
                "damper_allowed_power",
                None,
                "needs a damper: give --damper-inertia and --damper-frequency",
            )
        if (self.load_inertia is None) != (self.load_stiffness is None):
            raise InputError(
                "load_stiffness" if self.load_inertia is not None else "load_inertia",
                None,
                "the load needs both its inertia and the stiffness to the flywheel",
            )
        return self


Options = TypeVar("Options", bound=StudyOptions)


def given(settings: StudyOptions) -> frozenset[str]:
    """The fields of ``settings`` that were given (typed on the command line, sent to the
    API, passed to the model), as opposed to left at their defaults: a study takes an
    engine's value where a setting was not given, and refuses a given one that would not
    act."""
    return frozenset(settings.model_fields_set)


Kind = Literal["quantity", "number", "whole", "text", "list"]


def _unwrap(annotation: Any) -> tuple[Any, list[Any]]:
    """The base type of an annotation and its metadata, through ``X | None`` and
    ``Annotated`` (the constraints of a nested ``Field`` flattened)."""
    found: list[Any] = []
    while True:
        origin = get_origin(annotation)
        if origin is Annotated:
            annotation, *extra = get_args(annotation)
            for meta in extra:
                found += list(meta.metadata) if isinstance(meta, FieldInfo) else [meta]
        elif origin in (Union, types.UnionType):
            options = [a for a in get_args(annotation) if a is not type(None)]
            if len(options) != 1:
                return annotation, found
            annotation = options[0]
        else:
            return annotation, found


def _metadata(model: type[StudyOptions], name: str) -> list[Any]:
    """The field's constraints and validators, also those inside ``X | None``."""
    info = model.model_fields[name]
    return list(info.metadata) + _unwrap(info.annotation)[1]


def _quantity_kind(metadata: list[Any]) -> str | None:
    for meta in metadata:
        func = getattr(meta, "func", None)
        if isinstance(func, partial) and func.func is parse_quantity:
            return str(func.keywords["kind"])
    return None


def _show(value: float) -> str:
    return str(value) if isinstance(value, int) else f"{value:g}"


def field_kind(model: type[StudyOptions], name: str) -> tuple[Kind, str | None]:
    """How a field is written: its kind and, for a quantity, the quantity kind."""
    base, metadata = _unwrap(model.model_fields[name].annotation)
    quantity = _quantity_kind(list(model.model_fields[name].metadata) + metadata)
    if quantity is not None:
        return "quantity", quantity
    if get_origin(base) is list:
        return "list", None
    if base is int:
        return "whole", None
    if base is float:
        return "number", None
    return "text", None


def _bounds(metadata: list[Any]) -> Bounds:
    """The tightest (low, low is open, high, high is open) of a field's constraints."""
    low: float | None = None
    high: float | None = None
    low_open = high_open = False
    for meta in metadata:
        for attr, is_open in (("ge", False), ("gt", True)):
            value = getattr(meta, attr, None)
            if value is not None and (low is None or value > low or (value == low and is_open)):
                low, low_open = value, is_open
        for attr, is_open in (("le", False), ("lt", True)):
            value = getattr(meta, attr, None)
            if value is not None and (high is None or value < high or (value == high and is_open)):
                high, high_open = value, is_open
    return low, low_open, high, high_open


def _range_words(quantity: str | None, bounds: Bounds, whole: bool = False) -> str:
    """ "a length with a unit, e.g. '40 mm', from 0.001 mm to 100000 mm", "a number, greater
    than 0 and at most 1", ... for ``bounds`` (low, low is open, high, high is open)."""
    low, low_open, high, high_open = bounds
    if quantity is not None:
        article = "an" if quantity[0] in "aeiou" else "a"
        what = f"{article} {quantity} with a unit, e.g. '{KINDS[quantity][2]}',"

        def show(value: float) -> str:
            return format_quantity(float(value), quantity, digits=6)
    else:
        what = "a whole number" if whole else "a number"
        show = _show
    if low is not None and high is not None and not low_open and not high_open:
        return f"{what} from {show(low)} to {show(high)}"
    parts = []
    if low is not None:
        parts.append(f"{'greater than' if low_open else 'at least'} {show(low)}")
    if high is not None:
        parts.append(f"{'less than' if high_open else 'at most'} {show(high)}")
    return what.rstrip(",") + (", " + " and ".join(parts) if parts else "")


#: what a length that may be zero accepts, in words
ZERO_OR_LENGTH = (
    f"0, or {_range_words('length', (RANGES['length'][0], False, RANGES['length'][1], False))}"
)


def allowed(model: type[StudyOptions], name: str) -> str:
    """What a field accepts, in words: "a whole number from 16 to 100000", ..."""
    info = model.model_fields[name]
    kind, quantity = field_kind(model, name)
    base, _ = _unwrap(info.annotation)
    if kind == "list":
        _element, inner = _unwrap(get_args(base)[0])
        metadata = _metadata(model, name)
        shortest = next((m.min_length for m in metadata if hasattr(m, "min_length")), 0)
        longest = next((m.max_length for m in metadata if hasattr(m, "max_length")), None)
        count = f"{shortest} to {longest}" if longest else f"at least {shortest}"
        quantity = _quantity_kind(inner)
        if quantity is None:
            rest = _range_words(None, _bounds(inner)).removeprefix("a number")
            return f"{count} numbers{rest}, separated by commas"
        return f"{count} values, each {_range_words(quantity, _bounds(inner))}"
    if base is str:
        return "a text"
    if get_origin(base) is Literal:
        return "one of " + ", ".join(str(choice) for choice in get_args(base))
    if any(getattr(m, "func", None) is _zero_or_length for m in _metadata(model, name)):
        return ZERO_OR_LENGTH
    if name == "angle" and model is BalanceOptions:
        low, high = RANGES["angle"]
        return f"'optimal' or {_range_words('angle', (low, False, high, False))}"
    if model is PlotOptions and name == "order":
        return f"a harmonic order from 1 to {MAX_ORDER}, or 'rotating'"
    return _range_words(quantity, _bounds(_metadata(model, name)), kind == "whole")


def parse_options(
    model: type[Options],
    values: Mapping[str, Any],
    name: Callable[[str], str] = str,
) -> Options:
    """Validate a study's settings; raise :class:`InputError` naming the field as the user
    wrote it (``name(field)``), the value given and what is allowed.

    Values that are ``None`` are left out, so that the schema's default applies. A value
    in a list is named by its list's field and shown alone.
    """
    given = {key: value for key, value in values.items() if value is not None}
    try:
        return model.model_validate(given)
    except ValidationError as error:
        first = error.errors(include_url=False)[0]
        loc = [str(p) for p in first["loc"]]
        key = loc[0] if loc else ""
        value = first.get("input") if len(loc) > 1 else given.get(key, first.get("input"))
        inner = (first.get("ctx") or {}).get("error")
        if first["type"] == "extra_forbidden":
            raise InputError(
                name(key), value, f"unknown setting; known: {', '.join(model.model_fields)}"
            ) from None
        if isinstance(inner, InputError) and not loc:  # a check across fields
            field, text = inner.field, inner.allowed
            text = text if text.startswith("the ") else predicate(text)
            raise InputError(name(field), given.get(field, inner.value), text) from None
        if key not in model.model_fields:
            raise InputError(name(key), value, str(first.get("msg", ""))) from None
        text = allowed(model, key)
        if isinstance(inner, InputError):
            text = inner.allowed
        elif first["type"] in ("finite_number",) or (
            isinstance(inner, ValueError) and "finite" in str(inner)
        ):
            text = _finite(text)
        raise InputError(name(key), value, predicate(text)) from None


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


def _finite(text: str) -> str:
    """What is allowed, said to be finite: "a whole number from 1 to 64" -> "a finite whole
    number from 1 to 64"."""
    found = re.match(r"an? (.*)", text)
    return f"a finite {found.group(1)}" if found else f"{text} (a finite number)"


def default_text(model: type[StudyOptions], name: str) -> str:
    """A field's default as a user would type it ("" for a default of None)."""
    value = model.model_fields[name].default
    if value is None:
        return ""
    kind, quantity = field_kind(model, name)
    if kind == "quantity":
        return format_quantity(float(value), quantity or "length", digits=6)
    if kind == "list":
        return ", ".join(f"{v:g}" for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)
