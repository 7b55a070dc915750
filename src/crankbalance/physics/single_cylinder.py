r"""Single-cylinder balance factor, in-line and transverse forces, and rebalancing.

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
from abc import ABC, abstractmethod
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_positive, check_range
from ..results import ResultMixin
from .kinematics import KINEMATICS_MODELS, KinematicsModel, piston_acceleration
from .shop.holes import (
    FLAT_BOTTOM,
    STEEL_DENSITY,
    DepthReference,
    HoleDirection,
    check_drill,
    depth_for_volume,
    depth_limit,
    hole_geometry,
    hole_mass_properties,
    round_depth,
)

#: Range of balance factors accepted as input (0 = rotating mass only, 2 = 200 %).
BALANCE_FACTOR_RANGE: tuple[float, float] = (0.0, 2.0)


CorrectionKind = Literal["holes", "face"]
FaceOrientation = Literal["axial", "radial"]


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


def _check_mass(field_name: str, value: float) -> float:
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
    _check_mass("rotating_mass", rotating_mass)
    _check_mass("reciprocating_mass", reciprocating_mass)
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
    _check_mass("counterweight_mass", counterweight_mass)
    check_positive("counterweight_radius", counterweight_radius)
    check_positive("crank_radius", crank_radius)
    _check_mass("rotating_mass", rotating_mass)
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
    _check_mass("rotating_mass", rotating_mass)
    _check_mass("reciprocating_mass", reciprocating_mass)
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
        total += _check_mass(f"{field_name}.{name}", mass)
    return total


# ---------------------------------------------------------------------------------------
# tier 3 orchestrator: balance factor study
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
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


def _refined_peak(fun, samples: int = 720) -> float:
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

    def amplitude(fun) -> float:
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


# ---------------------------------------------------------------------------------------
# tier 2: corrections (how the unbalance is taken off the counterweights)
# ---------------------------------------------------------------------------------------


class _Layer(ABC):
    """What both corrections share: material taken off all webs alike, in a layer of a depth.

    Subclasses are frozen dataclasses with ``radius``, ``webs``, ``density`` and
    ``depth_resolution`` fields; they give :attr:`mass_per_depth` and say whether the cut goes
    inward from ``radius`` (radial holes, the shoulder) or keeps its centroid there.
    """

    radius: float
    webs: int
    density: float
    depth_resolution: float

    @property
    @abstractmethod
    def mass_per_depth(self) -> float:
        """Mass removed per metre of depth, all webs [kg/m]."""

    @property
    @abstractmethod
    def _cuts_inward(self) -> bool:
        """Whether the cut goes inward from ``radius`` (else its centroid stays there)."""

    def _check_layer(self) -> None:
        check_positive("correction_radius", self.radius)
        _check_count("webs", self.webs)
        check_positive("density", self.density)
        if not (self.depth_resolution >= 0 and math.isfinite(self.depth_resolution)):
            raise InputError("depth_resolution", self.depth_resolution, "must be >= 0 [m]")

    def centroid_radius(self, depth: float) -> float:
        """Radius of the centroid of the removed material at that depth [m]."""
        return self.radius - depth / 2.0 if self._cuts_inward else self.radius

    def removed_unbalance(self, depth: float) -> float:
        """First moment taken off all webs [kg m]."""
        return self.mass_per_depth * depth * self.centroid_radius(depth)

    def removed_mass(self, depth: float) -> float:
        """Mass taken off all webs at that depth [kg]."""
        return self.mass_per_depth * depth

    def deepen(self, depth: float, mass: float) -> float:
        """Depth at which ``mass`` more than at ``depth`` has come off [m]."""
        return depth + mass / self.mass_per_depth

    def innermost_radius(self, depth: float) -> float:
        """Radius of the cut's deepest point at that depth (>0: short of the crank axis) [m]."""
        return self.centroid_radius(2.0 * depth)


