"""The engine description: the schema of the engine file (TOML/JSON), validated.

Quantities are strings with units (``"40 mm"``, ``"2000 rpm"``); they are parsed to SI
floats on validation and written back with a display unit by :meth:`Schema.to_data`.
Unknown keys are errors, named with the closest allowed key. One schema serves the engine
file, the CLI, the web form and the API; ``docs/engine_file.md``'s reference tables and
``docs/engine.schema.json`` are written from it (:mod:`crankbalance.schema.document`).
Besides the rules that make an engine valid, :meth:`EngineSpec.plausibility` says, as
notes and not as errors, where a valid engine's numbers are unusual.

See ``docs/engine_file.md`` for the format and the numbering conventions. The module is
over 800 lines because every key carries its title and description here, once, for the
documentation, the JSON Schema and the forms, beside the rules that check it.
"""

from __future__ import annotations

import math
from typing import Any, Literal, NamedTuple

from ..errors import InputError
from .core import (
    MAX_VALUE_CHARS,
    REQUIRED,
    FieldProblem,
    Schema,
    closest,
    entry,
    field,
    parse_in_range,
    three_lengths,
)

__all__ = [
    "BANKS",
    "LAYOUTS",
    "MAX_CYLINDERS",
    "MAX_DESCRIPTION_CHARS",
    "MAX_NAME_CHARS",
    "MAX_OVERRIDES",
    "MAX_PISTON_SPEED",
    "MAX_QUANTITY_CHARS",
    "MAX_THROWS",
    "ROD_RATIO",
    "W_TYPES",
    "Articulated",
    "BalanceShafts",
    "Counterweights",
    "CrankTrain",
    "EngineSpec",
    "FieldProblem",
    "MassOverride",
    "Masses",
    "Mount",
    "Note",
    "Powertrain",
    "ShaftSet",
    "Throw",
    "parse_in_range",
    "spec_from_dict",
    "throw_count",
]

LAYOUTS: tuple[str, ...] = ("inline", "vee", "boxer", "w", "radial", "vr", "custom")
#: The two kinds of W engine: three banks on one pin each, or two VR banks (docs/engine_file.md).
W_TYPES: tuple[str, ...] = ("broad-arrow", "vr")
KINEMATICS: tuple[str, ...] = ("exact", "series", "first-order")

# --------------------------------------------------------------------------- limits
# Bounds on the work an engine file can ask for (docs/engine_file.md, "Limits").
#: Most cylinders of an engine, any layout.
MAX_CYLINDERS = 64
#: Most crank throws of an engine (``throw_angles`` entries, ``[[crank_train.throw]]`` tables).
MAX_THROWS = 64
#: Most ``[[masses.override]]`` tables.
MAX_OVERRIDES = 2 * MAX_CYLINDERS
#: Longest quantity string, in characters.
MAX_QUANTITY_CHARS = MAX_VALUE_CHARS
#: Longest ``name`` and ``description``, in characters.
MAX_NAME_CHARS = 200
MAX_DESCRIPTION_CHARS = 10_000
#: Longest ``numbering`` (the name of a maker's numbering scheme), in characters.
MAX_NUMBERING_CHARS = 40

# --------------------------------------------------------------------------- plausibility
#: highest plausible mean piston speed [m/s] (racing engines reach about 25 m/s)
MAX_PISTON_SPEED = 30.0
#: usual range of the rod length in crank radii (rod ratio l/r)
ROD_RATIO = (2.8, 4.5)


class Note(NamedTuple):
    """A plausibility note about a valid engine: the engine-file key it concerns (dotted,
    ``crank_train.rod_length``) and what is unusual."""

    field: str
    text: str


def _angle_or_optimal(value: Any, where: str) -> Any:
    """``"optimal"`` or an angle with a unit in the physical range of an angle."""
    if value == "optimal":
        return value
    try:
        return parse_in_range(value, "angle", where)
    except InputError:
        if isinstance(value, str) and not any(c.isdigit() for c in value):
            close = closest(value.strip().lower(), ["optimal"])
            hint = "; did you mean 'optimal'?" if close else ""
            raise InputError(where, value, f"must be 'optimal' or {ANGLE_WORDS}{hint}") from None
        raise


ANGLE_WORDS = "an angle with a unit, e.g. '30 deg'"


class _EngineTable(Schema):
    """A table of the engine file (named in the "is missing" messages)."""

    DOC = "docs/engine_file.md"


# --------------------------------------------------------------------------- crank train
class Throw(_EngineTable):
    """One crank throw of a custom layout (``[[crank_train.throw]]``)."""

    position: float = field(
        "length",
        zero=True,
        title="Throw position",
        description="Axial position of the throw's mid-plane, from any origin: the positions are "
        "re-centred on the middle of the throws' extent.",
    )
    angle: float = field(
        "angle",
        zero=True,
        title="Throw angle",
        description="Angle of the throw from the z axis, in the sense of rotation.",
    )
    banks: list[float] = field(
        "list",
        item=entry("angle", zero=True),
        min_items=1,
        max_items=MAX_CYLINDERS,
        title="Bank angles",
        description="One bank angle per cylinder on the pin; the cylinders are numbered throw after"
        " throw, in this order.",
    )


