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
    kind are taken in increasing index along the cylinders (symmetry breaking). Each
    share's spread is bounded below, :math:`U - L \ge` the least spread of that share on
    its own (exact by sorting when one or two kinds vary, no spares; with more, a scale
    step when the parts are weighed to a decimal step and the total does not divide
    evenly): without it the relaxation's bound is 0 and HiGHS spent seconds proving
    what the bound gives at the root (``docs/balance_shop.md``, "Matching").
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
``"milp"`` with ``objective="journal"`` (and ``model=``)
    The weighted spread plus the spread of the journals' bob-weights
    :math:`\max_t B_t - \min_t B_t`, :math:`B_t` the sum over the cylinders on journal t
    of :math:`W^{rot}_c + f\,W^{rec}_c` (:mod:`.journals`): the sets matched and put on
    the journals at once, the joint optimum of the two. The cylinders of a journal, and
    journals of as many rods, are interchangeable (symmetry breaking on the first kind).
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

**Bounded work.** The ``time_limit`` covers the whole of a ``"milp"`` matching, the
building of its model included: the clock starts when :func:`match_parts` is called. The
size is checked before anything is allocated: at most :data:`MAX_PART_SLOTS` part-slots
(parts listed times cylinders). A local search (:func:`local_search`: single-part swaps
and replacements by spares, best improvement first, until no move improves) runs first
on a share :data:`SEARCH_SHARE` of the limit; the MILP is then built, the clock checked
after every block of rows, and solved with what remains of the limit. A model of more than
:data:`MAX_MILP_NONZEROS` nonzeros is not built at all: the local search takes the whole
limit. The result says which: ``method`` is ``"milp"`` or ``"heuristic"``, ``status`` says
in words whether the optimum is proven, and ``gap`` gives the relative optimality gap
against the proven bound (None when no bound beyond zero is known). The exhaustive search
checks the clock too. The module is over 800 lines because the five methods, the bounded
MILP and the local search share the objectives and the set weights.
"""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import field, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError
from ...records import record
from ...results import ROUND_OFF, ResultMixin, below_round_off
from ..model import EngineModel
from ..shaking import free_forces
from .journals import JournalBasis

#: largest number of assignments the exhaustive search visits
EXHAUSTIVE_LIMIT = 2_000_000
#: most part-slots (parts listed, all kinds, times cylinders) a matching takes: the parts
#: file's 2000 parts on an engine's 64 cylinders; checked before anything is allocated
MAX_PART_SLOTS = 128_000
#: most nonzeros of the MILP's constraint matrix; a larger model is not built and the local
#: search alone matches. Measured (docs/balance_shop.md, "Bounded work"): up to 100 598
#: nonzeros (a spread over 6 kinds of 333 parts in 8 cylinders) the whole matching ended
#: within 5 % of a 1 s and of a 5 s limit; at 201 862, 1.54 times a 1 s limit, and at
#: 809 446, 9.4 times (HiGHS's presolve looks at the clock between its steps only)
MAX_MILP_NONZEROS = 100_000
#: share of the time limit the local search before the MILP may take (it usually ends,
#: at a local optimum, in a fraction of it)
SEARCH_SHARE = 0.25
#: how many assignments the exhaustive search visits between two looks at the clock
_CLOCK_EVERY = 2048
#: the clock of the time limit (seconds, monotonic)
_now = time.monotonic
#: objectives of the matching
OBJECTIVES = ("spread", "variance", "free", "journal")
#: sides of the polygon that measures a phasor's magnitude in the free-force objective
POLYGON_SIDES = 16
METHODS = ("milp", "pairing", "exhaustive", "as-listed")
#: the decimal steps [kg] a parts file's masses may be weighed to, coarsest first (1 g down
#: to 1 mg): the MILP's bound on a spread of many kinds (``_spread_bounds``)
GRID_STEPS = (1e-3, 1e-4, 1e-5, 1e-6)
#: how far from a whole number of steps a mass may lie (float rounding of the file's
#: decimals) and still be on the grid [steps]
GRID_TOLERANCE = 1e-6
#: the bounds given to the MILP are lowered by this share of themselves, so that rounding
#: in their computation never cuts off an optimum (a sum's rounding, about 1e-16 kg, lies
#: far within HiGHS's feasibility tolerance of the rows, 1e-7 g)
_BOUND_MARGIN = 1e-9


@record
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


@record
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
    journal_allowance : float
        Rotating allowance per journal, shared by the rods on it [kg] (the oil in a rod
        journal, as builders give it); :meth:`per_rod` turns it into the rods'
        ``rotating_allowance`` for an engine, and nothing matches before that.
    """

    kinds: tuple[PartKind, ...]
    reciprocating_allowance: float = 0.0
    rotating_allowance: float = 0.0
    journal_allowance: float = 0.0

    @property
    def names(self) -> tuple[str, ...]:
        """The kinds' names."""
        return tuple(kind.name for kind in self.kinds)

    def per_rod(self, cylinder_throw: ArrayLike, field: str = "oil") -> Inventory:
        """The inventory with its per-journal allowance shared by the rods of each journal:
        every journal holds as many rods, each gets ``journal_allowance / rods``, so the
        total over the engine and each journal's share stay the same.

        Parameters
        ----------
        cylinder_throw : array_like of int, shape (C,)
            The journal (0-based) of each cylinder [-].
        field : str
            How the user named the allowance, for the error.

        Returns
        -------
        Inventory
            With ``journal_allowance`` 0 and the share added to ``rotating_allowance``.

        Raises
        ------
        InputError
            If the journals hold different numbers of rods (the allowance per rod would
            differ between sets).
        """
        if not self.journal_allowance:
            return self
        rods = np.bincount(np.asarray(cylinder_throw, dtype=np.int64))
        rods = rods[rods > 0]
        if rods.size == 0 or np.any(rods != rods[0]):
            raise InputError(
                field,
                f"{1000 * self.journal_allowance:g} g per journal",
                "per journal on an engine whose journals hold as many rods each "
                f"(this one: {sorted(set(rods.tolist()))} rods); give the oil per rod",
            )
        share = self.journal_allowance / int(rods[0])
        return replace(
            self, rotating_allowance=self.rotating_allowance + share, journal_allowance=0.0
        )

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
        if self.journal_allowance:
            raise InputError(
                "oil",
                f"{1000 * self.journal_allowance:g} g per journal",
                "shared by the rods of each journal first (Inventory.per_rod with the engine)",
            )
        for kind in self.kinds:
            if kind.count < cylinders:
                raise InputError(
                    kind.name,
                    kind.count,
                    f"parts listed; {cylinders} cylinders need at least {cylinders}",
                )


