"""Quantity strings at the edges: ``"40 mm"`` -> 0.04 (SI float), and back for display.

Physics modules never import this module; they work in SI floats. The units engine files
use are read from a small table (every entry checked against pint by tests/test_units.py);
pint is imported only for any other unit, so that reading an engine file takes microseconds
and the command line starts fast (docs/performance.md).
"""

from __future__ import annotations

import math
import re
from functools import cache, lru_cache
from typing import Any

from .errors import InputError

# one number, then a unit expression whose only digits are exponents ("kg*m^2", "m**3")
_QUANTITY = re.compile(
    r"^\s*(?P<number>[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?)\s*"
    r"(?P<unit>[A-Za-z°µμ%][A-Za-z°µμ%·⋅²³_/*^.\s\d()-]*)?$"
)
_EXPONENT = re.compile(r"(\^|\*\*)\s*\(?-?\d+(\.\d+)?\)?")

# kind -> (SI unit pint understands, unit used when writing a value back, example)
KINDS: dict[str, tuple[str, str, str]] = {
    "length": ("m", "mm", "40 mm"),
    "area": ("m**2", "mm**2", "2000 mm^2"),
    "mass": ("kg", "g", "500 g"),
    "angle": ("rad", "deg", "30 deg"),
    "speed": ("rad/s", "rpm", "2000 rpm"),
    "inertia": ("kg*m**2", "kg*m**2", "0.002 kg*m^2"),
    "density": ("kg/m**3", "kg/m**3", "7850 kg/m^3"),
    "pressure": ("Pa", "bar", "50 bar"),
    "force": ("N", "N", "1000 N"),
    "torque": ("N*m", "N*m", "1.5 N*m"),
    "time": ("s", "s", "2 s"),
    "unbalance": ("kg*m", "g*mm", "10 g*mm"),
    "stiffness": ("N/m", "N/m", "1e7 N/m"),
    "modulus": ("Pa", "GPa", "210 GPa"),
    "viscosity": ("Pa*s", "Pa*s", "0.01 Pa*s"),
    "power": ("W", "kW", "10 kW"),
    "frequency": ("Hz", "Hz", "50 Hz"),
    "energy": ("J", "J", "500 J"),
    "specific_energy": ("J/kg", "MJ/kg", "44 MJ/kg"),
}

#: The physical range of each kind of quantity: (smallest size other than zero, largest
#: size), as written in messages. Wide enough for any engine from a model engine to a
#: ship's diesel, narrow enough that no computation overflows. The engine file checks the
#: size of a value (each key has its own rule on sign and zero); the study settings take
#: their signed ranges from it (``crankbalance.schema.settings.RANGES``), and a setting may narrow
#: its kind's range. docs/reliability.md lists them.
RANGES: dict[str, tuple[str, str]] = {
    "length": ("1 um", "100 m"),
    "area": ("1 um^2", "1e4 m^2"),
    "mass": ("1 mg", "1e6 kg"),
    "density": ("100 kg/m^3", "1e5 kg/m^3"),
    "inertia": ("1e-12 kg*m^2", "1e6 kg*m^2"),
    "unbalance": ("1e-12 kg*m", "1e5 kg*m"),
    "speed": ("1 rpm", "1e5 rpm"),
    "force": ("1e-6 N", "1e9 N"),
    "torque": ("1e-6 N*m", "1e7 N*m"),
    "time": ("1 ms", "600 s"),
    "stiffness": ("1e3 N/m", "1e12 N/m"),
    "modulus": ("1 MPa", "1e4 GPa"),
    "pressure": ("0.01 bar", "1000 bar"),
    "viscosity": ("1e-6 Pa*s", "100 Pa*s"),
    "angle": ("0 deg", "720 deg"),
}


@cache
def range_si(kind: str) -> tuple[float, float]:
    """:data:`RANGES` of ``kind`` in SI units (angles in rad, speeds in rad/s)."""
    low, high = RANGES[kind]
    return parse_quantity(low, kind, "range"), parse_quantity(high, kind, "range")


_ANGLE_UNITS = {"radian", "degree", "turn", "revolution", "arcminute", "arcsecond", "gradian"}
_ROTATION_UNITS = {"revolution", "radian", "degree", "turn", "revolutions_per_minute"}

