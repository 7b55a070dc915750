"""Counterweight optimiser against pymoo NSGA-II and scipy differential evolution.

Same problem, same bounds, same evaluation function (thickness in closed form from the
required first moment for every method): Table 3-sized requirement m_c r_c = 7880 g*mm,
8000 kg/m^3, radial space (true outer radius) <= 80 mm, mass <= 400 g, balance >= 100 %,
all five profile parameters free within DEFAULT_BOUNDS, thickness 4..30 mm.

Prints one table: wall time, evaluations, feasible designs, front size, hypervolume of
the mass-vs-radius front (normalised by the reference box), least mass. Also an
exhaustive grid for the least mass. Run:  python benchmarks/bench_counterweight.py
"""

from __future__ import annotations

import math
import time

import numpy as np

from crankbalance.physics.counterweight_optimize import (
    _Problem,
    hypervolume_2d,
    optimize_counterweight,
    pareto_indices,
    parse_bounds,
)

REQUIRED = 0.00788
BOUNDS = {"thickness": (0.004, 0.030)}
MAX_RADIUS, MAX_MASS = 0.080, 0.400
REF = (MAX_MASS, MAX_RADIUS)


def problem() -> _Problem:
    return _Problem(
        REQUIRED,
        parse_bounds(BOUNDS),
        8000.0,
        MAX_MASS,
        MAX_RADIUS,
        100.0,
        "true",
        ("mass", "radius"),
    )


def hv(f: np.ndarray) -> float:
    return hypervolume_2d(f, REF) / (REF[0] * REF[1])


def ours(seed: int, population: int = 4096, iterations: int = 40, children: int = 4096) -> dict:
    t = time.perf_counter()
    res = optimize_counterweight(
        REQUIRED,
        BOUNDS,
        max_radius=MAX_RADIUS,
        max_mass=MAX_MASS,
        rng=seed,
        population=population,
        iterations=iterations,
        children=children,
    )
    dt = time.perf_counter() - t
    f = np.c_[res.mass[res.pareto], res.outer_radius[res.pareto]]
    name = f"crankbalance {population}+{iterations}x{children}"
    return dict(
        name=name,
        time=dt,
        nfev=res.nfev,
        feasible=len(res.designs),
        front=len(f),
        hv=hv(f),
        least=res.fun,
    )


def nsga2(seed: int, pop: int = 100, gens: int = 300) -> dict | None:
    try:
        from pymoo.algorithms.moo.nsga2 import NSGA2
        from pymoo.core.problem import Problem
        from pymoo.optimize import minimize
    except ImportError:
        print("pymoo not installed (pip install 'crankbalance[geometry]'): NSGA-II skipped")
        return None
    prob = problem()
    store: list[np.ndarray] = []

    class P(Problem):
        def __init__(self):
            super().__init__(
                n_var=len(prob.low), n_obj=2, n_ieq_constr=1, xl=prob.low, xu=prob.high
            )

        def _evaluate(self, x, out, *args, **kwargs):
            ev = prob.evaluate(np.asarray(x))
            f = np.c_[
                np.where(ev["valid"], ev["mass"], 1e3), np.where(ev["valid"], ev["radius"], 1e3)
            ]
            out["F"] = f
            out["G"] = ev["violation"][:, None]
            if np.any(ev["feasible"]):
                store.append(f[ev["feasible"]])

    t = time.perf_counter()
    minimize(P(), NSGA2(pop_size=pop), ("n_gen", gens), seed=seed, verbose=False)
    dt = time.perf_counter() - t
    allf = np.vstack(store) if store else np.empty((0, 2))
    front = allf[pareto_indices(allf)] if len(allf) else allf
    return dict(
        name=f"pymoo NSGA-II {pop}x{gens}",
        time=dt,
        nfev=pop * gens,
        feasible=len(allf),
        front=len(front),
        hv=hv(front),
        least=float(front[:, 0].min()) if len(front) else math.nan,
    )


def de_least_mass(seed: int) -> dict:
    from scipy.optimize import differential_evolution

    prob = problem()

    def f(x):  # vectorised: x has shape (d, S)
        ev = prob.evaluate(np.atleast_2d(x.T))
        return np.where(ev["feasible"], ev["mass"], 10.0 + ev["violation"])

    t = time.perf_counter()
    res = differential_evolution(
        f,
        list(zip(prob.low, prob.high, strict=True)),
        rng=seed,
        vectorized=True,
        updating="deferred",
        maxiter=2000,
        tol=1e-10,
        polish=False,
    )
    dt = time.perf_counter() - t
    return dict(
        name="scipy differential_evolution",
        time=dt,
        nfev=res.nfev,
        feasible=math.nan,
        front=math.nan,
        hv=math.nan,
        least=float(res.fun),
    )


def exhaustive(n: int = 22) -> dict:
    prob = problem()
    axes = [np.linspace(lo, hi, n) for lo, hi in zip(prob.low, prob.high, strict=True)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(axes))
    t = time.perf_counter()
    best, fronts = math.inf, []
    for s in range(0, len(grid), 250_000):
        ev = prob.evaluate(grid[s : s + 250_000])
        if np.any(ev["feasible"]):
            best = min(best, float(ev["mass"][ev["feasible"]].min()))
            ff = ev["f"][ev["feasible"]]
            fronts.append(ff[pareto_indices(ff)])
    front = np.vstack(fronts)
    front = front[pareto_indices(front)]
    return dict(
        name=f"exhaustive grid {n}^5",
        time=time.perf_counter() - t,
        nfev=len(grid),
        feasible=math.nan,
        front=len(front),
        hv=hv(front),
        least=best,
    )


def main() -> None:
    ours(0)  # warm-up (imports)
    rows = [ours(1), ours(1, 2048, 20, 2048), nsga2(1), nsga2(2), de_least_mass(1), exhaustive()]
    rows = [r for r in rows if r is not None]
    print(
        f"{'method':32s} {'time s':>8s} {'evals':>9s} {'feasible':>9s} {'front':>6s} "
        f"{'HV (norm)':>10s} {'least mass g':>13s}"
    )
    for r in rows:

        def cell(v, fmt, width):
            return "-".rjust(width) if isinstance(v, float) and math.isnan(v) else format(v, fmt)

        print(
            f"{r['name']:32s} {r['time']:8.2f} {r['nfev']:9d} {cell(r['feasible'], '9', 9)} "
            f"{cell(r['front'], '6', 6)} {cell(r['hv'], '10.5f', 10)} {r['least'] * 1e3:13.3f}"
        )


if __name__ == "__main__":
    main()