@record
class Matching(ResultMixin):
    """Parts matched to cylinders, the set weights and the material to remove per set.

    Attributes
    ----------
    method : str
        How the assignment was found (:data:`METHODS`, or ``"heuristic"``: the local search
        of a ``milp`` matching, see the module docstring).
    objective : str
        ``"spread"``, ``"variance"`` or ``"free"`` (:data:`OBJECTIVES`).
    objective_value : float
        The objective reached [kg] (spread), [kg^2] (variance) or [N] (free).
    optimal : bool
        Whether the assignment is proven optimal for the objective (``as-listed`` and
        ``heuristic`` never are; ``milp`` is unless it reached its time limit).
    bound : float
        Proven lower bound of the objective (the value itself when optimal; 0 when none is
        known) [kg], [kg^2] or [N].
    kinds : tuple of str
        The kinds, in the order of ``part``.
    part : ndarray of int, shape (K, C)
        Index (0-based, file order) of the part of each kind in each cylinder.
    ids : tuple of tuple of str
        Per cylinder, the marks of its parts, one per kind.
    reciprocating, rotating : ndarray, shape (C,)
        Set weights per cylinder [kg], allowances included.
    reciprocating_spread, rotating_spread : float
        Heaviest minus lightest set [kg]; 0 when it is round-off of the sets' weights
        (at most ``ROUND_OFF`` times the heaviest, :func:`crankbalance.results.below_round_off`).
    remove_reciprocating, remove_rotating : ndarray, shape (C,)
        Material to remove per set to bring it to the lightest set [kg], round-off as 0
        (reciprocating: from the piston or the small end; rotating: from the big end).
    removed_total : float
        Sum of the material to remove [kg].
    free_force, free_couple : ndarray, shape (orders,)
        With the free-force objective: the largest free force [N] and couple [N*m] of
        each order the sets cause (crank balanced for the mean set); empty otherwise.
    status : str
        In words, how far the assignment is known to be optimal and why: ``"proven
        optimal"``, or ``"not proven optimal: ..."`` with the reason (the time limit, a
        local search), and the gap when a bound is known.
    gap : float or None
        Relative optimality gap, ``(objective_value - bound) / objective_value`` [-]; 0
        when optimal, None when no bound above zero is known.
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
    status: str = "proven optimal"
    gap: float | None = 0.0


@record
class _Clock:
    """The time limit of one matching, started when it was called."""

    start: float
    limit: float

    @classmethod
    def started(cls, limit: float) -> _Clock:
        return cls(_now(), float(limit))

    @property
    def end(self) -> float:
        return self.start + self.limit

    def remaining(self) -> float:
        return self.end - _now()


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


@record
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


#: what an objective takes from the engine: the free-force phasors or the journals
Basis = FreeForceBasis | JournalBasis | None


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
    basis: Basis = None,
) -> float:
    """The objective of an assignment (see the module docstring).

    Parameters
    ----------
    inventory : Inventory
        The parts.
    part : ndarray of int, shape (K, C)
        Index of the part of each kind in each cylinder.
    objective : {"spread", "variance", "free", "journal"}
        Weighted spread [kg], weighted sum of squared deviations from the mean of all
        listed parts [kg^2], the free forces and couples (module docstring) [N], or the
        weighted spread plus the spread of the journals' bob-weights [kg].
    weights : tuple of float
        Weights of the reciprocating and rotating terms [-].
    basis : FreeForceBasis or JournalBasis, optional
        The engine's phasors, for the ``"free"`` objective; its journals, for
        ``"journal"``.

    Returns
    -------
    float
        The objective [kg], [kg^2] or, for ``"free"``, [N].
    """
    if objective in ("free", "journal") and basis is None:
        raise InputError("objective", objective, "needs the engine (model)")
    if objective not in OBJECTIVES:
        raise InputError("objective", objective, f"must be one of {', '.join(OBJECTIVES)}")
    rec, rot = _set_weights(inventory, np.asarray(part))
    return float(_objectives(inventory, rec[None], rot[None], objective, weights, basis)[0])


def _objectives(
    inventory: Inventory,
    rec: NDArray[np.float64],
    rot: NDArray[np.float64],
    objective: str,
    weights: tuple[float, float],
    basis: Basis,
) -> NDArray[np.float64]:
    """The objective of many assignments at once, from their set weights of shape (M, C)."""
    w_rec, w_rot = _weights(weights)
    if objective == "journal":  # the sets' spread and the journals'
        assert isinstance(basis, JournalBasis)
        sets = w_rec * np.ptp(rec, axis=-1) + w_rot * np.ptp(rot, axis=-1)
        return sets + np.ptp(basis.weights(rec, rot), axis=-1)
    if objective == "free":
        assert isinstance(basis, FreeForceBasis)
        z = (
            basis.constant
            + (rec - inventory.reciprocating_allowance) @ basis.reciprocating
            + (rot - inventory.rotating_allowance) @ basis.rotating
        )
        return np.sum(_polygon(z), axis=-1)
    if objective == "spread":
        return w_rec * np.ptp(rec, axis=-1) + w_rot * np.ptp(rot, axis=-1)
    mean_rec, mean_rot = _means(inventory)
    return w_rec * np.sum((rec - mean_rec) ** 2, axis=-1) + w_rot * np.sum(
        (rot - mean_rot) ** 2, axis=-1
    )


def local_search(
    inventory: Inventory,
    cylinders: int,
    objective: str = "spread",
    weights: tuple[float, float] = (1.0, 1.0),
    basis: Basis = None,
    stop: float = math.inf,
) -> tuple[NDArray[np.int64], bool]:
    """A bounded heuristic matching: from the parts as listed, the best single move of one
    kind in one cylinder (its part swapped with another cylinder's, or replaced by a
    spare) is made while it lowers the objective, or leaves it and lowers the sum of the
    squared deviations of the set weights from their mean (which moves the search off a
    plateau: a spread does not change when a set that ties for the heaviest gets
    lighter).

    Each move is evaluated for all candidate parts at once; the memory is that of one
    batch, (parts of a kind) x (cylinders). Every accepted move lowers the pair (objective,
    deviations) in that order, so the search ends, at the latest when ``stop`` (a
    ``time.monotonic()`` time) is reached.

    Parameters
    ----------
    inventory : Inventory
        The parts.
    cylinders : int
        Number of cylinders.
    objective : {"spread", "variance", "free"}
        What to lower (see :func:`objective_value`).
    weights : tuple of float
        Weights of the reciprocating and rotating terms [-].
    basis : FreeForceBasis, optional
        The engine's phasors, for ``"free"``.
    stop : float
        ``time.monotonic()`` time at which the search ends [s].

    Returns
    -------
    part : ndarray of int, shape (K, C)
        The assignment found.
    converged : bool
        True when no move lowers the objective (a local optimum), False when ``stop``
        ended the search first.
    """
    kinds = inventory.kinds
    part = np.tile(np.arange(cylinders, dtype=np.int64), (len(kinds), 1))
    rec, rot = _set_weights(inventory, part)
    value = float(_objectives(inventory, rec[None], rot[None], objective, weights, basis)[0])
    spread = _deviations(rec, rot)
    improved = True
    while improved:
        improved = False
        for k, kind in enumerate(kinds):
            where = np.full(kind.count, -1, dtype=np.int64)  # the cylinder of each part
            where[part[k]] = np.arange(cylinders)
            used = np.flatnonzero(where >= 0)
            for c in range(cylinders):
                if _now() >= stop:
                    return part, False
                p = int(part[k, c])
                d_rec = kind.reciprocating - kind.reciprocating[p]
                d_rot = kind.rotating - kind.rotating[p]
                cand_rec = np.tile(rec, (kind.count, 1))
                cand_rot = np.tile(rot, (kind.count, 1))
                cand_rec[:, c] += d_rec
                cand_rot[:, c] += d_rot
                cand_rec[used, where[used]] -= d_rec[used]  # a swap: p goes where j was
                cand_rot[used, where[used]] -= d_rot[used]
                values = _objectives(inventory, cand_rec, cand_rot, objective, weights, basis)
                tie = 1e-9 * abs(value)
                j = int(np.argmin(values))
                if not values[j] < value - tie:  # none lower: the deviations, at the same value
                    spreads = np.where(
                        np.abs(values - value) <= tie, _deviations(cand_rec, cand_rot), np.inf
                    )
                    j = int(np.argmin(spreads))
                    if not spreads[j] < spread * (1 - 1e-9):
                        continue
                d = int(where[j])
                part[k, c], where[j], where[p] = j, c, d
                if d >= 0:
                    part[k, d] = p
                used = np.flatnonzero(where >= 0)
                rec, rot, value = cand_rec[j], cand_rot[j], float(values[j])
                spread = float(_deviations(rec, rot))
                improved = True
    return part, True


def _deviations(rec: NDArray[np.float64], rot: NDArray[np.float64]) -> Any:
    """Sum of the squared deviations of the set weights from their mean, per assignment
    (the last axis is the cylinders') [kg^2]."""
    rec_dev = rec - rec.mean(axis=-1, keepdims=True)
    rot_dev = rot - rot.mean(axis=-1, keepdims=True)
    return np.sum(rec_dev**2, axis=-1) + np.sum(rot_dev**2, axis=-1)


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
    objective : {"spread", "variance", "free", "journal"}, optional
        What to minimise: ``"spread"`` (default), ``"free"`` or ``"journal"`` (the weighted
        spread plus the spread of the journals' bob-weights: the sets matched and put on
        the journals at once) for ``milp``, ``"variance"`` for ``pairing``;
        ``exhaustive`` takes any.
    weights : tuple of float
        Weights of the reciprocating and rotating terms [-].
    time_limit : float
        Longest ``milp`` or ``exhaustive`` matching [s], from this call on (the MILP's
        model building included); when it is reached, the best assignment found is
        returned with ``optimal`` False, the proven lower ``bound`` and ``status`` saying
        so (module docstring, "Bounded work").
    model : EngineModel, optional
        The engine, for the ``"free"`` objective (its layout, kinematics and speed) and
        the ``"journal"`` objective (which journal each cylinder is on).
    fraction : float
        Fraction of the reciprocating share in the bob-weights [-] (``"free"``,
        ``"journal"``).
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
        exceed :data:`EXHAUSTIVE_LIMIT` assignments, or the parts and cylinders make more
        than :data:`MAX_PART_SLOTS` part-slots.
    """
    if not (isinstance(time_limit, int | float) and math.isfinite(time_limit) and time_limit > 0):
        raise InputError("time_limit", time_limit, "must be a finite time above 0 [s]")
    clock = _Clock.started(time_limit)
    inventory.check(cylinders)
    slots = cylinders * sum(kind.count for kind in inventory.kinds)
    if slots > MAX_PART_SLOTS:
        raise InputError(
            "parts",
            slots,
            f"part-slots (parts listed times {cylinders} cylinders); at most "
            f"{MAX_PART_SLOTS} are matched: list fewer spares",
        )
    weights = _weights(weights)
    if method not in METHODS:
        raise InputError("method", method, f"must be one of {', '.join(METHODS)}")
    solves = {"milp": ("spread", "free", "journal"), "pairing": ("variance",)}
    goal = objective or solves.get(method, ("spread",))[0]
    if goal not in OBJECTIVES:
        raise InputError("objective", goal, f"must be one of {', '.join(OBJECTIVES)}")
    if method in solves and goal not in solves[method]:
        raise InputError(
            "objective", goal, f"method {method!r} minimises the {' or '.join(solves[method])}"
        )
    basis: Basis = None
    if goal in ("free", "journal"):
        if model is None:
            raise InputError("objective", goal, "needs the engine (model) the sets go in")
        if model.cylinders != cylinders:
            raise InputError(
                "cylinders", cylinders, f"must be the engine's {model.cylinders} cylinders"
            )
    if goal == "free":
        assert model is not None
        basis = free_force_basis(model, inventory, fraction, orders)
    if goal == "journal":
        from ..single_cylinder import check_balance_factor

        assert model is not None
        check_balance_factor(fraction, "fraction")
        basis = JournalBasis(np.asarray(model.cylinder_throw), model.throws, float(fraction))
    if method == "as-listed":
        part = np.tile(np.arange(cylinders), (len(inventory.kinds), 1))
        return _matching(
            inventory, part, method, goal, weights, 0.0, basis, "as listed, not optimised"
        )
    if method == "pairing":
        part = _pairing(inventory, cylinders, weights)
        return _matching(inventory, part, method, goal, weights, None, basis)
    if method == "exhaustive":
        part, status = _exhaustive(inventory, cylinders, goal, weights, basis, clock)
        bound = None if status is None else 0.0
        return _matching(inventory, part, method, goal, weights, bound, basis, status)
    return _milp_matching(inventory, cylinders, goal, weights, basis, clock)


def _milp_matching(
    inventory: Inventory,
    cylinders: int,
    objective: str,
    weights: tuple[float, float],
    basis: Basis,
    clock: _Clock,
) -> Matching:
    """The MILP within the time limit, after a local search (module docstring, "Bounded
    work"): the better of the two assignments, with what is proven about it."""
    slots = cylinders * sum(kind.count for kind in inventory.kinds)
    nonzeros = _milp_nonzeros(inventory, cylinders, basis)
    exact = nonzeros <= MAX_MILP_NONZEROS
    stop = clock.start + (SEARCH_SHARE if exact else 1.0) * clock.limit
    found, converged = local_search(inventory, cylinders, objective, weights, basis, stop)
    why = "" if converged else "; the time limit ended the local search"
    heuristic = "not proven optimal: a local search"
    if not exact:
        status = (
            f"{heuristic}, as the MILP of {slots} part-slots would have {nonzeros} nonzeros, "
            f"above its cap of {MAX_MILP_NONZEROS}{why}"
        )
        return _matching(inventory, found, "heuristic", objective, weights, 0.0, basis, status)
    solved = _milp(inventory, cylinders, weights, clock, basis)
    if solved is None:
        status = f"{heuristic}, as the time limit ended the building of the MILP{why}"
        return _matching(inventory, found, "heuristic", objective, weights, 0.0, basis, status)
    part, bound = solved
    if bound is None:  # proven optimal
        assert part is not None
        return _matching(inventory, part, "milp", objective, weights, None, basis)
    low = max(bound, 0.0)
    searched = objective_value(inventory, found, objective, weights, basis)
    if part is not None and objective_value(inventory, part, objective, weights, basis) <= searched:
        status = "not proven optimal: the time limit ended the MILP"
        return _matching(inventory, part, "milp", objective, weights, low, basis, status)
    what = "nothing" if part is None else "nothing better"
    status = f"{heuristic}, as the MILP found {what} within the time limit{why}"
    return _matching(inventory, found, "heuristic", objective, weights, low, basis, status)


def _matching(
    inventory: Inventory,
    part: NDArray[np.int64],
    method: str,
    objective: str,
    weights: tuple[float, float],
    bound: float | None,
    basis: Basis = None,
    status: str | None = None,
) -> Matching:
    """The Matching of an assignment; ``bound`` None: proven optimal."""
    part = np.asarray(part, dtype=np.int64)
    value = objective_value(inventory, part, objective, weights, basis)
    low = value if bound is None else min(bound, value)
    if bound is None or value == 0:
        gap: float | None = 0.0
    else:
        gap = None if low <= 0 else (value - low) / value
    if status is None:
        status = "proven optimal"
    if bound is not None and gap is not None and value > 0:
        status += f" (gap {100 * gap:.3g} %)"
    force = couple = np.zeros(0)
    if isinstance(basis, FreeForceBasis):
        z = np.abs(_phasors(inventory, part, basis)).reshape(basis.orders, 4)
        force = z[:, 0] + z[:, 1]
        couple = (z[:, 2] + z[:, 3]) * basis.length
    rec, rot = _set_weights(inventory, part)
    # a set's weight is a sum of weighed parts: a difference at the round-off of the
    # heaviest set is none (the inline-4's sets of 507.2 g differed by 1.1e-16 kg)
    rec_level = ROUND_OFF * float(np.max(np.abs(rec)))
    rot_level = ROUND_OFF * float(np.max(np.abs(rot)))
    remove_rec = below_round_off(rec - rec.min(), rec_level)
    remove_rot = below_round_off(rot - rot.min(), rot_level)
    ids = tuple(
        tuple(kind.ids[i] for kind, i in zip(inventory.kinds, part[:, c], strict=True))
        for c in range(part.shape[1])
    )
    return Matching(
        method=method,
        objective=objective,
        objective_value=value,
        optimal=bound is None,
        bound=low,
        kinds=inventory.names,
        part=part,
        ids=ids,
        reciprocating=rec,
        rotating=rot,
        reciprocating_spread=float(below_round_off(np.ptp(rec), rec_level)),
        rotating_spread=float(below_round_off(np.ptp(rot), rot_level)),
        remove_reciprocating=remove_rec,
        remove_rotating=remove_rot,
        removed_total=float(remove_rec.sum() + remove_rot.sum()),
        free_force=force,
        free_couple=couple,
        status=status,
        gap=gap,
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
    basis: Basis,
    clock: _Clock,
) -> tuple[NDArray[np.int64], str | None]:
    """Every assignment (up to the order of the cylinders, unless the objective is the free
    force); the best (first found on ties), and None, or the status when the time limit
    ended the search first."""
    kinds = inventory.kinds
    ordered = objective in ("free", "journal")  # the cylinders are not interchangeable
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
    visited = 0
    for first in firsts:
        for rest in itertools.product(*(range(len(o)) for o in others)):
            part = np.array([first, *(o[i] for o, i in zip(others, rest, strict=True))])
            value = objective_value(inventory, part, objective, weights, basis)
            if value < best_value:
                best_value, best = value, part
            visited += 1
            if visited % _CLOCK_EVERY == 0 and clock.remaining() <= 0:
                status = (
                    f"not proven optimal: the time limit ended the search after {visited} "
                    f"of {count} assignments"
                )
                return best, status  # type: ignore[return-value]
    assert best is not None
    return best, None


def _milp_nonzeros(inventory: Inventory, cylinders: int, basis: Basis) -> int:
    """The most nonzeros the MILP's constraint matrix can have, counted before it is built."""
    n_x = cylinders * sum(kind.count for kind in inventory.kinds)
    assignment = 2 * n_x  # one part of each kind per cylinder; each part at most once
    spread = 4 * (n_x + cylinders) + 4  # W_c <= U, W_c >= L per share; U - L >= bound
    if isinstance(basis, JournalBasis):  # the spread's rows; B_t <= U, B_t >= L; symmetry
        journals = 2 * (n_x + basis.throws) + 2 * inventory.kinds[0].count * cylinders
        return assignment + spread + journals
    if basis is None:  # the spread's rows; the symmetry rows
        symmetry = 2 * inventory.kinds[0].count * max(cylinders - 1, 0)
        return assignment + spread + symmetry
    return assignment + basis.constant.size * POLYGON_SIDES * (n_x + 1)


class _Rows:
    """The MILP's constraint matrix as blocks of coordinates, and the bounds of its rows."""

    def __init__(self) -> None:
        self.count = 0
        self.low: list[NDArray[np.float64]] = []
        self.high: list[NDArray[np.float64]] = []
        self.coordinates: list[tuple[NDArray, NDArray, NDArray]] = []

    def block(self, count: int, low: ArrayLike, high: ArrayLike) -> int:
        """Add ``count`` rows with their bounds; the index of the first."""
        first = self.count
        self.low.append(np.broadcast_to(np.asarray(low, dtype=float), (count,)))
        self.high.append(np.broadcast_to(np.asarray(high, dtype=float), (count,)))
        self.count += count
        return first

    def entries(self, row: ArrayLike, column: ArrayLike, value: ArrayLike) -> None:
        """Coefficients at (row, column), zeros left out."""
        row, column, value = np.broadcast_arrays(row, column, np.asarray(value, dtype=float))
        keep = value != 0
        self.coordinates.append((row[keep].ravel(), column[keep].ravel(), value[keep].ravel()))

    def matrix(self, columns: int) -> Any:
        from scipy.sparse import coo_array

        row, column, value = (np.concatenate(part) for part in zip(*self.coordinates, strict=True))
        matrix = coo_array((value, (row, column)), shape=(self.count, columns)).tocsr()
        matrix.sort_indices()
        return matrix


def _milp(
    inventory: Inventory,
    cylinders: int,
    weights: tuple[float, float],
    clock: _Clock,
    basis: Basis = None,
) -> tuple[NDArray[np.int64] | None, float | None] | None:
    """The least weighted spread, or with ``basis`` the least free forces, by mixed-integer
    linear programming (module docstring), within what remains of the time limit.

    Returns None when the time limit ends the building of the model; else the assignment
    (None when the solver found none) and the proven lower bound (None: optimal)."""
    from scipy.optimize import Bounds, LinearConstraint, milp

    kinds = inventory.kinds
    c_count = cylinders
    counts = [kind.count for kind in kinds]
    offsets = np.concatenate([[0], np.cumsum(np.array(counts) * c_count)]).astype(np.int64)
    n_x = int(offsets[-1])
    # the column of part i of kind k in cylinder 0 (cylinder c: plus c), all kinds in turn
    first_column = np.concatenate(
        [offsets[k] + np.arange(n) * c_count for k, n in enumerate(counts)]
    )
    cylinder = np.arange(c_count)
    rows = _Rows()
    for k, count in enumerate(counts):
        columns = offsets[k] + np.arange(count * c_count)  # part-major: i * C + c
        one = rows.block(c_count, 1.0, 1.0)  # one part of each kind per cylinder
        rows.entries(one + np.tile(cylinder, count), columns, 1.0)
        least = 1.0 if count == c_count else 0.0  # each part at most once
        once = rows.block(count, least, 1.0)
        rows.entries(once + np.repeat(np.arange(count), c_count), columns, 1.0)
    if clock.remaining() <= 0:
        return None
    if basis is None:
        scale, cost_extra, fixed = _spread_rows(
            inventory, c_count, first_column, n_x, weights, rows
        )
    elif isinstance(basis, JournalBasis):  # the sets' spread, then the journals'
        scale, sets, _ = _spread_rows(
            inventory, c_count, first_column, n_x, weights, rows, symmetry=False
        )
        _, journals, fixed = _journal_rows(inventory, first_column, n_x + sets.size, basis, rows)
        cost_extra = np.concatenate([sets, journals])
    else:
        built = _free_rows(inventory, c_count, first_column, n_x, basis, rows, clock)
        if built is None:
            return None
        scale, cost_extra, fixed = built
    n_var = n_x + cost_extra.size
    matrix = rows.matrix(n_var)
    cost = np.concatenate([np.zeros(n_x), cost_extra])
    integrality = np.zeros(n_var)
    integrality[:n_x] = 1
    lower = np.zeros(n_var)
    upper = np.ones(n_var)
    lower[n_x:], upper[n_x:] = -np.inf, np.inf
    if fixed:  # the first kind's part c in cylinder c
        upper[: c_count * c_count] = np.eye(c_count).ravel()
        lower[: c_count * c_count] = np.eye(c_count).ravel()
    remaining = clock.remaining()
    if remaining <= 0:
        return None
    result = milp(
        cost,
        constraints=LinearConstraint(matrix, np.concatenate(rows.low), np.concatenate(rows.high)),
        integrality=integrality,
        bounds=Bounds(lower, upper),
        options={"mip_rel_gap": 0.0, "time_limit": remaining},
    )
    dual = getattr(result, "mip_dual_bound", None)
    bound = float(dual) / scale if dual is not None and math.isfinite(dual) else 0.0
    if result.x is None or result.status not in (0, 1):
        return None, bound
    x = np.round(result.x[:n_x]).astype(np.int64)
    part = np.empty((len(kinds), c_count), dtype=np.int64)
    for k, kind in enumerate(kinds):
        block = x[offsets[k] : offsets[k + 1]].reshape(kind.count, c_count)
        part[k] = np.argmax(block, axis=0)
    return part, None if result.status == 0 else bound


def _spread_rows(
    inventory: Inventory,
    c_count: int,
    first_column: NDArray,
    n_x: int,
    weights: tuple[float, float],
    rows: _Rows,
    symmetry: bool = True,
) -> tuple[float, NDArray[np.float64], bool]:
    """Rows of the spread: L <= W_c <= U per share; U - L at least the share's bound
    (:func:`_spread_bounds`); the symmetry breaking (``symmetry``: the cylinders are
    interchangeable); the costs of (U_rec, L_rec, U_rot, L_rot)."""
    kinds = inventory.kinds
    scale = 1000.0  # grams: the set weights are hundreds, the spreads single units
    cylinder = np.arange(c_count)
    columns = first_column[None, :] + cylinder[:, None]  # (C, parts)
    shares = (
        (np.concatenate([k.reciprocating for k in kinds]), inventory.reciprocating_allowance),
        (np.concatenate([k.rotating for k in kinds]), inventory.rotating_allowance),
    )
    # per cylinder, per share: W_c - U <= -base, then W_c - L >= -base
    low = np.tile([-np.inf, 0.0, -np.inf, 0.0], c_count)
    high = np.tile([0.0, np.inf, 0.0, np.inf], c_count)
    for s, (_, allowance) in enumerate(shares):
        base = scale * allowance
        high[2 * s :: 4] = -base
        low[2 * s + 1 :: 4] = -base
    first = rows.block(4 * c_count, low, high)
    for s, (share, _) in enumerate(shares):
        for bound in (0, 1):  # U, L
            row = first + 4 * cylinder + 2 * s + bound
            rows.entries(row[:, None], columns, scale * share[None, :])
            rows.entries(row, n_x + 2 * s + bound, -1.0)
    # symmetry: cylinders are interchangeable for a spread, so the first kind's part
    # index increases along the cylinders (with no spares: part c in cylinder c)
    n0 = kinds[0].count
    fixed = symmetry and n0 == c_count
    if symmetry and not fixed and c_count > 1:
        first = rows.block(c_count - 1, -np.inf, -1.0)
        index = np.arange(n0)
        for c in range(c_count - 1):
            rows.entries(first + c, index * c_count + c, index.astype(float))
            rows.entries(first + c, index * c_count + c + 1, -index.astype(float))
    # the spread of each share is at least its bound (_spread_bounds): U - L >= bound
    least = scale * np.asarray(_spread_bounds(inventory, c_count))
    first = rows.block(2, least, np.inf)
    for s in range(2):
        rows.entries(first + s, [n_x + 2 * s, n_x + 2 * s + 1], [1.0, -1.0])
    w_rec, w_rot = weights
    return scale, np.array([w_rec, -w_rec, w_rot, -w_rot]), fixed


def _spread_bounds(inventory: Inventory, cylinders: int) -> tuple[float, float]:
    """Lower bounds of the reciprocating and of the rotating spread over every assignment
    [kg], each share on its own (a bound of the weighted spread: its two terms weighted).

    Only the kinds whose share differs between their parts move the spread of a share:
    with none, the spread is 0; with one, the least spread is that of the closest
    ``cylinders`` parts in sorted order; with two and no spares, that of the heaviest part
    of one kind with the lightest of the other (sorted against reverse-sorted: the pairing
    that both lowers the heaviest sum and raises the lightest as far as any can). With
    more kinds, when every share is a whole multiple of a decimal step q (the scale's
    resolution: every part weighed to 0.1 g) and no varying kind has spares, the sets'
    total is fixed, so the sets are all equal only if the total divides evenly: when it
    does not, the spread is at least q. Otherwise the bound is 0."""
    bounds = []
    for share in ("reciprocating", "rotating"):
        values = [getattr(k, share) for k in inventory.kinds]
        varying = [v for v in values if np.ptp(v) > 0]
        bound = 0.0
        if len(varying) == 1:
            ordered = np.sort(varying[0])
            bound = float(
                np.min(ordered[cylinders - 1 :] - ordered[: ordered.size - cylinders + 1])
            )
        elif len(varying) == 2 and all(v.size == cylinders for v in varying):
            bound = float(np.ptp(np.sort(varying[0]) + np.sort(varying[1])[::-1]))
        elif varying and all(v.size == cylinders for v in varying):
            bound = _grid_bound(varying, cylinders)
        bounds.append(max(bound * (1 - _BOUND_MARGIN), 0.0))
    return bounds[0], bounds[1]


def _grid_bound(values: list[NDArray[np.float64]], cylinders: int) -> float:
    """The least spread above 0 of sums on a grid (see :func:`_spread_bounds`): the
    coarsest decimal step q in :data:`GRID_STEPS` of which every value is a whole
    multiple (within :data:`GRID_TOLERANCE` of a step), and, when the sets' total in
    steps does not divide by ``cylinders``, q less twice the most a set's sum can lie off
    the grid (the sets' sums, rounded to the grid, differ by a step at least); else 0."""
    for step in GRID_STEPS:
        off = [np.abs(v / step - np.round(v / step)) for v in values]
        if max(float(np.max(o)) for o in off) <= GRID_TOLERANCE:
            total = sum(int(np.sum(np.round(v / step))) for v in values)
            if total % cylinders == 0:
                return 0.0
            return step * (1.0 - 2.0 * sum(float(np.max(o)) for o in off))
    return 0.0


def _journal_rows(
    inventory: Inventory,
    first_column: NDArray,
    column: int,
    basis: JournalBasis,
    rows: _Rows,
) -> tuple[float, NDArray[np.float64], bool]:
    """Rows of the journals' bob-weights: L <= B_t <= U (U and L the columns ``column``
    and ``column + 1``), B_t the sum over the cylinders on journal t of their parts'
    R + f M and the allowances; the symmetry breaking; the costs of (U, L)."""
    scale = 1000.0  # grams, as the spread
    f = basis.fraction
    share = np.concatenate([k.rotating + f * k.reciprocating for k in inventory.kinds])
    per_set = inventory.rotating_allowance + f * inventory.reciprocating_allowance
    rods = np.bincount(basis.cylinder_throw, minlength=basis.throws)
    base = scale * per_set * rods
    # per journal: B_t - U <= -base_t, then B_t - L >= -base_t
    low = np.ravel(np.column_stack([np.full(basis.throws, -np.inf), -base]))
    high = np.ravel(np.column_stack([-base, np.full(basis.throws, np.inf)]))
    first = rows.block(2 * basis.throws, low, high)
    for c, t in enumerate(basis.cylinder_throw):
        for bound in (0, 1):  # U, L
            rows.entries(first + 2 * int(t) + bound, first_column + c, scale * share)
    for t in range(basis.throws):
        rows.entries(first + 2 * t, column, -1.0)
        rows.entries(first + 2 * t + 1, column + 1, -1.0)
    # symmetry: the cylinders of a journal are interchangeable, and so are journals of as
    # many rods: the first kind's part index increases along the cylinders of a journal
    # and, when every journal holds as many rods, along the journals' first cylinders
    on = [np.flatnonzero(basis.cylinder_throw == t) for t in range(basis.throws)]
    pairs = [(int(a), int(b)) for c in on for a, b in itertools.pairwise(c)]
    if len({c.size for c in on}) == 1:
        pairs += [(int(a[0]), int(b[0])) for a, b in itertools.pairwise(on) if a.size]
    if pairs:
        c_count = basis.cylinder_throw.size
        index = np.arange(inventory.kinds[0].count)
        first = rows.block(len(pairs), -np.inf, -1.0)
        for row, (a, b) in enumerate(pairs):
            rows.entries(first + row, index * c_count + a, index.astype(float))
            rows.entries(first + row, index * c_count + b, -index.astype(float))
    return scale, np.array([1.0, -1.0]), False


def _free_rows(
    inventory: Inventory,
    c_count: int,
    first_column: NDArray,
    n_x: int,
    basis: FreeForceBasis,
    rows: _Rows,
    clock: _Clock,
) -> tuple[float, NDArray[np.float64], bool] | None:
    """Rows of the free forces: Re(z_j e^-i theta_k) <= t_j, minimise sum t_j; None when
    the time limit is reached while they are built."""
    turns = np.exp(-2j * np.pi * np.arange(POLYGON_SIDES) / POLYGON_SIDES)
    components = basis.constant.size
    rec = np.concatenate([k.reciprocating for k in inventory.kinds])
    rot = np.concatenate([k.rotating for k in inventory.kinds])
    columns = first_column[:, None] + np.arange(c_count)[None, :]  # (parts, C)
    for j in range(components):
        high = -(basis.constant[j] * turns).real
        first = rows.block(POLYGON_SIDES, -np.inf, high)
        for t, turn in enumerate(turns):
            unit_rec = (basis.reciprocating[:, j] * turn).real
            unit_rot = (basis.rotating[:, j] * turn).real
            value = rec[:, None] * unit_rec[None, :] + rot[:, None] * unit_rot[None, :]
            rows.entries(first + t, columns, value)
            rows.entries(first + t, n_x + j, -1.0)
        if clock.remaining() <= 0:
            return None
    return 1.0, np.ones(components), False


@record
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