@dataclass(frozen=True)
class DrilledHoles(_Layer, ResultMixin):
    r"""Holes drilled into the counterweights, the same set on each web.

    Attributes
    ----------
    diameter : float
        Drill diameter [m].
    radius : float
        ``direction="axial"``: radius of the hole axes from the crank axis; ``"radial"``:
        radius of the counterweight rim where the holes start [m].
    number : int
        Holes per web.
    direction : {"axial", "radial"}
        Axial holes (parallel to the crank axis) keep their centroid at ``radius``; radial
        holes drilled inward from the rim have theirs at ``radius`` less the centroid depth.
    webs : int
        Webs carrying the same correction (2 keeps a single-cylinder crank dynamically
        balanced, Hoem and Røsholm (2016), Sec. 4.1.3).
    density : float
        Crank material density [kg/m^3].
    depth_resolution : float
        Machining step the depth is rounded to [m] (0 for none).
    point_angle : float
        Included drill-point angle [rad]: :data:`~crankbalance.physics.shop.holes.FLAT_BOTTOM` (pi,
        the default: flat-bottomed holes, as in Hoem and Røsholm (2016), whose numbers it
        reproduces) or e.g. :data:`~crankbalance.physics.shop.holes.DEFAULT_POINT_ANGLE` (118°).
    depth_to : {"shoulder", "tip"}
        What the depth is read to (the same for a flat bottom).
    web_thickness : float, optional
        Axial thickness of the web at the holes [m]: an axial hole ends in it (tip depth at
        most the thickness), a radial hole fits in it. None when not known: the drill's
        reach alone limits the depth (:func:`crankbalance.physics.shop.holes.depth_limit`).

    Volume, mass and centroid of each hole are those of
    :func:`crankbalance.physics.shop.holes.hole_mass_properties`, drill point included.
    :func:`rebalance` refuses a plan the drill cannot make (:meth:`check_plan`).
    """

    diameter: float
    radius: float
    number: int = 1
    direction: HoleDirection = "axial"
    webs: int = 2
    density: float = STEEL_DENSITY
    depth_resolution: float = 1e-6
    point_angle: float = FLAT_BOTTOM
    depth_to: DepthReference = "shoulder"
    web_thickness: float | None = None
    kind: str = field(default="holes", init=False)

    def __post_init__(self) -> None:
        check_positive("hole_diameter", self.diameter)
        _check_count("holes", self.number)
        if self.direction not in ("axial", "radial"):
            raise InputError("hole_direction", self.direction, "must be 'axial' or 'radial'")
        self._check_layer()
        if self.web_thickness is not None:
            check_positive("web_thickness", self.web_thickness)
        hole_geometry(self.diameter, 0.0, self.depth_to, self.point_angle)  # checks both

    def check_drill(self, names: Mapping[str, str] | None = None) -> None:
        """Refuse a drill these holes cannot be made with: smaller than
        :data:`~crankbalance.physics.shop.holes.MIN_DRILL_DIAMETER`, an axial hole that reaches
        across the crank axis, a radial hole wider than the web.

        Parameters
        ----------
        names : mapping of str to str, optional
            How the user named ``hole_diameter``, ``correction_radius`` and
            ``web_thickness`` (an option or a key of a file), for the message.
        """
        drill = _name(names, "hole_diameter")
        check_drill(self.diameter, {"diameter": drill})
        shown = f"{self.diameter * 1e3:.4g} mm"
        if self.direction == "axial" and self.diameter >= 2 * self.radius:
            raise InputError(
                drill,
                shown,
                f"is too large for axial holes at {_name(names, 'correction_radius')} = "
                f"{self.radius * 1e3:.4g} mm: a hole would reach across the crank axis; give a "
                f"drill below {2e3 * self.radius:.4g} mm",
            )
        if self.direction == "radial" and self.web_thickness is not None:
            if self.diameter > self.web_thickness:
                raise InputError(
                    drill,
                    shown,
                    f"is wider than the web, {_name(names, 'web_thickness')} = "
                    f"{self.web_thickness * 1e3:.4g} mm: give a smaller drill",
                )

    def check_plan(self, depth: float, names: Mapping[str, str] | None = None) -> None:
        """Refuse holes ``depth`` deep (as read to ``depth_to``) [m] that go deeper, to the
        tip, than the drill reaches or than the web is thick (axial holes)
        (:func:`~crankbalance.physics.shop.holes.depth_limit`), proposing as many holes per web
        as keep every hole within the limit.

        Parameters
        ----------
        depth : float
            Depth of every hole [m].
        names : mapping of str to str, optional
            How the user named ``hole_diameter``, ``holes`` and ``web_thickness``.
        """
        part = self.web_thickness if self.direction == "axial" else None
        limit, words = depth_limit(
            self.diameter, part, {"web_thickness": _name(names, "web_thickness")}
        )
        tip = float(hole_geometry(self.diameter, depth, self.depth_to, self.point_angle).tip_depth)
        if tip <= limit * (1 + 1e-9):
            return
        deepest = limit - hole_geometry(self.diameter, 0.0, "tip", self.point_angle).cone_height
        at_limit = self.removed_mass(limit if self.depth_to == "tip" else max(deepest, 0.0))
        per_hole = at_limit / self._holes
        needed = math.ceil(self.removed_mass(depth) / (per_hole * self.webs) - 1e-9)
        raise InputError(
            _name(names, "hole_diameter"),
            f"{self.diameter * 1e3:.4g} mm",
            f"would need {self.number} hole(s) per web {tip * 1e3:.4g} mm deep to the tip, "
            f"deeper than {words}; spread the material over {needed} holes per web "
            f"({_name(names, 'holes')}: {needed}), or give a larger drill",
        )

    @property
    def mass_per_depth(self) -> float:
        """Mass removed per metre of depth below the point, all holes on all webs [kg/m]."""
        return self.density * math.pi * self.diameter**2 / 4.0 * self.number * self.webs

    @property
    def _cuts_inward(self) -> bool:
        return self.direction == "radial"

    @property
    def _holes(self) -> int:
        return self.number * self.webs

    def removed_unbalance(self, depth: float) -> float:
        """First moment taken off all webs [kg m]."""
        hole = hole_mass_properties(
            self.diameter,
            depth,
            self.depth_to,
            self.direction,
            self.radius,
            self.density,
            self.point_angle,
        )
        return float(hole.first_moment) * self._holes

    def removed_mass(self, depth: float) -> float:
        """Mass taken off all webs at that depth [kg]."""
        geometry = hole_geometry(self.diameter, depth, self.depth_to, self.point_angle)
        return self.density * float(geometry.volume) * self._holes

    def deepen(self, depth: float, mass: float) -> float:
        """Depth at which ``mass`` more than at ``depth`` has come off [m] (depth 0: no
        hole yet, not the point alone)."""
        removed = self.removed_mass(depth) if depth > 0 else 0.0
        volume = (removed + mass) / (self.density * self._holes)
        return depth_for_volume(self.diameter, volume, self.depth_to, self.point_angle)

    def innermost_radius(self, depth: float) -> float:
        """Radius of the drill tip (radial holes) or of the hole axes (axial) [m]."""
        if self.direction == "axial":
            return self.radius
        return self.radius - float(
            hole_geometry(self.diameter, depth, self.depth_to, self.point_angle).tip_depth
        )


