r"""Balance-shaft module design: where to put the unbalance masses and the support bearings.

This module owns the design side of a balance shaft; the structural model (section,
statics, finite elements, natural frequencies) is :mod:`crankbalance.physics.beam`.

* :class:`BalanceShaft` -- one design (length, section, bearings, unbalance masses, speed),
  :func:`shaft_response` -- its state variables (:class:`ShaftResponse`), and
  :func:`design_checks` -- first critical speed, bearing capacity, deflection
  (:class:`DesignChecks`).
* The unbalance the engine requires of the shaft: :func:`inline4_secondary_unbalance`,
  :func:`inline3_couple_unbalance` (Kim (2018), Eqs. 4 and 12).
* Placement studies: Kim's objective (:func:`objective`), the inline-4 study
  (:func:`inline4_study`, :func:`inline4_closed_form`), the inline-3 rotor types
  (:func:`inline3_layout`, :func:`inline3_study`, :func:`compare_inline3_types`), results
  in :class:`PlacementStudy`.

The state variables of Kim (2018) follow from the beam model for any layout: bearing
reactions (amplitude of the rotating load on each bearing) and the difference between the
most and least loaded bearing; the deflection curve, its integral (the paper's *bending
measure*) and its maximum; the largest bending stress; the fundamental bending frequency of
the shaft carrying its unbalance masses. All are batched over many layouts at once, so a
whole placement study (hundreds of positions, dozens of objective weights) is one
vectorised evaluation.

Why one module over 800 lines: the single response and the placement studies share one
batched evaluator (``_evaluate``) and one set of input checks; splitting the studies off
would make that private evaluator a public interface for one caller.

Coordinates: ``x`` runs along the shaft from one end (0) to the other (``length``).
Loads are phasors in the frame turning with the shaft: an unbalance ``U = m e`` [kg m]
at phase ``phi`` gives the force ``U Omega^2 exp(i phi)``. Deflections, reactions and
moments are phasors too; their magnitudes are the amplitudes seen over one revolution.

References
----------
C.-J. Kim, "Location of unbalance mass and supporting bearing for different type of
balance shaft module", Mech. Sci. 9 (2018) 259, Eqs. 3-13, 17-25.
"""

from __future__ import annotations

import math
from dataclasses import field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_positive
from ..records import record
from ..results import ResultMixin
from .beam import (
    DEFAULT_ELEMENTS,
    DEFAULT_POINTS,
    BeamTheory,
    ShaftSection,
    beam_statics,
    bending_moment_at,
    check_resolution,
    check_theory,
    deflection_at,
    natural_frequencies,
    simpson,
)

SecondaryMeasure = Literal["reaction-difference", "inverse-frequency"]
SECONDARY_MEASURES: tuple[str, ...] = ("reaction-difference", "inverse-frequency")
RotorType = Literal["I", "II", "III"]
ROTOR_TYPES: tuple[str, ...] = ("I", "II", "III")
HoldMode = Literal["couple", "unbalance"]
HOLD_MODES: tuple[str, ...] = ("couple", "unbalance")


# --------------------------------------------------------------------------------------
# One shaft: design and response
# --------------------------------------------------------------------------------------


def _check_positions(name: str, values: tuple[float, ...], length: float) -> None:
    for i, v in enumerate(values):
        if not (0.0 <= v <= length):
            raise InputError(
                f"{name}[{i}]", v, f"must lie on the shaft, between 0 and {length:g} m"
            )


@record
class BalanceShaft(ResultMixin):
    """A balance shaft: length, section, bearings and unbalance masses.

    Parameters
    ----------
    length : float
        Shaft length [m].
    section : ShaftSection
        Uniform section and material.
    bearing_positions : tuple of float
        Bearing positions from the shaft end [m] (at least two distinct ones).
    mass_positions : tuple of float
        Positions of the unbalance masses [m].
    unbalances : tuple of float
        First moment m e of each unbalance mass [kg m].
    speed : float
        Shaft speed [rad/s] (twice the crank speed for a second-order shaft).
    phases : tuple of float, optional
        Angular position of each unbalance mass on the shaft [rad] (default all 0).
    unbalance_radius : float
        Radius of the centre of gravity of the unbalance masses [m]; sets their mass
        ``m = U / e`` for the natural frequency.
    bearing_stiffness : float, optional
        Radial bearing stiffness [N/m]; None for rigid bearings.
    """

    length: float
    section: ShaftSection
    bearing_positions: tuple[float, ...]
    mass_positions: tuple[float, ...]
    unbalances: tuple[float, ...]
    speed: float
    phases: tuple[float, ...] = ()
    unbalance_radius: float = 0.02
    bearing_stiffness: float | None = None

    def __post_init__(self) -> None:
        check_positive("length", self.length)
        object.__setattr__(
            self, "bearing_positions", tuple(float(v) for v in self.bearing_positions)
        )
        object.__setattr__(self, "mass_positions", tuple(float(v) for v in self.mass_positions))
        object.__setattr__(self, "unbalances", tuple(float(v) for v in self.unbalances))
        if not self.phases:
            object.__setattr__(self, "phases", tuple(0.0 for _ in self.mass_positions))
        object.__setattr__(self, "phases", tuple(float(v) for v in self.phases))
        if len(self.bearing_positions) < 2 or len(set(self.bearing_positions)) < len(
            self.bearing_positions
        ):
            raise InputError(
                "bearing_positions",
                self.bearing_positions,
                "needs at least two bearings, each at its own position",
            )
        _check_positions("bearing_positions", self.bearing_positions, self.length)
        if not self.mass_positions:
            raise InputError(
                "mass_positions", self.mass_positions, "needs at least one unbalance mass"
            )
        _check_positions("mass_positions", self.mass_positions, self.length)
        if len(self.unbalances) != len(self.mass_positions):
            raise InputError(
                "unbalances",
                self.unbalances,
                f"needs one value per mass ({len(self.mass_positions)})",
            )
        if len(self.phases) != len(self.mass_positions):
            raise InputError(
                "phases", self.phases, f"needs one value per mass ({len(self.mass_positions)})"
            )
        for i, u in enumerate(self.unbalances):
            if not (0.0 <= u < math.inf):
                raise InputError(f"unbalances[{i}]", u, "must be a finite first moment >= 0 kg*m")
        for i, p in enumerate(self.phases):
            if not math.isfinite(p):
                raise InputError(f"phases[{i}]", p, "must be a finite angle in rad")
        check_positive("speed", self.speed)
        check_positive("unbalance_radius", self.unbalance_radius)
        if self.bearing_stiffness is not None:
            check_positive("bearing_stiffness", self.bearing_stiffness)