class Articulated(_EngineTable):
    """Master-and-link rods of a radial engine (``[crank_train.articulated]``).

    The master rod is the conrod of the master cylinder (its length ``rod_length``); every
    other cylinder's rod is a link rod pinned to the master rod's big end. Rod masses are
    the ``[masses]`` conrod fields of each cylinder (overrides for the master or the links).
    """

    master_cylinder: int = field(
        "whole",
        default=1,
        ge=1,
        title="Master cylinder",
        hint="master-and-link rods (empty: 1)",
        description="Number of the cylinder the master rod drives; its rod is "
        "crank_train.rod_length.",
    )
    link_pin_radius: float = field(
        "length",
        ge=0,
        title="Link-pin radius",
        hint="link pins from the master's big-end centre, e.g. 56 mm (empty with the link rod "
        "length: each rod on the pin)",
        description="Distance of every link (knuckle) pin from the centre of the master rod's big "
        "end (0 gives the simple model).",
    )
    link_rod_length: float = field(
        "length",
        gt=0,
        title="Link-rod length",
        hint="centre distance of each link rod, e.g. 198 mm",
        description="Centre distance of every link rod, link pin to wrist pin; longer than crank "
        "radius plus link pin radius plus offset.",
    )
    link_pin_angles: list[float] | None = field(
        "list",
        default=None,
        item=entry("angle", zero=True),
        max_items=MAX_CYLINDERS,
        title="Link-pin angles",
        hint="one per cylinder from the master rod's axis, the master's 0 deg (empty: each "
        "cylinder's angle from the master)",
        description="One angle per cylinder (the master's 0 deg): the angle of that cylinder's link"
        " pin from the master rod's axis, in the sense of rotation; default the angle "
        "between the cylinder and the master cylinder, (k − m)·360°/n.",
    )