@dataclass(frozen=True)
class FaceRemoval(_Layer, ResultMixin):
    r"""A layer ground off a counterweight face, the same on each web.

    Attributes
    ----------
    area : float
        Face area ground on one web [m^2].
    radius : float
        ``orientation="axial"`` (a side face, normal along the crank axis): radius of the
        face centroid; ``"radial"`` (the shoulder, normal pointing away from the crank
        axis): radius of the face [m]. A radial layer of depth t has its centroid at
        ``radius - t/2``.
    orientation : {"axial", "radial"}
    webs : int
        Webs ground alike (2 keeps a single-cylinder crank dynamically balanced).
    density : float
        Crank material density [kg/m^3].
    depth_resolution : float
        Machining step the depth is rounded to [m] (0 for none).
    """

    area: float
    radius: float
    orientation: FaceOrientation = "radial"
    webs: int = 2
    density: float = STEEL_DENSITY
    depth_resolution: float = 1e-6
    kind: str = field(default="face", init=False)

    def __post_init__(self) -> None:
        check_positive("face_area", self.area)
        if self.orientation not in ("axial", "radial"):
            raise InputError("face_orientation", self.orientation, "must be 'axial' or 'radial'")
        self._check_layer()

    @property
    def mass_per_depth(self) -> float:
        """Mass removed per metre of depth on all webs [kg/m]."""
        return self.density * self.area * self.webs

    @property
    def _cuts_inward(self) -> bool:
        return self.orientation == "radial"


Correction = DrilledHoles | FaceRemoval


def _name(names: Mapping[str, str] | None, name: str) -> str:
    """How the user named a quantity (``names``), else its name here."""
    return name if names is None else names.get(name, name)


