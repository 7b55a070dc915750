r"""Crank counterweights: where the webs are, and the equations that size the masses on
them, for E engines of one layout at once (2021 paper, section 2, generalised).

With :math:`v_j = m_j r_c e^{i\psi_j}` the complex first moment of counterweight j at axial
position :math:`y_j`, the equations of each part of the crank (the whole crank, or each
half on its own) are the paper's Eq. 10, force and couple, x and z:

.. math:: \sum_j v_j = -U, \qquad \sum_j \frac{y_j}{L} v_j = -\frac{C_U}{L}

with :math:`U` the first moment of the unbalance to cancel (rotating masses plus
:math:`f_b` times the reciprocating masses on the pins) and :math:`C_U` its moment along
the crank (:math:`L`, the engine's length scale, keeps both rows of one size). The
paper's pattern (Eqs. 6-11, the sign-rule reading of docs/references.md) has equal masses
opposite their crankpins turned by :math:`\pm\alpha`, the sign following the side of the
mid-plane, :math:`v_j = M e^{i(\varphi_j + \pi + \sigma_j\alpha)}`: one real unknown
:math:`M` at a given angle (least squares), or, at the least-mass angle (``"optimal"``),
the two real unknowns :math:`X = M\cos\alpha`, :math:`Y = M\sin\alpha` of the linear system
:math:`v_j = e^{i(\varphi_j+\pi)}(X + i\sigma_j Y)` (least squares, least norm); webs in
the mid-plane (:math:`\sigma_j = 0`) make it non-linear, solved by an angle scan and a
bounded refinement. ``method="individual"`` gives each counterweight its own mass and
angle, the least :math:`\sum |v_j|^2` among the exact solutions (the pseudo-inverse).
Singular values below :data:`~crankbalance.results.ROUND_OFF` of the largest count as
zero: a rank decision must not follow round-off (issue 26: numpy's own cut-off, 9e-16,
did, and the W12's 300-120-300-120 crank got a mass that changed with its batch).

The engines are grouped by their web positions over their length scale (one set of
equations per group); each engine's numbers are computed on its own row
(:mod:`crankbalance.physics.balance_solver`).
"""

from __future__ import annotations

from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError
from ..records import record
from ..results import ROUND_OFF
from .balance_types import BatchCounterweights, CounterweightOptions, EngineFailed, SolverInput

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import ArrayLike, NDArray

    #: :func:`_factor2` of systems (E, R, 2): the matrix, q1 (E, R), r12 (E,), u (E, R),
    #: the divisors of x2 and x1 (E,), and the systems that need their least-norm solution
    _Factors = tuple[NDArray, NDArray, NDArray, NDArray, NDArray, NDArray, NDArray]


# --------------------------------------------------------------------------- the webs
def web_sides(throws: int, webs: tuple[int, ...] | None) -> tuple[NDArray, NDArray]:
    """Throw index and side of its throw's mid-plane of every counterweight web.

    Parameters
    ----------
    throws : int
        Number of throws T.
    webs : tuple of int, optional
        0/1 per web, two per throw from the y < 0 end; None: every web.

    Returns
    -------
    throw : ndarray of int, shape (W,)
        Index (0-based) of the throw of each web that carries a counterweight.
    side : ndarray, shape (W,)
        -1 for the web on the y < 0 side of its throw's mid-plane, +1 for the other [-].

    Raises
    ------
    InputError
        If ``webs`` does not have two entries per throw.
    """
    flags = np.ones(2 * throws, dtype=int) if webs is None else np.asarray(webs, dtype=int)
    if flags.size != 2 * throws:
        raise InputError(
            "counterweights.webs", list(flags), f"needs {2 * throws} entries (two per throw)"
        )
    index = np.flatnonzero(flags)
    return index // 2, np.where(index % 2 == 0, -1.0, 1.0)


def throw_pitch(throw_position: NDArray) -> float | None:
    """Smallest non-zero axial distance between throws.

    Parameters
    ----------
    throw_position : ndarray, shape (T,)
        Axial positions of the throws [m].

    Returns
    -------
    float or None
        The pitch [m]; None for one throw or throws all in one plane.
    """
    if throw_position.size > 1:
        spacing = np.diff(np.sort(throw_position))
        spacing = spacing[spacing > 0]
        if spacing.size:
            return float(spacing.min())
    return None


