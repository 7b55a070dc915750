"""Parametric crankshaft counterweight: geometry, mass properties, design and optimisation.

The profile is the one of the 2021 crankshaft-balancing paper (Sec. 4, Fig. 5): a
rectangle ``h_R x 2 r_cw`` (orange), a trapezoid of flank angle ``delta`` that widens
by the overhang ``l_c`` on each side (blue) and a circular segment of radius ``R_cw``
and angle ``alpha`` whose chord closes the trapezoid (green). The base web circle of
radius ``r_cw`` (red, centred on the crank axis) is not part of the counterweight and
is cut out of the three zones. The counterweight is the prism of that profile with
thickness ``t_cw`` and density ``rho``.

Coordinates: the crank axis is the origin, ``y`` points from the axis towards the
counterweight (its centre of gravity lies on ``+y``), ``x`` across.

Three tiers, as everywhere in crankbalance:

* pure vectorised functions (:func:`profile_section`, :func:`counterweight_properties`,
  :func:`thickness_for_first_moment`, :func:`validate_profile`),
* frozen dataclasses (:class:`CounterweightDesign`, :class:`CounterweightProperties`,
  :class:`CounterweightOptimum`),
* the orchestrator :func:`optimize_counterweight`, shaped like ``scipy.optimize``.

Exports (SVG, DXF R12, STL, optional STEP) and the read-back of mesh mass properties
live at the end of this module; trimesh and build123d are imported lazily.

References
----------
.. [1] Applied Sciences 11 (2021) 8997, Sec. 4, Eqs. 24-30, Table 3; errata in docs/references.md: the orange centroid term is
   ``(2/3) r_cw^3 (1 - sin^3(gamma/2))``; the printed ``R_min`` is the bound
   ``h_R + l_c tan(delta) + R_cw``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, NamedTuple

import numpy as np

from .errors import InputError
from .results import ResultMixin

ArrayLike = Any
RadiusMeasure = Literal["true", "paper"]
Objective = Literal["mass", "radius", "inertia"]
ExportFormat = Literal["svg", "dxf", "stl", "step"]

#: Shape parameters in the order used by arrays of designs (SI: m, rad).
PARAMETERS: tuple[str, ...] = (
    "web_radius",
    "rectangle_height",
    "trapezoid_angle",
    "segment_radius",
    "segment_angle",
    "thickness",
)
#: The paper's symbols for :data:`PARAMETERS` (for tables and docs).
SYMBOLS: dict[str, str] = {
    "web_radius": "r_cw",
    "rectangle_height": "h_R",
    "trapezoid_angle": "delta",
    "segment_radius": "R_cw",
    "segment_angle": "alpha",
    "thickness": "t_cw",
}
#: Default search range of each parameter [m or rad] (used for parameters not given).
DEFAULT_BOUNDS: dict[str, tuple[float, float]] = {
    "web_radius": (0.010, 0.020),
    "rectangle_height": (0.0, 0.030),
    "trapezoid_angle": (0.0, 1.46),
    "segment_radius": (0.020, 0.080),
    "segment_angle": (0.2, math.pi),
    "thickness": (0.005, 0.030),
}
#: Steel, as Table 3 of the paper implies (docs/references.md).
DEFAULT_DENSITY = 8000.0


# --------------------------------------------------------------------------------------
# Tier 1: pure, vectorised geometry
# --------------------------------------------------------------------------------------


class CircleCap(NamedTuple):
    """Area, first moment (in y) and polar second moment about the origin of a circle cap."""

    area: np.ndarray
    first_moment: np.ndarray
    polar_moment: np.ndarray


def circle_cap(radius: ArrayLike, centre_y: ArrayLike, cut_y: ArrayLike) -> CircleCap:
    """The part of the circle of ``radius`` centred at ``(0, centre_y)`` above ``y = cut_y``.

    Parameters
    ----------
    radius : array_like
        Circle radius rho [m].
    centre_y : array_like
        y of the circle centre c [m].
    cut_y : array_like
        Height of the cutting line [m]; outside ``[c - rho, c + rho]`` the cap is the
        whole circle or empty.

    Returns
    -------
    CircleCap
        area [m^2], first moment ``int y dA`` [m^3], polar moment ``int (x^2+y^2) dA`` [m^4].

    Notes
    -----
    With the half-angle :math:`\\theta = \\arccos((t - c)/\\rho)`:

    .. math::
        A = \\rho^2(\\theta - \\sin\\theta\\cos\\theta),\\quad
        S_c = \\tfrac23 \\rho^3 \\sin^3\\theta,\\quad
        J_c = \\rho^4\\Big(\\frac{\\theta}{2} - \\frac{\\sin\\theta\\cos\\theta
              (\\sin^2\\theta + 3\\cos^2\\theta)}{6}\\Big)

    about the circle centre (sector minus the triangle to the chord); moved to the origin
    with :math:`S = cA + S_c`, :math:`J = J_c + 2cS_c + c^2A`.
    """
    rho = np.asarray(radius, dtype=float)
    c = np.asarray(centre_y, dtype=float)
    theta = np.arccos(np.clip((np.asarray(cut_y, dtype=float) - c) / rho, -1.0, 1.0))
    s, co = np.sin(theta), np.cos(theta)
    area = rho**2 * (theta - s * co)
    s_c = 2.0 / 3.0 * rho**3 * s**3
    j_c = rho**4 * (theta / 2.0 - s * co * (s**2 + 3.0 * co**2) / 6.0)
    return CircleCap(area, c * area + s_c, j_c + 2.0 * c * s_c + c**2 * area)


def _strip_polar_moment(y0, y1, w0, w1):
    """Polar moment about the origin of ``|x| <= w(y)``, ``y0 <= y <= y1``, w linear.

    The integrand ``2/3 w^3 + 2 w y^2`` is a cubic in y, so Simpson's rule is exact.
    """
    ym, wm = 0.5 * (y0 + y1), 0.5 * (w0 + w1)

    def f(y, w):
        return 2.0 / 3.0 * w**3 + 2.0 * w * y**2

    return (y1 - y0) / 6.0 * (f(y0, w0) + 4.0 * f(ym, wm) + f(y1, w1))


class ProfileSection(NamedTuple):
    """Section properties of the counterweight profile (arrays, SI).

    ``first_moment`` is the area first moment ``int y dA`` [m^3] about the crank axis,
    ``polar_moment`` the polar second moment ``int (x^2 + y^2) dA`` [m^4] about it.
    ``hub_protrusion`` is True where the web circle reaches out through the segment's arc
    (the regime where the paper's Eqs. 26/30 need the correction, see the docs).
    """

    area: np.ndarray
    first_moment: np.ndarray
    polar_moment: np.ndarray
    area_green: np.ndarray
    area_blue: np.ndarray
    area_orange: np.ndarray
    cg_green: np.ndarray
    cg_blue: np.ndarray
    cg_orange: np.ndarray
    overhang: np.ndarray
    gamma: np.ndarray
    lam: np.ndarray
    top_height: np.ndarray
    segment_centre: np.ndarray
    outer_radius: np.ndarray
    radius_bound: np.ndarray
    hub_protrusion: np.ndarray


def profile_section(
    web_radius: ArrayLike,
    rectangle_height: ArrayLike,
    trapezoid_angle: ArrayLike,
    segment_radius: ArrayLike,
    segment_angle: ArrayLike,
) -> ProfileSection:
    """Area, first and polar moments, intersections and outer radius of the profile.

    Vectorised: all arguments broadcast. No validation (see :func:`validate_profile`);
    invalid parameter sets give meaningless numbers.

    Parameters
    ----------
    web_radius : array_like
        Radius r_cw of the base crank-web circle [m].
    rectangle_height : array_like
        Height h_R of the rectangle above the crank axis [m].
    trapezoid_angle : array_like
        Flank angle delta of the trapezoid from the chord direction [rad], ``0 <= delta < pi/2``.
    segment_radius : array_like
        Radius R_cw of the circular segment [m].
    segment_angle : array_like
        Angle alpha subtended by the segment's arc at its centre [rad].

    Returns
    -------
    ProfileSection

    Notes
    -----
    Paper Eqs. 24-26 and 30 with the corrected orange term (docs/references.md):

    .. math::
        l_c = R_{cw}\\sin\\tfrac{\\alpha}{2} - r_{cw},\\quad
        \\gamma = 2\\cos^{-1}\\min(1, h_R / r_{cw}),\\quad
        \\lambda = 2\\cos^{-1}\\min(1, (h_R + l_c\\tan\\delta) / r_{cw})

        A_{green} = R_{cw}^2(\\tfrac{\\alpha}{2} - \\sin\\tfrac{\\alpha}{2}\\cos\\tfrac{\\alpha}{2})
                  - r_{cw}^2(\\tfrac{\\lambda}{2}
                  - \\sin\\tfrac{\\lambda}{2}\\cos\\tfrac{\\lambda}{2})

        A_{blue} = (2r_{cw} + l_c)\\,l_c\\tan\\delta - r_{cw}^2(\\tfrac{\\gamma}{2} - \\ldots)
                 + r_{cw}^2(\\tfrac{\\lambda}{2} - \\ldots)

        A_{orange} = 2r_{cw}h_R - \\tfrac{\\pi}{2}r_{cw}^2 + r_{cw}^2(\\tfrac{\\gamma}{2} - \\ldots)

        S_{orange} = h_R^2 r_{cw} - \\tfrac23 r_{cw}^3(1 - \\sin^3\\tfrac{\\gamma}{2})

    Correction (not in the paper): when the web circle reaches above the top of the arc,
    :math:`r_{cw} > h_R + l_c\\tan\\delta + R_{cw}(1 - \\cos\\frac{\\alpha}{2})`, the paper
    subtracts the whole cap of the web circle above the chord although part of it lies
    outside the segment; the part of the web circle above the circles' crossing height
    :math:`y^*` that lies outside the segment circle is added back to the green zone.

    References
    ----------
    .. [1] 2021 paper, Sec. 4, Eqs. 24-30; errata in docs/references.md.
    """
    r = np.asarray(web_radius, dtype=float)
    h_r = np.asarray(rectangle_height, dtype=float)
    delta = np.asarray(trapezoid_angle, dtype=float)
    big_r = np.asarray(segment_radius, dtype=float)
    alpha = np.asarray(segment_angle, dtype=float)
    r, h_r, delta, big_r, alpha = np.broadcast_arrays(r, h_r, delta, big_r, alpha)

    half = alpha / 2.0
    s_a, c_a = np.sin(half), np.cos(half)
    l_c = big_r * s_a - r  # Eq. 26, last line
    h_t = l_c * np.tan(delta)  # trapezoid height
    top = h_r + h_t  # chord of the segment
    gamma = 2.0 * np.arccos(np.clip(h_r / r, -1.0, 1.0))  # Eq. 25
    lam = 2.0 * np.arccos(np.clip(top / r, -1.0, 1.0))  # Eq. 24

    def seg(radius, angle):  # area of a circular segment of full angle `angle`
        return radius**2 * (angle / 2.0 - np.sin(angle / 2.0) * np.cos(angle / 2.0))

    # Eq. 26: areas
    seg_green = seg(big_r, alpha)
    trap = (2.0 * r + l_c) * h_t
    area_green = seg_green - seg(r, lam)
    area_blue = trap - seg(r, gamma) + seg(r, lam)
    area_orange = 2.0 * r * h_r - r**2 * np.pi / 2.0 + seg(r, gamma)

    # Eq. 30: first moments (orange term corrected)
    centre = top - big_r * c_a  # y of the segment circle's centre
    s3_g, s3_l = np.sin(gamma / 2.0) ** 3, np.sin(lam / 2.0) ** 3
    mom_green = seg_green * centre + (2.0 * big_r * s_a) ** 3 / 12.0 - 2.0 / 3.0 * r**3 * s3_l
    mom_blue = trap * top - h_t**2 * (3.0 * r + l_c) / 3.0 - 2.0 / 3.0 * r**3 * (s3_g - s3_l)
    mom_orange = h_r**2 * r - 2.0 / 3.0 * r**3 * (1.0 - s3_g)

    # polar second moments about the crank axis (derived, see docs/counterweight.md)
    web_0 = circle_cap(r, 0.0, 0.0)
    web_r = circle_cap(r, 0.0, h_r)
    web_t = circle_cap(r, 0.0, top)
    seg_c = circle_cap(big_r, centre, top)
    j_green = seg_c.polar_moment - web_t.polar_moment
    j_blue = _strip_polar_moment(h_r, top, r, r + l_c) - (web_r.polar_moment - web_t.polar_moment)
    j_orange = 2.0 / 3.0 * r * h_r * (r**2 + h_r**2) - (web_0.polar_moment - web_r.polar_moment)

    # correction: the web circle pokes out through the arc (hub protrusion)
    hub = r > centre + big_r * (1.0 + 1e-12)
    if np.any(hub):
        safe_c = np.where(hub, centre, -1.0)
        y_star = (r**2 - big_r**2 + safe_c**2) / (2.0 * safe_c)
        y_star = np.clip(y_star, top, r)
        web_s = circle_cap(r, 0.0, y_star)
        seg_s = circle_cap(big_r, centre, y_star)
        area_green = area_green + np.where(hub, web_s.area - seg_s.area, 0.0)
        mom_green = mom_green + np.where(hub, web_s.first_moment - seg_s.first_moment, 0.0)
        j_green = j_green + np.where(hub, web_s.polar_moment - seg_s.polar_moment, 0.0)

    area = area_green + area_blue + area_orange  # Eq. 27
    first_moment = mom_green + mom_blue + mom_orange
    polar = j_green + j_blue + j_orange

    with np.errstate(divide="ignore", invalid="ignore"):
        cg_green = np.where(area_green > 0, mom_green / np.where(area_green > 0, area_green, 1), 0)
        cg_blue = np.where(area_blue > 0, mom_blue / np.where(area_blue > 0, area_blue, 1), 0)
        cg_orange = np.where(
            area_orange > 0, mom_orange / np.where(area_orange > 0, area_orange, 1), 0
        )

    # true outer radius: farthest point of the profile from the crank axis
    arc_top = np.where(centre >= 0.0, centre + big_r, 0.0)
    outer = np.maximum.reduce([arc_top, np.hypot(big_r * s_a, top), np.hypot(r, h_r)])
    bound = h_r + h_t + big_r  # the paper's R_min (Table 3)
    return ProfileSection(
        area,
        first_moment,
        polar,
        area_green,
        area_blue,
        area_orange,
        cg_green,
        cg_blue,
        cg_orange,
        l_c,
        gamma,
        lam,
        top,
        centre,
        outer,
        bound,
        hub,
    )


_PROFILE_RULES = (
    "web_radius",
    "rectangle_height",
    "trapezoid_angle",
    "segment_radius",
    "segment_angle",
)


def profile_validity(
    web_radius: ArrayLike,
    rectangle_height: ArrayLike,
    trapezoid_angle: ArrayLike,
    segment_radius: ArrayLike,
    segment_angle: ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Which parameter sets form a valid profile, and why not.

    Returns
    -------
    valid : ndarray of bool
    reason : ndarray of int
        0 for valid, else ``1 + index`` of the first failed rule in :data:`PROFILE_REASONS`.
    """
    r, h_r, delta, big_r, alpha = np.broadcast_arrays(
        *(
            np.asarray(v, dtype=float)
            for v in (web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle)
        )
    )
    with np.errstate(all="ignore"):
        rules = [
            ~(np.isfinite(r) & (r > 0)),
            ~(np.isfinite(h_r) & (h_r >= 0)),
            ~(np.isfinite(delta) & (delta >= 0) & (delta < np.pi / 2)),
            ~(np.isfinite(big_r) & (big_r > 0)),
            ~(np.isfinite(alpha) & (alpha > 0) & (alpha < 2 * np.pi)),
            big_r * np.sin(alpha / 2) < r * (1 - 1e-12),
        ]
        reason = np.zeros(r.shape, dtype=int)
        for i in range(len(rules) - 1, -1, -1):
            reason = np.where(rules[i], i + 1, reason)
        ok = reason == 0
        if np.any(ok):
            area = profile_section(
                np.where(ok, r, 1.0),
                np.where(ok, h_r, 0.0),
                np.where(ok, delta, 0.0),
                np.where(ok, big_r, 2.0),
                np.where(ok, alpha, np.pi),
            ).area
            empty = ok & ~(area > 1e-9 * np.where(ok, r, 1.0) ** 2)
            reason = np.where(empty, len(rules) + 1, reason)
    return reason == 0, reason


#: (field, what is allowed) of each validity rule, indexed by ``reason - 1``.
PROFILE_REASONS: tuple[tuple[str, str], ...] = (
    ("web_radius", "must be a finite length greater than zero"),
    ("rectangle_height", "must be a finite length >= 0"),
    ("trapezoid_angle", "must lie in [0, pi/2) rad (0 to below 90 deg)"),
    ("segment_radius", "must be a finite length greater than zero"),
    ("segment_angle", "must lie in (0, 2 pi) rad"),
    (
        "segment_radius",
        "too small for segment_angle: the segment chord 2 R_cw sin(alpha/2) must be at least "
        "the web diameter 2 r_cw (overhang l_c >= 0)",
    ),
    ("segment_radius", "the profile lies inside the web circle: the counterweight has no area"),
)


def validate_profile(
    web_radius: ArrayLike,
    rectangle_height: ArrayLike,
    trapezoid_angle: ArrayLike,
    segment_radius: ArrayLike,
    segment_angle: ArrayLike,
) -> None:
    """Raise :class:`InputError` naming the parameter if any set is not a valid profile."""
    values = (web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle)
    ok, reason = profile_validity(*values)
    if np.all(ok):
        return
    flat = np.ravel(reason)
    index = int(np.flatnonzero(flat)[0])
    field_name, allowed = PROFILE_REASONS[flat[index] - 1]
    value = np.ravel(
        np.broadcast_to(
            np.asarray(values[_PROFILE_RULES.index(field_name)], dtype=float), reason.shape
        )
    )[index]
    where = "" if reason.ndim == 0 else f"[{index}]"
    raise InputError(f"{field_name}{where}", float(value), allowed)


def _check_material(thickness: ArrayLike, density: ArrayLike) -> None:
    for name, value in (("thickness", thickness), ("density", density)):
        v = np.asarray(value, dtype=float)
        bad = ~(np.isfinite(v) & (v > 0))
        if np.any(bad):
            first = float(np.ravel(v)[int(np.flatnonzero(np.ravel(bad))[0])])
            raise InputError(name, first, "must be a finite number greater than zero")


@dataclass(frozen=True)
class CounterweightProperties(ResultMixin):
    """Mass properties of one counterweight or of many (array fields broadcast together).

    Attributes
    ----------
    area : Profile area A_cw [m^2] (Eq. 27).
    volume : V_cw = A_cw t_cw [m^3] (Eq. 28).
    mass : m_cw = V_cw rho [kg] (Eq. 29).
    cg_radius : Distance r_c of the centre of gravity from the crank axis [m] (Eq. 30).
    first_moment : m_cw r_c [kg m], the unbalance the counterweight provides.
    inertia : Mass moment of inertia about the crank axis [kg m^2].
    outer_radius : True radial space: largest distance of the profile from the axis [m].
    radius_bound : The paper's R_min = h_R + l_c tan(delta) + R_cw [m] (Table 3).
    overhang : l_c [m]; ``gamma``, ``lam``: intersection angles [rad] (Eqs. 24-25).
    area_green, area_blue, area_orange : Zone areas [m^2] (Eq. 26).
    hub_protrusion : True where the web circle reaches out through the segment's arc.
    balance : Achieved / required first moment [%] (only if a requirement was given).
    """

    area: Any
    volume: Any
    mass: Any
    cg_radius: Any
    first_moment: Any
    inertia: Any
    outer_radius: Any
    radius_bound: Any
    overhang: Any
    gamma: Any
    lam: Any
    area_green: Any
    area_blue: Any
    area_orange: Any
    hub_protrusion: Any
    balance: Any = None


def counterweight_properties(
    web_radius: ArrayLike,
    rectangle_height: ArrayLike,
    trapezoid_angle: ArrayLike,
    segment_radius: ArrayLike,
    segment_angle: ArrayLike,
    thickness: ArrayLike,
    density: ArrayLike = DEFAULT_DENSITY,
    required_first_moment: float | None = None,
) -> CounterweightProperties:
    """Mass, centre of gravity, first moment, inertia and outer radius (vectorised).

    Parameters
    ----------
    web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle : array_like
        Profile parameters r_cw [m], h_R [m], delta [rad], R_cw [m], alpha [rad].
    thickness : array_like
        Counterweight thickness t_cw along the crank axis [m].
    density : array_like
        Material density rho [kg/m^3]; 8000 reproduces Table 3 of the paper.
    required_first_moment : float, optional
        m_c r_c the balancing asks for [kg m]; gives ``balance`` [%].

    Returns
    -------
    CounterweightProperties

    Raises
    ------
    InputError
        If a parameter set is not a valid profile (the message names the parameter).

    Notes
    -----
    .. math::
        m_{cw} = \\rho t_{cw} A_{cw},\\quad m_{cw} r_c = \\rho t_{cw} \\int y\\,dA,\\quad
        J = \\rho t_{cw} \\int (x^2 + y^2)\\,dA

    References
    ----------
    .. [1] 2021 paper, Sec. 4, Eqs. 26-30.
    """
    validate_profile(web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle)
    _check_material(thickness, density)
    if required_first_moment is not None:
        _check_positive_scalar("required_first_moment", required_first_moment)
    sec = profile_section(
        web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle
    )
    return _properties_from_section(sec, thickness, density, required_first_moment)


def _properties_from_section(sec, thickness, density, required_first_moment=None):
    t = np.asarray(thickness, dtype=float)
    rho = np.asarray(density, dtype=float)
    mass = rho * t * sec.area
    first = rho * t * sec.first_moment
    balance = None if required_first_moment is None else 100.0 * first / required_first_moment

    def out(v):
        v = np.asarray(v)
        return v.item() if v.ndim == 0 else v

    return CounterweightProperties(
        area=out(sec.area),
        volume=out(sec.area * t),
        mass=out(mass),
        cg_radius=out(sec.first_moment / sec.area),
        first_moment=out(first),
        inertia=out(rho * t * sec.polar_moment),
        outer_radius=out(sec.outer_radius),
        radius_bound=out(sec.radius_bound),
        overhang=out(sec.overhang),
        gamma=out(sec.gamma),
        lam=out(sec.lam),
        area_green=out(sec.area_green),
        area_blue=out(sec.area_blue),
        area_orange=out(sec.area_orange),
        hub_protrusion=out(sec.hub_protrusion),
        balance=None if balance is None else out(balance),
    )


def _check_positive_scalar(name: str, value: Any) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(name, value, "must be a finite number greater than zero") from None
    if not (v > 0 and math.isfinite(v)):
        raise InputError(name, value, "must be a finite number greater than zero")
    return v


def thickness_for_first_moment(
    required_first_moment: float,
    web_radius: ArrayLike,
    rectangle_height: ArrayLike,
    trapezoid_angle: ArrayLike,
    segment_radius: ArrayLike,
    segment_angle: ArrayLike,
    density: float = DEFAULT_DENSITY,
    balance: float = 100.0,
) -> np.ndarray | float:
    """Thickness that gives ``balance`` % of the required first moment (closed form).

    .. math:: t_{cw} = \\frac{b\\, (m_c r_c)_{req}}{\\rho \\int y\\,dA}

    Parameters
    ----------
    required_first_moment : float
        m_c r_c asked for by the balancing [kg m].
    web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle : array_like
        Profile parameters [m, rad].
    density : float
        [kg/m^3].
    balance : float
        Target balance [%].

    Returns
    -------
    float or ndarray
        t_cw [m].
    """
    u = _check_positive_scalar("required_first_moment", required_first_moment)
    rho = _check_positive_scalar("density", density)
    b = _check_positive_scalar("balance", balance)
    validate_profile(web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle)
    sec = profile_section(
        web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle
    )
    t = b / 100.0 * u / (rho * sec.first_moment)
    return t.item() if np.ndim(t) == 0 else t


def required_first_moment(counterweights: Any, web: int | None = None) -> float:
    """The first moment m_c r_c one crank counterweight must provide [kg m].

    Parameters
    ----------
    counterweights : crankbalance.balancing.Counterweights
        The balancing solver's crank counterweights (``mass`` [kg] per web at ``cg_radius`` [m]).
    web : int, optional
        Web number (1-based, as in ``counterweights.web``); by default the largest one.

    Returns
    -------
    float
        m_c r_c [kg m].

    References
    ----------
    .. [1] 2021 paper, Eqs. 9-10 (m_c at r_c) and Sec. 4 (the shape must carry it).
    """
    mass = np.abs(np.asarray(counterweights.mass, dtype=float))
    if mass.size == 0:
        raise InputError("counterweights", "none", "the balancing found no crank counterweight")
    if web is None:
        m = float(mass.max())
    else:
        webs = [int(w) for w in np.asarray(counterweights.web).ravel()]
        if web not in webs:
            raise InputError("web", web, f"one of the counterweight webs {webs}")
        m = float(mass[webs.index(web)])
    return _check_positive_scalar("required_first_moment", m * float(counterweights.cg_radius))


# --------------------------------------------------------------------------------------
# Tier 2: one design
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class CounterweightDesign(ResultMixin):
    """One counterweight: its profile parameters, thickness and material.

    Attributes
    ----------
    web_radius : r_cw [m].
    rectangle_height : h_R [m].
    trapezoid_angle : delta [rad].
    segment_radius : R_cw [m].
    segment_angle : alpha [rad].
    thickness : t_cw [m].
    density : rho [kg/m^3].
    """

    web_radius: float
    rectangle_height: float
    trapezoid_angle: float
    segment_radius: float
    segment_angle: float
    thickness: float
    density: float = DEFAULT_DENSITY

    def __post_init__(self) -> None:
        for name in (*PARAMETERS, "density"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)):
                raise InputError(name, value, "must be a number (SI units)")
            object.__setattr__(self, name, float(value))
        validate_profile(*self.profile_parameters())
        _check_material(self.thickness, self.density)

    def profile_parameters(self) -> tuple[float, float, float, float, float]:
        """(r_cw, h_R, delta, R_cw, alpha) in SI."""
        return (
            self.web_radius,
            self.rectangle_height,
            self.trapezoid_angle,
            self.segment_radius,
            self.segment_angle,
        )

    def properties(self, required_first_moment: float | None = None) -> CounterweightProperties:
        """Mass properties (see :func:`counterweight_properties`)."""
        return counterweight_properties(
            *self.profile_parameters(), self.thickness, self.density, required_first_moment
        )

    def with_thickness_for(self, required_first_moment: float, balance: float = 100.0):
        """The same profile with the thickness that gives ``balance`` % of the requirement."""
        t = thickness_for_first_moment(
            required_first_moment, *self.profile_parameters(), density=self.density, balance=balance
        )
        return CounterweightDesign(*self.profile_parameters(), float(t), self.density)

    def outline(self, tolerance: float = 1e-5) -> list[np.ndarray]:
        """Closed boundary loops of the profile, counter-clockwise, as (N, 2) arrays [m].

        One loop normally; two (left and right horn) when the web circle pokes out
        through the segment's arc. Arcs are polygonised with a chord error below
        ``tolerance`` [m].
        """
        return [_sample_loop(loop, tolerance) for loop in profile_boundary(self)]


