"""Shared helpers for result objects: conversion to JSON-ready Python values."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np


def to_jsonable(value: Any) -> Any:
    """Convert dataclasses, numpy arrays and scalars, complex numbers to plain JSON values.

    Complex numbers become ``{"re": .., "im": ..}``; non-finite floats raise, since
    a NaN must never reach the output.
    """
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: to_jsonable(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, dict):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [to_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return to_jsonable(value.tolist())
    if isinstance(value, (complex, np.complexfloating)):
        return {"re": to_jsonable(float(value.real)), "im": to_jsonable(float(value.imag))}
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        number = float(value)
        if not math.isfinite(number):
            raise ValueError(f"non-finite number {number!r} in a result")
        return number
    return value


class ResultMixin:
    """Mixin for frozen result dataclasses: ``to_dict()`` gives JSON-ready values."""

    def to_dict(self) -> dict[str, Any]:
        out = to_jsonable(self)
        assert isinstance(out, dict)
        return out
