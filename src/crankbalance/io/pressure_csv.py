"""Cylinder-pressure tables (CSV): crank angle [deg] and absolute pressure [bar] per row.

This module owns the file format of ``crankbalance cycle --pressure-csv`` and
``crankbalance sensitivity --pressure-csv``: it reads the table, refuses what is not a
table of two numeric columns, and converts it to the SI arrays that
:func:`crankbalance.physics.engine_cycle.tabulated_pressure` and
:func:`crankbalance.physics.engine_cycle.engine_cycle` take. The physics checks of the table
(less than one cycle, which depends on the stroke count) stay with the model;
:func:`crankbalance.studies.performance.pressure_source` names the file in them.

Format: comma-separated, two columns (crank angle from firing TDC [deg], absolute
pressure [bar]); blank lines and ``#`` comments are ignored; the first row may be a header
(``angle_deg,pressure_bar``); at least 4 data rows; UTF-8 text. Every value is checked
against the physical range of its kind (:data:`crankbalance.units.RANGES`) here, naming
its line and column: an angle from -720 to 720 deg, each greater than the one before, a
pressure from 0 to 1000 bar (:data:`PRESSURE_RANGE_BAR`).
"""

from __future__ import annotations

import math
import os

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..units import range_si
from .reading import read_text

#: Largest pressure table read [bytes]; a cycle at 0.1 deg over 720 deg is about 150 kB.
MAX_FILE_BYTES = 5_000_000
#: Fewest data rows of a table.
MIN_ROWS = 4

#: Pressures a table may hold [bar]: absolute, so not below 0 (a gauge reading, which goes
#: below zero in the intake stroke, would be taken as absolute and shift every gas force
#: by the ambient pressure), and at most the largest pressure of ``units.RANGES``
#: (1000 bar, the largest pressure any input of crankbalance takes: 1e300 bar made the
#: cycle's arithmetic overflow). A vacuum may be written
#: 0, and values under the smallest pressure of the range (0.01 bar) are taken as they
#: are: no computation divides by a pressure.
PRESSURE_RANGE_BAR = (0.0, range_si("pressure")[1] / 1e5)
#: Crank angles a table may hold [deg]: those of ``units.RANGES``, -720 to 720 deg (a
#: table spans less than one cycle, 720 deg at most, from anywhere around firing TDC).
ANGLE_RANGE_DEG = (-math.degrees(range_si("angle")[1]), math.degrees(range_si("angle")[1]))

_FIELD = "pressure_csv"
_COLUMNS = ("angle_deg", "pressure_bar")
_RANGES = {"angle_deg": ANGLE_RANGE_DEG, "pressure_bar": PRESSURE_RANGE_BAR}
_WORDS = {
    "angle_deg": f"a crank angle from {ANGLE_RANGE_DEG[0]:g} to {ANGLE_RANGE_DEG[1]:g} deg",
    "pressure_bar": f"an absolute pressure from {PRESSURE_RANGE_BAR[0]:g} to "
    f"{PRESSURE_RANGE_BAR[1]:g} bar (a gauge reading: add the ambient pressure)",
}


def read_pressure_csv(path: str | os.PathLike[str]) -> tuple[NDArray, NDArray]:
    """Read a cylinder-pressure table: crank angle [deg] and absolute pressure [bar].

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file: per row the crank angle from firing TDC [deg] and the absolute
        cylinder pressure [bar], comma-separated; blank lines and ``#`` comments are
        skipped, a non-numeric first row is taken as the header. At most
        :data:`MAX_FILE_BYTES` bytes.

    Returns
    -------
    angle : ndarray
        Crank angle from firing TDC [rad], one value per data row.
    pressure : ndarray
        Absolute cylinder pressure [Pa], one value per data row.

    Raises
    ------
    InputError
        If the file cannot be read, is larger than :data:`MAX_FILE_BYTES`, is not UTF-8
        text, or is not at least :data:`MIN_ROWS` rows of two finite numbers in their
        ranges (:data:`ANGLE_RANGE_DEG`, :data:`PRESSURE_RANGE_BAR`); the error names the
        file (and line and column), the value found and what is allowed.
    """
    source = str(path)
    text = read_text(
        path, _FIELD, "a CSV table of crank angle and pressure, a few thousand rows", MAX_FILE_BYTES
    )
    rows = _parse_rows(text, source)
    if len(rows) < MIN_ROWS:
        raise InputError(
            _FIELD,
            source,
            f"must hold at least {MIN_ROWS} rows of: {', '.join(_COLUMNS)} (found {len(rows)})",
        )
    data = np.array(rows, dtype=float)
    return np.radians(data[:, 0]), data[:, 1] * 1e5


def _parse_rows(text: str, source: str) -> list[tuple[float, float]]:
    """The numeric rows of the table; a non-numeric first row is the header."""
    rows: list[tuple[float, float]] = []
    first = True
    for number, line in enumerate(text.splitlines(), start=1):
        content = line.split("#", 1)[0].strip()
        if not content:
            continue
        cells = [cell.strip() for cell in content.split(",")]
        if len(cells) != len(_COLUMNS):
            raise InputError(
                f"{_FIELD} {source}, line {number}",
                content,
                f"must be two comma-separated columns: {', '.join(_COLUMNS)}",
            )
        values = [_number(cell) for cell in cells]
        if first and all(v is None for v in values):
            first = False  # the header
            continue
        first = False
        checked: list[float] = []
        for cell, value, column in zip(cells, values, _COLUMNS, strict=True):
            if value is None or not math.isfinite(value):
                raise InputError(
                    f"{_FIELD} {source}, line {number}, {column}",
                    cell,
                    "must be a finite number",
                )
            low, high = _RANGES[column]
            if not low <= value <= high:
                raise InputError(
                    f"{_FIELD} {source}, line {number}, {column}",
                    cell,
                    f"must be {_WORDS[column]}",
                )
            checked.append(value)
        if rows and checked[0] <= rows[-1][0]:
            raise InputError(
                f"{_FIELD} {source}, line {number}, {_COLUMNS[0]}",
                cells[0],
                f"must be greater than the angle of the row before ({rows[-1][0]:g} deg): the "
                "angles increase strictly",
            )
        rows.append((checked[0], checked[1]))
    return rows


def _number(text: str) -> float | None:
    try:
        return float(text)
    except ValueError:
        return None
