r"""Main-bearing loads of a whole crankshaft over the engine cycle, and its internal bending.

This module owns the crank as a beam on its main bearings:

* :func:`crank_loads` -- the point loads on the crank over the cycle: the force the rods
  put on each crankpin (gas and reciprocating inertia, from the engine cycle), the
  d'Alembert force of each throw's rotating masses and of each counterweight.
* :func:`default_bearing_positions` -- one main bearing between neighbouring throws and
  one at each end (``T + 1`` bearings).
* :class:`CrankSection` and :func:`crank_stiffness` -- the bending stiffness along the
  crank, piecewise constant: journals, webs and crankpins (an equivalent-stiffness
  *approximation*, see :func:`crank_stiffness`).
* Two crank models: :func:`determinate_reactions` (each throw carried by its two
  neighbouring bearings, lever rule) and :func:`continuous_beam_reactions` (a continuous
  Euler-Bernoulli beam on all bearings, rigid or elastic, solved exactly by the force
  method with the piecewise-constant stiffness).
* :func:`main_bearing_loads` -- both put together: per bearing the load over the cycle
  (polar diagram), its largest and mean magnitude and the cubic-mean equivalent load, the
  bending moment at every journal and crankpin, and (:func:`bearing_friction`) the
  friction of each bearing through :mod:`crankbalance.physics.friction`.

Frames and signs (those of :mod:`crankbalance.physics.shaking` and
:mod:`crankbalance.physics.model`):
``y`` along the crank axis from the crank's mid-point, lateral vectors as complex numbers
:math:`z + i\,x`; crank angle :math:`\theta` of the first throw, a point of the crank at
angle :math:`\psi` (at :math:`\theta = 0`) sits at :math:`e^{i(\theta + \psi)}`. A *load*
is a force applied to the crank; a *bearing load* is the force the crank puts on the
bearing (the negative of the bearing's reaction on the crank), so that the bearing loads
add up to the loads. The bending moment at a station ``y`` is
:math:`M(y) = \sum_{y_P < y} P\,(y - y_P)` over the loads and reactions left of it (the
convention of :func:`crankbalance.physics.beam.bending_moment_at`), a complex number whose real
part is the moment of the z-components (bending in the y-z plane) and imaginary part that
of the x-components; its magnitude is the resultant bending moment.

Why one module over 800 lines: the loads, the stiffness and the three ways to carry them
(lever rule, continuous beam, clearance contact) are one model, the crank as a beam on its
bearings; each crank model takes the same loads and stiffness and gives the same result.

References
----------
J. M. Gere, S. P. Timoshenko, *Mechanics of Materials* (lever rule, force method,
three-moment equation, singularity functions); Hoem and Røsholm (2016), Sec. 4.2
(friction from the bearing load).
"""

from __future__ import annotations

import math
from dataclasses import field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_positive
from ..records import record
from ..results import ROUND_OFF, ResultMixin, below_round_off
from .beam import bending_moment_at
from .friction import friction_torque, petroff_torque

CrankModel = Literal["determinate", "indeterminate"]
CRANK_MODELS: tuple[str, ...] = ("determinate", "indeterminate")

#: relative tolerance of the position checks (a bearing at a throw, webs that touch)
_TINY = 1e-9
#: throws closer than this along the crank share one plane (:func:`crank_planes`) [m]
PLANE_TOLERANCE = 1e-6


# --------------------------------------------------------------------------------------
# Loads on the crank
# --------------------------------------------------------------------------------------


@record
class CrankLoads(ResultMixin):
    """Point loads on the crank over the cycle (input of the two crank models).

    Parameters
    ----------
    angle : ndarray, shape (S,)
        Crank angle of the first throw [rad].
    position : ndarray, shape (L,)
        Axial position of each load [m from the crank's mid-point].
    throw : ndarray of int, shape (L,)
        Index (0-based) of the throw each load belongs to.
    kind : tuple of str
        ``"throw"`` (crankpin force plus the throw's rotating masses, at the throw
        mid-plane) or ``"counterweight"``, per load.
    load : ndarray of complex, shape (L, S)
        Force applied to the crank, :math:`z + i x` [N].
    """

    angle: NDArray[np.float64] = field(repr=False)
    position: NDArray[np.float64]
    throw: NDArray[np.int64]
    kind: tuple[str, ...]
    load: NDArray[np.complex128] = field(repr=False)

    @property
    def total(self) -> NDArray[np.complex128]:
        """Sum of the loads at every angle [N]."""
        return np.asarray(self.load.sum(axis=0))


def _vector(name: str, value: ArrayLike, size: int | None = None) -> NDArray[np.float64]:
    """A finite 1-D float array (of ``size`` entries when given), else InputError."""
    array = np.atleast_1d(np.asarray(value, dtype=float))
    if array.ndim != 1 or not np.all(np.isfinite(array)):
        raise InputError(name, np.asarray(value).tolist(), "must be a list of finite numbers")
    if size is not None and array.size != size:
        raise InputError(name, array.tolist(), f"needs {size} entries")
    return array


