r"""Torsional vibration of the crank train: a lumped chain of inertias and shaft sections.

The crank train is a chain of N rigid inertias joined by N-1 massless torsional springs
(with viscous damping in parallel), free at both ends (free-free) or with a driven load at
the end (the load is one more inertia on one more spring):

    damper ring -(k_d, c_d)- front (pulley, hub) -k- throw 1 -k- ... -k- throw T
        -k- flywheel -(k_L)- load

* :func:`chain_matrices` -- the inertia, stiffness and damping matrices of a chain;
* :func:`natural_modes` -- undamped natural frequencies and mode shapes
  (``scipy.linalg.eigh`` on K and M) (:class:`TorsionalModes`);
* :func:`throw_inertias` -- one inertia per throw: the throw with its big ends and the mean
  inertia of its cylinders' reciprocating parts;
* :func:`carter_stiffness` -- the torsional stiffness of one crank throw from its journal,
  pin and web dimensions (Carter's equivalent length: an empirical approximation);
* :func:`crank_train` -- the chain of an engine (:class:`CrankTrain`);
* :func:`order_harmonics`, :func:`engine_excitation` -- the harmonics of the gas and
  inertia torque of every cylinder, by engine order, from one run of the whole-engine cycle
  (:func:`~crankbalance.physics.engine_cycle_all.engine_cycle_all`), which already phases each
  cylinder by its firing angle (:class:`EngineExcitation`);
* :func:`forced_response` -- steady-state amplitude of every mass and torque of every
  section, order by order, over a speed range, and the power the damper dissipates
  (:class:`ForcedResponse`);
* :func:`critical_speeds` -- where an engine order meets a natural frequency (the Campbell
  diagram's crossings);
* :func:`torsional_study` -- all of it for one chain and one excitation, its work counted
  first and bounded (:func:`response_size`, :data:`MAX_RESPONSE_SIZE`).

Angles are twists about the crank axis [rad] measured from the rigid rotation at the mean
speed ω; a harmonic of engine order n has the angular frequency Ω = n ω and is written
:math:`\mathrm{Re}(X e^{i n \theta})` with the crank angle θ = ω t (half orders for a
four-stroke). Torques on the crank are positive with rotation.

Why one module over 800 lines: the chain, its modes, the excitation and the forced response
are one model of one vibration, the lumped chain, and the study bounds its work from all
of them.

References
----------
Den Hartog (1956), ch. 5 (torsional vibration of engines: lumped model, mode shapes,
phase diagrams of the engine orders, dampers); Ker Wilson (1956), Vol. 1 (equivalent
systems, Carter's formula, reciprocating inertia, engine-order excitation); Hafner and
Maass (1985) (the torsional system of a multi-cylinder engine); Heywood (1988), Sec. 9.2.
"""

from __future__ import annotations

import math
from dataclasses import field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import linalg

from ..errors import InputError
from ..records import record
from ..results import ResultMixin
from .kinematics import piston_velocity
from .main_bearings import crank_planes
from .model import EngineModel

#: Carter's web term and journal length term (Ker Wilson 1956, Vol. 1; Carter 1928)
CARTER_WEB = 1.5
CARTER_JOURNAL_WEB = 0.8
CARTER_PIN = 0.75


def _positive(name: str, value: Any, *, zero: bool = False) -> NDArray[np.float64]:
    array = np.asarray(value, dtype=float)
    bad = ~np.isfinite(array) | ((array < 0) if zero else (array <= 0))
    if bad.any():
        shown = array[bad].ravel()[0]
        raise InputError(
            name, float(shown), "must be a finite number " + (">= 0" if zero else "> 0")
        )
    return array


