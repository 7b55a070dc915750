"""The engine description: pydantic models of the engine file (TOML/JSON), validated.

Quantities are strings with units (``"40 mm"``, ``"2000 rpm"``); they are parsed to SI
floats on validation and written back with a display unit by ``model_dump()``. Unknown
keys are errors. One model serves the engine file, the CLI and the web form.

See ``docs/engine_file.md`` for the format and the numbering conventions.
"""

from __future__ import annotations

import json
import math
import re
from functools import partial
from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    PlainSerializer,
    ValidationError,
    model_validator,
)

from ..errors import InputError
from ..physics.firing import SCHEMES
from ..units import RANGES, format_quantity, parse_quantity, range_si

Layout = Literal["inline", "vee", "boxer", "w", "radial", "vr", "custom"]
LAYOUTS: tuple[str, ...] = ("inline", "vee", "boxer", "w", "radial", "vr", "custom")
#: The two kinds of W engine: three banks on one pin each, or two VR banks (docs/engine_file.md).
W_TYPES: tuple[str, ...] = ("broad-arrow", "vr")
Kinematics = Literal["exact", "series", "first-order"]

# --------------------------------------------------------------------------- limits
# Bounds on the work an engine file can ask for (docs/engine_file.md, "Limits").
#: Most cylinders of an engine, any layout.
MAX_CYLINDERS = 64
#: Most crank throws of an engine (``throw_angles`` entries, ``[[crank_train.throw]]`` tables).
MAX_THROWS = 64
#: Most ``[[masses.override]]`` tables.
MAX_OVERRIDES = 2 * MAX_CYLINDERS
#: Longest quantity string, in characters.
MAX_QUANTITY_CHARS = 100
#: Longest ``name`` and ``description``, in characters.
MAX_NAME_CHARS = 200
MAX_DESCRIPTION_CHARS = 10_000


def parse_in_range(value: Any, kind: str, field: str = "") -> float:
    """A quantity string as an SI float, refused unless its size lies in the physical range
    of its kind (:data:`crankbalance.units.RANGES`) or it is zero; strings longer than
    :data:`MAX_QUANTITY_CHARS` are refused before parsing."""
    if isinstance(value, str) and len(value) > MAX_QUANTITY_CHARS:
        raise InputError(
            field, value, f"must be one number and a unit, at most {MAX_QUANTITY_CHARS} characters"
        )
    number = parse_quantity(value, kind, field)
    if kind in RANGES:
        low, high = range_si(kind)
        if abs(number) > high or 0 < abs(number) < low:
            words = RANGES[kind]
            size = " in size" if number < 0 else ""
            raise InputError(field, value, f"must lie between {words[0]} and {words[1]}{size}")
    return number


def _parser(kind: str) -> BeforeValidator:
    return BeforeValidator(partial(parse_in_range, kind=kind))


def _writer(kind: str) -> PlainSerializer:
    return PlainSerializer(partial(format_quantity, kind=kind), return_type=str, when_used="json")


# quantities: unit strings in the file, SI floats once validated
Length = Annotated[float, _parser("length"), _writer("length")]
Mass = Annotated[float, _parser("mass"), _writer("mass")]
Angle = Annotated[float, _parser("angle"), _writer("angle")]
Speed = Annotated[float, _parser("speed"), _writer("speed")]
Inertia = Annotated[float, _parser("inertia"), _writer("inertia")]


def _whole(value: Any) -> Any:
    """A count, an index or a 0/1 flag: an integer as written (no true/false, no "4")."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError("must be a whole number (not text, not true/false)")
    return value


def _finite(value: Any) -> Any:
    """A plain number as written (no true/false, no "0.5"), finite."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError("must be a number (not text, not true/false)")
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


Whole = Annotated[int, BeforeValidator(_whole)]
Fraction = Annotated[float, BeforeValidator(_finite)]


class FieldProblem(ValueError):
    """A validation failure of one named field inside a model validator (``field`` is
    relative to the model raising it, or dotted from the root when it contains a dot)."""

    def __init__(self, field: str, allowed: str) -> None:
        super().__init__(allowed)
        self.field = field
        self.allowed = allowed


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, strict=False)


# --------------------------------------------------------------------------- crank train
class Throw(_Strict):
    """One crank throw of a custom layout."""

    position: Length = Field(
        description="axial position of the throw mid-plane along the crank axis (any origin: "
        "positions are taken from the middle of the throws' extent)"
    )
    angle: Angle = Field(description="throw angle from the z axis, in the sense of rotation")
    banks: list[Angle] = Field(
        min_length=1,
        max_length=MAX_CYLINDERS,
        description="bank angle of each cylinder on this pin",
    )