@record
class ShaftResponse(ResultMixin):
    """State variables of one balance shaft at its speed.

    Attributes
    ----------
    reactions : ndarray
        Amplitude of the rotating load on each bearing [N].
    reaction_phases : ndarray
        Phase of each bearing load in the shaft frame [rad].
    reaction_difference : float
        Largest minus smallest bearing-load amplitude [N] (Kim (2018), Eq. 19 for two bearings).
    x : ndarray
        Stations of the deflection curve [m].
    deflection : ndarray
        Deflection amplitude at ``x`` [m].
    bending_measure : float
        Integral of the deflection amplitude over the shaft [m^2] (Kim (2018), Eq. 9).
    max_deflection : float
        Largest deflection amplitude [m].
    max_moment : float
        Largest bending-moment amplitude [N m].
    max_stress : float
        Largest bending stress M / Z [Pa].
    first_frequency : float
        Fundamental bending frequency with the unbalance masses [Hz].
    first_critical_speed : float
        The same as a shaft speed [rad/s] (no gyroscopic effect).
    speed : float
        Shaft speed of the evaluation [rad/s].
    """

    reactions: NDArray
    reaction_phases: NDArray
    reaction_difference: float
    x: NDArray
    deflection: NDArray
    bending_measure: float
    max_deflection: float
    max_moment: float
    max_stress: float
    first_frequency: float
    first_critical_speed: float
    speed: float

    def bearing_forces(self, n_angles: int = 73) -> tuple[NDArray, NDArray]:
        """Component of each bearing load along a fixed direction over one revolution.

        Returns ``(angle [rad], force [N] of shape (n_angles, n_bearings))``.
        """
        angle = np.linspace(0.0, 2 * math.pi, n_angles)
        force = self.reactions[None, :] * np.cos(angle[:, None] + self.reaction_phases[None, :])
        return angle, force


@record
class _Evaluation:
    reactions: NDArray  # complex (..., nb)
    x: NDArray
    deflection: NDArray  # complex (..., G)
    bending_measure: NDArray
    max_deflection: NDArray
    max_moment: NDArray
    frequency: NDArray | None


def _evaluate(
    length: float,
    section: ShaftSection,
    bearing_positions: NDArray,
    mass_positions: NDArray,
    unbalances: NDArray,
    speed: float,
    unbalance_radius: float,
    bearing_stiffness: float | None,
    theory: BeamTheory,
    n_elements: int,
    n_points: int,
    frequency: bool,
) -> _Evaluation:
    """All state variables for a batch of layouts (unbalances complex: U exp(i phi))."""
    x = np.linspace(0.0, length, n_points)
    forces = unbalances * speed**2
    shear = section.shear_stiffness if theory == "timoshenko" else None
    reactions, w, coef = beam_statics(
        length,
        section.bending_stiffness,
        bearing_positions,
        mass_positions,
        forces,
        x,
        shear_stiffness=shear,
        bearing_stiffness=bearing_stiffness,
    )
    batch = reactions.shape[:-1]
    positions = np.concatenate(
        [
            np.broadcast_to(mass_positions, batch + mass_positions.shape[-1:]),
            np.broadcast_to(bearing_positions, batch + bearing_positions.shape[-1:]),
        ],
        axis=-1,
    )
    loads = np.concatenate([np.broadcast_to(forces, batch + forces.shape[-1:]), reactions], axis=-1)
    amplitude = np.abs(w)
    bending = simpson(amplitude, length / (n_points - 1))
    sf = 0.0 if shear is None else 1.0 / shear
    w_points = deflection_at(positions, positions, loads, coef, section.bending_stiffness, sf)
    max_w = np.maximum(amplitude.max(-1), np.abs(w_points).max(-1))
    # |M| is convex between load points (M is linear there), so its maximum is at a load point
    max_m = np.abs(bending_moment_at(positions, positions, loads)).max(-1)
    freq = None
    if frequency:
        masses = np.abs(unbalances) / unbalance_radius
        freq = natural_frequencies(
            length,
            section,
            bearing_positions,
            mass_positions,
            masses,
            bearing_stiffness=bearing_stiffness,
            n_elements=n_elements,
            theory=theory,
        )[..., 0]
    return _Evaluation(reactions, x, w, bending, max_w, max_m, freq)


