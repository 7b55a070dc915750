r"""The rotor test bench of Hoem and Røsholm (2016) and the rotors it runs.

This module owns the single-rotor rig of the thesis, from the rotor to its spin-up:

* inertia of simple rotors (:func:`cylinder_inertia`, :func:`disc_inertia`,
  :func:`point_mass_inertia`, :func:`stepped_rotor_inertia`) and the disc-on-shaft test
  rotor with the inertia of a real crank (:class:`TestRotor`,
  :func:`equal_inertia_test_rotor`, Appendix E);
* crankpin overlap and the effect of stroking the crankpin on the rotating mass and the
  balance factor (:func:`crankpin_overlap`, :func:`stroking_effect`, Appendix C);
* the simulated bench (Sec. 5.2.5): a rigid rotor on two bearings with Coulomb friction
  driven by the actual bearing reactions (weight plus the rotating unbalance, split by
  the bearing positions), spun up by a motor whose torque comes from a PI speed controller
  that follows a ramp to the set speed and holds it (:class:`BenchRotor`,
  :func:`disc_rotor`, :class:`BenchSettings`, :func:`run_bench`, :class:`BenchResult`).
  The required torque is the mean motor torque over the hold (as in the thesis).

Why one module over 800 lines: the inertia helpers and the bench describe one rig (the
Appendix E rotor is the rotor of the Chapter 5 bench; :func:`disc_rotor` and
:func:`equal_inertia_test_rotor` are the same disc-on-journals formula seen from the bench
and from the design side), and no other model uses them. SI units throughout (lengths in
m, masses in kg, inertias in kg m^2).

References
----------
Hoem and Røsholm (2016), Sec. 4.3, Sec. 5.2.5, Appendices C and E.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import field

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, check_finite, check_nonnegative, check_positive, check_range
from ..records import record
from ..results import ResultMixin
from .shop.holes import STEEL_DENSITY
from .single_cylinder import balance_factor_from_mass_properties, check_mass

STANDARD_GRAVITY = 9.80665
#: Most evaluations of the equations of motion one :func:`run_bench` may take; a run that
#: needs more (a stiff rotor: high controller gains or friction on a small inertia, or a
#: very long run) stops with :class:`~crankbalance.errors.InputError` instead of running
#: on. An ordinary run takes about 100 evaluations per simulated revolution.
MAX_BENCH_EVALUATIONS = 500_000


# ======================================================================================
# Rotor test bench (Hoem and Røsholm (2016), Sec. 5.2.5)
# ======================================================================================


@record
class BenchRotor(ResultMixin):
    """A rigid rotor on two journal bearings with Coulomb friction.

    Parameters
    ----------
    mass : float
        Rotor mass [kg].
    inertia : float
        Mass moment of inertia about the spin axis [kg m^2].
    journal_diameter : float
        Diameter of the journals in the bearings [m].
    friction_coefficient : float
        Coulomb friction coefficient of each bearing [-].
    unbalance : float
        Static unbalance :math:`U = m_u r_u` [kg m].
    bearing_positions : tuple of float
        Axial positions of the two bearings [m].
    mass_position : float
        Axial position of the centre of gravity [m].
    unbalance_position : float
        Axial position of the unbalance plane [m].
    gravity : float
        Gravitational acceleration, perpendicular to the spin axis [m/s^2].
    """

    mass: float
    inertia: float
    journal_diameter: float
    friction_coefficient: float
    unbalance: float = 0.0
    bearing_positions: tuple[float, float] = (-0.05, 0.05)
    mass_position: float = 0.0
    unbalance_position: float = 0.0
    gravity: float = STANDARD_GRAVITY

    def __post_init__(self) -> None:
        check_positive("mass", self.mass)
        check_positive("inertia", self.inertia)
        check_positive("journal_diameter", self.journal_diameter)
        check_nonnegative("friction_coefficient", self.friction_coefficient)
        check_nonnegative("unbalance", self.unbalance)
        if self.unbalance**2 > self.mass * self.inertia:
            # U = integral of r dm <= sqrt(integral of r^2 dm * m) = sqrt(I m) (Cauchy-Schwarz)
            raise InputError(
                "unbalance",
                self.unbalance,
                f"cannot exceed sqrt(inertia * mass) = {math.sqrt(self.mass * self.inertia):.4g} "
                "kg m for this rotor (no mass distribution has a larger first moment)",
            )
        check_nonnegative("gravity", self.gravity)
        if len(self.bearing_positions) != 2:
            raise InputError("bearing_positions", self.bearing_positions, "must be two positions")
        a, b = (check_finite("bearing_positions", float(p)) for p in self.bearing_positions)
        if a == b:
            raise InputError(
                "bearing_positions", self.bearing_positions, "must be two different axial positions"
            )
        check_finite("mass_position", self.mass_position)
        check_finite("unbalance_position", self.unbalance_position)

    def load_shares(self, position: float) -> tuple[float, float]:
        """Shares of a force at an axial position carried by bearings A and B (lever rule)."""
        a, b = self.bearing_positions
        share_b = (position - a) / (b - a)
        return 1.0 - share_b, share_b


def disc_rotor(
    disc_diameter: float,
    disc_thickness: float,
    journal_diameter: float,
    length: float,
    friction_coefficient: float,
    density: float = 7850.0,
    hole_mass: float = 0.0,
    hole_radius: float = 0.0,
    bearing_positions: tuple[float, float] | None = None,
) -> BenchRotor:
    r"""The simplified test rotor of the thesis: a disc between two journals.

    .. math::
        m = \rho\frac{\pi}{4}\big(d_1^2 t + d_2^2 (L_1 - t)\big) - m_u,\qquad
        I = \frac{\rho\pi}{32}\big(d_1^4 t + d_2^4 (L_1 - t)\big) - m_u r_u^2,\qquad
        U = m_u r_u

    The drilled hole is treated as a point mass removed at its radius.

    Parameters
    ----------
    disc_diameter : float
        Disc diameter :math:`d_1` [m].
    disc_thickness : float
        Disc thickness :math:`t` [m].
    journal_diameter : float
        Journal diameter :math:`d_2` [m].
    length : float
        Overall length :math:`L_1` [m]; each journal is :math:`(L_1 - t)/2` long.
    friction_coefficient : float
        Coulomb friction coefficient of each bearing [-].
    density : float
        Material density [kg/m^3].
    hole_mass : float
        Mass removed to make the unbalance :math:`m_u` [kg].
    hole_radius : float
        Radius of the removed mass :math:`r_u` [m].
    bearing_positions : tuple of float, optional
        Axial bearing positions from the disc mid-plane [m]; default the journal mid-points,
        :math:`\pm(L_1 + t)/4`.

    Returns
    -------
    BenchRotor
        The rotor with its mass, inertia and unbalance, and the given friction.

    References
    ----------
    Hoem and Røsholm (2016), Appendix E, Eqs. 7.6-7.9 and Table 7.2; Table 5.2 (drilled holes).
    """
    check_positive("disc_diameter", disc_diameter)
    check_positive("disc_thickness", disc_thickness)
    check_positive("journal_diameter", journal_diameter)
    check_positive("length", length)
    check_positive("density", density)
    if disc_thickness >= length:
        raise InputError("disc_thickness", disc_thickness, f"must be less than length = {length}")
    check_nonnegative("hole_mass", hole_mass)
    check_nonnegative("hole_radius", hole_radius)
    journals = length - disc_thickness
    mass = (
        density * np.pi / 4 * (disc_diameter**2 * disc_thickness + journal_diameter**2 * journals)
    )
    inertia = stepped_rotor_inertia(
        disc_diameter, disc_thickness, journal_diameter, length, density
    )
    if hole_mass >= mass:
        raise InputError("hole_mass", hole_mass, f"must be less than the rotor mass {mass:.4g} kg")
    if bearing_positions is None:
        half = (length + disc_thickness) / 4
        bearing_positions = (-half, half)
    return BenchRotor(
        mass=float(mass - hole_mass),
        inertia=float(inertia - hole_mass * hole_radius**2),
        journal_diameter=journal_diameter,
        friction_coefficient=friction_coefficient,
        unbalance=hole_mass * hole_radius,
        bearing_positions=bearing_positions,
    )


@record
class BenchSettings(ResultMixin):
    """Run settings of the simulated bench.

    Parameters
    ----------
    speed : float
        Set speed [rad/s].
    ramp_time : float
        Duration of the linear speed ramp from rest [s] (thesis: 2 s).
    hold_time : float
        Duration of the hold at set speed [s] (thesis: 1.5 s); the required torque is the
        mean motor torque over it.
    proportional_gain : float
        PI controller proportional gain :math:`K_p` [N m s/rad].
    integral_gain : float
        PI controller integral gain :math:`K_i` [N m/rad].
    stick_speed : float
        Speed scale of the regularised Coulomb law
        :math:`\\operatorname{sgn}\\omega \\approx \\omega/\\sqrt{\\omega^2 + \\omega_s^2}` [rad/s].
    samples : int
        Number of time samples in the returned histories.
    rtol : float
        Relative tolerance of the integrator per step [-], in [1e-12, 1e-2].
    """

    speed: float
    ramp_time: float = 2.0
    hold_time: float = 1.5
    proportional_gain: float = 0.2
    integral_gain: float = 10.0
    stick_speed: float = 0.1
    samples: int = 1401
    rtol: float = 1e-6

    def __post_init__(self) -> None:
        check_positive("speed", self.speed)
        check_positive("ramp_time", self.ramp_time)
        check_positive("hold_time", self.hold_time)
        check_positive("proportional_gain", self.proportional_gain)
        check_nonnegative("integral_gain", self.integral_gain)
        check_positive("stick_speed", self.stick_speed)
        if (
            isinstance(self.samples, bool)
            or not isinstance(self.samples, (int, np.integer))
            or self.samples < 10
        ):
            raise InputError("samples", self.samples, "must be a whole number, at least 10")
        check_range("rtol", self.rtol, 1e-12, 1e-2)


@record
class BenchResult(ResultMixin):
    """Result of :func:`run_bench`.

    Attributes
    ----------
    settings : BenchSettings
        The run settings the result was computed with.
    required_torque : float
        Mean motor torque over the hold [N m] (Hoem and Røsholm 2016, Table 5.6).
    mean_friction_torque : float
        Mean bearing friction torque over the hold [N m].
    friction_power : float
        Mean friction power over the hold [W].
    final_speed : float
        Speed at the end of the run [rad/s].
    speed_ripple : float
        Peak-to-peak speed over the second half of the hold [rad/s].
    time, speed, motor_torque, friction_torque, bearing_load_a, bearing_load_b : ndarray
        Histories [s], [rad/s], [N m], [N m], [N], [N].
    """

    settings: BenchSettings
    required_torque: float
    mean_friction_torque: float
    friction_power: float
    final_speed: float
    speed_ripple: float
    time: NDArray = field(repr=False)
    speed: NDArray = field(repr=False)
    motor_torque: NDArray = field(repr=False)
    friction_torque: NDArray = field(repr=False)
    bearing_load_a: NDArray = field(repr=False)
    bearing_load_b: NDArray = field(repr=False)


def _bench_model(rotor: BenchRotor, settings: BenchSettings) -> Callable[..., tuple[float, ...]]:
    """The bench equations at one instant, on plain floats.

    The returned function maps ``(t, theta, omega, integral)`` (time [s], angle [rad], speed
    [rad/s], integral of the speed error [rad]) to ``(reference, motor, friction, alpha,
    load_a, load_b)`` ([rad/s], [N m], [N m], [rad/s^2], [N], [N]).
    """
    inertia = rotor.inertia
    weight = rotor.mass * rotor.gravity
    unbalance = rotor.unbalance
    gravity_torque = unbalance * rotor.gravity
    wa, wb = rotor.load_shares(rotor.mass_position)
    ua, ub = rotor.load_shares(rotor.unbalance_position)
    lever = 0.5 * rotor.journal_diameter * rotor.friction_coefficient
    kp, ki = settings.proportional_gain, settings.integral_gain
    w_set, t_ramp = settings.speed, settings.ramp_time
    ws2 = settings.stick_speed**2
    hypot, cos, sin, sqrt = math.hypot, math.cos, math.sin, math.sqrt

    def loads(c: float, s: float, omega: float, alpha: float) -> tuple[float, float]:
        # bearing reactions on the rotor: weight + U(-w^2 e_r + alpha e_t), e_r = (c, s)
        fx = unbalance * (-omega * omega * c - alpha * s)
        fz = unbalance * (-omega * omega * s + alpha * c)
        return hypot(ua * fx, wa * weight + ua * fz), hypot(ub * fx, wb * weight + ub * fz)

    def equations(t: float, theta: float, omega: float, integral: float) -> tuple[float, ...]:
        reference = w_set * t / t_ramp if t < t_ramp else w_set
        motor = kp * (reference - omega) + ki * integral
        sign = omega / sqrt(omega * omega + ws2)
        c, s = cos(theta), sin(theta)
        drive = motor - gravity_torque * c
        load_a, load_b = loads(c, s, omega, 0.0)
        alpha = (drive - lever * sign * (load_a + load_b)) / inertia
        load_a, load_b = loads(c, s, omega, alpha)  # one fixed-point pass for the alpha term
        friction = lever * sign * (load_a + load_b)
        return reference, motor, friction, (drive - friction) / inertia, load_a, load_b

    return equations


# Dormand and Prince (1980), RK5(4)7M: nodes, stage coefficients, fifth-order weights, and
# the weights of the difference to the embedded fourth-order solution (error estimate).
_DP_NODES = (1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0)
_DP_STAGES = (
    (1 / 5,),
    (3 / 40, 9 / 40),
    (44 / 45, -56 / 15, 32 / 9),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
)
_DP_WEIGHTS = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84)
_DP_ERROR = (71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40)


def _dormand_prince(
    rhs: Callable[[float, Sequence[float]], Sequence[float]],
    y0: Sequence[float],
    times: Sequence[float],
    rtol: float,
    atol: Sequence[float],
    max_step: float,
) -> NDArray:
    """Integrate ``y' = rhs(t, y)`` from ``times[0]``; the states at ``times``, shape (n, len).

    Embedded Runge-Kutta pair of Dormand and Prince (1980) with the usual step-size control
    (Hairer, Nørsett and Wanner 1993, Sec. II.4: the RMS of the error over
    ``atol + rtol |y|``, factor ``0.9 err^(-1/5)`` limited to [0.2, 10]). The steps land
    on every output time (a step within 10 % of one is stretched to it, so it may exceed
    ``max_step`` by that much). Plain floats, no numpy: the bench has five states, for which
    the per-step overhead of a general solver costs ten times the equations themselves.
    """
    (a21,), (a31, a32), (a41, a42, a43), (a51, a52, a53, a54), (a61, a62, a63, a64, a65) = (
        _DP_STAGES
    )
    c2, c3, c4, c5, _ = _DP_NODES
    b1, _, b3, b4, b5, b6 = _DP_WEIGHTS
    e1, _, e3, e4, e5, e6, e7 = _DP_ERROR
    n = len(y0)
    rng = range(n)
    t, y = float(times[0]), [float(v) for v in y0]
    k1 = rhs(t, y)
    h = max_step
    out = [y]
    for target in times[1:]:
        while t < target:
            last = t + 1.1 * h >= target
            step = target - t if last else h
            if step <= 1e-13 * max(1.0, abs(t)):
                raise RuntimeError(f"bench integration failed: step size vanished at t = {t} s")
            k2 = rhs(t + c2 * step, [y[i] + step * a21 * k1[i] for i in rng])
            k3 = rhs(t + c3 * step, [y[i] + step * (a31 * k1[i] + a32 * k2[i]) for i in rng])
            k4 = rhs(
                t + c4 * step,
                [y[i] + step * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]) for i in rng],
            )
            k5 = rhs(
                t + c5 * step,
                [
                    y[i] + step * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i])
                    for i in rng
                ],
            )
            k6 = rhs(
                t + step,
                [
                    y[i]
                    + step * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i])
                    for i in rng
                ],
            )
            t_new = target if last else t + step
            y_new = [
                y[i] + step * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i])
                for i in rng
            ]
            k7 = rhs(t_new, y_new)
            error = 0.0
            for i in rng:
                scale = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
                estimate = step * (
                    e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]
                )
                error += (estimate / scale) ** 2
            error = math.sqrt(error / n)
            if error <= 1.0:
                t, y, k1 = t_new, y_new, k7
                factor = 10.0 if error == 0.0 else min(10.0, 0.9 * error**-0.2)
                if not last or factor < 1.0:  # a step cut short to land on a time says little
                    h = min(max_step, step * factor)
            else:  # rejected; so is a step whose error is not finite
                h = step * (max(0.2, 0.9 * error**-0.2) if math.isfinite(error) else 0.2)
        out.append(y)
    return np.array(out).T


def run_bench(rotor: BenchRotor, settings: BenchSettings) -> BenchResult:
    r"""Simulate the rotor test bench: PI-controlled spin-up, hold, required torque.

    Equation of motion of the rigid rotor (angle :math:`\theta` of the unbalance from the
    horizontal, gravity along :math:`-z`):

    .. math::
        I\ddot\theta = T_m - \operatorname{sgn}(\dot\theta)\,\mu\frac{d}{2}
            \big(|\mathbf R_A| + |\mathbf R_B|\big) - U g\cos\theta

        \mathbf R_A + \mathbf R_B = m g\,\mathbf e_z
            + U\big(-\dot\theta^2\mathbf e_r + \ddot\theta\,\mathbf e_t\big)

        T_m = K_p(\omega_{ref} - \dot\theta) + K_i\int(\omega_{ref} - \dot\theta)\,dt,\quad
        \omega_{ref} = \omega_{set}\min(t/t_{ramp}, 1)

    The reactions are split between the bearings by the lever rule (weight at the centre of
    gravity, unbalance force in its plane). The required torque is the mean of :math:`T_m`
    over the hold, computed exactly by integrating :math:`T_m` along with the state.

    The ramp and the hold are integrated separately (the reference has a kink between
    them) by an embedded Dormand-Prince 5(4) pair (Dormand and Prince 1980) with relative
    tolerance ``settings.rtol`` and steps of at most an eighth of a revolution at set
    speed, landing on every sample time.

    Parameters
    ----------
    rotor : BenchRotor
        The rotor and its bearings.
    settings : BenchSettings
        Set speed, ramp, hold, controller gains, solver settings.

    Returns
    -------
    BenchResult

    Raises
    ------
    InputError
        When the run needs more than :data:`MAX_BENCH_EVALUATIONS` evaluations of the
        equations of motion (bounded work for any input).

    References
    ----------
    Hoem and Røsholm (2016), Sec. 5.2.5 (FEDEM test bench, Figs. 5.16, 5.17), Table 5.6, Appendix F.
    """
    equations = _bench_model(rotor, settings)
    evaluations = 0

    def rhs(t: float, y: Sequence[float]) -> tuple[float, ...]:
        nonlocal evaluations
        evaluations += 1
        if evaluations > MAX_BENCH_EVALUATIONS:
            raise InputError(
                "bench run",
                None,
                f"needs more than {MAX_BENCH_EVALUATIONS} evaluations of the equations of "
                "motion (a stiff rotor: lower the controller gains, raise the inertia, or "
                "shorten the run)",
            )
        reference, motor, friction, alpha, _, _ = equations(t, y[0], y[1], y[2])
        return y[1], alpha, reference - y[1], motor, friction

    t_ramp = settings.ramp_time
    t_end = t_ramp + settings.hold_time
    n_ramp = max(2, int(round(settings.samples * t_ramp / t_end)))
    n_hold = max(2, settings.samples - n_ramp + 1)
    grid_ramp = np.linspace(0.0, t_ramp, n_ramp)
    grid_hold = np.linspace(t_ramp, t_end, n_hold)
    period = 2 * np.pi / settings.speed
    atol = [1e-6, 1e-6 * settings.speed, 1e-8, 1e-8, 1e-8]
    first = _dormand_prince(rhs, [0.0] * 5, grid_ramp.tolist(), settings.rtol, atol, period / 8)
    second = _dormand_prince(
        rhs, first[:, -1].tolist(), grid_hold.tolist(), settings.rtol, atol, period / 8
    )
    time = np.concatenate([grid_ramp, grid_hold[1:]])
    states = np.concatenate([first, second[:, 1:]], axis=1)
    outputs = np.array([equations(t, *states[:3, k].tolist()) for k, t in enumerate(time.tolist())])
    hold = settings.hold_time
    required = (second[3, -1] - second[3, 0]) / hold
    friction = (second[4, -1] - second[4, 0]) / hold
    omega_hold = second[1]
    return BenchResult(
        settings=settings,
        required_torque=float(required),
        mean_friction_torque=float(friction),
        friction_power=float(friction * settings.speed),
        final_speed=float(second[1, -1]),
        speed_ripple=float(
            omega_hold[len(omega_hold) // 2 :].max() - omega_hold[len(omega_hold) // 2 :].min()
        ),
        time=time,
        speed=states[1],
        motor_torque=outputs[:, 1],
        friction_torque=outputs[:, 2],
        bearing_load_a=outputs[:, 4],
        bearing_load_b=outputs[:, 5],
    )


# ======================================================================================
# Rotor helpers: inertia, equal-inertia test rotor, crankpin overlap, stroking
# ======================================================================================


def cylinder_inertia(
    diameter: float, length: float, density: float = STEEL_DENSITY, bore: float = 0.0
) -> float:
    r"""Mass moment of inertia of a (hollow) cylinder about its own axis.

    .. math:: I = \frac{\rho\,\pi\,(d^4 - d_i^4)\,L}{32}

    Parameters
    ----------
    diameter : float
        Outer diameter [m].
    length : float
        Axial length [m].
    density : float
        Material density [kg/m^3].
    bore : float
        Inner diameter [m] (0 for a solid cylinder).

    Returns
    -------
    float
        Inertia about the cylinder axis [kg m^2].

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.6.
    """
    check_positive("diameter", diameter)
    check_positive("length", length)
    check_positive("density", density)
    if not 0 <= bore < diameter:
        raise InputError("bore", bore, f"must lie in [0, diameter = {diameter:g} m)")
    return density * math.pi * (diameter**4 - bore**4) * length / 32.0


def disc_inertia(mass: float, diameter: float) -> float:
    """Inertia of a solid disc of given mass about its axis: :math:`m r^2/2`.

    Parameters
    ----------
    mass : float
        Disc mass [kg].
    diameter : float
        Disc diameter [m].

    Returns
    -------
    float
        Inertia about the disc axis [kg m^2].

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.6.
    """
    check_mass("mass", mass)
    check_positive("diameter", diameter)
    return mass * (diameter / 2.0) ** 2 / 2.0


def point_mass_inertia(mass: float, radius: float) -> float:
    """Inertia of a mass concentrated at a radius: :math:`m r^2`.

    Parameters
    ----------
    mass : float
        The mass [kg].
    radius : float
        Its distance from the axis [m].

    Returns
    -------
    float
        Inertia about the axis [kg m^2].
    """
    check_mass("mass", mass)
    if not radius >= 0:
        raise InputError("radius", radius, "must be >= 0 [m]")
    return mass * radius**2


def stepped_rotor_inertia(
    disc_diameter: float,
    disc_thickness: float,
    shaft_diameter: float,
    overall_length: float,
    density: float = STEEL_DENSITY,
) -> float:
    r"""Inertia of a central disc on a shaft (the thesis' simplified crank).

    .. math:: I = \frac{\rho\pi}{32}\left(d_1^4 t + d_2^4 (L_1 - t)\right)

    Parameters
    ----------
    disc_diameter : float
        Disc diameter :math:`d_1` [m].
    disc_thickness : float
        Disc thickness :math:`t` [m].
    shaft_diameter : float
        Shaft diameter :math:`d_2` [m].
    overall_length : float
        Overall length :math:`L_1`, shaft ends included [m].
    density : float
        Material density [kg/m^3].

    Returns
    -------
    float
        Inertia about the rotor axis [kg m^2].

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.7.
    """
    check_positive("disc_thickness", disc_thickness)
    if not disc_thickness < overall_length:
        raise InputError(
            "disc_thickness",
            disc_thickness,
            f"must be shorter than overall_length = {overall_length:g} m",
        )
    return cylinder_inertia(disc_diameter, disc_thickness, density) + cylinder_inertia(
        shaft_diameter, overall_length - disc_thickness, density
    )


@record
class TestRotor(ResultMixin):
    """Disc-on-shaft test rotor with a prescribed inertia (Hoem and Røsholm (2016), Appendix E).

    Attributes
    ----------
    disc_diameter, shaft_diameter, overall_length : float
        :math:`d_1, d_2, L_1` [m].
    disc_thickness : float
        :math:`t` [m].
    shaft_end_length : float
        :math:`L_2 = (L_1 - t)/2`, each shaft end [m].
    inertia : float
        Its mass moment of inertia about the axis [kg m^2].
    mass : float
        Its mass [kg].
    density : float
        [kg/m^3].
    """

    __test__ = False  # not a pytest class

    disc_diameter: float
    shaft_diameter: float
    overall_length: float
    disc_thickness: float
    shaft_end_length: float
    inertia: float
    mass: float
    density: float


def equal_inertia_test_rotor(
    inertia: float,
    disc_diameter: float,
    shaft_diameter: float,
    overall_length: float,
    density: float = STEEL_DENSITY,
) -> TestRotor:
    r"""Disc thickness giving a disc-on-shaft rotor the inertia of a real crank.

    .. math::
        t = \frac{32 I/(\rho\pi) - d_2^4 L_1}{d_1^4 - d_2^4},\qquad L_2 = \frac{L_1 - t}{2}

    Parameters
    ----------
    inertia : float
        Inertia to match about the crank axis [kg m^2].
    disc_diameter : float
        Disc diameter :math:`d_1` [m].
    shaft_diameter : float
        Shaft diameter :math:`d_2` [m].
    overall_length : float
        Overall length :math:`L_1` [m].
    density : float
        Material density [kg/m^3].

    Returns
    -------
    TestRotor
        The rotor: its disc thickness, shaft-end length, inertia and mass.

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.8 and 7.9, Table 7.2: 2847.335 kg mm^2,
    d_1 = 100 mm (the table prints 98 mm, which gives t = 39.80 mm, not the printed
    36.704 mm), d_2 = 20 mm, L_1 = 188 mm -> t = 36.704 mm, L_2 = 75.648 mm.
    """
    check_positive("inertia", inertia)
    check_positive("disc_diameter", disc_diameter)
    check_positive("shaft_diameter", shaft_diameter)
    check_positive("overall_length", overall_length)
    check_positive("density", density)
    if not shaft_diameter < disc_diameter:
        raise InputError(
            "shaft_diameter",
            shaft_diameter,
            f"must be smaller than disc_diameter = {disc_diameter:g} m",
        )
    thickness = (32.0 * inertia / (density * math.pi) - shaft_diameter**4 * overall_length) / (
        disc_diameter**4 - shaft_diameter**4
    )
    if not 0 < thickness < overall_length:
        low = cylinder_inertia(shaft_diameter, overall_length, density)
        high = cylinder_inertia(disc_diameter, overall_length, density)
        raise InputError(
            "inertia",
            inertia,
            f"cannot be reached with these diameters and length: must lie "
            f"between {low:.6g} and {high:.6g} kg*m^2",
        )
    mass = (
        density
        * math.pi
        / 4.0
        * (disc_diameter**2 * thickness + shaft_diameter**2 * (overall_length - thickness))
    )
    return TestRotor(
        disc_diameter=disc_diameter,
        shaft_diameter=shaft_diameter,
        overall_length=overall_length,
        disc_thickness=thickness,
        shaft_end_length=(overall_length - thickness) / 2.0,
        inertia=stepped_rotor_inertia(
            disc_diameter, thickness, shaft_diameter, overall_length, density
        ),
        mass=mass,
        density=density,
    )


def crankpin_overlap(
    main_journal_diameter: float, crankpin_diameter: float, stroke: float
) -> float:
    r"""Crankpin overlap: how far the crankpin overlaps the main journal.

    Negative values mean no overlap (a gap).

    .. math:: CPO = \frac{D_{main} + D_{pin} - s}{2}

    Parameters
    ----------
    main_journal_diameter : float
        Main-journal diameter :math:`D_{main}` [m].
    crankpin_diameter : float
        Crankpin diameter :math:`D_{pin}` [m].
    stroke : float
        Piston stroke :math:`s` [m].

    Returns
    -------
    float
        Crankpin overlap [m].

    References
    ----------
    Hoem and Røsholm (2016) Sec. 4.3, Fig. 4.13.
    """
    check_positive("main_journal_diameter", main_journal_diameter)
    check_positive("crankpin_diameter", crankpin_diameter)
    check_positive("stroke", stroke)
    return (main_journal_diameter + crankpin_diameter - stroke) / 2.0


@record
class StrokingEffect(ResultMixin):
    """Effect of offset-grinding the crankpin to a smaller diameter.

    Hoem and Røsholm (2016), Appendix C.

    Attributes
    ----------
    crank_radius, new_crank_radius : float
        Throw radius before and after [m].
    stroke, new_stroke : float
        [m].
    crankpin_mass, new_crankpin_mass : float
        [kg].
    rotating_mass, new_rotating_mass : float
        :math:`m_{rot}` before and after [kg].
    rotating_unbalance, new_rotating_unbalance : float
        :math:`m_{rot} r` before and after [kg m].
    balance_factor, new_balance_factor : float
        With the counterweights unchanged [-].
    counterweight_correction : float
        First moment to take off the counterweights to restore the original balance factor
        [kg m] (negative: add).
    displacement_change : float
        Swept-volume change [m^3] (0 if no bore is given).
    crankpin_overlap, new_crankpin_overlap : float or None
        [m], if the main-journal diameter is given.
    """

    crank_radius: float
    new_crank_radius: float
    stroke: float
    new_stroke: float
    crankpin_mass: float
    new_crankpin_mass: float
    rotating_mass: float
    new_rotating_mass: float
    rotating_unbalance: float
    new_rotating_unbalance: float
    balance_factor: float
    new_balance_factor: float
    counterweight_correction: float
    displacement_change: float
    crankpin_overlap: float | None
    new_crankpin_overlap: float | None


def stroking_effect(
    crank_radius: float,
    crankpin_diameter: float,
    new_crankpin_diameter: float,
    crankpin_mass: float,
    rotating_mass: float,
    reciprocating_mass: float,
    counterweight_mass: float,
    counterweight_radius: float,
    crankpin_bore: float = 0.0,
    bore: float = 0.0,
    main_journal_diameter: float | None = None,
) -> StrokingEffect:
    r"""Stroking by offset grinding: a smaller crankpin whose outermost fibre stays put.

    .. math::
        r_{new} = r + \frac{d - d_{new}}{2},\quad
        m_{pin,new} = m_{pin}\frac{d_{new}^2 - d_i^2}{d^2 - d_i^2},\quad
        m_{rot,new} = m_{rot} - m_{pin} + m_{pin,new}

        f_{b,new} = \frac{m_{cw} r'/r_{new} - m_{rot,new}}{m_{rec}}

    Parameters
    ----------
    crank_radius : float
        Throw radius before [m].
    crankpin_diameter : float
        Crankpin diameter before grinding [m].
    new_crankpin_diameter : float
        Crankpin diameter after grinding [m].
    crankpin_mass : float
        Crankpin mass before [kg] (the part of :math:`m_{rot}` that changes).
    rotating_mass : float
        :math:`m_{rot}` before, crankpin included [kg].
    reciprocating_mass : float
        :math:`m_{rec}` [kg].
    counterweight_mass : float
        :math:`m_{cw}` [kg], unchanged by stroking.
    counterweight_radius : float
        :math:`r'` [m], unchanged by stroking.
    crankpin_bore : float
        Bore of a hollow crankpin [m].
    bore : float
        Cylinder bore for the displacement change [m] (0: not computed).
    main_journal_diameter : float, optional
        For the crankpin overlap before and after [m].

    Returns
    -------
    StrokingEffect
        Radius, stroke, masses, balance factor and overlap before and after, and the
        counterweight correction that restores the balance factor.

    References
    ----------
    Hoem and Røsholm (2016) Appendix C (qualitative: a smaller crankpin lightens the top half of
    the crank and lengthens the stroke); Eq. 6.2 for the balance factor.
    """
    check_positive("crank_radius", crank_radius)
    check_positive("crankpin_diameter", crankpin_diameter)
    check_positive("new_crankpin_diameter", new_crankpin_diameter)
    if not crankpin_bore < new_crankpin_diameter <= crankpin_diameter:
        raise InputError(
            "new_crankpin_diameter",
            new_crankpin_diameter,
            f"must lie in ({crankpin_bore:g}, {crankpin_diameter:g}] m "
            "(stroking makes the crankpin smaller, not below its bore)",
        )
    check_mass("crankpin_mass", crankpin_mass)
    check_mass("rotating_mass", rotating_mass)
    if crankpin_mass > rotating_mass:
        raise InputError(
            "crankpin_mass", crankpin_mass, f"must not exceed rotating_mass = {rotating_mass:g} kg"
        )
    if not bore >= 0:
        raise InputError("bore", bore, "must be >= 0 [m]")
    new_radius = crank_radius + (crankpin_diameter - new_crankpin_diameter) / 2.0
    new_pin = crankpin_mass * (
        (new_crankpin_diameter**2 - crankpin_bore**2) / (crankpin_diameter**2 - crankpin_bore**2)
    )
    new_rotating = rotating_mass - crankpin_mass + new_pin
    fb = balance_factor_from_mass_properties(
        counterweight_mass, counterweight_radius, crank_radius, rotating_mass, reciprocating_mass
    )
    fb_new = balance_factor_from_mass_properties(
        counterweight_mass, counterweight_radius, new_radius, new_rotating, reciprocating_mass
    )
    keep = (new_rotating + fb * reciprocating_mass) * new_radius
    area = math.pi * bore**2 / 4.0
    cpo = cpo_new = None
    if main_journal_diameter is not None:
        cpo = crankpin_overlap(main_journal_diameter, crankpin_diameter, 2 * crank_radius)
        cpo_new = crankpin_overlap(main_journal_diameter, new_crankpin_diameter, 2 * new_radius)
    return StrokingEffect(
        crank_radius=crank_radius,
        new_crank_radius=new_radius,
        stroke=2 * crank_radius,
        new_stroke=2 * new_radius,
        crankpin_mass=crankpin_mass,
        new_crankpin_mass=new_pin,
        rotating_mass=rotating_mass,
        new_rotating_mass=new_rotating,
        rotating_unbalance=rotating_mass * crank_radius,
        new_rotating_unbalance=new_rotating * new_radius,
        balance_factor=fb,
        new_balance_factor=fb_new,
        counterweight_correction=counterweight_mass * counterweight_radius - keep,
        displacement_change=area * 2 * (new_radius - crank_radius),
        crankpin_overlap=cpo,
        new_crankpin_overlap=cpo_new,
    )
