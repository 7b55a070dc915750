"""Ranking candidates: filters, the Pareto front and a top-N table, all mergeable.

The columns are those of :func:`crankbalance.physics.explore.merit.merit` (name with a unit
suffix, ``F2_N``); a column may be named without its suffix (``F2``) wherever a name is
asked for. :func:`pareto` and :func:`top` can run chunk by chunk: applied to the
concatenation of the chunks' results they give the result of the whole
(``docs/explorer.md``, "Ranking").

A filter is a small expression language, parsed with Python's :mod:`ast` and evaluated
by walking the tree (never ``eval``): column names, numbers, ``+ - * /``, unary minus,
``abs(...)``, comparisons ``< <= > >= == !=`` (chained as in ``0 <= F1 < 5``), ``and``,
``or``, ``not`` and parentheses, e.g. ``"F1 == 0 and M1 == 0 and F2 <= 1e-6"``.

A filter is bounded before it is parsed: at most :data:`FILTER_CHARS` characters,
:data:`FILTER_OPERATORS` operators and :data:`FILTER_DEPTH` levels of brackets, counted in
the text (:func:`_count_operators`), so that neither :func:`ast.parse` nor the evaluation
(recursive, one level per operator or bracket: at most ``FILTER_OPERATORS +
FILTER_DEPTH + 1`` levels) can recurse deeply; its numbers are finite and at most
:data:`FILTER_NUMBER` in size.
"""

from __future__ import annotations

import ast
import difflib
import math
import operator
import re
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError
from ...records import record
from ...results import ROUND_OFF, EngineScales, round_off

#: the unit suffixes a column name may be written without
UNITS: tuple[str, ...] = ("N", "Nm", "kg", "rad")
#: rows of the sweep compared together in :func:`pareto` (bounds the temporaries)
BLOCK = 256

_COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
}
_ARITHMETIC: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
}
#: the other syntax-tree nodes of the filter language
_NODES: tuple[type, ...] = (
    ast.Expression,
    ast.BoolOp,
    ast.And,
    ast.Or,
    ast.UnaryOp,
    ast.Not,
    ast.USub,
    ast.UAdd,
) + (ast.Compare, ast.BinOp, ast.Load, *_COMPARE, *_ARITHMETIC)
_ALLOWED = (
    "column names, numbers, + - * /, abs(), comparisons < <= > >= == !=, and, or, not, parentheses"
)
#: longest filter [characters]
FILTER_CHARS = 1000
#: most operators in a filter: arithmetic, comparisons, ``and``, ``or``, ``not``, and any
#: other punctuation (the language has none, but it is counted before the parse refuses it)
FILTER_OPERATORS = 100
#: deepest nesting of brackets in a filter (``abs(...)`` counts as one)
FILTER_DEPTH = 20
#: largest size of a number in a filter [the unit of its column]: far beyond any figure of
#: merit (the free forces of a ship's engine are ~1e7 N), far below a float's 1.8e308
FILTER_NUMBER = 1e15
#: the tokens of a filter's text: a number (with its exponent's sign), a word, a two-character
#: operator, one other non-blank character
_TOKEN = re.compile(
    r"(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
    r"|(?P<word>[^\W\d]\w*)"
    r"|(?P<operator><=|>=|==|!=|\*\*|//|\S)"
)
#: words that are operators
_WORD_OPERATORS = frozenset({"and", "or", "not", "if", "else", "lambda", "for", "in", "is"})
#: words that stand for a number a filter does not take
_NOT_FINITE = frozenset({"inf", "infinity", "nan"})
#: the closest column names shown for an unknown one
CLOSEST = 3


def column_name(name: str, columns: Iterable[str], field: str = "column") -> str:
    """The column a name stands for: the name itself, or the column it is without its unit.

    Parameters
    ----------
    name : str
        ``F2_N`` or ``F2``.
    columns : iterable of str
        The column names.
    field : str
        The field to name in the error (``--objectives``, ``--top-key``, ...).

    Returns
    -------
    str
        The column name.

    Raises
    ------
    InputError
        If no column has that name.
    """
    names = list(columns)
    if name in names:
        return name
    for unit in UNITS:
        if f"{name}_{unit}" in names:
            return f"{name}_{unit}"
    raise InputError(field, name, _unknown(name, names))


