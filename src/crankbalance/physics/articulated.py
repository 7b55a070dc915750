r"""Articulated (master-and-link) connecting rods of a radial engine: exact kinematics.

A radial engine has one crankpin. One *master rod* runs from the crankpin to the piston of
the *master cylinder*; its big end carries a flange with one *link pin* per other
cylinder, and each *link rod* (articulated rod) runs from its link pin to its piston.
Link pin k sits at the distance :math:`\rho_k` (the link pin radius) from the centre of
the master rod's big end, at the angle :math:`\gamma_k` (the link pin angle) from the
master rod's axis, measured in the sense of rotation as the bank angles are.

Vectors across the crank axis are complex numbers :math:`z + i\,x`, as in
:mod:`crankbalance.physics.shaking`; the crankpin of the throw is at :math:`P = r e^{i\theta}`
(:math:`\theta`: crank angle of the throw), cylinder c has the axis direction
:math:`u_c = e^{i\beta_c}`, and every wrist pin moves on a line parallel to its cylinder
axis at the lateral distance e (crank offset plus wrist-pin offset, the sign of
:mod:`crankbalance.physics.kinematics`). The positions, exactly:

* master piston: the ordinary slider-crank, :math:`Q_m = (s_m + i e)\,u_m` with
  :math:`s_m = r\cos\psi + \sqrt{l_m^2 - (e - r\sin\psi)^2}`, :math:`\psi = \theta - \beta_m`;
* master rod axis: :math:`D = Q_m - P` (length :math:`l_m`);
* link pin k: :math:`L_k = P + c_k D` with the constant :math:`c_k = \rho_k e^{i\gamma_k}/l_m`
  (the link pin turns and swings with the master rod);
* link piston k: with :math:`a + ib = \bar u_k L_k` (the link pin in the frame of
  cylinder k), :math:`s_k = a + \sqrt{l_k^2 - (e - b)^2}`, :math:`Q_k = (s_k + ie)\,u_k`.

Derivatives are analytic (``docs/theory.md``, "Articulated rods"): :math:`L_k` is linear
in :math:`P` and :math:`Q_m`, and with :math:`h = e - b`, :math:`q = \sqrt{l_k^2-h^2}`,
:math:`s' = a' + h b'/q`, :math:`s'' = a'' + (h b'' - b'^2)/q - (h b')^2/q^3`.

With :math:`\rho_k = 0` every link rod is an ordinary rod on the crankpin (the "simple"
radial of :func:`crankbalance.physics.model.standard_layout`). With :math:`\rho_k > 0` the link
pistons do not follow the slider-crank: their strokes and top dead centres differ a little
from cylinder to cylinder (:func:`dead_centres`), which is why makers set the link pin
angles a little away from the angles between the cylinders.

Masses (two-mass rods, as everywhere in crankbalance): the reciprocating mass of cylinder
c (piston, wrist pin and the small-end part of its rod) moves with its piston; the
master rod's big-end part turns with the crankpin; the big-end part :math:`n_k` of link
rod k moves with its link pin. In an :class:`~crankbalance.physics.model.EngineModel` every big
end is counted with the crank's rotating masses at the crankpin (as for plain rods), so
this module adds the remainder :math:`n_k\,(L_k - P)'' = n_k c_k D''` as the *link pin*
part of the force. The rods' own moments of inertia about their centres of gravity are
not modelled (as for the plain rods).

An engine model keeps only what the rest of the model lacks (:class:`Articulation`: the
master cylinder, the link rod lengths, the link pin radii and angles);
:meth:`Articulation.rods` joins it with the crank radius, bank angles and offsets into
the full geometry, :class:`ArticulatedRods`, which every function here takes.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..records import record
from ..results import ResultMixin

#: Samples per revolution the Fourier analysis starts with; doubled until the spectrum
#: above a quarter of the samples is negligible (:data:`ALIAS_TOLERANCE`).
FIRST_SAMPLES = 128
#: Most samples per revolution of the Fourier analysis.
MAX_SAMPLES = 8192
#: Largest harmonic between a quarter and a half of the samples, relative to the largest
#: harmonic, accepted as evidence that aliasing is below round-off.
ALIAS_TOLERANCE = 1e-14


@record
class ArticulatedRods(ResultMixin):
    r"""Geometry of a master-and-link rod assembly on one crankpin.

    Arrays have one entry per cylinder (numbering of ``docs/engine_file.md``); the entries
    of the master cylinder describe the master rod (link pin radius and angle there are
    zero).

    Parameters
    ----------
    master : int
        Index of the master cylinder (0-based).
    crank_radius : float
        Crank throw radius r [m].
    bank_angle : ndarray, shape (C,)
        Angle :math:`\beta_c` of each cylinder axis from z, in the sense of rotation [rad].
    rod_length : ndarray, shape (C,)
        Centre distance of each rod [m]: the master rod's (crankpin to wrist pin) at
        ``master``, each link rod's (link pin to wrist pin) elsewhere.
    link_pin_radius : ndarray, shape (C,)
        :math:`\rho_k`, distance of link pin k from the centre of the master rod's big
        end [m]; 0 at ``master``.
    link_pin_angle : ndarray, shape (C,)
        :math:`\gamma_k`, angle of link pin k from the master rod's axis (big end toward
        small end), in the sense of rotation [rad]; 0 at ``master``.
    offset : ndarray, shape (C,)
        Lateral distance of each cylinder's wrist-pin path from the crank axis [m]
        (crank offset plus wrist-pin offset, sign of :mod:`crankbalance.physics.kinematics`).

    Notes
    -----
    The usual design puts link pin k at :math:`\gamma_k = \beta_k - \beta_m`, the angle
    between cylinder k and the master cylinder (:func:`default_link_pin_angles`); makers
    move it by a degree or so to even out the strokes (:func:`even_stroke_angles`).
    """

    master: int
    crank_radius: float
    bank_angle: NDArray[np.float64]
    rod_length: NDArray[np.float64]
    link_pin_radius: NDArray[np.float64]
    link_pin_angle: NDArray[np.float64]
    offset: NDArray[np.float64]

    def __post_init__(self) -> None:
        count = np.asarray(self.bank_angle).size
        _check_rows(self, ("rod_length", "link_pin_radius", "link_pin_angle", "offset"), count)
        if isinstance(self.master, bool) or not 0 <= int(self.master) < count:
            raise InputError("master", self.master, f"must be a cylinder index 0..{count - 1}")
        if not (np.isfinite(self.crank_radius) and self.crank_radius > 0):
            raise InputError("crank_radius", self.crank_radius, "must be greater than zero")
        if np.any(np.asarray(self.link_pin_radius) < 0):
            raise InputError("link_pin_radius", self.link_pin_radius, "must not be negative")
        m = int(self.master)
        if self.link_pin_radius[m] != 0 or self.link_pin_angle[m] != 0:
            raise InputError(
                "link_pin_radius",
                float(self.link_pin_radius[m]),
                "the master cylinder carries no link pin: its entries must be zero",
            )
        reach = reach_problem(self)
        if reach is not None:
            raise InputError("rod_length", float(self.rod_length[reach]), _reach_text(reach))

    @property
    def cylinders(self) -> int:
        """Number of cylinders."""
        return int(np.asarray(self.bank_angle).size)

    @property
    def link_factor(self) -> NDArray[np.complex128]:
        r""":math:`c_k = \rho_k e^{i\gamma_k}/l_m`, link pin k's place on the master rod [-]."""
        rho = np.asarray(self.link_pin_radius, dtype=float)
        return rho * np.exp(1j * np.asarray(self.link_pin_angle)) / self.rod_length[self.master]