class CrankTrain(_EngineTable):
    """Layout and geometry of the crank train (``[crank_train]``)."""

    layout: str = field(
        "choice",
        choices=LAYOUTS,
        title="Layout",
        description="How the cylinders stand around the crank: inline, vee, boxer, w "
        "(broad-arrow or from two VR banks), radial, vr, or custom (throws given one by one "
        "as [[crank_train.throw]]).",
    )
    cylinders: int | None = field(
        "whole",
        default=None,
        ge=1,
        le=MAX_CYLINDERS,
        title="Cylinders",
        description="Number of cylinders (vee and boxer: even; broad-arrow W: a multiple of "
        "3; W from VR banks: even, at least 4; VR: at least 2; radial: at least 3); layout "
        "custom counts the banks of its throws.",
    )
    firing_order: list[int] | None = field(
        "list",
        default=None,
        item=entry("whole"),
        max_items=MAX_CYLINDERS,
        title="Firing order",
        description="A permutation of 1..n, in crankbalance's numbering or, with numbering or "
        "maker_numbers, in the maker's; default 1, 2, ..., n.",
        hint="e.g. 1, 3, 2 (empty: cylinder order)",
    )
    strokes: int = field(
        "choice",
        default=4,
        choices=(2, 4),
        title="Strokes per cycle",
        description="2 or 4: sets the even firing interval 360°·(strokes/2)/n.",
    )
    crank_radius: float = field(
        "length",
        gt=0,
        title="Crank radius",
        description="Throw radius, half the stroke.",
        hint="e.g. 40 mm",
    )
    rod_length: float = field(
        "length",
        gt=0,
        title="Rod length",
        description="Conrod length, centre to centre; the rod must be longer than the crank radius "
        "plus every cylinder's total offset.",
        hint="e.g. 135 mm",
    )
    crank_pitch: float | None = field(
        "length",
        default=None,
        gt=0,
        title="Crank pitch",
        description="Distance between consecutive throw mid-planes (required with more than one "
        "throw).",
        hint="e.g. 90 mm",
    )
    bank_angle: float | None = field(
        "angle",
        default=None,
        zero=True,
        title="Bank angle",
        description="vee: angle between the two banks, (0, 180°]; broad-arrow W: angle between "
        "adjacent banks, (0, 90°]; W from VR banks: angle between the two VR banks' "
        "centre lines, (0, 180°]; VR: the narrow angle between its two rows, (0, 180°].",
        hint="vee / W / VR only, e.g. 90 deg",
    )
    pin_offset: float = field(
        "length",
        default=0.0,
        zero=True,
        title="Wrist-pin offset",
        description="Wrist-pin offset (desaxé), the same for every cylinder.",
        hint="e.g. 0 mm",
    )
    crank_offset: float = field(
        "length",
        default=0.0,
        zero=True,
        title="Crank offset",
        description="Crank offset (desaxé), the same for every cylinder, added to pin_offset.",
    )
    throw_angles: list[float] | None = field(
        "list",
        default=None,
        item=entry("angle", zero=True),
        max_items=MAX_THROWS,
        title="Throw angles",
        description="One angle per throw: the crank given directly (needed for uneven-firing "
        "engines); default: from the firing order with even intervals.",
    )
    throw: list[Throw] | None = field(
        "list",
        default=None,
        item=entry("table", table=Throw),
        max_items=MAX_THROWS,
        title="Custom throws",
        description="Custom layout only: the throws, in order (a [[crank_train.throw]] "
        "table each).",
    )
    articulated: Articulated | None = field(
        "table",
        default=None,
        table=Articulated,
        title="Master-and-link rods",
        description="Radial only: master-and-link rods (see Articulated rods).",
    )
    w_type: str | None = field(
        "choice",
        default=None,
        choices=W_TYPES,
        title="Kind of W",
        hint="broad-arrow: three banks on each pin; vr: two VR banks (empty: broad-arrow)",
        description="Layout w only: broad-arrow (three banks, the default) or vr (two VR banks, "
        "VW's W8/W12/W16).",
    )
    vr_angle: float | None = field(
        "angle",
        default=None,
        zero=True,
        title="VR angle",
        hint="narrow angle between the rows of each VR bank, e.g. 15 deg",
        description="W from VR banks only (required there): the narrow angle between the two rows "
        "of each VR bank, (0, 90°].",
    )
    bore_offset: float = field(
        "length",
        default=0.0,
        zero=True,
        title="Rows' bore offset",
        hint="each row's bore axes from the crank axis, e.g. 12.5 mm (empty: 0 mm)",
        description="VR and W from VR banks only: distance of each row's bore axes from the crank "
        "axis, positive when the two rows' axes meet beyond the crank axis (away from "
        "the head), as in every VR.",
    )
    pin_split: float | None = field(
        "angle",
        default=None,
        zero=True,
        title="Pin split",
        hint="VR: angle between the two rows' crankpins, e.g. 22 deg (empty: even firing); "
        "vee: angle by which bank A's pin leads bank B's, e.g. 60 deg for a V6 60° "
        "(empty: one shared pin)",
        description="VR and W from VR banks: angle between the two rows' crankpins as the "
        "maker gives it, [0, 180°); default: the split even firing needs. vee: each throw "
        "split into two crankpins, one per bank, bank A's pin leading bank B's by this angle "
        "in the direction of rotation, (-180°, 180°]; each pin is a throw of its own, centred "
        "under its rod (rod_positions give the pins' axial places); even firing, bank B's "
        "cylinder of each throw firing one interval after bank A's, needs the firing interval "
        "minus bank_angle (V6 60°: 60°, V6 90°: 30°); default: one shared pin per throw.",
    )
    bank_offsets: list[float] | None = field(
        "list",
        default=None,
        item=entry("length", zero=True),
        max_items=3,
        title="Bank offsets",
        hint="one per bank (vee, boxer: 2; W: 3), e.g. 0 mm, 5 mm",
        description="vee, boxer (2 banks) and W (3 banks) only: the bore offset of each bank, one "
        "length per bank, added to pin_offset + crank_offset for the cylinders of that "
        "bank (banks as numbered below; not with VR rows, which take bore_offset).",
    )
    cylinder_offsets: list[float] | None = field(
        "list",
        default=None,
        item=entry("length", zero=True),
        max_items=MAX_CYLINDERS,
        title="Cylinder offsets",
        hint="one per cylinder, e.g. 0 mm, 2 mm, 0 mm (not with the offsets per bank)",
        description="Any layout: the bore offset of each cylinder, one length per cylinder, added "
        "to pin_offset + crank_offset (not together with bank_offsets).",
    )
    rod_positions: list[float] | None = field(
        "list",
        default=None,
        item=entry("length", zero=True),
        max_items=MAX_CYLINDERS,
        title="Rod positions on the pin",
        description="Any layout: the axial place of each cylinder's rod on its crankpin, from the "
        "throw's mid-plane along +y, one length per cylinder (side-by-side rods on a "
        "shared pin; a single rod off its throw's centre); default all 0 "
        "(knife-and-fork or master rods: all in the mid-plane); a vee with pin_split centres "
        "each rod's own pin there.",
        hint="one per cylinder from the throw's mid-plane, e.g. -10 mm, 10 mm "
        "(side-by-side rods; empty: all 0)",
    )
    numbering: str | None = field(
        "text",
        default=None,
        max_chars=MAX_NUMBERING_CHARS,
        title="Maker's numbering",
        hint="the firing order is then written in the maker's cylinder numbers (e.g. "
        "porsche-boxer: 1, 6, 2, 4, 3, 5; empty: crankbalance's numbering)",
        description="The maker's numbering firing_order is written in: porsche-boxer, gm-vee or "
        "ford-vee (see Makers' numbering).",
        words="the name of a numbering scheme: porsche-boxer, gm-vee or ford-vee",
    )
    maker_numbers: list[int] | None = field(
        "list",
        default=None,
        item=entry("whole"),
        max_items=MAX_CYLINDERS,
        title="Maker's cylinder numbers",
        hint="crankbalance's number of each of the maker's cylinders, e.g. 5, 1, 6, 2, 7, 3, "
        "8, 4; the firing order is then in the maker's numbers (empty: none)",
        description="Any layout, instead of numbering: crankbalance's number of each of the maker's"
        " cylinders 1, 2, ..., n (a permutation of 1..n).",
    )
    moment_reference: float = field(
        "length",
        default=0.0,
        zero=True,
        title="Moment reference",
        hint="point moments are taken about, from the crank's mid-point (empty: 0 mm)",
        description="The point moments are taken about, along +y from the crank's mid-point (e.g. "
        "the engine's centre of mass or mount centre), on the crank axis; a point off the "
        "axis is moment_point.",
    )
    moment_point: list[float] | None = three_lengths(
        "Moment point",
        "The point moments (the roll moment about y included) are taken about, x, y, z: y "
        "along +y from the crank's mid-point, x across, z along the cylinder axis of an "
        "in-line engine (e.g. a mount centre or the engine's centre of mass); not together "
        "with moment_reference, which is the point (0, moment_reference, 0).",
    )

    def check(self) -> None:
        r, l = self.crank_radius, self.rod_length
        self._check_vr()
        if self.moment_point is not None and self.moment_reference != 0.0:
            raise FieldProblem(
                "moment_point",
                "give either moment_point (x, y, z) or moment_reference (y), not both",
            )
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
            for key in ("throw_angles", "bank_angle", "crank_pitch"):
                if getattr(self, key) is not None:
                    raise FieldProblem(
                        key, "is not used with layout 'custom' (each throw gives its own)"
                    )
            count = sum(len(t.banks) for t in self.throw)
            if count > MAX_CYLINDERS:
                raise FieldProblem(
                    "throw", f"the throws carry {count} cylinders; at most {MAX_CYLINDERS}"
                )
            if self.cylinders is not None and self.cylinders != count:
                raise FieldProblem("cylinders", f"the throws carry {count} cylinders")
        else:
            self._check_standard()
        n_cyl = self.cylinder_count
        self._check_offsets(n_cyl)
        self._check_numbering(n_cyl)
        if self.firing_order is not None:
            if sorted(self.firing_order) != list(range(1, n_cyl + 1)):
                raise FieldProblem(
                    "firing_order", f"must be a permutation of 1..{n_cyl} (each cylinder once)"
                )

    def _check_standard(self) -> None:
        """The cylinders, bank angle, pitch and throw angles of a standard layout."""
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
            raise FieldProblem("crank_pitch", "is required for an engine with more than one throw")
        if self.throw_angles is not None and len(self.throw_angles) != throws:
            raise FieldProblem(
                "throw_angles", f"needs one angle per throw; this engine has {throws} throws"
            )

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
            from ..physics.firing import SCHEMES

            if self.maker_numbers is not None:
                raise FieldProblem(
                    "maker_numbers", "give either numbering (a named scheme) or maker_numbers"
                )
            scheme = SCHEMES.get(self.numbering)
            if scheme is None:
                close = closest(self.numbering, list(SCHEMES))
                hint = f"; did you mean '{close}'?" if close else ""
                raise FieldProblem("numbering", "must be one of " + ", ".join(SCHEMES) + hint)
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
            from ..physics.firing import SCHEMES

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
        if self.bore_offset != 0 and not self.has_vr_rows:
            raise FieldProblem(
                "bore_offset", "is only used with layout 'vr' or layout 'w' with w_type = 'vr'"
            )
        if self.pin_split is None:
            return
        if not (self.has_vr_rows or self.layout == "vee"):
            raise FieldProblem(
                "pin_split",
                f"is only used with layout 'vee', 'vr' or 'w' with w_type = 'vr' (not "
                f"'{self.layout}'"
                + (", which gives each throw's angle itself)" if self.layout == "custom" else ")"),
            )
        if self.throw_angles is not None:
            raise FieldProblem(
                "pin_split", "give either pin_split or throw_angles (the whole crank), not both"
            )
        split = math.degrees(self.pin_split)
        if self.has_vr_rows and not 0 <= split < 180.0:
            raise FieldProblem("pin_split", "must lie in [0, 180) deg for VR rows")
        if self.layout == "vee" and not -180.0 < split <= 180.0:
            raise FieldProblem("pin_split", "must lie in (-180, 180] deg for a vee")

    @property
    def split_vee(self) -> bool:
        """True for a vee whose throws are split into one pin per bank (``pin_split``)."""
        return self.layout == "vee" and self.pin_split is not None

    @property
    def throw_total(self) -> int:
        """Number of crank throws (a split pin is a throw of its own)."""
        if self.throw:
            return len(self.throw)
        return throw_count(self.layout, self.cylinder_count, self.w_type, self.split_vee)

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


