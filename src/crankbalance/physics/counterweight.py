"""Parametric crankshaft counterweight: geometry, mass properties and one design.

This module owns the geometry of the counterweight profile and nothing else: the closed
forms of area, first and polar moments (:func:`profile_section`, :func:`circle_cap`), the
validity rules (:func:`profile_validity`, :func:`validate_profile`), mass properties
(:func:`counterweight_properties`), the thickness for a required first moment
(:func:`thickness_for_first_moment`, :func:`required_first_moment`), the frozen
:class:`CounterweightDesign` and its exact boundary (:func:`profile_boundary`, lines and
arcs, polygonised by :meth:`CounterweightDesign.outline`). The optimiser lives in
:mod:`crankbalance.physics.counterweight_optimize`, the CAD files (SVG, DXF, STL, STEP, mesh
read-back) in :mod:`crankbalance.io.cad`.

Why one module over 800 lines: the closed forms, the validity rules, the design
and the exact boundary all rest on the same intersection geometry (``l_c``, ``gamma``,
``lambda``, the hub crossing ``y*``), and every public function carries full numpydoc;
splitting them would scatter one derivation over modules.

The profile is the one of the 2021 crankshaft-balancing paper (Sec. 4, Fig. 5): a
rectangle ``h_R x 2 r_cw`` (orange), a trapezoid of flank angle ``delta`` that widens
by the overhang ``l_c`` on each side (blue) and a circular segment of radius ``R_cw``
and angle ``alpha`` whose chord closes the trapezoid (green). The base web circle of
radius ``r_cw`` (red, centred on the crank axis) is not part of the counterweight and
is cut out of the three zones. The counterweight is the prism of that profile with
thickness ``t_cw`` and density ``rho``.

Coordinates: the crank axis is the origin, ``y`` points from the axis towards the
counterweight (its centre of gravity lies on ``+y``), ``x`` across.

References
----------
.. [1] Applied Sciences 11 (2021) 8997, Sec. 4, Eqs. 24-30, Table 3; errata in
   docs/references.md: the orange centroid term is
   ``(2/3) r_cw^3 (1 - sin^3(gamma/2))``; the printed ``R_min`` is the bound
   ``h_R + l_c tan(delta) + R_cw``.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from ..errors import InputError
from ..records import record
from ..results import ResultMixin

ArrayLike = Any

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
#: Steel, as Table 3 of the paper implies (docs/references.md).
DEFAULT_DENSITY = 8000.0


# --------------------------------------------------------------------------------------
# Tier 1: pure, vectorised geometry
# --------------------------------------------------------------------------------------


class CircleCap(NamedTuple):
    """Area, first moment (in y) and polar second moment about the origin of a circle cap.

    Parameters
    ----------
    area : ndarray
        Area of the cap [m^2].
    first_moment : ndarray
        First moment ``int y dA`` about the x axis [m^3].
    polar_moment : ndarray
        Polar second moment ``int (x^2 + y^2) dA`` about the origin [m^4].
    """

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

    References
    ----------
    .. [1] Appl. Sci. 2021, Sec. 4, Eq. 26 (the segment areas this generalises); the moments
       are derived in docs/counterweight.md.
    """
    rho = np.asarray(radius, dtype=float)
    c = np.asarray(centre_y, dtype=float)
    theta = np.arccos(np.clip((np.asarray(cut_y, dtype=float) - c) / rho, -1.0, 1.0))
    s, co = np.sin(theta), np.cos(theta)
    area = rho**2 * (theta - s * co)
    s_c = 2.0 / 3.0 * rho**3 * s**3
    j_c = rho**4 * (theta / 2.0 - s * co * (s**2 + 3.0 * co**2) / 6.0)
    return CircleCap(area, c * area + s_c, j_c + 2.0 * c * s_c + c**2 * area)


def _strip_polar_moment(
    y0: np.ndarray, y1: np.ndarray, w0: np.ndarray, w1: np.ndarray
) -> np.ndarray:
    """Polar moment about the origin of ``|x| <= w(y)``, ``y0 <= y <= y1``, w linear.

    The integrand ``2/3 w^3 + 2 w y^2`` is a cubic in y, so Simpson's rule is exact.
    """
    ym, wm = 0.5 * (y0 + y1), 0.5 * (w0 + w1)

    def f(y: np.ndarray, w: np.ndarray) -> np.ndarray:
        return 2.0 / 3.0 * w**3 + 2.0 * w * y**2

    return (y1 - y0) / 6.0 * (f(y0, w0) + 4.0 * f(ym, wm) + f(y1, w1))


