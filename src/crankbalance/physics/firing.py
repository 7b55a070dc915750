r"""The firing order: makers' cylinder numbering, the firing order a crank allows, and the
crank angle at which each cylinder fires (:func:`firing_angles`). Every question of the
firing order is answered here, once.

crankbalance numbers cylinders one way per layout (``docs/engine_file.md``, "Numbering and
geometry"): in-line and boxer one per throw from the y < 0 end (a boxer alternating sides,
odd cylinders at -90 deg), a vee bank A (-V/2) 1..T then bank B. Makers number their own
way; a **numbering** maps the maker's cylinder numbers to crankbalance's so that a firing
order can be entered as the maker prints it. The map is one tuple, ``to_crankbalance``:
entry k - 1 is crankbalance's number of the maker's cylinder k. It is applied at the edge
(:mod:`crankbalance.studies.build`); the physics never sees a maker's number.

Named schemes (:data:`SCHEMES`), each a rule for any cylinder count of its layout, with the
maker's cylinder 1 on crankbalance's throw 1 (the y < 0 end; numbered from the other end
the engine is the mirror image):

- ``"porsche-boxer"``: a boxer numbered bank after bank, 1..T along one bank and T+1..2T
  along the other (the rule of DIN 73021 that Porsche uses, e.g. the 911 flat-6 of 1964,
  firing 1-6-2-4-3-5; the 356 and 912 flat-4 count their two banks the same way): the
  maker's k-th cylinder of the first bank is crankbalance's 2k - 1, of the second 2k.
- ``"gm-vee"``: a vee numbered along the crank, odd cylinders 1-3-5-7 on the left bank
  and even 2-4-6-8 on the right, front to rear (Chevrolet small-block V8, 1955, firing
  1-8-4-3-6-5-7-2; the GM 90 deg V6 firing 1-6-5-4-3-2 the same). The engine turns
  clockwise seen from the front, so a crankpin reaches the right bank first: the right
  bank is crankbalance's bank A. The maker's 2k is crankbalance's k, 2k - 1 is T + k.
- ``"ford-vee"``: a vee numbered bank after bank, right bank 1..T then left bank T+1..2T,
  front to rear (Ford 289, 1963, and 302, 1968, firing 1-5-4-2-6-3-7-8; 351 Windsor, 1969,
  firing 1-3-7-2-6-5-4-8): the right bank leads, so the numbers are crankbalance's.

A firing order given with the crank (``throw_angles`` or custom throws) is checked against
the crank by :func:`check_firing_order`: the cylinders must reach their top dead centres in
that sequence within one cycle.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError
from ..records import record

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import ArrayLike, NDArray

#: angles closer than this are the same top dead centre [rad]
SAME_ANGLE = 1e-7


@record
class Scheme:
    """A maker's numbering rule for one layout.

    Parameters
    ----------
    layout : str
        The layout the rule numbers (``"boxer"`` or ``"vee"``).
    rule : str
        The maker's numbering in words.
    source : str
        The makers and years the rule and its example orders are taken from.
    kind : str
        ``"bank-after-bank"`` (a boxer's two sides, or a vee whose first bank is
        crankbalance's bank A), or ``"odd-even"`` (a vee numbered along the crank, even
        numbers on crankbalance's bank A).
    """

    layout: str
    rule: str
    source: str
    kind: str

    def to_crankbalance(self, cylinders: int) -> tuple[int, ...]:
        """crankbalance's number of each of the maker's cylinders.

        Parameters
        ----------
        cylinders : int
            Number of cylinders (even).

        Returns
        -------
        tuple of int
            Entry k - 1: crankbalance's number of the maker's cylinder k.
        """
        t = cylinders // 2
        if self.layout == "boxer":  # maker: 1..T one side, T+1..2T the other
            return tuple([2 * k + 1 for k in range(t)] + [2 * k + 2 for k in range(t)])
        if self.kind == "odd-even":  # maker 2k -> k (bank A), 2k - 1 -> T + k (bank B)
            return tuple(t + (m + 1) // 2 if m % 2 else m // 2 for m in range(1, cylinders + 1))
        return tuple(range(1, cylinders + 1))


#: the named numberings of ``crank_train.numbering`` (module docstring)
SCHEMES: dict[str, Scheme] = {
    "porsche-boxer": Scheme(
        layout="boxer",
        rule="bank after bank: 1..T along one bank, T+1..2T along the other, cylinder 1 at throw 1",
        source="DIN 73021; Porsche 911 flat-6 (1964), firing 1-6-2-4-3-5",
        kind="bank-after-bank",
    ),
    "gm-vee": Scheme(
        layout="vee",
        rule="along the crank: odd cylinders on the left bank, even on the right (bank A), "
        "front (throw 1) to rear",
        source="Chevrolet small-block V8 (1955), firing 1-8-4-3-6-5-7-2",
        kind="odd-even",
    ),
    "ford-vee": Scheme(
        layout="vee",
        rule="bank after bank: right bank (bank A) 1..T, left bank T+1..2T, front (throw 1) "
        "to rear",
        source="Ford 289 (1963) and 302 (1968), firing 1-5-4-2-6-3-7-8; Ford 351 Windsor "
        "(1969), firing 1-3-7-2-6-5-4-8",
        kind="bank-after-bank",
    ),
}


def to_crankbalance_order(order: Sequence[int], to_crankbalance: Sequence[int]) -> list[int]:
    """A firing order in the maker's numbers, in crankbalance's, from the same cylinder.

    Parameters
    ----------
    order : sequence of int
        Maker's cylinder numbers in firing order.
    to_crankbalance : sequence of int
        Entry k - 1: crankbalance's number of the maker's cylinder k.

    Returns
    -------
    list of int
        The same sequence in crankbalance's numbers.
    """
    return [int(to_crankbalance[m - 1]) for m in order]


def to_maker_order(order: Sequence[int], to_crankbalance: Sequence[int]) -> list[int]:
    """A firing order in crankbalance's numbers, in the maker's.

    Parameters
    ----------
    order : sequence of int
        crankbalance's cylinder numbers in firing order.
    to_crankbalance : sequence of int
        Entry k - 1: crankbalance's number of the maker's cylinder k.

    Returns
    -------
    list of int
        The same sequence in the maker's numbers.
    """
    maker = {int(c): m for m, c in enumerate(to_crankbalance, start=1)}
    return [maker[int(c)] for c in order]


def firing_tdc_angles(
    cylinder_angle: ArrayLike, cylinder_bank: ArrayLike, tdc_shift: ArrayLike
) -> NDArray[np.float64]:
    r"""Crank angle at which each cylinder is at a top dead centre, in [0, 2π).

    Cylinder c (crankpin at :math:`\varphi_c`, bank angle :math:`\beta_c`) is at top dead
    centre when :math:`\theta + \varphi_c - \beta_c = \psi_c`, :math:`\psi_c` the top dead
    centre of its offset slider-crank (:func:`crankbalance.physics.model.tdc_angle`; 0 without
    offset): :math:`\theta_c = \beta_c + \psi_c - \varphi_c` (the convention of
    :mod:`crankbalance.studies.build`).

    Parameters
    ----------
    cylinder_angle : array_like, shape (C,)
        Throw angle of each cylinder's crankpin [rad].
    cylinder_bank : array_like, shape (C,)
        Bank angle of each cylinder [rad].
    tdc_shift : array_like, shape (C,)
        Each cylinder's top-dead-centre angle past its axis, ``model.tdc_angle`` [rad].

    Returns
    -------
    ndarray, shape (C,)
        :math:`\theta_c` [rad], in [0, 2π).
    """
    theta = (
        np.asarray(cylinder_bank, dtype=float)
        + np.asarray(tdc_shift, dtype=float)
        - np.asarray(cylinder_angle, dtype=float)
    )
    out = np.mod(theta, 2 * np.pi)
    return np.where(out > 2 * np.pi - SAME_ANGLE, 0.0, out)


def order_intervals(tdc: ArrayLike, order: Sequence[int], strokes: int) -> NDArray[np.float64]:
    r"""The shortest firing intervals of an order on a crank, the last back to the first.

    From each cylinder of the order to the next, the crank turns to the next cylinder's
    next top dead centre: by :math:`(\theta_{next} - \theta_{this}) \bmod 2\pi`, a full
    turn for a four-stroke when both reach top dead centre together (the cam makes them
    fire a revolution apart), nothing for a two-stroke (which fires at every top dead
    centre, so both fire together; a cylinder firing with the first is listed right after
    it, so from the last back to the first it is a full turn). The order fits the crank
    when these intervals add up to at most one cycle (4π four-stroke, 2π two-stroke); a
    four-stroke whose intervals add up to 2π fires all its cylinders in one revolution
    and none in the next (a 180 deg twin), and any one interval may take that revolution.

    Parameters
    ----------
    tdc : array_like, shape (C,)
        Top-dead-centre angle of each cylinder [rad] (:func:`firing_tdc_angles`).
    order : sequence of int
        Cylinder numbers (1-based) in firing order, each once.
    strokes : {2, 4}
        Cycle type.

    Returns
    -------
    ndarray, shape (C,)
        Interval from each cylinder of the order to the next, the last to the first
        again [rad].
    """
    theta = np.asarray(tdc, dtype=float)[np.asarray(order, dtype=np.int64) - 1]
    step = np.mod(np.roll(theta, -1) - theta, 2 * np.pi)
    same = (step < SAME_ANGLE) | (step > 2 * np.pi - SAME_ANGLE)
    if strokes == 4:
        return np.where(same, 2 * np.pi, step)
    step = np.where(same, 0.0, step)
    if step.size and same[-1]:  # the last at the first's top dead centre: a turn to it
        step[-1] = 2 * np.pi
    return step


def crank_order(tdc: ArrayLike, first: int, strokes: int) -> tuple[list[int], NDArray[np.float64]]:
    r"""The most even firing order the crank allows, from cylinder ``first``.

    A two-stroke fires at every top dead centre; a four-stroke at one of each cylinder's
    two per cycle, chosen as :func:`crankbalance.physics.engine_cycle_all.firing_angles` chooses
    without a firing order (the most even intervals; every choice is tried).

    Parameters
    ----------
    tdc : array_like, shape (C,)
        Top-dead-centre angle of each cylinder [rad] (:func:`firing_tdc_angles`).
    first : int
        The cylinder to start from (1-based).
    strokes : {2, 4}
        Cycle type.

    Returns
    -------
    order : list of int
        Cylinder numbers in firing order.
    intervals : ndarray, shape (C,)
        Interval from each cylinder of the order to the next, the last to the first [rad].

    Raises
    ------
    InputError
        A four-stroke of more than ``MAX_FREE_CYLINDERS`` cylinders that does not fire
        evenly in the order 1..C (too many choices to try).
    """

    theta = np.asarray(tdc, dtype=float)
    cycle = math.pi * strokes
    fire = firing_angles(-theta, np.zeros_like(theta), None, strokes)
    after = np.mod(fire - fire[first - 1], cycle)
    after = np.where(after > cycle - SAME_ANGLE, 0.0, after)
    index = np.argsort(after, kind="stable")
    times = after[index]
    return [int(c) + 1 for c in index], np.diff(np.append(times, cycle))


def check_firing_order(
    tdc: ArrayLike,
    order: Sequence[int],
    strokes: int,
    field: str,
    value: object,
    maker_number: Sequence[int] | None = None,
) -> None:
    """Refuse a firing order the crank does not allow (:func:`order_intervals`).

    Parameters
    ----------
    tdc : array_like, shape (C,)
        Top-dead-centre angle of each cylinder [rad] (:func:`firing_tdc_angles`).
    order : sequence of int
        Cylinder numbers (1-based, crankbalance's) in firing order, each once.
    strokes : {2, 4}
        Cycle type.
    field : str
        The engine-file field the order came from, for the message.
    value : object
        The order as the user wrote it (the maker's numbers when a numbering is given).
    maker_number : sequence of int, optional
        The maker's number of each cylinder (by crankbalance's number), to give the
        order the crank allows in the maker's numbers too.

    Raises
    ------
    InputError
        When the shortest intervals of the order add up to more than one cycle; the
        message gives the top dead centres of the crank and an order it allows.
    """
    theta = np.asarray(tdc, dtype=float)
    cycle = math.pi * strokes
    steps = order_intervals(theta, order, strokes)
    if float(steps.sum()) <= cycle + 1e-6:
        return
    first = int(order[0])
    after = np.degrees(np.mod(theta - theta[first - 1] + SAME_ANGLE, 2 * np.pi) - SAME_ANGLE)
    angles = ", ".join(f"{c + 1}: {a:.4g}" for c, a in sorted(enumerate(after), key=lambda x: x[1]))
    try:
        allowed, gaps = crank_order(theta, first, strokes)
        hint = (
            "the most even order it allows is "
            + "-".join(map(str, allowed))
            + " (intervals "
            + "-".join(f"{g:.4g}" for g in np.degrees(gaps))
            + " deg)"
        )
        if maker_number is not None:
            hint += ", in the maker's numbers " + "-".join(
                str(maker_number[c - 1]) for c in allowed
            )
    except InputError:  # too many cylinders to try every choice
        hint = "give the order in which they reach it"
    raise InputError(
        field,
        value,
        f"this crank does not fire in that order within one cycle ({math.degrees(cycle):g} deg): "
        f"its shortest intervals add up to {math.degrees(float(steps.sum())):.4g} deg. The "
        f"cylinders reach top dead centre at (crankbalance's numbers: deg after cylinder "
        f"{first}'s, mod 360) {angles}; {hint}",
    )


#: a cylinder's firing angle may differ from one of its top dead centres by this much [rad]
TDC_TOLERANCE = 1e-6
#: most cylinders whose firing angles are chosen without a firing order (every one of the
#: 2^(C-1) choices of a four-stroke is tried)
MAX_FREE_CYLINDERS = 16


def firing_angles(
    cylinder_angle: ArrayLike,
    cylinder_bank: ArrayLike,
    firing_order: Sequence[int] | None,
    strokes: int,
    tdc_shift: ArrayLike | None = None,
) -> NDArray[np.float64]:
    r"""Crank angle of the first throw at which each cylinder fires, in [0, cycle).

    Cylinder c is at a top dead centre at :math:`\theta_c = \beta_c + \psi_c - \varphi_c`
    (mod :math:`2\pi`, :func:`crankbalance.physics.firing.firing_tdc_angles`; :math:`\psi_c`
    the top dead centre of an offset slider-crank past its axis, 0 without offset). A
    two-stroke fires at every top dead centre. A four-stroke fires at one of its two per
    cycle: the first cylinder of the firing order fires at
    :math:`\theta_c \in [0, 2\pi)`, and each next one at its next top dead centre, a
    full turn later when it is at top dead centre with the one before (the shortest
    intervals of :func:`crankbalance.physics.firing.order_intervals`, the same check
    :mod:`crankbalance.studies.build` makes of a firing order given with its crank); they
    must add up to at most one cycle. When they add up to one revolution (every cylinder
    fires in one), the empty revolution goes into the interval that leaves the firing most
    even (a 90° V-twin on one pin: 450°/270°, a 270° inline twin: 270°/450°). When the
    crank allows even firing (as :mod:`crankbalance.studies.build` derives the throw angles
    from the firing order), this gives exactly the even intervals.

    Without a firing order (``None``): the order 1, 2, ..., C when it fires evenly on this
    crank (what :mod:`crankbalance.studies.build` assumes), otherwise the choice of one
    top dead centre per cylinder that fires most evenly (the smallest largest deviation of
    an interval from :math:`4\pi/C`, then the smallest sum of squared deviations; every
    choice is tried, so at most :data:`MAX_FREE_CYLINDERS` cylinders).

    Parameters
    ----------
    cylinder_angle : array_like, shape (C,)
        Throw angle of each cylinder's crankpin :math:`\varphi_c` [rad].
    cylinder_bank : array_like, shape (C,)
        Bank angle of each cylinder :math:`\beta_c` [rad].
    firing_order : sequence of int or None
        Cylinder numbers (1-based) in firing order, each once; None when not known.
    strokes : {2, 4}
        Cycle type.
    tdc_shift : array_like, shape (C,), optional
        :math:`\psi_c` of each cylinder, :func:`crankbalance.physics.model.tdc_angle` of its offset
        [rad]; zeros when not given.

    Returns
    -------
    ndarray, shape (C,)
        Firing angle :math:`t_c` of each cylinder (by cylinder number) [rad], in
        [0, :math:`\pi\cdot` strokes).

    Raises
    ------
    InputError
        If the firing order is not a permutation of the cylinders, or if its cylinders
        cannot fire in that sequence within one cycle (``crank_train.firing_order``).

    References
    ----------
    The firing-interval convention of :mod:`crankbalance.studies.build`
    (``docs/engine_file.md``).
    """
    check_strokes(strokes)
    phi = np.asarray(cylinder_angle, dtype=float).reshape(-1)
    beta = np.asarray(cylinder_bank, dtype=float).reshape(-1)
    n = phi.size
    shift = np.zeros(n) if tdc_shift is None else np.asarray(tdc_shift, dtype=float).reshape(-1)
    if firing_order is None:
        return _free_firing(phi, beta, strokes, shift)
    order = list(firing_order)
    if beta.size != n or sorted(order) != list(range(1, n + 1)):
        raise InputError(
            "crank_train.firing_order",
            order,
            f"must name each of the {n} cylinders once (numbers 1 to {n})",
        )
    cycle = math.pi * strokes
    tdc = firing_tdc_angles(phi, beta, shift)
    index = np.array(order) - 1
    steps = order_intervals(tdc, order, strokes)  # the shortest, the last back to the first
    if steps.sum() > cycle + TDC_TOLERANCE:
        raise InputError(
            "crank_train.firing_order",
            order,
            "its cylinders do not reach their firing top dead centres in this sequence "
            f"within one cycle ({math.degrees(cycle):g} deg) of this crank; give the order "
            "in which the cylinders reach top dead centre, or give the firing angles",
        )
    if steps.sum() < cycle - TDC_TOLERANCE:  # a four-stroke firing all in one revolution:
        # the empty revolution goes into the interval that leaves the firing most even
        choices = steps[None, :] + 2 * np.pi * np.eye(n)
        deviation = np.abs(choices - cycle / n)
        worst = deviation.max(axis=1)
        best = np.flatnonzero(worst <= worst.min() + TDC_TOLERANCE)
        steps = choices[best[np.argmin((deviation[best] ** 2).sum(axis=1))]]
    times = np.empty(n)
    times[index] = float(tdc[index[0]]) + np.concatenate([[0.0], np.cumsum(steps[:-1])])
    return np.mod(times, cycle)


def _free_firing(phi: NDArray, beta: NDArray, strokes: int, shift: NDArray) -> NDArray[np.float64]:
    """Firing angles without a firing order (see :func:`firing_angles`)."""
    n = phi.size
    cycle = math.pi * strokes
    tdc = firing_tdc_angles(phi, beta, shift)
    try:
        even: NDArray[np.float64] | None = firing_angles(
            phi, beta, list(range(1, n + 1)), strokes, shift
        )
    except InputError:  # the cylinders do not reach top dead centre in the order 1..C
        even = None
    if even is not None:
        steps = np.diff(np.append(even, even[0] + cycle))
        if strokes == 2 or np.all(np.abs(steps - cycle / n) < TDC_TOLERANCE):
            return even
    if strokes == 2:  # every top dead centre fires: no choice
        return np.mod(tdc, cycle)
    if n > MAX_FREE_CYLINDERS:
        raise InputError(
            "crank_train.firing_order",
            None,
            f"is needed for this crank: its {n} cylinders cannot fire at even intervals "
            f"and more than {MAX_FREE_CYLINDERS} are too many to try every choice",
        )
    base = tdc[0] + np.mod(tdc - tdc[0], 2 * np.pi)  # one revolution from cylinder 1
    bits = (np.arange(2 ** (n - 1))[:, None] >> np.arange(n - 1)) & 1
    times = np.concatenate(
        [np.full((bits.shape[0], 1), base[0]), base[1:] + 2 * np.pi * bits], axis=1
    )
    ordered = np.sort(times, axis=1)
    gaps = np.diff(np.concatenate([ordered, ordered[:, :1] + cycle], axis=1), axis=1)
    deviation = np.abs(gaps - cycle / n)
    worst = deviation.max(axis=1)
    best = np.flatnonzero(worst <= worst.min() + TDC_TOLERANCE)
    pick = best[np.argmin((deviation[best] ** 2).sum(axis=1))]
    return np.mod(times[pick], cycle)


def check_strokes(strokes: int) -> None:
    """Refuse a cycle other than two or four strokes.

    Parameters
    ----------
    strokes : int
        Strokes per working cycle.

    Raises
    ------
    InputError
        If ``strokes`` is neither 2 nor 4.
    """
    if strokes not in (2, 4):
        raise InputError("strokes", strokes, "must be 2 or 4")
