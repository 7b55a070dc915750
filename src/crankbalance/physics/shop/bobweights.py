r"""Bob-weights per crankpin for any crank (vee, boxer, W, in-line), and the free forces a
bob-weight fraction leaves in the running engine (issue 16, item 3;
``docs/balance_shop.md``, "Bob-weights").

A crank is balanced in the balancing machine with a bob-weight clamped on each crankpin
(rod journal) at the crank radius: the *rotating share* of the rods on that pin (every big
end, its bearing shells, the oil allowance) plus a chosen fraction :math:`f` of their
*reciprocating share* (pistons, pins, rings, locks, small ends):

.. math:: B_t = \sum_{c \in t} R_c + f \sum_{c \in t} M_c

The machine makes crank plus bob-weights balanced (force and couple), so the crank itself
carries the first moment :math:`-B_t\,r` opposite each pin. In the running engine the real
rotating parts :math:`\sum_{c\in t} R_c` sit on the pin, and the crank is left with a net
rotating mass :math:`\sum_{c\in t} R_c - B_t` at each pin, :math:`-f \sum_{c\in t} M_c` for
exact bob-weights. The free forces of the engine are then the reciprocating phasors of
:func:`crankbalance.physics.shaking.free_forces` plus that rotating first-order phasor: the
fraction trades the forward first-order force of the reciprocating masses against a
forward force of the counterweights; the backward first-order phasor and every higher
order stay as they are. For a common-pin 90° vee the forward phasor of a pin's pair is
exactly one rod's reciprocating mass, so :math:`f = 1/2` cancels the first order
completely; :func:`best_fraction` finds the fraction that minimises the largest first-order
force (or couple) for any crank.

This generalises the single-cylinder bob-weight of Hoem and Røsholm (2016), Sec. 3.2
(:func:`crankbalance.physics.single_cylinder.bob_weight`), which it calls per pin; the free forces
follow Den Hartog (1956) ch. 5 and Taylor (1985) ch. 8.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError
from ...records import record
from ...results import ResultMixin
from ..model import EngineModel
from ..shaking import free_forces
from ..single_cylinder import bob_weight, check_balance_factor

#: relative size below which the counterweights' first-order phasor counts as zero
#: (a crank whose pins cancel, such as an in-line 4: the fraction changes no free force)
NO_EFFECT = 1e-9


@record
class BobWeights(ResultMixin):
    """Bob-weight of every crankpin (throw) of a crank.

    Attributes
    ----------
    fraction : float
        Fraction :math:`f` of the reciprocating share in the bob-weight [-].
    rods_on_pin : ndarray of int, shape (T,)
        Rods on each pin.
    rotating : ndarray, shape (T,)
        Rotating share of each pin: big ends, shells, oil of its rods [kg].
    reciprocating : ndarray, shape (T,)
        Reciprocating share of each pin: pistons, pins, rings, locks, small ends [kg].
    bob_weight : ndarray, shape (T,)
        :math:`B_t = R_t + f M_t` [kg], to clamp at the crank radius.
    """

    fraction: float
    rods_on_pin: NDArray[np.int64]
    rotating: NDArray[np.float64]
    reciprocating: NDArray[np.float64]
    bob_weight: NDArray[np.float64]


def _per_cylinder(values: ArrayLike, count: int, name: str) -> NDArray[np.float64]:
    array = np.asarray(values, dtype=float)
    if array.shape != (count,):
        raise InputError(name, array.shape, f"must hold one mass per cylinder ({count})")
    bad = np.flatnonzero(~(np.isfinite(array) & (array >= 0)))
    if bad.size:
        raise InputError(f"{name}[{bad[0] + 1}]", float(array[bad[0]]), "must be a mass >= 0")
    return array


def pin_shares(cylinder_throw: ArrayLike, values: ArrayLike, throws: int) -> NDArray[np.float64]:
    """Sum per-cylinder values over the cylinders of each throw (crankpin).

    Parameters
    ----------
    cylinder_throw : array_like of int, shape (C,)
        Index (0-based) of the throw each cylinder sits on [-].
    values : array_like, shape (C,)
        One mass per cylinder [kg].
    throws : int
        Number of throws T.

    Returns
    -------
    ndarray, shape (T,)
        The sum over the cylinders on each throw [kg].
    """
    index = np.asarray(cylinder_throw, dtype=np.int64)
    sums = np.bincount(index, weights=np.asarray(values, dtype=float), minlength=throws)
    return np.asarray(sums, dtype=np.float64)


def bob_weights(
    model: EngineModel,
    fraction: float,
    rotating: ArrayLike,
    reciprocating: ArrayLike | None = None,
) -> BobWeights:
    """Bob-weight of each crankpin: its rotating share plus ``fraction`` of its reciprocating
    share.

    Parameters
    ----------
    model : EngineModel
        The engine: which throw each cylinder sits on (``cylinder_throw``).
    fraction : float
        Fraction :math:`f` of the reciprocating share, in [0, 2] [-] (0.5 for a 90° V8).
    rotating : array_like, shape (C,)
        Rotating share of each cylinder's rod: big end, bearing shells, oil [kg].
    reciprocating : array_like, shape (C,), optional
        Reciprocating share of each cylinder: piston, pin, rings, locks, small end [kg];
        the model's ``reciprocating_mass`` when not given.

    Returns
    -------
    BobWeights
        Shares and bob-weight per pin [kg].

    Raises
    ------
    InputError
        If the fraction is outside [0, 2] or a mass is negative or not finite.

    References
    ----------
    Hoem and Røsholm (2016), Sec. 3.2 (one cylinder); per pin as in Taylor (1985) ch. 8.
    """
    check_balance_factor(fraction, "fraction")
    count = model.cylinders
    rot = _per_cylinder(rotating, count, "rotating")
    rec = _per_cylinder(
        model.reciprocating_mass if reciprocating is None else reciprocating,
        count,
        "reciprocating",
    )
    rot_pin = pin_shares(model.cylinder_throw, rot, model.throws)
    rec_pin = pin_shares(model.cylinder_throw, rec, model.throws)
    rods = np.bincount(model.cylinder_throw, minlength=model.throws).astype(np.int64)
    weights = [bob_weight(r, m, fraction) for r, m in zip(rot_pin, rec_pin, strict=True)]
    return BobWeights(float(fraction), rods, rot_pin, rec_pin, np.array(weights))


@record
class RemainingForces(ResultMixin):
    r"""Free forces and couples of an engine whose crank was balanced with given bob-weights.

    Phasors at crank angle 0, complex :math:`z + i x` as in :mod:`crankbalance.physics.shaking`;
    index k belongs to order k + 1. The first order includes the crank's net rotating
    masses (real rotating parts minus the bob-weights).

    Attributes
    ----------
    fraction : float
        Fraction of the reciprocating share in the bob-weights [-] (NaN when the
        bob-weights were given, not computed).
    force_forward, force_backward : ndarray of complex, shape (K,)
        Forward and backward force phasors per order [N].
    couple_forward, couple_backward : ndarray of complex, shape (K,)
        Couple phasors about the crank mid-point per order [N*m].
    force_amplitude : ndarray, shape (K,)
        Largest force magnitude over a revolution per order [N].
    couple_amplitude : ndarray, shape (K,)
        Largest couple magnitude over a revolution per order [N*m].
    """

    fraction: float
    force_forward: NDArray[np.complex128]
    force_backward: NDArray[np.complex128]
    couple_forward: NDArray[np.complex128]
    couple_backward: NDArray[np.complex128]
    force_amplitude: NDArray[np.float64]
    couple_amplitude: NDArray[np.float64]


def remaining_forces(
    model: EngineModel,
    fraction: float,
    reciprocating: ArrayLike | None = None,
    orders: int = 2,
) -> RemainingForces:
    """The free forces and couples left in the running engine when the crank was balanced
    with exact bob-weights of the given fraction.

    The rotating parts cancel (the crank was balanced against them); each pin keeps a net
    rotating mass :math:`-f M_t` at the crank radius.

    Parameters
    ----------
    model : EngineModel
        The engine (layout, kinematics, speed).
    fraction : float
        Fraction :math:`f` of the reciprocating share in the bob-weights, in [0, 2] [-].
    reciprocating : array_like, shape (C,), optional
        Reciprocating share of each cylinder [kg]; the model's when not given.
    orders : int
        Highest order computed (>= 1).

    Returns
    -------
    RemainingForces
        Phasors and amplitudes per order [N], [N*m].

    References
    ----------
    Den Hartog (1956) ch. 5; Taylor (1985) ch. 8 (free forces of the crank train).
    """
    if isinstance(orders, bool) or not isinstance(orders, int) or not 1 <= orders <= 64:
        raise InputError("orders", orders, "must be a whole number from 1 to 64")
    rec = model.reciprocating_mass if reciprocating is None else reciprocating
    weights = bob_weights(model, fraction, np.zeros(model.cylinders), rec)
    engine = dataclasses.replace(
        model,
        reciprocating_mass=_per_cylinder(rec, model.cylinders, "reciprocating"),
        throw_rotating_mass=-weights.fraction * weights.reciprocating,
        cylinder_rotating_mass=np.zeros(model.cylinders),  # the balance at the throw centre
    )
    forces = free_forces(engine, orders)
    fwd = forces.force_forward.copy()
    cfwd = forces.couple_forward.copy()
    fwd[0] += forces.rotating_force
    cfwd[0] += forces.rotating_couple
    return RemainingForces(
        fraction=weights.fraction,
        force_forward=fwd,
        force_backward=forces.force_backward,
        couple_forward=cfwd,
        couple_backward=forces.couple_backward,
        force_amplitude=np.abs(fwd) + np.abs(forces.force_backward),
        couple_amplitude=np.abs(cfwd) + np.abs(forces.couple_backward),
    )


def best_fraction(
    model: EngineModel, reciprocating: ArrayLike | None = None, quantity: str = "force"
) -> float | None:
    r"""The bob-weight fraction that minimises the largest first-order free force (or
    couple) of the running engine.

    The forward first-order phasor is :math:`F^+(f) = F^+(0) - f\,S` with :math:`S` the
    counterweights' phasor per unit fraction; the backward phasor does not depend on
    :math:`f`. The largest magnitude :math:`|F^+(f)| + |F^-|` is least for the projection
    :math:`f^* = \mathrm{Re}(F^+(0)\,\bar S)/|S|^2`, held in [0, 2].

    Parameters
    ----------
    model : EngineModel
        The engine.
    reciprocating : array_like, shape (C,), optional
        Reciprocating share of each cylinder [kg]; the model's when not given.
    quantity : {"force", "couple"}
        What to minimise.

    Returns
    -------
    float or None
        The fraction [-], or None when the fraction changes no first-order force (couple):
        the pins' phasors cancel, as in an in-line 4 or a boxer 4.
    """
    if quantity not in ("force", "couple"):
        raise InputError("quantity", quantity, "must be 'force' or 'couple'")
    none = remaining_forces(model, 0.0, reciprocating, orders=1)
    full = remaining_forces(model, 1.0, reciprocating, orders=1)
    start = none.force_forward[0] if quantity == "force" else none.couple_forward[0]
    end = full.force_forward[0] if quantity == "force" else full.couple_forward[0]
    slope = start - end
    # the size of the counterweights' phasor were every pin's share in phase
    rec = np.sum(model.reciprocating_mass if reciprocating is None else reciprocating)
    scale = model.crank_radius * model.speed**2 * float(rec)
    if quantity == "couple":
        scale *= float(np.max(np.abs(model.throw_position)))
    if not abs(slope) > NO_EFFECT * scale:
        return None
    best = (start * slope.conjugate()).real / abs(slope) ** 2
    return float(min(max(best, 0.0), 2.0))