def shaft_response(
    shaft: BalanceShaft,
    *,
    theory: BeamTheory = "euler-bernoulli",
    n_elements: int = DEFAULT_ELEMENTS,
    n_points: int = DEFAULT_POINTS,
) -> ShaftResponse:
    """State variables of one balance shaft: reactions, deflection, stress, first frequency.

    Parameters
    ----------
    shaft : BalanceShaft
        The design.
    theory : {"euler-bernoulli", "timoshenko"}
        Beam theory (Timoshenko adds shear deflection and rotary inertia: use it for
        short, stocky shafts, length/diameter below about 10).
    n_elements : int
        Elements of the frequency model.
    n_points : int
        Stations of the deflection curve (odd).

    Returns
    -------
    ShaftResponse
    """
    check_theory(theory)
    check_resolution(n_elements, n_points)
    u = np.array(shaft.unbalances) * np.exp(1j * np.array(shaft.phases))
    ev = _evaluate(
        shaft.length,
        shaft.section,
        np.array(shaft.bearing_positions),
        np.array(shaft.mass_positions),
        u,
        shaft.speed,
        shaft.unbalance_radius,
        shaft.bearing_stiffness,
        theory,
        n_elements,
        n_points,
        True,
    )
    amp = np.abs(ev.reactions)
    assert ev.frequency is not None
    f1 = float(ev.frequency)
    return ShaftResponse(
        reactions=amp,
        reaction_phases=np.where(amp > 0, np.angle(ev.reactions), 0.0),
        reaction_difference=float(amp.max() - amp.min()),
        x=ev.x,
        deflection=np.abs(ev.deflection),
        bending_measure=float(ev.bending_measure),
        max_deflection=float(ev.max_deflection),
        max_moment=float(ev.max_moment),
        max_stress=float(ev.max_moment / shaft.section.section_modulus),
        first_frequency=f1,
        first_critical_speed=2 * math.pi * f1,
        speed=shaft.speed,
    )


# --------------------------------------------------------------------------------------
# Design checks
# --------------------------------------------------------------------------------------


@record
class DesignChecks(ResultMixin):
    """Pass/fail of the checks a designer needs, with the numbers behind them.

    Attributes
    ----------
    critical_speed_ratio : float
        First critical speed over the maximum shaft speed [-].
    required_ratio : float
        1 + required separation margin [-].
    critical_speed_ok : bool
    max_bearing_load : float
        Largest bearing-load amplitude at the maximum speed [N].
    bearing_capacity : float or None
        Allowed bearing load [N]; None if not checked.
    bearing_ok : bool
    max_deflection : float
        Largest deflection at the maximum speed [m].
    deflection_limit : float or None
        Allowed deflection [m]; None if not checked.
    deflection_ok : bool
    dynamic_amplification : float
        Single-mode estimate ``1 / |1 - (Omega / omega_1)^2|`` of how much the whirling
        shaft exceeds the static (rotating-frame) deflection [-].
    ok : bool
        All checks pass.
    """

    critical_speed_ratio: float
    required_ratio: float
    critical_speed_ok: bool
    max_bearing_load: float
    bearing_capacity: float | None
    bearing_ok: bool
    max_deflection: float
    deflection_limit: float | None
    deflection_ok: bool
    dynamic_amplification: float
    ok: bool = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "ok", self.critical_speed_ok and self.bearing_ok and self.deflection_ok
        )