class Articulated(_Strict):
    """Master-and-link rods of a radial engine (``[crank_train.articulated]``).

    The master rod is the conrod of the master cylinder (its length ``rod_length``); every
    other cylinder's rod is a link rod pinned to the master rod's big end. Rod masses are
    the ``[masses]`` conrod fields of each cylinder (overrides for the master or the links).
    """

    master_cylinder: Whole = Field(default=1, ge=1, description="cylinder of the master rod")
    link_pin_radius: Length = Field(
        description="distance of each link pin from the centre of the master rod's big end"
    )
    link_rod_length: Length = Field(description="centre distance of each link rod")
    link_pin_angles: list[Angle] | None = Field(
        default=None,
        max_length=MAX_CYLINDERS,
        description="angle of each cylinder's link pin from the master rod's axis, one per "
        "cylinder (the master's 0); default: the angle between the cylinder and the master",
    )

    @model_validator(mode="after")
    def _check(self) -> Articulated:
        if self.link_pin_radius < 0:
            raise FieldProblem("link_pin_radius", "must not be negative")
        if self.link_rod_length <= 0:
            raise FieldProblem("link_rod_length", "must be greater than zero")
        return self


class CrankTrain(_Strict):
    """Layout and geometry of the crank train."""

    layout: Layout
    cylinders: Whole | None = Field(default=None, ge=1, le=MAX_CYLINDERS)
    firing_order: list[Whole] | None = Field(default=None, max_length=MAX_CYLINDERS)
    strokes: Annotated[Literal[2, 4], BeforeValidator(_whole)] = 4
    crank_radius: Length
    rod_length: Length
    crank_pitch: Length | None = None
    bank_angle: Angle | None = None
    pin_offset: Length = 0.0
    crank_offset: Length = 0.0
    throw_angles: list[Angle] | None = Field(default=None, max_length=MAX_THROWS)
    throw: list[Throw] | None = Field(default=None, max_length=MAX_THROWS)
    articulated: Articulated | None = None
    w_type: Literal["broad-arrow", "vr"] | None = Field(
        default=None,
        description="layout w: 'broad-arrow' (three banks, default) or 'vr' (two VR banks)",
    )
    vr_angle: Angle | None = Field(
        default=None, description="W from VR banks: narrow angle between the rows of each bank"
    )
    bore_offset: Length = Field(
        default=0.0,
        description="VR rows: distance of each row's bore axes from the crank axis, positive "
        "when the rows' axes meet beyond the crank axis (away from the head)",
    )
    pin_split: Angle | None = Field(
        default=None,
        description="VR rows: angle between the crankpins of the two rows (default: the split "
        "even firing needs)",
    )
    bank_offsets: list[Length] | None = Field(
        default=None,
        max_length=3,
        description="bore offset of each bank (vee, boxer: 2 banks; W: 3), added to "
        "pin_offset + crank_offset for the cylinders of that bank",
    )
    cylinder_offsets: list[Length] | None = Field(
        default=None,
        max_length=MAX_CYLINDERS,
        description="bore offset of each cylinder, added to pin_offset + crank_offset",
    )
    rod_positions: list[Length] | None = Field(
        default=None,
        max_length=MAX_CYLINDERS,
        description="axial position of each cylinder's rod on its crankpin, from the "
        "throw's mid-plane (side-by-side rods)",
    )
    numbering: str | None = Field(
        default=None,
        max_length=40,
        description="the maker's cylinder numbering firing_order is written in: "
        + ", ".join(SCHEMES),
    )
    maker_numbers: list[Whole] | None = Field(
        default=None,
        max_length=MAX_CYLINDERS,
        description="crankbalance's number of each of the maker's cylinders 1, 2, ... "
        "(firing_order is then in the maker's numbers)",
    )
    moment_reference: Length = Field(
        default=0.0,
        description="point moments are taken about, along the crank axis from the crank's "
        "mid-point (the middle of the throws' extent)",
    )

    @model_validator(mode="after")
    def _check(self) -> CrankTrain:
        r, l = self.crank_radius, self.rod_length
        if r <= 0:
            raise FieldProblem("crank_radius", "must be greater than zero")
        self._check_vr()
        if l <= r + abs(self.pin_offset + self.crank_offset):
            raise FieldProblem(
                "rod_length",
                "must exceed crank_radius plus the total offset "
                f"(rod {l * 1e3:g} mm, crank radius {r * 1e3:g} mm)",
            )
        if self.layout == "custom":
            if not self.throw:
                raise FieldProblem(
                    "throw", "layout 'custom' needs its throws as [[crank_train.throw]] tables"
                )
            for key in ("throw_angles", "bank_angle"):
                if getattr(self, key) is not None:
                    raise FieldProblem(key, "is not used with layout 'custom' (give it per throw)")
            count = sum(len(t.banks) for t in self.throw)
            if count > MAX_CYLINDERS:
                raise FieldProblem(
                    "throw", f"the throws carry {count} cylinders; at most {MAX_CYLINDERS}"
                )
            if self.cylinders is not None and self.cylinders != count:
                raise FieldProblem("cylinders", f"the throws carry {count} cylinders")
        else:
            if self.throw is not None:
                raise FieldProblem("throw", "[[crank_train.throw]] tables need layout = 'custom'")
            if self.cylinders is None:
                raise FieldProblem("cylinders", f"is required for layout '{self.layout}'")
            n = self.cylinders
            if self.layout in ("vee", "boxer") and n % 2:
                raise FieldProblem(
                    "cylinders", f"a {self.layout} engine needs an even number of cylinders"
                )
            if self.layout == "w" and n % 3 and not self.has_vr_rows:
                raise FieldProblem(
                    "cylinders", "a W engine (three banks) needs a multiple of 3 cylinders"
                )
            if self.layout == "w" and self.has_vr_rows and (n % 2 or n < 4):
                raise FieldProblem(
                    "cylinders",
                    "a W engine from two VR banks needs an even number of cylinders, at least 4",
                )
            if self.layout == "vr" and n < 2:
                raise FieldProblem("cylinders", "a VR engine needs at least 2 cylinders")
            if self.layout == "radial" and n < 3:
                raise FieldProblem("cylinders", "a radial engine needs at least 3 cylinders")
            if self.layout in ("vee", "w", "vr"):
                if self.bank_angle is None:
                    raise FieldProblem("bank_angle", f"is required for layout '{self.layout}'")
                limit = 90.0 if self.layout == "w" and not self.has_vr_rows else 180.0
                if not 0 < math.degrees(self.bank_angle) < limit + 1e-9:
                    raise FieldProblem(
                        "bank_angle", f"must lie in (0, {limit:g}] deg for layout '{self.layout}'"
                    )
            elif self.bank_angle is not None:
                raise FieldProblem("bank_angle", f"is not used with layout '{self.layout}'")
            throws = throw_count(self.layout, n, self.w_type)
            if throws > 1 and self.crank_pitch is None:
                raise FieldProblem(
                    "crank_pitch", "is required for an engine with more than one throw"
                )
            if self.crank_pitch is not None and self.crank_pitch <= 0:
                raise FieldProblem("crank_pitch", "must be greater than zero")
            if self.throw_angles is not None and len(self.throw_angles) != throws:
                raise FieldProblem(
                    "throw_angles", f"needs one angle per throw; this engine has {throws} throws"
                )
        n_cyl = self.cylinder_count
        self._check_offsets(n_cyl)
        self._check_numbering(n_cyl)
        if self.firing_order is not None:
            if sorted(self.firing_order) != list(range(1, n_cyl + 1)):
                raise FieldProblem(
                    "firing_order", f"must be a permutation of 1..{n_cyl} (each cylinder once)"
                )
        return self

    def _check_offsets(self, n_cyl: int) -> None:
        """Per-bank and per-cylinder offsets and rod positions: one per bank or cylinder,
        and every cylinder's total offset short enough for its rod."""
        banks = BANKS.get(self.layout)
        if self.bank_offsets is not None:
            if self.has_vr_rows:
                raise FieldProblem(
                    "bank_offsets",
                    "is not used with VR rows: give bore_offset (the rows' offset) and, "
                    "cylinder by cylinder, cylinder_offsets",
                )
            if banks is None:
                raise FieldProblem(
                    "bank_offsets",
                    f"is for layouts with banks (vee, boxer, w), not '{self.layout}'; give "
                    "cylinder_offsets (one per cylinder) instead",
                )
            if len(self.bank_offsets) != banks:
                raise FieldProblem(
                    "bank_offsets", f"needs one offset per bank: {banks} for '{self.layout}'"
                )
            if self.cylinder_offsets is not None:
                raise FieldProblem(
                    "cylinder_offsets", "give either bank_offsets or cylinder_offsets, not both"
                )
        for key in ("cylinder_offsets", "rod_positions"):
            values = getattr(self, key)
            if values is not None and len(values) != n_cyl:
                raise FieldProblem(key, f"needs one length per cylinder: {n_cyl} for this engine")
        shared = self.pin_offset + self.crank_offset
        extra = list(self.cylinder_offsets or self.bank_offsets or [0.0])
        rows = (-self.bore_offset, self.bore_offset) if self.has_vr_rows else (0.0,)
        worst = max(abs(shared + e + b) for e in extra for b in rows)
        if self.rod_length <= self.crank_radius + worst:
            key = "cylinder_offsets" if self.cylinder_offsets else "bank_offsets"
            if not (self.cylinder_offsets or self.bank_offsets):
                key = "bore_offset"
            raise FieldProblem(
                key,
                f"the largest total offset ({worst * 1e3:g} mm, with pin_offset and "
                "crank_offset"
                + (" and the rows' bore_offset" if self.has_vr_rows else "")
                + ") leaves no rod: rod_length must exceed crank_radius plus it",
            )

    def _check_numbering(self, n_cyl: int) -> None:
        """``numbering`` names a scheme for this layout; ``maker_numbers`` is a map."""
        if self.numbering is not None:
            if self.maker_numbers is not None:
                raise FieldProblem(
                    "maker_numbers", "give either numbering (a named scheme) or maker_numbers"
                )
            scheme = SCHEMES.get(self.numbering)
            if scheme is None:
                raise FieldProblem("numbering", "must be one of " + ", ".join(SCHEMES))
            if scheme.layout != self.layout:
                raise FieldProblem(
                    "numbering",
                    f"'{self.numbering}' numbers a {scheme.layout} engine, not layout "
                    f"'{self.layout}'; give maker_numbers (crankbalance's number of each of "
                    "the maker's cylinders) instead",
                )
        if self.maker_numbers is not None and sorted(self.maker_numbers) != list(
            range(1, n_cyl + 1)
        ):
            raise FieldProblem(
                "maker_numbers",
                f"must give crankbalance's number of each of the maker's cylinders 1..{n_cyl}: "
                f"a permutation of 1..{n_cyl}",
            )

    def maker_map(self) -> tuple[int, ...] | None:
        """crankbalance's number of each of the maker's cylinders (entry k - 1 for the
        maker's k), or None when the engine file uses crankbalance's numbering."""
        if self.maker_numbers is not None:
            return tuple(int(c) for c in self.maker_numbers)
        if self.numbering is not None:
            return SCHEMES[self.numbering].to_crankbalance(self.cylinder_count)
        return None

    @property
    def has_vr_rows(self) -> bool:
        """True for layout "vr" and for a W from VR banks (``w_type = "vr"``)."""
        return self.layout == "vr" or (self.layout == "w" and self.w_type == "vr")

    def _check_vr(self) -> None:
        """The keys of VR rows (docs/engine_file.md, "VR and W from VR banks")."""
        if self.w_type is not None and self.layout != "w":
            raise FieldProblem("w_type", f"is only used with layout 'w' (not '{self.layout}')")
        is_w_vr = self.layout == "w" and self.w_type == "vr"
        if self.vr_angle is not None and not is_w_vr:
            raise FieldProblem(
                "vr_angle",
                "is only used with layout 'w' and w_type = 'vr' (a VR engine's narrow angle "
                "is its bank_angle)",
            )
        if is_w_vr:
            if self.vr_angle is None:
                raise FieldProblem("vr_angle", "is required for a W from VR banks (w_type = 'vr')")
            if not 0 < math.degrees(self.vr_angle) < 90.0 + 1e-9:
                raise FieldProblem("vr_angle", "must lie in (0, 90] deg")
        for key, given in (
            ("bore_offset", self.bore_offset != 0),
            ("pin_split", self.pin_split is not None),
        ):
            if given and not self.has_vr_rows:
                raise FieldProblem(
                    key, "is only used with layout 'vr' or layout 'w' with w_type = 'vr'"
                )
        if self.pin_split is not None and self.has_vr_rows:
            if self.throw_angles is not None:
                raise FieldProblem(
                    "pin_split", "give either pin_split or throw_angles (the whole crank), not both"
                )
            if not 0 <= math.degrees(self.pin_split) < 180.0:
                raise FieldProblem("pin_split", "must lie in [0, 180) deg")

    @property
    def cylinder_count(self) -> int:
        if self.layout == "custom":
            return sum(len(t.banks) for t in self.throw or [])
        assert self.cylinders is not None
        return self.cylinders


