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
from collections.abc import Sequence
from typing import Any

from ..results import JSON_DIGITS, UNITS, angle, clean_number, number, to_jsonable

__all__ = [
    "JSON_DIGITS",
    "UNITS",
    "angle",
    "clean_number",
    "depth_read_to",
    "in_output_style",
    "json_text",
    "number",
    "plural",
    "symbol",
    "text",
]

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


#: the parser's spellings of units (:mod:`crankbalance.units`, engine files, defaults) ->
#: the output's symbols, in that order: ``kg*m**2`` and ``kg*m^2`` -> ``kg·m²``,
#: ``g*mm`` -> ``g·mm``, ``N m`` -> ``N·m``, ``30 deg`` -> ``30°``
_STYLE: tuple[tuple[str, str], ...] = (
    (r"\b(N|kg) m\b", r"\1·m"),
    (r"(?<=·m) s\b", "·s"),
    (r"(\*\*|\^)2\b", "²"),
    (r"(\*\*|\^)3\b", "³"),
    (r"(?<=[A-Za-zµ])\*(?=[A-Za-zµ])", "·"),
    (r"(?<=\d) ?(degrees\b|deg\b|°)", "°"),
)


def in_output_style(text: str) -> str:
    """A text with its units written in the output's symbols (:data:`UNITS`): ``"0.002
    kg*m^2"`` -> ``"0.002 kg·m²"``, ``"10 g*mm"`` -> ``"10 g·mm"``, ``"[N m s/rad]"`` ->
    ``"[N·m·s/rad]"``, ``"30 deg"`` and ``"30 °"`` -> ``"30°"``; the parser reads every one
    of them.

    >>> in_output_style("0.002 kg*m**2, 10 g*mm, 1.5 N m, 30 deg, 7850 kg/m^3")
    '0.002 kg·m², 10 g·mm, 1.5 N·m, 30°, 7850 kg/m³'
    """
    import re

    for pattern, replacement in _STYLE:
        text = re.sub(pattern, replacement, text)
    return text


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


def moment_point(reference: float | Sequence[float]) -> str:
    """The point moments are taken about, in words: the crankshaft mid-point, or the point
    ``reference`` [m] from it along +y (``EngineModel.moment_reference``), or, given as
    (x, y, z) [m] (``EngineModel.moment_point``) and off the crank axis, its three
    coordinates."""
    x, y, z = (0.0, float(reference), 0.0) if isinstance(reference, float | int) else reference
    if abs(x) >= 1e-12 or abs(z) >= 1e-12:
        where = ", ".join(text(v, "length") for v in (x, y, z))
        return f"the point (x, y, z) = ({where}) from the crankshaft mid-point"
    if abs(y) < 1e-12:
        return "the crankshaft mid-point"
    return f"the point {text(y, 'length')} from the crankshaft mid-point along +y"


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
