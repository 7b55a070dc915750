"""The settings of the counterweight studies: the shape, its optimisation and its design.

Part of :mod:`crankbalance.schema.settings`, imported when one of its schemas is first
asked for (see there)."""

from __future__ import annotations

from typing import Any, Literal

from ...errors import InputError
from ..core import FieldProblem, field
from .common import (
    COUNTERWEIGHT_CHILDREN,
    MAX_COUNTERWEIGHT_DESIGNS,
    MAX_THREE_OBJECTIVE_DESIGNS,
    StudyOptions,
    choice,
    counterweight_designs,
    length_or_zero,
    number,
    quantity,
    requirement,
    text,
    whole,
)


class CounterweightOptions(StudyOptions):
    """Counterweight shape optimisation (Appl. Sci. 2021, Sec. 4-5)."""

    density: float = quantity(
        "density",
        8000.0,
        "Density",
        "Density of the counterweight's material.",
        hint="e.g. 8000 kg/m^3",
    )
    max_mass: float | None = quantity(
        "mass",
        None,
        "Largest mass",
        "The heaviest counterweight a design may have; empty: no limit.",
        hint="e.g. 400 g",
    )
    max_radius: float | None = quantity(
        "length",
        None,
        "Largest radial space",
        "The radial space a design may take from the crank axis; empty: no limit.",
        hint="e.g. 80 mm",
    )
    min_balance: float = number(
        100.0,
        "Smallest balance [%]",
        "The smallest first moment a design must reach, in per cent of the required one.",
        ge=1,
        le=1000,
    )
    iterations: int = whole(
        40,
        "Iterations",
        "Rounds of the optimiser after its first sample, each breeding "
        f"{COUNTERWEIGHT_CHILDREN} designs.",
        ge=0,
        le=1000,
    )
    population: int = whole(
        4096, "Population", "Designs of the optimiser's first sample.", ge=16, le=100_000
    )
    seed: int | None = whole(
        None,
        "Random seed",
        "Seed of the optimiser's random numbers, for repeatable runs; empty: a new seed each run.",
        ge=0,
        le=2**32 - 1,
    )

    def check(self) -> None:
        problem = self.budget_problem(2)
        if problem is not None:
            raise FieldProblem("iterations", problem)

    def check_budget(self, objectives: int) -> None:
        """Refuse more designs than the budget of ``objectives`` objectives (2: mass and
        radial space, 3: with the inertia), naming ``iterations``."""
        problem = self.budget_problem(objectives)
        if problem is not None:
            raise InputError("iterations", self.iterations, problem)

    def budget_problem(self, objectives: int) -> str | None:
        """What is wrong with the designs' budget of ``objectives`` objectives, or None."""
        designs = counterweight_designs(self.population, self.iterations)
        budget = MAX_COUNTERWEIGHT_DESIGNS if objectives < 3 else MAX_THREE_OBJECTIVE_DESIGNS
        if designs <= budget:
            return None
        return (
            f"must keep population + iterations x {COUNTERWEIGHT_CHILDREN} at most "
            f"{budget:,} designs, the optimiser's work budget with {objectives} objectives "
            f"(here {self.population:,} + {self.iterations:,} x {COUNTERWEIGHT_CHILDREN} = "
            f"{designs:,}): lower the iterations or the population"
        )


#: the profile parameters of a counterweight (the 2021 paper, Sec. 4), in the order of
#: :class:`crankbalance.physics.counterweight.CounterweightDesign`
PROFILE_PARAMETERS = (
    "web_radius",
    "rectangle_height",
    "trapezoid_angle",
    "segment_radius",
    "segment_angle",
    "thickness",
)


class CounterweightRequirementOptions(StudyOptions):
    """The first moment a counterweight must carry, m_c r_c: given, or from a mass and its
    CG radius (or from the engine's balancing, the study's engine)."""

    first_moment: float | None = requirement(
        None,
        "Required first moment m_c r_c",
        "The first moment the counterweight must carry; empty: from the mass and CG radius, "
        "or from the engine's balancing.",
    )
    cw_mass: float | None = quantity(
        "mass", None, "Counterweight mass m_c", "The counterweight's mass, with its CG radius."
    )
    cg_radius: float | None = quantity(
        "length", None, "Counterweight CG radius r_c", "The radius of its centre of gravity."
    )


