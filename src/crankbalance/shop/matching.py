r"""Matching weighed parts to cylinders (issue 16, item 2; ``docs/balance_shop.md``,
"Parts and matching").

Each cylinder gets one part of every kind (piston, pin, ring set, locks, rod, bearing
shells). A part carries a *reciprocating* share (piston, pin, rings, locks, a rod's small
end) and a *rotating* share (a rod's big end, the shells); a cylinder's set weights are
the sums over its parts, plus an allowance per rod (the oil in the big end). Parts of a
kind may outnumber the cylinders (spares); the spares stay on the shelf.

Methods, all exact for the objective they state:

``"milp"``
    Least weighted spread (heaviest minus lightest set) of the reciprocating and rotating
    set weights, :math:`w_{rec}\,(\max_c W^{rec}_c - \min_c W^{rec}_c) +
    w_{rot}\,(\max_c W^{rot}_c - \min_c W^{rot}_c)`, over any number of kinds, by
    mixed-integer linear programming (``scipy.optimize.milp``, HiGHS, relative gap 0):
    binary :math:`x_{kic}` (part i of kind k in cylinder c), one part of each kind per
    cylinder, each part at most once, bounds :math:`L \le W_c \le U` and the objective
    :math:`U - L`. Cylinders are interchangeable for a spread, so the parts of the first
    kind are taken in increasing index along the cylinders (symmetry breaking).
``"pairing"``
    Two kinds paired on a separable objective by ``scipy.optimize.linear_sum_assignment``:
    the sum over the sets of the weighted squared deviation of the set weights from the
    mean, :math:`\sum_c w_{rec} (W^{rec}_c - \bar W^{rec})^2 + w_{rot} (W^{rot}_c -
    \bar W^{rot})^2` with :math:`\bar W` the mean of all listed parts (so the cost of a pair
    depends on the pair alone); with no spares this is the variance of the set weights
    times the number of cylinders.
``"exhaustive"``
    Every assignment (up to the order of the cylinders), for small sets: the check of the
    two others, on either objective.
``"as-listed"``
    Part i of every kind in cylinder i: the starting point the others improve on.

The alternative to matching is to machine every part of a kind to the lightest one used
(:func:`machine_to_lightest`); either way the material to remove is reported, per set
(matched) or per part (machined).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..results import ResultMixin

#: largest number of assignments the exhaustive search visits
EXHAUSTIVE_LIMIT = 2_000_000
#: objectives of the matching
OBJECTIVES = ("spread", "variance")
METHODS = ("milp", "pairing", "exhaustive", "as-listed")


@dataclass(frozen=True)
class PartKind(ResultMixin):
    """One kind of weighed part, each part with its reciprocating and rotating share.

    Attributes
    ----------
    name : str
        The kind as written in the parts file (``"piston"``, ``"rod"``).
    ids : tuple of str
        The parts' marks, in the order of the file.
    reciprocating : ndarray, shape (n,)
        Reciprocating share of each part [kg] (a rod's small end).
    rotating : ndarray, shape (n,)
        Rotating share of each part [kg] (a rod's big end).
    """

    name: str
    ids: tuple[str, ...]
    reciprocating: NDArray[np.float64]
    rotating: NDArray[np.float64]

    @property
    def count(self) -> int:
        """Number of parts of this kind."""
        return len(self.ids)


@dataclass(frozen=True)
class Inventory(ResultMixin):
    """Every weighed part of an engine, by kind, and the allowances added to every set.

    Attributes
    ----------
    kinds : tuple of PartKind
        The kinds of parts, in the order of the file.
    reciprocating_allowance : float
        Added to every set's reciprocating weight [kg].
    rotating_allowance : float
        Added to every set's rotating weight [kg] (the oil in the big end).
    """

    kinds: tuple[PartKind, ...]
    reciprocating_allowance: float = 0.0
    rotating_allowance: float = 0.0

    @property
    def names(self) -> tuple[str, ...]:
        """The kinds' names."""
        return tuple(kind.name for kind in self.kinds)

    def check(self, cylinders: int, field: str = "cylinders") -> None:
        """Raise :class:`InputError` unless every kind has a part for each of ``cylinders``.

        Parameters
        ----------
        cylinders : int
            Number of cylinders to fill.
        field : str
            How the user named the number of cylinders.
        """
        if isinstance(cylinders, bool) or not isinstance(cylinders, int) or cylinders < 1:
            raise InputError(field, cylinders, "must be a whole number of cylinders, 1 or more")
        if not self.kinds:
            raise InputError("parts", None, "lists no part; give at least one kind of part")
        for kind in self.kinds:
            if kind.count < cylinders:
                raise InputError(
                    kind.name,
                    kind.count,
                    f"parts listed; {cylinders} cylinders need at least {cylinders}",
                )


@dataclass(frozen=True)
class Matching(ResultMixin):
    """Parts matched to cylinders, the set weights and the material to remove per set.

    Attributes
    ----------
    method : str
        How the assignment was found (:data:`METHODS`).
    objective : str
        ``"spread"`` or ``"variance"`` (:data:`OBJECTIVES`).
    objective_value : float
        The objective reached [kg] (spread) or [kg^2] (variance).
    optimal : bool
        Whether the assignment is proven optimal for the objective (``as-listed`` never
        is; ``milp`` is unless it reached its time limit).
    bound : float
        Proven lower bound of the objective (the value itself when optimal; 0 for
        ``as-listed``) [kg] or [kg^2].
    kinds : tuple of str
        The kinds, in the order of ``part``.
    part : ndarray of int, shape (K, C)
        Index (0-based, file order) of the part of each kind in each cylinder.
    ids : tuple of tuple of str
        Per cylinder, the marks of its parts, one per kind.
    reciprocating, rotating : ndarray, shape (C,)
        Set weights per cylinder [kg], allowances included.
    reciprocating_spread, rotating_spread : float
        Heaviest minus lightest set [kg].
    remove_reciprocating, remove_rotating : ndarray, shape (C,)
        Material to remove per set to bring it to the lightest set [kg] (reciprocating:
        from the piston or the small end; rotating: from the big end).
    removed_total : float
        Sum of the material to remove [kg].
    """

    method: str
    objective: str
    objective_value: float
    optimal: bool
    bound: float
    kinds: tuple[str, ...]
    part: NDArray[np.int64]
    ids: tuple[tuple[str, ...], ...]
    reciprocating: NDArray[np.float64]
    rotating: NDArray[np.float64]
    reciprocating_spread: float
    rotating_spread: float
    remove_reciprocating: NDArray[np.float64]
    remove_rotating: NDArray[np.float64]
    removed_total: float


def _weights(weights: tuple[float, float]) -> tuple[float, float]:
    if len(weights) != 2 or not all(math.isfinite(w) and w >= 0 for w in weights):
        raise InputError("weights", weights, "must be two finite numbers >= 0 (rec, rot)")
    if not sum(weights) > 0:
        raise InputError("weights", weights, "must not both be zero")
    return float(weights[0]), float(weights[1])


def _set_weights(
    inventory: Inventory, part: NDArray[np.int64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Reciprocating and rotating weight of each set [kg], for ``part`` of shape (K, C)."""
    rec = np.full(part.shape[1], inventory.reciprocating_allowance)
    rot = np.full(part.shape[1], inventory.rotating_allowance)
    for kind, index in zip(inventory.kinds, part, strict=True):
        rec = rec + kind.reciprocating[index]
        rot = rot + kind.rotating[index]
    return rec, rot


def _means(inventory: Inventory) -> tuple[float, float]:
    """Mean set weights over all listed parts [kg] (the targets of the variance)."""
    rec = inventory.reciprocating_allowance + sum(
        float(k.reciprocating.mean()) for k in inventory.kinds
    )
    rot = inventory.rotating_allowance + sum(float(k.rotating.mean()) for k in inventory.kinds)
    return rec, rot


def objective_value(
    inventory: Inventory,
    part: NDArray[np.int64],
    objective: str = "spread",
    weights: tuple[float, float] = (1.0, 1.0),
) -> float:
    """The objective of an assignment (see the module docstring).

    Parameters
    ----------
    inventory : Inventory
        The parts.
    part : ndarray of int, shape (K, C)
        Index of the part of each kind in each cylinder.
    objective : {"spread", "variance"}
        Weighted spread [kg] or weighted sum of squared deviations from the mean of all
        listed parts [kg^2].
    weights : tuple of float
        Weights of the reciprocating and rotating terms [-].

    Returns
    -------
    float
        The objective [kg] or [kg^2].
    """
    w_rec, w_rot = _weights(weights)
    rec, rot = _set_weights(inventory, np.asarray(part))
    if objective == "spread":
        return w_rec * float(np.ptp(rec)) + w_rot * float(np.ptp(rot))
    if objective == "variance":
        mean_rec, mean_rot = _means(inventory)
        return w_rec * float(np.sum((rec - mean_rec) ** 2)) + w_rot * float(
            np.sum((rot - mean_rot) ** 2)
        )
    raise InputError("objective", objective, f"must be one of {', '.join(OBJECTIVES)}")


def match_parts(
    inventory: Inventory,
    cylinders: int,
    method: str = "milp",
    objective: str | None = None,
    weights: tuple[float, float] = (1.0, 1.0),
    time_limit: float = 60.0,
) -> Matching:
    """Assign parts to cylinders (see the module docstring for the methods).

    Parameters
    ----------
    inventory : Inventory
        The weighed parts.
    cylinders : int
        Number of cylinders (sets).
    method : {"milp", "pairing", "exhaustive", "as-listed"}
        How to assign.
    objective : {"spread", "variance"}, optional
        What to minimise: ``"spread"`` for ``milp``, ``"variance"`` for ``pairing`` (the
        only one each solves); ``exhaustive`` takes either (``"spread"`` by default).
    weights : tuple of float
        Weights of the reciprocating and rotating terms [-].
    time_limit : float
        Longest MILP solve [s]; when it is reached, the best assignment found is returned
        with ``optimal`` False and the proven lower ``bound`` of the objective.

    Returns
    -------
    Matching
        The assignment, set weights [kg] and material to remove [kg].

    Raises
    ------
    InputError
        If a kind has fewer parts than cylinders, the method does not solve the objective,
        ``pairing`` is asked for with other than two kinds, the exhaustive search would
        exceed :data:`EXHAUSTIVE_LIMIT` assignments, or the MILP found no assignment in
        its time limit.
    """
    inventory.check(cylinders)
    weights = _weights(weights)
    if method not in METHODS:
        raise InputError("method", method, f"must be one of {', '.join(METHODS)}")
    solves = {"milp": "spread", "pairing": "variance"}
    goal = objective or solves.get(method, "spread")
    if goal not in OBJECTIVES:
        raise InputError("objective", goal, f"must be one of {', '.join(OBJECTIVES)}")
    if method in solves and goal != solves[method]:
        raise InputError(
            "objective", goal, f"method {method!r} minimises the {solves[method]} only"
        )
    bound: float | None = None  # proven lower bound of the objective; None: optimal
    if method == "as-listed":
        part, bound = np.tile(np.arange(cylinders), (len(inventory.kinds), 1)), 0.0
    elif method == "pairing":
        part = _pairing(inventory, cylinders, weights)
    elif method == "exhaustive":
        part = _exhaustive(inventory, cylinders, goal, weights)
    else:
        part, bound = _milp(inventory, cylinders, weights, time_limit)
    return _matching(inventory, part, method, goal, weights, bound)


def _matching(
    inventory: Inventory,
    part: NDArray[np.int64],
    method: str,
    objective: str,
    weights: tuple[float, float],
    bound: float | None,
) -> Matching:
    part = np.asarray(part, dtype=np.int64)
    value = objective_value(inventory, part, objective, weights)
    rec, rot = _set_weights(inventory, part)
    remove_rec, remove_rot = rec - rec.min(), rot - rot.min()
    ids = tuple(
        tuple(kind.ids[i] for kind, i in zip(inventory.kinds, part[:, c], strict=True))
        for c in range(part.shape[1])
    )
    return Matching(
        method=method,
        objective=objective,
        objective_value=value,
        optimal=bound is None,
        bound=value if bound is None else min(bound, value),
        kinds=inventory.names,
        part=part,
        ids=ids,
        reciprocating=rec,
        rotating=rot,
        reciprocating_spread=float(np.ptp(rec)),
        rotating_spread=float(np.ptp(rot)),
        remove_reciprocating=remove_rec,
        remove_rotating=remove_rot,
        removed_total=float(remove_rec.sum() + remove_rot.sum()),
    )


def _pairing(
    inventory: Inventory, cylinders: int, weights: tuple[float, float]
) -> NDArray[np.int64]:
    """Two kinds paired by linear_sum_assignment on the separable squared deviation."""
    from scipy.optimize import linear_sum_assignment

    if len(inventory.kinds) != 2:
        raise InputError(
            "method",
            "pairing",
            f"pairs two kinds of parts; the inventory has {len(inventory.kinds)} "
            f"({', '.join(inventory.names)}): use 'milp'",
        )
    first, second = inventory.kinds
    mean_rec, mean_rot = _means(inventory)
    w_rec, w_rot = weights
    rec = (
        inventory.reciprocating_allowance
        + first.reciprocating[:, None]
        + second.reciprocating[None, :]
    )
    rot = inventory.rotating_allowance + first.rotating[:, None] + second.rotating[None, :]
    cost = w_rec * (rec - mean_rec) ** 2 + w_rot * (rot - mean_rot) ** 2
    if first.count == cylinders and second.count == cylinders:
        rows, cols = linear_sum_assignment(cost)
    else:
        rows, cols = _rectangular_pairs(cost, cylinders)
    return np.vstack([rows, cols]).astype(np.int64)


def _rectangular_pairs(cost: NDArray, cylinders: int) -> tuple[NDArray, NDArray]:
    """``cylinders`` pairs (one part of each kind per pair, each part at most once) of
    least total cost: an assignment of both kinds' parts to the pairs and to "unused".

    Each first-kind part i either starts pair (i, j) or is unused; the square problem has
    the first kind's parts plus the second kind's unused slots as rows and the second
    kind's parts plus the first kind's unused slots as columns: (n1 + n2 - C) each.
    """
    from scipy.optimize import linear_sum_assignment

    n1, n2 = cost.shape
    spare1, spare2 = n1 - cylinders, n2 - cylinders
    size = n1 + spare2
    big = float(np.max(cost)) * (size + 1) + 1.0
    square = np.full((size, n2 + spare1), big)
    square[:n1, :n2] = cost
    square[:n1, n2:] = 0.0  # first-kind part i unused
    square[n1:, :n2] = 0.0  # second-kind part j unused
    rows, cols = linear_sum_assignment(square)
    pairs = [(r, c) for r, c in zip(rows, cols, strict=True) if r < n1 and c < n2]
    if len(pairs) != cylinders:
        raise AssertionError("pairing: the square problem did not give one pair a cylinder")
    first, second = zip(*pairs, strict=True)
    return np.array(first), np.array(second)


def _exhaustive(
    inventory: Inventory, cylinders: int, objective: str, weights: tuple[float, float]
) -> NDArray[np.int64]:
    """Every assignment up to the order of the cylinders; the best (first found on ties)."""
    kinds = inventory.kinds
    count = math.comb(kinds[0].count, cylinders)
    for kind in kinds[1:]:
        count *= math.perm(kind.count, cylinders)
    if count > EXHAUSTIVE_LIMIT:
        raise InputError(
            "method",
            "exhaustive",
            f"would visit {count} assignments (at most {EXHAUSTIVE_LIMIT}); use 'milp'",
        )
    firsts = list(itertools.combinations(range(kinds[0].count), cylinders))
    others = [
        np.array(list(itertools.permutations(range(k.count), cylinders)), dtype=np.int64)
        for k in kinds[1:]
    ]
    best_value, best = math.inf, None
    for first in firsts:
        for rest in itertools.product(*(range(len(o)) for o in others)):
            part = np.array([first, *(o[i] for o, i in zip(others, rest, strict=True))])
            value = objective_value(inventory, part, objective, weights)
            if value < best_value:
                best_value, best = value, part
    assert best is not None
    return best


def _milp(
    inventory: Inventory, cylinders: int, weights: tuple[float, float], time_limit: float
) -> tuple[NDArray[np.int64], float | None]:
    """Least weighted spread by mixed-integer linear programming (module docstring)."""
    from scipy.optimize import Bounds, LinearConstraint, milp
    from scipy.sparse import lil_array

    kinds = inventory.kinds
    c_count = cylinders
    offsets = np.cumsum([0] + [k.count * c_count for k in kinds])
    n_x = int(offsets[-1])
    u_rec, l_rec, u_rot, l_rot = n_x, n_x + 1, n_x + 2, n_x + 3
    n_var = n_x + 4
    # grams: the set weights are hundreds, the spreads single units
    scale = 1000.0

    def var(k: int, i: int, c: int) -> int:
        return int(offsets[k]) + i * c_count + c

    rows: list[tuple[dict[int, float], float, float]] = []
    for k, kind in enumerate(kinds):
        for c in range(c_count):  # one part of each kind per cylinder
            rows.append(({var(k, i, c): 1.0 for i in range(kind.count)}, 1.0, 1.0))
        for i in range(kind.count):  # each part at most once (exactly when no spares)
            least = 1.0 if kind.count == c_count else 0.0
            rows.append(({var(k, i, c): 1.0 for c in range(c_count)}, least, 1.0))
    for c in range(c_count):
        for top, bottom, share, allowance in (
            (u_rec, l_rec, "reciprocating", inventory.reciprocating_allowance),
            (u_rot, l_rot, "rotating", inventory.rotating_allowance),
        ):
            weight = {
                var(k, i, c): scale * float(getattr(kind, share)[i])
                for k, kind in enumerate(kinds)
                for i in range(kind.count)
            }
            base = scale * allowance
            rows.append(({**weight, top: -1.0}, -np.inf, -base))  # W_c <= U
            rows.append(({**weight, bottom: -1.0}, -base, np.inf))  # W_c >= L
    # symmetry: cylinders are interchangeable for a spread, so the first kind's part
    # index increases along the cylinders (with no spares: part c in cylinder c)
    fixed = kinds[0].count == c_count
    for c in range(c_count - 1 if not fixed else 0):
        row = {var(0, i, c): float(i) for i in range(kinds[0].count)}
        for i in range(kinds[0].count):
            row[var(0, i, c + 1)] = row.get(var(0, i, c + 1), 0.0) - float(i)
        rows.append((row, -np.inf, -1.0))
    matrix = lil_array((len(rows), n_var))
    low = np.empty(len(rows))
    high = np.empty(len(rows))
    for r, (coefficients, lo, hi) in enumerate(rows):
        for column, value in coefficients.items():
            matrix[r, column] = value
        low[r], high[r] = lo, hi
    cost = np.zeros(n_var)
    w_rec, w_rot = weights
    cost[[u_rec, l_rec, u_rot, l_rot]] = [w_rec, -w_rec, w_rot, -w_rot]
    integrality = np.zeros(n_var)
    integrality[:n_x] = 1
    lower = np.zeros(n_var)
    upper = np.ones(n_var)
    lower[n_x:], upper[n_x:] = -np.inf, np.inf
    if fixed:
        upper[: c_count * c_count] = np.eye(c_count).ravel()
        lower[: c_count * c_count] = np.eye(c_count).ravel()
    result = milp(
        cost,
        constraints=LinearConstraint(matrix.tocsr(), low, high),
        integrality=integrality,
        bounds=Bounds(lower, upper),
        options={"mip_rel_gap": 0.0, "time_limit": float(time_limit)},
    )
    if result.x is None or result.status not in (0, 1):
        raise InputError(
            "method",
            "milp",
            f"found no assignment ({result.message}); give a longer time limit, or fewer "
            "spares or kinds",
        )
    x = np.round(result.x[:n_x]).astype(np.int64)
    part = np.empty((len(kinds), c_count), dtype=np.int64)
    for k, kind in enumerate(kinds):
        block = x[offsets[k] : offsets[k + 1]].reshape(kind.count, c_count)
        part[k] = np.argmax(block, axis=0)
    if result.status == 0:
        return part, None
    return part, max(float(result.mip_dual_bound or 0.0) / scale, 0.0)


@dataclass(frozen=True)
class MachineToLightest(ResultMixin):
    """Every part used machined to the lightest of its kind (share by share).

    The lightest ``C`` parts of each kind are used (ranked by their total mass); a rod's
    small end comes to the lightest small end and its big end to the lightest big end.

    Attributes
    ----------
    kinds : tuple of str
        The kinds.
    used : tuple of tuple of str
        Per kind, the marks of the parts used.
    remove_reciprocating, remove_rotating : tuple of ndarray
        Per kind, the material to remove from each used part's reciprocating and rotating
        share [kg].
    reciprocating, rotating : float
        The set weight every cylinder then has [kg].
    removed_total : float
        Sum of the material to remove [kg].
    """

    kinds: tuple[str, ...]
    used: tuple[tuple[str, ...], ...]
    remove_reciprocating: tuple[NDArray[np.float64], ...]
    remove_rotating: tuple[NDArray[np.float64], ...]
    reciprocating: float
    rotating: float
    removed_total: float


def machine_to_lightest(inventory: Inventory, cylinders: int) -> MachineToLightest:
    """The material to remove when every part is machined to the lightest of its kind.

    Parameters
    ----------
    inventory : Inventory
        The weighed parts.
    cylinders : int
        Number of cylinders: the lightest ``cylinders`` parts of each kind are used.

    Returns
    -------
    MachineToLightest
        Material to remove per part [kg] and the equal set weights [kg].
    """
    inventory.check(cylinders)
    used, off_rec, off_rot = [], [], []
    rec = inventory.reciprocating_allowance
    rot = inventory.rotating_allowance
    for kind in inventory.kinds:
        chosen = np.sort(np.argsort(kind.reciprocating + kind.rotating, kind="stable")[:cylinders])
        k_rec, k_rot = kind.reciprocating[chosen], kind.rotating[chosen]
        used.append(tuple(kind.ids[i] for i in chosen))
        off_rec.append(k_rec - k_rec.min())
        off_rot.append(k_rot - k_rot.min())
        rec += float(k_rec.min())
        rot += float(k_rot.min())
    total = float(sum(a.sum() for a in off_rec) + sum(a.sum() for a in off_rot))
    return MachineToLightest(
        inventory.names, tuple(used), tuple(off_rec), tuple(off_rot), rec, rot, total
    )