def _unknown(name: str, columns: list[str]) -> str:
    """What to say of an unknown column: the closest names (never the whole list, which has
    hundreds of names at ``--orders 64``) and where the columns are listed."""
    short = list(dict.fromkeys(_short(columns)))
    same = [c for c in short if c.lower() == name.lower()]  # "f1": F1 first
    close = same + difflib.get_close_matches(name, short, n=CLOSEST, cutoff=0.5)
    close = list(dict.fromkeys(close))[:CLOSEST]
    hint = f"closest: {', '.join(close)}" if close else "no column has a similar name"
    return f"a column of the explorer ({hint}; all in docs/explorer.md, 'Figures of merit')"


def _short(columns: list[str]) -> list[str]:
    """Column names without their unit suffixes, for messages."""
    out = []
    for name in columns:
        base, _, unit = name.rpartition("_")
        out.append(base if base and unit in UNITS else name)
    return out


@record
class Filter:
    """A parsed filter: call it on the columns to get the mask of the rows it keeps.

    Parameters
    ----------
    text : str
        The filter as written.
    tree : ast.Expression
        Its syntax tree, checked by :func:`parse_filter`.
    field : str
        The field its errors name.
    """

    text: str
    tree: ast.Expression
    field: str = "filter"

    def __call__(self, values: Mapping[str, ArrayLike]) -> NDArray[np.bool_]:
        """Mask of the rows the filter keeps.

        Parameters
        ----------
        values : mapping of str to array_like, each shape (B,)
            The columns [their units].

        Returns
        -------
        ndarray of bool, shape (B,)
            True where the row passes.
        """
        size = np.shape(next(iter(values.values())))[0] if values else 0
        result = np.asarray(self._evaluate(self.tree.body, values))
        if result.dtype != bool:
            raise self._error("a condition (a comparison), not a number")
        return np.broadcast_to(result, (size,)).copy()

    def _error(self, allowed: str) -> InputError:
        return InputError(self.field, self.text, allowed)

    def _evaluate(self, node: ast.AST, values: Mapping[str, ArrayLike]) -> Any:
        if isinstance(node, ast.BoolOp):
            parts = [self._condition(v, values) for v in node.values]
            join = np.logical_and if isinstance(node.op, ast.And) else np.logical_or
            out = parts[0]
            for part in parts[1:]:
                out = join(out, part)
            return out
        if isinstance(node, ast.UnaryOp):
            if isinstance(node.op, ast.Not):
                return np.logical_not(self._condition(node.operand, values))
            value = self._number(node.operand, values)
            return -value if isinstance(node.op, ast.USub) else value
        if isinstance(node, ast.Compare):
            left = self._number(node.left, values)
            out = None
            for op, right_node in zip(node.ops, node.comparators, strict=True):
                right = self._number(right_node, values)
                step = _COMPARE[type(op)](left, right)
                out = step if out is None else np.logical_and(out, step)
                left = right
            return out
        if isinstance(node, ast.BinOp):
            left, right = self._number(node.left, values), self._number(node.right, values)
            # x / 0 is ±inf, 0 / 0 and inf - inf NaN (a comparison with NaN is false), an
            # overflow ±inf: no warning (docs/explorer.md, "Ranking")
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                return _ARITHMETIC[type(node.op)](left, right)
        if isinstance(node, ast.Call):
            return np.abs(self._number(node.args[0], values))
        if isinstance(node, ast.Name):
            return np.asarray(values[column_name(node.id, values, self.field)], dtype=float)
        if isinstance(node, ast.Constant):
            return float(node.value)  # type: ignore[arg-type]  # parse_filter: a number
        raise self._error(_ALLOWED)  # parse_filter lets no other node through

    def _condition(self, node: ast.AST, values: Mapping[str, ArrayLike]) -> Any:
        value = np.asarray(self._evaluate(node, values))
        if value.dtype != bool:
            raise self._error("and, or and not join conditions (comparisons), not numbers")
        return value

    def _number(self, node: ast.AST, values: Mapping[str, ArrayLike]) -> Any:
        value = np.asarray(self._evaluate(node, values))
        if value.dtype == bool:
            raise self._error("a comparison compares numbers, not conditions")
        return value


