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
import re
import time
from dataclasses import dataclass, field
from typing import Any

from ..errors import InputError
from ..schema.core import Field, default_text, parse_value
from ..schema.engine import EngineSpec
from .computation import Computed
from .form import (
    DEFAULTS,
    FIELD_BY_KEY,
    FIELDS,
    NO_SHAFTS,
    OVERRIDE_NUMBERS,
    THROW_ANGLE,
    THROWS,
    FormField,
    cell_for,
    field_for,
    form_message,
    format_value,
)
from .studies import PREFIXES, setting_errors

SETTINGS_TAG = "# crankbalance-web settings: "
SETTINGS_WHERE = "crankbalance-web settings"  # the settings line, as its tag names it
#: largest engine file or project the web page and the API take [bytes]: an engine file is
#: a few kB (the largest preset well under 1 kB, a 64-throw custom engine under 10 kB)
MAX_BYTES = 65_536
log = logging.getLogger("crankbalance.web")

#: the study settings the tabs show, each its study's prefix and the schema field's name
#: (:data:`.studies.PREFIXES`: ``cw_density`` is ``density`` of ``CounterweightOptions``)
STUDY_SETTINGS = (
    "orders",
    # counterweight design
    *("cw_density", "cw_max_mass", "cw_max_radius", "cw_min_balance"),
    *("cw_iterations", "cw_population", "cw_seed"),
    # single cylinder and its rebalancing
    *("sc_cylinder", "sc_balance_factor", "sc_grade", "sc_rotor_mass", "sc_residual"),
    *("rb_new_reciprocating", "rb_new_rotating", "rb_cw_mass", "rb_cw_radius"),
    *("rb_hole_diameter", "rb_point_angle", "rb_depth_to", "rb_holes", "rb_hole_radius"),
    # balance shaft
    *("bs_length", "bs_diameter", "bs_weight", "bs_points"),
    # performance
    *("pf_bore", "pf_balance_factors", "pf_crank_inertia", "pf_friction_coefficient"),
    "pf_journal_diameter",
)


def _schema_default(key: str) -> str:
    """The schema's default of a study setting, as typed ("" for none)."""
    prefix = max((p for p in PREFIXES if key.startswith(p)), key=len)
    return default_text(PREFIXES[prefix].FIELDS[key[len(prefix) :]])


