"""Speed of the balancing solver (issue 3 targets), side by side in one run.

Run: python benchmarks/bench_balancing.py
"""

from __future__ import annotations

import timeit
from pathlib import Path

import numpy as np

from crankbalance.io.engine_file import load_engine
from crankbalance.physics.balancing import CounterweightOptions, balance, counterweight_angle_sweep
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import balance_options

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "paper_inline3.toml"


def per_call(func, number: int = 100) -> float:
    return min(timeit.repeat(func, repeat=5, number=number)) / number


def main() -> None:
    spec = load_engine(EXAMPLE)
    model = build_model(spec)
    cw, primary, secondary = balance_options(spec)
    rows = []
    t = per_call(lambda: balance(model, cw, primary, secondary))
    rows.append(
        (
            "solve paper inline-3: counterweights, 2 shaft pairs, time-domain check",
            f"{t * 1e3:.3f} ms",
            "< 2 ms",
        )
    )
    v12 = build_model(load_engine("v12-60"))
    opts = CounterweightOptions(0.05, angle="optimal", balance_factor=0.5)
    t = per_call(lambda: balance(v12, opts))
    rows.append(
        ("solve V12 60 deg: optimal-angle counterweights, check", f"{t * 1e3:.3f} ms", "< 2 ms")
    )
    angles = np.radians(np.arange(0.0, 90.0001, 0.1))
    t = per_call(lambda: counterweight_angle_sweep(model, cw, angles))
    rows.append(
        (
            f"counterweight angle sweep 0-90 deg in 0.1 deg ({angles.size} angles)",
            f"{t * 1e3:.3f} ms",
            "< 50 ms",
        )
    )
    width = max(len(r[0]) for r in rows)
    print(f"{'case'.ljust(width)}  {'measured':>12}  {'target':>8}")
    print(f"{'-' * width}  {'-' * 12}  {'-' * 8}")
    for name, value, target in rows:
        print(f"{name.ljust(width)}  {value:>12}  {target:>8}")


if __name__ == "__main__":
    main()
