r"""Crankshaft counterweights and balance shafts for one engine (2021 paper, sections 2-3,
generalised): the one-engine face of the solver.

:func:`balance` takes an :class:`~crankbalance.physics.model.EngineModel` and returns a
:class:`BalanceResult` (counterweights, shafts, the residual of every component, the
solver's notes). It is the solver of many engines on a batch of one: the equations, their
sources and tolerances are in :mod:`crankbalance.physics.balance_solver` and
:mod:`crankbalance.physics.balance_counterweights` (the one implementation; options and
results in :mod:`crankbalance.physics.balance_types`), many engines at once go to
:func:`crankbalance.physics.balance_batch.balance_batch`, and the time-domain check of a
result is :func:`crankbalance.physics.balance_check.verify` (optional: the residuals come
from the phasor solution).

Counterweights follow the paper's pattern (all of equal mass :math:`m_c` at radius
:math:`r_c`, each opposite its crankpin turned by :math:`\pm\alpha`, the sign following
the side of the mid-plane, Eqs. 6-11 with the docs/references.md reading of the sign rule)
or, ``method="individual"``, each its own mass and angle (least :math:`\sum m_j^2`); the
residual of each component is reported, never hidden. Also here: where the webs are
(:func:`web_layout`), the time histories of balancing masses (:func:`point_mass_history`)
and the counterweight mass of the pattern versus its angle
(:func:`counterweight_angle_sweep`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import field
from typing import TYPE_CHECKING

import numpy as np

from ..records import record
from ..results import ROUND_OFF, ResultMixin, engine_scales, number
from .balance_counterweights import crank_middle, pattern_masses, throw_pitch, web_sides
from .balance_remaining import FACTOR_OPTION, Remaining, next_step, step_words
from .balance_solver import CHECK_TOLERANCE, model_input, solve, throw_unbalance
from .balance_types import (
    BatchBalance,
    BatchCounterweights,
    BatchShafts,
    CounterweightOptions,
    EngineFailed,
    ShaftOptions,
)
from .model import EngineModel

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import ArrayLike, NDArray

__all__ = [
    "AngleSweep",
    "BalanceResult",
    "ComponentResidual",
    "CounterweightOptions",
    "Counterweights",
    "Remaining",
    "Shaft",
    "ShaftMass",
    "ShaftOptions",
    "ShaftSet",
    "balance",
    "counterweight_angle_sweep",
    "default_web_offset",
    "point_mass_history",
    "web_layout",
    "what_is_left",
]


# --------------------------------------------------------------------------- results
@record
class Counterweights(ResultMixin):
    """Crank counterweights found by the solver.

    Per counterweight: web number (1-based, two per throw), throw number, axial position
    [m], mass [kg] at ``cg_radius`` and direction at crank angle 0 [rad, from +z toward +x].
    ``alpha`` is the pattern's turn angle (None for ``individual``).

    Parameters
    ----------
    method : {"pattern", "individual"}
        How the counterweights were sized.
    scope : {"whole", "halves"}
        Whether the crank was balanced as a whole or each half on its own.
    cg_radius : float
        Radius of the counterweights' centre of gravity [m].
    alpha : float or None
        Turn angle of the pattern [rad]; None for ``individual``.
    web : ndarray of int, shape (W,)
        Web number of each counterweight (1-based, two per throw).
    throw : ndarray of int, shape (W,)
        Throw number of each counterweight (1-based).
    position : ndarray, shape (W,)
        Axial position from the crankshaft mid-point [m].
    mass : ndarray, shape (W,)
        Mass at ``cg_radius`` [kg].
    direction : ndarray, shape (W,)
        Direction at crank angle 0, from +z toward +x [rad].
    note : str
        Remark of the solver (already balanced, pattern flipped), empty if none.
    """

    method: str
    scope: str
    cg_radius: float
    alpha: float | None
    web: NDArray[np.int64]
    throw: NDArray[np.int64]
    position: NDArray[np.float64]
    mass: NDArray[np.float64]
    direction: NDArray[np.float64]
    note: str = ""

    @property
    def count(self) -> int:
        return int(self.web.size)

    @property
    def moments(self) -> NDArray[np.complex128]:
        """Complex first moments :math:`m\\rho e^{i\\psi}` of the counterweights [kg·m]."""
        return self.mass * self.cg_radius * np.exp(1j * self.direction)


@record
class ShaftMass(ResultMixin):
    """One point mass of a balance shaft.

    Parameters
    ----------
    position : float
        Axial position from the crankshaft mid-point [m].
    mass : float
        Mass at the shaft's ``cg_radius`` [kg].
    phase : float
        Direction at crank angle 0, from +z toward +x [rad].
    """

    position: float
    mass: float
    phase: float


@record
class Shaft(ResultMixin):
    """One balance shaft: order (1 or 2), sense (+1 co-rotating, -1 counter-rotating),
    the CG radius of its masses and the masses (axial position [m], mass [kg], phase at
    crank angle 0 [rad, from +z toward +x]).

    Parameters
    ----------
    order : int
        Speed of the shaft in multiples of the crank speed (1 or 2).
    sense : int
        +1 co-rotating, -1 counter-rotating.
    cg_radius : float
        Radius of the centre of gravity of its masses [m].
    masses : tuple of ShaftMass
        Its masses; empty when there is nothing to cancel.
    note : str
        Remark of the solver, empty if none.
    """

    order: int
    sense: int
    cg_radius: float
    masses: tuple[ShaftMass, ...]
    note: str = ""

    @property
    def mass(self) -> float:
        """Largest single mass on the shaft [kg]."""
        return max((m.mass for m in self.masses), default=0.0)


@record
class ShaftSet(ResultMixin):
    """The balance shafts of one order.

    Parameters
    ----------
    order : int
        1 (primary) or 2 (secondary).
    arrangement : {"pair", "counter-rotating"}
        As :class:`ShaftOptions`.
    length : float
        Axial distance between the outer masses [m].
    shafts : tuple of Shaft
        The co-rotating shaft (``pair`` only) and the counter-rotating one.
    """

    order: int
    arrangement: str
    length: float
    shafts: tuple[Shaft, ...]


@record
class ComponentResidual(ResultMixin):
    """Amplitude of one component before and after balancing.

    Parameters
    ----------
    component : str
        ``"rotating"`` (rotating masses and the counterweight share that carries them) or
        ``"order1"``, ``"order2"``, ... (reciprocating masses).
    targeted : bool
        Whether a counterweight or shaft was asked to cancel this component.
    force_before, force_after : float
        Largest force of the component over a revolution, without and with the balancing
        masses [N].
    moment_before, moment_after : float
        The same for the moment about the crankshaft mid-point [N·m].
    force_forward_after, force_backward_after : float
        The forward-rotating (co-rotating) and backward-rotating parts of
        ``force_after``, :math:`|F_n^+|` and :math:`|F_n^-|` [N].
    moment_forward_after, moment_backward_after : float
        The same of ``moment_after``, :math:`|C_n^{+}|` and :math:`|C_n^{-}|` [N·m].
    """

    component: str
    targeted: bool
    force_before: float
    force_after: float
    moment_before: float
    moment_after: float
    force_forward_after: float
    force_backward_after: float
    moment_forward_after: float
    moment_backward_after: float


@record
class BalanceResult(ResultMixin):
    """Everything the solver found, with the residual of each component (from the phasor
    solution; :func:`crankbalance.physics.balance_check.verify` checks it in the time
    domain).

    Parameters
    ----------
    counterweights : Counterweights or None
        Crank counterweights, None when none were asked for.
    extra_counterweights : Counterweights or None
        The extra crank masses that replace the co-rotating primary shaft of a single
        counter-rotating primary shaft (Eq. 17 of Appl. Sci. 2021, corrected), else None.
    primary, secondary : ShaftSet or None
        Balance shafts of order 1 and 2, None when none were asked for.
    residuals : tuple of ComponentResidual
        ``"rotating"`` first, then ``"order1"``, ``"order2"``, ...
    notes : tuple of str
        Remarks of the solver.
    rotating_share : ndarray of complex, shape (W,), or None
        First moments of the counterweights' share that carries the rotating masses
        [kg·m] (the rest, the balance-factor share, counts to the first order); None
        without counterweights.
    remaining : tuple of Remaining
        Every free force and couple left, forward and backward apart, in words with the
        next step that would remove it (:func:`what_is_left`).
    """

    counterweights: Counterweights | None
    extra_counterweights: Counterweights | None
    primary: ShaftSet | None
    secondary: ShaftSet | None
    residuals: tuple[ComponentResidual, ...]
    notes: tuple[str, ...] = field(default=())
    rotating_share: NDArray[np.complex128] | None = None
    remaining: tuple[Remaining, ...] = field(default=())

    def residual(self, component: str) -> ComponentResidual:
        for item in self.residuals:
            if item.component == component:
                return item
        raise KeyError(component)


# --------------------------------------------------------------------------- the webs
def web_layout(
    model: EngineModel, web_offset: float | None = None, webs: tuple[int, ...] | None = None
) -> tuple[NDArray, NDArray]:
    """Throw index and axial position of every web that carries a counterweight.

    Webs are numbered two per throw from the y < 0 end; each sits ``web_offset`` from its
    throw mid-plane (the paper's a/4, Eq. 7).

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    web_offset : float, optional
        Axial distance of each web from its throw mid-plane [m]; default
        :func:`default_web_offset`.
    webs : tuple of int, optional
        0/1 per web, two per throw; None: every web.

    Returns
    -------
    throw : ndarray of int
        Index (0-based) of the throw of each web that carries a counterweight.
    position : ndarray
        Axial position of each such web from the crankshaft mid-point [m].

    Raises
    ------
    InputError
        If ``webs`` does not have two entries per throw.

    References
    ----------
    Appl. Sci. 2021, Eq. 7.
    """
    if web_offset is None:
        web_offset = default_web_offset(model)
    throw, side = web_sides(model.throws, webs)
    return throw, model.throw_position[throw] + side * web_offset


def default_web_offset(model: EngineModel) -> float:
    """A quarter of the throw pitch (paper Eq. 7); for one throw, half the crank radius.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).

    Returns
    -------
    float
        Axial distance of a web from its throw mid-plane [m]: a quarter of the smallest
        non-zero distance between throws, or half the crank radius without one.

    References
    ----------
    Appl. Sci. 2021, Eq. 7 (a/4).
    """
    pitch = throw_pitch(model.throw_position)
    return pitch / 4.0 if pitch is not None else model.crank_radius / 2.0


# --------------------------------------------------------------------------- the study
def balance(
    model: EngineModel,
    counterweights: CounterweightOptions | None = None,
    primary: ShaftOptions | None = None,
    secondary: ShaftOptions | None = None,
    orders: int = 8,
) -> BalanceResult:
    """Counterweights and balance shafts for an engine: the solver on a batch of one.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    counterweights : CounterweightOptions, optional
        Crank counterweights (rotating masses plus the balance-factor share).
    primary, secondary : ShaftOptions, optional
        Balance shafts at crank speed and at twice crank speed.
    orders : int
        Orders reported in the residuals (orders 1 and 2 always are).

    Returns
    -------
    BalanceResult
        Counterweights, shafts and the residual of each component, from the phasor
        solution (:func:`crankbalance.physics.balance_check.verify` checks them in the
        time domain).

    Raises
    ------
    InputError
        For options this engine cannot have, or counterweights that cannot balance it (a
        part of the crank without one, all in one plane with a couple to cancel).

    References
    ----------
    Appl. Sci. 2021, Eqs. 1-23, with the errata of docs/references.md.
    """
    inputs = model_input(model, max(orders, 2))
    try:
        found = solve(inputs, counterweights, primary, secondary)
    except EngineFailed as failed:
        raise failed.error from None
    return _one_engine(
        found,
        counterweights,
        primary,
        secondary,
        float(inputs.length[0]),
        (float(inputs.force_round_off[0]), float(inputs.moment_round_off[0])),
    )


def _one_engine(
    found: BatchBalance,
    counterweights: CounterweightOptions | None,
    primary: ShaftOptions | None,
    secondary: ShaftOptions | None,
    length: float,
    levels: tuple[float, float],
) -> BalanceResult:
    """The :class:`BalanceResult` of a batch of one, with the solver's notes and what is
    left (``levels``: the engine's force and moment round-off [N], [N·m])."""
    notes: list[str] = []
    cw = extra = None
    missed = False
    if found.counterweights is not None and counterweights is not None:
        cw = _counterweights_of(found.counterweights)
        none_needed = bool(found.counterweights.already_balanced[0])
        if cw.note and not (none_needed and counterweights.scope != "halves"):
            notes.append(cw.note)
        if none_needed and counterweights.scope != "halves":
            notes.append(
                "no counterweights: the rotating masses"
                + (
                    " and the balance factor's share of the reciprocating ones"
                    if counterweights.balance_factor
                    else ""
                )
                + " leave no free first-order force or couple on the whole crank; "
                'scope = "halves" puts counterweights on each half of the crank on its '
                "own, to relieve the main bearings (paper section 3.1)"
            )
        tolerance = CHECK_TOLERANCE / ROUND_OFF
        missed_force = float(found.counterweights.missed_force[0])
        missed_moment = float(found.counterweights.missed_moment[0])
        missed = missed_force > tolerance * levels[0] or missed_moment > tolerance * levels[1]
        if missed:
            notes.append(
                "the counterweights cannot reach their target, "
                + (
                    "equal counterweights at this angle cannot balance it"
                    if counterweights.method == "pattern"
                    else "counterweights in these planes cannot balance it"
                )
                + " (the rotating masses"
                + (
                    f" and {counterweights.balance_factor:g} times the reciprocating "
                    "masses' first order"
                    if counterweights.balance_factor
                    else ""
                )
                + f"): {missed_force:.4g} N and {missed_moment:.4g} N·m of the crank-speed "
                "forward force and couple are left beyond it; "
                + (
                    'angle = "optimal" or method = "individual" can reach it'
                    if counterweights.method == "pattern"
                    else "put counterweights on webs in more planes"
                )
            )
    if found.extra_counterweights is not None:
        extra = _counterweights_of(found.extra_counterweights)
        notes.append(
            "single counter-rotating primary shaft: the forward primary phasors are "
            "carried by extra crank counterweight masses (same first moment and couple as "
            "the co-rotating shaft they replace)"
        )
    if secondary is not None and secondary.arrangement != "pair":
        notes.append(
            "secondary: a single counter-rotating shaft leaves the forward second-order "
            "phasors unbalanced (nothing on the crank turns at 2w)"
        )
    r = found.residuals
    residuals = tuple(
        ComponentResidual(*row)  # (name, targeted, the eight sizes)
        for row in zip(
            r.components,
            r.targeted.tolist(),
            r.force_before[0].tolist(),
            r.force_after[0].tolist(),
            r.moment_before[0].tolist(),
            r.moment_after[0].tolist(),
            r.force_forward_after[0].tolist(),
            r.force_backward_after[0].tolist(),
            r.moment_forward_after[0].tolist(),
            r.moment_backward_after[0].tolist(),
            strict=True,
        )
    )
    rotating_left = residuals[0].force_after + residuals[0].moment_after / length > 0
    if cw is not None and rotating_left and not missed:
        notes.append(
            "the counterweights do not cancel the rotating masses (see the residual): with "
            "equal counterweights this angle cannot balance both force and couple; "
            'angle = "optimal" or method = "individual" can'
        )
    share = None if found.rotating_share is None else found.rotating_share[0]
    return BalanceResult(
        cw,
        extra,
        _shafts_of(found.primary),
        _shafts_of(found.secondary),
        residuals,
        tuple(notes),
        share,
        what_is_left(residuals, counterweights, primary, secondary, missed),
    )


def what_is_left(
    residuals: Sequence[ComponentResidual],
    counterweights: CounterweightOptions | None,
    primary: ShaftOptions | None,
    secondary: ShaftOptions | None,
    missed: bool = False,
) -> tuple[Remaining, ...]:
    """Every free force and couple a balancing result leaves, forward and backward apart,
    in words with the next step that would remove it.

    Parameters
    ----------
    residuals : sequence of ComponentResidual
        The result's residuals (``"rotating"``, ``"order1"``, ...) [N], [N·m].
    counterweights : CounterweightOptions or None
        The crank counterweights asked for (their balance factor and method).
    primary, secondary : ShaftOptions or None
        The balance shafts asked for.
    missed : bool
        Whether the counterweights fell short of their target (a pattern that cannot
        reach it).

    Returns
    -------
    tuple of Remaining
        One entry per component, quantity and sense left, largest order last.
    """
    out: list[Remaining] = []
    for c in residuals:
        ff, fb = c.force_forward_after, c.force_backward_after
        mf, mb = c.moment_forward_after, c.moment_backward_after
        if max(ff, fb, mf, mb) <= 0.0:
            continue  # nothing left of this component
        sizes = (
            ("force", "N", "forward", ff),
            ("force", "N", "backward", fb),
            ("couple", "N·m", "forward", mf),
            ("couple", "N·m", "backward", mb),
        )
        rotating = c.component == "rotating"
        order = 1 if rotating else int(c.component.removeprefix("order"))
        for quantity, unit, rotation, amount in sizes:
            if amount <= 0.0:
                continue
            # results.number's 4 digits (10 000 and more whole, never 1.28e+04); its
            # plain format below that, which it equals there, spares the solver's path
            shown = f"{amount:.4g}" if amount < 1e4 else number(amount)
            text = (
                f"the rotating masses' {quantity}, {rotation}-rotating: {shown} {unit}"
                if rotating
                else f"order {order} {quantity}, {rotation}-rotating: {shown} {unit}"
            )
            step = next_step(c.component, order, rotation, counterweights, primary, missed)
            out.append(
                Remaining(
                    c.component,
                    order,
                    quantity,
                    rotation,
                    amount,
                    text,
                    step_words(step, FACTOR_OPTION),
                    step,
                )
            )
    return tuple(out)


def _counterweights_of(found: BatchCounterweights) -> Counterweights:
    """Engine 0 of the solver's counterweights, with its note."""
    already = bool(found.already_balanced[0])
    note = ""
    if already:
        note = "already balanced: no counterweight mass needed"
    elif found.flipped[0]:
        note = "the counterweights point toward their crankpins (the pattern was flipped)"
    pattern = found.method == "pattern" and not already
    return Counterweights(
        found.method,
        "halves" if found.halves[0] else "whole",
        found.cg_radius,
        float(found.alpha[0]) if pattern else None,
        found.web.copy(),  # the solver's are kept by the model's input (read-only)
        found.throw,
        found.position[0].copy(),
        found.mass[0],
        found.direction[0],
        note,
    )


def _shafts_of(found: BatchShafts | None) -> ShaftSet | None:
    """Engine 0 of the solver's shafts of one order."""
    if found is None:
        return None
    shafts = []
    for s, sense in enumerate(found.sense.tolist()):
        layout = int(found.layout[0, s])
        if layout == 0:
            shafts.append(
                Shaft(
                    found.order,
                    sense,
                    found.cg_radius,
                    (),
                    "nothing to cancel: no shaft mass needed",
                )
            )
            continue
        slots = (1,) if layout == 1 else (0, 2)
        masses = tuple(
            ShaftMass(
                float(found.position[k]), float(found.mass[0, s, k]), float(found.phase[0, s, k])
            )
            for k in slots
        )
        shafts.append(Shaft(found.order, sense, found.cg_radius, masses))
    return ShaftSet(found.order, found.arrangement, found.length, tuple(shafts))


# --------------------------------------------------------------------------- time histories
def point_mass_history(
    speed: float,
    angle: ArrayLike,
    first_moments: Sequence[tuple[ArrayLike, ArrayLike]] = (),
    shafts: Sequence[ShaftSet | None] = (),
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    r"""Force and couple of balancing point masses versus crank angle.

    A mass :math:`m` at radius :math:`\rho`, axial position :math:`y`, turning at
    :math:`s k\omega` (order :math:`k`, sense :math:`s = \pm 1`) with phase :math:`\psi` at
    crank angle 0 gives the force :math:`m\rho(k\omega)^2 e^{i(\psi + s k \theta)}` and
    :math:`y` times that to the couple. Crank counterweights turn with the crank
    (:math:`k = 1`, :math:`s = +1`) and are given by their first moments. This is the one
    place the time histories of the balancing masses are built: the solver's time-domain
    check (:func:`verify`) and the "after balancing" curves of
    :func:`crankbalance.output.figures.balanced_curves` both use it.

    Parameters
    ----------
    speed : float
        Crank speed :math:`\omega` [rad/s].
    angle : array_like
        Crank angles :math:`\theta` [rad].
    first_moments : sequence of (array_like, array_like)
        Sets of masses turning with the crank, each a pair of complex first moments
        :math:`m\rho e^{i\psi}` [kg·m] and axial positions :math:`y` [m] (e.g.
        ``(Counterweights.moments, Counterweights.position)``). Empty sets are skipped.
    shafts : sequence of ShaftSet or None
        Balance-shaft sets whose masses are added (None entries are skipped).

    Returns
    -------
    force : ndarray of complex
        :math:`F_z + iF_x` [N] at every angle (complex ``z + i x``, as
        :mod:`crankbalance.physics.shaking`).
    couple : ndarray of complex
        :math:`\sum y F` [N·m] at every angle, about the crankshaft mid-point (the moment is
        :math:`iC`).
    """
    theta = np.asarray(angle, dtype=float)
    w = speed
    force = np.zeros(theta.shape, complex)
    couple = np.zeros(theta.shape, complex)
    for moments, position in first_moments:
        m_rho = np.asarray(moments)
        if m_rho.size == 0:
            continue
        each = (m_rho * w**2)[:, None] * np.exp(1j * theta)[None, :]
        force += each.sum(axis=0)
        couple += (np.asarray(position)[:, None] * each).sum(axis=0)
    for group in shafts:
        if group is None:
            continue
        for shaft in group.shafts:
            for mass in shaft.masses:
                f = (
                    mass.mass
                    * shaft.cg_radius
                    * (shaft.order * w) ** 2
                    * np.exp(1j * (mass.phase + shaft.sense * shaft.order * theta))
                )
                force += f
                couple += mass.position * f
    return force, couple


# --------------------------------------------------------------------------- the angle
@record
class AngleSweep(ResultMixin):
    """Counterweight mass of the paper's equal-mass pattern versus its angle.

    ``mass`` [kg] per counterweight and ``residual`` [kg·m]: the first-moment residual of
    the force and couple equations (couple divided by the crank length); zero where the
    pattern balances the crank exactly.

    Parameters
    ----------
    angle : ndarray, shape (A,)
        Turn angle :math:`\\alpha` of the pattern [rad].
    mass : ndarray, shape (A,)
        Mass of each counterweight at its CG radius [kg].
    residual : ndarray, shape (A,)
        Residual of the equations [kg·m].
    """

    angle: NDArray[np.float64]
    mass: NDArray[np.float64]
    residual: NDArray[np.float64]


def counterweight_angle_sweep(
    model: EngineModel, options: CounterweightOptions, angles: ArrayLike
) -> AngleSweep:
    """Mass of the equal counterweights and the residual for every angle in ``angles``
    [rad] at once (the rotating masses plus the balance-factor share, whole crank).

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    options : CounterweightOptions
        Webs, CG radius, balance factor and web offset; ``angle``, ``scope`` and
        ``method`` are not used.
    angles : array_like, shape (A,)
        Turn angles :math:`\\alpha` [rad].

    Returns
    -------
    AngleSweep
        Mass per counterweight [kg] and residual [kg·m] at each angle.

    References
    ----------
    Appl. Sci. 2021, Eqs. 8-10 (the pattern of equal counterweights).
    """
    throw_of_web, y = web_layout(model, options.web_offset, options.webs)
    _, length = engine_scales(model)
    rotating, rotating_couple, reciprocating, reciprocating_couple = throw_unbalance(model)
    fb = options.balance_factor
    target = (rotating + fb * reciprocating).sum()
    couple = (rotating_couple + fb * reciprocating_couple).sum()
    a = np.array([np.ones_like(y), y / length])
    b = -np.array([target, couple / length])
    opposite = model.throw_angle[throw_of_web] + np.pi
    side = np.sign(np.round((y - crank_middle(model.throw_position)) / length, 12))
    moment, residual = pattern_masses(a, b, opposite, side, angles)
    return AngleSweep(np.asarray(angles, dtype=float), np.abs(moment) / options.cg_radius, residual)