def design_checks(
    response: ShaftResponse,
    *,
    max_speed: float | None = None,
    critical_speed_margin: float = 0.25,
    bearing_capacity: float | None = None,
    deflection_limit: float | None = None,
) -> DesignChecks:
    r"""Check a shaft response against the first critical speed, bearing capacity and deflection.

    Loads and deflections scale with the square of speed, so they are taken to
    ``max_speed`` (default: the speed of the response).

    .. math:: \omega_1 \ge (1 + \text{margin})\,\Omega_\max, \quad
              \max_k |R_k| \le C, \quad \max_x |w| \le w_\text{allowed}

    Parameters
    ----------
    response : ShaftResponse
        Result of :func:`shaft_response`.
    max_speed : float, optional
        Maximum shaft speed [rad/s].
    critical_speed_margin : float
        Required separation of the first critical speed above the maximum speed [-]
        (0.25: 25 %).
    bearing_capacity : float, optional
        Allowed radial load of one bearing [N].
    deflection_limit : float, optional
        Allowed deflection [m].

    Returns
    -------
    DesignChecks
        Pass/fail of each check with the numbers behind it.
    """
    speed = response.speed if max_speed is None else check_positive("max_speed", max_speed)
    if not (0.0 <= critical_speed_margin < math.inf):
        raise InputError(
            "critical_speed_margin", critical_speed_margin, "must be a finite number >= 0"
        )
    if bearing_capacity is not None:
        check_positive("bearing_capacity", bearing_capacity)
    if deflection_limit is not None:
        check_positive("deflection_limit", deflection_limit)
    scale = (speed / response.speed) ** 2
    ratio = response.first_critical_speed / speed
    load = float(response.reactions.max() * scale)
    deflection = response.max_deflection * scale
    # 1 / |1 - 1/ratio^2|, written so that a ratio near zero does not divide by zero
    detuning = abs(ratio**2 - 1.0)
    amplification = ratio**2 / detuning if detuning > 1e-12 * ratio**2 else 1e12
    return DesignChecks(
        critical_speed_ratio=ratio,
        required_ratio=1.0 + critical_speed_margin,
        critical_speed_ok=bool(ratio >= 1.0 + critical_speed_margin),
        max_bearing_load=load,
        bearing_capacity=bearing_capacity,
        bearing_ok=bool(bearing_capacity is None or load <= bearing_capacity),
        max_deflection=deflection,
        deflection_limit=deflection_limit,
        deflection_ok=bool(deflection_limit is None or deflection <= deflection_limit),
        dynamic_amplification=amplification,
    )


# --------------------------------------------------------------------------------------
# Required unbalance from the engine (Kim (2018), Eqs. 4 and 12)
# --------------------------------------------------------------------------------------


def inline4_secondary_unbalance(
    reciprocating_mass: float, crank_radius: float, rod_length: float
) -> float:
    r"""First moment each shaft of a counter-rotating pair needs for an inline-4 [kg m].

    .. math:: m_b r_b = \frac{m_p r^2}{2 l}

    The shafts turn at twice crank speed; with first-order-series kinematics the four
    cylinders' second-order force is :math:`4 m_p r^2 \omega^2 / l`.

    Parameters
    ----------
    reciprocating_mass : float
        Reciprocating mass per cylinder m_p [kg].
    crank_radius : float
        Crank radius r [m].
    rod_length : float
        Conrod length l [m].

    Returns
    -------
    float
        First moment m_b r_b of each shaft [kg m].

    References
    ----------
    Kim (2018), Eqs. 2-4.
    """
    check_positive("reciprocating_mass", reciprocating_mass)
    check_positive("crank_radius", crank_radius)
    check_positive("rod_length", rod_length)
    return reciprocating_mass * crank_radius**2 / (2 * rod_length)


def inline3_couple_unbalance(
    reciprocating_mass: float, crank_radius: float, cylinder_pitch: float, shaft_length: float
) -> float:
    r"""First moment of each of the two opposed masses of an inline-3 primary shaft [kg m].

    One shaft turning at crank speed cancels half the primary couple
    (:math:`\tfrac{\sqrt3}{2} m_p r \omega^2 a`, the other half is left to the crank
    counterweights); with its masses ``shaft_length`` apart:

    .. math:: m_B r_B = \frac{\sqrt3\, m_p r a}{2 l_3}

    Parameters
    ----------
    reciprocating_mass : float
        Reciprocating mass per cylinder m_p [kg].
    crank_radius : float
        Crank radius r [m].
    cylinder_pitch : float
        Distance between neighbouring cylinder axes a [m].
    shaft_length : float
        Distance between the two shaft masses l_3 [m].

    Returns
    -------
    float
        First moment m_B r_B of each of the two masses [kg m].

    References
    ----------
    Kim (2018), Eqs. 10-12 (the square root is lost in the text extraction).
    """
    check_positive("reciprocating_mass", reciprocating_mass)
    check_positive("crank_radius", crank_radius)
    check_positive("cylinder_pitch", cylinder_pitch)
    check_positive("shaft_length", shaft_length)
    return math.sqrt(3) * reciprocating_mass * crank_radius * cylinder_pitch / (2 * shaft_length)


# --------------------------------------------------------------------------------------
# Placement studies (Kim (2018), Sect. 3)
# --------------------------------------------------------------------------------------


def inline4_closed_form(position: ArrayLike) -> tuple[NDArray, NDArray]:
    r"""Shapes of the inline-4 state variables for a load at :math:`\xi = x/L` on end bearings.

    .. math:: A \propto \int_0^L w\,dx = \frac{W L^4}{24 EI}\,\xi(1-\xi)\,[1 + \xi(1-\xi)],
              \qquad B = \frac{|f_A - f_B|}{W} = |1 - 2\xi|

    Parameters
    ----------
    position : array_like
        Load position as a fraction of the bearing distance, :math:`\xi = x / L` [-].

    Returns
    -------
    bending : ndarray
        Bending measure in units of its scale, :math:`A / (W L^4 / 24 EI)` [-].
    reaction_difference : ndarray
        Difference of the two bearing reactions per unit load, B [-].

    References
    ----------
    Kim (2018), Eqs. 6-9 and 19; docs/references.md, Kim (2018).
    """
    xi = np.asarray(position, dtype=float)
    return xi * (1 - xi) * (1 + xi * (1 - xi)), np.abs(1 - 2 * xi)


