"""The balance shop sheet: one printable page for the bench, HTML or PDF (issue 16).

It shows the parts per cylinder (the matched sets), the spread and the material to remove
(matched, as listed, every part machined to the lightest), which sets share each journal
(crankpin) and the spread of the journals' bob-weights, the bob-weight per crankpin, and
with readings the hole plan per correction plane (a table and a drawing of the angles and
depths, :func:`crankbalance.output.figures.shop.hole_plan`) and the ISO 21940-11 sign-off.
Every number comes from :class:`crankbalance.studies.shop.ShopStudy`, which is also embedded as JSON
(``<script type="application/json" id="crankbalance-data">``). The page is built as the
report's is (:mod:`crankbalance.output.html`: style, tables, figures, the document;
:mod:`crankbalance.output.render`: PDF printing), and written atomically
(:func:`crankbalance.io.files.write_atomic`).
"""

from __future__ import annotations

import datetime as _dt
import html as _html
import os
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import InputError
from .format import json_text, text
from .html import figure_html, page, table

if TYPE_CHECKING:  # pragma: no cover
    from ..physics.shop.journals import JournalPairing
    from ..studies.shop import ShopStudy

SHEET_SCHEMA = "crankbalance.shop-sheet/2"


def _g(value: float) -> str:
    return text(value, "mass", 5)


def journals_words(pairing: JournalPairing) -> str:
    """How the sets were put on the journals, in words."""
    how = {
        "milp": "paired for the least spread of the journals' bob-weights",
        "exhaustive": "paired for the least spread of the journals' bob-weights",
        "as-listed": "as listed",
        "joint": "matched and paired at once for the least spread of the journals' bob-weights",
    }[pairing.method]
    return f"Sets {how} ({pairing.status})"


def journal_cylinders(pairing: JournalPairing, journal: int) -> str:
    """The numbers of the cylinders on a journal, ``"1, 5"``."""
    return ", ".join(str(c + 1) for c, t in enumerate(pairing.cylinder_throw) if t == journal)