def crank_middle(throw_position: NDArray) -> float:
    """The crank's mid-point: the middle of the throws' extent.

    Parameters
    ----------
    throw_position : ndarray, shape (T,)
        Axial positions of the throws from the moment reference point [m].

    Returns
    -------
    float
        Its position from the moment reference point [m] (0 unless the engine file moves
        the reference; minus ``EngineModel.moment_reference``).
    """
    return 0.5 * float(throw_position.min() + throw_position.max())


@record
class Webs:
    """The counterweight webs of E engines of one layout.

    Parameters
    ----------
    throw : ndarray of int, shape (W,)
        Throw index (0-based) of each web.
    number : ndarray of int, shape (W,)
        Web number (1-based, two per throw from the y < 0 end).
    position : ndarray, shape (E, W)
        Axial position of each web [m].
    groups : list of ndarray of int
        The engines whose web positions over their length scale are equal, group by
        group (one set of equations per group) [-].
    """

    throw: NDArray[np.int64]
    number: NDArray[np.int64]
    position: NDArray[np.float64]
    groups: list[NDArray[np.int64]]


def web_geometry(inputs: SolverInput, options: CounterweightOptions) -> Webs:
    """Every engine's counterweight webs: each ``web_offset`` from its throw's mid-plane
    (default a quarter of the throw pitch, half the crank radius for one throw; paper
    Eq. 7), grouped by equal equations.

    Parameters
    ----------
    inputs : SolverInput
        The engines.
    options : CounterweightOptions
        The webs that carry a counterweight and their offset.

    Returns
    -------
    Webs
        Throws, numbers and positions of the webs, and the groups of engines.

    Raises
    ------
    InputError
        If ``options.webs`` does not have two entries per throw.
    """
    key = ("webs", options.webs, options.web_offset)
    webs: Webs | None = inputs.memo.get(key)
    if webs is None:
        webs = inputs.memo[key] = _web_geometry(inputs, options)
    return webs


def _web_geometry(inputs: SolverInput, options: CounterweightOptions) -> Webs:
    """:func:`web_geometry` computed, its arrays read-only (the input keeps them)."""
    y = inputs.throw_position
    throw, side = web_sides(y.size, options.webs)
    if options.web_offset is not None:
        offset = np.full(inputs.size, float(options.web_offset))
    else:
        pitch = throw_pitch(y)
        offset = np.full(inputs.size, pitch / 4.0) if pitch is not None else inputs.crank_radius / 2
    position = y[throw] + side * offset[:, None]
    normal = position / inputs.length[:, None]
    if inputs.size == 1 or np.all(normal == normal[:1]):
        groups = [np.arange(inputs.size)]
    else:
        _, inverse = np.unique(normal, axis=0, return_inverse=True)
        inverse = inverse.reshape(-1)
        order = np.argsort(inverse, kind="stable")
        groups = np.split(order, np.cumsum(np.bincount(inverse))[:-1])
    number = 2 * throw + (side > 0) + 1
    for array in (throw, number, position):
        array.flags.writeable = False
    return Webs(throw, number, position, groups)


def _parts(
    throw_position: NDArray, length: float, scope: str, throw_of_web: NDArray
) -> list[tuple[NDArray, NDArray]]:
    """(throw mask, web mask) of each part the counterweights balance on its own."""
    if scope == "whole":
        return [(np.ones(throw_position.size, bool), np.ones(throw_of_web.size, bool))]
    # halves of the crank about its own middle (not the moment reference point)
    y = (throw_position - crank_middle(throw_position)) / length
    if np.any(np.abs(y) <= ROUND_OFF) or throw_position.size < 2:
        raise InputError(
            "counterweights.scope",
            "halves",
            "balancing each half needs an even number of throws off the mid-plane",
        )
    lower = y < 0
    return [(lower, lower[throw_of_web]), (~lower, ~lower[throw_of_web])]


# --------------------------------------------------------------------------- counterweights
_FIRST = np.zeros(1, np.intp)  # the one column of a whole crank's target (E, 1)
_FIRST.flags.writeable = False


