r"""Beam model of a balance shaft: section, statics, deflection and natural frequencies.

This module owns the structural model that :mod:`crankbalance.physics.balance_shaft` designs with:
a straight beam of uniform circular (solid or hollow) section on two or more point
bearings, loaded by point forces.

* :class:`ShaftSection` -- section and material (area, I, Cowper's shear coefficient).
* Statics, solved exactly by superposing closed-form beam functions (Euler-Bernoulli or
  Timoshenko, rigid or elastic bearings): :func:`beam_statics`, :func:`deflection_at`,
  :func:`bending_moment_at`, and :func:`simpson` for the integral of the deflection.
* Dynamics, a small finite-element model (cubic Hermite / Friedman-Kosmatka Timoshenko
  elements): :func:`element_matrices`, :func:`assemble`, :func:`shape_vectors`,
  :func:`natural_frequencies`.
* The input checks they share: bearings and positions on the shaft, beam theory and
  resolution (:func:`check_theory`, :func:`check_resolution`).

Everything is batched over leading axes, so many layouts are one vectorised evaluation.
Coordinates: ``x`` runs along the shaft from one end (0) to the other (``length``).
Loads, reactions and deflections are phasors in the frame turning with the shaft.

References
----------
C.-J. Kim, "Location of unbalance mass and supporting bearing for different type of
balance shaft module", Mech. Sci. 9 (2018) 259, Eqs. 6-9, 20-21.
J. M. Gere, S. P. Timoshenko, *Mechanics of Materials* (beam deflection tables).
Z. Friedman, J. B. Kosmatka, "An improved two-node Timoshenko beam finite element",
Computers & Structures 47 (1993) 473-481 (element matrices).
G. R. Cowper, "The shear coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966) 335.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_positive
from ..records import record
from ..results import ResultMixin

BeamTheory = Literal["euler-bernoulli", "timoshenko"]
BEAM_THEORIES: tuple[str, ...] = ("euler-bernoulli", "timoshenko")

#: Default number of beam elements of the frequency model (error < 0.01 % for a
#: uniform shaft, see tests/test_balance_shaft.py).
DEFAULT_ELEMENTS = 24
#: Default number of points of the deflection curve (odd: Simpson's rule).
DEFAULT_POINTS = 201


# --------------------------------------------------------------------------------------
# Section and material
# --------------------------------------------------------------------------------------


@record
class ShaftSection(ResultMixin):
    """Uniform circular shaft section and its material.

    Parameters
    ----------
    outer_diameter : float
        Outer diameter of the shaft [m].
    inner_diameter : float
        Bore diameter, 0 for a solid shaft [m].
    youngs_modulus : float
        Young's modulus E [Pa] (steel 210 GPa).
    density : float
        Density [kg/m^3] (steel 7850).
    poisson_ratio : float
        Poisson's ratio [-]; sets G = E / (2 (1 + nu)) and Cowper's shear coefficient.
    """

    outer_diameter: float
    inner_diameter: float = 0.0
    youngs_modulus: float = 210e9
    density: float = 7850.0
    poisson_ratio: float = 0.3

    def __post_init__(self) -> None:
        check_positive("outer_diameter", self.outer_diameter)
        if not (0.0 <= self.inner_diameter < self.outer_diameter):
            raise InputError(
                "inner_diameter",
                self.inner_diameter,
                f"must be >= 0 and smaller than outer_diameter ({self.outer_diameter:g} m)",
            )
        check_positive("youngs_modulus", self.youngs_modulus)
        check_positive("density", self.density)
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise InputError("poisson_ratio", self.poisson_ratio, "must lie between -1 and 0.5")

    @property
    def area(self) -> float:
        """Cross-section area A [m^2]."""
        return math.pi / 4 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> float:
        """Second moment of area I [m^4]."""
        return math.pi / 64 * (self.outer_diameter**4 - self.inner_diameter**4)

    @property
    def shear_modulus(self) -> float:
        """Shear modulus G = E / (2 (1 + nu)) [Pa]."""
        return self.youngs_modulus / (2 * (1 + self.poisson_ratio))

    @property
    def shear_coefficient(self) -> float:
        r"""Cowper's shear coefficient of a hollow circular section [-].

        .. math:: \kappa = \frac{6 (1+\nu)(1+m^2)^2}{(7+6\nu)(1+m^2)^2 + (20+12\nu) m^2},
                  \quad m = d_i / d_o
        """
        nu = self.poisson_ratio
        m2 = (self.inner_diameter / self.outer_diameter) ** 2
        return 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)

    @property
    def bending_stiffness(self) -> float:
        """E I [N m^2]."""
        return self.youngs_modulus * self.second_moment

    @property
    def shear_stiffness(self) -> float:
        """kappa G A [N]."""
        return self.shear_coefficient * self.shear_modulus * self.area

    @property
    def mass_per_length(self) -> float:
        """rho A [kg/m]."""
        return self.density * self.area

    @property
    def section_modulus(self) -> float:
        """Bending section modulus I / (d_o / 2) [m^3]."""
        return self.second_moment / (self.outer_diameter / 2)


# --------------------------------------------------------------------------------------
# Statics: exact superposition of beam functions (batched)
# --------------------------------------------------------------------------------------


def _check_on_shaft(name: str, values: NDArray, length: float) -> None:
    """Raise InputError unless every position lies on the shaft, 0 <= x <= length."""
    if values.size and not (
        np.all(np.isfinite(values)) and values.min() >= 0.0 and values.max() <= length
    ):
        bad = values[~((values >= 0.0) & (values <= length))]
        shown = float(bad.flat[0]) if bad.size else values.tolist()
        raise InputError(name, shown, f"must lie on the shaft, between 0 and {length:g} m")


def _check_bearings(positions: NDArray, length: float) -> None:
    """Raise InputError unless there are at least two bearings, all on the shaft and distinct.

    Two bearings at one point carry no moment: the statics would be singular and the
    rigid-bearing constraints of the frequency model rank-deficient (a wrong frequency).
    """
    _check_on_shaft("bearing_positions", positions, length)
    if positions.ndim == 0 or positions.shape[-1] < 2:
        raise InputError("bearing_positions", positions.tolist(), "needs at least two bearings")
    gaps = np.diff(np.sort(positions, axis=-1), axis=-1)
    if np.any(gaps <= 1e-12 * length):
        raise InputError(
            "bearing_positions", positions.tolist(), "needs each bearing at its own position"
        )


def _influence(distance: NDArray, bending_stiffness: float, shear_flexibility: float) -> NDArray:
    r"""Deflection at distance ``d`` to the right of a unit upward point force.

    .. math:: g(d) = \frac{\langle d\rangle^3}{6 EI} - \frac{\langle d\rangle}{\kappa G A}

    (plus a rigid-body line fixed by the supports). ``<d>`` is ``max(d, 0)``.
    """
    d = np.maximum(distance, 0.0)
    return d**3 / (6.0 * bending_stiffness) - d * shear_flexibility


def beam_statics(
    length: float,
    bending_stiffness: float,
    bearing_positions: ArrayLike,
    force_positions: ArrayLike,
    forces: ArrayLike,
    x: ArrayLike,
    *,
    shear_stiffness: float | None = None,
    bearing_stiffness: float | None = None,
) -> tuple[NDArray, NDArray, NDArray]:
    r"""Bearing reactions and deflection of a free beam on point supports (batched, exact).

    The beam carries point forces ``F_j`` at ``x_j`` and reactions ``R_k`` at the bearings
    ``x_k``. With all point loads ``P`` (forces and reactions) the deflection is

    .. math:: w(x) = a + b x + \sum_P P \left(\frac{\langle x - x_P\rangle^3}{6 EI}
              - \frac{\langle x - x_P\rangle}{\kappa G A}\right)

    (the shear term only for Timoshenko, ``shear_stiffness`` given). The unknowns
    ``R_k, a, b`` follow from force and moment equilibrium and ``w(x_k) = -R_k / k``
    (``k`` infinite for rigid bearings), so any number >= 2 of bearings is handled.

    Parameters
    ----------
    length : float
        Shaft length [m] (only used for checks).
    bending_stiffness : float
        E I [N m^2].
    bearing_positions : array_like, shape (..., n_bearings)
        Bearing positions along the shaft [m].
    force_positions : array_like, shape (..., n_forces)
        Positions of the applied forces [m].
    forces : array_like, shape (..., n_forces)
        Force phasors [N] (complex allowed: the phase is the angle in the rotating frame).
    x : array_like, shape (n_points,)
        Where to evaluate the deflection [m].
    shear_stiffness : float, optional
        kappa G A [N]; None for Euler-Bernoulli.
    bearing_stiffness : float, optional
        Radial stiffness of each bearing [N/m]; None for rigid bearings.

    Returns
    -------
    reactions : ndarray, shape (..., n_bearings)
        Bearing reaction phasors [N] (force of the bearing on the shaft).
    deflection : ndarray, shape (..., n_points)
        Deflection phasors at ``x`` [m].
    coefficients : ndarray, shape (..., 2)
        The rigid-body line ``a, b`` [m, -].

    References
    ----------
    Gere & Timoshenko, Mechanics of Materials (superposition, singularity functions);
    Kim (2018), Eqs. 6-9 are the two-bearing, one-load special case.
    """
    check_positive("length", length)
    check_positive("bending_stiffness", bending_stiffness)
    xb = np.asarray(bearing_positions, dtype=float)
    xf = np.asarray(force_positions, dtype=float)
    f = np.asarray(forces)
    xs = np.asarray(x, dtype=float)
    _check_bearings(xb, length)
    _check_on_shaft("force_positions", xf, length)
    ei = float(bending_stiffness)
    sf = 0.0 if shear_stiffness is None else 1.0 / float(shear_stiffness)
    cb = 0.0 if bearing_stiffness is None else 1.0 / float(bearing_stiffness)
    batch = np.broadcast_shapes(xb.shape[:-1], xf.shape[:-1], f.shape[:-1])
    xb = np.broadcast_to(xb, batch + xb.shape[-1:])
    xf = np.broadcast_to(xf, batch + xf.shape[-1:])
    f = np.broadcast_to(f, batch + f.shape[-1:]).astype(complex)
    nb = xb.shape[-1]
    n = nb + 2
    mat = np.zeros(batch + (n, n))
    rhs = np.zeros(batch + (n,), dtype=complex)
    mat[..., 0, :nb] = 1.0
    rhs[..., 0] = -f.sum(axis=-1)
    mat[..., 1, :nb] = xb
    rhs[..., 1] = -(f * xf).sum(axis=-1)
    g_bb = _influence(xb[..., :, None] - xb[..., None, :], ei, sf)  # (.., i, k)
    mat[..., 2:, :nb] = g_bb + cb * np.eye(nb)
    mat[..., 2:, nb] = 1.0
    mat[..., 2:, nb + 1] = xb
    rhs[..., 2:] = -(f[..., None, :] * _influence(xb[..., :, None] - xf[..., None, :], ei, sf)).sum(
        -1
    )
    both = np.concatenate([rhs.real[..., None], rhs.imag[..., None]], axis=-1)
    sol = np.linalg.solve(mat, both)
    sol = sol[..., 0] + 1j * sol[..., 1]
    reactions = sol[..., :nb]
    coefficients = sol[..., nb:]
    positions = np.concatenate([xf, xb], axis=-1)
    loads = np.concatenate([f, reactions], axis=-1)
    deflection = deflection_at(xs, positions, loads, coefficients, ei, sf)
    return reactions, deflection, coefficients


def _past_loads(x: ArrayLike, load_positions: NDArray) -> tuple[NDArray, NDArray]:
    """Stations along the shaft and their distances past every point load (batched).

    Parameters
    ----------
    x : array_like, shape (n,) or (..., n)
        Stations along the shaft [m]; one row is shared by every batch of loads.
    load_positions : ndarray, shape (..., n_loads)
        Positions of the point loads [m].

    Returns
    -------
    stations : ndarray, shape (..., n)
        ``x`` broadcast to the batch of loads [m].
    past : ndarray, shape (..., n, n_loads)
        ``stations - load_position`` for every station and load [m] (negative before the
        load).
    """
    x = np.asarray(x, dtype=float)
    xx = x if x.ndim > 1 else np.broadcast_to(x, load_positions.shape[:-1] + x.shape)
    return xx, xx[..., :, None] - load_positions[..., None, :]


def deflection_at(
    x: NDArray,
    load_positions: NDArray,
    loads: NDArray,
    coefficients: NDArray,
    bending_stiffness: float,
    shear_flexibility: float,
) -> NDArray:
    r"""Deflection phasors of a beam in equilibrium under point loads (batched).

    .. math:: w(x) = a + b x + \sum_P P \left(\frac{\langle x - x_P\rangle^3}{6 EI}
              - \frac{\langle x - x_P\rangle}{\kappa G A}\right)

    Parameters
    ----------
    x : ndarray, shape (n,) or (..., n)
        Stations along the shaft [m].
    load_positions : ndarray, shape (..., n_loads)
        Positions of all point loads, applied forces and bearing reactions [m].
    loads : ndarray, shape (..., n_loads)
        Load phasors [N], in equilibrium.
    coefficients : ndarray, shape (..., 2)
        Rigid-body line: offset ``a`` [m] and slope ``b`` [-] (from :func:`beam_statics`).
    bending_stiffness : float
        E I [N m^2].
    shear_flexibility : float
        1 / (kappa G A) [N^-1]; 0 for Euler-Bernoulli.

    Returns
    -------
    ndarray, shape (..., n)
        Deflection phasors at ``x`` [m].

    References
    ----------
    Gere & Timoshenko, Mechanics of Materials (superposition, singularity functions).
    """
    xx, past = _past_loads(x, load_positions)
    g = _influence(past, bending_stiffness, shear_flexibility)
    return coefficients[..., :1] + coefficients[..., 1:] * xx + (g * loads[..., None, :]).sum(-1)


def bending_moment_at(x: NDArray, load_positions: NDArray, loads: NDArray) -> NDArray:
    r"""Bending-moment phasors :math:`M(x) = \sum_{x_P < x} P (x - x_P)` (batched).

    Parameters
    ----------
    x : ndarray, shape (n,) or (..., n)
        Stations along the shaft [m].
    load_positions : ndarray, shape (..., n_loads)
        Positions of all point loads, applied forces and bearing reactions [m].
    loads : ndarray, shape (..., n_loads)
        Load phasors [N], in equilibrium.

    Returns
    -------
    ndarray, shape (..., n)
        Bending-moment phasors at ``x`` [N m].
    """
    arm = np.maximum(_past_loads(x, load_positions)[1], 0.0)
    return (arm * loads[..., None, :]).sum(-1)


def simpson(values: NDArray, spacing: float) -> NDArray:
    """Composite Simpson rule along the last axis (odd number of equally spaced samples).

    Parameters
    ----------
    values : ndarray, shape (..., n)
        Samples of the integrand, ``n`` odd and at least 3 [any unit].
    spacing : float
        Distance between the samples [m].

    Returns
    -------
    ndarray, shape (...)
        The integral [unit of ``values`` times m].
    """
    n = values.shape[-1]
    if n % 2 == 0 or n < 3:
        raise InputError("n_points", n, "must be an odd number >= 3")
    w = np.ones(n)
    w[1:-1:2] = 4.0
    w[2:-1:2] = 2.0
    return (values * w).sum(-1) * spacing / 3.0


# --------------------------------------------------------------------------------------
# Dynamics: beam finite elements (batched)
# --------------------------------------------------------------------------------------


def element_matrices(
    element_length: float, section: ShaftSection, theory: BeamTheory = "euler-bernoulli"
) -> tuple[NDArray, NDArray]:
    r"""Stiffness and mass matrix of one beam element, DOFs (w1, theta1, w2, theta2).

    Euler-Bernoulli: cubic Hermite element, consistent translational mass, no rotary
    inertia. Timoshenko: Friedman-Kosmatka element (shear parameter
    :math:`\phi = 12 EI / (\kappa G A h^2)`), translational and rotary inertia.

    .. math:: K = \frac{EI}{(1+\phi)h^3}\begin{bmatrix}12 & 6h & -12 & 6h\\
              6h & (4+\phi)h^2 & -6h & (2-\phi)h^2\\ -12 & -6h & 12 & -6h\\
              6h & (2-\phi)h^2 & -6h & (4+\phi)h^2\end{bmatrix}

    Parameters
    ----------
    element_length : float
        Element length h [m].
    section : ShaftSection
        Section and material.
    theory : {"euler-bernoulli", "timoshenko"}
        Beam theory.

    Returns
    -------
    stiffness : ndarray, shape (4, 4)
        Element stiffness matrix [N/m, N, N m].
    mass : ndarray, shape (4, 4)
        Element mass matrix [kg, kg m, kg m^2].

    References
    ----------
    Kim (2018), Eqs. 20-21 (the stiffness matrix, with e = phi); Friedman & Kosmatka (1993).
    """
    h = float(element_length)
    ei = section.bending_stiffness
    phi = 0.0 if theory == "euler-bernoulli" else 12 * ei / (section.shear_stiffness * h**2)
    k = (
        ei
        / ((1 + phi) * h**3)
        * np.array(
            [
                [12, 6 * h, -12, 6 * h],
                [6 * h, (4 + phi) * h**2, -6 * h, (2 - phi) * h**2],
                [-12, -6 * h, 12, -6 * h],
                [6 * h, (2 - phi) * h**2, -6 * h, (4 + phi) * h**2],
            ]
        )
    )
    p2 = phi * phi
    m1, m2 = 70 * p2 + 147 * phi + 78, (35 * p2 + 77 * phi + 44) / 4
    m3, m4 = 35 * p2 + 63 * phi + 27, (35 * p2 + 63 * phi + 26) / 4
    m5, m6 = (7 * p2 + 14 * phi + 8) / 4, (7 * p2 + 14 * phi + 6) / 4
    mt = (
        section.mass_per_length
        * h
        / (210 * (1 + phi) ** 2)
        * np.array(
            [
                [m1, m2 * h, m3, -m4 * h],
                [m2 * h, m5 * h**2, m4 * h, -m6 * h**2],
                [m3, m4 * h, m1, -m2 * h],
                [-m4 * h, -m6 * h**2, -m2 * h, m5 * h**2],
            ]
        )
    )
    if theory == "euler-bernoulli":
        return k, mt
    c = 15 * phi - 3
    r1, r2 = (10 * p2 + 5 * phi + 4) * h**2, (5 * p2 - 5 * phi - 1) * h**2
    mr = (
        section.density
        * section.second_moment
        / (30 * (1 + phi) ** 2 * h)
        * np.array(
            [
                [36, -c * h, -36, -c * h],
                [-c * h, r1, c * h, r2],
                [-36, c * h, 36, c * h],
                [-c * h, r2, c * h, r1],
            ]
        )
    )
    return k, mt + mr


def assemble(
    length: float, section: ShaftSection, n_elements: int, theory: BeamTheory = "euler-bernoulli"
) -> tuple[NDArray, NDArray]:
    """Global stiffness and mass matrices of a uniform free-free shaft, 2 DOFs per node.

    Parameters
    ----------
    length : float
        Shaft length [m].
    section : ShaftSection
        Section and material.
    n_elements : int
        Number of equal beam elements.
    theory : {"euler-bernoulli", "timoshenko"}
        Beam theory.

    Returns
    -------
    stiffness, mass : ndarray, shape (2 (n_elements + 1), 2 (n_elements + 1))
        Global matrices, DOFs (w, theta) per node from x = 0 [N/m, kg and mixed].

    References
    ----------
    Kim (2018), Eqs. 20-21 (global assembly of the element matrices).
    """
    ke, me = element_matrices(length / n_elements, section, theory)
    ndof = 2 * (n_elements + 1)
    k = np.zeros((ndof, ndof))
    m = np.zeros((ndof, ndof))
    for e in range(n_elements):
        s = slice(2 * e, 2 * e + 4)
        k[s, s] += ke
        m[s, s] += me
    return k, m


def shape_vectors(
    x: ArrayLike,
    length: float,
    n_elements: int,
    section: ShaftSection,
    theory: BeamTheory = "euler-bernoulli",
) -> NDArray:
    """Global interpolation vectors ``n(x)`` with ``w(x) = n(x) . u`` (batched over ``x``).

    Parameters
    ----------
    x : array_like
        Stations along the shaft [m].
    length : float
        Shaft length [m].
    n_elements : int
        Number of equal beam elements.
    section : ShaftSection
        Section and material (the shear parameter of the Timoshenko element).
    theory : {"euler-bernoulli", "timoshenko"}
        Beam theory.

    Returns
    -------
    ndarray, shape x.shape + (2 (n_elements + 1),)
        Interpolation vector of each station [-, m].

    References
    ----------
    Friedman & Kosmatka (1993) (interpolation functions; cubic Hermite for phi = 0).
    """
    xs = np.asarray(x, dtype=float)
    h = length / n_elements
    phi = (
        0.0
        if theory == "euler-bernoulli"
        else 12 * section.bending_stiffness / (section.shear_stiffness * h**2)
    )
    e = np.clip(np.floor(xs / h).astype(int), 0, n_elements - 1)
    s = xs / h - e
    s2, s3 = s * s, s * s * s
    q = 1.0 / (1.0 + phi)
    local = np.stack(
        [
            q * (2 * s3 - 3 * s2 - phi * s + 1 + phi),
            q * h * (s3 - (2 + phi / 2) * s2 + (1 + phi / 2) * s),
            -q * (2 * s3 - 3 * s2 - phi * s),
            q * h * (s3 - (1 - phi / 2) * s2 - (phi / 2) * s),
        ],
        axis=-1,
    )
    out = np.zeros(xs.shape + (2 * (n_elements + 1),))
    idx = 2 * e[..., None] + np.arange(4)
    np.put_along_axis(out, idx, local, axis=-1)
    return out


def natural_frequencies(
    length: float,
    section: ShaftSection,
    bearing_positions: ArrayLike,
    mass_positions: ArrayLike,
    masses: ArrayLike,
    *,
    bearing_stiffness: float | None = None,
    n_elements: int = DEFAULT_ELEMENTS,
    theory: BeamTheory = "euler-bernoulli",
    n_modes: int = 1,
) -> NDArray:
    r"""Lowest bending natural frequencies [Hz] of the shaft with point masses (batched).

    Uniform beam elements; point masses and bearings may sit anywhere (they act through
    the element interpolation). Rigid bearings are constraints ``n(x_k) . u = 0``,
    eliminated with a null-space basis; elastic ones add ``k n n^T``. The generalised
    problem :math:`K u = \omega^2 M u` is solved as its inverse,
    :math:`L^{-1} M L^{-T} v = \omega^{-2} v` with :math:`K = L L^T`, by a batched
    symmetric eigensolver: the lowest frequencies are then the largest eigenvalues, which
    the solver returns to the precision of the arithmetic. (Reduced by a factor of M
    instead, the lowest eigenvalue carries round-off of the machine epsilon times the
    condition of K, about 1e7 for a shaft: errors of 1e-9 that change with the processor's
    BLAS kernels.) A stiffness that is not positive definite (a shaft free to move as a
    rigid body on elastic supports of zero stiffness) falls back to the factor of M.

    Parameters
    ----------
    length : float
        Shaft length [m].
    section : ShaftSection
        Section and material.
    bearing_positions : array_like, shape (..., n_bearings)
        Bearing positions [m].
    mass_positions, masses : array_like, shape (..., n_masses)
        Positions [m] and masses [kg] of the point masses (the unbalance masses).
    bearing_stiffness : float, optional
        Radial bearing stiffness [N/m]; None for rigid bearings.
    n_elements : int
        Number of beam elements.
    theory : {"euler-bernoulli", "timoshenko"}
        Beam theory.
    n_modes : int
        Number of frequencies returned.

    Returns
    -------
    ndarray, shape (..., n_modes)
        Natural frequencies [Hz], ascending.
    """
    check_positive("length", length)
    check_theory(theory)
    check_resolution(n_elements, DEFAULT_POINTS)
    k0, m0 = assemble(length, section, n_elements, theory)
    xb = np.asarray(bearing_positions, dtype=float)
    xm = np.asarray(mass_positions, dtype=float)
    mm = np.asarray(masses, dtype=float)
    _check_bearings(xb, length)
    _check_on_shaft("mass_positions", xm, length)
    if not (np.all(np.isfinite(mm)) and (mm.size == 0 or mm.min() >= 0)):
        raise InputError("masses", mm.tolist(), "must be finite masses >= 0 kg")
    batch = np.broadcast_shapes(xb.shape[:-1], xm.shape[:-1], mm.shape[:-1])
    xb = np.broadcast_to(xb, batch + xb.shape[-1:])
    xm = np.broadcast_to(xm, batch + xm.shape[-1:])
    mm = np.broadcast_to(mm, batch + mm.shape[-1:])
    nm = shape_vectors(xm, length, n_elements, section, theory)  # (..., n_masses, ndof)
    m = m0 + np.einsum("...j,...ja,...jb->...ab", mm, nm, nm)
    nb = shape_vectors(xb, length, n_elements, section, theory)  # (..., n_bearings, ndof)
    if bearing_stiffness is None:
        q, _ = np.linalg.qr(np.swapaxes(nb, -1, -2), mode="complete")
        z = q[..., :, xb.shape[-1] :]
        zt = np.swapaxes(z, -1, -2)
        kr = zt @ k0 @ z
        mr = zt @ m @ z
    else:
        kr = k0 + float(bearing_stiffness) * np.einsum("...ja,...jb->...ab", nb, nb)
        mr = m
    try:
        # the largest eigenvalues of L^-1 M L^-T (K = L L^T) are 1/omega^2 of the lowest modes
        mu = _reduced_eigenvalues(kr, mr)[..., ::-1][..., :n_modes]
        lam = 1.0 / mu
    except np.linalg.LinAlgError:  # K singular: a rigid-body mode, omega = 0
        lam = _reduced_eigenvalues(mr, kr)[..., :n_modes]
    return np.sqrt(np.maximum(lam, 0.0)) / (2 * math.pi)


def _reduced_eigenvalues(factored: NDArray, other: NDArray) -> NDArray:
    """Eigenvalues (ascending) of ``L^-1 other L^-T`` with ``factored = L L^T`` (batched);
    raises LinAlgError when ``factored`` is not positive definite."""
    inv = np.linalg.inv(np.linalg.cholesky(factored))
    a = inv @ other @ np.swapaxes(inv, -1, -2)
    return np.linalg.eigvalsh(0.5 * (a + np.swapaxes(a, -1, -2)))


def check_theory(theory: str) -> None:
    """Refuse an unknown beam theory.

    Parameters
    ----------
    theory : str
        Beam theory, one of :data:`BEAM_THEORIES`.

    Raises
    ------
    InputError
        If ``theory`` is not one of :data:`BEAM_THEORIES`.
    """
    if theory not in BEAM_THEORIES:
        raise InputError("theory", theory, f"must be one of {', '.join(BEAM_THEORIES)}")


def check_resolution(n_elements: int, n_points: int) -> None:
    """Refuse a resolution the beam model cannot use.

    Parameters
    ----------
    n_elements : int
        Number of beam elements of the frequency model, 2 to 400.
    n_points : int
        Number of stations of the deflection curve, odd and at least 3.

    Raises
    ------
    InputError
        If either is outside what is allowed.
    """
    if not (isinstance(n_elements, (int, np.integer)) and 2 <= n_elements <= 400):
        raise InputError("n_elements", n_elements, "must be an integer between 2 and 400")
    if not (isinstance(n_points, (int, np.integer)) and n_points >= 3 and n_points % 2 == 1):
        raise InputError("n_points", n_points, "must be an odd integer >= 3")
