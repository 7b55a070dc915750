"""Counterweight optimisation: feasible designs, Pareto front, hypervolume, search bounds.

This module owns the search over the counterweight profiles of
:mod:`crankbalance.physics.counterweight`: the parameter ranges (:data:`DEFAULT_BOUNDS`,
:func:`parse_bounds`), the vectorised evaluation of designs against the constraints, the
archive search :func:`optimize_counterweight` (shaped like ``scipy.optimize``, reporting
:class:`OptimizationProgress` to a callback and returning a :class:`CounterweightOptimum`)
and the multi-objective helpers :func:`pareto_indices` and :func:`hypervolume_2d`. The
geometry it evaluates is in :mod:`crankbalance.physics.counterweight`.

References
----------
.. [1] Applied Sciences 11 (2021) 8997, Sec. 4-5 and Table 3 (the counterweight design
   tab: constraints, parameter ranges, least mass and least radial space).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from typing import Literal

import numpy as np

from ..errors import InputError
from ..records import record
from ..results import ResultMixin
from .counterweight import (
    DEFAULT_DENSITY,
    PARAMETERS,
    CounterweightDesign,
    check_positive_number,
    profile_section,
    profile_validity,
)

RadiusMeasure = Literal["true", "paper"]
Objective = Literal["mass", "radius", "inertia"]

#: Default search range of each parameter [m or rad] (used for parameters not given).
DEFAULT_BOUNDS: dict[str, tuple[float, float]] = {
    "web_radius": (0.010, 0.020),
    "rectangle_height": (0.0, 0.030),
    "trapezoid_angle": (0.0, 1.46),
    "segment_radius": (0.020, 0.080),
    "segment_angle": (0.2, math.pi),
    "thickness": (0.005, 0.030),
}


# --------------------------------------------------------------------------------------
# Search ranges
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

    Parameters
    ----------
    bounds : mapping or None
        Parameter name (:data:`~crankbalance.physics.counterweight.PARAMETERS`) -> ``(low, high)``
        [m or rad] to leave it free, or a number [m or rad] to fix it. Parameters not given
        take :data:`DEFAULT_BOUNDS`.

    Returns
    -------
    dict
        Every parameter name -> ``(low, high)`` [m or rad]; ``low == high`` when fixed.

    Raises
    ------
    InputError
        Naming the parameter, for unknown names, ``low > high`` or values outside the domain.

    References
    ----------
    .. [1] Appl. Sci. 2021, Sec. 5 (fourth tab: parameter ranges, fixed/free selectors).
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


def clear_of_journal(
    bounds: Mapping[str, float | tuple[float, float] | Sequence[float]] | None,
    journal_radius: float,
) -> dict[str, float | tuple[float, float]]:
    """The bounds with the web circle kept clear of the main journal.

    The counterweight's profile leaves out the web circle of radius r_cw about the crank
    axis (:mod:`crankbalance.physics.counterweight`), which is where the main journal
    sits: a counterweight is clear of the journal exactly when r_cw is at least the
    journal's radius. (The crankpin lies opposite, below the axis, where the profile has
    nothing.) A web radius not given is searched from the journal's radius up, over a
    range as wide as its default one: ``(max(lo, rj), max(hi, max(lo, rj) + hi - lo))``
    for the default ``(lo, hi)`` of :data:`DEFAULT_BOUNDS`.

    Parameters
    ----------
    bounds : mapping or None
        Parameter name -> ``(low, high)`` or a fixed value [m or rad], as for
        :func:`parse_bounds`; left unchanged but for ``web_radius``.
    journal_radius : float
        Radius of the main journal the web circle must clear [m].

    Returns
    -------
    dict
        The bounds given, with ``web_radius`` added when it was not given.

    Raises
    ------
    InputError
        ``journal_radius`` not a positive finite length, or a given web radius (its lower
        end for a range) below it, naming ``web_radius``.
    """
    rj = check_positive_number("journal_radius", journal_radius)
    out: dict[str, float | tuple[float, float]] = {
        name: value if isinstance(value, (int, float)) else (float(value[0]), float(value[1]))
        for name, value in (bounds or {}).items()
    }
    given = out.get("web_radius")
    if given is None:
        lo, hi = DEFAULT_BOUNDS["web_radius"]
        low = max(lo, rj)
        out["web_radius"] = (low, max(hi, low + hi - lo))
        return out
    low_given = float(given) if isinstance(given, (int, float)) else given[0]
    if low_given < rj:
        raise InputError(
            "web_radius",
            given,
            f"must be at least the main journal's radius, {rj * 1e3:.4g} mm, or the "
            "counterweight overlaps the journal",
        )
    return out


@record
class OptimizationProgress:
    """State passed to the ``callback`` of :func:`optimize_counterweight` after each iteration.

    Attributes
    ----------
    iteration, n_iterations : Round just finished, and rounds asked for.
    nfev : Designs evaluated so far.
    n_feasible : Feasible designs found so far.
    n_pareto : Designs on the current front.
    least_mass : Least feasible mass so far [kg] (None if none or mass is no objective).
    elapsed : Wall time since the start [s].
    """

    iteration: int
    n_iterations: int
    nfev: int
    n_feasible: int
    n_pareto: int
    least_mass: float | None
    elapsed: float


@record
class CounterweightOptimum(ResultMixin):
    """Result of :func:`optimize_counterweight` (shaped like ``scipy.optimize.OptimizeResult``).

    Attributes
    ----------
    designs : ndarray, shape (N, 6)
        Every feasible design found, columns :data:`PARAMETERS` [m or rad, per column].
    mass : ndarray, shape (N,)
        Mass of each design [kg].
    outer_radius : ndarray, shape (N,)
        Largest distance of the profile from the crank axis [m].
    radius_bound : ndarray, shape (N,)
        The paper's R_min bound (Table 3) [m].
    inertia : ndarray, shape (N,)
        Mass moment of inertia about the crank axis [kg m^2].
    cg_radius : ndarray, shape (N,)
        Distance of the centre of gravity from the crank axis [m].
    first_moment : ndarray, shape (N,)
        m_cw r_c [kg m].
    balance : ndarray, shape (N,)
        Achieved / required first moment [%].
    pareto : ndarray of int
        Indices of the Pareto-optimal designs (mass vs radial space, and inertia if
        asked), sorted by radial space [-].
    least_mass, least_radius : int
        Indices of the least-mass and least-radius feasible designs.
    x : ndarray, shape (6,)
        Parameters of the least-mass design, as scipy's ``x`` [m or rad, per column].
    fun : float
        Its mass, as scipy's ``fun`` [kg].
    nfev : int
        Designs evaluated.
    nit : int
        Iterations (rounds) run.
    success : bool
        Whether the run succeeded (as scipy's ``success``).
    message : str
        How the run ended.
    required_first_moment : float
        First moment asked for [kg m].
    density : float
        Material density [kg/m^3].
    free : tuple of str
        Names of the parameters that were varied.
    objectives : tuple of str
        Names of the objectives minimised.
    radius_measure : {"true", "paper"}
        ``"true"`` (largest distance of the profile from the axis) or ``"paper"`` (the
        R_min bound of Table 3); used for the constraint and the front.
    elapsed : float
        Wall time of the run [s].
    parameter_names : tuple of str
        Column names of ``designs`` and ``x``.

    References
    ----------
    Appl. Sci. 2021, Sec. 4 (counterweight optimisation), Table 3.
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
        """The feasible design number ``index`` as a :class:`CounterweightDesign`.

        Parameters
        ----------
        index : int
            Row of :attr:`designs` [-].

        Returns
        -------
        CounterweightDesign
            Its parameters [SI] with the optimum's density.
        """
        r, h, delta, big_r, alpha, t = (float(v) for v in self.designs[index])
        return CounterweightDesign(r, h, delta, big_r, alpha, t, self.density)

    @property
    def least_mass_design(self) -> CounterweightDesign:
        """The least-mass feasible design."""
        return self.design(self.least_mass)

    @property
    def least_radius_design(self) -> CounterweightDesign:
        """The least-radius feasible design."""
        return self.design(self.least_radius)

    def pareto_table(self) -> list[dict[str, float]]:
        """The Pareto designs as rows (SI), least radius first."""
        return [self.row(int(i)) for i in self.pareto]

    def row(self, index: int) -> dict[str, float]:
        """One feasible design with its properties (SI).

        Parameters
        ----------
        index : int
            Row of :attr:`designs` [-].

        Returns
        -------
        dict
            :data:`PARAMETERS` [m, rad] and mass [kg], outer_radius, radius_bound [m],
            inertia [kg m^2], cg_radius [m], first_moment [kg m], balance [%].
        """
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

    Parameters
    ----------
    objectives : ndarray
        (N, k) objective values, one row per design [any units, smaller is better].

    Returns
    -------
    ndarray of int
        Row indices of the Pareto front, in lexicographic order of their objectives.

    References
    ----------
    .. [1] Kung, Luccio and Preparata 1975, "On finding the maxima of a set of vectors"
       (the sort-and-sweep filters used for two and three objectives).
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
    """Hypervolume (area) dominated by 2-objective ``points`` (minimisation) up to ``reference``.

    Parameters
    ----------
    points : ndarray
        (N, 2) objective values [units of each objective]; points not below the reference
        in both objectives are ignored.
    reference : sequence of 2 floats
        Reference point [units of each objective], worse than every point of interest.

    Returns
    -------
    float
        The dominated area [product of the two units].

    References
    ----------
    .. [1] Zitzler and Thiele 1999, "Multiobjective evolutionary algorithms: a comparative
       case study and the strength Pareto approach" (the hypervolume indicator).
    """
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
        required: float,
        bounds: Mapping[str, tuple[float, float]],
        density: float,
        max_mass: float,
        max_radius: float,
        min_balance: float,
        radius_measure: RadiusMeasure,
        objectives: Sequence[Objective],
    ) -> None:
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
        Material density rho [kg/m^3].
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
        Initial sample size [designs], refinement rounds [-] and designs evaluated per
        round [designs].
    rng : int or numpy.random.Generator, optional
        Seed for repeatable runs.
    callback : callable, optional
        Called with an :class:`OptimizationProgress` after each round; return True to stop.

    Returns
    -------
    CounterweightOptimum
        Every feasible design with its properties (SI), the Pareto front and the extremes.

    Raises
    ------
    InputError
        For bad bounds or constraints, or when no feasible design is found.

    References
    ----------
    .. [1] Appl. Sci. 2021, Sec. 5 (fourth tab: constraints, parameter ranges,
       fixed/free selectors) and Table 3 (least mass, least radial space).
    """
    t0 = time.perf_counter()
    required = check_positive_number("required_first_moment", required_first_moment)
    rho = check_positive_number("density", density)
    b_min = check_positive_number("min_balance", min_balance)
    m_max = math.inf if max_mass is None else check_positive_number("max_mass", max_mass)
    r_max = math.inf if max_radius is None else check_positive_number("max_radius", max_radius)
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