# The units engine files, presets and the command line use, read without pint: pint's
# name -> (SI factor, exponents of pint's root units (m, kg, s, rad)). The radian is
# dimensionless, as in pint (a length may be written "40 mm*rad", a turn is 2 pi), but it
# counts as a unit ("30 deg" has one, "1 mm/m" has none). tests/test_units.py checks
# every spelling below against pint (same name, same root units and factor); any other
# unit goes to pint. docs/performance.md says why.
_Dims = tuple[int, ...]
_NONE: _Dims = (0, 0, 0, 0)
_LENGTH, _MASS, _TIME, _ANGLE = (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)
_FREQUENCY, _ANGULAR_SPEED = (0, 0, -1, 0), (0, 0, -1, 1)
_FORCE, _PRESSURE = (1, 1, -2, 0), (-1, 1, -2, 0)
_ENERGY, _POWER = (2, 1, -2, 0), (2, 1, -3, 0)
_PREFIXES = {
    "G": ("giga", 1e9),
    "M": ("mega", 1e6),
    "k": ("kilo", 1e3),
    "c": ("centi", 1e-2),
    "m": ("milli", 1e-3),
    "u": ("micro", 1e-6),  # also written with the micro sign or the Greek letter mu
}
_UNITS: tuple[tuple[tuple[str, ...], str, str, float, _Dims, str], ...] = (
    # symbols (and other names), pint's name, its plural ("" for none), SI factor, root
    # units, prefixes (the prefixed symbols and names are pint's too)
    (("m",), "meter", "meters", 1.0, _LENGTH, "kcmu"),
    (("in",), "inch", "inches", 0.0254, _LENGTH, ""),
    (("ft",), "foot", "feet", 0.3048, _LENGTH, ""),
    (("g",), "gram", "grams", 1e-3, _MASS, "km"),
    (("lb",), "pound", "pounds", 0.45359237, _MASS, ""),
    (("s",), "second", "seconds", 1.0, _TIME, "m"),
    (("min",), "minute", "minutes", 60.0, _TIME, ""),
    (("h", "hr"), "hour", "hours", 3600.0, _TIME, ""),
    (("rad",), "radian", "radians", 1.0, _ANGLE, ""),
    (("deg",), "degree", "degrees", math.pi / 180, _ANGLE, ""),
    (("revolution", "revolutions"), "turn", "turns", 2 * math.pi, _ANGLE, ""),
    (("rpm",), "revolutions_per_minute", "", 2 * math.pi / 60, _ANGULAR_SPEED, ""),
    (("Hz",), "hertz", "", 1.0, _FREQUENCY, "k"),
    (("N",), "newton", "newtons", 1.0, _FORCE, "kMm"),
    (("Pa",), "pascal", "pascals", 1.0, _PRESSURE, "kMG"),
    (("bar",), "bar", "bars", 1e5, _PRESSURE, "m"),
    (("J",), "joule", "joules", 1.0, _ENERGY, "kM"),
    (("W",), "watt", "watts", 1.0, _POWER, "kM"),
)


def _unit_table() -> tuple[dict[str, tuple[float, _Dims]], dict[str, str]]:
    """pint's name -> (SI factor, root units), and spelling -> pint's name, of every unit
    of :data:`_UNITS` with its prefixes."""
    table: dict[str, tuple[float, _Dims]] = {}
    spellings: dict[str, str] = {}
    for symbols, name, plural, factor, dims, prefixes in _UNITS:
        longs = (name, plural) if plural else (name,)
        table[name] = (factor, dims)
        spellings.update(dict.fromkeys((*symbols, *longs), name))
        for prefix in prefixes:
            long, scale = _PREFIXES[prefix]
            table[long + name] = (scale * factor, dims)
            marks = ("u", "µ", "μ") if prefix == "u" else (prefix,)
            written = [m + s for m in marks for s in symbols] + [long + s for s in longs]
            spellings.update(dict.fromkeys(written, long + name))
    return table, spellings


_TABLE, _SPELLINGS = _unit_table()

# one unit of a product or quotient: "*" or "/" (none before the first), the unit, and an
# integer exponent written "^2" or "**2" (not "^02", which pint reads as "^0 2")
_TERM = re.compile(r"\s*([*/]?)\s*([^\W\d_]+)\s*(?:(?:\^|\*\*)\s*(-?(?:0|[1-9]\d*)))?\s*")


