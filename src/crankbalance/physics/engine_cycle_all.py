r"""The whole engine over one working cycle: every cylinder at once, phased by its firing.

Every cylinder of an :class:`~crankbalance.physics.model.EngineModel` (its bank angle, the throw it
sits on, shared crankpins included) runs the single-cylinder model of
:mod:`crankbalance.physics.engine_cycle`
(:func:`~crankbalance.physics.engine_cycle.cylinder_forces`: exact
slider-crank, gas force from the Wiebe model or a pressure table per cylinder) at its own
firing phase (the crank angle at which each cylinder fires,
:func:`crankbalance.physics.firing.firing_angles`). The module gives:

* :func:`engine_cycle_all` -- the crank torque (gas, inertia, total, per cylinder), the
  speed fluctuation at a given rotating inertia, the flywheel that meets a target speed
  fluctuation (and its check by re-integration), and the force the rods put on each
  crankpin (``throw_force``) (:class:`EngineCycleResult`);
* :func:`flywheel_inertia` -- the energy method of flywheel sizing (closed form).

Frames and angles: as :mod:`crankbalance.physics.model` and :mod:`crankbalance.physics.shaking`.
The crank angle :math:`\theta` is that of the first throw; a throw at :math:`\varphi_t` has its
crankpin at :math:`r e^{i(\theta + \varphi_t)}` in the complex plane :math:`z + i x`; cylinder c
(bank :math:`\beta_c`, throw angle :math:`\varphi_c`) is at a top dead centre when :math:`\theta
+ \varphi_c - \beta_c \equiv 0 \pmod{2\pi}`, and fires at the crank angle :math:`t_c` (one of
those, once per cycle of :math:`2\pi` or :math:`4\pi`). Its crank angle from its own firing TDC
is :math:`\theta - t_c`.

Friction is not in this model (the torques are indicated: gas and inertia); the
main-bearing loads and their friction belong to the crank's bearing model, which takes
``throw_force`` from here.

References
----------
Hoem and Røsholm (2016), Sec. 2.3; Den Hartog (1956), Secs. 5.3-5.4 (inertia torque);
Taylor (1985), Vol. 2, ch. 8 (torque of multi-cylinder engines, flywheel sizing by the
energy method); Heywood (1988), Sec. 9.2 (the Wiebe model).
"""

from __future__ import annotations

import math
from dataclasses import field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_positive
from ..records import record
from ..results import ResultMixin
from .engine_cycle import (
    CylinderSpec,
    PressureSource,
    check_samples,
    cycle_angles,
    cylinder_forces,
    cylinder_pressure,
    speed_from_energy,
)
from .firing import TDC_TOLERANCE, check_strokes
from .limits import MAX_FLUCTUATION_TARGET as MAX_FLUCTUATION_TARGET
from .limits import MIN_FLUCTUATION_TARGET as MIN_FLUCTUATION_TARGET
from .model import EngineModel, model_fire_angles, tdc_shift


def flywheel_inertia(
    angle: ArrayLike, torque: ArrayLike, speed: float, target: float
) -> tuple[float, float]:
    r"""Rotating inertia that keeps the speed fluctuation at a target: the energy method.

    Over a cycle sampled evenly, with the mean torque :math:`\bar T` taken by a constant
    load, the energy the rotating parts take and give back is
    :math:`E(\theta) = \int (T - \bar T)\,d\theta`; with the largest excursion
    :math:`\Delta E = \max E - \min E` and
    :math:`\tfrac12 I(\omega_{max}^2 - \omega_{min}^2) = \Delta E`,
    :math:`\omega_{max} + \omega_{min} \approx 2\bar\omega`:

    .. math:: I = \frac{\Delta E}{\delta\,\bar\omega^2},\qquad
              \delta = \frac{\omega_{max} - \omega_{min}}{\bar\omega}

    Parameters
    ----------
    angle : array_like, shape (S,)
        Crank angle of the samples, evenly spaced over one whole cycle [rad].
    torque : array_like, shape (S,)
        Crank torque at the mean speed (gas and inertia, less friction if any) [N m].
    speed : float
        Mean crank speed :math:`\bar\omega` [rad/s].
    target : float
        Speed fluctuation :math:`\delta` to meet, from :data:`MIN_FLUCTUATION_TARGET` to
        :data:`MAX_FLUCTUATION_TARGET` [-].

    Returns
    -------
    inertia : float
        Rotating inertia about the crank axis that meets the target [kg m^2]: all of it,
        including the mean inertia of the reciprocating parts when ``torque`` holds their
        inertia torque.
    energy_excursion : float
        :math:`\Delta E` [J].

    References
    ----------
    Taylor (1985), Vol. 2, ch. 8 (flywheel by the energy method); Den Hartog (1956),
    Sec. 5.4 (coefficient of fluctuation).
    """
    check_positive("speed", speed)
    if not (MIN_FLUCTUATION_TARGET <= target <= MAX_FLUCTUATION_TARGET):
        raise InputError(
            "speed_fluctuation_target",
            target,
            f"must be from {MIN_FLUCTUATION_TARGET:g} to {MAX_FLUCTUATION_TARGET:g}",
        )
    theta = np.asarray(angle, dtype=float)
    t = np.asarray(torque, dtype=float)
    excursion = energy_excursion(theta, t)
    return excursion / (target * speed**2), excursion