def throw_count(layout: str, cylinders: int, w_type: str | None = None, split: bool = False) -> int:
    """Number of crank throws of a standard layout (``w_type`` "vr": a W from VR banks,
    one throw per cylinder; ``split``: a vee with split pins, one pin per cylinder)."""
    if (layout == "w" and w_type == "vr") or (layout == "vee" and split):
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


class _MassFields(_EngineTable):
    """The masses of one cylinder and one throw (``[masses]`` and its overrides)."""

    piston: float | None = field(
        "mass",
        default=None,
        ge=0,
        title="Piston",
        hint="with rings, e.g. 500 g",
        description="Piston with rings and clips.",
    )
    wrist_pin: float | None = field(
        "mass",
        default=None,
        ge=0,
        title="Wrist pin",
        description="Wrist pin.",
    )
    conrod: float | None = field(
        "mass",
        default=None,
        gt=0,
        title="Conrod",
        description="Conrod mass, with either conrod_rotating_fraction or conrod_cg_from_big_end "
        "(its split); optional conrod_inertia.",
    )
    conrod_rotating_fraction: float | None = field(
        "number",
        default=None,
        ge=0.0,
        le=1.0,
        title="Conrod rotating share",
        hint="0..1, e.g. 0.6667",
        description="Share of the conrod's mass at the big end, 0..1.",
    )
    conrod_cg_from_big_end: float | None = field(
        "length",
        default=None,
        ge=0,
        title="Conrod CG from the big end",
        hint="e.g. 45 mm",
        description="Distance of the conrod's centre of gravity from the big-end centre (instead of"
        " conrod_rotating_fraction).",
    )
    conrod_inertia: float | None = field(
        "inertia",
        default=None,
        ge=0,
        title="Conrod inertia",
        hint="about its CG; optional, e.g. 2000 kg*mm^2",
        description="The conrod's moment of inertia about its CG: the analysis reports the error of"
        " the two-mass split against it.",
    )
    crankpin: float | None = field(
        "mass",
        default=None,
        ge=0,
        title="Crankpin",
        description="Crankpin (per throw).",
    )
    crank_web: float | None = field(
        "mass",
        default=None,
        ge=0,
        title="Crank web",
        hint="each of the two webs of a throw",
        description="Each of the two webs of a throw, reduced to the crank radius with "
        "crank_web_cg_radius: 2·m_web·r_web/r.",
    )
    crank_web_cg_radius: float | None = field(
        "length",
        default=None,
        ge=0,
        title="Crank-web CG radius",
        description="Radius of a crank web's centre of gravity.",
    )
    reciprocating: float | None = field(
        "mass",
        default=None,
        ge=0,
        title="Reciprocating mass",
        hint="per cylinder",
        description="Total per cylinder (instead of piston, wrist pin and conrod share).",
    )
    rotating: float | None = field(
        "mass",
        default=None,
        ge=0,
        title="Rotating mass",
        hint="per throw, big ends included",
        description="Total per throw, all big ends on the pin included (instead of crankpin and "
        "webs).",
    )

    def check(self) -> None:
        if self.conrod_rotating_fraction is not None and self.conrod_cg_from_big_end is not None:
            raise FieldProblem(
                "conrod_cg_from_big_end",
                "give conrod_rotating_fraction or conrod_cg_from_big_end, not both",
            )


