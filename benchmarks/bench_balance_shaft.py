"""Timings of the balance-shaft model (crankbalance.physics.balance_shaft); prints a table.

Run: ``python benchmarks/bench_balance_shaft.py``. Target (issue 6): the full optimum
sweep, 200 design positions x 20 weights with all state variables (FE frequency
included), under 0.5 s.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from crankbalance.physics.balance_shaft import (
    BalanceShaft,
    compare_inline3_types,
    inline4_secondary_unbalance,
    inline4_study,
    shaft_response,
)
from crankbalance.physics.beam import ShaftSection, beam_statics, natural_frequencies

SECTION = ShaftSection(outer_diameter=0.025)
UNBALANCE = inline4_secondary_unbalance(0.5, 0.043, 0.140)
SPEED = 2 * 6000 * 2 * np.pi / 60
WEIGHTS = np.linspace(0.2, 4.0, 20)
POSITIONS = np.linspace(0.0, 1.0, 200)


def best_of(function: Callable[[], object], repeat: int = 7) -> float:
    """Smallest wall time of ``repeat`` runs [s] (after one warm-up run)."""
    function()
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    shaft = BalanceShaft(0.3, SECTION, (0.0, 0.3), (0.2,), (UNBALANCE,), SPEED)
    x = np.linspace(0, 0.3, 201)
    cases: list[tuple[str, Callable[[], object], float | None]] = [
        (
            "inline-4 sweep: 200 positions x 20 weights (EB)",
            lambda: inline4_study(
                UNBALANCE, SPEED, 0.3, SECTION, positions=POSITIONS, weights=WEIGHTS
            ),
            0.5,
        ),
        (
            "inline-4 sweep: 200 positions x 20 weights (Timoshenko)",
            lambda: inline4_study(
                UNBALANCE,
                SPEED,
                0.3,
                SECTION,
                positions=POSITIONS,
                weights=WEIGHTS,
                theory="timoshenko",
            ),
            0.5,
        ),
        (
            "inline-3 sweep: 3 rotor types x 200 positions x 20 weights",
            lambda: compare_inline3_types(2e-3, SPEED / 2, 0.3, SECTION, weights=WEIGHTS),
            None,
        ),
        (
            "single FE frequency solve (24 elements, 1 mass)",
            lambda: natural_frequencies(0.3, SECTION, [0.0, 0.3], [0.2], [0.165]),
            None,
        ),
        ("single shaft response (statics + FE)", lambda: shaft_response(shaft), None),
        (
            "statics only, 200 layouts x 201 stations",
            lambda: beam_statics(
                0.3,
                SECTION.bending_stiffness,
                [0.0, 0.3],
                POSITIONS[:, None] * 0.3,
                np.full((200, 1), 1000.0),
                x,
            ),
            None,
        ),
    ]
    rows = []
    for name, function, target in cases:
        seconds = best_of(function)
        verdict = "" if target is None else ("ok" if seconds < target else "SLOW")
        rows.append(
            (
                name,
                f"{1000 * seconds:.2f}",
                "" if target is None else f"{1000 * target:.0f}",
                verdict,
            )
        )
    widths = [max(len(r[i]) for r in rows + [("case", "ms", "target ms", "")]) for i in range(4)]
    header = ("case", "ms", "target ms", "")
    print(
        "  ".join(
            h.ljust(w) if i == 0 else h.rjust(w)
            for i, (h, w) in enumerate(zip(header, widths, strict=True))
        )
    )
    print("  ".join("-" * w for w in widths))
    for r in rows:
        print(
            "  ".join(
                c.ljust(w) if i == 0 else c.rjust(w)
                for i, (c, w) in enumerate(zip(r, widths, strict=True))
            )
        )


if __name__ == "__main__":
    main()