def solve_counterweights(
    inputs: SolverInput,
    webs: Webs,
    options: CounterweightOptions,
    halves: NDArray[np.bool_],
    target: NDArray,
    target_couple: NDArray,
    angle: NDArray | None = None,
) -> BatchCounterweights:
    """Counterweights whose forward first-order phasors cancel the targets of every engine.

    Parameters
    ----------
    inputs : SolverInput
        The engines.
    webs : Webs
        Their webs (:func:`web_geometry`).
    options : CounterweightOptions
        Method, angle and CG radius of the counterweights.
    halves : ndarray of bool, shape (E,)
        Whether each engine's halves are balanced each on its own.
    target : ndarray of complex, shape (E, T) or (E, 1)
        First moments to cancel per throw, or the whole crank's (``halves`` all False)
        [kg·m].
    target_couple : ndarray of complex, shape (E, T) or (E, 1)
        Their moments along the crank [kg·m²].
    angle : ndarray, shape (E,), optional
        The pattern's angle of each engine, in place of the options' [rad].

    Returns
    -------
    BatchCounterweights
        Masses [kg], directions [rad], the pattern's angle [rad] and the flags.

    Raises
    ------
    EngineFailed
        For an engine with a part of the crank without counterweight, or all its
        counterweights in one plane while a couple is to be cancelled.

    References
    ----------
    Appl. Sci. 2021, Eqs. 6-11 (Eq. 10 with the minus sign in the counterweight matrix,
    the sign rule of Eq. 8 generalised; docs/references.md).
    """
    n, count = inputs.size, webs.throw.size
    mass = np.zeros((n, count))
    direction = np.zeros((n, count))
    alpha = np.zeros(n)
    flipped = np.zeros(n, bool)
    already = np.zeros(n, bool)
    first = inputs.force_round_off / inputs.speed_squared  # first moments at round-off [kg·m]
    # the scopes the engines ask for: an engine balanced as a whole takes the whole
    # crank's equations, the others each half's (a batch of one asks for one)
    in_halves = int(np.count_nonzero(halves))
    scopes = ("whole",) if in_halves == 0 else ("halves",) if in_halves == n else None
    solved = False  # whether any engine got counterweights (else their moments are zero)
    for group in webs.groups:
        for scope in scopes or ("whole", "halves"):
            sub = group if scopes else group[halves[group] == (scope == "halves")]
            if not sub.size:
                continue
            equations = _equations(inputs, webs, options, scope, group)
            a, side = equations.a, equations.side
            b = np.empty((sub.size, a.shape[0]), complex)  # (E, Q), column by column
            sums = []
            parts = zip(equations.parts, equations.throws, strict=True)
            if sub.size == n:  # every engine, in order (one group, one scope)
                own, own_couple, own_length = target, target_couple, inputs.length
            else:
                own, own_couple, own_length = target[sub], target_couple[sub], inputs.length[sub]
            for q, ((_, web_mask), part_throws) in enumerate(parts):
                # take keeps each engine's row in one piece (a[:, mask] would not), so
                # its sum runs alike in a batch of one and of thousands
                # (a whole crank's target (E, 1) is its own sum)
                throws = part_throws if target.shape[-1] > 1 else _FIRST
                force = np.add.reduce(own.take(throws, axis=-1), -1)
                couple = np.add.reduce(own_couple.take(throws, axis=-1), -1)
                sums.append((web_mask, force, couple))
                b[:, 2 * q] = -force
                b[:, 2 * q + 1] = -couple / own_length
            still = np.maximum.reduce(np.abs(b), -1, initial=0.0) <= first[sub]
            already[sub] = still
            balanced = int(np.count_nonzero(still))
            if balanced == sub.size:
                continue
            live = None if balanced == 0 else ~still  # None: every engine of sub
            _check_planes(inputs, webs, options, sub, live, sums, equations.planes)
            if live is None:
                engines = sub
            else:
                engines, b = sub[live], b[live]
            solved = True
            if options.method == "individual":
                # least sum |v|^2 among the exact solutions
                pinv = equations.pinv  # (W, Q)
                v = np.einsum("eq,wq->ew", b, pinv.astype(b.dtype))  # each engine's row
                mass[engines] = np.abs(v) / options.cg_radius
                direction[engines] = np.where(mass[engines] > 0, np.angle(v), 0.0)
                continue
            optimal = angle is None and options.angle == "optimal"
            opposite, factors = _pattern(inputs, webs, options, scope, group, engines, optimal)
            if optimal:
                turn, m_c = _optimal_patterns(a, b, opposite, side, factors)
            else:
                fixed = options.angle if angle is None else angle[engines]
                turn = np.broadcast_to(np.asarray(fixed, dtype=float), engines.shape)
                m_c = _pattern_moments(a, b, opposite, side, turn)
            flip = m_c < 0  # the pattern points the wrong way: flip it (alpha + 180 deg)
            turned = opposite + side * turn[:, None] + np.where(flip, np.pi, 0.0)[:, None]
            mass[engines] = (np.abs(m_c) / options.cg_radius)[:, None]
            direction[engines] = np.mod(turned, 2 * np.pi)
            alpha[engines] = turn
            flipped[engines] = flip
    # what the counterweights leave of their target, the whole crank's crank-speed forward
    # force and couple (zero when they reach it)
    w2 = inputs.speed_squared
    if solved:
        moments = mass * options.cg_radius * np.exp(1j * direction)
        totals = (np.add.reduce(moments, -1), np.add.reduce(moments * webs.position, -1))
    else:  # no mass anywhere: the same zeros (+0) the expressions above give
        moments = np.zeros((n, count), complex)
        totals = (np.zeros(n, complex), np.zeros(n, complex))
    missed_force = w2 * np.abs(totals[0] + np.add.reduce(target, -1))
    missed_moment = w2 * np.abs(totals[1] + np.add.reduce(target_couple, -1))
    found = BatchCounterweights(
        options.method,
        options.cg_radius,
        webs.number,
        webs.throw + 1,
        webs.position,
        mass,
        direction,
        alpha,
        halves.copy(),
        flipped,
        already,
        # below_round_off of sizes (their own sizes)
        np.where(missed_force <= inputs.force_round_off, 0.0, missed_force),
        np.where(missed_moment <= inputs.moment_round_off, 0.0, missed_moment),
    )
    # the record's moments and their sums are these (the same expressions): kept, not
    # computed again
    for array in (moments, *totals):
        array.flags.writeable = False
    found.__dict__["moments"] = moments
    found.__dict__["moment_sums"] = totals
    return found