class MassOverride(_MassFields):
    """Masses that differ for some cylinders (per-cylinder fields) or throws (per-throw
    fields) (``[[masses.override]]``)."""

    cylinders: list[int] | None = field(
        "list",
        default=None,
        item=entry("whole"),
        max_items=MAX_CYLINDERS,
        title="Cylinders",
        description="The cylinders whose per-cylinder masses this table gives.",
    )
    throws: list[int] | None = field(
        "list",
        default=None,
        item=entry("whole"),
        max_items=MAX_THROWS,
        title="Throws",
        description="The throws whose per-throw masses this table gives.",
    )

    def check(self) -> None:
        super().check()
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


class Masses(_MassFields):
    """Masses per cylinder (reciprocating side) and per throw (rotating side)
    (``[masses]``).

    Either parts (piston, wrist_pin, conrod with its split; crankpin, crank_web with its
    CG radius) or totals (``reciprocating`` per cylinder, ``rotating`` per throw).
    """

    override: list[MassOverride] = field(
        "list",
        default=[],
        item=entry("table", table=MassOverride),
        max_items=MAX_OVERRIDES,
        title="Mass overrides",
        description="Masses that differ for some cylinders or throws ([[masses.override]] tables).",
    )

    def check(self) -> None:
        super().check()
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


