r"""Single-cylinder balance factor, in-line and transverse forces, and the balance-factor
study (rebalancing a crank after new parts: :mod:`crankbalance.physics.rebalancing`).

**Balance factor.** The balance factor :math:`f_b` is the share of the reciprocating mass
*of one cylinder* that the crank counterweight balances, *on top of 100 % of the rotating
mass*. The counterweight's first moment is therefore (Hoem and Røsholm (2016), Eq. 4.6 and 6.1,
corrected)

.. math:: m_{cw}\,r' = (m_{rot} + f_b\,m_{rec})\,r

so :math:`f_b = 0` balances the rotating mass only, :math:`f_b = 0.5` adds half the
reciprocating mass ("50 %"), :math:`f_b = 1` all of it. Other definitions in use (share of
rotating *plus* reciprocating mass, or of the whole conrod) are *not* this one.

**Forces.** With the rotating mass balanced, the shaking force of one cylinder on the
frame is the reciprocating inertia along the cylinder axis plus the centrifugal force of the
extra counterweight :math:`f_b m_{rec}` (at the crank radius, opposite the crankpin):

.. math::
    F_i = -m_{rec}\,\ddot s - f_b\,P\cos\theta,\qquad F_t = -f_b\,P\sin\theta,
    \qquad P = m_{rec}\,r\,\omega^2

With the first-order model :math:`-\ddot s = r\omega^2\cos\theta` this is Hoem and Røsholm (2016),
Eq. 4.7/4.8:
:math:`F_i = (1-f_b)P\cos\theta`, :math:`F_t = -f_b P\sin\theta`, whose peak resultant is
:math:`\max(f_b, |1-f_b|)\,P`, least at :math:`f_b = 0.5`.

Angles: :math:`\theta` from the cylinder axis (0 at top dead centre); in-line positive away
from the crank along the cylinder axis, transverse positive toward the side the crankpin
moves to just after top dead centre. SI units throughout.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_positive, check_range
from ..records import record
from ..results import ResultMixin
from .kinematics import KINEMATICS_MODELS, KinematicsModel, piston_acceleration
from .limits import BALANCE_FACTOR_RANGE as BALANCE_FACTOR_RANGE

# ---------------------------------------------------------------------------------------
# validation helpers
# ---------------------------------------------------------------------------------------


def check_balance_factor(value: float, field_name: str = "balance_factor") -> float:
    """Return ``value`` if it is a balance factor in :data:`BALANCE_FACTOR_RANGE`, else raise
    :class:`~crankbalance.errors.InputError` naming ``field_name``.

    Parameters
    ----------
    value : float
        Balance factor :math:`f_b` to check [-].
    field_name : str
        Name of the input it came from, used in the error message.

    Returns
    -------
    float
        ``value``, when it lies in [0, 2] [-].

    Raises
    ------
    InputError
        If ``value`` is not a finite number in :data:`BALANCE_FACTOR_RANGE`.
    """
    low, high = BALANCE_FACTOR_RANGE
    return check_range(field_name, value, low, high)


def check_mass(field_name: str, value: float) -> float:
    """A mass as given, or :class:`~crankbalance.errors.InputError` naming the field.

    Parameters
    ----------
    field_name : str
        The field to name in the error.
    value : float
        The mass [kg].

    Returns
    -------
    float
        ``value``, finite and not negative [kg].
    """
    if not (value >= 0 and math.isfinite(value)):
        raise InputError(field_name, value, "must be a finite mass >= 0 [kg]")
    return float(value)


def _check_model(model: str) -> None:
    if model not in KINEMATICS_MODELS:
        raise InputError("model", model, f"must be one of {', '.join(KINEMATICS_MODELS)}")


# ---------------------------------------------------------------------------------------
# tier 1: pure functions
# ---------------------------------------------------------------------------------------


def primary_force(reciprocating_mass: float, crank_radius: float, speed: float) -> float:
    r"""Amplitude of the primary reciprocating force :math:`P = m_{rec} r \omega^2` [N].

    Parameters
    ----------
    reciprocating_mass : float
        Reciprocating mass of one cylinder [kg].
    crank_radius : float
        Crank throw radius [m].
    speed : float
        Crank speed [rad/s].

    Returns
    -------
    float
        :math:`P` [N].

    References
    ----------
    Hoem and Røsholm (2016) Eq. 4.5.
    """
    return reciprocating_mass * crank_radius * speed**2


def single_cylinder_forces(
    angle: ArrayLike,
    balance_factor: ArrayLike,
    reciprocating_mass: float,
    crank_radius: float,
    speed: float,
    rod_length: float | None = None,
    offset: float = 0.0,
    model: KinematicsModel = "exact",
) -> tuple[NDArray, NDArray]:
    r"""In-line and transverse shaking force of one cylinder [N] with the rotating mass balanced.

    Parameters
    ----------
    angle : array_like
        Crank angle :math:`\theta` from the cylinder axis [rad].
    balance_factor : array_like
        :math:`f_b` [-]: share of the reciprocating mass balanced by the counterweight on
        top of the rotating mass; broadcasts against ``angle``.
    reciprocating_mass : float
        Reciprocating mass of the cylinder [kg].
    crank_radius : float
        Crank throw radius [m].
    speed : float
        Crank speed [rad/s].
    rod_length : float, optional
        Conrod length [m]; needed for ``"exact"`` and ``"series"``.
    offset : float
        Lateral offset of the wrist-pin path [m]; must be 0 unless ``model="exact"``.
    model : {"exact", "series", "first-order"}
        Piston kinematics.

    Returns
    -------
    in_line, transverse : ndarray
        Forces along and across the cylinder axis [N].

    Notes
    -----
    .. math::
        F_i = -m_{rec}\ddot s - f_b m_{rec} r\omega^2\cos\theta,\qquad
        F_t = -f_b m_{rec} r\omega^2\sin\theta

    References
    ----------
    Hoem and Røsholm (2016) Eq. 4.7 and 4.8 (first-order model, :math:`r' = r`).
    """
    _check_model(model)
    if not math.isfinite(offset):
        raise InputError("offset", offset, "must be a finite length [m]")
    if offset != 0.0 and model != "exact":
        raise InputError(
            "offset",
            offset,
            f"the {model!r} kinematics has no wrist-pin offset; use model='exact' "
            "(with the conrod length) or offset = 0",
        )
    psi = np.asarray(angle, dtype=float)
    fb = np.asarray(balance_factor, dtype=float)
    p = primary_force(reciprocating_mass, crank_radius, speed)
    if model == "first-order":
        inertia = np.cos(psi)
    else:
        if rod_length is None:
            raise InputError(
                "rod_length",
                rod_length,
                f"the {model!r} kinematics needs the conrod length; "
                "give it or use model='first-order'",
            )
        if model == "exact":
            inertia = -piston_acceleration(psi, crank_radius, rod_length, offset) / crank_radius
        else:
            from .kinematics import series_coefficients

            a2, a4, a6 = series_coefficients(crank_radius / rod_length)
            inertia = (
                np.cos(psi) + a2 * np.cos(2 * psi) + a4 * np.cos(4 * psi) + a6 * np.cos(6 * psi)
            )
    in_line = p * (inertia - fb * np.cos(psi))
    transverse = -p * fb * np.sin(psi) * np.ones_like(in_line)
    return in_line, transverse


def first_order_peak_resultant(balance_factor: ArrayLike) -> NDArray:
    r"""Peak resultant of the first-order model over :math:`P` [-]: :math:`\max(f_b, |1-f_b|)`.

    Parameters
    ----------
    balance_factor : array_like
        :math:`f_b` [-], any shape.

    Returns
    -------
    ndarray
        Largest resultant shaking force over a revolution divided by
        :math:`P = m_{rec} r \omega^2` [-], the shape of ``balance_factor``.

    References
    ----------
    Hoem and Røsholm (2016) Fig. 4.8 (least at :math:`f_b = 0.5`).
    """
    fb = np.asarray(balance_factor, dtype=float)
    return np.maximum(fb, np.abs(1.0 - fb))


def counterweight_moment(
    rotating_mass: float, reciprocating_mass: float, balance_factor: float, crank_radius: float
) -> float:
    r"""First moment the counterweight (webs included) must have [kg m].

    Parameters
    ----------
    rotating_mass : float
        :math:`m_{rot}`: crankpin + conrod big end + big-end bearing [kg].
    reciprocating_mass : float
        :math:`m_{rec}`: piston assembly + wrist pin + conrod small end [kg].
    balance_factor : float
        :math:`f_b` in [0, 2] [-].
    crank_radius : float
        :math:`r`: crank throw radius [m].

    Returns
    -------
    float
        :math:`m_{cw}\,r'` [kg m].

    Notes
    -----
    .. math:: m_{cw}\,r' = (m_{rot} + f_b\,m_{rec})\,r

    References
    ----------
    Hoem and Røsholm (2016) Eq. 6.1, corrected: the print reads :math:`(m_{rec} + f_b m_{rec})`;
    the rotating mass belongs in the first term (cf. Eq. 4.6 and 6.2).
    """
    check_mass("rotating_mass", rotating_mass)
    check_mass("reciprocating_mass", reciprocating_mass)
    check_balance_factor(balance_factor)
    check_positive("crank_radius", crank_radius)
    return (rotating_mass + balance_factor * reciprocating_mass) * crank_radius


def balance_factor_from_mass_properties(
    counterweight_mass: float,
    counterweight_radius: float,
    crank_radius: float,
    rotating_mass: float,
    reciprocating_mass: float,
) -> float:
    r"""Balance factor of an existing crank from its mass properties [-].

    Parameters
    ----------
    counterweight_mass : float
        :math:`m_{cw}`: mass of the counterweights plus crank webs [kg].
    counterweight_radius : float
        :math:`r'`: distance of their common centre of gravity from the crank axis [m].
    crank_radius : float
        :math:`r`: crank throw radius (half the stroke) [m].
    rotating_mass : float
        :math:`m_{rot}`: crankpin + conrod big end + big-end bearing [kg].
    reciprocating_mass : float
        :math:`m_{rec}`: piston assembly + wrist pin + conrod small end (+ bearing) [kg].

    Returns
    -------
    float
        :math:`f_b` [-] (not checked against :data:`BALANCE_FACTOR_RANGE`).

    Notes
    -----
    .. math:: f_b = \frac{m_{cw}\,r'/r - m_{rot}}{m_{rec}}

    References
    ----------
    Hoem and Røsholm (2016) Eq. 6.2; Sec. 6.3.3: 2020.40 g, 6.16 mm, 26.9 mm -> 0.6375.
    """
    check_mass("counterweight_mass", counterweight_mass)
    check_positive("counterweight_radius", counterweight_radius)
    check_positive("crank_radius", crank_radius)
    check_mass("rotating_mass", rotating_mass)
    check_positive("reciprocating_mass", reciprocating_mass)
    return (
        counterweight_mass * counterweight_radius / crank_radius - rotating_mass
    ) / reciprocating_mass


def bob_weight(rotating_mass: float, reciprocating_mass: float, balance_factor: float) -> float:
    r"""Bob-weight to clamp on the crankpin in a balancing machine [kg].

    With the bob-weight at the crank radius the crank runs smooth exactly when its
    counterweight has the target balance factor.

    Parameters
    ----------
    rotating_mass : float
        :math:`m_{rot}` [kg].
    reciprocating_mass : float
        :math:`m_{rec}` [kg].
    balance_factor : float
        Target :math:`f_b` in [0, 2] [-].

    Returns
    -------
    float
        :math:`m_{bob}` [kg].

    Notes
    -----
    .. math:: m_{bob} = m_{rot} + f_b\,m_{rec}

    References
    ----------
    Hoem and Røsholm (2016) Sec. 3.2 and 6.3.2 (force balance before Eq. 6.1).
    """
    check_mass("rotating_mass", rotating_mass)
    check_mass("reciprocating_mass", reciprocating_mass)
    check_balance_factor(balance_factor)
    return rotating_mass + balance_factor * reciprocating_mass


def sum_parts(parts: dict[str, float], field_name: str = "parts") -> float:
    """Sum named part masses [kg], refusing negative or non-finite entries.

    Parameters
    ----------
    parts : dict of str to float
        Part name to mass [kg].
    field_name : str
        Prefix of the field named in the error message (``field_name.part``).

    Returns
    -------
    float
        Sum of the masses [kg].

    Raises
    ------
    InputError
        If a mass is negative or not finite.
    """
    total = 0.0
    for name, mass in parts.items():
        total += check_mass(f"{field_name}.{name}", mass)
    return total


# ---------------------------------------------------------------------------------------
# tier 3 orchestrator: balance factor study
# ---------------------------------------------------------------------------------------


@record
class BalanceFactorStudy(ResultMixin):
    """Forces of one cylinder over a revolution for one balance factor, and the sweep.

    Attributes
    ----------
    balance_factor : float
        :math:`f_b` studied [-] (share of the reciprocating mass on the counterweight, on top
        of 100 % of the rotating mass).
    model : str
        Piston kinematics used.
    primary_force : float
        :math:`P = m_{rec} r \\omega^2` [N].
    crank_angle : ndarray
        Crank angles [rad].
    in_line, transverse, resultant : ndarray
        Forces at those angles [N].
    direction : ndarray
        Direction of the residual force vector, from the cylinder axis toward the
        transverse axis [rad] (the polar curve is ``(resultant, direction)``).
    in_line_amplitude, transverse_amplitude, peak_resultant : float
        Largest magnitudes over a revolution [N].
    sweep_balance_factor, sweep_peak_resultant : ndarray
        Peak resultant [N] against the balance factor [-].
    optimum_balance_factor, optimum_peak_resultant : float
        Balance factor with the least peak resultant [-] and that peak [N].
    """

    balance_factor: float
    model: str
    primary_force: float
    crank_angle: NDArray
    in_line: NDArray
    transverse: NDArray
    resultant: NDArray
    direction: NDArray
    in_line_amplitude: float
    transverse_amplitude: float
    peak_resultant: float
    sweep_balance_factor: NDArray
    sweep_peak_resultant: NDArray
    optimum_balance_factor: float
    optimum_peak_resultant: float


def _refined_peak(fun: Callable[[NDArray], NDArray], samples: int = 720) -> float:
    """Largest value of a smooth 2*pi-periodic function: grid search, then local refinement."""
    from scipy.optimize import minimize_scalar

    grid = 2.0 * np.pi * np.arange(samples) / samples
    values = fun(grid)
    k = int(np.argmax(values))
    step = 2.0 * np.pi / samples
    best = minimize_scalar(
        lambda x: -float(fun(np.array([x]))[0]),
        bounds=(grid[k] - step, grid[k] + step),
        method="bounded",
        options={"xatol": 1e-12},
    )
    return max(float(values[k]), -float(best.fun))


def peak_resultant(
    balance_factor: float,
    reciprocating_mass: float,
    crank_radius: float,
    speed: float,
    rod_length: float | None = None,
    offset: float = 0.0,
    model: KinematicsModel = "exact",
) -> float:
    r"""Largest magnitude of the residual shaking force over one revolution [N].

    Parameters
    ----------
    balance_factor : float
        :math:`f_b` [-].
    reciprocating_mass : float
        Reciprocating mass of the cylinder [kg].
    crank_radius : float
        Crank throw radius [m].
    speed : float
        Crank speed [rad/s].
    rod_length : float, optional
        Conrod length [m]; needed unless ``model="first-order"``.
    offset : float
        Lateral wrist-pin path offset [m]; must be 0 unless ``model="exact"``.
    model : {"exact", "series", "first-order"}
        Piston kinematics.

    Returns
    -------
    float
        Peak resultant force [N] (720-point grid, refined locally).

    Notes
    -----
    .. math:: \max_\theta \sqrt{F_i(\theta)^2 + F_t(\theta)^2}

    References
    ----------
    Hoem and Røsholm (2016) Fig. 4.8.
    """

    def magnitude(psi: NDArray) -> NDArray:
        fi, ft = single_cylinder_forces(
            psi, balance_factor, reciprocating_mass, crank_radius, speed, rod_length, offset, model
        )
        return np.hypot(fi, ft)

    return _refined_peak(magnitude)


def balance_factor_study(
    reciprocating_mass: float,
    crank_radius: float,
    speed: float,
    balance_factor: float = 0.5,
    rod_length: float | None = None,
    offset: float = 0.0,
    model: KinematicsModel = "exact",
    samples: int = 360,
    sweep: Sequence[float] | NDArray | None = None,
) -> BalanceFactorStudy:
    r"""Forces versus crank angle for one balance factor, and the peak resultant versus f_b.

    Parameters
    ----------
    reciprocating_mass : float
        Reciprocating mass of the cylinder [kg].
    crank_radius : float
        Crank throw radius [m].
    speed : float
        Crank speed [rad/s].
    balance_factor : float
        :math:`f_b` in [0, 2] [-]: share of the reciprocating mass balanced by the
        counterweight, on top of 100 % of the rotating mass.
    rod_length : float, optional
        Conrod length [m]; needed unless ``model="first-order"``.
    offset : float
        Lateral wrist-pin path offset [m]; must be 0 unless ``model="exact"``.
    model : {"exact", "series", "first-order"}
        Piston kinematics.
    samples : int
        Crank angles per revolution in the returned curves.
    sweep : sequence of float, optional
        Balance factors of the sweep [-], each in [0, 2]; default 0, 0.01, ..., 1.

    Returns
    -------
    BalanceFactorStudy
        Curves for ``balance_factor``, the sweep and the optimum balance factor.

    Notes
    -----
    .. math::
        F_i = -m_{rec}\ddot s - f_b P\cos\theta,\quad F_t = -f_b P\sin\theta,\quad
        f_b^{*} = \arg\min_{f_b}\max_\theta |F|

    References
    ----------
    Hoem and Røsholm (2016) Sec. 4.1.2, Eq. 4.7-4.8, Fig. 4.4-4.8.
    """
    from scipy.optimize import minimize_scalar

    _check_model(model)
    check_positive("reciprocating_mass", reciprocating_mass)
    check_positive("crank_radius", crank_radius)
    check_positive("speed", speed)
    check_balance_factor(balance_factor)
    if rod_length is not None:
        check_positive("rod_length", rod_length)
        if rod_length <= crank_radius + abs(offset):
            raise InputError(
                "rod_length", rod_length, "must exceed the crank radius plus the offset"
            )
    if model != "first-order" and rod_length is None:
        raise InputError(
            "rod_length",
            rod_length,
            f"the {model!r} kinematics needs the conrod length; give it or use model='first-order'",
        )
    if not (isinstance(samples, int) and samples >= 8):
        raise InputError("samples", samples, "must be an integer >= 8")
    args = (reciprocating_mass, crank_radius, speed, rod_length, offset, model)
    theta = 2.0 * np.pi * np.arange(samples) / samples
    fi, ft = single_cylinder_forces(theta, balance_factor, *args)
    resultant = np.hypot(fi, ft)
    direction = np.arctan2(ft, fi)

    def peak(fb: float) -> float:
        return peak_resultant(fb, *args)

    def amplitude(fun: Callable[[NDArray], NDArray]) -> float:
        return _refined_peak(lambda psi: np.abs(fun(psi)))

    in_line_amplitude = amplitude(lambda psi: single_cylinder_forces(psi, balance_factor, *args)[0])
    transverse_amplitude = amplitude(
        lambda psi: single_cylinder_forces(psi, balance_factor, *args)[1]
    )
    fbs = np.linspace(0.0, 1.0, 101) if sweep is None else np.asarray(sweep, dtype=float)
    for value in fbs:
        check_balance_factor(float(value), "sweep")
    sweep_peak = np.array([peak(float(fb)) for fb in fbs])
    # the peak is a maximum of norms of functions affine in f_b, hence convex in f_b
    best = minimize_scalar(
        peak, bounds=BALANCE_FACTOR_RANGE, method="bounded", options={"xatol": 1e-9}
    )
    return BalanceFactorStudy(
        balance_factor=float(balance_factor),
        model=model,
        primary_force=primary_force(reciprocating_mass, crank_radius, speed),
        crank_angle=theta,
        in_line=fi,
        transverse=ft,
        resultant=resultant,
        direction=direction,
        in_line_amplitude=in_line_amplitude,
        transverse_amplitude=transverse_amplitude,
        peak_resultant=peak(balance_factor),
        sweep_balance_factor=fbs,
        sweep_peak_resultant=sweep_peak,
        optimum_balance_factor=float(best.x),
        optimum_peak_resultant=float(best.fun),
    )