# --------------------------------------------------------------------------------------
# Boundary (exact primitives) for exports and polygons
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Line:
    start: tuple[float, float]
    end: tuple[float, float]


@dataclass(frozen=True)
class _Arc:
    centre: tuple[float, float]
    radius: float
    start_angle: float  # rad
    end_angle: float  # rad; the arc runs from start to end, counter-clockwise if ccw
    ccw: bool

    def point(self, angle: float) -> tuple[float, float]:
        return (
            self.centre[0] + self.radius * math.cos(angle),
            self.centre[1] + self.radius * math.sin(angle),
        )

    @property
    def sweep(self) -> float:
        d = self.end_angle - self.start_angle
        return d if self.ccw else -d


def profile_boundary(design: CounterweightDesign) -> list[list[_Line | _Arc]]:
    """The boundary loops of the profile as lines and arcs (counter-clockwise)."""
    r, h_r, delta, big_r, alpha = design.profile_parameters()
    sec = profile_section(r, h_r, delta, big_r, alpha)
    l_c, top, yc = float(sec.overhang), float(sec.top_height), float(sec.segment_centre)
    corner = (r + l_c, top)
    phi_r = math.atan2(top - yc, r + l_c)  # angle of the right chord end seen from the centre
    loops: list[list[_Line | _Arc]] = []

    def right_side() -> list[_Line | _Arc]:
        items: list[_Line | _Arc] = []
        if h_r > 0:
            items.append(_Line((r, 0.0), (r, h_r)))
        if math.hypot(l_c, top - h_r) > 0:
            items.append(_Line((r, h_r), corner))
        return items

    def mirror(items: list[_Line | _Arc]) -> list[_Line | _Arc]:
        out: list[_Line | _Arc] = []
        for it in reversed(items):
            if isinstance(it, _Line):
                out.append(_Line((-it.end[0], it.end[1]), (-it.start[0], it.start[1])))
            else:
                out.append(
                    _Arc(
                        (-it.centre[0], it.centre[1]),
                        it.radius,
                        math.pi - it.end_angle,
                        math.pi - it.start_angle,
                        it.ccw,
                    )
                )
        return out

    if not bool(sec.hub_protrusion):
        loop = right_side()
        loop.append(_Arc((0.0, yc), big_r, phi_r, math.pi - phi_r, True))
        loop += mirror(right_side())
        loop.append(_Arc((0.0, 0.0), r, math.pi, 0.0, False))  # web circle, left to right
        loops.append(loop)
    else:
        y_star = float(np.clip((r**2 - big_r**2 + yc**2) / (2 * yc), top, r))
        x_star = math.sqrt(max(r**2 - y_star**2, 0.0))
        right = right_side()
        right.append(_Arc((0.0, yc), big_r, phi_r, math.atan2(y_star - yc, x_star), True))
        right.append(_Arc((0.0, 0.0), r, math.atan2(y_star, x_star), 0.0, False))
        loops.append(right)
        loops.append(mirror(right))
    return loops


