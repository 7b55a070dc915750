"""Speed of the free-force analysis (issue 2 targets), measured side by side in one run.

Run: python benchmarks/bench_analyze.py
Prints a table: curves of a built model, from an engine file to JSON, and the cold start
of the command line. One analysis of a built model and the batched analysis have their
own scripts, each with its reference: bench_one_engine.py and bench_batch_analysis.py.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
import timeit
from pathlib import Path

from crankbalance.io.engine_file import load_engine
from crankbalance.shaking import free_forces
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import Analysis, analyze

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "paper_inline3.toml"


def per_call(func, repeat: int = 5, number: int = 200) -> float:
    """Best-of-``repeat`` mean time of one call [s]."""
    return min(timeit.repeat(func, repeat=repeat, number=number)) / number


def main() -> None:
    rows: list[tuple[str, str, str]] = []
    model = build_model(load_engine("v12-60"))
    forces = free_forces(model, 8)
    t = per_call(lambda: Analysis(model, forces).curves(), number=50)
    rows.append(
        ("curves of 720 crank angles (V12, 8 orders + exact total)", f"{t * 1e3:.3f} ms", "-")
    )
    t = per_call(lambda: json.dumps(analyze(load_engine(EXAMPLE)).to_dict()), number=50)
    rows.append(("engine file -> JSON (paper inline-3)", f"{t * 1e3:.3f} ms", "< 5 ms"))

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
