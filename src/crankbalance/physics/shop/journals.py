r"""Which matched sets share a journal (issue 27; ``docs/balance_shop.md``, "Journals").

On a crank whose crankpins (rod journals) carry more than one rod (a common-pin vee, a W),
the balancing machine sees one bob-weight per journal, the sum over the sets on it of
:math:`b_s = R_s + f M_s` (a set's rotating share plus the fraction ``f`` of its
reciprocating share, :func:`crankbalance.physics.shop.bobweights.bob_weights`). Which sets
share a journal is free once the sets are matched; :func:`pair_journals` chooses it so that
the journals' bob-weights are as alike as can be: the least spread
:math:`\max_t B_t - \min_t B_t`.

Methods, each exact for that objective:

``"milp"``
    Binary :math:`y_{st}` (set s on journal t), each set on one journal, journal t holding
    its :math:`n_t` rods, :math:`L \le \sum_s b_s y_{st} \le U`, minimise :math:`U - L`
    (``scipy.optimize.milp``, HiGHS, relative gap 0) within a time limit; when every
    journal holds as many rods the journals are interchangeable and set 0 goes on the
    first (symmetry breaking). The result says whether the optimum was proven.
``"exhaustive"``
    Every grouping of the sets into journals (up to the order of the sets on a journal and
    of journals of the same size), at most :data:`MAX_GROUPINGS`: 105 for a V8, 10 395 for
    a V12; the check of the MILP.
``"as-listed"``
    Set c in cylinder c: the order of the matching.

The joint optimum (the parts matched and grouped onto journals at once) is the matching's
objective ``"journal"`` (:func:`crankbalance.physics.shop.matching.match_parts`), whose
phasor-free description of the engine is :class:`JournalBasis`.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Iterator

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError
from ...records import record
from ...results import ResultMixin

#: most groupings the exhaustive pairing visits (a V12's 10 395; a V16 has 2 027 025)
MAX_GROUPINGS = 200_000
#: the methods of :func:`pair_journals`
PAIRING_METHODS = ("milp", "exhaustive", "as-listed")
#: the MILP works in grams: bob-weights are hundreds, their spreads units
_SCALE = 1000.0


@record
class JournalBasis(ResultMixin):
    """What the journals' bob-weights take from an engine: which journal each cylinder's
    rod is on, and the fraction of the reciprocating share in the bob-weights.

    Attributes
    ----------
    cylinder_throw : ndarray of int, shape (C,)
        The journal (crankpin, 0-based) of each cylinder [-].
    throws : int
        Number of journals T [-].
    fraction : float
        Fraction f of the reciprocating share in the bob-weights [-].
    """

    cylinder_throw: NDArray[np.int64]
    throws: int
    fraction: float

    def weights(self, reciprocating: ArrayLike, rotating: ArrayLike) -> NDArray[np.float64]:
        """The journals' bob-weights of set weights in cylinder order.

        Parameters
        ----------
        reciprocating, rotating : array_like, shape (..., C)
            Set weights per cylinder [kg].

        Returns
        -------
        ndarray, shape (..., T)
            Bob-weight per journal [kg].
        """
        onto = np.eye(self.throws)[self.cylinder_throw]  # (C, T)
        share = np.asarray(rotating, float) + self.fraction * np.asarray(reciprocating, float)
        out: NDArray[np.float64] = share @ onto
        return out


@record
class JournalPairing(ResultMixin):
    """Matched sets on the journals, and the journals' bob-weights.

    Attributes
    ----------
    method : str
        ``"milp"``, ``"exhaustive"``, ``"as-listed"`` (:data:`PAIRING_METHODS`) or
        ``"joint"`` (the parts matched with the journals, objective ``"journal"``).
    optimal : bool
        Whether the spread is proven the least.
    status : str
        In words: ``"proven optimal"`` or ``"not proven optimal: ..."`` with the reason.
    cylinder_throw : ndarray of int, shape (C,)
        The journal (0-based) of each cylinder [-].
    set_of_cylinder : ndarray of int, shape (C,)
        The matched set (its index in the matching's order) in each cylinder.
    journal_sets : tuple of tuple of int
        Per journal, the sets on it (by cylinder number).
    bob_weight : ndarray, shape (T,)
        Bob-weight of each journal [kg].
    spread : float
        Heaviest minus lightest journal [kg].
    as_listed_spread : float
        The spread with set c in cylinder c [kg].
    """

    method: str
    optimal: bool
    status: str
    cylinder_throw: NDArray[np.int64]
    set_of_cylinder: NDArray[np.int64]
    journal_sets: tuple[tuple[int, ...], ...]
    bob_weight: NDArray[np.float64]
    spread: float
    as_listed_spread: float


def groupings(rods: ArrayLike) -> int:
    r"""Number of ways to put C sets on journals holding ``rods`` each, up to the order of
    the sets on a journal and of journals of the same size.

    Parameters
    ----------
    rods : array_like of int, shape (T,)
        Rods on each journal [-].

    Returns
    -------
    int
        :math:`C! / (\prod_t n_t! \prod_m k_m!)`, with :math:`k_m` journals of m rods.
    """
    n = [int(r) for r in np.asarray(rods)]
    count = math.factorial(sum(n))
    for r in n:
        count //= math.factorial(r)
    for size in set(n):
        count //= math.factorial(n.count(size))
    return count


def _groupings(sets: tuple[int, ...], sizes: tuple[int, ...]) -> Iterator[list[tuple[int, ...]]]:
    """Every partition of ``sets`` into blocks of the multiset ``sizes``, each once: the
    lowest set left opens a block of one of the sizes left (each size once)."""
    if not sets:
        yield []
        return
    first, rest = sets[0], sets[1:]
    for size in sorted(set(sizes)):
        left = list(sizes)
        left.remove(size)
        for others in itertools.combinations(rest, size - 1):
            block = (first, *others)
            remaining = tuple(s for s in rest if s not in others)
            for tail in _groupings(remaining, tuple(left)):
                yield [block, *tail]


def _result(
    method: str,
    status: str,
    cylinder_throw: NDArray[np.int64],
    throws: int,
    set_weight: NDArray[np.float64],
    journal_of_set: NDArray[np.int64],
) -> JournalPairing:
    """The pairing that puts set s on journal ``journal_of_set[s]``: the sets of a journal
    go on its cylinders in increasing order."""
    set_of_cylinder = np.empty(cylinder_throw.size, dtype=np.int64)
    for t in range(throws):
        set_of_cylinder[np.flatnonzero(cylinder_throw == t)] = np.flatnonzero(journal_of_set == t)
    bob = np.bincount(cylinder_throw, weights=set_weight[set_of_cylinder], minlength=throws)
    listed = np.bincount(cylinder_throw, weights=set_weight, minlength=throws)
    return JournalPairing(
        method=method,
        optimal=status.startswith("proven optimal"),
        status=status,
        cylinder_throw=cylinder_throw,
        set_of_cylinder=set_of_cylinder,
        journal_sets=tuple(
            tuple(int(s) for s in set_of_cylinder[cylinder_throw == t]) for t in range(throws)
        ),
        bob_weight=np.asarray(bob, dtype=np.float64),
        spread=float(np.ptp(bob)),
        as_listed_spread=float(np.ptp(listed)),
    )


def pair_journals(
    set_weight: ArrayLike,
    cylinder_throw: ArrayLike,
    throws: int,
    method: str = "milp",
    time_limit: float = 60.0,
) -> JournalPairing:
    """Put matched sets on the journals with the least spread of the journals' bob-weights
    (module docstring).

    Parameters
    ----------
    set_weight : array_like, shape (C,)
        Each set's share of a bob-weight, :math:`R_s + f M_s` [kg].
    cylinder_throw : array_like of int, shape (C,)
        The journal (0-based) of each cylinder [-]; journal t holds as many sets as it has
        cylinders.
    throws : int
        Number of journals T [-].
    method : {"milp", "exhaustive", "as-listed"}
        How to pair.
    time_limit : float
        Longest MILP [s]; when it is reached the best pairing found is returned with
        ``optimal`` False and ``status`` saying so.

    Returns
    -------
    JournalPairing
        The sets per cylinder and journal, and the journals' bob-weights [kg].

    Raises
    ------
    InputError
        For an unknown method, weights that are not one finite mass per cylinder, a time
        limit that is not above zero, or an exhaustive pairing of more than
        :data:`MAX_GROUPINGS` groupings.
    """
    throw = np.asarray(cylinder_throw, dtype=np.int64)
    weight = np.asarray(set_weight, dtype=float)
    if method not in PAIRING_METHODS:
        raise InputError("method", method, f"must be one of {', '.join(PAIRING_METHODS)}")
    if weight.shape != throw.shape or not np.isfinite(weight).all():
        raise InputError("set_weight", weight.tolist(), f"{throw.size} finite masses [kg]")
    if not (isinstance(time_limit, int | float) and math.isfinite(time_limit) and time_limit > 0):
        raise InputError("time_limit", time_limit, "must be a finite time above 0 [s]")
    rods = np.bincount(throw, minlength=throws)
    listed = throw.copy()
    # as listed: set c on cylinder c's journal
    if np.all(rods <= 1):
        status = "proven optimal (one rod per journal: nothing to pair)"
        return _result("as-listed", status, throw, throws, weight, listed)
    if method == "as-listed":
        status = "as listed, not optimised"
        return _result("as-listed", status, throw, throws, weight, listed)
    if method == "exhaustive":
        count = groupings(rods)
        if count > MAX_GROUPINGS:
            raise InputError(
                "method", method, f"would visit {count} groupings (at most {MAX_GROUPINGS})"
            )
        best, journal_of_set = math.inf, listed
        slots = {size: [t for t in range(throws) if rods[t] == size] for size in set(rods)}
        for blocks in _groupings(tuple(range(throw.size)), tuple(int(r) for r in rods)):
            sums = [float(weight[list(b)].sum()) for b in blocks]
            spread = max(sums) - min(sums)
            if spread < best:
                best = spread
                free = {size: list(ts) for size, ts in slots.items()}
                journal_of_set = np.empty(throw.size, dtype=np.int64)
                for block in blocks:
                    journal_of_set[list(block)] = free[len(block)].pop(0)
        return _result("exhaustive", "proven optimal", throw, throws, weight, journal_of_set)
    return _milp_pairing(weight, throw, throws, rods, time_limit)


def _milp_pairing(
    weight: NDArray[np.float64],
    throw: NDArray[np.int64],
    throws: int,
    rods: NDArray[np.int64],
    time_limit: float,
) -> JournalPairing:
    """The MILP of the module docstring; the as-listed pairing when it finds none."""
    from scipy.optimize import Bounds, LinearConstraint, milp

    start = time.monotonic()
    sets = throw.size
    n_y = sets * throws  # column s * T + t
    rows: list[NDArray[np.float64]] = []
    low: list[float] = []
    high: list[float] = []

    def add(row: NDArray[np.float64], bounds: tuple[float, float]) -> None:
        rows.append(row)
        low.append(bounds[0])
        high.append(bounds[1])

    for s in range(sets):  # each set on one journal
        row = np.zeros(n_y + 2)
        row[s * throws : (s + 1) * throws] = 1
        add(row, (1.0, 1.0))
    for t in range(throws):  # journal t holds its rods
        row = np.zeros(n_y + 2)
        row[t:n_y:throws] = 1
        add(row, (float(rods[t]), float(rods[t])))
    for t in range(throws):  # B_t - U <= 0, B_t - L >= 0
        for column, bounds in ((n_y, (-np.inf, 0.0)), (n_y + 1, (0.0, np.inf))):
            row = np.zeros(n_y + 2)
            row[t:n_y:throws] = _SCALE * weight
            row[column] = -1
            add(row, bounds)
    lower, upper = np.zeros(n_y + 2), np.ones(n_y + 2)
    lower[n_y:], upper[n_y:] = -np.inf, np.inf
    if np.all(rods == rods[0]):  # interchangeable journals: set 0 on journal 0
        lower[0] = 1
    integrality = np.r_[np.ones(n_y), 0, 0]
    cost = np.r_[np.zeros(n_y), 1.0, -1.0]
    remaining = max(time_limit - (time.monotonic() - start), 0.0)
    result = milp(
        cost,
        constraints=LinearConstraint(np.array(rows), low, high),
        integrality=integrality,
        bounds=Bounds(lower, upper),
        options={"mip_rel_gap": 0.0, "time_limit": remaining},
    )
    if result.x is None or result.status not in (0, 1):
        status = "not proven optimal: the time limit ended the MILP before a pairing; as listed"
        return _result("as-listed", status, throw, throws, weight, throw.copy())
    y = np.round(result.x[:n_y]).reshape(sets, throws)
    status = "proven optimal" if result.status == 0 else "not proven optimal: the time limit"
    return _result("milp", status, throw, throws, weight, np.argmax(y, axis=1))
