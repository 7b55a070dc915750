"""The engine form of the web page, derived from the engine file's schema.

Every form field is bound to one key path of the engine file (``docs/engine_file.md``)
and takes from that key's :class:`~crankbalance.schema.core.Field` everything the schema
knows: the label is the field's title, the hint its hint, the options of a choice its
choices (the schema's default first), and a value is checked by the schema's own parse of
a typed text (:func:`~crankbalance.schema.core.parse_value`, source ``"text"``), so the
form refuses exactly what an engine file refuses, in the schema's words. What the schema
does not know stays here: which card a field sits in (:data:`ENGINE_FIELDS` ...), which
fields show for which layout and mass mode (``group``, ``layouts``), the form's own
choices (no shaft set, a maker's numbering scheme) and how a message names a field (by its
label, :func:`form_message`).

Nothing here imports NiceGUI.
"""

from __future__ import annotations

import re
from typing import Any, Literal

from ..errors import InputError
from ..physics.firing import SCHEMES
from ..records import record
from ..schema.core import Field, Schema, default_text, parse_value
from ..schema.engine import EngineSpec

#: how the form shows and the tests exercise a field: an input of text, a quantity, a
#: list, a number, a select of ``options``, an angle or the word "optimal"
Kind = Literal[
    "text", "quantity", "quantitylist", "int", "float", "intlist", "choice", "angle_or_optimal"
]
#: the choice of the shaft fields that leaves the shaft set out of the engine file
NO_SHAFTS = "none"


def schema_field(path: tuple[str, ...]) -> Field:
    """The schema's field of an engine-file key path (``("crank_train", "rod_length")``);
    the tables of a list of tables are walked into (``("masses", "override", "cylinders")``),
    ``"[]"`` is an entry of a list (``("crank_train", "throw_angles", "[]")``)."""
    table: type[Schema] | None = EngineSpec
    spec: Field | None = None
    for part in path:
        if part == "[]":  # an entry of the list
            assert spec is not None and spec.item is not None, path
            spec = spec.item
            continue
        assert table is not None, path
        spec = table.FIELDS[part]
        table = spec.table or (spec.item.table if spec.item is not None else None)
    assert spec is not None
    return spec


def _kind(spec: Field) -> Kind:
    """The form's kind of a schema field."""
    if spec.parse is not None:  # a quantity with a word of its own: the counterweight angle
        return "angle_or_optimal"
    if spec.kind == "list":
        assert spec.item is not None
        return "quantitylist" if spec.item.quantity is not None else "intlist"
    if spec.quantity is not None:
        return "quantity"
    kinds: dict[str, Kind] = {"whole": "int", "number": "float", "choice": "choice"}
    return kinds.get(spec.kind, "text")


@record
class FormField:
    """One input of the form, bound to ``path`` in the engine file; label, hint, kind and
    options come from the schema's field :attr:`spec` (:func:`form_field`)."""

    key: str
    path: tuple[str, ...]
    spec: Field
    label: str
    kind: Kind
    options: tuple[str, ...] = ()
    hint: str = ""
    group: str = ""  # "parts", "totals", "fraction", "cg", "primary", "secondary", ...
    #: layouts the field means something for (empty: all); shown for the others only
    #: while it holds a value, so that a value is never dropped unseen
    layouts: tuple[str, ...] = ()

    @property
    def dotted(self) -> str:
        return ".".join(self.path)

    @property
    def default(self) -> str:
        """The schema's default as typed ("" when there is none)."""
        return default_text(self.spec)

    def check(self, text: str) -> Any:
        """The value of a typed text, checked by the schema (kind, unit, range, entries);
        an :class:`InputError` names the engine-file key (:attr:`dotted`)."""
        return parse_value(self.spec, text.strip(), self.dotted)


def form_field(
    key: str,
    path: tuple[str, ...],
    *,
    group: str = "",
    layouts: tuple[str, ...] = (),
    options: tuple[str, ...] | None = None,
    label: str = "",
) -> FormField:
    """The form field of the key ``path``: the schema's title, hint and choices (the default
    first), unless the form gives its own ``options`` or ``label``."""
    spec = schema_field(path)
    if options is None and spec.kind == "choice":
        default = default_text(spec)
        options = tuple(sorted((str(c) for c in spec.choices), key=lambda c: c != default))
    kind: Kind = "choice" if options else _kind(spec)
    return FormField(
        key, path, spec, label or spec.title, kind, options or (), spec.hint, group, layouts
    )


