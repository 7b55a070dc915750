r"""Free forces and moments of any engine, by order, as rotating phasors and as curves.

Vectors across the crank axis are complex numbers :math:`z + i\,x` (z: cylinder axis of
an in-line engine, x: across), so a direction at angle :math:`\theta` from z toward x is
:math:`e^{i\theta}` and the crank turns in the positive sense. The order-n part of a
force is

.. math:: F_n(\theta) = F_n^{+} e^{in\theta} + F_n^{-} e^{-in\theta}

with a forward (co-rotating) and a backward (counter-rotating) phasor. Its largest
magnitude over a revolution is :math:`|F_n^+| + |F_n^-|`. Moments are taken about the
moment reference point (the crankshaft mid-point unless the engine file moves it); the
*couple* :math:`C = \sum y\,F` carries the same phasors weighted by the axial position y,
and the moment vector across the crank axis is :math:`M = iC` (:math:`M_x = y F_z`,
:math:`M_z = -y F_x`). The sixth component, the *roll moment* :math:`M_y` about the crank
axis (:mod:`crankbalance.physics.roll`), is a real curve of each order,
:math:`M_{y,n} = \mathrm{Re}(R_n e^{in\theta})`; about a reference point off the crank
axis at :math:`(p_x, p_y, p_z)` it gains :math:`p_x F_z - p_z F_x`, which is
:math:`R_n \mathrel{+}= qF_n^+ + \overline{qF_n^-}` with :math:`q = p_x + ip_z`.

For cylinder c (throw angle :math:`\varphi_c`, bank angle :math:`\beta_c`, reciprocating
mass :math:`m_c`) with the normalised inertia harmonics :math:`c_n = a_n - i b_n`
(:mod:`crankbalance.physics.kinematics`) and :math:`P_c = m_c r\omega^2`:

.. math::
    F_n^{+} = \sum_c \tfrac{P_c}{2}\,c_n\,e^{i[n(\varphi_c-\beta_c)+\beta_c]},\qquad
    F_n^{-} = \sum_c \tfrac{P_c}{2}\,\bar c_n\,e^{i[-n(\varphi_c-\beta_c)+\beta_c]}

The rotating masses give a forward first-order phasor only:
:math:`F_{rot} = \sum_t m_t r\omega^2 e^{i\varphi_t}`.

These are the forces the crank train exerts on the engine block (inertia forces).

Why one module over 800 lines: the phasors of one engine and of a batch, their amplitudes
and their curves are one computation, the sums over the cylinders (:func:`_cylinder_sums`),
which the articulated rods enter through the same coefficients.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError
from ..records import record
from ..results import ResultMixin
from .kinematics import (
    CHUNK,
    KinematicsModel,
    cached_exact_coefficients,
    harmonic_coefficients,
    piston_acceleration,
    piston_velocity,
)
from .model import EngineBatch, EngineModel
from .roll import articulated_roll, articulated_roll_curve, roll_coefficients, roll_harmonics

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import ArrayLike, NDArray


@record
class FreeForces(ResultMixin):
    r"""Free forces and moments of one engine by order (phasors at crank angle 0).

    Forces in N, couples in N·m, complex as :math:`z + i x` (see module docstring).
    ``force_forward[k]`` belongs to ``orders[k]``.

    Parameters
    ----------
    orders : ndarray of int, shape (K,)
        Harmonic orders 1..K of the reciprocating forces.
    force_forward, force_backward : ndarray of complex, shape (K,)
        Forward (co-rotating) and backward (counter-rotating) phasors :math:`F_n^{\pm}` of
        the reciprocating inertia force, summed over the cylinders [N].
    couple_forward, couple_backward : ndarray of complex, shape (K,)
        The same phasors weighted by the axial position, :math:`C_n^{\pm} = \sum y F`,
        about the crankshaft mid-point [N·m]; the moment vector is :math:`M = iC`.
    rotating_force : complex
        First-order forward phasor of the rotating masses [N].
    rotating_couple : complex
        Its couple about the moment reference point [N·m].
    roll : ndarray of complex, shape (K,)
        :math:`R_n`, the roll moment of each order about the axis through the moment
        reference point parallel to the crank, :math:`M_{y,n} = \mathrm{Re}(R_n
        e^{in\theta})`: the reaction of the reciprocating inertia torque, the moment of
        the offset cylinders' inertia forces, and of every force about a reference point
        off the crank axis [N·m].
    rotating_roll : complex
        The rotating masses' first-order roll moment about that axis, :math:`qF_{rot}`
        (zero about the crank axis itself) [N·m].

    References
    ----------
    The phasor form of the matrix formulation of Appl. Sci. 2021; closed forms of the
    free forces and moments in Den Hartog (1956) ch. 5 and Taylor (1985) ch. 8.
    """

    orders: NDArray[np.int64]
    force_forward: NDArray[np.complex128]
    force_backward: NDArray[np.complex128]
    couple_forward: NDArray[np.complex128]
    couple_backward: NDArray[np.complex128]
    rotating_force: complex
    rotating_couple: complex
    roll: NDArray[np.complex128]
    rotating_roll: complex

    @property
    def force_amplitude(self) -> NDArray[np.float64]:
        """Largest magnitude of each order's force over a revolution [N]."""
        return np.abs(self.force_forward) + np.abs(self.force_backward)

    @property
    def moment_amplitude(self) -> NDArray[np.float64]:
        """Largest magnitude of each order's moment over a revolution [N·m]."""
        return np.abs(self.couple_forward) + np.abs(self.couple_backward)

    @property
    def roll_amplitude(self) -> NDArray[np.float64]:
        """Largest roll moment of each order over a revolution, :math:`|R_n|` [N·m]."""
        return np.abs(self.roll)

    def order(self, n: int) -> int:
        """Index of order ``n`` in the arrays."""
        found = np.flatnonzero(self.orders == n)
        if not found.size:
            raise KeyError(f"order {n} not computed (orders {self.orders.tolist()})")
        return int(found[0])


