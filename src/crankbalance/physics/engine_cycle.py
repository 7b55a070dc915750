r"""Engine-cycle torque simulation and the balance-factor sensitivity sweep.

This module owns the crank-train cycle model of one or several cylinders:

* the cylinder (:class:`CylinderSpec`, :func:`stroke_length`, :func:`cylinder_volume`);
* the cylinder pressure, from a Wiebe heat-release model (:func:`wiebe_burn_fraction`,
  :class:`WiebeCombustion`, :func:`wiebe_pressure`) or a table (:func:`tabulated_pressure`);
* :func:`engine_cycle` -- one working cycle at a given mean speed: gas force,
  reciprocating inertia with the variable inertia of the crank train, main-bearing loads
  including the counterweight of a balance factor, friction torque from those loads, net
  torque, speed fluctuation and crank acceleration (:class:`CycleResult`);
* :func:`balance_sensitivity` -- sweep of the balance factor (and a scale on the
  reciprocating mass) with the indicators of Hoem and Røsholm (2016), Sec. 1/4.2: mean
  friction torque and power loss, peak and mean main-bearing load, peak net torque,
  maximum crank acceleration, shaking forces (:class:`SensitivityResult`).

Balance factor (everywhere in this module): the share :math:`f_b` of the reciprocating mass
per cylinder that the crank counterweight balances *on top of* 100 % of the rotating mass,
:math:`m_{cw} r' = (m_{rot} + f_b m_{rec}) r` (Hoem and Røsholm (2016), Eq. 4.6).

Frames: crank angle :math:`\theta` from the cylinder axis (0 = top dead centre, for the
firing cylinder the firing TDC); :math:`z` along the cylinder axis away from the crank
(in-line), :math:`x` across it (transverse), crankpin at :math:`r(\sin\theta, \cos\theta)`.
Torques are positive in the sense of rotation.

Why one module over 800 lines: the pressure models, the cycle and the sweep are one model
(the sweep is a loop over :func:`engine_cycle`, the cycle integrates the pressure models
over the same crank-angle grid, and they share the cylinder and its checks); most of the
length is the numpydoc of the physics.

References
----------
Hoem and Røsholm (2016), Secs. 2.3, 4.2 and 5.1; Heywood, Internal Combustion Engine
Fundamentals, Secs. 9.2.1-9.2.2.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_finite, check_nonnegative, check_positive, check_range
from ..records import record
from ..results import ResultMixin
from . import kinematics
from .firing import check_strokes
from .limits import BALANCE_FACTOR_RANGE
from .limits import BURN_DURATION_RANGE as BURN_DURATION_RANGE
from .limits import BURN_ENDS as BURN_ENDS
from .limits import GAMMA_RANGE as GAMMA_RANGE
from .limits import IGNITION_RANGE as IGNITION_RANGE

GAS_CONSTANT_AIR = 287.0

Strokes = Literal[2, 4]


# ======================================================================================
# Engine cycle
# ======================================================================================


@record
class CylinderSpec(ResultMixin):
    """One cylinder of a single-cylinder (or per-cylinder) engine-cycle model.

    Parameters
    ----------
    bore : float
        Cylinder bore [m].
    crank_radius : float
        Crank throw radius (half the stroke for zero offset) [m].
    rod_length : float
        Conrod length, big-end to small-end centre [m].
    reciprocating_mass : float
        Reciprocating mass per cylinder (piston assembly + small end) [kg].
    crank_inertia : float
        Moment of inertia of everything that purely rotates (crankshaft with counterweights,
        big end, flywheel, clutch) about the crank axis [kg m^2].
    balance_factor : float
        Share of the reciprocating mass balanced by the crank counterweight on top of 100 %
        of the rotating mass, :math:`m_{cw} r' = (m_{rot} + f_b m_{rec}) r`, in [0, 2] [-].
    journal_diameter : float
        Main-journal diameter [m].
    friction_coefficient : float
        Coulomb friction coefficient of the main bearings [-].
    offset : float
        Lateral offset of the wrist-pin path (desaxé) [m].
    crankshaft_weight : float
        Constant load on the main bearings along :math:`-z` (crankshaft weight with a
        vertical cylinder) [N].
    crankcase_pressure : float
        Pressure under the piston [Pa].
    """

    bore: float
    crank_radius: float
    rod_length: float
    reciprocating_mass: float
    crank_inertia: float
    balance_factor: float = 0.0
    journal_diameter: float = 0.03
    friction_coefficient: float = 0.005
    offset: float = 0.0
    crankshaft_weight: float = 0.0
    crankcase_pressure: float = 1.0e5

    def __post_init__(self) -> None:
        check_positive("bore", self.bore)
        check_positive("crank_radius", self.crank_radius)
        check_positive("rod_length", self.rod_length)
        if self.rod_length <= self.crank_radius + abs(self.offset):
            raise InputError(
                "rod_length",
                self.rod_length,
                f"must exceed crank_radius + |offset| = {self.crank_radius + abs(self.offset):g} m",
            )
        check_nonnegative("reciprocating_mass", self.reciprocating_mass)
        check_positive("crank_inertia", self.crank_inertia)
        check_range("balance_factor", self.balance_factor, *BALANCE_FACTOR_RANGE)
        check_positive("journal_diameter", self.journal_diameter)
        check_nonnegative("friction_coefficient", self.friction_coefficient)
        check_finite("offset", self.offset)
        check_nonnegative("crankshaft_weight", self.crankshaft_weight)
        check_nonnegative("crankcase_pressure", self.crankcase_pressure)

    @property
    def piston_area(self) -> float:
        """Piston crown area [m^2]."""
        return math.pi * self.bore**2 / 4

    @property
    def stroke(self) -> float:
        """Piston stroke, exact with offset [m]."""
        return stroke_length(self.crank_radius, self.rod_length, self.offset)

    @property
    def displacement(self) -> float:
        """Swept volume [m^3]."""
        return self.piston_area * self.stroke


def stroke_length(crank_radius: float, rod_length: float, offset: float = 0.0) -> float:
    r"""Piston stroke of a slider-crank with offset [m].

    .. math:: S = \sqrt{(l + r)^2 - e^2} - \sqrt{(l - r)^2 - e^2}

    Parameters
    ----------
    crank_radius : float
        Crank throw radius r [m].
    rod_length : float
        Conrod length l [m].
    offset : float
        Wrist-pin path offset e [m].

    Returns
    -------
    float
        Piston stroke S [m].

    References
    ----------
    Any machine-dynamics text; Hoem and Røsholm (2016), Sec. 2.1 for e = 0.
    """
    return math.sqrt((rod_length + crank_radius) ** 2 - offset**2) - math.sqrt(
        (rod_length - crank_radius) ** 2 - offset**2
    )


def cylinder_volume(
    angle: ArrayLike,
    bore: float,
    crank_radius: float,
    rod_length: float,
    compression_ratio: float,
    offset: float = 0.0,
) -> NDArray:
    r"""Cylinder volume over the crank angle [m^3].

    .. math:: V = V_c + A_p\,(s_{TDC} - s(\theta)),\qquad V_c = \frac{A_p S}{\varepsilon - 1}

    Parameters
    ----------
    angle : array_like
        Crank angle from the cylinder axis [rad].
    bore : float
        Cylinder bore [m].
    crank_radius : float
        Crank throw radius [m].
    rod_length : float
        Conrod length [m].
    compression_ratio : float
        Geometric compression ratio :math:`\varepsilon` [-].
    offset : float
        Wrist-pin path offset [m].

    Returns
    -------
    ndarray
        Cylinder volume at each angle [m^3].
    """
    if not compression_ratio > 1:
        raise InputError("compression_ratio", compression_ratio, "must be greater than 1")
    area = math.pi * bore**2 / 4
    top = math.sqrt((rod_length + crank_radius) ** 2 - offset**2)
    clearance = area * stroke_length(crank_radius, rod_length, offset) / (compression_ratio - 1)
    return clearance + area * (
        top - kinematics.piston_position(angle, crank_radius, rod_length, offset)
    )


def wiebe_burn_fraction(
    angle: ArrayLike,
    ignition_angle: float,
    burn_duration: float,
    efficiency_factor: float = 5.0,
    form_factor: float = 2.0,
    burn_end: str = "complete",
) -> NDArray:
    r"""Wiebe mass fraction burnt [-].

    .. math:: x_b = 1 - \exp\!\Big[-a\Big(\frac{\theta - \theta_0}{\Delta\theta}\Big)^{m+1}\Big]
              \quad (\theta > \theta_0),\qquad 0 \text{ before}

    With ``burn_end = "complete"`` the exponential runs on past
    :math:`\theta_0 + \Delta\theta` (99.3 % burnt there for a = 5) to a complete burn; with
    ``"stop"`` the burn ends at :math:`\theta_0 + \Delta\theta`, the fraction held at
    :math:`1 - e^{-a}` after it.

    Parameters
    ----------
    angle : array_like
        Crank angle from firing TDC [rad].
    ignition_angle : float
        Start of combustion :math:`\theta_0` [rad] (negative = before TDC).
    burn_duration : float
        Burn duration :math:`\Delta\theta` [rad].
    efficiency_factor : float
        Wiebe :math:`a` (5 gives 99.3 % burnt at the end of the duration) [-].
    form_factor : float
        Wiebe :math:`m` [-].
    burn_end : {"complete", "stop"}
        End-of-burn convention (:data:`BURN_ENDS`).

    Returns
    -------
    ndarray
        Mass fraction burnt at each angle [-].

    References
    ----------
    Heywood, Internal Combustion Engine Fundamentals, Eq. 9.23.
    """
    check_positive("burn_duration", burn_duration)
    if burn_end not in BURN_ENDS:
        raise InputError("burn_end", burn_end, "'complete' or 'stop'")
    top = 1.0 if burn_end == "stop" else None
    phase = np.clip((np.asarray(angle, dtype=float) - ignition_angle) / burn_duration, 0, top)
    return 1.0 - np.exp(-efficiency_factor * phase ** (form_factor + 1.0))


@record
class WiebeCombustion(ResultMixin):
    """Single-zone Wiebe heat-release model of the cylinder pressure.

    Parameters
    ----------
    compression_ratio : float
        Geometric compression ratio [-].
    ignition_angle : float
        Start of combustion from firing TDC [rad], negative before TDC.
    burn_duration : float
        Burn duration [rad].
    intake_pressure : float
        Cylinder pressure at the start of compression (sets the load) [Pa].
    intake_temperature : float
        Charge temperature at the start of compression [K].
    air_fuel_ratio : float
        Air/fuel mass ratio [-].
    heating_value : float
        Lower heating value of the fuel [J/kg].
    combustion_efficiency : float
        Share of the fuel energy released as heat in the cylinder (lumps wall heat loss) [-].
    heat_release : float, optional
        Heat released per cycle [J]; overrides the fuel-based value when given.
    gamma : float
        Ratio of specific heats of the charge [-].
    exhaust_pressure : float, optional
        Pressure during the exhaust stroke (four-stroke) [Pa]; default the intake pressure.
    efficiency_factor, form_factor : float
        Wiebe :math:`a` and :math:`m` [-].
    fuel_mass : float, optional
        Fuel burnt per cycle [kg]; the heat released is then
        ``combustion_efficiency * fuel_mass * heating_value`` (not with ``heat_release``).
    burn_end : {"complete", "stop"}
        End-of-burn convention of :func:`wiebe_burn_fraction` (:data:`BURN_ENDS`).
    """

    compression_ratio: float
    ignition_angle: float
    burn_duration: float
    intake_pressure: float = 1.0e5
    intake_temperature: float = 320.0
    air_fuel_ratio: float = 14.7
    heating_value: float = 44.0e6
    combustion_efficiency: float = 0.8
    heat_release: float | None = None
    gamma: float = 1.3
    exhaust_pressure: float | None = None
    efficiency_factor: float = 5.0
    form_factor: float = 2.0
    fuel_mass: float | None = None
    burn_end: str = "complete"

    def __post_init__(self) -> None:
        if not (self.compression_ratio > 1 and math.isfinite(self.compression_ratio)):
            raise InputError("compression_ratio", self.compression_ratio, "must be greater than 1")
        check_range("ignition_angle", self.ignition_angle, *IGNITION_RANGE)
        check_range("burn_duration", self.burn_duration, *BURN_DURATION_RANGE)
        check_positive("intake_pressure", self.intake_pressure)
        check_positive("intake_temperature", self.intake_temperature)
        check_positive("air_fuel_ratio", self.air_fuel_ratio)
        check_positive("heating_value", self.heating_value)
        check_range("combustion_efficiency", self.combustion_efficiency, 0.0, 1.0)
        if self.heat_release is not None:
            check_nonnegative("heat_release", self.heat_release)
        if self.fuel_mass is not None:
            check_nonnegative("fuel_mass", self.fuel_mass)
            if self.heat_release is not None:
                raise InputError(
                    "fuel_mass", self.fuel_mass, "give either heat_release or fuel_mass, not both"
                )
        if self.burn_end not in BURN_ENDS:
            raise InputError("burn_end", self.burn_end, "'complete' or 'stop'")
        check_range("gamma", self.gamma, *GAMMA_RANGE)
        if self.exhaust_pressure is not None:
            check_positive("exhaust_pressure", self.exhaust_pressure)
        check_positive("efficiency_factor", self.efficiency_factor)
        check_nonnegative("form_factor", self.form_factor)


def wiebe_pressure(
    angle: ArrayLike, cylinder: CylinderSpec, combustion: WiebeCombustion, strokes: Strokes = 4
) -> NDArray:
    r"""Cylinder pressure of the Wiebe single-zone model [Pa].

    Closed cycle from bottom dead centre (:math:`-\pi`) to bottom dead centre (:math:`+\pi`)
    around firing TDC, with the first law integrated exactly (integrating factor
    :math:`V^\gamma`):

    .. math::
        \frac{dp}{d\theta} = -\gamma\frac{p}{V}\frac{dV}{d\theta}
            + \frac{\gamma - 1}{V} Q\frac{dx_b}{d\theta}
        \;\Rightarrow\;
        p V^\gamma = p_1 V_1^\gamma + (\gamma - 1) Q\int_{-\pi}^{\theta}
            V^{\gamma - 1}\,dx_b

    Valves are taken to open and close at the dead centres: for a four-stroke the exhaust
    stroke runs at ``exhaust_pressure`` and the intake stroke at ``intake_pressure``; for a
    two-stroke the cylinder is scavenged at bottom dead centre. The heat released is
    Q as given (``heat_release``), else :math:`\eta_c\,m_f\,L_{hv}` of the fuel given
    (``fuel_mass``), else :math:`Q = \eta_c\,L_{hv}\,p_1 V_1/(R T_1\,\mathrm{AFR})` of
    the charge; with ``burn_end = "stop"`` the share :math:`1 - e^{-a}` of it.

    Parameters
    ----------
    angle : array_like
        Crank angle from firing TDC [rad], any values (wrapped onto the cycle).
    cylinder : CylinderSpec
        Geometry (bore, crank radius, rod length, offset).
    combustion : WiebeCombustion
        Combustion model parameters.
    strokes : {2, 4}
        Cycle type.

    Returns
    -------
    ndarray
        Absolute cylinder pressure at each angle [Pa].

    References
    ----------
    Heywood, Internal Combustion Engine Fundamentals, Secs. 9.2.1 and 9.2.2 (Wiebe function,
    single-zone heat release); Hoem and Røsholm (2016), Sec. 2.3 (the gas torque in the engine
    torque).
    """
    check_strokes(strokes)
    theta = np.asarray(angle, dtype=float)
    cycle = np.pi * strokes / 2  # half cycle: pi (2-stroke) or 2 pi (4-stroke)
    wrapped = (theta + cycle) % (2 * cycle) - cycle
    geometry = (
        cylinder.bore,
        cylinder.crank_radius,
        cylinder.rod_length,
        combustion.compression_ratio,
        cylinder.offset,
    )
    # fine grid over the closed part, exact integrating factor, interpolation onto `angle`
    grid = np.linspace(-np.pi, np.pi, 2881)
    volume = cylinder_volume(grid, *geometry)
    gamma = combustion.gamma
    v1 = float(cylinder_volume(-np.pi, *geometry))
    heat = _heat_release(combustion, v1)
    burnt = wiebe_burn_fraction(
        grid,
        combustion.ignition_angle,
        combustion.burn_duration,
        combustion.efficiency_factor,
        combustion.form_factor,
        combustion.burn_end,
    )
    integrand = volume ** (gamma - 1.0)
    source = np.concatenate(
        [[0.0], np.cumsum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(burnt))]
    )
    start = combustion.intake_pressure * v1**gamma
    closed = (start + (gamma - 1.0) * heat * source) / volume**gamma
    pressure = np.interp(wrapped, grid, closed)
    if strokes == 4:
        exhaust = (
            combustion.exhaust_pressure
            if combustion.exhaust_pressure is not None
            else combustion.intake_pressure
        )
        pressure = np.where(wrapped > np.pi, exhaust, pressure)
        pressure = np.where(wrapped < -np.pi, combustion.intake_pressure, pressure)
    return pressure


def _heat_release(combustion: WiebeCombustion, bdc_volume: float) -> float:
    if combustion.heat_release is not None:
        return combustion.heat_release
    c = combustion
    if c.fuel_mass is not None:
        return c.combustion_efficiency * c.fuel_mass * c.heating_value
    air = c.intake_pressure * bdc_volume / (GAS_CONSTANT_AIR * c.intake_temperature)
    return c.combustion_efficiency * c.heating_value * air / c.air_fuel_ratio


def check_samples(samples_per_revolution: int) -> None:
    """Raise :class:`~crankbalance.errors.InputError` unless the angle resolution of a
    cycle is a whole number (not a bool) of at least 36 samples per revolution (one
    cylinder's cycle here, every cylinder's in :mod:`crankbalance.physics.engine_cycle_all`).

    Parameters
    ----------
    samples_per_revolution : int
        Samples of one crank revolution [-].
    """
    if (
        isinstance(samples_per_revolution, bool)
        or not isinstance(samples_per_revolution, (int, np.integer))
        or samples_per_revolution < 36
    ):
        raise InputError(
            "samples_per_revolution", samples_per_revolution, "must be a whole number, at least 36"
        )


def tabulated_pressure(
    angle: ArrayLike, table_angle: ArrayLike, table_pressure: ArrayLike, strokes: Strokes = 4
) -> NDArray:
    """Cylinder pressure from a measured or simulated table, periodic over the cycle [Pa].

    Parameters
    ----------
    angle : array_like
        Crank angles where the pressure is wanted, from firing TDC [rad].
    table_angle : array_like
        Crank angles of the table from firing TDC [rad], strictly increasing, spanning
        less than one cycle (2 pi for two-stroke, 4 pi for four-stroke).
    table_pressure : array_like
        Absolute cylinder pressure at those angles [Pa].
    strokes : {2, 4}
        Cycle type (sets the period).

    Returns
    -------
    ndarray
        Absolute cylinder pressure at each angle [Pa], linear between the table rows and
        periodic over the cycle.
    """
    check_strokes(strokes)
    a = np.asarray(table_angle, dtype=float)
    p = np.asarray(table_pressure, dtype=float)
    if a.ndim != 1 or a.shape != p.shape or a.size < 4:
        raise InputError(
            "pressure table", a.size, "needs matching angle and pressure columns, at least 4 rows"
        )
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(p))):
        raise InputError("pressure table", "non-finite value", "must hold finite numbers only")
    if np.any(np.diff(a) <= 0):
        raise InputError("pressure table angle", "not increasing", "must increase strictly")
    period = np.pi * strokes
    if a[-1] - a[0] >= period + 1e-9:
        raise InputError(
            "pressure table angle",
            float(np.degrees(a[-1] - a[0])),
            f"must span less than one cycle ({np.degrees(period):g} deg)",
        )
    if np.any(p < 0):
        raise InputError("pressure table pressure", float(p.min()), "must be absolute, >= 0")
    return np.interp(np.asarray(angle, dtype=float), a, p, period=period)


PressureSource = WiebeCombustion | tuple[NDArray, NDArray]


@record
class CycleResult(ResultMixin):
    r"""Result of :func:`engine_cycle` (arrays over the crank angle of one cycle).

    Attributes
    ----------
    speed_mean : float
        Mean crank speed the cycle is run at [rad/s].
    strokes : int
        Strokes per working cycle (2 or 4).
    angle : ndarray
        Crank angle of the first cylinder from its firing TDC [rad].
    pressure : ndarray, shape (cylinders, samples)
        Cylinder pressures [Pa].
    gas_torque, inertia_torque, friction_torque, net_torque : ndarray
        Torques summed over the cylinders [N m]; ``net = gas + inertia - friction`` at the mean
        speed (Hoem and Røsholm (2016), Sec. 2.3).
    inline_load, transverse_load : ndarray, shape (cylinders, samples)
        Main-bearing load of each cylinder's crank along and across its cylinder axis [N]
        (all main bearings of that throw together).
    bearing_load : ndarray, shape (cylinders, samples)
        Magnitude of that load [N] (the polar load diagram is ``(transverse, inline)``).
    shaking_inline, shaking_transverse : ndarray, shape (cylinders, samples)
        Free inertia force of each cylinder's crank train (no gas force) [N].
    speed, crank_acceleration : ndarray
        Crank speed [rad/s] and acceleration [rad/s^2] over the cycle at the given load.
    load_torque : float
        Constant brake torque that keeps the mean speed [N m].
    indicated_work, gas_work : float
        Closed-loop integral of p dV, and work of the gas torque over the cycle [J].
    mean_friction_torque : float
        Mean of ``friction_torque`` over the cycle [N m].
    friction_power : float
        ``mean_friction_torque`` times the mean speed [W].
    peak_bearing_load, mean_bearing_load : float
        Largest and mean ``bearing_load`` over all cylinders and angles [N].
    peak_net_torque : float
        Largest (signed) value of ``net_torque`` [N m].
    max_crank_acceleration : float
        Largest magnitude of ``crank_acceleration`` [rad/s^2].
    speed_fluctuation : float
        Cyclic irregularity :math:`(\omega_{max} - \omega_{min})/\omega_{mean}` [-].
    peak_shaking_inline, peak_shaking_transverse : float
        Largest magnitude of ``shaking_inline`` and ``shaking_transverse`` summed over the
        cylinders [N].
    peak_shaking_force : float
        Largest magnitude of the resultant of those sums [N].
    """

    speed_mean: float
    strokes: int
    angle: NDArray = field(repr=False)
    pressure: NDArray = field(repr=False)
    gas_torque: NDArray = field(repr=False)
    inertia_torque: NDArray = field(repr=False)
    friction_torque: NDArray = field(repr=False)
    net_torque: NDArray = field(repr=False)
    inline_load: NDArray = field(repr=False)
    transverse_load: NDArray = field(repr=False)
    bearing_load: NDArray = field(repr=False)
    shaking_inline: NDArray = field(repr=False)
    shaking_transverse: NDArray = field(repr=False)
    speed: NDArray = field(repr=False)
    crank_acceleration: NDArray = field(repr=False)
    load_torque: float
    indicated_work: float
    gas_work: float
    mean_friction_torque: float
    friction_power: float
    peak_bearing_load: float
    mean_bearing_load: float
    peak_net_torque: float
    max_crank_acceleration: float
    speed_fluctuation: float
    peak_shaking_inline: float
    peak_shaking_transverse: float
    peak_shaking_force: float


def cycle_angles(strokes: int, samples_per_revolution: int) -> NDArray:
    r"""The crank angles of one working cycle, centred on the firing top dead centre.

    Parameters
    ----------
    strokes : int
        Strokes per working cycle (2 or 4) [-].
    samples_per_revolution : int
        Samples of one crank revolution [-].

    Returns
    -------
    ndarray, shape (samples_per_revolution * strokes / 2,)
        Equally spaced angles from :math:`-\pi s/2` to before :math:`\pi s/2` [rad].
    """
    n = samples_per_revolution * strokes // 2
    half = np.pi * strokes / 2
    return -half + 2 * half * np.arange(n) / n


def engine_cycle(
    cylinders: CylinderSpec | Sequence[CylinderSpec],
    speed: float,
    pressure: PressureSource,
    strokes: Strokes = 4,
    phases: ArrayLike | None = None,
    samples_per_revolution: int = 720,
) -> CycleResult:
    r"""One working cycle of a single- or multi-cylinder crank train at a mean speed.

    For each cylinder (crank angle :math:`\theta_j = \theta - \varphi_j`), with the exact
    slider-crank :math:`s(\theta)` of :mod:`crankbalance.physics.kinematics`:

    .. math::
        F_g = (p - p_{cc})A_p,\qquad
        F_{rod,z} = m_{rec}\ddot s + F_g,\qquad F_{rod,x} = F_{rod,z}\,u/q

        \mathbf F_{bearing} = -\mathbf F_{rod} - f_b m_{rec} r\omega^2\,\mathbf e_r
            - W_{crank}\mathbf e_z,\qquad \mathbf e_r = (\sin\theta, \cos\theta)

        T = \mathbf e_\theta\text{-moment of } -\mathbf F_{rod} \text{ at the crankpin}
          = -(F_g + m_{rec}\ddot s)\,\frac{ds}{d\theta}

        T_f = \mu\frac{d}{2}|\mathbf F_{bearing}|,\qquad
        T_{net} = T_{gas} + T_{inertia} - T_f

    The speed over the cycle follows from the Lagrange equation of the crank train with the
    variable inertia :math:`J(\theta) = I_{crank} + \sum_j m_{rec,j}\,s_j'(\theta)^2`,
    which integrates exactly to an energy balance under a constant brake torque
    :math:`T_L = \overline{T_{gas} - T_f}`:

    .. math::
        \tfrac12 J(\theta)\,\omega^2 = E_0 + \int (T_{gas} - T_f - T_L)\,d\theta,\qquad
        \ddot\theta = \frac{T_{gas} - T_f - T_L - \tfrac12 J'\omega^2}{J}

    with :math:`E_0` set so that the time-mean speed is ``speed``. Loads and friction use the
    mean speed (the fluctuation is small).

    Parameters
    ----------
    cylinders : CylinderSpec or sequence of CylinderSpec
        One cylinder, or one per cylinder (crank inertias are added).
    speed : float
        Mean crank speed [rad/s].
    pressure : WiebeCombustion or (angle, pressure) arrays
        Pressure model, or a table over the cycle from firing TDC ([rad], [Pa]).
    strokes : {2, 4}
        Cycle type.
    phases : array_like, optional
        Firing phase of each cylinder after cylinder 1 [rad]; also its throw angle
        (in-line engine). Default: even firing.
    samples_per_revolution : int
        Angle resolution.

    Returns
    -------
    CycleResult

    References
    ----------
    Hoem and Røsholm (2016), Sec. 2.3 (engine torque from inertia, gas and friction),
    Eqs. 4.6-4.8 (balance factor, in-line and transverse forces), Sec. 4.2.1 (friction
    torque from the bearing
    load); Den Hartog, Mechanical Vibrations, Sec. 5.3 (inertia torque).
    """
    check_strokes(strokes)
    specs = [cylinders] if isinstance(cylinders, CylinderSpec) else list(cylinders)
    if not specs or not all(isinstance(c, CylinderSpec) for c in specs):
        raise InputError("cylinders", cylinders, "must be one or more CylinderSpec")
    check_positive("speed", speed)
    check_samples(samples_per_revolution)
    count = len(specs)
    cycle_angle = np.pi * strokes
    if phases is None:
        phase = cycle_angle * np.arange(count) / count
    else:
        phase = np.asarray(phases, dtype=float).reshape(-1)
        if phase.size != count or not np.all(np.isfinite(phase)):
            raise InputError("phases", phases, f"must give {count} finite angles")
    theta = cycle_angles(strokes, int(samples_per_revolution))
    w = speed
    pressures, gas_t, inertia_t, inline, transverse, shake_z, shake_x = ([] for _ in range(7))
    slope_sq, slope_dd = [], []
    indicated = 0.0
    for spec, ph in zip(specs, phase, strict=True):
        local = theta - ph
        p = cylinder_pressure(local, spec, pressure, strokes)
        pressures.append(p)
        f = cylinder_forces(local, spec, p, w)
        rod_z = f.inertia + f.gas  # rod force on piston, z
        rod_x = rod_z * f.u / f.q
        gas_t.append(f.gas_torque)
        inertia_t.append(f.inertia_torque)
        excess = spec.balance_factor * spec.reciprocating_mass * spec.crank_radius * w**2
        bz = -rod_z - excess * np.cos(local) - spec.crankshaft_weight
        bx = -rod_x - excess * np.sin(local)
        inline.append(bz)
        transverse.append(bx)
        shake_z.append(-f.inertia - excess * np.cos(local))
        shake_x.append(-excess * np.sin(local))
        slope_sq.append(spec.reciprocating_mass * f.slope**2)
        slope_dd.append(2 * spec.reciprocating_mass * f.slope * f.curvature)
        indicated += f.indicated_work
    inline_a, transverse_a = np.array(inline), np.array(transverse)
    load = np.hypot(inline_a, transverse_a)
    lever = np.array([0.5 * c.journal_diameter * c.friction_coefficient for c in specs])
    friction = np.sum(lever[:, None] * load, axis=0)
    gas_torque = np.sum(gas_t, axis=0)
    inertia_torque = np.sum(inertia_t, axis=0)
    net = gas_torque + inertia_torque - friction
    step = cycle_angle / theta.size
    gas_work = float(np.sum(gas_torque) * step)
    load_torque = float(np.mean(gas_torque - friction))
    inertia_total = sum(c.crank_inertia for c in specs) + np.sum(slope_sq, axis=0)
    inertia_slope = np.sum(slope_dd, axis=0)
    driving = gas_torque - friction - load_torque
    work = np.concatenate([[0.0], np.cumsum(0.5 * (driving[1:] + driving[:-1]) * step)])
    omega = speed_from_energy(work, inertia_total, w, step)
    acceleration = (driving - 0.5 * inertia_slope * omega**2) / inertia_total
    shake_z_a, shake_x_a = np.array(shake_z), np.array(shake_x)
    return CycleResult(
        speed_mean=float(w),
        strokes=int(strokes),
        angle=theta,
        pressure=np.array(pressures),
        gas_torque=gas_torque,
        inertia_torque=inertia_torque,
        friction_torque=friction,
        net_torque=net,
        inline_load=inline_a,
        transverse_load=transverse_a,
        bearing_load=load,
        shaking_inline=shake_z_a,
        shaking_transverse=shake_x_a,
        speed=omega,
        crank_acceleration=acceleration,
        load_torque=load_torque,
        indicated_work=indicated,
        gas_work=gas_work,
        mean_friction_torque=float(np.mean(friction)),
        friction_power=float(np.mean(friction) * w),
        peak_bearing_load=float(load.max()),
        mean_bearing_load=float(load.mean()),
        peak_net_torque=float(net.max()),
        max_crank_acceleration=float(np.abs(acceleration).max()),
        speed_fluctuation=float((omega.max() - omega.min()) / w),
        peak_shaking_inline=float(np.abs(shake_z_a.sum(axis=0)).max()),
        peak_shaking_transverse=float(np.abs(shake_x_a.sum(axis=0)).max()),
        peak_shaking_force=float(np.hypot(shake_z_a.sum(axis=0), shake_x_a.sum(axis=0)).max()),
    )


@record
class CylinderForces(ResultMixin):
    r"""The forces of one cylinder's crank train over the crank angle (:func:`cylinder_forces`).

    Attributes
    ----------
    gas : ndarray
        Gas force on the piston, :math:`(p - p_{cc})A_p`, pushing it toward the crank [N].
    inertia : ndarray
        Reciprocating inertia force :math:`m_{rec}\ddot s` along the cylinder axis, away
        from the crank [N]; the rod's force on the piston along the axis is
        ``gas + inertia``.
    u, q : ndarray
        Transverse and axial components of the rod from big end to small end [m]; the
        rod's force on the piston across the axis is ``(gas + inertia) * u / q``.
    gas_torque, inertia_torque : ndarray
        Torque on the crank of the gas and of the inertia part of the rod force, positive
        with rotation [N m].
    slope, curvature : ndarray
        :math:`ds/d\theta` [m/rad] and :math:`d^2s/d\theta^2` [m/rad^2] of the piston.
    indicated_work : float
        Closed-loop integral of p dV over the samples (trapezoids) [J].
    """

    gas: NDArray = field(repr=False)
    inertia: NDArray = field(repr=False)
    u: NDArray = field(repr=False)
    q: NDArray = field(repr=False)
    gas_torque: NDArray = field(repr=False)
    inertia_torque: NDArray = field(repr=False)
    slope: NDArray = field(repr=False)
    curvature: NDArray = field(repr=False)
    indicated_work: float


def cylinder_forces(
    angle: NDArray, cylinder: CylinderSpec, pressure: NDArray, speed: float
) -> CylinderForces:
    r"""Gas and reciprocating inertia forces of one cylinder and their torques on the crank.

    With the exact slider-crank of :mod:`crankbalance.physics.kinematics` (crank angle
    :math:`\theta` from the cylinder axis, crankpin at :math:`r(\sin\theta, \cos\theta)`):

    .. math::
        F_g = (p - p_{cc})A_p,\qquad F_i = m_{rec}\,\omega^2 s''(\theta),\qquad
        u = e - r\sin\theta,\quad q = \sqrt{l^2 - u^2}

        T = z_{pin}F_x - x_{pin}F_z \text{ of } \mathbf F = -(F_g + F_i)(1, u/q)

    The rod is a two-force member: it pushes the piston with
    :math:`(F_g + F_i)(1, u/q)` in (axis, across) and the crankpin with the opposite force.
    This is the one place both :func:`engine_cycle` and the whole-engine cycle
    (:func:`crankbalance.physics.engine_cycle_all.engine_cycle_all`) take those forces from.

    Parameters
    ----------
    angle : ndarray
        Crank angle from the cylinder's firing TDC [rad].
    cylinder : CylinderSpec
        Geometry, reciprocating mass and crankcase pressure.
    pressure : ndarray
        Absolute cylinder pressure at each angle [Pa].
    speed : float
        Crank speed [rad/s].

    Returns
    -------
    CylinderForces
        The forces [N], the rod's components [m], torques [N m], the piston's slope and
        curvature, and the indicated work [J].

    References
    ----------
    Hoem and Røsholm (2016), Sec. 2.3; Den Hartog (1956), Sec. 5.3.
    """
    local = angle
    r, l_, e = cylinder.crank_radius, cylinder.rod_length, cylinder.offset
    p = pressure
    s1 = kinematics.piston_velocity(local, r, l_, e)  # ds/dtheta [m/rad]
    s2 = kinematics.piston_acceleration(local, r, l_, e)  # d2s/dtheta2 [m/rad^2]
    u = e - r * np.sin(local)
    q = np.sqrt(l_**2 - u**2)
    gas = (p - cylinder.crankcase_pressure) * cylinder.piston_area
    inertial = cylinder.reciprocating_mass * speed**2 * s2
    pin_x, pin_z = r * np.sin(local), r * np.cos(local)
    # torque of the force -F_rod at the crankpin, positive with rotation
    gas_t = pin_z * (-gas * u / q) - pin_x * (-gas)
    inertia_t = pin_z * (-inertial * u / q) - pin_x * (-inertial)
    volume = cylinder.piston_area * (-kinematics.piston_position(local, r, l_, e))
    indicated = float(np.sum(0.5 * (p + np.roll(p, -1)) * (np.roll(volume, -1) - volume)))
    return CylinderForces(
        gas=gas,
        inertia=inertial,
        u=u,
        q=q,
        gas_torque=gas_t,
        inertia_torque=inertia_t,
        slope=s1,
        curvature=s2,
        indicated_work=indicated,
    )


def cylinder_pressure(
    angle: NDArray, spec: CylinderSpec, source: PressureSource, strokes: int
) -> NDArray:
    """Cylinder pressure over the cycle from a Wiebe combustion or a table.

    Parameters
    ----------
    angle : ndarray
        Crank angle of the cylinder from its firing top dead centre [rad].
    spec : CylinderSpec
        The cylinder (bore, compression, for the Wiebe model).
    source : WiebeCombustion or tuple of (ndarray, ndarray)
        The Wiebe model, or a table (crank angle [rad], absolute pressure [Pa]).
    strokes : int
        Strokes per working cycle (2 or 4) [-].

    Returns
    -------
    ndarray
        Absolute cylinder pressure at every angle [Pa].

    Raises
    ------
    InputError
        For a source that is neither.
    """
    if isinstance(source, WiebeCombustion):
        return wiebe_pressure(angle, spec, source, strokes)  # type: ignore[arg-type]
    if isinstance(source, tuple) and len(source) == 2:
        return tabulated_pressure(angle, source[0], source[1], strokes)  # type: ignore[arg-type]
    raise InputError(
        "pressure",
        type(source).__name__,
        "must be a WiebeCombustion or a tuple (angle [rad], pressure [Pa])",
    )


def speed_from_energy(work: NDArray, inertia: NDArray, mean_speed: float, step: float) -> NDArray:
    r"""Speed over the cycle from :math:`\tfrac{1}{2} J\omega^2 = E_0 + W` with the
    time-mean speed prescribed (Newton's method on :math:`E_0`).

    Parameters
    ----------
    work : ndarray, shape (N,)
        Work done on the crank since the start of the cycle at each sample [J].
    inertia : ndarray, shape (N,)
        Rotating inertia of the crank train at each sample [kg m^2].
    mean_speed : float
        Time-mean crank speed [rad/s].
    step : float
        Crank angle between samples [rad].

    Returns
    -------
    ndarray, shape (N,)
        Crank speed at each sample [rad/s].

    Raises
    ------
    InputError
        Naming ``crank_inertia`` when the inertia is too small for the cycle (the crank
        would nearly stop).
    """
    # Start from E0 = 1/2 J_mean w^2 - mean(W); Newton on the time-mean speed condition.
    energy0 = 0.5 * float(np.mean(inertia)) * mean_speed**2 - float(np.mean(work))
    # the least E0 that keeps the kinetic energy above zero at every sample, with a margin
    # in proportion to the work (an absolute one vanishes in the rounding of a large work,
    # and a zero speed would divide by zero below)
    floor = float(np.max(-work)) + 1e-12 * max(1.0, float(np.max(np.abs(work))))
    energy0 = max(energy0, floor * 1.01 + 1e-9)
    for _ in range(50):
        kinetic = energy0 + work
        omega = np.sqrt(2.0 * kinetic / inertia)
        # time-mean speed = cycle / sum(dtheta / omega)
        harmonic = 1.0 / np.mean(1.0 / omega)
        # d(harmonic)/dE0 = harmonic^2 * mean(omega^-2 * d omega/dE0), d omega/dE0 = 1/(J omega)
        derivative = harmonic**2 * np.mean(1.0 / (omega**3 * inertia))
        update = (harmonic - mean_speed) / derivative
        energy0 = max(energy0 - update, 0.5 * (energy0 + floor))
        if abs(update) < 1e-12 * energy0:
            break
    omega = np.sqrt(2.0 * (energy0 + work) / inertia)
    achieved = 1.0 / np.mean(1.0 / omega)
    if abs(achieved - mean_speed) > 1e-6 * mean_speed or np.ptp(omega) > 0.5 * mean_speed:
        raise InputError(
            "crank_inertia",
            float(np.mean(inertia)),
            f"is too small for this cycle at {mean_speed * 30 / np.pi:.0f} rpm: its torque "
            f"gives and takes {float(np.ptp(work)):.4g} J within the cycle, which would swing "
            "the speed by more than half its mean (the crank would nearly stop); give the "
            "inertia of crankshaft, flywheel and clutch together",
        )
    return omega


# ======================================================================================
# Performance sensitivity
# ======================================================================================


@record
class SensitivityResult(ResultMixin):
    """Result of :func:`balance_sensitivity`; every indicator has shape
    ``(len(mass_scales), len(balance_factors))``.

    Attributes
    ----------
    speed : float
        Mean crank speed of every cycle [rad/s].
    balance_factors : ndarray
        Balance factors swept [-].
    mass_scales : ndarray
        Factors on the reciprocating mass (< 1: lighter parts) [-].
    mean_friction_torque : ndarray [N m]
    friction_power : ndarray [W]
    peak_bearing_load, mean_bearing_load : ndarray [N]
    peak_net_torque : ndarray [N m]
    max_crank_acceleration : ndarray [rad/s^2]
    speed_fluctuation : ndarray [-]
    peak_shaking_inline, peak_shaking_transverse, peak_shaking_force : ndarray [N]
    """

    speed: float
    balance_factors: NDArray
    mass_scales: NDArray
    mean_friction_torque: NDArray
    friction_power: NDArray
    peak_bearing_load: NDArray
    mean_bearing_load: NDArray
    peak_net_torque: NDArray
    max_crank_acceleration: NDArray
    speed_fluctuation: NDArray
    peak_shaking_inline: NDArray
    peak_shaking_transverse: NDArray
    peak_shaking_force: NDArray


SENSITIVITY_INDICATORS: tuple[str, ...] = (
    "mean_friction_torque",
    "friction_power",
    "peak_bearing_load",
    "mean_bearing_load",
    "peak_net_torque",
    "max_crank_acceleration",
    "speed_fluctuation",
    "peak_shaking_inline",
    "peak_shaking_transverse",
    "peak_shaking_force",
)


def balance_sensitivity(
    cylinder: CylinderSpec,
    speed: float,
    pressure: PressureSource,
    balance_factors: ArrayLike,
    mass_scales: ArrayLike = (1.0,),
    strokes: Strokes = 4,
    samples_per_revolution: int = 360,
    progress: Callable[[int, int], None] | None = None,
) -> SensitivityResult:
    r"""Sweep the balance factor (and the reciprocating mass) of a single cylinder.

    Each point is one :func:`engine_cycle`; the balance factor is the share of the
    reciprocating mass balanced by the counterweight on top of 100 % of the rotating mass.

    Parameters
    ----------
    cylinder : CylinderSpec
        Base cylinder; its ``balance_factor`` and ``reciprocating_mass`` are replaced.
    speed : float
        Mean crank speed [rad/s].
    pressure : WiebeCombustion or (angle, pressure) arrays
        Pressure model.
    balance_factors : array_like
        Balance factors to evaluate, each in [0, 2] [-].
    mass_scales : array_like
        Factors on the reciprocating mass [-].
    strokes : {2, 4}
        Cycle type.
    samples_per_revolution : int
        Angle resolution of each cycle.
    progress : callable, optional
        Called as ``progress(done, total)`` after each point.

    Returns
    -------
    SensitivityResult
        Every indicator over (mass scale, balance factor).

    References
    ----------
    Hoem and Røsholm (2016), Sec. 1 (performance indicators), Sec. 4.2 and Sec. 5.1 (friction
    torque against the balance factor, Figs. 5.2-5.6).
    """
    factors = np.atleast_1d(np.asarray(balance_factors, dtype=float))
    scales = np.atleast_1d(np.asarray(mass_scales, dtype=float))
    if factors.size == 0 or factors.ndim != 1:
        raise InputError("balance_factors", balance_factors, "must be a non-empty list")
    if scales.size == 0 or scales.ndim != 1 or np.any(~(scales > 0) | ~np.isfinite(scales)):
        raise InputError(
            "mass_scales", mass_scales, "must be a non-empty list of finite numbers > 0"
        )
    low, high = BALANCE_FACTOR_RANGE
    outside = factors[~((factors >= low) & (factors <= high))]
    if outside.size:  # refuse before the first (possibly long) cycle is computed
        raise InputError(
            "balance_factors", float(outside[0]), f"each must lie between {low:g} and {high:g}"
        )
    out = {name: np.zeros((scales.size, factors.size)) for name in SENSITIVITY_INDICATORS}
    total, done = scales.size * factors.size, 0
    from dataclasses import replace

    for i, scale in enumerate(scales):
        for k, factor in enumerate(factors):
            spec = replace(
                cylinder,
                balance_factor=float(factor),
                reciprocating_mass=cylinder.reciprocating_mass * float(scale),
            )
            result = engine_cycle(
                spec, speed, pressure, strokes, samples_per_revolution=samples_per_revolution
            )
            for name in SENSITIVITY_INDICATORS:
                out[name][i, k] = getattr(result, name)
            done += 1
            if progress is not None:
                progress(done, total)
    return SensitivityResult(speed=float(speed), balance_factors=factors, mass_scales=scales, **out)
