"""Engine file -> result, in one process: a preset loaded, validated, built and analysed.

Run: python benchmarks/bench_parse.py [--preset NAME] [--repeat N]

Prints the best-of-N time of each stage (read the preset's TOML, validate it into an
``EngineSpec``, build the ``EngineModel``, analyse it) and of the whole, the target
(issue 30: at most 0.5 ms; issue 13 asked 1 ms) and the ratio of the whole to a bare
analysis of the built model and to the TOML parse alone, both measured in the same run.
One quantity string read by ``crankbalance.units`` is timed too.

The whole is timed twice: as a program that reads the same engine again meets it (the
text's spec and the spec's model kept: ``io.engine_file.PARSE_CACHE``,
``studies.build.BUILD_CACHE``; the target is on this one) and the first time an engine is
seen (both caches emptied before every call, so it reads, validates, builds and analyses).
"""

from __future__ import annotations

import argparse
import timeit
import tomllib
from collections.abc import Callable

from crankbalance.io import engine_file
from crankbalance.io.engine_file import load_engine, preset_text
from crankbalance.physics.shaking import free_forces
from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies import build
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze
from crankbalance.units import parse_quantity

TARGET_S = 0.5e-3


def best(func: Callable[[], object], repeat: int) -> float:
    """Best-of-``repeat`` time of one call [s] (each repeat the mean of a batch)."""
    number = max(1, int(0.02 / max(timeit.timeit(func, number=1), 1e-7)))
    return min(timeit.repeat(func, repeat=repeat, number=number)) / number


def fresh_build(spec: object) -> object:
    """``build_model`` of a spec not seen before (its cache emptied)."""
    build._built.cache_clear()
    return build_model(spec)  # type: ignore[arg-type]


def first_time(preset: str) -> object:
    """Engine file to result with nothing kept from an earlier call."""
    engine_file._parsed.cache_clear()
    build._built.cache_clear()
    return analyze(load_engine(preset), 8)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--preset", default="inline4", help="engine preset")
    parser.add_argument("--repeat", type=int, default=7, help="best of N")
    args = parser.parse_args()

    text = preset_text(args.preset)
    data = tomllib.loads(text)
    spec = spec_from_dict(data)
    model = build_model(spec)
    stages = {
        "read the TOML (tomllib.loads)": lambda: tomllib.loads(text),
        "validate (spec_from_dict)": lambda: spec_from_dict(data),
        "build the model (build_model, first time)": lambda: fresh_build(spec),
        "analyse the model (free_forces, 8 orders)": lambda: free_forces(model, 8),
        "one quantity ('6000 rpm' -> rad/s)": lambda: parse_quantity("6000 rpm", "speed", "s"),
    }
    times = {name: best(func, args.repeat) for name, func in stages.items()}
    whole = best(lambda: analyze(load_engine(args.preset), 8), args.repeat)
    first = best(lambda: first_time(args.preset), args.repeat)
    width = max(map(len, stages)) + 2
    print(f"preset {args.preset}, best of {args.repeat}")
    for name, t in times.items():
        print(f"  {name:{width}s} {t * 1e3:8.4f} ms")
    verdict = "met" if whole <= TARGET_S else "NOT met"
    print(f"  {'whole: analyze(load_engine(preset))':{width}s} {whole * 1e3:8.4f} ms")
    print(f"  {'whole, the first time the engine is seen':{width}s} {first * 1e3:8.4f} ms")
    print(
        f"measured {whole * 1e3:.3f} ms; target <= {TARGET_S * 1e3:g} ms ({verdict}); "
        f"{whole / times['analyse the model (free_forces, 8 orders)']:.1f} x a bare analysis, "
        f"{whole / times['read the TOML (tomllib.loads)']:.1f} x the TOML parse"
    )


if __name__ == "__main__":
    main()