@record
class PlacementStudy(ResultMixin):
    """State variables, normalised objective and optimum along one design variable.

    Attributes
    ----------
    case : str
        ``"inline4"`` or ``"inline3-I"``, ``"inline3-II"``, ``"inline3-III"``.
    design_variable : str
        What ``positions`` is.
    positions : ndarray
        Design variable as a fraction of the shaft length [-].
    bearing_positions, mass_positions : ndarray
        Layout at each design point [m], shape (n, 2).
    unbalances : ndarray
        First moment of each mass at each design point [kg m], shape (n, n_masses).
    reactions : ndarray
        Bearing-load amplitudes [N], shape (n, n_bearings).
    reaction_difference : ndarray
        Largest minus smallest bearing load [N].
    bending_measure : ndarray
        Integral of the deflection amplitude [m^2].
    max_deflection : ndarray
        [m]
    max_stress : ndarray
        [Pa]
    first_frequency : ndarray
        Fundamental bending frequency with the masses [Hz].
    secondary : str
        Which measure is B: ``"reaction-difference"`` or ``"inverse-frequency"``.
    normalised_bending, normalised_secondary : ndarray
        A / max A and B / max B over the design range [-].
    weight : float
        w of the objective [-].
    objective : ndarray
        J = (A/max A)^2 + w (B/max B)^2 along the design variable [-].
    optimum_position : float
        Minimiser of J (refined by a parabola through the three best points) [-].
    optimum_objective : float
        J there [-].
    weights : ndarray
        The swept weights w [-].
    optimum_positions : ndarray
        Optimum position for each swept weight [-].
    """

    case: str
    design_variable: str
    positions: NDArray
    bearing_positions: NDArray
    mass_positions: NDArray
    unbalances: NDArray
    reactions: NDArray
    reaction_difference: NDArray
    bending_measure: NDArray
    max_deflection: NDArray
    max_stress: NDArray
    first_frequency: NDArray
    secondary: str
    normalised_bending: NDArray
    normalised_secondary: NDArray
    weight: float
    objective: NDArray
    optimum_position: float
    optimum_objective: float
    weights: NDArray
    optimum_positions: NDArray


def objective(
    normalised_bending: ArrayLike, normalised_secondary: ArrayLike, weight: ArrayLike
) -> NDArray:
    r"""Kim's objective for one or many weights (weights along a new leading axis).

    .. math:: J = \left(\frac{A}{\operatorname{norm} A}\right)^2
              + w \left(\frac{B}{\operatorname{norm} B}\right)^2

    Parameters
    ----------
    normalised_bending : array_like, shape (n,)
        A / max A along the design variable [-].
    normalised_secondary : array_like, shape (n,)
        B / max B along the design variable [-].
    weight : array_like
        One weight w [-], or weights of shape (n_weights,).

    Returns
    -------
    ndarray, shape (n,) or (n_weights, n)
        The objective J [-].

    References
    ----------
    Kim (2018), Eqs. 17 and 23, as checked in docs/references.md (norm = maximum over the
    design range).
    """
    a = np.asarray(normalised_bending, dtype=float)
    b = np.asarray(normalised_secondary, dtype=float)
    w = np.asarray(weight, dtype=float)
    return a**2 + w[..., None] * b**2 if w.ndim else a**2 + w * b**2


def normalise(values: NDArray) -> NDArray:
    """Divide by the largest value over the design range (zero stays zero, never NaN).

    Parameters
    ----------
    values : ndarray
        Values of a state variable over the design range [any unit, >= 0].

    Returns
    -------
    ndarray
        ``values / max(values)`` [-], zeros if the maximum is not positive.

    References
    ----------
    Kim (2018), Eqs. 17 and 23 (the norm of A and B).
    """
    top = float(np.max(values))
    return values / top if top > 0 else np.zeros_like(values)


def minimise_on_grid(positions: NDArray, values: NDArray) -> tuple[NDArray, NDArray]:
    """Minimum of sampled curves (last axis) refined by a parabola through three points.

    Ties between equal minima (a mirror-symmetric shaft has two) go to the larger
    position, the paper's convention (67 % rather than 33 %).

    Parameters
    ----------
    positions : ndarray, shape (n,)
        Design points, strictly increasing [-].
    values : ndarray, shape (n,) or (m, n)
        Sampled curve(s) along the last axis [any unit].

    Returns
    -------
    position : ndarray, shape values.shape[:-1]
        Minimiser of each curve [-].
    value : ndarray, shape values.shape[:-1]
        The minimum [unit of ``values``].
    """
    v = np.atleast_2d(values)
    n = v.shape[-1]
    best = v.min(-1, keepdims=True)
    tol = 1e-9 * np.maximum(np.abs(best), 1e-300)
    idx = n - 1 - np.argmax((v <= best + tol)[..., ::-1], axis=-1)
    inner = np.clip(idx, 1, n - 2)
    x0, x1, x2 = positions[inner - 1], positions[inner], positions[inner + 1]
    rows = np.arange(v.shape[0])
    y0, y1, y2 = v[rows, inner - 1], v[rows, inner], v[rows, inner + 1]
    den = (x0 - x1) * (x0 - x2) * (x1 - x2)
    a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / np.where(den == 0, 1, den)
    b = (x2**2 * (y0 - y1) + x1**2 * (y2 - y0) + x0**2 * (y1 - y2)) / np.where(den == 0, 1, den)
    c = y1 - a * x1**2 - b * x1
    interior = (idx == inner) & (a > 0)
    xv = np.where(interior, -b / np.where(a > 0, 2 * a, 1), positions[idx])
    xv = np.clip(xv, x0, x2)
    yv = np.where(interior, a * xv**2 + b * xv + c, v[rows, idx])
    shape = values.shape[:-1]
    return xv.reshape(shape), yv.reshape(shape)


