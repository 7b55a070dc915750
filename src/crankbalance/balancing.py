r"""Crankshaft counterweights and balance shafts for any engine (2021 paper, sections 2-3,
generalised), with a built-in time-domain check of what they leave.

Every order's free force and couple is a sum of a forward and a backward phasor
(:mod:`crankbalance.shaking`). A mass :math:`m` at radius :math:`\rho` turning at
:math:`k\omega` with phase :math:`\psi` adds :math:`m\rho(k\omega)^2 e^{i\psi}` to the forward
phasor of order k (to the backward one if it turns against the crank), and :math:`y` times
that to the couple. So:

* crank counterweights (order 1, forward) cancel the rotating masses and, with a balance
  factor :math:`f_b`, the share :math:`f_b` of the reciprocating masses put on the crank;
* a co-rotating primary shaft cancels the forward primary phasors left, a counter-rotating
  one the backward ones; secondary shafts do the same at :math:`\pm 2\omega`.

Counterweights follow the paper's pattern (all of equal mass :math:`m_c` at radius
:math:`r_c`, each opposite its crankpin turned by :math:`\pm\alpha`, the sign following
the side of the mid-plane, Eqs. 6-11 with the docs/references.md reading of the sign rule) or,
``method="individual"``, each its own mass and angle (least :math:`\sum m_j^2`). The
equations are the paper's Eq. 10: force and couple, x and z, solved together in the least
squares sense; the residual of each is reported, never hidden.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import InputError
from .model import EngineModel
from .results import ResultMixin
from .shaking import FreeForces, exact_time_domain, free_forces

Method = Literal["pattern", "individual"]
Scope = Literal["auto", "whole", "halves"]
Arrangement = Literal["pair", "counter-rotating"]

#: relative size below which a force or couple counts as zero (round-off of the sums)
ZERO = 1e-10


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
        Axial distance of each web from its throw mid-plane [m]; default
        :func:`default_web_offset`.

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


# --------------------------------------------------------------------------- results
@dataclass(frozen=True)
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


@dataclass(frozen=True)
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


@dataclass(frozen=True)
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


@dataclass(frozen=True)
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


@dataclass(frozen=True)
class ComponentResidual(ResultMixin):
    """Amplitude of one component before and after balancing (time-domain check).

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
    """

    component: str
    targeted: bool
    force_before: float
    force_after: float
    moment_before: float
    moment_after: float


@dataclass(frozen=True)
class BalanceResult(ResultMixin):
    """Everything the solver found, with the time-domain residual of each component.

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
    """

    counterweights: Counterweights | None
    extra_counterweights: Counterweights | None
    primary: ShaftSet | None
    secondary: ShaftSet | None
    residuals: tuple[ComponentResidual, ...]
    notes: tuple[str, ...] = field(default=())

    def residual(self, component: str) -> ComponentResidual:
        for item in self.residuals:
            if item.component == component:
                return item
        raise KeyError(component)


# --------------------------------------------------------------------------- helpers
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
    t = model.throws
    if web_offset is None:
        web_offset = default_web_offset(model)
    flags = np.ones(2 * t, dtype=int) if webs is None else np.asarray(webs, dtype=int)
    if flags.size != 2 * t:
        raise InputError(
            "counterweights.webs", list(flags), f"needs {2 * t} entries (two per throw)"
        )
    index = np.flatnonzero(flags)
    throw = index // 2
    side = np.where(index % 2 == 0, -1.0, 1.0)
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
    if model.throws > 1:
        spacing = np.diff(np.sort(model.throw_position))
        spacing = spacing[spacing > 0]
        if spacing.size:
            return float(spacing.min()) / 4.0
    return model.crank_radius / 2.0


def _parts(model: EngineModel, scope: str, throw_of_web: NDArray) -> list[tuple[NDArray, NDArray]]:
    """(throw mask, web mask) of each part the counterweights must balance on its own."""
    if scope == "whole":
        return [(np.ones(model.throws, bool), np.ones(throw_of_web.size, bool))]
    y = model.throw_position
    if np.any(np.abs(y) < 1e-12) or model.throws < 2:
        raise InputError(
            "counterweights.scope",
            "halves",
            "balancing each half needs an even number of throws off the mid-plane",
        )
    lower = y < 0
    return [(lower, lower[throw_of_web]), (~lower, ~lower[throw_of_web])]


def _scale(model: EngineModel) -> tuple[float, float]:
    """Force and length scales of an engine, for relative tolerances."""
    mass = float(model.throw_rotating_mass.sum() + model.reciprocating_mass.sum())
    force = max(mass, 1e-30) * model.crank_radius * model.speed**2
    length = max(float(np.ptp(model.throw_position)), model.crank_radius)
    return force, length


# --------------------------------------------------------------------------- counterweights
def solve_counterweights(
    model: EngineModel,
    options: CounterweightOptions,
    target_force: complex,
    target_couple: NDArray | complex,
    part_targets: list[tuple[complex, complex]] | None = None,
) -> Counterweights:
    """Counterweights whose forward first-order phasors cancel the given targets.

    ``part_targets`` gives (force, couple) per part for ``scope="halves"``; otherwise
    the whole crank's ``target_force`` and ``target_couple`` are used. Targets are the
    unbalance to cancel, as first moments :math:`\\sum m\\,r\\,e^{i\\varphi}` [kg·m] and
    :math:`\\sum y\\,m\\,r\\,e^{i\\varphi}` [kg·m²].

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    options : CounterweightOptions
        Webs, CG radius, angle, scope and method; ``scope="auto"`` is taken as whole.
    target_force : complex
        First moment of the unbalance of the whole crank, :math:`z + i x` [kg·m].
    target_couple : complex
        Its moment about the crankshaft mid-point [kg·m²].
    part_targets : list of (complex, complex), optional
        (first moment [kg·m], moment [kg·m²]) of each half for ``scope="halves"``.

    Returns
    -------
    Counterweights
        Mass [kg] and direction [rad] of every counterweight.

    Raises
    ------
    InputError
        If a part needs balancing but has no counterweight, or its counterweights all lie
        in one plane while a couple is to be cancelled.

    References
    ----------
    Appl. Sci. 2021, Eqs. 6-11 (Eq. 10 with the minus sign in the counterweight matrix, the
    sign rule of Eq. 8 generalised; docs/references.md).
    """
    throw_of_web, y = web_layout(model, options.web_offset, options.webs)
    scope = "whole" if options.scope == "auto" else options.scope
    parts = _parts(model, scope, throw_of_web)
    targets = part_targets if part_targets is not None else [(target_force, complex(target_couple))]
    force_scale, length = _scale(model)
    size = force_scale / model.speed**2  # kg·m
    rows: list[NDArray] = []  # one complex row per equation over the webs
    rhs: list[complex] = []
    for (_, web_mask), (force, couple) in zip(parts, targets, strict=True):
        rows.append(np.where(web_mask, 1.0, 0.0))
        rhs.append(-force)
        rows.append(np.where(web_mask, y / length, 0.0))
        rhs.append(-couple / length)
    a = np.array(rows, dtype=complex)
    b = np.array(rhs, dtype=complex)
    webs_numbered = (
        np.flatnonzero(
            np.ones(2 * model.throws) if options.webs is None else np.asarray(options.webs)
        )
        + 1
    )
    if np.abs(b).max(initial=0.0) < ZERO * size:
        zero = np.zeros(throw_of_web.size)
        return Counterweights(
            options.method,
            scope,
            options.cg_radius,
            None,
            webs_numbered,
            throw_of_web + 1,
            y,
            zero,
            np.zeros_like(zero),
            "already balanced: no counterweight mass needed",
        )
    # a couple can only be cancelled by counterweights in more than one plane
    for (_, web_mask), (force, couple) in zip(parts, targets, strict=True):
        planes = np.unique(np.round(y[web_mask], 12))
        if planes.size == 0:
            raise InputError(
                "counterweights.webs",
                list(options.webs or []),
                "a part of the crank that needs balancing has no counterweight",
            )
        moment_about_plane = couple - planes[0] * force
        if planes.size == 1 and abs(moment_about_plane) > ZERO * size * length:
            raise InputError(
                "counterweights.webs",
                list(options.webs or []),
                f"all counterweights lie in one plane (y = {planes[0] * 1e3:g} mm): they cannot "
                "cancel the couple of the rotating masses; put counterweights on webs in two "
                "planes",
            )
    if options.method == "individual":
        v, *_ = np.linalg.lstsq(a, b, rcond=None)  # least sum |v|^2 among exact solutions
        mass = np.abs(v) / options.cg_radius
        direction = np.angle(v)
        return Counterweights(
            "individual",
            scope,
            options.cg_radius,
            None,
            webs_numbered,
            throw_of_web + 1,
            y,
            mass,
            np.where(mass > 0, direction, 0.0),
        )
    opposite = model.throw_angle[throw_of_web] + np.pi
    side = np.sign(np.round(y / length, 12))
    if options.angle == "optimal":
        alpha, m_c = _optimal_pattern(a, b, opposite, side)
    else:
        alpha = float(options.angle)
        m_c = float(pattern_masses(a, b, opposite, side, np.array([alpha]))[0][0])
    direction = opposite + side * alpha
    note = ""
    if m_c < 0:  # the pattern points the wrong way: flip it (same as alpha + 180 deg)
        m_c, direction = -m_c, direction + np.pi
        note = "the counterweights point toward their crankpins (the pattern was flipped)"
    mass = np.full(throw_of_web.size, m_c / options.cg_radius)
    return Counterweights(
        "pattern",
        scope,
        options.cg_radius,
        alpha,
        webs_numbered,
        throw_of_web + 1,
        y,
        mass,
        np.mod(direction, 2 * np.pi),
        note,
    )


def pattern_masses(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray, alphas: ArrayLike
) -> tuple[NDArray, NDArray]:
    """First moment :math:`m_c r_c` [kg·m] of the equal counterweights of the paper's
    pattern and the residual of the equations, for many angles :math:`\\alpha` at once.

    Vectorised over ``alphas`` (least squares with one real unknown per angle).

    Parameters
    ----------
    a : ndarray of complex, shape (E, W)
        Equations over the webs: a row of ones (force) and a row of axial positions over
        the crank length (couple) per part [-].
    b : ndarray of complex, shape (E,)
        Right-hand sides: minus the first moment to cancel, and minus its moment over the
        crank length [kg·m].
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
    coeff = unit @ a.T  # (A, E): each equation's coefficient of m_c r_c
    num = np.real(np.conj(coeff) @ b)
    den = np.sum(np.abs(coeff) ** 2, axis=1)
    safe = den > 1e-300
    moment = np.where(safe, num / np.where(safe, den, 1.0), 0.0)
    residual = np.linalg.norm(coeff * moment[:, None] - b[None, :], axis=1)
    return moment, residual


