"""The one exception type of crankbalance for bad input."""

from __future__ import annotations

import math
from typing import Any


class InputError(ValueError):
    """Bad input: names the field, the value given and what is allowed.

    Parameters
    ----------
    field : str
        Dotted path of the offending field, e.g. ``crank_train.rod_length``.
    value : Any
        The value that was given.
    allowed : str
        What would have been accepted.
    """

    def __init__(self, field: str, value: Any, allowed: str) -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        if value is None:
            super().__init__(f"{field}: {allowed}")
        else:
            super().__init__(f"{field} = {_show(value)}: {allowed}")


def _show(value: Any) -> str:
    """The value as shown in a message, at most 80 characters: a longer one keeps its start
    and its end (a long path keeps its file name)."""
    text = repr(value)
    return text if len(text) <= 80 else text[:37] + "..." + text[-40:]


def check_positive(field: str, value: float) -> float:
    """Return ``value`` if it is a finite number > 0, else raise :class:`InputError`."""
    if not (value > 0 and value < float("inf")):
        raise InputError(field, value, "must be a finite number greater than zero")
    return float(value)


def check_finite(field: str, value: float) -> float:
    """Return ``value`` if it is a finite number, else raise :class:`InputError`."""
    if not math.isfinite(value):
        raise InputError(field, value, "must be a finite number")
    return float(value)


def check_nonnegative(field: str, value: float) -> float:
    """Return ``value`` if it is a finite number >= 0, else raise :class:`InputError`."""
    if not (value >= 0 and math.isfinite(value)):
        raise InputError(field, value, "must be a finite number, zero or greater")
    return float(value)


def check_range(field: str, value: float, low: float, high: float) -> float:
    """Return ``value`` if it is finite and ``low <= value <= high``, else raise.

    NaN and infinities are refused even when a bound is infinite.
    """
    if not (math.isfinite(value) and low <= value <= high):
        raise InputError(field, value, f"must be a finite number from {low:g} to {high:g}")
    return float(value)


class ResultError(ValueError):
    """A computed result that is not a finite number, found before it was printed or served.

    Parameters
    ----------
    quantity : str
        Where the value sits in the result, e.g. ``summary.energy_check_ratio``.
    value : float
        The value (NaN or an infinity).
    """

    def __init__(self, quantity: str, value: float) -> None:
        self.quantity = quantity
        self.value = value
        super().__init__(
            f"the result {quantity or 'value'} is not a finite number ({value!r}) for these "
            "inputs; nothing was output"
        )