# --------------------------------------------------------------------------- balancing options
class Counterweights(_EngineTable):
    """Crankshaft counterweights (``[counterweights]``; 2021 paper, section 3.1)."""

    webs: list[int] | None = field(
        "list",
        default=None,
        item=entry("choice", choices=(0, 1)),
        max_items=2 * MAX_THROWS,
        title="Webs with a counterweight",
        description="0/1 per web, two webs per throw (1: the web carries a counterweight); default "
        "all webs.",
        hint="0/1, two per throw, e.g. 1, 1, 0, 0, 1, 1 (empty: all)",
    )
    cg_radius: float = field(
        "length",
        gt=0,
        title="Counterweight CG radius",
        description="Radius of the counterweights' CG.",
        hint="e.g. 30 mm (empty: no counterweight table, defaults)",
    )
    angle: float | Literal["optimal"] = field(
        "angle",
        default=0.0,
        parse=_angle_or_optimal,
        words=f"'optimal' or {ANGLE_WORDS}",
        title="Counterweight angle",
        description="Angle of each counterweight from the position opposite its crankpin, or "
        "optimal.",
        hint="e.g. 30 deg, or optimal",
    )
    balance_factor: float = field(
        "number",
        default=0.0,
        ge=0.0,
        le=2.0,
        title="Balance factor",
        description="Share of the reciprocating mass of all cylinders on a pin put at that crankpin"
        " on the counterweights, by each cylinder's forward first order, offsets included "
        "(0.5 cancels the forward primary of every cylinder: the forward half of a single "
        "cylinder's primary and the whole primary of a 90° V pair).",
        hint="0..2, share of the primary reciprocating force",
    )
    scope: Literal["auto", "whole", "halves"] = field(
        "choice",
        default="auto",
        choices=("auto", "whole", "halves"),
        title="Counterweight scope",
        description="auto or whole: the whole crank (a crank already balanced as a whole "
        "gets no counterweight mass); halves: each half of the crank on its own.",
    )
    method: Literal["pattern", "individual"] = field(
        "choice",
        default="pattern",
        choices=("pattern", "individual"),
        title="Counterweight method",
        description="pattern: equal counterweights turned by ±α (the paper); individual: each its "
        "own mass and angle (least Σm²).",
    )
    web_offset: float | None = field(
        "length",
        default=None,
        ge=0,
        title="Counterweight web offset",
        description="Axial distance of each web from its throw mid-plane; default a quarter of the "
        "crank pitch (paper Eq. 7), half the crank radius for one throw.",
    )

    def check(self) -> None:
        if self.webs is not None and not any(self.webs):
            raise FieldProblem("webs", "has no counterweight (all zeros)")


class ShaftSet(_EngineTable):
    """A set of balance shafts for one order (``[balance_shafts.primary]`` or
    ``[balance_shafts.secondary]``)."""

    arrangement: Literal["pair", "counter-rotating"] = field(
        "choice",
        default="pair",
        choices=("pair", "counter-rotating"),
        title="Shaft arrangement",
        description="pair (co- and counter-rotating) or counter-rotating.",
    )
    cg_radius: float = field(
        "length",
        gt=0,
        title="Shaft CG radius",
        description="CG radius of the shaft masses.",
        hint="e.g. 30 mm",
    )
    length: float = field(
        "length",
        gt=0,
        title="Shaft length",
        description="Distance between the outer masses.",
        hint="e.g. 200 mm",
    )


class BalanceShafts(_EngineTable):
    """Balance shafts of the first and the second order (``[balance_shafts]``)."""

    primary: ShaftSet | None = field(
        "table",
        default=None,
        table=ShaftSet,
        title="Primary shafts",
        description="Shafts at crank speed against the first-order force and moment.",
    )
    secondary: ShaftSet | None = field(
        "table",
        default=None,
        table=ShaftSet,
        title="Secondary shafts",
        description="Shafts at twice crank speed against the second-order force and moment.",
    )


# --------------------------------------------------------------------------- powertrain
#: Most ``[[powertrain.mount]]`` tables (physics.mounts.MAX_MOUNTS).
MAX_MOUNTS = 16
#: Largest loss factor of a mount.
MAX_LOSS_FACTOR = 2.0


class Mount(_EngineTable):
    """One elastic mount of the powertrain (``[[powertrain.mount]]``)."""

    name: str = field(
        "text",
        default="",
        max_chars=MAX_NAME_CHARS,
        title="Mount name",
        description="Its name in the tables; empty: mount 1, mount 2, ... in order.",
    )
    position: list[float] = three_lengths(
        "Mount position",
        "Its elastic centre x, y, z from the crank's reference point "
        "(crank_train.moment_point), in the engine axes.",
        default=REQUIRED,
        hint="x, y, z, e.g. -250 mm, 180 mm, 120 mm",
    )
    stiffness: list[float] = field(
        "list",
        item=entry("stiffness", ge=0.0, zero=True),
        min_items=3,
        max_items=3,
        title="Mount stiffnesses",
        description="Principal stiffnesses: compression, first shear, second shear. Before "
        "orientation the compression axis is the engine's z, the first shear x, the second y.",
        hint="compression, shear, shear, e.g. 250 N/mm, 80 N/mm, 80 N/mm",
    )
    orientation: list[float] | None = field(
        "list",
        default=None,
        item=entry("angle", zero=True),
        min_items=3,
        max_items=3,
        title="Mount orientation",
        description="Rotations of its axes: a about the engine's x, then b about y, then c "
        "about z (fixed axes, R = Rz(c) Ry(b) Rx(a)); default 0, 0, 0.",
        hint="a, b, c, e.g. 0 deg, 30 deg, 0 deg",
    )
    loss_factor: float = field(
        "number",
        default=0.1,
        ge=0.0,
        le=MAX_LOSS_FACTOR,
        title="Loss factor",
        description="Hysteretic damping η of all three directions, stiffness k(1 + iη) (rubber "
        "about 0.05-0.25); default 0.1.",
    )