def _check_rows(obj: object, names: tuple[str, ...], count: int) -> None:
    """Every named field one finite number per cylinder (a frozen dataclass's arrays)."""
    for name in names:
        value = np.asarray(getattr(obj, name), dtype=float)
        if value.shape != (count,):
            raise InputError(name, value.tolist(), f"needs one entry per cylinder ({count})")
        if not np.all(np.isfinite(value)):
            raise InputError(name, value.tolist(), "must be finite numbers")


@record
class Articulation(ResultMixin):
    r"""The master-and-link rods of an engine model: what its other fields do not hold.

    Parameters
    ----------
    master : int
        Index of the master cylinder (0-based); its rod is the model's ``rod_length``.
    link_rod_length : ndarray, shape (C,)
        Centre distance of each link rod, link pin to wrist pin [m]; 0 at ``master``.
    link_pin_radius : ndarray, shape (C,)
        :math:`\rho_k`, distance of link pin k from the centre of the master rod's big
        end [m]; 0 at ``master``.
    link_pin_angle : ndarray, shape (C,)
        :math:`\gamma_k`, angle of link pin k from the master rod's axis [rad]; 0 at
        ``master``.

    Notes
    -----
    The big-end mass of each link rod is the model's ``cylinder_rotating_mass`` (the
    rotating part of each rod's two-mass split), counted in the throw's rotating mass;
    see the module docstring.
    """

    master: int
    link_rod_length: NDArray[np.float64]
    link_pin_radius: NDArray[np.float64]
    link_pin_angle: NDArray[np.float64]

    def __post_init__(self) -> None:
        count = np.asarray(self.link_rod_length).size
        _check_rows(self, ("link_rod_length", "link_pin_radius", "link_pin_angle"), count)
        if isinstance(self.master, bool) or not 0 <= int(self.master) < count:
            raise InputError("master", self.master, f"must be a cylinder index 0..{count - 1}")
        if self.link_rod_length[int(self.master)] != 0:
            raise InputError(
                "link_rod_length",
                float(self.link_rod_length[int(self.master)]),
                "the master cylinder has no link rod: its entry must be zero",
            )

    def rods(
        self,
        crank_radius: float,
        rod_length: float,
        bank_angle: ArrayLike,
        offset: ArrayLike,
    ) -> ArticulatedRods:
        """The full geometry with the engine's crank, master rod, bank angles and offsets.

        Parameters
        ----------
        crank_radius : float
            Crank throw radius [m].
        rod_length : float
            Master rod centre distance [m].
        bank_angle : array_like, shape (C,)
            Bank angle of each cylinder [rad].
        offset : array_like, shape (C,)
            Lateral offset of each cylinder's wrist-pin path [m].

        Returns
        -------
        ArticulatedRods
            The assembly, checked (every rod reaches its wrist-pin path).
        """
        rods = np.array(self.link_rod_length, dtype=float)
        rods[int(self.master)] = rod_length
        return ArticulatedRods(
            master=int(self.master),
            crank_radius=float(crank_radius),
            bank_angle=np.asarray(bank_angle, dtype=float),
            rod_length=rods,
            link_pin_radius=np.asarray(self.link_pin_radius, dtype=float),
            link_pin_angle=np.asarray(self.link_pin_angle, dtype=float),
            offset=np.broadcast_to(np.asarray(offset, dtype=float), rods.shape).copy(),
        )


