"""
The balance shop for a crossplane V8
====================================

The balance shop, worked for a 90° crossplane V8 (docs/balance_shop.md): from the weighed
parts in v8_parts.csv to matched sets, bob-weights, the hole plan of a two-plane reading, the
ISO 21940-11 sign-off, and the printable shop sheet (v8_shop_sheet.html in the working
directory, or the file given as the first argument; `crankbalance shop sheet ... -o sheet.pdf`
prints it to PDF).

The same from the command line::

    crankbalance shop match examples/v8_parts.csv --engine v8-crossplane
    crankbalance shop sheet examples/v8_parts.csv --engine v8-crossplane -o sheet.html \\
        --reading "12.5 g @ 40 mm, 35 deg" --reading "8 g @ 40 mm, 200 deg" \\
        --measuring-planes "0 mm, 400 mm" --correction-planes "50 mm, 350 mm" \\
        --hole-radius "45 mm" --depth-to tip --rotor-mass "25 kg" --bearings "-20 mm, 420 mm"
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from crankbalance.output.shop_sheet import write_sheet
from crankbalance.schema.settings import ShopOptions, parse_options
from crankbalance.studies.shop import shop_study

# this script's path, also when the documentation's gallery runs it (without __file__)
PARTS = Path(sys.argv[0]).resolve().parent / "v8_parts.csv"

# the settings as a shop person types them (units in the text)
options = parse_options(
    ShopOptions,
    {
        "fraction": "50%",  # 90° V8: rotating plus half the reciprocating weight
        # the balancing machine's readings, plane 1 then plane 2 (heavy spot)
        "reading": ["12.5 g @ 40 mm, 35 deg", "8 g @ 40 mm, 200 deg"],
        "measuring_planes": "0 mm, 400 mm",
        "correction_planes": "50 mm, 350 mm",  # the front and rear counterweight faces
        "hole_radius": "45 mm",
        "hole_diameter": "8 mm",
        "max_depth": "15 mm",
        "depth_to": "tip",  # the quill scale reads the depth to the drill's tip
        "rotor_mass": "25 kg",
        "bearings": "-20 mm, 420 mm",
    },
)
study = shop_study("v8-crossplane", PARTS, options)

m = study.parts.matching
print(f"matched sets ({m.method}, {'proven optimal' if m.optimal else 'time limit'}):")
for c, ids in enumerate(m.ids):
    print(
        f"  cylinder {c + 1}: {' '.join(ids)}  reciprocating {m.reciprocating[c] * 1e3:.1f} g, "
        f"rotating {m.rotating[c] * 1e3:.1f} g"
    )
print(
    f"spread {m.reciprocating_spread * 1e3:.1f} g / {m.rotating_spread * 1e3:.1f} g, "
    f"remove {m.removed_total * 1e3:.1f} g (machining every part to the lightest: "
    f"{study.parts.machined.removed_total * 1e3:.1f} g)"
)
j = study.parts.journals  # which sets share a crankpin: the least spread of the journals
pins = range(len(j.bob_weight))
on_pin = [[c + 1 for c, t in enumerate(j.cylinder_throw) if t == pin] for pin in pins]
print(
    f"cylinders per crankpin {on_pin} ({j.status}): journals' spread {j.spread * 1e3:.2f} g, "
    f"as listed {j.as_listed_spread * 1e3:.2f} g"
)
b = study.parts.bob_weights
print("bob-weights per crankpin:", ", ".join(f"{w * 1e3:.1f} g" for w in b.bob_weight))
assert study.holes is not None
for j, holes in enumerate(study.holes.holes):
    angles = ", ".join(f"{math.degrees(a) % 360:.1f}°" for a in holes.angles)
    print(
        f"plane {j + 1}: {holes.number} holes of {holes.diameter * 1e3:g} mm at {angles}, "
        f"{holes.depth * 1e3:.1f} mm deep to the {holes.depth_to}; "
        f"residual {abs(study.holes.residual[j]) * 1e6:.2f} g·mm "
        f"(permissible {study.holes.check.tolerance[j] * 1e6:.1f} g·mm)"
    )
print("ISO 21940-11", study.holes.grade, "PASS" if study.holes.check.passed else "FAIL")
print("wrote", write_sheet(study, sys.argv[1] if len(sys.argv) > 1 else "v8_shop_sheet.html"))
