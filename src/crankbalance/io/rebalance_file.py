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
from functools import partial
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError, model_validator

from ..errors import InputError
from ..schema.engine import FieldProblem, input_error, parse_in_range
from ..units import parse_factor
from .reading import parse_toml, read_text

#: largest rebalance file read [bytes]; the example is about 2 kB
MAX_FILE_BYTES = 1_000_000
DOC = "docs/single_cylinder.md"


def _quantity(kind: str) -> Any:
    return BeforeValidator(partial(parse_in_range, kind=kind))


Length = Annotated[float, _quantity("length")]
Mass = Annotated[float, _quantity("mass")]
Area = Annotated[float, _quantity("area")]
Density = Annotated[float, _quantity("density")]
Speed = Annotated[float, _quantity("speed")]
Unbalance = Annotated[float, _quantity("unbalance")]
Angle = Annotated[float, _quantity("angle")]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


def _target(value: Any) -> Any:
    """A target balance factor: a number, a percentage or ``"factory"`` (the crank's own)."""
    if isinstance(value, str) and value.strip().lower() == "factory":
        return "factory"
    from ..physics.single_cylinder import check_balance_factor

    try:
        number = parse_factor(value, "")
    except InputError:
        raise InputError(
            "", value, "must be a number such as 0.28, a percentage '28%' or 'factory'"
        ) from None
    return check_balance_factor(number, "")


Target = Annotated[float | Literal["factory"], BeforeValidator(_target)]


def _positive(model: Any, names: tuple[str, ...]) -> None:
    for name in names:
        value = getattr(model, name)
        if value is not None and not value > 0:
            raise FieldProblem(name, "must be greater than zero")


class Counterweight(_Strict):
    """``[counterweight]``: counterweights + webs, measured on the crank."""

    mass: Mass | None = None
    cg_radius: Length | None = None

    @model_validator(mode="after")
    def _check(self) -> Counterweight:
        _positive(self, ("mass", "cg_radius"))
        return self


class Parts(_Strict):
    """``[old]`` or ``[new]``: the rotating and reciprocating masses of one cylinder, as
    named parts (``[old.rotating]``) or as totals (``rotating_mass``)."""

    label: str | None = None
    rotating: dict[str, Mass] | None = None
    reciprocating: dict[str, Mass] | None = None
    rotating_mass: Mass | None = None
    reciprocating_mass: Mass | None = None

    @model_validator(mode="after")
    def _check(self) -> Parts:
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
            for name, mass in (parts or {}).items():
                if not mass >= 0:
                    raise FieldProblem(f"{kind}.{name}", "must not be negative")
            if total is not None and not total > 0:
                raise FieldProblem(f"{kind}_mass", "must be greater than zero")
        return self

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


class Correction(_Strict):
    """``[correction]``: how material comes off the counterweights (face or holes)."""

    method: Literal["face", "holes"] = "face"
    radius: Length | None = None
    area: Area | None = None
    orientation: Literal["radial", "axial"] | None = None
    diameter: Length | None = None
    number: int | None = Field(default=None, ge=1, le=1000)
    direction: Literal["axial", "radial"] | None = None
    point_angle: Angle | None = None
    depth_to: Literal["shoulder", "tip"] | None = None
    web_thickness: Length | None = None
    webs: int = Field(default=2, ge=1, le=64)
    density: Density | None = None
    depth_resolution: Length | None = None

    @model_validator(mode="after")
    def _check(self) -> Correction:
        _positive(self, ("radius", "area", "diameter", "density", "web_thickness"))
        if self.point_angle is not None and not 0 < self.point_angle <= math.pi:
            raise FieldProblem("point_angle", "must be above 0 and at most 180 deg (flat bottom)")
        if self.depth_resolution is not None and self.depth_resolution < 0:
            raise FieldProblem("depth_resolution", "must not be negative")
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
        return self


#: [correction] keys that belong to one method only
METHOD_KEYS: dict[str, tuple[str, ...]] = {
    "face": ("area", "orientation"),
    "holes": ("diameter", "number", "direction", "point_angle", "depth_to", "web_thickness"),
}


class Tolerance(_Strict):
    """``[tolerance]``: the permissible residual, given or from an ISO 21940-11 grade."""

    grade: str | None = None
    rotor_mass: Mass | None = None
    speed: Speed | None = None
    unbalance: Unbalance | None = None

    @model_validator(mode="after")
    def _check(self) -> Tolerance:
        _positive(self, ("rotor_mass", "speed", "unbalance"))
        if self.unbalance is not None:
            for key in ("grade", "rotor_mass", "speed"):
                if getattr(self, key) is not None:
                    raise FieldProblem(
                        key, "give tolerance.unbalance, or grade, rotor_mass and speed, not both"
                    )
        return self


class RebalanceFile(_Strict):
    """A whole rebalance parts file."""

    name: str | None = None
    crank_radius: Length | None = None
    targets: list[Target] | None = Field(default=None, min_length=1, max_length=50)
    counterweight: Counterweight | None = None
    old: Parts | None = None
    new: Parts | None = None
    correction: Correction | None = None
    tolerance: Tolerance | None = None

    @model_validator(mode="before")
    @classmethod
    def _one_target(cls, data: Any) -> Any:
        if isinstance(data, dict) and "targets" in data and not isinstance(data["targets"], list):
            return {**data, "targets": [data["targets"]]}
        return data

    @model_validator(mode="after")
    def _check(self) -> RebalanceFile:
        _positive(self, ("crank_radius",))
        return self


def rebalance_file_from_dict(data: Any, source: str = "parts") -> RebalanceFile:
    """Validate the contents of a rebalance parts file; :class:`InputError` names the key."""
    if not isinstance(data, dict):
        raise InputError(source, type(data).__name__, "must be a table of keys and values")
    try:
        return RebalanceFile.model_validate(data)
    except ValidationError as error:
        raise input_error(error, data, RebalanceFile, DOC, source) from None


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