def _check_articulated(ct: CrankTrain) -> None:
    """The ``[crank_train.articulated]`` table against the rest of the crank train."""
    art = ct.articulated
    if art is None:
        return
    where = "crank_train.articulated"
    if ct.layout != "radial":
        raise FieldProblem(
            f"{where}.master_cylinder", "master-and-link rods need layout = 'radial'"
        )
    n = ct.cylinder_count
    if art.master_cylinder > n:
        raise FieldProblem(f"{where}.master_cylinder", f"must be a cylinder number 1..{n}")
    shared = ct.pin_offset + ct.crank_offset
    offset = max(abs(shared + extra) for extra in (ct.cylinder_offsets or [0.0]))
    need = ct.crank_radius + art.link_pin_radius + offset
    if art.link_rod_length <= need:
        raise FieldProblem(
            f"{where}.link_rod_length",
            "must exceed crank_radius plus link_pin_radius plus the largest total offset "
            f"({need * 1e3:g} mm)",
        )
    if art.link_pin_angles is not None:
        if len(art.link_pin_angles) != n:
            raise FieldProblem(
                f"{where}.link_pin_angles",
                f"needs one angle per cylinder ({n}), 0 for the master cylinder",
            )
        if art.link_pin_angles[art.master_cylinder - 1] != 0:
            raise FieldProblem(
                f"{where}.link_pin_angles",
                f"entry {art.master_cylinder} is the master cylinder's: it must be 0 deg",
            )


