r"""Rebalancing a single-cylinder crank after new parts: how material comes off the
counterweights (:class:`DrilledHoles`, :class:`FaceRemoval`) and the eight-step procedure
of Hoem and Røsholm (2016), Sec. 6.4 (:func:`rebalance`).

The counterweights' first moment must become (the balance factor of
:mod:`crankbalance.physics.single_cylinder`)

.. math::
    (m_{cw}r')_{new} = (m_{rot} + f_b m_{rec})_{new}\,r,\quad
    m_u r_u = (m_{cw}r')_{old} - (m_{cw}r')_{new},\quad
    m_{corr} = \frac{m_u r_u}{r_{corr}}

so material of first moment :math:`m_u r_u` comes off, in layers of a depth (holes drilled
into every web alike, or a face ground off), each layer measured on the modified geometry
until the residual is within the tolerance (ISO 21940-11 :math:`U_{per}`). Holes keep their
drill point (:mod:`crankbalance.physics.shop.holes`). SI units throughout.

References
----------
Hoem and Røsholm (2016) Sec. 6.4, Eq. 6.1 (corrected), 6.3-6.5; Table 6.2.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import field
from typing import Literal

import numpy as np

from ..errors import InputError, check_positive
from ..records import record
from ..results import ResultMixin
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
from .single_cylinder import (
    balance_factor_from_mass_properties,
    bob_weight,
    check_balance_factor,
    check_mass,
    counterweight_moment,
)

CorrectionKind = Literal["holes", "face"]
#: most holes per web a split of too deep holes proposes (:meth:`DrilledHoles.split`)
MAX_SPLIT_HOLES = 1000
FaceOrientation = Literal["axial", "radial"]


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


@record
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
    drill_length : float, optional
        The drill's usable length [m]: no hole deeper, to the tip. None: a jobber drill's,
        :data:`~crankbalance.physics.shop.holes.MAX_DEPTH_RATIO` diameters.

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
    drill_length: float | None = None
    kind: str = field(default="holes", init=False)

    def __post_init__(self) -> None:
        check_positive("hole_diameter", self.diameter)
        _check_count("holes", self.number)
        if self.direction not in ("axial", "radial"):
            raise InputError("hole_direction", self.direction, "must be 'axial' or 'radial'")
        self._check_layer()
        if self.web_thickness is not None:
            check_positive("web_thickness", self.web_thickness)
        if self.drill_length is not None:
            check_positive("drill_length", self.drill_length)
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

    def depth_limit(self, names: Mapping[str, str] | None = None) -> tuple[float, str]:
        """The deepest hole, to the tip [m], and where the limit comes from: the drill's
        length (or reach) and, for axial holes, the web's thickness
        (:func:`~crankbalance.physics.shop.holes.depth_limit`)."""
        part = self.web_thickness if self.direction == "axial" else None
        return depth_limit(
            self.diameter,
            part,
            {
                "web_thickness": _name(names, "web_thickness"),
                "drill_length": _name(names, "drill_length"),
            },
            self.drill_length,
        )

    def split(self, depth: float, max_holes: int = MAX_SPLIT_HOLES) -> tuple[int, float]:
        r"""Split holes: the fewest holes per web (at least :attr:`number`, at most
        ``max_holes``) that take off the same mass as :attr:`number` holes ``depth`` deep
        (as read to ``depth_to``) [m], each within :meth:`depth_limit`, and their depth [m].

        Each hole keeps its drill point, so n holes of depth :math:`t_n` remove
        :math:`n V(t_n) = N V(t)` with :math:`V = \pi d^2/4\,(s + h/3)`
        (:func:`~crankbalance.physics.shop.holes.depth_for_volume`). Returns
        ``(number, depth)`` unchanged when the holes fit; ``(0, nan)`` when no number up to
        ``max_holes`` fits.
        """
        limit, _ = self.depth_limit()
        volume = float(hole_geometry(self.diameter, depth, self.depth_to, self.point_angle).volume)
        total = volume * self.number
        for n in range(self.number, max_holes + 1):
            each = depth_for_volume(self.diameter, total / n, self.depth_to, self.point_angle)
            tip = float(
                hole_geometry(self.diameter, each, self.depth_to, self.point_angle).tip_depth
            )
            if tip <= limit * (1 + 1e-9):
                return n, each
        return 0, math.nan

    def check_plan(self, depth: float, names: Mapping[str, str] | None = None) -> None:
        """Refuse holes ``depth`` deep (as read to ``depth_to``) [m] that go deeper, to the
        tip, than the drill reaches (its length) or than the web is thick (axial holes)
        (:meth:`depth_limit`), proposing split holes: the fewest holes per web, side by side,
        that take off the same mass within the limit (:meth:`split`), and their depth.

        Parameters
        ----------
        depth : float
            Depth of every hole [m].
        names : mapping of str to str, optional
            How the user named ``hole_diameter``, ``holes``, ``web_thickness`` and
            ``drill_length``.
        """
        limit, words = self.depth_limit(names)
        tip = float(hole_geometry(self.diameter, depth, self.depth_to, self.point_angle).tip_depth)
        if tip <= limit * (1 + 1e-9):
            return
        needed, each = self.split(depth)
        to = "" if self.point_angle == FLAT_BOTTOM else f" to the {self.depth_to}"
        advice = (
            f"split them: {needed} per web side by side, {each * 1e3:.4g} mm deep{to}, "
            f"take off the same mass ({_name(names, 'holes')}: {needed}), or give a larger drill"
            if needed
            else f"no number of holes up to {MAX_SPLIT_HOLES} per web fits; give a larger drill"
        )
        raise InputError(
            _name(names, "hole_diameter"),
            f"{self.diameter * 1e3:.4g} mm",
            f"would need {self.number} hole(s) per web {tip * 1e3:.4g} mm deep to the tip, "
            f"deeper than {words}; {advice}",
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


@record
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


@record
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


@record
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
        check_mass(name, value)
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
