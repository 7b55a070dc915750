"""The balance shop's parts file (CSV or TOML): every weighed part of an engine
(``examples/v8_parts.csv``; ``docs/balance_shop.md``, "Parts and matching").

Kinds of parts (:data:`KINDS`): ``piston``, ``pin``, ``rings`` (a ring set), ``locks``
(a pair of pin locks), ``rod`` (big end and small end from the usual two-end weighing,
with the total if weighed), ``shell`` (a big-end bearing shell pair), and the oil, given
once: ``oil`` the allowance in one big end, added to every rod, or ``journal_oil`` the oil
in one rod journal, shared by the rods on it (the same total either way:
:meth:`~crankbalance.physics.shop.matching.Inventory.per_rod`).

CSV: one part per row, a header naming the columns, units in brackets on the mass
columns::

    part,id,mass [g],big_end [g],small_end [g]
    piston,P1,512.4,,
    rod,R1,638.2,452.0,186.3
    oil,,4.0,,

``part`` and ``mass`` are required columns (``big_end`` and ``small_end`` when the file
lists rods); ``id`` is the part's mark (``piston 3`` when left empty); blank lines and
lines starting with ``#`` are skipped. Any mass unit (``g``, ``kg``, ``oz``) may be used.

TOML: an array of tables per kind with quantity strings, and the oil allowance as a key::

    oil = "4 g"
    [[piston]]
    id = "P1"
    mass = "512.4 g"
    [[rod]]
    id = "R1"
    big_end = "452.0 g"
    small_end = "186.3 g"
    mass = "638.2 g"

Every problem is one :class:`~crankbalance.errors.InputError` naming the file and the line
and column (CSV) or key (TOML) as written, the value and what is allowed. Files are read
through :func:`crankbalance.io.reading.read_text` (a regular UTF-8 file of at most
:data:`MAX_FILE_BYTES`).
"""

from __future__ import annotations

import csv
import math
import os
import re
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError
from ..physics.shop.matching import Inventory, PartKind
from ..records import record
from ..schema.engine import MAX_QUANTITY_CHARS, parse_in_range
from .reading import parse_toml, read_text

#: largest parts file read [bytes]
MAX_FILE_BYTES = 1_000_000
#: most parts in one file
MAX_PARTS = 2000
#: kinds of parts and the share each mass goes to ("rod": small end reciprocating, big
#: end rotating; "oil": the allowance per rod, rotating)
KINDS: dict[str, str] = {
    "piston": "reciprocating",
    "pin": "reciprocating",
    "rings": "reciprocating",
    "locks": "reciprocating",
    "rod": "both",
    "shell": "rotating",
    "oil": "allowance",
    "journal_oil": "allowance",
}
#: the kinds given once, as an allowance: per rod, per journal (shared by its rods)
ALLOWANCES = ("oil", "journal_oil")
#: longest cell of a CSV parts file, in characters (a mark or a mass needs a few; the TOML
#: file's quantities have the same bound)
MAX_CELL_CHARS = MAX_QUANTITY_CHARS
#: largest difference between a rod's weighed total and the sum of its two ends, as a
#: fraction of the total (the two-end weighing loses a little to how the rod is held)
ROD_SUM_TOLERANCE = 0.01
DOC = "docs/balance_shop.md"
WHAT = "a parts file (.csv or .toml)"
_HEADER = re.compile(r"^\s*(?P<name>[A-Za-z_]+)\s*(?:\[(?P<unit>[^\]]*)\])?\s*$")
_MASS_COLUMNS = ("mass", "big_end", "small_end")
#: control characters (NUL, escape, ...), which no cell may hold (a tab may)
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f]")


@record
class _Part:
    kind: str
    mark: str
    mass: float | None
    big_end: float | None
    small_end: float | None
    where: str  # how the user finds it: "line 4" or "piston[2]"
    field: str  # prefix of the field names in messages
    sep: str = ", "  # between the prefix and a column (CSV) or key (TOML)

    def at(self, name: str) -> str:
        """The field name of one of the part's values, as the user finds it."""
        return f"{self.field}{self.sep}{name}"


