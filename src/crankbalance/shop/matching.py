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
``"milp"`` with ``objective="free"``
    Least free forces and couples the sets cause in the running engine, orders 1 to
    ``orders``, with the crank balanced for the mean set (one bob-weight per pin, rotating
    share plus ``fraction`` of the reciprocating share of the mean of all listed parts):
    the sum over the orders of the largest force plus the largest couple divided by the
    half-length of the crank, each phasor's magnitude measured by the regular polygon of
    :data:`POLYGON_SIDES` sides (``max_k Re(z e^{-i 2 pi k / K})``, within
    :math:`\cos(\pi/K)` of :math:`|z|`, linear in the assignment: exact for that
    measure); the true amplitudes are reported. The cylinders are not interchangeable
    here, so there is no symmetry breaking.
``"pairing"``
    Two kinds paired on a separable objective by ``scipy.optimize.linear_sum_assignment``:
    the sum over the sets of the weighted squared deviation of the set weights from the
    mean, :math:`\sum_c w_{rec} (W^{rec}_c - \bar W^{rec})^2 + w_{rot} (W^{rot}_c -
    \bar W^{rot})^2` with :math:`\bar W` the mean of all listed parts (so the cost of a pair
    depends on the pair alone); with no spares this is the variance of the set weights
    times the number of cylinders.
``"exhaustive"``
    Every assignment (up to the order of the cylinders, except for the free forces), for
    small sets: the check of the others, on any objective.
``"as-listed"``
    Part i of every kind in cylinder i: the starting point the others improve on.

The alternative to matching is to machine every part of a kind to the lightest one used
(:func:`machine_to_lightest`); either way the material to remove is reported, per set
(matched) or per part (machined).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..model import EngineModel
from ..results import ResultMixin
from ..shaking import free_forces

#: largest number of assignments the exhaustive search visits
EXHAUSTIVE_LIMIT = 2_000_000
#: objectives of the matching
OBJECTIVES = ("spread", "variance", "free")
#: sides of the polygon that measures a phasor's magnitude in the free-force objective
POLYGON_SIDES = 16
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
    free_force, free_couple : ndarray, shape (orders,)
        With the free-force objective: the largest free force [N] and couple [N*m] of
        each order the sets cause (crank balanced for the mean set); empty otherwise.
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
    free_force: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    free_couple: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))


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


@dataclass(frozen=True)
class FreeForceBasis(ResultMixin):
    """The free-force phasors of the sets, linear in the parts' masses.

    Component j of the phasors is, for order n = j // 4 + 1, the forward force, the
    backward force, the forward couple / ``length`` and the backward couple / ``length``.

    Attributes
    ----------
    reciprocating : ndarray of complex, shape (C, J)
        Phasors of 1 kg of reciprocating mass in each cylinder [N/kg].
    rotating : ndarray of complex, shape (C, J)
        Phasors of 1 kg of rotating mass on each cylinder's pin [N/kg].
    constant : ndarray of complex, shape (J,)
        Phasors of the allowances and of the crank balanced for the mean set [N].
    length : float
        Half-length of the crank, the couples' divisor [m].
    orders : int
        Highest order.
    """

    reciprocating: NDArray[np.complex128]
    rotating: NDArray[np.complex128]
    constant: NDArray[np.complex128]
    length: float
    orders: int


def _components(model: EngineModel, length: float, orders: int) -> NDArray[np.complex128]:
    """The phasor components of an engine's free forces (FreeForceBasis order)."""
    forces = free_forces(model, orders)
    fwd = forces.force_forward.copy()
    cfwd = forces.couple_forward.copy()
    fwd[0] += forces.rotating_force
    cfwd[0] += forces.rotating_couple
    return np.stack(
        [fwd, forces.force_backward, cfwd / length, forces.couple_backward / length], axis=1
    ).ravel()