def _optimal_pattern(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray
) -> tuple[float, float]:
    """Turn angle and first moment of the least-mass pattern that balances.

    Without counterweights in the mid-plane the pattern is linear in
    :math:`X = m_c r_c\\cos\\alpha`, :math:`Y = m_c r_c\\sin\\alpha`: solved exactly by
    least squares (least :math:`m_c` among exact solutions). Otherwise the angle is found
    by a scan and a bounded refinement.
    """
    base = np.exp(1j * opposite)
    if not np.any(side == 0):
        # direction e^{i(opposite + side*alpha)} = base (cos a + i side sin a)
        cx = a @ base
        cy = a @ (1j * side * base)
        matrix = np.vstack(
            [np.column_stack([cx.real, cy.real]), np.column_stack([cx.imag, cy.imag])]
        )
        rhs = np.concatenate([b.real, b.imag])
        (x, yv), *_ = np.linalg.lstsq(matrix, rhs, rcond=None)
        return float(np.arctan2(yv, x)), float(np.hypot(x, yv))
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
def solve_shaft(
    order: int,
    sense: int,
    force: complex,
    couple: complex,
    cg_radius: float,
    length: float,
    speed: float,
    scale: float,
) -> Shaft:
    """Masses of one balance shaft that cancel a phasor pair (force [N], couple [N·m]).

    Force only: one mass mid-shaft; couple only: two masses in opposite phase at
    :math:`\\pm l/2` (paper Eq. 13); both: two masses at :math:`\\pm l/2` sized together.

    Parameters
    ----------
    order : int
        Shaft speed in multiples of the crank speed (1 or 2).
    sense : int
        +1 co-rotating (cancels forward phasors), -1 counter-rotating (backward).
    force : complex
        Phasor of the force to cancel, :math:`z + i x` [N].
    couple : complex
        Phasor of the couple to cancel, about the crankshaft mid-point [N·m].
    cg_radius : float
        Radius of the centre of gravity of the shaft masses [m].
    length : float
        Axial distance between the two outer masses, :math:`l_{sh}` [m].
    speed : float
        Crank speed [rad/s].
    scale : float
        Force scale of the engine, below ``ZERO`` times which a phasor counts as zero [N].

    Returns
    -------
    Shaft
        Its masses [kg], axial positions [m] and phases [rad].

    References
    ----------
    Appl. Sci. 2021, Eqs. 13-22, with the errata of docs/references.md (masses at
    :math:`\\pm l_{sh}/2`, factor 4 of :math:`(2\\omega)^2` for the secondary shafts).
    """
    gain = cg_radius * (order * speed) ** 2  # force per kg of shaft mass at phase 0
    has_force = abs(force) > ZERO * scale
    has_couple = abs(couple) > ZERO * scale * length
    if not has_force and not has_couple:
        return Shaft(order, sense, cg_radius, (), "nothing to cancel: no shaft mass needed")
    if not has_couple:
        v = -force / gain
        return Shaft(order, sense, cg_radius, (ShaftMass(0.0, abs(v), _phase(v)),))
    half = length / 2
    # v1 + v2 = -F/g ; -h v1 + h v2 = -C/g
    v2 = (-force / gain - couple / (gain * half)) / 2 if has_force else -couple / (gain * length)
    v1 = -force / gain - v2 if has_force else -v2
    return Shaft(
        order,
        sense,
        cg_radius,
        (ShaftMass(-half, abs(v1), _phase(v1)), ShaftMass(half, abs(v2), _phase(v2))),
    )


