"""The web application's project: form texts -> engine-file dictionary -> validated spec.

Nothing here imports NiceGUI: a :class:`Project` is one user's state (the texts of the
form fields, the settings of the study tabs and the last results) and is tested on its
own. The web page keeps one Project per browser tab (client); there is no module state.

Every form field is bound to one key path of the engine file (``docs/engine_file.md``),
so the one validated model of :mod:`crankbalance.schema.engine` checks the form exactly as it
checks a file; its :class:`~crankbalance.errors.InputError` names the field, which is
how a message finds its way beside the field it concerns.
"""

from __future__ import annotations

import copy
import json
import logging
import math
import re
import time
from dataclasses import dataclass, field
from typing import Any, Literal

from ..errors import InputError
from ..physics.firing import SCHEMES
from ..schema.engine import (
    LAYOUTS,
    W_TYPES,
    Counterweights,
    CrankTrain,
    EngineSpec,
    ShaftSet,
    spec_from_dict,
)
from ..units import parse_quantity

Kind = Literal[
    "text", "quantity", "quantitylist", "int", "float", "intlist", "choice", "angle_or_optimal"
]
SETTINGS_TAG = "# crankbalance-web settings: "
SETTINGS_WHERE = "crankbalance-web settings"  # the settings line, as its tag names it
#: largest engine file or project the web page and the API take [bytes]: an engine file is
#: a few kB (the largest preset well under 1 kB, a 64-throw custom engine under 10 kB)
MAX_BYTES = 65_536
log = logging.getLogger("crankbalance.web")


def _choices(model: Any, name: str, first: str | None = None) -> tuple[str, ...]:
    """The allowed values of a choice of the engine file's schema, as form options."""
    values = [str(v) for v in model.FIELDS[name].choices]
    if first is not None:
        values.sort(key=lambda v: v != first)
    return tuple(values)


@dataclass(frozen=True)
class FormField:
    """One input of the form, bound to ``path`` in the engine file."""

    key: str
    path: tuple[str, ...]
    label: str
    kind: Kind = "quantity"
    unit: str = "length"  # quantity kind for kind == "quantity"
    options: tuple[str, ...] = ()
    hint: str = ""
    group: str = ""  # "parts", "totals", "fraction", "cg", "primary", "secondary", ...
    #: layouts the field means something for (empty: all); shown for the others only
    #: while it holds a value, so that a value is never dropped unseen
    layouts: tuple[str, ...] = ()

    @property
    def dotted(self) -> str:
        return ".".join(self.path)


