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

import functools
from typing import TYPE_CHECKING, Literal

import numpy as np

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import ArrayLike, NDArray

KinematicsModel = Literal["exact", "series", "first-order"]
KINEMATICS_MODELS: tuple[str, ...] = ("exact", "series", "first-order")

#: Number of samples per revolution used for the Fourier analysis of the exact motion.
#: The harmonic amplitudes decay like rod_ratio**n, so 64 samples leave an aliasing
#: error far below round-off for any rod ratio a real engine has (< 0.5).
FOURIER_SAMPLES = 64

#: Engines computed together by the batched functions (here and in
#: :mod:`crankbalance.physics.shaking`): the temporaries of one chunk stay in the processor's
#: cache, and the memory of a call is its results and one chunk's temporaries.
CHUNK = 1024


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

    Notes
    -----
    The exact coefficients of one rod ratio and offset (scalars) are kept in a small
    cache (:func:`cached_exact_coefficients`); arrays are computed afresh.
    """
    lam = np.asarray(rod_ratio, dtype=float)
    if model == "exact":
        offset = np.asarray(offset_ratio, dtype=float)
        if lam.ndim == 0 and offset.ndim == 0:
            return cached_exact_coefficients(float(lam), float(offset), int(orders)).copy()
        return exact_coefficients(lam, orders, offset)
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


@functools.lru_cache(maxsize=8)
def _half_turn(orders: int, zero_offset: bool) -> tuple[NDArray, NDArray, NDArray]:
    """Sample angles of the exact motion and the weights that turn samples into harmonics.

    Returns the sines and squared cosines of the sample angles and the weight matrix W, so
    that ``A(samples) @ W`` are the coefficients of the orders W's columns belong to
    (see :func:`exact_coefficients`). Read-only arrays, built once per ``orders``.
    """
    n = FOURIER_SAMPLES
    while n < 4 * orders:
        n *= 2
    j = np.arange(-(n // 4), n // 4 + 1)
    psi = 2.0 * np.pi * j / n
    order = np.arange(1, orders + 1)
    even = order % 2 == 0
    # the samples at psi and pi - psi are equal: count each interior one twice; the two at
    # psi = +-pi/2 are their own mirror image
    fold = np.where(np.abs(j) == n // 4, 1.0, 2.0)[:, None]
    angle = np.outer(psi, order)
    weights = (2.0 / n) * fold * np.where(even, np.cos(angle), np.sin(angle))
    sin, cos2 = np.sin(psi), np.cos(psi) ** 2
    if zero_offset:
        # the samples are also even in psi: fold -psi onto psi; the sine weights cancel
        half = n // 4
        weights = weights[half:, even].copy()
        weights[1:] += weights[1:]
        sin, cos2 = sin[half:], cos2[half:]
    for array in (sin, cos2, weights):
        array.flags.writeable = False
    return sin, cos2, weights


def exact_coefficients(
    rod_ratio: ArrayLike, orders: int = 8, offset_ratio: ArrayLike = 0.0
) -> NDArray[np.complex128]:
    r"""Exact harmonic coefficients :math:`c_n = a_n - i b_n` of the piston inertia.

    The exact normalised inertia is :math:`f(\psi) = \cos\psi + A(\psi)` with

    .. math:: A = \frac{1}{q}\left(\cos^2\psi + u\sin\psi
              + \frac{u^2\cos^2\psi}{q^2}\right),\quad u = \epsilon - \sin\psi,
              \quad q = \sqrt{\lambda^{-2} - u^2}

    (:func:`piston_acceleration` with :math:`r = 1`, :math:`l = 1/\lambda`). A depends on
    :math:`\sin\psi` and :math:`\cos^2\psi` only, so :math:`A(\pi - \psi) = A(\psi)`:
    its even orders have no sine part, its odd orders no cosine part, and the cosine of the
    first order is exactly 1. The discrete Fourier transform of the
    :data:`FOURIER_SAMPLES` (or more) equally spaced samples of a revolution is therefore
    taken from the samples of half a revolution, :math:`|\psi| \le \pi/2`, as one
    real matrix product; with no offset A is also even in :math:`\psi` and a quarter of
    a revolution suffices.

    Parameters
    ----------
    rod_ratio : array_like
        :math:`\lambda = r/l` [-], any shape (one value per engine).
    orders : int
        Highest order returned.
    offset_ratio : array_like
        :math:`\epsilon = e/r` [-], lateral wrist-pin path offset over crank radius,
        broadcast against ``rod_ratio``.

    Returns
    -------
    ndarray of complex, shape ``broadcast(rod_ratio, offset_ratio).shape + (orders,)``
        :math:`c_n` of orders 1..``orders`` [-].
    """
    lam = np.asarray(rod_ratio, dtype=float)
    offset = np.asarray(offset_ratio, dtype=float)
    shape = np.broadcast_shapes(lam.shape, offset.shape)
    inv2 = np.broadcast_to(lam, shape).reshape(-1) ** -2.0
    zero_offset = not np.any(offset)
    offset = np.broadcast_to(offset, shape).reshape(-1)
    sin, cos2, weights = _half_turn(int(orders), zero_offset)
    s2 = sin * sin
    out = np.zeros((inv2.size, orders), dtype=complex)
    for start in range(0, inv2.size, CHUNK):  # bounded temporaries, one thread of BLAS
        part = slice(start, start + CHUNK)
        if zero_offset:
            q2 = inv2[part, None] - s2
            samples = ((cos2 - s2) + (cos2 * s2) / q2) / np.sqrt(q2)
            out.real[part, 1::2] = samples @ weights
        else:
            u = offset[part, None] - sin
            u2 = u * u
            q2 = inv2[part, None] - u2
            samples = (cos2 + u * sin + (cos2 * u2) / q2) / np.sqrt(q2)
            parts = samples @ weights
            out.real[part, 1::2] = parts[:, 1::2]
            out.imag[part, 0::2] = -parts[:, 0::2]
    out.real[:, 0] = 1.0
    return out.reshape(shape + (orders,))


#: How many (rod ratio, offset ratio, orders) the cache of exact coefficients keeps.
CACHE_SIZE = 256


@functools.lru_cache(maxsize=CACHE_SIZE)
def cached_exact_coefficients(
    rod_ratio: float, offset_ratio: float, orders: int
) -> NDArray[np.complex128]:
    r""":func:`exact_coefficients` of one engine, kept for the next call with the same
    arguments (least recently used out beyond :data:`CACHE_SIZE` entries).

    Parameters
    ----------
    rod_ratio : float
        :math:`\lambda = r/l` [-].
    offset_ratio : float
        :math:`e/r` [-].
    orders : int
        Highest order returned.

    Returns
    -------
    ndarray of complex, shape (orders,)
        :math:`c_n` of orders 1..``orders`` [-]; read-only (it is shared), copy to change.
    """
    out = exact_coefficients(np.array([rod_ratio]), orders, np.array([offset_ratio]))[0]
    out.flags.writeable = False
    return out


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