#: Number of banks of the layouts that take ``bank_offsets`` (docs/engine_file.md).
BANKS: dict[str, int] = {"vee": 2, "boxer": 2, "w": 3}


def throw_count(layout: str, cylinders: int, w_type: str | None = None) -> int:
    """Number of crank throws of a standard layout (``w_type`` "vr": a W from VR banks,
    one throw per cylinder)."""
    if layout == "w" and w_type == "vr":
        return cylinders
    return {
        "inline": cylinders,
        "boxer": cylinders,
        "vee": cylinders // 2,
        "w": cylinders // 3,
        "radial": 1,
    }.get(layout, cylinders)


# --------------------------------------------------------------------------- masses
_CYLINDER_FIELDS = (
    "piston",
    "wrist_pin",
    "conrod",
    "conrod_rotating_fraction",
    "conrod_cg_from_big_end",
    "conrod_inertia",
    "reciprocating",
)
_THROW_FIELDS = ("crankpin", "crank_web", "crank_web_cg_radius", "rotating")


class _MassFields(_Strict):
    piston: Mass | None = Field(default=None, description="piston with rings and clips")
    wrist_pin: Mass | None = None
    conrod: Mass | None = None
    conrod_rotating_fraction: Fraction | None = Field(default=None, ge=0.0, le=1.0)
    conrod_cg_from_big_end: Length | None = None
    conrod_inertia: Inertia | None = Field(default=None, description="conrod inertia about its CG")
    crankpin: Mass | None = None
    crank_web: Mass | None = Field(default=None, description="each of the two webs of a throw")
    crank_web_cg_radius: Length | None = None
    reciprocating: Mass | None = Field(default=None, description="total per cylinder")
    rotating: Mass | None = Field(default=None, description="total per throw, big ends included")

    @model_validator(mode="after")
    def _check_values(self) -> _MassFields:
        for name in (
            "piston",
            "wrist_pin",
            "conrod",
            "crankpin",
            "crank_web",
            "reciprocating",
            "rotating",
            "conrod_inertia",
        ):
            value = getattr(self, name)
            if value is not None and value < 0:
                raise FieldProblem(name, "must not be negative")
        if self.conrod is not None and self.conrod <= 0:
            raise FieldProblem("conrod", "must be greater than zero")
        if self.conrod_rotating_fraction is not None and self.conrod_cg_from_big_end is not None:
            raise FieldProblem(
                "conrod_cg_from_big_end",
                "give conrod_rotating_fraction or conrod_cg_from_big_end, not both",
            )
        if self.conrod_cg_from_big_end is not None and self.conrod_cg_from_big_end < 0:
            raise FieldProblem("conrod_cg_from_big_end", "must not be negative")
        if self.crank_web_cg_radius is not None and self.crank_web_cg_radius < 0:
            raise FieldProblem("crank_web_cg_radius", "must not be negative")
        return self


