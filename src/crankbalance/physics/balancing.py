r"""Crankshaft counterweights and balance shafts for any engine (2021 paper, sections 2-3,
generalised), with a built-in time-domain check of what they leave.

Every order's free force and couple is a sum of a forward and a backward phasor
(:mod:`crankbalance.physics.shaking`). A mass :math:`m` at radius :math:`\rho` turning at
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

Many engines of one topology (a firing-order or crank study) go to :func:`balance_batch`:
an :class:`EngineBatch` of arrays with a leading engine axis in, a :class:`BatchBalance`
of arrays out, engine by engine the results of :func:`balance`, solved with stacked numpy
linear algebra in chunks of bounded memory (docs/performance.md). The module is
long because the one-engine solver, its check and the batch solver share their equations,
web layout and tolerances, which belong in one place.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, fields, replace
from typing import Any, ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..results import ResultMixin
from .kinematics import harmonic_coefficients
from .model import EngineModel
from .shaking import FreeForces, exact_time_domain, free_forces, reciprocating_phasors

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
    if web_offset is None:
        web_offset = default_web_offset(model)
    throw, side = _web_sides(model.throws, webs)
    return throw, model.throw_position[throw] + side * web_offset


def _web_sides(throws: int, webs: tuple[int, ...] | None) -> tuple[NDArray, NDArray]:
    """Throw index and side of its throw mid-plane (-1 or +1) of every counterweight web."""
    flags = np.ones(2 * throws, dtype=int) if webs is None else np.asarray(webs, dtype=int)
    if flags.size != 2 * throws:
        raise InputError(
            "counterweights.webs", list(flags), f"needs {2 * throws} entries (two per throw)"
        )
    index = np.flatnonzero(flags)
    return index // 2, np.where(index % 2 == 0, -1.0, 1.0)


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
    pitch = _throw_pitch(model.throw_position)
    return pitch / 4.0 if pitch is not None else model.crank_radius / 2.0


def _throw_targets(model: EngineModel, balance_factor: float) -> tuple[NDArray, NDArray]:
    """Per throw, the unbalance the crank counterweights carry [kg·m] (rotating masses plus
    ``balance_factor`` times the reciprocating masses on the pin, at the throw angle) and
    its first moment about the moment reference point [kg·m²], each mass at its own axial
    position (big ends and rods of side-by-side rods at the rod's position)."""
    r = model.crank_radius
    turn = np.exp(1j * model.throw_angle)
    rec = model.reciprocating_mass
    pin_rec = np.bincount(model.cylinder_throw, weights=rec, minlength=model.throws)
    # the rods' own axial places: exact zeros added when every rod is in its throw's plane
    pin_rec_a = np.bincount(
        model.cylinder_throw, weights=rec * model.cylinder_axial, minlength=model.throws
    )
    force = model.throw_rotating_mass * r * turn + balance_factor * (pin_rec * r * turn)
    couple = force * model.throw_position + (
        model.throw_axial_moment + balance_factor * pin_rec_a
    ) * (r * turn)
    return force, couple


def _middle(throw_position: NDArray) -> float:
    """The crank's mid-point [m]: the middle of the throws' extent, measured from the moment
    reference point (0 unless the engine file moves the reference; minus
    ``EngineModel.moment_reference``)."""
    return 0.5 * float(throw_position.min() + throw_position.max())


def _throw_pitch(throw_position: NDArray) -> float | None:
    """Smallest non-zero axial distance between throws [m], None without one."""
    if throw_position.size > 1:
        spacing = np.diff(np.sort(throw_position))
        spacing = spacing[spacing > 0]
        if spacing.size:
            return float(spacing.min())
    return None


def _parts(model: EngineModel, scope: str, throw_of_web: NDArray) -> list[tuple[NDArray, NDArray]]:
    """(throw mask, web mask) of each part the counterweights must balance on its own."""
    if scope == "whole":
        return [(np.ones(model.throws, bool), np.ones(throw_of_web.size, bool))]
    # halves of the crank about its own middle (not the moment reference point)
    y = model.throw_position - _middle(model.throw_position)
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
    force, length = _scales(
        model.throw_rotating_mass,
        model.reciprocating_mass,
        model.crank_radius,
        model.speed,
        model.throw_position,
    )
    return float(force), float(length)


def _scales(
    rotating: NDArray, reciprocating: NDArray, crank_radius: ArrayLike, speed: ArrayLike, y: NDArray
) -> tuple[NDArray, NDArray]:
    """Force [N] and length [m] scales of one engine or a batch (leading engine axis)."""
    mass = np.sum(rotating, axis=-1) + np.sum(reciprocating, axis=-1)
    force = np.maximum(mass, 1e-30) * crank_radius * np.square(speed)
    return force, np.maximum(np.ptp(y), crank_radius)


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
            raise _no_counterweight(options)
        moment_about_plane = couple - planes[0] * force
        if planes.size == 1 and abs(moment_about_plane) > ZERO * size * length:
            raise _one_plane(options, planes[0])
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
    side = np.sign(np.round((y - _middle(model.throw_position)) / length, 12))
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


def _no_counterweight(options: CounterweightOptions) -> InputError:
    return InputError(
        "counterweights.webs",
        list(options.webs or []),
        "a part of the crank that needs balancing has no counterweight",
    )


def _one_plane(options: CounterweightOptions, plane: float) -> InputError:
    return InputError(
        "counterweights.webs",
        list(options.webs or []),
        f"all counterweights lie in one plane (y = {plane * 1e3:g} mm): they cannot "
        "cancel the couple of the rotating masses; put counterweights on webs in two "
        "planes",
    )


def _single_shaft_without_counterweights() -> InputError:
    return InputError(
        "balance_shafts.primary.arrangement",
        "counter-rotating",
        "a single counter-rotating shaft needs [counterweights] on the "
        "crank to take the co-rotating half",
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
    w = model.speed
    w2 = w**2
    force_scale, length = _scale(model)
    notes: list[str] = []
    fb = counterweights.balance_factor if counterweights else 0.0
    rot_moment, rot_couple = _throw_targets(model, 0.0)  # kg·m, kg·m² per throw
    # per throw: what the crank counterweights carry, and its first moment along the crank
    target, target_couple = _throw_targets(model, fb)

    cw: Counterweights | None = None
    cw_rotating: NDArray | None = None
    if counterweights is not None:
        scope = counterweights.scope
        whole_f, whole_c = target.sum(), target_couple.sum()
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
                    complex(target_couple[mask].sum()),
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
                        complex(rot_couple[mask].sum()),
                    )
                    for mask, _ in _parts(model, "halves", throw_of_web)
                ]
            cw_rotating = solve_counterweights(
                model,
                fixed,
                complex(rot_moment.sum()),
                complex(rot_couple.sum()),
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
                raise _single_shaft_without_counterweights()
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
    turn = np.exp(1j * model.throw_angle)
    rot = (model.throw_rotating_mass * r * turn)[:, None] * crank_turn
    rot_f = w**2 * rot.sum(axis=0)
    rot_c = w**2 * (model.throw_position[:, None] * rot).sum(axis=0)
    rot_c += w**2 * ((model.throw_axial_moment * r * turn)[:, None] * crank_turn).sum(axis=0)
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
    target, target_couple = _throw_targets(model, options.balance_factor)
    a = np.array([np.ones_like(y), y / length], dtype=complex)
    b = -np.array([target.sum(), target_couple.sum() / length])
    opposite = model.throw_angle[throw_of_web] + np.pi
    side = np.sign(np.round((y - _middle(model.throw_position)) / length, 12))
    moment, residual = pattern_masses(a, b, opposite, side, angles)
    return AngleSweep(np.asarray(angles, dtype=float), np.abs(moment) / options.cg_radius, residual)


# --------------------------------------------------------------------------- batches
#: engines solved together in one pass of :func:`balance_batch` (bounds the temporaries to
#: a few MB; the result grows with the batch, about 1 kB per engine)
BATCH_CHUNK = 2048
#: share of an engine's force scale (forces) or force scale times crank length (moments)
#: below which the batch check counts a targeted component as cancelled
CHECK_TOLERANCE = 1e-9


@dataclass(frozen=True)
class EngineBatch:
    """Many engines of one topology: arrays with a leading engine axis (E engines).

    The ``topology`` fixes what the engines share: the throws' axial positions, the throw
    and bank angle of each cylinder and the kinematics model. Each engine has its own throw
    angles, masses, crank radius, conrod length, cylinder offsets and speed. Build it with
    :func:`engine_batch` or :func:`stack_models`. Rods side by side on a pin
    (``topology.cylinder_axial`` not zero) are refused there: the batch solvers put every
    rod and big end in its throw's plane.

    Parameters
    ----------
    topology : EngineModel
        The shared layout (its throw angles, masses, radius, rod length, offset and speed
        are not used).
    throw_angle : ndarray, shape (E, T)
        Throw angles [rad].
    throw_rotating_mass : ndarray, shape (E, T)
        Rotating mass of each throw at the crank radius [kg].
    reciprocating_mass : ndarray, shape (E, C)
        Reciprocating mass of each cylinder [kg].
    crank_radius, rod_length : ndarray, shape (E,)
        Crank radius and conrod length [m].
    cylinder_offset : ndarray, shape (E, C)
        Each cylinder's total offset (crank, wrist-pin and bank offsets) [m].
    speed : ndarray, shape (E,)
        Crank speed [rad/s].
    """

    topology: EngineModel
    throw_angle: NDArray[np.float64]
    throw_rotating_mass: NDArray[np.float64]
    reciprocating_mass: NDArray[np.float64]
    crank_radius: NDArray[np.float64]
    rod_length: NDArray[np.float64]
    cylinder_offset: NDArray[np.float64]
    speed: NDArray[np.float64]

    @property
    def size(self) -> int:
        """Number of engines E."""
        return int(self.crank_radius.size)

    def model(self, index: int) -> EngineModel:
        """Engine ``index`` as an :class:`EngineModel`, for the one-engine functions."""
        return replace(
            self.topology,
            throw_angle=self.throw_angle[index].copy(),
            throw_rotating_mass=self.throw_rotating_mass[index].copy(),
            reciprocating_mass=self.reciprocating_mass[index].copy(),
            crank_radius=float(self.crank_radius[index]),
            rod_length=float(self.rod_length[index]),
            cylinder_offset=self.cylinder_offset[index].copy(),
            speed=float(self.speed[index]),
        )

    def take(self, index: slice | NDArray[np.int64]) -> EngineBatch:
        """The engines ``index`` (a slice or integer indices) as a batch."""
        return _take(self, index)

    PER_ENGINE: ClassVar[tuple[str, ...]] = (
        "throw_angle",
        "throw_rotating_mass",
        "reciprocating_mass",
        "crank_radius",
        "rod_length",
        "cylinder_offset",
        "speed",
    )


def engine_batch(
    topology: EngineModel,
    size: int | None = None,
    *,
    throw_angle: ArrayLike | None = None,
    throw_rotating_mass: ArrayLike | None = None,
    reciprocating_mass: ArrayLike | None = None,
    crank_radius: ArrayLike | None = None,
    rod_length: ArrayLike | None = None,
    cylinder_offset: ArrayLike | None = None,
    speed: ArrayLike | None = None,
) -> EngineBatch:
    """Engines of one topology from arrays; what is not given is the topology's value.

    An array with a leading engine axis gives one value per engine; without it (per-throw
    and per-cylinder arrays of one dimension, scalars) the value is shared by all engines.

    Parameters
    ----------
    topology : EngineModel
        The shared layout and the default of every value not given.
    size : int, optional
        Number of engines E; default the leading axis of the arrays given (1 if none has
        one).
    throw_angle : array_like, shape (E, T) or (T,), optional
        Throw angles [rad].
    throw_rotating_mass : array_like, shape (E, T) or (T,), optional
        Rotating mass of each throw at the crank radius [kg].
    reciprocating_mass : array_like, shape (E, C) or (C,), optional
        Reciprocating mass of each cylinder [kg].
    crank_radius, rod_length : array_like, shape (E,) or scalar, optional
        Crank radius and conrod length [m].
    cylinder_offset : array_like, shape (E, C) or (C,), optional
        Each cylinder's total offset (crank, wrist-pin and bank offsets) [m].
    speed : array_like, shape (E,) or scalar, optional
        Crank speed [rad/s].

    Returns
    -------
    EngineBatch
        The engines, every array with its leading engine axis.

    Raises
    ------
    InputError
        If the arrays disagree on the number of engines or have the wrong shape, or an
        engine has a non-finite value, a crank radius or speed not above zero, a negative
        mass, or a conrod not longer than the crank radius plus the offset; or the
        topology has rods side by side on a pin (``cylinder_axial`` not zero).
    """
    if np.any(topology.cylinder_axial):
        raise InputError(
            "crank_train.rod_positions",
            [float(a) for a in topology.cylinder_axial],
            "rods in their throw's plane (all zero) for the batch solvers (explorer, "
            "batch balancing); analyse and balance this engine on its own",
        )
    tails = {
        "throw_angle": (topology.throws,),
        "throw_rotating_mass": (topology.throws,),
        "reciprocating_mass": (topology.cylinders,),
        "crank_radius": (),
        "rod_length": (),
        "cylinder_offset": (topology.cylinders,),
        "speed": (),
    }
    arguments = {
        "throw_angle": throw_angle,
        "throw_rotating_mass": throw_rotating_mass,
        "reciprocating_mass": reciprocating_mass,
        "crank_radius": crank_radius,
        "rod_length": rod_length,
        "cylinder_offset": cylinder_offset,
        "speed": speed,
    }
    given = {k: np.asarray(v, dtype=float) for k, v in arguments.items() if v is not None}
    sizes = {a.shape[0] for k, a in given.items() if a.ndim == len(tails[k]) + 1}
    if size is not None:
        sizes.add(size)
    if len(sizes) > 1 or min(sizes, default=1) < 1:
        raise InputError(
            "engine_batch", sorted(sizes), "one number of engines, 1 or more, for every array"
        )
    n = sizes.pop() if sizes else 1
    values: dict[str, NDArray] = {}
    for name, tail in tails.items():
        value = given.get(name, np.asarray(getattr(topology, name), dtype=float))
        try:
            values[name] = np.array(np.broadcast_to(value, (n, *tail)), dtype=float)
        except ValueError:
            raise InputError(name, list(np.shape(value)), f"shape {(n, *tail)} or {tail}") from None
    _check_engines(values)
    return EngineBatch(topology, **values)


def _check_engines(values: dict[str, NDArray]) -> None:
    """Raise :class:`InputError` for the first engine with an impossible value."""
    r, length = values["crank_radius"], values["rod_length"]
    e = np.abs(values["cylinder_offset"]).max(axis=-1, initial=0.0)
    checks = [(name, np.isfinite(a), "must be finite") for name, a in values.items()]
    checks += [
        ("crank_radius", r > 0, "must be greater than zero"),
        ("speed", values["speed"] > 0, "must be greater than zero"),
        ("throw_rotating_mass", values["throw_rotating_mass"] >= 0, "must be zero or more"),
        ("reciprocating_mass", values["reciprocating_mass"] >= 0, "must be zero or more"),
        ("rod_length", length > r + np.abs(e), "must exceed the crank radius plus the offset"),
    ]
    for name, ok, allowed in checks:
        bad = np.flatnonzero(~ok.reshape(ok.shape[0], -1).all(axis=1))
        if bad.size:
            i = int(bad[0])
            raise InputError(name, values[name][i].tolist(), f"{allowed} (engine {i})")


def stack_models(models: Sequence[EngineModel]) -> EngineBatch:
    """Engine models of one topology stacked into a batch.

    Parameters
    ----------
    models : sequence of EngineModel
        The engines; all have the throw positions, cylinder throws and bank angles and the
        kinematics model of the first.

    Returns
    -------
    EngineBatch
        The engines in the order given (the first is the topology).

    Raises
    ------
    InputError
        If ``models`` is empty or an engine's topology differs from the first's.
    """
    if not models:
        raise InputError("models", [], "at least one engine")
    for i, m in enumerate(models):
        if m.articulation is not None:
            raise InputError(
                f"models[{i}]",
                m.name,
                "has master-and-link rods, which the batch solver does not model; "
                "balance it on its own (balance)",
            )
    first = models[0]
    for i, m in enumerate(models):
        same = (
            m.kinematics == first.kinematics
            and np.array_equal(m.throw_position, first.throw_position)
            and np.array_equal(m.cylinder_throw, first.cylinder_throw)
            and np.array_equal(m.cylinder_bank, first.cylinder_bank)
        )
        if not same:
            raise InputError(
                "models",
                f"engine {i} ({m.name})",
                "engines of one topology: the throw positions, cylinder throws, bank "
                "angles and kinematics of the first",
            )
    return engine_batch(
        first,
        len(models),
        throw_angle=[m.throw_angle for m in models],
        throw_rotating_mass=[m.throw_rotating_mass for m in models],
        reciprocating_mass=[m.reciprocating_mass for m in models],
        crank_radius=[m.crank_radius for m in models],
        rod_length=[m.rod_length for m in models],
        cylinder_offset=[m.cylinder_offset for m in models],
        speed=[m.speed for m in models],
    )


@dataclass(frozen=True)
class BatchCounterweights(ResultMixin):
    """Crank counterweights of a batch (as :class:`Counterweights`, W per engine).

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
    """The balance shafts of one order for a batch (as :class:`ShaftSet`).

    Each shaft has three mass slots at the axial positions :math:`-l/2, 0, +l/2`; its
    ``layout`` says which hold a mass, as the one-engine :func:`solve_shaft`: 0 nothing to
    cancel (no mass), 1 a force only (one mass mid-shaft), 2 a couple (the two outer
    masses, sized together with the force).

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
    """What the balancing masses of a batch leave, component by component.

    Rebuilt from the reported masses, radii, phases and positions of the counterweights
    and shaft masses (each a point mass adding :math:`m\\rho(k\\omega)^2 e^{i\\psi}` to its
    order and sense), added to the free forces; the same numbers as the one-engine
    solver's time-domain check (:func:`verify`), to its round-off.

    Parameters
    ----------
    components : tuple of str
        ``"rotating"``, then ``"order1"`` .. ``"order<K>"`` (the columns).
    targeted : ndarray of bool, shape (K + 1,)
        Whether a counterweight or shaft was asked to cancel each component.
    force_before, force_after : ndarray, shape (E, K + 1)
        Largest force of each component over a revolution, without and with the balancing
        masses [N] (0 below 1e-13 of the engine's force scale, as :func:`verify`).
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
    """Counterweights, balance shafts and residuals of every engine of a batch.

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


def balance_batch(
    batch: EngineBatch,
    counterweights: CounterweightOptions | None = None,
    primary: ShaftOptions | None = None,
    secondary: ShaftOptions | None = None,
    orders: int = 8,
    chunk: int = BATCH_CHUNK,
) -> BatchBalance:
    """Counterweights and balance shafts for many engines of one topology at once.

    Engine by engine the same results as :func:`balance` (the same equations, least
    squares and tolerances; degenerate cases handled alike: nothing to cancel gives zero
    masses, rank-deficient equations the least-norm solution, and the inputs for which
    :func:`balance` raises raise the same :class:`InputError`, naming the engine). The
    equations are solved with stacked numpy linear algebra: one pseudo-inverse per web
    geometry for ``individual`` counterweights, a two-unknown least squares per engine for
    the ``optimal`` pattern, closed forms for the shafts. The engines are processed
    ``chunk`` at a time, so the temporaries stay bounded whatever the batch size.

    Parameters
    ----------
    batch : EngineBatch
        The engines (:func:`engine_batch`, :func:`stack_models`).
    counterweights : CounterweightOptions, optional
        Crank counterweights, the same for every engine.
    primary, secondary : ShaftOptions, optional
        Balance shafts at crank speed and at twice crank speed.
    orders : int
        Orders reported in the residuals (orders 1 and 2 always are).
    chunk : int
        Engines solved together.

    Returns
    -------
    BatchBalance
        Per engine: counterweight masses [kg] and directions [rad], shaft masses [kg] and
        phases [rad], residual forces [N] and moments [N·m] by order, and the check.

    Raises
    ------
    InputError
        As :func:`balance`, for the first engine it fails on; or a ``chunk`` below 1.

    References
    ----------
    Appl. Sci. 2021, Eqs. 1-23, with the errata of docs/references.md.
    """
    if primary is not None and primary.arrangement != "pair" and counterweights is None:
        raise _single_shaft_without_counterweights()
    out: Any = None  # _chunked gives one chunk or more
    for start, piece in _chunked(batch, chunk):
        try:
            part = _balance_chunk(piece, counterweights, primary, secondary, orders)
        except _EngineFailed as failed:
            e = failed.error
            raise InputError(
                e.field, e.value, f"{e.allowed} (engine {start + failed.engine} of the batch)"
            ) from None
        out = _gather(out, part, start, batch.size)
    return out


def check_batch(
    batch: EngineBatch, result: BatchBalance, chunk: int = BATCH_CHUNK
) -> BatchResiduals:
    """Residuals of the balancing masses in ``result`` on the engines of ``batch``.

    Recomputes the free forces and adds the forces of every counterweight and shaft mass
    from its reported mass, radius, phase and position: change a mass of ``result``
    (:func:`dataclasses.replace`) and the check shows what it leaves.

    Parameters
    ----------
    batch : EngineBatch
        The engines ``result`` was solved for.
    result : BatchBalance
        The balancing masses (from :func:`balance_batch`, possibly changed).
    chunk : int
        Engines checked together.

    Returns
    -------
    BatchResiduals
        Forces [N] and moments [N·m] before and after, per component, and the check.
    """
    orders = len(result.residuals.components) - 1
    out: Any = None  # _chunked gives one chunk or more
    for start, piece in _chunked(batch, chunk):
        got = _take(result, slice(start, start + piece.size))
        part = _residuals(
            piece,
            _chunk_forces(piece, orders),
            got.counterweights,
            got.rotating_share,
            got.extra_counterweights,
            got.primary,
            got.secondary,
        )
        out = _gather(out, part, start, batch.size)
    return out


class _EngineFailed(Exception):
    """An :class:`InputError` of one engine of a chunk (index within the chunk)."""

    def __init__(self, error: InputError, engine: int) -> None:
        super().__init__(str(error))
        self.error = error
        self.engine = engine


def _chunked(batch: EngineBatch, chunk: int) -> list[tuple[int, EngineBatch]]:
    if not (isinstance(chunk, int | np.integer) and chunk >= 1):
        raise InputError("chunk", chunk, "an integer of 1 or more")
    if batch.size <= chunk:
        return [(0, batch)]
    return [
        (start, batch.take(slice(start, start + chunk))) for start in range(0, batch.size, chunk)
    ]


def _take(obj: Any, index: slice | NDArray[np.int64]) -> Any:
    """The engines ``index`` of a batch dataclass (its ``PER_ENGINE`` arrays, recursively)."""
    return _per_engine(obj, lambda a: a[index])


def _per_engine(obj: Any, func: Callable[[NDArray], NDArray]) -> Any:
    """A batch dataclass with ``func`` applied to its ``PER_ENGINE`` arrays, recursively."""
    if obj is None:
        return None
    changes = {}
    for f in fields(obj):
        value = getattr(obj, f.name)
        if f.name in obj.PER_ENGINE and value is not None:
            changes[f.name] = func(value)
        elif hasattr(value, "PER_ENGINE"):
            changes[f.name] = _per_engine(value, func)
    return replace(obj, **changes)


def _gather(out: Any, part: Any, start: int, total: int) -> Any:
    """Put the chunk ``part`` (engines from ``start``) into ``out``, the result of all
    ``total`` engines (allocated from the first chunk; the first chunk is the result when
    it holds every engine)."""
    size = part.size if isinstance(part, BatchBalance) else part.balanced.size
    if out is None:
        if size == total:
            return part
        out = _per_engine(part, lambda a: np.empty((total, *a.shape[1:]), a.dtype))
    _fill(out, part, slice(start, start + size))
    return out


def _fill(out: Any, part: Any, index: slice) -> None:
    if out is None:
        return
    for f in fields(out):
        value = getattr(out, f.name)
        if f.name in out.PER_ENGINE and value is not None:
            value[index] = getattr(part, f.name)
        elif hasattr(value, "PER_ENGINE"):
            _fill(value, getattr(part, f.name), index)


@dataclass(frozen=True)
class _ChunkForces:
    """Free-force phasors (E, K), rotating first moments (E, T) and scales of a chunk."""

    forward: NDArray
    backward: NDArray
    couple_forward: NDArray
    couple_backward: NDArray
    rotating: NDArray
    scale: NDArray
    length: NDArray


def _chunk_forces(batch: EngineBatch, orders: int) -> _ChunkForces:
    """The free forces of every engine (:func:`free_forces`, stacked)."""
    topo = batch.topology
    r = batch.crank_radius
    ratio, offset = r / batch.rod_length, batch.cylinder_offset / r[:, None]
    if np.all(offset == offset[:, :1]):  # one offset per engine: coefficients per engine
        if np.all(ratio == ratio[0]) and np.all(offset == offset[0, 0]):  # computed once
            ratio, offset = ratio[:1], offset[:1]
        coeff = harmonic_coefficients(ratio, orders, offset[:, 0], topo.kinematics)  # type: ignore[arg-type]
        each = False
    else:  # per cylinder
        coeff = harmonic_coefficients(ratio[:, None], orders, offset, topo.kinematics)  # type: ignore[arg-type]
        each = True
    phasors = reciprocating_phasors(
        coeff,
        batch.reciprocating_mass,
        batch.throw_angle[:, topo.cylinder_throw],
        topo.cylinder_bank,
        topo.cylinder_position,
        r,
        batch.speed,
        per_cylinder=each,
    )
    scale, length = _scales(
        batch.throw_rotating_mass,
        batch.reciprocating_mass,
        r,
        batch.speed,
        topo.throw_position,
    )
    rotating = batch.throw_rotating_mass * r[:, None] * np.exp(1j * batch.throw_angle)
    return _ChunkForces(*phasors, rotating, scale, length)


def _balance_chunk(
    batch: EngineBatch,
    counterweights: CounterweightOptions | None,
    primary: ShaftOptions | None,
    secondary: ShaftOptions | None,
    orders: int,
) -> BatchBalance:
    """:func:`balance` for every engine of a chunk."""
    topo = batch.topology
    n, y = batch.size, topo.throw_position
    forces = _chunk_forces(batch, max(orders, 2))
    w = batch.speed
    w2 = w**2
    scale, length = forces.scale, forces.length
    size = scale / w2  # kg·m
    rot_moment = forces.rotating
    pins = np.zeros((topo.cylinders, topo.throws))
    pins[np.arange(topo.cylinders), topo.cylinder_throw] = 1.0
    rec_moment = (batch.reciprocating_mass @ pins) * batch.crank_radius[:, None]
    rec_moment = rec_moment * np.exp(1j * batch.throw_angle)
    fb = counterweights.balance_factor if counterweights else 0.0
    target = rot_moment + fb * rec_moment

    cw: BatchCounterweights | None = None
    share: NDArray | None = None
    webs: _Webs | None = None
    if counterweights is not None:
        whole_f, whole_c = target.sum(axis=-1), (target * y).sum(axis=-1)
        if counterweights.scope == "auto":
            balanced = (np.abs(whole_f) < ZERO * size) & (np.abs(whole_c) < ZERO * size * length)
            halves = balanced & (topo.throws % 2 == 0 and topo.throws >= 2)
        else:
            halves = np.full(n, counterweights.scope == "halves")
        webs = _web_geometry(batch, counterweights, length)
        cw = _counterweights_batch(
            batch, webs, counterweights, halves, whole_f, whole_c, target, size, length
        )
        moments = share = cw.moments
        if fb != 0.0:
            # the share that carries the rotating masses alone, at the same angle
            share = _counterweights_batch(
                batch,
                webs,
                counterweights,
                halves,
                rot_moment.sum(axis=-1),
                (rot_moment * y).sum(axis=-1),
                rot_moment,
                size,
                length,
                angle=cw.alpha,
            ).moments

    fwd1_f, fwd1_c = forces.forward[:, 0], forces.couple_forward[:, 0]
    if cw is not None and share is not None:
        beyond = (moments - share) * w2[:, None]
        fwd1_f = fwd1_f + beyond.sum(axis=-1)
        fwd1_c = fwd1_c + (beyond * cw.position).sum(axis=-1)

    extra: BatchCounterweights | None = None
    primary_set: BatchShafts | None = None
    if primary is not None:
        shafts = []
        if primary.arrangement == "pair":
            shafts.append(_shaft_batch(1, +1, fwd1_f, fwd1_c, primary, w, scale))
        elif counterweights is not None and webs is not None:
            opts = replace(counterweights, scope="whole", method="individual")
            extra = _counterweights_batch(
                batch, webs, opts, np.zeros(n, bool), fwd1_f / w2, fwd1_c / w2, None, size, length
            )
        shafts.append(
            _shaft_batch(
                1, -1, forces.backward[:, 0], forces.couple_backward[:, 0], primary, w, scale
            )
        )
        primary_set = _shaft_set(1, primary, shafts)

    secondary_set: BatchShafts | None = None
    if secondary is not None:
        shafts = []
        if secondary.arrangement == "pair":
            shafts.append(
                _shaft_batch(
                    2, +1, forces.forward[:, 1], forces.couple_forward[:, 1], secondary, w, scale
                )
            )
        shafts.append(
            _shaft_batch(
                2, -1, forces.backward[:, 1], forces.couple_backward[:, 1], secondary, w, scale
            )
        )
        secondary_set = _shaft_set(2, secondary, shafts)

    residuals = _residuals(batch, forces, cw, share, extra, primary_set, secondary_set)
    return BatchBalance(cw, extra, primary_set, secondary_set, share, residuals)


@dataclass(frozen=True)
class _Webs:
    """Counterweight webs of a chunk: throw (0-based) and number (1-based) of each web,
    positions (E, W) [m], and the groups of engines with the same positions over the
    crank length (the same equations)."""

    throw: NDArray
    number: NDArray
    position: NDArray
    groups: list[NDArray]


def _web_geometry(batch: EngineBatch, options: CounterweightOptions, length: NDArray) -> _Webs:
    """:func:`web_layout` of every engine, grouped by equal equations."""
    topo = batch.topology
    throw, side = _web_sides(topo.throws, options.webs)
    if options.web_offset is not None:
        offset = np.full(batch.size, float(options.web_offset))
    else:
        pitch = _throw_pitch(topo.throw_position)
        offset = np.full(batch.size, pitch / 4.0) if pitch is not None else batch.crank_radius / 2.0
    position = topo.throw_position[throw] + side * offset[:, None]
    normal = position / length[:, None]
    if np.all(normal == normal[:1]):
        groups = [np.arange(batch.size)]
    else:
        _, inverse = np.unique(normal, axis=0, return_inverse=True)
        inverse = inverse.reshape(-1)
        order = np.argsort(inverse, kind="stable")
        groups = np.split(order, np.cumsum(np.bincount(inverse))[:-1])
    number = 2 * throw + (side > 0) + 1
    return _Webs(throw, number, position, groups)


def _counterweights_batch(
    batch: EngineBatch,
    webs: _Webs,
    options: CounterweightOptions,
    halves: NDArray,
    force: NDArray,
    couple: NDArray,
    per_throw: NDArray | None,
    size: NDArray,
    length: NDArray,
    angle: NDArray | None = None,
) -> BatchCounterweights:
    """:func:`solve_counterweights` for every engine of a chunk.

    ``force`` and ``couple`` are the whole crank's targets (E,) [kg·m, kg·m²], ``per_throw``
    the per-throw first moments (E, T) the halves' targets are summed from; ``angle`` (E,)
    replaces the options' angle of the pattern.
    """
    topo = batch.topology
    n, count = batch.size, webs.throw.size
    mass = np.zeros((n, count))
    direction = np.zeros((n, count))
    alpha = np.zeros(n)
    flipped = np.zeros(n, bool)
    already = np.zeros(n, bool)
    for group in webs.groups:
        y = webs.position[group[0]]
        normal = y / length[group[0]]
        for scope in ("whole", "halves"):
            sub = group[halves[group] == (scope == "halves")]
            if not sub.size:
                continue
            parts = _parts(topo, scope, webs.throw)
            rows: list[NDArray] = []
            rhs: list[NDArray] = []
            targets = []
            for throw_mask, web_mask in parts:
                if scope == "whole" or per_throw is None:
                    f, c = force[sub], couple[sub]
                else:
                    t = per_throw[sub][:, throw_mask]
                    f, c = t.sum(axis=-1), (t * topo.throw_position[throw_mask]).sum(axis=-1)
                targets.append((web_mask, f, c))
                rows += [np.where(web_mask, 1.0, 0.0), np.where(web_mask, normal, 0.0)]
                rhs += [-f, -c / length[sub]]
            a = np.array(rows)
            b = np.stack(rhs, axis=-1)
            still = np.abs(b).max(axis=-1, initial=0.0) < ZERO * size[sub]
            already[sub] = still
            live = ~still
            if not live.any():
                continue
            _check_planes(webs, options, sub, live, targets, size[sub], length[sub])
            engines, b = sub[live], b[live]
            if options.method == "individual":
                # least sum |v|^2 among exact solutions, the cut-off of np.linalg.lstsq
                pinv = np.linalg.pinv(a, rcond=np.finfo(float).eps * max(a.shape))
                v = b @ pinv.T
                mass[engines] = np.abs(v) / options.cg_radius
                direction[engines] = np.where(mass[engines] > 0, np.angle(v), 0.0)
                continue
            opposite = batch.throw_angle[engines][:, webs.throw] + np.pi
            middle = _middle(topo.throw_position) / length[group[0]]
            side = np.sign(np.round(normal - middle, 12))
            if angle is None and options.angle == "optimal":
                turn, m_c = _optimal_patterns(a, b, opposite, side)
            else:
                fixed = options.angle if angle is None else angle[engines]
                turn = np.broadcast_to(np.asarray(fixed, dtype=float), engines.shape)
                m_c = _pattern_moments(a, b, opposite, side, turn)
            flip = m_c < 0  # the pattern points the wrong way: flip it
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
    webs: _Webs,
    options: CounterweightOptions,
    sub: NDArray,
    live: NDArray,
    targets: list[tuple[NDArray, NDArray, NDArray]],
    size: NDArray,
    length: NDArray,
) -> None:
    """The one-engine solver's errors: a part without counterweight, or all its
    counterweights in one plane while a couple is to be cancelled."""
    for web_mask, force, couple in targets:
        planes = np.unique(np.round(webs.position[sub[0]][web_mask], 12))
        if planes.size == 0:
            raise _EngineFailed(_no_counterweight(options), int(sub[live][0]))
        if planes.size == 1:
            plane = np.round(webs.position[sub][:, web_mask][:, 0], 12)
            bad = live & (np.abs(couple - plane * force) > ZERO * size * length)
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                raise _EngineFailed(_one_plane(options, float(plane[i])), int(sub[i]))


