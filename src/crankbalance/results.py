"""Shared helpers for result objects: conversion to JSON-ready Python values, and the one
rule of round-off ("below round-off is zero") every layer applies to forces and moments."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, Protocol, TypeVar, overload

import numpy as np

from .errors import ResultError
from .records import record

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import ArrayLike, NDArray

    #: the scalars of a batch of engines, one per engine
    Batch = NDArray[np.float64]

#: significant digits kept in JSON: enough for any measured input, none of the float noise
JSON_DIGITS = 12

#: an angle at most this far from 0 (or 360) is 0 [deg]: far below any angle measured or
#: machined, far above the float noise of a phase (about 1e-15 °)
ANGLE_ROUND_OFF = 1e-9

#: share of a scale below which a quantity of that scale is round-off, i.e. zero: the sums
#: of phasors that cancel leave about 1e-16 to 1e-15 of the size of their terms, and the
#: smallest real residual a balancing study reports is far above 1e-12
ROUND_OFF = 1e-12


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
    "velocity": ("mm/s", 1e3),
    "angular_acceleration": ("rad/s²", 1.0),
    "frequency": ("Hz", 1.0),
    "angle": ("°", 180.0 / math.pi),
    "angle_deg": ("°", 1.0),
    "crank_angle": ("°", 180.0 / math.pi),
    "stress": ("MPa", 1e-6),
    "pressure": ("bar", 1e-5),
    "power": ("W", 1.0),
    "energy": ("J", 1.0),
    "time": ("s", 1.0),
    "percent": ("%", 1.0),
    "ratio": ("", 1.0),
}


#: a scalar of an engine (float) or of each engine of a batch (ndarray, shape (E,))
Scalar = TypeVar("Scalar", float, "NDArray[np.float64]", covariant=True)


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


def angle(degrees: float) -> float:
    """An angle in degrees, in the one range used everywhere: [0, 360).

    An angle within :data:`ANGLE_ROUND_OFF` of 0 or 360 is 0 (the phase of a sum of phasors
    that cancel carries about 1e-15 ° of noise).

    >>> angle(-90.0), angle(360.0), angle(-1e-13), angle(2.98e-15)
    (270.0, 0.0, 0.0, 0.0)
    """
    value = clean_number(float(degrees)) % 360.0
    value = clean_number(value)
    return 0.0 if min(value, 360.0 - value) <= ANGLE_ROUND_OFF else value


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


# --------------------------------------------------------------------------- display
#: the kind (of :data:`UNITS`) of a JSON key's value, by the suffix naming its SI unit,
#: longest first (``_kg_m2`` before ``_kg_m`` before ``_m``)
JSON_SUFFIXES: tuple[tuple[str, str], ...] = (
    ("_kg_m2", "inertia"),
    ("_kg_m", "unbalance"),
    ("_rad_s2", "angular_acceleration"),
    ("_rad_s", "speed"),
    ("_rad", "angle"),
    ("_m_s", "velocity"),
    ("_percent", "percent"),
    ("_deg", "angle_deg"),
    ("_Nm", "moment"),
    ("_kg", "mass_kg"),
    ("_Pa", "pressure"),
    ("_hz", "frequency"),
    ("_N", "force"),
    ("_W", "power"),
    ("_J", "energy"),
    ("_m", "length"),
    ("_s", "time"),
)
#: the JSON keys (in radians) whose value is a position of the crank, which a display
#: shows in [0, 360) like the text output (:func:`angle`); other angles in radians keep
#: their sign, which says a direction (a deviation, a twist, a rotation, an ignition
#: before top dead centre) or their range (a firing angle of a four-stroke in [0, 720))
CRANK_ANGLES = ("peak_load_crank_angle_rad", "throw_angle_rad")
#: rows of a table a display shows (the rest counted); ``to_dict()`` has them all
DISPLAY_ROWS = 12
#: numbers of a list a display shows (the rest counted)
DISPLAY_ITEMS = 8
#: values (name and value) the ``repr`` of a result shows, after its verdicts
REPR_VALUES = 6
#: verdicts the ``repr`` of a result shows (the rest counted; the HTML display has them all)
REPR_VERDICTS = 3
#: values a line of the ``repr`` of a result shows
REPR_VALUES_PER_LINE = 3
#: rows and columns of the one table the ``repr`` of a result shows
REPR_ROWS = 5
REPR_COLUMNS = 6
#: characters of a line of the ``repr`` (a longer line is cut with "…")
REPR_WIDTH = 110
#: a text of a result longer than this is a note (shown in the HTML display under "notes",
#: counted in the ``repr``), not a verdict
NOTE_LENGTH = 160
#: a list of texts each at most this long is a list of names, shown in one line; a list
#: with a longer text is a list of sentences, one line each
WORD_LENGTH = 24
#: lines of the ``repr`` of a result at most: title, verdicts, values, one table, the rest
REPR_LINES = 15


def key_label(key: str) -> tuple[str, str]:
    """A JSON key as a display names it, and its kind of :data:`UNITS` (``""`` for a value
    without unit): ``amplitude_N`` -> ``("amplitude [N]", "force")``; a key of
    :data:`CRANK_ANGLES` is of the kind ``crank_angle``."""
    if key in CRANK_ANGLES:
        return f"{key[: -len('_rad')].replace('_', ' ')} [°]", "crank_angle"
    for suffix, kind in JSON_SUFFIXES:
        if key.endswith(suffix) and len(key) > len(suffix):
            return f"{key[: -len(suffix)].replace('_', ' ')} [{UNITS[kind][0]}]", kind
    return key.replace("_", " "), ""


def shown(value: Any, kind: str = "") -> str:
    """A JSON value as a display shows it: a number in the unit of ``kind`` (the SI value
    times its factor of :data:`UNITS`, 4 significant digits, round-off as 0), a list of up
    to :data:`DISPLAY_ITEMS` of them, ``yes``/``no``, ``-`` for none; a position of the
    crank (kind ``crank_angle``) in [0, 360)."""
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int | float):
        converted = float(value) * (UNITS[kind][1] if kind else 1.0)
        return number(angle(converted) if kind == "crank_angle" else converted)
    if isinstance(value, list):
        items = [shown(v, kind) for v in value[:DISPLAY_ITEMS]]
        more = len(value) - DISPLAY_ITEMS
        return ", ".join(items) + (f", … ({more} more)" if more > 0 else "")
    if isinstance(value, dict) and set(value) == {"re", "im"}:
        return f"{shown(value['re'], kind)} + {shown(value['im'], kind)}j"
    return str(value)


@record
class Table:
    """A table of a result's display: its caption, the column labels (unit in brackets)
    and the rows as text; ``more`` rows are left out (:data:`DISPLAY_ROWS`)."""

    caption: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    more: int = 0


@record
class Summary:
    """What a result shows in a notebook: a title, its verdicts (sentences), its values
    (label with unit, value), its tables (the first is the one the ``repr`` shows) and its
    notes (definitions and assumptions: long texts)."""

    title: str
    verdicts: tuple[str, ...] = ()
    values: tuple[tuple[str, str], ...] = ()
    tables: tuple[Table, ...] = ()
    notes: tuple[str, ...] = ()


def _is_row(value: Any) -> bool:
    return isinstance(value, dict) and set(value) != {"re", "im"}


def _table(caption: str, rows: list[dict[str, Any]], columns: tuple[str, ...] = ()) -> Table:
    """The table of ``rows``, its ``columns`` (JSON keys it has) first."""
    keys = [k for k, v in rows[0].items() if not (isinstance(v, list) and v and _is_row(v[0]))]
    keys = [k for k in keys if not _is_row(rows[0][k])]
    keys = [k for k in dict.fromkeys(columns) if k in keys] + [k for k in keys if k not in columns]
    labels = [key_label(k) for k in keys]
    body = tuple(
        tuple(shown(row.get(k), kind) for k, (_, kind) in zip(keys, labels, strict=True))
        for row in rows[:DISPLAY_ROWS]
    )
    more = max(len(rows) - DISPLAY_ROWS, 0)
    return Table(caption, tuple(label for label, _ in labels), body, more)


def summarize(
    title: str,
    data: dict[str, Any],
    verdicts: tuple[str, ...] = (),
    first: str = "",
    columns: tuple[str, ...] = (),
) -> Summary:
    """The display of a result's JSON (``to_dict()``): its short top-level texts (a list of
    names, :data:`WORD_LENGTH`, as one line) as verdicts after ``verdicts``, its other
    texts (nested, or longer than :data:`NOTE_LENGTH`) as notes, its numbers (those of its
    tables too, two levels down) as values with their units, its lists of rows as tables,
    the one captioned ``first`` first, with its ``columns`` (JSON keys) first; the
    ``schema`` key is left out."""
    said = list(verdicts)
    notes: list[str] = []
    values: list[tuple[str, str]] = []
    tables: list[Table] = []

    def text(nested: bool, line: str) -> None:
        (notes if nested or len(line) > NOTE_LENGTH else said).append(line)

    def walk(prefix: str, table: dict[str, Any], depth: int) -> None:
        for key, value in table.items():
            if key == "schema":
                continue
            label, kind = key_label(key)
            name = f"{prefix}{label}"
            if isinstance(value, str) and (not prefix or len(value) > 40):
                text(bool(prefix), f"{name}: {value}" if prefix else value)
            elif isinstance(value, list) and value and all(isinstance(v, str) for v in value):
                if max(map(len, value)) <= WORD_LENGTH:  # names: one line
                    text(bool(prefix), f"{name}: {shown(value)}")
                else:  # sentences: one each
                    for item in value:
                        text(bool(prefix), f"{name}: {item}")
            elif isinstance(value, list) and value and _is_row(value[0]):
                rows = [v for v in value if _is_row(v)]
                tables.append(_table(name, rows, columns if name == first else ()))
            elif _is_row(value):
                if depth < 2:
                    walk(f"{name} · ", value, depth + 1)
            elif not (isinstance(value, list) and not value):
                values.append((name, shown(value, kind)))

    walk("", data, 0)
    tables.sort(key=lambda t: t.caption != first)
    return Summary(title, tuple(said), tuple(values), tuple(tables), tuple(notes))


def _cut(line: str, width: int = REPR_WIDTH) -> str:
    return line if len(line) <= width else line[: width - 1] + "…"


def _text_table(table: Table) -> list[str]:
    """A table of a ``repr``: its caption, its header and its first :data:`REPR_ROWS` rows
    of :data:`REPR_COLUMNS` columns, aligned, and a line counting the rows left out."""
    columns = min(len(table.header), REPR_COLUMNS)
    rows = [table.header[:columns], *(row[:columns] for row in table.rows[:REPR_ROWS])]
    rows = [tuple(_cut(cell, 28) for cell in row) for row in rows]
    widths = [max(len(row[k]) for row in rows) for k in range(columns)]
    caption = f"{table.caption}:"
    if columns < len(table.header):
        caption += f" (first {columns} of {len(table.header)} columns)"
    lines = [caption]
    lines += [
        _cut("  " + "  ".join(c.rjust(w) for c, w in zip(row, widths, strict=True))) for row in rows
    ]
    more = len(table.rows) - REPR_ROWS + table.more
    if more > 0:
        lines.append(f"  … {more} more rows")
    return lines


def summary_text(summary: Summary) -> str:
    """The ``repr`` of a result, at most :data:`REPR_LINES` lines: its title, its first
    verdicts (:data:`REPR_VERDICTS`), its first values (:data:`REPR_VALUES`, in lines of
    :data:`REPR_VALUES_PER_LINE`),
    its first table (:data:`REPR_ROWS` rows) and a line naming what the HTML display
    shows besides (its other tables, the notes). A verdict is shown whole (a short text of
    the JSON, at most :data:`NOTE_LENGTH` characters, or a sentence of the result's
    headline); the other lines are cut at :data:`REPR_WIDTH` characters."""
    lines = [summary.title, *summary.verdicts[:REPR_VERDICTS]]
    first = summary.values[:REPR_VALUES]
    for at in range(0, len(first), REPR_VALUES_PER_LINE):
        shown = first[at : at + REPR_VALUES_PER_LINE]
        lines.append(_cut("; ".join(f"{label} {value}" for label, value in shown)))
    if summary.tables:
        lines += _text_table(summary.tables[0])
    rest = []
    if len(summary.verdicts) > REPR_VERDICTS:
        more = len(summary.verdicts) - REPR_VERDICTS
        rest.append(f"{more} more verdict{'s' if more > 1 else ''}")
    if len(summary.tables) > 1:
        rest.append("tables: " + ", ".join(t.caption for t in summary.tables[1:]))
    if summary.notes:
        rest.append(f"{len(summary.notes)} notes" if len(summary.notes) > 1 else "1 note")
    if rest:
        lines.append(_cut(f"(the HTML display has {'; '.join(rest)})"))
    return "\n".join(lines)


def summary_html(summary: Summary) -> str:
    """The HTML display of a result (Jupyter's ``_repr_html_``): its title, its verdicts,
    its first table, a table of its values, its other tables (units in the column labels)
    and its notes, folded."""
    from html import escape

    def table(caption: str, header: tuple[str, ...], rows: Any, more: int = 0) -> str:
        head = "".join(f"<th>{escape(h)}</th>" for h in header)
        body = "".join(
            "<tr>" + "".join(f"<td>{escape(cell)}</td>" for cell in row) + "</tr>" for row in rows
        )
        if more:
            body += f'<tr><td colspan="{len(header)}">… {more} more rows</td></tr>'
        return (
            f"<table><caption>{escape(caption)}</caption><thead><tr>{head}</tr></thead>"
            f"<tbody>{body}</tbody></table>"
        )

    tables = [table(t.caption, t.header, t.rows, t.more) for t in summary.tables]
    parts = [f"<div class='crankbalance-result'><h4>{escape(summary.title)}</h4>"]
    if summary.verdicts:
        items = "".join(f"<li>{escape(v)}</li>" for v in summary.verdicts)
        parts.append(f"<ul>{items}</ul>")
    parts += tables[:1]
    if summary.values:
        parts.append(table("values", ("quantity", "value"), summary.values))
    parts += tables[1:]
    if summary.notes:
        items = "".join(f"<li>{escape(v)}</li>" for v in summary.notes)
        parts.append(f"<details><summary>notes</summary><ul>{items}</ul></details>")
    parts.append("</div>")
    return "".join(parts)


class ResultMixin:
    """Mixin for frozen result dataclasses: ``to_dict()`` gives JSON-ready values, and a
    study result (a dataclass with ``repr=False``) displays itself in a notebook.

    The display is driven by ``to_dict()`` (:func:`summarize`: units from the keys'
    suffixes, round-off as 0) with the verdicts of :meth:`headline` and the table of
    :meth:`main_table` first: ``repr(result)`` is at most :data:`REPR_LINES` lines,
    ``result._repr_html_()`` the tables. Its figures are :func:`crankbalance.plot` of it.
    """

    def to_dict(self) -> dict[str, Any]:
        out = to_jsonable(self)
        assert isinstance(out, dict)
        return out

    def headline(self) -> tuple[str, ...]:
        """The key verdicts of the result, in sentences with units (none by default: the
        strings of ``to_dict()`` are shown)."""
        return ()

    def main_table(self) -> str:
        """The caption of the table the ``repr`` shows and the HTML display puts first
        (by default the first of ``to_dict()``)."""
        return ""

    def main_columns(self) -> tuple[str, ...]:
        """The JSON keys of the columns the table of :meth:`main_table` shows first (the
        ``repr`` shows its first :data:`REPR_COLUMNS`); by default its own order."""
        return ()

    def display_summary(self) -> Summary:
        """What the result shows in a notebook (:func:`summarize` of ``to_dict()``)."""
        data = self.to_dict()
        engine = data.get("engine")
        name = engine.get("name") if isinstance(engine, dict) else None
        title = type(self).__name__ + (f": {name}" if isinstance(name, str) else "")
        return summarize(title, data, self.headline(), self.main_table(), self.main_columns())

    def __repr__(self) -> str:
        return summary_text(self.display_summary())

    def _repr_html_(self) -> str:
        return summary_html(self.display_summary())
