"""Shared helpers for result objects: conversion to JSON-ready Python values."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from .errors import ResultError

#: significant digits kept in JSON: enough for any measured input, none of the float noise
JSON_DIGITS = 12


def clean_number(value: float, digits: int = JSON_DIGITS) -> float:
    """``value`` rounded to ``digits`` significant digits, with ``-0.0`` as ``0.0``.

    >>> clean_number(1999.9999999999998)
    2000.0
    >>> clean_number(-0.0)
    0.0
    """
    if value == 0.0 or not math.isfinite(value):
        return 0.0 if value == 0.0 else value
    rounded = float(f"{value:.{digits}g}")
    return rounded + 0.0  # -0.0 + 0.0 == 0.0


def angle(degrees: float) -> float:
    """An angle in degrees, in the one range used everywhere: [0, 360).

    >>> angle(-90.0), angle(360.0), angle(-1e-13)
    (270.0, 0.0, 0.0)
    """
    value = clean_number(float(degrees)) % 360.0
    value = clean_number(value)
    return 0.0 if value >= 360.0 else value


def _clean(value: Any, is_angle: bool) -> Any:
    """Normalise the angles (``is_angle``) of a JSON value: numbers and lists of numbers."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return angle(value) if is_angle else value
    if isinstance(value, list):
        return [_clean(v, is_angle) for v in value]
    return value


def to_jsonable(value: Any, path: str = "") -> Any:
    """Convert dataclasses, numpy arrays and scalars, complex numbers to plain JSON values.

    Complex numbers become ``{"re": .., "im": ..}``; a non-finite float raises
    :class:`~crankbalance.errors.ResultError` naming where it sits (``path``, then the keys
    and indices down to it, e.g. ``summary.energy_check_ratio``), since a NaN must never
    reach the output. Every float is rounded to 12 significant digits (no float noise:
    1999.9999999999998 -> 2000.0, no ``-0.0``), and the value of every dictionary key ending
    in ``_deg`` is put in the one range of angles, [0, 360).
    """
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
        return to_jsonable(fields, path)
    if isinstance(value, dict):
        return {
            str(k): _clean(to_jsonable(v, _join(path, str(k))), str(k).endswith("_deg"))
            for k, v in value.items()
        }
    if isinstance(value, (list, tuple)):
        return [to_jsonable(v, f"{path}[{k}]") for k, v in enumerate(value)]
    if isinstance(value, np.ndarray):
        return to_jsonable(value.tolist(), path)
    if isinstance(value, (complex, np.complexfloating)):
        return {
            "re": to_jsonable(float(value.real), _join(path, "re")),
            "im": to_jsonable(float(value.imag), _join(path, "im")),
        }
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        number = float(value)
        if not math.isfinite(number):
            raise ResultError(path, number)
        return clean_number(number)
    return value


def _join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def require_finite(value: Any, path: str = "") -> None:
    """Raise :class:`~crankbalance.errors.ResultError` if any number in ``value`` (a result,
    a dictionary, a list, an array) is NaN or infinite; the check of every output, text or
    JSON, before it is printed or written."""
    to_jsonable(value, path)


class ResultMixin:
    """Mixin for frozen result dataclasses: ``to_dict()`` gives JSON-ready values."""

    def to_dict(self) -> dict[str, Any]:
        out = to_jsonable(self)
        assert isinstance(out, dict)
        return out