F = FormField
ENGINE_FIELDS: tuple[FormField, ...] = (
    F("name", ("name",), "Engine name", "text"),
    F("layout", ("crank_train", "layout"), "Layout", "choice", options=LAYOUTS),
    F("cylinders", ("crank_train", "cylinders"), "Cylinders", "int"),
    F(
        "firing_order",
        ("crank_train", "firing_order"),
        "Firing order",
        "intlist",
        hint="e.g. 1, 3, 2 (empty: cylinder order)",
    ),
    F(
        "strokes",
        ("crank_train", "strokes"),
        "Strokes per cycle",
        "choice",
        options=_choices(CrankTrain, "strokes", first="4"),
    ),
    F(
        "bank_angle",
        ("crank_train", "bank_angle"),
        "Bank angle",
        unit="angle",
        hint="vee / W / VR only, e.g. 90 deg",
    ),
    F("crank_pitch", ("crank_train", "crank_pitch"), "Crank pitch", hint="e.g. 90 mm"),
    F("crank_radius", ("crank_train", "crank_radius"), "Crank radius", hint="e.g. 40 mm"),
    F("rod_length", ("crank_train", "rod_length"), "Rod length", hint="e.g. 135 mm"),
    F("pin_offset", ("crank_train", "pin_offset"), "Wrist-pin offset", hint="e.g. 0 mm"),
    F("speed", ("speed",), "Speed", unit="speed", hint="e.g. 2000 rpm"),
    F(
        "kinematics",
        ("kinematics",),
        "Kinematics",
        "choice",
        options=_choices(EngineSpec, "kinematics"),
    ),
)
BALANCING_FIELDS: tuple[FormField, ...] = (
    F(
        "cw_webs",
        ("counterweights", "webs"),
        "Webs with a counterweight",
        "intlist",
        hint="0/1, two per throw, e.g. 1, 1, 0, 0, 1, 1 (empty: all)",
        group="cw",
    ),
    F(
        "cw_cg_radius",
        ("counterweights", "cg_radius"),
        "Counterweight CG radius",
        hint="e.g. 30 mm (empty: no counterweight table, defaults)",
        group="cw",
    ),
    F(
        "cw_angle",
        ("counterweights", "angle"),
        "Counterweight angle",
        "angle_or_optimal",
        hint="e.g. 30 deg, or optimal",
        group="cw",
    ),
    F(
        "cw_balance_factor",
        ("counterweights", "balance_factor"),
        "Balance factor",
        "float",
        hint="0..2, share of the primary reciprocating force",
        group="cw",
    ),
    F(
        "cw_method",
        ("counterweights", "method"),
        "Counterweight method",
        "choice",
        options=_choices(Counterweights, "method"),
        group="cw",
    ),
    F(
        "primary_arrangement",
        ("balance_shafts", "primary", "arrangement"),
        "Primary shafts",
        "choice",
        options=("none", *_choices(ShaftSet, "arrangement")),
        group="primary",
    ),
    F(
        "primary_cg_radius",
        ("balance_shafts", "primary", "cg_radius"),
        "Primary shaft CG radius",
        hint="e.g. 30 mm",
        group="primary",
    ),
    F(
        "primary_length",
        ("balance_shafts", "primary", "length"),
        "Primary shaft length",
        hint="e.g. 200 mm",
        group="primary",
    ),
    F(
        "secondary_arrangement",
        ("balance_shafts", "secondary", "arrangement"),
        "Secondary shafts",
        "choice",
        options=("none", *_choices(ShaftSet, "arrangement")),
        group="secondary",
    ),
    F(
        "secondary_cg_radius",
        ("balance_shafts", "secondary", "cg_radius"),
        "Secondary shaft CG radius",
        hint="e.g. 30 mm",
        group="secondary",
    ),
    F(
        "secondary_length",
        ("balance_shafts", "secondary", "length"),
        "Secondary shaft length",
        hint="e.g. 200 mm",
        group="secondary",
    ),
)
#: the crank train's details beyond the general fields: offsets per bank or cylinder, rod
#: positions on shared pins, the moment reference and a radial's master-and-link rods
DETAIL_FIELDS: tuple[FormField, ...] = (
    F(
        "w_type",
        ("crank_train", "w_type"),
        "W type",
        "choice",
        options=W_TYPES,
        hint="broad-arrow: three banks on each pin; vr: two VR banks (empty: broad-arrow)",
        layouts=("w",),
    ),
    F(
        "vr_angle",
        ("crank_train", "vr_angle"),
        "VR angle",
        unit="angle",
        hint="narrow angle between the rows of each VR bank, e.g. 15 deg",
        group="w-vr",
        layouts=("w",),
    ),
    F(
        "bore_offset",
        ("crank_train", "bore_offset"),
        "Bore offset of the VR rows",
        hint="each row's bore axes from the crank axis, e.g. 12.5 mm (empty: 0 mm)",
        group="vr-rows",
        layouts=("vr", "w"),
    ),
    F(
        "pin_split",
        ("crank_train", "pin_split"),
        "Pin split of the VR rows",
        unit="angle",
        hint="angle between the two rows' crankpins, e.g. 22 deg (empty: even firing)",
        group="vr-rows",
        layouts=("vr", "w"),
    ),
    F(
        "numbering",
        ("crank_train", "numbering"),
        "Maker's numbering",
        "choice",
        options=tuple(SCHEMES),
        hint="the firing order is then written in the maker's cylinder numbers "
        "(e.g. porsche-boxer: 1, 6, 2, 4, 3, 5; empty: crankbalance's numbering)",
        layouts=("vee", "boxer"),
    ),
    F(
        "maker_numbers",
        ("crank_train", "maker_numbers"),
        "Maker's numbers",
        "intlist",
        hint="crankbalance's number of each of the maker's cylinders, e.g. 5, 1, 6, 2, 7, "
        "3, 8, 4; the firing order is then in the maker's numbers (empty: none)",
    ),
    F(
        "bank_offsets",
        ("crank_train", "bank_offsets"),
        "Bore offset of each bank",
        "quantitylist",
        hint="one per bank (vee, boxer: 2; W: 3), e.g. 0 mm, 5 mm",
        layouts=("vee", "boxer", "w"),
        group="banks",
    ),
    F(
        "cylinder_offsets",
        ("crank_train", "cylinder_offsets"),
        "Bore offset of each cylinder",
        "quantitylist",
        hint="one per cylinder, e.g. 0 mm, 2 mm, 0 mm (not with the offsets per bank)",
    ),
    F(
        "rod_positions",
        ("crank_train", "rod_positions"),
        "Rod positions on the pin",
        "quantitylist",
        hint="one per cylinder from the throw's mid-plane, e.g. -10 mm, 10 mm "
        "(side-by-side rods; empty: all 0)",
        layouts=("vee", "boxer", "w", "radial", "custom"),
    ),
    F(
        "moment_reference",
        ("crank_train", "moment_reference"),
        "Moment reference",
        hint="point moments are taken about, from the crank's mid-point (empty: 0 mm)",
    ),
    F(
        "master_cylinder",
        ("crank_train", "articulated", "master_cylinder"),
        "Master rod's cylinder",
        "int",
        hint="master-and-link rods (empty: 1)",
        group="articulated",
        layouts=("radial",),
    ),
    F(
        "link_pin_radius",
        ("crank_train", "articulated", "link_pin_radius"),
        "Link pin radius",
        hint="link pins from the master's big-end centre, e.g. 56 mm "
        "(empty with the link rod length: each rod on the pin)",
        group="articulated",
        layouts=("radial",),
    ),
    F(
        "link_rod_length",
        ("crank_train", "articulated", "link_rod_length"),
        "Link rod length",
        hint="centre distance of each link rod, e.g. 198 mm",
        group="articulated",
        layouts=("radial",),
    ),
    F(
        "link_pin_angles",
        ("crank_train", "articulated", "link_pin_angles"),
        "Link pin angles",
        "quantitylist",
        unit="angle",
        hint="one per cylinder from the master rod's axis, the master's 0 deg "
        "(empty: each cylinder's angle from the master)",
        group="articulated",
        layouts=("radial",),
    ),
)
MASS_FIELDS: tuple[FormField, ...] = (
    F(
        "piston",
        ("masses", "piston"),
        "Piston (with rings)",
        unit="mass",
        hint="e.g. 500 g",
        group="parts",
    ),
    F("wrist_pin", ("masses", "wrist_pin"), "Wrist pin", unit="mass", group="parts"),
    F("conrod", ("masses", "conrod"), "Conrod", unit="mass", group="parts"),
    F(
        "conrod_rotating_fraction",
        ("masses", "conrod_rotating_fraction"),
        "Conrod rotating fraction",
        "float",
        hint="0..1, e.g. 0.6667",
        group="fraction",
    ),
    F(
        "conrod_cg_from_big_end",
        ("masses", "conrod_cg_from_big_end"),
        "Conrod CG from big end",
        hint="e.g. 45 mm",
        group="cg",
    ),
    F(
        "conrod_inertia",
        ("masses", "conrod_inertia"),
        "Conrod inertia about its CG",
        unit="inertia",
        hint="optional, e.g. 2000 kg*mm^2",
        group="parts",
    ),
    F("crankpin", ("masses", "crankpin"), "Crankpin", unit="mass", group="parts"),
    F("crank_web", ("masses", "crank_web"), "Crank web (each)", unit="mass", group="parts"),
    F(
        "crank_web_cg_radius",
        ("masses", "crank_web_cg_radius"),
        "Crank web CG radius",
        group="parts",
    ),
    F(
        "reciprocating",
        ("masses", "reciprocating"),
        "Reciprocating mass per cylinder",
        unit="mass",
        group="totals",
    ),
    F(
        "rotating",
        ("masses", "rotating"),
        "Rotating mass per throw (big ends incl.)",
        unit="mass",
        group="totals",
    ),
)
FIELDS: tuple[FormField, ...] = ENGINE_FIELDS + DETAIL_FIELDS + BALANCING_FIELDS + MASS_FIELDS
FIELD_BY_KEY: dict[str, FormField] = {f.key: f for f in FIELDS}
FIELD_BY_PATH: dict[str, FormField] = {f.dotted: f for f in FIELDS}
DEFAULTS: dict[str, str] = {
    "strokes": "4",
    "kinematics": "exact",
    "cw_method": "pattern",
    "primary_arrangement": "none",
    "secondary_arrangement": "none",
    "layout": "inline",
}

