"""The input schemas: their import and the validation of an engine file, before (pydantic)
and after (crankbalance.schema.core).

Run: python benchmarks/bench_schema.py [--runs N] [--before REF] [--no-before]

Measured, each in fresh interpreters of the same Python (the median of N runs):

* the engine file's schema alone (``crankbalance.schema.engine``; before:
  ``crankbalance.spec``), timed inside the interpreter from its first import, against
  ``python -c pass`` (the interpreter's own start, wall time);
* the settings schema with it (``schema.settings``; before: ``options``), timed after the
  physics modules they take constants from and numpy are imported: the schemas' own cost;
* the whole ``import`` of both in a fresh interpreter (wall time), against ``python -c
  "import numpy"``, which every study command loads anyway;
* validating every preset (``spec_from_dict`` of its parsed TOML, best of N batches)
  against ``tomllib.loads`` of the same text.

"Before" is the pydantic code of commit REF (default: the last one before issue 26
moved the modules), read with ``git archive`` into a temporary folder; it needs pydantic
installed (the web extra brings it) and is left out with ``--no-before``. Each tree runs
with a bytecode cache of its own (``PYTHONPYCACHEPREFIX``), filled by a warm-up run.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from io import BytesIO
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: the last commit with the pydantic schemas (crankbalance.spec, crankbalance.options)
BEFORE = "5fe67737a88f8f4340195778df75299fe478bf25"
#: targets: importing a schema [s], validating a preset [s]
TARGET_IMPORT_S = 5e-3
TARGET_VALIDATE_S = 0.2e-3

#: module names in each layout: the engine schema, the settings schema, their physics
LAYOUTS = {
    "after": (
        "crankbalance.schema.engine",
        # every study's schema: the package imports its families on first use (issue 30)
        ", ".join(
            f"crankbalance.schema.settings.{family}"
            for family in ("common", "counterweight", "single", "shaft", "cycle", "crank")
            + ("shop", "explore")
        ),
        "crankbalance.physics.engine_cycle, crankbalance.physics.engine_cycle_all, "
        "crankbalance.physics.explore.work, crankbalance.physics.single_cylinder, "
        "crankbalance.physics.firing",
    ),
    "before": (
        "crankbalance.spec",
        "crankbalance.options",
        "crankbalance.engine_cycle, crankbalance.engine_cycle_all, "
        "crankbalance.explore.work, crankbalance.single_cylinder, crankbalance.numbering",
    ),
}

_TIMED_IMPORT = """
import time, sys
{pre}
start = time.perf_counter()
import {modules}
print(time.perf_counter() - start)
"""

_VALIDATE = """
import json, timeit, tomllib
from importlib import resources
from {engine} import spec_from_dict
folder = resources.files("crankbalance") / "presets"
out = {{}}
for path in sorted(folder.iterdir(), key=lambda p: p.name):
    if not path.name.endswith(".toml"):
        continue
    text = path.read_text("utf-8")
    data = tomllib.loads(text)
    spec_from_dict(data)
    def best(func):
        number = max(1, int(0.02 / max(timeit.timeit(func, number=1), 1e-7)))
        return min(timeit.repeat(func, repeat={runs}, number=number)) / number
    out[path.name[:-5]] = (best(lambda: spec_from_dict(data)), best(lambda: tomllib.loads(text)))
print(json.dumps(out))
"""


def python(code: str, env: dict[str, str]) -> str:
    """Run ``code`` in a fresh interpreter; its output."""
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    return done.stdout


def wall(code: str, env: dict[str, str], runs: int) -> float:
    """Median wall time of a fresh interpreter running ``code`` [s]."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], env=env, check=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def measure(src: Path, layout: str, runs: int, cache: str) -> dict[str, object]:
    """The measurements of one source tree."""
    engine, options, physics = LAYOUTS[layout]
    env = {**os.environ, "PYTHONPATH": str(src), "PYTHONPYCACHEPREFIX": cache}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    both = f"{engine}, {options}"
    python(f"import {both}", env)  # warm-up: fills the bytecode cache
    median = statistics.median
    engine_alone = median(
        float(python(_TIMED_IMPORT.format(pre="", modules=engine), env)) for _ in range(runs)
    )
    pre = f"import numpy, {physics}"
    own = median(
        float(python(_TIMED_IMPORT.format(pre=pre, modules=both), env)) for _ in range(runs)
    )
    cold = wall(f"import {both}", env, runs)
    presets = json.loads(python(_VALIDATE.format(engine=engine, runs=runs), env))
    return {"engine": engine_alone, "own": own, "cold": cold, "presets": presets}