def _phase(v: complex) -> float:
    return float(np.mod(np.angle(v), 2 * np.pi)) if abs(v) > 0 else 0.0


# --------------------------------------------------------------------------- the study
def balance(
    model: EngineModel,
    counterweights: CounterweightOptions | None = None,
    primary: ShaftOptions | None = None,
    secondary: ShaftOptions | None = None,
    orders: int = 8,
) -> BalanceResult:
    """Counterweights and balance shafts for an engine, checked in the time domain.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    counterweights : CounterweightOptions, optional
        Crank counterweights (rotating masses plus the balance-factor share).
    primary, secondary : ShaftOptions, optional
        Balance shafts at crank speed and at twice crank speed.
    orders : int
        Orders reported in the residual check.

    Returns
    -------
    BalanceResult
        Counterweights, shafts and the residual of each component.

    References
    ----------
    Appl. Sci. 2021, Eqs. 1-23, with the errata of docs/references.md.
    """
    forces = free_forces(model, max(orders, 2))
    r, w = model.crank_radius, model.speed
    w2 = w**2
    force_scale, length = _scale(model)
    notes: list[str] = []
    rot_moment = model.throw_rotating_mass * r * np.exp(1j * model.throw_angle)  # kg·m
    pin_rec = np.bincount(
        model.cylinder_throw, weights=model.reciprocating_mass, minlength=model.throws
    )
    rec_moment = pin_rec * r * np.exp(1j * model.throw_angle)
    fb = counterweights.balance_factor if counterweights else 0.0
    target = rot_moment + fb * rec_moment  # per throw: what the crank counterweights carry

    cw: Counterweights | None = None
    cw_rotating: NDArray | None = None
    if counterweights is not None:
        scope = counterweights.scope
        whole_f, whole_c = target.sum(), (target * model.throw_position).sum()
        size = force_scale / w2
        if scope == "auto":
            balanced = abs(whole_f) < ZERO * size and abs(whole_c) < ZERO * size * length
            scope = (
                "halves" if balanced and model.throws % 2 == 0 and model.throws >= 2 else "whole"
            )
            if scope == "halves":
                notes.append(
                    "the crank is balanced as a whole; each half is balanced on its own "
                    "(paper section 3.1)"
                )
        opts = CounterweightOptions(**{**counterweights.__dict__, "scope": scope})
        part_targets = None
        if scope == "halves":
            throw_of_web, _ = web_layout(model, opts.web_offset, opts.webs)
            part_targets = [
                (
                    complex(target[mask].sum()),
                    complex((target[mask] * model.throw_position[mask]).sum()),
                )
                for mask, _ in _parts(model, "halves", throw_of_web)
            ]
        cw = solve_counterweights(model, opts, complex(whole_f), complex(whole_c), part_targets)
        if cw.note:
            notes.append(cw.note)
        # the share of the counterweights that carries the rotating masses alone (same
        # angle; the equations are linear in the targets), for the residual check
        cw_rotating = cw.moments
        if fb != 0.0:
            fixed = CounterweightOptions(**{**opts.__dict__, "angle": cw.alpha or 0.0})
            rot_parts = None
            if part_targets is not None:
                throw_of_web, _ = web_layout(model, opts.web_offset, opts.webs)
                rot_parts = [
                    (
                        complex(rot_moment[mask].sum()),
                        complex((rot_moment[mask] * model.throw_position[mask]).sum()),
                    )
                    for mask, _ in _parts(model, "halves", throw_of_web)
                ]
            cw_rotating = solve_counterweights(
                model,
                fixed,
                complex(rot_moment.sum()),
                complex((rot_moment * model.throw_position).sum()),
                rot_parts,
            ).moments

    # first order left after the crank counterweights: the forward reciprocating phasors
    # plus what the counterweights do beyond the rotating masses (balance-factor share)
    k1 = forces.order(1)
    fwd1_f, fwd1_c = forces.force_forward[k1], forces.couple_forward[k1]
    if cw is not None and cw_rotating is not None:
        beyond = (cw.moments - cw_rotating) * w2
        fwd1_f = fwd1_f + beyond.sum()
        fwd1_c = fwd1_c + (beyond * cw.position).sum()

    extra: Counterweights | None = None
    primary_set: ShaftSet | None = None
    if primary is not None:
        shafts = []
        if primary.arrangement == "pair":
            shafts.append(
                solve_shaft(
                    1, +1, fwd1_f, fwd1_c, primary.cg_radius, primary.length, w, force_scale
                )
            )
        else:
            # Eq. 17 done right: the co-rotating shaft's first moment and couple go onto the
            # crank counterweights as an extra set of masses
            if counterweights is None:
                raise InputError(
                    "balance_shafts.primary.arrangement",
                    "counter-rotating",
                    "a single counter-rotating shaft needs [counterweights] on the "
                    "crank to take the co-rotating half",
                )
            opts = CounterweightOptions(
                **{**counterweights.__dict__, "scope": "whole", "method": "individual"}
            )
            extra = solve_counterweights(model, opts, fwd1_f / w2, fwd1_c / w2)
            notes.append(
                "single counter-rotating primary shaft: the forward primary phasors "
                "are carried by extra crank counterweight masses (same first moment "
                "and couple as the co-rotating shaft they replace)"
            )
        shafts.append(
            solve_shaft(
                1,
                -1,
                forces.force_backward[k1],
                forces.couple_backward[k1],
                primary.cg_radius,
                primary.length,
                w,
                force_scale,
            )
        )
        primary_set = ShaftSet(1, primary.arrangement, primary.length, tuple(shafts))

    secondary_set: ShaftSet | None = None
    if secondary is not None:
        k2 = forces.order(2)
        shafts = []
        if secondary.arrangement == "pair":
            shafts.append(
                solve_shaft(
                    2,
                    +1,
                    forces.force_forward[k2],
                    forces.couple_forward[k2],
                    secondary.cg_radius,
                    secondary.length,
                    w,
                    force_scale,
                )
            )
        else:
            notes.append(
                "secondary: a single counter-rotating shaft leaves the forward "
                "second-order phasors unbalanced (nothing on the crank turns at 2w)"
            )
        shafts.append(
            solve_shaft(
                2,
                -1,
                forces.force_backward[k2],
                forces.couple_backward[k2],
                secondary.cg_radius,
                secondary.length,
                w,
                force_scale,
            )
        )
        secondary_set = ShaftSet(2, secondary.arrangement, secondary.length, tuple(shafts))

    # the check always covers orders 1 and 2, the ones the shafts can target
    residuals = verify(
        model, forces, cw, cw_rotating, extra, primary_set, secondary_set, max(orders, 2)
    )
    if cw is not None and residuals[0].force_after + residuals[0].moment_after / length > 0:
        notes.append(
            "the counterweights do not cancel the rotating masses (see the residual): with "
            "equal counterweights this angle cannot balance both force and couple; "
            'angle = "optimal" or method = "individual" can'
        )
    return BalanceResult(cw, extra, primary_set, secondary_set, residuals, tuple(notes))


