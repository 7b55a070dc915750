"""Speed of the free-force analysis (issue 2 targets), measured side by side in one run.

Run: python benchmarks/bench_analyze.py
Prints a table: time per analysis of a built model, from an engine file to JSON, batched
engines per second, and the cold start of the command line.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
import timeit
from pathlib import Path

import numpy as np

from crankbalance.io.engine_file import load_engine
from crankbalance.shaking import batch_amplitudes, free_forces
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import Analysis, analyze

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "paper_inline3.toml"


def per_call(func, repeat: int = 5, number: int = 200) -> float:
    """Best-of-``repeat`` mean time of one call [s]."""
    return min(timeit.repeat(func, repeat=repeat, number=number)) / number


def main() -> None:
    rows: list[tuple[str, str, str]] = []
    model = build_model(load_engine("v12-60"))
    t = per_call(lambda: free_forces(model, 8))
    rows.append(
        (
            "analyse a built model (V12, 8 orders, amplitudes + phasors)",
            f"{t * 1e3:.4f} ms",
            "< 0.1 ms",
        )
    )
    forces = free_forces(model, 8)
    t = per_call(lambda: Analysis(model, forces).curves(), number=50)
    rows.append(
        ("curves of 720 crank angles (V12, 8 orders + exact total)", f"{t * 1e3:.3f} ms", "-")
    )
    t = per_call(lambda: json.dumps(analyze(load_engine(EXAMPLE)).to_dict()), number=50)
    rows.append(("engine file -> JSON (paper inline-3)", f"{t * 1e3:.3f} ms", "< 5 ms"))

    engines, cylinders = 100_000, 8
    rng = np.random.default_rng(1)
    shape = (engines, cylinders)
    args = (
        rng.uniform(0.03, 0.06, engines),
        rng.uniform(0.12, 0.2, engines),
        rng.uniform(300, 900, engines),
        rng.uniform(0.3, 0.8, shape),
        rng.uniform(0, 2 * np.pi, shape),
        rng.uniform(-0.8, 0.8, shape),
        rng.uniform(-0.2, 0.2, shape),
    )
    times = []
    for _ in range(3):  # best of three: the first run also pays for page faults
        start = time.perf_counter()
        batch_amplitudes(*args, orders=8)
        times.append(time.perf_counter() - start)
    t = min(times)
    rows.append(
        (
            f"batched: {engines} engines of {cylinders} cylinders, 8 orders",
            f"{engines / t:,.0f} engines/s",
            "> 100,000 engines/s",
        )
    )

    starts = []
    for _ in range(3):
        start = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "crankbalance", "analyze", str(EXAMPLE)],
            check=True,
            capture_output=True,
        )
        starts.append(time.perf_counter() - start)
    rows.append(
        ("`crankbalance analyze FILE` cold start (best of 3)", f"{min(starts):.3f} s", "< 1 s")
    )

    width = max(len(r[0]) for r in rows)
    print(f"{'case'.ljust(width)}  {'measured':>22}  {'target':>20}")
    print(f"{'-' * width}  {'-' * 22}  {'-' * 20}")
    for name, value, target in rows:
        print(f"{name.ljust(width)}  {value:>22}  {target:>20}")


if __name__ == "__main__":
    main()
