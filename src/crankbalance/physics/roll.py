r"""The roll moment: the free moment about the crank axis, by order.

The crank train turns at constant speed; what it exerts on the block about the crank axis
(y, positive in the crank's sense of rotation, from z toward x) is, for every moving mass
point i (position :math:`r_i`, velocity :math:`v_i`, inertia force
:math:`F_i = -m_i a_i`),

.. math:: M_y = \sum_i \left[(r_i \times F_i)_y - \frac{F_i \cdot v_i}{\omega}\right]

(the rate of change of the train's angular momentum, and the reaction of the torque the
inertia forces put on the crank, :math:`T = \sum_i F_i\cdot v_i/\omega`, which the crank
passes to what it drives). The masses turning with the crankpin at constant speed add
nothing. For a piston of mass m on a cylinder with the offset e (the wrist-pin path's
lateral distance from the crank axis), travel s along its axis and :math:`\psi` the crank
angle from the axis, this is

.. math:: M_y = -F\,(e + s'), \qquad F = -m\ddot s,\quad s' = \frac{ds}{d\psi}

the reaction of the inertia torque :math:`F s'` and the moment :math:`-Fe` of the
inertia force whose line misses the crank axis by e (the side force of an offset
cylinder). It does not depend on the bank angle. In units of :math:`m r^2\omega^2` it is
a function of :math:`\psi`, :math:`\lambda = r/l` and :math:`e/r` alone; its harmonics
:math:`d_n` (:func:`roll_coefficients`) are such that

.. math:: M_y = m r^2\omega^2\,\mathrm{Re}\sum_n d_n e^{in\psi}.

With the textbook series of the slider-crank (no offset) the inertia torque on the crank
is :math:`m r^2\omega^2[(\lambda/4 + \lambda^3/16)\sin\psi - \tfrac12\sin 2\psi -
(3\lambda/4 + 9\lambda^3/32)\sin 3\psi - (\lambda^2/4)\sin 4\psi + \dots]`, and
:math:`M_y` is its negative (``tests/test_roll.py`` holds the exact coefficients to it).

The gas forces' torque and its reaction are the engine cycle's
(:mod:`crankbalance.physics.engine_cycle`), not counted here.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # the master-and-link rods are imported where they are used
    from numpy.typing import NDArray

    from .articulated import ArticulatedRods

from .kinematics import (
    FOURIER_SAMPLES,
    KinematicsModel,
    harmonic_coefficients,
    piston_acceleration,
    piston_velocity,
)

#: Orders of the truncated series models ("series", "first-order") beyond the highest
#: one asked for that enter the products: the series has no order above 6.
SERIES_ORDERS = 6


def _samples(orders: int) -> int:
    """Samples per revolution for the harmonics of orders 1..``orders`` of a product of
    two series of up to ``orders + SERIES_ORDERS`` orders: above twice its highest order."""
    n = FOURIER_SAMPLES
    while n <= 4 * (orders + SERIES_ORDERS):
        n *= 2
    return n


@functools.lru_cache(maxsize=64)
def roll_coefficients(
    rod_ratio: float, offset_ratio: float, orders: int, kinematics: KinematicsModel = "exact"
) -> NDArray[np.complex128]:
    r"""Harmonics :math:`d_n` of one piston's roll moment on the block, per :math:`m r^2\omega^2`.

    Parameters
    ----------
    rod_ratio : float
        :math:`\lambda = r/l` [-].
    offset_ratio : float
        :math:`e/r` [-], the wrist-pin path's offset over the crank radius.
    orders : int
        Highest order K [-].
    kinematics : {"exact", "series", "first-order"}
        ``"exact"``: the exact motion; the others: the piston travel and inertia of their
        truncated series (:func:`crankbalance.physics.kinematics.harmonic_coefficients`,
        offset neglected in the motion, kept as the inertia force's lever).

    Returns
    -------
    ndarray of complex, shape (K,)
        :math:`d_n` of orders 1..K, :math:`M_y = m r^2\omega^2\,\mathrm{Re}\sum_n d_n
        e^{in\psi}` [-]; read-only (cached). The row of :func:`roll_harmonics` for one pair.
    """
    out = roll_harmonics(np.array([rod_ratio]), np.array([offset_ratio]), orders, kinematics)[0]
    out.flags.writeable = False
    return out


def roll_harmonics(
    rod_ratio: NDArray[np.float64],
    offset_ratio: NDArray[np.float64],
    orders: int,
    kinematics: KinematicsModel = "exact",
) -> NDArray[np.complex128]:
    r"""Harmonics :math:`d_n` of the roll moment of many pistons at once: one row per pair
    of rod ratio and offset (the rows of :func:`roll_coefficients`).

    Parameters
    ----------
    rod_ratio : ndarray, shape (P,)
        :math:`\lambda = r/l` of each pair [-].
    offset_ratio : ndarray, shape (P,)
        :math:`e/r` of each pair [-].
    orders : int
        Highest order K [-].
    kinematics : {"exact", "series", "first-order"}
        As :func:`roll_coefficients`.

    Returns
    -------
    ndarray of complex, shape (P, K)
        :math:`d_n` of orders 1..K of each pair [-].

    Notes
    -----
    The discrete Fourier transform of :math:`-f(\psi)(\epsilon + s'(\psi))` over
    :func:`_samples` equally spaced angles, :math:`f = -\ddot s/(r\omega^2)`, every pair's
    samples transformed by one call. The exact harmonics decay like :math:`\lambda^n`; the
    series' products are trigonometric polynomials of at most twice their highest order,
    which those samples resolve exactly.
    """
    n = _samples(int(orders))
    psi = 2.0 * np.pi * np.arange(n) / n
    lam = np.asarray(rod_ratio, dtype=float)[:, None]
    eps = np.asarray(offset_ratio, dtype=float)[:, None]
    if kinematics == "exact":
        force = -piston_acceleration(psi, 1.0, 1.0 / lam, eps)
        rate = piston_velocity(psi, 1.0, 1.0 / lam, eps)
    else:
        c = harmonic_coefficients(lam[:, 0], int(orders) + SERIES_ORDERS, 0.0, kinematics)
        k = np.arange(1, c.shape[-1] + 1)
        turn = np.exp(1j * np.outer(k, psi))
        force = (c @ turn).real
        rate = ((1j * c / k) @ turn).real  # s = Re sum c_k/k^2 e^{ik psi}
    spectrum = np.fft.fft(-force * (eps + rate), axis=-1) * (2.0 / n)
    return np.array(spectrum[:, 1 : int(orders) + 1])


def articulated_roll(
    rods: ArticulatedRods,
    reciprocating_mass: NDArray[np.float64],
    big_end_mass: NDArray[np.float64],
    orders: int,
    speed: float,
) -> NDArray[np.complex128]:
    r"""Roll moment harmonics of a master-and-link rod assembly, at throw angle 0.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    reciprocating_mass : ndarray, shape (C,)
        Mass moving with each wrist pin [kg].
    big_end_mass : ndarray, shape (C,)
        Big-end part of each rod [kg]; a link rod's moves with its link pin, the master
        rod's turns with the crankpin (and adds nothing).
    orders : int
        Highest order K [-].
    speed : float
        Crank speed [rad/s].

    Returns
    -------
    ndarray of complex, shape (K,)
        :math:`R_n` with :math:`M_y(\theta) = \mathrm{Re}\sum_n R_n e^{in\theta}`,
        :math:`\theta` the throw's crank angle [N·m].

    Notes
    -----
    The exact motion (:func:`crankbalance.physics.articulated.motion`) sampled as many
    times per revolution as the inertia forces' harmonics need
    (:func:`crankbalance.physics.articulated.harmonics`), the sum over the pistons and link
    pins of the module's formula, and its discrete Fourier transform.
    """
    from .articulated import harmonics

    n = harmonics(rods, orders).samples
    theta = 2.0 * np.pi * np.arange(n) / n
    curve = articulated_roll_curve(rods, reciprocating_mass, big_end_mass, theta, speed)
    spectrum = np.fft.fft(curve) * (2.0 / n)
    return np.asarray(spectrum[1 : int(orders) + 1], dtype=complex)


def articulated_roll_curve(
    rods: ArticulatedRods,
    reciprocating_mass: NDArray[np.float64],
    big_end_mass: NDArray[np.float64],
    angle: NDArray[np.float64],
    speed: float,
) -> NDArray[np.float64]:
    r"""Roll moment of a master-and-link rod assembly versus crank angle, exactly.

    Parameters
    ----------
    rods : ArticulatedRods
        The rod assembly.
    reciprocating_mass : ndarray, shape (C,)
        Mass moving with each wrist pin [kg].
    big_end_mass : ndarray, shape (C,)
        Big-end part of each rod [kg] (a link rod's moves with its link pin).
    angle : ndarray, shape (M,)
        Crank angles of the throw [rad].
    speed : float
        Crank speed [rad/s].

    Returns
    -------
    ndarray, shape (M,)
        :math:`M_y` on the block, the module's sum over the pistons and the big ends
        [N·m].
    """
    w = float(speed)
    from .articulated import motion, piston_position

    move = motion(rods, angle, w)
    axis = np.exp(1j * np.asarray(rods.bank_angle, dtype=float))[None, :]
    where = np.concatenate([piston_position(rods, move), move.big_end], axis=1)
    rate = np.concatenate([move.travel_velocity * axis, move.big_end_velocity], axis=1)
    accel = np.concatenate([move.travel_acceleration * axis, move.big_end_acceleration], axis=1)
    mass = np.concatenate([reciprocating_mass, big_end_mass])[None, :]
    force = -mass * accel
    roll = (np.conj(where) * force).imag - (np.conj(force) * rate).real / w
    return np.asarray(roll.sum(axis=1), dtype=float)
