"""Quantity strings at the edges: ``"40 mm"`` -> 0.04 (SI float), and back for display.

Physics modules never import this module; they work in SI floats.
pint is imported lazily so that importing crankbalance stays fast.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import Any

from .errors import InputError

# one number, then a unit expression whose only digits are exponents ("kg*m^2", "m**3")
_QUANTITY = re.compile(
    r"^\s*[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\s*"
    r"(?P<unit>[A-Za-z°µμ%][A-Za-z°µμ%_/*^.\s\d()-]*)?$"
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
}

_ANGLE_UNITS = {"radian", "degree", "turn", "revolution", "arcminute", "arcsecond", "gradian"}
_SI_DISPLAY_FACTOR: dict[str, float] = {}


@lru_cache(maxsize=1)
def registry() -> Any:
    """The shared pint unit registry (created on first use)."""
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
    ureg = registry()
    try:
        quantity = ureg.Quantity(text.replace("°", " deg").replace("^", "**"))
    except Exception:
        raise InputError(
            field, value, f"is not a quantity; write {_a(kind)} such as {example!r}"
        ) from None
    if not isinstance(quantity, ureg.Quantity) or quantity.unitless:
        raise InputError(field, value, f"{_a(kind)} needs a unit, e.g. {example!r}")
    magnitude = quantity.magnitude
    if isinstance(magnitude, complex) or not isinstance(magnitude, (int, float)):
        raise InputError(field, value, f"must be a single real {kind}, e.g. {example!r}")
    if not math.isfinite(float(magnitude)):
        raise InputError(field, value, f"must be a finite {kind}, e.g. {example!r}")
    if kind == "angle":
        names = {name for name, _ in quantity.unit_items()}
        if not names <= _ANGLE_UNITS:
            raise InputError(field, value, f"must be an angle in deg or rad, e.g. {example!r}")
    if kind == "speed":
        names = {name for name, _ in quantity.unit_items()}
        if names == {"hertz"}:  # a frequency of revolution: 1 Hz = 1 rev/s
            quantity = quantity.magnitude * ureg.revolution / ureg.second
        elif not (names & {"revolution", "radian", "degree", "turn", "revolutions_per_minute"}):
            raise InputError(
                field, value, f"must be a rotational speed (rpm, rad/s, Hz), e.g. {example!r}"
            )
    try:
        return float(quantity.to(si_unit).magnitude)
    except Exception:
        raise InputError(
            field, value, f"has the wrong unit for {_a(kind)}; write e.g. {example!r}"
        ) from None


def format_quantity(value: float, kind: str, digits: int = 12) -> str:
    """Write an SI float back as a string in the display unit of its kind."""
    si_unit, display, _ = KINDS[kind]
    factor = _SI_DISPLAY_FACTOR.get(kind)
    if factor is None:
        ureg = registry()
        factor = float(ureg.Quantity(1.0, si_unit).to(display).magnitude)
        _SI_DISPLAY_FACTOR[kind] = factor
    shown = display.replace("**", "^")
    return f"{value * factor:.{digits}g} {shown}"


def parse_factor(value: Any, field: str) -> float:
    """A balance factor as written: ``0.28``, ``"0.28"`` or ``"28%"`` -> 0.28 (the range is
    checked by :func:`crankbalance.single_cylinder.check_balance_factor`)."""
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