def _reach_text(cylinder: int) -> str:
    return (
        f"the rod of cylinder {cylinder + 1} cannot reach its wrist-pin path at every crank "
        "angle: it must be longer than the crank radius plus the link pin radius plus the offset"
    )


def default_link_pin_angles(bank_angle: ArrayLike, master: int) -> NDArray[np.float64]:
    r"""Link pin angles equal to the angles between each cylinder and the master cylinder.

    Parameters
    ----------
    bank_angle : array_like, shape (C,)
        Bank angle of each cylinder [rad].
    master : int
        Index of the master cylinder (0-based).

    Returns
    -------
    ndarray, shape (C,)
        :math:`\gamma_k = \beta_k - \beta_m` wrapped to (-π, π] [rad]; 0 for the master.
    """
    beta = np.asarray(bank_angle, dtype=float)
    gamma = np.mod(beta - beta[master] + np.pi, 2 * np.pi) - np.pi
    return np.where(np.isclose(gamma, -np.pi), np.pi, gamma)


@record
class ArticulatedMotion(ResultMixin):
    """Exact motion of every big end and piston of an articulated rod assembly.

    Parameters
    ----------
    angle : ndarray, shape (M,)
        Crank angle of the throw :math:`\\theta` [rad].
    crankpin : ndarray of complex, shape (M,)
        Crankpin centre :math:`z + ix` [m].
    big_end, big_end_velocity, big_end_acceleration : ndarray of complex, shape (M, C)
        Big-end centre of each rod (the crankpin for the master rod, the link pin for a
        link rod) [m], its velocity [m/s] and acceleration [m/s^2].
    travel, travel_velocity, travel_acceleration : ndarray, shape (M, C)
        Wrist-pin distance from the crank axis along each cylinder axis [m], its rate
        [m/s] and its second rate [m/s^2].
    speed : float
        Crank speed of the rates [rad/s]; 1 gives derivatives by the crank angle.
    """

    angle: NDArray[np.float64]
    crankpin: NDArray[np.complex128]
    big_end: NDArray[np.complex128]
    big_end_velocity: NDArray[np.complex128]
    big_end_acceleration: NDArray[np.complex128]
    travel: NDArray[np.float64]
    travel_velocity: NDArray[np.float64]
    travel_acceleration: NDArray[np.float64]
    speed: float


