"""
Inline-4 with eight or four counterweights
==========================================

Inline-4 with eight or four counterweights: main-bearing loads and crank bending.

An inline-4 with a flat (0-180-180-0) crank is free of first-order forces and couples
without any counterweight, yet its crank carries each half's rotating masses as a couple
that the centre bearing and the crank's bending take. Counterweights on every web (eight)
balance each throw on its own; four (webs 1, 4, 5, 8) balance each half. This example runs
the whole engine cycle of the ``inline4`` preset at 6000 rpm (gas forces from the Wiebe
model and reciprocating inertia through the rods) for both patterns, prints the loads of
each main bearing and the bending at the centre journal for both crank models, and writes
the polar load diagrams and journal bending moments of the two overlaid
(``inline4_counterweights.html`` in the working directory, or the file given as the first
argument: .html, .png or .svg). The same numbers from the command line::

    crankbalance bearings inline4
    crankbalance bearings inline4 --webs 1,0,0,1,1,0,0,1

See docs/main_bearings.md for the model, its assumptions and this case worked out.
"""

from __future__ import annotations

import sys
from pathlib import Path

from crankbalance.studies.loads import bearing_loads

PATTERNS = {"8 counterweights": None, "4 counterweights": [1, 0, 0, 1, 1, 0, 0, 1]}


def main(output: str) -> None:
    studies = {name: bearing_loads("inline4", {"webs": webs}) for name, webs in PATTERNS.items()}
    eight, four = studies.values()
    print(
        f"{eight.model.name} at {eight.cycle.speed_mean * 30 / 3.141592653589793:.0f} rpm, "
        "gas and inertia, rigid bearings\n"
    )
    for name, study in studies.items():
        cw = study.balance.counterweights
        print(f"{name}: {cw.count} x {cw.mass[0] * 1e3:.1f} g = {cw.mass.sum():.3f} kg")
    print()
    header = (
        f"{'bearing':>7} {'y mm':>7} | {'mean N, 8':>10} {'mean N, 4':>10} | "
        f"{'max N, 8':>9} {'max N, 4':>9} | {'|M| N·m, 8':>10} {'|M| N·m, 4':>10}"
    )
    for model in ("determinate", "indeterminate"):
        a, b = eight.results[model], four.results[model]
        print(f"{model} crank")
        print(header)
        for k, y in enumerate(a.bearing_position):
            print(
                f"{k + 1:>7} {y * 1e3:>7.1f} | {a.mean_load[k]:>10.0f} {b.mean_load[k]:>10.0f} | "
                f"{a.max_load[k]:>9.0f} {b.max_load[k]:>9.0f} | "
                f"{a.max_journal_moment[k]:>10.1f} {b.max_journal_moment[k]:>10.1f}"
            )
        fa, fb = a.friction, b.friction
        assert fa is not None and fb is not None
        print(
            f"Coulomb friction of the main bearings: {fa.coulomb_power.sum():.0f} W (8) and "
            f"{fb.coulomb_power.sum():.0f} W (4)\n"
        )
    centre = eight.results["indeterminate"].bearing_position.size // 2
    a, b = eight.results["indeterminate"], four.results["indeterminate"]
    print(
        f"Centre bearing (indeterminate crank): mean load {b.mean_load[centre]:.0f} N with four "
        f"counterweights against {a.mean_load[centre]:.0f} N with eight "
        f"({b.mean_load[centre] / a.mean_load[centre] - 1:+.0%}); centre-journal bending "
        f"{b.max_journal_moment[centre]:.0f} against {a.max_journal_moment[centre]:.0f} N·m."
    )
    print(
        "The determinate crank gives the same loads for both patterns: by the lever rule the "
        "centrifugal forces of each pattern put nothing on the bearings (docs/main_bearings.md)."
    )
    from crankbalance.io.files import write_atomic
    from crankbalance.output import render
    from crankbalance.output.figures.loads import bearing_loads_figure

    fig = bearing_loads_figure(list(studies.values()), labels=tuple(studies))
    suffix = Path(output).suffix.lower()
    data = render.to_html(fig) if suffix == ".html" else render.to_image(fig, suffix[1:])  # type: ignore[arg-type]
    write_atomic(output, data)
    print(f"wrote {output}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "inline4_counterweights.html")