@record
class _Equations:
    """The counterweight equations of the engines of one group balanced as one scope says
    (:func:`_equations`): the same for every engine of the group.

    Parameters
    ----------
    length : float
        The length scale [m].
    normal : ndarray, shape (W,)
        The webs' positions over it [-].
    parts : list of (ndarray of bool, ndarray of bool)
        Each part's throw mask (T,) and web mask (W,).
    throws : list of ndarray of int
        Each part's throws (the positions in the throw mask).
    planes : list of str
        Each part's webs: ``"none"``, ``"one"`` plane or ``"many"``.
    a : ndarray, shape (Q, W)
        The equations' matrix.
    side : ndarray, shape (W,)
        Each web's side of the crank's mid-plane (-1, 0, +1), for the pattern's sign rule.
    """

    length: float
    normal: NDArray
    parts: list[tuple[NDArray, NDArray]]
    throws: list[NDArray]
    planes: list[str]
    a: NDArray
    side: NDArray

    @cached_property
    def pinv(self) -> NDArray:
        """The pseudo-inverse (W, Q) of ``a``, singular values at most
        :data:`~crankbalance.results.ROUND_OFF` of the largest counting as zero (read-only)."""
        found = np.linalg.pinv(self.a, rcond=ROUND_OFF)
        found.flags.writeable = False
        return found