class MassOverride(_MassFields):
    """Masses that differ for some cylinders (per-cylinder fields) or throws (per-throw fields)."""

    cylinders: list[Whole] | None = Field(default=None, max_length=MAX_CYLINDERS)
    throws: list[Whole] | None = Field(default=None, max_length=MAX_THROWS)

    @model_validator(mode="after")
    def _check_target(self) -> MassOverride:
        given = {k for k in _CYLINDER_FIELDS + _THROW_FIELDS if getattr(self, k) is not None}
        if self.cylinders is None and self.throws is None:
            raise FieldProblem(
                "cylinders", "an override needs `cylinders = [...]` or `throws = [...]`"
            )
        if self.cylinders is not None and self.throws is not None:
            raise FieldProblem(
                "throws", "an override takes either `cylinders` or `throws`, not both"
            )
        if self.cylinders is not None and given & set(_THROW_FIELDS):
            bad = sorted(given & set(_THROW_FIELDS))
            raise FieldProblem(bad[0], "is a per-throw mass: override it with `throws = [...]`")
        if self.throws is not None and given & set(_CYLINDER_FIELDS):
            bad = sorted(given & set(_CYLINDER_FIELDS))
            raise FieldProblem(
                bad[0], "is a per-cylinder mass: override it with `cylinders = [...]`"
            )
        if not given:
            raise FieldProblem("cylinders", "an override must change at least one mass")
        return self