def _sample_loop(loop: list[_Line | _Arc], tolerance: float) -> np.ndarray:
    points: list[tuple[float, float]] = []
    for item in loop:
        if isinstance(item, _Line):
            points.append(item.start)
        else:
            # chord error rho (1 - cos(dphi/2)) <= tolerance
            dphi_max = 2.0 * math.acos(max(-1.0, 1.0 - tolerance / item.radius))
            n = max(2, math.ceil(abs(item.sweep) / max(dphi_max, 1e-9)))
            n = min(n, 20000)
            for k in range(n):
                a = item.start_angle + (item.end_angle - item.start_angle) * k / n
                points.append(item.point(a))
    pts = np.asarray(points, dtype=float)
    # drop consecutive duplicates
    keep = np.ones(len(pts), dtype=bool)
    keep[1:] = np.any(np.abs(np.diff(pts, axis=0)) > 1e-15, axis=1)
    return pts[keep]


# --------------------------------------------------------------------------------------
# Tier 3: optimisation
# --------------------------------------------------------------------------------------

_DOMAIN: dict[str, tuple[float, float, str]] = {
    # name: (lowest allowed, highest allowed, text)
    "web_radius": (0.0, math.inf, "a length > 0"),
    "rectangle_height": (0.0, math.inf, "a length >= 0"),
    "trapezoid_angle": (0.0, math.pi / 2, "an angle in [0, pi/2)"),
    "segment_radius": (0.0, math.inf, "a length > 0"),
    "segment_angle": (0.0, 2 * math.pi, "an angle in (0, 2 pi)"),
    "thickness": (0.0, math.inf, "a length > 0"),
}