# --------------------------------------------------------------------------- verification
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
    :func:`crankbalance.figures.balanced_curves` both use it.

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
        :mod:`crankbalance.shaking`).
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


def verify(
    model: EngineModel,
    forces: FreeForces,
    cw: Counterweights | None,
    cw_rotating: NDArray | None,
    extra: Counterweights | None,
    primary: ShaftSet | None,
    secondary: ShaftSet | None,
    orders: int = 8,
    samples: int = 256,
) -> tuple[ComponentResidual, ...]:
    """Rebuild the time history of every mass and measure what is left, order by order.

    The crank train's reciprocating forces come straight from the slider-crank motion
    (exact kinematics) or from the model's harmonic series; each counterweight and shaft
    mass is a point mass whose force is evaluated at every crank angle. ``cw_rotating``
    holds the first moments of the counterweights' share that carries the rotating masses
    (the rest, balance factor and Eq. 17 extra, counts to the first order). The order-by-order
    amplitudes are then read off a discrete Fourier transform of the totals, so this check
    shares no algebra with the solver.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    forces : FreeForces
        Its phasors (used for the reciprocating forces unless the kinematics is exact).
    cw : Counterweights or None
        Crank counterweights.
    cw_rotating : ndarray of complex or None
        First moments of the counterweight share that carries the rotating masses [kg·m].
    extra : Counterweights or None
        The Eq. 17 extra counterweights.
    primary, secondary : ShaftSet or None
        Balance shafts of order 1 and 2.
    orders : int
        Highest reciprocating order checked.
    samples : int
        Crank angles per revolution of the time histories (more than twice ``orders``).

    Returns
    -------
    tuple of ComponentResidual
        ``"rotating"``, then ``"order1"`` .. ``"order<orders>"``; forces [N], moments
        [N·m].
    """
    theta = 2 * np.pi * np.arange(samples) / samples
    w = model.speed
    r = model.crank_radius
    crank_turn = np.exp(1j * theta)

    # rotating: crank masses and the counterweight share that carries them
    rot = (model.throw_rotating_mass * r * np.exp(1j * model.throw_angle))[:, None] * crank_turn
    rot_f = w**2 * rot.sum(axis=0)
    rot_c = w**2 * (model.throw_position[:, None] * rot).sum(axis=0)
    if model.kinematics == "exact":
        rec_f, rec_c = exact_time_domain(model, theta)
    else:
        from .shaking import phasor_curve

        rec_f = phasor_curve(forces.force_forward, forces.force_backward, forces.orders, theta).sum(
            axis=0
        )
        rec_c = phasor_curve(
            forces.couple_forward, forces.couple_backward, forces.orders, theta
        ).sum(axis=0)

    # counterweights: the share that carries the rotating masses, and the rest (balance
    # factor share and the Eq. 17 extra set) that counts to the first order
    zero = np.zeros(samples, complex)
    cw_rot_f, cw_rot_c = zero, zero
    beyond: list[tuple[ArrayLike, ArrayLike]] = []
    if cw is not None and cw_rotating is not None:
        cw_rot_f, cw_rot_c = point_mass_history(w, theta, [(cw_rotating, cw.position)])
        beyond.append((cw.moments - cw_rotating, cw.position))
    if extra is not None:
        beyond.append((extra.moments, extra.position))
    cw_rec_f, cw_rec_c = point_mass_history(w, theta, beyond)
    # balance shafts by order (primary shafts turn at order 1, secondary at order 2)
    shaft_f: dict[int, NDArray] = {}
    shaft_c: dict[int, NDArray] = {}
    for order, group in ((1, primary), (2, secondary)):
        shaft_f[order], shaft_c[order] = point_mass_history(w, theta, shafts=(group,))

    def amplitude(series: NDArray, order: int) -> float:
        spectrum = np.fft.fft(series) / samples
        return float(abs(spectrum[order]) + abs(spectrum[-order]))

    force_scale, length = _scale(model)
    out = [
        ComponentResidual(
            "rotating",
            cw is not None,
            _clean(amplitude(rot_f, 1), force_scale),
            _clean(amplitude(rot_f + cw_rot_f, 1), force_scale),
            _clean(amplitude(rot_c, 1), force_scale * length),
            _clean(amplitude(rot_c + cw_rot_c, 1), force_scale * length),
        )
    ]
    for order in range(1, orders + 1):
        after_f = rec_f + (cw_rec_f if order == 1 else 0) + shaft_f.get(order, 0)
        after_c = rec_c + (cw_rec_c if order == 1 else 0) + shaft_c.get(order, 0)
        targeted = (order == 1 and primary is not None) or (order == 2 and secondary is not None)
        out.append(
            ComponentResidual(
                f"order{order}",
                targeted,
                _clean(amplitude(rec_f, order), force_scale),
                _clean(amplitude(after_f, order), force_scale),
                _clean(amplitude(rec_c, order), force_scale * length),
                _clean(amplitude(after_c, order), force_scale * length),
            )
        )
    return tuple(out)


def _clean(value: float, scale: float) -> float:
    """Values below round-off of the engine's scale are reported as exactly zero."""
    return 0.0 if value < 1e-13 * scale else value


@dataclass(frozen=True)
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
    _, length = _scale(model)
    r = model.crank_radius
    pin_rec = np.bincount(
        model.cylinder_throw, weights=model.reciprocating_mass, minlength=model.throws
    )
    target = (
        (model.throw_rotating_mass + options.balance_factor * pin_rec)
        * r
        * np.exp(1j * model.throw_angle)
    )
    a = np.array([np.ones_like(y), y / length], dtype=complex)
    b = -np.array([target.sum(), (target * model.throw_position).sum() / length])
    opposite = model.throw_angle[throw_of_web] + np.pi
    side = np.sign(np.round(y / length, 12))
    moment, residual = pattern_masses(a, b, opposite, side, angles)
    return AngleSweep(np.asarray(angles, dtype=float), np.abs(moment) / options.cg_radius, residual)