def free_forces(
    model: EngineModel, orders: int = 8, kinematics: KinematicsModel | None = None
) -> FreeForces:
    """Free forces and moments of an engine, orders 1..``orders``, and of its rotating masses.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    orders : int
        Highest harmonic order.
    kinematics : {"exact", "series", "first-order"}, optional
        Overrides ``model.kinematics``.

    Returns
    -------
    FreeForces
        Phasors of the reciprocating forces [N] and couples [N·m] by order, and of the
        rotating masses.

    References
    ----------
    Appl. Sci. 2021 (matrix formulation of the free forces and moments, any number of
    cranks, in-line and V); Den Hartog (1956) ch. 5.
    """
    coeff = cylinder_coefficients(model, orders, kinematics)
    p, theta, weights = _model_weights(model)
    fwd, bwd, cfwd, cbwd = _phasors(
        _cylinder_sums(
            p,
            theta,
            model.cylinder_bank,
            model.cylinder_position,
            orders,
            coeff,
            per_cylinder=True,
            weights=weights,
        )
    )
    if model.articulation is not None:
        link = _link_pin_phasors(model, orders)
        fwd, bwd, cfwd, cbwd = fwd + link[0], bwd + link[1], cfwd + link[2], cbwd + link[3]
    rotating = model.derived.get(("rotating_phasors",))  # of the model alone: kept by it
    if rotating is None:
        rotating = model.derived[("rotating_phasors",)] = rotating_phasors(
            model.throw_rotating_mass,
            model.throw_rotating_moment,
            model.throw_angle,
            model.crank_radius,
            model.speed,
        )
    rotating_force, rotating_couple = rotating
    q = complex(model.reference_x, model.reference_z)
    roll = roll_phasors(model, orders, kinematics) + q * fwd + np.conj(q * bwd)
    return FreeForces(
        orders=np.arange(1, orders + 1),
        force_forward=fwd,
        force_backward=bwd,
        couple_forward=cfwd,
        couple_backward=cbwd,
        rotating_force=complex(rotating_force),
        rotating_couple=complex(rotating_couple),
        roll=roll,
        rotating_roll=complex(q * rotating_force),
    )


def _model_weights(model: EngineModel) -> tuple[NDArray, NDArray, NDArray[np.complex128]]:
    r"""The arguments of :func:`_cylinder_sums` that :func:`free_forces` takes from ``model``
    alone: :math:`p_c = \tfrac{1}{2} m_c r\omega^2`, :math:`\theta_c = \varphi_c -
    \beta_c` and the weights of :func:`_sum_weights`, computed once per model and kept by
    it (:attr:`~crankbalance.physics.model.EngineModel.derived`, read-only)."""
    found = model.derived.get(("free_forces.weights",))
    if found is None:
        accel = model.crank_radius * model.speed**2  # r w^2 [m/s^2]
        p = 0.5 * accel * model.reciprocating_mass
        theta = model.cylinder_angle - model.cylinder_bank
        weights = _sum_weights(p, model.cylinder_bank, model.cylinder_position)
        for kept in (p, theta, weights):  # new arrays
            kept.flags.writeable = False
        found = model.derived[("free_forces.weights",)] = (p, theta, weights)
    return found


def roll_phasors(
    model: EngineModel, orders: int = 8, kinematics: KinematicsModel | None = None
) -> NDArray[np.complex128]:
    r"""Roll moment of each order about the crank axis, :math:`R_n` (module docstring).

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    orders : int
        Highest harmonic order K.
    kinematics : {"exact", "series", "first-order"}, optional
        Overrides ``model.kinematics``.

    Returns
    -------
    ndarray of complex, shape (K,)
        :math:`R_n = r^2\omega^2 \sum_c m_c d_{n,c} e^{in(\varphi_c - \beta_c)}` with
        each cylinder's harmonics :math:`d_{n,c}`
        (:func:`crankbalance.physics.roll.roll_coefficients`); with master-and-link rods
        the assembly's exact roll (:func:`crankbalance.physics.roll.articulated_roll`)
        [N·m]. The rows :math:`d_{n,c}` and the weights are computed once per model and
        kept by it (:attr:`~crankbalance.physics.model.EngineModel.derived`, read-only).

    References
    ----------
    The inertia torque of the slider-crank, Taylor (1985) ch. 8; Den Hartog (1956) ch. 5.
    """
    mode = kinematics or model.kinematics
    rods = model.articulated_rods
    if rods is not None:
        _exact_only(mode)
        phi, _y = _single_throw(model)
        harm = articulated_roll(
            rods, model.reciprocating_mass, model.cylinder_rotating_mass, orders, model.speed
        )
        return np.asarray(harm * np.exp(1j * np.arange(1, orders + 1) * phi), dtype=complex)
    key = ("roll_rows", orders, mode)
    found = model.derived.get(key)  # the model is frozen: its rows and weights are kept
    if found is None:
        rows = roll_rows(
            np.array([model.rod_ratio]),
            (model.cylinder_offset / model.crank_radius)[None],
            orders,
            mode,
        )
        angle = (model.cylinder_angle - model.cylinder_bank)[None]
        scale = (
            np.asarray(model.reciprocating_mass[None], dtype=float)
            * ((np.array([model.crank_radius]) * np.array([model.speed])) ** 2)[:, None]
        )
        for kept in (rows, angle, scale):  # new arrays, or the cache's read-only row
            kept.flags.writeable = False
        found = model.derived[key] = (rows, angle, scale)
    rows, angle, scale = found
    return _roll_sum(rows, angle, scale, orders)[0]


