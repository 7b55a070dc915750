"""Declarative schemas: every input of crankbalance described once.

A schema is a frozen record (a subclass of :class:`Schema`) whose fields are declared
with :func:`field`: the kind of value (a quantity kind of :data:`crankbalance.units.KINDS`
such as ``"length"``, or ``"number"``, ``"whole"``, ``"factor"``, ``"choice"``,
``"text"``, ``"list"``, ``"table"``), its default, its range, its title, description and
form hint. From that one description come

* the validation of an engine file or of a study's settings (:meth:`Schema.parse`): every
  error is one :class:`~crankbalance.errors.InputError` naming the field as the user wrote
  it (``crank_train.rod_length``, ``--max-mass``, a web setting's key), the value, and what
  is allowed; an unknown key anywhere in the input is reported first, with the closest
  allowed key (``did you mean 'rod_length'?``) or the table it belongs in; a decimal comma
  is named as such;
* the words of what a field allows (:func:`allowed`), for help texts and messages;
* the reference tables of ``docs/`` and a published JSON Schema (:func:`json_schema`,
  :mod:`crankbalance.schema.document`), the command-line options and the web form, which
  the edges derive from :attr:`Schema.FIELDS`.

Values come from two kinds of source. A *file* (TOML, JSON, the API's body, Python) has
types: a count must be an integer, a fraction a number, a quantity a string with a unit.
*Text* (the command line, the web form) has only strings: a number is read from its text
and a list from comma-separated values. :meth:`Schema.parse` takes the source.

Quantities are checked after unit conversion. A quantity field with both bounds keeps
them as written (the settings: ``ge``/``le`` from their signed ranges). A quantity field
without bounds, or with only a sign rule (``gt=0``: "must be greater than zero",
``ge=0``: "must not be negative"), is checked in size against the physical range of its
kind (:data:`crankbalance.units.RANGES`, :func:`parse_in_range`: "must lie between 1 um
and 100 m"), zero refused unless ``zero`` or ``ge=0`` (the engine file).

Checks across fields are a schema's :meth:`Schema.check`, which raises
:class:`FieldProblem` naming the field (relative to the schema, or dotted from the root);
the parser turns it into an ``InputError`` naming the field as written, with the value the
user gave. Nothing here imports more than the standard library and
:mod:`crankbalance.units`, so that validating an engine file costs microseconds and
importing the schemas a few milliseconds (docs/performance.md).

The module is over 800 lines because it is the whole machinery (declaring a field,
reading a value, the words of what is allowed, the messages, writing back, the JSON
Schema), whose parts all read the one :class:`Field`; split, the rules of one kind of
value would sit in several files.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Any, ClassVar, Literal, Self, dataclass_transform

from ..errors import InputError
from ..units import KINDS, RANGES, format_quantity, parse_factor, parse_quantity, range_si

Source = Literal["file", "text"]
#: the non-quantity kinds of value a field may take
PLAIN_KINDS = ("number", "whole", "factor", "choice", "text", "flag", "list", "table", "any")
#: longest text of a quantity, a number or a word in a file, in characters (longer is
#: refused unread); typed texts (the command line, a form) are bounded by their edge
MAX_VALUE_CHARS = 100
#: a number written with a decimal comma, alone or before a unit: "1,5" or "1,5 kg"
_DECIMAL_COMMA = re.compile(r"\s*([-+]?\d+),(\d+)(\s*[^\d\s,].*)?\s*")


class _Required:
    """The default of a field that must be given."""

    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()


#: the options of a :class:`Field` with their defaults (see :func:`field`)
_OPTIONS: dict[str, Any] = {
    "default": None,
    "title": "",
    "description": "",
    "hint": "",
    "low": None,
    "high": None,
    "low_open": False,
    "high_open": False,
    "zero": False,
    "choices": (),
    "item": None,
    "table": None,
    "min_items": 0,
    "max_items": None,
    "max_chars": None,
    "words": "",
    "parse": None,
    "example": "",
    "single": False,
    "metavar": "",
}


class Field:
    """The description of one input field (see :func:`field`): a frozen record (a plain
    class, its attributes set at once: the settings schema makes about 340 of them at
    every start of the command line)."""

    kind: str
    default: Any
    title: str
    description: str
    hint: str
    low: float | None
    high: float | None
    low_open: bool
    high_open: bool
    zero: bool
    choices: tuple[Any, ...]
    item: Field | None
    table: type[Schema] | None
    min_items: int
    max_items: int | None
    max_chars: int | None
    words: str
    parse: Callable[[Any, str], Any] | None
    example: str
    single: bool
    #: what a command's help shows after the option when the kind does not say it
    #: (``STIFFNESS [N·m/rad]`` for a setting with a parser of its own); "" for the kind's
    metavar: str
    #: the quantity kind (``"length"``...), or None for a plain kind
    quantity: str | None
    #: a quantity checked in size against the physical range of its kind: no bounds, or
    #: only a sign rule (``gt=0`` or ``ge=0``)
    in_size: bool

    def __init__(self, kind: str, **options: Any) -> None:
        unknown = options.keys() - _OPTIONS.keys()
        if unknown:
            raise TypeError(f"Field has no option {sorted(unknown)[0]}")
        state = self.__dict__
        state.update(_OPTIONS)
        state.update(options)
        quantity = kind if kind in KINDS else None  # read on every value: computed once
        state["kind"] = kind
        state["quantity"] = quantity
        state["in_size"] = quantity is not None and self.high is None and self.low in (None, 0)

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError("Field is frozen: use replace()")

    def replace(self, **changes: Any) -> Field:
        """A copy with ``changes``."""
        return Field(self.kind, **{**{k: getattr(self, k) for k in _OPTIONS}, **changes})

    def __repr__(self) -> str:
        given = [f"{k}={getattr(self, k)!r}" for k, v in _OPTIONS.items() if getattr(self, k) != v]
        return f"Field({', '.join([repr(self.kind), *given])})"

    @property
    def required(self) -> bool:
        return self.default is REQUIRED


def field(
    kind: str,
    *,
    default: Any = REQUIRED,
    title: str = "",
    description: str = "",
    hint: str = "",
    ge: float | None = None,
    gt: float | None = None,
    le: float | None = None,
    lt: float | None = None,
    zero: bool = False,
    choices: Sequence[Any] = (),
    item: Field | None = None,
    table: type[Schema] | None = None,
    min_items: int = 0,
    max_items: int | None = None,
    max_chars: int | None = None,
    words: str = "",
    parse: Callable[[Any, str], Any] | None = None,
    example: str = "",
    single: bool = False,
    metavar: str = "",
) -> Any:
    """Declare a field of a :class:`Schema`.

    Parameters
    ----------
    kind : str
        A quantity kind of :data:`crankbalance.units.KINDS` (the value is a string with a
        unit, stored in SI), or one of :data:`PLAIN_KINDS`: ``number`` (a finite number),
        ``whole`` (an integer), ``factor`` (a number or a percentage ``"28%"``),
        ``choice`` (one of ``choices``), ``text``, ``flag`` (true or false), ``list`` (of
        ``item``), ``table`` (a nested schema ``table``), ``any`` (checked by ``parse``).
    default : optional
        The value when the field is not given; :data:`REQUIRED` (the default) when it must
        be given; a list default is copied for every instance.
    title, description : str
        A label for forms and help, and a sentence of what the field means (the reference
        tables of ``docs/`` and the JSON Schema show both).
    hint : str
        A short text beside a form's input: an example, or what leaving it empty means.
    ge, gt, le, lt : float, optional
        Bounds of a number or a quantity (in SI). A quantity with both bounds keeps them
        as written; a quantity without bounds, or with only ``gt=0`` or ``ge=0`` (a sign
        rule), is checked in size against the physical range of its kind
        (:func:`parse_in_range`), zero refused unless ``zero`` or ``ge=0``.
    zero : bool
        Zero is allowed besides the range (an offset, a bore that may be solid).
    choices : sequence
        The values of a ``choice``.
    item : Field
        The field of each entry of a ``list``.
    table : type
        The schema of a ``table``.
    min_items, max_items : int
        Bounds on the entries of a list (checked before any entry is read).
    max_chars : int
        Longest text.
    words : str
        What the field allows, in words, where the generated words would not say it.
    parse : callable, optional
        ``parse(value, field_name) -> value``: a parser of its own (a value such as
        ``"optimal"`` or a reading); it raises :class:`InputError` for a bad value.
        Explicit bounds still apply to a number it returns. On a ``list`` it reads a text
        given for the whole list (``"0:1:0.1"``) into its entries.
    example : str
        An example of a quantity as typed (default the kind's, ``'40 mm'``).
    single : bool
        A ``list`` that takes a lone value as a list of one (a setting that may be given
        several times: one ``--speed``, or ``"speed": "3000 rpm"`` in a JSON body).
    metavar : str
        What a command's help shows after the option when the kind does not say it
        (``STIFFNESS [N·m/rad]``); empty: the kind's (``LENGTH [mm]``, ``NUMBER``).

    Returns
    -------
    Field
        For the class body of a :class:`Schema`.
    """
    low, low_open = (gt, True) if gt is not None else (ge, False)
    high, high_open = (lt, True) if lt is not None else (le, False)
    if kind not in KINDS and kind not in PLAIN_KINDS:
        raise ValueError(f"unknown field kind {kind!r}")
    return Field(
        kind,
        default=default,
        title=title,
        description=description,
        hint=hint,
        low=low,
        high=high,
        low_open=low_open,
        high_open=high_open,
        zero=zero,
        choices=tuple(choices),
        item=item,
        table=table,
        min_items=min_items,
        max_items=max_items,
        max_chars=max_chars,
        words=words,
        parse=parse,
        example=example,
        single=single,
        metavar=metavar,
    )


def entry(kind: str, **options: Any) -> Field:
    """The field of each entry of a list (the options of :func:`field`, no default)."""
    spec: Field = field(kind, default=None, **options)
    return spec


def three_lengths(
    title: str,
    description: str,
    *,
    default: Any = None,
    hint: str = "x, y, z, e.g. 0 mm, 40 mm, 120 mm",
    **item: Any,
) -> Any:
    """Declare a field of three lengths x, y, z (a point, or a box's edges): a list of
    exactly three entries, each a length with a unit checked in size against the physical
    range of a length; a refusal names the field as written (``--moment-point``,
    ``crank_train.moment_point[2]``).

    Parameters
    ----------
    title, description, hint : str
        As :func:`field`'s.
    default : optional
        None (the field may be left out) unless given; :data:`REQUIRED` when it must be.
    **item
        The options of each entry (:func:`entry`): none for a point (zero or a length of
        either sign), ``gt=0.0`` for a size.

    Returns
    -------
    Field
        For the class body of a :class:`Schema`.
    """
    return field(
        "list",
        default=default,
        item=entry("length", **(item or {"zero": True})),
        min_items=3,
        max_items=3,
        title=title,
        description=description,
        hint=hint,
    )


class FieldProblem(ValueError):
    """A failed check across fields, raised by :meth:`Schema.check`: ``field`` is relative
    to the schema raising it, or dotted from the root when it holds a dot."""

    def __init__(self, field: str, allowed: str) -> None:
        super().__init__(allowed)
        self.field = field
        self.allowed = allowed


#: how a field path is written for the user: the path's parts (names and list indices)
Namer = Callable[[Sequence[str | int]], str]


def dotted(path: Sequence[str | int]) -> str:
    """An engine file's way of naming a key: ``masses.override[2].cylinders``."""
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + _key_text(part)
    return out


def _key_text(key: str) -> str:
    """A key as written in TOML: bare when it can be, else quoted with escapes (a key in a
    message never carries a line break or a control character into the terminal)."""
    if re.fullmatch(r"[A-Za-z0-9_-]+", key):
        return key
    import json

    return json.dumps(key[:MAX_VALUE_CHARS])


@dataclass_transform(kw_only_default=True, frozen_default=True, field_specifiers=(field,))
class Schema:
    """Base of every schema: a frozen, keyword-only record of validated values.

    Subclasses declare fields with :func:`field` and may define :meth:`check` (across
    fields). Create one with :meth:`parse` (from a file's table or a form's texts), copy
    one with :meth:`replace`, write one back with :meth:`to_data` (units) or
    :meth:`values` (SI). The class is no dataclass: generating a dataclass's code costs
    about a millisecond a class, and crankbalance has forty schemas; the same behaviour
    (keyword-only construction, frozen, equality by value) is written here once.
    """

    #: the fields of the schema, name -> :class:`Field`, in declaration order (inherited
    #: fields first)
    FIELDS: ClassVar[dict[str, Field]] = {}
    #: where the format is described (named in "is missing" messages)
    DOC: ClassVar[str] = ""
    #: how an unknown key is called, and how the list of the known ones is introduced
    UNKNOWN: ClassVar[tuple[str, str]] = ("unknown key", "allowed keys here")
    #: the fields holding a table or a list of tables (checked by :meth:`validate`)
    _NESTED: ClassVar[tuple[str, ...]] = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        fields: dict[str, Field] = {}
        for base in reversed(cls.__mro__[1:]):  # inherited fields first, as pydantic
            fields.update(base.__dict__.get("FIELDS", {}))
        for key, spec in list(cls.__dict__.items()):
            if isinstance(spec, Field):
                fields[key] = spec
                delattr(cls, key)
        cls.FIELDS = fields
        cls._NESTED = tuple(
            key
            for key, spec in fields.items()
            if spec.table is not None or (spec.item is not None and spec.item.table is not None)
        )

    def __init__(self, **values: Any) -> None:
        held = self.__dict__  # frozen: __setattr__ refuses, the fields are set here
        held["_given"] = frozenset(values)
        for key, spec in self.FIELDS.items():
            if key in values:
                held[key] = values.pop(key)
            elif spec.required:
                raise TypeError(f"{type(self).__name__} needs {key}")
            else:
                default = spec.default
                held[key] = list(default) if isinstance(default, list) else default
        if values:
            raise TypeError(f"{type(self).__name__} has no field {next(iter(values))}")

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is frozen: use replace({key}=...)")

    def __delattr__(self, key: str) -> None:
        raise AttributeError(f"{type(self).__name__} is frozen")

    def __reduce__(self) -> tuple[Any, ...]:
        values = {key: getattr(self, key) for key in self.FIELDS}
        return (_rebuild, (type(self), values, self.given()))

    def given(self) -> frozenset[str]:
        """The fields that were given (parsed from the input or passed to the constructor),
        as opposed to left at their defaults: a study takes an engine's value where a
        setting was not given, and refuses a given one that would not act."""
        given: frozenset[str] = self.__dict__["_given"]
        return given

    def _values(self) -> tuple[Any, ...]:
        return tuple(map(self.__dict__.__getitem__, self.FIELDS))  # every field is held there

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        assert isinstance(other, Schema)
        return other is self or self._values() == other._values()

    def __hash__(self) -> int:
        # an instance is frozen: its hash is computed once (a spec is the key of the
        # built-model cache, studies.build; hashing it afresh cost 15 us)
        held = self.__dict__
        if "_hash" not in held:
            values = self._values()
            held["_hash"] = hash(tuple(tuple(v) if isinstance(v, list) else v for v in values))
        return int(held["_hash"])

    def __repr__(self) -> str:
        shown = ", ".join(f"{key}={getattr(self, key)!r}" for key in self.FIELDS)
        return f"{type(self).__name__}({shown})"

    def check(self) -> None:
        """Checks across fields; raise :class:`FieldProblem`. Nothing by default."""

    # ----------------------------------------------------------------- construction
    @classmethod
    def parse(
        cls,
        data: Any,
        *,
        source: Source = "file",
        name: Namer = dotted,
        path: tuple[str | int, ...] = (),
    ) -> Self:
        """Validate ``data`` (a mapping of field names to values as written) and return the
        instance; raise :class:`InputError` on the first problem, naming the field with
        ``name(path)``. An unknown key anywhere in ``data`` (nested tables included) is
        the first problem reported.

        Parameters
        ----------
        data : mapping
            Field name -> value as written. A value of None is not given (the default).
        source : {"file", "text"}
            "text": the values are typed strings (command line, web form): numbers and
            lists are read from text. "file": values have their types (TOML, JSON).
        name : callable
            Writes a field's path as the user knows it (default: dotted keys).
        path : tuple
            Where ``data`` sits in the whole input (for nested tables).
        """
        if not isinstance(data, Mapping):
            where = name(path) if path else "input"
            raise InputError(where, type(data).__name__, "must be a table of keys and values")
        if not path:
            stray = _stray_key(cls, data, ())
            if stray is not None:
                raise _unknown_key(cls, *stray, name)
        fields = cls.FIELDS
        values: dict[str, Any] = {}
        for key, spec in fields.items():
            raw = data.get(key)
            if raw is None:
                if spec.required:
                    raise InputError(name((*path, key)), None, _missing(cls))
                continue
            values[key] = _value(spec, raw, source, name, (*path, key))
        instance = cls(**values)
        instance.validate(data, name=name, path=path)
        return instance

    def validate(
        self,
        data: Any = None,
        *,
        name: Namer = dotted,
        path: tuple[str | int, ...] = (),
    ) -> None:
        """Run :meth:`check` (and the checks of nested tables first); a problem is an
        :class:`InputError` naming the field, with its value as written in ``data``."""
        for key in self._NESTED:
            value = getattr(self, key)
            if isinstance(value, Schema):
                sub = data.get(key) if isinstance(data, Mapping) else None
                value.validate(sub, name=name, path=(*path, key))
            elif isinstance(value, list):
                raws = data.get(key) if isinstance(data, Mapping) else None
                for k, item in enumerate(value):
                    sub = raws[k] if isinstance(raws, list) and k < len(raws) else None
                    item.validate(sub, name=name, path=(*path, key, k))
        try:
            self.check()
        except FieldProblem as problem:
            raise _problem(problem, data, name, path) from None

    def replace(self, **changes: Any) -> Self:
        """A copy with ``changes`` (SI values, as the fields hold them), checked again."""
        copy = type(self)(**{**{key: getattr(self, key) for key in self.given()}, **changes})
        kept = {key: getattr(self, key) for key in self.FIELDS if key not in copy.given()}
        copy.__dict__.update(kept)  # the values left at their defaults, still not given
        copy.validate()
        return copy

    # ----------------------------------------------------------------- writing back
    def to_data(self, *, defaults: bool = False) -> dict[str, Any]:
        """The instance as a file's table: quantities as strings with a unit, nested tables
        as dictionaries; None values and (unless ``defaults``) defaults left out."""
        out: dict[str, Any] = {}
        for key, spec in self.FIELDS.items():
            value = getattr(self, key)
            if value is None or (not defaults and not spec.required and value == spec.default):
                continue
            out[key] = _written(spec, value, defaults)
        return out

    def values(self) -> dict[str, Any]:
        """Every field as the instance holds it (SI values), nested schemas as dictionaries:
        the settings as Python sees them (None and defaults included)."""
        return {key: _held(getattr(self, key)) for key in self.FIELDS}

    @classmethod
    def fields(cls) -> Iterator[tuple[str, Field]]:
        """The fields, name and description, in declaration order."""
        return iter(cls.FIELDS.items())


def _rebuild(cls: type[Schema], values: dict[str, Any], given: frozenset[str]) -> Schema:
    """An instance from its values and the fields given, as pickled (checked when it was
    made)."""
    instance = cls(**{key: values[key] for key in given})
    instance.__dict__.update(values)
    return instance


def _held(value: Any) -> Any:
    if isinstance(value, Schema):
        return value.values()
    if isinstance(value, list):
        return [_held(v) for v in value]
    return value


# --------------------------------------------------------------------------- values
def _value(spec: Field, raw: Any, source: Source, name: Namer, path: tuple[str | int, ...]) -> Any:
    """One value as written -> the value the field holds; InputError naming ``path``."""
    if spec.kind == "table":
        assert spec.table is not None
        return spec.table.parse(raw, source=source, name=name, path=path)
    if spec.kind == "list":
        return _list(spec, raw, source, name, path)
    if spec.parse is not None:  # a parser of its own names what it parses: named now
        return _scalar(spec, raw, source, name(path))
    try:  # the field is named when a value is refused (naming costs more than reading)
        return _scalar(spec, raw, source, _HERE)
    except InputError as error:
        if error.field != _HERE:
            raise
        raise InputError(name(path), error.value, error.allowed) from None


def parse_value(spec: Field, raw: Any, where: str, *, source: Source = "text") -> Any:
    """One value of the field ``spec`` as written (a form's text by default) -> the value
    the field holds, checked as :meth:`Schema.parse` checks it (kind, unit, range, list
    size); a refusal is an :class:`InputError` naming ``where`` (a list's entries too).
    Checks across fields are the schema's :meth:`Schema.check`, not made here."""
    return _value(spec, raw, source, lambda _path: where, ())


#: the field of a refusal before it is named (:func:`_value` names it)
_HERE = "\x00field"


def _scalar(spec: Field, raw: Any, source: Source, where: str) -> Any:
    """A value that is neither a table nor a list; a refusal names ``where``."""
    limit = spec.max_chars or (MAX_VALUE_CHARS if source == "file" else None)
    if isinstance(raw, str) and limit is not None and len(raw) > limit:
        if spec.quantity is not None and spec.parse is None:
            raise InputError(where, raw, _TOO_LONG)
        raise InputError(where, f"{len(raw)} characters", f"must be at most {limit} characters")
    if spec.parse is not None:
        value = spec.parse(raw, where)
        if isinstance(value, float) and not spec.in_size:
            _check_bounds(spec, value, raw, where)
        return value
    if spec.quantity is not None:
        value = _quantity(raw, spec.kind, where)
        _check_bounds(spec, value, raw, where)
        return value
    if spec.kind == "number":
        value = _number(spec, raw, source, where)
        _check_bounds(spec, value, raw, where)
        return value
    if spec.kind == "factor":
        _decimal_comma(raw, where)
        value = parse_factor(raw, where)
        _check_bounds(spec, value, raw, where)
        return value
    if spec.kind == "whole":
        value = _whole(spec, raw, source, where)
        _check_bounds(spec, value, raw, where)
        return value
    if spec.kind == "choice":
        return parse_choice(spec, raw, source, where)
    if spec.kind == "text":
        if not isinstance(raw, str):
            raise InputError(where, raw, "must be a text")
        return raw
    if spec.kind == "flag":
        if isinstance(raw, bool):
            return raw
        if source == "text" and isinstance(raw, str) and raw.strip().lower() in _FLAGS:
            return _FLAGS[raw.strip().lower()]
        raise InputError(where, raw, "must be true or false")
    return raw  # "any" without a parser


_FLAGS = {"true": True, "yes": True, "1": True, "false": False, "no": False, "0": False}
_TOO_LONG = f"must be one number and a unit, at most {MAX_VALUE_CHARS} characters"


def _decimal_comma(raw: Any, where: str) -> None:
    """Refuse a number written with a decimal comma, "1,5 kg", saying how to write it."""
    if isinstance(raw, str):
        found = _DECIMAL_COMMA.fullmatch(raw)
        if found is not None:
            fixed = f"{found.group(1)}.{found.group(2)}{found.group(3) or ''}".strip()
            raise InputError(where, raw, f"has a decimal comma; write {fixed!r}")


def _quantity(raw: Any, kind: str, where: str) -> float:
    """A quantity string as an SI float (:func:`crankbalance.units.parse_quantity`)."""
    try:
        return parse_quantity(raw, kind, where)
    except InputError:
        _decimal_comma(raw, where)  # "1,5 kg": said so (looked for only when refused)
        raise


def parse_in_range(value: Any, kind: str, field: str = "") -> float:
    """A quantity string as an SI float, refused unless its size lies in the physical range
    of its kind (:data:`crankbalance.units.RANGES`) or it is zero; strings longer than
    :data:`MAX_VALUE_CHARS` are refused before parsing."""
    if isinstance(value, str) and len(value) > MAX_VALUE_CHARS:
        raise InputError(field, value, _TOO_LONG)
    number = _quantity(value, kind, field)
    _in_range(number, kind, value, field)
    return number


def _in_range(number: float, kind: str, raw: Any, where: str) -> None:
    if kind in RANGES:
        low, high = range_si(kind)
        if abs(number) > high or 0 < abs(number) < low:
            words = RANGES[kind]
            size = " in size" if number < 0 else ""
            raise InputError(where, raw, f"must lie between {words[0]} and {words[1]}{size}")


def _number(spec: Field, raw: Any, source: Source, where: str) -> float:
    if isinstance(raw, bool):
        raise InputError(where, raw, f"must be {allowed(spec)} (not true/false)")
    if isinstance(raw, str):
        _decimal_comma(raw, where)
        if source == "file":
            raise InputError(where, raw, f"must be {allowed(spec)}, written without quotes")
        try:
            raw = float(raw.strip())
        except ValueError:
            raise InputError(where, raw, f"must be {allowed(spec)}") from None
    if not isinstance(raw, (int, float)):
        raise InputError(where, raw, f"must be {allowed(spec)}")
    if not math.isfinite(raw):
        raise InputError(where, raw, f"must be {_finite(allowed(spec))}")
    return raw


def _whole(spec: Field, raw: Any, source: Source, where: str) -> int:
    """A whole number: from a file an integer as written (no true/false, no "4", no 4.0);
    from text also a number with no fraction ("1e3", and 8.0 from a JSON form)."""
    if isinstance(raw, bool):
        raise InputError(where, raw, f"must be {allowed(spec)} (not true/false)")
    if isinstance(raw, int):
        return raw
    if source == "file":
        how = "written without quotes" if isinstance(raw, str) else "without a decimal point"
        raise InputError(where, raw, f"must be {allowed(spec)}, {how}")
    if isinstance(raw, str):
        if re.fullmatch(r"\s*[-+]?\d{1,30}\s*", raw):
            return int(raw)
        try:
            number = float(raw.strip())
        except ValueError:
            raise InputError(where, raw, f"must be {allowed(spec)}") from None
    elif isinstance(raw, float):
        number = raw
    else:
        raise InputError(where, raw, f"must be {allowed(spec)}")
    if not math.isfinite(number):
        raise InputError(where, raw, f"must be {_finite(allowed(spec))}")
    if number != int(number) or abs(number) > 2**53:
        raise InputError(where, raw, f"must be {allowed(spec)}")
    return int(number)


def parse_choice(spec: Field, raw: Any, source: Source, where: str) -> Any:
    """One of ``spec.choices`` (a typed text matched without case); InputError naming ``where``."""
    if isinstance(raw, str) and source == "text" and raw not in spec.choices:
        for choice in spec.choices:  # a typed "4" for the choice 4, "Pattern" for "pattern"
            if str(choice).lower() == raw.strip().lower():
                return choice
    if raw in spec.choices and type(raw) in {type(c) for c in spec.choices}:
        return raw
    shown = ", ".join(str(c) for c in spec.choices)
    close = closest(str(raw), [str(c) for c in spec.choices]) if isinstance(raw, str) else None
    hint = f"; did you mean '{close}'?" if close else ""
    raise InputError(where, raw, f"must be one of {shown}{hint}")


def _list(spec: Field, raw: Any, source: Source, name: Namer, path: tuple[str | int, ...]) -> Any:
    if spec.parse is not None and isinstance(raw, str):  # a text of the whole list
        raw = spec.parse(raw, name(path))
    if spec.single and not isinstance(raw, (list, tuple)):
        raw = [raw]
    if isinstance(raw, str) and source == "text":
        raw = [part.strip() for part in raw.split(",")] if raw.strip() else []
    if not isinstance(raw, (list, tuple)):
        raise InputError(name(path), raw, f"must be a list ({allowed(spec)})")
    exactly = spec.min_items == spec.max_items  # "exactly 3 entries", not "at least 3"
    if spec.max_items is not None and len(raw) > spec.max_items:
        words = f"takes {'exactly' if exactly else 'at most'} {spec.max_items} entries"
        if spec.words:  # a list described in words of its own ("at most 64 files, ...")
            words = f"must be {spec.words}"
        raise InputError(name(path), f"{len(raw)} entries", words)
    if len(raw) < spec.min_items:
        words = f"needs {'exactly' if exactly else 'at least'} {spec.min_items} entries"
        raise InputError(name(path), raw, words)
    assert spec.item is not None
    item_name = name if spec.item.kind == "table" else _item_namer(name, path)
    return [_value(spec.item, v, source, item_name, (*path, k)) for k, v in enumerate(raw)]


def _item_namer(name: Namer, path: tuple[str | int, ...]) -> Namer:
    """Entries of a list of values are named by their list (``--speed``, not ``--speed[1]``)
    on the command line; a file names the entry."""
    if name is dotted:
        return name
    return lambda _path: name(path)


def _check_bounds(spec: Field, value: float, raw: Any, where: str) -> None:
    if spec.in_size:
        _in_range(value, spec.kind, raw, where)  # an infinity too: "must lie between"
    if not math.isfinite(value):
        raise InputError(where, raw, f"must be {_finite(allowed(spec))}")
    if spec.zero and value == 0:
        return
    if spec.in_size:
        if spec.low is None:
            if value == 0 and spec.kind in RANGES and range_si(spec.kind)[0] > 0:
                raise InputError(where, raw, f"must be {allowed(spec)}")
        elif spec.low_open and value <= 0:
            raise InputError(where, raw, "must be greater than zero")
        elif value < 0:
            raise InputError(where, raw, "must not be negative")
        return
    if spec.low is not None and (value < spec.low or (spec.low_open and value == spec.low)):
        raise InputError(where, raw, f"must be {allowed(spec)}")
    if spec.high is not None and (value > spec.high or (spec.high_open and value == spec.high)):
        raise InputError(where, raw, f"must be {allowed(spec)}")


# --------------------------------------------------------------------------- words
#: significant digits of a limit in its display unit: a limit that needs more is rounded
#: to this many, outward (a lower limit up, an upper one down) so the words stay true
#: (0.001 rad reads "0.0573 deg", not "0.0572958 deg")
LIMIT_DIGITS = 4


def _show(spec: Field, value: float, side: int = 0) -> str:
    """A limit as written in a hint; ``side`` -1 for a lower limit, +1 for an upper one."""
    if spec.quantity is None:
        return str(value) if isinstance(value, int) else f"{value:g}"
    exact = format_quantity(float(value), spec.kind, digits=6)
    shown, unit = exact.split(" ", 1)
    x = float(shown)
    if x == 0 or float(f"{x:.{LIMIT_DIGITS}g}") == x:
        return exact
    step = 10.0 ** (math.floor(math.log10(abs(x))) - LIMIT_DIGITS + 1)
    rounded = {-1: math.ceil, 1: math.floor}.get(side, round)(x / step) * step
    return f"{rounded:.{LIMIT_DIGITS}g} {unit}"


def allowed(spec: Field) -> str:
    """What a field accepts, in words ("a length with a unit, e.g. '40 mm', from 0.001 mm to
    100000 mm", "a whole number from 16 to 100000", "one of pattern, individual")."""
    if spec.words:
        return spec.words
    if spec.kind == "list":
        assert spec.item is not None
        count = (
            f"at least {spec.min_items}"
            if spec.max_items is None
            else str(spec.min_items)
            if spec.min_items == spec.max_items
            else f"{spec.min_items} to {spec.max_items}"
        )
        what = "entries" if spec.item.kind == "table" else "values"
        return f"{count} {what}, each {allowed(spec.item)}"
    if spec.kind == "table":
        return "a table (see the documentation)"
    if spec.kind == "choice":
        return "one of " + ", ".join(str(c) for c in spec.choices)
    if spec.kind == "text":
        return "a text" + (f" of at most {spec.max_chars} characters" if spec.max_chars else "")
    if spec.kind == "flag":
        return "true or false"
    if spec.quantity is not None:
        example = spec.example or KINDS[spec.kind][2]
        article = "an" if spec.kind[0] in "aeiou" else "a"
        kind = spec.kind.replace("_", " ")  # the kind in words: "a specific energy"
        what = f"{article} {kind} with a unit, e.g. '{example}',"
        if spec.in_size:
            return _in_size_words(spec, what)
    else:
        what = {"whole": "a whole number", "factor": "a number or a percentage"}.get(
            spec.kind, "a number"
        )
    words = _between(spec, what)
    return ("0, or " if spec.zero else "") + words


def _in_size_words(spec: Field, what: str) -> str:
    """The words of a quantity checked in size against its physical range."""
    if spec.kind not in RANGES:
        return what.rstrip(",")
    low, high = RANGES[spec.kind]
    from_zero = range_si(spec.kind)[0] == 0  # zero is inside the range: no "0, or"
    span = f"at most {high}" if from_zero else f"from {low} to {high}"
    zero = "0, or " if not from_zero else ""
    if spec.low is not None:  # a sign rule
        return (zero if not spec.low_open or spec.zero else "") + f"{what} {span}"
    return (zero if spec.zero else "") + f"{what} of either sign, {span} in size"


def _between(spec: Field, what: str) -> str:
    low, high = spec.low, spec.high
    if low is not None and high is not None and not spec.low_open and not spec.high_open:
        return f"{what} from {_show(spec, low, -1)} to {_show(spec, high, 1)}"
    parts = []
    if low is not None:
        parts.append(f"{'greater than' if spec.low_open else 'at least'} {_show(spec, low, -1)}")
    if high is not None:
        parts.append(f"{'less than' if spec.high_open else 'at most'} {_show(spec, high, 1)}")
    return what.rstrip(",") + (", " + " and ".join(parts) if parts else "")


def _finite(text: str) -> str:
    found = re.match(r"(?:0, or )?an? (.*)", text)
    return f"a finite {found.group(1)}" if found else f"{text} (a finite number)"


def default_text(spec: Field) -> str:
    """A field's default as a user would type it ("" for none or a required field)."""
    value = spec.default
    if value is None or value is REQUIRED:
        return ""
    if spec.quantity is not None and isinstance(value, (int, float)):
        return format_quantity(float(value), spec.kind, digits=6)
    if isinstance(value, list):
        item = spec.item or spec
        return ", ".join(default_text(item.replace(default=v)) for v in value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def _written(spec: Field, value: Any, defaults: bool) -> Any:
    if isinstance(value, Schema):
        return value.to_data(defaults=defaults)
    if isinstance(value, list):
        item = spec.item or spec
        return [_written(item, v, defaults) for v in value]
    if (
        spec.quantity is not None
        and isinstance(value, (int, float))
        and not isinstance(value, bool)
    ):
        return format_quantity(float(value), spec.kind)
    return value


# --------------------------------------------------------------------------- messages
def closest(word: str, candidates: Sequence[str]) -> str | None:
    """The candidate closest to a misspelt ``word`` (None when none is close)."""
    import difflib

    found = difflib.get_close_matches(word[:MAX_VALUE_CHARS], candidates, n=1, cutoff=0.6)
    return found[0] if found else None


def _stray_key(
    cls: type[Schema], data: Mapping[Any, Any], path: tuple[str | int, ...]
) -> tuple[type[Schema], tuple[str | int, ...], Any, Any] | None:
    """The first unknown key of ``data`` and of its nested tables (lists of tables up to
    their cap), as (schema, path of its table, key, value), or None."""
    fields = cls.FIELDS
    for key in data:
        if key not in fields:
            return cls, path, key, data[key]
    for key in cls._NESTED:
        value = data.get(key)
        spec = fields[key]
        found = None
        if spec.table is not None and isinstance(value, Mapping):
            found = _stray_key(spec.table, value, (*path, key))
        elif spec.item is not None and spec.item.table is not None and isinstance(value, list):
            for k, item in enumerate(value[: spec.max_items]):
                if found is None and isinstance(item, Mapping):
                    found = _stray_key(spec.item.table, item, (*path, key, k))
        if found is not None:
            return found
    return None


def _tables(cls: type[Schema], path: tuple[str, ...] = ()) -> Iterator[tuple[str, type[Schema]]]:
    """Every table of a schema, as its TOML header (``[crank_train]``,
    ``[[masses.override]]``; the top level as "")."""
    for key, spec in cls.FIELDS.items():
        if spec.table is not None:
            yield f"[{'.'.join((*path, key))}]", spec.table
            yield from _tables(spec.table, (*path, key))
        elif spec.item is not None and spec.item.table is not None:
            yield f"[[{'.'.join((*path, key))}]]", spec.item.table
            yield from _tables(spec.item.table, (*path, key))


def _unknown_key(
    root: type[Schema],
    cls: type[Schema],
    path: tuple[str | int, ...],
    key: Any,
    value: Any,
    name: Namer,
) -> InputError:
    """An unknown key named with the closest allowed key of its table or, when it is a key
    of another table, with that table."""
    where = name((*path, str(key)))
    value = None if isinstance(value, Mapping) else value  # a table: its name alone
    unknown, listed = cls.UNKNOWN
    close = closest(str(key), list(cls.FIELDS))
    if close is not None:
        return InputError(where, value, f"{unknown}; did you mean '{close}'?")
    homes = [header for header, table in (("", root), *_tables(root)) if key in table.FIELDS]
    if homes:
        home = f"in {homes[0]}" if homes[0] else "at the top level, before any [table]"
        return InputError(where, value, f"{unknown} here; {key} belongs {home}")
    known = ", ".join(cls.FIELDS)
    return InputError(where, value, f"{unknown}; {listed}: {known}")


def _missing(cls: type[Schema]) -> str:
    doc = f" (see {cls.DOC})" if cls.DOC else ""
    return f"is missing; it is required{doc}"


def _problem(
    problem: FieldProblem, data: Any, name: Namer, path: tuple[str | int, ...]
) -> InputError:
    parts: list[str | int] = []
    for piece in problem.field.split("."):
        found = re.fullmatch(r"([^\[]+)((\[\d+\])*)", piece)
        if found is None:
            parts.append(piece)
            continue
        parts.append(found.group(1))
        parts += [int(i) for i in re.findall(r"\[(\d+)\]", found.group(2))]
    full = tuple(parts) if "." in problem.field else (*path, *parts)
    relative = full[len(path) :] if full[: len(path)] == path else full
    return InputError(name(full), _lookup(data, relative), problem.allowed)


def _lookup(data: Any, path: Sequence[str | int]) -> Any:
    for part in path:
        if isinstance(data, Mapping) and part in data:
            data = data[part]
        elif isinstance(data, list) and isinstance(part, int) and part < len(data):
            data = data[part]
        else:
            return None
    return "{...}" if isinstance(data, Mapping) else data


# --------------------------------------------------------------------------- JSON Schema
def json_schema(cls: type[Schema], *, title: str = "") -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of a schema's file form: quantities are strings
    with a unit, described with their range in words; unknown keys are not allowed."""
    properties = {key: _json_field(spec) for key, spec in cls.FIELDS.items()}
    out: dict[str, Any] = {
        "type": "object",
        "properties": properties,
        "additionalProperties": False,
    }
    if title:
        out = {"$schema": "https://json-schema.org/draft/2020-12/schema", "title": title, **out}
    required = [key for key, spec in cls.FIELDS.items() if spec.required]
    if required:
        out["required"] = required
    if cls.__doc__:
        out["description"] = " ".join(cls.__doc__.split("\n\n")[0].split())
    return out


def _json_field(spec: Field) -> dict[str, Any]:
    if spec.kind == "table":
        assert spec.table is not None
        out = json_schema(spec.table)
    elif spec.kind == "list":
        assert spec.item is not None
        out = {"type": "array", "items": _json_field(spec.item)}
        if spec.min_items:
            out["minItems"] = spec.min_items
        if spec.max_items is not None:
            out["maxItems"] = spec.max_items
    elif spec.kind == "choice":
        out = {"enum": list(spec.choices)}
    elif spec.quantity is not None:
        out = {"type": "string", "examples": [spec.example or KINDS[spec.kind][2]]}
        if spec.max_chars is None:
            out["maxLength"] = MAX_VALUE_CHARS
    elif spec.kind in ("number", "whole"):
        out = {"type": "integer" if spec.kind == "whole" else "number"}
        for key, bound, is_open in (
            ("minimum", spec.low, spec.low_open),
            ("maximum", spec.high, spec.high_open),
        ):
            if bound is not None:
                out[("exclusiveM" + key[1:]) if is_open else key] = bound
    elif spec.kind == "factor":
        out = {"type": ["number", "string"]}
    elif spec.kind == "text":
        out = {"type": "string"}
        if spec.max_chars:
            out["maxLength"] = spec.max_chars
    elif spec.kind == "flag":
        out = {"type": "boolean"}
    else:
        out = {}
    if spec.title:
        out["title"] = spec.title
    words = allowed(spec) if spec.kind not in ("table",) else ""
    description = " ".join(
        t for t in (spec.description, f"Allowed: {words}." if words else "") if t
    )
    if description:
        out["description"] = description
    if spec.default is not REQUIRED and spec.default is not None and spec.kind != "table":
        out["default"] = _written(spec, spec.default, True)
    return out