def _check_study_inputs(
    unbalance: float,
    speed: float,
    length: float,
    positions: NDArray,
    weights: NDArray,
    weight: float,
    theory: str,
    secondary: str,
    n_elements: int,
    n_points: int,
) -> None:
    check_positive("unbalance", unbalance)
    check_positive("speed", speed)
    check_positive("length", length)
    check_theory(theory)
    check_resolution(n_elements, n_points)
    if secondary not in SECONDARY_MEASURES:
        raise InputError("secondary", secondary, f"must be one of {', '.join(SECONDARY_MEASURES)}")
    if positions.ndim != 1 or positions.size < 3:
        raise InputError("positions", positions.tolist(), "needs at least 3 design points")
    if not (np.all(np.isfinite(positions)) and positions.min() >= 0 and positions.max() <= 1):
        raise InputError(
            "positions", positions.tolist(), "must be fractions of the length in [0, 1]"
        )
    if np.any(np.diff(positions) <= 0):
        raise InputError("positions", positions.tolist(), "must be strictly increasing")
    if not (0.0 <= weight < math.inf):
        raise InputError("weight", weight, "must be a finite number >= 0")
    if (
        weights.ndim != 1
        or weights.size < 1
        or not np.all(np.isfinite(weights))
        or weights.min() < 0
    ):
        raise InputError("weights", weights.tolist(), "must be finite numbers >= 0")


def _study(
    case: str,
    design_variable: str,
    positions: NDArray,
    bearings: NDArray,
    masses: NDArray,
    unbalances: NDArray,
    speed: float,
    length: float,
    section: ShaftSection,
    unbalance_radius: float,
    bearing_stiffness: float | None,
    theory: BeamTheory,
    secondary: SecondaryMeasure,
    weight: float,
    weights: NDArray,
    n_elements: int,
    n_points: int,
) -> PlacementStudy:
    ev = _evaluate(
        length,
        section,
        bearings,
        masses,
        unbalances,
        speed,
        unbalance_radius,
        bearing_stiffness,
        theory,
        n_elements,
        n_points,
        True,
    )
    assert ev.frequency is not None
    amp = np.abs(ev.reactions)
    difference = amp.max(-1) - amp.min(-1)
    a_norm = normalise(ev.bending_measure)
    if secondary == "reaction-difference":
        b_norm = normalise(difference)
    else:
        b_norm = normalise(1.0 / ev.frequency)
    j = objective(a_norm, b_norm, weight)
    opt_x, opt_j = minimise_on_grid(positions, j)
    opt_xs, _ = minimise_on_grid(positions, objective(a_norm, b_norm, weights))
    return PlacementStudy(
        case=case,
        design_variable=design_variable,
        positions=positions,
        bearing_positions=np.broadcast_to(bearings, positions.shape + bearings.shape[-1:]).copy(),
        mass_positions=np.broadcast_to(masses, positions.shape + masses.shape[-1:]).copy(),
        unbalances=np.abs(np.broadcast_to(unbalances, positions.shape + unbalances.shape[-1:])),
        reactions=amp,
        reaction_difference=difference,
        bending_measure=ev.bending_measure,
        max_deflection=ev.max_deflection,
        max_stress=ev.max_moment / section.section_modulus,
        first_frequency=ev.frequency,
        secondary=secondary,
        normalised_bending=a_norm,
        normalised_secondary=b_norm,
        weight=float(weight),
        objective=j,
        optimum_position=float(opt_x),
        optimum_objective=float(opt_j),
        weights=weights,
        optimum_positions=np.asarray(opt_xs),
    )


def default_weights() -> NDArray:
    """The default weight sweep: 20 values of w from 0.2 to 4.0.

    Returns
    -------
    ndarray, shape (20,)
        Weights w of the objective [-].
    """
    return np.linspace(0.2, 4.0, 20)