def _shaft(which: str, name: str) -> FormField:
    """A field of the primary or secondary shaft set, named with its set ("Primary shaft
    CG radius" from the schema's "Shaft CG radius"); no set is a choice of the form."""
    spec = schema_field(("balance_shafts", which, name))
    label = f"{which.capitalize()} {spec.title[0].lower()}{spec.title[1:]}"
    options = (NO_SHAFTS, *(str(c) for c in spec.choices)) if spec.kind == "choice" else None
    path = ("balance_shafts", which, name)
    return form_field(f"{which}_{name}", path, group=which, options=options, label=label)


_F = form_field
ENGINE_FIELDS: tuple[FormField, ...] = (
    _F("name", ("name",)),
    _F("layout", ("crank_train", "layout")),
    _F("cylinders", ("crank_train", "cylinders")),
    _F("firing_order", ("crank_train", "firing_order")),
    _F("strokes", ("crank_train", "strokes")),
    _F("bank_angle", ("crank_train", "bank_angle")),
    _F("crank_pitch", ("crank_train", "crank_pitch")),
    _F("crank_radius", ("crank_train", "crank_radius")),
    _F("rod_length", ("crank_train", "rod_length")),
    _F("pin_offset", ("crank_train", "pin_offset")),
    _F("speed", ("speed",)),
    _F("kinematics", ("kinematics",)),
)
BALANCING_FIELDS: tuple[FormField, ...] = (
    _F("cw_webs", ("counterweights", "webs"), group="cw"),
    _F("cw_cg_radius", ("counterweights", "cg_radius"), group="cw"),
    _F("cw_angle", ("counterweights", "angle"), group="cw"),
    _F("cw_balance_factor", ("counterweights", "balance_factor"), group="cw"),
    _F("cw_method", ("counterweights", "method"), group="cw"),
    *(
        _shaft(which, name)
        for which in ("primary", "secondary")
        for name in ("arrangement", "cg_radius", "length")
    ),
)
#: the crank train's details beyond the general fields: offsets per bank or cylinder, rod
#: positions on shared pins, the moment reference and a radial's master-and-link rods
DETAIL_FIELDS: tuple[FormField, ...] = (
    _F("w_type", ("crank_train", "w_type"), layouts=("w",)),
    _F("vr_angle", ("crank_train", "vr_angle"), group="w-vr", layouts=("w",)),
    _F("bore_offset", ("crank_train", "bore_offset"), group="vr-rows", layouts=("vr", "w")),
    _F("pin_split", ("crank_train", "pin_split"), group="split", layouts=("vr", "w", "vee")),
    # the schema takes any scheme's name as text; the form offers the schemes there are
    _F("numbering", ("crank_train", "numbering"), options=tuple(SCHEMES), layouts=("vee", "boxer")),
    _F("maker_numbers", ("crank_train", "maker_numbers")),
    _F(
        "bank_offsets",
        ("crank_train", "bank_offsets"),
        layouts=("vee", "boxer", "w"),
        group="banks",
    ),
    _F("cylinder_offsets", ("crank_train", "cylinder_offsets")),
    _F(
        "rod_positions",
        ("crank_train", "rod_positions"),
        layouts=("vee", "boxer", "w", "radial", "custom"),
    ),
    _F("moment_reference", ("crank_train", "moment_reference")),
    *(
        _F(name, ("crank_train", "articulated", name), group="articulated", layouts=("radial",))
        for name in ("master_cylinder", "link_pin_radius", "link_rod_length", "link_pin_angles")
    ),
)
MASS_FIELDS: tuple[FormField, ...] = (
    *(_F(name, ("masses", name), group="parts") for name in ("piston", "wrist_pin", "conrod")),
    _F("conrod_rotating_fraction", ("masses", "conrod_rotating_fraction"), group="fraction"),
    _F("conrod_cg_from_big_end", ("masses", "conrod_cg_from_big_end"), group="cg"),
    *(
        _F(name, ("masses", name), group="parts")
        for name in ("conrod_inertia", "crankpin", "crank_web", "crank_web_cg_radius")
    ),
    *(_F(name, ("masses", name), group="totals") for name in ("reciprocating", "rotating")),
)
FIELDS: tuple[FormField, ...] = ENGINE_FIELDS + DETAIL_FIELDS + BALANCING_FIELDS + MASS_FIELDS
FIELD_BY_KEY: dict[str, FormField] = {f.key: f for f in FIELDS}
FIELD_BY_PATH: dict[str, FormField] = {f.dotted: f for f in FIELDS}
#: the text a select shows for a key the engine file leaves out: the schema's default of a
#: choice, no shaft set
DEFAULTS: dict[str, str] = {
    f.key: NO_SHAFTS if f.options[0] == NO_SHAFTS else f.default
    for f in FIELDS
    if f.kind == "choice" and (f.default or f.options[0] == NO_SHAFTS)
}
#: the numbers of a mass override (the cylinders or throws it applies to)
OVERRIDE_NUMBERS = schema_field(("masses", "override", "cylinders"))
#: an angle of the crank editor's throw angles
THROW_ANGLE: Field = schema_field(("crank_train", "throw_angles", "[]"))
#: a throw of the crank editor: position and angle, the bank angles of its cylinders
THROWS = tuple(
    (part, schema_field(("crank_train", "throw", part))) for part in ("position", "angle", "banks")
)