class ProfileSection(NamedTuple):
    """Section properties of the counterweight profile (arrays, SI).

    ``first_moment`` is the area first moment ``int y dA`` [m^3] about the crank axis,
    ``polar_moment`` the polar second moment ``int (x^2 + y^2) dA`` [m^4] about it.
    ``hub_protrusion`` is True where the web circle reaches out through the segment's arc
    (the regime where the paper's Eqs. 26/30 need the correction, see the docs).

    Parameters
    ----------
    area : ndarray
        Profile area A_cw [m^2] (Eq. 27).
    first_moment : ndarray
        ``int y dA`` about the crank axis [m^3].
    polar_moment : ndarray
        ``int (x^2 + y^2) dA`` about the crank axis [m^4].
    area_green, area_blue, area_orange : ndarray
        Areas of the segment, trapezoid and rectangle zones, web circle cut out [m^2]
        (Eq. 26).
    cg_green, cg_blue, cg_orange : ndarray
        y of the centroid of each zone [m]; 0 where the zone is empty.
    overhang : ndarray
        l_c, how far the trapezoid widens on each side beyond the web circle [m].
    gamma, lam : ndarray
        Angles gamma and lambda at which the web circle crosses the top of the rectangle
        and the chord of the segment [rad] (Eqs. 24-25).
    top_height : ndarray
        y of the segment's chord, h_R + l_c tan(delta) [m].
    segment_centre : ndarray
        y of the centre of the segment's circle [m].
    outer_radius : ndarray
        Largest distance of the profile from the crank axis [m].
    radius_bound : ndarray
        The paper's R_min = h_R + l_c tan(delta) + R_cw [m] (Table 3), a bound.
    hub_protrusion : ndarray of bool
        Where the web circle reaches out through the segment's arc (a mask) [-].

    References
    ----------
    Appl. Sci. 2021, Sec. 4, Eqs. 24-30, Table 3, with the errata of docs/references.md.
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
        Areas [m^2], moments [m^3, m^4], intersection angles [rad] and radii [m].

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
    .. [1] Appl. Sci. 2021, Sec. 4, Eqs. 24-30; errata in docs/references.md.
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

    def seg(radius: ArrayLike, angle: ArrayLike) -> np.ndarray:
        # area of a circular segment of full angle `angle`
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
    """Which parameter sets form a valid profile, and why not (vectorised, never raises).

    Parameters
    ----------
    web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle : array_like
        Profile parameters r_cw [m], h_R [m], delta [rad], R_cw [m], alpha [rad].

    Returns
    -------
    valid : ndarray of bool
        True where the set is a valid profile.
    reason : ndarray of int
        0 for valid, else ``1 + index`` of the first failed rule in :data:`PROFILE_REASONS`.

    References
    ----------
    .. [1] Appl. Sci. 2021, Sec. 4, Fig. 5 (the profile the rules keep well formed).
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
    """Raise :class:`InputError` naming the parameter if any set is not a valid profile.

    Parameters
    ----------
    web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle : array_like
        Profile parameters r_cw [m], h_R [m], delta [rad], R_cw [m], alpha [rad].

    Raises
    ------
    InputError
        For the first invalid set, naming the parameter (``[index]`` for arrays).

    References
    ----------
    .. [1] Appl. Sci. 2021, Sec. 4, Fig. 5.
    """
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


@record
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
    overhang : l_c [m].
    gamma : Intersection angle gamma of the web circle and the rectangle [rad] (Eq. 25).
    lam : Intersection angle lambda of the web circle and the chord [rad] (Eq. 24).
    area_green, area_blue, area_orange : Zone areas [m^2] (Eq. 26).
    hub_protrusion : True where the web circle reaches out through the segment's arc [-].
    balance : Achieved / required first moment [%] (only if a requirement was given).
    """

    area: float | np.ndarray
    volume: float | np.ndarray
    mass: float | np.ndarray
    cg_radius: float | np.ndarray
    first_moment: float | np.ndarray
    inertia: float | np.ndarray
    outer_radius: float | np.ndarray
    radius_bound: float | np.ndarray
    overhang: float | np.ndarray
    gamma: float | np.ndarray
    lam: float | np.ndarray
    area_green: float | np.ndarray
    area_blue: float | np.ndarray
    area_orange: float | np.ndarray
    hub_protrusion: bool | np.ndarray
    balance: float | np.ndarray | None = None


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
        Scalars for scalar input, else arrays (SI).

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
    .. [1] Appl. Sci. 2021, Sec. 4, Eqs. 26-30.
    """
    validate_profile(web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle)
    _check_material(thickness, density)
    if required_first_moment is not None:
        check_positive_number("required_first_moment", required_first_moment)
    sec = profile_section(
        web_radius, rectangle_height, trapezoid_angle, segment_radius, segment_angle
    )
    return _properties_from_section(sec, thickness, density, required_first_moment)