def crank_loads(
    angle: ArrayLike,
    throw_force: ArrayLike,
    throw_angle: ArrayLike,
    throw_position: ArrayLike,
    throw_rotating_mass: ArrayLike,
    crank_radius: float,
    speed: ArrayLike,
    acceleration: ArrayLike | None = None,
    counterweight_mass: ArrayLike = (),
    counterweight_radius: float = 0.0,
    counterweight_direction: ArrayLike = (),
    counterweight_position: ArrayLike = (),
    counterweight_throw: ArrayLike = (),
) -> CrankLoads:
    r"""The point loads on the crank over the cycle.

    A mass :math:`m` at radius :math:`\rho` and angle :math:`\psi` (at crank angle 0)
    turning with the crank at speed :math:`\omega` and acceleration :math:`\alpha` needs
    the force :math:`m\ddot{\mathbf r} = m\rho(i\alpha - \omega^2)e^{i(\theta+\psi)}`; the
    bearings supply it, so it enters as the d'Alembert load
    :math:`m\rho(\omega^2 - i\alpha)e^{i(\theta+\psi)}`. Per throw ``t`` (at its mid-plane
    :math:`y_t`): the crankpin force plus that of its rotating masses (crankpin, webs
    reduced to the crank radius, big ends: ``model.throw_rotating_mass``); per
    counterweight: its own, at its web.

    Parameters
    ----------
    angle : array_like, shape (S,)
        Crank angle of the first throw [rad].
    throw_force : array_like of complex, shape (T, S)
        Force the conrods put on each crankpin, :math:`z + i x` [N] (gas and reciprocating
        inertia through the rods; without the throw's rotating masses and counterweights).
    throw_angle : array_like, shape (T,)
        Angle of each throw at crank angle 0 [rad].
    throw_position : array_like, shape (T,)
        Axial position of each throw [m].
    throw_rotating_mass : array_like, shape (T,)
        Rotating mass of each throw at the crank radius [kg].
    crank_radius : float
        Crank radius [m].
    speed : array_like, shape (S,) or scalar
        Crank speed [rad/s].
    acceleration : array_like, shape (S,) or scalar, optional
        Crank angular acceleration [rad/s^2]; None for none.
    counterweight_mass : array_like, shape (W,)
        Counterweight masses at ``counterweight_radius`` [kg].
    counterweight_radius : float
        Radius of their centre of gravity [m].
    counterweight_direction : array_like, shape (W,)
        Their direction at crank angle 0, from +z toward +x [rad].
    counterweight_position : array_like, shape (W,)
        Their axial positions (web planes) [m].
    counterweight_throw : array_like of int, shape (W,)
        Index (0-based) of the throw of each counterweight's web [-].

    Returns
    -------
    CrankLoads
        T throw loads, then W counterweight loads.
    """
    theta = _vector("angle", angle)
    s = theta.size
    y = _vector("throw_position", throw_position)
    t = y.size
    phi = _vector("throw_angle", throw_angle, t)
    m_rot = _vector("throw_rotating_mass", throw_rotating_mass, t)
    if np.any(m_rot < 0):
        raise InputError("throw_rotating_mass", m_rot.tolist(), "must be masses >= 0 kg")
    check_positive("crank_radius", crank_radius)
    pin = np.asarray(throw_force, dtype=complex)
    if pin.shape != (t, s) or not np.all(np.isfinite(pin)):
        raise InputError(
            "throw_force",
            f"array of shape {pin.shape}",
            f"must be finite forces of shape ({t}, {s}): one row per throw, one column "
            "per crank angle",
        )
    w = np.broadcast_to(np.asarray(speed, dtype=float), (s,))
    if not np.all(np.isfinite(w)) or np.any(w < 0):
        raise InputError("speed", np.asarray(speed).tolist(), "must be finite speeds >= 0 rad/s")
    a = np.zeros(s) if acceleration is None else np.asarray(acceleration, dtype=float)
    a = np.broadcast_to(a, (s,))
    if not np.all(np.isfinite(a)):
        raise InputError("acceleration", "non-finite", "must be finite [rad/s^2]")
    factor = (w**2 - 1j * a) * np.exp(1j * theta)  # (S,)
    rotating = (m_rot * crank_radius * np.exp(1j * phi))[:, None] * factor
    m_cw = _vector("counterweight_mass", counterweight_mass)
    n_cw = m_cw.size
    if n_cw and np.any(m_cw < 0):
        raise InputError("counterweight_mass", m_cw.tolist(), "must be masses >= 0 kg")
    psi = _vector("counterweight_direction", counterweight_direction, n_cw)
    y_cw = _vector("counterweight_position", counterweight_position, n_cw)
    cw_throw = np.atleast_1d(np.asarray(counterweight_throw, dtype=np.int64))
    if cw_throw.size != n_cw or (n_cw and (cw_throw.min() < 0 or cw_throw.max() >= t)):
        raise InputError(
            "counterweight_throw",
            cw_throw.tolist(),
            f"needs {n_cw} throw indices from 0 to {t - 1}",
        )
    if n_cw:
        check_positive("counterweight_radius", counterweight_radius)
    cw = (m_cw * counterweight_radius * np.exp(1j * psi))[:, None] * factor
    return CrankLoads(
        angle=theta,
        position=np.concatenate([y, y_cw]),
        throw=np.concatenate([np.arange(t), cw_throw]).astype(np.int64),
        kind=("throw",) * t + ("counterweight",) * n_cw,
        load=np.concatenate([pin + rotating, cw]).reshape(t + n_cw, s),
    )