def sheet_html(study: ShopStudy, static: bool = False) -> str:
    """The shop sheet of ``study`` (a ShopStudy) as one HTML document; ``static=True`` draws
    the figure as inline SVG (for printing to PDF)."""
    from .figures.shop import hole_plan

    esc = _html.escape
    p = study.parts
    m = p.matching
    out = [f"<h1>Balance shop sheet: {esc(p.engine)}</h1>"]
    out.append(
        f'<p class="meta">parts file {esc(p.parts_source)}, {p.cylinders} cylinders, '
        f"{_dt.datetime.now().isoformat(timespec='minutes')}</p>"
    )
    out.append("<h2>Parts per cylinder (matched sets)</h2>")
    out.append(f"<p>Matching: {esc(m.method)} ({esc(m.status)}).</p>")
    rows = [
        [str(c + 1), *m.ids[c], _g(m.reciprocating[c]), _g(m.rotating[c])]
        + [_g(m.remove_reciprocating[c]), _g(m.remove_rotating[c])]
        for c in range(p.cylinders)
    ]
    header = ["cylinder", *m.kinds, "reciprocating", "rotating", "remove (recip.)"]
    out.append(table([*header, "remove (rotating)"], rows))
    out.append("<h2>Material to remove</h2>")
    out.append(
        table(
            ["", "reciprocating spread", "rotating spread", "material to remove"],
            [
                [label, _g(x.reciprocating_spread), _g(x.rotating_spread), _g(x.removed_total)]
                for label, x in (("matched", m), ("as listed", p.as_listed))
            ]
            + [
                [
                    "every part machined to the lightest",
                    _g(0.0),
                    _g(0.0),
                    _g(p.machined.removed_total),
                ]
            ],
        )
    )
    pairing = p.journals
    out.append("<h2>Sets on the journals</h2>")
    out.append(
        f"<p>{esc(journals_words(pairing))}; spread of the journals' bob-weights "
        f"{_g(pairing.spread)} (as listed {_g(pairing.as_listed_spread)}).</p>"
    )
    out.append(
        table(
            ["crankpin", "cylinders (sets in the parts table)", "bob-weight"],
            [
                [str(t + 1), journal_cylinders(pairing, t), _g(pairing.bob_weight[t])]
                for t in range(len(pairing.bob_weight))
            ],
        )
    )
    b = p.bob_weights
    out.append("<h2>Bob-weights</h2>")
    out.append(
        f"<p>Rotating share plus {b.fraction:g} of the reciprocating share, clamped at the "
        f"crank radius {text(p.crank_radius, 'length')}.</p>"
    )
    out.append(
        table(
            ["crankpin", "rods", "rotating", "reciprocating", "bob-weight"],
            [
                [str(t + 1), str(b.rods_on_pin[t]), _g(b.rotating[t]), _g(b.reciprocating[t])]
                + [_g(b.bob_weight[t])]
                for t in range(len(b.bob_weight))
            ],
        )
    )
    h = study.holes
    if h is None:
        out.append("<h2>Hole plan</h2><p>No balancing-machine readings given.</p>")
    else:
        out.append("<h2>Hole plan</h2>")
        first = h.holes[0]
        how = "heavy-metal slugs" if first.method == "heavy metal" else "drilled holes"
        out.append(
            f"<p>{how.capitalize()} Ø{text(first.diameter, 'length')}, point "
            f"{text(first.point_angle, 'angle')}, {esc(first.direction)}, at "
            f"{text(first.radius, 'length')}; depths read to the {esc(first.depth_to)}.</p>"
        )
        rows, notes = [], []
        for j, holes in enumerate(h.holes):
            rows.append(
                [
                    f"{j + 1} at {text(h.plan.correction_planes[j], 'length')}",
                    text(h.plan.amount[j], "unbalance", 4),
                    text(h.plan.remove_angle[j], "angle", 4),
                    str(holes.number),
                    ", ".join(text(a, "angle", 4) for a in holes.angles) or "–",
                    text(holes.shoulder_depth, "length", 4),
                    text(holes.tip_depth, "length", 4),
                    _g(holes.hole_mass),
                    text(abs(h.residual[j]), "unbalance", 3),
                ]
            )
            if holes.note:
                notes.append(f"Plane {j + 1}: {holes.note}.")
        header = ["plane", "unbalance", "heavy spot", "holes", "angles", "depth to shoulder"]
        out.append(table([*header, "depth to tip", "mass per hole", "predicted residual"], rows))
        out += [f"<p>{esc(note)}</p>" for note in notes]
        out.append(figure_html("holes", "Hole plan to scale", hole_plan(h), static, True))
        c = h.check
        out.append("<h2>ISO 21940-11 sign-off</h2>")
        out.append(
            table(
                ["plane", "predicted residual", "permissible", "verdict"],
                [
                    [str(j + 1), text(c.residual[j], "unbalance", 3)]
                    + [text(c.tolerance[j], "unbalance", 4), "pass" if v.passed else "FAIL"]
                    for j, v in enumerate(c.verdicts)
                ],
            )
        )
        verdict = "PASS" if c.passed else "FAIL"
        out.append(
            f"<p><b>ISO 21940-11 {esc(h.grade)}, {text(h.rotor_mass, 'mass_kg')}, "
            f"{text(h.speed, 'speed')}: {verdict}</b>. Checked by: ____________ "
            "Date: ____________</p>"
        )
    from ..studies.shop import shop_json

    data = json_text({"schema": SHEET_SCHEMA, "study": shop_json(study)}, indent=None)
    return page(f"{p.engine}: balance shop sheet", out, data)


def write_sheet(
    study: ShopStudy, path: str | os.PathLike[str], chromium: str | None = None
) -> Path:
    """Write the shop sheet of ``study`` to ``path`` (``.html``/``.htm`` or ``.pdf``),
    atomically."""
    from ..io.files import write_atomic

    target = Path(path)
    suffix = target.suffix.lower()
    if suffix not in (".html", ".htm", ".pdf"):
        raise InputError("output", str(path), "a file name ending in .html or .pdf")
    if suffix == ".pdf":
        from .render import find_chromium, html_to_pdf

        exe = find_chromium(chromium)
        data: str | bytes = html_to_pdf(sheet_html(study, static=True), exe)
    else:
        data = sheet_html(study)
    write_atomic(target, data)
    return target