def load_parts_file(path: str | os.PathLike[str]) -> Inventory:
    """Read and validate a parts file (CSV or TOML, by its suffix; see the module docstring).

    Parameters
    ----------
    path : str or os.PathLike
        The file; ``.toml`` is read as TOML, anything else as CSV.

    Returns
    -------
    Inventory
        The parts by kind in SI [kg] and the oil allowance per rod [kg].

    Raises
    ------
    InputError
        Naming the file, line and column (or key), the value and what is allowed.
    """
    source = str(path)
    text = read_text(path, "parts", WHAT, MAX_FILE_BYTES)
    if Path(path).suffix.lower() == ".toml":
        return parts_from_toml(parse_toml(text, "parts", source), source)
    return parts_from_csv(text, source)


# --------------------------------------------------------------------------- CSV
def parts_from_csv(text: str, source: str = "parts.csv") -> Inventory:
    """Validate the text of a CSV parts file (see the module docstring).

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        The file's name, for messages.

    Returns
    -------
    Inventory
        The parts [kg].
    """
    lines = [
        (number, line)
        for number, line in enumerate(text.splitlines(), start=1)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not lines:
        raise InputError("parts", source, "holds no header and no part; see " + DOC)
    number, header_line = lines[0]
    header = f"{source}, line {number} (header)"
    columns = _header(_cells(header_line, header, []), header)
    labels = [label for _, label, _ in columns]
    parts: list[_Part] = []
    for number, line in lines[1:]:
        where = f"{source}, line {number}"
        cells = _cells(line, where, labels)
        if len(cells) > len(columns):
            raise InputError(
                where, line, f"has {len(cells)} cells; the header names {len(columns)} columns"
            )
        cells += [""] * (len(columns) - len(cells))
        row: dict[str, Any] = {}
        for (name, label, unit), cell in zip(columns, cells, strict=True):
            value = cell.strip()
            if name in _MASS_COLUMNS:
                row[name] = None if not value else _mass(value, unit, f"{where}, {label}", cell)
            else:
                row[name] = value
        parts.append(
            _Part(
                kind=_kind(row.get("part", ""), f"{where}, part"),
                mark=row.get("id", ""),
                mass=row.get("mass"),
                big_end=row.get("big_end"),
                small_end=row.get("small_end"),
                where=f"line {number}",
                field=where,
            )
        )
        if len(parts) > MAX_PARTS:
            raise InputError("parts", source, f"lists more than {MAX_PARTS} parts")
    return _inventory(parts, source)


def _cells(line: str, where: str, labels: list[str]) -> list[str]:
    """The cells of one line (strict CSV: a quoted cell ends on its line, its closing quote
    is followed by a comma or the end of the line); a cell longer than
    :data:`MAX_CELL_CHARS` or any other CSV error is an :class:`InputError` naming the line
    and the column (its header ``labels``, or its number)."""
    try:
        cells = next(csv.reader([line], strict=True))
    except csv.Error as error:
        index, cell = _bad_cell(line)
        if len(cell) > MAX_CELL_CHARS:
            _too_long(where, labels, index, cell)
        raise InputError(
            f"{where}, {_column(labels, index)}",
            cell,
            f"is not a valid CSV cell ({error}): a cell in double quotes ends on its line, "
            "with a comma or the end of the line after its closing quote, and a quote inside "
            'it doubled ("")',
        ) from None
    for index, cell in enumerate(cells):
        if len(cell) > MAX_CELL_CHARS:
            _too_long(where, labels, index, cell)
        control = _CONTROL.search(cell)
        if control:
            raise InputError(
                f"{where}, {_column(labels, index)}",
                cell,
                f"holds the control character {control.group()!r} at character "
                f"{control.start() + 1}; a cell is printable text",
            )
    return cells


def _too_long(where: str, labels: list[str], index: int, cell: str) -> None:
    raise InputError(
        f"{where}, {_column(labels, index)}",
        cell,
        f"is {len(cell)} characters long; a cell holds at most {MAX_CELL_CHARS}",
    )


def _column(labels: list[str], index: int) -> str:
    """A column as the user finds it: its header as written, else its number."""
    if index < len(labels):
        return labels[index]
    if labels:
        return f"column {index + 1} (the header names {len(labels)})"
    return f"column {index + 1}"


def _bad_cell(line: str) -> tuple[int, str]:
    """Where the csv module stopped on a line: the line cut into cells at the commas outside
    double quotes, the first that is no valid CSV cell on its own (its index, and the cell
    as written)."""
    cells, start, quoted = [], 0, False
    for k, char in enumerate(line):
        if char == '"':
            quoted = not quoted
        elif char == "," and not quoted:
            cells.append(line[start:k])
            start = k + 1
    cells.append(line[start:])
    for index, cell in enumerate(cells):
        if len(cell) > MAX_CELL_CHARS:
            return index, cell
        try:
            next(csv.reader([cell], strict=True), None)
        except csv.Error:
            return index, cell
    return len(cells) - 1, cells[-1]


def _header(cells: list[str], where: str) -> list[tuple[str, str, str | None]]:
    """Per column: its name, its label as written, its unit (None: no unit given)."""
    allowed = "part, id, mass [unit], big_end [unit], small_end [unit]"
    columns: list[tuple[str, str, str | None]] = []
    for cell in cells:
        match = _HEADER.match(cell)
        name = match.group("name").lower() if match else ""
        if name not in ("part", "id", *_MASS_COLUMNS):
            raise InputError(where, cell, f"is not a column; the columns are {allowed}")
        if any(name == seen for seen, _, _ in columns):
            raise InputError(where, cell, "names a column twice; give it once")
        unit = match.group("unit") if match else None
        if name in _MASS_COLUMNS:
            if not unit or not unit.strip():
                raise InputError(where, cell, f"needs its unit in brackets, e.g. '{name} [g]'")
            _mass("1", unit, f"{where}, {cell.strip()}", cell)  # the unit is a mass unit
        elif unit is not None:
            raise InputError(where, cell, f"takes no unit; write '{name}'")
        columns.append((name, cell.strip(), unit))
    for required in ("part", "mass"):
        if not any(name == required for name, _, _ in columns):
            raise InputError(where, ",".join(cells), f"has no '{required}' column; give {allowed}")
    return columns


def _mass(value: str, unit: str | None, field: str, written: Any) -> float:
    """A mass cell (a plain number) in the column's unit, as kg."""
    try:
        number = float(value)
    except ValueError:
        raise InputError(field, written, "must be a number (the unit is in the header)") from None
    if not math.isfinite(number):
        raise InputError(field, written, "must be a finite number")
    try:
        return parse_in_range(f"{value} {unit}", "mass", field)
    except InputError as error:
        raise InputError(field, written, error.allowed) from None


# --------------------------------------------------------------------------- TOML
def parts_from_toml(data: Any, source: str = "parts.toml") -> Inventory:
    """Validate the table of a TOML parts file (see the module docstring).

    Parameters
    ----------
    data : dict
        The parsed TOML.
    source : str
        The file's name, for messages.

    Returns
    -------
    Inventory
        The parts [kg].
    """
    if not isinstance(data, dict):
        raise InputError("parts", source, "must be a table of keys and values")
    parts: list[_Part] = []
    for key, value in data.items():
        where = f"{source}: {key}"
        if key == "name":
            continue
        if key in ALLOWANCES:
            parts.append(_Part(key, "", _quantity(value, where), None, None, key, where))
            continue
        kind = _kind(key, f"{source}: key")
        if kind in ALLOWANCES or not isinstance(value, list):
            raise InputError(where, value, f"must be an array of tables ([[{key}]]) of parts")
        for index, entry in enumerate(value, start=1):
            at = f"{key}[{index}]"
            field = f"{source}: {at}"
            if not isinstance(entry, dict):
                raise InputError(field, entry, "must be a table with id and mass")
            allowed = ("id", "mass", "big_end", "small_end")
            for name in entry:
                if name not in allowed:
                    raise InputError(
                        f"{field}.{name}",
                        entry[name],
                        f"unknown key; allowed: {', '.join(allowed)}",
                    )
            mark = entry.get("id", "")
            if not isinstance(mark, str | int) or isinstance(mark, bool):
                raise InputError(f"{field}.id", mark, "must be a text or a whole number")
            masses = {
                name: None if name not in entry else _quantity(entry[name], f"{field}.{name}")
                for name in _MASS_COLUMNS
            }
            parts.append(_Part(kind, str(mark), **masses, where=at, field=field, sep="."))
            if len(parts) > MAX_PARTS:
                raise InputError("parts", source, f"lists more than {MAX_PARTS} parts")
    return _inventory(parts, source)


def _quantity(value: Any, field: str) -> float:
    if isinstance(value, str) and len(value) > MAX_QUANTITY_CHARS:
        raise InputError(
            field,
            value,
            f"must be a mass such as '512.4 g' (at most {MAX_QUANTITY_CHARS} characters)",
        )
    return parse_in_range(value, "mass", field)


# --------------------------------------------------------------------------- both
def _kind(value: str, field: str) -> str:
    kind = value.strip().lower()
    if kind not in KINDS:
        raise InputError(field, value, f"must be a kind of part: {', '.join(KINDS)}")
    return kind


def _inventory(parts: list[_Part], source: str) -> Inventory:
    """Check every part and gather them by kind."""
    by_kind: dict[str, list[tuple[str, float, float]]] = {}
    oil: list[_Part] = []
    for part in parts:
        if part.kind in ALLOWANCES:
            oil.append(part)
            continue
        share = _shares(part)
        marks = by_kind.setdefault(part.kind, [])
        mark = part.mark.strip() or f"{part.kind} {len(marks) + 1}"
        if any(mark == seen for seen, _, _ in marks):
            raise InputError(
                part.at("id"), mark, f"is given to two {part.kind}s; mark each part once"
            )
        marks.append((mark, *share))
    if len(oil) > 1:
        raise InputError(
            f"{oil[1].field}",
            None,
            "gives the oil allowance twice; give it once, per rod (oil) or per journal "
            "(journal_oil)",
        )
    allowance = {name: 0.0 for name in ALLOWANCES}
    if oil:
        if oil[0].mass is None:
            per = "rod" if oil[0].kind == "oil" else "journal"
            raise InputError(oil[0].at("mass"), None, f"is missing; give the oil per {per}")
        allowance[oil[0].kind] = oil[0].mass
    if not by_kind:
        raise InputError("parts", source, f"lists no part; give at least one of {', '.join(KINDS)}")
    kinds = tuple(
        PartKind(
            name,
            tuple(mark for mark, _, _ in entries),
            np.array([rec for _, rec, _ in entries]),
            np.array([rot for _, _, rot in entries]),
        )
        for name, entries in by_kind.items()
    )
    return Inventory(kinds, 0.0, allowance["oil"], allowance["journal_oil"])


def _shares(part: _Part) -> tuple[float, float]:
    """The reciprocating and rotating share of a part [kg]."""
    if part.kind != "rod":
        for name in ("big_end", "small_end"):
            if getattr(part, name) is not None:
                raise InputError(
                    part.at(name),
                    _grams(getattr(part, name)),
                    f"applies to rods only; leave it empty for a {part.kind}",
                )
        if part.mass is None:
            raise InputError(part.at("mass"), None, f"is missing; give the {part.kind}'s mass")
        if not part.mass > 0:
            raise InputError(part.at("mass"), _grams(part.mass), "must be greater than zero")
        return (part.mass, 0.0) if KINDS[part.kind] == "reciprocating" else (0.0, part.mass)
    for name in ("big_end", "small_end"):
        value = getattr(part, name)
        if value is None:
            raise InputError(part.at(name), None, "is missing; a rod needs both ends' weights")
        if not value > 0:
            raise InputError(part.at(name), _grams(value), "must be greater than zero")
    big, small = part.big_end, part.small_end
    assert big is not None and small is not None
    if part.mass is not None:
        difference = big + small - part.mass
        if not abs(difference) <= ROD_SUM_TOLERANCE * part.mass:
            raise InputError(
                part.at("mass"),
                _grams(part.mass),
                f"differs from big_end + small_end = {1000 * (big + small):.6g} g by "
                f"{1000 * difference:+.3g} g, more than {100 * ROD_SUM_TOLERANCE:g} % of the "
                "total; re-weigh the rod",
            )
    return small, big


def _grams(value: float) -> str:
    return f"{1000 * value:.6g} g"