def _pattern_moments(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray, alpha: NDArray
) -> NDArray:
    """:func:`pattern_masses` (the moment) with one angle, right-hand side and crank per
    engine: a (Q, W), b (E, Q), opposite (E, W), side (W,), alpha (E,)."""
    unit = np.exp(1j * (opposite + side * alpha[:, None]))
    coeff = unit @ a.T
    num = np.real(np.sum(np.conj(coeff) * b, axis=-1))
    den = np.sum(np.abs(coeff) ** 2, axis=-1)
    safe = den > 1e-300
    return np.where(safe, num / np.where(safe, den, 1.0), 0.0)


def _optimal_patterns(
    a: NDArray, b: NDArray, opposite: NDArray, side: NDArray
) -> tuple[NDArray, NDArray]:
    """:func:`_optimal_pattern` for every engine: turn angles and first moments (E,)."""
    if np.any(side == 0):
        found = [
            _optimal_pattern(a.astype(complex), b[i], opposite[i], side) for i in range(len(b))
        ]
        return np.array([f[0] for f in found]), np.array([f[1] for f in found])
    base = np.exp(1j * opposite)
    cx = base @ a.T
    cy = (1j * side * base) @ a.T
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
    solution.
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
        (x1[i], x2[i]), *_ = np.linalg.lstsq(matrix[i], rhs[i], rcond=None)
    return x1, x2