#: settings of the study tabs (saved with the project as a comment line of the engine file)
DEFAULT_SETTINGS: dict[str, Any] = {
    "mass_mode": "parts",  # parts | totals
    "conrod_split": "cg",  # fraction | cg
    "orders": 8,
    "curve_quantity": "force",
    "polar_order": 1,
    # counterweight design
    "cw_density": "8000 kg/m^3",
    "cw_max_mass": "",
    "cw_max_radius": "",
    "cw_min_balance": "100",
    "cw_iterations": "12",
    "cw_population": "1024",
    "cw_seed": "1",
    # single cylinder
    "sc_cylinder": "1",
    "sc_balance_factor": "0.5",
    "sc_grade": "G6.3",
    "sc_rotor_mass": "",
    "sc_residual": "",
    "rb_new_reciprocating": "",
    "rb_new_rotating": "",
    "rb_cw_mass": "",
    "rb_cw_radius": "",
    "rb_hole_diameter": "8 mm",
    "rb_point_angle": "180 deg",
    "rb_depth_to": "tip",
    "rb_holes": "1",
    "rb_hole_radius": "",
    # balance shaft
    "bs_length": "300 mm",
    "bs_diameter": "25 mm",
    "bs_weight": "2",
    "bs_points": "41",
    # performance
    "pf_bore": "",
    "pf_balance_factors": "0, 0.25, 0.5, 0.75, 1",
    "pf_crank_inertia": "",
    "pf_friction_coefficient": "0.005",
    "pf_journal_diameter": "30 mm",
}


