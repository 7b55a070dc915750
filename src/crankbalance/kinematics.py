r"""Slider-crank kinematics: exact piston motion and its harmonic content.

Conventions (see ``docs/theory.md``): the crank turns at constant speed :math:`\omega`;
:math:`\psi` is the crank angle measured from the cylinder axis (0 at top dead centre
for zero offset); :math:`s` is the wrist-pin distance from the crank axis along the
cylinder axis. The wrist pin moves on a line parallel to the cylinder axis at the lateral
distance ``offset`` (crank offset plus wrist-pin offset, positive on the side the crankpin
moves toward just after :math:`\psi = 0`).

All functions are pure numpy and broadcast over their arguments, so many crank angles
and many engines are evaluated at once.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

KinematicsModel = Literal["exact", "series", "first-order"]
KINEMATICS_MODELS: tuple[str, ...] = ("exact", "series", "first-order")

#: Number of samples per revolution used for the Fourier analysis of the exact motion.
#: The harmonic amplitudes decay like rod_ratio**n, so 64 samples leave an aliasing
#: error far below round-off for any rod ratio a real engine has (< 0.5).
FOURIER_SAMPLES = 64


def _rod_terms(
    angle: ArrayLike, crank_radius: ArrayLike, rod_length: ArrayLike, offset: ArrayLike
) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    psi = np.asarray(angle, dtype=float)
    r = np.asarray(crank_radius, dtype=float)
    u = np.asarray(offset, dtype=float) - r * np.sin(psi)
    q = np.sqrt(np.asarray(rod_length, dtype=float) ** 2 - u**2)
    return psi, r, u, q


def piston_position(
    angle: ArrayLike, crank_radius: ArrayLike, rod_length: ArrayLike, offset: ArrayLike = 0.0
) -> NDArray:
    r"""Wrist-pin distance from the crank axis along the cylinder axis [m].

    Parameters
    ----------
    angle : array_like
        Crank angle from the cylinder axis [rad].
    crank_radius : array_like
        Crank throw radius [m].
    rod_length : array_like
        Conrod length, big-end to small-end centre [m].
    offset : array_like
        Lateral distance of the wrist-pin path from the crank axis [m].

    Returns
    -------
    ndarray
        Wrist-pin distance from the crank axis [m], the broadcast shape of the arguments.

    Notes
    -----
    .. math:: s = r\cos\psi + \sqrt{l^2 - (e - r\sin\psi)^2}

    References
    ----------
    Any machine-dynamics text; Hoem and Røsholm (2016) section 2.1 for :math:`e = 0`.
    """
    psi, r, _u, q = _rod_terms(angle, crank_radius, rod_length, offset)
    return r * np.cos(psi) + q


def piston_velocity(
    angle: ArrayLike,
    crank_radius: ArrayLike,
    rod_length: ArrayLike,
    offset: ArrayLike = 0.0,
    speed: ArrayLike = 1.0,
) -> NDArray:
    r"""Piston velocity along the cylinder axis [m/s] at constant crank speed [rad/s].

    Parameters
    ----------
    angle : array_like
        Crank angle from the cylinder axis [rad].
    crank_radius : array_like
        Crank throw radius [m].
    rod_length : array_like
        Conrod length, big-end to small-end centre [m].
    offset : array_like
        Lateral distance of the wrist-pin path from the crank axis [m].
    speed : array_like
        Crank speed [rad/s]; the default 1 gives the derivative with respect to the crank
        angle, ``ds/dpsi`` [m/rad].

    Returns
    -------
    ndarray
        Piston velocity [m/s], the broadcast shape of the arguments; positive away from
        the crank axis.

    Notes
    -----
    .. math:: \dot s = \omega\left(-r\sin\psi + \frac{u\,r\cos\psi}{q}\right),\quad
              u = e - r\sin\psi,\ q = \sqrt{l^2 - u^2}

    References
    ----------
    The derivative of :func:`piston_position`; Hoem and Røsholm (2016) section 2.1 for
    :math:`e = 0`.
    """
    psi, r, u, q = _rod_terms(angle, crank_radius, rod_length, offset)
    return np.asarray(speed) * (-r * np.sin(psi) + u * r * np.cos(psi) / q)


def piston_acceleration(
    angle: ArrayLike,
    crank_radius: ArrayLike,
    rod_length: ArrayLike,
    offset: ArrayLike = 0.0,
    speed: ArrayLike = 1.0,
) -> NDArray:
    r"""Piston acceleration along the cylinder axis [m/s²] at constant crank speed.

    Parameters
    ----------
    angle : array_like
        Crank angle from the cylinder axis [rad].
    crank_radius : array_like
        Crank throw radius [m].
    rod_length : array_like
        Conrod length, big-end to small-end centre [m].
    offset : array_like
        Lateral distance of the wrist-pin path from the crank axis [m].
    speed : array_like
        Crank speed [rad/s]; the default 1 gives the derivative with respect to the crank
        angle, ``d2s/dpsi2`` [m/rad²].

    Returns
    -------
    ndarray
        Piston acceleration [m/s²], the broadcast shape of the arguments; positive away
        from the crank axis.

    Notes
    -----
    .. math:: \ddot s = \omega^2\left(-r\cos\psi - \frac{r^2\cos^2\psi + u\,r\sin\psi}{q}
              - \frac{(u\,r\cos\psi)^2}{q^3}\right)

    References
    ----------
    The second derivative of :func:`piston_position`; Hoem and Røsholm (2016) section 2.1
    for :math:`e = 0`.
    """
    psi, r, u, q = _rod_terms(angle, crank_radius, rod_length, offset)
    c = r * np.cos(psi)
    d2 = -c - (c * c + u * r * np.sin(psi)) / q - (u * c) ** 2 / q**3
    return np.asarray(speed) ** 2 * d2


def harmonic_coefficients(
    rod_ratio: ArrayLike,
    orders: int = 8,
    offset_ratio: ArrayLike = 0.0,
    model: KinematicsModel = "exact",
) -> NDArray[np.complex128]:
    r"""Harmonic coefficients of the piston inertia (normalised acceleration).

    The normalised inertia :math:`f(\psi) = -\ddot s/(r\omega^2)` is written as
    :math:`f = \sum_n a_n\cos n\psi + b_n\sin n\psi`. This returns :math:`c_n = a_n - i b_n`
    for :math:`n = 1..\text{orders}` (last axis), so that the n-th order part is
    :math:`\mathrm{Re}(c_n e^{in\psi})`. With no offset :math:`b_n = 0` and
    :math:`a_n = A_n` of the classical series.

    Parameters
    ----------
    rod_ratio : array_like
        :math:`\lambda = r/l` [-], any shape (one value per engine).
    orders : int
        Highest order returned.
    offset_ratio : array_like
        :math:`e/r` [-], lateral wrist-pin path offset over crank radius.
    model : {"exact", "series", "first-order"}
        ``"exact"``: Fourier analysis of the exact motion; ``"series"``: the classical
        series to :math:`\lambda^5` (offset neglected); ``"first-order"``: :math:`A_1 = 1`,
        :math:`A_2 = \lambda` (as the 2021 paper; offset neglected).

    Returns
    -------
    ndarray of complex, shape ``rod_ratio.shape + (orders,)``
    """
    lam = np.asarray(rod_ratio, dtype=float)
    if model == "exact":
        n = FOURIER_SAMPLES
        while n < 4 * orders:
            n *= 2
        psi = 2.0 * np.pi * np.arange(n) / n
        sin, cos = np.sin(psi), np.cos(psi)
        # the acceleration of piston_acceleration() with r = 1, l = 1/lambda, written out so
        # that the sines and cosines of the sample angles are shared by all engines
        u = np.asarray(offset_ratio, dtype=float)[..., None] - sin
        q = np.sqrt((1.0 / lam[..., None]) ** 2 - u * u)
        uc = u * cos
        f = cos + (cos * cos + u * sin) / q + uc * uc / q**3  # = -s''/(r w^2)
        spectrum = np.fft.rfft(f, axis=-1)
        return 2.0 * spectrum[..., 1 : orders + 1] / n
    out = np.zeros(lam.shape + (orders,), dtype=complex)
    out[..., 0] = 1.0
    if model == "first-order":
        if orders >= 2:
            out[..., 1] = lam
        return out
    if model == "series":
        series = series_coefficients(lam)
        for k, order in enumerate((2, 4, 6)):
            if order <= orders:
                out[..., order - 1] = series[k]
        return out
    raise ValueError(f"unknown kinematics model {model!r}; allowed: {KINEMATICS_MODELS}")


def series_coefficients(rod_ratio: ArrayLike) -> tuple[NDArray, NDArray, NDArray]:
    r"""Classical series coefficients :math:`A_2, A_4, A_6` of the piston inertia.

    Parameters
    ----------
    rod_ratio : array_like
        :math:`\lambda = r/l`, crank radius over conrod length [-], any shape.

    Returns
    -------
    a2, a4, a6 : ndarray
        Coefficients of the second, fourth and sixth order of the normalised piston inertia
        :math:`-\ddot s/(r\omega^2)` [-], each of the shape of ``rod_ratio``.

    Notes
    -----
    Zero wrist-pin offset, series truncated after :math:`\lambda^5`:

    .. math::
        A_2 = \lambda + \tfrac{\lambda^3}{4} + \tfrac{15\lambda^5}{128},\quad
        A_4 = -\left(\tfrac{\lambda^3}{4} + \tfrac{3\lambda^5}{16}\right),\quad
        A_6 = \tfrac{9\lambda^5}{128}

    References
    ----------
    Hoem and Røsholm (2016) Eq. 2.6, with the A6 misprint (9/28) corrected to 9/128 as in
    docs/references.md.
    """
    lam = np.asarray(rod_ratio, dtype=float)
    a2 = lam + lam**3 / 4 + 15 * lam**5 / 128
    a4 = -(lam**3 / 4 + 3 * lam**5 / 16)
    a6 = 9 * lam**5 / 128
    return a2, a4, a6