def _box(part: str, what: str, optional: bool = False) -> Any:
    return three_lengths(
        f"{part} size",
        f"The {what} as a solid box of uniform density: its edges along x, y, z.",
        default=None if optional else REQUIRED,
        hint="x, y, z, e.g. 400 mm, 450 mm, 500 mm",
        gt=0.0,
    )


def _centre(part: str, what: str, optional: bool = False) -> Any:
    return three_lengths(
        f"{part} centre",
        f"The centre of the {what}'s box x, y, z from the crank's reference point.",
        default=None if optional else REQUIRED,
        hint="x, y, z, e.g. 0 mm, 0 mm, 150 mm",
    )


class PowertrainEstimate(_EngineTable):
    """The powertrain's mass, centre of gravity and inertia estimated from the engine's own
    crank-train masses, a block and a gearbox as boxes (``[powertrain.estimate]``,
    docs/mounts.md, "Estimating the powertrain")."""

    block_mass: float = field(
        "mass",
        gt=0.0,
        title="Block mass",
        description="Mass of the engine without its crank train's rotating and reciprocating "
        "masses: block, head, crankshaft journals and counterweights, flywheel, ancillaries.",
        hint="e.g. 110 kg",
    )
    block_size: list[float] = _box("Block", "block")
    block_center: list[float] = _centre("Block", "block")
    gearbox_mass: float | None = field(
        "mass",
        default=None,
        gt=0.0,
        title="Gearbox mass",
        description="Mass of the gearbox (with the clutch and the differential); empty: no "
        "gearbox.",
        hint="e.g. 45 kg",
    )
    gearbox_size: list[float] | None = _box("Gearbox", "gearbox", optional=True)
    gearbox_center: list[float] | None = _centre("Gearbox", "gearbox", optional=True)

    def check(self) -> None:
        given = [
            getattr(self, n) is not None for n in ("gearbox_mass", "gearbox_size", "gearbox_center")
        ]
        if any(given) and not all(given):
            raise FieldProblem(
                "gearbox_mass", "a gearbox needs gearbox_mass, gearbox_size and gearbox_center"
            )


class Powertrain(_EngineTable):
    """The powertrain (engine and gearbox) as a rigid body on its mounts (``[powertrain]``,
    docs/mounts.md): its mass, centre of gravity and inertia given, or estimated
    (``[powertrain.estimate]``)."""

    mass: float | None = field(
        "mass",
        default=None,
        gt=0.0,
        title="Powertrain mass",
        description="Mass of the powertrain: engine, gearbox and all that the mounts carry "
        "(with cg and inertia; or a [powertrain.estimate] table instead of the three).",
        hint="e.g. 180 kg",
    )
    cg: list[float] | None = three_lengths(
        "Centre of gravity",
        "Its centre of gravity x, y, z from the crank's reference point.",
        hint="x, y, z, e.g. 0 mm, 150 mm, 60 mm",
    )
    inertia: list[float] | None = field(
        "list",
        default=None,
        item=entry("inertia", gt=0.0),
        min_items=3,
        max_items=3,
        title="Moments of inertia",
        description="Ixx, Iyy, Izz about the centre of gravity, engine axes.",
        hint="e.g. 8 kg*m^2, 6 kg*m^2, 9 kg*m^2",
    )
    estimate: PowertrainEstimate | None = field(
        "table",
        default=None,
        table=PowertrainEstimate,
        title="Estimate of the powertrain",
        description="Estimate mass, centre of gravity and inertia from the crank train's "
        "masses, a block and a gearbox as boxes (instead of mass, cg, inertia and products).",
    )
    products: list[float] | None = field(
        "list",
        default=None,
        item=entry("inertia", zero=True),
        min_items=3,
        max_items=3,
        title="Products of inertia",
        description="The tensor's off-diagonal entries Ixy, Iyz, Ixz about the centre of "
        "gravity, each −∫xy dm etc. (the negative of the product of inertia); default 0.",
        hint="Ixy, Iyz, Ixz, e.g. 0.3 kg*m^2, 0 kg*m^2, -0.5 kg*m^2",
    )
    up: list[float] | None = field(
        "list",
        default=None,
        item=entry("number"),
        min_items=3,
        max_items=3,
        title="Upward direction",
        description="The upward vertical in the engine axes, x, y, z (any length); default "
        "0, 0, 1 (cylinders up). Weight acts against it.",
    )
    mount: list[Mount] = field(
        "list",
        item=entry("table", table=Mount),
        min_items=1,
        max_items=MAX_MOUNTS,
        title="Mounts",
        description="The mounts, a [[powertrain.mount]] table each (at least three to hold the "
        "body in all six directions, unless each holds in several).",
    )

    def check(self) -> None:
        if self.up is not None and not any(self.up):
            raise FieldProblem("up", "must not be 0, 0, 0")
        body = [n for n in ("mass", "cg", "inertia", "products") if getattr(self, n) is not None]
        if self.estimate is not None:
            if body:
                raise FieldProblem(
                    body[0], "is estimated by [powertrain.estimate]: give one or the other"
                )
        else:
            for name in ("mass", "cg", "inertia"):
                if getattr(self, name) is None:
                    raise FieldProblem(
                        name, "is missing (or give a [powertrain.estimate] table instead)"
                    )
        if self.inertia is None:
            return
        ixx, iyy, izz = self.inertia
        if ixx + iyy < izz or iyy + izz < ixx or ixx + izz < iyy:
            raise FieldProblem(
                "inertia",
                "no rigid body has these: each moment must be at most the sum of the other two",
            )
        if self.products is not None:
            import numpy as np

            tensor = np.array(
                [
                    [ixx, self.products[0], self.products[2]],
                    [self.products[0], iyy, self.products[1]],
                    [self.products[2], self.products[1], izz],
                ]
            )
            if np.linalg.eigvalsh(tensor)[0] <= 0:
                raise FieldProblem(
                    "products", "with these the inertia tensor is not positive definite"
                )
        names = [m.name for m in self.mount if m.name]
        for name in names:
            if names.count(name) > 1:
                raise FieldProblem("mount", f"two mounts are named {name!r}")


