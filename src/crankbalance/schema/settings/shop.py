"""The settings of the balance shop.

Part of :mod:`crankbalance.schema.settings`, imported when one of its schemas is first
asked for (see there)."""

from __future__ import annotations

import math
from typing import Any, Literal

from ...errors import InputError
from ...units import parse_quantity
from .. import core
from ..core import FieldProblem, entry, field
from .common import (
    DEPTH_TO,
    RANGES,
    READING_WORDS,
    DepthTo,
    StudyOptions,
    choice,
    factor,
    length_or_zero,
    point_angle,
    quantity,
    text,
    whole,
)


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
    point_angle: float = point_angle(
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
    spacing: float = length_or_zero(
        0.002, "Material between holes", "Material left between neighbouring holes."
    )
    depth_resolution: float = length_or_zero(
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