def motion(rods: ArticulatedRods, angle: ArrayLike, speed: float = 1.0) -> ArticulatedMotion:
    r"""Exact positions, velocities and accelerations of the big ends and pistons.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    angle : array_like, shape (M,)
        Crank angles of the throw :math:`\theta` [rad].
    speed : float
        Constant crank speed :math:`\omega` [rad/s]; 1 gives derivatives by the angle.

    Returns
    -------
    ArticulatedMotion
        Big-end centres and wrist-pin travel with their first and second rates.

    Notes
    -----
    The formulas are in the module docstring; the rates are the analytic derivatives
    times :math:`\omega` and :math:`\omega^2`.
    """
    theta = np.atleast_1d(np.asarray(angle, dtype=float))
    big, big1, big2, s, s1, s2 = _kinematics(rods, theta)
    w = float(speed)
    return ArticulatedMotion(
        angle=theta,
        crankpin=np.asarray(rods.crank_radius * np.exp(1j * theta), dtype=complex),
        big_end=big,
        big_end_velocity=np.asarray(big1 * w, dtype=complex),
        big_end_acceleration=np.asarray(big2 * w**2, dtype=complex),
        travel=s,
        travel_velocity=s1 * w,
        travel_acceleration=s2 * w**2,
        speed=w,
    )


def piston_position(rods: ArticulatedRods, motion_: ArticulatedMotion) -> NDArray[np.complex128]:
    """Wrist-pin centre of each cylinder from its travel, :math:`(s + ie)\\,e^{i\\beta}`.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    motion_ : ArticulatedMotion
        Its motion, from :func:`motion`.

    Returns
    -------
    ndarray of complex, shape (M, C)
        Wrist-pin centres :math:`z + ix` [m].
    """
    return (motion_.travel + 1j * rods.offset) * np.exp(1j * np.asarray(rods.bank_angle))


def _slider(
    local: NDArray, local1: NDArray, local2: NDArray, rod: ArrayLike, offset: ArrayLike
) -> tuple[NDArray, NDArray, NDArray]:
    """Travel of a wrist pin and its first two derivatives from its big end in the
    cylinder's frame (``local = a + ib`` and the derivatives by the crank angle)."""
    a, b = local.real, local.imag
    a1, b1 = local1.real, local1.imag
    a2, b2 = local2.real, local2.imag
    h = offset - b
    q = np.sqrt(np.asarray(rod, dtype=float) ** 2 - h**2)
    s = a + q
    s1 = a1 + h * b1 / q
    s2 = a2 + (h * b2 - b1**2) / q - (h * b1) ** 2 / q**3
    return s, s1, s2