def _format_value(value: Any) -> str:
    if isinstance(value, list):
        return ", ".join(str(v) for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def check_field(f: FormField, text: str) -> Any:
    """Parse the text of one field on its own; raise InputError naming the field."""
    text = text.strip()
    where = f.dotted
    if f.kind == "text":
        return text
    if f.kind == "choice":
        if text not in f.options:
            raise InputError(where, text, f"must be one of {', '.join(f.options)}")
        return int(text) if f.key == "strokes" else text
    if f.kind == "int":
        try:
            return int(text)
        except ValueError:
            raise InputError(where, text, "must be a whole number, e.g. 3") from None
    if f.kind == "float":
        try:
            value = float(text)
        except ValueError:
            raise InputError(where, text, "must be a number, e.g. 0.5") from None
        if not math.isfinite(value):
            raise InputError(where, text, "must be a finite number")
        return value
    if f.kind == "intlist":
        parts = [p for p in text.replace(";", ",").replace(" ", ",").split(",") if p]
        try:
            return [int(p) for p in parts]
        except ValueError:
            raise InputError(
                where, text, "must be whole numbers separated by commas, e.g. 1, 3, 2"
            ) from None
    if f.kind == "quantitylist":
        parts = [p.strip() for p in text.replace(";", ",").split(",") if p.strip()]
        example = "0 deg, 40 deg, 80 deg" if f.unit == "angle" else "-10 mm, 10 mm"
        for part in parts:
            try:
                parse_quantity(part, f.unit, where)
            except InputError as error:
                raise InputError(
                    where, part, f"{error.allowed}; give them separated by commas, e.g. {example}"
                ) from None
        return parts
    if f.kind == "angle_or_optimal":
        if text.lower() == "optimal":
            return "optimal"
        parse_quantity(text, "angle", where)
        return text
    parse_quantity(text, f.unit, where)
    return text


@dataclass
class Computed:
    """The results of one computation (None where a study failed)."""

    spec: EngineSpec
    analysis: Any
    study: Any
    elapsed: float
    error: str = ""


@dataclass
class Project:
    """One user's project: form texts, settings, unknown engine-file keys kept as they are."""

    texts: dict[str, str] = field(default_factory=dict)
    settings: dict[str, Any] = field(default_factory=lambda: dict(DEFAULT_SETTINGS))
    extras: dict[str, Any] = field(default_factory=dict)
    errors: dict[str, str] = field(default_factory=dict)
    general_error: str = ""
    #: plausibility warnings of a valid engine by field key (shown beside the field)
    warnings: dict[str, str] = field(default_factory=dict)
    #: the crank editor: throw angles (None: from the firing order), custom throws
    #: (position, angle, banks) and mass overrides (target, numbers, mass, value), as texts
    throw_angles: list[str] | None = None
    throws: list[dict[str, str]] = field(default_factory=list)
    overrides: list[dict[str, str]] = field(default_factory=list)
    spec: EngineSpec | None = None
    computed: Computed | None = None

    # ------------------------------------------------------------------ loading
    @classmethod
    def from_spec(cls, spec: EngineSpec, settings: dict[str, Any] | None = None) -> Project:
        project = cls()
        project.load_spec(spec, settings)
        return project

    @classmethod
    def from_preset(cls, name: str) -> Project:
        from ..io.engine_file import preset_text

        return cls.from_text(preset_text(name), f"preset {name}")

    @classmethod
    def from_text(cls, text: str, source: str = "project file", fmt: str = "toml") -> Project:
        project = cls()
        project.load_text(text, source, fmt)
        return project

    def load_text(self, text: str, source: str = "project file", fmt: str = "toml") -> None:
        """Replace the project by the content of an engine file; on error raise InputError
        and leave the project as it was (a bad settings line is an error too)."""
        spec = parse_untrusted(text, source, fmt)
        settings = _settings_from_text(text)
        self.load_spec(spec, settings)

    def load_spec(self, spec: EngineSpec, settings: dict[str, Any] | None = None) -> None:
        data = spec.to_data()
        texts: dict[str, str] = {}
        extras = copy.deepcopy(data)
        for f in FIELDS:
            value = _pop_path(extras, f.path)
            if value is not None:
                texts[f.key] = _format_value(value)
        train = extras.get("crank_train", {})
        angles = train.pop("throw_angles", None)
        throws = train.pop("throw", [])
        overrides = extras.get("masses", {}).pop("override", [])
        _prune(extras)
        for key, value in DEFAULTS.items():
            texts.setdefault(key, value)
        masses = data.get("masses", {})
        for name in ("primary", "secondary"):
            table = data.get("balance_shafts", {}).get(name)
            if table is not None and f"{name}_arrangement" not in texts:
                texts[f"{name}_arrangement"] = "pair"
            if table is not None and texts.get(f"{name}_arrangement") == "none":
                texts[f"{name}_arrangement"] = "pair"
        new_settings = dict(DEFAULT_SETTINGS)
        new_settings["mass_mode"] = "parts" if "piston" in masses else "totals"
        new_settings["conrod_split"] = "fraction" if "conrod_rotating_fraction" in masses else "cg"
        if settings:
            new_settings.update({k: v for k, v in settings.items() if k in DEFAULT_SETTINGS})
        self.texts, self.extras, self.settings = texts, extras, new_settings
        self.throw_angles = None if angles is None else [str(a) for a in angles]
        self.throws = [
            {
                "position": str(t["position"]),
                "angle": str(t.get("angle", "0 deg")),
                "banks": ", ".join(str(b) for b in t["banks"]),
            }
            for t in throws
        ]
        self.overrides = [
            {
                "target": "cylinders" if "cylinders" in item else "throws",
                "numbers": _format_value(item.get("cylinders", item.get("throws", []))),
                "mass": key,
                "value": _format_value(value),
            }
            for item in overrides
            for key, value in item.items()
            if key not in ("cylinders", "throws")
        ]
        self.validate()

    # ------------------------------------------------------------------ editing
    def set(self, key: str, text: str) -> dict[str, str]:
        """Change one field and validate the whole engine; return the errors by field key."""
        if key not in FIELD_BY_KEY:
            raise KeyError(key)
        self.texts[key] = "" if text is None else str(text)
        return self.validate()

    def set_setting(self, key: str, value: Any) -> dict[str, str]:
        if key not in DEFAULT_SETTINGS:
            raise KeyError(key)
        self.settings[key] = value
        if key in ("mass_mode", "conrod_split"):
            return self.validate()
        return self.errors

    def active(self, f: FormField) -> bool:
        """Whether a field takes part in the engine (parts/totals, conrod split, shafts)."""
        s = self.settings
        if f.layouts and not self._means_something(f):
            return bool(self.texts.get(f.key, "").strip())
        if f.group in ("parts", "fraction", "cg") and s["mass_mode"] != "parts":
            return False
        if f.group == "totals" and s["mass_mode"] != "totals":
            return False
        if f.group in ("fraction", "cg") and s["conrod_split"] != f.group:
            return False
        if f.group in ("primary", "secondary") and not f.key.endswith("arrangement"):
            return self.texts.get(f"{f.group}_arrangement", "none") != "none"
        return True

    def _means_something(self, f: FormField) -> bool:
        """Whether a detail field means something for the layout (and W type) in the form:
        the VR rows' fields for layout vr and a W from VR banks, the VR angle for the latter."""
        layout = self.texts.get("layout")
        w_vr = layout == "w" and self.texts.get("w_type") == "vr"
        if f.group == "w-vr":
            return w_vr
        if f.group == "vr-rows":
            return layout == "vr" or w_vr
        if f.group == "banks":  # a W from VR banks gives its offsets per cylinder
            return layout in f.layouts and not w_vr
        return layout in f.layouts

    def file_dict(self) -> tuple[dict[str, Any], dict[str, str]]:
        """The engine-file dictionary of the form, and the errors of single fields."""
        data = copy.deepcopy(self.extras)
        errors: dict[str, str] = {}
        for f in FIELDS:
            text = self.texts.get(f.key, "").strip()
            if not self.active(f) or not text:
                continue
            if (f.key.endswith("_arrangement") and text == "none") or (
                f.key == "cw_method" and text == "pattern"
            ):
                continue  # no shaft set / the default method needs no counterweight table
            try:
                value = check_field(f, text)
            except InputError as error:
                errors[f.key] = self.message(error)
                continue
            _set_path(data, f.path, value)
        self._editor_dict(data, errors)
        return data, errors

    def _editor_dict(self, data: dict[str, Any], errors: dict[str, str]) -> None:
        """Put the crank editor's tables into the engine-file dictionary ``data``; the
        errors of single cells go to ``errors`` under the cell's key (``throw.2.banks``)."""

        def angle(text: str, key: str) -> str:
            try:
                parse_quantity(text.strip(), "angle", key)
            except InputError as error:
                errors[key] = self.message(error)
            return text.strip()

        custom = self.texts.get("layout") == "custom"
        if self.throw_angles is not None and not custom:
            angles = [angle(a, f"throw_angles.{k}") for k, a in enumerate(self.throw_angles)]
            _set_path(data, ("crank_train", "throw_angles"), angles)
        if custom and self.throws:
            throws = []
            for k, row in enumerate(self.throws):
                try:
                    parse_quantity(row["position"].strip(), "length", f"throw.{k}.position")
                except InputError as error:
                    errors[f"throw.{k}.position"] = self.message(error)
                banks = [b for b in row["banks"].replace(";", ",").split(",") if b.strip()]
                throws.append(
                    {
                        "position": row["position"].strip(),
                        "angle": angle(row["angle"], f"throw.{k}.angle"),
                        "banks": [angle(b, f"throw.{k}.banks") for b in banks],
                    }
                )
            _set_path(data, ("crank_train", "throw"), throws)
        items = []
        for k, row in enumerate(self.overrides):
            numbers = F(f"override.{k}.numbers", ("override", str(k), "numbers"), "", "intlist")
            try:
                targets = check_field(numbers, row["numbers"])
                value = check_field(FIELD_BY_KEY[row["mass"]], row["value"])
            except InputError as error:
                part = "numbers" if error.field == numbers.key else "value"
                errors[f"override.{k}.{part}"] = self.message(error)
                continue
            items.append({row["target"]: targets, row["mass"]: value})
        if self.overrides:
            _set_path(data, ("masses", "override"), items)

    def validate(self) -> dict[str, str]:
        """Check every field, then the whole engine through the spec model."""
        data, errors = self.file_dict()
        self.general_error = ""
        self.spec = None
        if not errors:
            try:
                self.spec = spec_from_dict(data)
            except InputError as error:
                key = self.key_for(error.field)
                if key is not None:
                    errors[key] = self.message(error)
                else:
                    self.general_error = self.message(error)
        offer = self.default_cw_cg_radius()
        if "cw_cg_radius" in errors and offer and not self.texts.get("cw_cg_radius", "").strip():
            errors["cw_cg_radius"] += f"; e.g. {offer}, {CW_CG_WORDS} (button below)"
        self.errors = errors
        self.warnings = {}
        for note in self.spec.plausibility() if self.spec is not None else ():
            key = self.key_for(note.field)
            if key is not None:
                self.warnings[key] = f"Warning: {note.text}"
        return errors

    def default_cw_cg_radius(self) -> str | None:
        """The counterweight CG radius offered from the engine's geometry:
        :data:`CW_CG_SHARE` of the crank radius (None while the crank radius is not valid)."""
        try:
            radius = parse_quantity(self.texts.get("crank_radius", "").strip(), "length", "r")
        except InputError:
            return None
        return f"{round(CW_CG_SHARE * radius * 1e3, 2):g} mm" if radius > 0 else None

    def message(self, error: InputError) -> str:
        """``error`` in the words of the form (see :func:`form_message`)."""
        return form_message(error)

    def key_for(self, dotted: str) -> str | None:
        """The key of the form field or crank-editor cell an InputError's field belongs to."""
        cell = _cell_for(dotted)
        if cell is not None:
            return cell
        f = self.field_for(dotted)
        return None if f is None else f.key

    def field_for(self, dotted: str) -> FormField | None:
        """The visible form field an InputError belongs to (None: a general message)."""
        f = _field_for(dotted)
        if f is not None and self.active(f):
            return f
        if dotted.split(".")[0].split("[")[0] == "masses":
            rotating_side = any(k in dotted for k in ("crankpin", "crank_web", "rotating"))
            if self.settings["mass_mode"] == "totals":
                wanted = "rotating" if rotating_side else "reciprocating"
            else:
                wanted = "crankpin" if rotating_side else "piston"
            return FIELD_BY_KEY[wanted]
        return None

    # ------------------------------------------------------------------ computing
    def compute(self) -> Computed | None:
        """Free forces and moments and the balancing study of the current engine."""
        from ..studies.engine import analyze, balance_engine

        if self.spec is None:
            return None
        t0 = time.perf_counter()
        orders = int(self.settings.get("orders", 8))
        try:
            analysis = analyze(self.spec, orders=orders)
            study = balance_engine(self.spec, orders=max(orders, 2))
            error = ""
        except InputError as exc:
            key = self.key_for(exc.field)
            if key is not None:
                self.errors[key] = self.message(exc)
            else:
                self.general_error = self.message(exc)
            return None
        self.computed = Computed(self.spec, analysis, study, time.perf_counter() - t0, error)
        return self.computed

    # ------------------------------------------------------------------ saving
    def to_toml(self) -> str:
        """The project as an engine file (its settings in a comment line the CLI ignores)."""
        from ..io.engine_file import engine_to_toml

        if self.spec is None:
            raise InputError(
                "project", None, "has errors; correct the fields marked in red before saving"
            )
        settings = json.dumps(self.settings, separators=(",", ":"), sort_keys=True)
        return f"{SETTINGS_TAG}{settings}\n" + engine_to_toml(self.spec)

    def to_json(self) -> str:
        if self.spec is None:
            raise InputError(
                "project", None, "has errors; correct the fields marked in red before saving"
            )
        return json.dumps(self.spec.to_data(), indent=2) + "\n"


# --------------------------------------------------------------------------- reading
def read_text(raw: bytes, source: str) -> str:
    """The text of an uploaded engine file or API body: at most :data:`MAX_BYTES`, decoded
    as the command line decodes an engine file (:func:`~crankbalance.io.reading.decode_text`:
    UTF-8, a byte-order mark dropped)."""
    from ..io.reading import decode_text

    if len(raw) > MAX_BYTES:
        raise InputError(
            source,
            f"{len(raw)} bytes",
            f"is larger than {MAX_BYTES} bytes; an engine file is a few kB of TOML or JSON",
        )
    return decode_text(raw, source, "binary data", "a TOML or JSON engine file")


def parse_untrusted(text: str, source: str, fmt: str) -> EngineSpec:
    """The engine of a text from outside (an upload, an API body): every failure to read it
    is an :class:`InputError` naming ``source``, never a traceback in the server's log."""
    from ..io.engine_file import parse_engine_text

    try:
        return parse_engine_text(text, source, fmt)
    except InputError:
        raise
    except RecursionError:
        raise InputError(source, "nesting", "is nested too deeply to be an engine file") from None
    except Exception as error:  # a reader's failure on hostile input: refused in one line
        detail = " ".join(str(error).split())[:200]
        log.warning("%s refused: %s: %s", source, type(error).__name__, detail)
        raise InputError(
            source, type(error).__name__, f"cannot be read as an engine file ({detail})"
        ) from None


# --------------------------------------------------------------------------- defaults
#: counterweight CG radius offered, as a share of the crank radius: the 2021 paper's
#: inline-3 has its counterweight CG at 30 mm on a 40 mm crank radius
CW_CG_SHARE = 0.75
CW_CG_WORDS = "3/4 of the crank radius, as the 2021 paper's 30 mm for 40 mm"

# --------------------------------------------------------------------------- messages
_CELL = re.compile(
    r"crank_train\.(throw_angles)\[(\d+)\]|crank_train\.(throw)\[(\d+)\]\.?(\w*)"
    r"|masses\.(override)\[(\d+)\]\.?(\w*)"
)
#: words of keys that have no field of their own in the form
_KEY_WORDS = {
    "crank_train.throw_angles": "Throw angles (crank editor)",
    "crank_train.throw": "Custom throws (crank editor)",
    "crank_train.crank_offset": "Crank offset",
    "crank_train.articulated": "Master-and-link rods",
    "masses.override": "Mass overrides (crank editor)",
    "counterweights.scope": "Counterweight scope",
    "counterweights.web_offset": "Counterweight web offset",
    "description": "Description",
}


def _cell_for(dotted: str) -> str | None:
    """The crank-editor cell an engine-file key points at (``throw.2.banks``), or None."""
    m = _CELL.fullmatch(dotted)
    if m is None:
        table = re.fullmatch(r"crank_train\.(throw_angles|throw)|masses\.(override)\b.*", dotted)
        return None if table is None else table.group(1) or table.group(2)
    if m.group(1):
        return f"throw_angles.{m.group(2)}"
    if m.group(3):
        part = m.group(5) if m.group(5) in ("position", "angle", "banks") else "banks"
        return f"throw.{m.group(4)}.{part}"
    part = "numbers" if m.group(8) in ("", "cylinders", "throws") else "value"
    return f"override.{m.group(7)}.{part}"


def label_of(dotted: str) -> str:
    """The words of the form for a key of the engine file or a crank-editor cell."""
    m = re.fullmatch(r"(?:crank_train\.)?throw_angles[.\[](\d+)\]?", dotted)
    if m:
        return f"Throw {int(m.group(1)) + 1} angle"
    m = re.fullmatch(r"(?:crank_train\.)?throw[.\[](\d+)\]?\.?(\w*)", dotted)
    if m:
        return f"Throw {int(m.group(1)) + 1} {m.group(2) or 'table'}"
    m = re.fullmatch(r"(?:masses\.)?override[.\[](\d+)\]?\.?(\w*)", dotted)
    if m:
        part = m.group(2)
        what = part if part in ("", "numbers", "cylinders", "throws", "value") else None
        words = FIELD_BY_KEY[part].label.lower() if what is None else (what or "row")
        return f"Mass override {int(m.group(1)) + 1}: {words}"
    if dotted in _KEY_WORDS:
        return _KEY_WORDS[dotted]
    f = _field_for(dotted)
    return dotted if f is None else f.label


def _words(text: str) -> str:
    """Keys of the engine file inside a message replaced by the form's words (lower case),
    references to the documentation dropped."""
    text = re.sub(r"\s*\(see docs/[^)]*\)|;?\s*see docs/\S+", "", text)
    text = text.replace("[[crank_train.throw]] tables", "custom throws (crank editor)")
    for target in ("cylinders", "throws"):  # the target of a mass override
        text = text.replace(f"`{target} = [...]`", f"the target {target.capitalize()}")

    def word(m: re.Match[str]) -> str:
        key = m.group(1) or m.group(2)
        if key in SHORT_KEYS:
            key = SHORT_KEYS[key]
        elif "." not in key and "_" not in key and not m.group(1):
            return m.group(0)
        label = label_of(key)
        if label == key:
            return m.group(0)
        return label[0].lower() + label[1:]

    return re.sub(
        r"`([^`=]+?)(?: = \[\.\.\.\])?`|\b([a-z][a-z0-9_]*(?:\.[a-z_]+)+|[a-z]+_[a-z0-9_]+)\b",
        word,
        text,
    )


#: bare key names used in messages, with the key of the form they stand for
SHORT_KEYS: dict[str, str] = {f.path[-1]: f.dotted for f in FIELDS if len(f.path) > 1}
SHORT_KEYS.update(
    {
        "throw_angles": "crank_train.throw_angles",
        "crank_offset": "crank_train.crank_offset",
        "cylinders": "crank_train.cylinders",
    }
)


def form_message(error: InputError) -> str:
    """An InputError in the words of the form: the field's label (``Rod length``), not the
    engine-file key (``crank_train.rod_length``), and other keys in the text as labels."""
    label = label_of(error.field)
    if error.field == label:  # not a key of the engine file: a file name, a setting
        label = error.field
    value = error.value
    if isinstance(value, list):  # a list field as the form writes it: "-10 mm, 10 mm"
        value = _format_value(value)
    shown = "" if value is None else f" = {value if isinstance(value, str) else repr(value)}"
    if len(shown) > 83:
        shown = shown[:80] + "..."
    return f"{label}{shown}: {_words(error.allowed)}"


# --------------------------------------------------------------------------- helpers
def _field_for(dotted: str) -> FormField | None:
    """The form field an InputError's field path points at (the nearest one above it)."""
    path = dotted.replace("[", ".[").split(".")
    while path:
        f = FIELD_BY_PATH.get(".".join(path))
        if f is not None:
            return f
        path = path[:-1]
    return None


#: settings of the page that are a choice among words (the others are checked by the
#: study's options schema, ``polar_order`` by :data:`_POLAR_ORDER`)
SETTING_CHOICES: dict[str, tuple[str, ...]] = {
    "mass_mode": ("parts", "totals"),
    "conrod_split": ("fraction", "cg"),
    "curve_quantity": ("force", "moment"),
}
_POLAR_ORDER = re.compile(r"rotating|[1-9][0-9]?")


def _settings_from_text(text: str) -> dict[str, Any]:
    """The settings line of a saved project, checked as the form checks them; a line that
    does not hold valid settings is refused (it must not load and fail later)."""
    line = next((ln for ln in text.splitlines()[:5] if ln.startswith(SETTINGS_TAG)), None)
    if line is None:
        return {}
    try:
        value = json.loads(line[len(SETTINGS_TAG) :])
    except (ValueError, RecursionError):
        value = None
    if not isinstance(value, dict):
        raise InputError(
            SETTINGS_WHERE,
            line[len(SETTINGS_TAG) :],
            'must be one JSON object on its line, e.g. {"orders": 8}',
        )
    problem = _settings_problem(value)
    if problem:
        raise InputError(SETTINGS_WHERE, None, problem)
    return value


def _settings_problem(settings: dict[str, Any]) -> str | None:
    """The message of the first setting of a saved project that is unknown, not a text or
    a number, or not a valid value (None when all are good)."""
    from .studies import setting_errors  # studies imports this module

    for key, value in settings.items():
        if key not in DEFAULT_SETTINGS:
            allowed = "unknown setting; known: " + ", ".join(DEFAULT_SETTINGS)
        elif isinstance(value, bool) or not isinstance(value, str | int | float):
            allowed = "must be a text or a number"
        elif key in SETTING_CHOICES and value not in SETTING_CHOICES[key]:
            allowed = "must be one of " + ", ".join(SETTING_CHOICES[key])
        elif key == "polar_order" and not _POLAR_ORDER.fullmatch(str(value)):
            allowed = "must be rotating or an order from 1 to 99"
        else:
            continue
        return str(InputError(key, value, allowed))
    errors = setting_errors({k: v for k, v in settings.items() if k not in SETTING_CHOICES})
    return next((str(error) for error in errors.values()), None)


def _pop_path(data: dict[str, Any], path: tuple[str, ...]) -> Any:
    node: Any = data
    for part in path[:-1]:
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    if isinstance(node, dict):
        return node.pop(path[-1], None)
    return None


def _set_path(data: dict[str, Any], path: tuple[str, ...], value: Any) -> None:
    node = data
    for part in path[:-1]:
        node = node.setdefault(part, {})
    node[path[-1]] = value


def _prune(data: dict[str, Any]) -> None:
    """Drop empty tables left after the form's keys were taken out."""
    for key in list(data):
        value = data[key]
        if isinstance(value, dict):
            _prune(value)
            if not value:
                del data[key]