class Masses(_MassFields):
    """Masses per cylinder (reciprocating side) and per throw (rotating side).

    Either parts (piston, wrist_pin, conrod with its split; crankpin, crank_web with its
    CG radius) or totals (``reciprocating`` per cylinder, ``rotating`` per throw).
    """

    override: list[MassOverride] = Field(default_factory=list, max_length=MAX_OVERRIDES)

    @model_validator(mode="after")
    def _check_complete(self) -> Masses:
        parts_rec = ("piston", "wrist_pin", "conrod")
        if self.reciprocating is None:
            missing = [k for k in parts_rec if getattr(self, k) is None]
            if missing:
                raise FieldProblem(
                    missing[0],
                    "is required: give the parts (piston, wrist_pin, conrod) "
                    "or the total `reciprocating`",
                )
        elif any(getattr(self, k) is not None for k in ("piston", "wrist_pin")):
            raise FieldProblem(
                "reciprocating",
                "give either `reciprocating` or the parts piston/wrist_pin, not both",
            )
        if self.conrod is not None and (
            self.conrod_rotating_fraction is None and self.conrod_cg_from_big_end is None
        ):
            raise FieldProblem(
                "conrod", "needs its split: conrod_rotating_fraction or conrod_cg_from_big_end"
            )
        if self.rotating is None:
            missing = [k for k in ("crankpin",) if getattr(self, k) is None]
            if self.crank_web is not None and self.crank_web_cg_radius is None:
                missing.append("crank_web_cg_radius")
            if missing:
                raise FieldProblem(
                    missing[0],
                    "is required: give the parts (crankpin, crank_web, "
                    "crank_web_cg_radius) or the total `rotating`",
                )
            if self.conrod is None:
                raise FieldProblem(
                    "conrod", "is required with the rotating parts (its big end turns with the pin)"
                )
        elif any(getattr(self, k) is not None for k in ("crankpin", "crank_web")):
            raise FieldProblem(
                "rotating", "give either `rotating` or the parts crankpin/crank_web, not both"
            )
        return self


# --------------------------------------------------------------------------- balancing options
class Counterweights(_Strict):
    """Crankshaft counterweights (2021 paper, section 3.1)."""

    webs: list[Annotated[Literal[0, 1], BeforeValidator(_whole)]] | None = Field(
        default=None,
        max_length=2 * MAX_THROWS,
        description="two webs per throw, 1 = carries a counterweight (default all)",
    )
    cg_radius: Length
    angle: Angle | Literal["optimal"] = 0.0
    balance_factor: Fraction = Field(default=0.0, ge=0.0, le=2.0)
    scope: Literal["auto", "whole", "halves"] = "auto"
    method: Literal["pattern", "individual"] = "pattern"
    web_offset: Length | None = Field(
        default=None,
        description="axial distance of each web from its throw mid-plane "
        "(default: a quarter of the crank pitch, as the 2021 paper)",
    )

    @model_validator(mode="after")
    def _check(self) -> Counterweights:
        if self.cg_radius <= 0:
            raise FieldProblem("cg_radius", "must be greater than zero")
        if self.webs is not None and not any(self.webs):
            raise FieldProblem("webs", "has no counterweight (all zeros)")
        if self.web_offset is not None and self.web_offset < 0:
            raise FieldProblem("web_offset", "must not be negative")
        return self