def _check_count(name: str, value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise InputError(name, value, "must be a whole number >= 1")
    return int(value)


# ---------------------------------------------------------------------------------------
# tier 3 orchestrator: the eight-step rebalancing procedure
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class RebalanceIteration(ResultMixin):
    """One pass of steps 3-8 of the rebalancing procedure.

    Attributes
    ----------
    iteration : int
        1 for the first correction.
    unbalance_to_correct : float
        Unbalance this pass set out to remove [kg m].
    correction_radius : float
        Radius the correction mass was computed for (step 3) [m].
    correction_mass : float
        ``unbalance_to_correct / correction_radius`` (step 4) [kg], all webs.
    depth : float
        Total depth of the holes / the ground layer after this pass (step 5) [m].
    removed_mass : float
        Total mass removed so far, all webs [kg].
    removed_unbalance : float
        First moment removed so far, measured on the modified geometry (step 6) [kg m].
    residual : float
        Remaining unbalance (step 7) [kg m]: positive = counterweight still too heavy.
    within_tolerance : bool
        ``abs(residual) <= tolerance`` (step 8).
    """

    iteration: int
    unbalance_to_correct: float
    correction_radius: float
    correction_mass: float
    depth: float
    removed_mass: float
    removed_unbalance: float
    residual: float
    within_tolerance: bool


@dataclass(frozen=True)
class RebalanceResult(ResultMixin):
    """Outcome of rebalancing a single-cylinder crank after new parts.

    Attributes
    ----------
    original_balance_factor : float
        :math:`f_b` of the crank with the old parts [-].
    target_balance_factor : float
        :math:`f_b` aimed for with the new parts [-].
    original_moment : float
        :math:`(m_{cw} r')_{old}` [kg m] (step 1).
    required_moment : float
        :math:`(m_{cw} r')_{new} = (m_{rot,new} + f_b m_{rec,new}) r` [kg m] (step 1).
    unbalance : float
        :math:`m_u r_u = (m_{cw} r')_{old} - (m_{cw} r')_{new}` [kg m] (step 2); positive:
        material must come off the counterweights.
    correction : DrilledHoles or FaceRemoval
        How the correction is realised.
    iterations : list of RebalanceIteration
        Each pass of steps 3-8.
    residual : float
        Final signed residual unbalance [kg m].
    achieved_balance_factor : float
        Balance factor of the corrected crank with the new parts [-].
    tolerance : float
        Largest accepted residual [kg m].
    passed : bool
        Whether the final residual is within the tolerance.
    status : str
        ``"converged"``, ``"overcorrected"`` or ``"max_iterations"``.
    bob_weight : float
        Bob-weight for a balancing-machine check with the new parts [kg].
    """

    original_balance_factor: float
    target_balance_factor: float
    original_moment: float
    required_moment: float
    unbalance: float
    correction: DrilledHoles | FaceRemoval
    iterations: list[RebalanceIteration]
    residual: float
    achieved_balance_factor: float
    tolerance: float
    passed: bool
    status: str
    bob_weight: float


def rebalance(
    old_rotating_mass: float,
    old_reciprocating_mass: float,
    new_rotating_mass: float,
    new_reciprocating_mass: float,
    counterweight_mass: float,
    counterweight_radius: float,
    crank_radius: float,
    correction: DrilledHoles | FaceRemoval,
    tolerance: float,
    target_balance_factor: float | None = None,
    max_iterations: int = 10,
    names: Mapping[str, str] | None = None,
) -> RebalanceResult:
    r"""Rebalance a single-cylinder crank after new parts (the thesis' eight steps).

    Parameters
    ----------
    old_rotating_mass, old_reciprocating_mass : float
        :math:`m_{rot}`, :math:`m_{rec}` with the parts the crank was balanced for [kg].
    new_rotating_mass, new_reciprocating_mass : float
        The same with the new parts [kg].
    counterweight_mass, counterweight_radius : float
        :math:`m_{cw}` (counterweights + webs) [kg] and its CG radius :math:`r'` [m],
        measured on the existing crank.
    crank_radius : float
        Crank throw radius [m].
    correction : DrilledHoles or FaceRemoval
        How material is taken off (its ``radius`` is the step-3 choice).
    tolerance : float
        Largest accepted residual unbalance [kg m], e.g. ISO 21940-11 :math:`U_{per}`.
    target_balance_factor : float, optional
        :math:`f_b` wanted with the new parts, in [0, 2] [-]; default: the crank's present
        (factory) factor.
    max_iterations : int
        Passes of steps 3-8 before giving up.
    names : mapping of str to str, optional
        How the user named the correction's quantities (``hole_diameter``, ``holes``,
        ``web_thickness``, ``correction_radius``: an option or a key of a file), for the
        messages of :meth:`DrilledHoles.check_drill` and :meth:`DrilledHoles.check_plan`.

    Returns
    -------
    RebalanceResult
        The correction, its iterations, the residual [kg m] and the balance factor achieved.

    Notes
    -----
    .. math::
        (m_{cw}r')_{new} = (m_{rot} + f_b m_{rec})_{new}\,r,\quad
        m_u r_u = (m_{cw}r')_{old} - (m_{cw}r')_{new},\quad
        m_{corr} = \frac{m_u r_u}{r_{corr}}

    Steps 1-8: (1) first moments old and new; (2) the unbalance; (3) the correction radius;
    (4) the correction mass; (5) its realisation (depth rounded to the machining step);
    (6) the first moment actually removed, measured on the modified geometry; (7) the
    residual; (8) accept when within the tolerance, else repeat 3-7 on the residual with the
    radius of the next layer.

    References
    ----------
    Hoem and Røsholm (2016) Sec. 6.4, Eq. 6.1 (corrected), 6.3-6.5; Table 6.2.
    """
    for name, value in (
        ("old_rotating_mass", old_rotating_mass),
        ("new_rotating_mass", new_rotating_mass),
    ):
        _check_mass(name, value)
    check_positive("old_reciprocating_mass", old_reciprocating_mass)
    check_positive("new_reciprocating_mass", new_reciprocating_mass)
    check_positive("tolerance", tolerance)
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise InputError("max_iterations", max_iterations, "must be an integer >= 1")
    if isinstance(correction, DrilledHoles):
        correction.check_drill(names)
    original = balance_factor_from_mass_properties(
        counterweight_mass,
        counterweight_radius,
        crank_radius,
        old_rotating_mass,
        old_reciprocating_mass,
    )
    target = original if target_balance_factor is None else target_balance_factor
    check_balance_factor(target, "target_balance_factor")
    # step 1
    original_moment = counterweight_mass * counterweight_radius
    required = counterweight_moment(new_rotating_mass, new_reciprocating_mass, target, crank_radius)
    # step 2
    unbalance = original_moment - required
    if unbalance < -tolerance:
        reachable = (original_moment / crank_radius - new_rotating_mass) / new_reciprocating_mass
        advice = (
            f"choose at most {reachable:.4f}"
            if reachable >= 0
            else f"the counterweights are too light even for f_b = 0 with the new parts "
            f"(the crank would have f_b = {reachable:.4f})"
        )
        raise InputError(
            "target_balance_factor",
            target,
            f"needs {-unbalance * 1e6:.4g} g*mm added to the counterweights; removing "
            f"material (holes, grinding) can only lower the balance factor; {advice}",
        )
    iterations: list[RebalanceIteration] = []
    depth = 0.0
    residual = unbalance
    status = "converged"
    if abs(residual) > tolerance:
        status = "max_iterations"
        for k in range(1, max_iterations + 1):
            to_correct = residual
            # step 3: the next layer starts at the present depth
            radius = correction.centroid_radius(2.0 * depth)
            mass = to_correct / radius  # step 4
            depth = round_depth(
                correction.deepen(depth, mass), correction.depth_resolution
            )  # step 5
            if not correction.innermost_radius(depth) > 0:
                raise InputError(
                    "correction",
                    correction.kind,
                    f"needs a cut {depth * 1e3:.4g} mm deep from radius "
                    f"{correction.radius * 1e3:.4g} mm, through the crank axis; use a larger "
                    "face area, more or larger holes, or axial holes",
                )
            if isinstance(correction, DrilledHoles):
                correction.check_plan(depth, names)
            removed = correction.removed_unbalance(depth)  # step 6
            residual = unbalance - removed  # step 7
            ok = abs(residual) <= tolerance  # step 8
            iterations.append(
                RebalanceIteration(
                    iteration=k,
                    unbalance_to_correct=to_correct,
                    correction_radius=radius,
                    correction_mass=mass,
                    depth=depth,
                    removed_mass=correction.removed_mass(depth),
                    removed_unbalance=removed,
                    residual=residual,
                    within_tolerance=ok,
                )
            )
            if ok:
                status = "converged"
                break
            if residual < 0:
                status = "overcorrected"
                break
    achieved = (
        (original_moment - (unbalance - residual)) / crank_radius - new_rotating_mass
    ) / new_reciprocating_mass
    return RebalanceResult(
        original_balance_factor=original,
        target_balance_factor=target,
        original_moment=original_moment,
        required_moment=required,
        unbalance=unbalance,
        correction=correction,
        iterations=iterations,
        residual=residual,
        achieved_balance_factor=achieved,
        tolerance=tolerance,
        passed=abs(residual) <= tolerance,
        status=status,
        bob_weight=bob_weight(new_rotating_mass, new_reciprocating_mass, target),
    )