def _equations(
    inputs: SolverInput, webs: Webs, options: CounterweightOptions, scope: str, group: NDArray
) -> _Equations:
    """The equations of the engines of ``group`` balanced as ``scope`` says, kept by the
    input for its next solve (its arrays read-only)."""
    key = ("equations", options.webs, options.web_offset, scope, int(group[0]))
    found: _Equations | None = inputs.memo.get(key)
    if found is None:
        length = float(inputs.length[group[0]])
        normal = webs.position[group[0]] / length
        parts = _parts(inputs.throw_position, length, scope, webs.throw)
        rows: list[NDArray] = []
        planes = []
        for _throw_mask, web_mask in parts:
            rows += [np.where(web_mask, 1.0, 0.0), np.where(web_mask, normal, 0.0)]
            plane = np.round(normal[web_mask], 12)
            planes.append(
                "none" if plane.size == 0 else "one" if plane.min() == plane.max() else "many"
            )
        a = np.array(rows)  # (Q, W), the same for the engines of the group
        side = np.sign(np.round(normal - crank_middle(inputs.throw_position) / length, 12))
        throws = [np.flatnonzero(throw_mask) for throw_mask, _ in parts]
        for array in (normal, a, side, *throws, *(m for part in parts for m in part)):
            array.flags.writeable = False
        found = inputs.memo[key] = _Equations(length, normal, parts, throws, planes, a, side)
    return found


def _pattern(
    inputs: SolverInput,
    webs: Webs,
    options: CounterweightOptions,
    scope: str,
    group: NDArray,
    engines: NDArray,
    optimal: bool,
) -> tuple[NDArray, _Factors | None]:
    """Each web's direction opposite its crankpin (E, W) [rad] of ``engines`` (a part of
    ``group``), and, for the least-mass pattern (``optimal``), the factors of its equations
    (:func:`_pattern_factors`; None with webs in the mid-plane or not ``optimal``): from the
    engines alone. One engine's input (kept by its model) keeps them for its next solve; a
    batch's, solved once, does not (they would only hold memory)."""
    key = ("pattern", options.webs, options.web_offset, scope, int(group[0]), engines.tobytes())
    found = inputs.memo.get(key)
    if found is None or (optimal and found[1] is None and not np.any(found[2] == 0)):
        opposite = np.take(inputs.throw_angle[engines], webs.throw, axis=-1) + np.pi
        equations = _equations(inputs, webs, options, scope, group)
        side = equations.side
        factors = (
            _pattern_factors(equations.a, opposite, side)
            if optimal and not np.any(side == 0)
            else None
        )
        for array in (opposite, *(factors or ())):
            array.flags.writeable = False
        found = (opposite, factors, side)
        if inputs.size == 1:
            inputs.memo[key] = found
    return found[0], found[1]


def _check_planes(
    inputs: SolverInput,
    webs: Webs,
    options: CounterweightOptions,
    sub: NDArray,
    live: NDArray | None,
    sums: list[tuple[NDArray, NDArray, NDArray]],
    planes: list[str],
) -> None:
    """A part without counterweight, or all its counterweights in one plane while a
    couple is to be cancelled: :class:`EngineFailed` naming the first such engine
    (``planes``: each part's, :class:`_Equations`; ``live``: the engines of ``sub`` to
    check, None for all)."""
    for (web_mask, force, couple), kind in zip(sums, planes, strict=True):
        if kind == "none":
            raise EngineFailed(
                InputError(
                    "counterweights.webs",
                    list(options.webs or []),
                    "a part of the crank that needs balancing has no counterweight",
                ),
                int(sub[0] if live is None else sub[live][0]),
            )
        if kind == "one":
            couple_first = inputs.moment_round_off[sub] / inputs.speed[sub] ** 2  # [kg·m²]
            plane = webs.position[sub, np.flatnonzero(web_mask)[0]]
            bad = np.abs(couple - plane * force) > couple_first
            if live is not None:
                bad &= live
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                raise EngineFailed(
                    InputError(
                        "counterweights.webs",
                        list(options.webs or []),
                        f"all counterweights lie in one plane (y = {plane[i] * 1e3:g} mm): "
                        "they cannot cancel the couple of the rotating masses; put "
                        "counterweights on webs in two planes",
                    ),
                    int(sub[i]),
                )


def _coefficients(unit: NDArray, a: NDArray) -> NDArray:
    """Each equation's coefficient of the pattern's unknown, engine by engine:
    ``unit`` (E, W) over the webs, ``a`` (Q, W) the equations; (E, Q) (einsum's own loops,
    no matrix product across the engines)."""
    return np.einsum("ew,qw->eq", unit, a.astype(unit.dtype))