class ShaftSet(_Strict):
    """A set of balance shafts for one order."""

    arrangement: Literal["pair", "counter-rotating"] = "pair"
    cg_radius: Length
    length: Length

    @model_validator(mode="after")
    def _check(self) -> ShaftSet:
        if self.cg_radius <= 0:
            raise FieldProblem("cg_radius", "must be greater than zero")
        if self.length <= 0:
            raise FieldProblem("length", "must be greater than zero")
        return self


class BalanceShafts(_Strict):
    primary: ShaftSet | None = None
    secondary: ShaftSet | None = None


class EngineSpec(_Strict):
    """A whole engine: the contents of one engine file."""

    name: str = Field(default="engine", max_length=MAX_NAME_CHARS)
    description: str = Field(default="", max_length=MAX_DESCRIPTION_CHARS)
    speed: Speed
    kinematics: Kinematics = "exact"
    crank_train: CrankTrain
    masses: Masses
    counterweights: Counterweights | None = None
    balance_shafts: BalanceShafts | None = None

    @model_validator(mode="after")
    def _check(self) -> EngineSpec:
        if self.speed <= 0:
            raise FieldProblem("speed", "must be greater than zero")
        ct = self.crank_train
        n_cyl = ct.cylinder_count
        n_throw = len(ct.throw) if ct.throw else throw_count(ct.layout, n_cyl, ct.w_type)
        for k, item in enumerate(self.masses.override):
            for number in item.cylinders or []:
                if not 1 <= number <= n_cyl:
                    raise FieldProblem(
                        f"masses.override[{k}].cylinders",
                        f"cylinder {number} does not exist (1..{n_cyl})",
                    )
            for number in item.throws or []:
                if not 1 <= number <= n_throw:
                    raise FieldProblem(
                        f"masses.override[{k}].throws",
                        f"throw {number} does not exist (1..{n_throw})",
                    )
        _check_override_overlap(self.masses.override)
        _check_articulated_engine(self)
        if self.counterweights is not None and self.counterweights.webs is not None:
            if len(self.counterweights.webs) != 2 * n_throw:
                raise FieldProblem(
                    "counterweights.webs",
                    f"needs one entry per web: {2 * n_throw} for {n_throw} throws",
                )
        return self

    def to_file_dict(self) -> dict[str, Any]:
        """The spec as an engine-file dictionary (quantities as unit strings)."""
        return self.model_dump(mode="json", exclude_none=True, exclude_defaults=True)


#: override fields that give one quantity two ways (the later table would replace the
#: earlier's, build.py): the conrod's split
_SAME_QUANTITY = {"conrod_cg_from_big_end": "conrod_rotating_fraction"}


def _check_override_overlap(overrides: list[MassOverride]) -> None:
    """Refuse two ``[[masses.override]]`` tables that give one cylinder (or throw) the same
    mass, which the later would replace without a word, and a number listed twice in one
    table (docs/engine_file.md, "Overrides")."""
    first: dict[tuple[str, int, str], int] = {}
    for k, item in enumerate(overrides):
        target = "cylinders" if item.cylinders is not None else "throws"
        numbers = item.cylinders if item.cylinders is not None else item.throws or []
        word = target[:-1]
        if len(set(numbers)) < len(numbers):
            twice = next(n for n in numbers if numbers.count(n) > 1)
            raise FieldProblem(
                f"masses.override[{k}].{target}", f"lists {word} {twice} twice; give it once"
            )
        given = [
            name for name in _CYLINDER_FIELDS + _THROW_FIELDS if getattr(item, name) is not None
        ]
        for number in numbers:
            for name in given:
                key = (target, number, _SAME_QUANTITY.get(name, name))
                if key in first:
                    raise FieldProblem(
                        f"masses.override[{k}].{target}",
                        f"masses.override[{first[key]}] and masses.override[{k}] both give "
                        f"{word} {number} its {name} (the later would replace the "
                        "earlier's without a word); give it once",
                    )
                first[key] = k