def _kinematics(rods: ArticulatedRods, theta: NDArray) -> tuple[NDArray, ...]:
    """Big ends (M, C) complex and travels (M, C) with derivatives by the crank angle."""
    r, m = rods.crank_radius, int(rods.master)
    e = np.asarray(rods.offset, dtype=float)
    turn = np.exp(1j * theta)[:, None]
    pin, pin1, pin2 = r * turn, 1j * r * turn, -r * turn
    axis = np.exp(1j * np.asarray(rods.bank_angle, dtype=float))[None, :]
    rod = np.asarray(rods.rod_length, dtype=float)
    # master piston: slider-crank on the crankpin
    um = axis[:, m : m + 1]
    sm, sm1, sm2 = _slider(pin * um.conj(), pin1 * um.conj(), pin2 * um.conj(), rod[m], e[m])
    rod_axis = (sm + 1j * e[m]) * um - pin  # D = Q_m - P
    rod_axis1, rod_axis2 = sm1 * um - pin1, sm2 * um - pin2
    c = rods.link_factor[None, :]
    big, big1, big2 = pin + c * rod_axis, pin1 + c * rod_axis1, pin2 + c * rod_axis2
    big[:, m], big1[:, m], big2[:, m] = pin[:, 0], pin1[:, 0], pin2[:, 0]
    s, s1, s2 = _slider(big * axis.conj(), big1 * axis.conj(), big2 * axis.conj(), rod, e)
    s[:, m], s1[:, m], s2[:, m] = sm[:, 0], sm1[:, 0], sm2[:, 0]
    return big, big1, big2, s, s1, s2


def reach_problem(rods: ArticulatedRods) -> int | None:
    """The first cylinder whose rod cannot reach its wrist-pin path at some crank angle.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.

    Returns
    -------
    int or None
        Index of the cylinder (0-based), or None when every rod reaches everywhere.

    Notes
    -----
    The master rod reaches when :math:`l_m > r + |e_m|`. A link pin stays within
    :math:`r + \\rho_k` of the crank axis, so :math:`l_k > r + \\rho_k + |e|` suffices;
    a shorter rod is refused although it might reach on the path it actually sweeps.
    """
    rod = np.asarray(rods.rod_length, dtype=float)
    need = (
        rods.crank_radius
        + np.asarray(rods.link_pin_radius, dtype=float)
        + np.abs(np.asarray(rods.offset, dtype=float))
    )
    short = np.flatnonzero(~(rod > need))
    return int(short[0]) if short.size else None


@record
class DeadCentres(ResultMixin):
    """Top and bottom dead centre and stroke of every piston of an articulated assembly.

    Parameters
    ----------
    tdc_angle, bdc_angle : ndarray, shape (C,)
        Crank angle of the throw at each piston's top (farthest from the crank axis) and
        bottom dead centre, in [0, 2π) [rad].
    tdc_travel, bdc_travel : ndarray, shape (C,)
        Wrist-pin distance from the crank axis there [m].
    stroke : ndarray, shape (C,)
        ``tdc_travel - bdc_travel`` [m].
    tdc_lag : ndarray, shape (C,)
        ``tdc_angle`` minus the crank angle :math:`\\beta_c` at which a plain slider-crank
        on the crankpin would be at top dead centre (zero offset), wrapped to (-π, π] [rad].
    """

    tdc_angle: NDArray[np.float64]
    bdc_angle: NDArray[np.float64]
    tdc_travel: NDArray[np.float64]
    bdc_travel: NDArray[np.float64]
    stroke: NDArray[np.float64]
    tdc_lag: NDArray[np.float64]


