"""Shared helpers for result objects: conversion to JSON-ready Python values, and the one
rule of round-off ("below round-off is zero") every layer applies to forces and moments."""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Protocol, TypeVar, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import ResultError

#: significant digits kept in JSON: enough for any measured input, none of the float noise
JSON_DIGITS = 12

#: share of a scale below which a quantity of that scale is round-off, i.e. zero: the sums
#: of phasors that cancel leave about 1e-16 to 1e-15 of the size of their terms, and the
#: smallest real residual a balancing study reports is far above 1e-12
ROUND_OFF = 1e-12


#: a scalar of an engine (float) or of each engine of a batch (ndarray, shape (E,))
Scalar = TypeVar("Scalar", float, NDArray[np.float64], covariant=True)
#: the scalars of a batch of engines, one per engine
Batch = NDArray[np.float64]


class EngineScales(Protocol[Scalar]):
    """What :func:`round_off` reads of an engine or a batch of engines (leading engine axis):
    an :class:`~crankbalance.physics.model.EngineModel` or an
    :class:`~crankbalance.physics.model.EngineBatch`."""

    @property
    def reciprocating_mass(self) -> NDArray[np.float64]: ...
    @property
    def throw_rotating_mass(self) -> NDArray[np.float64]: ...
    @property
    def throw_position(self) -> NDArray[np.float64]: ...
    @property
    def crank_radius(self) -> Scalar: ...
    @property
    def speed(self) -> Scalar: ...


@overload
def engine_scales(engine: EngineScales[float]) -> tuple[float, float]: ...
@overload
def engine_scales(engine: EngineScales[Batch]) -> tuple[Batch, Batch]: ...
def engine_scales(engine: EngineScales[Scalar]) -> tuple[Scalar, Scalar]:
    r"""Force and length scales of an engine (or of each engine of a batch).

    The force scale is every mass at the crank radius turning at the crank speed,
    :math:`F = (\sum m_{rec} + \sum m_{rot})\,r\,\omega^2`; the length scale is the
    crank's extent along its axis (first to last throw), or the crank radius when that is
    smaller (a single throw has no extent).

    Parameters
    ----------
    engine : EngineModel or EngineBatch
        The engine(s): reciprocating masses [kg] per cylinder, rotating masses [kg] per
        throw, throw positions [m], crank radius [m] and speed [rad/s].

    Returns
    -------
    force : float or ndarray, shape (E,)
        :math:`F` [N].
    length : float or ndarray, shape (E,)
        :math:`L = \max(y_{max} - y_{min}, r)` [m].
    """
    mass = np.sum(engine.reciprocating_mass, axis=-1) + np.sum(engine.throw_rotating_mass, axis=-1)
    force = mass * engine.crank_radius * np.square(engine.speed)
    length = np.maximum(np.ptp(engine.throw_position, axis=-1), engine.crank_radius)
    return force, length


@overload
def round_off(engine: EngineScales[float]) -> tuple[float, float]: ...
@overload
def round_off(engine: EngineScales[Batch]) -> tuple[Batch, Batch]: ...
def round_off(engine: EngineScales[Scalar]) -> tuple[Scalar, Scalar]:
    """Round-off levels of an engine's forces and moments: a force or moment whose size is
    at most its level is zero (:data:`ROUND_OFF` of :func:`engine_scales`).

    Parameters
    ----------
    engine : EngineModel or EngineBatch
        The engine(s), as :func:`engine_scales`.

    Returns
    -------
    force : float or ndarray, shape (E,)
        :math:`10^{-12} F` [N].
    moment : float or ndarray, shape (E,)
        :math:`10^{-12} F L` [N·m].
    """
    force, length = engine_scales(engine)
    return ROUND_OFF * force, ROUND_OFF * force * length


def below_round_off(value: ArrayLike, level: ArrayLike) -> NDArray[Any]:
    """``value`` with every entry whose size is at most ``level`` set to exactly zero.

    Parameters
    ----------
    value : array_like, real or complex
        Forces [N] or moments [N·m].
    level : array_like
        Their round-off level (:func:`round_off`), broadcast against ``value``.

    Returns
    -------
    ndarray
        ``value`` with its round-off set to zero (same dtype).
    """
    v = np.asarray(value)
    return np.where(np.abs(v) <= level, 0.0, v)  # a Python zero keeps v's dtype


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