def _profile(title: str, metavar: str) -> Any:
    """A profile parameter of ``counterweight optimize``: a value fixes it, ``LOW..HIGH``
    leaves it free in that range (read by the study), empty: the optimiser's range;
    ``metavar`` its kind and unit in the command's help."""
    return text(
        None,
        f"{title} (value or LOW..HIGH)",
        "A value fixes the parameter, LOW..HIGH leaves it free in that range; empty: the "
        "optimiser's range.",
        metavar=metavar,
    )


class CounterweightOptimizeOptions(CounterweightOptions, CounterweightRequirementOptions):
    """``counterweight optimize``: the requirement, the profile parameters, the radial
    measure, the objectives and how many Pareto designs are listed."""

    web_radius: str | None = _profile("Web circle radius r_cw", "LENGTH [mm]")
    rectangle_height: str | None = _profile("Rectangle height h_R", "LENGTH [mm]")
    trapezoid_angle: str | None = _profile("Trapezoid angle delta", "ANGLE [°]")
    segment_radius: str | None = _profile("Segment radius R_cw", "LENGTH [mm]")
    segment_angle: str | None = _profile("Segment angle alpha", "ANGLE [°]")
    thickness: str | None = _profile("Thickness t_cw", "LENGTH [mm]")
    journal_diameter: float | None = quantity(
        "length",
        None,
        "Main journal diameter",
        "The web circle r_cw must clear the main journal: r_cw is searched from half this "
        "diameter up; empty: the engine's journal (1.3 x crank radius) with an engine, else "
        "no limit.",
        hint="e.g. 52 mm",
    )
    radius_measure: Literal["true", "paper"] = choice(
        "true",
        ("true", "paper"),
        "Radial space",
        "How the radial space is measured: true, the outer radius; paper, the 2021 paper's "
        "R_min bound.",
    )
    inertia: bool = field(
        "flag",
        default=False,
        title="Inertia as a third objective",
        description="Minimise the counterweight's moment of inertia too.",
    )
    pareto: int = whole(
        10,
        "Pareto designs listed",
        "How many designs of the Pareto front are listed, evenly spread along it.",
        ge=0,
        le=10**6,
    )

    def check(self) -> None:
        problem = self.budget_problem(3 if self.inertia else 2)
        if problem is not None:
            raise FieldProblem("iterations", problem)


class CounterweightDesignOptions(StudyOptions):
    """``counterweight optimize|show|export|check``: the requirement and the profile
    parameters (each a value, or for ``optimize`` both ends of a range)."""

    first_moment: float | None = requirement(
        None, "Required first moment m_c r_c", "The first moment the counterweight must carry."
    )
    cw_mass: float | None = quantity(
        "mass",
        None,
        "Counterweight mass m_c",
        "Counterweight mass from the balancing (with the CG radius: the requirement).",
    )
    cg_radius: float | None = quantity(
        "length",
        None,
        "Counterweight CG radius r_c",
        "Radius of the counterweight's centre of gravity from the balancing.",
    )
    web_radius: float | None = quantity(
        "length", None, "Web circle radius r_cw", "Radius of the web's circle about the crank axis."
    )
    rectangle_height: float | None = length_or_zero(
        None, "Rectangle height h_R", "Height of the profile's rectangle."
    )
    trapezoid_angle: float | None = quantity(
        "angle",
        None,
        "Trapezoid angle delta",
        "Angle delta of the profile's trapezoid flanks.",
        ge=0,
    )
    segment_radius: float | None = quantity(
        "length", None, "Segment radius R_cw", "Radius of the profile's outer circular segment."
    )
    segment_angle: float | None = quantity(
        "angle",
        None,
        "Segment angle alpha",
        "Angle alpha of the profile's outer circular segment.",
        gt=0,
    )
    thickness: float | None = quantity(
        "length", None, "Thickness t_cw", "Axial thickness of the counterweight."
    )
    density: float = quantity(
        "density", 8000.0, "Density", "Density of the counterweight's material."
    )
    unit: float = quantity(
        "length",
        1e-3,
        "Length unit of a CAD file",
        "The length one unit of a checked CAD file stands for.",
    )
