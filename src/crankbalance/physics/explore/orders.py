r"""Enumeration of firing orders and the cranks they imply, with their equivalences.

A candidate engine is a topology (throws, cylinders, banks, masses) and the crank angle
:math:`f_c` at which each cylinder fires. Cylinder 1 fires at 0; the firing sequence takes
the steps of the problem's interval pattern (even by default). A cylinder is at its
firing top dead centre when :math:`f_c + \varphi_{t(c)} - \beta_c \equiv 0 \pmod{2\pi}`
(``model.py``), so the firing order implies the crank, :math:`\varphi_{t(c)} = \beta_c - f_c`,
the rule of ``studies/build.py``; where several cylinders share a crankpin the order is
kept only if they agree on its angle.

Index space: index ``i = r (C-1)! + k`` where ``r`` is the rotation of the interval pattern
at which cylinder 1 fires (0 for even firing) and ``k`` the rank of the sequence of the
other cylinders in the factorial number system (Lehmer code), so a chunk of indices is
unranked without listing the others. :func:`chunk` keeps the canonical representative of
each class of equivalent descriptions, the one with the smallest index: rigid rotation of
the crank (removed by starting at cylinder 1), renumbering from the other end (a mirror
image of the engine) and, when the problem asks for it, time reversal. Which of these are
symmetries of a topology is found from its geometry and masses, not assumed.
``docs/explorer.md`` ("Enumeration") explains the choices.

Why one module over 800 lines: the index space, its unranking, the consistency of shared
pins, the symmetries and the size of a range are one enumeration; split, each part would
need the plan of the others.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Iterator, Sequence
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError
from ...records import record
from ..kinematics import KinematicsModel
from ..model import EngineModel, standard_layout, tdc_angle
from .candidates import Candidates

#: Layouts the explorer enumerates ("vr": two offset rows, one crankpin per cylinder; a W
#: from VR banks is layout "w" with ``vr_angle``).
LAYOUTS = ("inline", "boxer", "vee", "w", "radial", "vr")
#: Crank families: every crank the orders imply, planar cranks only, non-planar only, or
#: one crankpin per cylinder (vee and W).
CRANKS = ("any", "flat", "cross", "split")
#: Most cylinders: the index space ``P (C-1)!`` must fit a 64-bit integer.
MAX_CYLINDERS = 20
#: The plain engine used when no base is given: every number the explorer's topology takes
#: when the user names only a layout [SI units].
PLAIN = {
    "speed": 2 * math.pi * 6000 / 60,
    "crank_radius": 0.05,
    "rod_length": 0.15,
    "crank_pitch": 0.1,
    "reciprocating_mass": 0.5,
    "throw_rotating_mass": 1.0,
}
_TOL = 1e-9  # [rad] angles closer than this are equal
#: how close a candidate's crank must be to a fixed crank (``fixed_throw_angles``) [rad]:
#: 1e-4 deg, so a crank typed to four decimals of a degree (a VR's pins at 104.7027 deg)
#: is found; the candidate keeps its own exact crank
FIXED_CRANK_TOL = math.radians(1e-4)
#: smallest bank angle [rad] of a vee or W: banks closer than this (a thousand times the
#: tolerance of equal angles) cannot be told apart, and no symmetry, not even the identity,
#: was found for them (a 1e-12 deg vee ended in a ValueError of numpy)
MIN_BANK_ANGLE = 1000 * _TOL


def _gap(a: NDArray[np.float64]) -> NDArray[np.float64]:
    """Distance of an angle from 0 on the circle [rad]."""
    return np.abs(np.remainder(a + np.pi, 2 * np.pi) - np.pi)


@record(eq=False)
class Problem:
    """What to enumerate: a topology, its cycle and firing intervals, the crank family.

    Build it with :func:`problem`.

    Parameters
    ----------
    layout : str
        One of :data:`LAYOUTS`.
    topology : EngineModel
        Throws, cylinders, banks, masses and geometry shared by every candidate; with
        ``crank="split"`` one throw per cylinder (the cylinders of a pin's group at the
        group's axial position, each with its share of the throw's rotating mass).
    strokes : int
        Strokes per working cycle (2 or 4).
    crank : str
        One of :data:`CRANKS`.
    intervals : tuple of float
        Crank angle from each firing to the next [rad], C steps summing to the cycle
        (2π for 2-stroke, 4π for 4-stroke); all equal for even firing.
    fixed_throw_angles : tuple of float or None
        Throw angles [rad] of a fixed crank, one per throw of the topology: only the
        firing orders it allows (compared after rotating both cranks to the same throw 1).
    mirror : bool
        Whether an engine numbered from the other end (its mirror image) is the same.
    reversal : bool
        Whether an engine run backwards (the reverse firing order on the mirrored crank)
        is the same; not applied when the pistons are offset or the reversed interval
        pattern is no rotation of the pattern.
    """

    layout: str
    topology: EngineModel
    strokes: int
    crank: str
    intervals: tuple[float, ...]
    fixed_throw_angles: tuple[float, ...] | None = None
    mirror: bool = True
    reversal: bool = False

    @cached_property
    def _plan(self) -> _Plan:
        return _make_plan(self)

    @cached_property
    def pin_bank(self) -> NDArray[np.float64]:
        r"""Angle of each cylinder's crankpin at the crank angle where it fires [rad]:
        :math:`\beta_c + \psi_c - \psi_1`, its bank angle turned by the offset
        slider-crank's top-dead-centre angle :math:`\psi_c = \arcsin(e_c/(l+r))`
        (:func:`~crankbalance.physics.model.tdc_angle`) less cylinder 1's, the rule of
        ``studies/build.py``: a candidate's crank is :math:`\varphi_{t(c)} =
        \beta_c + \psi_c - \psi_1 - f_c`, so the offset rows of a VR engine fire at the
        candidate's even intervals (the bank angle itself without offsets)."""
        t = self.topology
        psi = tdc_angle(t.cylinder_offset, t.crank_radius, t.rod_length)
        return np.asarray(t.cylinder_bank + (psi - psi[0]), dtype=float)


@record
class _Plan:
    cylinders: int
    factorial: NDArray[np.int64]  # (C-1,) (C-2-k)! for Lehmer digit k
    span: int  # (C-1)!
    period: int  # P: distinct rotations of the interval pattern
    times: NDArray[np.float64]  # (P, C) fire time of slot k at rotation r [rad]
    kappa: int | None  # p[j] == p[kappa - j]: the pattern's reflection, if any
    group: tuple[tuple[NDArray[np.int64], int], ...]  # (cylinder map, time sign)
    pin_first: NDArray[np.int64]  # (C,) first cylinder on each cylinder's throw
    throw_first: NDArray[np.int64]  # (T,) first cylinder on each throw


def problem(
    layout: str,
    cylinders: int,
    strokes: int,
    bank_angle: float | None = None,
    crank: str = "any",
    intervals: Sequence[float] | None = None,
    fixed_throw_angles: Sequence[float] | None = None,
    base: EngineModel | None = None,
    mirror: bool = True,
    reversal: bool = False,
    vr_angle: float | None = None,
) -> Problem:
    """A problem from words: layout, cylinders, strokes and the crank family.

    Parameters
    ----------
    layout : str
        ``inline``, ``boxer``, ``vee``, ``w`` (broad arrow, three banks; two VR banks with
        ``vr_angle``), ``radial`` or ``vr`` (two rows ``bank_angle`` apart, one crankpin
        per cylinder; the rows' bore offsets come with ``base``).
    cylinders : int
        Number of cylinders, 1 to :data:`MAX_CYLINDERS`.
    strokes : int
        2 or 4.
    bank_angle : float, optional
        Vee angle, the angle between neighbouring banks of a W, or a VR's narrow angle
        between its rows [rad]; required for those layouts and not used by the others.
    crank : str
        ``any`` (every crank a firing order implies), ``flat`` (planar: every throw at 0 or
        π from throw 1), ``cross`` (not planar) or ``split`` (vee and W: each cylinder has
        its own crankpin, so every firing order is consistent).
    intervals : sequence of float, optional
        Uneven firing: the crank angle from each firing to the next [rad], one per
        cylinder, summing to 2π (2-stroke) or 4π (4-stroke); default even firing.
    fixed_throw_angles : sequence of float, optional
        A fixed crank [rad], one angle per throw (per cylinder with ``crank="split"``):
        only the firing orders it allows are enumerated.
    base : EngineModel, optional
        Masses and geometry, a model of the same layout (e.g. ``studies.build.build_model``
        of an engine file); default the plain engine :data:`PLAIN`.
    mirror : bool
        Count an engine numbered from the other end as the same (default True).
    reversal : bool
        Count an engine run backwards as the same (default False).
    vr_angle : float, optional
        Layout ``w`` only: a W from two VR banks, ``bank_angle`` apart, each with two rows
        ``vr_angle`` apart (:func:`~crankbalance.physics.model.standard_layout`) [rad].

    Returns
    -------
    Problem
        The problem, ready for :func:`count` and :func:`chunk`.
    """
    if layout not in LAYOUTS:
        raise InputError("layout", layout, f"one of {', '.join(LAYOUTS)}")
    if isinstance(cylinders, bool) or not isinstance(cylinders, (int, np.integer)):
        raise InputError("cylinders", cylinders, "a whole number")
    if not 1 <= cylinders <= MAX_CYLINDERS:
        raise InputError("cylinders", cylinders, f"from 1 to {MAX_CYLINDERS}")
    if vr_angle is not None and layout != "w":
        raise InputError("vr_angle", vr_angle, "only with layout w (a W from VR banks)")
    if vr_angle is not None and not MIN_BANK_ANGLE <= vr_angle <= math.pi / 2:
        raise InputError("vr_angle", vr_angle, f"from {math.degrees(MIN_BANK_ANGLE):.2g} to 90 deg")
    per_throw = {"vee": 2, "boxer": 2, "w": 3 if vr_angle is None else 2}.get(layout, 1)
    if cylinders % per_throw:
        vr_w = " (a W from two VR banks: give its engine file)" if layout == "w" else ""
        raise InputError(
            "cylinders", cylinders, f"a multiple of {per_throw} for layout {layout}{vr_w}"
        )
    if strokes not in (2, 4):
        raise InputError("strokes", strokes, "2 or 4")
    v = _bank_angle(layout, bank_angle)
    if crank not in CRANKS:
        raise InputError("crank", crank, f"one of {', '.join(CRANKS)}")
    if crank == "split" and (layout not in ("vee", "w") or vr_angle is not None):
        raise InputError(
            "crank", crank, "split crankpins need layout vee or a broad-arrow w (a VR has them)"
        )
    cycle = 2 * math.pi * strokes / 2
    steps = _intervals(intervals, cylinders, cycle)
    topology = _topology(layout, cylinders, strokes, v, crank == "split", base, vr_angle)
    fixed = None
    if fixed_throw_angles is not None:
        fixed = tuple(float(a) for a in fixed_throw_angles)
        if len(fixed) != topology.throws or not all(map(math.isfinite, fixed)):
            raise InputError(
                "fixed_throw_angles",
                list(fixed_throw_angles),
                f"{topology.throws} finite angles, one per throw",
            )
    return Problem(layout, topology, strokes, crank, steps, fixed, bool(mirror), bool(reversal))


def _bank_angle(layout: str, bank_angle: float | None) -> float:
    if layout not in ("vee", "w", "vr"):
        if bank_angle is not None:
            raise InputError("bank_angle", bank_angle, f"is not used with layout {layout}")
        return 0.0
    limit = math.pi if layout in ("vee", "vr") else math.pi / 2
    if bank_angle is None or not MIN_BANK_ANGLE <= bank_angle <= limit + 1e-12:
        raise InputError(
            "bank_angle",
            bank_angle,
            f"required for layout {layout}, from {math.degrees(MIN_BANK_ANGLE):.2g} to "
            f"{math.degrees(limit):g} deg",
        )
    return float(bank_angle)


def _intervals(intervals: Sequence[float] | None, n: int, cycle: float) -> tuple[float, ...]:
    if intervals is None:
        return (cycle / n,) * n
    steps = tuple(float(a) for a in intervals)
    if (
        len(steps) != n
        or not all(math.isfinite(a) and a > 0 for a in steps)
        or abs(sum(steps) - cycle) > _TOL * cycle
    ):
        raise InputError(
            "intervals",
            list(intervals),
            f"{n} positive angles summing to {math.degrees(cycle):g} deg (one working cycle)",
        )
    return steps


def _topology(
    layout: str,
    n: int,
    strokes: int,
    v: float,
    split: bool,
    base: EngineModel | None,
    vr_angle: float | None,
) -> EngineModel:
    positions, throw_of, banks = standard_layout(layout, n, v, PLAIN["crank_pitch"], vr_angle)
    articulation = None
    t = positions.size
    if base is None:
        name = f"plain {layout} {n}"
        scalars: tuple[float, KinematicsModel, float, float] = (
            PLAIN["speed"],
            "exact",
            PLAIN["crank_radius"],
            PLAIN["rod_length"],
        )
        rot = np.full(t, PLAIN["throw_rotating_mass"])
        rec = np.full(n, PLAIN["reciprocating_mass"])
        offset, axial, big_end = np.zeros(n), np.zeros(n), np.zeros(n)
    else:
        same = (
            base.cylinders == n
            and base.throws == t
            and np.array_equal(base.cylinder_throw, throw_of)
            and bool(np.all(_gap(base.cylinder_bank - banks) < _TOL))
        )
        if not same:
            raise InputError(
                "base",
                base.name,
                f"a model of the same layout ({layout}, {n} cylinders"
                + (f", bank angle {math.degrees(v):g} deg" if v else "")
                + ")",
            )
        name = base.name
        scalars = (base.speed, base.kinematics, base.crank_radius, base.rod_length)
        positions = base.throw_position.astype(float)
        rot = base.throw_rotating_mass.astype(float)
        rec = base.reciprocating_mass.astype(float)
        offset = base.cylinder_offset.astype(float)
        axial = base.cylinder_axial.astype(float)
        big_end = base.cylinder_rotating_mass.astype(float)
        articulation = base.articulation  # master-and-link rods: merit per distinct crank
    if split:  # one pin per cylinder, at its rod's position, with its share of the mass
        share = np.bincount(throw_of, minlength=t)[throw_of]
        positions, rot = positions[throw_of] + axial, rot[throw_of] / share
        throw_of, axial = np.arange(n, dtype=np.int64), np.zeros(n)
    speed, kinematics, radius, rod = scalars
    return EngineModel(
        name=name,
        speed=float(speed),
        kinematics=kinematics,
        crank_radius=float(radius),
        rod_length=float(rod),
        strokes=strokes,
        throw_angle=np.zeros(positions.size),
        throw_position=positions,
        throw_rotating_mass=rot,
        cylinder_throw=throw_of,
        cylinder_bank=banks,
        reciprocating_mass=rec,
        cylinder_offset=offset,
        cylinder_axial=axial,
        cylinder_rotating_mass=big_end,
        firing_order=tuple(range(1, n + 1)),
        firing_order_given=False,
        articulation=articulation,
    )


# --------------------------------------------------------------------------- plan
def _make_plan(p: Problem) -> _Plan:
    n = p.topology.cylinders
    steps = np.array(p.intervals)
    period = next(
        q for q in range(1, n + 1) if n % q == 0 and np.allclose(np.roll(steps, -q), steps, 0, _TOL)
    )
    times = np.array(
        [np.concatenate(([0.0], np.cumsum(np.roll(steps, -r))[:-1])) for r in range(period)]
    )
    j = np.arange(n)
    kappa = next((k for k in range(n) if np.allclose(steps[(k - j) % n], steps, 0, _TOL)), None)
    # run backwards, an offset piston pin is offset the other way: no longer the engine
    backwards = p.reversal and kappa is not None and not np.any(p.topology.cylinder_offset)
    signs = (1, -1) if backwards else (1,)
    throw_of = p.topology.cylinder_throw
    throw_first = np.array([np.flatnonzero(throw_of == t)[0] for t in range(p.topology.throws)])
    return _Plan(
        cylinders=n,
        factorial=np.array([math.factorial(n - 2 - k) for k in range(n - 1)], dtype=np.int64),
        span=math.factorial(n - 1),
        period=period,
        times=times,
        kappa=kappa,
        group=_symmetries(p.topology, p.mirror, signs),
        pin_first=throw_first[throw_of],
        throw_first=throw_first,
    )


def _symmetries(
    m: EngineModel, mirror: bool, signs: tuple[int, ...]
) -> tuple[tuple[NDArray[np.int64], int], ...]:
    """Maps of cylinders onto cylinders that leave the engine unchanged.

    An element (``to``, ``s``) turns cylinder c into cylinder ``to[c]``: the axial position
    y becomes ±y (−y: numbering from the other end, the mirror image), the bank angle β
    becomes s β + α for some rigid rotation α of the whole engine about the crank axis, and
    s = −1 (time reversal) turns crank angles and fire angles into their negatives. It is
    kept when every cylinder lands on a cylinder with the same reciprocating mass, offset
    and big-end mass whose throw has the same rotating mass, and cylinders sharing a throw
    land on one throw.
    """
    y, b = m.cylinder_position, m.cylinder_bank
    rec, rot = m.reciprocating_mass, m.throw_rotating_mass[m.cylinder_throw]
    own = np.stack([m.cylinder_offset, m.cylinder_rotating_mass])  # (2, C)
    size = 1e-9 * (1.0 + float(np.max(np.abs(y))))
    same_throw = m.cylinder_throw[:, None] == m.cylinder_throw[None, :]
    found: dict[tuple[tuple[int, ...], int], NDArray[np.int64]] = {}
    for a in (1, -1) if mirror else (1,):
        for s in signs:
            for alpha in b - s * b[0]:
                hit = (
                    (np.abs(y[None, :] - a * y[:, None]) < size)
                    & (_gap(b[None, :] - (s * b[:, None] + alpha)) < _TOL)
                    & np.isclose(rec[None, :], rec[:, None], rtol=1e-9, atol=0)
                    & np.isclose(rot[None, :], rot[:, None], rtol=1e-9, atol=0)
                    & np.all(np.isclose(own[:, None, :], own[:, :, None], 1e-9, 0), axis=0)
                )
                if not np.all(hit.sum(axis=1) == 1):
                    continue
                to = np.argmax(hit, axis=1).astype(np.int64)
                if np.unique(to).size == to.size and np.array_equal(
                    same_throw, same_throw[np.ix_(to, to)]
                ):
                    found[(tuple(to.tolist()), s)] = to
    return tuple((to, s) for (_, s), to in found.items())


# --------------------------------------------------------------------------- index space
def count(problem: Problem) -> int:
    """Size of the index space: ``P (C-1)!`` firing sequences starting at cylinder 1.

    Parameters
    ----------
    problem : Problem
        The problem.

    Returns
    -------
    int
        Number of indices; :func:`chunk` over ``[0, count)`` yields every distinct engine
        once (most indices are not canonical or not consistent, so far fewer candidates).
    """
    plan = problem._plan
    return plan.period * plan.span


def _unrank(plan: _Plan, index: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Slot of each cylinder (B, C) and the pattern's rotation (B,) of each index."""
    n = plan.cylinders
    rot, rank = np.divmod(index, plan.span)
    rest = np.tile(np.arange(1, n, dtype=np.int64), (index.size, 1))
    slots = np.zeros((index.size, n), dtype=np.int64)
    rows = np.arange(index.size)
    for k in range(n - 1):
        digit = (rank // plan.factorial[k]) % (n - 1 - k)
        slots[rows, rest[rows, digit]] = k + 1
        keep = np.arange(n - 2 - k)[None, :]
        rest = np.take_along_axis(rest, keep + (keep >= digit[:, None]), axis=1)
    return slots, rot


_Prefixes = tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64], NDArray[np.int64]]


def _root(problem: Problem, r: int) -> _Prefixes:
    """The one prefix of rotation ``r`` before any choice: cylinder 1 in slot 0."""
    throw_of = problem.topology.cylinder_throw
    m = problem._plan.cylinders - 1
    pin = np.full((1, problem.topology.throws), np.nan)
    first = np.remainder(problem.pin_bank[0] - problem._plan.times[r, 0], 2 * np.pi)
    pin[0, throw_of[0]] = first
    if problem.fixed_throw_angles is not None:  # every pin known: a fixed crank prunes early
        fixed = np.array(problem.fixed_throw_angles)
        pin[0] = np.remainder(first + fixed - fixed[throw_of[0]], 2 * np.pi)
    rest = np.arange(1, m + 1, dtype=np.int64)[None, :]
    return np.zeros(1, dtype=np.int64), np.zeros((1, m + 1), dtype=np.int64), pin, rest


def _children(
    problem: Problem, r: int, k: int, prefixes: _Prefixes, lo_end: int, hi_end: int
) -> tuple[_Prefixes, NDArray[np.int64]]:
    """The consistent prefixes one Lehmer digit (``k``) deeper whose blocks meet
    ``[lo_end, hi_end)``, and the position of each one's parent, by increasing index.

    A prefix is ``(lo, slots, pin, rest)``: the first index of its block (B,), the slots
    chosen so far (B, C), each throw's pin angle so far (B, T) [rad] (NaN: no cylinder of
    the throw placed yet) and the cylinders not yet placed (B, C-1-k). A child whose
    cylinder disagrees with a cylinder already on its pin is dropped with its whole block.
    """
    plan = problem._plan
    m = plan.cylinders - 1
    bank, throw_of = problem.pin_bank, problem.topology.cylinder_throw
    lo, slots, pin, rest = prefixes
    width = int(plan.factorial[k])
    digit = np.tile(np.arange(m - k), lo.size)
    parent = np.repeat(np.arange(lo.size), m - k)
    child_lo = lo[parent] + digit * width
    cylinder = rest[parent, digit]
    angle = np.remainder(bank[cylinder] - plan.times[r, k + 1], 2 * np.pi)
    known = pin[parent, throw_of[cylinder]]
    ok = (child_lo < hi_end) & (child_lo + width > lo_end)
    tol = _TOL if problem.fixed_throw_angles is None else FIXED_CRANK_TOL
    ok &= np.isnan(known) | (_gap(angle - known) < tol)
    parent, digit, cylinder, angle = parent[ok], digit[ok], cylinder[ok], angle[ok]
    lo = child_lo[ok]
    slots = slots[parent]
    slots[np.arange(lo.size), cylinder] = k + 1
    pin = pin[parent]
    pin[np.arange(lo.size), throw_of[cylinder]] = angle
    keep = np.arange(m - 1 - k)[None, :]
    rest = np.take_along_axis(rest[parent], keep + (keep >= digit[:, None]), axis=1)
    return (lo, slots, pin, rest), parent


def _rotations(plan: _Plan, start: int, stop: int) -> Iterator[tuple[int, int, int]]:
    """Each rotation r of the interval pattern that ``[start, stop)`` meets, with the range
    in that rotation's own indices."""
    for r in range(start // plan.span, (stop - 1) // plan.span + 1 if stop > start else 0):
        yield r, start - r * plan.span, stop - r * plan.span


#: Lehmer digits at the end of an index that :func:`_every_order` takes from one table of
#: the permutations of that many cylinders (6: 720 rows)
TABLE_DIGITS = 6


def _pins_alone(plan: _Plan) -> bool:
    """Whether every cylinder has a crankpin of its own (no pin to agree on)."""
    return bool(np.array_equal(plan.pin_first, np.arange(plan.cylinders)))


@functools.cache
def _lexicographic(j: int) -> NDArray[np.int64]:
    """Every permutation of ``range(j)`` in lexicographic order, shape (j!, j), read-only."""
    table = np.array(list(itertools.permutations(range(j))), dtype=np.int64)
    table = table.reshape(math.factorial(j), j)
    table.flags.writeable = False
    return table


def _every_order(
    plan: _Plan, start: int, stop: int
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """What :func:`_consistent` gives when no two cylinders share a pin: every index of
    ``[start, stop)`` (each its :func:`_unrank`), built block by block. The last ``j`` =
    min(C - 1, :data:`TABLE_DIGITS`) Lehmer digits run through all their values in a block
    of j! indices, which places the cylinders the block's first index leaves for the last
    j slots in every order, lexicographically: one table of those permutations serves
    every block."""
    n = plan.cylinders
    j = min(n - 1, TABLE_DIGITS)
    width = math.factorial(j)
    first = start // width
    heads = np.arange(first, -(-stop // width), dtype=np.int64) * width
    head_slots, _ = _unrank(plan, heads)
    head = np.argsort(head_slots, axis=1)  # the cylinder in each slot; the last j ascending
    sequence = np.empty((heads.size, width, n), dtype=np.int64)
    sequence[:, :, : n - j] = head[:, None, : n - j]
    sequence[:, :, n - j :] = head[:, n - j :][:, _lexicographic(j)]
    sequence = sequence.reshape(-1, n)[start - first * width : stop - first * width]
    slots = np.empty_like(sequence)
    slots[np.arange(sequence.shape[0])[:, None], sequence] = np.arange(n)
    index = np.arange(start, stop, dtype=np.int64)
    return index, slots, index // plan.span


#: most children of one level of the enumeration of a range, times the cylinders (8 bytes
#: each: 16 MB per array): a wider level is enumerated half after half (:func:`_consistent`)
LEVEL_ELEMENTS = 2_000_000
#: the most memory the prefixes of the enumeration of a range take at once [bytes]: a level
#: of LEVEL_ELEMENTS and its children's arrays, with the halves waiting their turn
TREE_BYTES = 48 * LEVEL_ELEMENTS


def _consistent(
    problem: Problem, start: int, stop: int
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """Indices, slots and rotations of the orders in ``[start, stop)`` whose cylinders
    sharing a crankpin agree on its angle, by increasing index.

    The Lehmer digits are chosen slot after slot (:func:`_children`); a prefix whose
    cylinders already disagree on a pin is dropped with the whole block of indices it
    starts, so a shared-pin layout never visits most of its inconsistent orders. A level
    whose children would exceed :data:`LEVEL_ELEMENTS` is split in two halves, the second
    waiting until the first is done (the prefixes are in index order, so the orders come
    out in index order): the memory stays bounded however the consistent orders cluster.
    """
    plan = problem._plan
    m = plan.cylinders - 1
    if problem.fixed_throw_angles is None and _pins_alone(plan):  # nothing to prune
        return _every_order(plan, start, stop)
    out: list[tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]] = []
    for r, lo_end, hi_end in _rotations(plan, start, stop):
        waiting: list[tuple[int, _Prefixes]] = [(0, _root(problem, r))]
        while waiting:
            k, level = waiting.pop()
            while k < m:
                wide = level[0].size * (m - k) * plan.cylinders > LEVEL_ELEMENTS
                if wide and level[0].size > 1:
                    half = level[0].size // 2
                    waiting.append((k, tuple(a[half:] for a in level)))  # type: ignore[arg-type]
                    level = tuple(a[:half] for a in level)  # type: ignore[assignment]
                    continue
                level = _children(problem, r, k, level, lo_end, hi_end)[0]
                k += 1
            lo, slots = level[0], level[1]
            out.append((lo + r * plan.span, slots, np.full(lo.size, r, dtype=np.int64)))
    if not out:
        empty = np.zeros(0, dtype=np.int64)
        return empty, np.zeros((0, m + 1), dtype=np.int64), empty
    return (
        np.concatenate([o[0] for o in out]),
        np.concatenate([o[1] for o in out]),
        np.concatenate([o[2] for o in out]),
    )


@record
class Size:
    """How large the enumeration of a range of indices is, known before it is listed.

    Parameters
    ----------
    orders : int
        Consistent firing orders in the range [-] (every candidate is one of them).
    prefixes : int
        Prefixes the enumeration builds over the range, all levels together [-] (its
        cost: a shared-pin layout builds many more prefixes than it finds orders).
    widest : int
        Most prefixes of one level [-] (what the enumeration of the whole range holds at
        once).
    exact : bool
        Whether the three are counted; else they are estimated (:func:`size`).
    """

    orders: int
    prefixes: int
    widest: int
    exact: bool


#: most children the exact count of :func:`size` builds at one level, times the cylinders
#: (about 32 MB per array of int64): beyond, the rest is estimated
SIZE_ELEMENTS = 4_000_000
#: random paths of the estimate of :func:`size` (Knuth's estimator)
SIZE_PATHS = 8192


@functools.lru_cache(maxsize=16)
def size(problem: Problem, start: int, stop: int) -> Size:
    """How many consistent firing orders ``[start, stop)`` holds, and how many prefixes
    their enumeration builds: counted, or estimated when counting would cost too much.

    On layouts where no two cylinders share a crankpin every order is consistent and every
    prefix is built: the sizes follow from the range. Otherwise the prefixes are
    enumerated level by level as :func:`chunk` does, while a level stays under
    :data:`SIZE_ELEMENTS`; when the enumeration ends, the sizes are exact (the W12's 480
    orders among 39.9 million indices). Else the levels below the last one counted are
    estimated by Knuth's estimator (D. E. Knuth, Estimating the efficiency of backtrack
    programs, Math. Comp. 29 (1975) 121-136): :data:`SIZE_PATHS` random paths down from
    prefixes of that level, each choosing one consistent child at random and weighted by
    the product of the numbers of children met; the mean weight at a level times the
    prefixes counted is an unbiased estimate of that level's prefixes.

    Parameters
    ----------
    problem : Problem
        The problem.
    start, stop : int
        Index range, ``0 <= start <= stop <= count(problem)``.

    Returns
    -------
    Size
        The orders, prefixes and widest level of the range, and whether they are exact.
    """
    total = count(problem)
    if not 0 <= start <= stop <= total:
        raise InputError("span", (start, stop), f"0 <= start <= stop <= {total}")
    plan = problem._plan
    m = plan.cylinders - 1
    unshared = np.unique(problem.topology.cylinder_throw).size == plan.cylinders
    if unshared and problem.fixed_throw_angles is None:
        built = sum(_blocks(plan, start, stop, k) for k in range(m + 1))
        return Size(stop - start, built, stop - start, True)
    rng = np.random.default_rng(0)
    orders = prefixes = widest = 0
    exact = True
    for r, lo_end, hi_end in _rotations(plan, start, stop):
        level = _root(problem, r)
        for k in range(m):
            prefixes += level[0].size
            widest = max(widest, level[0].size)
            if level[0].size * (m - k) * plan.cylinders > SIZE_ELEMENTS:
                exact = False
                found, built, most = _estimate(problem, r, k, level, lo_end, hi_end, rng)
                orders, prefixes, widest = orders + found, prefixes + built, max(widest, most)
                break
            level = _children(problem, r, k, level, lo_end, hi_end)[0]
        else:
            prefixes += level[0].size
            widest = max(widest, level[0].size)
            orders += level[0].size
    return Size(orders, prefixes, widest, exact)


def _blocks(plan: _Plan, start: int, stop: int, k: int) -> int:
    """Blocks of prefixes of level ``k`` (each (C-1-k)! indices) that ``[start, stop)``
    meets, summed over the rotations: the prefixes an unshared-pin layout builds."""
    width = math.factorial(plan.cylinders - 1 - k)
    return sum(
        (min(hi, plan.span) - 1) // width - max(lo, 0) // width + 1
        for _, lo, hi in _rotations(plan, start, stop)
    )


def _estimate(
    problem: Problem,
    r: int,
    k: int,
    level: _Prefixes,
    lo_end: int,
    hi_end: int,
    rng: np.random.Generator,
) -> tuple[int, int, int]:
    """The orders, the prefixes (levels below ``k``) and the widest level below the
    prefixes ``level`` of level ``k``, estimated (:func:`size`)."""
    m = problem._plan.cylinders - 1
    paths, weight = _thin(level, np.ones(level[0].size), rng)
    built = widest = 0.0
    for j in range(k, m):
        children, parent = _children(problem, r, j, paths, lo_end, hi_end)
        weight = weight[parent]
        built += float(weight.sum())
        widest = max(widest, float(weight.sum()))
        paths, weight = _thin(children, weight, rng)
    return math.ceil(weight.sum()), math.ceil(built), math.ceil(widest)


def _thin(
    prefixes: _Prefixes, weight: NDArray[np.float64], rng: np.random.Generator
) -> tuple[_Prefixes, NDArray[np.float64]]:
    """At most :data:`SIZE_PATHS` of the prefixes, drawn uniformly without replacement,
    each standing for ``n / SIZE_PATHS`` times its weight: the weighted sum of the kept
    prefixes' descendants is an unbiased estimate of that of all."""
    n = prefixes[0].size
    if n <= SIZE_PATHS:
        return prefixes, weight
    pick = np.sort(rng.choice(n, size=SIZE_PATHS, replace=False))
    kept: _Prefixes = tuple(a[pick] for a in prefixes)  # type: ignore[assignment]
    return kept, weight[pick] * (n / SIZE_PATHS)


def template(problem: Problem) -> Candidates:
    """One candidate of the problem's topology (its own crank and firing order, which need
    not be consistent): what the figures of merit of a batch look like (their columns do
    not depend on the values), before any enumeration.

    Parameters
    ----------
    problem : Problem
        The problem.

    Returns
    -------
    Candidates
        A batch of one candidate, index 0.
    """
    t = problem.topology
    return Candidates(
        topology=t,
        throw_angle=t.throw_angle[None, :],
        firing_order=np.array([t.firing_order], dtype=np.int64),
        fire_angle=np.zeros((1, t.cylinders)),
        equivalents=np.ones(1, dtype=np.int64),
        index=np.zeros(1, dtype=np.int64),
    )


def _rank(plan: _Plan, slots: NDArray[np.int64], rot: NDArray[np.int64]) -> NDArray[np.int64]:
    """Inverse of :func:`_unrank`."""
    rest = np.argsort(slots, axis=1)[:, 1:]
    rank = np.zeros(slots.shape[0], dtype=np.int64)
    for k in range(plan.cylinders - 1):
        rank += np.sum(rest[:, k + 1 :] < rest[:, k : k + 1], axis=1) * plan.factorial[k]
    return rot * plan.span + rank


def _transform(
    plan: _Plan, to: NDArray[np.int64], s: int, slots: NDArray[np.int64], rot: NDArray[np.int64]
) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """The same engines described after one symmetry, cylinder 1 again firing first."""
    n = plan.cylinders
    new = np.empty_like(slots)
    new[:, to] = (s * slots) % n
    if s == -1:  # the reversed pattern read from the reflection kappa
        assert plan.kappa is not None
        rot = (plan.kappa - rot + 1) % n
    first = new[:, 0]
    return (new - first[:, None]) % n, (rot + first) % plan.period


def _crank(
    problem: Problem, slots: NDArray[np.int64], rot: NDArray[np.int64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """Fire angles (B, C), throw angles (B, T) [rad] and which rows the problem allows."""
    plan = problem._plan
    fire = plan.times[rot[:, None], slots]
    pin = np.remainder(problem.pin_bank - fire, 2 * np.pi)
    if _pins_alone(plan):  # every pin's one cylinder agrees with itself
        ok = np.ones(pin.shape[0], dtype=bool)
    else:
        ok = np.all(_gap(pin - pin[:, plan.pin_first]) < _TOL, axis=1)
    throw = pin[:, plan.throw_first]
    relative = throw - throw[:, :1]
    if problem.crank in ("flat", "cross"):
        planar = np.all(_gap(2 * relative) < 2 * _TOL, axis=1)
        ok &= planar if problem.crank == "flat" else ~planar
    if problem.fixed_throw_angles is not None:
        fixed = np.array(problem.fixed_throw_angles)
        ok &= np.all(_gap(relative - (fixed - fixed[0])) < FIXED_CRANK_TOL, axis=1)
    return fire, throw, ok


def chunk(problem: Problem, start: int, stop: int) -> Candidates:
    """The canonical candidates whose index lies in ``[start, stop)``.

    A candidate is kept when its firing order is consistent with the crank family (and
    the fixed crank) and no equivalent description has a smaller index. Chunks therefore
    hold different numbers of candidates; the union over any split of ``[0, count)`` is
    the same set in the same order.

    Parameters
    ----------
    problem : Problem
        The problem.
    start, stop : int
        Index range, ``0 <= start <= stop <= count(problem)``.

    Returns
    -------
    Candidates
        The canonical candidates in the range, by increasing index.
    """
    total = count(problem)
    if not 0 <= start <= stop <= total:
        raise InputError("chunk", (start, stop), f"0 <= start <= stop <= {total}")
    return _canonical(problem, *_consistent(problem, start, stop))


def _canonical(
    problem: Problem, index: NDArray[np.int64], slots: NDArray[np.int64], rot: NDArray[np.int64]
) -> Candidates:
    """The candidates among the rows (indices, slots, rotations) that the crank family
    and the fixed crank allow and that are the canonical description of their engine."""
    if _every_crank_allowed(problem):  # the cranks of the canonical rows only
        keep, equivalents = _equivalences(problem, slots, rot, index)
        index, slots, rot, equivalents = index[keep], slots[keep], rot[keep], equivalents[keep]
        fire, throw, _ = _crank(problem, slots, rot)
    else:
        fire, throw, ok = _crank(problem, slots, rot)
        index, slots, rot, fire, throw = index[ok], slots[ok], rot[ok], fire[ok], throw[ok]
        keep, equivalents = _equivalences(problem, slots, rot, index)
        index, slots, fire, throw, equivalents = (
            index[keep],
            slots[keep],
            fire[keep],
            throw[keep],
            equivalents[keep],
        )
    return Candidates(
        topology=problem.topology,
        throw_angle=throw,
        firing_order=np.argsort(slots, axis=1) + 1,
        fire_angle=fire,
        equivalents=equivalents,
        index=index,
    )


#: most indices of a problem whose equivalences (:func:`_equivalences`) are looked up in a
#: table made once per problem (9 bytes an index: 363 kB for 8! = 40 320 indices); a
#: larger problem computes them for each range
ORBIT_TABLE = 40_320
#: indices of the orbit table computed at once (its temporaries: under 5 MB)
ORBIT_PIECE = 8192


def _equivalences(
    problem: Problem, slots: NDArray[np.int64], rot: NDArray[np.int64], index: NDArray[np.int64]
) -> tuple[NDArray[np.bool_], NDArray[np.int64]]:
    """Whether each allowed row is the canonical description of its engine (no
    equivalent description has a smaller index), and how many distinct descriptions it
    has: from :func:`_orbit` of the rows, or, for a problem of at most
    :data:`ORBIT_TABLE` indices, looked up in :func:`_orbit_table` (the same numbers:
    each row's images depend on that row alone)."""
    table = _orbit_table(problem) if count(problem) <= ORBIT_TABLE else None
    if table is not None:
        return table[0][index], table[1][index]
    images = _orbit(problem, slots, rot, index)
    return np.min(images, axis=1) == index, _distinct(images)


@functools.lru_cache(maxsize=16)
def _orbit_table(problem: Problem) -> tuple[NDArray[np.bool_], NDArray[np.int64]]:
    """:func:`_equivalences` of every index of the problem (its rows unranked), computed
    once, read-only; the rows a crank family or a fixed crank does not allow are never
    looked up."""
    total = count(problem)
    canonical = np.empty(total, dtype=bool)
    equivalents = np.empty(total, dtype=np.int64)
    for start in range(0, total, ORBIT_PIECE):  # bounded temporaries
        index = np.arange(start, min(start + ORBIT_PIECE, total), dtype=np.int64)
        slots, rot = _unrank(problem._plan, index)
        images = _orbit(problem, slots, rot, index)
        canonical[index] = np.min(images, axis=1) == index
        equivalents[index] = _distinct(images)
    canonical.flags.writeable = False
    equivalents.flags.writeable = False
    return canonical, equivalents


def _every_crank_allowed(problem: Problem) -> bool:
    """Whether :func:`_crank` allows every row: no pin shared, every crank of the
    family, no fixed crank (so :func:`chunk` derives the cranks of the rows it keeps
    only; a row's crank is computed on its own, the same bits either way)."""
    return (
        problem.crank not in ("flat", "cross")
        and problem.fixed_throw_angles is None
        and _pins_alone(problem._plan)
    )


def at(problem: Problem, index: ArrayLike) -> Candidates:
    """The canonical candidates among the given indices: what :func:`chunk` of each index
    alone gives, for all of them at once (a random search's draws, each its own index).

    Each index is unranked directly (:func:`_unrank`) and kept when the enumeration would
    reach it (cylinders sharing a crankpin agree on its angle, compared in firing sequence
    as :func:`_children` compares them), the crank family and the fixed crank allow it,
    and no equivalent description has a smaller index.

    Parameters
    ----------
    problem : Problem
        The problem.
    index : array_like of int, shape (B,)
        Indices, increasing and distinct, each ``0 <= index < count(problem)`` [-].

    Returns
    -------
    Candidates
        The canonical candidates among them, by increasing index.

    Raises
    ------
    InputError
        For indices outside the index space, not increasing or not distinct.
    """
    index = np.asarray(index, dtype=np.int64).reshape(-1)
    total = count(problem)
    if index.size and (index[0] < 0 or index[-1] >= total or np.any(np.diff(index) <= 0)):
        raise InputError(
            "index", f"{index.size} indices", f"increasing, distinct, from 0 to {total - 1}"
        )
    plan = problem._plan
    slots, rot = _unrank(plan, index)
    # the enumeration's rule: each cylinder agrees with the one placed before it on its pin
    angle = np.remainder(problem.pin_bank - plan.times[rot[:, None], slots], 2 * np.pi)
    reached = np.ones(index.size, dtype=bool)
    throw_of = problem.topology.cylinder_throw
    for t in range(problem.topology.throws):
        group = np.flatnonzero(throw_of == t)
        if group.size > 1:
            order = np.argsort(slots[:, group], axis=1)
            placed = np.take_along_axis(angle[:, group], order, axis=1)
            reached &= np.all(_gap(np.diff(placed, axis=1)) < _TOL, axis=1)
    return _canonical(problem, index[reached], slots[reached], rot[reached])


def _orbit(
    problem: Problem,
    slots: NDArray[np.int64],
    rot: NDArray[np.int64],
    index: NDArray[np.int64] | None = None,
) -> NDArray[np.int64]:
    """Index of each allowed equivalent description (B, G); disallowed ones are max int.

    The rows are allowed; a symmetry keeps pins shared and cranks planar or not, so an
    image can only be disallowed by a fixed crank. ``index``, when given, is the rows' own
    index, used for the identity.
    """
    plan = problem._plan
    out = np.empty((slots.shape[0], len(plan.group)), dtype=np.int64)
    n = plan.cylinders
    for g, (to, s) in enumerate(plan.group):
        if index is not None and s == 1 and np.array_equal(to, np.arange(n)):
            out[:, g] = index
            continue
        image, image_rot = _transform(plan, to, s, slots, rot)
        out[:, g] = _rank(plan, image, image_rot)
        if problem.fixed_throw_angles is not None:  # the rest holds for every image
            ok = _crank(problem, image, image_rot)[2]
            out[:, g] = np.where(ok, out[:, g], np.iinfo(np.int64).max)
    return out


def _distinct(images: NDArray[np.int64]) -> NDArray[np.int64]:
    """Number of distinct allowed indices per row."""
    s = np.sort(images, axis=1)
    fresh = np.concatenate([np.ones((s.shape[0], 1), bool), s[:, 1:] != s[:, :-1]], axis=1)
    return np.sum(fresh & (s != np.iinfo(np.int64).max), axis=1).astype(np.int64)


def equivalent_orders(problem: Problem, firing_order: Sequence[int]) -> list[tuple[int, ...]]:
    """Every firing order that describes the same engine as ``firing_order``, itself too.

    Parameters
    ----------
    problem : Problem
        The problem (its equivalences, crank family and fixed crank).
    firing_order : sequence of int
        Cylinder numbers (crankbalance's numbering) in firing sequence; its first cylinder
        fires at the start of the problem's first interval (any cylinder may come first).

    Returns
    -------
    list of tuple of int
        The equivalent orders by increasing index (the first is the canonical one), each
        written from the cylinder that fires at the start of the first interval (cylinder
        1 for even firing).
    """
    plan = problem._plan
    n = plan.cylinders
    order = [int(c) for c in firing_order]
    if sorted(order) != list(range(1, n + 1)):
        raise InputError("firing_order", order, f"a permutation of 1..{n} (each cylinder once)")
    slots = np.empty((1, n), dtype=np.int64)
    slots[0, np.array(order) - 1] = np.arange(n)
    slots, rot = _transform(plan, np.arange(n), 1, slots, np.zeros(1, dtype=np.int64))
    if not _crank(problem, slots, rot)[2][0]:
        raise InputError(
            "firing_order",
            order,
            f"an order the problem allows (crank {problem.crank}"
            + (", the fixed crank" if problem.fixed_throw_angles else "")
            + "; cylinders sharing a crankpin must agree on its angle)",
        )
    images = _orbit(problem, slots, rot)[0]
    found = np.unique(images[images != np.iinfo(np.int64).max])
    slots, rot = _unrank(plan, found)
    sequence = np.argsort(slots, axis=1) + 1
    return [
        tuple(int(c) for c in np.roll(row, r % n)) for row, r in zip(sequence, rot, strict=True)
    ]