def dead_centres(rods: ArticulatedRods, samples: int = 720) -> DeadCentres:
    """Dead centres and strokes of every piston: sampled extremes refined by Newton steps.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    samples : int
        Crank angles sampled over a revolution before the refinement [-].

    Returns
    -------
    DeadCentres
        Crank angles [rad], travels [m] and strokes [m] of every cylinder.

    Notes
    -----
    Each extreme is the sample of largest (smallest) travel refined with Newton steps on
    :math:`s'(\\theta) = 0` using the analytic :math:`s''`, until the step is below 1e-14 rad.
    """
    theta = np.linspace(0.0, 2 * np.pi, int(samples), endpoint=False)
    _b, _b1, _b2, s, _s1, _s2 = _kinematics(rods, theta)
    top = _refine(rods, theta[np.argmax(s, axis=0)])
    bottom = _refine(rods, theta[np.argmin(s, axis=0)])
    tdc_travel = _travel_at(rods, top)
    bdc_travel = _travel_at(rods, bottom)
    lag = np.mod(top - np.asarray(rods.bank_angle) + np.pi, 2 * np.pi) - np.pi
    return DeadCentres(
        tdc_angle=np.mod(top, 2 * np.pi),
        bdc_angle=np.mod(bottom, 2 * np.pi),
        tdc_travel=tdc_travel,
        bdc_travel=bdc_travel,
        stroke=tdc_travel - bdc_travel,
        tdc_lag=lag,
    )


def _travel_at(rods: ArticulatedRods, angle: NDArray) -> NDArray:
    """Travel of cylinder c at crank angle ``angle[c]``."""
    s = _kinematics(rods, angle)[3]
    return np.asarray(np.diagonal(s), dtype=float)


def _refine(rods: ArticulatedRods, angle: NDArray) -> NDArray:
    """Newton steps on each cylinder's travel rate, from the start angle of each."""
    theta = np.array(angle, dtype=float)
    for _ in range(50):
        _b, _b1, _b2, _s, s1, s2 = _kinematics(rods, theta)
        step = np.diagonal(s1) / np.diagonal(s2)
        theta = theta - step
        if np.all(np.abs(step) < 1e-14):
            break
    return theta


@record
class ArticulatedHarmonics(ResultMixin):
    r"""Harmonics of the inertia forces of an articulated assembly, per kilogram.

    Per unit mass at unit crank speed: multiply a row by the mass [kg] and
    :math:`\omega^2` [rad^2/s^2] to get forces [N]. Phasors at crank angle 0 of the throw
    in the convention of :mod:`crankbalance.physics.shaking`.

    Parameters
    ----------
    orders : ndarray of int, shape (K,)
        Harmonic orders 1..K.
    piston_forward, piston_backward : ndarray of complex, shape (C, K)
        Forward and backward phasors of :math:`-\ddot Q_c/\omega^2`, the inertia force of
        1 kg moving with the wrist pin of cylinder c at 1 rad/s [m].
    link_forward, link_backward : ndarray of complex, shape (C, K)
        The same of :math:`-(\ddot L_k - \ddot P)/\omega^2`, the inertia force of 1 kg
        at link pin k beyond that of 1 kg at the crankpin [m]; zero for the master.
    samples : int
        Samples per revolution of the Fourier analysis [-].
    alias_bound : float
        Largest harmonic magnitude between a quarter and a half of ``samples``, relative
        to the largest harmonic: a bound of the relative aliasing error [-].
    """

    orders: NDArray[np.int64]
    piston_forward: NDArray[np.complex128]
    piston_backward: NDArray[np.complex128]
    link_forward: NDArray[np.complex128]
    link_backward: NDArray[np.complex128]
    samples: int
    alias_bound: float


