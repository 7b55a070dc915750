r"""Rotor helpers: inertia of simple rotors, the equal-inertia test rotor, crankpin overlap,
and the effect of crankshaft stroking on rotating mass and balance.

SI units throughout (lengths in m, masses in kg, inertias in kg m^2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import InputError, check_positive
from .results import ResultMixin
from .single_cylinder import (
    STEEL_DENSITY,
    _check_mass,
    balance_factor_from_mass_properties,
)


def cylinder_inertia(
    diameter: float, length: float, density: float = STEEL_DENSITY, bore: float = 0.0
) -> float:
    r"""Mass moment of inertia of a (hollow) cylinder about its own axis [kg m^2].

    Parameters
    ----------
    diameter : float
        Outer diameter [m].
    length : float
        Axial length [m].
    density : float
        Material density [kg/m^3].
    bore : float
        Inner diameter [m] (0 for a solid cylinder).

    .. math:: I = \frac{\rho\,\pi\,(d^4 - d_i^4)\,L}{32}

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.6.
    """
    check_positive("diameter", diameter)
    check_positive("length", length)
    check_positive("density", density)
    if not 0 <= bore < diameter:
        raise InputError("bore", bore, f"must lie in [0, diameter = {diameter:g} m)")
    return density * math.pi * (diameter**4 - bore**4) * length / 32.0


def disc_inertia(mass: float, diameter: float) -> float:
    r"""Inertia of a solid disc of given mass about its axis [kg m^2]: :math:`m r^2/2`.

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.6.
    """
    _check_mass("mass", mass)
    check_positive("diameter", diameter)
    return mass * (diameter / 2.0) ** 2 / 2.0


def point_mass_inertia(mass: float, radius: float) -> float:
    r"""Inertia of a mass concentrated at a radius [kg m^2]: :math:`m r^2`."""
    _check_mass("mass", mass)
    if not radius >= 0:
        raise InputError("radius", radius, "must be >= 0 [m]")
    return mass * radius**2


def stepped_rotor_inertia(
    disc_diameter: float,
    disc_thickness: float,
    shaft_diameter: float,
    overall_length: float,
    density: float = STEEL_DENSITY,
) -> float:
    r"""Inertia of a central disc on a shaft (the thesis' simplified crank) [kg m^2].

    Parameters
    ----------
    disc_diameter : float
        :math:`d_1` [m].
    disc_thickness : float
        :math:`t` [m].
    shaft_diameter : float
        :math:`d_2` [m].
    overall_length : float
        :math:`L_1`, shaft ends included [m].
    density : float
        [kg/m^3].

    .. math:: I = \frac{\rho\pi}{32}\left(d_1^4 t + d_2^4 (L_1 - t)\right)

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.7.
    """
    check_positive("disc_thickness", disc_thickness)
    if not disc_thickness < overall_length:
        raise InputError(
            "disc_thickness",
            disc_thickness,
            f"must be shorter than overall_length = {overall_length:g} m",
        )
    return cylinder_inertia(disc_diameter, disc_thickness, density) + cylinder_inertia(
        shaft_diameter, overall_length - disc_thickness, density
    )


@dataclass(frozen=True)
class TestRotor(ResultMixin):
    """Disc-on-shaft test rotor with a prescribed inertia (Hoem and Røsholm (2016), Appendix E).

    Attributes
    ----------
    disc_diameter, shaft_diameter, overall_length : float
        :math:`d_1, d_2, L_1` [m].
    disc_thickness : float
        :math:`t` [m].
    shaft_end_length : float
        :math:`L_2 = (L_1 - t)/2`, each shaft end [m].
    inertia : float
        Its mass moment of inertia about the axis [kg m^2].
    mass : float
        Its mass [kg].
    density : float
        [kg/m^3].
    """

    __test__ = False  # not a pytest class

    disc_diameter: float
    shaft_diameter: float
    overall_length: float
    disc_thickness: float
    shaft_end_length: float
    inertia: float
    mass: float
    density: float


def equal_inertia_test_rotor(
    inertia: float,
    disc_diameter: float,
    shaft_diameter: float,
    overall_length: float,
    density: float = STEEL_DENSITY,
) -> TestRotor:
    r"""Disc thickness giving a disc-on-shaft rotor the inertia of a real crank.

    Parameters
    ----------
    inertia : float
        Inertia to match about the crank axis [kg m^2].
    disc_diameter, shaft_diameter, overall_length : float
        :math:`d_1`, :math:`d_2`, :math:`L_1` [m].
    density : float
        [kg/m^3].

    .. math::
        t = \frac{32 I/(\rho\pi) - d_2^4 L_1}{d_1^4 - d_2^4},\qquad L_2 = \frac{L_1 - t}{2}

    References
    ----------
    Hoem and Røsholm (2016) Appendix E, Eq. 7.8 and 7.9, Table 7.2: 2847.335 kg mm^2,
    d_1 = 100 mm (the table prints 98 mm, which gives t = 39.80 mm, not the printed
    36.704 mm), d_2 = 20 mm, L_1 = 188 mm -> t = 36.704 mm, L_2 = 75.648 mm.
    """
    check_positive("inertia", inertia)
    check_positive("disc_diameter", disc_diameter)
    check_positive("shaft_diameter", shaft_diameter)
    check_positive("overall_length", overall_length)
    check_positive("density", density)
    if not shaft_diameter < disc_diameter:
        raise InputError(
            "shaft_diameter",
            shaft_diameter,
            f"must be smaller than disc_diameter = {disc_diameter:g} m",
        )
    thickness = (32.0 * inertia / (density * math.pi) - shaft_diameter**4 * overall_length) / (
        disc_diameter**4 - shaft_diameter**4
    )
    if not 0 < thickness < overall_length:
        low = cylinder_inertia(shaft_diameter, overall_length, density)
        high = cylinder_inertia(disc_diameter, overall_length, density)
        raise InputError(
            "inertia",
            inertia,
            f"cannot be reached with these diameters and length: must lie "
            f"between {low:.6g} and {high:.6g} kg*m^2",
        )
    mass = (
        density
        * math.pi
        / 4.0
        * (disc_diameter**2 * thickness + shaft_diameter**2 * (overall_length - thickness))
    )
    return TestRotor(
        disc_diameter=disc_diameter,
        shaft_diameter=shaft_diameter,
        overall_length=overall_length,
        disc_thickness=thickness,
        shaft_end_length=(overall_length - thickness) / 2.0,
        inertia=stepped_rotor_inertia(
            disc_diameter, thickness, shaft_diameter, overall_length, density
        ),
        mass=mass,
        density=density,
    )


def crankpin_overlap(
    main_journal_diameter: float, crankpin_diameter: float, stroke: float
) -> float:
    r"""Crankpin overlap [m]: how far the crankpin overlaps the main journal.

    Negative values mean no overlap (a gap).

    .. math:: CPO = \frac{D_{main} + D_{pin} - s}{2}

    References
    ----------
    Hoem and Røsholm (2016) Sec. 4.3, Fig. 4.13.
    """
    check_positive("main_journal_diameter", main_journal_diameter)
    check_positive("crankpin_diameter", crankpin_diameter)
    check_positive("stroke", stroke)
    return (main_journal_diameter + crankpin_diameter - stroke) / 2.0


@dataclass(frozen=True)
class StrokingEffect(ResultMixin):
    """Effect of offset-grinding the crankpin to a smaller diameter (Hoem and Røsholm (2016), Appendix C).

    Attributes
    ----------
    crank_radius, new_crank_radius : float
        Throw radius before and after [m].
    stroke, new_stroke : float
        [m].
    crankpin_mass, new_crankpin_mass : float
        [kg].
    rotating_mass, new_rotating_mass : float
        :math:`m_{rot}` before and after [kg].
    rotating_unbalance, new_rotating_unbalance : float
        :math:`m_{rot} r` before and after [kg m].
    balance_factor, new_balance_factor : float
        With the counterweights unchanged [-].
    counterweight_correction : float
        First moment to take off the counterweights to restore the original balance factor
        [kg m] (negative: add).
    displacement_change : float
        Swept-volume change [m^3] (0 if no bore is given).
    crankpin_overlap, new_crankpin_overlap : float or None
        [m], if the main-journal diameter is given.
    """

    crank_radius: float
    new_crank_radius: float
    stroke: float
    new_stroke: float
    crankpin_mass: float
    new_crankpin_mass: float
    rotating_mass: float
    new_rotating_mass: float
    rotating_unbalance: float
    new_rotating_unbalance: float
    balance_factor: float
    new_balance_factor: float
    counterweight_correction: float
    displacement_change: float
    crankpin_overlap: float | None
    new_crankpin_overlap: float | None


def stroking_effect(
    crank_radius: float,
    crankpin_diameter: float,
    new_crankpin_diameter: float,
    crankpin_mass: float,
    rotating_mass: float,
    reciprocating_mass: float,
    counterweight_mass: float,
    counterweight_radius: float,
    crankpin_bore: float = 0.0,
    bore: float = 0.0,
    main_journal_diameter: float | None = None,
) -> StrokingEffect:
    r"""Stroking by offset grinding: a smaller crankpin whose outermost fibre stays put.

    Parameters
    ----------
    crank_radius : float
        Throw radius before [m].
    crankpin_diameter, new_crankpin_diameter : float
        Crankpin diameter before and after grinding [m].
    crankpin_mass : float
        Crankpin mass before [kg] (the part of :math:`m_{rot}` that changes).
    rotating_mass : float
        :math:`m_{rot}` before, crankpin included [kg].
    reciprocating_mass : float
        :math:`m_{rec}` [kg].
    counterweight_mass, counterweight_radius : float
        :math:`m_{cw}` [kg] and :math:`r'` [m], unchanged by stroking.
    crankpin_bore : float
        Bore of a hollow crankpin [m].
    bore : float
        Cylinder bore for the displacement change [m] (0: not computed).
    main_journal_diameter : float, optional
        For the crankpin overlap before and after [m].

    .. math::
        r_{new} = r + \frac{d - d_{new}}{2},\quad
        m_{pin,new} = m_{pin}\frac{d_{new}^2 - d_i^2}{d^2 - d_i^2},\quad
        m_{rot,new} = m_{rot} - m_{pin} + m_{pin,new}

        f_{b,new} = \frac{m_{cw} r'/r_{new} - m_{rot,new}}{m_{rec}}

    References
    ----------
    Hoem and Røsholm (2016) Appendix C (qualitative: a smaller crankpin lightens the top half of
    the crank and lengthens the stroke); Eq. 6.2 for the balance factor.
    """
    check_positive("crank_radius", crank_radius)
    check_positive("crankpin_diameter", crankpin_diameter)
    check_positive("new_crankpin_diameter", new_crankpin_diameter)
    if not crankpin_bore < new_crankpin_diameter <= crankpin_diameter:
        raise InputError(
            "new_crankpin_diameter",
            new_crankpin_diameter,
            f"must lie in ({crankpin_bore:g}, {crankpin_diameter:g}] m "
            "(stroking makes the crankpin smaller, not below its bore)",
        )
    _check_mass("crankpin_mass", crankpin_mass)
    _check_mass("rotating_mass", rotating_mass)
    if crankpin_mass > rotating_mass:
        raise InputError(
            "crankpin_mass", crankpin_mass, f"must not exceed rotating_mass = {rotating_mass:g} kg"
        )
    if not bore >= 0:
        raise InputError("bore", bore, "must be >= 0 [m]")
    new_radius = crank_radius + (crankpin_diameter - new_crankpin_diameter) / 2.0
    new_pin = crankpin_mass * (
        (new_crankpin_diameter**2 - crankpin_bore**2) / (crankpin_diameter**2 - crankpin_bore**2)
    )
    new_rotating = rotating_mass - crankpin_mass + new_pin
    fb = balance_factor_from_mass_properties(
        counterweight_mass, counterweight_radius, crank_radius, rotating_mass, reciprocating_mass
    )
    fb_new = balance_factor_from_mass_properties(
        counterweight_mass, counterweight_radius, new_radius, new_rotating, reciprocating_mass
    )
    keep = (new_rotating + fb * reciprocating_mass) * new_radius
    area = math.pi * bore**2 / 4.0
    cpo = cpo_new = None
    if main_journal_diameter is not None:
        cpo = crankpin_overlap(main_journal_diameter, crankpin_diameter, 2 * crank_radius)
        cpo_new = crankpin_overlap(main_journal_diameter, new_crankpin_diameter, 2 * new_radius)
    return StrokingEffect(
        crank_radius=crank_radius,
        new_crank_radius=new_radius,
        stroke=2 * crank_radius,
        new_stroke=2 * new_radius,
        crankpin_mass=crankpin_mass,
        new_crankpin_mass=new_pin,
        rotating_mass=rotating_mass,
        new_rotating_mass=new_rotating,
        rotating_unbalance=rotating_mass * crank_radius,
        new_rotating_unbalance=new_rotating * new_radius,
        balance_factor=fb,
        new_balance_factor=fb_new,
        counterweight_correction=counterweight_mass * counterweight_radius - keep,
        displacement_change=area * 2 * (new_radius - crank_radius),
        crankpin_overlap=cpo,
        new_crankpin_overlap=cpo_new,
    )
