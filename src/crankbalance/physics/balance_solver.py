r"""The balancing equations: crank counterweights and balance shafts for one engine or many
engines of one layout at once, and what they leave (2021 paper, sections 2-3, generalised).

This is the one implementation of the equations: :func:`crankbalance.physics.balancing.balance`
solves one engine as a batch of one, :func:`crankbalance.physics.balance_batch.balance_batch`
many engines chunk by chunk. Both hand :func:`solve` a :class:`SolverInput` (arrays with a
leading engine axis) and read a :class:`BatchBalance`.

Every order's free force and couple is a sum of a forward and a backward phasor
(:mod:`crankbalance.physics.shaking`). A mass :math:`m` at radius :math:`\rho` turning at
:math:`k\omega` with phase :math:`\psi` adds :math:`m\rho(k\omega)^2 e^{i\psi}` to the forward
phasor of order k (to the backward one if it turns against the crank), and :math:`y` times
that to the couple. So:

* crank counterweights (order 1, forward) cancel the rotating masses and, with a balance
  factor :math:`f_b`, the share :math:`f_b` of the reciprocating masses put on the crank;
* a co-rotating primary shaft cancels the forward primary phasors left, a counter-rotating
  one the backward ones; secondary shafts do the same at :math:`\pm 2\omega`.

**Counterweights.** With :math:`v_j = m_j r_c e^{i\psi_j}` the complex first moment of
counterweight j at axial position :math:`y_j`, the equations of each part of the crank (the
whole crank, or each half on its own) are the paper's Eq. 10, force and couple, x and z:

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

**Balance shafts** (Eqs. 13-22 with the errata of docs/references.md): a force alone takes
one mass mid-shaft, a couple two masses at :math:`\pm l/2`, sized together with the force.

**Residuals.** Each counterweight and shaft mass is added back as the point-mass phasor
:math:`m\rho(k\omega)^2 e^{i\psi}` (and :math:`y` times it) to the free forces, component
by component: the rotating masses with the counterweights' share that carries them, and
each order of the reciprocating masses with the rest (the balance-factor share and the
Eq. 17 extra set count to the first order). Values at most the engine's round-off
(:func:`crankbalance.results.round_off`) are zero. The time-domain verification of these
numbers is :func:`crankbalance.physics.balance_check.verify`, a separate, optional check.

Every engine's numbers are computed by operations on its own row (element by element,
sums over its own contiguous axes; columns picked with ``np.take``, whose result keeps each
row in one piece): no matrix product runs across the engine axis, so a result does not
depend, to the last bit, on the other engines of its batch (the explorer's Pareto front
compares candidates to the last bit).

The module holds one subject, the equations, and is long because the counterweight
methods, the shafts and the residuals share the same arrays and tolerances.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..results import ROUND_OFF, ResultMixin, below_round_off, engine_scales
from .model import EngineBatch, EngineModel
from .shaking import BatchFreeForces

Method = Literal["pattern", "individual"]
Scope = Literal["auto", "whole", "halves"]
Arrangement = Literal["pair", "counter-rotating"]

#: share of an engine's force scale (forces) or force scale times length scale (moments)
#: below which the residual check counts a targeted component as cancelled
CHECK_TOLERANCE = 1e-9


# --------------------------------------------------------------------------- options
@dataclass(frozen=True)
class CounterweightOptions:
    """Crank counterweights: web pattern, CG radius, angle, balance factor, scope.

    ``webs`` holds 0/1 for each web, two per throw (None: all webs). ``angle`` is the
    turn :math:`\\alpha` [rad] from the position opposite the crankpin, or ``"optimal"``.
    ``web_offset`` is the axial distance of each web from its throw mid-plane [m]
    (the paper's a/4 when None).

    Parameters
    ----------
    cg_radius : float
        Radius of the counterweights' centre of gravity, :math:`r_c` [m].
    webs : tuple of int, optional
        0/1 per web, two per throw from the y < 0 end (the paper's :math:`Y_{cw}`); None:
        a counterweight on every web.
    angle : float or "optimal"
        Turn :math:`\\alpha` of the pattern from the position opposite the crankpin [rad],
        or ``"optimal"`` for the least-mass angle that balances.
    balance_factor : float
        Share :math:`f_b` of the reciprocating masses the counterweights carry on top of
        the rotating masses [-].
    scope : {"auto", "whole", "halves"}
        Balance the crank as a whole or each half on its own; ``"auto"`` takes halves when
        the crank is balanced as a whole and has an even number of throws.
    method : {"pattern", "individual"}
        The paper's equal-mass pattern, or each counterweight its own mass and angle
        (least :math:`\\sum m_j^2`).
    web_offset : float, optional
        Axial distance of each web from its throw mid-plane [m]; default a quarter of the
        throw pitch, half the crank radius for one throw (:func:`web_geometry`).

    References
    ----------
    Appl. Sci. 2021, section 2 (Eqs. 6-11), with the sign-rule reading of
    docs/references.md.
    """

    cg_radius: float
    webs: tuple[int, ...] | None = None
    angle: float | Literal["optimal"] = 0.0
    balance_factor: float = 0.0
    scope: Scope = "auto"
    method: Method = "pattern"
    web_offset: float | None = None


@dataclass(frozen=True)
class ShaftOptions:
    """Balance shafts of one order: ``pair`` (co- and counter-rotating) or a single
    ``counter-rotating`` shaft; CG radius of their masses and distance between the outer
    masses [m]. The shafts' mid-point is taken in the crank's mid-plane (y = 0).

    Parameters
    ----------
    cg_radius : float
        Radius of the centre of gravity of the shaft masses, :math:`r_{c1}` or
        :math:`r_{c2}` [m].
    length : float
        Axial distance between the outer masses, :math:`l_{sh}` [m].
    arrangement : {"pair", "counter-rotating"}
        A co- and a counter-rotating shaft, or a single counter-rotating shaft.

    References
    ----------
    Appl. Sci. 2021, section 3 (Eqs. 13-22), with the errata of docs/references.md.
    """

    cg_radius: float
    length: float
    arrangement: Arrangement = "pair"


# --------------------------------------------------------------------------- the input
@dataclass(frozen=True)
class SolverInput:
    """What :func:`solve` needs of E engines of one layout: arrays with a leading engine
    axis (E = 1 for one engine). Build it with :func:`solver_input`.

    Parameters
    ----------
    throw_position : ndarray, shape (T,)
        Axial position of each throw from the moment reference point [m].
    throw_angle : ndarray, shape (E, T)
        Throw angles [rad].
    rotating, rotating_couple : ndarray of complex, shape (E, T)
        First moment of each throw's rotating masses, :math:`m_t r e^{i\\varphi_t}` [kg·m],
        and its moment along the crank (big ends of side-by-side rods at their own places)
        [kg·m²].
    reciprocating, reciprocating_couple : ndarray of complex, shape (E, T)
        The same for the reciprocating masses on each throw's pin [kg·m], [kg·m²].
    forces : BatchFreeForces
        The free forces of every engine, orders 1..K (K at least 2) [N], [N·m].
    crank_radius, speed : ndarray, shape (E,)
        Crank radius [m] and crank speed [rad/s].
    length : ndarray, shape (E,)
        Length scale of each engine [m] (:func:`crankbalance.results.engine_scales`).
    force_round_off, moment_round_off : ndarray, shape (E,)
        Round-off levels of forces [N] and moments [N·m]
        (:func:`crankbalance.results.round_off`).
    """

    throw_position: NDArray[np.float64]
    throw_angle: NDArray[np.float64]
    rotating: NDArray[np.complex128]
    rotating_couple: NDArray[np.complex128]
    reciprocating: NDArray[np.complex128]
    reciprocating_couple: NDArray[np.complex128]
    forces: BatchFreeForces
    crank_radius: NDArray[np.float64]
    speed: NDArray[np.float64]
    length: NDArray[np.float64]
    force_round_off: NDArray[np.float64]
    moment_round_off: NDArray[np.float64]

    @property
    def size(self) -> int:
        """Number of engines E."""
        return int(self.speed.size)


def solver_input(engine: EngineModel | EngineBatch, forces: BatchFreeForces) -> SolverInput:
    """The solver's input for one engine (a batch of one) or a batch of one layout.

    Parameters
    ----------
    engine : EngineModel or EngineBatch
        The engine(s): throw angles [rad], rotating masses per throw [kg], reciprocating
        masses per cylinder [kg], crank radius [m] and speed [rad/s], and the layout
        (throw positions, each cylinder's throw and rod place, the big ends of
        side-by-side rods).
    forces : BatchFreeForces
        Their free forces, orders 1..K with K at least 2
        (:func:`crankbalance.physics.shaking.batch_free_forces`; for one engine
        :func:`~crankbalance.physics.shaking.free_forces` with an engine axis of 1).

    Returns
    -------
    SolverInput
        The arrays of :func:`solve`.
    """
    rotating, rotating_couple, reciprocating, reciprocating_couple = throw_unbalance(engine)
    force_scale, length = (np.reshape(x, -1) for x in engine_scales(engine))
    return SolverInput(
        throw_position=engine.throw_position,
        throw_angle=np.reshape(engine.throw_angle, rotating.shape),
        rotating=rotating,
        rotating_couple=rotating_couple,
        reciprocating=reciprocating,
        reciprocating_couple=reciprocating_couple,
        forces=forces,
        crank_radius=np.reshape(engine.crank_radius, -1),
        speed=np.reshape(engine.speed, -1),
        length=length,
        force_round_off=ROUND_OFF * force_scale,
        moment_round_off=ROUND_OFF * force_scale * length,
    )


def throw_unbalance(
    engine: EngineModel | EngineBatch,
) -> tuple[NDArray[np.complex128], ...]:
    r"""Per throw, the first moments the crank counterweights can carry, and their moments
    along the crank, each mass at its own axial place (the big ends and rods of
    side-by-side rods at the rod's place).

    Parameters
    ----------
    engine : EngineModel or EngineBatch
        The engine(s), as :func:`solver_input`.

    Returns
    -------
    rotating : ndarray of complex, shape (E, T)
        :math:`m_t r e^{i\varphi_t}` of the rotating masses [kg·m] (E = 1 for a model).
    rotating_couple : ndarray of complex, shape (E, T)
        :math:`(m_t y_t + \sum_c m_{b,c} a_c) r e^{i\varphi_t}` [kg·m²].
    reciprocating : ndarray of complex, shape (E, T)
        :math:`\sum_c m_{rec,c} r e^{i\varphi_t}` over the cylinders on the pin [kg·m].
    reciprocating_couple : ndarray of complex, shape (E, T)
        :math:`\sum_c m_{rec,c} (y_t + a_c) r e^{i\varphi_t}` [kg·m²].

    References
    ----------
    Appl. Sci. 2021, Eqs. 6-10 (the unbalance the counterweights cancel).
    """
    topology = engine.topology if isinstance(engine, EngineBatch) else engine
    y = topology.throw_position
    throws, cylinders = topology.throws, topology.cylinders
    throw_angle = np.reshape(engine.throw_angle, (-1, throws))
    rotating_mass = np.reshape(engine.throw_rotating_mass, (-1, throws))
    reciprocating_mass = np.reshape(engine.reciprocating_mass, (-1, cylinders))
    turn = np.reshape(engine.crank_radius, (-1, 1)) * np.exp(1j * throw_angle)  # r e^{i phi}
    # each cylinder's reciprocating mass on its pin (summed engine by engine)
    pins = np.arange(throws)[None, :] == topology.cylinder_throw[:, None]  # (C, T)
    on_pin = reciprocating_mass[:, :, None] * pins  # (E, C, T)
    pin_mass = on_pin.sum(axis=1)
    pin_axial = (on_pin * topology.cylinder_axial[:, None]).sum(axis=1)
    return (
        rotating_mass * turn,
        (rotating_mass * y + topology.throw_axial_moment) * turn,
        pin_mass * turn,
        (pin_mass * y + pin_axial) * turn,
    )


# --------------------------------------------------------------------------- the solver
class EngineFailed(Exception):
    """An :class:`~crankbalance.errors.InputError` of one engine of a :func:`solve` call:
    the one-engine solver raises ``error`` itself, the batch names the engine.

    Parameters
    ----------
    error : InputError
        What is wrong, as for one engine.
    engine : int
        Index of the engine in the :class:`SolverInput` [-].
    """

    def __init__(self, error: InputError, engine: int) -> None:
        super().__init__(str(error))
        self.error = error
        self.engine = engine


def solve(
    inputs: SolverInput,
    counterweights: CounterweightOptions | None = None,
    primary: ShaftOptions | None = None,
    secondary: ShaftOptions | None = None,
) -> BatchBalance:
    """Counterweights, balance shafts and residuals of every engine of ``inputs``.

    Parameters
    ----------
    inputs : SolverInput
        The engines (:func:`solver_input`).
    counterweights : CounterweightOptions, optional
        Crank counterweights, the same for every engine.
    primary, secondary : ShaftOptions, optional
        Balance shafts at crank speed and at twice crank speed.

    Returns
    -------
    BatchBalance
        Per engine: counterweight masses [kg] and directions [rad], shaft masses [kg] and
        phases [rad], residual forces [N] and moments [N·m] by component, and the check.

    Raises
    ------
    InputError
        For options no engine of the layout can have: a ``webs`` of the wrong length, a
        ``halves`` scope the crank cannot have, a single counter-rotating shaft without
        counterweights.
    EngineFailed
        For an engine the counterweights cannot balance: a part of the crank without a
        counterweight, or all its counterweights in one plane with a couple to cancel.

    References
    ----------
    Appl. Sci. 2021, Eqs. 1-23, with the errata of docs/references.md.
    """
    if primary is not None and primary.arrangement != "pair" and counterweights is None:
        raise InputError(
            "balance_shafts.primary.arrangement",
            "counter-rotating",
            "a single counter-rotating shaft needs [counterweights] on the "
            "crank to take the co-rotating half",
        )
    forces = inputs.forces
    w2 = inputs.speed**2
    cw: BatchCounterweights | None = None
    share: NDArray[np.complex128] | None = None
    extra: BatchCounterweights | None = None
    webs: Webs | None = None
    fwd1, cfwd1 = forces.force_forward[:, 0], forces.couple_forward[:, 0]
    if counterweights is not None:
        fb = counterweights.balance_factor
        target = inputs.rotating + fb * inputs.reciprocating
        target_couple = inputs.rotating_couple + fb * inputs.reciprocating_couple
        webs = web_geometry(inputs, counterweights)
        halves = _halves(inputs, counterweights.scope, target, target_couple)
        cw = _counterweights(inputs, webs, counterweights, halves, target, target_couple)
        share = cw.moments
        if fb != 0.0:
            # the share that carries the rotating masses alone, at the same angle (the
            # equations are linear in the targets)
            share = _counterweights(
                inputs,
                webs,
                counterweights,
                halves,
                inputs.rotating,
                inputs.rotating_couple,
                angle=cw.alpha,
            ).moments
            # what the counterweights do beyond the rotating masses counts to order 1
            beyond = (cw.moments - share) * w2[:, None]
            fwd1 = fwd1 + beyond.sum(axis=-1)
            cfwd1 = cfwd1 + (beyond * cw.position).sum(axis=-1)

    primary_set: BatchShafts | None = None
    if primary is not None:
        shafts = []
        if primary.arrangement == "pair":
            shafts.append(_shaft(inputs, 1, +1, fwd1, cfwd1, primary))
        elif counterweights is not None and webs is not None:
            # Eq. 17 done right: the co-rotating shaft's first moment and couple go onto
            # the crank counterweights as an extra set of masses
            opts = replace(counterweights, scope="whole", method="individual")
            extra = _counterweights(
                inputs,
                webs,
                opts,
                np.zeros(inputs.size, bool),
                (fwd1 / w2)[:, None],
                (cfwd1 / w2)[:, None],
            )
        shafts.append(
            _shaft(
                inputs,
                1,
                -1,
                forces.force_backward[:, 0],
                forces.couple_backward[:, 0],
                primary,
            )
        )
        primary_set = _shaft_set(1, primary, shafts)

    secondary_set: BatchShafts | None = None
    if secondary is not None:
        shafts = []
        if secondary.arrangement == "pair":
            shafts.append(
                _shaft(
                    inputs,
                    2,
                    +1,
                    forces.force_forward[:, 1],
                    forces.couple_forward[:, 1],
                    secondary,
                )
            )
        shafts.append(
            _shaft(
                inputs,
                2,
                -1,
                forces.force_backward[:, 1],
                forces.couple_backward[:, 1],
                secondary,
            )
        )
        secondary_set = _shaft_set(2, secondary, shafts)

    residuals = balance_residuals(inputs, cw, share, extra, primary_set, secondary_set)
    return BatchBalance(cw, extra, primary_set, secondary_set, share, residuals)


def _halves(
    inputs: SolverInput, scope: str, target: NDArray, target_couple: NDArray
) -> NDArray[np.bool_]:
    """Whether each engine's crank halves are balanced on their own: as asked, or with
    ``"auto"`` when the crank is balanced as a whole and has an even number of throws
    (paper section 3.1)."""
    if scope != "auto":
        return np.full(inputs.size, scope == "halves")
    throws = inputs.throw_position.size
    if throws < 2 or throws % 2:
        return np.zeros(inputs.size, bool)
    w2 = inputs.speed**2
    return (np.abs(target.sum(axis=-1)) <= inputs.force_round_off / w2) & (
        np.abs(target_couple.sum(axis=-1)) <= inputs.moment_round_off / w2
    )


# --------------------------------------------------------------------------- webs
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


@dataclass(frozen=True)
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
def _counterweights(
    inputs: SolverInput,
    webs: Webs,
    options: CounterweightOptions,
    halves: NDArray[np.bool_],
    target: NDArray,
    target_couple: NDArray,
    angle: NDArray | None = None,
) -> BatchCounterweights:
    """Counterweights whose forward first-order phasors cancel the targets of every engine.

    ``target`` and ``target_couple`` (E, T) are the first moments [kg·m] and their moments
    along the crank [kg·m²] to cancel, per throw (or (E, 1): the whole crank's, with
    ``halves`` all False); ``angle`` (E,) replaces the options' angle of the pattern.
    """
    n, count = inputs.size, webs.throw.size
    mass = np.zeros((n, count))
    direction = np.zeros((n, count))
    alpha = np.zeros(n)
    flipped = np.zeros(n, bool)
    already = np.zeros(n, bool)
    y_throw = inputs.throw_position
    first = inputs.force_round_off / inputs.speed**2  # first moments at round-off [kg·m]
    for group in webs.groups:
        length = float(inputs.length[group[0]])
        normal = webs.position[group[0]] / length
        for scope in ("whole", "halves"):
            sub = group[halves[group] == (scope == "halves")]
            if not sub.size:
                continue
            parts = _parts(y_throw, length, scope, webs.throw)
            rows: list[NDArray] = []
            rhs: list[NDArray] = []
            sums = []
            for throw_mask, web_mask in parts:
                # np.take keeps each engine's row in one piece (a[:, mask] would not), so
                # its sum runs alike in a batch of one and of thousands
                # (a whole crank's target (E, 1) is its own sum)
                throws = np.flatnonzero(throw_mask) if target.shape[-1] > 1 else [0]
                force = np.take(target[sub], throws, axis=-1).sum(axis=-1)
                couple = np.take(target_couple[sub], throws, axis=-1).sum(axis=-1)
                sums.append((web_mask, force, couple))
                rows += [np.where(web_mask, 1.0, 0.0), np.where(web_mask, normal, 0.0)]
                rhs += [-force, -couple / inputs.length[sub]]
            a = np.array(rows)  # (Q, W), the same for the engines of the group
            b = np.stack(rhs, axis=-1)  # (E, Q)
            still = np.abs(b).max(axis=-1, initial=0.0) <= first[sub]
            already[sub] = still
            live = ~still
            if not live.any():
                continue
            _check_planes(inputs, webs, options, sub, live, sums)
            engines, b = sub[live], b[live]
            if options.method == "individual":
                # least sum |v|^2 among the exact solutions
                pinv = np.linalg.pinv(a, rcond=ROUND_OFF)  # (W, Q)
                v = (b[:, None, :] * pinv[None, :, :]).sum(axis=-1)  # each engine's row
                mass[engines] = np.abs(v) / options.cg_radius
                direction[engines] = np.where(mass[engines] > 0, np.angle(v), 0.0)
                continue
            opposite = np.take(inputs.throw_angle[engines], webs.throw, axis=-1) + np.pi
            middle = crank_middle(y_throw) / length
            side = np.sign(np.round(normal - middle, 12))
            if angle is None and options.angle == "optimal":
                turn, m_c = _optimal_patterns(a, b, opposite, side)
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
    return BatchCounterweights(
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
    )


def _check_planes(
    inputs: SolverInput,
    webs: Webs,
    options: CounterweightOptions,
    sub: NDArray,
    live: NDArray,
    sums: list[tuple[NDArray, NDArray, NDArray]],
) -> None:
    """A part without counterweight, or all its counterweights in one plane while a
    couple is to be cancelled: :class:`EngineFailed` naming the first such engine."""
    couple_first = inputs.moment_round_off[sub] / inputs.speed[sub] ** 2  # [kg·m²]
    length = inputs.length[sub[0]]
    for web_mask, force, couple in sums:
        planes = np.unique(np.round(webs.position[sub[0]][web_mask] / length, 12))
        if planes.size == 0:
            raise EngineFailed(
                InputError(
                    "counterweights.webs",
                    list(options.webs or []),
                    "a part of the crank that needs balancing has no counterweight",
                ),
                int(sub[live][0]),
            )
        if planes.size == 1:
            plane = webs.position[sub, np.flatnonzero(web_mask)[0]]
            bad = live & (np.abs(couple - plane * force) > couple_first)
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
    ``unit`` (E, W) over the webs, ``a`` (Q, W) the equations; (E, Q)."""
    return (unit[:, None, :] * a[None, :, :]).sum(axis=-1)


def _pattern_moments(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray, alpha: NDArray
) -> NDArray:
    """First moment :math:`m_c r_c` of the pattern at one angle per engine (least squares
    with one real unknown): a (Q, W), b (E, Q), opposite (E, W), side (W,), alpha (E,)."""
    coeff = _coefficients(np.exp(1j * (opposite + side * alpha[:, None])), a)
    num = np.real(np.sum(np.conj(coeff) * b, axis=-1))
    den = np.sum(np.abs(coeff) ** 2, axis=-1)
    safe = den > _floor(a)
    return np.where(safe, num / np.where(safe, den, 1.0), 0.0)


def _floor(a: NDArray) -> float:
    """Round-off of the squared coefficients of the pattern's equations ``a`` (Q, W): a
    pattern whose coefficients are all below it acts on nothing (no mass)."""
    return float(ROUND_OFF**2 * np.sum(np.abs(a).sum(axis=-1) ** 2))


def _optimal_patterns(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray
) -> tuple[NDArray, NDArray]:
    """Turn angle and first moment of the least-mass pattern that balances, per engine.

    Without counterweights in the mid-plane the pattern is linear in
    :math:`X = m_c r_c\\cos\\alpha`, :math:`Y = m_c r_c\\sin\\alpha`: least squares, least
    :math:`m_c` among the exact solutions. Otherwise, engine by engine, an angle scan and a
    bounded refinement (:func:`optimal_pattern_scan`).
    """
    if np.any(side == 0):
        found = [optimal_pattern_scan(a, b[i], opposite[i], side) for i in range(len(b))]
        return np.array([f[0] for f in found]), np.array([f[1] for f in found])
    # direction e^{i(opposite + side*alpha)} = base (cos alpha + i side sin alpha)
    base = np.exp(1j * opposite)
    cx, cy = _coefficients(base, a), _coefficients(1j * side * base, a)
    matrix = np.stack(
        [np.concatenate([cx.real, cx.imag], axis=-1), np.concatenate([cy.real, cy.imag], axis=-1)],
        axis=-1,
    )
    x, yv = _lstsq2(matrix, np.concatenate([b.real, b.imag], axis=-1))
    return np.arctan2(yv, x), np.hypot(x, yv)


def _lstsq2(matrix: NDArray, rhs: NDArray) -> tuple[NDArray, NDArray]:
    """Least squares with two unknowns for many systems: matrix (E, R, 2), rhs (E, R).

    A QR factorisation by Gram-Schmidt; a system whose columns are nearly parallel
    (condition above about 1e6) goes to :func:`numpy.linalg.lstsq`, for its least-norm
    solution, singular values below :data:`~crankbalance.results.ROUND_OFF` of the largest
    counting as zero.
    """
    c1, c2 = matrix[..., 0], matrix[..., 1]
    r11 = np.linalg.norm(c1, axis=-1)
    ok = r11 > 0
    q1 = c1 / np.where(ok, r11, 1.0)[:, None]
    r12 = np.sum(q1 * c2, axis=-1)
    u = c2 - r12[:, None] * q1
    r22 = np.linalg.norm(u, axis=-1)
    ok &= r11 * r22 > 1e-6 * (r11**2 + r12**2 + r22**2)
    x2 = np.sum(u * rhs, axis=-1) / np.where(ok, r22**2, 1.0)
    x1 = (np.sum(q1 * rhs, axis=-1) - r12 * x2) / np.where(ok, r11, 1.0)
    for i in np.flatnonzero(~ok):
        (x1[i], x2[i]), *_ = np.linalg.lstsq(matrix[i], rhs[i], rcond=ROUND_OFF)
    return x1, x2


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


# --------------------------------------------------------------------------- shafts
def _shaft(
    inputs: SolverInput,
    order: int,
    sense: int,
    force: NDArray,
    couple: NDArray,
    options: ShaftOptions,
) -> tuple[int, NDArray, NDArray]:
    """One balance shaft of every engine: sense, layout (E,) and the complex unknowns
    :math:`m e^{i\\psi}` (E, 3) [kg] in the slots at -l/2, 0, +l/2.

    Force only: one mass mid-shaft; couple only: two masses in opposite phase at
    :math:`\\pm l/2` (paper Eq. 13); both: two masses at :math:`\\pm l/2` sized together.
    """
    gain = options.cg_radius * (order * inputs.speed) ** 2  # force per kg at phase 0
    has_force = np.abs(force) > inputs.force_round_off
    has_couple = np.abs(couple) > inputs.moment_round_off
    half = options.length / 2
    # v1 + v2 = -F/g ; -h v1 + h v2 = -C/g
    v2 = np.where(
        has_force,
        (-force / gain - couple / (gain * half)) / 2,
        -couple / (gain * options.length),
    )
    v1 = np.where(has_force, -force / gain - v2, -v2)
    v = np.zeros((force.size, 3), complex)
    v[:, 0] = np.where(has_couple, v1, 0.0)
    v[:, 1] = np.where(has_force & ~has_couple, -force / gain, 0.0)
    v[:, 2] = np.where(has_couple, v2, 0.0)
    layout = np.where(has_couple, 2, np.where(has_force, 1, 0))
    return sense, layout, v


def _shaft_set(
    order: int, options: ShaftOptions, shafts: list[tuple[int, NDArray, NDArray]]
) -> BatchShafts:
    v = np.stack([s[2] for s in shafts], axis=1)  # (E, S, 3)
    mass = np.abs(v)
    half = options.length / 2
    return BatchShafts(
        order,
        options.arrangement,
        options.length,
        options.cg_radius,
        np.array([s[0] for s in shafts]),
        np.array([-half, 0.0, half]),
        np.stack([s[1] for s in shafts], axis=1),
        mass,
        np.where(mass > 0, np.mod(np.angle(v), 2 * np.pi), 0.0),
    )


# --------------------------------------------------------------------------- residuals
def balance_residuals(
    inputs: SolverInput,
    cw: BatchCounterweights | None,
    share: NDArray | None,
    extra: BatchCounterweights | None,
    primary: BatchShafts | None,
    secondary: BatchShafts | None,
) -> BatchResiduals:
    """Forces and moments before and after the balancing masses, from the masses as
    reported (change one and the residual shows what it leaves).

    Parameters
    ----------
    inputs : SolverInput
        The engines and their free forces.
    cw : BatchCounterweights or None
        Crank counterweights.
    share : ndarray of complex, shape (E, W), or None
        First moments of the counterweights' share that carries the rotating masses
        [kg·m]; the rest counts to the first order.
    extra : BatchCounterweights or None
        The Eq. 17 extra counterweights.
    primary, secondary : BatchShafts or None
        Balance shafts of order 1 and 2.

    Returns
    -------
    BatchResiduals
        Per engine and component: forces [N] and moments [N·m] before and after (zero at
        most the round-off), and the check.
    """
    forces = inputs.forces
    w2 = inputs.speed**2
    rot_f, rot_c = forces.rotating_force, forces.rotating_couple
    after_rot_f, after_rot_c = rot_f, rot_c
    fwd, bwd = forces.force_forward.copy(), forces.force_backward.copy()
    cfwd, cbwd = forces.couple_forward.copy(), forces.couple_backward.copy()
    first_order: list[tuple[NDArray, NDArray]] = []
    if cw is not None and share is not None:
        after_rot_f = rot_f + w2 * share.sum(axis=-1)
        after_rot_c = rot_c + w2 * (share * cw.position).sum(axis=-1)
        first_order.append((cw.moments - share, cw.position))
    if extra is not None:
        first_order.append((extra.moments, extra.position))
    for moments, position in first_order:
        fwd[:, 0] += w2 * moments.sum(axis=-1)
        cfwd[:, 0] += w2 * (moments * position).sum(axis=-1)
    for group in (primary, secondary):
        if group is None:
            continue
        k = group.order - 1
        gain = group.cg_radius * (group.order * inputs.speed) ** 2
        for s, sense in enumerate(group.sense):
            f = group.mass[:, s] * gain[:, None] * np.exp(1j * group.phase[:, s])
            force, couple = (fwd, cfwd) if sense > 0 else (bwd, cbwd)
            force[:, k] += f.sum(axis=-1)
            couple[:, k] += (f * group.position).sum(axis=-1)
    force_level = inputs.force_round_off[:, None]
    moment_level = inputs.moment_round_off[:, None]

    def amplitude(first: NDArray, forward: NDArray, backward: NDArray, level: NDArray) -> NDArray:
        """Columns rotating and orders 1..K, zero at most the round-off."""
        value = np.column_stack([np.abs(first), np.abs(forward) + np.abs(backward)])
        return below_round_off(value, level)

    force_before = amplitude(rot_f, forces.force_forward, forces.force_backward, force_level)
    moment_before = amplitude(rot_c, forces.couple_forward, forces.couple_backward, moment_level)
    force_after = amplitude(after_rot_f, fwd, bwd, force_level)
    moment_after = amplitude(after_rot_c, cfwd, cbwd, moment_level)
    orders = fwd.shape[1]
    targeted = np.array(
        [cw is not None, primary is not None, secondary is not None] + [False] * (orders - 2)
    )
    tolerance = CHECK_TOLERANCE / ROUND_OFF  # the levels are ROUND_OFF of the scales
    balanced = np.all(
        ~targeted
        | ((force_after <= tolerance * force_level) & (moment_after <= tolerance * moment_level)),
        axis=-1,
    )
    components = ("rotating",) + tuple(f"order{k}" for k in range(1, orders + 1))
    return BatchResiduals(
        components, targeted, force_before, force_after, moment_before, moment_after, balanced
    )


# --------------------------------------------------------------------------- results
@dataclass(frozen=True)
class BatchCounterweights(ResultMixin):
    """Crank counterweights of E engines (W per engine; one engine's are
    :class:`crankbalance.physics.balancing.Counterweights`).

    Parameters
    ----------
    method : {"pattern", "individual"}
        How the counterweights were sized.
    cg_radius : float
        Radius of the counterweights' centre of gravity [m].
    web : ndarray of int, shape (W,)
        Web number of each counterweight (1-based, two per throw).
    throw : ndarray of int, shape (W,)
        Throw number of each counterweight (1-based).
    position : ndarray, shape (E, W)
        Axial position from the crankshaft mid-point [m].
    mass : ndarray, shape (E, W)
        Mass at ``cg_radius`` [kg].
    direction : ndarray, shape (E, W)
        Direction at crank angle 0, from +z toward +x [rad].
    alpha : ndarray, shape (E,)
        Turn angle of the pattern [rad]; 0 for ``individual`` and where the crank needed
        no counterweight (the one-engine solver's None).
    halves : ndarray of bool, shape (E,)
        Whether each half of the crank was balanced on its own (else the whole crank).
    flipped : ndarray of bool, shape (E,)
        Whether the pattern pointed toward the crankpins and was flipped.
    already_balanced : ndarray of bool, shape (E,)
        Whether there was nothing to cancel (all masses zero).
    """

    method: str
    cg_radius: float
    web: NDArray[np.int64]
    throw: NDArray[np.int64]
    position: NDArray[np.float64]
    mass: NDArray[np.float64]
    direction: NDArray[np.float64]
    alpha: NDArray[np.float64]
    halves: NDArray[np.bool_]
    flipped: NDArray[np.bool_]
    already_balanced: NDArray[np.bool_]

    PER_ENGINE: ClassVar[tuple[str, ...]] = (
        "position",
        "mass",
        "direction",
        "alpha",
        "halves",
        "flipped",
        "already_balanced",
    )

    @property
    def moments(self) -> NDArray[np.complex128]:
        """Complex first moments :math:`m\\rho e^{i\\psi}`, shape (E, W) [kg·m]."""
        return self.mass * self.cg_radius * np.exp(1j * self.direction)


@dataclass(frozen=True)
class BatchShafts(ResultMixin):
    """The balance shafts of one order of E engines (one engine's are
    :class:`crankbalance.physics.balancing.ShaftSet`).

    Each shaft has three mass slots at the axial positions :math:`-l/2, 0, +l/2`; its
    ``layout`` says which hold a mass: 0 nothing to cancel (no mass), 1 a force only (one
    mass mid-shaft), 2 a couple (the two outer masses, sized together with the force).

    Parameters
    ----------
    order : int
        1 (primary) or 2 (secondary).
    arrangement : {"pair", "counter-rotating"}
        As :class:`ShaftOptions`.
    length : float
        Axial distance between the outer masses [m].
    cg_radius : float
        Radius of the centre of gravity of the shaft masses [m].
    sense : ndarray of int, shape (S,)
        +1 co-rotating, -1 counter-rotating, one per shaft (``pair``: +1, -1).
    position : ndarray, shape (3,)
        Axial positions of the three slots [m].
    layout : ndarray of int, shape (E, S)
        0, 1 or 2 (see above) per engine and shaft.
    mass : ndarray, shape (E, S, 3)
        Mass in each slot [kg], 0 where none.
    phase : ndarray, shape (E, S, 3)
        Direction of each mass at crank angle 0, from +z toward +x [rad].
    """

    order: int
    arrangement: str
    length: float
    cg_radius: float
    sense: NDArray[np.int64]
    position: NDArray[np.float64]
    layout: NDArray[np.int64]
    mass: NDArray[np.float64]
    phase: NDArray[np.float64]

    PER_ENGINE: ClassVar[tuple[str, ...]] = ("layout", "mass", "phase")

    @property
    def largest(self) -> NDArray[np.float64]:
        """Largest single mass of each shaft, shape (E, S) [kg] (:attr:`Shaft.mass`)."""
        return self.mass.max(axis=-1)


@dataclass(frozen=True)
class BatchResiduals(ResultMixin):
    """What the balancing masses of E engines leave, component by component
    (:func:`balance_residuals`).

    Parameters
    ----------
    components : tuple of str
        ``"rotating"``, then ``"order1"`` .. ``"order<K>"`` (the columns).
    targeted : ndarray of bool, shape (K + 1,)
        Whether a counterweight or shaft was asked to cancel each component.
    force_before, force_after : ndarray, shape (E, K + 1)
        Largest force of each component over a revolution, without and with the balancing
        masses [N] (zero at most the engine's round-off,
        :func:`crankbalance.results.round_off`).
    moment_before, moment_after : ndarray, shape (E, K + 1)
        The same for the moment about the crankshaft mid-point [N·m].
    balanced : ndarray of bool, shape (E,)
        The residual check: every targeted component is cancelled, its force and moment
        after balancing below :data:`CHECK_TOLERANCE` of the engine's force scale (times
        the crank length for moments).
    """

    components: tuple[str, ...]
    targeted: NDArray[np.bool_]
    force_before: NDArray[np.float64]
    force_after: NDArray[np.float64]
    moment_before: NDArray[np.float64]
    moment_after: NDArray[np.float64]
    balanced: NDArray[np.bool_]

    PER_ENGINE: ClassVar[tuple[str, ...]] = (
        "force_before",
        "force_after",
        "moment_before",
        "moment_after",
        "balanced",
    )

    def column(self, component: str) -> int:
        """Index of ``component`` in the columns."""
        return self.components.index(component)


@dataclass(frozen=True)
class BatchBalance(ResultMixin):
    """Counterweights, balance shafts and residuals of E engines (:func:`solve`).

    Parameters
    ----------
    counterweights : BatchCounterweights or None
        Crank counterweights, None when none were asked for.
    extra_counterweights : BatchCounterweights or None
        The Eq. 17 extra crank masses of a single counter-rotating primary shaft, else None.
    primary, secondary : BatchShafts or None
        Balance shafts of order 1 and 2, None when none were asked for.
    rotating_share : ndarray of complex, shape (E, W), or None
        First moments of the counterweights' share that carries the rotating masses
        [kg·m] (the rest, the balance-factor share, counts to the first order).
    residuals : BatchResiduals
        Forces and moments before and after, per component, and the residual check.
    """

    counterweights: BatchCounterweights | None
    extra_counterweights: BatchCounterweights | None
    primary: BatchShafts | None
    secondary: BatchShafts | None
    rotating_share: NDArray[np.complex128] | None
    residuals: BatchResiduals

    PER_ENGINE: ClassVar[tuple[str, ...]] = ("rotating_share",)

    @property
    def size(self) -> int:
        """Number of engines E."""
        return int(self.residuals.balanced.size)