def chain_matrices(
    inertia: ArrayLike,
    stiffness: ArrayLike,
    damping: ArrayLike | None = None,
    absolute_damping: ArrayLike | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    r"""Inertia, stiffness and damping matrices of a chain of inertias.

    Section s joins mass s and mass s+1: :math:`K_{ss} \mathrel{+}= k_s`,
    :math:`K_{s+1,s+1} \mathrel{+}= k_s`, :math:`K_{s,s+1} = K_{s+1,s} = -k_s`; the
    damping of the sections likewise, and the absolute damping (to ground) on the
    diagonal.

    Parameters
    ----------
    inertia : array_like, shape (N,)
        Mass moments of inertia [kg m^2].
    stiffness : array_like, shape (N-1,)
        Torsional stiffness of each section [N m/rad].
    damping : array_like, shape (N-1,), optional
        Viscous damping of each section [N m s/rad]; default none.
    absolute_damping : array_like, shape (N,), optional
        Viscous damping of each mass to ground [N m s/rad]; default none.

    Returns
    -------
    tuple of ndarray, each (N, N)
        M [kg m^2], K [N m/rad], C [N m s/rad].
    """
    j = _positive("inertia", inertia)
    k = _positive("stiffness", stiffness, zero=True)
    if j.ndim != 1 or k.shape != (j.size - 1,) or j.size < 2:
        raise InputError("stiffness", k.size, f"must have one value per section ({j.size - 1})")
    c = np.zeros(k.size) if damping is None else _positive("damping", damping, zero=True)
    ca = (
        np.zeros(j.size)
        if absolute_damping is None
        else _positive("absolute_damping", absolute_damping, zero=True)
    )
    if c.shape != k.shape or ca.shape != j.shape:
        raise InputError("damping", c.size, "must have one value per section")

    def assemble(values: NDArray[np.float64]) -> NDArray[np.float64]:
        out = np.zeros((j.size, j.size))
        index = np.arange(values.size)
        out[index, index] += values
        out[index + 1, index + 1] += values
        out[index, index + 1] -= values
        out[index + 1, index] -= values
        return out

    return np.diag(j), assemble(k), assemble(c) + np.diag(ca)


@record
class TorsionalModes(ResultMixin):
    """Result of :func:`natural_modes`: undamped natural frequencies and mode shapes.

    Attributes
    ----------
    frequency : ndarray, shape (N,)
        Natural angular frequencies, ascending [rad/s]; a free-free chain's first is the
        rigid rotation (0).
    mode_shape : ndarray, shape (N, N)
        Column m is mode m's twist of every mass, scaled to a largest magnitude of 1 with
        the first mass positive (or the first non-zero one) [-].
    nodes : ndarray of int, shape (N,)
        Sign changes along the chain of each mode (its nodes; 0 for the rigid mode).
    """

    frequency: NDArray[np.float64]
    mode_shape: NDArray[np.float64] = field(repr=False)
    nodes: NDArray[np.int64]


def natural_modes(inertia: ArrayLike, stiffness: ArrayLike) -> TorsionalModes:
    r"""Undamped natural frequencies and mode shapes of a chain: :math:`K\phi = \omega^2 M\phi`.

    Parameters
    ----------
    inertia : array_like, shape (N,)
        Mass moments of inertia [kg m^2].
    stiffness : array_like, shape (N-1,)
        Torsional stiffness of each section [N m/rad].

    Returns
    -------
    TorsionalModes
        Frequencies [rad/s], mode shapes [-], nodes.
    """
    m, k, _ = chain_matrices(inertia, stiffness)
    values, vectors = linalg.eigh(k, m)
    # A free chain turns rigidly at zero frequency, once per piece a loose section (k = 0)
    # leaves: those are the smallest eigenvalues, and every other one is > 0. They are set
    # by count, not by a threshold: the rounding of the rigid mode grows with the stiffest
    # section over the lightest mass (a 1e-12 kg m^2 flywheel puts it near 1e3 rad^2/s^2),
    # and a threshold on that scale would zero elastic modes too.
    values[: 1 + int(np.count_nonzero(np.asarray(stiffness, dtype=float) == 0))] = 0.0
    omega = np.sqrt(np.clip(values, 0.0, None))
    shapes = vectors / np.max(np.abs(vectors), axis=0)
    for col in range(shapes.shape[1]):
        lead = shapes[np.abs(shapes[:, col]) > 1e-9, col]
        if lead.size and lead[0] < 0:
            shapes[:, col] *= -1
    signs = np.where(np.abs(shapes) > 1e-9, np.sign(shapes), 0.0)
    nodes = np.array(
        [int(np.sum(np.diff(s[s != 0]) != 0)) for s in signs.T],
        dtype=np.int64,
    )
    return TorsionalModes(frequency=omega, mode_shape=shapes, nodes=nodes)


def crank_stations(model: EngineModel) -> tuple[NDArray[np.int64], tuple[str, ...]]:
    """The throw masses of the chain: one per axial plane of the crank, front to rear.

    Throws sharing an axial position (:func:`~crankbalance.physics.main_bearings.crank_planes`;
    a W engine built from VR banks has two in every plane) are one mass of the chain, and
    the chain runs in axial order whatever the order the throws are listed in.

    Parameters
    ----------
    model : EngineModel
        The engine (its throw positions).

    Returns
    -------
    station_of_throw : ndarray of int, shape (T,)
        Station (0-based, front first) of each throw [-].
    names : tuple of str
        Name of each station: ``throw 3``, or ``throws 1+7`` for throws in one plane.
    """
    station = crank_planes(model.throw_position)[1]
    names = tuple(
        ("throw " if np.sum(station == p) == 1 else "throws ")
        + "+".join(str(t + 1) for t in np.flatnonzero(station == p))
        for p in range(int(station.max()) + 1)
    )
    return station, names


def rotating_throw_inertia(
    model: EngineModel, throw_inertia: ArrayLike | None = None
) -> NDArray[np.float64]:
    r"""Inertia of each throw with its big ends, without its pistons: ``throw_inertia``, else
    its rotating mass at the crank radius, :math:`J_{throw,t} = m_{rot,t} r^2`.

    Parameters
    ----------
    model : EngineModel
        The engine.
    throw_inertia : float or array_like, shape (T,), optional
        Inertia of each throw (pin, webs, counterweights, big ends) [kg m^2].

    Returns
    -------
    ndarray, shape (T,)
        Inertia of each throw [kg m^2].
    """
    if throw_inertia is None:
        return np.asarray(model.throw_rotating_mass, dtype=float) * model.crank_radius**2
    return np.array(
        np.broadcast_to(_positive("throw_inertia", throw_inertia), (model.throws,)), dtype=float
    )


def throw_inertias(
    model: EngineModel, throw_inertia: ArrayLike | None = None
) -> NDArray[np.float64]:
    r"""One inertia per crank station (:func:`crank_stations`): its throws with their big
    ends plus their pistons' mean share.

    .. math::
        J_t = J_{throw,t} + \sum_{c \in t} m_c\,\overline{s_c'^2},\qquad
        \overline{s'^2} = \frac{r^2}{2}\Big(1 + \frac{\lambda^2}{4} + \dots\Big)

    The reciprocating parts move with :math:`s'(\alpha)`, so their kinetic energy
    :math:`\tfrac12 m s'^2 \omega^2` varies over a revolution; its mean is that of an
    inertia :math:`m\,\overline{s'^2}` (Den Hartog 1956, Sec. 5.3; Ker Wilson 1956: the
    usual :math:`m r^2/2`, here the exact mean of the slider-crank). Without
    ``throw_inertia`` the throw is its rotating mass at the crank radius,
    :math:`J_{throw} = m_{rot,t} r^2` (crankpin, webs reduced to the crank radius, big
    ends: an approximation that under-estimates webs and counterweights, whose mass lies
    at other radii; give the inertia from the drawing when known).

    Parameters
    ----------
    model : EngineModel
        The engine: throws, cylinders on them, masses, crank radius, rod length.
    throw_inertia : float or array_like, shape (T,), optional
        Inertia of each throw (pin, webs, counterweights, big ends) about the crank axis
        [kg m^2]; default :math:`m_{rot,t} r^2`.

    Returns
    -------
    ndarray, shape (P,)
        Inertia of each station (throws in one plane added), front first, with the
        reciprocating share [kg m^2].
    """
    r = model.crank_radius
    base = rotating_throw_inertia(model, throw_inertia)
    angle = np.linspace(0.0, 2.0 * math.pi, 3600, endpoint=False)
    offset = np.asarray(model.cylinder_offset, dtype=float)
    slope = piston_velocity(angle[:, None], r, model.rod_length, offset[None, :])  # (S, C)
    share = np.asarray(model.reciprocating_mass, dtype=float) * np.mean(slope**2, axis=0)
    per_throw = base.copy()
    np.add.at(per_throw, np.asarray(model.cylinder_throw, dtype=int), share)
    station = crank_stations(model)[0]
    return np.bincount(station, weights=per_throw).astype(float)


def carter_stiffness(
    journal_diameter: float,
    pin_diameter: float,
    journal_length: float,
    pin_length: float,
    web_thickness: float,
    web_width: float,
    crank_radius: float,
    shear_modulus: float = 80.0e9,
    journal_bore: float = 0.0,
    pin_bore: float = 0.0,
) -> float:
    r"""Torsional stiffness of one crank throw (journal, two webs, pin) by Carter's formula.

    The throw is replaced by a plain shaft of the journal's diameter and the equivalent
    length

    .. math::
        L_e = (l_j + 0.8\,h) + 0.75\,l_p\,\frac{D_j^4 - d_j^4}{D_p^4 - d_p^4}
              + 1.5\,r\,\frac{D_j^4 - d_j^4}{h\,w^3},\qquad
        k = \frac{G \pi (D_j^4 - d_j^4)}{32 L_e}

    (Carter 1928, as given by Ker Wilson 1956, Vol. 1). An empirical approximation: it
    fits measured cranks of its time to about ±10 % and knows nothing of fillets, oil holes
    or overlap of journal and pin; an FE model or a measurement is the reference.

    Parameters
    ----------
    journal_diameter, pin_diameter : float
        Outer diameters of main journal and crankpin [m].
    journal_length, pin_length : float
        Lengths of one main journal and one crankpin between the webs [m].
    web_thickness : float
        Web thickness h along the crank axis [m].
    web_width : float
        Web width w across the crank, at the section between journal and pin [m].
    crank_radius : float
        Crank radius r [m].
    shear_modulus : float
        Shear modulus G of the crank material [Pa]; 80 GPa for steel.
    journal_bore, pin_bore : float
        Bore diameters of hollow journal and pin [m]; 0 for solid.

    Returns
    -------
    float
        Torsional stiffness of one throw [N m/rad].
    """
    for name, value in (
        ("journal_diameter", journal_diameter),
        ("pin_diameter", pin_diameter),
        ("journal_length", journal_length),
        ("pin_length", pin_length),
        ("web_thickness", web_thickness),
        ("web_width", web_width),
        ("crank_radius", crank_radius),
        ("shear_modulus", shear_modulus),
    ):
        _positive(name, value)
    _positive("journal_bore", journal_bore, zero=True)
    _positive("pin_bore", pin_bore, zero=True)
    if journal_bore >= journal_diameter:
        raise InputError("journal_bore", journal_bore, "must be smaller than the journal diameter")
    if pin_bore >= pin_diameter:
        raise InputError("pin_bore", pin_bore, "must be smaller than the pin diameter")
    polar_j = journal_diameter**4 - journal_bore**4
    polar_p = pin_diameter**4 - pin_bore**4
    length = (
        journal_length
        + CARTER_JOURNAL_WEB * web_thickness
        + CARTER_PIN * pin_length * polar_j / polar_p
        + CARTER_WEB * crank_radius * polar_j / (web_thickness * web_width**3)
    )
    return float(shear_modulus * math.pi * polar_j / (32.0 * length))


@record
class CrankTrain(ResultMixin):
    """Result of :func:`crank_train`: the lumped chain of an engine's crank train.

    Attributes
    ----------
    names : tuple of str
        Name of each mass along the chain (``damper ring``, ``front``, ``throw 1``, ...,
        ``flywheel``, ``load``).
    inertia : ndarray, shape (N,)
        Inertia of each mass [kg m^2].
    stiffness : ndarray, shape (N-1,)
        Stiffness of each section [N m/rad] (section s joins masses s and s+1).
    damping : ndarray, shape (N-1,)
        Viscous damping of each section [N m s/rad].
    throw_index : ndarray of int, shape (T,)
        Index of each throw's mass in the chain.
    front_index : int
        Index of the front mass (pulley and damper hub).
    damper_section : int or None
        Index of the damper's spring section (ring to hub), None without a damper.
    """

    names: tuple[str, ...]
    inertia: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    throw_index: NDArray[np.int64]
    front_index: int
    damper_section: int | None


def crank_train(
    throw_inertia: ArrayLike,
    throw_stiffness: ArrayLike,
    front_inertia: float,
    front_stiffness: float,
    flywheel_inertia: float,
    flywheel_stiffness: float,
    damper_inertia: float | None = None,
    damper_stiffness: float = 0.0,
    damper_damping: float = 0.0,
    load_inertia: float | None = None,
    load_stiffness: float | None = None,
    shaft_damping_ratio: float = 0.0,
    throw_names: tuple[str, ...] | None = None,
) -> CrankTrain:
    r"""The chain of a crank train: damper ring, front, throws, flywheel, load.

    Throw 1 is next to the front end (pulley, damper hub), the last throw next to the
    flywheel. The damper is a ring on a spring and a dashpot to the hub (a tuned rubber
    damper; :math:`k_d = J_d \omega_d^2`, :math:`c_d = 2\zeta_d J_d \omega_d` for a ring
    tuned to :math:`\omega_d` with damping ratio :math:`\zeta_d`; Den Hartog 1956,
    Sec. 3.3). The crank's own damping is stiffness-proportional in each crank section,
    :math:`c_s = 2\zeta k_s/\omega_1` with :math:`\omega_1` the first elastic natural
    frequency of the chain without damper ring and load (so that mode has about the
    damping ratio ζ; a simplification of the cylinder and hysteresis damping of Ker
    Wilson 1956).

    Parameters
    ----------
    throw_inertia : array_like, shape (T,)
        Inertia of each throw with its reciprocating share [kg m^2]
        (:func:`throw_inertias`).
    throw_stiffness : float or array_like, shape (T-1,)
        Stiffness between neighbouring throws [N m/rad].
    front_inertia : float
        Pulley, timing gear and damper hub [kg m^2].
    front_stiffness : float
        Stiffness from the front mass to throw 1 [N m/rad].
    flywheel_inertia : float
        Flywheel (and clutch) [kg m^2].
    flywheel_stiffness : float
        Stiffness from the last throw to the flywheel [N m/rad].
    damper_inertia : float, optional
        Inertia of the damper ring [kg m^2]; none: no damper.
    damper_stiffness : float
        Stiffness of the damper's spring, ring to hub [N m/rad].
    damper_damping : float
        Viscous damping of the damper, ring to hub [N m s/rad].
    load_inertia : float, optional
        Driven load (gearbox input, generator, propeller) [kg m^2]; none: free end.
    load_stiffness : float, optional
        Stiffness of the coupling or shaft from the flywheel to the load [N m/rad];
        needed with ``load_inertia``.
    shaft_damping_ratio : float
        Damping ratio ζ of the crank's own damping [-], from 0 to 0.5.
    throw_names : tuple of str, optional
        Name of each throw mass (:func:`crank_stations`); default ``throw 1``, ...

    Returns
    -------
    CrankTrain
        The chain: inertias [kg m^2], stiffnesses [N m/rad], damping [N m s/rad].
    """
    jt = np.atleast_1d(_positive("throw_inertia", throw_inertia))
    throws = jt.size
    kt = np.broadcast_to(
        np.atleast_1d(_positive("throw_stiffness", throw_stiffness)), (throws - 1,)
    )
    if not 0.0 <= shaft_damping_ratio <= 0.5:
        raise InputError("shaft_damping_ratio", shaft_damping_ratio, "must be from 0 to 0.5")
    names: list[str] = []
    inertia: list[float] = []
    stiffness: list[float] = []
    damping: list[float] = []
    damper_section = None
    if damper_inertia is not None:
        _positive("damper_inertia", damper_inertia)
        _positive("damper_stiffness", damper_stiffness, zero=True)
        _positive("damper_damping", damper_damping, zero=True)
        if damper_stiffness == 0 and damper_damping == 0:
            raise InputError(
                "damper_stiffness", damper_stiffness, "> 0 (or a damping > 0): the ring is loose"
            )
        names.append("damper ring")
        inertia.append(float(damper_inertia))
        stiffness.append(float(damper_stiffness))
        damping.append(float(damper_damping))
        damper_section = 0
    front = len(names)
    names.append("front")
    inertia.append(float(_positive("front_inertia", front_inertia)))
    stiffness.append(float(_positive("front_stiffness", front_stiffness)))
    damping.append(0.0)
    if throw_names is not None and len(throw_names) != throws:
        raise InputError("throw_names", throw_names, f"needs one name per throw mass ({throws})")
    for t in range(throws):
        names.append(f"throw {t + 1}" if throw_names is None else throw_names[t])
        inertia.append(float(jt[t]))
        if t < throws - 1:
            stiffness.append(float(kt[t]))
            damping.append(0.0)
    stiffness.append(float(_positive("flywheel_stiffness", flywheel_stiffness)))
    damping.append(0.0)
    names.append("flywheel")
    inertia.append(float(_positive("flywheel_inertia", flywheel_inertia)))
    if load_inertia is not None:
        if load_stiffness is None:
            raise InputError("load_stiffness", None, "is needed with a load inertia")
        names.append("load")
        inertia.append(float(_positive("load_inertia", load_inertia)))
        stiffness.append(float(_positive("load_stiffness", load_stiffness)))
        damping.append(0.0)
    k = np.array(stiffness)
    c = np.array(damping)
    crank = slice(front, front + throws + 1)  # sections front..flywheel
    if shaft_damping_ratio > 0:
        j_engine = np.array(inertia[front : front + throws + 2])
        omega_1 = natural_modes(j_engine, k[crank]).frequency[1]
        c[crank] = 2.0 * shaft_damping_ratio * k[crank] / omega_1
    return CrankTrain(
        names=tuple(names),
        inertia=np.array(inertia),
        stiffness=k,
        damping=c,
        throw_index=np.arange(front + 1, front + 1 + throws, dtype=np.int64),
        front_index=front,
        damper_section=damper_section,
    )


def order_harmonics(
    angle: ArrayLike, values: ArrayLike, orders: ArrayLike
) -> NDArray[np.complex128]:
    r"""Complex harmonics of a periodic signal sampled evenly over one cycle.

    With the signal :math:`y(\theta) = \bar y + \mathrm{Re}\sum_n Y_n e^{i n\theta}`,
    :math:`Y_n = \frac{2}{S}\sum_s y_s e^{-i n \theta_s}` (a discrete Fourier transform at
    the samples' own angles, so the cycle may start anywhere).

    Parameters
    ----------
    angle : array_like, shape (S,)
        Evenly spaced angles covering one cycle without its end point [rad].
    values : array_like, shape (..., S)
        The signal at those angles [any unit].
    orders : array_like, shape (n,)
        Orders n (per revolution; multiples of 2π/cycle) [-].

    Returns
    -------
    ndarray of complex, shape (..., n)
        :math:`Y_n` [the signal's unit].
    """
    theta = np.asarray(angle, dtype=float)
    n = np.asarray(orders, dtype=float)
    basis = np.exp(-1j * np.outer(theta, n))  # (S, n)
    return np.asarray(np.asarray(values, dtype=float) @ basis * (2.0 / theta.size), dtype=complex)


@record
class EngineExcitation(ResultMixin):
    r"""Result of :func:`engine_excitation`: torque harmonics of every cylinder by order.

    A cylinder's torque at speed ω is :math:`\mathrm{Re}\sum_n (G_n + I_n (\omega /
    \omega_0)^2) e^{i n \theta}`: the gas part does not depend on the speed (a pressure
    given over the crank angle), the inertia part grows with its square.

    Attributes
    ----------
    orders : ndarray, shape (n,)
        Engine orders [-] (multiples of 1/2 for a four-stroke, of 1 for a two-stroke).
    reference_speed : float
        Speed ω0 of the cycle the harmonics come from [rad/s].
    gas : ndarray of complex, shape (C, n)
        Gas-torque harmonics :math:`G_n` of each cylinder [N m].
    inertia : ndarray of complex, shape (C, n)
        Inertia-torque harmonics :math:`I_n` at ω0 [N m].
    cylinder_throw : ndarray of int, shape (C,)
        Throw mass of the chain each cylinder drives (its crank station,
        :func:`crank_stations`: throws in one plane are one mass).
    fire_angle : ndarray, shape (C,)
        Firing crank angle :math:`t_c` of each cylinder [rad]; cylinder c's harmonic is
        the first-firing cylinder's times :math:`e^{-i n (t_c - t_1)}` for equal cylinders.
    mean_torque : float
        Mean torque of the engine at ω0 [N m].
    """

    orders: NDArray[np.float64]
    reference_speed: float
    gas: NDArray[np.complex128] = field(repr=False)
    inertia: NDArray[np.complex128] = field(repr=False)
    cylinder_throw: NDArray[np.int64]
    fire_angle: NDArray[np.float64]
    mean_torque: float

    def throw_torque(self, speed: float) -> NDArray[np.complex128]:
        """Harmonics of the torque on each throw at ``speed``.

        Parameters
        ----------
        speed : float
            Crank speed [rad/s].

        Returns
        -------
        ndarray of complex, shape (T, n)
            Sum over the cylinders on each throw [N m].
        """
        per_cylinder = self.gas + self.inertia * (speed / self.reference_speed) ** 2
        throws = int(np.max(self.cylinder_throw)) + 1
        out = np.zeros((throws, self.orders.size), dtype=complex)
        np.add.at(out, self.cylinder_throw, per_cylinder)
        return out


def engine_orders(strokes: int, highest: float) -> NDArray[np.float64]:
    """The engine orders of a cycle up to ``highest``.

    Parameters
    ----------
    strokes : int
        2 or 4.
    highest : float
        Highest order [-].

    Returns
    -------
    ndarray
        1/2, 1, 3/2, ... (four-stroke) or 1, 2, 3, ... (two-stroke) [-].
    """
    step = 2.0 / strokes
    return np.asarray(step * np.arange(1, int(math.floor(highest / step + 1e-9)) + 1), dtype=float)


def engine_excitation(
    cycle: Any, model: EngineModel, highest_order: float = 12.0
) -> EngineExcitation:
    """Torque harmonics of every cylinder from one whole-engine cycle.

    ``cycle`` is an :class:`~crankbalance.physics.engine_cycle_all.EngineCycleResult`: its
    ``cylinder_gas_torque`` and ``cylinder_inertia_torque`` are already phased by each
    cylinder's firing angle (all over the crank angle of the first throw), so the harmonics
    of engine order n carry the phase :math:`-n t_c` of the firing order without further
    work (:func:`order_harmonics` over the cycle's ``crank_angle``).

    Parameters
    ----------
    cycle : EngineCycleResult
        One working cycle of all cylinders at one speed.
    model : EngineModel
        The same engine (which throw each cylinder drives).
    highest_order : float
        Highest engine order [-].

    Returns
    -------
    EngineExcitation
        Gas and inertia harmonics [N m] per cylinder and order.
    """
    if not 0.5 <= highest_order <= 64:
        raise InputError("highest_order", highest_order, "must be from 0.5 to 64")
    orders = engine_orders(int(cycle.strokes), highest_order)
    theta = np.asarray(cycle.crank_angle, dtype=float)
    return EngineExcitation(
        orders=orders,
        reference_speed=float(cycle.speed_mean),
        gas=order_harmonics(theta, cycle.cylinder_gas_torque, orders),
        inertia=order_harmonics(theta, cycle.cylinder_inertia_torque, orders),
        cylinder_throw=crank_stations(model)[0][np.asarray(model.cylinder_throw, dtype=int)],
        fire_angle=np.asarray(cycle.fire_angle, dtype=float),
        mean_torque=float(cycle.mean_torque),
    )


@record
class ForcedResponse(ResultMixin):
    r"""Result of :func:`forced_response`: steady state, order by order, over speed.

    Attributes
    ----------
    speed : ndarray, shape (P,)
        Crank speeds [rad/s].
    orders : ndarray, shape (n,)
        Engine orders [-].
    amplitude : ndarray of complex, shape (P, n, N)
        Twist of every mass per order [rad] (:math:`\mathrm{Re}(X e^{i n\theta})`).
    section_torque : ndarray of complex, shape (P, n, N-1)
        Torque in every section per order, :math:`(k_s + i n\omega c_s)(X_s - X_{s+1})`
        [N m].
    amplitude_peak : ndarray, shape (P, N)
        Synthesised amplitude of each mass: the largest magnitude over a cycle of the sum
        of all orders with their phases, :math:`\max_\theta|\mathrm{Re}\sum_n X_n
        e^{in\theta}|` [rad].
    torque_peak : ndarray, shape (P, N-1)
        Synthesised vibratory torque of each section, likewise [N m].
    damper_power : ndarray, shape (P,)
        Mean power dissipated in the damper section, summed over the orders [W]; zeros
        without a damper.
    total_dissipated_power : ndarray, shape (P,)
        Mean power dissipated by all damping, summed over the orders [W].
    input_power : ndarray, shape (P,)
        Mean power the excitation puts in, :math:`\sum_n \tfrac12\mathrm{Re}(F^H\,i\Omega X)`
        [W]; equals ``total_dissipated_power`` (the energy balance).
    """

    speed: NDArray[np.float64]
    orders: NDArray[np.float64]
    amplitude: NDArray[np.complex128] = field(repr=False)
    section_torque: NDArray[np.complex128] = field(repr=False)
    amplitude_peak: NDArray[np.float64] = field(repr=False)
    torque_peak: NDArray[np.float64] = field(repr=False)
    damper_power: NDArray[np.float64] = field(repr=False)
    total_dissipated_power: NDArray[np.float64] = field(repr=False)
    input_power: NDArray[np.float64] = field(repr=False)


def forced_response(
    train: CrankTrain,
    excitation: EngineExcitation,
    speed: ArrayLike,
) -> ForcedResponse:
    r"""Steady-state torsional response to the engine orders over a range of speeds.

    At speed ω each order n drives the chain at :math:`\Omega = n\omega` with the torques
    :math:`F_t` of :meth:`EngineExcitation.throw_torque` on the throws:

    .. math::
        (K - \Omega^2 M + i\Omega C)\,X = F

    Parameters
    ----------
    train : CrankTrain
        The chain.
    excitation : EngineExcitation
        Torque harmonics of the cylinders.
    speed : array_like, shape (P,)
        Crank speeds [rad/s].

    Returns
    -------
    ForcedResponse
        Amplitudes [rad], section torques [N m], powers [W].
    """
    omega = np.atleast_1d(_positive("speed", speed))
    m, k, c = chain_matrices(train.inertia, train.stiffness, train.damping)
    n_mass, orders = train.inertia.size, excitation.orders
    amplitude = np.zeros((omega.size, orders.size, n_mass), dtype=complex)
    dissipated = np.zeros((omega.size, n_mass - 1))  # per section, summed over the orders
    input_power = np.zeros(omega.size)
    # one speed at a time: only the amplitudes of the result are kept for all speeds
    for p, w in enumerate(omega):
        force = np.zeros((orders.size, n_mass), dtype=complex)
        force[:, train.throw_index] = excitation.throw_torque(float(w)).T
        big_omega = orders * w
        system = (
            k[None, :, :]
            - big_omega[:, None, None] ** 2 * m[None]
            + 1j * big_omega[:, None, None] * c
        )
        x = np.linalg.solve(system, force[:, :, None])[:, :, 0]  # (n, N)
        amplitude[p] = x
        dissipated[p] = (
            0.5 * big_omega[:, None] ** 2 * train.damping * np.abs(x[:, :-1] - x[:, 1:]) ** 2
        ).sum(axis=0)
        velocity = 1j * big_omega[:, None] * x
        input_power[p] = 0.5 * float(np.real(np.sum(np.conj(force) * velocity)))
    twist = amplitude[..., :-1] - amplitude[..., 1:]
    big = orders[None, :] * omega[:, None]  # (P, n)
    section_torque = (train.stiffness + 1j * big[..., None] * train.damping) * twist
    damper_power = (
        dissipated[:, train.damper_section]
        if train.damper_section is not None
        else np.zeros(omega.size)
    )
    return ForcedResponse(
        speed=omega,
        orders=orders,
        amplitude=amplitude,
        section_torque=section_torque,
        amplitude_peak=synthesised_peak(amplitude, orders),
        torque_peak=synthesised_peak(section_torque, orders),
        damper_power=damper_power,
        total_dissipated_power=dissipated.sum(axis=1),
        input_power=input_power,
    )


def synthesised_peak(harmonics: ArrayLike, orders: ArrayLike) -> NDArray[np.float64]:
    r"""Largest magnitude over one cycle of a signal given by its order harmonics.

    :math:`\max_\theta \big|\mathrm{Re}\sum_n X_n e^{i n \theta}\big|`, sampled at 16
    points per period of the highest order over the period of the lowest order step. With
    the orders :math:`n = k\,n_1` (whole :math:`k`) and :math:`S` samples
    :math:`\theta_j = 2\pi j / (S n_1)`, the signal at the samples is the inverse real
    discrete Fourier transform of the harmonics placed at the bins :math:`k`
    (``numpy.fft.irfft``: :math:`S \log S` operations per curve instead of :math:`S` times
    the number of orders).

    Parameters
    ----------
    harmonics : array_like of complex, shape (P, n, ...)
        Harmonics :math:`X_n` on axis 1 [any unit].
    orders : array_like, shape (n,)
        Their orders [-], whole multiples of the smallest.

    Returns
    -------
    ndarray, shape (P, ...)
        The peak [the harmonics' unit].
    """
    n = np.asarray(orders, dtype=float)
    x = np.moveaxis(np.asarray(harmonics, dtype=complex), 1, -1)  # (P, ..., n)
    step = float(n.min())
    bins = np.rint(n / step).astype(np.int64)
    if not (step > 0 and np.allclose(bins * step, n, rtol=1e-9, atol=0.0)):
        raise InputError("orders", n.tolist(), "must be whole multiples of the smallest, > 0")
    samples = int(math.ceil(16 * n.max() / step))
    out = np.empty(x.shape[:-1])
    spectrum = np.zeros((*x.shape[1:-1], samples // 2 + 1), dtype=complex)
    for p in range(x.shape[0]):  # one speed at a time: (..., samples) stays small
        spectrum[..., bins] = x[p]
        # irfft gives (1/S) (X_0 + 2 Re sum_k X_k e^{2 pi i k j / S}) for 0 < k < S/2
        out[p] = np.abs(np.fft.irfft(spectrum, n=samples, axis=-1)).max(axis=-1) * (samples / 2)
    return out


def critical_speeds(
    frequency: ArrayLike, orders: ArrayLike, low: float, high: float
) -> list[tuple[int, float, float]]:
    r"""Where an engine order meets a natural frequency: :math:`\omega = \omega_m / n`.

    Parameters
    ----------
    frequency : array_like, shape (N,)
        Natural angular frequencies [rad/s]; zeros (rigid modes) are skipped.
    orders : array_like, shape (n,)
        Engine orders [-].
    low, high : float
        Speed range [rad/s].

    Returns
    -------
    list of (int, float, float)
        (mode index, order [-], crank speed [rad/s]) in the range, by speed.
    """
    found = []
    for mode, w in enumerate(np.asarray(frequency, dtype=float)):
        if w <= 0:
            continue
        for n in np.asarray(orders, dtype=float):
            speed = w / n
            if low <= speed <= high:
                found.append((mode, float(n), float(speed)))
    return sorted(found, key=lambda item: item[2])


def order_vector_sum(
    fire_angle: ArrayLike, orders: ArrayLike, weight: ArrayLike | None = None
) -> NDArray[np.float64]:
    r"""Relative amplitude of each engine order: the phase diagram's vector sum.

    :math:`\big|\sum_c \beta_c e^{-i n t_c}\big|` with the firing angles :math:`t_c` and
    the weights :math:`\beta_c` (a mode shape at each cylinder's throw; default 1): how
    strongly equal cylinders excite that mode at order n (Den Hartog 1956, Sec. 5.5; Ker
    Wilson 1956). Orders with all cylinders in phase (sum of the weights) are the *major*
    orders.

    Parameters
    ----------
    fire_angle : array_like, shape (C,)
        Firing crank angle of each cylinder [rad].
    orders : array_like, shape (n,)
        Engine orders [-].
    weight : array_like, shape (C,), optional
        Mode-shape amplitude at each cylinder [-].

    Returns
    -------
    ndarray, shape (n,)
        Magnitude of the vector sum [-] (in units of one cylinder's harmonic).
    """
    t = np.asarray(fire_angle, dtype=float)
    beta = np.ones_like(t) if weight is None else np.asarray(weight, dtype=float)
    n = np.asarray(orders, dtype=float)
    return np.abs(np.exp(-1j * np.outer(n, t)) @ beta)


@record
class ResonanceCheck(ResultMixin):
    """One crossing of an engine order with a natural frequency, and the response there.

    Attributes
    ----------
    mode : int
        Mode index (1: the first elastic mode).
    order : float
        Engine order [-].
    speed : float
        Crank speed of the crossing [rad/s].
    relative_excitation : float
        Vector sum of the order over the cylinders weighted by the mode shape at their
        throws (:func:`order_vector_sum`) [-].
    front_amplitude : float
        Front end's synthesised amplitude (all orders) [rad].
    crank_twist : float
        Synthesised twist front end to flywheel [rad].
    max_section_torque : float
        Largest synthesised vibratory torque of a section [N m].
    damper_power : float
        Power the damper dissipates, summed over the orders [W].
    """

    mode: int
    order: float
    speed: float
    relative_excitation: float
    front_amplitude: float
    crank_twist: float
    max_section_torque: float
    damper_power: float


@record
class TorsionalStudy(ResultMixin):
    """Result of :func:`torsional_study`: the torsional model of an engine's crank train.

    Attributes
    ----------
    train : CrankTrain
        The chain with the load when one is given.
    modes : TorsionalModes
        Natural modes of ``train``.
    modes_free : TorsionalModes
        Natural modes of the chain without the load (free-free engine); the same as
        ``modes`` without a load.
    excitation : EngineExcitation
        Torque harmonics of the cylinders.
    response : ForcedResponse
        The sweep over the speed range.
    resonances : tuple of ResonanceCheck
        Every crossing of an order with an elastic mode in the speed range, by speed.
    front_amplitude : ndarray, shape (P,)
        Front end's synthesised amplitude over the sweep (all orders) [rad].
    crank_twist : ndarray, shape (P,)
        Synthesised twist front end to flywheel over the sweep [rad].
    damper_allowed_power : float or None
        Power the damper may dissipate [W], None when not given.
    """

    train: CrankTrain
    modes: TorsionalModes
    modes_free: TorsionalModes
    excitation: EngineExcitation
    response: ForcedResponse = field(repr=False)
    resonances: tuple[ResonanceCheck, ...]
    front_amplitude: NDArray[np.float64] = field(repr=False)
    crank_twist: NDArray[np.float64] = field(repr=False)
    damper_allowed_power: float | None = None

    @property
    def damper_max_power(self) -> float:
        """Largest damper power over the sweep and the resonances [W]."""
        at = [r.damper_power for r in self.resonances]
        return float(max([float(self.response.damper_power.max()), *at]))


def _summaries(
    train: CrankTrain, response: ForcedResponse
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    flywheel = train.throw_index[-1] + 1
    twist = response.amplitude[..., train.front_index] - response.amplitude[..., flywheel]
    return response.amplitude_peak[:, train.front_index], synthesised_peak(twist, response.orders)


#: most complex amplitudes one :func:`torsional_study` computes: the speeds of the sweep
#: and of the resonances in the speed range, times the engine orders, times the masses of
#: the chain (:func:`response_size`). Time and memory grow with it: at the cap a 64-throw
#: chain takes about 6 s of one loaded core and 300 MB, an inline-6 about 2 s
#: (docs/torsional.md, "Bounds").
MAX_RESPONSE_SIZE = 4_000_000


def response_size(train: CrankTrain, orders: ArrayLike, speed: ArrayLike) -> tuple[int, int]:
    """The work of :func:`torsional_study`, counted before it is done.

    Parameters
    ----------
    train : CrankTrain
        The chain.
    orders : array_like, shape (n,)
        Engine orders [-].
    speed : array_like, shape (P,)
        Crank speeds of the sweep [rad/s].

    Returns
    -------
    resonances : int
        Crossings of an order with an elastic mode in the speed range (:func:`critical_speeds`):
        each one more speed of response.
    size : int
        Complex amplitudes the sweep and the resonances compute,
        ``(P + resonances) * n * N`` [-]; at most :data:`MAX_RESPONSE_SIZE`.
    """
    omega = np.atleast_1d(_positive("speed", speed))
    n = np.atleast_1d(np.asarray(orders, dtype=float))
    modes = natural_modes(train.inertia, train.stiffness)
    crossings = critical_speeds(modes.frequency, n, float(omega.min()), float(omega.max()))
    return len(crossings), (omega.size + len(crossings)) * n.size * train.inertia.size


def torsional_study(
    train: CrankTrain,
    excitation: EngineExcitation,
    speed: ArrayLike,
    damper_allowed_power: float | None = None,
) -> TorsionalStudy:
    """Natural modes, forced response over ``speed``, resonances and the damper check.

    Parameters
    ----------
    train : CrankTrain
        The chain (:func:`crank_train`).
    excitation : EngineExcitation
        Torque harmonics of the cylinders (:func:`engine_excitation`).
    speed : array_like, shape (P,)
        Crank speeds of the sweep, ascending [rad/s].
    damper_allowed_power : float, optional
        Power the damper may dissipate [W].

    Returns
    -------
    TorsionalStudy
        Modes, sweep, resonances [rad/s, rad, N m, W].
    """
    omega = np.atleast_1d(_positive("speed", speed))
    resonances, size = response_size(train, excitation.orders, omega)
    if size > MAX_RESPONSE_SIZE:
        raise InputError(
            "speed",
            f"{omega.size} speeds and {resonances} resonances x {excitation.orders.size} "
            f"orders x {train.inertia.size} masses = {size} amplitudes",
            f"must make at most {MAX_RESPONSE_SIZE} amplitudes: fewer speeds, fewer orders "
            "or a narrower speed range",
        )
    modes = natural_modes(train.inertia, train.stiffness)
    with_load = "load" in train.names
    modes_free = natural_modes(train.inertia[:-1], train.stiffness[:-1]) if with_load else modes
    response = forced_response(train, excitation, omega)
    front, twist = _summaries(train, response)
    crossings = critical_speeds(
        modes.frequency, excitation.orders, float(omega.min()), float(omega.max())
    )
    checks = []
    if crossings:
        at = forced_response(train, excitation, [s for _m, _n, s in crossings])
        front_at, twist_at = _summaries(train, at)
        throw_of_cylinder = train.throw_index[excitation.cylinder_throw]
        for i, (mode, order, speed_i) in enumerate(crossings):
            weight = modes.mode_shape[throw_of_cylinder, mode]
            checks.append(
                ResonanceCheck(
                    mode=mode,
                    order=order,
                    speed=speed_i,
                    relative_excitation=float(
                        order_vector_sum(excitation.fire_angle, [order], weight)[0]
                    ),
                    front_amplitude=float(front_at[i]),
                    crank_twist=float(twist_at[i]),
                    max_section_torque=float(at.torque_peak[i].max()),
                    damper_power=float(at.damper_power[i]),
                )
            )
    if damper_allowed_power is not None:
        _positive("damper_allowed_power", damper_allowed_power)
    return TorsionalStudy(
        train=train,
        modes=modes,
        modes_free=modes_free,
        excitation=excitation,
        response=response,
        resonances=tuple(checks),
        front_amplitude=front,
        crank_twist=twist,
        damper_allowed_power=damper_allowed_power,
    )
