"""The rebalance parts file (TOML): a single-cylinder crank's old and new parts, its
counterweight, the correction and the tolerance (``examples/crf250r_rebalance.toml``,
``docs/single_cylinder.md``; Hoem and Røsholm (2016), Sec. 6.4).

Quantities are unit strings, parsed to SI floats on validation and checked against the
physical range of their kind (:data:`crankbalance.units.RANGES`); unknown keys are
errors.
Every key is optional here: the ``rebalance`` command completes the file with its options,
and :func:`crankbalance.studies.rebalance.rebalance_parts` says what is still missing.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Literal

from ..errors import InputError
from ..schema.core import FieldProblem, Schema, entry, field, parse_in_range
from ..units import parse_factor
from .reading import parse_toml, read_text

#: largest rebalance file read [bytes]; the example is about 2 kB
MAX_FILE_BYTES = 1_000_000
DOC = "docs/single_cylinder.md"
#: most target balance factors of one rebalancing
MAX_TARGETS = 50


def _target(value: Any, where: str) -> Any:
    """A target balance factor: a number, a percentage or ``"factory"`` (the crank's own)."""
    if isinstance(value, str) and value.strip().lower() == "factory":
        return "factory"
    from ..physics.single_cylinder import check_balance_factor

    try:
        number = parse_factor(value, where)
    except InputError:
        raise InputError(
            where, value, "must be a number such as 0.28, a percentage '28%' or 'factory'"
        ) from None
    return check_balance_factor(number, where)


def _part_masses(value: Any, where: str) -> dict[str, float]:
    """A table of named part masses, ``[old.rotating]``: name -> mass [kg], each 0 or more."""
    if not isinstance(value, Mapping):
        raise InputError(where, value, "must be a table of part names and masses")
    masses = {}
    for name, mass in value.items():
        masses[name] = parse_in_range(mass, "mass", f"{where}.{name}")
        if masses[name] < 0:
            raise InputError(f"{where}.{name}", mass, "must not be negative")
    return masses


class _Table(Schema):
    DOC = DOC


class Counterweight(_Table):
    """``[counterweight]``: counterweights + webs, measured on the crank."""

    mass: float | None = field(
        "mass",
        default=None,
        gt=0,
        title="Counterweight mass",
        description="Mass of the counterweights with their webs.",
    )
    cg_radius: float | None = field(
        "length",
        default=None,
        gt=0,
        title="Counterweight CG radius",
        description="Radius of the centre of gravity of the counterweights with their webs.",
    )


class Parts(_Table):
    """``[old]`` or ``[new]``: the rotating and reciprocating masses of one cylinder, as
    named parts (``[old.rotating]``) or as totals (``rotating_mass``)."""

    label: str | None = field(
        "text", default=None, title="Label", description="A name for these parts."
    )
    rotating: dict[str, float] | None = field(
        "any",
        default=None,
        parse=_part_masses,
        words="a table of part names and masses, e.g. crankpin = '50 g'",
        title="Rotating parts",
        description="The rotating parts by name with their masses.",
    )
    reciprocating: dict[str, float] | None = field(
        "any",
        default=None,
        parse=_part_masses,
        words="a table of part names and masses, e.g. piston = '200 g'",
        title="Reciprocating parts",
        description="The reciprocating parts by name with their masses.",
    )
    rotating_mass: float | None = field(
        "mass",
        default=None,
        gt=0,
        title="Rotating mass",
        description="The total rotating mass (instead of the parts).",
    )
    reciprocating_mass: float | None = field(
        "mass",
        default=None,
        gt=0,
        title="Reciprocating mass",
        description="The total reciprocating mass (instead of the parts).",
    )

    def check(self) -> None:
        for kind in ("rotating", "reciprocating"):
            parts, total = getattr(self, kind), getattr(self, f"{kind}_mass")
            if parts is not None and total is not None:
                raise FieldProblem(
                    f"{kind}_mass", f"give [..{kind}] part masses or the total, not both"
                )
            if parts is None and total is None:
                raise FieldProblem(kind, f"give the {kind} part masses or {kind}_mass")
            if parts is not None and not parts:
                raise FieldProblem(kind, "lists no part")

    @property
    def rotating_total(self) -> float:
        """Rotating mass [kg]: the total, or the sum of the parts."""
        return self.rotating_mass if self.rotating is None else sum(self.rotating.values())  # type: ignore[return-value]

    @property
    def reciprocating_total(self) -> float:
        """Reciprocating mass [kg]: the total, or the sum of the parts."""
        if self.reciprocating is None:
            return self.reciprocating_mass  # type: ignore[return-value]
        return sum(self.reciprocating.values())


class Correction(_Table):
    """``[correction]``: how material comes off the counterweights (face or holes)."""

    method: Literal["face", "holes"] = field(
        "choice",
        default="face",
        choices=("face", "holes"),
        title="Method",
        description="face: grind the face; holes: drill.",
    )
    radius: float | None = field(
        "length",
        default=None,
        gt=0,
        title="Radius",
        description="Radius at which material comes off.",
    )
    area: float | None = field(
        "area", default=None, gt=0, title="Face area", description="Area ground per web."
    )
    orientation: Literal["radial", "axial"] | None = field(
        "choice",
        default=None,
        choices=("radial", "axial"),
        title="Face orientation",
        description="The ground face's orientation.",
    )
    diameter: float | None = field(
        "length", default=None, gt=0, title="Drill diameter", description="Drill diameter."
    )
    number: int | None = field(
        "whole",
        default=None,
        ge=1,
        le=1000,
        title="Holes per web",
        description="Holes drilled side by side in each web.",
    )
    direction: Literal["axial", "radial"] | None = field(
        "choice",
        default=None,
        choices=("axial", "radial"),
        title="Hole direction",
        description="The holes' direction.",
    )
    point_angle: float | None = field(
        "angle",
        default=None,
        zero=True,
        title="Drill point angle",
        description="The drill point's included angle (180 deg: flat bottom).",
    )
    depth_to: Literal["shoulder", "tip"] | None = field(
        "choice",
        default=None,
        choices=("shoulder", "tip"),
        title="Depth read to",
        description="What the depths of pointed holes are read to.",
    )
    web_thickness: float | None = field(
        "length",
        default=None,
        gt=0,
        title="Web thickness",
        description="Axial thickness of the web at the holes.",
    )
    drill_length: float | None = field(
        "length",
        default=None,
        gt=0,
        title="Drill length",
        description="Usable length of the drill: the deepest hole, to the tip.",
    )
    webs: int = field(
        "whole",
        default=2,
        ge=1,
        le=64,
        title="Webs",
        description="Webs the correction is shared between.",
    )
    density: float | None = field(
        "density", default=None, gt=0, title="Density", description="The crank's density."
    )
    depth_resolution: float | None = field(
        "length",
        default=None,
        ge=0,
        title="Machining step",
        description="The step the depths are rounded to.",
    )

    def check(self) -> None:
        if self.point_angle is not None and not 0 < self.point_angle <= math.pi:
            raise FieldProblem("point_angle", "must be above 0 and at most 180 deg (flat bottom)")
        for name, keys in METHOD_KEYS.items():
            if name == self.method:
                continue
            for key in keys:
                if getattr(self, key) is not None:
                    raise FieldProblem(
                        key,
                        f"does not apply to method {self.method!r}; remove it or set the "
                        "method (--method face|holes)",
                    )


#: [correction] keys that belong to one method only
METHOD_KEYS: dict[str, tuple[str, ...]] = {
    "face": ("area", "orientation"),
    "holes": (
        "diameter",
        "number",
        "direction",
        "point_angle",
        "depth_to",
        "web_thickness",
        "drill_length",
    ),
}


class Tolerance(_Table):
    """``[tolerance]``: the permissible residual, given or from an ISO 21940-11 grade."""

    grade: str | None = field(
        "text", default=None, title="Grade", description="The ISO 21940-11 grade."
    )
    rotor_mass: float | None = field(
        "mass", default=None, gt=0, title="Rotor mass", description="The crank's mass."
    )
    speed: float | None = field(
        "speed", default=None, gt=0, title="Speed", description="The largest service speed."
    )
    unbalance: float | None = field(
        "unbalance",
        default=None,
        gt=0,
        title="Permissible unbalance",
        description="The permissible residual unbalance, instead of a grade.",
    )

    def check(self) -> None:
        if self.unbalance is not None:
            for key in ("grade", "rotor_mass", "speed"):
                if getattr(self, key) is not None:
                    raise FieldProblem(
                        key, "give tolerance.unbalance, or grade, rotor_mass and speed, not both"
                    )


class RebalanceFile(_Table):
    """A whole rebalance parts file."""

    name: str | None = field("text", default=None, title="Name", description="A name.")
    crank_radius: float | None = field(
        "length", default=None, gt=0, title="Crank radius", description="Crank throw radius."
    )
    targets: list[float | str] | None = field(
        "list",
        default=None,
        item=entry(
            "any",
            parse=_target,
            words="a number such as 0.28, a percentage '28%' or 'factory'",
        ),
        min_items=1,
        max_items=MAX_TARGETS,
        title="Targets",
        description="The balance factors to rebalance to (factory: the crank's own).",
    )
    counterweight: Counterweight | None = field(
        "table",
        default=None,
        table=Counterweight,
        title="Counterweight",
        description="The counterweights with their webs, measured on the crank.",
    )
    old: Parts | None = field(
        "table",
        default=None,
        table=Parts,
        title="Old parts",
        description="The cylinder's masses with the old parts.",
    )
    new: Parts | None = field(
        "table",
        default=None,
        table=Parts,
        title="New parts",
        description="The cylinder's masses with the new parts.",
    )
    correction: Correction | None = field(
        "table",
        default=None,
        table=Correction,
        title="Correction",
        description="How material comes off the counterweights.",
    )
    tolerance: Tolerance | None = field(
        "table",
        default=None,
        table=Tolerance,
        title="Tolerance",
        description="The permissible residual unbalance.",
    )


def rebalance_file_from_dict(data: Any, source: str = "parts") -> RebalanceFile:
    """Validate the contents of a rebalance parts file; :class:`InputError` names the key."""
    if not isinstance(data, dict):
        raise InputError(source, type(data).__name__, "must be a table of keys and values")
    if "targets" in data and not isinstance(data["targets"], list):
        data = {**data, "targets": [data["targets"]]}  # one target as itself
    return RebalanceFile.parse(data)


def read_rebalance_data(path: str | os.PathLike[str], field: str = "parts") -> dict[str, Any]:
    """The TOML table of a rebalance parts file, read with the bounds of
    :mod:`crankbalance.io.reading`: a regular file of at most :data:`MAX_FILE_BYTES`,
    UTF-8 text, bounded nesting."""
    text = read_text(path, field, "a rebalance parts file (.toml)", MAX_FILE_BYTES)
    return parse_toml(text, field, str(path))


def load_rebalance_file(path: str | os.PathLike[str]) -> RebalanceFile:
    """Read and validate a rebalance parts file (see ``examples/crf250r_rebalance.toml``)."""
    data = read_rebalance_data(path)
    if "name" not in data:
        data["name"] = Path(path).stem
    return rebalance_file_from_dict(data, str(path))
