r"""Figures of merit of a batch of candidate engines, one column per figure.

:func:`merit` takes a :class:`~crankbalance.physics.explore.candidates.Candidates` batch and
returns a dictionary of columns of length B, every column named with its SI unit as a
suffix (``F2_N``, ``M1_Nm``, ``cw_mass_kg``, ``mirror_rad``; no suffix for pure numbers
and counts). The figures and their formulas are in ``docs/explorer.md`` ("Figures of
merit"):

- free forces and moments of the reciprocating masses, orders 1..K, forward and backward
  phasor magnitudes and the largest magnitude over a revolution
  (:mod:`crankbalance.physics.shaking`);
- the rotating masses' force and couple, the crank without counterweights;
- counterweight mass, balance shafts needed and what is left, for a balancing target with
  a balance factor (:func:`crankbalance.physics.balance_batch.balance_batch`; an engine
  with master-and-link rods by the one-engine :func:`crankbalance.physics.balancing.balance`
  once per distinct crank, as its forces by :func:`crankbalance.physics.shaking.free_forces`);
- crank symmetry: how far the crank is from its mirror image about its mid-plane;
- firing intervals: the largest deviation from even firing, of the engine and of each bank;
- torsional excitation: the relative vector sum of each engine order's gas-torque
  harmonic over the cylinders, weighted by a mode shape (:data:`TORSION_ASSUMPTION`).

Forces and moments at most the engine's round-off (:func:`crankbalance.results.round_off`,
the one rule of every output) are exactly zero, so a filter can ask for ``F2 == 0``.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError
from ...results import ROUND_OFF, below_round_off, round_off
from ..balance_batch import balance_batch
from ..balance_types import BatchBalance, CounterweightOptions, ShaftOptions
from ..balancing import balance
from ..model import EngineBatch, EngineModel, engine_batch
from ..shaking import BatchFreeForces, batch_free_forces, free_forces
from .candidates import Candidates

Target = Literal["none", "counterweights", "primary", "secondary"]
#: balancing targets, from the least to the most: no balancing, crank counterweights
#: only, counterweights and a primary shaft pair, and a secondary shaft pair as well
TARGETS: tuple[str, ...] = ("none", "counterweights", "primary", "secondary")
#: the balancing columns of a target other than "none" (:func:`balance_columns`)
BALANCE_COLUMNS: tuple[str, ...] = (
    "cw_mass_kg",
    "shafts",
    "shaft_mass_kg",
    "residual_F_N",
    "residual_M_Nm",
)
#: the named mode shapes (or one weight per cylinder)
MODE_SHAPES: tuple[str, ...] = ("uniform", "linear")
#: the assumption behind the torsional-excitation columns, to print beside them
TORSION_ASSUMPTION = (
    "torsional excitation X<k> = |sum_c w_c exp(i k a_c)| / sum_c |w_c| for engine order "
    "k, a_c the crank angle at which cylinder c fires: every cylinder's gas-torque "
    "harmonic of order k has the same amplitude and the same phase relative to its own "
    "firing (equal cylinders), and w_c is the relative amplitude of the torsional mode at "
    "cylinder c (1 = every cylinder's harmonic in phase at the mode's antinode)"
)


def merit(
    candidates: Candidates,
    target: Target = "counterweights",
    balance_factor: float = 0.0,
    mode_shape: str | ArrayLike = "uniform",
    orders: int = 8,
    counterweights: CounterweightOptions | None = None,
    shafts: ShaftOptions | None = None,
) -> dict[str, NDArray]:
    """Figures of merit of every candidate, as columns.

    Parameters
    ----------
    candidates : Candidates
        The batch (B candidates of one topology).
    target : {"none", "counterweights", "primary", "secondary"}
        Balancing target: none (no balancing columns), crank counterweights only, with a
        primary balance shaft pair, or with primary and secondary shaft pairs.
    balance_factor : float
        Share of the reciprocating masses the counterweights carry [-] (ignored when
        ``counterweights`` is given: its own factor counts).
    mode_shape : {"uniform", "linear"} or array_like, shape (C,)
        Weights of the torsional mode at the cylinders [-]: all 1, linear along the crank
        (:func:`mode_weights`), or one per cylinder (crankbalance's numbering).
    orders : int
        Highest order K of the free forces and moments and of the torsional excitation.
    counterweights : CounterweightOptions, optional
        Default: a counterweight on every web at the crank radius, at the least-mass angle
        (as ``balance_engine`` without a [counterweights] table), with ``balance_factor``.
    shafts : ShaftOptions, optional
        The balance shafts of both orders; default a co- and counter-rotating pair at the
        crank radius, its outer masses as far apart as the outer throws (twice the crank
        radius at least).

    Returns
    -------
    dict of str to ndarray, each shape (B,)
        ``F<n>_N``, ``F<n>f_N``, ``F<n>b_N`` largest, forward and backward force of order
        n [N]; ``M<n>_Nm``, ``M<n>f_Nm``, ``M<n>b_Nm`` the same for the moment about the
        crank mid-point [N·m]; ``Frot_N``, ``Mrot_Nm`` force and couple of the rotating
        masses [N], [N·m]; ``mirror_rad`` [rad]; ``interval_dev_rad`` and
        ``bank_interval_dev_rad`` [rad]; ``X<k>`` torsional excitation of engine order k
        [-] (``X1p5`` is order 1.5); unless ``target`` is "none": ``cw_mass_kg`` total
        counterweight mass [kg], ``shafts`` shafts needed [-], ``shaft_mass_kg`` total
        shaft mass [kg], ``residual_F_N`` and ``residual_M_Nm`` the largest force [N] and
        moment [N·m] of any order left after balancing.

    Raises
    ------
    InputError
        For an unknown target or mode shape, a mode shape of the wrong length, or orders
        outside 1..64.

    References
    ----------
    Free forces and the vector sum of the cylinders' torque harmonics (phase diagrams,
    major and minor orders): Den Hartog (1956) ch. 5 (textbook).
    """
    topo = candidates.topology
    weights = _checked(topo, target, mode_shape, orders)
    # the forces, the symmetry and the balancing depend on the crank alone: computed once
    # per distinct crank of the batch, each candidate's row taken from its crank's (every
    # engine's numbers come from its own row, so they are the bits of a batch of all)
    first, crank_of = distinct_rows(candidates.throw_angle)
    cranks = candidates if first.size == candidates.size else candidates.take(first)

    def each(columns: dict[str, NDArray]) -> dict[str, NDArray]:
        """Every candidate's row of columns computed per distinct crank (the columns of
        one dtype taken at once, as the rows of one array)."""
        if cranks is candidates:
            return columns
        out: dict[str, NDArray] = {}
        for dtype in {v.dtype for v in columns.values()}:
            names = [k for k, v in columns.items() if v.dtype == dtype]
            rows = np.stack([columns[k] for k in names]).take(crank_of, axis=1)
            out.update(zip(names, rows, strict=True))
        return {k: out[k] for k in columns}

    free, shared = _free_columns(cranks, int(orders))
    out = each(free | {"mirror_rad": mirror_asymmetry(cranks.throw_angle)})
    cycle = 2 * np.pi * topo.strokes / 2
    out["interval_dev_rad"] = interval_deviation(candidates.fire_angle, cycle)
    out["bank_interval_dev_rad"] = bank_interval_deviation(
        candidates.fire_angle, topo.cylinder_bank, cycle, whole=out["interval_dev_rad"]
    )
    steps = torsion_orders(topo.strokes, int(orders))
    excitation = torsional_excitation(candidates.fire_angle, weights, steps)
    for k, order in enumerate(steps):
        out[order_name(order)] = excitation[:, k]
    if target != "none":
        out.update(
            each(
                balance_columns(
                    cranks, target, balance_factor, counterweights, shafts, int(orders), shared
                )
            )
        )
    return out


def _checked(
    topology: EngineModel, target: str, mode_shape: str | ArrayLike, orders: int
) -> NDArray[np.float64]:
    """The mode's weights at the cylinders, after the checks of :func:`merit`'s target,
    orders and mode shape."""
    if target not in TARGETS:
        raise InputError("target", target, f"one of {', '.join(TARGETS)}")
    if not (isinstance(orders, int | np.integer) and 1 <= orders <= 64):
        raise InputError("orders", orders, "an integer from 1 to 64")
    return mode_weights(topology, mode_shape)


def column_names(
    topology: EngineModel,
    target: Target = "counterweights",
    balance_factor: float = 0.0,
    mode_shape: str | ArrayLike = "uniform",
    orders: int = 8,
) -> list[str]:
    """The names of the columns :func:`merit` gives for a batch of ``topology``, in its
    order, without evaluating a candidate (the run's plan counts them:
    :func:`crankbalance.physics.explore.work.plan`).

    Parameters
    ----------
    topology : EngineModel
        The layout.
    target, balance_factor, mode_shape, orders
        As :func:`merit` (``balance_factor`` [-] does not change the columns).

    Returns
    -------
    list of str
        The column names.

    Raises
    ------
    InputError
        As :func:`merit`, for an unknown target or mode shape, a mode shape of the wrong
        length, or orders outside 1..64.
    """
    _checked(topology, target, mode_shape, orders)
    names = [
        f"{q}{n}{s}_{u}"
        for n in range(1, int(orders) + 1)
        for q, u in (("F", "N"), ("M", "Nm"))
        for s in ("", "f", "b")
    ]
    names += ["Frot_N", "Mrot_Nm", "mirror_rad", "interval_dev_rad", "bank_interval_dev_rad"]
    names += [order_name(order) for order in torsion_orders(topology.strokes, int(orders))]
    return names + (list(BALANCE_COLUMNS) if target != "none" else [])


def distinct_rows(rows: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """The distinct rows of a 2-D array, bit for bit (a crank of the batch, each once).

    Parameters
    ----------
    rows : array_like, shape (B, N)
        The rows (throw angles [rad], say).

    Returns
    -------
    first : ndarray of int, shape (D,)
        Position of the first row of each distinct row, in increasing order [-].
    inverse : ndarray of int, shape (B,)
        For each row, the position in ``first`` of its distinct row [-], so that
        ``rows[first][inverse]`` is ``rows``.
    """
    a = np.ascontiguousarray(rows)
    if a.shape[0] <= 1:
        return np.arange(a.shape[0]), np.zeros(a.shape[0], dtype=np.int64)
    key = a.view(np.dtype((np.void, a.dtype.itemsize * a.shape[1]))).ravel()
    # runs of equal neighbours first (the explorer's slices come crank by crank, the
    # sorted fire angles of even firing are all alike): the sort sees one row per run;
    # a row's first appearance is the start of its first run
    size = a.dtype.itemsize
    bits = a.reshape(a.shape[0], -1).view(f"u{size}" if size in (1, 2, 4, 8) else np.uint8)
    run = np.flatnonzero(np.r_[True, np.any(bits[1:] != bits[:-1], axis=1)])
    lengths = np.diff(np.r_[run, a.shape[0]])
    if _increasing(a.reshape(a.shape[0], -1)[run]):  # sorted already: each run is a row
        return run.astype(np.int64), np.repeat(np.arange(run.size, dtype=np.int64), lengths)
    _, first, inverse = np.unique(key[run], return_index=True, return_inverse=True)
    order = np.argsort(first)  # distinct rows in the order they first appear
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    of_run = rank[inverse.reshape(-1)].astype(np.int64)
    return run[first[order]].astype(np.int64), np.repeat(of_run, lengths)


def _increasing(rows: NDArray) -> bool:
    """Whether each row is lexicographically greater than the one before it, by value (so
    no two rows are equal, in value or in bits)."""
    if rows.shape[0] < 2:
        return True
    differ = rows[1:] != rows[:-1]
    at = differ.argmax(axis=1)[:, None]  # the first column where two neighbours differ
    after = np.take_along_axis(rows[1:], at, axis=1)
    return bool(
        np.all(
            np.take_along_axis(differ, at, axis=1)
            & (after > np.take_along_axis(rows[:-1], at, axis=1))
        )
    )


def order_name(order: float) -> str:
    """Column name of the torsional excitation of an engine order: ``X1``, ``X1p5``.

    Parameters
    ----------
    order : float
        Engine order, a whole or half number [-].

    Returns
    -------
    str
        ``X`` and the order, ``p5`` for a half.
    """
    whole = math.floor(order)
    return f"X{whole}" if order == whole else f"X{whole}p5"


def torsion_orders(strokes: int, orders: int) -> NDArray[np.float64]:
    """Engine orders of the gas-torque harmonics: steps of 1/2 for 4-stroke, 1 for 2-stroke.

    Parameters
    ----------
    strokes : int
        Strokes per working cycle (2 or 4).
    orders : int
        Highest order.

    Returns
    -------
    ndarray, shape (N,)
        Orders 0.5, 1, ..., ``orders`` (4-stroke) or 1, 2, ..., ``orders`` [-].
    """
    step = 2.0 / strokes
    return np.arange(1, round(orders / step) + 1, dtype=float) * step


def mode_weights(topology: EngineModel, mode_shape: str | ArrayLike) -> NDArray[np.float64]:
    """Relative amplitude of the torsional mode at each cylinder.

    ``"uniform"``: 1 at every cylinder. ``"linear"``: the first mode of a crank with a
    heavy flywheel at the y > 0 end (after the last throw) as a straight line, with its
    node one throw pitch beyond the last throw: :math:`w = (T - t)/T` for throw
    :math:`t = 0..T-1`, 1 at the free end (throw 1) down to :math:`1/T`; cylinders on one
    throw share its weight.

    Parameters
    ----------
    topology : EngineModel
        The layout (throws of the cylinders).
    mode_shape : {"uniform", "linear"} or array_like, shape (C,)
        A named shape or one weight per cylinder [-] (finite, not all zero).

    Returns
    -------
    ndarray, shape (C,)
        Weights [-].

    Raises
    ------
    InputError
        For an unknown name, a wrong length, a non-finite or an all-zero weight.
    """
    if isinstance(mode_shape, str):
        if mode_shape == "uniform":
            return np.ones(topology.cylinders)
        if mode_shape == "linear":
            t = topology.throws
            return (t - topology.cylinder_throw) / t
        raise InputError(
            "mode_shape", mode_shape, f"one of {', '.join(MODE_SHAPES)} or a weight per cylinder"
        )
    weights = np.asarray(mode_shape, dtype=float)
    if weights.shape != (topology.cylinders,) or not np.all(np.isfinite(weights)):
        raise InputError(
            "mode_shape",
            weights.tolist(),
            f"{topology.cylinders} finite weights, one per cylinder",
        )
    if not np.any(weights):
        raise InputError("mode_shape", weights.tolist(), "weights not all zero")
    return weights


def free_columns(candidates: Candidates, orders: int) -> dict[str, NDArray]:
    """Free forces and moments of every candidate by order, and of the rotating masses.

    Parameters
    ----------
    candidates : Candidates
        The batch.
    orders : int
        Highest order K.

    Returns
    -------
    dict of str to ndarray, each shape (B,)
        ``F<n>_N``, ``F<n>f_N``, ``F<n>b_N`` [N], ``M<n>_Nm``, ``M<n>f_Nm``, ``M<n>b_Nm``
        [N·m] for n = 1..K, and ``Frot_N`` [N], ``Mrot_Nm`` [N·m]: magnitudes of the
        phasors of :func:`crankbalance.physics.shaking.batch_free_forces` (the moment's
        magnitude is the couple's), each zero at most the engine's round-off
        (:func:`crankbalance.results.round_off`).
    """
    return _free_columns(candidates, orders)[0]


def _free_columns(
    candidates: Candidates, orders: int
) -> tuple[dict[str, NDArray], tuple[EngineBatch, BatchFreeForces] | None]:
    """:func:`free_columns`, and the batch and phasors they come from when the batch
    solver can take them (:func:`balance_columns`' ``shared``: a topology without
    master-and-link rods, orders 1..K with K at least 2); else None."""
    if candidates.size == 0:  # an empty chunk of the enumeration: empty columns
        names = column_names(candidates.topology, "none", orders=orders)[: 6 * orders + 2]
        return {name: np.zeros(0) for name in names}, None
    shared = None
    if candidates.topology.articulation is not None:
        f, force, moment = _articulated_forces(candidates, orders)
    else:
        batch = engine_batch(
            candidates.topology, candidates.size, throw_angle=candidates.throw_angle
        )
        f = batch_free_forces(batch, orders)
        force, moment = (level[:, None] for level in round_off(batch))
        shared = (batch, f) if orders >= 2 else None
    sizes = {}
    for name, fwd, bwd, level in (
        ("F", f.force_forward, f.force_backward, force),
        ("M", f.couple_forward, f.couple_backward, moment),
    ):
        # every order at once, order by order in rows: |phasor|, zero at most the level
        # (the bits of np.abs(below_round_off(...)) of each column)
        forward = np.abs(fwd[:, :orders].T, order="C")
        backward = np.abs(bwd[:, :orders].T, order="C")
        forward[forward <= level[:, 0]] = 0.0
        backward[backward <= level[:, 0]] = 0.0
        sizes[name] = (forward + backward, forward, backward)
    out: dict[str, NDArray] = {}
    for n in range(orders):
        for name, unit in (("F", "N"), ("M", "Nm")):
            total, forward, backward = sizes[name]
            out[f"{name}{n + 1}_{unit}"] = total[n]
            out[f"{name}{n + 1}f_{unit}"] = forward[n]
            out[f"{name}{n + 1}b_{unit}"] = backward[n]
    out["Frot_N"] = np.abs(below_round_off(f.rotating_force, force[:, 0]))
    out["Mrot_Nm"] = np.abs(below_round_off(f.rotating_couple, moment[:, 0]))
    return out, shared


def _articulated_forces(
    candidates: Candidates, orders: int
) -> tuple[BatchFreeForces, NDArray[np.float64], NDArray[np.float64]]:
    """The phasors of a batch whose topology has master-and-link rods, one engine at a
    time by the one-engine path (:func:`crankbalance.physics.shaking.free_forces`, the
    exact articulated piston motion), with their round-off levels (B, 1): the batch model
    has no master-and-link rods, and :func:`merit` calls this once per distinct crank (one
    for a radial, whose every order shares its single throw)."""
    rows = [(free_forces(model, orders), round_off(model)) for model in _one_engines(candidates)]
    f = BatchFreeForces(
        np.arange(1, orders + 1),
        *(
            np.array([getattr(r[0], name) for r in rows])
            for name in (
                "force_forward",
                "force_backward",
                "couple_forward",
                "couple_backward",
                "rotating_force",
                "rotating_couple",
                "roll",
                "rotating_roll",
            )
        ),
    )
    levels = np.array([r[1] for r in rows], dtype=float)
    return f, levels[:, :1], levels[:, 1:]


def _one_engines(candidates: Candidates) -> list[EngineModel]:
    """Each candidate as an engine of its own (the topology on the candidate's crank), for
    the one-engine path of master-and-link rods, which the batch model has not."""
    return [
        dataclasses.replace(candidates.topology, throw_angle=np.array(angle, dtype=float))
        for angle in candidates.throw_angle
    ]


def mirror_asymmetry(throw_angle: ArrayLike) -> NDArray[np.float64]:
    r"""How far each crank is from its mirror image about the crank's mid-plane.

    The largest angle between throw t and throw T + 1 - t,
    :math:`\max_t |\varphi_t - \varphi_{T+1-t}|` (wrapped to [0, π]). Zero for a
    mirror-symmetric crank (the flat inline-4, the inline-6, the crossplane V8 is not):
    with equal masses at symmetric positions such a crank has no free couple of any order.

    Parameters
    ----------
    throw_angle : array_like, shape (B, T)
        Throw angles [rad].

    Returns
    -------
    ndarray, shape (B,)
        The asymmetry [rad], 0 to π.
    """
    phi = np.asarray(throw_angle, dtype=float)
    gap = np.abs(np.remainder(phi - phi[:, ::-1] + np.pi, 2 * np.pi) - np.pi)
    return np.where(gap < 1e-9, 0.0, gap).max(axis=-1, initial=0.0)


def interval_deviation(fire_angle: ArrayLike, cycle: float) -> NDArray[np.float64]:
    """Largest deviation of the firing intervals from even, per candidate.

    The fire angles sorted around the cycle give C intervals (the last closes the cycle);
    even firing has every interval ``cycle / C``.

    Parameters
    ----------
    fire_angle : array_like, shape (B, C)
        Crank angle at which each cylinder fires [rad].
    cycle : float
        Crank angle of one working cycle, 4π (4-stroke) or 2π (2-stroke) [rad].

    Returns
    -------
    ndarray, shape (B,)
        :math:`\\max |\\Delta - \\text{cycle}/C|` over the intervals Δ [rad]; 0 for one
        cylinder.
    """
    alpha = np.sort(np.mod(np.asarray(fire_angle, dtype=float), cycle), axis=-1)
    if alpha.shape[0] > 1:  # each distinct set of angles once (all alike for even firing)
        first, inverse = distinct_rows(alpha)
        if first.size < alpha.shape[0]:
            return _deviation(alpha[first], cycle)[inverse]
    return _deviation(alpha, cycle)


def _deviation(alpha: NDArray[np.float64], cycle: float) -> NDArray[np.float64]:
    """:func:`interval_deviation` of angles sorted in [0, cycle)."""
    gaps = np.diff(alpha, axis=-1, append=alpha[:, :1] + cycle)
    dev = np.abs(gaps - cycle / alpha.shape[-1]).max(axis=-1, initial=0.0)
    return np.where(dev < 1e-9, 0.0, dev)


def bank_interval_deviation(
    fire_angle: ArrayLike, bank: ArrayLike, cycle: float, whole: ArrayLike | None = None
) -> NDArray[np.float64]:
    """Largest deviation from even firing of the cylinders of each bank, over the banks.

    A bank is the cylinders of one bank angle (a vee's two banks, a boxer's two sides, a
    W's three banks; an in-line engine is one bank): how even the pulses into that bank's
    exhaust manifold are (the crossplane V8: 90° off, the flat-plane V8: even).

    Parameters
    ----------
    fire_angle : array_like, shape (B, C)
        Crank angle at which each cylinder fires [rad].
    bank : array_like, shape (C,)
        Bank angle of each cylinder [rad].
    cycle : float
        Crank angle of one working cycle [rad].
    whole : array_like, shape (B,), optional
        :func:`interval_deviation` of all the cylinders, when computed before: an engine
        of one bank takes a copy of it [rad].

    Returns
    -------
    ndarray, shape (B,)
        The largest :func:`interval_deviation` of any bank [rad].
    """
    alpha = np.asarray(fire_angle, dtype=float)
    key = np.round(np.mod(np.asarray(bank, dtype=float), 2 * np.pi), 9)
    banks = np.unique(key)
    if whole is not None and banks.size == 1:  # one bank: its deviation is the whole's
        return np.array(whole, dtype=float)
    dev = np.zeros(alpha.shape[0])
    for value in banks:
        dev = np.maximum(dev, interval_deviation(alpha[:, key == value], cycle))
    return dev


def torsional_excitation(
    fire_angle: ArrayLike, weights: ArrayLike, orders: ArrayLike
) -> NDArray[np.float64]:
    r"""Relative vector sum of the gas-torque harmonics over the cylinders, per order.

    .. math:: X_k = \frac{|\sum_c w_c\,e^{i k \alpha_c}|}{\sum_c |w_c|}

    with :math:`\alpha_c` the crank angle at which cylinder c fires: 1 where every
    cylinder's harmonic adds in phase (the major orders of an even-firing engine with a
    uniform mode), 0 where they cancel (:data:`TORSION_ASSUMPTION`). Computed once per
    distinct row of fire angles (with equal weights, per distinct set: every even-firing
    candidate of a problem has the same value), the angles summed in increasing order.

    Parameters
    ----------
    fire_angle : array_like, shape (B, C)
        Crank angle at which each cylinder fires [rad].
    weights : array_like, shape (C,)
        Mode shape at the cylinders [-].
    orders : array_like, shape (N,)
        Engine orders k [-].

    Returns
    -------
    ndarray, shape (B, N)
        :math:`X_k` [-], 0 to 1.

    References
    ----------
    Den Hartog (1956) ch. 5 (the phase diagrams of the harmonics of the cylinders).
    """
    w = np.asarray(weights, dtype=float)
    alpha = np.asarray(fire_angle, dtype=float)
    k = np.asarray(orders, dtype=float)
    if alpha.shape[0] > 1:
        if np.all(w == w[0]):  # equal weights: the sum does not depend on the cylinders' order
            alpha = np.sort(alpha, axis=-1)
        first, inverse = distinct_rows(alpha)  # each distinct set of fire angles once
        if first.size < alpha.shape[0]:
            return torsional_excitation(alpha[first], w, k)[inverse]
    value = np.empty((alpha.shape[0], k.size))
    for j, order in enumerate(k):  # one order at a time: temporaries of (B, C)
        angle = order * alpha
        # each row summed on its own (not a matrix product, whose rounding may depend on
        # the number of rows): a candidate's value does not depend on its batch
        value[:, j] = np.hypot((np.cos(angle) * w).sum(axis=-1), (np.sin(angle) * w).sum(axis=-1))
    value /= np.abs(w).sum()
    return below_round_off(value, ROUND_OFF)  # a share of 1: the one rule on its own scale


def balance_columns(
    candidates: Candidates,
    target: Target,
    balance_factor: float,
    counterweights: CounterweightOptions | None,
    shafts: ShaftOptions | None,
    orders: int,
    shared: tuple[EngineBatch, BatchFreeForces] | None = None,
) -> dict[str, NDArray]:
    """Counterweights and balance shafts every candidate needs for a balancing target.

    Parameters
    ----------
    candidates : Candidates
        The batch.
    target : {"counterweights", "primary", "secondary"}
        See :func:`merit`.
    balance_factor : float
        Share of the reciprocating masses the default counterweights carry [-].
    counterweights : CounterweightOptions, optional
        See :func:`merit`.
    shafts : ShaftOptions, optional
        See :func:`merit`.
    orders : int
        Highest order of the residuals.
    shared : (EngineBatch, BatchFreeForces), optional
        The candidates' batch (:func:`~crankbalance.physics.model.engine_batch` of their
        throw angles) and its free forces of orders 1..max(``orders``, 2)
        (:func:`~crankbalance.physics.shaking.batch_free_forces`), when :func:`merit` has
        them already; default: built here, the forces computed by the solver.

    Returns
    -------
    dict of str to ndarray, each shape (B,)
        ``cw_mass_kg`` [kg], ``shafts`` [-], ``shaft_mass_kg`` [kg], ``residual_F_N``
        [N], ``residual_M_Nm`` [N·m] (see :func:`merit`).
    """
    topo = candidates.topology
    names = BALANCE_COLUMNS
    if candidates.size == 0:
        return {name: np.zeros(0) for name in names}
    cw = counterweights or CounterweightOptions(
        cg_radius=topo.crank_radius, angle="optimal", balance_factor=balance_factor
    )
    shaft = shafts or ShaftOptions(
        cg_radius=topo.crank_radius,
        length=max(float(np.ptp(topo.throw_position)), 2 * topo.crank_radius),
    )
    level = TARGETS.index(target)
    primary = shaft if level >= 2 else None
    secondary = shaft if level >= 3 else None
    if topo.articulation is not None:
        return _articulated_balance(candidates, cw, primary, secondary, orders)
    batch, forces = shared or (
        engine_batch(topo, candidates.size, throw_angle=candidates.throw_angle),
        None,
    )
    result: BatchBalance = balance_batch(batch, cw, primary, secondary, orders, forces=forces)
    count = np.zeros(candidates.size, dtype=np.int64)
    shaft_mass = np.zeros(candidates.size)
    for group in (result.primary, result.secondary):
        if group is not None:
            count += (group.layout > 0).sum(axis=-1)
            shaft_mass += group.mass.sum(axis=(1, 2))
    res = result.residuals
    assert result.counterweights is not None  # counterweights are always asked for
    cw_mass = result.counterweights.mass.sum(axis=-1)
    if result.extra_counterweights is not None:  # a single counter-rotating primary shaft
        cw_mass = cw_mass + result.extra_counterweights.mass.sum(axis=-1)
    return dict(
        zip(
            names,
            (
                cw_mass,
                count,
                shaft_mass,
                res.force_after.max(axis=-1),
                res.moment_after.max(axis=-1),
            ),
            strict=True,
        )
    )


def _articulated_balance(
    candidates: Candidates,
    counterweights: CounterweightOptions,
    primary: ShaftOptions | None,
    secondary: ShaftOptions | None,
    orders: int,
) -> dict[str, NDArray]:
    """:func:`balance_columns` of a batch whose topology has master-and-link rods: each
    candidate balanced by the one-engine solver
    (:func:`crankbalance.physics.balancing.balance`, what ``crankbalance balance`` calls, on
    the exact articulated forces), since the batch model has no master-and-link rods;
    :func:`merit` calls it once per distinct crank (one for a radial)."""
    rows = []
    for model in _one_engines(candidates):
        result = balance(model, counterweights, primary, secondary, orders)
        assert result.counterweights is not None  # counterweights are always asked for
        cw_mass = float(result.counterweights.mass.sum())
        if result.extra_counterweights is not None:  # a single counter-rotating primary shaft
            cw_mass += float(result.extra_counterweights.mass.sum())
        shafts = [s for group in (result.primary, result.secondary) if group for s in group.shafts]
        rows.append(
            (
                cw_mass,
                sum(1 for s in shafts if s.masses),
                sum(m.mass for s in shafts for m in s.masses),
                max(c.force_after for c in result.residuals),
                max(c.moment_after for c in result.residuals),
            )
        )
    columns = np.array(rows, dtype=float).T
    out = dict(zip(BALANCE_COLUMNS, columns, strict=True))
    out["shafts"] = out["shafts"].astype(np.int64)
    return out