class EngineSpec(_EngineTable):
    """A whole engine: the contents of one engine file."""

    name: str = field(
        "text",
        default="engine",
        max_chars=MAX_NAME_CHARS,
        title="Engine name",
        description="Free text: the engine's name, shown in every output.",
    )
    description: str = field(
        "text",
        default="",
        max_chars=MAX_DESCRIPTION_CHARS,
        title="Description",
        description="Free text.",
    )
    speed: float = field(
        "speed",
        gt=0,
        title="Speed",
        description="Crank speed (rpm, rad/s, Hz = rev/s).",
        hint="e.g. 2000 rpm",
    )
    kinematics: Literal["exact", "series", "first-order"] = field(
        "choice",
        default="exact",
        choices=KINEMATICS,
        title="Kinematics",
        description="exact: Fourier analysis of the exact slider-crank motion (offsets included); "
        "series: classical series to λ⁵ (A2, A4, A6); first-order: A1 = 1, A2 = λ, as "
        "the 2021 paper.",
    )
    crank_train: CrankTrain = field(
        "table",
        table=CrankTrain,
        title="Crank train",
        description="Layout and geometry of the crank train.",
    )
    masses: Masses = field(
        "table",
        table=Masses,
        title="Masses",
        description="Masses per cylinder and per throw, as parts or totals.",
    )
    counterweights: Counterweights | None = field(
        "table",
        default=None,
        table=Counterweights,
        title="Counterweights",
        description="Options of the balancing solver (crankbalance balance); without it, "
        "counterweights on every web at the crank radius at the optimal angle.",
    )
    balance_shafts: BalanceShafts | None = field(
        "table",
        default=None,
        table=BalanceShafts,
        title="Balance shafts",
        description="Balance shafts the balancing solver sizes; without it, none.",
    )
    powertrain: Powertrain | None = field(
        "table",
        default=None,
        table=Powertrain,
        title="Powertrain on its mounts",
        description="The powertrain as a rigid body on elastic mounts (crankbalance mounts, "
        "docs/mounts.md); without it, no mount study.",
    )

    def check(self) -> None:
        ct = self.crank_train
        n_cyl = ct.cylinder_count
        n_throw = ct.throw_total
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

    def plausibility(self) -> list[Note]:
        """Notes (not errors) about a valid engine whose numbers are unusual: a mean piston
        speed 2 s n = 2 r omega / pi above :data:`MAX_PISTON_SPEED`, a rod length outside
        :data:`ROD_RATIO` crank radii. Each names the key to check first."""
        ct = self.crank_train
        notes = []
        piston_speed = 2.0 * ct.crank_radius * self.speed / math.pi
        if piston_speed > MAX_PISTON_SPEED:
            notes.append(
                Note(
                    "speed",
                    f"mean piston speed {piston_speed:.3g} m/s, above about "
                    f"{MAX_PISTON_SPEED:g} m/s; check the speed and the crank radius",
                )
            )
        ratio = ct.rod_length / ct.crank_radius
        if not ROD_RATIO[0] <= ratio <= ROD_RATIO[1]:
            notes.append(
                Note(
                    "crank_train.rod_length",
                    f"the rod is {ratio:.3g} crank radii long, outside the usual "
                    f"{ROD_RATIO[0]:g}-{ROD_RATIO[1]:g}; check the rod length and the crank "
                    "radius",
                )
            )
        return notes


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


# --------------------------------------------------------------------------- reading
def spec_from_dict(data: Any) -> EngineSpec:
    """Validate an engine-file dictionary; raise :class:`InputError` on the first problem
    (an unknown key anywhere first, named with the closest allowed key)."""
    if not isinstance(data, dict):
        raise InputError("engine file", type(data).__name__, "must be a table of keys and values")
    return EngineSpec.parse(data)