def parse_bounds(
    bounds: Mapping[str, float | tuple[float, float] | Sequence[float]] | None,
) -> dict[str, tuple[float, float]]:
    """Complete and check a bounds mapping: name -> (low, high), or a number to fix it.

    Parameters not given take :data:`DEFAULT_BOUNDS`. Raises :class:`InputError` naming
    the parameter for unknown names, ``low > high`` or values outside the domain.
    """
    out = dict(DEFAULT_BOUNDS)
    for name, value in (bounds or {}).items():
        if name not in PARAMETERS:
            raise InputError(f"bounds.{name}", value, f"unknown parameter; use one of {PARAMETERS}")
        if isinstance(value, (int, float, np.floating)) and not isinstance(value, bool):
            low = high = float(value)
        else:
            try:
                low, high = (float(v) for v in value)  # type: ignore[union-attr]
            except (TypeError, ValueError):
                raise InputError(
                    f"bounds.{name}", value, "must be a number (fixed) or a pair (low, high)"
                ) from None
        lo_ok, hi_ok, text = _DOMAIN[name]
        strict_low = name != "rectangle_height" and name != "trapezoid_angle"
        bad_low = (low <= lo_ok) if strict_low else (low < lo_ok)
        bad_high = (high >= hi_ok) if name in ("trapezoid_angle", "segment_angle") else high > hi_ok
        if not (math.isfinite(low) and math.isfinite(high)) or bad_low or bad_high:
            raise InputError(f"bounds.{name}", value, f"must be {text} (SI units)")
        if low > high:
            raise InputError(f"bounds.{name}", value, "low must not exceed high")
        out[name] = (low, high)
    return out


@dataclass(frozen=True)
class OptimizationProgress:
    """State passed to the ``callback`` of :func:`optimize_counterweight` after each iteration."""

    iteration: int
    n_iterations: int
    nfev: int
    n_feasible: int
    n_pareto: int
    least_mass: float | None
    elapsed: float


