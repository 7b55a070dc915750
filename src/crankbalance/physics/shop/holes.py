r"""Drilled holes with their drill point, and drilling plans for a correction in one plane.

**A drilled hole.** A twist drill of diameter :math:`d` and point angle :math:`\alpha`
(118° for the usual jobber drill, 180° for a flat bottom) cuts a cylinder of length
:math:`s`, the depth to the *shoulder* where the full diameter ends, and a cone of height
:math:`h = (d/2)/\tan(\alpha/2)` beyond it; the depth to the *tip* is :math:`t = s + h`. A
depth gauge reads one or the other, so every function here takes the reference as a
required argument. With :math:`A = \pi d^2/4` and depths along the hole axis from the
entry face:

.. math::
    V = A\,(s + h/3),\qquad S = A\,\frac{s^2}{2} + \frac{A h}{3}\Big(s + \frac{h}{4}\Big),
    \qquad z_c = S/V

(the centroid of a cone lies a quarter of its height from its base). A hole read to the tip
and shallower than its point (:math:`t < h`) is a cone of height :math:`t`:
:math:`V = A t^3/(3h^2)`, :math:`z_c = t/4`. An axial hole (parallel to the crank axis) at
radius :math:`\rho` has its centroid at that radius; a radial hole drilled inward from a
rim at radius :math:`R` has it at :math:`r_c = R - z_c`. Its first moment about the crank
axis is :math:`\rho_m V r_c`.

The entry face is taken flat and square to the hole. A radial hole in a round rim of radius
:math:`R` meets a curved face and, with the depth read from the rim on the hole axis,
leaves about :math:`\pi d^4/(128 R)` undrilled (2.5 mm³ for an 8 mm hole at 40 mm).

**A drilling plan** takes a required correction, an unbalance :math:`U` [kg m] at the
heavy-spot angle :math:`\varphi` in one correction plane, off with :math:`n` equal holes at
:math:`\varphi + (k - (n-1)/2)\,p`, :math:`k = 0..n-1` (symmetric about the heavy spot, so
the resultant lies on it), or puts heavy-metal slugs at the light spot
:math:`\varphi + \pi`. The pitch :math:`p` is the least that leaves ``spacing`` of material
between neighbouring holes: :math:`2 r_i \sin(p/2) = d + \mathrm{spacing}` with
:math:`r_i` the radius of the innermost full-diameter section (the hole axis for axial
holes, the shoulder at the largest depth for radial holes, where radial holes come closest).
The fewest holes whose depth stays within ``max_depth`` are used; the depth is rounded to the
machining step and the residual predicted from the rounded depth.

**What a drill can do** (:func:`check_drill`, :func:`depth_limit`). A correction plan takes
no drill below :data:`MIN_DRILL_DIAMETER` (1 mm) and no hole deeper, to the tip, than
:data:`MAX_DEPTH_RATIO` (10) times the drill, the reach of a standard jobber drill, nor
deeper than the part (an axial hole in a web of a given thickness). An axial hole must not
reach the crank axis (its drill smaller than twice its radius), a radial hole must fit in the
web's thickness. A plan that needs deeper holes spreads the material over more holes, and
says so (:attr:`DrillingPlan.note`); when no number of holes fits, it is refused, naming the
drill and the limit.

SI units throughout; angles in radians, counterclockwise seen along the crank axis.

Why one module over 800 lines: a hole and a plan of holes are one subject, the plan is
the geometry of its holes (their depth, centroid and pitch), and the limits of a drill
bind both.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError, check_nonnegative, check_positive
from ...records import record
from ...results import ResultMixin

#: Density of crankshaft steel used when none is given [kg/m^3] (Hoem and Røsholm (2016),
#: Appendix E).
STEEL_DENSITY = 7850.0
#: Point angle of a standard twist drill [rad] (118°).
DEFAULT_POINT_ANGLE = math.radians(118.0)
#: Point angle of a flat-bottomed hole [rad] (180°: no cone).
FLAT_BOTTOM = math.pi

#: Smallest drill a correction plan takes [m]: a smaller twist drill breaks in crank steel,
#: and a hole of it takes off next to nothing (1 mm, 10 mm deep: 0.06 g of steel).
MIN_DRILL_DIAMETER = 1e-3
#: Deepest hole a correction plan takes, to the tip, in drill diameters: the reach of a
#: standard (jobber) twist drill, whose flutes are about ten diameters long (DIN 338; an
#: 8 mm drill: 75 mm); deeper holes need long-series or gun drills.
MAX_DEPTH_RATIO = 10.0

DepthReference = Literal["shoulder", "tip"]
HoleDirection = Literal["axial", "radial"]
DEPTH_REFERENCES: tuple[str, ...] = ("shoulder", "tip")


def round_depth(depth: float, resolution: float) -> float:
    """A depth rounded to the nearest step of the machining resolution.

    Parameters
    ----------
    depth : float
        Depth [m].
    resolution : float
        Machining step [m]; 0 leaves the depth as it is.

    Returns
    -------
    float
        The rounded depth [m].
    """
    return depth if resolution <= 0 else round(depth / resolution) * resolution


def cone_height(diameter: float, point_angle: float = DEFAULT_POINT_ANGLE) -> float:
    r"""Height of the drill-point cone, :math:`h = (d/2)/\tan(\alpha/2)` [m].

    Parameters
    ----------
    diameter : float
        Drill diameter :math:`d` [m].
    point_angle : float
        Included point angle :math:`\alpha` in (0, pi] [rad]; pi is a flat bottom.

    Returns
    -------
    float
        :math:`h` [m]; 0 for a flat bottom.
    """
    check_positive("diameter", diameter)
    if not (0.0 < point_angle <= math.pi):
        raise InputError(
            "point_angle",
            point_angle,
            "must be an angle greater than 0 and at most 180 deg (pi rad, a flat bottom) [rad]",
        )
    return 0.0 if point_angle == math.pi else 0.5 * diameter / math.tan(0.5 * point_angle)


def _mm(value: float) -> str:
    return f"{value * 1e3:.4g} mm"


def _named(names: Mapping[str, str] | None, name: str) -> str:
    return name if names is None else names.get(name, name)


def check_drill(diameter: float, names: Mapping[str, str] | None = None) -> float:
    """Refuse a drill smaller than :data:`MIN_DRILL_DIAMETER`.

    Parameters
    ----------
    diameter : float
        Drill diameter [m].
    names : mapping of str to str, optional
        How the user named the quantities (``{"diameter": "--hole-diameter"}``).

    Returns
    -------
    float
        The diameter [m].
    """
    check_positive(_named(names, "diameter"), diameter)
    if diameter < MIN_DRILL_DIAMETER * (1 - 1e-12):
        raise InputError(
            _named(names, "diameter"),
            _mm(diameter),
            f"must be at least {_mm(MIN_DRILL_DIAMETER)}: a smaller twist drill breaks in "
            "crank steel and takes off next to nothing",
        )
    return float(diameter)


def depth_limit(
    diameter: float,
    part_depth: float | None = None,
    names: Mapping[str, str] | None = None,
    drill_length: float | None = None,
) -> tuple[float, str]:
    """The deepest hole a drill may make in a part, to the tip, and where the limit comes
    from: the drill's length (else :data:`MAX_DEPTH_RATIO` drill diameters), or the part's
    depth when that is less.

    Parameters
    ----------
    diameter : float
        Drill diameter [m].
    part_depth : float, optional
        How deep the part is along the hole (the web's thickness for an axial hole) [m];
        None when not known (then the drill's reach alone limits, and the words say so).
    names : mapping of str to str, optional
        How the user named the quantities (``{"web_thickness": "--web-thickness"}``).
    drill_length : float, optional
        The drill's usable length (its flutes) [m]; None: a jobber drill's,
        :data:`MAX_DEPTH_RATIO` diameters.

    Returns
    -------
    limit : float
        Deepest tip depth [m].
    words : str
        The limit and where it comes from, for messages.
    """
    reach = MAX_DEPTH_RATIO * diameter if drill_length is None else drill_length
    thickness = _named(names, "web_thickness")
    if part_depth is not None and part_depth <= reach:
        return float(part_depth), f"the part's depth, {thickness} = {_mm(part_depth)}"
    words = (
        f"{MAX_DEPTH_RATIO:g} times the {_mm(diameter)} drill, {_mm(reach)}, the reach of a "
        "jobber drill"
        if drill_length is None
        else f"the drill's length, {_named(names, 'drill_length')} = {_mm(reach)}"
    )
    if part_depth is None:
        words += f" (the part's depth is not given: {thickness})"
    return float(reach), words


def _check_reference(depth_to: str) -> None:
    if depth_to not in DEPTH_REFERENCES:
        raise InputError(
            "depth_to",
            depth_to,
            "must be 'shoulder' (the depth read to the end of the full diameter) or 'tip' "
            "(read to the drill point)",
        )


def _check_direction(direction: str) -> None:
    if direction not in ("axial", "radial"):
        raise InputError("direction", direction, "must be 'axial' or 'radial'")


@record
class HoleGeometry(ResultMixin):
    """Volume and centroid of drilled holes (arrays the shape of the depth given).

    Attributes
    ----------
    volume : ndarray
        Material removed by one hole [m^3].
    centroid_depth : ndarray
        Depth of its centroid along the hole axis from the entry face [m] (0 for no hole).
    shoulder_depth, tip_depth : ndarray
        Depth to the end of the full diameter and to the drill point [m] (a hole read to
        the tip and shallower than its point has no shoulder: 0).
    cone_height : float
        Height of the drill-point cone [m].
    """

    volume: NDArray
    centroid_depth: NDArray
    shoulder_depth: NDArray
    tip_depth: NDArray
    cone_height: float


def hole_geometry(
    diameter: float,
    depth: ArrayLike,
    depth_to: DepthReference,
    point_angle: float = DEFAULT_POINT_ANGLE,
) -> HoleGeometry:
    r"""Volume and centroid of a drilled hole with its drill point, in closed form.

    Parameters
    ----------
    diameter : float
        Drill diameter :math:`d` [m].
    depth : array_like
        Depth of the hole as read [m], >= 0, any shape.
    depth_to : {"shoulder", "tip"}
        What the depth is read to: the shoulder (end of the full diameter) or the tip of
        the drill point.
    point_angle : float
        Included point angle [rad]; :data:`DEFAULT_POINT_ANGLE` (118°), pi for a flat bottom.

    Returns
    -------
    HoleGeometry
        Volume [m^3], centroid depth [m], shoulder and tip depths [m].

    Notes
    -----
    .. math::
        V = A(s + h/3),\quad z_c = \frac{A s^2/2 + (A h/3)(s + h/4)}{V},\quad
        A = \pi d^2/4,\ h = \frac{d/2}{\tan(\alpha/2)}

    and for a point alone (:math:`t < h`): :math:`V = A t^3/(3h^2)`, :math:`z_c = t/4`.
    """
    h = cone_height(diameter, point_angle)
    _check_reference(depth_to)
    given = np.asarray(depth, dtype=float)
    if not np.all(np.isfinite(given) & (given >= 0)):
        raise InputError("depth", depth, "must be finite depths >= 0 [m]")
    tip = given + h if depth_to == "shoulder" else given
    shoulder = np.maximum(tip - h, 0.0)
    area = math.pi * diameter**2 / 4.0
    full = tip >= h
    partial = np.where(full, 0.0, tip)  # the point alone, t < h (never when h = 0)
    h_safe = h if h > 0 else 1.0
    volume = np.where(full, area * (shoulder + h / 3.0), area * partial**3 / (3.0 * h_safe**2))
    moment = np.where(
        full,
        area * shoulder**2 / 2.0 + area * h / 3.0 * (shoulder + h / 4.0),
        volume * partial / 4.0,
    )
    centroid = np.divide(moment, volume, out=np.zeros_like(volume), where=volume > 0)
    return HoleGeometry(volume, centroid, shoulder, tip, h)


def depth_for_volume(
    diameter: float,
    volume: float,
    depth_to: DepthReference,
    point_angle: float = DEFAULT_POINT_ANGLE,
) -> float:
    r"""Depth of a hole that removes a given volume: the inverse of :func:`hole_geometry`.

    Parameters
    ----------
    diameter : float
        Drill diameter [m].
    volume : float
        Volume to remove with one hole [m^3], >= 0.
    depth_to : {"shoulder", "tip"}
        Reference of the depth returned.
    point_angle : float
        Included point angle [rad].

    Returns
    -------
    float
        Depth as read to ``depth_to`` [m]. A volume smaller than the point's cone read to
        the shoulder gives 0 (the least such a hole removes is its point).
    """
    h = cone_height(diameter, point_angle)
    _check_reference(depth_to)
    check_nonnegative("volume", volume)
    area = math.pi * diameter**2 / 4.0
    cone = area * h / 3.0
    if volume >= cone:
        shoulder = volume / area - h / 3.0
        return shoulder if depth_to == "shoulder" else shoulder + h
    return 0.0 if depth_to == "shoulder" else (3.0 * volume * h**2 / area) ** (1.0 / 3.0)


@record
class HoleMass(ResultMixin):
    """Mass properties of drilled holes about the crank axis (arrays the shape of the depth).

    Attributes
    ----------
    volume : ndarray
        Volume of one hole [m^3].
    mass : ndarray
        Mass it removes [kg].
    centroid_depth : ndarray
        Depth of its centroid along the hole axis from the entry face [m].
    centroid_radius : ndarray
        Distance of its centroid from the crank axis [m].
    first_moment : ndarray
        Mass times centroid radius, the unbalance it removes [kg m].
    """

    volume: NDArray
    mass: NDArray
    centroid_depth: NDArray
    centroid_radius: NDArray
    first_moment: NDArray


def hole_mass_properties(
    diameter: float,
    depth: ArrayLike,
    depth_to: DepthReference,
    direction: HoleDirection,
    radius: float,
    density: float = STEEL_DENSITY,
    point_angle: float = DEFAULT_POINT_ANGLE,
) -> HoleMass:
    r"""Mass, centroid and first moment about the crank axis of a drilled hole.

    Parameters
    ----------
    diameter : float
        Drill diameter [m].
    depth : array_like
        Depth as read [m], >= 0, any shape.
    depth_to : {"shoulder", "tip"}
        What the depth is read to.
    direction : {"axial", "radial"}
        Axial: parallel to the crank axis, its axis at ``radius``; radial: drilled toward
        the crank axis from a rim at ``radius``.
    radius : float
        Radius of the hole axis (axial) or of the rim where the hole starts (radial) [m].
    density : float
        Density of the material drilled [kg/m^3].
    point_angle : float
        Included point angle [rad]; pi for a flat bottom.

    Returns
    -------
    HoleMass
        Volume [m^3], mass [kg], centroid depth and radius [m], first moment [kg m].

    Notes
    -----
    .. math:: r_c = \rho\ \text{(axial)},\qquad r_c = R - z_c\ \text{(radial)},\qquad
        U = \rho_m V r_c
    """
    _check_direction(direction)
    check_positive("radius", radius)
    check_positive("density", density)
    geometry = hole_geometry(diameter, depth, depth_to, point_angle)
    if direction == "radial" and np.any(geometry.tip_depth >= radius):
        raise InputError(
            "depth",
            depth,
            f"a radial hole from radius {radius * 1e3:.4g} mm must end short of the crank "
            "axis: a tip depth less than the radius",
        )
    mass = density * geometry.volume
    centroid_radius = (
        np.full_like(mass, radius) if direction == "axial" else radius - geometry.centroid_depth
    )
    return HoleMass(
        volume=geometry.volume,
        mass=mass,
        centroid_depth=geometry.centroid_depth,
        centroid_radius=centroid_radius,
        first_moment=mass * centroid_radius,
    )


@record
class DrillingPlan(ResultMixin):
    """Holes (or heavy-metal slugs) that correct an unbalance in one correction plane.

    Attributes
    ----------
    method : str
        ``"drill"`` (material taken off at the heavy spot) or ``"heavy metal"`` (slugs
        pressed into holes drilled at the light spot, filling them to the shoulder).
    direction : str
        ``"axial"`` or ``"radial"`` holes.
    depth_to : str
        What :attr:`depth` is read to: ``"shoulder"`` or ``"tip"``.
    diameter : float
        Drill (and slug) diameter [m].
    point_angle : float
        Included drill-point angle [rad].
    radius : float
        Radius of the hole axes (axial) or of the rim where the holes start (radial) [m].
    unbalance : complex
        Unbalance to correct, :math:`U e^{i\\varphi}` with :math:`\\varphi` the heavy
        spot [kg m].
    number : int
        Holes (or slugs); 0 when there is nothing to correct.
    angles : ndarray
        Angle of each hole [rad].
    pitch : float
        Angle between neighbouring holes [rad].
    depth : float
        Depth of every hole as read to ``depth_to``, rounded to the machining step [m].
    shoulder_depth, tip_depth : float
        The same depth read to the shoulder and to the tip [m].
    hole_mass : float
        Mass one hole removes, or with heavy metal the net mass one slug adds (slug
        less the material drilled for it) [kg].
    slug_length : float
        Length of each heavy-metal slug [m] (0 when drilling).
    hole_moment : float
        First moment of one hole's correction about the crank axis [kg m].
    correction : complex
        Unbalance the holes take off, in the convention of ``unbalance`` [kg m].
    residual : complex
        ``unbalance - correction``, what remains [kg m].
    residual_amount : float
        ``abs(residual)`` [kg m].
    note : str
        Why the holes are more than ``max_depth`` alone would need, when a drill's reach or
        the part's depth limited them (empty otherwise).
    """

    method: str
    direction: str
    depth_to: str
    diameter: float
    point_angle: float
    radius: float
    unbalance: complex
    number: int
    angles: NDArray
    pitch: float
    depth: float
    shoulder_depth: float
    tip_depth: float
    hole_mass: float
    slug_length: float
    hole_moment: float
    correction: complex
    residual: complex
    residual_amount: float
    note: str = ""


def _offsets(number: int, pitch: float) -> NDArray:
    """Angles of ``number`` holes a ``pitch`` apart, symmetric about 0 [rad]."""
    return (np.arange(number) - (number - 1) / 2.0) * pitch


def drilling_plan(
    unbalance: float,
    angle: float,
    diameter: float,
    radius: float,
    max_depth: float,
    depth_to: DepthReference,
    direction: HoleDirection = "axial",
    point_angle: float = DEFAULT_POINT_ANGLE,
    density: float = STEEL_DENSITY,
    spacing: float = 0.0,
    edge_distance: float = 0.0,
    web_sector: tuple[float, float] | None = None,
    outer_radius: float | None = None,
    web_thickness: float | None = None,
    depth_resolution: float = 0.0,
    slug_density: float | None = None,
    max_holes: int = 12,
    names: Mapping[str, str] | None = None,
) -> DrillingPlan:
    r"""Plan the holes (or heavy-metal slugs) that correct an unbalance in one plane.

    Parameters
    ----------
    unbalance : float
        Amount :math:`U` of the unbalance to correct [kg m], >= 0.
    angle : float
        Angle :math:`\varphi` of its heavy spot [rad].
    diameter : float
        Drill diameter [m] (with heavy metal also the slug diameter).
    radius : float
        Axial holes: radius of the hole axes; radial holes: radius of the rim [m].
    max_depth : float
        Deepest hole allowed, read to ``depth_to`` [m].
    depth_to : {"shoulder", "tip"}
        What the depths (``max_depth`` and the plan's) are read to.
    direction : {"axial", "radial"}
        Holes parallel to the crank axis, or toward it from the rim.
    point_angle : float
        Included drill-point angle [rad]; pi for flat-bottomed holes.
    density : float
        Density of the crank material [kg/m^3].
    spacing : float
        Least material between neighbouring holes [m].
    edge_distance : float
        Least material between a hole and an edge of the web [m]: the ends of
        ``web_sector``, the rim at ``outer_radius`` (axial holes), the faces of a web
        ``web_thickness`` thick (radial holes).
    web_sector : tuple of float, optional
        Start and end angle of the counterweight, counterclockwise [rad]; holes stay inside
        it. Default: anywhere within 90° of the correction's direction.
    outer_radius : float, optional
        Outer radius of the counterweight face, for axial holes [m].
    web_thickness : float, optional
        Axial thickness of the web [m]: a radial hole must fit in it (with
        ``edge_distance`` to each face), an axial hole must end in it (its tip depth at most
        the thickness). Not given, the drill's reach alone limits the depth
        (:func:`depth_limit`).
    depth_resolution : float
        Machining step the depth is rounded to [m]; 0 for none.
    slug_density : float, optional
        Density of heavy metal [kg/m^3] (e.g. 17 000-18 500 for tungsten alloys): slugs of
        the drill's diameter pressed into holes at the light spot, filling them to the
        shoulder, instead of holes at the heavy spot.
    max_holes : int
        Most holes the plan may use.
    names : mapping of str to str, optional
        How the user named the parameters, for messages (``{"diameter":
        "--hole-diameter", "max_depth": "--max-depth"}``).

    Returns
    -------
    DrillingPlan
        The holes, their angles [rad] and depth [m], and the predicted residual [kg m].

    Raises
    ------
    InputError
        When the correction cannot be made with these limits, or the drill cannot make it
        (:func:`check_drill`, a drill that crosses the crank axis or does not fit in the
        web); the message names the drill and the limit, and says what to change.

    Notes
    -----
    With :math:`n` equal holes at offsets :math:`\delta_k` around the correction's
    direction, each must carry :math:`U / \sum_k \cos\delta_k`; the depth follows from
    :func:`hole_mass_properties` (monotonic in the depth) by root finding, then rounding.
    The depth is held within ``max_depth``, :data:`MAX_DEPTH_RATIO` drill diameters and,
    for axial holes, ``web_thickness`` (:func:`depth_limit`); when the last two call for
    more holes than ``max_depth`` alone would, the plan's ``note`` says so.
    """
    check_nonnegative("unbalance", unbalance)
    if not math.isfinite(angle):
        raise InputError("angle", angle, "must be a finite angle [rad]")
    check_drill(diameter, names)
    h = cone_height(diameter, point_angle)
    _check_reference(depth_to)
    _check_direction(direction)
    check_positive("radius", radius)
    check_positive("max_depth", max_depth)
    check_positive("density", density)
    for name, value in (
        ("spacing", spacing),
        ("edge_distance", edge_distance),
        ("depth_resolution", depth_resolution),
    ):
        check_nonnegative(name, value)
    if isinstance(max_holes, bool) or not isinstance(max_holes, int) or max_holes < 1:
        raise InputError("max_holes", max_holes, "must be a whole number >= 1")
    if slug_density is not None and not (slug_density > density and math.isfinite(slug_density)):
        raise InputError(
            "slug_density",
            slug_density,
            f"must be a finite density above the crank material's {density:g} kg/m^3 "
            "(heavy metal adds mass only when denser than what is drilled out)",
        )
    max_tip = max_depth + h if depth_to == "shoulder" else max_depth
    if direction == "radial" and max_tip >= radius:
        raise InputError(
            _named(names, "max_depth"),
            _mm(max_depth),
            f"radial holes from the rim at {_named(names, 'radius')} = {_mm(radius)} must end "
            f"short of the crank axis: a tip depth below {_mm(radius)}",
        )
    if direction == "axial" and diameter >= 2 * radius:
        raise InputError(
            _named(names, "diameter"),
            _mm(diameter),
            f"is too large for axial holes at {_named(names, 'radius')} = {_mm(radius)}: a "
            f"hole would reach across the crank axis; give a drill below {_mm(2 * radius)}",
        )
    # the deepest tip: max_depth, the drill's reach, an axial hole's web
    part = web_thickness if direction == "axial" else None
    reach_tip, reach_words = depth_limit(diameter, part, names)
    limit_words = f"{_named(names, 'max_depth')} = {_mm(max_depth)} to the {depth_to}"
    if reach_tip < max_tip:
        max_tip, limit_words = reach_tip, reach_words
        if max_tip <= h and depth_to == "shoulder":
            raise InputError(
                _named(names, "diameter"),
                _mm(diameter),
                f"has a point {_mm(h)} long, as deep as {reach_words} allows; give a smaller "
                "drill or a larger point angle",
            )
    limit = max_tip - h if depth_to == "shoulder" else max_tip
    max_shoulder = max(max_tip - h, 0.0)
    if slug_density is not None and max_shoulder <= 0:
        raise InputError(
            _named(names, "max_depth"),
            _mm(max_depth),
            f"leaves no room for a slug as deep as {limit_words}: the hole must go past its point",
        )
    if direction == "axial" and outer_radius is not None:
        if radius + diameter / 2 + edge_distance > outer_radius:
            raise InputError(
                "radius",
                radius,
                f"holes of {diameter * 1e3:.4g} mm at this radius leave less than the edge "
                f"distance {edge_distance * 1e3:.4g} mm to the rim at "
                f"{outer_radius * 1e3:.4g} mm; use a smaller radius or drill",
            )
    if direction == "radial" and web_thickness is not None:
        if diameter + 2 * edge_distance > web_thickness:
            raise InputError(
                _named(names, "diameter"),
                _mm(diameter),
                f"does not fit in the web, {_named(names, 'web_thickness')} = "
                f"{_mm(web_thickness)} thick, with {_mm(edge_distance)} to each face; use a "
                "smaller drill",
            )
    heavy_metal = slug_density is not None
    centre = angle + math.pi if heavy_metal else angle
    # the radius where neighbouring holes come closest: the axis, or the deepest shoulder
    inner = radius if direction == "axial" else radius - max_shoulder
    pitch_sine = (diameter + spacing) / (2.0 * inner)
    pitch = 2.0 * math.asin(pitch_sine) if pitch_sine <= 1 else math.inf
    room_low, room_high = _room(
        web_sector, centre, (diameter / 2 + edge_distance) / inner, edge_distance, heavy_metal
    )
    slug_rho = 0.0 if slug_density is None else float(slug_density)

    def moment(depth: float) -> float:
        """First moment one hole's correction makes about the crank axis [kg m]."""
        hole = hole_mass_properties(
            diameter, depth, depth_to, direction, radius, density, point_angle
        )
        removed = float(hole.first_moment)
        if not heavy_metal:
            return removed
        shoulder = float(hole_geometry(diameter, depth, depth_to, point_angle).shoulder_depth)
        slug_radius = radius if direction == "axial" else radius - shoulder / 2
        slug = slug_rho * math.pi * diameter**2 / 4 * shoulder * slug_radius
        return slug - removed

    unit = complex(math.cos(angle), math.sin(angle))
    target = complex(unbalance) * unit

    def fewest(deepest: float) -> tuple[int | None, int, float]:
        """The fewest holes that carry the unbalance, each at most ``deepest`` deep (None:
        no number that fits), how many fit, and the most the fitting ones take [kg m]."""
        best, fits = 0.0, 0
        for number in range(1 if unbalance > 0 else 0, max_holes + 1):
            offsets = _offsets(number, pitch if number > 1 else 0.0)
            if number and (-offsets[0] > room_low or offsets[-1] > room_high):
                break
            fits = number
            gain = float(np.sum(np.cos(offsets)))
            if number and gain * moment(deepest) < unbalance:
                best = max(best, gain * moment(deepest))
                continue
            return number, fits, best
        return None, fits, best

    found, fits, best = fewest(limit)
    note = ""
    if found is not None and limit < max_depth:
        alone = fewest(max_depth)[0]
        if alone is not None and alone < found:
            note = f"split into {found} holes: {alone} would go deeper than {limit_words}"
    if found is not None:
        number = found
        offsets = _offsets(number, pitch if number > 1 else 0.0)
        gain = float(np.sum(np.cos(offsets)))
        depth = _depth_for_moment(moment, unbalance / gain, limit) if number else 0.0
        depth = round_depth(depth, depth_resolution)
        if depth > limit:  # rounded up past the limit: one step less
            depth = math.floor(limit / depth_resolution) * depth_resolution
        per_hole = moment(depth) if number else 0.0
        angles = (centre + offsets) % (2 * math.pi)
        sign = -1.0 if heavy_metal else 1.0
        correction = complex(sign * per_hole * np.sum(np.exp(1j * angles))) if number else 0j
        geometry = hole_geometry(diameter, depth, depth_to, point_angle)
        shoulder = float(geometry.shoulder_depth)
        slug_mass = slug_rho * math.pi * diameter**2 / 4 * shoulder
        removed_mass = density * float(geometry.volume)
        return DrillingPlan(
            method="heavy metal" if heavy_metal else "drill",
            direction=direction,
            depth_to=depth_to,
            diameter=diameter,
            point_angle=point_angle,
            radius=radius,
            unbalance=target,
            number=number,
            angles=angles,
            pitch=pitch if number > 1 else 0.0,
            depth=depth,
            shoulder_depth=shoulder,
            tip_depth=float(geometry.tip_depth),
            hole_mass=slug_mass - removed_mass if heavy_metal else removed_mass,
            slug_length=shoulder if heavy_metal else 0.0,
            hole_moment=per_hole,
            correction=correction,
            residual=target - correction,
            residual_amount=abs(target - correction),
            note=note,
        )
    what = "slugs" if heavy_metal else "holes"
    deeper = (
        f"a larger {_named(names, 'max_depth')}"
        if limit == max_depth
        else "a thicker part"
        if limit_words.startswith("the part")
        else "a larger drill"
    )
    raise InputError(
        "unbalance",
        f"{unbalance * 1e6:.4g} g*mm",
        f"is more than the holes take: at most {fits} {what} of {_mm(diameter)} "
        f"({_named(names, 'diameter')}) fit (spacing {_mm(spacing)}, max_holes {max_holes}), "
        f"taking {best * 1e6:.4g} g*mm as deep as {limit_words}; use {deeper}, a larger "
        "drill or radius, less spacing"
        + ("" if heavy_metal else ", or heavy metal at the light spot"),
    )


def _room(
    web_sector: tuple[float, float] | None,
    centre: float,
    edge_sine: float,
    edge_distance: float,
    heavy_metal: bool,
) -> tuple[float, float]:
    """How far the outermost holes may sit on either side of ``centre`` [rad]: within the
    web sector less the edge distance (``edge_sine``: its sine at the innermost radius), and
    within 90 deg, beyond which a hole works against the correction."""
    if web_sector is None:
        return math.pi / 2, math.pi / 2
    start, end = (float(a) for a in web_sector)
    if not (math.isfinite(start) and math.isfinite(end)):
        raise InputError("web_sector", web_sector, "must be two finite angles [rad]")
    edge_angle = math.asin(edge_sine) if edge_sine <= 1 else math.inf
    width = (end - start) % (2 * math.pi) or 2 * math.pi
    offset = (centre - start) % (2 * math.pi)
    low, high = offset - edge_angle, width - offset - edge_angle
    if min(low, high) < 0:
        where = "light" if heavy_metal else "heavy"
        raise InputError(
            "web_sector",
            web_sector,
            f"the {where} spot at {math.degrees(centre) % 360:.4g} deg is not on the web "
            f"with the edge distance {edge_distance * 1e3:.4g} mm; give the sector of the "
            "counterweight that holds it",
        )
    return min(low, math.pi / 2), min(high, math.pi / 2)


def _depth_for_moment(moment: Callable[[float], float], target: float, max_depth: float) -> float:
    """Depth in [0, max_depth] at which ``moment(depth)`` equals ``target`` [m]."""
    from scipy.optimize import brentq

    if moment(0.0) >= target:
        return 0.0
    return float(brentq(lambda d: moment(d) - target, 0.0, max_depth, xtol=1e-12, rtol=1e-14))
