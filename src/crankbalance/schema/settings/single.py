"""The settings of the single-cylinder studies: balance factor, rebalancing and the
ISO 21940-11 tolerance.

Part of :mod:`crankbalance.schema.settings`, imported when one of its schemas is first
asked for (see there)."""

from __future__ import annotations

import math
from typing import Any, Literal

from ...errors import InputError
from ...units import parse_factor
from ..core import entry, field
from .common import (
    BALANCE_FACTOR_LIMITS,
    DEPTH_TO,
    MAX_HOLES,
    DepthTo,
    StudyOptions,
    choice,
    factor,
    length_or_zero,
    number,
    point_angle,
    quantity,
    requirement,
    text,
    whole,
)


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
    point_angle: float = point_angle(
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
    point_angle: float | None = point_angle(
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
    depth_resolution: float | None = length_or_zero(
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
    tolerance: float | None = requirement(
        None,
        "Permissible residual unbalance",
        "The permissible residual unbalance, instead of a grade.",
    )


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
