"""The explorer on a dask LocalCluster of 2 workers against in process (issue 30, item 4),
measured side by side in one run.

Run: python benchmarks/bench_explore_cluster.py [--seconds 30] [--workers 2] [--repeat 2]
[--load K] [--chunk N]

BLAS runs on one thread on both sides: set here before numpy is imported for this
process, and by dask's nanny in every worker (``distributed.nanny.pre-spawn-environ``:
OMP, MKL and OpenBLAS at 1 thread); the explorer's figures use no matrix product across
engines, so a second BLAS thread would not help the in-process run anyway. The problem is
the 12-cylinder two-stroke in-line engine (39 916 800 firing orders, each one a
candidate) with counterweights, Pareto front of F1, M1, F2, M2 and the top 20. A first
short run measures this process's rate, and the slice (a span of indices from 0) is sized
to take about ``--seconds`` in process. Then:

1. a LocalCluster of ``--workers`` processes (one thread each, as ``run`` starts it:
   ``studies.explore.local_cluster``) is started and warmed
   (the imports and a small task on every worker), its start and warm-up timed on their
   own: a user
   keeps a cluster, so the issue's target is the run;
2. ``--repeat`` times, one after the other: the slice in process (``studies.explore.run``)
   and on that cluster (``scheduler=`` its address);
3. once, the slice on a LocalCluster that the run starts and stops itself
   (``workers=``): start, imports and stop in the time.

Printed for each run: the load average (1 min) before it, the elapsed time, the CPU time
of this process and of the workers (their own counters, read before and after), the
speed-up over the in-process run of the same repeat (the measure, target at least 1.6),
and whether the Pareto set and top-N are those of the run in process. The CPU time shows
where the time goes: the workers' CPU against the in-process CPU is the cluster's own
overhead (scheduling, pickling, the imports); the in-process CPU against its elapsed time
is the share of a core the machine gave it. ``--load K`` keeps K ``yes > /dev/null``
processes running during the whole benchmark (a loaded machine); ``--chunk N`` sets the
indices per task of every run (default: chosen by the run); ``--dask-environ`` starts the
kept cluster with dask's own worker environment (``MALLOC_TRIM_THRESHOLD_=65536``, as
before round six) instead of ``local_cluster``'s.
"""

from __future__ import annotations

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_name] = "1"

import argparse  # noqa: E402
import functools  # noqa: E402
import resource  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402
from _load import cpu_load  # noqa: E402

from crankbalance.physics.explore import merit, orders  # noqa: E402
from crankbalance.studies.explore import Keep, evaluate_task, local_cluster, run  # noqa: E402

TARGET_SPEEDUP = 1.6
OBJECTIVES = ("F1_N", "M1_Nm", "F2_N", "M2_Nm")
CALIBRATION = 100_000  # indices of the first, sizing run


def cpu_seconds() -> float:
    """User and system CPU time of this process [s] (run on a worker by ``client.run``)."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def workers_cpu(client: Any) -> float:
    """The CPU time of the cluster's worker processes, summed [s]."""
    return float(sum(client.run(cpu_seconds).values()))


def timed(func: Callable[[], Any]) -> tuple[float, float, Any]:
    """Elapsed and CPU time of this process of one call [s], and its result."""
    start, start_cpu = time.perf_counter(), cpu_seconds()
    out = func()
    return time.perf_counter() - start, cpu_seconds() - start_cpu, out


def same(a: Any, b: Any) -> bool:
    """Whether two runs kept the same Pareto set and top-N (rows, every column)."""
    for x, y in ((a.top, b.top), (a.pareto, b.pareto)):
        if set(x) != set(y):
            return False
        for name in x:
            if not np.array_equal(x[name], y[name]):
                return False
    return True


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--load", type=int, default=0, help="K `yes` processes meanwhile")
    parser.add_argument("--chunk", type=int, default=None, help="indices per task")
    parser.add_argument(
        "--dask-environ",
        action="store_true",
        help="the kept cluster with dask's own worker environment (MALLOC_TRIM_THRESHOLD_)",
    )
    args = parser.parse_args()
    with cpu_load(args.load):
        measure(args)