def batch_roll_phasors(
    rod_ratio: NDArray[np.float64],
    offset_ratio: NDArray[np.float64],
    mass: NDArray[np.float64],
    angle: NDArray[np.float64],
    crank_radius: NDArray[np.float64],
    speed: NDArray[np.float64],
    orders: int,
    kinematics: KinematicsModel,
) -> NDArray[np.complex128]:
    r"""Roll moment of each order about the crank axis of many engines, :math:`R_n`: the
    equations of :func:`roll_phasors` with an engine axis (one engine is a batch of one).

    Parameters
    ----------
    rod_ratio : ndarray, shape (E,)
        :math:`\lambda = r/l` of each engine [-].
    offset_ratio : ndarray, shape (E, C)
        Each cylinder's offset over the crank radius, :math:`e/r` [-].
    mass : ndarray, shape (E, C)
        Reciprocating mass of each cylinder [kg].
    angle : ndarray, shape (E, C)
        Each cylinder's throw angle less its bank angle, :math:`\varphi_c - \beta_c` [rad].
    crank_radius, speed : ndarray, shape (E,)
        Crank radius [m] and crank speed [rad/s].
    orders : int
        Highest harmonic order K.
    kinematics : {"exact", "series", "first-order"}
        Piston kinematics model.

    Returns
    -------
    ndarray of complex, shape (E, K)
        :math:`R_n = r^2\omega^2 \sum_c m_c d_{n,c} e^{in(\varphi_c - \beta_c)}` of every
        engine, each engine's from its own row (no sum across the engines) [N·m].
    """
    ratio = np.broadcast_to(np.asarray(offset_ratio, dtype=float), np.shape(mass))
    rows = roll_rows(rod_ratio, ratio, orders, kinematics)
    scale = np.asarray(mass, dtype=float) * ((crank_radius * speed) ** 2)[:, None]
    return _roll_sum(rows, np.asarray(angle, dtype=float), scale, orders)


def roll_rows(
    rod_ratio: NDArray[np.float64],
    offset_ratio: NDArray[np.float64],
    orders: int,
    kinematics: KinematicsModel,
) -> NDArray[np.complex128]:
    r"""Roll harmonics :math:`d_{n,c}` of each cylinder of many engines
    (:func:`crankbalance.physics.roll.roll_coefficients`), the rows of
    :func:`batch_roll_phasors`.

    Parameters
    ----------
    rod_ratio : ndarray, shape (E,)
        :math:`\lambda = r/l` of each engine [-].
    offset_ratio : ndarray, shape (E, C)
        Each cylinder's offset over the crank radius, :math:`e/r` [-].
    orders : int
        Highest harmonic order K.
    kinematics : {"exact", "series", "first-order"}
        Piston kinematics model.

    Returns
    -------
    ndarray of complex, shape (K,), (E, 1, K) or (E, C, K)
        One row for all when every engine and cylinder shares its rod ratio and offset
        (read-only, from the cache); one row per engine when its cylinders share one
        offset; else each cylinder's row, each distinct pair of rod ratio and offset
        computed once (all rows by one transform) [-].
    """
    ratio = np.asarray(offset_ratio, dtype=float)
    lam = np.broadcast_to(np.asarray(rod_ratio, dtype=float)[:, None], ratio.shape)
    if np.all(lam == lam.flat[0]) and np.all(ratio == ratio.flat[0]):  # one row for all
        return roll_coefficients(float(lam.flat[0]), float(ratio.flat[0]), orders, kinematics)
    if np.all(ratio == ratio[:, :1]):  # one offset per engine: one row per engine
        return roll_harmonics(lam[:, 0], ratio[:, 0], orders, kinematics)[:, None, :]
    # each distinct (rod ratio, offset) once
    pairs = np.stack([lam.reshape(-1), ratio.reshape(-1)], axis=-1)
    shared, index = np.unique(pairs, axis=0, return_inverse=True)
    rows = roll_harmonics(shared[:, 0], shared[:, 1], orders, kinematics)
    return rows[index.reshape(-1)].reshape(*ratio.shape, orders)


def _roll_sum(
    rows: NDArray[np.complex128],
    angle: NDArray[np.float64],
    scale: NDArray[np.float64],
    orders: int,
) -> NDArray[np.complex128]:
    r""":math:`R_n = \sum_c s_c d_{n,c} e^{in\theta_c}` of each engine (shape (E, K)) from
    the rows of :func:`roll_rows`, the angles (E, C) and the weights :math:`s_c = m_c
    r^2\omega^2` (E, C)."""
    turn = _powers(angle, orders)
    return np.asarray(np.einsum("ec,eck->ek", scale, rows * turn), dtype=complex)


def cylinder_coefficients(
    model: EngineModel, orders: int = 8, kinematics: KinematicsModel | None = None
) -> NDArray[np.complex128]:
    r"""Harmonic coefficients :math:`c_{n,c}` of each cylinder's normalised piston inertia.

    Row c belongs to cylinder c (its own offset ``model.cylinder_offset[c]``); the phasor
    sums of :func:`free_forces` weight each cylinder by its own row. This is the one place
    the per-cylinder kinematics enters the free forces. With master-and-link rods
    (``model.articulation``) the rows are those of the exact articulated piston motion
    (:func:`crankbalance.physics.articulated.cylinder_coefficients`; exact kinematics only).

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    orders : int
        Highest harmonic order K.
    kinematics : {"exact", "series", "first-order"}, optional
        Overrides ``model.kinematics``.

    Returns
    -------
    ndarray of complex, shape (C, K) or (1, K)
        :math:`c_n = a_n - i b_n` of orders 1..K of each cylinder
        (:func:`crankbalance.physics.kinematics.harmonic_coefficients`), one row for all
        when the cylinders share one offset; read-only, kept by the model for the next
        call (:attr:`~crankbalance.physics.model.EngineModel.derived`) [-].
    """
    mode = kinematics or model.kinematics
    key = ("cylinder_coefficients", orders, mode)
    rows = model.derived.get(key)  # the model is frozen: its rows are computed once
    if rows is None:
        if model.articulation is not None:
            rows = _articulated_rows(model, orders, mode)
        else:
            rows = coefficient_rows(
                model.rod_ratio, model.cylinder_offset / model.crank_radius, orders, mode
            )
        if rows.flags.writeable:
            rows = rows.copy() if rows.base is not None else rows
            rows.flags.writeable = False
        model.derived[key] = rows
    return rows


