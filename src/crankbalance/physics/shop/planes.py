r"""Two-plane balancing-machine readings to the correction each correction plane needs.

A balancing machine spins the crank (with its bob-weights) and shows, for each of its two
measuring planes, an amount (a mass at a radius) and an angle. This module turns those
readings into the unbalance to correct in the two correction planes the builder names
(counterweight faces or rims), predicts the residual a correction leaves, refines the
plan from a second reading, and checks the predicted residual against ISO 21940-11.

Conventions. An unbalance is a complex number :math:`U = m\,r\,e^{i\alpha}` [kg m] in the
crank's own frame: :math:`\alpha` is measured from the same reference as the crank's throw
angles and in the same sense (:mod:`crankbalance.physics.model`), so a reading at the angle of
crankpin 1 points at crankpin 1. A *heavy-spot* reading names where the unbalance is
(remove material there); a *light-spot* reading names where to add mass, so the unbalance
is opposite, :math:`U = -m\,r\,e^{i\alpha}`. Axial positions are along the crank axis [m],
any origin, the same for every plane.

Rigid rotor (statics). Unbalances :math:`U_k` in planes :math:`s_k` are equivalent to
:math:`U_1, U_2` in two planes :math:`z_1 \ne z_2` when the resultant and the moment agree,
:math:`U_1 + U_2 = \sum U_k` and :math:`z_1 U_1 + z_2 U_2 = \sum s_k U_k`, so

.. math:: U_1 = \sum_k U_k\,\frac{z_2 - s_k}{z_2 - z_1},\qquad
          U_2 = \sum_k U_k\,\frac{s_k - z_1}{z_2 - z_1}

(:func:`transfer_matrix`), exact for a rigid rotor. The machine's reading changes by
:math:`A\,W` when corrections :math:`W` (the unbalance the corrections add, one per
correction plane) are made; for a rigid rotor on a machine that shows unbalance, :math:`A`
is the transfer from the correction to the measuring planes (:func:`rigid_influence`).
The correction that cancels a reading :math:`R` is :math:`W = -A^{-1}R`.

Iteration (influence coefficients). A second reading after a correction measures the
real :math:`A` along the correction made: :math:`\Delta R = A\,W`. One run gives two of
the four complex coefficients' equations; the estimate is then the rank-one update of the
previous matrix that reproduces the observed change exactly and leaves the response to
any correction orthogonal to :math:`W` unchanged (Broyden 1965). Two runs with independent
corrections (the classical trial weights, one per plane, Thearle 1934) determine :math:`A`;
more runs give its least-squares estimate (Goodman 1964).
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError, check_positive
from ...records import record
from ...results import ResultMixin
from ..tolerance import (
    PlaneAllocation,
    ToleranceVerdict,
    allocate_to_planes,
    check_residual,
    permissible_unbalance,
)

Convention = Literal["heavy", "light"]
CONVENTIONS: tuple[str, ...] = ("heavy", "light")

#: relative size below which a matrix counts as singular (conditioning of A, of runs)
SINGULAR = 1e-9


def axial_pair(field: str, value: ArrayLike) -> NDArray[np.float64]:
    """Two finite axial positions that differ, as an array, or
    :class:`~crankbalance.errors.InputError` naming the field.

    Parameters
    ----------
    field : str
        The field to name in the error.
    value : array_like, shape (2,)
        The two positions [m].

    Returns
    -------
    ndarray, shape (2,)
        The positions [m].
    """
    planes = np.asarray(value, dtype=float)
    if planes.shape != (2,) or not np.all(np.isfinite(planes)):
        raise InputError(field, value, "must be two finite axial positions [m]")
    if planes[0] == planes[1]:
        raise InputError(field, value, "must be two different axial positions [m]")
    return planes


def _complex_pair(field: str, value: ArrayLike) -> NDArray[np.complex128]:
    out = np.asarray(value, dtype=complex)
    if out.shape != (2,) or not np.all(np.isfinite(out)):
        raise InputError(field, value, "must be two finite unbalances [kg m], one per plane")
    return out


def reading_unbalance(
    mass: ArrayLike, radius: ArrayLike, angle: ArrayLike, convention: Convention = "heavy"
) -> NDArray[np.complex128]:
    r"""Unbalance vectors of balancing-machine readings (heavy-spot form) [kg m].

    Parameters
    ----------
    mass : array_like
        Amount shown, as a mass at ``radius`` [kg] (>= 0), one per measuring plane.
    radius : array_like
        Radius the amount refers to [m] (> 0).
    angle : array_like
        Angle shown [rad], in the crank's frame (module docstring).
    convention : {"heavy", "light"}
        ``"heavy"``: the angle is the heavy spot (remove there); ``"light"``: the angle is
        the light spot (add there), the unbalance is opposite.

    Returns
    -------
    ndarray of complex
        :math:`U = \pm m\,r\,e^{i\alpha}` [kg m], ``+`` for heavy spot, ``-`` for light.

    Raises
    ------
    InputError
        If a mass is negative, a radius not positive, an angle not finite, or the
        convention unknown.
    """
    if convention not in CONVENTIONS:
        raise InputError("convention", convention, "must be 'heavy' or 'light'")
    m = np.asarray(mass, dtype=float)
    r = np.asarray(radius, dtype=float)
    a = np.asarray(angle, dtype=float)
    if not np.all((m >= 0) & np.isfinite(m)):
        raise InputError("mass", mass, "must be finite masses [kg], zero or greater")
    if not np.all((r > 0) & np.isfinite(r)):
        raise InputError("radius", radius, "must be finite radii [m] greater than zero")
    if not np.all(np.isfinite(a)):
        raise InputError("angle", angle, "must be finite angles [rad]")
    sign = 1.0 if convention == "heavy" else -1.0
    return sign * m * r * np.exp(1j * a)


def transfer_matrix(source: ArrayLike, target: ArrayLike) -> NDArray[np.float64]:
    r"""Rigid-rotor transfer of unbalances in any planes to two planes.

    Parameters
    ----------
    source : array_like, shape (N,)
        Axial positions of the planes the unbalances are in [m].
    target : array_like, shape (2,)
        Axial positions of the two planes to transfer to [m] (different).

    Returns
    -------
    ndarray, shape (2, N)
        :math:`T` [-] with :math:`U_{target} = T\,U_{source}`:
        :math:`T_{1k} = (z_2 - s_k)/(z_2 - z_1)`, :math:`T_{2k} = (s_k - z_1)/(z_2 - z_1)`.

    Notes
    -----
    The two target unbalances have the resultant and the moment of the source ones (statics
    of a rigid rotor), exactly.
    """
    z1, z2 = axial_pair("target", target)
    s = np.asarray(source, dtype=float)
    if s.ndim != 1 or not np.all(np.isfinite(s)):
        raise InputError("source", source, "must be finite axial positions [m]")
    return np.stack([(z2 - s) / (z2 - z1), (s - z1) / (z2 - z1)])


def rigid_influence(measuring_planes: ArrayLike, correction_planes: ArrayLike) -> NDArray:
    """Influence matrix of a rigid rotor: reading change per correction [-].

    Parameters
    ----------
    measuring_planes : array_like, shape (2,)
        Axial positions of the machine's measuring planes [m].
    correction_planes : array_like, shape (2,)
        Axial positions of the correction planes [m].

    Returns
    -------
    ndarray of complex, shape (2, 2)
        :math:`A` [-] with :math:`\\Delta R = A\\,W`: the transfer of the corrections from
        the correction planes to the measuring planes.
    """
    axial_pair("measuring_planes", measuring_planes)
    axial_pair("correction_planes", correction_planes)
    return transfer_matrix(correction_planes, measuring_planes).astype(complex)


@record
class TwoPlanePlan(ResultMixin):
    """The correction two correction planes need, from one two-plane reading.

    Attributes
    ----------
    measuring_planes, correction_planes : ndarray, shape (2,)
        Axial positions [m].
    reading : ndarray of complex, shape (2,)
        Unbalance read in the measuring planes, heavy-spot form [kg m].
    influence : ndarray of complex, shape (2, 2)
        Influence matrix used, reading change per correction [-].
    influence_method : str
        How it was found: ``"rigid"``, ``"given"`` (by the caller), ``"rank-one update"`` or
        ``"least squares"`` (:func:`estimate_influence`).
    unbalance : ndarray of complex, shape (2,)
        Unbalance in the correction planes, :math:`A^{-1}R` [kg m].
    correction : ndarray of complex, shape (2,)
        Unbalance the corrections must add, ``-unbalance`` [kg m].
    amount : ndarray, shape (2,)
        ``|unbalance|`` [kg m].
    remove_angle, add_angle : ndarray, shape (2,)
        Where to remove material (the heavy spot) and where to add it (opposite) [rad],
        in [0, 2 pi).
    correction_radius : ndarray, shape (2,)
        Radius of the corrections [m].
    mass : ndarray, shape (2,)
        Mass to remove or add at ``correction_radius``, ``amount / correction_radius`` [kg].
    applied_runs, reading_changes : ndarray of complex, shape (R, 2)
        Corrections made so far and the reading change each caused [kg m] (R = 0 for a
        first reading): the data the influence matrix was estimated from.
    """

    measuring_planes: NDArray[np.float64]
    correction_planes: NDArray[np.float64]
    reading: NDArray[np.complex128]
    influence: NDArray[np.complex128]
    influence_method: str
    unbalance: NDArray[np.complex128]
    correction: NDArray[np.complex128]
    amount: NDArray[np.float64]
    remove_angle: NDArray[np.float64]
    add_angle: NDArray[np.float64]
    correction_radius: NDArray[np.float64]
    mass: NDArray[np.float64]
    applied_runs: NDArray[np.complex128]
    reading_changes: NDArray[np.complex128]


def _plan(
    reading: NDArray,
    measuring: NDArray,
    correction_planes: NDArray,
    radius: NDArray,
    influence: NDArray,
    method: str,
    runs: NDArray,
    changes: NDArray,
) -> TwoPlanePlan:
    scale = np.linalg.norm(influence)
    if not (np.all(np.isfinite(influence)) and abs(np.linalg.det(influence)) > SINGULAR * scale**2):
        raise InputError(
            "influence",
            influence.tolist(),
            "must be an invertible 2x2 matrix (the corrections must move the reading "
            "independently in the two planes)",
        )
    unbalance = np.linalg.solve(influence, reading)
    remove = np.mod(np.angle(unbalance), 2 * np.pi)
    amount = np.abs(unbalance)
    return TwoPlanePlan(
        measuring_planes=measuring,
        correction_planes=correction_planes,
        reading=reading,
        influence=influence,
        influence_method=method,
        unbalance=unbalance,
        correction=-unbalance,
        amount=amount,
        remove_angle=remove,
        add_angle=np.mod(remove + np.pi, 2 * np.pi),
        correction_radius=radius,
        mass=amount / radius,
        applied_runs=runs,
        reading_changes=changes,
    )


def _radius(value: ArrayLike) -> NDArray[np.float64]:
    radius = np.broadcast_to(np.asarray(value, dtype=float), (2,)).copy()
    for r in radius:
        check_positive("correction_radius", float(r))
    return radius


def plan_correction(
    reading: ArrayLike,
    measuring_planes: ArrayLike,
    correction_planes: ArrayLike,
    correction_radius: ArrayLike,
    influence: ArrayLike | None = None,
) -> TwoPlanePlan:
    r"""The correction per correction plane that cancels a two-plane reading.

    Parameters
    ----------
    reading : array_like of complex, shape (2,)
        Unbalance in the measuring planes, heavy-spot form [kg m]
        (:func:`reading_unbalance`).
    measuring_planes : array_like, shape (2,)
        Axial positions of the measuring planes [m].
    correction_planes : array_like, shape (2,)
        Axial positions of the correction planes the builder names [m].
    correction_radius : float or array_like, shape (2,)
        Radius at which each plane is corrected [m].
    influence : array_like of complex, shape (2, 2), optional
        Influence matrix [-]; default: the rigid rotor's (:func:`rigid_influence`).

    Returns
    -------
    TwoPlanePlan
        Unbalance and correction per correction plane [kg m], angles [rad], mass [kg].

    Notes
    -----
    .. math:: U = A^{-1} R, \qquad W = -U

    With the rigid :math:`A` this is the statics transfer of :func:`transfer_matrix` from
    the measuring to the correction planes.
    """
    measuring = axial_pair("measuring_planes", measuring_planes)
    planes = axial_pair("correction_planes", correction_planes)
    read = _complex_pair("reading", reading)
    radius = _radius(correction_radius)
    if influence is None:
        matrix, method = rigid_influence(measuring, planes), "rigid"
    else:
        matrix, method = np.asarray(influence, dtype=complex), "given"
        if matrix.shape != (2, 2):
            raise InputError("influence", influence, "must be a 2x2 matrix")
    empty = np.zeros((0, 2), dtype=complex)
    return _plan(read, measuring, planes, radius, matrix, method, empty, empty)


def predicted_residual(plan: TwoPlanePlan, applied: ArrayLike) -> NDArray[np.complex128]:
    r"""Unbalance left in the correction planes after a correction [kg m].

    Parameters
    ----------
    plan : TwoPlanePlan
        The plan the correction was made for.
    applied : array_like of complex, shape (2,)
        Unbalance the correction actually added in each correction plane [kg m] (for
        holes: minus the first moment of the material removed, at its angle; e.g. the
        achieved correction of a drilling plan with its depths rounded).

    Returns
    -------
    ndarray of complex, shape (2,)
        :math:`U + W_{applied}` [kg m]; zero when the plan was followed exactly.
    """
    return plan.unbalance + _complex_pair("applied", applied)


def predicted_reading(plan: TwoPlanePlan, applied: ArrayLike) -> NDArray[np.complex128]:
    r"""Reading the machine should show after a correction [kg m].

    Parameters
    ----------
    plan : TwoPlanePlan
        The plan the correction was made for.
    applied : array_like of complex, shape (2,)
        Unbalance the correction added in each correction plane [kg m].

    Returns
    -------
    ndarray of complex, shape (2,)
        :math:`R + A\,W_{applied}` [kg m], heavy-spot form, in the measuring planes.
    """
    return plan.reading + plan.influence @ _complex_pair("applied", applied)


def estimate_influence(
    prior: ArrayLike, applied: ArrayLike, change: ArrayLike
) -> tuple[NDArray[np.complex128], str]:
    r"""Influence matrix from corrections made and the reading changes they caused.

    Parameters
    ----------
    prior : array_like of complex, shape (2, 2)
        Matrix before the last run [-], kept along directions the runs did not probe.
    applied : array_like of complex, shape (R, 2)
        Corrections made, one run per row [kg m].
    change : array_like of complex, shape (R, 2)
        Reading change each run caused [kg m].

    Returns
    -------
    matrix : ndarray of complex, shape (2, 2)
        Estimated :math:`A` [-].
    method : str
        ``"least squares"`` when the runs' corrections span both planes (the matrix is
        then determined by the runs alone), else ``"rank-one update"`` of ``prior`` by the
        last run.

    Notes
    -----
    Least squares (Goodman 1964): :math:`A^T = \arg\min \lVert W A^T - \Delta R\rVert`.
    Rank-one update (Broyden 1965), last run :math:`w, \delta`:
    :math:`A = A_0 + (\delta - A_0 w)\,w^H / (w^H w)`.
    """
    a0 = np.asarray(prior, dtype=complex)
    w = np.asarray(applied, dtype=complex).reshape(-1, 2)
    d = np.asarray(change, dtype=complex).reshape(-1, 2)
    if w.shape != d.shape or not w.size:
        raise InputError("applied", applied, "must be one correction per reading change")
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(d))):
        raise InputError("applied", applied, "must be finite unbalances [kg m]")
    singular = np.linalg.svd(w, compute_uv=False)
    if singular.size == 2 and singular[1] > SINGULAR * singular[0]:
        transposed = np.linalg.lstsq(w, d, rcond=None)[0]
        return transposed.T, "least squares"
    last, seen = w[-1], d[-1]
    size = np.vdot(last, last).real
    if not size > 0:
        raise InputError("applied", applied, "the last correction must not be zero")
    return a0 + np.outer(seen - a0 @ last, last.conj()) / size, "rank-one update"


def second_reading(plan: TwoPlanePlan, applied: ArrayLike, reading: ArrayLike) -> TwoPlanePlan:
    r"""The next plan, from the reading after a correction (influence coefficients).

    Parameters
    ----------
    plan : TwoPlanePlan
        The plan before the correction.
    applied : array_like of complex, shape (2,)
        Unbalance the correction actually added per correction plane [kg m].
    reading : array_like of complex, shape (2,)
        The new reading in the measuring planes, heavy-spot form [kg m].

    Returns
    -------
    TwoPlanePlan
        The correction still needed, with the influence matrix re-estimated from every
        run so far (:func:`estimate_influence`).

    Notes
    -----
    The change :math:`\Delta R = R_{new} - R` is what the correction :math:`W` did; for a
    rigid rotor on a calibrated machine :math:`\Delta R = A_{rigid} W` and the plan is
    unchanged in method. A machine or rotor that responds differently (calibration gain
    or phase, a flexible crank) is learnt from the runs.
    """
    w = _complex_pair("applied", applied)
    new = _complex_pair("reading", reading)
    runs = np.vstack([plan.applied_runs, w[None, :]])
    changes = np.vstack([plan.reading_changes, (new - plan.reading)[None, :]])
    matrix, method = estimate_influence(plan.influence, runs, changes)
    return _plan(
        new,
        plan.measuring_planes,
        plan.correction_planes,
        plan.correction_radius,
        matrix,
        method,
        runs,
        changes,
    )


@record
class PlaneCheck(ResultMixin):
    """ISO 21940-11 check of the residual unbalance in two correction planes.

    Attributes
    ----------
    allocation : PlaneAllocation
        Split of :math:`U_{per}` to the bearings and the correction planes, the planes in
        axial order [kg m].
    tolerance : ndarray, shape (2,)
        Permissible residual per correction plane, in the order the planes were given
        [kg m].
    residual : ndarray, shape (2,)
        Magnitude of the residual per correction plane [kg m].
    verdicts : tuple of ToleranceVerdict
        One per correction plane, in the order given.
    passed : bool
        Both planes within their tolerance.
    """

    allocation: PlaneAllocation
    tolerance: NDArray[np.float64]
    residual: NDArray[np.float64]
    verdicts: tuple[ToleranceVerdict, ...]
    passed: bool


def plane_tolerances(
    grade: str | float,
    rotor_mass: float,
    speed: float,
    bearings: ArrayLike,
    center_of_mass: float,
    correction_planes: ArrayLike,
) -> tuple[PlaneAllocation, NDArray[np.float64]]:
    r"""Permissible residual unbalance of each correction plane (ISO 21940-11).

    Parameters
    ----------
    grade : str or float
        Balance quality grade, ``"G6.3"`` or its number [mm/s].
    rotor_mass : float
        Mass of the rotor balanced [kg].
    speed : float
        Largest service speed [rad/s].
    bearings : array_like, shape (2,)
        Axial positions of the two main bearings that carry the crank in service [m].
    center_of_mass : float
        Axial position of the rotor's centre of mass [m].
    correction_planes : array_like, shape (2,)
        Axial positions of the correction planes [m], in any order.

    Returns
    -------
    allocation : PlaneAllocation
        :func:`crankbalance.physics.tolerance.allocate_to_planes` with the planes in axial order.
    tolerance : ndarray, shape (2,)
        Permissible residual of each correction plane, in the order given [kg m].
    """
    a, b = np.sort(axial_pair("bearings", bearings))
    planes = axial_pair("correction_planes", correction_planes)
    order = np.argsort(planes)
    total = permissible_unbalance(grade, rotor_mass, speed)
    low, high = planes[order]
    allocation = allocate_to_planes(total, float(a), float(b), center_of_mass, low, high)
    tolerance = np.empty(2)
    tolerance[order] = (allocation.plane_1, allocation.plane_2)
    return allocation, tolerance


def iso_check(
    residual: ArrayLike,
    grade: str | float,
    rotor_mass: float,
    speed: float,
    bearings: ArrayLike,
    center_of_mass: float,
    correction_planes: ArrayLike,
) -> PlaneCheck:
    """Check a (predicted or measured) residual in two correction planes against the grade.

    Parameters
    ----------
    residual : array_like of complex, shape (2,)
        Residual unbalance per correction plane [kg m] (e.g. :func:`predicted_residual`).
    grade : str or float
        Balance quality grade, ``"G6.3"`` or its number [mm/s].
    rotor_mass : float
        Mass of the rotor balanced [kg].
    speed : float
        Largest service speed [rad/s].
    bearings : array_like, shape (2,)
        Axial positions of the main bearings [m].
    center_of_mass : float
        Axial position of the rotor's centre of mass [m].
    correction_planes : array_like, shape (2,)
        Axial positions of the correction planes [m].

    Returns
    -------
    PlaneCheck
        Tolerances [kg m], residual magnitudes [kg m], the verdict per plane.
    """
    size = np.abs(_complex_pair("residual", residual))
    allocation, tolerance = plane_tolerances(
        grade, rotor_mass, speed, bearings, center_of_mass, correction_planes
    )
    verdicts = tuple(
        check_residual(float(u), float(t)) for u, t in zip(size, tolerance, strict=True)
    )
    return PlaneCheck(
        allocation=allocation,
        tolerance=tolerance,
        residual=size,
        verdicts=verdicts,
        passed=all(v.passed for v in verdicts),
    )
