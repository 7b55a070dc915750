r"""Balance tolerances for rotors with rigid behaviour (ISO 21940-11, formerly ISO 1940-1).

The balance quality grade G is the product of the specific unbalance (the eccentricity of
the centre of mass, :math:`e = U/m`) and the largest service speed, in mm/s. The
permissible residual unbalance of a rotor of mass :math:`m` at the service speed
:math:`\Omega` follows as

.. math:: U_{per} = \frac{G\,m}{\Omega}
          \quad\Leftrightarrow\quad
          U_{per}\,[\mathrm{g\,mm}] = \frac{1000\,G\,[\mathrm{mm/s}]\;m\,[\mathrm{kg}]}
                                           {\Omega\,[\mathrm{rad/s}]}

This module works in SI: the grade is a speed [m/s] (G 6.3 is 0.0063 m/s), the unbalance a
mass times a length [kg m]. ``1 g mm = 1e-6 kg m``.

Allocation to two planes (the rule used here, see ``docs/single_cylinder.md``):

1. To the *bearing* planes A and B by the lever rule of the centre of mass,
   :math:`U_{per,A} = U_{per} L_B / L`, :math:`U_{per,B} = U_{per} L_A / L`, with each share
   held between 30 % and 70 % of :math:`U_{per}` (ISO 21940-11 / ISO 1940-1:2003,
   clause 7, for rotors whose centre of mass is far from mid-span).
2. To the *correction* planes I and II (between or outside the bearings) by the rigid-body
   transfer of their residuals to the bearings in the worst phase: the correction-plane
   tolerances keep the same 30-70 lever-rule ratio and are scaled down until, with both
   residuals in the least favourable relative phase, neither bearing plane exceeds its
   share. For planes at the bearings this gives step 1 again; for symmetric planes between
   the bearings it gives :math:`U_{per}/2` each; for symmetric planes outside the bearings
   (overhung, plane distance :math:`b > L`) it gives :math:`\tfrac{U_{per}}{2}\,L/b` each,
   the reduction ISO 1940-1 prescribes for outboard correction planes.
"""

from __future__ import annotations

import math

from ..errors import InputError, check_positive
from ..records import record
from ..results import ResultMixin

#: Lower and upper share of U_per one bearing plane may receive (ISO 21940-11, clause 7).
PLANE_SHARE_LIMITS: tuple[float, float] = (0.3, 0.7)


@record
class BalanceGrade(ResultMixin):
    """One balance quality grade and the rotor types it is recommended for.

    Attributes
    ----------
    name : str
        Grade designation, e.g. ``"G 6.3"``.
    value : float
        :math:`e\\,\\Omega` [m/s] (G 6.3 -> 0.0063 m/s).
    examples : str
        Typical rotor types (paraphrased from the standard's table of examples).
    crank_drive : bool
        Whether the examples include crankshaft drives or engine parts.
    """

    name: str
    value: float
    examples: str
    crank_drive: bool


_GRADES: tuple[tuple[str, float, str, bool], ...] = (
    (
        "G 4000",
        4000.0,
        "Crankshaft drives of rigidly mounted slow marine diesel engines with an uneven number "
        "of cylinders (inherently unbalanced).",
        True,
    ),
    (
        "G 1600",
        1600.0,
        "Crankshaft drives of rigidly mounted large two-stroke engines (large slow marine "
        "diesels, inherently balanced).",
        True,
    ),
    (
        "G 630",
        630.0,
        "Crankshaft drives of rigidly mounted large four-stroke engines; crankshaft drives of "
        "elastically mounted marine diesel engines (inherently unbalanced, elastically mounted).",
        True,
    ),
    (
        "G 250",
        250.0,
        "Crankshaft drives of rigidly mounted fast four-cylinder diesel engines (inherently "
        "unbalanced, rigidly mounted).",
        True,
    ),
    (
        "G 100",
        100.0,
        "Crankshaft drives of fast diesel engines with six or more cylinders; complete "
        "reciprocating engines (petrol or diesel) for cars, trucks and locomotives.",
        True,
    ),
    (
        "G 40",
        40.0,
        "Crankshaft drives of elastically mounted fast four-stroke engines with six or more "
        "cylinders (inherently balanced, elastically mounted); car wheels, rims, drive shafts.",
        True,
    ),
    (
        "G 16",
        16.0,
        "Crankshaft drives of engines with six or more cylinders under special requirements "
        "(inherently balanced, rigidly mounted); individual engine components for cars, trucks "
        "and locomotives; drive shafts; agricultural machinery; crushers.",
        True,
    ),
    (
        "G 6.3",
        6.3,
        "Individual engine components under special requirements (Hoem and Røsholm 2016 "
        "use it for a racing "
        "crankshaft); flywheels, fans, pump impellers, centrifuges, general machinery, "
        "electric motors up to 950 rpm.",
        True,
    ),
    (
        "G 2.5",
        2.5,
        "Gas and steam turbines, turbo-compressors, machine-tool drives, electric motors above "
        "950 rpm, turbine-driven pumps.",
        False,
    ),
    (
        "G 1",
        1.0,
        "Grinding-machine drives, audio and video drives, small armatures with "
        "special requirements.",
        False,
    ),
    ("G 0.4", 0.4, "Spindles, discs and armatures of precision grinders; gyroscopes.", False),
)