def parse_filter(text: str, columns: Iterable[str], field: str = "filter") -> Filter:
    """Parse and check a filter against the column names, once, before any run.

    Parameters
    ----------
    text : str
        The filter, e.g. ``"F1 == 0 and M1 == 0"`` (see the module docstring).
    columns : iterable of str
        The columns the filter may name (with or without their unit suffixes).
    field : str
        The field to name in errors (``--filter`` on the command line).

    Returns
    -------
    Filter
        The parsed filter, to call on each chunk's columns.

    Raises
    ------
    InputError
        Naming ``field`` and the filter text: a syntax error, an element outside the
        language, an unknown column, or numbers where conditions belong.
    """
    names = list(columns)
    if not isinstance(text, str):
        raise InputError(field, text, f"a text; {_ALLOWED}")
    _check_size(text, field)
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as error:
        raise InputError(field, text, f"not an expression ({error.msg}); {_ALLOWED}") from None
    except ValueError as error:  # a NUL character (Python 3.11)
        raise InputError(field, text, f"not an expression ({error}); {_ALLOWED}") from None
    functions = {id(node.func) for node in ast.walk(tree) if isinstance(node, ast.Call)}
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and id(node) not in functions:
            if node.id.lower() in _NOT_FINITE:
                raise InputError(field, text, f"{node.id!r}: {_NUMBERS}")
            try:
                column_name(node.id, names, field)
            except InputError as error:
                unknown = f"unknown column {node.id!r}; {error.allowed}"
                raise InputError(field, text, unknown) from None
            continue
        if isinstance(node, ast.Constant):
            if not isinstance(node.value, int | float) or isinstance(node.value, bool):
                raise InputError(field, text, f"{node.value!r} is not a number; {_ALLOWED}")
            if not _bounded(node.value):
                raise InputError(field, text, f"{_literal(text, node)}: {_NUMBERS}")
            continue
        if isinstance(node, ast.Call):
            plain = isinstance(node.func, ast.Name) and node.func.id == "abs"
            if not plain or len(node.args) != 1 or node.keywords:
                raise InputError(field, text, f"the one function is abs(x); {_ALLOWED}")
            continue
        if isinstance(node, ast.Name):  # the name of the function abs
            continue
        if not isinstance(node, _NODES):
            raise InputError(field, text, _ALLOWED)
    parsed = Filter(text, tree, field)
    probe = {name: np.zeros(1) for name in names}
    parsed(probe)  # types: conditions where conditions belong
    return parsed


_NUMBERS = "numbers in a filter are finite and at most {} in size".format(
    f"{FILTER_NUMBER:g}".replace("e+", "e")
)


def _bounded(value: int | float) -> bool:
    """Whether a literal is finite and at most :data:`FILTER_NUMBER` in size (an integer is
    compared as an integer: ``10**400`` is never converted to a float)."""
    if isinstance(value, int):
        return abs(value) <= int(FILTER_NUMBER)
    return math.isfinite(value) and abs(value) <= FILTER_NUMBER


def _literal(text: str, node: ast.Constant) -> str:
    """The number as written (shortened), for the message."""
    written = ast.get_source_segment(text.strip(), node) or repr(node.value)
    return repr(written if len(written) <= 24 else written[:21] + "...")


def _count_operators(text: str) -> tuple[int, int]:
    """Operators and the deepest nesting of brackets in a filter's text, counted from its
    tokens (:data:`_TOKEN`) without parsing it: every non-word, non-number character other
    than a closing bracket is an operator (``(`` too), and so are the words ``and``, ``or``,
    ``not`` and the other Python words that build expressions."""
    operators = depth = deepest = 0
    for match in _TOKEN.finditer(text):
        kind, token = match.lastgroup, match.group()
        if kind == "word":
            operators += token in _WORD_OPERATORS
        elif kind == "operator":
            if token in ")]}":
                depth -= 1
                continue
            operators += 1
            if token in "([{":
                depth += 1
                deepest = max(deepest, depth)
    return operators, deepest


def _check_size(text: str, field: str) -> None:
    """Refuse a filter longer, with more operators or deeper than the limits, before any
    parse (so that the parser's and the evaluation's recursion stay bounded)."""
    if len(text) > FILTER_CHARS:
        raise InputError(
            field, text, f"at most {FILTER_CHARS} characters (this one has {len(text):,})"
        )
    operators, depth = _count_operators(text)
    if operators > FILTER_OPERATORS:
        raise InputError(
            field,
            text,
            f"at most {FILTER_OPERATORS} operators and brackets (this one has {operators})",
        )
    if depth > FILTER_DEPTH:
        raise InputError(
            field, text, f"brackets nested at most {FILTER_DEPTH} deep (this one: {depth})"
        )