def harmonics(rods: ArticulatedRods, orders: int = 8) -> ArticulatedHarmonics:
    """Forward and backward phasors of every piston's and link pin's inertia, per kilogram.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    orders : int
        Highest harmonic order K [-].

    Returns
    -------
    ArticulatedHarmonics
        Phasors per kilogram at 1 rad/s [m], and the sampling they came from.

    Notes
    -----
    The discrete Fourier transform of the exact accelerations over one revolution,
    :math:`F_n^{+} = \\tfrac{1}{N}\\sum_j F(\\theta_j) e^{-in\\theta_j}`,
    :math:`F_n^{-} = \\tfrac{1}{N}\\sum_j F(\\theta_j) e^{in\\theta_j}`. The harmonics
    decay geometrically with the order; N starts at :data:`FIRST_SAMPLES` and is doubled
    until every harmonic between N/4 and N/2 is below :data:`ALIAS_TOLERANCE` of the
    largest, so the aliased harmonics (orders above N/2 folded back) are negligible too.
    Raises :class:`~crankbalance.errors.InputError` when :data:`MAX_SAMPLES` do not suffice.
    """
    k = int(orders)
    if not 1 <= k <= 64:
        raise InputError("orders", orders, "must be a whole number from 1 to 64")
    n = FIRST_SAMPLES
    while True:
        n = max(n, 4 * k)
        theta = 2 * np.pi * np.arange(n) / n
        _big, _b1, big2, _s, _s1, s2 = _kinematics(rods, theta)
        axis = np.exp(1j * np.asarray(rods.bank_angle, dtype=float))[None, :]
        piston = -s2 * axis  # (M, C)
        link = -(big2 - (-rods.crank_radius * np.exp(1j * theta))[:, None])
        spectrum = np.fft.fft(np.concatenate([piston, link], axis=1), axis=0) / n  # (N, 2C)
        size = np.abs(spectrum)
        top = float(size.max()) or 1.0
        tail = float(size[n // 4 : n - n // 4 + 1].max()) / top
        if tail < ALIAS_TOLERANCE or n >= MAX_SAMPLES:
            break
        n *= 2
    if tail >= ALIAS_TOLERANCE:
        raise InputError(
            "rod geometry",
            f"aliasing bound {tail:.1e} at {n} samples",
            "a rod is so short against the crank that its motion is not smooth enough "
            "for a Fourier analysis; lengthen the rods",
        )
    count = rods.cylinders
    forward = spectrum[1 : k + 1].T
    backward = spectrum[n - np.arange(1, k + 1)].T
    return ArticulatedHarmonics(
        orders=np.arange(1, k + 1),
        piston_forward=forward[:count],
        piston_backward=backward[:count],
        link_forward=forward[count:],
        link_backward=backward[count:],
        samples=n,
        alias_bound=tail,
    )


def inertia_force(
    rods: ArticulatedRods,
    reciprocating_mass: ArrayLike,
    big_end_mass: ArrayLike,
    angle: ArrayLike,
    speed: float,
) -> NDArray[np.complex128]:
    r"""Inertia force of each cylinder's moving masses on the block versus crank angle, exactly.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    reciprocating_mass : array_like, shape (C,)
        Mass moving with each wrist pin: piston, wrist pin and the small-end part of the
        rod [kg].
    big_end_mass : array_like, shape (C,)
        Big-end part of each rod [kg]; a link rod's moves with its link pin (the master
        rod's turns with the crankpin and adds nothing here).
    angle : array_like, shape (M,)
        Crank angles of the throw [rad].
    speed : float
        Crank speed [rad/s].

    Returns
    -------
    ndarray of complex, shape (M, C)
        :math:`-m_c \ddot Q_c - n_c(\ddot L_c - \ddot P)` of each cylinder c as
        :math:`F_z + iF_x` [N]; the masses turning with the crankpin (every big end
        included) are the rotating part, outside this force.
    """
    theta = np.atleast_1d(np.asarray(angle, dtype=float))
    _big, _b1, big2, _s, _s1, s2 = _kinematics(rods, theta)
    axis = np.exp(1j * np.asarray(rods.bank_angle, dtype=float))[None, :]
    pin2 = -rods.crank_radius * np.exp(1j * theta)[:, None]
    mass = np.asarray(reciprocating_mass, dtype=float)[None, :]
    ends = np.asarray(big_end_mass, dtype=float)[None, :]
    force = mass * s2 * axis + ends * (big2 - pin2)
    return np.asarray(-(float(speed) ** 2) * force, dtype=complex)


def cylinder_coefficients(rods: ArticulatedRods, orders: int = 8) -> NDArray[np.complex128]:
    r"""Harmonic coefficients of each piston's normalised inertia, as a slider-crank's.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    orders : int
        Highest harmonic order K [-].

    Returns
    -------
    ndarray of complex, shape (C, K)
        :math:`c_{n,c} = a_n - i b_n` with :math:`-\ddot s_c/(r\omega^2) = \sum_n
        \mathrm{Re}(c_{n,c} e^{in\psi_c})`, :math:`\psi_c = \theta - \beta_c` [-]: the form
        of :func:`crankbalance.physics.kinematics.harmonic_coefficients` and of
        :func:`crankbalance.physics.shaking.cylinder_coefficients`, so a link piston takes the
        place of a slider-crank row. The master's row is the slider-crank's.

    Notes
    -----
    Every piston moves along its own axis, so its force per kilogram,
    :math:`-\ddot s_c u_c`, has the forward phasor :math:`\tfrac{r}{2} c_{n,c}
    e^{i(1-n)\beta_c}` (:func:`harmonics`), from which :math:`c_{n,c}` is read. The link
    pins' own forces are not along a cylinder axis: they are the ``link_forward`` and
    ``link_backward`` phasors of :func:`harmonics`.
    """
    h = harmonics(rods, orders)
    n = h.orders[None, :]
    beta = np.asarray(rods.bank_angle, dtype=float)[:, None]
    return np.asarray(
        (2.0 / rods.crank_radius) * h.piston_forward * np.exp(-1j * (1 - n) * beta),
        dtype=complex,
    )


def even_stroke_angles(rods: ArticulatedRods, search: float = np.radians(15.0)) -> NDArray:
    r"""Link pin angles that give every link piston the master piston's stroke.

    Each link piston's motion depends on its own link pin only, so each angle is found on
    its own: bisection on the shift :math:`\delta_k` of :math:`\gamma_k` within
    :math:`\pm` ``search`` until the stroke equals the master's (:func:`dead_centres`).

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly; its link pin angles are the start of the search.
    search : float
        Largest shift of a link pin angle tried, either way [rad].

    Returns
    -------
    ndarray, shape (C,)
        Link pin angles [rad] (the master's 0) at which every stroke equals the master's
        to 1e-12 of the crank radius.

    Notes
    -----
    This is why makers set the link pin angles a little away from the angles between the
    cylinders (``docs/theory.md``, "Articulated rods"): with :math:`\gamma_k = \beta_k -
    \beta_m` the link strokes are longer than the master's. One angle evens out the
    strokes; the top dead centre positions (the compression ratios) then still differ a
    little, which the link rod lengths or the pistons make up.
    Raises :class:`~crankbalance.errors.InputError` when no shift within ``search``
    reaches the master's stroke.
    """
    m = int(rods.master)
    links = np.arange(rods.cylinders) != m
    target = dead_centres(rods).stroke[m]
    start = np.asarray(rods.link_pin_angle, dtype=float)

    def excess(shift: NDArray) -> NDArray:
        trial = replace(rods, link_pin_angle=start + np.where(links, shift, 0.0))
        return dead_centres(trial).stroke - target

    low = np.full(rods.cylinders, -float(search))
    high = np.full(rods.cylinders, float(search))
    f_low, f_high = excess(low), excess(high)
    bad = links & (np.sign(f_low) == np.sign(f_high))
    if np.any(bad):
        k = int(np.flatnonzero(bad)[0])
        raise InputError(
            "link_pin_angle",
            float(np.degrees(start[k])),
            f"no shift within {np.degrees(search):g} deg gives cylinder {k + 1} the master's "
            "stroke",
        )
    for _ in range(200):
        mid = 0.5 * (low + high)
        f_mid = excess(mid)
        left = np.sign(f_mid) == np.sign(f_low)
        low, f_low = np.where(left, mid, low), np.where(left, f_mid, f_low)
        high = np.where(left, high, mid)
        if np.all(np.abs(f_mid[links]) < 1e-12 * rods.crank_radius) or np.all(
            (high - low)[links] < 1e-15
        ):
            break
    return np.where(links, start + 0.5 * (low + high), 0.0)