#: All balance quality grades, coarsest first. ``value`` in m/s.
GRADES: tuple[BalanceGrade, ...] = tuple(
    BalanceGrade(name, number / 1000.0, text, crank) for name, number, text, crank in _GRADES
)


def grade_names() -> list[str]:
    """Designations of all grades, e.g. ``["G 4000", ..., "G 0.4"]``.

    Returns
    -------
    list of str
        The designations of :data:`GRADES`, coarsest first.

    References
    ----------
    ISO 21940-11:2016, table of balance quality grades.
    """
    return [grade.name for grade in GRADES]


def balance_grade(grade: str | float, field: str = "grade") -> BalanceGrade:
    r"""Look a grade up by designation (``"G6.3"``, ``"G 6.3"``, ``"6.3"``) or number [mm/s].

    Parameters
    ----------
    grade : str or float
        Designation, with or without ``G`` and blanks, or the number of the grade
        :math:`e\,\Omega` [mm/s] (6.3 for G 6.3).
    field : str
        Name of the input the grade came from, used in the error message.

    Returns
    -------
    BalanceGrade
        The grade of :data:`GRADES` whose number matches (relative tolerance 1e-9).

    Raises
    ------
    InputError
        If the grade is not one of the standard's grades G 0.4 ... G 4000.

    References
    ----------
    ISO 21940-11:2016, table of balance quality grades.
    """
    allowed = "must be one of " + ", ".join(name.replace(" ", "") for name in grade_names())
    if isinstance(grade, bool):
        raise InputError(field, grade, allowed)
    if isinstance(grade, str):
        text = grade.strip().upper().replace(" ", "")
        text = text[1:] if text.startswith("G") else text
        try:
            number = float(text)
        except ValueError:
            raise InputError(field, grade, allowed) from None
    else:
        number = float(grade)
    for item in GRADES:
        if math.isclose(item.value * 1000.0, number, rel_tol=1e-9):
            return item
    raise InputError(field, grade, allowed)


def permissible_unbalance(grade: str | float, rotor_mass: float, speed: float) -> float:
    r"""Permissible residual unbalance of a rigid rotor [kg m].

    Parameters
    ----------
    grade : str or float
        Balance quality grade: ``"G6.3"`` or the number of the grade [mm/s].
    rotor_mass : float
        Mass of the rotor [kg].
    speed : float
        Largest service speed :math:`\Omega` [rad/s].

    Returns
    -------
    float
        :math:`U_{per}` [kg m] (multiply by 1e6 for g mm).

    Notes
    -----
    .. math:: U_{per} = \frac{G\,m}{\Omega}, \qquad
              U_{per}\,[\mathrm{g\,mm}] = \frac{1000\,G\,[\mathrm{mm/s}]\,m\,[\mathrm{kg}]}{\Omega}

    References
    ----------
    ISO 21940-11:2016 (formerly ISO 1940-1), Eq. for :math:`U_{per}`; Hoem and Røsholm (2016)
    Eq. 4.15: G 6.3, 2.7 kg, 15200 rpm -> 10.69 g mm.
    """
    item = balance_grade(grade)
    check_positive("rotor_mass", rotor_mass)
    check_positive("speed", speed)
    return item.value * rotor_mass / speed


def specific_unbalance(grade: str | float, speed: float) -> float:
    r"""Permissible eccentricity of the centre of mass :math:`e_{per} = G/\Omega` [m].

    Parameters
    ----------
    grade : str or float
        Balance quality grade: ``"G6.3"`` or the number of the grade [mm/s].
    speed : float
        Largest service speed :math:`\Omega` [rad/s].

    Returns
    -------
    float
        :math:`e_{per}` [m], the permissible residual unbalance per unit rotor mass
        [kg m/kg] (multiply by 1e6 for g mm/kg or µm).

    References
    ----------
    ISO 21940-11:2016 (formerly ISO 1940-1), definition of the balance quality grade
    :math:`G = e_{per}\,\Omega`.
    """
    item = balance_grade(grade)
    check_positive("speed", speed)
    return item.value / speed


@record
class PlaneAllocation(ResultMixin):
    """Permissible residual unbalance split between two planes.

    Attributes
    ----------
    total : float
        :math:`U_{per}` of the whole rotor [kg m].
    bearing_a, bearing_b : float
        Share of the bearing planes A and B [kg m].
    plane_1, plane_2 : float
        Tolerance in the correction planes I and II [kg m].
    share_a : float
        :math:`U_{per,A}/U_{per}` after the 30-70 % limits [-].
    rule : str
        The allocation rule, in words.
    """

    total: float
    bearing_a: float
    bearing_b: float
    plane_1: float
    plane_2: float
    share_a: float
    rule: str


def _clip_share(share: float) -> float:
    low, high = PLANE_SHARE_LIMITS
    return min(max(share, low), high)