@dataclass(frozen=True)
class CounterweightOptimum(ResultMixin):
    """Result of :func:`optimize_counterweight` (shaped like ``scipy.optimize.OptimizeResult``).

    Attributes
    ----------
    designs : (N, 6) array of every feasible design found, columns :data:`PARAMETERS` [SI].
    mass, outer_radius, radius_bound, inertia, cg_radius, first_moment, balance :
        Their properties [kg, m, m, kg m^2, m, kg m, %].
    pareto : Indices of the Pareto-optimal designs (mass vs radial space, and inertia if
        asked), sorted by radial space.
    least_mass, least_radius : Indices of the least-mass and least-radius feasible designs.
    x, fun : Parameters and mass of the least-mass design (as scipy's ``x`` and ``fun``).
    radius_measure : ``"true"`` (largest distance of the profile from the axis) or
        ``"paper"`` (the R_min bound of Table 3); used for the constraint and the front.
    """

    designs: np.ndarray
    mass: np.ndarray
    outer_radius: np.ndarray
    radius_bound: np.ndarray
    inertia: np.ndarray
    cg_radius: np.ndarray
    first_moment: np.ndarray
    balance: np.ndarray
    pareto: np.ndarray
    least_mass: int
    least_radius: int
    x: np.ndarray
    fun: float
    nfev: int
    nit: int
    success: bool
    message: str
    required_first_moment: float
    density: float
    free: tuple[str, ...]
    objectives: tuple[str, ...]
    radius_measure: str
    elapsed: float
    parameter_names: tuple[str, ...] = PARAMETERS

    @property
    def radius(self) -> np.ndarray:
        """The radial space used in the constraint and the front [m]."""
        return self.outer_radius if self.radius_measure == "true" else self.radius_bound

    def design(self, index: int) -> CounterweightDesign:
        """The feasible design number ``index`` as a :class:`CounterweightDesign`."""
        r, h, delta, big_r, alpha, t = (float(v) for v in self.designs[index])
        return CounterweightDesign(r, h, delta, big_r, alpha, t, self.density)

    @property
    def least_mass_design(self) -> CounterweightDesign:
        return self.design(self.least_mass)

    @property
    def least_radius_design(self) -> CounterweightDesign:
        return self.design(self.least_radius)

    def pareto_table(self) -> list[dict[str, float]]:
        """The Pareto designs as rows (SI), least radius first."""
        return [self.row(int(i)) for i in self.pareto]

    def row(self, index: int) -> dict[str, float]:
        """One feasible design with its properties (SI)."""
        out = {name: float(self.designs[index, k]) for k, name in enumerate(PARAMETERS)}
        out.update(
            mass=float(self.mass[index]),
            outer_radius=float(self.outer_radius[index]),
            radius_bound=float(self.radius_bound[index]),
            inertia=float(self.inertia[index]),
            cg_radius=float(self.cg_radius[index]),
            first_moment=float(self.first_moment[index]),
            balance=float(self.balance[index]),
        )
        return out


def pareto_indices(objectives: np.ndarray) -> np.ndarray:
    """Indices of the non-dominated rows of ``objectives`` (minimisation), sorted by column 0.

    Exact duplicates keep one representative.
    """
    f = np.asarray(objectives, dtype=float)
    n, k = f.shape
    if n == 0:
        return np.zeros(0, dtype=int)
    order = np.lexsort(f.T[::-1])  # by column 0, then 1, ...
    if k == 2:
        second = f[order, 1]
        best_before = np.minimum.accumulate(np.r_[np.inf, second[:-1]])
        return order[second < best_before]
    if k == 3:
        return _pareto_3d(f, order)
    front: list[int] = []
    front_f = np.empty((0, k))
    chunk = 1024
    for start in range(0, n, chunk):
        idx = order[start : start + chunk]
        c = f[idx]
        dom = np.zeros(len(idx), dtype=bool)
        if len(front_f):
            le = np.all(front_f[:, None, :] <= c[None, :, :], axis=2)
            dom |= np.any(le, axis=0)
        le = np.all(c[:, None, :] <= c[None, :, :], axis=2)
        le &= np.tri(len(idx), k=-1, dtype=bool).T  # row i (earlier) dominates column j > i
        dom |= np.any(le, axis=0)
        keep = idx[~dom]
        front.extend(keep.tolist())
        front_f = np.vstack([front_f, f[keep]])
    return np.asarray(front, dtype=int)


def _pareto_3d(f: np.ndarray, order: np.ndarray) -> np.ndarray:
    """Three objectives, rows visited in lexicographic order: a row is dominated iff an
    earlier row has column 1 <= and column 2 <=, i.e. the prefix minimum of column 2 over
    the column-1 ranks reaches it. Chunks keep the work vectorised."""
    n = len(order)
    rank = np.empty(n, dtype=int)
    rank_sorted = np.searchsorted(np.unique(f[:, 1]), f[:, 1])
    rank[:] = rank_sorted
    best = np.full(int(rank.max()) + 1, np.inf)  # min column 2 per column-1 rank, so far
    keep_all = []
    chunk = 512
    for start in range(0, n, chunk):
        idx = order[start : start + chunk]
        c = f[idx]
        prefix = np.minimum.accumulate(best)
        dom = prefix[rank[idx]] <= c[:, 2]
        le = (c[:, None, 1] <= c[None, :, 1]) & (c[:, None, 2] <= c[None, :, 2])
        le &= np.tri(len(idx), k=-1, dtype=bool).T
        dom |= np.any(le, axis=0)
        keep_all.append(idx[~dom])
        np.minimum.at(best, rank[idx], c[:, 2])
    return np.concatenate(keep_all)


def hypervolume_2d(points: np.ndarray, reference: Sequence[float]) -> float:
    """Hypervolume (area) dominated by 2-objective ``points`` (minimisation) up to ``reference``."""
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    ref = np.asarray(reference, dtype=float)
    p = p[np.all(p < ref, axis=1)]
    if len(p) == 0:
        return 0.0
    p = p[pareto_indices(p)]  # sorted by column 0, column 1 decreasing
    widths = np.diff(np.r_[p[:, 0], ref[0]])
    return float(np.sum(widths * (ref[1] - p[:, 1])))


class _Problem:
    """Vectorised evaluation of designs for the optimiser."""

    def __init__(
        self,
        required,
        bounds,
        density,
        max_mass,
        max_radius,
        min_balance,
        radius_measure,
        objectives,
    ):
        self.required = required
        self.bounds = bounds
        self.density = density
        self.max_mass = max_mass
        self.max_radius = max_radius
        self.min_balance = min_balance
        self.radius_measure = radius_measure
        self.objectives = objectives
        shape = PARAMETERS[:5]
        self.free = tuple(n for n in shape if bounds[n][0] < bounds[n][1])
        self.free_index = np.array([shape.index(n) for n in self.free], dtype=int)
        self.low = np.array([bounds[n][0] for n in self.free])
        self.high = np.array([bounds[n][1] for n in self.free])
        self.fixed = np.array([bounds[n][0] for n in shape])
        self.t_low, self.t_high = bounds["thickness"]

    def full(self, x: np.ndarray) -> np.ndarray:
        out = np.repeat(self.fixed[None, :], len(x), axis=0)
        out[:, self.free_index] = x
        return out

    def evaluate(self, x: np.ndarray) -> dict[str, np.ndarray]:
        p = self.full(x)
        valid, _ = profile_validity(*p.T)
        safe = np.where(valid[:, None], p, np.array([1.0, 0.0, 0.0, 2.0, math.pi]))
        sec = profile_section(*safe.T)
        rho = self.density
        with np.errstate(divide="ignore", invalid="ignore"):
            t_need = self.min_balance / 100.0 * self.required / (rho * sec.first_moment)
        if self.t_low < self.t_high:
            t = np.maximum(t_need, self.t_low)
        else:
            t = np.full(len(x), self.t_low)
        mass = rho * t * sec.area
        first = rho * t * sec.first_moment
        balance = 100.0 * first / self.required
        radius = sec.outer_radius if self.radius_measure == "true" else sec.radius_bound
        inertia = rho * t * sec.polar_moment
        # normalised constraint violations (0 where satisfied)
        viol = np.where(valid, 0.0, 1e3)
        viol = viol + np.maximum(t / self.t_high - 1.0, 0.0) * valid
        viol = viol + np.where(valid, np.maximum(1.0 - balance / self.min_balance, 0.0), 0.0)
        if math.isfinite(self.max_mass):
            viol = viol + np.where(valid, np.maximum(mass / self.max_mass - 1.0, 0.0), 0.0)
        if math.isfinite(self.max_radius):
            viol = viol + np.where(valid, np.maximum(radius / self.max_radius - 1.0, 0.0), 0.0)
        viol = np.where(viol < 1e-12, 0.0, viol)
        full = np.column_stack([p, t])
        objs = {"mass": mass, "radius": radius, "inertia": inertia}
        return {
            "x": x,
            "params": full,
            "valid": valid,
            "feasible": valid & (viol == 0.0),
            "violation": viol,
            "mass": mass,
            "radius": radius,
            "outer_radius": sec.outer_radius,
            "radius_bound": sec.radius_bound,
            "inertia": inertia,
            "cg_radius": np.where(valid, sec.first_moment / np.where(valid, sec.area, 1.0), 0.0),
            "first_moment": first,
            "balance": balance,
            "f": np.column_stack([objs[o] for o in self.objectives]),
        }