def inline4_study(
    unbalance: float,
    speed: float,
    length: float,
    section: ShaftSection,
    *,
    weight: float = 2.0,
    positions: ArrayLike | None = None,
    weights: ArrayLike | None = None,
    unbalance_radius: float = 0.02,
    bearing_stiffness: float | None = None,
    theory: BeamTheory = "euler-bernoulli",
    secondary: SecondaryMeasure = "reaction-difference",
    n_elements: int = DEFAULT_ELEMENTS,
    n_points: int = DEFAULT_POINTS,
) -> PlacementStudy:
    r"""Where to put the unbalance mass of an inline-4 second-order balance shaft.

    Bearings at both shaft ends, one unbalance mass at :math:`x = \xi L`; the design
    variable :math:`\xi` is swept over ``positions`` and

    .. math:: J(\xi) = \left(\frac{A}{\max A}\right)^2 + w\left(\frac{B}{\max B}\right)^2

    with A the integral of the deflection and B the difference of the two bearing
    reactions (or the inverse first natural frequency, ``secondary="inverse-frequency"``).

    Parameters
    ----------
    unbalance : float
        First moment m e the shaft must carry [kg m]
        (:func:`inline4_secondary_unbalance`).
    speed : float
        Shaft speed [rad/s] (twice crank speed).
    length : float
        Distance between the two bearings = shaft length [m].
    section : ShaftSection
        Shaft section and material.
    weight : float
        w of the objective [-].
    positions : array_like, optional
        Design points as fractions of the length [-] (default 200 points over [0, 1]).
    weights : array_like, optional
        Weights w of the sweep [-] (default :func:`default_weights`).
    unbalance_radius : float
        Centre-of-gravity radius of the unbalance mass [m] (its mass for the frequency).
    bearing_stiffness : float, optional
        Radial bearing stiffness [N/m]; None for rigid.
    theory : {"euler-bernoulli", "timoshenko"}
        Beam theory.
    secondary : {"reaction-difference", "inverse-frequency"}
        What B is: the difference of the bearing reactions [N] or the inverse first
        natural frequency [s].
    n_elements, n_points : int
        Resolution of the frequency model and of the deflection curve.

    Returns
    -------
    PlacementStudy

    References
    ----------
    Kim (2018), Sect. 3.1, Eqs. 17-19, Figs. 6-7 (optimum 67 % with w = 2).
    """
    xi = np.linspace(0.0, 1.0, 200) if positions is None else np.asarray(positions, dtype=float)
    ws = default_weights() if weights is None else np.atleast_1d(np.asarray(weights, dtype=float))
    _check_study_inputs(
        unbalance, speed, length, xi, ws, weight, theory, secondary, n_elements, n_points
    )
    check_positive("unbalance_radius", unbalance_radius)
    bearings = np.array([0.0, length])
    masses = (xi * length)[:, None]
    u = np.full((xi.size, 1), float(unbalance), dtype=complex)
    return _study(
        "inline4",
        "unbalance-mass position x / L (bearings at both ends)",
        xi,
        bearings,
        masses,
        u,
        speed,
        length,
        section,
        unbalance_radius,
        bearing_stiffness,
        theory,
        secondary,
        weight,
        ws,
        n_elements,
        n_points,
    )


def inline3_layout(
    rotor_type: RotorType, positions: ArrayLike, length: float, bearing_offset: float
) -> tuple[NDArray, NDArray]:
    """Bearing and mass positions [m] of the three inline-3 rotor types (assumed geometry).

    The design variable ``z`` (fraction of the length) is the position of the second
    unbalance mass, as in Kim (2018), Figs. 8-9; ``o = bearing_offset`` [m].

    * ``"I"``   bearing - mass - mass - bearing: bearings at 0 and L, masses at o and z
      (both masses between the bearings).
    * ``"II"``  mass - bearing - bearing - mass: masses at 0 and z, bearings at o and
      z - o (both masses overhung by o; the second bearing follows the second mass).
    * ``"III"`` mass - bearing - mass - bearing: mass at 0, bearing at o (the paper's
      y, "near the first unbalance mass"), mass at z, bearing at L (Kim (2018), Fig. 5, "one-end
      weight"; the paper's representative type).

    The paper does not give these dimensions (Fig. 4 is missing from the text); they are
    this module's assumptions, see docs/balance_shaft.md.

    Parameters
    ----------
    rotor_type : {"I", "II", "III"}
        Order of masses and bearings.
    positions : array_like, shape (n,)
        Second mass position z as a fraction of the length [-].
    length : float
        Shaft length L [m].
    bearing_offset : float
        Distance o between a bearing and the neighbouring mass [m].

    Returns
    -------
    bearings : ndarray, shape (n, 2)
        Bearing positions [m].
    masses : ndarray, shape (n, 2)
        Mass positions [m].

    References
    ----------
    Kim (2018), Sect. 3.2, Figs. 5 and 8-9.
    """
    if rotor_type not in ROTOR_TYPES:
        raise InputError("rotor_type", rotor_type, f"must be one of {', '.join(ROTOR_TYPES)}")
    z = np.asarray(positions, dtype=float) * length
    o = np.full_like(z, bearing_offset)
    zero, end = np.zeros_like(z), np.full_like(z, length)
    if rotor_type == "I":
        bearings, masses = np.stack([zero, end], -1), np.stack([o, z], -1)
    elif rotor_type == "II":
        bearings, masses = np.stack([o, z - o], -1), np.stack([zero, z], -1)
    else:
        bearings, masses = np.stack([o, end], -1), np.stack([zero, z], -1)
    return bearings, masses