def free_force_basis(
    model: EngineModel, inventory: Inventory, fraction: float = 0.5, orders: int = 2
) -> FreeForceBasis:
    """The free-force phasors the sets cause, per kilogram in each cylinder.

    Parameters
    ----------
    model : EngineModel
        The engine (layout, kinematics, speed); its masses are not used.
    inventory : Inventory
        The parts: the mean of all listed parts is the set the crank is balanced for.
    fraction : float
        Fraction of the reciprocating share in the bob-weights [-].
    orders : int
        Highest order (1 to 8).

    Returns
    -------
    FreeForceBasis
        Phasors per kilogram [N/kg] and the constant part [N].
    """
    from ..single_cylinder import check_balance_factor

    check_balance_factor(fraction, "fraction")
    if isinstance(orders, bool) or not isinstance(orders, int) or not 1 <= orders <= 8:
        raise InputError("orders", orders, "must be a whole number from 1 to 8")
    count, throws = model.cylinders, model.throws
    length = float(np.max(np.abs(model.throw_position))) or float(model.crank_radius)
    none = replace(
        model,
        reciprocating_mass=np.zeros(count),
        throw_rotating_mass=np.zeros(throws),
        cylinder_rotating_mass=np.zeros(count),
    )
    rec = np.array(
        [
            _components(replace(none, reciprocating_mass=np.eye(count)[c]), length, orders)
            for c in range(count)
        ]
    )
    pins = np.eye(throws)[model.cylinder_throw]
    # 1 kg on cylinder c's big end: on its throw, at its rod's axial place on the pin
    rot = np.array(
        [
            _components(
                replace(none, throw_rotating_mass=pin, cylinder_rotating_mass=np.eye(count)[c]),
                length,
                orders,
            )
            for c, pin in enumerate(pins)
        ]
    )
    mean_rec, mean_rot = _means(inventory)
    rods = np.bincount(model.cylinder_throw, minlength=throws)
    # the crank, balanced for the mean set
    balance = np.asarray(-rods * (mean_rot + fraction * mean_rec), dtype=np.float64)
    constant = _components(replace(none, throw_rotating_mass=balance), length, orders)
    constant = constant + rec.sum(axis=0) * inventory.reciprocating_allowance
    constant = constant + rot.sum(axis=0) * inventory.rotating_allowance
    return FreeForceBasis(rec, rot, constant, length, orders)


def _polygon(z: NDArray[np.complex128]) -> NDArray[np.float64]:
    """The polygonal magnitude of phasors: max over the sides of Re(z e^-i theta_k)."""
    turns = np.exp(-2j * np.pi * np.arange(POLYGON_SIDES) / POLYGON_SIDES)
    return np.max((np.asarray(z)[..., None] * turns).real, axis=-1)


def _phasors(inventory: Inventory, part: NDArray, basis: FreeForceBasis) -> NDArray:
    """The free-force phasors of an assignment [N]."""
    rec, rot = _set_weights(inventory, part)
    rec = rec - inventory.reciprocating_allowance  # the allowances are in the constant
    rot = rot - inventory.rotating_allowance
    return basis.constant + rec @ basis.reciprocating + rot @ basis.rotating