def _sobol(n: int, d: int, rng: np.random.Generator) -> np.ndarray:
    from scipy.stats import qmc

    m = max(1, math.ceil(math.log2(max(n, 2))))
    return qmc.Sobol(d, scramble=True, seed=rng).random_base2(m)[:n]


def optimize_counterweight(
    required_first_moment: float,
    bounds: Mapping[str, float | tuple[float, float]] | None = None,
    *,
    density: float = DEFAULT_DENSITY,
    max_mass: float | None = None,
    max_radius: float | None = None,
    min_balance: float = 100.0,
    radius_measure: RadiusMeasure = "true",
    objectives: Sequence[Objective] = ("mass", "radius"),
    population: int = 4096,
    iterations: int = 40,
    children: int = 4096,
    rng: int | np.random.Generator | None = None,
    callback: Callable[[OptimizationProgress], bool | None] | None = None,
) -> CounterweightOptimum:
    """Feasible counterweights, their Pareto front and the least-mass / least-radius designs.

    The thickness is not searched: for each profile it follows in closed form from the
    required first moment (:func:`thickness_for_first_moment` at ``min_balance``, raised to
    the lower thickness bound if needed), because mass, radial space and inertia all grow
    with it. The remaining free profile parameters are searched by a vectorised archive
    method: a scrambled Sobol sample of ``population`` designs, then ``iterations`` rounds
    in which the current Pareto set breeds ``children`` Gaussian mutants (step shrinking
    geometrically from 10 % to 0.01 % of each range, some coordinates snapped to their
    bounds, where constrained optima lie). Every feasible design found is returned.

    Parameters
    ----------
    required_first_moment : float
        m_c r_c the counterweight must provide at 100 % balance [kg m] (from the balancing
        solver, or typed in).
    bounds : mapping, optional
        Parameter name (:data:`PARAMETERS`) -> ``(low, high)`` [SI] to leave it free within
        that range, or a number to fix it. Missing names take :data:`DEFAULT_BOUNDS`.
    density : float
        [kg/m^3].
    max_mass : float, optional
        Largest counterweight mass [kg].
    max_radius : float, optional
        Largest radial space [m] (measured as ``radius_measure``).
    min_balance : float
        Smallest acceptable balance, achieved / required first moment [%].
    radius_measure : {"true", "paper"}
        Radial space as the true outer radius or as the paper's bound R_min.
    objectives : sequence of {"mass", "radius", "inertia"}
        Objectives of the Pareto front; ``("mass", "radius", "inertia")`` adds inertia.
    population, iterations, children : int
        Initial sample size, refinement rounds and designs evaluated per round.
    rng : int or numpy.random.Generator, optional
        Seed for repeatable runs.
    callback : callable, optional
        Called with an :class:`OptimizationProgress` after each round; return True to stop.

    Returns
    -------
    CounterweightOptimum

    Raises
    ------
    InputError
        For bad bounds or constraints, or when no feasible design is found.

    References
    ----------
    .. [1] 2021 paper, Sec. 5 (fourth tab: constraints, parameter ranges,
       fixed/free selectors) and Table 3 (least mass, least radial space).
    """
    t0 = time.perf_counter()
    required = _check_positive_scalar("required_first_moment", required_first_moment)
    rho = _check_positive_scalar("density", density)
    b_min = _check_positive_scalar("min_balance", min_balance)
    m_max = math.inf if max_mass is None else _check_positive_scalar("max_mass", max_mass)
    r_max = math.inf if max_radius is None else _check_positive_scalar("max_radius", max_radius)
    if radius_measure not in ("true", "paper"):
        raise InputError("radius_measure", radius_measure, "must be 'true' or 'paper'")
    objs = tuple(objectives)
    if (
        not objs
        or any(o not in ("mass", "radius", "inertia") for o in objs)
        or len(set(objs)) != len(objs)
    ):
        raise InputError(
            "objectives", objectives, "distinct names from 'mass', 'radius', 'inertia'"
        )
    for name, v in (("population", population), ("iterations", iterations), ("children", children)):
        if (
            isinstance(v, bool)
            or not isinstance(v, (int, np.integer))
            or v < (0 if name == "iterations" else 1)
        ):
            raise InputError(name, v, "must be a positive integer")
    full_bounds = parse_bounds(bounds)
    gen = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)
    prob = _Problem(required, full_bounds, rho, m_max, r_max, b_min, radius_measure, objs)
    d = len(prob.free)
    span = prob.high - prob.low

    archive: list[dict[str, np.ndarray]] = []
    nfev = 0
    front_x = np.empty((0, d))
    front_f = np.empty((0, len(objs)))
    best_infeasible: tuple[np.ndarray, np.ndarray] | None = None

    def absorb(ev: dict[str, np.ndarray]) -> None:
        nonlocal front_x, front_f, best_infeasible, nfev
        nfev += len(ev["x"])
        feas = ev["feasible"]
        if np.any(feas):
            archive.append({k: v[feas] for k, v in ev.items()})
            cx = np.vstack([front_x, ev["x"][feas]])
            cf = np.vstack([front_f, ev["f"][feas]])
            keep = pareto_indices(cf)
            front_x, front_f = cx[keep], cf[keep]
        # keep the least-violating designs to steer the search while nothing is feasible
        cand_x = ev["x"] if best_infeasible is None else np.vstack([best_infeasible[0], ev["x"]])
        cand_v = (
            ev["violation"]
            if best_infeasible is None
            else np.r_[best_infeasible[1], ev["violation"]]
        )
        order = np.argsort(cand_v, kind="stable")[:64]
        best_infeasible = (cand_x[order], cand_v[order])

    if d == 0:
        absorb(prob.evaluate(np.zeros((1, 0))))
        iterations = 0
    else:
        x0 = prob.low + _sobol(population, d, gen) * span
        absorb(prob.evaluate(x0))

    sigma0, sigma1 = 0.1, 1e-4
    nit = 0
    message = "maximum number of iterations reached"
    for k in range(iterations):
        nit = k + 1
        sigma = sigma0 * (sigma1 / sigma0) ** (k / max(iterations - 1, 1))
        if len(front_x):
            parents = front_x
            if len(parents) > 256:  # thin evenly along the front (sorted by first objective)
                pick = np.unique(
                    np.r_[
                        np.linspace(0, len(parents) - 1, 256).round().astype(int),
                        np.argmin(front_f, axis=0),
                    ]
                )
                parents = parents[pick]
        else:
            assert best_infeasible is not None
            parents = best_infeasible[0]
        if len(front_x):
            # the extremes of the front (least mass, least radius, ...) get a share of their
            # own: they sit on active constraints, where progress needs many small steps
            elites = front_x[np.argmin(front_f, axis=0)]
            n_elite = children // (4 * len(objs))
            spread = children - n_elite * len(objs)
            base = np.vstack(
                [
                    np.repeat(elites, n_elite, axis=0),
                    np.repeat(parents, math.ceil(spread / len(parents)), axis=0)[:spread],
                ]
            )
        else:
            base = np.repeat(parents, math.ceil(children / len(parents)), axis=0)[:children]
        step = gen.standard_normal(base.shape) * (sigma * span)
        # a quarter of the children move along one coordinate only (line search on bounds)
        one = gen.random(len(base)) < 0.25
        mask = np.ones(base.shape, dtype=bool)
        mask[one] = False
        mask[one, gen.integers(0, d, one.sum())] = True
        xc = base + step * mask
        snap = gen.random(base.shape) < 0.02
        xc = np.where(snap, np.where(gen.random(base.shape) < 0.5, prob.low, prob.high), xc)
        xc = np.clip(xc, prob.low, prob.high)
        absorb(prob.evaluate(xc))
        if callback is not None:
            n_feas = sum(len(a["x"]) for a in archive)
            least = (
                float(front_f[:, objs.index("mass")].min())
                if (len(front_f) and "mass" in objs)
                else None
            )
            state = OptimizationProgress(
                nit, iterations, nfev, n_feas, len(front_x), least, time.perf_counter() - t0
            )
            if callback(state):
                message = "stopped by the callback"
                break

    if not archive:
        given = [f"required first moment {required:.6g} kg m", f"min_balance {b_min:g} %"]
        if max_mass is not None:
            given.append(f"max_mass {m_max:.6g} kg")
        if max_radius is not None:
            given.append(f"max_radius {r_max:.6g} m ({radius_measure})")
        closest = (
            "" if best_infeasible is None else f"; least violation {best_infeasible[1][0]:.3g}"
        )
        raise InputError(
            "constraints",
            None,
            f"infeasible: no counterweight within the parameter ranges meets "
            f"{', '.join(given)} ({nfev} designs tried{closest}). Relax max_mass, max_radius "
            "or min_balance, or widen the parameter ranges (thickness especially)",
        )
    allv = {k: np.concatenate([a[k] for a in archive]) for k in archive[0]}
    # remove exact duplicates (snapping and clipping repeat designs)
    _, uniq = np.unique(allv["params"], axis=0, return_index=True)
    uniq = np.sort(uniq)
    allv = {k: v[uniq] for k, v in allv.items()}
    pareto = pareto_indices(allv["f"])
    pareto = pareto[np.argsort(allv["radius"][pareto], kind="stable")]
    i_mass = int(np.lexsort((allv["radius"], allv["mass"]))[0])
    i_rad = int(np.lexsort((allv["mass"], allv["radius"]))[0])
    return CounterweightOptimum(
        designs=allv["params"],
        mass=allv["mass"],
        outer_radius=allv["outer_radius"],
        radius_bound=allv["radius_bound"],
        inertia=allv["inertia"],
        cg_radius=allv["cg_radius"],
        first_moment=allv["first_moment"],
        balance=allv["balance"],
        pareto=pareto,
        least_mass=i_mass,
        least_radius=i_rad,
        x=allv["params"][i_mass].copy(),
        fun=float(allv["mass"][i_mass]),
        nfev=nfev,
        nit=nit,
        success=True,
        message=message,
        required_first_moment=required,
        density=rho,
        free=prob.free,
        objectives=objs,
        radius_measure=radius_measure,
        elapsed=time.perf_counter() - t0,
    )


