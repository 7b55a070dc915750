"""The mount optimiser: mount stiffnesses and/or positions within bounds toward chosen goals
(all six natural frequencies in a band, the roll mode decoupled, the least transmitted
force over the speed range), on scipy (docs/mounts.md, "The mount optimiser").

The variables are the natural logarithm of one factor per mount on its three stiffnesses
(and on its viscous damping) and each mount's move along x, y, z; the goals are nonlinear
constraints of a seeded differential evolution (``scipy.optimize.differential_evolution``),
then a local search (SLSQP) from its best and from the mounts as given; the answer is the
best layout that meets the goals, or, when none does, the one nearest to meeting them. The
work is bounded before it starts (:data:`MAX_OPTIMIZER_EVALUATIONS`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..records import record
from ..results import ResultMixin
from .mounts import Mount, Powertrain, Response, check_held, forced_response, modes

#: Most evaluations of one optimisation (population x (generations + 1), each one modal
#: analysis and one forced response on :data:`OPTIMIZER_SPEEDS` speeds); refused before the
#: work starts. docs/mounts.md, "The mount optimiser".
MAX_OPTIMIZER_EVALUATIONS = 20_000
#: Speed samples of the optimiser's own sweep (the optimum is then shown on the study's).
OPTIMIZER_SPEEDS = 40
#: Population of the differential evolution per variable.
OPTIMIZER_POPULATION = 10
#: Iterations of the final local search (SLSQP) from the evolution's best.
OPTIMIZER_POLISH_ITERATIONS = 50


@record
class MountGoals:
    """What the mount optimiser aims at (:func:`optimize_mounts`).

    Parameters
    ----------
    variables : tuple of str
        ``"stiffness"`` (each mount's three stiffnesses scaled by one factor) and/or
        ``"position"`` (each mount moved along x, y, z).
    stiffness_range : tuple of float
        Lowest and highest factor on a mount's stiffnesses [-].
    position_range : float
        Largest move of a mount along each axis [m].
    band : tuple of float or None
        All six natural frequencies within (low, high) [Hz]; None: no band.
    roll_energy : float or None
        At least this share of the roll mode's kinetic energy in roll [%].
    roll_axis_angle : float or None
        The roll mode at most this far from the torque-roll axis [rad].
    objective : {"force", "change"}
        The least root-mean-square mount force over the speeds (:func:`rms_mount_force`),
        or the least change of the mounts (sum of squares of the variables' moves over
        their ranges).
    iterations : int
        Generations of the differential evolution [-].
    """

    variables: tuple[str, ...]
    stiffness_range: tuple[float, float] = (0.5, 2.0)
    position_range: float = 0.02
    band: tuple[float, float] | None = None
    roll_energy: float | None = None
    roll_axis_angle: float | None = None
    objective: str = "force"
    iterations: int = 40


def with_variables(pt: Powertrain, goals: MountGoals, x: ArrayLike) -> Powertrain:
    """The powertrain with the optimiser's variables applied: first the natural logarithm
    of each mount's stiffness factor (``"stiffness"``), then each mount's move x, y, z
    (``"position"``).

    Parameters
    ----------
    pt : Powertrain
        The powertrain as given.
    goals : MountGoals
        Which variables there are.
    x : array_like
        The variables [-], [m].

    Returns
    -------
    Powertrain
    """
    values = np.asarray(x, dtype=float)
    n = len(pt.mounts)
    scale = np.ones(n)
    move = np.zeros((n, 3))
    at = 0
    if "stiffness" in goals.variables:
        scale = np.exp(values[:n])
        at = n
    if "position" in goals.variables:
        move = values[at : at + 3 * n].reshape(n, 3)
    mounts = tuple(
        Mount(
            m.name,
            m.position + move[i],
            m.stiffness * scale[i],
            m.orientation,
            m.loss_factor,
            m.damping * scale[i],
        )
        for i, m in enumerate(pt.mounts)
    )
    return Powertrain(pt.mass, pt.cg, pt.inertia, mounts, pt.up)


def variable_bounds(pt: Powertrain, goals: MountGoals) -> list[tuple[float, float]]:
    """The bounds of the optimiser's variables (:func:`with_variables`).

    Parameters
    ----------
    pt : Powertrain
        The powertrain.
    goals : MountGoals
        Its variables and ranges.

    Returns
    -------
    list of (float, float)
        [-] for the logarithms of the stiffness factors, [m] for the moves.
    """
    n = len(pt.mounts)
    out: list[tuple[float, float]] = []
    if "stiffness" in goals.variables:
        low, high = goals.stiffness_range
        out += [(math.log(low), math.log(high))] * n
    if "position" in goals.variables:
        out += [(-goals.position_range, goals.position_range)] * (3 * n)
    return out


def rms_mount_force(response: Response) -> float:
    """The root-mean-square over the speeds of the mount forces of every order and mount,
    :math:`\\sqrt{\\overline{\\sum_{k,i} P_{ski}^2}}` with P the largest length over a cycle.

    Parameters
    ----------
    response : Response
        A forced response.

    Returns
    -------
    float
        [N].
    """
    return float(np.sqrt(np.mean(np.sum(response.mount_peak**2, axis=(1, 2)))))


def goal_margins(pt: Powertrain, goals: MountGoals) -> dict[str, float]:
    """Each goal's margin, non-negative when it is met: the band's lower and upper sides
    [Hz], the roll energy above its target [%], the roll angle below its limit [deg].

    Parameters
    ----------
    pt : Powertrain
        A powertrain.
    goals : MountGoals
        The goals.

    Returns
    -------
    dict of str to float
        ``band_low``, ``band_high``, ``roll_energy``, ``roll_axis_angle`` (those asked for).
    """
    if not _holds(pt):
        return {name: -1e6 for name in _goal_names(goals)}
    md = modes(pt)
    out: dict[str, float] = {}
    if goals.band is not None:
        out["band_low"] = float(md.frequencies[0] - goals.band[0])
        out["band_high"] = float(goals.band[1] - md.frequencies[-1])
    if goals.roll_energy is not None:
        out["roll_energy"] = float(md.energy[md.roll_mode, 3] - goals.roll_energy)
    if goals.roll_axis_angle is not None:
        out["roll_axis_angle"] = math.degrees(goals.roll_axis_angle - md.roll_axis_angle)
    return out


def _goal_names(goals: MountGoals) -> list[str]:
    names = ["band_low", "band_high"] if goals.band is not None else []
    names += ["roll_energy"] if goals.roll_energy is not None else []
    return names + (["roll_axis_angle"] if goals.roll_axis_angle is not None else [])


def _holds(pt: Powertrain) -> bool:
    try:
        check_held(pt)
    except InputError:
        return False
    return True


@record
class MountOptimum(ResultMixin):
    """The mount optimiser's answer.

    Parameters
    ----------
    goals : MountGoals
        What it aimed at.
    powertrain : Powertrain
        The powertrain with the optimised mounts.
    variables : ndarray
        The variables found (:func:`with_variables`) [-], [m].
    objective_before, objective_after : float
        The objective of the mounts as given and as found [N] or [-].
    margins_before, margins_after : dict of str to float
        Each goal's margin (:func:`goal_margins`), as given and as found [Hz], [%], [deg].
    feasible : bool
        Whether every goal is met (every margin at least -1e-6).
    evaluations : int
        Calls of the objective and the goals, each one mount layout [-].
    generations : int
        Generations of the differential evolution run [-].
    """

    goals: MountGoals
    powertrain: Powertrain
    variables: NDArray[np.float64]
    objective_before: float
    objective_after: float
    margins_before: dict[str, float]
    margins_after: dict[str, float]
    feasible: bool
    evaluations: int
    generations: int


def optimizer_evaluations(n_variables: int, iterations: int) -> int:
    """The evaluations one optimisation makes, about: the population
    (:data:`OPTIMIZER_POPULATION` per variable) over every generation and the first, plus
    the two local searches' (each iteration a finite-difference gradient of the objective
    and of the goals).

    Parameters
    ----------
    n_variables : int
        Variables [-].
    iterations : int
        Generations [-].

    Returns
    -------
    int
        [-], at most :data:`MAX_OPTIMIZER_EVALUATIONS` for a run.
    """
    population = OPTIMIZER_POPULATION * n_variables
    local = 2 * OPTIMIZER_POLISH_ITERATIONS * 2 * (n_variables + 2)  # two starts
    return population * (iterations + 1) + local


def check_optimizer_work(pt: Powertrain, goals: MountGoals) -> None:
    """Refuse an optimisation whose evaluations (:func:`optimizer_evaluations`) exceed
    :data:`MAX_OPTIMIZER_EVALUATIONS`: one :class:`InputError` naming the iterations.

    Parameters
    ----------
    pt : Powertrain
        The powertrain (its number of mounts).
    goals : MountGoals
        The variables and the generations.

    Returns
    -------
    None
    """
    n_variables = len(variable_bounds(pt, goals))
    work = optimizer_evaluations(n_variables, goals.iterations)
    if work > MAX_OPTIMIZER_EVALUATIONS:
        raise InputError(
            "optimize_iterations",
            goals.iterations,
            f"the optimiser would evaluate up to {work} mount layouts ({n_variables} "
            f"variables); at most {MAX_OPTIMIZER_EVALUATIONS}: fewer iterations or variables",
        )


def optimize_mounts(
    pt: Powertrain,
    goals: MountGoals,
    loads: ArrayLike,
    orders: ArrayLike,
    reference_speed: float,
    speeds: ArrayLike,
    progress: Callable[[int, int, float], None] | None = None,
    seed: int = 0,
    gas: ArrayLike | None = None,
) -> MountOptimum:
    """Mount stiffnesses and/or positions within bounds toward the goals: a differential
    evolution (``scipy.optimize.differential_evolution``, seeded, the goals as nonlinear
    constraints), then a local search (SLSQP) from its best and from the mounts as given.

    The work is bounded before it starts (:func:`optimizer_evaluations` at most
    :data:`MAX_OPTIMIZER_EVALUATIONS`); the forced response of the objective is on
    ``speeds`` (the study gives :data:`OPTIMIZER_SPEEDS`).

    Parameters
    ----------
    pt : Powertrain
        The powertrain as given (the start of the search).
    goals : MountGoals
        Variables, bounds, goals and objective.
    loads : array_like of complex, shape (K, 6)
        Each order's loads at the reference point (:func:`order_loads`) [N], [N·m].
    orders : array_like of int, shape (K,)
        Engine orders [-].
    reference_speed : float
        The speed the loads are given at [rad/s].
    speeds : array_like, shape (S,)
        Crank speeds of the objective's sweep [rad/s].
    progress : callable, optional
        [-] Called after each generation with (generation, generations, the best objective
        among the layouts that meet the goals, inf while none does).
    seed : int
        The evolution's random seed [-].
    gas : array_like of complex, shape (K, 6), optional
        Loads that do not scale with the speed (the gas torque's reaction) [N·m].

    Returns
    -------
    MountOptimum
    """
    from scipy import optimize

    if not goals.variables:
        raise InputError("optimize", goals.variables, "stiffness and/or position")
    check_held(pt)
    check_optimizer_work(pt, goals)
    bounds = variable_bounds(pt, goals)
    n_variables = len(bounds)
    x0 = np.zeros(n_variables)
    widths = np.array([high - low for low, high in bounds])
    names = _goal_names(goals)

    def objective(x: NDArray[np.float64]) -> float:
        evaluated[0] += 1
        if goals.objective == "change":
            return float(np.sum(((x - x0) / widths) ** 2))
        trial = with_variables(pt, goals, x)
        if not _holds(trial):
            return 1e12
        return rms_mount_force(forced_response(trial, loads, orders, reference_speed, speeds, gas))

    def margins(x: NDArray[np.float64]) -> NDArray[np.float64]:
        evaluated[0] += 1
        found = goal_margins(with_variables(pt, goals, x), goals)
        return np.array([found[name] for name in names])

    constraints = [optimize.NonlinearConstraint(margins, 0.0, np.inf)] if names else []
    generation = [0]
    evaluated = [0]

    def callback(intermediate_result: Any) -> None:
        generation[0] += 1
        if progress is not None:
            x = np.asarray(intermediate_result.x, dtype=float)
            met = not names or bool(np.all(margins(x) >= -1e-6))
            progress(generation[0], goals.iterations, objective(x) if met else math.inf)

    evolved = optimize.differential_evolution(
        objective,
        bounds,
        maxiter=goals.iterations,
        popsize=OPTIMIZER_POPULATION,
        rng=np.random.default_rng(seed),
        constraints=constraints,
        polish=False,
        init="sobol" if n_variables > 1 else "latinhypercube",
        x0=x0,
        callback=callback,
        tol=1e-8,
    )
    low, high = np.array([b[0] for b in bounds]), np.array([b[1] for b in bounds])

    def rank(x: NDArray[np.float64]) -> tuple[float, float]:
        """Layouts that meet the goals first (by objective), then by their worst margin."""
        worst = float(np.min(margins(x))) if names else 0.0
        return (0.0, objective(x)) if worst >= -1e-6 else (1.0, -worst)

    best = np.asarray(evolved.x, dtype=float)
    for start in (best, x0):  # a local search from the evolution's best and from the start
        local = optimize.minimize(
            objective,
            start,
            method="SLSQP",
            bounds=bounds,
            constraints=[{"type": "ineq", "fun": margins}] if names else [],
            options={"maxiter": OPTIMIZER_POLISH_ITERATIONS},
        )
        candidate = np.clip(np.asarray(local.x, dtype=float), low, high)
        if rank(candidate) < rank(best):
            best = candidate
    found = with_variables(pt, goals, best)
    after = goal_margins(found, goals)
    return MountOptimum(
        goals,
        found,
        best,
        objective(x0),
        objective(best),
        goal_margins(pt, goals),
        after,
        all(v >= -1e-6 for v in after.values()),
        evaluated[0],
        generation[0],
    )