def energy_excursion(angle: ArrayLike, torque: ArrayLike) -> float:
    r"""Largest excursion of :math:`E(\theta) = \int (T - \bar T)\,d\theta` over a cycle [J].

    Parameters
    ----------
    angle : array_like, shape (S,)
        Crank angle of the samples, evenly spaced over one whole cycle [rad].
    torque : array_like, shape (S,)
        Crank torque at each sample [N m].

    Returns
    -------
    float
        :math:`\max E - \min E` [J] (trapezoids, the cycle closed periodically).
    """
    theta = np.asarray(angle, dtype=float)
    t = np.asarray(torque, dtype=float)
    if theta.ndim != 1 or theta.shape != t.shape or theta.size < 4:
        raise InputError("torque", t.shape, "needs one value per angle, at least 4 samples")
    step = float(theta[1] - theta[0])
    swing = t - np.mean(t)
    energy = np.concatenate([[0.0], np.cumsum(0.5 * (swing + np.roll(swing, -1)) * step)])
    return float(np.ptp(energy))


@record
class EngineCycleResult(ResultMixin):
    r"""Result of :func:`engine_cycle_all`: the whole engine over one working cycle.

    Arrays over the cycle have S samples; per cylinder (C, S), per throw (T, S). Complex
    forces are :math:`z + i x` in the engine frame (:mod:`crankbalance.physics.shaking`).

    Attributes
    ----------
    speed_mean : float
        Mean crank speed [rad/s].
    strokes : int
        Strokes per working cycle (2 or 4).
    angle : ndarray, shape (S,)
        Crank angle of the first cylinder of the firing order from its axis (its firing
        TDC without offset; the origin of the one-cylinder model) [rad], from minus to
        plus half a cycle.
    crank_angle : ndarray, shape (S,)
        Crank angle of the first throw at the same samples, ``angle + fire_angle[first] -
        psi[first]`` [rad] (:math:`\psi` the top dead centre of an offset slider-crank past
        its axis; throw t's crankpin is at :math:`r e^{i(\theta + \varphi_t)}`).
    fire_angle : ndarray, shape (C,)
        Crank angle of the first throw at which each cylinder fires [rad], in [0, cycle).
    pressure : ndarray, shape (C, S)
        Cylinder pressures [Pa].
    cylinder_gas_torque, cylinder_inertia_torque : ndarray, shape (C, S)
        Each cylinder's gas and reciprocating-inertia torque on the crank [N m].
    gas_torque, inertia_torque, torque : ndarray, shape (S,)
        Their sums over the cylinders, and ``torque = gas + inertia`` [N m] (indicated, at
        the mean speed, positive with rotation).
    throw_force : ndarray of complex, shape (T, S)
        Force the rods of the cylinders on each throw put on its crankpin: gas and
        reciprocating inertia through the rod, :math:`-\sum_c (F_g + F_i)(1 + i\,u/q)
        e^{i\beta_c}` [N]; without the throw's own rotating mass (crankpin, webs, big
        ends: ``EngineModel.throw_rotating_mass``) and without counterweights.
    throw_force_inertia : ndarray of complex, shape (T, S)
        The reciprocating-inertia part of ``throw_force`` [N] (the rest is the gas part).
    side_force : ndarray of complex, shape (C, S)
        Force of each piston on its cylinder wall, :math:`(F_g + F_i)(u/q)\,i e^{i\beta_c}`
        [N]; with the inertia parts of ``throw_force`` it sums to the free inertia force.
    side_force_inertia : ndarray of complex, shape (C, S)
        The reciprocating-inertia part of ``side_force`` [N].
    mean_torque : float
        Mean of ``torque`` over the cycle, the indicated torque the load takes [N m].
    indicated_work : float
        Sum over the cylinders of the closed-loop integral of p dV [J].
    gas_work : float
        Work of ``gas_torque`` over the cycle [J].
    indicated_power : float
        ``mean_torque`` times the mean speed [W].
    peak_torque, min_torque : float
        Largest and smallest ``torque`` [N m].
    crank_inertia : float
        Purely rotating inertia the speed was computed with (crank, flywheel) [kg m^2].
    speed : ndarray, shape (S,)
        Crank speed over the cycle under the constant load ``mean_torque`` [rad/s].
    crank_acceleration : ndarray, shape (S,)
        Crank acceleration [rad/s^2].
    speed_fluctuation : float
        :math:`(\omega_{max} - \omega_{min})/\bar\omega` with ``crank_inertia`` [-].
    energy_excursion : float
        Largest excursion of :math:`\int (T - \bar T)\,d\theta` [J].
    speed_fluctuation_target : float or None
        The target of the flywheel sizing [-], None when none was asked.
    required_inertia : float or None
        Purely rotating inertia that meets the target by the energy method, less the mean
        inertia of the reciprocating parts :math:`\overline{\sum_c m_c s_c'^2}` (which
        turns with the crank like a flywheel) [kg m^2]; 0 when those alone meet it.
    required_inertia_fluctuation : float or None
        Speed fluctuation with ``required_inertia``, from the speed integration (the check
        of the closed form) [-].
    """

    speed_mean: float
    strokes: int
    angle: NDArray = field(repr=False)
    crank_angle: NDArray = field(repr=False)
    fire_angle: NDArray = field(repr=False)
    pressure: NDArray = field(repr=False)
    cylinder_gas_torque: NDArray = field(repr=False)
    cylinder_inertia_torque: NDArray = field(repr=False)
    gas_torque: NDArray = field(repr=False)
    inertia_torque: NDArray = field(repr=False)
    torque: NDArray = field(repr=False)
    throw_force: NDArray = field(repr=False)
    throw_force_inertia: NDArray = field(repr=False)
    side_force: NDArray = field(repr=False)
    side_force_inertia: NDArray = field(repr=False)
    mean_torque: float
    indicated_work: float
    gas_work: float
    indicated_power: float
    peak_torque: float
    min_torque: float
    crank_inertia: float
    speed: NDArray = field(repr=False)
    crank_acceleration: NDArray = field(repr=False)
    speed_fluctuation: float
    energy_excursion: float
    speed_fluctuation_target: float | None = None
    required_inertia: float | None = None
    required_inertia_fluctuation: float | None = None