# --------------------------------------------------------------------------------------
# Exports: SVG, DXF (R12), STL, STEP (optional) and mass properties read back
# --------------------------------------------------------------------------------------

_MM = 1e3  # exports are written in millimetres (CAD convention)


def profile_svg(design: CounterweightDesign, *, show_web: bool = True) -> str:
    """The profile as an SVG document (millimetres, exact arcs, crank axis at the origin).

    SVG's y axis points down, so the drawing is flipped (``transform="scale(1,-1)"``) to
    keep the counterweight above the crank axis as in the paper's Fig. 5.
    """
    loops = profile_boundary(design)
    sec = design.properties()
    size = float(max(sec.outer_radius, design.web_radius)) * _MM * 1.05
    d = []
    for loop in loops:
        first = loop[0]
        start = first.start if isinstance(first, _Line) else first.point(first.start_angle)
        d.append(f"M {start[0] * _MM:.6f} {start[1] * _MM:.6f}")
        for it in loop:
            if isinstance(it, _Line):
                d.append(f"L {it.end[0] * _MM:.6f} {it.end[1] * _MM:.6f}")
            else:
                end = it.point(it.end_angle)
                large = 1 if abs(it.sweep) > math.pi else 0
                sweep = 1 if it.ccw else 0  # in the flipped (y up) frame
                d.append(
                    f"A {it.radius * _MM:.6f} {it.radius * _MM:.6f} 0 {large} {sweep} "
                    f"{end[0] * _MM:.6f} {end[1] * _MM:.6f}"
                )
        d.append("Z")
    web = ""
    if show_web:
        web = (
            f'<circle cx="0" cy="0" r="{design.web_radius * _MM:.6f}" fill="none" '
            'stroke="#c0392b" stroke-dasharray="2 1" stroke-width="0.3"/>'
        )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * size:.3f}mm" '
        f'height="{2 * size:.3f}mm" '
        f'viewBox="{-size:.3f} {-size:.3f} {2 * size:.3f} {2 * size:.3f}">\n'
        f"<title>crankbalance counterweight, mass {sec.mass * 1e3:.2f} g</title>\n"
        '<g transform="scale(1,-1)">\n'
        f'<path d="{" ".join(d)}" fill="#7f8c8d" fill-rule="evenodd" stroke="black" '
        'stroke-width="0.3"/>\n'
        f"{web}\n"
        '<path d="M -2 0 L 2 0 M 0 -2 L 0 2" stroke="black" stroke-width="0.2"/>\n'
        "</g>\n</svg>\n"
    )


def profile_dxf(design: CounterweightDesign) -> str:
    """The profile as a DXF R12 (AC1009) text file: LINE and ARC entities, millimetres.

    Layer ``COUNTERWEIGHT`` holds the closed profile, layer ``WEB`` the web circle.
    """
    out = [
        "0",
        "SECTION",
        "2",
        "HEADER",
        "9",
        "$ACADVER",
        "1",
        "AC1009",
        "9",
        "$INSUNITS",
        "70",
        "4",
        "0",
        "ENDSEC",
        "0",
        "SECTION",
        "2",
        "ENTITIES",
    ]

    def num(v: float) -> str:
        return f"{v:.9f}"

    for loop in profile_boundary(design):
        for it in loop:
            if isinstance(it, _Line):
                out += [
                    "0",
                    "LINE",
                    "8",
                    "COUNTERWEIGHT",
                    "10",
                    num(it.start[0] * _MM),
                    "20",
                    num(it.start[1] * _MM),
                    "30",
                    "0.0",
                    "11",
                    num(it.end[0] * _MM),
                    "21",
                    num(it.end[1] * _MM),
                    "31",
                    "0.0",
                ]
            else:
                a0, a1 = (
                    (it.start_angle, it.end_angle) if it.ccw else (it.end_angle, it.start_angle)
                )
                out += [
                    "0",
                    "ARC",
                    "8",
                    "COUNTERWEIGHT",
                    "10",
                    num(it.centre[0] * _MM),
                    "20",
                    num(it.centre[1] * _MM),
                    "30",
                    "0.0",
                    "40",
                    num(it.radius * _MM),
                    "50",
                    num(math.degrees(a0) % 360.0),
                    "51",
                    num(math.degrees(a1) % 360.0),
                ]
    out += [
        "0",
        "CIRCLE",
        "8",
        "WEB",
        "10",
        "0.0",
        "20",
        "0.0",
        "30",
        "0.0",
        "40",
        num(design.web_radius * _MM),
        "0",
        "ENDSEC",
        "0",
        "EOF",
    ]
    return "\n".join(out) + "\n"


def profile_mesh(
    design: CounterweightDesign, tolerance: float = 2e-6
) -> tuple[np.ndarray, np.ndarray]:
    """Closed triangle mesh of the counterweight prism [m]: (vertices (V, 3), faces (F, 3)).

    The crank axis is the z axis, the profile lies in ``0 <= z <= thickness``, the centre of
    gravity on ``+y``. The profile is cut into horizontal slabs at every vertex height of
    both arcs (chord error below ``tolerance`` [m]); each slab is a trapezoid between the
    web circle and the outer boundary, mirrored about ``x = 0``. A flat ledge
    (``trapezoid_angle = 0``) gets a slope of 1e-6 of the size so that slabs stay trapezoids.
    """
    r, h_r, delta, big_r, alpha = design.profile_parameters()
    sec = profile_section(r, h_r, delta, big_r, alpha)
    l_c, top, yc = float(sec.overhang), float(sec.top_height), float(sec.segment_centre)
    hub = bool(sec.hub_protrusion)
    eps = 1e-6 * max(r, big_r)
    if l_c > 0 and top - h_r < eps:
        # a flat ledge (delta = 0): give it a tiny slope so that every slab is a trapezoid
        # (changes the volume by about 1e-6 relative)
        top = h_r + eps
        yc = top - big_r * math.cos(alpha / 2)
    y_end = yc + big_r
    if hub:
        y_end = float(np.clip((r**2 - big_r**2 + yc**2) / (2 * yc), top, r))

    def angles(radius: float, a_max: float) -> np.ndarray:
        dphi = 2.0 * math.acos(max(-1.0, 1.0 - tolerance / radius))
        return np.linspace(0.0, a_max, max(2, math.ceil(a_max / dphi)) + 1)

    levels = np.r_[
        0.0,
        h_r,
        top,
        y_end,
        min(r, y_end),
        yc + big_r * np.cos(angles(big_r, math.pi)),
        r * np.cos(angles(r, math.pi / 2)),
    ]
    levels = np.unique(np.clip(levels, 0.0, y_end))
    levels = levels[np.r_[True, np.diff(levels) > 1e-12 * max(r, big_r)]]
    y = levels
    span = top - h_r
    frac = np.clip((y - h_r) / span, 0.0, 1.0) if span > 0 else (y > h_r).astype(float)
    w_out = np.where(y <= h_r, r, r + l_c * frac)
    w_out = np.where(y > top, np.sqrt(np.maximum(big_r**2 - (y - yc) ** 2, 0.0)), w_out)
    w_in = np.sqrt(np.maximum(r**2 - y**2, 0.0))
    w_in = np.minimum(w_in, w_out)
    n = len(y)
    # vertices of the right half: inner chain then outer chain; left half mirrored
    v2 = np.vstack([np.c_[w_in, y], np.c_[w_out, y], np.c_[-w_in, y], np.c_[-w_out, y]])
    k = np.arange(n - 1)
    i0, i1, o0, o1 = k, k + 1, n + k, n + k + 1
    right = np.r_[np.c_[i0, o0, o1], np.c_[i0, o1, i1]]
    left = right[:, ::-1] + 2 * n
    tri = np.r_[right, left]
    # merge coincident vertices (centre line, web-circle ends, hub crossing)
    key = np.round(v2 / (1e-9 * max(r, big_r)))
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    v2 = v2[first]
    tri = inverse.reshape(-1)[tri]
    tri = tri[(tri[:, 0] != tri[:, 1]) & (tri[:, 1] != tri[:, 2]) & (tri[:, 0] != tri[:, 2])]
    # zero-area triangles (collinear) are kept out as well
    p = v2[tri]
    area2 = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 2, 0] - p[:, 0, 0]) * (
        p[:, 1, 1] - p[:, 0, 1]
    )
    proper = np.abs(area2) > 1e-18 * max(r, big_r) ** 2
    tri, area2 = tri[proper], area2[proper]
    tri = np.where((area2 < 0)[:, None], tri[:, ::-1], tri)  # all counter-clockwise
    nv = len(v2)
    t = design.thickness
    vertices = np.vstack([np.c_[v2, np.zeros(nv)], np.c_[v2, np.full(nv, t)]])
    faces = [tri[:, ::-1], tri + nv]
    # walls on boundary edges (edges used by exactly one cap triangle)
    edges = np.r_[tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]
    undirected = np.sort(edges, axis=1)
    _, inv, counts = np.unique(undirected, axis=0, return_inverse=True, return_counts=True)
    boundary = edges[counts[inv.reshape(-1)] == 1]
    a, b = boundary[:, 0], boundary[:, 1]
    faces += [np.c_[a, b, b + nv], np.c_[a, b + nv, a + nv]]
    return vertices, np.vstack(faces)


