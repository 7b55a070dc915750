r"""Bearing friction models.

Three families, all pure numpy functions of SI floats (arrays broadcast):

* Coulomb friction of a bearing carrying a constant load plus a rotating unbalance load
  (Hoem and Røsholm (2016), Sec. 4.2.1): :math:`T = \mu F_m d/2` with the *mean equivalent load*
  :math:`F_m`.
  Three means are offered: the thesis' approximation
  :math:`F_m = f_m (F_w + F_u)`, :math:`f_m = x^2 - x + 1`, :math:`x = F_w/(F_w + F_u)`
  (Eq. 4.13/4.14 as corrected in docs/references.md), the exact cubic mean it
  approximates (the rolling-bearing mean load), and the arithmetic mean of the load
  magnitude over a revolution (what a Coulomb joint driven by the actual reaction force
  dissipates on average; closed form with the complete elliptic integral).
* The friction coefficient back-computed from a measured torque (Hoem and Røsholm (2016), Eq. 5.1),
to reduce
  test-rig data as the thesis did.
* A hydrodynamic journal bearing: Petroff's torque and the eccentricity-corrected form of
  Hoem and Røsholm (2016), Appendix A (Eq. 7.2, after Heywood), and squeeze-film stiffness and
  damping
  (Eqs. 7.4, 7.5), with the exact Reynolds solution of a rectangular squeeze film for
  comparison.

The bench and engine-cycle simulations that use these are in
:mod:`crankbalance.physics.rotor_bench` and
:mod:`crankbalance.physics.engine_cycle`.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipe

from ..errors import InputError

MeanLoadMethod = Literal["approximate", "cubic", "arithmetic"]
MEAN_LOAD_METHODS: tuple[str, ...] = ("approximate", "cubic", "arithmetic")

#: Quadrature points per revolution for the cubic mean (periodic trapezoid rule; the
#: integrand is smooth except for a weak kink when both loads are equal, where 512
#: points still give 1e-7 relative accuracy).
CUBIC_MEAN_SAMPLES = 512


def _nonnegative(field: str, value: ArrayLike) -> NDArray:
    array = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(array)) or np.any(array < 0):
        raise InputError(field, value, "must be finite and not negative")
    return array


def _positive(field: str, value: ArrayLike) -> NDArray:
    array = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(array)) or np.any(array <= 0):
        raise InputError(field, value, "must be finite and greater than zero")
    return array


def _method(method: str) -> str:
    if method not in MEAN_LOAD_METHODS:
        raise InputError("method", method, f"must be one of {', '.join(MEAN_LOAD_METHODS)}")
    return method


# --------------------------------------------------------------------------------------
# Constant load plus rotating unbalance
# --------------------------------------------------------------------------------------


def mean_load_factor(constant_load: ArrayLike, rotating_load: ArrayLike) -> NDArray:
    r"""Factor :math:`f_m` of the mean equivalent load [-].

    .. math:: f_m = x^2 - x + 1,\qquad x = \frac{F_w}{F_w + F_u}

    Parameters
    ----------
    constant_load : array_like
        Load constant in magnitude and direction, e.g. the rotor weight, :math:`F_w` [N].
    rotating_load : array_like
        Load of constant magnitude rotating with the shaft, e.g. the unbalance force
        :math:`F_u = U\omega^2` [N].

    Returns
    -------
    ndarray
        :math:`f_m`, between 0.75 (equal loads) and 1 (one load alone) [-].

    References
    ----------
    Hoem and Røsholm (2016) Eq. 4.14, garbled in the text; checked reading in docs/references.md.
    """
    w = _nonnegative("constant_load", constant_load)
    u = _nonnegative("rotating_load", rotating_load)
    total = w + u
    if np.any(total <= 0):
        raise InputError(
            "constant_load + rotating_load",
            total.tolist(),
            "must be greater than zero (the bearing carries no load)",
        )
    x = w / total
    return x * x - x + 1.0


def mean_equivalent_load(
    constant_load: ArrayLike, rotating_load: ArrayLike, method: MeanLoadMethod = "approximate"
) -> NDArray:
    r"""Mean equivalent bearing load of a constant plus a rotating load [N].

    .. math::
        \text{approximate:}\quad F_m = f_m (F_w + F_u)

        \text{cubic:}\quad F_m = \Big(\frac{1}{2\pi}\int_0^{2\pi}
            |F_w + F_u e^{i\theta}|^3\,d\theta\Big)^{1/3}

        \text{arithmetic:}\quad F_m = \frac{1}{2\pi}\int_0^{2\pi}|F_w + F_u e^{i\theta}|\,d\theta
            = \frac{2}{\pi}(F_w + F_u)\,E(k^2),\quad k^2 = \frac{4F_wF_u}{(F_w+F_u)^2}

    The thesis' :math:`f_m` is a fit of the cubic mean (the dynamic equivalent load of
    rolling bearings, which governs fatigue); the arithmetic mean is the one that sets the
    average Coulomb friction torque of a joint whose friction follows the actual reaction
    force, as in the simulated bench of Hoem and Røsholm (2016), Sec. 5.2.5 and
    :func:`crankbalance.physics.rotor_bench.run_bench`.

    Parameters
    ----------
    constant_load : array_like
        Load constant in magnitude and direction, :math:`F_w` [N].
    rotating_load : array_like
        Load of constant magnitude rotating with the shaft, :math:`F_u` [N].
    method : {"approximate", "cubic", "arithmetic"}
        Which mean (see above).

    Returns
    -------
    ndarray
        :math:`F_m` [N].

    References
    ----------
    Hoem and Røsholm (2016), Eqs. 4.13, 4.14 (docs/references.md reading); SKF/ISO 281 mean load of
    a constant
    plus a rotating load (cubic mean); Byrd & Friedman, complete elliptic integral E.
    """
    _method(method)
    w = _nonnegative("constant_load", constant_load)
    u = _nonnegative("rotating_load", rotating_load)
    if method == "approximate":
        return mean_load_factor(w, u) * (w + u)
    if method == "arithmetic":
        total = w + u
        safe = np.where(total > 0, total, 1.0)
        m = np.where(total > 0, 4.0 * (w / safe) * (u / safe), 0.0)  # no underflow of safe**2
        return 2.0 / np.pi * total * ellipe(np.clip(m, 0.0, 1.0))
    theta = 2.0 * np.pi * np.arange(CUBIC_MEAN_SAMPLES) / CUBIC_MEAN_SAMPLES
    w_, u_ = np.broadcast_arrays(w, u)
    magnitude_sq = (
        w_[..., None] ** 2
        + u_[..., None] ** 2
        + 2.0 * w_[..., None] * u_[..., None] * np.cos(theta)
    )
    return np.mean(np.clip(magnitude_sq, 0.0, None) ** 1.5, axis=-1) ** (1.0 / 3.0)


def friction_torque(
    friction_coefficient: ArrayLike, load: ArrayLike, journal_diameter: ArrayLike
) -> NDArray:
    r"""Coulomb friction torque of a journal under a load [N m].

    .. math:: T = \mu F \frac{d}{2}

    Parameters
    ----------
    friction_coefficient : array_like
        Coulomb friction coefficient :math:`\mu` [-].
    load : array_like
        Bearing load magnitude :math:`F` (or a mean equivalent load) [N].
    journal_diameter : array_like
        Journal diameter :math:`d` [m].

    Returns
    -------
    ndarray
        Friction torque :math:`T` [N m], the broadcast shape of the arguments.

    References
    ----------
    Hoem and Røsholm (2016), Eqs. 4.10 and 4.12.
    """
    mu = _nonnegative("friction_coefficient", friction_coefficient)
    load_ = _nonnegative("load", load)
    d = _positive("journal_diameter", journal_diameter)
    return mu * load_ * 0.5 * d


def unbalanced_friction_torque(
    friction_coefficient: ArrayLike,
    constant_load: ArrayLike,
    rotating_load: ArrayLike,
    journal_diameter: ArrayLike,
    method: MeanLoadMethod = "approximate",
) -> NDArray:
    r"""Friction torque of a bearing under a constant plus a rotating load [N m].

    .. math:: T = \mu F_m \frac{d}{2},\qquad F_m \text{ from } :func:`mean_equivalent_load`

    Parameters
    ----------
    friction_coefficient : array_like
        Coulomb friction coefficient :math:`\mu` [-].
    constant_load : array_like
        Constant load, e.g. the rotor weight [N].
    rotating_load : array_like
        Rotating unbalance load :math:`U\omega^2` [N].
    journal_diameter : array_like
        Journal diameter [m].
    method : {"approximate", "cubic", "arithmetic"}
        Mean equivalent load used (the thesis uses "approximate").

    Returns
    -------
    ndarray
        Mean friction torque :math:`T` [N m], the broadcast shape of the arguments.

    References
    ----------
    Hoem and Røsholm (2016), Eq. 4.12 with Eqs. 4.13, 4.14.
    """
    load = mean_equivalent_load(constant_load, rotating_load, method)
    return friction_torque(friction_coefficient, load, journal_diameter)


def friction_coefficient_from_torque(
    torque: ArrayLike,
    constant_load: ArrayLike,
    rotating_load: ArrayLike,
    journal_diameter: ArrayLike,
    method: MeanLoadMethod = "approximate",
) -> NDArray:
    r"""Coulomb friction coefficient back-computed from a measured friction torque [-].

    .. math:: \mu = \frac{T_{friction}}{F_m \cdot 0.5\,d}

    Parameters
    ----------
    torque : array_like
        Measured torque needed to hold the speed (all bearings together) [N m].
    constant_load : array_like
        Constant load, all bearings together (rotor weight) [N].
    rotating_load : array_like
        Rotating unbalance load :math:`U\omega^2` [N].
    journal_diameter : array_like
        Journal diameter [m].
    method : {"approximate", "cubic", "arithmetic"}
        Mean equivalent load (the thesis uses "approximate").

    Returns
    -------
    ndarray
        Coulomb friction coefficient :math:`\mu` [-], the broadcast shape of the arguments.

    References
    ----------
    Hoem and Røsholm (2016), Eq. 5.1 and Table 5.5.
    """
    t = _nonnegative("torque", torque)
    load = mean_equivalent_load(constant_load, rotating_load, method)
    d = _positive("journal_diameter", journal_diameter)
    if np.any(load <= 0):
        raise InputError(
            "constant_load + rotating_load",
            np.asarray(load).tolist(),
            "must be greater than zero (the bearing carries no load)",
        )
    with np.errstate(over="ignore", divide="ignore"):  # checked just below
        mu = t / (load * 0.5 * d)
    if not np.all(np.isfinite(mu)):
        raise InputError(
            "torque",
            torque,
            "is too large for this load and journal diameter: the friction coefficient "
            "would not be a finite number",
        )
    return mu


def torque_from_transducer_voltage(
    voltage: ArrayLike, zero_voltage: float = 0.2, volts_per_newton_metre: float = 4.8 / 5.0
) -> NDArray:
    r"""Torque from the HBM T22 transducer reading of the thesis rig [N m].

    .. math:: T = \frac{V - V_0}{k},\qquad V_0 = 0.2\ \text{V},\ k = 4.8/5\ \text{V/(N m)}

    (0.2 V at zero torque and 5 V at 5 N m, Figs. 5.9, 5.10.)

    Parameters
    ----------
    voltage : array_like
        Transducer output [V].
    zero_voltage : float
        Output at zero torque [V].
    volts_per_newton_metre : float
        Slope [V/(N m)].

    Returns
    -------
    ndarray
        Torque :math:`T` [N m], the shape of ``voltage``.

    References
    ----------
    Hoem and Røsholm (2016), Sec. 5.2.1; Table 5.6 reading in docs/references.md: torque = (V -
    0.2) 5/4.8.
    """
    v = np.asarray(voltage, dtype=float)
    if not np.all(np.isfinite(v)):
        raise InputError("voltage", voltage, "must be finite")
    return (v - zero_voltage) / volts_per_newton_metre


# --------------------------------------------------------------------------------------
# Hydrodynamic journal bearing
# --------------------------------------------------------------------------------------


def petroff_torque(
    viscosity: ArrayLike,
    journal_diameter: ArrayLike,
    bearing_length: ArrayLike,
    radial_clearance: ArrayLike,
    speed: ArrayLike,
) -> NDArray:
    r"""Petroff friction torque of a concentric, fully flooded journal bearing [N m].

    Couette shear :math:`\tau = \eta\,\omega r/c` over the area :math:`\pi D L`, lever :math:`D/2`:

    .. math:: T = \frac{\pi\,\eta\,\omega\,D^3 L}{4\,c}

    Parameters
    ----------
    viscosity : array_like
        Dynamic oil viscosity :math:`\eta` [Pa s].
    journal_diameter : array_like
        Journal (bearing) diameter :math:`D` [m].
    bearing_length : array_like
        Axial bearing length :math:`L` [m].
    radial_clearance : array_like
        Mean radial clearance :math:`c = \bar h` [m].
    speed : array_like
        Shaft speed :math:`\omega` [rad/s].

    Returns
    -------
    ndarray
        Friction torque on the journal :math:`T` [N m], the broadcast shape of the
        arguments; its sign follows ``speed``.

    References
    ----------
    Petroff (1883); Heywood (1988) Sec. 13.4; Shigley (Budynas and Nisbett 2015) Eq. 12-6;
    Hoem and Røsholm (2016), Appendix A Eq. 7.2 with :math:`\varepsilon = 0`.
    """
    return journal_bearing_torque(
        viscosity, journal_diameter, bearing_length, radial_clearance, speed
    )


def journal_bearing_torque(
    viscosity: ArrayLike,
    journal_diameter: ArrayLike,
    bearing_length: ArrayLike,
    radial_clearance: ArrayLike,
    speed: ArrayLike,
    eccentricity_ratio: ArrayLike = 0.0,
    load: ArrayLike = 0.0,
    attitude_angle: ArrayLike = 0.0,
) -> NDArray:
    r"""Friction torque on the journal of an eccentric hydrodynamic bearing [N m].

    .. math::
        T = F_f\,r_j,\qquad
        F_f = \frac{\pi\,\eta\,D^2 L\,\omega}{2\,\bar h\sqrt{1-\varepsilon^2}}
              + \frac{\bar h\,\varepsilon\,W}{D}\sin\phi

    The thesis prints the first term as :math:`\pi^2\eta D^2 L\omega/(\ldots)`; that is
    Heywood's form with the speed :math:`N` in revolutions per second. With :math:`\omega`
    in rad/s the factor is :math:`\pi/2` (:math:`\pi^2 N = \pi\omega/2`); with
    :math:`\varepsilon = 0` this is Petroff's torque.

    Parameters
    ----------
    viscosity : array_like
        Dynamic oil viscosity :math:`\eta` [Pa s].
    journal_diameter : array_like
        Journal diameter :math:`D = 2 r_j` [m].
    bearing_length : array_like
        Axial bearing length :math:`L` [m].
    radial_clearance : array_like
        Mean radial clearance :math:`\bar h` [m].
    speed : array_like
        Shaft speed :math:`\omega` [rad/s].
    eccentricity_ratio : array_like
        :math:`\varepsilon = (\bar h - h_m)/\bar h`, in [0, 1) [-].
    load : array_like
        Bearing load :math:`W` [N].
    attitude_angle : array_like
        Attitude angle :math:`\phi` [rad].

    Returns
    -------
    ndarray
        Friction torque on the journal :math:`T` [N m], the broadcast shape of the
        arguments; its sign follows ``speed``.

    References
    ----------
    Hoem and Røsholm (2016), Appendix A Eq. 7.2 (after Heywood); the friction coefficient is Eq.
    7.3, ``F_f / W``.
    """
    eta = _nonnegative("viscosity", viscosity)
    d = _positive("journal_diameter", journal_diameter)
    length = _positive("bearing_length", bearing_length)
    c = _positive("radial_clearance", radial_clearance)
    w = np.asarray(speed, dtype=float)
    if not np.all(np.isfinite(w)):
        raise InputError("speed", speed, "must be finite")
    eps = np.asarray(eccentricity_ratio, dtype=float)
    if not np.all((eps >= 0) & (eps < 1)):
        raise InputError("eccentricity_ratio", eccentricity_ratio, "must lie in [0, 1)")
    load_ = _nonnegative("load", load)
    phi = np.asarray(attitude_angle, dtype=float)
    shear = np.pi * eta * d**2 * length * w / (2.0 * c * np.sqrt(1.0 - eps**2))
    offset = c * eps * load_ / d * np.sin(phi) * np.sign(w)
    return (shear + offset) * 0.5 * d


def squeeze_film_stiffness(load: ArrayLike, gap: ArrayLike) -> NDArray:
    r"""Squeeze-film stiffness of a bearing [N/m].

    .. math:: k = \frac{3 A_E}{H} P_{SQ} = \frac{3W}{H}

    The squeeze-film force at a given squeeze velocity varies as :math:`H^{-3}`
    (:func:`rectangular_squeeze_film_damping`), so :math:`-dW/dH = 3W/H`.

    Parameters
    ----------
    load : array_like
        Shaft load carried by the film :math:`W` [N].
    gap : array_like
        Bearing/journal gap :math:`H` [m].

    Returns
    -------
    ndarray
        Squeeze-film stiffness :math:`k` [N/m], the broadcast shape of the arguments.

    References
    ----------
    Hoem and Røsholm (2016), Appendix A Eq. 7.4 (after Weston et al.).
    """
    return 3.0 * _nonnegative("load", load) / _positive("gap", gap)


def squeeze_film_damping(
    viscosity: ArrayLike,
    squeeze_area: ArrayLike,
    gap: ArrayLike,
    bearing_length: ArrayLike,
    bearing_width: ArrayLike,
) -> NDArray:
    r"""Squeeze-film damping coefficient of a bearing as given in the thesis [N s/m].

    .. math:: C_D = \frac{3\,\eta\,A_E^2}{H^3\,(Z/L + L/Z)}

    With :math:`A_E = ZL` and :math:`L \gg Z` this tends to :math:`3\eta Z^3L/H^3`, three
    times the exact Reynolds value of a long flat plate (:math:`\eta Z^3 L/H^3`); for a
    square plate it is 3.56 times :func:`rectangular_squeeze_film_damping`. The formula is
    given as printed; use the Reynolds solution where the absolute value matters.

    Parameters
    ----------
    viscosity : array_like
        Dynamic oil viscosity :math:`\eta` [Pa s].
    squeeze_area : array_like
        Squeeze area :math:`A_E` [m^2].
    gap : array_like
        Bearing/journal gap :math:`H` [m].
    bearing_length : array_like
        Bearing length :math:`L` [m].
    bearing_width : array_like
        Bearing width :math:`Z` [m].

    Returns
    -------
    ndarray
        Damping coefficient :math:`C_D` [N s/m], the broadcast shape of the arguments.

    References
    ----------
    Hoem and Røsholm (2016), Appendix A Eq. 7.5 (after Weston et al.).
    """
    eta = _nonnegative("viscosity", viscosity)
    area = _positive("squeeze_area", squeeze_area)
    h = _positive("gap", gap)
    length = _positive("bearing_length", bearing_length)
    width = _positive("bearing_width", bearing_width)
    return 3.0 * eta * area**2 / (h**3 * (width / length + length / width))


def rectangular_squeeze_film_damping(
    viscosity: ArrayLike,
    gap: ArrayLike,
    bearing_length: ArrayLike,
    bearing_width: ArrayLike,
    terms: int = 50,
) -> NDArray:
    r"""Exact squeeze-film damping of a flat rectangular film (Reynolds equation) [N s/m].

    The Reynolds equation :math:`\nabla^2 p = 12\eta\dot h/h^3` with :math:`p = 0` on the
    edges of a :math:`Z \times L` rectangle (:math:`Z \le L`) gives (the torsion analogy):

    .. math::
        C = \frac{\eta Z^3 L}{H^3}\,\beta,\qquad
        \beta = 1 - \frac{192\,Z}{\pi^5 L}\sum_{n=1,3,5,\ldots}\frac{\tanh(n\pi L/2Z)}{n^5}

    Parameters
    ----------
    viscosity : array_like
        Dynamic oil viscosity [Pa s].
    gap : array_like
        Film thickness :math:`H` [m].
    bearing_length, bearing_width : array_like
        Sides of the rectangle [m] (order does not matter).
    terms : int
        Number of odd terms of the series (50 give a relative error below 1e-8).

    Returns
    -------
    ndarray
        Damping coefficient :math:`C` [N s/m], the broadcast shape of the arguments.

    References
    ----------
    Hamrock, Schmid & Jacobson, Fundamentals of Fluid Film Lubrication, ch. 15
    (squeeze film between parallel rectangular plates); Timoshenko & Goodier, torsion of a
    rectangular bar (same series).
    """
    eta = _nonnegative("viscosity", viscosity)
    h = _positive("gap", gap)
    a = _positive("bearing_length", bearing_length)
    b = _positive("bearing_width", bearing_width)
    long_side = np.maximum(a, b)
    short_side = np.minimum(a, b)
    n = 2.0 * np.arange(terms) + 1.0
    ratio = (long_side / short_side)[..., None]
    series = np.sum(np.tanh(n * np.pi * ratio / 2.0) / n**5, axis=-1)
    beta = 1.0 - 192.0 / np.pi**5 / (long_side / short_side) * series
    return eta * short_side**3 * long_side / h**3 * beta
