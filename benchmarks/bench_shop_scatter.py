"""Tolerance statistics (issue 16, item 5): Monte Carlo samples per second of CPU.

One sample is one complete set of parts drawn for the 8 cylinders of the crossplane V8
preset (pistons, pins, rings, two locks and the small end per cylinder; the big end and
two bearing shells; every weighed part also read on a 0.1 g scale) and its residuals
computed: the unbalance in two correction planes, the free forces and couples of orders 1
and 2, their histograms and the tolerance checks (``shop.scatter.scatter_study``).

Reference, measured in the same run: numpy drawing the same random numbers alone (the
same count of single-precision normal and uniform draws, PCG64), the floor any Monte
Carlo of these parts has. CPU time (``time.process_time``), best of a few runs, so that
other processes on the machine count less. BLAS runs on one thread unless
``OPENBLAS_NUM_THREADS`` is set (the products are small; threads only contend).

    python benchmarks/bench_shop_scatter.py [samples]

Target: at least 1e6 samples per second.
"""

from __future__ import annotations

import os
import sys

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time  # noqa: E402
from collections.abc import Callable  # noqa: E402

import numpy as np  # noqa: E402

from crankbalance.io.engine_file import load_engine  # noqa: E402
from crankbalance.physics.shop.scatter import CHUNK, PartScatter, scatter_study  # noqa: E402
from crankbalance.studies.build import build_model  # noqa: E402

TARGET = 1e6  # samples per second
G = 1e-3  # kg per g
PARTS = (
    PartScatter("piston", "reciprocating", 0.5 * G),
    PartScatter("pin", "reciprocating", 0.3 * G),
    PartScatter("rings", "reciprocating", 0.2 * G, "uniform"),
    PartScatter("locks", "reciprocating", 0.02 * G, "uniform", count=2),
    PartScatter("small end", "reciprocating", 0.4 * G),
    PartScatter("big end", "rotating", 0.6 * G),
    PartScatter("shells", "rotating", 0.1 * G, count=2),
)
SCALE = 0.1 * G


def cpu_time(function: Callable[[], object], repeat: int = 3) -> float:
    """Best-of-``repeat`` CPU time of one call [s]."""
    times = []
    for _ in range(repeat):
        start = time.process_time()
        function()
        times.append(time.process_time() - start)
    return min(times)


def main() -> None:
    samples = int(sys.argv[1]) if len(sys.argv) > 1 else 2_000_000
    model = build_model(load_engine("v8-crossplane"))
    cylinders = model.cylinders

    def study() -> object:
        return scatter_study(
            model,
            PARTS,
            (-0.2, 0.2),
            0.5,
            samples,
            seed=1,
            scale_step=SCALE,
            plane_tolerance=(2e-5, 2e-5),
            force_limit=(50.0, 50.0),
        )

    # the draws the study makes per cylinder: one normal per kind, one uniform per
    # uniform part and per weighed part
    uniforms = sum(p.count for p in PARTS if p.distribution == "uniform")
    uniforms += sum(p.count for p in PARTS if p.weighed)
    rng = np.random.default_rng(1)

    def draws() -> None:
        for start in range(0, samples, CHUNK):
            size = min(CHUNK, samples - start)
            rng.standard_normal((size, 2 * cylinders), dtype=np.float32)
            rng.random((uniforms, size, cylinders), dtype=np.float32)

    study()  # warm-up: imports, caches
    measured = samples / cpu_time(study)
    reference = samples / cpu_time(draws)
    per_sample = 2 + uniforms
    print(f"samples: {samples}, cylinders: {cylinders}, random draws per cylinder: {per_sample}")
    print(f"{'case':<46}  {'samples/s':>12}  {'target':>10}  {'ratio':>6}")
    print(f"{'scatter_study, crossplane V8':<46}  {measured:>12.3e}  {TARGET:>10.1e}  ", end="")
    print(f"{measured / TARGET:>6.2f}")
    print(f"{'reference: numpy draws of the same numbers':<46}  {reference:>12.3e}  ", end="")
    print(f"{'':>10}  {'':>6}")
    print(f"measured / reference: {measured / reference:.2f}")


if __name__ == "__main__":
    main()