@lru_cache(maxsize=1024)
def _table_unit(unit: str) -> tuple[frozenset[str], float, tuple[int, ...]] | None:
    """The unit names (pint's), SI factor and root units (m, kg, s, rad) of a unit
    expression when it is a plain product or quotient of units of the table, read left to
    right as pint does (``kg/m*s`` is kg·s/m); ``None`` for anything else, which pint
    reads."""
    units: dict[str, int] = {}
    position = 0
    while position < len(unit):
        term = _TERM.match(unit, position)
        if term is None or (term.group(1) == "") != (position == 0):
            return None
        name = _SPELLINGS.get(term.group(2))
        if name is None:
            return None
        exponent = int(term.group(3) or 1)
        units[name] = units.get(name, 0) + (-exponent if term.group(1) == "/" else exponent)
        position = term.end()
    factor, dims = 1.0, _NONE
    for name, exponent in units.items():
        if exponent:  # "m/m" leaves no meter
            entry_factor, entry_dims = _TABLE[name]
            factor *= entry_factor**exponent
            dims = tuple(d + exponent * e for d, e in zip(dims, entry_dims, strict=True))
    return frozenset(name for name, exponent in units.items() if exponent), factor, dims


def _known_unit(expression: str) -> tuple[float, tuple[int, ...]]:
    """SI factor and root units of the SI or display unit of a kind (all in the table)."""
    found = _table_unit(expression)
    assert found is not None, f"{expression} is missing from the table of units"
    return found[1], found[2]


@lru_cache(maxsize=1)
def registry() -> Any:
    """The shared pint unit registry (created on first use: only units outside the table
    of common units need it)."""
    import pint

    return pint.UnitRegistry()


def _a(kind: str) -> str:
    return ("an " if kind[0] in "aeiou" else "a ") + kind


def parse_quantity(value: Any, kind: str, field: str) -> float:
    """Parse a quantity string of the given kind into an SI float.

    Parameters
    ----------
    value : str
        The text, e.g. ``"40 mm"``; a plain number is refused (units are required).
    kind : str
        One of :data:`KINDS` (``"length"``, ``"mass"``, ``"angle"``, ``"speed"``, ...).
    field : str
        Field name used in the error message.

    Returns
    -------
    float
        The value in SI units (angles in rad, speeds in rad/s).
    """
    si_unit, _display, example = KINDS[kind]
    value = _from_pint(value, kind, field)
    if isinstance(value, bool) or not isinstance(value, str):
        if isinstance(value, (int, float)):
            raise InputError(field, value, f"{_a(kind)} needs a unit, e.g. {example!r}")
        raise InputError(field, value, f"must be {_a(kind)} written as a string, e.g. {example!r}")
    text = value.strip()
    if not text:
        raise InputError(field, value, f"must be {_a(kind)}, e.g. {example!r}")
    match = _QUANTITY.match(text)
    unit = (match.group("unit") or "") if match else ""
    if match is None or ".." in text or re.search(r"\d", _EXPONENT.sub("", unit)):
        raise InputError(
            field, value, f"must be one number and a unit, e.g. {example!r} (not a range)"
        )
    if not math.isfinite(float(match.group("number"))):  # "1e999 oz", 400 digits: before
        # pint, which keeps an integer as it is and overflows converting it to a float
        raise InputError(field, value, f"must be a finite {kind}, e.g. {example!r}")
    magnitude: Any
    unit = written_unit(unit)
    text = f"{match.group('number')} {unit}"
    found = _table_unit(unit.replace("°", " deg"))
    if found is not None:  # units of the table only: no pint
        names, factor, dims = found
        magnitude, unitless = float(match.group("number")), not any(dims)
    else:
        ureg = registry()
        try:
            quantity = ureg.Quantity(text.replace("°", " deg").replace("^", "**"))
        except Exception:
            raise InputError(
                field, value, f"is not a quantity; write {_a(kind)} such as {example!r}"
            ) from None
        if not isinstance(quantity, ureg.Quantity):
            raise InputError(field, value, f"{_a(kind)} needs a unit, e.g. {example!r}")
        magnitude, names = quantity.magnitude, frozenset(n for n, _ in quantity.unit_items())
        unitless = quantity.unitless  # no root unit left: "1 mm/m", "28 %"
    if unitless:
        raise InputError(field, value, f"{_a(kind)} needs a unit, e.g. {example!r}")
    if isinstance(magnitude, complex) or not isinstance(magnitude, (int, float)):
        raise InputError(field, value, f"must be a single real {kind}, e.g. {example!r}")
    if not math.isfinite(float(magnitude)):
        raise InputError(field, value, f"must be a finite {kind}, e.g. {example!r}")
    if kind == "angle" and not names <= _ANGLE_UNITS:
        raise InputError(field, value, f"must be an angle in deg or rad, e.g. {example!r}")
    hertz = kind == "speed" and names == {"hertz"}  # a frequency of revolution: 1 Hz = 1 rev/s
    if kind == "speed" and not hertz and not names & _ROTATION_UNITS:
        raise InputError(
            field, value, f"must be a rotational speed (rpm, rad/s, Hz), e.g. {example!r}"
        )
    if found is not None:
        factor, dims = _known_unit("turn/s") if hertz else (factor, dims)
        si_factor, si_dims = _known_unit(si_unit)
        if dims[:3] == si_dims[:3]:  # the same dimension (the radian is dimensionless)
            return magnitude * factor / si_factor
    else:
        if hertz:
            quantity = magnitude * ureg.revolution / ureg.second
        try:
            return float(quantity.to(si_unit).magnitude)
        except Exception:  # pint refuses the conversion: another dimension
            raise InputError(field, value, _wrong_unit(kind, example)) from None
    raise InputError(field, value, _wrong_unit(kind, example))