def coefficient_rows(
    rod_ratio: ArrayLike, offset_ratio: ArrayLike, orders: int, kinematics: str
) -> NDArray[np.complex128]:
    r"""Harmonic coefficients :math:`c_{n,c}` of the cylinders of one engine or of a batch.

    The kinematics of the free forces of a model (:func:`cylinder_coefficients`) and of a
    batch (:func:`batch_free_forces`). Engines sharing their rod ratio and offsets share
    one set of rows (each distinct offset once, exact ones from their cache); an engine
    whose cylinders share one offset has one row for all (a cylinder axis of 1).

    Parameters
    ----------
    rod_ratio : array_like, shape () or (E,)
        :math:`\lambda = r/l` [-] of the engine or of each engine.
    offset_ratio : array_like, shape (C,) or (E, C)
        Each cylinder's offset over the crank radius, :math:`e/r` [-].
    orders : int
        Highest harmonic order K.
    kinematics : {"exact", "series", "first-order"}
        Piston kinematics model (:func:`crankbalance.physics.kinematics.harmonic_coefficients`).

    Returns
    -------
    ndarray of complex, shape (C, K), (1, K), (E, 1, K) or (E, C, K)
        :math:`c_n = a_n - i b_n` of orders 1..K, broadcasting over the cylinders (and the
        engines) of the arguments; a cylinder axis of 1 when the cylinders share one row
        (read-only then, from the cache) [-].
    """
    lam = np.asarray(rod_ratio, dtype=float)
    ratio = np.asarray(offset_ratio, dtype=float)
    first = ratio.reshape(-1, ratio.shape[-1])[0]
    if np.all(lam == lam.flat[0]) and np.all(ratio == first):  # one set of rows for all
        lam0 = float(lam.flat[0])

        def row(e: float) -> NDArray[np.complex128]:
            if kinematics == "exact":
                return cached_exact_coefficients(lam0, e, orders)
            return harmonic_coefficients(lam0, orders, e, kinematics)  # type: ignore[arg-type]

        if np.all(first == first[0]):  # one offset: one row for every cylinder (read-only)
            return row(float(first[0]))[None, :]
        shared, index = np.unique(first, return_inverse=True)
        rows = np.asarray([row(float(e)) for e in shared], dtype=complex)
        return rows.reshape(shared.size, orders)[index.reshape(-1)]
    if np.all(ratio == ratio[..., :1]):  # one offset per engine: one row per engine
        return harmonic_coefficients(lam, orders, ratio[..., 0], kinematics)[..., None, :]  # type: ignore[arg-type]
    return harmonic_coefficients(lam[..., None], orders, ratio, kinematics)  # type: ignore[arg-type]