def engine_cycle_all(
    model: EngineModel,
    pressure: PressureSource | list[PressureSource],
    *,
    bore: float,
    crank_inertia: float,
    speed: float | None = None,
    fire_angle: ArrayLike | None = None,
    crankcase_pressure: float = 1.0e5,
    speed_fluctuation_target: float | None = None,
    samples_per_revolution: int = 720,
) -> EngineCycleResult:
    r"""One working cycle of the whole engine: all cylinders firing, torque, speed, pin forces.

    For each cylinder c at its crank angle from firing TDC :math:`\theta - t_c`, the
    forces of :func:`~crankbalance.physics.engine_cycle.cylinder_forces` (gas force
    :math:`F_g`, reciprocating inertia :math:`F_i = m_c\omega^2 s''`, rod components
    :math:`u, q`) give, in the engine frame (:math:`e^{i\beta_c}` along its axis):

    .. math::
        T = \sum_c T_{g,c} + T_{i,c},\qquad
        \mathbf F_{pin,t} = -\sum_{c \in t} (F_{g,c} + F_{i,c})
            \Big(1 + i\frac{u_c}{q_c}\Big) e^{i\beta_c}

    The speed over the cycle follows the Lagrange equation of the crank train with the
    variable inertia :math:`J(\theta) = I + \sum_c m_c s_c'^2`, integrated exactly as
    :math:`\tfrac12 J\omega^2 = E_0 + \int (T_g - \bar T_g)\,d\theta` with :math:`E_0` set
    by the mean speed (as :func:`~crankbalance.physics.engine_cycle.engine_cycle`, without
    friction). A flywheel target is met by :func:`flywheel_inertia` on the total torque
    and checked by that integration with the inertia found.

    Parameters
    ----------
    model : EngineModel
        The engine: throws, banks, firing order, reciprocating masses, strokes.
    pressure : WiebeCombustion or (angle, pressure) arrays, or a list of them
        One pressure model for every cylinder, or a list with one per cylinder in
        cylinder-number order; a table gives [rad] from firing TDC and [Pa].
    bore : float
        Cylinder bore [m].
    crank_inertia : float
        Inertia of everything that purely rotates (crankshaft with counterweights, big
        ends, flywheel, clutch) about the crank axis [kg m^2].
    speed : float, optional
        Mean crank speed [rad/s]; default ``model.speed``.
    fire_angle : array_like, shape (C,), optional
        Crank angle of the first throw at which each cylinder fires [rad]; each must be a
        top dead centre of its cylinder. Default :func:`firing_angles` of the model.
    crankcase_pressure : float
        Pressure under the pistons [Pa].
    speed_fluctuation_target : float, optional
        Speed fluctuation to size the rotating inertia for [-].
    samples_per_revolution : int
        Angle resolution.

    Returns
    -------
    EngineCycleResult
        Torques [N m], pin and side forces [N], speed [rad/s], flywheel sizing.

    References
    ----------
    Hoem and Røsholm (2016), Sec. 2.3; Den Hartog (1956), Secs. 5.3-5.4; Taylor (1985),
    Vol. 2, ch. 8.
    """
    strokes = int(model.strokes)
    check_strokes(strokes)
    w = float(model.speed if speed is None else speed)
    check_positive("speed", w)
    check_positive("bore", bore)
    check_positive("crank_inertia", crank_inertia)
    check_samples(samples_per_revolution)
    if model.articulation is not None:
        raise InputError(
            "crank_train.articulated",
            "master-and-link rods",
            "the whole-engine cycle models every cylinder as a plain slider-crank; an "
            "articulated radial's link pistons are not (analyze gives their free forces)",
        )
    count = model.cylinders
    sources = _sources(pressure, count)
    fire = _fire_angles(model, fire_angle)
    psi = tdc_shift(model)
    cycle = math.pi * strokes
    first = model.firing_order[0] - 1 if model.firing_order_given else 0
    theta = cycle_angles(strokes, int(samples_per_revolution))
    step = cycle / theta.size
    specs = [
        CylinderSpec(
            bore=bore,
            crank_radius=model.crank_radius,
            rod_length=model.rod_length,
            reciprocating_mass=float(mass),
            crank_inertia=crank_inertia,
            offset=float(offset),
            crankcase_pressure=crankcase_pressure,
        )
        for mass, offset in zip(model.reciprocating_mass, model.cylinder_offset, strict=True)
    ]
    shape = (count, theta.size)
    pressures, gas_t, inertia_t = np.empty(shape), np.empty(shape), np.empty(shape)
    side, side_inertia = np.empty(shape, complex), np.empty(shape, complex)
    pin, pin_inertia = np.empty(shape, complex), np.empty(shape, complex)
    inertia_total = np.full(theta.size, float(crank_inertia))
    inertia_slope = np.zeros(theta.size)
    indicated = 0.0
    for c, spec in enumerate(specs):
        # this cylinder's crank angle from its axis, where the one-cylinder model (and
        # ``theta`` for the first cylinder) has its origin: its firing top dead centre is
        # psi_c past the axis, so the cylinders fire at their real top dead centres
        local = theta - (fire[c] - fire[first]) + (psi[c] - psi[first])
        p = cylinder_pressure(local, spec, sources[c], strokes)
        f = cylinder_forces(local, spec, p, w)
        axis = np.exp(1j * model.cylinder_bank[c])
        obliquity = f.u / f.q
        pressures[c], gas_t[c], inertia_t[c] = p, f.gas_torque, f.inertia_torque
        pin[c] = -(f.gas + f.inertia) * (1 + 1j * obliquity) * axis
        pin_inertia[c] = -f.inertia * (1 + 1j * obliquity) * axis
        side[c] = (f.gas + f.inertia) * obliquity * 1j * axis
        side_inertia[c] = f.inertia * obliquity * 1j * axis
        inertia_total += spec.reciprocating_mass * f.slope**2
        inertia_slope += 2 * spec.reciprocating_mass * f.slope * f.curvature
        indicated += f.indicated_work
    throw_force = np.zeros((model.throws, theta.size), complex)
    throw_force_inertia = np.zeros((model.throws, theta.size), complex)
    np.add.at(throw_force, model.cylinder_throw, pin)
    np.add.at(throw_force_inertia, model.cylinder_throw, pin_inertia)
    gas_torque, inertia_torque = gas_t.sum(axis=0), inertia_t.sum(axis=0)
    torque = gas_torque + inertia_torque
    load = float(np.mean(gas_torque))
    driving = gas_torque - load
    work = np.concatenate([[0.0], np.cumsum(0.5 * (driving[1:] + driving[:-1]) * step)])
    excursion = energy_excursion(theta, torque)
    required = achieved = None
    if speed_fluctuation_target is not None:
        total, _ = flywheel_inertia(theta, torque, w, speed_fluctuation_target)
        variable = inertia_total - crank_inertia  # the reciprocating parts' share
        # the mean of the reciprocating parts' inertia turns with the crank like a flywheel
        required = max(total - float(np.mean(variable)), 0.0)
        check = speed_from_energy(work, required + variable, w, step)
        achieved = float(np.ptp(check) / w)
    try:
        omega = speed_from_energy(work, inertia_total, w, step)
    except InputError as error:
        if required is None:
            raise
        raise InputError(
            "crank_inertia",
            crank_inertia,
            f"{error.allowed}; a speed fluctuation of {speed_fluctuation_target:g} needs "
            f"{required:.4g} kg m^2 of purely rotating inertia",
        ) from None
    acceleration = (driving - 0.5 * inertia_slope * omega**2) / inertia_total
    return EngineCycleResult(
        speed_mean=w,
        strokes=strokes,
        angle=theta,
        crank_angle=theta + fire[first] - psi[first],
        fire_angle=fire,
        pressure=pressures,
        cylinder_gas_torque=gas_t,
        cylinder_inertia_torque=inertia_t,
        gas_torque=gas_torque,
        inertia_torque=inertia_torque,
        torque=torque,
        throw_force=throw_force,
        throw_force_inertia=throw_force_inertia,
        side_force=side,
        side_force_inertia=side_inertia,
        mean_torque=float(np.mean(torque)),
        indicated_work=indicated,
        gas_work=float(np.sum(gas_torque) * step),
        indicated_power=float(np.mean(torque) * w),
        peak_torque=float(torque.max()),
        min_torque=float(torque.min()),
        crank_inertia=float(crank_inertia),
        speed=omega,
        crank_acceleration=acceleration,
        speed_fluctuation=float(np.ptp(omega) / w),
        energy_excursion=excursion,
        speed_fluctuation_target=(
            None if speed_fluctuation_target is None else float(speed_fluctuation_target)
        ),
        required_inertia=required,
        required_inertia_fluctuation=achieved,
    )