def crank_planes(throw_position: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The axial planes of a crank's throws: throws closer than ``PLANE_TOLERANCE`` share one.

    Throws of different banks can sit in one plane (a W engine built from VR banks: two
    throws at every axial position); the crank then has one throw's length, webs and
    bearing bay per plane, and the loads of the throws in a plane act together there.

    Parameters
    ----------
    throw_position : array_like, shape (T,)
        Axial positions of the throws, in any order [m].

    Returns
    -------
    planes : ndarray, shape (P,)
        Axial position of each plane, ascending [m] (the mean of its throws).
    plane_of_throw : ndarray of int, shape (T,)
        Plane (0-based) of each throw [-].
    """
    y = _vector("throw_position", throw_position)
    order = np.argsort(y, kind="stable")
    new_plane = np.diff(y[order]) > PLANE_TOLERANCE
    plane_sorted = np.concatenate([[0], np.cumsum(new_plane)]).astype(np.int64)
    plane_of_throw = np.empty(y.size, dtype=np.int64)
    plane_of_throw[order] = plane_sorted
    count = np.bincount(plane_of_throw)
    planes = np.bincount(plane_of_throw, weights=y) / count
    return planes, plane_of_throw


def default_bearing_positions(throw_position: ArrayLike, end_overhang: float) -> NDArray:
    """One main bearing between neighbouring throw planes and one at each end (``P + 1``).

    Throws in one axial plane (:func:`crank_planes`) share their bay. Between two planes
    the bearing sits at the mid-point; the end bearings sit half the smallest plane pitch
    beyond the end planes (``end_overhang`` beyond them for a single plane).

    Parameters
    ----------
    throw_position : array_like, shape (T,)
        Axial positions of the throws, in any order [m].
    end_overhang : float
        Distance of an end bearing from a single throw [m] (only used for T = 1).

    Returns
    -------
    ndarray, shape (P + 1,)
        Bearing positions, ascending [m] (P the number of throw planes).
    """
    y = crank_planes(throw_position)[0]
    if y.size == 1:
        d = check_positive("end_overhang", end_overhang)
        return np.array([y[0] - d, y[0] + d])
    gaps = np.diff(y)
    half = 0.5 * float(gaps.min())
    return np.concatenate([[y[0] - half], 0.5 * (y[1:] + y[:-1]), [y[-1] + half]])


def _check_bearing_positions(bearings: ArrayLike) -> NDArray:
    """Bearing positions: at least two, finite and distinct; returned as given (order kept)."""
    xb = _vector("bearing_positions", bearings)
    if xb.size < 2:
        raise InputError("bearing_positions", xb.tolist(), "needs at least two bearings")
    span = max(float(np.ptp(xb)), 1e-30)
    if np.any(np.diff(np.sort(xb)) <= _TINY * span):
        raise InputError("bearing_positions", xb.tolist(), "needs each bearing at its own position")
    return xb


# --------------------------------------------------------------------------------------
# Crank stiffness: the equivalent stepped beam (approximation)
# --------------------------------------------------------------------------------------


@record
class CrankSection(ResultMixin):
    r"""Dimensions and material of a crank, for its equivalent bending stiffness.

    Parameters
    ----------
    journal_diameter : float
        Main-journal diameter :math:`D_j` [m].
    pin_diameter : float
        Crankpin diameter :math:`D_p` [m].
    web_thickness : float
        Axial thickness :math:`h` of each web [m].
    web_width : float
        Width :math:`b` of each web across the crank arm [m].
    youngs_modulus : float
        Young's modulus :math:`E` [Pa] (steel 210 GPa, nodular cast iron about 170 GPa).
    poisson_ratio : float
        Poisson's ratio :math:`\nu` [-], for :math:`G = E/(2(1+\nu))`.
    """

    journal_diameter: float
    pin_diameter: float
    web_thickness: float
    web_width: float
    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3

    def __post_init__(self) -> None:
        for name in ("journal_diameter", "pin_diameter", "web_thickness", "web_width"):
            check_positive(name, getattr(self, name))
        check_positive("youngs_modulus", self.youngs_modulus)
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise InputError("poisson_ratio", self.poisson_ratio, "must lie between -1 and 0.5")

    @property
    def journal_stiffness(self) -> float:
        r""":math:`E\,\pi D_j^4/64` [N m^2]."""
        return self.youngs_modulus * math.pi * self.journal_diameter**4 / 64

    @property
    def pin_stiffness(self) -> float:
        r""":math:`E\,\pi D_p^4/64` [N m^2]."""
        return self.youngs_modulus * math.pi * self.pin_diameter**4 / 64

    def web_stiffness(self, crank_radius: float) -> float:
        r"""Equivalent bending stiffness of a web over its thickness [N m^2].

        A bending moment of the crank passes a web as out-of-plane bending of the web
        (moment across the crank arm, :math:`E I_w`, :math:`I_w = b h^3/12`) or as
        twisting of the web (moment along the arm, :math:`G J_w`,
        :math:`J_w \approx b h^3/3` for :math:`b \gg h`), each over the arm length
        :math:`r`. Averaging the two compliances over the direction of the moment (the
        crank turns under the loads) and spreading the result over the web thickness
        :math:`h` gives

        .. math:: (EI)_w = \frac{h}{\tfrac{r}{2}\left(\frac{1}{E I_w}
                  + \frac{1}{G J_w}\right)}

        capped at the journal's stiffness (a stubby web is not softer than its journal).

        Parameters
        ----------
        crank_radius : float
            Crank radius :math:`r`, the length of the arm [m].

        Returns
        -------
        float
            :math:`(EI)_w` [N m^2].
        """
        r = check_positive("crank_radius", crank_radius)
        e = self.youngs_modulus
        g = e / (2 * (1 + self.poisson_ratio))
        b, h = self.web_width, self.web_thickness
        compliance = 0.5 * r * (12 / (e * b * h**3) + 3 / (g * b * h**3))
        return min(h / compliance, self.journal_stiffness)


@record
class CrankStiffness(ResultMixin):
    """Piecewise-constant bending stiffness along the crank.

    Parameters
    ----------
    edges : ndarray, shape (K + 1,)
        Segment boundaries along the crank, ascending [m].
    stiffness : ndarray, shape (K,)
        Bending stiffness EI of each segment [N m^2].
    """

    edges: NDArray[np.float64]
    stiffness: NDArray[np.float64]

    def __post_init__(self) -> None:
        e = _vector("edges", self.edges)
        k = _vector("stiffness", self.stiffness, e.size - 1)
        if e.size < 2 or np.any(np.diff(e) <= 0):
            raise InputError("edges", e.tolist(), "must be at least two ascending positions")
        if np.any(k <= 0):
            raise InputError("stiffness", k.tolist(), "must be positive [N m^2]")

    def at(self, y: ArrayLike) -> NDArray:
        """Stiffness at stations ``y`` (the segment's to the right of an edge).

        Parameters
        ----------
        y : array_like
            Stations along the crank [m].

        Returns
        -------
        ndarray
            EI at ``y`` [N m^2].
        """
        index = np.clip(
            np.searchsorted(self.edges, y, side="right") - 1, 0, self.stiffness.size - 1
        )
        return np.asarray(self.stiffness[index])


def uniform_stiffness(start: float, end: float, bending_stiffness: float) -> CrankStiffness:
    """One bending stiffness from ``start`` to ``end`` (a uniform beam).

    Parameters
    ----------
    start, end : float
        Ends of the beam [m].
    bending_stiffness : float
        EI [N m^2].

    Returns
    -------
    CrankStiffness
        One segment.
    """
    check_positive("bending_stiffness", bending_stiffness)
    return CrankStiffness(np.array([float(start), float(end)]), np.array([bending_stiffness]))


def crank_stiffness(
    throw_position: ArrayLike,
    web_offset: float,
    crank_radius: float,
    section: CrankSection,
    start: float,
    end: float,
) -> CrankStiffness:
    r"""Bending stiffness along a crank as a stepped straight beam (an approximation).

    Around each throw ``t`` (mid-plane :math:`y_t`) the two webs occupy
    :math:`o - h/2 \le |y - y_t| \le o + h/2` (``o`` the web offset, ``h`` the web
    thickness) with :meth:`CrankSection.web_stiffness`, the crankpin the stretch between
    them with :math:`E\pi D_p^4/64`, and the journals everything else with
    :math:`E\pi D_j^4/64`. The crankpin's offset from the journal axis is not modelled
    (the beam is straight), nor shear or the fillets: an equivalent-stiffness model,
    labelled as such wherever it is reported; the reactions it gives are checked against
    a finite-element model of the same stepped beam (tests), not against a crank.

    Parameters
    ----------
    throw_position : array_like, shape (T,)
        Axial positions of the throws [m]; throws in one plane (:func:`crank_planes`)
        share their webs and crankpin length.
    web_offset : float
        Axial distance of each web's mid-plane from its throw's mid-plane [m].
    crank_radius : float
        Crank radius (the web's arm) [m].
    section : CrankSection
        Dimensions and material.
    start, end : float
        Ends of the beam (covering every bearing and load) [m].

    Returns
    -------
    CrankStiffness
        Segments and their EI.
    """
    y = crank_planes(throw_position)[0]
    o = check_positive("web_offset", web_offset)
    h = section.web_thickness
    if h >= 2 * o:
        raise InputError(
            "web_thickness",
            h,
            f"must be less than twice the web offset ({2 * o:g} m): the two webs of a "
            "throw would overlap and leave no crankpin",
        )
    if y.size > 1 and np.any(np.diff(y) < 2 * o + h - _TINY * o):
        raise InputError(
            "web_thickness",
            h,
            "makes the webs of neighbouring throws overlap: the throw pitch must be at least "
            "twice the web offset plus the web thickness",
        )
    if not end > start:
        raise InputError("end", end, f"must be greater than start ({start:g} m)")
    faces = np.concatenate([y - o - h / 2, y - o + h / 2, y + o - h / 2, y + o + h / 2])
    edges = np.unique(np.concatenate([[start, end], faces[(faces > start) & (faces < end)]]))
    mid = 0.5 * (edges[1:] + edges[:-1])
    distance = np.min(np.abs(mid[:, None] - y[None, :]), axis=1)
    stiffness = np.where(
        distance < o - h / 2,
        section.pin_stiffness,
        np.where(
            distance <= o + h / 2, section.web_stiffness(crank_radius), section.journal_stiffness
        ),
    )
    return CrankStiffness(edges, stiffness.astype(float))


# --------------------------------------------------------------------------------------
# The two crank models
# --------------------------------------------------------------------------------------


def determinate_reactions(
    bearing_positions: ArrayLike,
    throw_position: ArrayLike,
    load_position: ArrayLike,
    load_throw: ArrayLike,
    loads: ArrayLike,
) -> NDArray[np.complex128]:
    r"""Bearing reactions of the statically determinate crank (lever rule per throw).

    Every throw, with its loads, is a beam simply supported on its two neighbouring
    bearings (the nearest on either side of the throw's mid-plane, :math:`y_l < y_t <
    y_r`): a load :math:`P` at :math:`y` gives

    .. math:: R_l = -P\,\frac{y_r - y}{y_r - y_l},\qquad R_r = -P\,\frac{y - y_l}{y_r - y_l}

    The crank acts as if hinged at every bearing in this model: its bending moment at a
    bearing is zero when every load lies between its own throw's two bearings.

    Parameters
    ----------
    bearing_positions : array_like, shape (B,)
        Bearing positions [m].
    throw_position : array_like, shape (T,)
        Axial positions of the throws [m].
    load_position : array_like, shape (L,)
        Axial positions of the loads [m].
    load_throw : array_like of int, shape (L,)
        Throw (0-based) of each load [-].
    loads : array_like of complex, shape (L, S)
        Loads on the crank [N].

    Returns
    -------
    ndarray of complex, shape (B, S)
        Reaction of each bearing on the crank [N].
    """
    xb = _check_bearing_positions(bearing_positions)
    yt = _vector("throw_position", throw_position)
    yl = _vector("load_position", load_position)
    tl = np.asarray(load_throw, dtype=np.int64)
    p = np.asarray(loads, dtype=complex)
    p = p.reshape(yl.size, -1)
    reactions = np.zeros((xb.size, p.shape[1]), dtype=complex)
    for t, y in enumerate(yt):
        left = np.flatnonzero(xb < y)
        right = np.flatnonzero(xb > y)
        if not left.size or not right.size:
            raise InputError(
                "bearing_positions",
                xb.tolist(),
                f"needs a bearing on each side of every throw for the determinate model "
                f"(throw {t + 1} at {y:g} m has none on one side)",
            )
        i = left[np.argmax(xb[left])]
        j = right[np.argmin(xb[right])]
        span = xb[j] - xb[i]
        mine = tl == t
        share = (xb[j] - yl[mine]) / span
        reactions[i] -= (share[:, None] * p[mine]).sum(axis=0)
        reactions[j] -= ((1 - share)[:, None] * p[mine]).sum(axis=0)
    return reactions


def _influence(x: NDArray, p: NDArray, stiffness: CrankStiffness) -> NDArray:
    r"""Deflection at ``x`` of a unit load at ``p`` (no rigid-body line), piecewise EI.

    .. math:: g(x, p) = \int_p^x \frac{(x - s)(s - p)}{EI(s)}\,ds \quad (x > p),
              \qquad 0 \text{ otherwise}

    integrated exactly segment by segment (the uniform case is :math:`(x-p)^3/6EI`).
    """
    x_, p_ = np.broadcast_arrays(np.asarray(x, float), np.asarray(p, float))
    s0 = stiffness.edges[:-1]
    s1 = stiffness.edges[1:]
    xx = x_[..., None]
    pp = p_[..., None]
    u = np.maximum(pp, s0) - pp  # local coordinates from the load
    v = np.minimum(xx, s1) - pp
    big_x = xx - pp
    part = big_x * (v**2 - u**2) / 2 - (v**3 - u**3) / 3
    part = np.where(v > u, part, 0.0) / stiffness.stiffness
    return np.asarray(part.sum(axis=-1))


def continuous_beam_reactions(
    bearing_positions: ArrayLike,
    load_position: ArrayLike,
    loads: ArrayLike,
    stiffness: CrankStiffness,
    bearing_stiffness: ArrayLike | None = None,
) -> NDArray[np.complex128]:
    r"""Bearing reactions of the crank as a continuous beam on all bearings (exact).

    The crank is a free Euler-Bernoulli beam with piecewise-constant :math:`EI(y)` loaded
    by the point loads :math:`P_j` and the reactions :math:`R_k`. Its deflection is

    .. math:: w(y) = a + b\,y + \sum_P P\,g(y, y_P),\qquad
              g(y, p) = \int_p^y \frac{(y-s)(s-p)}{EI(s)}\,ds\ (y > p)

    and the unknowns :math:`R_k, a, b` follow from force and moment equilibrium and
    :math:`w(y_k) = -R_k/k_k` at every bearing (:math:`k_k` infinite for rigid bearings):
    the force method, with the flexibility integrals done exactly per segment. With a
    uniform EI this is :func:`crankbalance.physics.beam.beam_statics` (Euler-Bernoulli).

    Parameters
    ----------
    bearing_positions : array_like, shape (B,)
        Bearing positions [m].
    load_position : array_like, shape (L,)
        Axial positions of the loads [m].
    loads : array_like of complex, shape (L, S)
        Loads on the crank [N].
    stiffness : CrankStiffness
        EI along the crank; must cover every bearing and load.
    bearing_stiffness : float or array_like, shape (B,), optional
        Radial stiffness of each bearing [N/m]; None for rigid bearings.

    Returns
    -------
    ndarray of complex, shape (B, S)
        Reaction of each bearing on the crank [N].
    """
    xb = _check_bearing_positions(bearing_positions)
    yl = _vector("load_position", load_position)
    p = np.asarray(loads, dtype=complex).reshape(yl.size, -1)
    lo, hi = stiffness.edges[0], stiffness.edges[-1]
    for name, values in (("bearing_positions", xb), ("load_position", yl)):
        outside = values[(values < lo - _TINY * (hi - lo)) | (values > hi + _TINY * (hi - lo))]
        if outside.size:
            raise InputError(
                name, float(outside[0]), f"must lie on the crank beam, from {lo:g} to {hi:g} m"
            )
    nb = xb.size
    if bearing_stiffness is None:
        compliance = np.zeros(nb)
    else:
        k = np.broadcast_to(np.asarray(bearing_stiffness, dtype=float), (nb,))
        if not np.all(np.isfinite(k)) or np.any(k <= 0):
            raise InputError(
                "bearing_stiffness",
                np.asarray(bearing_stiffness).tolist(),
                "must be positive finite stiffnesses [N/m]",
            )
        compliance = 1.0 / k
    # scale the rigid-body unknowns so the system is well conditioned
    length = max(float(hi - lo), 1e-30)
    flex = _influence(xb[:, None], xb[None, :], stiffness)
    scale = max(float(np.abs(flex).max()), float(compliance.max()), 1e-300)
    n = nb + 2
    mat = np.zeros((n, n))
    mat[0, :nb] = 1.0
    mat[1, :nb] = (xb - lo) / length
    mat[2:, :nb] = (flex + np.diag(compliance)) / scale
    mat[2:, nb] = 1.0
    mat[2:, nb + 1] = (xb - lo) / length
    rhs = np.zeros((n, p.shape[1]), dtype=complex)
    rhs[0] = -p.sum(axis=0)
    rhs[1] = -(((yl - lo) / length)[:, None] * p).sum(axis=0)
    rhs[2:] = -(_influence(xb[:, None], yl[None, :], stiffness) / scale) @ p
    sol = np.linalg.solve(mat, np.concatenate([rhs.real, rhs.imag], axis=1))
    half = p.shape[1]
    return np.asarray(sol[:nb, :half] + 1j * sol[:nb, half:])


def condensed_stiffness(
    bearing_positions: ArrayLike,
    load_position: ArrayLike,
    stiffness: CrankStiffness,
) -> tuple[NDArray, NDArray]:
    r"""The free crank beam condensed onto its bearing points (exact for point loads).

    Euler-Bernoulli beam elements (:func:`crankbalance.physics.beam.element_matrices`, cubic
    Hermite, exact between point loads for a piecewise-constant EI) with a node at every
    stiffness step, bearing and load; static condensation onto the bearings' deflections
    :math:`u_B`: with the applied loads :math:`f`,

    .. math:: R = K_c\,u_B - L f,\qquad K_c = K_{BB} - K_{BI}K_{II}^{-1}K_{IB},\quad
              L f = f_B - K_{BI}K_{II}^{-1}f_I

    where ``R`` are the forces the bearings put on the crank.

    Parameters
    ----------
    bearing_positions : array_like, shape (B,)
        Bearing positions [m].
    load_position : array_like, shape (L,)
        Positions of the loads [m].
    stiffness : CrankStiffness
        EI along the crank; must cover every bearing and load.

    Returns
    -------
    condensed : ndarray, shape (B, B)
        :math:`K_c` [N/m].
    transfer : ndarray, shape (B, L)
        :math:`L`, the loads carried over to the bearing points [-].
    """
    from .beam import ShaftSection, element_matrices

    xb = _check_bearing_positions(bearing_positions)
    yl = _vector("load_position", load_position)
    nodes = np.unique(np.concatenate([stiffness.edges, xb, yl]))
    n = nodes.size
    k = np.zeros((2 * n, 2 * n))
    modulus = 210e9  # any: the section below is chosen to give the segment's EI
    for e in range(n - 1):
        ei = float(stiffness.at(0.5 * (nodes[e] + nodes[e + 1])))
        diameter = (64 * ei / (math.pi * modulus)) ** 0.25
        ke, _ = element_matrices(nodes[e + 1] - nodes[e], ShaftSection(diameter, 0.0, modulus))
        k[2 * e : 2 * e + 4, 2 * e : 2 * e + 4] += ke
    index = {float(x): i for i, x in enumerate(nodes)}
    b = np.array([2 * index[float(x)] for x in xb])
    inner = np.setdiff1d(np.arange(2 * n), b)
    k_bi = k[np.ix_(b, inner)]
    solve = np.linalg.solve(k[np.ix_(inner, inner)], np.eye(inner.size))
    condensed = k[np.ix_(b, b)] - k_bi @ solve @ k[np.ix_(inner, b)]
    place = np.zeros((2 * n, yl.size))
    place[[2 * index[float(y)] for y in yl], np.arange(yl.size)] = 1.0
    transfer = place[b] - k_bi @ solve @ place[inner]
    # the free beam moves as a rigid body without effort: remove the round-off that the
    # condensation leaves in those two modes, and any negative eigenvalue it left
    rigid, _ = np.linalg.qr(np.stack([np.ones(xb.size), xb - xb.mean()], axis=1))
    project = np.eye(xb.size) - rigid @ rigid.T
    condensed = project @ (0.5 * (condensed + condensed.T)) @ project
    values, vectors = np.linalg.eigh(condensed)
    return (vectors * np.maximum(values, 0.0)) @ vectors.T, transfer


#: the Newton iterations of the clearance solution stop when the force residual is this
#: small against the loads (or after :data:`CLEARANCE_ITERATIONS`)
CLEARANCE_TOLERANCE = 1e-8
CLEARANCE_ITERATIONS = 200
#: most entries of the clearance solution's Hessians, samples x (2 x bearings)^2: its time
#: and memory grow with it (each Newton step solves one 2B x 2B system per sample and its
#: line search evaluates the gradient 60 times); at the cap one crank model takes about
#: 4 s of one loaded core and 100 MB (docs/main_bearings.md, "Bounds of the work")
MAX_CONTACT_SIZE = 2_000_000


def clearance_reactions(
    bearing_positions: ArrayLike,
    load_position: ArrayLike,
    loads: ArrayLike,
    stiffness: CrankStiffness,
    bearing_stiffness: float,
    clearance: float,
) -> NDArray[np.complex128]:
    r"""Bearing reactions of the continuous crank in bearings with radial clearance.

    Each bearing is a ring of radial clearance :math:`c` with a contact stiffness
    :math:`k`: the journal, displaced by :math:`u` (complex, :math:`z + i x`), feels
    :math:`R = -k\,(|u| - c)^+\,u/|u|`. The crank's displacement at the bearings
    minimises the convex potential energy

    .. math:: \Pi(u) = \tfrac12 u^T K_c u - u^T L f + \sum_k \tfrac{k}{2}((|u_k| - c)^+)^2

    (:func:`condensed_stiffness`; both planes at once, coupled by the rings), found for
    every crank angle by Newton's method with a backtracking line search from the
    elastic solution without clearance. A journal inside its clearance carries nothing;
    with :math:`c = 0` this is the elastic model of :func:`continuous_beam_reactions`.
    When nothing at all holds the crank (the loads balance and every journal floats
    inside its clearance) its position is not unique, the reactions (zero) are.

    Parameters
    ----------
    bearing_positions : array_like, shape (B,)
        Bearing positions [m].
    load_position : array_like, shape (L,)
        Positions of the loads [m].
    loads : array_like of complex, shape (L, S)
        Loads on the crank [N].
    stiffness : CrankStiffness
        EI along the crank.
    bearing_stiffness : float
        Contact stiffness of each bearing beyond its clearance [N/m].
    clearance : float
        Radial clearance of each bearing [m].

    Returns
    -------
    ndarray of complex, shape (B, S)
        Reaction of each bearing on the crank [N].

    Raises
    ------
    InputError
        When ``S (2B)^2`` exceeds :data:`MAX_CONTACT_SIZE`, before any work.
    """
    from ..errors import ResultError

    k = check_positive("bearing_stiffness", bearing_stiffness)
    if not (math.isfinite(clearance) and clearance >= 0):
        raise InputError("clearance", clearance, "must be a finite length >= 0 m")
    yl = _vector("load_position", load_position)
    p = np.asarray(loads, dtype=complex).reshape(yl.size, -1)
    size = p.shape[1] * (2 * np.size(bearing_positions)) ** 2
    if size > MAX_CONTACT_SIZE:
        raise InputError(
            "loads",
            f"{p.shape[1]} samples x (2 x {np.size(bearing_positions)} bearings)^2 = {size}",
            f"must make at most {MAX_CONTACT_SIZE} entries of the contact model: fewer "
            "samples or fewer bearings",
        )
    condensed, transfer = condensed_stiffness(bearing_positions, yl, stiffness)
    nb = condensed.shape[0]
    force = transfer @ p  # (B, S), the loads at the bearing points
    # real unknowns per sample: the z then the x displacement of every bearing
    big_k = np.kron(np.eye(2), condensed)
    rhs = np.concatenate([force.real, force.imag]).T  # (S, 2B)
    scale = max(float(np.abs(p).sum(axis=0).max(initial=0.0)), 1e-300)
    ridge = 1e-12 * k * np.eye(2 * nb)  # a floating crank: the smallest-move position

    def contact(u: NDArray) -> tuple[NDArray, NDArray]:
        """Ring forces on the crank (as +gradient terms) and their Hessian blocks."""
        uz, ux = u[:, :nb], u[:, nb:]
        r = np.hypot(uz, ux)
        touching = r > clearance
        safe = np.where(r > 0, r, 1.0)
        factor = np.where(touching, 1.0 - clearance / safe, 0.0)
        grad = k * np.concatenate([factor * uz, factor * ux], axis=1)
        nz, nx = uz / safe, ux / safe
        radial = np.where(touching, clearance / safe, 0.0)
        hess = np.zeros((u.shape[0], 2 * nb, 2 * nb))
        i = np.arange(nb)
        hess[:, i, i] = k * (factor + radial * nz * nz)
        hess[:, nb + i, nb + i] = k * (factor + radial * nx * nx)
        hess[:, i, nb + i] = hess[:, nb + i, i] = k * radial * nz * nx
        return grad, hess

    u = np.linalg.solve(big_k + k * np.eye(2 * nb), rhs.T).T  # no clearance: elastic
    # a Newton step from inside the clearance (where only the ridge holds the crank) may be
    # huge: no step moves a journal by more than a few clearances and elastic deflections
    reach = 4.0 * clearance + 10.0 * float(np.abs(u).max(initial=0.0)) + 1e-30

    def gradient(v: NDArray) -> NDArray:
        return np.asarray(v @ big_k.T - rhs + contact(v)[0] + v @ ridge)

    for _ in range(CLEARANCE_ITERATIONS):
        grad_c, hess_c = contact(u)
        residual = u @ big_k.T - rhs + grad_c + u @ ridge
        if np.abs(residual).max() <= CLEARANCE_TOLERANCE * scale:
            break
        step = np.linalg.solve(big_k + hess_c + ridge, -residual[..., None])[..., 0]
        longest = np.abs(step).max(axis=1)
        high = np.minimum(1.0, reach / np.where(longest > 0, longest, 1.0))
        # exact line search: the energy is convex along the step, so its slope
        # g(u + t d) . d rises with t; bisect for its zero (slopes, not energies: no
        # cancellation of large energies)
        low = np.zeros_like(high)
        done = (gradient(u + high[:, None] * step) * step).sum(axis=1) <= 0
        t = high.copy()
        for _ in range(60):
            mid = 0.5 * (low + high)
            rising = (gradient(u + mid[:, None] * step) * step).sum(axis=1) > 0
            high = np.where(rising, mid, high)
            low = np.where(rising, low, mid)
        t = np.where(done, t, 0.5 * (low + high))
        u = u + t[:, None] * step
    else:
        raise ResultError(
            "bearing clearance solution (Newton did not converge; a softer bearing "
            "stiffness converges)",
            math.nan,
        )
    # the ring forces from the beam's side, R = K_c u - L f: in equilibrium with the loads
    # to round-off (the rings' law holds to the Newton tolerance)
    beam = u @ big_k.T - rhs
    return np.asarray((beam[:, :nb] + 1j * beam[:, nb:]).T)


# --------------------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------------------


@record
class BearingFriction(ResultMixin):
    r"""Friction of each main bearing over the cycle (:mod:`crankbalance.physics.friction`).

    Parameters
    ----------
    coulomb_torque : ndarray, shape (B,)
        Mean over the cycle of :math:`\mu |F(\theta)| d/2` per bearing
        (:func:`crankbalance.physics.friction.friction_torque` at every angle) [N m].
    coulomb_power : ndarray, shape (B,)
        That torque times the mean speed [W].
    petroff_torque : ndarray or None, shape (B,)
        Petroff torque of a concentric, fully flooded bearing
        (:func:`crankbalance.physics.friction.petroff_torque`), load independent [N m]; None
        without viscosity, bearing length and clearance.
    petroff_power : ndarray or None, shape (B,)
        That torque times the mean speed [W].
    """

    coulomb_torque: NDArray[np.float64]
    coulomb_power: NDArray[np.float64]
    petroff_torque: NDArray[np.float64] | None = None
    petroff_power: NDArray[np.float64] | None = None


@record
class MainBearingLoads(ResultMixin):
    r"""Main-bearing loads and crank bending of one crank model over the cycle.

    Parameters
    ----------
    model : {"determinate", "indeterminate"}
        The crank model.
    angle : ndarray, shape (S,)
        Crank angle of the first throw [rad].
    bearing_position : ndarray, shape (B,)
        Bearing positions [m].
    load : ndarray of complex, shape (B, S)
        Force of the crank on each bearing, :math:`z + i x` [N] (polar diagram).
    max_load, mean_load : ndarray, shape (B,)
        Largest and mean magnitude of ``load`` over the cycle [N].
    equivalent_load : ndarray, shape (B,)
        Cubic mean :math:`(\overline{|F|^3})^{1/3}` over the cycle [N] (the mean of
        :func:`crankbalance.physics.friction.mean_equivalent_load`, ``"cubic"``).
    throw_position : ndarray, shape (T,)
        Throw mid-planes [m].
    journal_moment : ndarray of complex, shape (B, S)
        Bending moment of the crank at each bearing (journal) [N m].
    pin_moment : ndarray of complex, shape (T, S)
        Bending moment at each throw mid-plane (crankpin) [N m].
    max_journal_moment : ndarray, shape (B,)
        Largest magnitude of ``journal_moment`` [N m].
    max_pin_moment : ndarray, shape (T,)
        Largest magnitude of ``pin_moment`` [N m].
    friction : BearingFriction or None
        Friction per bearing, None when not asked for.
    """

    model: str
    angle: NDArray[np.float64] = field(repr=False)
    bearing_position: NDArray[np.float64]
    load: NDArray[np.complex128] = field(repr=False)
    max_load: NDArray[np.float64]
    mean_load: NDArray[np.float64]
    equivalent_load: NDArray[np.float64]
    throw_position: NDArray[np.float64]
    journal_moment: NDArray[np.complex128] = field(repr=False)
    pin_moment: NDArray[np.complex128] = field(repr=False)
    max_journal_moment: NDArray[np.float64]
    max_pin_moment: NDArray[np.float64]
    friction: BearingFriction | None = None


def bearing_friction(
    load: ArrayLike,
    speed: float,
    journal_diameter: float,
    friction_coefficient: float,
    viscosity: float | None = None,
    bearing_length: float | None = None,
    clearance: float | None = None,
) -> BearingFriction:
    r"""Friction of each main bearing over the cycle, with :mod:`crankbalance.physics.friction`.

    Coulomb: :math:`T = \overline{\mu |F(\theta)| d/2}`, the mean over the crank-angle
    samples of :func:`~crankbalance.physics.friction.friction_torque` (for a constant plus a
    rotating load this is the ``"arithmetic"`` :func:`~crankbalance.physics.friction.
    mean_equivalent_load`). Hydrodynamic, when viscosity, bearing length and radial
    clearance are given: :func:`~crankbalance.physics.friction.petroff_torque` at the mean speed.

    Parameters
    ----------
    load : array_like of complex, shape (B, S)
        Bearing loads over the cycle [N].
    speed : float
        Time-mean crank speed [rad/s] (the power of an angle-mean torque).
    journal_diameter : float
        Main-journal diameter [m].
    friction_coefficient : float
        Coulomb friction coefficient [-].
    viscosity : float, optional
        Oil viscosity [Pa s].
    bearing_length : float, optional
        Axial length of each main bearing [m].
    clearance : float, optional
        Radial clearance [m].

    Returns
    -------
    BearingFriction
        Per bearing.
    """
    magnitude = np.abs(np.asarray(load, dtype=complex))
    mean_speed = check_positive("speed", speed)
    coulomb = friction_torque(friction_coefficient, magnitude, journal_diameter).mean(axis=-1)
    petroff = None
    given = [v is not None for v in (viscosity, bearing_length, clearance)]
    if any(given) and not all(given):
        missing = [
            n
            for n, v in zip(("viscosity", "bearing_length", "clearance"), given, strict=True)
            if not v
        ]
        raise InputError(
            missing[0],
            None,
            "is needed with the other Petroff inputs (viscosity, bearing "
            "length and clearance go together)",
        )
    if viscosity is not None and bearing_length is not None and clearance is not None:
        one = petroff_torque(viscosity, journal_diameter, bearing_length, clearance, mean_speed)
        petroff = np.full(magnitude.shape[0], float(one))
    return BearingFriction(
        coulomb_torque=coulomb,
        coulomb_power=coulomb * mean_speed,
        petroff_torque=petroff,
        petroff_power=None if petroff is None else petroff * mean_speed,
    )


#: most elements (samples x stations x loads) of one step of the bending moments: the
#: moment at every station of every load at a block of samples at once, about 32 MB
MOMENT_BLOCK = 2_000_000


def _moments(x: NDArray, positions: NDArray, every: NDArray) -> NDArray:
    """Bending moments at the stations ``x`` of the loads ``every`` (S, L) at ``positions``
    (:func:`crankbalance.physics.beam.bending_moment_at`), a block of samples at a time so that
    its temporaries stay within :data:`MOMENT_BLOCK` elements; shape (n, S)."""
    step = max(1, MOMENT_BLOCK // max(1, x.size * positions.size))
    blocks = [
        bending_moment_at(x, positions, every[s : s + step]) for s in range(0, len(every), step)
    ]
    return np.concatenate(blocks).T


def main_bearing_loads(
    loads: CrankLoads,
    bearing_positions: ArrayLike,
    throw_position: ArrayLike,
    model: CrankModel = "indeterminate",
    stiffness: CrankStiffness | None = None,
    bearing_stiffness: ArrayLike | None = None,
    clearance: float | None = None,
) -> MainBearingLoads:
    """Main-bearing loads and crank bending over the cycle for one crank model.

    Parameters
    ----------
    loads : CrankLoads
        Loads on the crank (:func:`crank_loads`).
    bearing_positions : array_like, shape (B,)
        Bearing positions [m] (:func:`default_bearing_positions`).
    throw_position : array_like, shape (T,)
        Throw mid-planes [m].
    model : {"determinate", "indeterminate"}
        :func:`determinate_reactions` or :func:`continuous_beam_reactions`.
    stiffness : CrankStiffness, optional
        EI along the crank; needed for ``"indeterminate"``.
    bearing_stiffness : float or array_like, shape (B,), optional
        Radial bearing stiffness [N/m] (indeterminate model); None for rigid.
    clearance : float, optional
        Radial clearance of every bearing [m] (indeterminate model with a scalar
        ``bearing_stiffness``: :func:`clearance_reactions`); None for none.

    Returns
    -------
    MainBearingLoads
        Without friction (:func:`bearing_friction` adds it).
    """
    if model not in CRANK_MODELS:
        raise InputError("model", model, f"must be one of {', '.join(CRANK_MODELS)}")
    xb = _check_bearing_positions(bearing_positions)
    yt = _vector("throw_position", throw_position)
    if model == "determinate":
        for name, value in (("bearing_stiffness", bearing_stiffness), ("clearance", clearance)):
            if value is not None:
                raise InputError(
                    name,
                    np.asarray(value).tolist(),
                    "only acts in the indeterminate model (the determinate crank's reactions "
                    "do not depend on the bearings' stiffness or clearance)",
                )
        reactions = determinate_reactions(xb, yt, loads.position, loads.throw, loads.load)
    else:
        if stiffness is None:
            raise InputError("stiffness", None, "is needed by the indeterminate model")
        if clearance is None:
            reactions = continuous_beam_reactions(
                xb, loads.position, loads.load, stiffness, bearing_stiffness
            )
        elif bearing_stiffness is None or np.ndim(bearing_stiffness) != 0:
            raise InputError(
                "clearance",
                clearance,
                "needs one bearing stiffness (the rings' contact stiffness) to act",
            )
        else:
            reactions = clearance_reactions(
                xb,
                loads.position,
                loads.load,
                stiffness,
                float(np.asarray(bearing_stiffness)),
                clearance,
            )
    positions = np.concatenate([loads.position, xb])
    every = np.concatenate([loads.load, reactions]).T  # (S, L + B)
    journal, pin = (_moments(x, positions, every) for x in (xb, yt))
    # what is at most the round-off of the loads' moments is exactly zero (an end journal):
    # the one rule (results.ROUND_OFF) on the scale of these loads, which gas forces make
    # larger than the engine's inertia scale
    scale = float(np.abs(every).sum(axis=1).max(initial=0.0)) * float(np.ptp(positions))
    journal = below_round_off(journal, ROUND_OFF * scale)
    pin = below_round_off(pin, ROUND_OFF * scale)
    bearing_load = -reactions
    magnitude = np.abs(bearing_load)
    return MainBearingLoads(
        model=model,
        angle=loads.angle,
        bearing_position=xb,
        load=bearing_load,
        max_load=magnitude.max(axis=1),
        mean_load=magnitude.mean(axis=1),
        equivalent_load=np.mean(magnitude**3, axis=1) ** (1.0 / 3.0),
        throw_position=yt,
        journal_moment=journal,
        pin_moment=pin,
        max_journal_moment=np.abs(journal).max(axis=1),
        max_pin_moment=np.abs(pin).max(axis=1),
    )