def inline3_study(
    rotor_type: RotorType,
    unbalance: float,
    speed: float,
    length: float,
    section: ShaftSection,
    *,
    weight: float = 2.0,
    positions: ArrayLike | None = None,
    weights: ArrayLike | None = None,
    bearing_offset: float | None = None,
    hold: HoldMode = "couple",
    unbalance_radius: float = 0.02,
    bearing_stiffness: float | None = None,
    theory: BeamTheory = "euler-bernoulli",
    secondary: SecondaryMeasure = "inverse-frequency",
    n_elements: int = DEFAULT_ELEMENTS,
    n_points: int = DEFAULT_POINTS,
) -> PlacementStudy:
    r"""Where to put the second unbalance mass of an inline-3 primary-couple balance shaft.

    Two opposed unbalance masses (phases 0 and :math:`\pi`) make the couple; the layout of
    masses and bearings is one of the three rotor types of :func:`inline3_layout`. The
    second mass position ``z`` is swept and

    .. math:: J(z) = \left(\frac{A}{\max A}\right)^2 + w\left(\frac{B}{\max B}\right)^2,
              \quad B = 1 / f_1

    with A the integral of the deflection amplitude and f1 the fundamental bending
    frequency of the shaft with its masses (FE model).

    Parameters
    ----------
    rotor_type : {"I", "II", "III"}
        Order of masses and bearings.
    unbalance : float
        First moment of each mass when the masses are ``length`` apart [kg m]
        (Kim (2018), Eq. 12, :func:`inline3_couple_unbalance`); the couple to make is
        ``unbalance * length * speed**2``.
    speed : float
        Shaft speed [rad/s] (crank speed for the primary couple).
    length : float
        Shaft length [m].
    section : ShaftSection
        Shaft section and material.
    weight : float
        w of the objective [-].
    positions : array_like, optional
        z / L design points [-] (default 200 points over [0.3, 1]).
    weights : array_like, optional
        Weights w of the sweep [-] (default :func:`default_weights`).
    bearing_offset : float, optional
        Distance o between a bearing and the neighbouring mass [m] (default 0.1 L).
    hold : {"couple", "unbalance"}
        ``"couple"`` (default, physical): each mass carries ``unbalance * length /
        spacing`` so the couple stays the one required; ``"unbalance"``: each mass keeps
        ``unbalance`` as the paper's "same unbalance quantity" (the couple then varies).
    unbalance_radius, bearing_stiffness, theory, secondary, n_elements, n_points
        As :func:`inline4_study`: centre-of-gravity radius of the masses [m], radial
        bearing stiffness [N/m] (None: rigid), beam theory, measure B, resolution.

    Returns
    -------
    PlacementStudy

    References
    ----------
    Kim (2018), Sect. 3.2, Eqs. 10-13, 23-25, Figs. 8-9 (the paper's 69 % is not reproducible,
    see docs/balance_shaft.md).
    """
    z = np.linspace(0.3, 1.0, 200) if positions is None else np.asarray(positions, dtype=float)
    ws = default_weights() if weights is None else np.atleast_1d(np.asarray(weights, dtype=float))
    _check_study_inputs(
        unbalance, speed, length, z, ws, weight, theory, secondary, n_elements, n_points
    )
    check_positive("unbalance_radius", unbalance_radius)
    if hold not in HOLD_MODES:
        raise InputError("hold", hold, f"must be one of {', '.join(HOLD_MODES)}")
    o = 0.1 * length if bearing_offset is None else float(bearing_offset)
    if not (0.0 <= o < 0.5 * length):
        raise InputError("bearing_offset", bearing_offset, f"must lie in [0, {0.5 * length:g}) m")
    bearings, masses = inline3_layout(rotor_type, z, length, o)
    spacing = masses[:, 1] - masses[:, 0]
    lowest = {"I": o, "II": 2 * o, "III": o}[rotor_type] / length
    if z.min() <= lowest + 1e-9:
        raise InputError(
            "positions",
            float(z.min()),
            f"type {rotor_type} needs every z / L > {lowest:g} (keeps its order of "
            "masses and bearings)",
        )
    if hold == "couple":
        per_mass = unbalance * length / spacing
    else:
        per_mass = np.full_like(spacing, unbalance)
    u = per_mass[:, None] * np.array([1.0, -1.0])
    return _study(
        f"inline3-{rotor_type}",
        f"second unbalance-mass position z / L (type {rotor_type})",
        z,
        bearings,
        masses,
        u.astype(complex),
        speed,
        length,
        section,
        unbalance_radius,
        bearing_stiffness,
        theory,
        secondary,
        weight,
        ws,
        n_elements,
        n_points,
    )


def compare_inline3_types(
    unbalance: float, speed: float, length: float, section: ShaftSection, **options: object
) -> dict[str, PlacementStudy]:
    """Run :func:`inline3_study` for the three rotor types with the same options.

    Parameters
    ----------
    unbalance : float
        First moment of each mass when the masses are ``length`` apart [kg m].
    speed : float
        Shaft speed [rad/s].
    length : float
        Shaft length [m].
    section : ShaftSection
        Shaft section and material.
    **options
        Keyword options of :func:`inline3_study`.

    Returns
    -------
    dict of str to PlacementStudy
        One study per rotor type, keyed "I", "II", "III".

    References
    ----------
    Kim (2018), Sect. 3.2, Fig. 9 (comparison of the rotor types).
    """
    return {
        t: inline3_study(t, unbalance, speed, length, section, **options)  # type: ignore[arg-type]
        for t in ROTOR_TYPES
    }