def tolerances(names: Iterable[str], engine: EngineScales[float]) -> NDArray[np.float64]:
    r"""Round-off tolerance of each objective, from the engine's scale (the one rule of
    :func:`crankbalance.results.round_off`).

    A column's unit suffix gives its level: ``_N`` the engine's force round-off, ``_Nm``
    its moment round-off, ``_kg`` :data:`~crankbalance.results.ROUND_OFF` times the
    engine's mass (the force level over :math:`r\omega^2`), ``_rad``
    :data:`~crankbalance.results.ROUND_OFF` times π (the largest angle of those columns),
    and a pure number :data:`~crankbalance.results.ROUND_OFF` (shares of 1, counts).

    Parameters
    ----------
    names : iterable of str
        The objectives' column names, with their unit suffixes.
    engine : EngineModel
        The engine every candidate shares: masses [kg], throw positions [m], crank radius
        [m] and speed [rad/s] (the topology of the explorer's problem).

    Returns
    -------
    ndarray, shape (K,)
        The tolerance of each objective [its unit].
    """
    force, moment = round_off(engine)
    mass = force / (engine.crank_radius * engine.speed**2)
    level = {"N": force, "Nm": moment, "kg": mass, "rad": ROUND_OFF * math.pi}
    out = []
    for name in names:
        base, _, unit = name.rpartition("_")
        out.append(level[unit] if base and unit in level else ROUND_OFF)
    return np.asarray(out, dtype=float)


def pareto(values: ArrayLike, tolerance: ArrayLike = 0.0) -> NDArray[np.bool_]:
    r"""Mask of the rows no other row dominates (every objective minimised).

    Row j dominates row i when it is no worse in every column and better in one, both
    beyond the column's ``tolerance``: :math:`v_{jk} \le v_{ik} + t_k` for every k and
    :math:`v_{jk} < v_{ik} - t_k` for one. Rows equal within the tolerance (differing by
    round-off) do not dominate each other, so both stay. Mergeable: for any split of the
    rows, ``pareto`` of the rows kept by ``pareto`` of each part is ``pareto`` of all.

    Parameters
    ----------
    values : array_like, shape (B, K)
        The objectives of each row [their units]; NaN is not allowed.
    tolerance : array_like, shape (K,) or scalar
        The round-off of each objective [its unit] (:func:`tolerances`), at least 0;
        default 0 (exact comparison).

    Returns
    -------
    ndarray of bool, shape (B,)
        True for the rows of the Pareto front.

    Notes
    -----
    The rows are sorted lexicographically, so a row is dominated exactly (tolerance 0)
    only by one before it, and a row dominated by a dominated row is dominated by a row of
    the front (dominance is transitive). Equal rows are swept once. One sweep in blocks
    compares each block with the front found so far and with itself: about B·F·K
    comparisons for a front of F rows. With a tolerance a row can be dominated by one
    after it (its first objective larger by less than the tolerance), so a last pass
    compares the front with itself (F·F·K).
    Transitivity holds with a tolerance as long as values closer than the tolerance are
    round-off of one value, as every figure of merit's are (docs/explorer.md, "Ranking").
    """
    v = np.asarray(values, dtype=float)
    if v.ndim != 2:
        raise InputError("pareto", list(v.shape), "a (rows, objectives) array")
    if np.isnan(v).any():
        raise InputError("pareto", "NaN", "finite or infinite objectives, not NaN")
    tol = np.broadcast_to(np.asarray(tolerance, dtype=float), (v.shape[1],))
    if not (np.isfinite(tol).all() and (tol >= 0).all()):
        raise InputError("tolerance", tol.tolist(), "finite numbers of 0 or more")
    order = np.lexsort(v.T[::-1]) if v.shape[1] else np.arange(v.shape[0])
    sorted_v = v[order]
    if v.shape[0] > 1 and v.shape[1]:
        # equal rows share their fate (they never dominate one another and dominate the
        # same rows): the sweep runs over the distinct rows only (the explorer's
        # candidates of one crank have equal forces and moments)
        fresh = np.concatenate([[True], np.any(sorted_v[1:] != sorted_v[:-1], axis=1)])
        if not fresh.all():
            keep = np.zeros(v.shape[0], bool)
            keep[order] = pareto(sorted_v[fresh], tol)[np.cumsum(fresh) - 1]
            return keep
    kept: list[NDArray[np.int64]] = []
    front = np.empty((0, v.shape[1]))
    for start in range(0, v.shape[0], BLOCK):
        block = sorted_v[start : start + BLOCK]
        alive = np.flatnonzero(~_dominated(block, front, tol))
        alive = alive[~_dominated_within(block[alive], tol)]
        kept.append(start + alive)
        front = np.concatenate([front, block[alive]])
    rows = np.concatenate(kept) if kept else np.zeros(0, np.int64)
    if tol.any():  # a row dominated by one after it in the sort
        rows = rows[~_dominated_within(front, tol)]
    keep = np.zeros(v.shape[0], bool)
    keep[order[rows]] = True
    return keep