#: settings of the page and the study tabs (saved with the project as a comment line of
#: the engine file): the page's own modes, then every study setting with its schema's
#: default (no edge decides a default: the page starts where the command line does)
DEFAULT_SETTINGS: dict[str, Any] = {
    "mass_mode": "parts",  # parts | totals
    "conrod_split": "cg",  # fraction | cg
    "curve_quantity": "force",
    "polar_order": 1,
    **{key: _schema_default(key) for key in STUDY_SETTINGS},
}


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
    #: the engine as loaded (:meth:`engine_state`), to tell whether it was edited since
    loaded_state: str = ""

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
                texts[f.key] = format_value(value)
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
            if table is not None and texts.get(f"{name}_arrangement") == NO_SHAFTS:
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
                "numbers": format_value(item.get("cylinders", item.get("throws", []))),
                "mass": key,
                "value": format_value(value),
            }
            for item in overrides
            for key, value in item.items()
            if key not in ("cylinders", "throws")
        ]
        self.validate()
        self.loaded_state = self.engine_state()

    def engine_state(self) -> str:
        """What describes the engine in the form (its engine-file dictionary as the form
        would write it, without the description), as one text to compare."""
        data, errors = self.file_dict()
        data.pop("description", None)
        return json.dumps([data, errors], sort_keys=True, default=str)

    def saved_spec(self) -> EngineSpec:
        """The engine as saved: only what describes the current engine. The description of
        the engine as loaded (a preset's, a file's) is dropped once the engine was edited:
        the page cannot tell whether its words still hold (docs/web.md)."""
        if self.spec is None:
            raise InputError(
                "project", None, "has errors; correct the fields marked in red before saving"
            )
        if not self.spec.description or self.engine_state() == self.loaded_state:
            return self.spec
        return self.spec.replace(description="")

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
            return self.texts.get(f"{f.group}_arrangement", NO_SHAFTS) != NO_SHAFTS
        return True

    def _means_something(self, f: FormField) -> bool:
        """Whether a detail field means something for the layout (and W type) in the form:
        the VR rows' fields for layout vr and a W from VR banks (the pin split for a vee
        too), the VR angle for the latter."""
        layout = self.texts.get("layout")
        w_vr = layout == "w" and self.texts.get("w_type") == "vr"
        if f.group == "w-vr":
            return w_vr
        if f.group == "vr-rows":
            return layout == "vr" or w_vr
        if f.group == "split":  # VR rows' pins, or a vee's throws split into two pins
            return layout in ("vr", "vee") or w_vr
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
            if (f.key.endswith("_arrangement") and text == NO_SHAFTS) or (
                f.key == "cw_method" and text == f.default
            ):
                continue  # no shaft set / the default method needs no counterweight table
            try:
                f.check(text)
            except InputError as error:
                errors[f.key] = self.message(error)
                continue
            _set_path(data, f.path, text)
        self._editor_dict(data, errors)
        return data, errors

    def _editor_dict(self, data: dict[str, Any], errors: dict[str, str]) -> None:
        """Put the crank editor's tables into the engine-file dictionary ``data``; the
        errors of single cells go to ``errors`` under the cell's key (``throw.2.banks``)."""

        def cell(spec: Field, text: str, key: str) -> str:
            try:
                parse_value(spec, text.strip(), key)
            except InputError as error:
                errors[key] = self.message(error)
            return text.strip()

        custom = self.texts.get("layout") == "custom"
        if self.throw_angles is not None and not custom:
            angles = [
                cell(THROW_ANGLE, a, f"throw_angles.{k}") for k, a in enumerate(self.throw_angles)
            ]
            _set_path(data, ("crank_train", "throw_angles"), angles)
        if custom and self.throws:
            throws = [
                {part: cell(spec, row[part], f"throw.{k}.{part}") for part, spec in THROWS}
                for k, row in enumerate(self.throws)
            ]
            _set_path(data, ("crank_train", "throw"), throws)
        items = []
        for k, row in enumerate(self.overrides):
            where = f"override.{k}.numbers"
            try:
                targets = parse_value(OVERRIDE_NUMBERS, row["numbers"].strip(), where)
                FIELD_BY_KEY[row["mass"]].check(row["value"])
            except InputError as error:
                part = "numbers" if error.field == where else "value"
                errors[f"override.{k}.{part}"] = self.message(error)
                continue
            items.append({row["target"]: targets, row["mass"]: row["value"].strip()})
        if self.overrides:
            _set_path(data, ("masses", "override"), items)

    def validate(self) -> dict[str, str]:
        """Check every field, then the whole engine through the spec model."""
        data, errors = self.file_dict()
        self.general_error = ""
        self.spec = None
        if not errors:
            try:
                self.spec = EngineSpec.parse(data, source="text")
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
            radius = FIELD_BY_KEY["crank_radius"].check(self.texts.get("crank_radius", ""))
        except InputError:
            return None
        return f"{round(CW_CG_SHARE * radius * 1e3, 2):g} mm" if radius > 0 else None

    def message(self, error: InputError) -> str:
        """``error`` in the words of the form (see :func:`form_message`)."""
        return form_message(error)

    def key_for(self, dotted: str) -> str | None:
        """The key of the form field or crank-editor cell an InputError's field belongs to."""
        cell = cell_for(dotted)
        if cell is not None:
            return cell
        f = self.field_for(dotted)
        return None if f is None else f.key

    def field_for(self, dotted: str) -> FormField | None:
        """The visible form field an InputError belongs to (None: a general message)."""
        f = field_for(dotted)
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
        """The project as an engine file (its settings in a comment line the CLI ignores):
        :meth:`saved_spec`."""
        from ..io.engine_file import engine_to_toml

        spec = self.saved_spec()
        settings = json.dumps(self.settings, separators=(",", ":"), sort_keys=True)
        return f"{SETTINGS_TAG}{settings}\n" + engine_to_toml(spec)

    def to_json(self) -> str:
        return json.dumps(self.saved_spec().to_data(), indent=2) + "\n"


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
