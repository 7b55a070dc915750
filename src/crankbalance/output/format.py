"""One output vocabulary for the CLI, the web page and the report.

An edge module: the physics modules never import it. It owns

* the unit symbols printed in text (``N·m``, ``µm``, ``g·mm``, ``kg·m²``, ``°`` ...);
* :func:`text`, the one formatter of a value with its unit: a fixed number of significant
  digits, no ``-0``, no float noise (a speed typed as 2000 rpm prints as ``2000 rpm``);
* :func:`angle` (from :mod:`crankbalance.results`), the one range of angles, [0, 360)
  degrees, for text and JSON alike;
* :func:`plural` ("1 throw", "3 throws");
* :func:`clean_number`, which :func:`crankbalance.results.to_jsonable` applies to every
  float of every JSON output (12 significant digits, ``-0.0`` -> ``0.0``).

JSON keys carry SI values and name their unit in a suffix (``_m``, ``_kg``, ``_kg_m``,
``_kg_m2``, ``_N``, ``_Nm``, ``_Pa``, ``_W``, ``_J``, ``_s``, ``_rad_s``, ``_hz``, ``_deg``,
``_percent``); ``docs/json.md`` lists every schema. The unit *parser* of the command line
(:mod:`crankbalance.units`) is separate and still accepts ``g*mm`` and friends.
"""

from __future__ import annotations

import math
from typing import Any

from ..results import JSON_DIGITS, angle, clean_number, to_jsonable

__all__ = [
    "JSON_DIGITS",
    "angle",
    "clean_number",
    "depth_read_to",
    "json_text",
    "number",
    "plural",
    "symbol",
    "text",
]

#: the symbol printed after a value of each kind, and the factor from its SI value
UNITS: dict[str, tuple[str, float]] = {
    "force": ("N", 1.0),
    "moment": ("N·m", 1.0),
    "torque": ("N·m", 1.0),
    "mass": ("g", 1e3),
    "mass_kg": ("kg", 1.0),
    "length": ("mm", 1e3),
    "length_m": ("m", 1.0),
    "deflection": ("µm", 1e6),
    "unbalance": ("g·mm", 1e6),
    "first_moment": ("g·mm", 1e6),
    "inertia": ("kg·m²", 1.0),
    "speed": ("rpm", 30.0 / math.pi),
    "frequency": ("Hz", 1.0),
    "angle": ("°", 180.0 / math.pi),
    "angle_deg": ("°", 1.0),
    "stress": ("MPa", 1e-6),
    "pressure": ("bar", 1e-5),
    "power": ("W", 1.0),
    "energy": ("J", 1.0),
    "time": ("s", 1.0),
    "percent": ("%", 1.0),
    "ratio": ("", 1.0),
}

#: the symbols, by name, for text that builds its own labels
N, NM, KG, G, MM, UM, GMM, KGM2, RPM, HZ, DEG = (
    "N",
    "N·m",
    "kg",
    "g",
    "mm",
    "µm",
    "g·mm",
    "kg·m²",
    "rpm",
    "Hz",
    "°",
)


def number(value: float, digits: int = 4) -> str:
    """A number with ``digits`` significant digits, never ``-0`` nor float noise.

    Values of ``10**digits`` and more print whole (``15200``, not ``1.52e+04``).

    >>> number(1999.9999999999998), number(-0.0001, 2), number(15200.0), number(0.5)
    ('2000', '-0.0001', '15200', '0.5')
    """
    value = clean_number(float(value))
    if 10.0**digits <= abs(value) < 1e15:
        out = f"{round(value):d}"
    else:
        out = f"{value:.{digits}g}"
    return "0" if float(out) == 0.0 else out


def symbol(kind: str) -> str:
    """The unit symbol of a kind of value (``"moment"`` -> ``"N·m"``)."""
    return UNITS[kind][0]


def convert(value: float, kind: str) -> float:
    """An SI value (radians for angles) in the unit text shows for ``kind``."""
    factor = UNITS[kind][1]
    out = float(value) * factor
    if kind in ("angle", "angle_deg"):
        out = angle(out)
    return out


def text(value: float, kind: str, digits: int = 4) -> str:
    """An SI value as text in its display unit: ``text(0.0033, "unbalance")`` -> ``3.3 g·mm``.

    Angles (``"angle"`` from radians, ``"angle_deg"`` from degrees) are put in [0, 360)
    and print as ``30°``.
    """
    unit = symbol(kind)
    shown = number(convert(value, kind), digits)
    if not unit:
        return shown
    if unit in ("°", "%"):
        return f"{shown}{unit}"
    return f"{shown} {unit}"


def moment_point(reference: float) -> str:
    """The point moments are taken about, in words: the crankshaft mid-point, or the point
    ``reference`` [m] from it along +y (``EngineModel.moment_reference``)."""
    if abs(reference) < 1e-12:
        return "the crankshaft mid-point"
    return f"the point {text(reference, 'length')} from the crankshaft mid-point along +y"


def depth_read_to(point_angle: float, depth_to: str) -> str:
    """What the depth of drilled holes is read to, after the depth: ``""`` for flat-bottomed
    holes (``point_angle`` pi: one depth), else ``" to the tip"`` or ``" to the shoulder"``
    (``point_angle`` [rad]; the depths of pointed holes differ by the point's height)."""
    return "" if point_angle >= math.pi else f" to the {depth_to}"


def plural(count: int, word: str, many: str | None = None) -> str:
    """``plural(1, "throw")`` -> ``1 throw``; ``plural(3, "throw")`` -> ``3 throws``."""
    return f"{count} {word if count == 1 else (many or word + 's')}"


def json_text(payload: Any, indent: int | None = 2) -> str:
    """The text of one JSON output: every value through :func:`~crankbalance.results.to_jsonable`
    (12 significant digits, no ``-0.0``, angles in [0, 360))."""
    import json  # here: a command printing a table does not load it

    return json.dumps(to_jsonable(payload), indent=indent, ensure_ascii=False)


def _scaled(value: Any, factor: float) -> Any:
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, int | float):
        return value * factor
    if isinstance(value, list | tuple):
        return [_scaled(v, factor) for v in value]
    return value


def keyed(values: dict[str, Any], names: dict[str, str | tuple[str, float]]) -> dict[str, Any]:
    """``values`` with its keys renamed to the JSON convention (unit in a suffix).

    ``names`` maps an old key to its new key, or to ``(new key, factor)`` when the value
    changes unit too (radians -> degrees: ``("phase_deg", 180 / math.pi)``). Keys not in
    ``names`` stay as they are; the order of the keys is kept.
    """
    out: dict[str, Any] = {}
    for key, value in values.items():
        name = names.get(key, key)
        if isinstance(name, tuple):
            out[name[0]] = _scaled(value, name[1])
        else:
            out[name] = value
    return out