def _check_articulated_engine(spec: EngineSpec) -> None:
    """What master-and-link rods need beyond the crank train: exact kinematics and the
    rod masses (the link rods' big ends move with the link pins, not with the crankpin)."""
    if spec.crank_train.articulated is None:
        return
    _check_articulated(spec.crank_train)
    if spec.kinematics != "exact":
        raise FieldProblem(
            "kinematics", "master-and-link rods (crank_train.articulated) need 'exact'"
        )
    if spec.masses.conrod is None:
        raise FieldProblem(
            "masses.conrod",
            "is required with crank_train.articulated: give the rod masses with their split "
            "(the master rod's by an override of the master cylinder, or the link rods')",
        )


# --------------------------------------------------------------------------- errors
def spec_from_dict(data: Any) -> EngineSpec:
    """Validate an engine-file dictionary; raise :class:`InputError` on the first problem."""
    if not isinstance(data, dict):
        raise InputError("engine file", type(data).__name__, "must be a table of keys and values")
    try:
        return EngineSpec.model_validate(data)
    except ValidationError as error:
        raise input_error(error, data) from None


def input_error(
    error: ValidationError,
    data: Any,
    root: type[BaseModel] | None = None,
    doc: str = "docs/engine_file.md",
    source: str = "engine file",
) -> InputError:
    """The first problem of a pydantic validation of ``data`` against ``root`` (default
    :class:`EngineSpec`) as an :class:`InputError` naming the dotted key as written in the
    file, the value and what is allowed; ``doc`` is where the format is described."""
    first = error.errors(include_url=False)[0]
    loc = list(first["loc"])
    kind = first["type"]
    value = first.get("input")
    ctx = first.get("ctx") or {}
    inner = ctx.get("error")
    if isinstance(inner, FieldProblem):
        path = inner.field.split(".") if "." in inner.field and not loc else loc + [inner.field]
        return InputError(_dotted(path), _lookup(data, path), inner.allowed)
    field = _dotted(loc) or source
    if kind == "extra_forbidden":
        parent = _model_at([str(p) for p in loc[:-1]], root or EngineSpec)
        allowed = ", ".join(parent.model_fields) if parent is not None else f"see {doc}"
        return InputError(field, value, f"unknown key; allowed keys here: {allowed}")
    if kind == "missing":
        return InputError(field, None, f"is missing; it is required (see {doc})")
    if isinstance(inner, InputError):
        return InputError(field, inner.value, inner.allowed)
    if kind == "too_long":
        return InputError(
            field,
            f"{ctx.get('actual_length')} entries",
            f"takes at most {ctx.get('max_length')} entries (see {doc})",
        )
    if kind == "string_too_long":
        return InputError(
            field, f"{len(value)} characters", f"takes at most {ctx.get('max_length')} characters"
        )
    if kind in ("literal_error", "enum"):
        return InputError(field, value, f"must be one of {ctx.get('expected', '')}")
    message = str(first.get("msg", ""))
    if message.startswith("Value error, "):
        message = message[len("Value error, ") :]
    return InputError(field, _short_value(value), message)


def _lookup(data: Any, path: list[Any]) -> Any:
    for part in path:
        if isinstance(data, dict) and part in data:
            data = data[part]
        elif isinstance(data, list) and isinstance(part, int) and part < len(data):
            data = data[part]
        else:
            return None
    return _short_value(data)


def _dotted(loc: Any) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif isinstance(part, str) and part.startswith(("function-", "union[", "literal[")):
            continue
        else:
            out += ("." if out else "") + _key_text(str(part))
    return out


def _key_text(key: str) -> str:
    """A key as written in TOML: bare when it can be, else quoted with escapes (a key in a
    message never carries a line break or a control character into the terminal)."""
    return key if re.fullmatch(r"[A-Za-z0-9_-]+(\[\d+\])*", key) else json.dumps(key)


def _short_value(value: Any) -> Any:
    if isinstance(value, dict):
        return "{...}"
    return value


def _model_at(loc: list[str], root: type[BaseModel]) -> type[BaseModel] | None:
    model: Any = root
    for part in loc:
        if part.isdigit():
            continue
        field = model.model_fields.get(part) if hasattr(model, "model_fields") else None
        if field is None:
            return None
        model = _inner_model(field.annotation)
        if model is None:
            return None
    return model if isinstance(model, type) and issubclass(model, BaseModel) else None


def _inner_model(annotation: Any) -> Any:
    import typing

    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = _inner_model(arg)
        if found is not None:
            return found
    return None