#: :func:`_dominated_within` compares every row first with each objective's smallest row
#: and every PROBE-th row
PROBE = 16


def _dominated_within(rows: NDArray, tol: NDArray) -> NDArray[np.bool_]:
    """``_dominated(rows, rows, tol)``, the rows first compared with a few of them (each
    objective's smallest row and every :data:`PROBE`-th row: strong ones, the rows being
    sorted), and only those none of these dominates compared with all (the same answer: a
    row is dominated when one of the rows dominates it)."""
    if rows.shape[0] <= PROBE:
        return _dominated(rows, rows, tol)
    probe = np.unique(np.r_[np.argmin(rows, axis=0), np.arange(0, rows.shape[0], PROBE)])
    out = _dominated(rows, rows[probe], tol)
    rest = np.flatnonzero(~out)
    out[rest] = _dominated(rows[rest], rows, tol)
    return out


def _dominated(rows: NDArray, by: NDArray, tol: NDArray) -> NDArray[np.bool_]:
    """Whether each of ``rows`` is dominated by one of ``by`` beyond ``tol`` (a block of
    each at once, objective by objective: (rows, by) temporaries, never (rows, by, K))."""
    out = np.zeros(rows.shape[0], bool)
    for first in range(0, rows.shape[0], 16 * BLOCK):
        r = rows[first : first + 16 * BLOCK]
        for start in range(0, by.shape[0], 16 * BLOCK):
            b = by[start : start + 16 * BLOCK]
            no_worse = np.ones((r.shape[0], b.shape[0]), bool)
            better = np.zeros_like(no_worse)
            for k in range(r.shape[1]):
                mine, theirs = r[:, k, None], b[None, :, k]
                no_worse &= theirs <= mine + tol[k]
                better |= theirs < mine - tol[k]
            out[first : first + r.shape[0]] |= (no_worse & better).any(axis=1)
    return out


def top(
    values: Mapping[str, ArrayLike],
    key: str,
    n: int,
    index: ArrayLike | None = None,
    field: str = "top",
) -> NDArray[np.int64]:
    """Positions of the ``n`` rows with the smallest ``key``, best first.

    Ties are broken by ``index`` (the candidates' enumeration index), so the choice does
    not depend on the order of the rows: ``top`` of the rows kept by ``top`` of each
    chunk is ``top`` of all.

    Parameters
    ----------
    values : mapping of str to array_like, each shape (B,)
        The columns [their units].
    key : str
        The column to minimise (with or without its unit suffix).
    n : int
        How many rows (fewer when there are fewer).
    index : array_like of int, shape (B,), optional
        Tie-break [-]: the candidates' enumeration index; default the row positions.
    field : str
        The field to name in errors.

    Returns
    -------
    ndarray of int, shape (min(n, B),)
        Row positions, the smallest ``key`` first.

    Raises
    ------
    InputError
        For an unknown column or an ``n`` below 1.
    """
    if not (isinstance(n, int | np.integer) and n >= 1):
        raise InputError(field, n, "an integer of 1 or more")
    column = np.asarray(values[column_name(key, values, field)], dtype=float)
    tie = np.arange(column.size) if index is None else np.asarray(index)
    return np.lexsort((tie, column))[:n]