def objective_value(
    inventory: Inventory,
    part: NDArray[np.int64],
    objective: str = "spread",
    weights: tuple[float, float] = (1.0, 1.0),
    basis: FreeForceBasis | None = None,
) -> float:
    """The objective of an assignment (see the module docstring).

    Parameters
    ----------
    inventory : Inventory
        The parts.
    part : ndarray of int, shape (K, C)
        Index of the part of each kind in each cylinder.
    objective : {"spread", "variance", "free"}
        Weighted spread [kg], weighted sum of squared deviations from the mean of all
        listed parts [kg^2], or the free forces and couples (module docstring) [N].
    weights : tuple of float
        Weights of the reciprocating and rotating terms [-].
    basis : FreeForceBasis, optional
        The engine's phasors, for the ``"free"`` objective.

    Returns
    -------
    float
        The objective [kg], [kg^2] or, for ``"free"``, [N].
    """
    if objective == "free":
        if basis is None:
            raise InputError("objective", objective, "needs the engine (model)")
        return float(np.sum(_polygon(_phasors(inventory, np.asarray(part), basis))))
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
    model: EngineModel | None = None,
    fraction: float = 0.5,
    orders: int = 2,
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
    objective : {"spread", "variance", "free"}, optional
        What to minimise: ``"spread"`` (default) or ``"free"`` for ``milp``, ``"variance"``
        for ``pairing``; ``exhaustive`` takes any.
    weights : tuple of float
        Weights of the reciprocating and rotating terms [-].
    time_limit : float
        Longest MILP solve [s]; when it is reached, the best assignment found is returned
        with ``optimal`` False and the proven lower ``bound`` of the objective.
    model : EngineModel, optional
        The engine, for the ``"free"`` objective (its layout, kinematics and speed).
    fraction : float
        Fraction of the reciprocating share in the bob-weights [-] (``"free"``).
    orders : int
        Highest order of the free forces (``"free"``).

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
    solves = {"milp": ("spread", "free"), "pairing": ("variance",)}
    goal = objective or solves.get(method, ("spread",))[0]
    if goal not in OBJECTIVES:
        raise InputError("objective", goal, f"must be one of {', '.join(OBJECTIVES)}")
    if method in solves and goal not in solves[method]:
        raise InputError(
            "objective", goal, f"method {method!r} minimises the {' or '.join(solves[method])}"
        )
    basis = None
    if goal == "free":
        if model is None:
            raise InputError("objective", goal, "needs the engine (model) the sets go in")
        if model.cylinders != cylinders:
            raise InputError(
                "cylinders", cylinders, f"must be the engine's {model.cylinders} cylinders"
            )
        basis = free_force_basis(model, inventory, fraction, orders)
    bound: float | None = None  # proven lower bound of the objective; None: optimal
    if method == "as-listed":
        part, bound = np.tile(np.arange(cylinders), (len(inventory.kinds), 1)), 0.0
    elif method == "pairing":
        part = _pairing(inventory, cylinders, weights)
    elif method == "exhaustive":
        part = _exhaustive(inventory, cylinders, goal, weights, basis)
    else:
        part, bound = _milp(inventory, cylinders, weights, time_limit, basis)
    return _matching(inventory, part, method, goal, weights, bound, basis)


def _matching(
    inventory: Inventory,
    part: NDArray[np.int64],
    method: str,
    objective: str,
    weights: tuple[float, float],
    bound: float | None,
    basis: FreeForceBasis | None = None,
) -> Matching:
    part = np.asarray(part, dtype=np.int64)
    value = objective_value(inventory, part, objective, weights, basis)
    force = couple = np.zeros(0)
    if basis is not None:
        z = np.abs(_phasors(inventory, part, basis)).reshape(basis.orders, 4)
        force = z[:, 0] + z[:, 1]
        couple = (z[:, 2] + z[:, 3]) * basis.length
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
        free_force=force,
        free_couple=couple,
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
    assert len(pairs) == cylinders, "the square problem gives exactly one pair per cylinder"
    first, second = zip(*pairs, strict=True)
    return np.array(first), np.array(second)


def _exhaustive(
    inventory: Inventory,
    cylinders: int,
    objective: str,
    weights: tuple[float, float],
    basis: FreeForceBasis | None,
) -> NDArray[np.int64]:
    """Every assignment (up to the order of the cylinders, unless the objective is the free
    force); the best (first found on ties)."""
    kinds = inventory.kinds
    ordered = objective == "free"  # the cylinders are not interchangeable
    count = (math.perm if ordered else math.comb)(kinds[0].count, cylinders)
    for kind in kinds[1:]:
        count *= math.perm(kind.count, cylinders)
    if count > EXHAUSTIVE_LIMIT:
        raise InputError(
            "method",
            "exhaustive",
            f"would visit {count} assignments (at most {EXHAUSTIVE_LIMIT}); use 'milp'",
        )
    choose = itertools.permutations if ordered else itertools.combinations
    firsts = list(choose(range(kinds[0].count), cylinders))
    others = [
        np.array(list(itertools.permutations(range(k.count), cylinders)), dtype=np.int64)
        for k in kinds[1:]
    ]
    best_value, best = math.inf, None
    for first in firsts:
        for rest in itertools.product(*(range(len(o)) for o in others)):
            part = np.array([first, *(o[i] for o, i in zip(others, rest, strict=True))])
            value = objective_value(inventory, part, objective, weights, basis)
            if value < best_value:
                best_value, best = value, part
    assert best is not None
    return best