def _sources(pressure: object, count: int) -> list[PressureSource]:
    """One pressure source per cylinder from one source or a list of them."""
    if isinstance(pressure, list):
        if len(pressure) != count:
            raise InputError(
                "pressure",
                f"{len(pressure)} sources",
                f"must be one for every cylinder or one per cylinder ({count})",
            )
        return list(pressure)
    return [pressure] * count  # type: ignore[list-item]


def _fire_angles(model: EngineModel, fire_angle: ArrayLike | None) -> NDArray[np.float64]:
    """The firing angles of the model, or the given ones checked against its crank."""
    shift = tdc_shift(model)
    if fire_angle is None:
        return model_fire_angles(model)
    fire = np.asarray(fire_angle, dtype=float).reshape(-1)
    if fire.size != model.cylinders or not np.all(np.isfinite(fire)):
        raise InputError("fire_angle", fire_angle, f"must give {model.cylinders} finite angles")
    gap = np.remainder(fire + model.cylinder_angle - model.cylinder_bank - shift + np.pi, 2 * np.pi)
    off = np.flatnonzero(np.abs(gap - np.pi) > TDC_TOLERANCE)
    if off.size:
        c = int(off[0])
        raise InputError(
            f"fire_angle (cylinder {c + 1})",
            f"{math.degrees(fire[c]):g} deg",
            "must be a top dead centre of that cylinder: crank angle + throw angle - bank "
            "angle - its offset's top-dead-centre angle asin(e/(l+r)) a multiple of 360 deg",
        )
    return np.mod(fire, math.pi * model.strokes)