def measure(args: argparse.Namespace) -> None:
    from dask.distributed import Client

    problem = orders.problem("inline", 12, 2)
    total = orders.count(problem)
    evaluate = functools.partial(merit.merit, target="counterweights")
    keep = Keep(objectives=OBJECTIVES, key="residual_M_Nm", n=20)
    slice_of = functools.partial(run, problem, evaluate, keep=keep, chunk=args.chunk)
    load = os.getloadavg()[0]
    wall, cpu, _ = timed(lambda: slice_of(span=(0, CALIBRATION)))
    size = int(min(total, CALIBRATION * args.seconds / wall))
    span = (0, size)
    print(
        f"12-cylinder two-stroke in-line, {total:,} firing orders; slice of {size:,} indices "
        f"(sized to {args.seconds:g} s in process: {CALIBRATION:,} took {wall:.2f} s, "
        f"{cpu:.2f} s CPU); load average (1 min) {load:.2f} on {os.cpu_count()} CPUs; "
        f"BLAS 1 thread; {args.load} `yes` beside; chunk {args.chunk or 'chosen by the run'}; "
        f"kept cluster: {'dask' if args.dask_environ else 'local_cluster'} environment"
    )
    rows: list[tuple[str, float, float, float, float, Any]] = []
    start = time.perf_counter()
    if args.dask_environ:  # as before issue 30's round six: dask's own environment
        from dask.distributed import LocalCluster

        kept = LocalCluster(
            n_workers=args.workers, threads_per_worker=1, dashboard_address=None, silence_logs=50
        )
    else:
        kept = local_cluster(args.workers)
    with kept as cluster:
        address = cluster.scheduler_address
        with Client(address) as client:
            client.wait_for_workers(args.workers)
            started = time.perf_counter() - start
            # on every worker: the imports and a first small task, outside the clock
            warm, _, _ = timed(
                lambda: client.run(
                    evaluate_task, problem, evaluate, None, keep, False, None, (0, 64)
                )
            )
            print(
                f"cluster of {args.workers} started in {started:.2f} s, warmed (imports, a "
                f"small task on every worker) in {warm:.2f} s: not in the times below"
            )
            for k in range(1, args.repeat + 1):
                load = os.getloadavg()[0]
                wall, cpu, local = timed(lambda: slice_of(span=span))
                rows.append((f"{k}: in process", load, wall, cpu, 0.0, local))
                load = os.getloadavg()[0]
                before = workers_cpu(client)
                wall, cpu, there = timed(lambda: slice_of(span=span, scheduler=address))
                there_cpu = workers_cpu(client) - before
                rows.append((f"{k}: cluster started before", load, wall, cpu, there_cpu, there))
    load = os.getloadavg()[0]
    wall, cpu, fresh = timed(lambda: slice_of(span=span, workers=args.workers))
    rows.append(("cluster started by the run", load, wall, cpu, float("nan"), fresh))
    print(
        f"{'case':<30} {'load':>5} {'elapsed':>8} {'CPU here':>8} {'workers':>8} "
        f"{'CPU/in-proc':>11} {'speed-up':>8} {'target':>7} same"
    )
    reference = rows[0]
    for name, load, wall, cpu, there_cpu, result in rows:
        if name.endswith("in process"):
            reference = (name, load, wall, cpu, there_cpu, result)
            print(f"{name:<30} {load:5.2f} {wall:7.2f}s {cpu:7.2f}s {'':>8} {1:11.2f} {1:8.2f}")
            continue
        share = (cpu + there_cpu) / reference[3]
        workers = "" if np.isnan(there_cpu) else f"{there_cpu:7.2f}s"
        print(
            f"{name:<30} {load:5.2f} {wall:7.2f}s {cpu:7.2f}s {workers:>8} "
            f"{'' if np.isnan(share) else f'{share:.2f}':>11} {reference[2] / wall:8.2f} "
            f"{f'>= {TARGET_SPEEDUP:g}':>7} {same(reference[5], result)}"
        )
    print(f"load average (1 min) after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