def _properties_from_section(
    sec: ProfileSection,
    thickness: ArrayLike,
    density: ArrayLike,
    required_first_moment: float | None = None,
) -> CounterweightProperties:
    t = np.asarray(thickness, dtype=float)
    rho = np.asarray(density, dtype=float)
    mass = rho * t * sec.area
    first = rho * t * sec.first_moment
    balance = None if required_first_moment is None else 100.0 * first / required_first_moment

    def out(v: ArrayLike) -> float | np.ndarray:
        a = np.asarray(v)
        return a.item() if a.ndim == 0 else a

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
        hub_protrusion=bool(sec.hub_protrusion)
        if np.ndim(sec.hub_protrusion) == 0
        else sec.hub_protrusion,
        balance=None if balance is None else out(balance),
    )


def check_positive_number(name: str, value: Any) -> float:
    """A number greater than zero as a float, or :class:`~crankbalance.errors.InputError`
    naming the field (also for a value that is not a number).

    Parameters
    ----------
    name : str
        The field to name in the error.
    value : float
        The number [its unit].

    Returns
    -------
    float
        ``value``, finite and greater than zero [its unit].
    """
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
    web_radius : array_like
        Radius r_cw of the base crank-web circle [m].
    rectangle_height : array_like
        Height h_R of the rectangle above the crank axis [m].
    trapezoid_angle : array_like
        Flank angle delta of the trapezoid [rad].
    segment_radius : array_like
        Radius R_cw of the circular segment [m].
    segment_angle : array_like
        Angle alpha subtended by the segment's arc at its centre [rad].
    density : float
        Material density rho [kg/m^3].
    balance : float
        Target balance, achieved / required first moment [%].

    Returns
    -------
    float or ndarray
        Thickness t_cw [m].

    References
    ----------
    .. [1] Appl. Sci. 2021, Sec. 4, Eqs. 28-30 (mass and first moment are linear in t_cw).
    """
    u = check_positive_number("required_first_moment", required_first_moment)
    rho = check_positive_number("density", density)
    b = check_positive_number("balance", balance)
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
    counterweights : crankbalance.physics.balancing.Counterweights
        The balancing solver's crank counterweights (``mass`` [kg] per web at ``cg_radius`` [m]).
    web : int, optional
        Web number (1-based, as in ``counterweights.web``); by default the largest one.

    Returns
    -------
    float
        m_c r_c [kg m].

    References
    ----------
    .. [1] Appl. Sci. 2021, Eqs. 9-10 (m_c at r_c) and Sec. 4 (the shape must carry it).
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
    return check_positive_number("required_first_moment", m * float(counterweights.cg_radius))


# --------------------------------------------------------------------------------------
# Tier 2: one design
# --------------------------------------------------------------------------------------


@record
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
        """Mass properties (see :func:`counterweight_properties`).

        Parameters
        ----------
        required_first_moment : float, optional
            m_c r_c the balancing asks for [kg m]; gives ``balance`` [%].

        Returns
        -------
        CounterweightProperties
            Mass properties (SI).
        """
        return counterweight_properties(
            *self.profile_parameters(), self.thickness, self.density, required_first_moment
        )

    def with_thickness_for(
        self, required_first_moment: float, balance: float = 100.0
    ) -> CounterweightDesign:
        """The same profile with the thickness that gives ``balance`` % of the requirement.

        Parameters
        ----------
        required_first_moment : float
            m_c r_c asked for by the balancing [kg m].
        balance : float
            Target balance [%].

        Returns
        -------
        CounterweightDesign
            Same profile and density, thickness t_cw [m] from
            :func:`thickness_for_first_moment`.
        """
        t = thickness_for_first_moment(
            required_first_moment, *self.profile_parameters(), density=self.density, balance=balance
        )
        return CounterweightDesign(*self.profile_parameters(), float(t), self.density)

    def outline(self, tolerance: float = 1e-5) -> list[np.ndarray]:
        """Closed boundary loops of the profile, counter-clockwise, as (N, 2) arrays [m].

        One loop normally; two (left and right horn) when the web circle pokes out
        through the segment's arc. Arcs are polygonised with a chord error below
        ``tolerance`` [m].

        Parameters
        ----------
        tolerance : float
            Largest chord error of the polygonised arcs [m].

        Returns
        -------
        list of ndarray
            (N, 2) points (x, y) [m] of each loop.
        """
        return [_sample_loop(loop, tolerance) for loop in profile_boundary(self)]


# --------------------------------------------------------------------------------------
# Boundary (exact primitives) for exports and polygons
# --------------------------------------------------------------------------------------


@record
class BoundaryLine:
    """A straight piece of the profile boundary from ``start`` to ``end`` (x, y) [m].

    Parameters
    ----------
    start, end : tuple of float
        End points (x, y) [m], crank axis at the origin.
    """

    start: tuple[float, float]
    end: tuple[float, float]


@record
class BoundaryArc:
    """A circular piece of the profile boundary: ``centre`` (x, y) [m], ``radius`` [m],
    from ``start_angle`` to ``end_angle`` [rad], counter-clockwise if ``ccw``.

    Parameters
    ----------
    centre : tuple of float
        Centre (x, y) of the circle [m].
    radius : float
        Radius of the circle [m].
    start_angle, end_angle : float
        Polar angles about ``centre`` where the arc starts and ends [rad].
    ccw : bool
        Whether the arc runs counter-clockwise from start to end.
    """

    centre: tuple[float, float]
    radius: float
    start_angle: float  # rad
    end_angle: float  # rad; the arc runs from start to end, counter-clockwise if ccw
    ccw: bool

    def point(self, angle: float) -> tuple[float, float]:
        """The point (x, y) [m] of the circle at ``angle``.

        Parameters
        ----------
        angle : float
            Polar angle about :attr:`centre` [rad].
        """
        return (
            self.centre[0] + self.radius * math.cos(angle),
            self.centre[1] + self.radius * math.sin(angle),
        )

    @property
    def sweep(self) -> float:
        """Angle swept from start to end [rad], positive for either direction."""
        d = self.end_angle - self.start_angle
        return d if self.ccw else -d


def profile_boundary(design: CounterweightDesign) -> list[list[BoundaryLine | BoundaryArc]]:
    """The boundary loops of the profile as exact lines and arcs (counter-clockwise).

    Parameters
    ----------
    design : CounterweightDesign
        The counterweight (its thickness and density are not used).

    Returns
    -------
    list of list of BoundaryLine or BoundaryArc
        One closed loop normally; two (left and right horn) when the web circle pokes out
        through the segment's arc.

    References
    ----------
    .. [1] Appl. Sci. 2021, Sec. 4, Fig. 5.
    """
    r, h_r, delta, big_r, alpha = design.profile_parameters()
    sec = profile_section(r, h_r, delta, big_r, alpha)
    l_c, top, yc = float(sec.overhang), float(sec.top_height), float(sec.segment_centre)
    corner = (r + l_c, top)
    phi_r = math.atan2(top - yc, r + l_c)  # angle of the right chord end seen from the centre
    loops: list[list[BoundaryLine | BoundaryArc]] = []

    def right_side() -> list[BoundaryLine | BoundaryArc]:
        items: list[BoundaryLine | BoundaryArc] = []
        if h_r > 0:
            items.append(BoundaryLine((r, 0.0), (r, h_r)))
        if math.hypot(l_c, top - h_r) > 0:
            items.append(BoundaryLine((r, h_r), corner))
        return items

    def mirror(items: list[BoundaryLine | BoundaryArc]) -> list[BoundaryLine | BoundaryArc]:
        out: list[BoundaryLine | BoundaryArc] = []
        for it in reversed(items):
            if isinstance(it, BoundaryLine):
                out.append(BoundaryLine((-it.end[0], it.end[1]), (-it.start[0], it.start[1])))
            else:
                out.append(
                    BoundaryArc(
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
        loop.append(BoundaryArc((0.0, yc), big_r, phi_r, math.pi - phi_r, True))
        loop += mirror(right_side())
        loop.append(BoundaryArc((0.0, 0.0), r, math.pi, 0.0, False))  # web circle, left to right
        loops.append(loop)
    else:
        y_star = float(np.clip((r**2 - big_r**2 + yc**2) / (2 * yc), top, r))
        x_star = math.sqrt(max(r**2 - y_star**2, 0.0))
        right = right_side()
        right.append(BoundaryArc((0.0, yc), big_r, phi_r, math.atan2(y_star - yc, x_star), True))
        right.append(BoundaryArc((0.0, 0.0), r, math.atan2(y_star, x_star), 0.0, False))
        loops.append(right)
        loops.append(mirror(right))
    return loops


def _sample_loop(loop: list[BoundaryLine | BoundaryArc], tolerance: float) -> np.ndarray:
    points: list[tuple[float, float]] = []
    for item in loop:
        if isinstance(item, BoundaryLine):
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