def _pattern_moments(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray, alpha: NDArray
) -> NDArray:
    """First moment :math:`m_c r_c` of the pattern at one angle per engine (least squares
    with one real unknown): a (Q, W), b (E, Q), opposite (E, W), side (W,), alpha (E,)."""
    coeff = _coefficients(np.exp(1j * (opposite + side * alpha[:, None])), a)
    num = (np.conj(coeff) * b).sum(axis=-1).real
    den = (np.abs(coeff) ** 2).sum(axis=-1)
    safe = den > _floor(a)
    return np.where(safe, num / np.where(safe, den, 1.0), 0.0)


def _floor(a: NDArray) -> float:
    """Round-off of the squared coefficients of the pattern's equations ``a`` (Q, W): a
    pattern whose coefficients are all below it acts on nothing (no mass)."""
    return float(ROUND_OFF**2 * np.sum(np.abs(a).sum(axis=-1) ** 2))


def _optimal_patterns(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray, factors: _Factors | None = None
) -> tuple[NDArray, NDArray]:
    """Turn angle and first moment of the least-mass pattern that balances, per engine.

    Without counterweights in the mid-plane the pattern is linear in
    :math:`X = m_c r_c\\cos\\alpha`, :math:`Y = m_c r_c\\sin\\alpha`: least squares, least
    :math:`m_c` among the exact solutions (``factors``: those of :func:`_pattern_factors`
    for these arguments, when kept). Otherwise, engine by engine, an angle scan and a
    bounded refinement (:func:`optimal_pattern_scan`).
    """
    if factors is None and np.any(side == 0):  # (kept factors: no web in the mid-plane)
        found = [optimal_pattern_scan(a, b[i], opposite[i], side) for i in range(len(b))]
        return np.array([f[0] for f in found]), np.array([f[1] for f in found])
    if factors is None:
        factors = _pattern_factors(a, opposite, side)
    x, yv = _solve2(factors, np.concatenate([b.real, b.imag], axis=-1))
    return np.arctan2(yv, x), np.hypot(x, yv)


def _pattern_factors(a: NDArray, opposite: NDArray, side: NDArray) -> _Factors:
    """The factors (:func:`_factor2`) of the least-mass pattern's least squares: a (Q, W),
    opposite (E, W), side (W,) without zeros."""
    # direction e^{i(opposite + side*alpha)} = base (cos alpha + i side sin alpha)
    base = np.exp(1j * opposite)
    cx, cy = _coefficients(base, a), _coefficients(1j * side * base, a)
    matrix = np.stack(
        [np.concatenate([cx.real, cx.imag], axis=-1), np.concatenate([cy.real, cy.imag], axis=-1)],
        axis=-1,
    )
    return _factor2(matrix)


def _lstsq2(matrix: NDArray, rhs: NDArray) -> tuple[NDArray, NDArray]:
    """Least squares with two unknowns for many systems: matrix (E, R, 2), rhs (E, R).

    A QR factorisation by Gram-Schmidt (:func:`_factor2`, :func:`_solve2`); a system whose
    columns are nearly parallel (condition above about 1e6) goes to
    :func:`numpy.linalg.lstsq`'s rule, for its least-norm solution, singular values below
    :data:`~crankbalance.results.ROUND_OFF` of the largest counting as zero.
    """
    return _solve2(_factor2(matrix), rhs)


def _factor2(matrix: NDArray) -> _Factors:
    """The QR factors of :func:`_lstsq2` (Gram-Schmidt), of the matrix alone."""
    c1, c2 = matrix[..., 0], matrix[..., 1]
    r11 = np.linalg.norm(c1, axis=-1)
    ok = r11 > 0
    q1 = c1 / np.where(ok, r11, 1.0)[:, None]
    r12 = np.sum(q1 * c2, axis=-1)
    u = c2 - r12[:, None] * q1
    r22 = np.linalg.norm(u, axis=-1)
    ok &= r11 * r22 > 1e-6 * (r11**2 + r12**2 + r22**2)
    bad = np.flatnonzero(~ok)
    return matrix, q1, r12, u, np.where(ok, r22**2, 1.0), np.where(ok, r11, 1.0), bad


def _solve2(factors: _Factors, rhs: NDArray) -> tuple[NDArray, NDArray]:
    """:func:`_lstsq2` of the systems of ``factors`` (:func:`_factor2`) for ``rhs`` (E, R)."""
    matrix, q1, r12, u, den2, den1, bad = factors
    x2 = np.add.reduce(u * rhs, -1) / den2
    x1 = (np.add.reduce(q1 * rhs, -1) - r12 * x2) / den1
    if bad.size:  # the least-norm solutions of all of them at once (issue 30)
        x1[bad], x2[bad] = _least_norm2(matrix[bad], rhs[bad])
    return x1, x2