def before_tree(ref: str, folder: Path) -> Path | None:
    """The ``src`` folder of commit ``ref``, unpacked into ``folder`` (None without git
    or without pydantic)."""
    try:
        import pydantic  # noqa: F401
    except ImportError:
        print("before: pydantic is not installed; left out")
        return None
    try:
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", ref, "src"], capture_output=True, check=True
        ).stdout
    except (OSError, subprocess.CalledProcessError) as error:
        print(f"before: git archive {ref} failed ({error}); left out")
        return None
    with tarfile.open(fileobj=BytesIO(archive)) as tar:
        tar.extractall(folder, filter="data")
    return folder / "src"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=9, help="runs (fresh interpreters) each")
    parser.add_argument("--before", default=BEFORE, help="commit of the pydantic schemas")
    parser.add_argument("--no-before", action="store_true", help="measure this tree only")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="crankbalance-bench-schema-") as tmp:
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        start = wall("pass", env, args.runs)
        numpy = wall("import numpy", env, args.runs)
        results = {"after": measure(ROOT / "src", "after", args.runs, f"{tmp}/after")}
        old = None if args.no_before else before_tree(args.before, Path(tmp) / "before")
        if old is not None:
            results["before"] = measure(old, "before", args.runs, f"{tmp}/before")

    ms = 1e3
    print(f"python -c pass: {start * ms:.1f} ms; python -c 'import numpy': {numpy * ms:.1f} ms")
    print(f"{'':46s} {'before':>10s} {'after':>10s} {'target':>10s} {'after/target':>12s}")

    def row(label: str, key: str, target: float) -> None:
        values = [results[k][key] for k in ("before", "after") if k in results]
        shown = [f"{float(v) * ms:8.2f} ms" for v in values]  # type: ignore[arg-type]
        if len(shown) == 1:
            shown.insert(0, f"{'-':>11s}")
        after = float(results["after"][key])  # type: ignore[arg-type]
        print(f"{label:46s} {shown[0]} {shown[1]} {target * ms:7.2f} ms {after / target:12.2f}")

    row("import the engine file's schema", "engine", TARGET_IMPORT_S)
    row("import both schemas, physics preloaded", "own", TARGET_IMPORT_S)
    row("fresh interpreter importing both (wall)", "cold", numpy + TARGET_IMPORT_S)
    presets = {k: results[k]["presets"] for k in results}
    after = presets["after"]
    assert isinstance(after, dict)
    validate = [after[name][0] for name in after]
    toml = [after[name][1] for name in after]
    slowest = max(after, key=lambda name: after[name][0])
    median = statistics.median
    print(
        f"validate a preset (spec_from_dict), {len(after)} presets: median "
        f"{median(validate) * ms:.4f} ms, slowest {slowest} {after[slowest][0] * ms:.4f} ms; "
        f"target {TARGET_VALIDATE_S * ms:g} ms, ratio {after[slowest][0] / TARGET_VALIDATE_S:.2f}"
    )
    print(f"  {median(validate) / median(toml):.2f} x tomllib.loads of the same text (median)")
    if "before" in presets:
        before = presets["before"]
        assert isinstance(before, dict)
        ratios = [after[n][0] / before[n][0] for n in after if n in before]
        old = [b[0] for b in before.values()]
        print(
            f"  before (pydantic): median {median(old) * ms:.4f} ms, "
            f"{median(old) / median(b[1] for b in before.values()):.2f} x tomllib.loads; "
            f"after / before: median {median(ratios):.2f}"
        )


if __name__ == "__main__":
    main()
