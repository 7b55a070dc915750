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

**Counterweights** (Eqs. 6-11): :mod:`crankbalance.physics.balance_counterweights`, the
equal-mass pattern at a given or the least-mass angle, or each counterweight its own mass
and angle, for the whole crank or each half; the share that carries the rotating masses
is solved again at the same angle (the equations are linear in the targets).

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

Options, input and results are in :mod:`crankbalance.physics.balance_types`.
"""

from __future__ import annotations

import functools
from dataclasses import replace
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from ..errors import InputError
from ..results import ROUND_OFF, engine_scales
from .balance_counterweights import Webs, solve_counterweights, web_geometry
from .balance_types import (
    BatchBalance,
    BatchCounterweights,
    BatchResiduals,
    BatchShafts,
    CounterweightOptions,
    ShaftOptions,
    SolverInput,
)
from .model import EngineBatch, EngineModel
from .shaking import (
    BatchFreeForces,
    FreeForces,
    coefficient_rows,
    cylinder_coefficients,
    free_forces,
)

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import NDArray

_Record = TypeVar("_Record", SolverInput, BatchFreeForces)

#: share of an engine's force scale (forces) or force scale times length scale (moments)
#: below which the residual check counts a targeted component as cancelled
CHECK_TOLERANCE = 1e-9


# --------------------------------------------------------------------------- the input
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
    rotating, rotating_couple, reciprocating, reciprocating_couple = throw_unbalance(
        engine, forces.orders.size
    )
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


def model_input(model: EngineModel, orders: int) -> SolverInput:
    """The solver's input of one engine (a batch of one), its free forces of orders
    1..``orders`` included, computed once per model and kept by it
    (:attr:`~crankbalance.physics.model.EngineModel.derived`; a model is frozen), its
    arrays read-only.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    orders : int
        Highest order of the free forces, at least 2.

    Returns
    -------
    SolverInput
        The arrays of :func:`solve`, an engine axis of 1.
    """
    key = ("balance_solver.model_input", orders)
    found: SolverInput | None = model.derived.get(key)
    if found is None:
        batch = batch_of_one(free_forces(model, orders))
        found = _read_only(replace(solver_input(model, batch), forces=_read_only(batch)))
        model.derived[key] = found
    return found


def batch_of_one(forces: FreeForces) -> BatchFreeForces:
    """One engine's free forces with an engine axis of 1 (views, no copy).

    Parameters
    ----------
    forces : FreeForces
        Phasors of one engine [N], [N·m].

    Returns
    -------
    BatchFreeForces
        The same phasors, shape (1, K) and (1,).
    """
    return BatchFreeForces(
        forces.orders,
        forces.force_forward[None],
        forces.force_backward[None],
        forces.couple_forward[None],
        forces.couple_backward[None],
        np.array([forces.rotating_force]),
        np.array([forces.rotating_couple]),
        forces.roll[None],
        np.array([forces.rotating_roll]),
    )


def _read_only(record: _Record) -> _Record:
    """``record`` with read-only views of its arrays (a record a model keeps)."""
    views: dict[str, Any] = {}
    for name, value in vars(record).items():
        if isinstance(value, np.ndarray):
            views[name] = value.view()
            views[name].flags.writeable = False
    return replace(record, **views)


def throw_unbalance(
    engine: EngineModel | EngineBatch, orders: int = 2
) -> tuple[NDArray[np.complex128], ...]:
    r"""Per throw, the first moments the crank counterweights can carry, and their moments
    along the crank, each mass at its own axial place (the big ends and rods of
    side-by-side rods at the rod's place).

    The reciprocating masses enter by the forward-rotating part of their first order:
    cylinder c's forward primary phasor is
    :math:`F_{1,c}^+ = \tfrac12 m_{rec,c} r\omega^2 c_{1,c} e^{i\varphi_c}`
    (:mod:`crankbalance.physics.shaking`), the phasor of a mass
    :math:`\tfrac12 m_{rec,c} r c_{1,c}` turning with the crank, so the first moment
    :math:`m_{rec,c} r c_{1,c} e^{i\varphi_c}` put on the crank with a balance factor
    :math:`f_b` leaves :math:`(1 - 2f_b) F_{1,c}^+`: 0.5 cancels the forward primary of
    every cylinder. A centred cylinder has :math:`c_1 = 1` exactly (the pin's
    :math:`m_{rec} r e^{i\varphi}` of the 2021 paper); an offset cylinder (bore, pin or
    crank offset, a VR row) or the link rod of an articulated radial has its first
    harmonic shifted in phase and amplitude, and :math:`c_{1,c}` carries the shift.

    Parameters
    ----------
    engine : EngineModel or EngineBatch
        The engine(s), as :func:`solver_input`.
    orders : int
        Orders of the harmonic coefficients the free forces were computed with (the
        first is taken from the same rows, to the last bit).

    Returns
    -------
    rotating : ndarray of complex, shape (E, T)
        :math:`m_t r e^{i\varphi_t}` of the rotating masses [kg·m] (E = 1 for a model).
    rotating_couple : ndarray of complex, shape (E, T)
        :math:`(m_t y_t + \sum_c m_{b,c} a_c) r e^{i\varphi_t}` [kg·m²].
    reciprocating : ndarray of complex, shape (E, T)
        :math:`\sum_c m_{rec,c} c_{1,c} r e^{i\varphi_t}` over the cylinders on the pin
        [kg·m].
    reciprocating_couple : ndarray of complex, shape (E, T)
        :math:`\sum_c m_{rec,c} c_{1,c} (y_t + a_c) r e^{i\varphi_t}` [kg·m²].

    References
    ----------
    Appl. Sci. 2021, Eqs. 6-10 (the unbalance the counterweights cancel).
    """
    topology = engine.topology if isinstance(engine, EngineBatch) else engine
    y = topology.throw_position
    throws, cylinders = topology.throws, topology.cylinders
    throw_angle = np.reshape(engine.throw_angle, (-1, throws))
    rotating_mass = np.reshape(engine.throw_rotating_mass, (-1, throws))
    reciprocating_mass: NDArray = np.reshape(engine.reciprocating_mass, (-1, cylinders))
    first = _first_harmonic(engine, orders)
    if np.any(first != 1.0):  # offset cylinders: their forward primary, phase and size
        reciprocating_mass = reciprocating_mass * first
    turn = np.reshape(engine.crank_radius, (-1, 1)) * np.exp(1j * throw_angle)  # r e^{i phi}
    # each cylinder's reciprocating mass on its pin, summed engine by engine (einsum's own
    # loops, no matrix product across the engines)
    pins = (np.arange(throws)[None, :] == topology.cylinder_throw[:, None]).astype(float)
    pin_mass = np.einsum("ec,ct->et", reciprocating_mass, pins)
    pin_axial = (
        np.einsum("ec,ct->et", reciprocating_mass * topology.cylinder_axial, pins)
        if np.any(topology.cylinder_axial)
        else 0.0  # every rod in its throw's plane
    )
    return (
        rotating_mass * turn,
        (rotating_mass * y + topology.throw_axial_moment) * turn,
        pin_mass * turn,
        (pin_mass * y + pin_axial) * turn,
    )


def _first_harmonic(engine: EngineModel | EngineBatch, orders: int) -> NDArray[np.complex128]:
    """:math:`c_{1,c}` of every cylinder, shape (E, C) or (1, C) or (1, 1), from the rows
    the free forces use (:func:`crankbalance.physics.shaking.cylinder_coefficients`)."""
    if isinstance(engine, EngineBatch):
        r = engine.crank_radius
        rows = coefficient_rows(
            r / engine.rod_length,
            engine.cylinder_offset / r[:, None],
            orders,
            engine.topology.kinematics,
        )
    else:
        rows = cylinder_coefficients(engine, orders)
    first = rows[..., 0]
    return first[None, :] if first.ndim == 1 else first


# --------------------------------------------------------------------------- the solver
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
    w2 = inputs.speed_squared
    cw: BatchCounterweights | None = None
    share: NDArray[np.complex128] | None = None
    extra: BatchCounterweights | None = None
    webs: Webs | None = None
    moments: NDArray[np.complex128] | None = None  # the counterweights' first moments
    fwd1, cfwd1 = forces.force_forward[:, 0], forces.couple_forward[:, 0]
    if counterweights is not None:
        fb = counterweights.balance_factor
        target = inputs.rotating + fb * inputs.reciprocating
        target_couple = inputs.rotating_couple + fb * inputs.reciprocating_couple
        webs = web_geometry(inputs, counterweights)
        halves = _halves(inputs, counterweights.scope)
        cw = solve_counterweights(inputs, webs, counterweights, halves, target, target_couple)
        moments = share = cw.moments
        if fb != 0.0:
            # the share that carries the rotating masses alone, at the same angle (the
            # equations are linear in the targets)
            share = solve_counterweights(
                inputs,
                webs,
                counterweights,
                halves,
                inputs.rotating,
                inputs.rotating_couple,
                angle=cw.alpha,
            ).moments
            # what the counterweights do beyond the rotating masses counts to order 1
            beyond = (moments - share) * w2[:, None]
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
            extra = solve_counterweights(
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

    residuals = balance_residuals(inputs, cw, share, extra, primary_set, secondary_set, moments)
    return BatchBalance(cw, extra, primary_set, secondary_set, share, residuals)


def _halves(inputs: SolverInput, scope: str) -> NDArray[np.bool_]:
    """Whether each engine's crank halves are balanced on their own: only when asked
    (``"halves"``, paper section 3.1). ``"auto"`` balances the crank as a whole, so a
    crank already balanced as a whole gets no counterweights (issue 27: the V12 and
    flat-6 were given 7-50 kg by the old ``"auto"``, which took halves there). Kept by
    the input (read-only)."""
    key = ("halves", scope == "halves")
    found: NDArray[np.bool_] | None = inputs.memo.get(key)
    if found is None:
        found = inputs.memo[key] = np.full(inputs.size, scope == "halves")
        found.flags.writeable = False
    return found


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
def residual_phasors(
    inputs: SolverInput,
    cw: BatchCounterweights | None,
    share: NDArray | None,
    extra: BatchCounterweights | None,
    primary: BatchShafts | None,
    secondary: BatchShafts | None,
) -> tuple[NDArray, NDArray, NDArray, NDArray, NDArray, NDArray]:
    """The free forces and couples the balancing masses leave, as phasors: the engine's plus
    those of the counterweights (the share that carries the rotating masses to the rotating
    component, the rest to the first order), the extra counterweights and the shafts.

    Parameters
    ----------
    inputs : SolverInput
        The engines and their free forces.
    cw : BatchCounterweights or None
        Crank counterweights.
    share : ndarray of complex, shape (E, W), or None
        First moments of the counterweights' share that carries the rotating masses
        [kg·m].
    extra : BatchCounterweights or None
        The Eq. 17 extra counterweights.
    primary, secondary : BatchShafts or None
        Balance shafts of order 1 and 2.

    Returns
    -------
    rotating_force, rotating_couple : ndarray of complex, shape (E,)
        The rotating component left [N], [N·m].
    force_forward, force_backward : ndarray of complex, shape (E, K)
        Each order's force phasors left [N].
    couple_forward, couple_backward : ndarray of complex, shape (E, K)
        Each order's couple phasors left [N·m].
    """
    parts = _residual_start(inputs)[0].copy()
    return _add_balancing(parts, inputs, cw, share, extra, primary, secondary)


def _add_balancing(
    parts: NDArray,
    inputs: SolverInput,
    cw: BatchCounterweights | None,
    share: NDArray | None,
    extra: BatchCounterweights | None,
    primary: BatchShafts | None,
    secondary: BatchShafts | None,
    moments: NDArray | None = None,
) -> tuple[NDArray, NDArray, NDArray, NDArray, NDArray, NDArray]:
    """Add the balancing masses' phasors, in place, to the "after" parts of ``parts``
    (E, 2, 4, K + 1) (:func:`_residual_start`'s layout, the after parts a copy of the
    before ones): the share of the counterweights that carries the rotating masses to the
    rotating component, the rest (``moments``, the counterweights' first moments when the
    solver has them, less the share) and the extra counterweights to the first order, the
    shafts to their order. Returns views of the after parts: rotating force and couple
    (E,), forward and backward forces, forward and backward couples (E, K)."""
    w2 = inputs.speed_squared
    rotating_after = parts[:, :, 2, 0]  # (E, 2): the rotating masses' force and couple
    fwd, bwd = parts[:, 0, 2, 1:], parts[:, 0, 3, 1:]
    cfwd, cbwd = parts[:, 1, 2, 1:], parts[:, 1, 3, 1:]
    first_order: list[tuple[NDArray, NDArray]] = []  # the counterweights beyond the share
    if cw is not None and share is not None:
        # all of the counterweights the share (no balance factor): their sums are kept
        total, couple = (
            cw.moment_sums
            if share is cw.moments
            else (share.sum(axis=-1), (share * cw.position).sum(axis=-1))
        )
        rotating_after[:, 0] += w2 * total
        rotating_after[:, 1] += w2 * couple
        if share is not moments:  # (no balance factor: all of it is the share, nothing beyond)
            first_order.append(((cw.moments if moments is None else moments) - share, cw.position))
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
    return rotating_after[:, 0], rotating_after[:, 1], fwd, bwd, cfwd, cbwd


def balance_residuals(
    inputs: SolverInput,
    cw: BatchCounterweights | None,
    share: NDArray | None,
    extra: BatchCounterweights | None,
    primary: BatchShafts | None,
    secondary: BatchShafts | None,
    moments: NDArray | None = None,
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
    moments : ndarray of complex, shape (E, W), optional
        ``cw.moments``, when the caller has them (:func:`solve`) [kg·m]; default:
        computed from ``cw``'s masses and directions.

    Returns
    -------
    BatchResiduals
        Per engine and component: forces [N] and moments [N·m] before and after (zero at
        most the round-off), and the check.
    """
    before, level, force_limit, moment_limit = _residual_start(inputs)
    # every size at once, (E, 2, 4, K + 1): forces then moments; the forward and backward
    # parts before, then after (the rotating masses turn forward only: no backward part);
    # the after parts start as the before ones, and each mass adds its phasors to them
    parts = before.copy() if inputs.size == 1 else before  # a batch's is its own
    fwd = _add_balancing(parts, inputs, cw, share, extra, primary, secondary, moments)[2]
    orders = fwd.shape[1]
    size = np.abs(parts)
    # (the results are views of these two, which they cover whole: no memory held beyond;
    # a size is its own size, so the round-off cut compares it as below_round_off does)
    after = size[:, :, 2:]  # forward after, backward after
    each = np.where(after <= level, 0.0, after)
    total = size[:, :, 0::2] + size[:, :, 1::2]  # before, after
    both = np.where(total <= level, 0.0, total)
    force_before, force_after = both[:, 0, 0], both[:, 0, 1]
    moment_before, moment_after = both[:, 1, 0], both[:, 1, 1]
    force_forward, force_backward = each[:, 0, 0], each[:, 0, 1]
    moment_forward, moment_backward = each[:, 1, 0], each[:, 1, 1]
    components, targeted = _components(
        orders, cw is not None, primary is not None, secondary is not None
    )
    balanced = np.logical_and.reduce(  # np.all without its Python wrapper
        ~targeted | ((force_after <= force_limit) & (moment_after <= moment_limit)), -1
    )
    return BatchResiduals(
        components,
        targeted,
        force_before,
        force_after,
        moment_before,
        moment_after,
        force_forward,
        force_backward,
        moment_forward,
        moment_backward,
        balanced,
    )


@functools.lru_cache(maxsize=256)
def _components(
    orders: int, counterweights: bool, primary: bool, secondary: bool
) -> tuple[tuple[str, ...], NDArray[np.bool_]]:
    """The residuals' components (``"rotating"``, ``"order1"``, ...) and which of them the
    masses asked for target (read-only), for ``orders`` orders."""
    targeted = np.array([counterweights, primary, secondary] + [False] * (orders - 2))
    targeted.flags.writeable = False
    return ("rotating",) + tuple(f"order{k}" for k in range(1, orders + 1)), targeted


def _residual_start(inputs: SolverInput) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """What the residuals of ``inputs`` start from, whatever the masses: the parts before,
    twice (E, 2, 4, K + 1) (:func:`balance_residuals`), the round-off levels (E, 2, 1, 1)
    and the check's limits of the force and moment left (E, 1) [N], [N·m]. Kept by one
    engine's input for its next solve (read-only); a batch's, solved once, does not."""
    kept: tuple[NDArray, NDArray, NDArray, NDArray] | None = inputs.memo.get(("residuals",))
    if kept is not None:
        return kept
    forces = inputs.forces
    orders = forces.force_forward.shape[1]
    before = np.zeros((forces.force_forward.shape[0], 2, 4, orders + 1), complex)
    for q, (rotating, forward, backward) in enumerate(
        (
            (forces.rotating_force, forces.force_forward, forces.force_backward),
            (forces.rotating_couple, forces.couple_forward, forces.couple_backward),
        )
    ):
        for after in (0, 2):
            before[:, q, after, 0], before[:, q, after, 1:] = rotating, forward
            before[:, q, after + 1, 1:] = backward
    level = np.stack([inputs.force_round_off, inputs.moment_round_off], axis=-1)[..., None, None]
    tolerance = CHECK_TOLERANCE / ROUND_OFF  # the levels are ROUND_OFF of the scales
    force_limit = tolerance * inputs.force_round_off[:, None]
    moment_limit = tolerance * inputs.moment_round_off[:, None]
    found = (before, level, force_limit, moment_limit)
    if inputs.size == 1:
        for array in found:
            array.flags.writeable = False
        inputs.memo[("residuals",)] = found
    return found