def _milp(
    inventory: Inventory,
    cylinders: int,
    weights: tuple[float, float],
    time_limit: float,
    basis: FreeForceBasis | None = None,
) -> tuple[NDArray[np.int64], float | None]:
    """The least weighted spread, or with ``basis`` the least free forces, by mixed-integer
    linear programming (module docstring)."""
    from scipy.optimize import Bounds, LinearConstraint, milp
    from scipy.sparse import lil_array

    kinds = inventory.kinds
    c_count = cylinders
    offsets = np.cumsum([0] + [k.count * c_count for k in kinds])
    n_x = int(offsets[-1])

    def var(k: int, i: int, c: int) -> int:
        return int(offsets[k]) + i * c_count + c

    rows: list[tuple[dict[int, float], float, float]] = []
    for k, kind in enumerate(kinds):
        for c in range(c_count):  # one part of each kind per cylinder
            rows.append(({var(k, i, c): 1.0 for i in range(kind.count)}, 1.0, 1.0))
        for i in range(kind.count):  # each part at most once (exactly when no spares)
            least = 1.0 if kind.count == c_count else 0.0
            rows.append(({var(k, i, c): 1.0 for c in range(c_count)}, least, 1.0))
    if basis is None:
        scale, cost_extra, fixed = _spread_rows(inventory, c_count, var, n_x, weights, rows)
    else:
        scale, cost_extra, fixed = _free_rows(inventory, c_count, var, n_x, basis, rows)
    n_var = n_x + cost_extra.size
    matrix = lil_array((len(rows), n_var))
    low = np.empty(len(rows))
    high = np.empty(len(rows))
    for r, (coefficients, lo, hi) in enumerate(rows):
        for column, value in coefficients.items():
            matrix[r, column] = value
        low[r], high[r] = lo, hi
    cost = np.concatenate([np.zeros(n_x), cost_extra])
    integrality = np.zeros(n_var)
    integrality[:n_x] = 1
    lower = np.zeros(n_var)
    upper = np.ones(n_var)
    lower[n_x:], upper[n_x:] = -np.inf, np.inf
    if fixed:  # the first kind's part c in cylinder c
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


Rows = list[tuple[dict[int, float], float, float]]


def _spread_rows(
    inventory: Inventory,
    c_count: int,
    var: Callable[[int, int, int], int],
    n_x: int,
    weights: tuple[float, float],
    rows: Rows,
) -> tuple[float, NDArray[np.float64], bool]:
    """Rows and costs of the spread: L <= W_c <= U per share; the symmetry breaking."""
    kinds = inventory.kinds
    u_rec, l_rec, u_rot, l_rot = n_x, n_x + 1, n_x + 2, n_x + 3
    scale = 1000.0  # grams: the set weights are hundreds, the spreads single units
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
    w_rec, w_rot = weights
    return scale, np.array([w_rec, -w_rec, w_rot, -w_rot]), fixed


def _free_rows(
    inventory: Inventory,
    c_count: int,
    var: Callable[[int, int, int], int],
    n_x: int,
    basis: FreeForceBasis,
    rows: Rows,
) -> tuple[float, NDArray[np.float64], bool]:
    """Rows and costs of the free forces: Re(z_j e^-i theta_k) <= t_j, minimise sum t_j."""
    turns = np.exp(-2j * np.pi * np.arange(POLYGON_SIDES) / POLYGON_SIDES)
    components = basis.constant.size
    for j in range(components):
        for turn in turns:
            row: dict[int, float] = {n_x + j: -1.0}
            for k, kind in enumerate(inventory.kinds):
                for c in range(c_count):
                    unit_rec = (basis.reciprocating[c, j] * turn).real
                    unit_rot = (basis.rotating[c, j] * turn).real
                    for i in range(kind.count):
                        value = kind.reciprocating[i] * unit_rec + kind.rotating[i] * unit_rot
                        if value:
                            row[var(k, i, c)] = float(value)
            rows.append((row, -np.inf, -float((basis.constant[j] * turn).real)))
    return 1.0, np.ones(components), False


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
