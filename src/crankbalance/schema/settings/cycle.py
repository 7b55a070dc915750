"""The settings of the engine-cycle studies: performance, friction, the rotor bench,
combustion, cycle and sensitivity.

Part of :mod:`crankbalance.schema.settings`, imported when one of its schemas is first
asked for (see there)."""

from __future__ import annotations

import math

from ...physics.limits import BURN_DURATION_RANGE, BURN_ENDS, GAMMA_RANGE, IGNITION_RANGE
from ...units import format_quantity
from ..core import FieldProblem, entry, field
from .common import (
    ENGINE_INERTIA_TEXT,
    FLUCTUATION_TARGET,
    MAX_BENCH_CONTROL,
    MAX_BENCH_REVOLUTIONS,
    MAX_BENCH_RUNS,
    MAX_PRESSURE_TABLES,
    MAX_SETTING_CHARS,
    MAX_SWEEP,
    RANGES,
    RPM,
    THESIS_CRANK_INERTIA,
    StudyOptions,
    balance_factors,
    choice,
    factor,
    friction,
    number,
    number_sweep,
    quantity,
    whole,
)


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
    balance_factors: list[float] = balance_factors(
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
    friction_coefficient: float = friction(
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
    friction_coefficient: float | None = friction(
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
    friction_coefficient: float | None = friction(
        None, "Friction coefficient", "Coulomb friction coefficient of each bearing."
    )
    speed: list[float] = field(
        "list",
        default=[3000 * RPM],
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
    friction_coefficient: float = friction(
        0.005, "Friction coefficient", "Coulomb friction coefficient of the main bearing."
    )
    speed: float = quantity("speed", 9000 * RPM, "Mean speed", "Mean crank speed of the cycle.")
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
    balance_factors: list[float] = balance_factors(
        [0.1 * k for k in range(11)], "Balance factors", "The balance factors of the sweep."
    )
    mass_scales: list[float] = field(
        "list",
        default=[1.0],
        item=entry("number", gt=0, le=10),
        min_items=1,
        max_items=MAX_SWEEP,
        parse=number_sweep,
        title="Reciprocating-mass scales",
        description="Factors on the reciprocating mass (lighter parts below 1).",
    )
