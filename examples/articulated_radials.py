"""
Articulated radials: master-and-link rods
=========================================

Master-and-link rods against the simple radial model, for the articulated presets.

For each radial preset with ``[crank_train.articulated]`` this prints

1. the free force amplitudes of orders 1-4 [N]: the simple model (every rod on the
   crankpin, the same masses), the articulated model of the preset (link pin angles equal
   to the angles between the cylinders) and the articulated model with the link pin angles
   that even out the strokes (:func:`crankbalance.physics.articulated.even_stroke_angles`);
2. every cylinder's stroke [mm], top dead centre position [mm from the crank axis] and
   lag of its top dead centre behind the plain slider-crank's [deg], for both angle sets.

The tables in docs/theory.md ("Articulated rods") are this script's output.
Run: ``python examples/articulated_radials.py``.
"""

from __future__ import annotations

import dataclasses
from dataclasses import replace

import numpy as np

from crankbalance.physics.articulated import dead_centres, even_stroke_angles
from crankbalance.physics.shaking import free_forces
from crankbalance.studies.engine import as_model

PRESETS = ("radial5-kinner", "radial7-scarab", "radial9-r985")
ORDERS = 4


def main() -> None:
    for name in PRESETS:
        model = as_model(name)
        rods, links = model.articulated_rods, model.articulation
        assert rods is not None and links is not None
        angles = even_stroke_angles(rods)
        evened = dataclasses.replace(model, articulation=replace(links, link_pin_angle=angles))
        even = evened.articulated_rods
        assert even is not None
        engines = {
            "simple": dataclasses.replace(model, articulation=None),
            "articulated": model,
            "even strokes": evened,
        }
        amplitude = {k: free_forces(m, ORDERS).force_amplitude for k, m in engines.items()}
        print(f"## {model.name} ({name}), {model.speed * 30 / np.pi:.0f} rpm")
        print()
        print("| order | simple N | articulated N | change | even strokes N |")
        print("|---|---:|---:|---:|---:|")
        for k in range(ORDERS):
            simple, art, evened = (amplitude[key][k] for key in engines)
            change = f"{100 * (art / simple - 1):+.1f} %" if simple > 1e-6 * art else "new"
            if simple <= 1e-9 and art <= 1e-9:
                change = "-"
            print(f"| {k + 1} | {simple:.1f} | {art:.1f} | {change} | {evened:.1f} |")
        print()
        print(
            "| cylinder | link pin angle deg | stroke mm | TDC mm | TDC lag deg "
            "| even-stroke angle deg | TDC mm | TDC lag deg |"
        )
        print("|---|---:|---:|---:|---:|---:|---:|---:|")
        plain, evened_dc = dead_centres(rods), dead_centres(even)
        for c in range(rods.cylinders):
            role = " (master)" if c == rods.master else ""
            print(
                f"| {c + 1}{role} | {np.degrees(rods.link_pin_angle[c]):.3f} "
                f"| {1e3 * plain.stroke[c]:.3f} | {1e3 * plain.tdc_travel[c]:.2f} "
                f"| {np.degrees(plain.tdc_lag[c]):+.3f} "
                f"| {np.degrees(even.link_pin_angle[c]):.3f} "
                f"| {1e3 * evened_dc.tdc_travel[c]:.2f} "
                f"| {np.degrees(evened_dc.tdc_lag[c]):+.3f} |"
            )
        print()


if __name__ == "__main__":
    main()
