"""The settings of the balance-shaft studies: placement, sections, design and check.

Part of :mod:`crankbalance.schema.settings`, imported when one of its schemas is first
asked for (see there)."""

from __future__ import annotations

from typing import Any, Literal

from ...units import format_quantity
from ..core import FieldProblem, entry, field
from .common import (
    MAX_SHAFT_ITEMS,
    MAX_SHAFT_POINTS,
    MAX_SWEEP,
    RANGES,
    StudyOptions,
    choice,
    length_or_zero,
    number,
    quantity,
    requirement,
    whole,
)


def _weight(default: Any, title: str, description: str, **options: Any) -> Any:
    """The weight w of the balance-shaft placement objective [-]."""
    return number(default, title, description, ge=0, le=1000, **options)


def _slender(length: float, diameter: float) -> None:
    """A shaft the beam model can describe: at least as long as its diameter."""
    if length < diameter:
        raise FieldProblem(
            "length",
            f"must be at least the diameter ({format_quantity(diameter, 'length', 6)}): the "
            "beam model needs a shaft longer than it is thick",
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


class ShaftSectionOptions(StudyOptions):
    """``shaft ...``: the shaft's section and material, the masses' radius, the bearings."""

    length: float = quantity("length", 0.3, "Shaft length", "Length of the balance shaft.")
    diameter: float = quantity("length", 0.025, "Outer diameter", "Outer diameter of the shaft.")
    bore: float = length_or_zero(
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

    unbalance: float | None = requirement(
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