def _least_norm2(matrix: NDArray, rhs: NDArray) -> tuple[NDArray, NDArray]:
    """Least-norm least squares of many systems (E, R, 2) by their singular values, as
    :func:`numpy.linalg.lstsq` with ``rcond=ROUND_OFF`` solves each (a singular value at
    most ROUND_OFF of the largest counts as zero), one stacked SVD for all."""
    u, s, vt = np.linalg.svd(matrix, full_matrices=False)  # (E, R, 2), (E, 2), (E, 2, 2)
    keep = s > ROUND_OFF * s[:, :1]
    projected = np.einsum("erk,er->ek", u, rhs) / np.where(keep, s, 1.0)
    x = np.einsum("ekj,ek->ej", vt, np.where(keep, projected, 0.0))
    return x[:, 0], x[:, 1]


def pattern_masses(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray, alphas: ArrayLike
) -> tuple[NDArray, NDArray]:
    """First moment :math:`m_c r_c` [kg·m] of the equal counterweights of the paper's
    pattern and the residual of the equations, for many angles :math:`\\alpha` at once.

    Vectorised over ``alphas`` (least squares with one real unknown per angle).

    Parameters
    ----------
    a : ndarray, shape (Q, W)
        Equations over the webs: a row of ones (force) and a row of axial positions over
        the length scale (couple) per part [-].
    b : ndarray of complex, shape (Q,)
        Right-hand sides: minus the first moment to cancel, and minus its moment over the
        length scale [kg·m].
    opposite : ndarray, shape (W,)
        Direction opposite the crankpin of each web [rad].
    side : ndarray, shape (W,)
        Side of the mid-plane of each web (-1, 0 or +1) [-].
    alphas : array_like, shape (A,)
        Turn angles :math:`\\alpha` to evaluate [rad].

    Returns
    -------
    moment : ndarray, shape (A,)
        Least-squares :math:`m_c r_c` per angle [kg·m]; negative when the pattern points
        toward the crankpins.
    residual : ndarray, shape (A,)
        Euclidean norm of the residual of the equations [kg·m].

    References
    ----------
    Appl. Sci. 2021, Eqs. 8-10.
    """
    alpha = np.asarray(alphas, dtype=float)
    unit = np.exp(1j * (opposite[None, :] + side[None, :] * alpha[:, None]))  # (A, W)
    coeff = _coefficients(unit, a)  # (A, Q): each equation's coefficient of m_c r_c
    num = np.real(np.conj(coeff) @ b)
    den = np.sum(np.abs(coeff) ** 2, axis=1)
    safe = den > _floor(a)
    moment = np.where(safe, num / np.where(safe, den, 1.0), 0.0)
    residual = np.linalg.norm(coeff * moment[:, None] - b[None, :], axis=1)
    return moment, residual


def optimal_pattern_scan(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray
) -> tuple[float, float]:
    """Turn angle and first moment of the least-mass pattern of one engine with
    counterweights in the crank's mid-plane: a scan of :math:`\\alpha` over -90..90 deg
    in steps of 0.5 deg and a bounded refinement of the best step.

    Parameters
    ----------
    a, b, opposite, side
        As :func:`pattern_masses` [-], [kg·m], [rad], [-].

    Returns
    -------
    alpha : float
        The turn angle of least residual [rad].
    moment : float
        Its :math:`m_c r_c` [kg·m].
    """
    from scipy.optimize import minimize_scalar

    grid = np.radians(np.arange(-90.0, 90.0001, 0.5))
    moment, residual = pattern_masses(a, b, opposite, side, grid)
    score = residual + 1e-9 * np.abs(moment)
    k = int(np.argmin(score))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    best = minimize_scalar(
        lambda t: float(np.sum(pattern_masses(a, b, opposite, side, [t])[1])),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": 1e-12},
    )
    alpha = float(best.x)
    return alpha, float(pattern_masses(a, b, opposite, side, [alpha])[0][0])
