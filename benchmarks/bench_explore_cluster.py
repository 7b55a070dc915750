"""The explorer on a dask LocalCluster of 2 workers against in process (issue 30, item 4),
measured side by side in one run.

Run: python benchmarks/bench_explore_cluster.py [--seconds 30] [--workers 2]

BLAS runs on one thread (set here before numpy is imported), in this process and in the
workers, as the explorer's tasks do on a worker. The problem is the 12-cylinder two-stroke
in-line engine (39 916 800 firing orders) with counterweights, Pareto front of F1, M1, F2,
M2 and the top 20. A first short run measures this process's rate, and the slice (a span
of indices from 0) is sized to take about ``--seconds`` in process. Then, one after the
other, on that slice:

1. in process (``studies.explore.run``);
2. on a LocalCluster of ``--workers`` processes that ``run`` starts and stops itself
   (``workers=``): the cluster's start and stop are in the time;
3. on a LocalCluster started before the clock (``scheduler=`` its address): the tasks
   alone.

Printed: each elapsed time, this process's CPU time beside it, the speed-up over in
process (the measure, target at least 1.6), whether the Pareto set and top-N are the same
as in process, and the load average before and after (the machine is shared: a speed-up
over one process needs the second core free).
"""

from __future__ import annotations

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_name] = "1"

import argparse  # noqa: E402
import functools  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from crankbalance.physics.explore import merit, orders  # noqa: E402
from crankbalance.studies.explore import Keep, run  # noqa: E402

TARGET_SPEEDUP = 1.6
OBJECTIVES = ("F1_N", "M1_Nm", "F2_N", "M2_Nm")
CALIBRATION = 40_000  # indices of the first, sizing run


def timed(func: Callable[[], Any]) -> tuple[float, float, Any]:
    """Elapsed and CPU time of this process of one call [s], and its result."""
    start, start_cpu = time.perf_counter(), time.process_time()
    out = func()
    return time.perf_counter() - start, time.process_time() - start_cpu, out


def same(a: Any, b: Any) -> bool:
    """Whether two runs kept the same Pareto set and top-N (by index)."""
    return bool(
        np.array_equal(a.top["index"], b.top["index"])
        and np.array_equal(np.sort(a.pareto["index"]), np.sort(b.pareto["index"]))
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    from dask.distributed import LocalCluster

    problem = orders.problem("inline", 12, 2)
    total = orders.count(problem)
    evaluate = functools.partial(merit.merit, target="counterweights")
    keep = Keep(objectives=OBJECTIVES, key="residual_M_Nm", n=20)
    load = os.getloadavg()[0]
    wall, _, _ = timed(lambda: run(problem, evaluate, keep=keep, span=(0, CALIBRATION)))
    size = int(min(total, CALIBRATION * args.seconds / wall))
    span = (0, size)
    print(
        f"12-cylinder two-stroke in-line, {total:,} firing orders; slice of {size:,} indices "
        f"(sized to {args.seconds:g} s in process); load average (1 min) {load:.2f} on "
        f"{os.cpu_count()} CPUs; BLAS 1 thread"
    )
    local = timed(lambda: run(problem, evaluate, keep=keep, span=span))
    started = timed(lambda: run(problem, evaluate, keep=keep, span=span, workers=args.workers))
    with LocalCluster(
        n_workers=args.workers,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        silence_logs=50,
    ) as cluster:
        address = cluster.scheduler_address
        ready = timed(lambda: run(problem, evaluate, keep=keep, span=span, scheduler=address))
    rows = [
        ("in process", local, ""),
        (f"LocalCluster x{args.workers}, started by the run", started, ""),
        (f"LocalCluster x{args.workers}, started before", ready, ""),
    ]
    print(f"{'case':<40} {'elapsed':>9} {'CPU here':>9} {'speed-up':>9} {'target':>7} same")
    for name, (wall, cpu, result), _ in rows:
        speedup = local[0] / wall
        target = "" if result is local[2] else f">= {TARGET_SPEEDUP:g}"
        agree = "" if result is local[2] else str(same(local[2], result))
        print(f"{name:<40} {wall:8.2f}s {cpu:8.2f}s {speedup:9.2f} {target:>7} {agree}")
    print(f"load average (1 min) after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