#: spellings of units people write, as the parser reads them: the output's own symbols
#: (``N·m``, ``kg·m²``, ``g·mm``) and the unambiguous ``RPM`` and ``Nm`` (no unit is
#: spelt so: the nanometre is ``nm``); docs/engine_file.md lists them
SPELLINGS: tuple[tuple[str, str], ...] = (
    (r"·|⋅", "*"),
    (r"²", "^2"),
    (r"³", "^3"),
    (r"\b(RPM|Rpm)\b", "rpm"),
    (r"\b(k?)Nm\b", r"\1N*m"),
)


def written_unit(unit: str) -> str:
    """A unit as written, with the spellings of :data:`SPELLINGS` read as the parser's:
    ``"N·m"`` -> ``"N*m"``, ``"RPM"`` -> ``"rpm"``, ``"Nm"`` -> ``"N*m"``."""
    for pattern, replacement in SPELLINGS:
        unit = re.sub(pattern, replacement, unit)
    return unit


def _from_pint(value: Any, kind: str, field: str) -> Any:
    """A pint quantity (of any registry) as its text, ``"3000 rpm"``; any other value as
    it is. An array quantity is refused."""
    if not (hasattr(value, "magnitude") and hasattr(value, "units") and hasattr(value, "to")):
        return value
    magnitude = value.magnitude
    if isinstance(magnitude, bool) or not isinstance(magnitude, int | float):
        try:
            magnitude = float(magnitude)
        except (TypeError, ValueError):
            raise InputError(field, value, f"must be a single {kind}") from None
    return f"{float(magnitude)!r} {format(value.units, '~')}"


def _wrong_unit(kind: str, example: str) -> str:
    return f"has the wrong unit for {_a(kind)}; write e.g. {example!r}"


def format_quantity(value: float, kind: str, digits: int = 12) -> str:
    """Write an SI float back as a string in the display unit of its kind."""
    si_unit, display, _ = KINDS[kind]
    factor = _known_unit(si_unit)[0] / _known_unit(display)[0]
    return f"{value * factor:.{digits}g} {display.replace('**', '^')}"


def parse_factor(value: Any, field: str) -> float:
    """A balance factor as written: ``0.28``, ``"0.28"`` or ``"28%"`` -> 0.28 (the range is
    checked by :func:`crankbalance.physics.single_cylinder.check_balance_factor`)."""
    hint = "must be a number such as 0.28 or a percentage '28%'"
    if isinstance(value, bool):
        raise InputError(field, value, hint)
    if isinstance(value, (int, float)):
        number = float(value)
    elif isinstance(value, str):
        text = value.strip()
        scale = 1.0
        if text.endswith("%"):
            text, scale = text[:-1].strip(), 0.01
        try:
            number = float(text) * scale
        except ValueError:
            raise InputError(field, value, hint) from None
    else:
        raise InputError(field, value, hint)
    if not math.isfinite(number):
        raise InputError(field, value, "must be a finite number")
    return number