def _shaft_batch(
    order: int,
    sense: int,
    force: NDArray,
    couple: NDArray,
    options: ShaftOptions,
    speed: NDArray,
    scale: NDArray,
) -> tuple[int, NDArray, NDArray]:
    """:func:`solve_shaft` for every engine: sense, layout (E,) and the complex unknowns
    :math:`m e^{i\\psi}` (E, 3) [kg] in the slots at -l/2, 0, +l/2."""
    gain = options.cg_radius * (order * speed) ** 2
    has_force = np.abs(force) > ZERO * scale
    has_couple = np.abs(couple) > ZERO * scale * options.length
    half = options.length / 2
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


def _residuals(
    batch: EngineBatch,
    forces: _ChunkForces,
    cw: BatchCounterweights | None,
    share: NDArray | None,
    extra: BatchCounterweights | None,
    primary: BatchShafts | None,
    secondary: BatchShafts | None,
) -> BatchResiduals:
    """Forces and moments before and after the balancing masses, from the reported masses
    (:func:`verify` in the frequency domain)."""
    w2 = batch.speed**2
    y = batch.topology.throw_position
    rot_f = w2 * forces.rotating.sum(axis=-1)
    rot_c = w2 * (forces.rotating * y).sum(axis=-1)
    after_rot_f, after_rot_c = rot_f, rot_c
    fwd, bwd = forces.forward.copy(), forces.backward.copy()
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
        gain = group.cg_radius * (group.order * batch.speed) ** 2
        for s, sense in enumerate(group.sense):
            f = group.mass[:, s] * gain[:, None] * np.exp(1j * group.phase[:, s])
            force, couple = (fwd, cfwd) if sense > 0 else (bwd, cbwd)
            force[:, k] += f.sum(axis=-1)
            couple[:, k] += (f * group.position).sum(axis=-1)
    scale = forces.scale[:, None]
    moment_scale = scale * forces.length[:, None]

    def amplitude(first: NDArray, forward: NDArray, backward: NDArray, limit: NDArray) -> NDArray:
        """Columns rotating and orders 1..K; 0 below round-off of the scale (as verify)."""
        value = np.column_stack([np.abs(first), np.abs(forward) + np.abs(backward)])
        return np.where(value < 1e-13 * limit, 0.0, value)

    force_before = amplitude(rot_f, forces.forward, forces.backward, scale)
    moment_before = amplitude(rot_c, forces.couple_forward, forces.couple_backward, moment_scale)
    force_after = amplitude(after_rot_f, fwd, bwd, scale)
    moment_after = amplitude(after_rot_c, cfwd, cbwd, moment_scale)
    orders = fwd.shape[1]
    targeted = np.array(
        [cw is not None, primary is not None, secondary is not None] + [False] * (orders - 2)
    )
    balanced = np.all(
        ~targeted
        | (
            (force_after <= CHECK_TOLERANCE * scale)
            & (moment_after <= CHECK_TOLERANCE * moment_scale)
        ),
        axis=-1,
    )
    components = ("rotating",) + tuple(f"order{k}" for k in range(1, orders + 1))
    return BatchResiduals(
        components, targeted, force_before, force_after, moment_before, moment_after, balanced
    )