def format_value(value: Any) -> str:
    """A value of the engine file as the form shows it (a list as "1, 3, 2")."""
    if isinstance(value, list):
        return ", ".join(str(v) for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


# --------------------------------------------------------------------------- messages
_CELL = re.compile(
    r"crank_train\.(throw_angles)\[(\d+)\]|crank_train\.(throw)\[(\d+)\]\.?(\w*)"
    r"|masses\.(override)\[(\d+)\]\.?(\w*)"
)
#: the tables the crank editor shows (their keys have no field of their own in the form)
EDITOR_KEYS = ("crank_train.throw_angles", "crank_train.throw", "masses.override")


def cell_for(dotted: str) -> str | None:
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


def field_for(dotted: str) -> FormField | None:
    """The form field an InputError's field path points at (the nearest one above it)."""
    path = dotted.replace("[", ".[").split(".")
    while path:
        f = FIELD_BY_PATH.get(".".join(path))
        if f is not None:
            return f
        path = path[:-1]
    return None


def _title_of(dotted: str) -> str | None:
    """The schema's title of an engine-file key without a form field ("Crank offset"), the
    crank editor's tables said so; None for no key of the engine file."""
    try:
        spec = schema_field(tuple(dotted.split(".")))
    except (KeyError, AssertionError):
        return None
    if spec.kind == "table" and "." not in dotted:  # a whole table: named by its key
        return None
    return f"{spec.title} (crank editor)" if dotted in EDITOR_KEYS else spec.title or None


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
    f = field_for(dotted)
    if f is not None and f.dotted == dotted:
        return f.label
    return _title_of(dotted) or (dotted if f is None else f.label)


def key_label(key: str) -> str:
    """The words of the form for a key of its errors: a field's label, a crank-editor cell
    (``override.0.value``) in words."""
    f = FIELD_BY_KEY.get(key)
    return label_of(key) if f is None else f.label


#: bare key names used in messages, with the key of the form they stand for
SHORT_KEYS: dict[str, str] = {f.path[-1]: f.dotted for f in FIELDS if len(f.path) > 1}
SHORT_KEYS.update(
    {
        "throw_angles": "crank_train.throw_angles",
        "crank_offset": "crank_train.crank_offset",
        "cylinders": "crank_train.cylinders",
    }
)


def words(text: str) -> str:
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


def form_message(error: InputError) -> str:
    """An InputError in the words of the form: the field's label (``Rod length``), not the
    engine-file key (``crank_train.rod_length``), and other keys in the text as labels."""
    label = label_of(error.field)
    if error.field == label:  # not a key of the engine file: a file name, a setting
        label = error.field
    value = error.value
    if isinstance(value, list):  # a list field as the form writes it: "-10 mm, 10 mm"
        value = format_value(value)
    shown = "" if value is None else f" = {value if isinstance(value, str) else repr(value)}"
    if len(shown) > 83:
        shown = shown[:80] + "..."
    return f"{label}{shown}: {words(error.allowed)}"