def write_stl(design: CounterweightDesign, path: str | Path, tolerance: float = 2e-6) -> Path:
    """Write the counterweight prism as a binary STL in millimetres (see :func:`profile_mesh`)."""
    vertices, faces = profile_mesh(design, tolerance)
    tri = vertices[faces] * _MM
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = normals / np.where(norm > 0, norm, 1.0)
    record = np.zeros(len(faces), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["n"] = normals
    record["v"] = tri
    path = Path(path)
    with path.open("wb") as fh:
        fh.write(b"crankbalance counterweight, mm".ljust(80, b" "))
        fh.write(np.uint32(len(faces)).tobytes())
        fh.write(record.tobytes())
    return path


def _cad_missing(what: str) -> InputError:
    return InputError(
        "format", what, "STEP needs the optional CAD extra: pip install 'crankbalance[cad]'"
    )


def write_step(design: CounterweightDesign, path: str | Path) -> Path:
    """Write the counterweight as a STEP solid (millimetres) with build123d (``cad`` extra)."""
    try:
        import build123d as bd
    except ImportError:
        raise _cad_missing("step") from None
    faces = []
    for loop in profile_boundary(design):
        edges = []
        for it in loop:
            if isinstance(it, _Line):
                edges.append(
                    bd.Line(tuple(v * _MM for v in it.start), tuple(v * _MM for v in it.end))
                )
            else:
                mid = it.point(0.5 * (it.start_angle + it.end_angle))
                p0, p1 = it.point(it.start_angle), it.point(it.end_angle)
                edges.append(bd.ThreePointArc(*(tuple(v * _MM for v in p) for p in (p0, mid, p1))))
        faces.append(bd.Face(bd.Wire(edges)))
    solid = bd.extrude(
        bd.Sketch() + faces if len(faces) > 1 else faces[0], amount=design.thickness * _MM
    )
    path = Path(path)
    bd.export_step(solid, str(path))
    return path


def export_counterweight(
    design: CounterweightDesign, path: str | Path, fmt: ExportFormat | None = None
) -> Path:
    """Write ``design`` to ``path`` as SVG, DXF, STL or STEP (from the suffix unless ``fmt``)."""
    path = Path(path)
    kind = (fmt or path.suffix.lstrip(".")).lower()
    if kind in ("stp",):
        kind = "step"
    if kind not in ("svg", "dxf", "stl", "step"):
        raise InputError("format", kind, "one of svg, dxf, stl, step")
    try:
        if kind == "svg":
            path.write_text(profile_svg(design))
        elif kind == "dxf":
            path.write_text(profile_dxf(design))
        elif kind == "stl":
            write_stl(design, path)
        else:
            write_step(design, path)
    except OSError as error:
        raise InputError("path", str(path), f"must be a writable file ({error.strerror})") from None
    return path


@dataclass(frozen=True)
class MeshMassProperties(ResultMixin):
    """Mass properties of a CAD part read back from STL/STEP (SI).

    Attributes
    ----------
    volume : [m^3]. mass : [kg]. centre_of_gravity : (3,) [m].
    cg_radius : Distance of the centre of gravity from the crank axis [m].
    first_moment : mass * cg_radius [kg m].
    inertia : Mass moment of inertia about the crank axis [kg m^2].
    watertight : Whether the mesh is closed (otherwise the numbers are not trustworthy).
    balance : first_moment / required [%] if a requirement was given.
    """

    volume: float
    mass: float
    centre_of_gravity: np.ndarray
    cg_radius: float
    first_moment: float
    inertia: float
    watertight: bool
    balance: float | None = None


def mesh_mass_properties(
    path: str | Path,
    density: float = DEFAULT_DENSITY,
    *,
    length_unit: float = 1e-3,
    axis_point: Sequence[float] = (0.0, 0.0, 0.0),
    axis_direction: Sequence[float] = (0.0, 0.0, 1.0),
    required_first_moment: float | None = None,
) -> MeshMassProperties:
    """Read an STL (or STEP, with the ``cad`` extra) part and compute its mass properties.

    Parameters
    ----------
    path : str or Path
        The file (``.stl``, ``.step``/``.stp``; other mesh formats trimesh reads also work).
    density : float
        [kg/m^3].
    length_unit : float
        Metres per file unit (1e-3 for millimetres, as :func:`write_stl` writes).
    axis_point, axis_direction : sequence of 3 floats
        The crank axis in file units (a point on it and its direction).
    required_first_moment : float, optional
        [kg m]; gives the balance [%].
    """
    rho = _check_positive_scalar("density", density)
    scale = _check_positive_scalar("length_unit", length_unit)
    path = Path(path)
    if not path.is_file():
        raise InputError("path", str(path), "must be an existing STL or STEP file")
    try:
        import trimesh
    except ImportError:
        raise InputError(
            "path", str(path), "reading meshes needs trimesh: pip install 'crankbalance[geometry]'"
        ) from None
    if path.suffix.lower() in (".step", ".stp"):
        try:
            import build123d as bd
        except ImportError:
            raise _cad_missing(path.suffix) from None
        shape = bd.import_step(str(path))
        verts, tris = shape.tessellate(1e-4, 0.005)  # [file units], [rad]
        mesh = trimesh.Trimesh(np.array([tuple(v) for v in verts]), np.asarray(tris))
    else:
        try:
            mesh = trimesh.load_mesh(str(path), force="mesh")
        except Exception as error:  # noqa: BLE001 - any reader failure is bad input
            raise InputError("path", str(path), f"not a readable mesh ({error})") from None
    vertices = np.asarray(mesh.vertices, dtype=float) * scale
    mesh = trimesh.Trimesh(vertices, np.asarray(mesh.faces), process=False)
    volume = float(abs(mesh.volume))
    if not volume > 0:
        raise InputError("path", str(path), "the mesh encloses no volume")
    sign = 1.0 if mesh.volume > 0 else -1.0
    cg = np.asarray(mesh.center_mass, dtype=float)
    inertia_cg = (
        np.asarray(mesh.moment_inertia, dtype=float) * rho * sign
    )  # unit density in trimesh
    n = np.asarray(axis_direction, dtype=float)
    p0 = np.asarray(axis_point, dtype=float) * scale
    if n.shape != (3,) or not (np.all(np.isfinite(n)) and np.linalg.norm(n) > 0):
        raise InputError("axis_direction", axis_direction, "three finite numbers, not all zero")
    if p0.shape != (3,) or not np.all(np.isfinite(p0)):
        raise InputError("axis_point", axis_point, "three finite numbers")
    n = n / np.linalg.norm(n)
    rel = cg - p0
    perp = rel - np.dot(rel, n) * n
    dist = float(np.linalg.norm(perp))
    mass = rho * volume
    inertia = float(n @ inertia_cg @ n) + mass * dist**2
    first = mass * dist
    balance = None
    if required_first_moment is not None:
        balance = (
            100.0 * first / _check_positive_scalar("required_first_moment", required_first_moment)
        )
    return MeshMassProperties(
        volume, mass, cg, dist, first, inertia, bool(mesh.is_watertight), balance
    )