def rotating_phasors(
    mass: ArrayLike,
    moment: ArrayLike,
    throw_angle: ArrayLike,
    crank_radius: ArrayLike,
    speed: ArrayLike,
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    r"""First-order phasors of force and couple of the rotating masses, one engine or many.

    .. math:: F_{rot} = r\omega^2 \sum_t m_t e^{i\varphi_t},\qquad
              C_{rot} = r\omega^2 \sum_t (m_t y_t + \textstyle\sum_c m_{b,c} a_c)
              e^{i\varphi_t}

    (the big ends of side-by-side rods at their own axial places,
    :attr:`~crankbalance.physics.model.EngineModel.throw_rotating_moment`).

    Parameters
    ----------
    mass : array_like, shape (..., T)
        Rotating mass of each throw at the crank radius [kg].
    moment : array_like, shape (..., T)
        Its first moment about the moment reference point along the crank axis [kg·m].
    throw_angle : array_like, shape (..., T)
        Throw angles [rad].
    crank_radius, speed : array_like, shape (...)
        Crank radius [m] and crank speed [rad/s].

    Returns
    -------
    force : ndarray of complex, shape (...)
        Forward first-order phasor :math:`F_{rot}` [N].
    couple : ndarray of complex, shape (...)
        Its couple :math:`C_{rot}` about the moment reference point [N·m].

    References
    ----------
    Appl. Sci. 2021 (the rotating masses in the matrix formulation); Den Hartog (1956)
    ch. 5.
    """
    turn = np.exp(1j * np.asarray(throw_angle, dtype=float))
    accel = np.multiply(crank_radius, np.square(speed))
    force = accel * np.multiply(mass, turn).sum(axis=-1)
    couple = accel * np.multiply(moment, turn).sum(axis=-1)
    return force, couple


@record
class BatchFreeForces(ResultMixin):
    r"""Free forces and moments of a batch of engines by order (:class:`FreeForces`, with a
    leading engine axis).

    Parameters
    ----------
    orders : ndarray of int, shape (K,)
        Harmonic orders 1..K.
    force_forward, force_backward : ndarray of complex, shape (E, K)
        :math:`F_n^{\pm}` of each engine [N].
    couple_forward, couple_backward : ndarray of complex, shape (E, K)
        :math:`C_n^{\pm}` about the moment reference point [N·m].
    rotating_force : ndarray of complex, shape (E,)
        First-order forward phasor of the rotating masses [N].
    rotating_couple : ndarray of complex, shape (E,)
        Its couple [N·m].
    roll : ndarray of complex, shape (E, K)
        :math:`R_n`, the roll moment of each order about the axis through the moment
        reference point parallel to the crank (:attr:`FreeForces.roll`) [N·m].
    rotating_roll : ndarray of complex, shape (E,)
        The rotating masses' first-order roll moment about that axis [N·m].
    """

    orders: NDArray[np.int64]
    force_forward: NDArray[np.complex128]
    force_backward: NDArray[np.complex128]
    couple_forward: NDArray[np.complex128]
    couple_backward: NDArray[np.complex128]
    rotating_force: NDArray[np.complex128]
    rotating_couple: NDArray[np.complex128]
    roll: NDArray[np.complex128]
    rotating_roll: NDArray[np.complex128]


def batch_free_forces(batch: EngineBatch, orders: int = 8) -> BatchFreeForces:
    """:func:`free_forces` of every engine of a batch, by the same functions: the
    harmonic coefficients (:func:`coefficient_rows`, computed once when the engines share
    their rod ratio and offsets), the phasor sums over the cylinders
    (:func:`reciprocating_phasors`), the rotating masses (:func:`rotating_phasors`) and the
    roll moment (:func:`batch_roll_phasors`, about the topology's reference point).

    Parameters
    ----------
    batch : EngineBatch
        The engines (:func:`crankbalance.physics.model.engine_batch`).
    orders : int
        Highest harmonic order K.

    Returns
    -------
    BatchFreeForces
        Phasors of every engine [N], [N·m].

    References
    ----------
    As :func:`free_forces`.
    """
    topo = batch.topology
    r = batch.crank_radius
    coeff = coefficient_rows(
        r / batch.rod_length, batch.cylinder_offset / r[:, None], orders, topo.kinematics
    )
    fwd, bwd, cfwd, cbwd = reciprocating_phasors(
        coeff,
        batch.reciprocating_mass,
        np.take(batch.throw_angle, topo.cylinder_throw, axis=-1),
        topo.cylinder_bank,
        topo.cylinder_position,
        r,
        batch.speed,
        per_cylinder=True,
    )
    y = topo.throw_position
    force, couple = rotating_phasors(
        batch.throw_rotating_mass,
        batch.throw_rotating_mass * y + topo.throw_axial_moment,
        batch.throw_angle,
        r,
        batch.speed,
    )
    q = complex(topo.reference_x, topo.reference_z)
    roll = batch_roll_phasors(
        r / batch.rod_length,
        batch.cylinder_offset / r[:, None],
        batch.reciprocating_mass,
        np.take(batch.throw_angle, topo.cylinder_throw, axis=-1) - topo.cylinder_bank,
        r,
        batch.speed,
        orders,
        topo.kinematics,
    )
    roll = roll + q * fwd + np.conj(q * bwd)
    return BatchFreeForces(
        np.arange(1, orders + 1), fwd, bwd, cfwd, cbwd, force, couple, roll, q * force
    )


def reciprocating_phasors(
    coefficients: ArrayLike,
    mass: ArrayLike,
    throw_angle: ArrayLike,
    bank: ArrayLike,
    position: ArrayLike,
    crank_radius: ArrayLike,
    speed: ArrayLike,
    per_cylinder: bool = False,
) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    r"""Forward and backward phasors of force and couple, by order, for many engines at once.

    Parameters
    ----------
    coefficients : array_like of complex, shape (..., K) or (..., C, K)
        Harmonic coefficients :math:`c_n` of orders 1..K of the normalised piston
        inertia [-], shared by the cylinders of an engine or, with ``per_cylinder``, one
        row per cylinder (:func:`cylinder_coefficients`).
    mass, throw_angle, bank, position : array_like, shape (..., C)
        Per cylinder: reciprocating mass [kg], throw angle [rad], bank angle [rad],
        axial position [m]. Pad absent cylinders of smaller engines with zero mass.
    crank_radius, speed : array_like, shape (...)
        Crank radius [m] and crank speed [rad/s].
    per_cylinder : bool
        True when ``coefficients`` has a cylinder axis (shape (..., C, K)).

    Returns
    -------
    force_forward, force_backward, couple_forward, couple_backward : ndarray, shape (..., K)
        Complex phasors :math:`F_n^{\pm}` [N] and :math:`C_n^{\pm}` [N·m] of each order.

    References
    ----------
    Appl. Sci. 2021 (matrix formulation), written with rotating phasors as in the module
    docstring.
    """
    c = np.asarray(coefficients)
    return _phasors(
        _engine_sums(
            mass, throw_angle, bank, position, crank_radius, speed, c.shape[-1], c, per_cylinder
        )
    )


def _phasors(sums: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """:math:`F^+, F^-, C^+, C^-` from the coefficient-weighted sums of :func:`_cylinder_sums`
    (a new array of the caller's, whose rows 1 and 3 are conjugated in place)."""
    np.conjugate(sums[..., 1::2, :], out=sums[..., 1::2, :])
    return sums[..., 0, :], sums[..., 1, :], sums[..., 2, :], sums[..., 3, :]


def _engine_sums(
    mass: ArrayLike,
    throw_angle: ArrayLike,
    bank: ArrayLike,
    position: ArrayLike,
    crank_radius: ArrayLike,
    speed: ArrayLike,
    orders: int,
    coefficients: NDArray | None = None,
    per_cylinder: bool = False,
) -> NDArray[np.complex128]:
    """:func:`_cylinder_sums` from the arguments of :func:`reciprocating_phasors`."""
    beta = np.asarray(bank, dtype=float)
    half = 0.5 * np.asarray(crank_radius, dtype=float) * np.asarray(speed, dtype=float) ** 2
    p = np.multiply(mass, half[..., None])
    theta = np.subtract(throw_angle, beta)
    return _cylinder_sums(p, theta, beta, position, orders, coefficients, per_cylinder)


def _cylinder_sums(
    p: NDArray,
    theta: NDArray,
    beta: NDArray,
    position: ArrayLike,
    orders: int,
    coefficients: NDArray | None = None,
    per_cylinder: bool = False,
    weights: NDArray[np.complex128] | None = None,
) -> NDArray[np.complex128]:
    r"""The four sums over the cylinders behind the phasors of :func:`reciprocating_phasors`.

    With :math:`p_c = \tfrac{1}{2} m_c r\omega^2`, :math:`w_c = p_c e^{i\beta_c}` and
    :math:`z_c = e^{i\theta_c}`, :math:`\theta_c = \varphi_c - \beta_c` (arrays of shape
    (..., C)), the rows of the result (axis -2) are :math:`G_0 = \sum_c w_c z_c^n`,
    :math:`G_1 = \sum_c \bar w_c z_c^n` and the same weighted by the axial position
    :math:`y_c`, :math:`G_2` and :math:`G_3`. Shape ``(..., 4, orders)``.

    Without ``coefficients`` these are the bare sums. With coefficients :math:`c_n` shared
    by the cylinders (shape (..., K)) each row is multiplied by them, so that
    :math:`F_n^+ = c_n G_0`, :math:`F_n^- = \overline{c_n G_1}` (as :math:`\sum w \bar
    z^n = \overline{\sum \bar w z^n}`), :math:`C_n^+ = c_n G_2` and :math:`C_n^- =
    \overline{c_n G_3}` once :func:`_phasors` conjugates rows 1 and 3. With
    ``per_cylinder`` coefficients :math:`c_{n,c}` (shape (..., C, K)) each cylinder's power
    is weighted by its own row, :math:`F_n^+ = \sum_c c_{n,c} w_c z_c^n` and so on; when
    all the rows are equal the shared row is factored out instead (the same numbers, to
    the last bit, as an engine whose cylinders share one offset). ``weights``: those of
    :func:`_sum_weights` of ``p``, ``beta`` and ``position``, computed before (one model's,
    kept by :func:`free_forces`).
    """
    if coefficients is not None and per_cylinder:
        if coefficients.shape[-2] == 1 or np.all(coefficients == coefficients[..., :1, :]):
            coefficients, per_cylinder = coefficients[..., 0, :], False
        else:
            return _weighted_sums(p, theta, beta, position, orders, coefficients)
    if weights is None:
        weights = _sum_weights(p, beta, position)
    sums = weights @ _powers(theta, orders)
    return sums if coefficients is None else coefficients[..., None, :] * sums


def _sum_weights(p: NDArray, beta: NDArray, position: ArrayLike) -> NDArray[np.complex128]:
    r"""The weights of the four sums of :func:`_cylinder_sums`, :math:`w_c`, :math:`\bar
    w_c`, :math:`w_c y_c`, :math:`\bar w_c y_c` (shape (..., 4, C))."""
    w = p * np.exp(1j * beta)
    wy = w * position
    weights = np.empty(wy.shape[:-1] + (4,) + wy.shape[-1:], dtype=complex)  # (..., 4, C)
    weights[..., 0, :] = w
    weights[..., 2, :] = wy
    np.conjugate(weights[..., 0::2, :], out=weights[..., 1::2, :])
    return weights


def _powers(theta: NDArray, orders: int) -> NDArray[np.complex128]:
    """:math:`z_c^n = e^{in\theta_c}` of orders 1..K, shape (..., C, K).

    One engine (no engine axis): the exponentials of all the angles at once, the fewest
    numpy calls. An engine axis, however long: the powers of one exponential per cylinder,
    each engine's numbers computed alike whatever the batch (a batch of one gives the bits
    of a batch of thousands, so a result does not depend on its batch).
    """
    if theta.ndim <= 1:  # one engine: the fewest numpy calls
        return np.exp(1j * theta[..., None] * np.arange(1.0, orders + 1))
    # many: z**1 .. z**K by doubling, z**(m+1..2m) = z**(1..m) * z**m, orders first so
    # that every product runs over all the engines and cylinders at once
    powers = np.empty((orders,) + theta.shape, dtype=complex)  # (K, ..., C)
    np.exp(1j * theta, out=powers[0])
    done = 1
    while done < orders:
        step = min(done, orders - done)
        np.multiply(powers[:step], powers[done - 1], out=powers[done : done + step])
        done += step
    return powers.transpose(tuple(range(1, powers.ndim)) + (0,))  # (..., C, K)


def _weighted_sums(
    p: NDArray,
    theta: NDArray,
    beta: NDArray,
    position: ArrayLike,
    orders: int,
    coefficients: NDArray,
) -> NDArray[np.complex128]:
    """:func:`_cylinder_sums` with a row of coefficients per cylinder (shape (..., C, K))."""
    w = p * np.exp(1j * beta)
    y = np.asarray(position, dtype=float)
    z = coefficients * _powers(theta, orders)  # (..., C, K)
    rows = [w, np.conj(w), w * y, np.conj(w) * y]
    return np.stack([np.einsum("...c,...ck->...k", r, z) for r in rows], axis=-2)


def batch_amplitudes(
    crank_radius: ArrayLike,
    rod_length: ArrayLike,
    speed: ArrayLike,
    mass: ArrayLike,
    throw_angle: ArrayLike,
    bank: ArrayLike,
    position: ArrayLike,
    orders: int = 8,
    offset: ArrayLike = 0.0,
    kinematics: KinematicsModel = "exact",
    chunk: int = CHUNK,
) -> tuple[NDArray, NDArray]:
    r"""Force and moment amplitudes of many engines at once, a chunk of engines at a time.

    Engine parameters have shape (E,), per-cylinder arrays (E, C) (pad smaller engines
    with zero mass); a scalar, or a (C,) array, is shared by all the engines. Only the
    reciprocating masses are counted. The memory of a call is its two (E, K) results and
    the temporaries of one chunk.

    Parameters
    ----------
    crank_radius, rod_length : array_like, shape (E,) or scalar
        Crank radius and conrod length [m].
    speed : array_like, shape (E,) or scalar
        Crank speed [rad/s].
    mass, throw_angle, bank, position : array_like, shape (E, C) or (C,)
        Per cylinder: reciprocating mass [kg], throw angle [rad], bank angle [rad],
        axial position from the crankshaft mid-point [m].
    orders : int
        Highest harmonic order K.
    offset : array_like, shape (E,) or scalar
        Crank offset plus wrist-pin offset [m].
    kinematics : {"exact", "series", "first-order"}
        Piston kinematics model, see :func:`crankbalance.physics.kinematics.harmonic_coefficients`.
    chunk : int
        Engines computed together [-]; changes the speed, not the results.

    Returns
    -------
    force_amplitude : ndarray, shape (E, K)
        :math:`|F_n^+| + |F_n^-|`, largest force of each order over a revolution [N].
    moment_amplitude : ndarray, shape (E, K)
        :math:`|C_n^+| + |C_n^-|`, largest moment of each order over a revolution [N·m].
        Both are of shape (K,) when no argument has an engine axis.

    Notes
    -----
    :math:`|F_n^+| + |F_n^-| = |c_n|\,(|G_0| + |G_1|)` with the sums over the cylinders of
    :func:`_cylinder_sums`, so the phasors themselves are never formed.
    """
    engine = [np.asarray(a, dtype=float) for a in (crank_radius, rod_length, speed, offset)]
    cylinder = [np.asarray(a, dtype=float) for a in (mass, throw_angle, bank, position)]
    if any(a.ndim > 1 for a in engine) or any(a.ndim not in (1, 2) for a in cylinder):
        raise ValueError(
            "batch_amplitudes: engine parameters are scalars or (E,) arrays, per-cylinder "
            "parameters (C,) or (E, C) arrays; got shapes "
            f"{[a.shape for a in engine]} and {[a.shape for a in cylinder]}"
        )
    lead = np.broadcast_shapes(*(a.shape for a in engine), *(a.shape[:-1] for a in cylinder))
    engines = lead[0] if lead else 1
    force = np.empty((engines, orders))
    moment = np.empty((engines, orders))
    step = max(1, int(chunk))
    for start in range(0, engines, step):
        part = slice(start, min(start + step, engines))
        r, l, w, e = (a[part] if a.ndim == 1 and a.shape[0] != 1 else a for a in engine)
        m, phi, beta, y = (a[part] if a.ndim == 2 and a.shape[0] != 1 else a for a in cylinder)
        size = np.abs(harmonic_coefficients(r / l, orders, e / r, kinematics))
        sums = np.abs(_engine_sums(m, phi, beta, y, r, w, orders))
        force[part] = size * (sums[..., 0, :] + sums[..., 1, :])
        moment[part] = size * (sums[..., 2, :] + sums[..., 3, :])
    if not lead:
        return force[0], moment[0]
    return force, moment


# --------------------------------------------------------------------------- curves
@record
class Curves(ResultMixin):
    """Forces [N] and moments [N·m] versus crank angle of the first throw [rad].

    Arrays by order have shape (K, M); totals (M,). Components: ``fx``, ``fz`` and
    ``mx``, ``my``, ``mz`` (moment about the moment reference point; ``my`` the roll
    moment about the axis through it along the crank).

    Parameters
    ----------
    angle : ndarray, shape (M,)
        Crank angle of the first throw [rad].
    orders : ndarray of int, shape (K,)
        Harmonic orders of the rows of the per-order arrays.
    fx, fz : ndarray, shape (K, M)
        Reciprocating inertia force of each order, components x and z [N].
    mx, mz : ndarray, shape (K, M)
        Its moment about the moment reference point, components x and z [N·m].
    my : ndarray, shape (K, M)
        Roll moment of each order (:attr:`FreeForces.roll`) [N·m].
    total_fx, total_fz : ndarray, shape (M,)
        Total reciprocating force [N]: exact time domain for the exact kinematics, the sum
        of the orders otherwise.
    total_mx, total_mz : ndarray, shape (M,)
        Total reciprocating moment [N·m], as ``total_fx``.
    total_my : ndarray, shape (M,)
        Total roll moment [N·m], as ``total_fx`` (:func:`roll_time_domain`).
    rotating_fx, rotating_fz : ndarray, shape (M,)
        Force of the rotating masses [N].
    rotating_mx, rotating_mz : ndarray, shape (M,)
        Moment of the rotating masses about the moment reference point [N·m].
    rotating_my : ndarray, shape (M,)
        Their roll moment (zero unless the reference point is off the crank axis) [N·m].
    """

    angle: NDArray[np.float64]
    orders: NDArray[np.int64]
    fx: NDArray[np.float64]
    fz: NDArray[np.float64]
    mx: NDArray[np.float64]
    mz: NDArray[np.float64]
    total_fx: NDArray[np.float64]
    total_fz: NDArray[np.float64]
    total_mx: NDArray[np.float64]
    total_mz: NDArray[np.float64]
    rotating_fx: NDArray[np.float64]
    rotating_fz: NDArray[np.float64]
    rotating_mx: NDArray[np.float64]
    rotating_mz: NDArray[np.float64]
    my: NDArray[np.float64]
    total_my: NDArray[np.float64]
    rotating_my: NDArray[np.float64]


def phasor_curve(
    forward: ArrayLike, backward: ArrayLike, orders: ArrayLike, angle: ArrayLike
) -> NDArray[np.complex128]:
    r"""Evaluate :math:`F^+ e^{in\theta} + F^- e^{-in\theta}` for each order, shape (K, M).

    Parameters
    ----------
    forward, backward : array_like of complex, shape (K,)
        Forward and backward phasors of each order [N] or [N·m]; the curve has their unit.
    orders : array_like, shape (K,)
        Harmonic order n of each phasor [-].
    angle : array_like, shape (M,)
        Crank angle of the first throw :math:`\theta` [rad].

    Returns
    -------
    ndarray of complex, shape (K, M)
        :math:`z + i x` components of each order at each angle, in the unit of the phasors.
    """
    n = np.asarray(orders, dtype=float)[:, None]
    theta = np.asarray(angle, dtype=float)[None, :]
    turn = np.exp(1j * n * theta)
    return np.asarray(forward)[:, None] * turn + np.asarray(backward)[:, None] * np.conj(turn)


def curves(model: EngineModel, forces: FreeForces, angle: ArrayLike | None = None) -> Curves:
    """Curves of every order from the phasors, and the exact total from the time domain.

    The total of the reciprocating forces is computed directly from the exact slider-crank
    motion when ``model.kinematics == "exact"`` (not as a sum of orders); for the series
    and first-order models it is the sum of the computed orders.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    forces : FreeForces
        Its phasors, from :func:`free_forces`.
    angle : array_like, optional
        Crank angles of the first throw [rad]; default 720 points over one revolution.

    Returns
    -------
    Curves
        Forces [N] and moments [N·m] by order, total and of the rotating masses.
    """
    theta = (
        np.linspace(0, 2 * np.pi, 720, endpoint=False)
        if angle is None
        else np.asarray(angle, dtype=float)
    )
    f = phasor_curve(forces.force_forward, forces.force_backward, forces.orders, theta)
    m = 1j * phasor_curve(forces.couple_forward, forces.couple_backward, forces.orders, theta)
    roll = (forces.roll[:, None] * np.exp(1j * np.outer(forces.orders, theta))).real
    if model.kinematics == "exact":
        total_f, total_c = exact_time_domain(model, theta)
        total_m = 1j * total_c
        total_roll = roll_time_domain(model, theta)
    else:
        total_f, total_m, total_roll = f.sum(axis=0), m.sum(axis=0), roll.sum(axis=0)
    rot = phasor_curve([forces.rotating_force], [0.0], [1], theta)[0]
    rot_m = 1j * phasor_curve([forces.rotating_couple], [0.0], [1], theta)[0]
    rot_roll = (forces.rotating_roll * np.exp(1j * theta)).real
    return Curves(
        angle=theta,
        orders=forces.orders,
        fx=f.imag,
        fz=f.real,
        mx=m.imag,
        mz=m.real,
        total_fx=total_f.imag,
        total_fz=total_f.real,
        total_mx=total_m.imag,
        total_mz=total_m.real,
        rotating_fx=rot.imag,
        rotating_fz=rot.real,
        rotating_mx=rot_m.imag,
        rotating_mz=rot_m.real,
        my=roll,
        total_my=total_roll,
        rotating_my=rot_roll,
    )


def roll_time_domain(model: EngineModel, angle: ArrayLike) -> NDArray[np.float64]:
    r"""Roll moment of the reciprocating masses versus crank angle, straight from the exact
    motion (no harmonic analysis), about the axis through the moment reference point.

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    angle : array_like, shape (M,)
        Crank angles of the first throw [rad].

    Returns
    -------
    ndarray, shape (M,)
        :math:`M_y = \sum_c -F_c(e_c + \dot s_c/\omega) + p_x F_z - p_z F_x` [N·m]
        (:mod:`crankbalance.physics.roll`; the link pins' part with master-and-link rods).
    """
    theta = np.asarray(angle, dtype=float)
    force, _couple = exact_time_domain(model, theta)
    shift = (complex(model.reference_x, model.reference_z) * force).real
    rods = model.articulated_rods
    if rods is not None:
        phi, _y = _single_throw(model)
        curve = articulated_roll_curve(
            rods, model.reciprocating_mass, model.cylinder_rotating_mass, theta + phi, model.speed
        )
        return np.asarray(curve + shift, dtype=float)
    psi = theta[:, None] + (model.cylinder_angle - model.cylinder_bank)[None, :]
    r, l, e, w = model.crank_radius, model.rod_length, model.cylinder_offset, model.speed
    accel = piston_acceleration(psi, r, l, e[None, :], w)
    rate = piston_velocity(psi, r, l, e[None, :], w)
    axial = model.reciprocating_mass[None, :] * accel  # -F along each cylinder axis
    return np.asarray((axial * (e[None, :] + rate / w)).sum(axis=1) + shift, dtype=float)


def exact_time_domain(model: EngineModel, angle: ArrayLike) -> tuple[NDArray, NDArray]:
    """Reciprocating inertia force and couple versus crank angle, straight from the exact
    slider-crank acceleration of every cylinder (no harmonic analysis).

    Parameters
    ----------
    model : EngineModel
        The engine (SI arrays).
    angle : array_like, shape (M,)
        Crank angles of the first throw [rad].

    Returns
    -------
    force : ndarray of complex, shape (M,)
        Reciprocating inertia force :math:`F_z + iF_x` summed over the cylinders [N].
    couple : ndarray of complex, shape (M,)
        Its couple :math:`\\sum y F` about the crankshaft mid-point [N·m].
    """
    if model.articulation is not None:
        return _articulated_time_domain(model, angle)
    theta = np.asarray(angle, dtype=float)[:, None]
    psi = theta + (model.cylinder_angle - model.cylinder_bank)[None, :]
    acc = piston_acceleration(
        psi, model.crank_radius, model.rod_length, model.cylinder_offset[None, :], model.speed
    )
    force = -model.reciprocating_mass[None, :] * acc * np.exp(1j * model.cylinder_bank)[None, :]
    return force.sum(axis=1), (force * model.cylinder_position[None, :]).sum(axis=1)


# --------------------------------------------------------------------------- articulated rods
def _articulated_rows(model: EngineModel, orders: int, mode: str) -> NDArray[np.complex128]:
    """:func:`cylinder_coefficients` of a radial with master-and-link rods: every piston's
    own coefficients from its exact motion
    (:func:`crankbalance.physics.articulated.cylinder_coefficients`)."""
    rods = model.articulated_rods
    assert rods is not None
    _exact_only(mode)
    _single_throw(model)
    from .articulated import cylinder_coefficients as articulated_coefficients

    return articulated_coefficients(rods, orders)


def _exact_only(mode: str) -> None:
    """Refuse a kinematics model other than the exact one for master-and-link rods."""
    if mode != "exact":
        raise InputError(
            "kinematics",
            mode,
            "master-and-link rods are modelled with the exact kinematics only: 'exact'",
        )


def _link_pin_phasors(model: EngineModel, orders: int) -> tuple[NDArray, ...]:
    r"""Forward and backward phasors of force [N] and couple [N·m] of the link rods' big
    ends beyond the crankpin: :math:`-n_k(\ddot L_k - \ddot P)`, with :math:`n_k` the
    rods' big-end masses (``cylinder_rotating_mass``), turned by the throw angle
    :math:`\varphi` as :math:`e^{\pm in\varphi}`, the couple at each rod's axial position."""
    rods = model.articulated_rods
    assert rods is not None
    phi, _y = _single_throw(model)
    from .articulated import harmonics as articulated_harmonics

    h = articulated_harmonics(rods, orders)
    turn = np.exp(1j * h.orders * phi)
    mass = model.speed**2 * model.cylinder_rotating_mass
    lever = mass * model.cylinder_position
    fwd, bwd = mass @ h.link_forward * turn, mass @ h.link_backward * np.conj(turn)
    cfwd, cbwd = lever @ h.link_forward * turn, lever @ h.link_backward * np.conj(turn)
    return fwd, bwd, cfwd, cbwd


def _articulated_time_domain(model: EngineModel, angle: ArrayLike) -> tuple[NDArray, NDArray]:
    """:func:`exact_time_domain` of a radial with master-and-link rods."""
    rods = model.articulated_rods
    assert rods is not None
    phi, _y = _single_throw(model)
    from .articulated import inertia_force as articulated_inertia_force

    force = articulated_inertia_force(
        rods,
        model.reciprocating_mass,
        model.cylinder_rotating_mass,
        np.asarray(angle, dtype=float) + phi,
        model.speed,
    )
    return force.sum(axis=1), (force * model.cylinder_position[None, :]).sum(axis=1)


def _single_throw(model: EngineModel) -> tuple[float, float]:
    """Angle [rad] and axial position [m] of the one throw of an articulated radial."""
    if model.throws != 1:
        raise InputError(
            "articulation", model.throws, "master-and-link rods sit on one throw (a radial)"
        )
    return float(model.throw_angle[0]), float(model.throw_position[0])