def allocate_to_planes(
    total: float,
    bearing_a: float,
    bearing_b: float,
    center_of_mass: float,
    plane_1: float | None = None,
    plane_2: float | None = None,
) -> PlaneAllocation:
    r"""Split a permissible residual unbalance between two bearing and two correction planes.

    Parameters
    ----------
    total : float
        Permissible residual unbalance of the rotor :math:`U_{per}` [kg m].
    bearing_a, bearing_b : float
        Axial positions of the bearings [m] (any origin; ``bearing_b > bearing_a``).
    center_of_mass : float
        Axial position of the rotor's centre of mass [m].
    plane_1, plane_2 : float, optional
        Axial positions of the correction planes [m]; default: the bearing planes.

    Returns
    -------
    PlaneAllocation
        Bearing-plane shares and correction-plane tolerances [kg m].

    Notes
    -----
    .. math::
        U_{per,A} = U_{per}\,\mathrm{clip}\!\left(\tfrac{L_B}{L}, 0.3, 0.7\right),\quad
        U_{per,B} = U_{per} - U_{per,A}

        U_{I} = s\,a_I,\ U_{II} = s\,a_{II},\quad
        s = \min\left(\frac{U_{per,A}}{a_I\frac{|z_B - z_I|}{L} + a_{II}\frac{|z_B - z_{II}|}{L}},
                      \frac{U_{per,B}}{a_I\frac{|z_I - z_A|}{L} + a_{II}\frac{|z_{II} - z_A|}{L}}
                 \right)

    with :math:`a_I = \mathrm{clip}((z_{II} - z_c)/(z_{II} - z_I), 0.3, 0.7)`,
    :math:`a_{II} = 1 - a_I`.

    References
    ----------
    ISO 21940-11:2016 clause 7 (allocation of :math:`U_{per}` to the bearing planes, 30/70 %
    limits); the transfer to correction planes is the worst-phase rigid-body statics stated
    in the module docstring.
    """
    check_positive("total", total)
    span = bearing_b - bearing_a
    if not span > 0:
        raise InputError(
            "bearing_b",
            bearing_b,
            f"must lie beyond bearing_a = {bearing_a:g} m (positive bearing span)",
        )
    share_a = _clip_share((bearing_b - center_of_mass) / span)
    u_a = total * share_a
    u_b = total - u_a
    z1 = bearing_a if plane_1 is None else plane_1
    z2 = bearing_b if plane_2 is None else plane_2
    if not z2 > z1:
        raise InputError("plane_2", z2, f"must lie beyond plane_1 = {z1:g} m")
    a1 = _clip_share((z2 - center_of_mass) / (z2 - z1))
    a2 = 1.0 - a1
    load_a = (a1 * abs(bearing_b - z1) + a2 * abs(bearing_b - z2)) / span
    load_b = (a1 * abs(z1 - bearing_a) + a2 * abs(z2 - bearing_a)) / span
    limits = [u / load for u, load in ((u_a, load_a), (u_b, load_b)) if load > 0]
    scale = min(limits)
    rule = (
        "bearing planes: lever rule of the centre of mass, each share held in 30-70 % of "
        "U_per (ISO 21940-11 cl. 7); correction planes: same ratio, scaled so that both "
        "residuals in the worst relative phase keep each bearing plane within its share"
    )
    return PlaneAllocation(
        total=total,
        bearing_a=u_a,
        bearing_b=u_b,
        plane_1=scale * a1,
        plane_2=scale * a2,
        share_a=share_a,
        rule=rule,
    )


@record
class ToleranceVerdict(ResultMixin):
    """Pass/fail of a measured residual unbalance against its permissible value.

    Attributes
    ----------
    residual : float
        Measured residual unbalance [kg m] (magnitude).
    permissible : float
        Permissible residual unbalance [kg m].
    ratio : float
        ``residual / permissible`` [-]; at most 1 passes.
    passed : bool
        ``residual <= permissible``.
    """

    residual: float
    permissible: float
    ratio: float
    passed: bool


def check_residual(residual: float, permissible: float) -> ToleranceVerdict:
    """Compare a residual unbalance [kg m] with the permissible one [kg m].

    Parameters
    ----------
    residual : float
        Measured residual unbalance, a magnitude [kg m] (finite, >= 0).
    permissible : float
        Permissible residual unbalance [kg m], e.g. from :func:`permissible_unbalance` or
        one plane of :func:`allocate_to_planes` (> 0).

    Returns
    -------
    ToleranceVerdict
        The ratio ``residual / permissible`` [-] and whether it is at most 1.

    Raises
    ------
    InputError
        If ``residual`` is negative or not finite, or ``permissible`` is not positive.

    References
    ----------
    ISO 21940-11:2016: a rotor is within tolerance when its residual unbalance does not
    exceed :math:`U_{per}`.
    """
    if not (residual >= 0 and math.isfinite(residual)):
        raise InputError("residual", residual, "must be a finite unbalance >= 0 (a magnitude)")
    check_positive("permissible", permissible)
    ratio = residual / permissible
    return ToleranceVerdict(
        residual=residual, permissible=permissible, ratio=ratio, passed=ratio <= 1.0
    )
