"""Engine balancing reports: one self-contained HTML file (interactive figures, plotly.js
inlined, no network) or a PDF (the same page with static SVG figures, printed by a headless
Chromium).

This module owns the report's content: what it shows and in which order. The page's
building blocks (style, tables, figures with captions, the document around them) are
:mod:`crankbalance.output.html`'s, shared with the shop sheet; the figures come from
:mod:`crankbalance.output.figures` (:mod:`~crankbalance.output.figures.engine`,
:mod:`~crankbalance.output.figures.balancing`, :mod:`~crankbalance.output.figures.crank3d`);
turning them into SVG or HTML and printing the page to PDF is done by
:mod:`crankbalance.output.render`.

Contents: engine data, mass split, free forces and moments by order, rotating masses,
balancing masses (counterweights, balance shafts), residuals before/after balancing, the
powertrain on its mounts when the engine file has a ``[powertrain]`` (the mount study under
the forces the balancing leaves, :func:`crankbalance.studies.mounts.compare`), the
figures of :mod:`crankbalance.output.figures`, and the settings used (solver options and the engine
file itself). Every number comes from :func:`crankbalance.studies.engine.analyze` and
:func:`crankbalance.studies.engine.balance_engine`; both results are also embedded as JSON
(``<script type="application/json" id="crankbalance-data">``) so a reader or a test can
check the page against the API.

Public functions
----------------
- ``build_report(engine, orders=8, **overrides) -> Report``
- ``report_html(report, static=False) -> str``
- ``report_bytes(report, fmt, chromium=None) -> bytes`` (``"html"`` or ``"pdf"``)
- ``write_report(engine, path, orders=8, chromium=None, **overrides) -> Path``
  (``.html`` or ``.pdf`` by suffix, written atomically)

The 3-D crank is a WebGL scene that a browser does not print: the interactive page shows it
on screen only and prints the same crank drawn flat in three views
(:func:`crankbalance.output.figures.crank_flat.crank_views`); the PDF has both as images.
"""

from __future__ import annotations

import datetime as _dt
import html as _html
import json
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import InputError
from ..records import record
from ..results import to_jsonable
from .format import angle, convert, moment_point
from .html import figure_html, fmt, page, table

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

    from ..physics.model import EngineModel
    from ..schema.engine import EngineSpec
    from ..studies.engine import Analysis, BalanceStudy
    from ..studies.mounts import MountsResult
    from .figures.common import Quantity

REPORT_SCHEMA = "crankbalance.report/4"
#: the report's figures that are WebGL scenes: on screen only in the interactive page (a
#: browser does not print them; the flat views of :mod:`.figures.crank_flat` print instead)
SCREEN_ONLY_FIGURES = frozenset({"crank"})
#: the file formats of a report (:func:`report_bytes`), by file suffix
REPORT_FORMATS = ("html", "pdf")


@record
class Report:
    """What a report shows: the analysis and balancing results and the settings."""

    analysis: Analysis
    study: BalanceStudy
    engine_file: str  # TOML text of the engine, as used
    settings: dict[str, Any]
    created: str
    mounts: MountsResult | None = None  # the engine file has a [powertrain]

    def data(self) -> dict[str, Any]:
        """The numbers of the report (the API's JSON contracts) and its settings; with a
        ``[powertrain]`` the mount study of the balanced engine (``mounts``)."""
        out = {
            "schema": REPORT_SCHEMA,
            "created": self.created,
            "analysis": self.analysis.to_dict(),
            "balance": self.study.to_dict(),
            "settings": self.settings,
        }
        if self.mounts is not None:
            out["mounts"] = self.mounts.to_dict()
        return out


def build_report(
    engine: str | os.PathLike[str] | EngineSpec, orders: int = 8, **overrides: Any
) -> Report:
    """Analyse and balance ``engine`` (preset name, engine file or EngineSpec).

    ``overrides`` go to :func:`~crankbalance.studies.engine.balance_engine` (``angle``,
    ``balance_factor``, ``method``, ``scope``, ``cg_radius``, ``webs``, ``primary``,
    ``secondary``).
    """
    import dataclasses

    from .. import __version__
    from ..io.engine_file import engine_to_toml, load_engine
    from ..schema.engine import EngineSpec
    from ..studies.engine import analyze, balance_engine, balance_options

    spec = engine if isinstance(engine, EngineSpec) else load_engine(engine)
    # the balancing contract always reports orders 1 and 2 (balance_engine needs both)
    study = balance_engine(spec, max(orders, 2), **overrides)
    analysis = analyze(study.model, orders)
    cw, primary, secondary = balance_options(spec)
    extra = dict(overrides)
    primary = extra.pop("primary", primary)
    secondary = extra.pop("secondary", secondary)
    if extra:
        cw = dataclasses.replace(cw, **extra)

    def options(value: Any) -> Any:
        if value is None:
            return None
        out = {}
        for key, item in dataclasses.asdict(value).items():
            out[key] = list(item) if isinstance(item, tuple) else item
        return out

    settings = {
        "crankbalance_version": __version__,
        "orders": orders,
        "kinematics": study.model.kinematics,
        "counterweights": options(cw),
        "primary_shafts": options(primary),
        "secondary_shafts": options(secondary),
        "overrides": {
            k: (options(v) if dataclasses.is_dataclass(v) else v) for k, v in overrides.items()
        },
        "units": "SI (m, kg, rad) in the options; angles in the tables in degrees",
    }
    created = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    mounts = None
    if spec.powertrain is not None:
        from ..schema.settings import MountsOptions
        from ..studies.mounts import Choice, compare

        # the mount study's defaults, under the forces this balancing leaves
        choice = Choice("as balanced", cw, primary, secondary)
        mounts = compare(spec, MountsOptions.parse({}), [choice])[0][1]
    return Report(analysis, study, engine_to_toml(spec), settings, created, mounts)


# --------------------------------------------------------------------------- formatting
def _angle(value: float | None) -> float | None:
    """An angle in degrees in the one range of the output vocabulary, [0, 360)."""
    if value is None:
        return None
    return angle(0.0 if abs(value) < 1e-9 else float(value))


def maker_order(model: EngineModel) -> str:
    """The firing order in the maker's numbering, as the report appends it to the firing
    order: `` (maker's numbering: 1-6-2-4-3-5)`` when the engine file used a maker's
    numbering and gave the firing order, else ``""``."""
    if model.maker_number is None or not model.firing_order_given:
        return ""
    return (
        " (maker's numbering: "
        + "-".join(str(model.maker_number[c - 1]) for c in model.firing_order)
        + ")"
    )


def _distinct(values: list[float], scale: float = 1.0, digits: int = 5) -> str:
    shown = [fmt(v * scale, digits) for v in values]
    return shown[0] if len(set(shown)) == 1 else ", ".join(shown)


# --------------------------------------------------------------------------- figures
def report_figures(report: Report) -> list[tuple[str, str, go.Figure]]:
    """(id, caption, figure) of every figure in the report."""
    from .figures.balancing import residuals_bar
    from .figures.crank3d import crank_3d
    from .figures.crank_flat import crank_views
    from .figures.engine import curves_figure, orders_bar, polar_figure

    a, s = report.analysis, report.study
    figs: list[tuple[str, str, go.Figure]] = [
        (
            "orders",
            "Free force and moment amplitudes by order (forward and backward phasors "
            "stacked; 'rot' is the bare crank's rotating masses).",
            orders_bar(a),
        ),
        (
            "curves-force",
            "Free forces versus crank angle: reciprocating total, orders, and the "
            "whole engine before and after balancing.",
            curves_figure(a, s, "force"),
        ),
        (
            "curves-moment",
            f"Free moments about {moment_point(a.model.moment_point)} versus crank angle.",
            curves_figure(a, s, "moment"),
        ),
    ]
    amp = a.forces.force_amplitude + a.forces.moment_amplitude
    for n in (int(n) for n in a.forces.orders if n <= 2):
        k = a.forces.order(n)
        if amp[k] > 0:
            quantity: Quantity = (
                "force"
                if a.forces.force_amplitude[k] >= a.forces.moment_amplitude[k] * 1e-12
                and a.forces.force_amplitude[k] > 0
                else "moment"
            )
            figs.append(
                (
                    f"polar-{n}-{quantity}",
                    f"Rotating-vector diagram of order {n} ({quantity}).",
                    polar_figure(a, n, quantity),
                )
            )
    figs += [
        (
            "crank",
            "The crankshaft at crank angle 0 with its counterweights and balance shafts "
            "(shafts beside the crank at a schematic distance).",
            crank_3d(s.model, s),
        ),
        (
            "crank-views",
            "The same crankshaft drawn flat, seen from the side, from above and along the "
            "crank axis (equal scales; these views print where the 3-D view cannot).",
            crank_views(s.model, s),
        ),
        (
            "residuals",
            "Amplitude of every component before and after balancing (time-domain "
            "check of the solver).",
            residuals_bar(s),
        ),
    ]
    if report.mounts is not None:
        from .figures.mounts import mounts_figure

        figs.append(
            (
                "mounts",
                "The powertrain on its mounts, under the forces the balancing leaves: the "
                "Campbell diagram of its six rigid-body modes and the force each mount "
                "transmits over speed, by order.",
                mounts_figure(report.mounts),
            )
        )
    return figs


# --------------------------------------------------------------------------- HTML
def report_html(report: Report, static: bool = False, figures: bool = True) -> str:
    """The report as one HTML document.

    ``static=True`` draws the figures as inline SVG images (for printing to PDF); otherwise
    they are interactive plotly figures with plotly.js inlined once (no network needed).
    """
    a = report.analysis.to_dict()
    b = report.study.to_dict()
    e = a["engine"]
    esc = _html.escape
    parts: list[str] = []
    parts.append(f"<h1>{esc(e['name'])}</h1>")
    parts.append(
        f'<p class="meta">crankbalance {esc(report.settings["crankbalance_version"])}'
        f" balancing report, {esc(report.created)}</p>"
    )

    # engine data
    parts.append("<h2>Engine</h2>")
    rows = [
        ["cylinders", e["cylinders"]],
        ["throws", e["throws"]],
        ["speed [rpm]", convert(e["speed_rad_s"], "speed")],
        ["crank radius [mm]", e["crank_radius_m"] * 1e3],
        ["rod length [mm]", e["rod_length_m"] * 1e3],
        ["rod ratio r/l", e["rod_ratio"]],
        ["offset per cylinder [mm]", _distinct(list(e["cylinder_offset_m"]), 1e3)],
        ["rod position on its pin [mm]", _distinct(list(e["cylinder_axial_m"]), 1e3)],
        ["kinematics", e["kinematics"]],
        [
            "firing order",
            "-".join(str(c) for c in report.study.model.firing_order)
            + ("" if report.study.model.firing_order_given else " (not given: cylinder order)")
            + maker_order(report.study.model),
        ],
    ]
    parts.append(table(["quantity", "value"], rows))
    throw_rows = [
        [
            t + 1,
            _angle(e["throw_angle_deg"][t]),
            e["throw_position_m"][t] * 1e3,
            a["masses"]["rotating_kg"][t],
        ]
        for t in range(e["throws"])
    ]
    parts.append("<h3>Throws</h3>")
    parts.append(table(["throw", "angle [°]", "position y [mm]", "rotating mass [kg]"], throw_rows))
    cyl_rows = [
        [
            c + 1,
            e["cylinder_throw"][c],
            _angle(e["cylinder_bank_deg"][c]),
            a["masses"]["reciprocating_kg"][c],
        ]
        for c in range(e["cylinders"])
    ]
    parts.append("<h3>Cylinders</h3>")
    parts.append(
        table(["cylinder", "throw", "bank angle [°]", "reciprocating mass [kg]"], cyl_rows)
    )

    # mass split
    parts.append("<h2>Mass split</h2>")
    m = a["masses"]
    parts.append(
        f"<p>Reciprocating mass per cylinder: {_distinct(m['reciprocating_kg'])} kg; "
        f"rotating mass per throw (at the crank radius, big ends included): "
        f"{_distinct(m['rotating_kg'])} kg.</p>"
    )
    if m["conrods"]:
        rods = m["conrods"]
        parts.append(
            table(
                [
                    "conrod",
                    "mass [kg]",
                    "rotating [kg]",
                    "reciprocating [kg]",
                    "CG from big end [mm]",
                    "two-mass inertia [kg·m²]",
                    "inertia error [kg·m²]",
                ],
                [
                    [
                        r["cylinder"],
                        r["mass_kg"],
                        r["rotating_kg"],
                        r["reciprocating_kg"],
                        r["cg_from_big_end_m"] * 1e3,
                        r["inertia_two_mass_kg_m2"],
                        r["inertia_error_kg_m2"],
                    ]
                    for r in rods
                ],
            )
        )

    # free forces and moments
    parts.append("<h2>Free forces and moments</h2>")
    parts.append(
        "<p>Reciprocating masses, by order; amplitude = largest magnitude over a "
        "revolution = |forward| + |backward|; moments about "
        f"{moment_point(report.study.model.moment_point)}; the roll moment about the axis "
        "through it along the crank (y); phases at crank angle 0 from +z toward +x.</p>"
    )
    rows = [
        [
            f["order"],
            f["amplitude_N"],
            f["forward_N"],
            f["backward_N"],
            mo["amplitude_Nm"],
            mo["forward_Nm"],
            mo["backward_Nm"],
            y["amplitude_Nm"],
        ]
        for f, mo, y in zip(a["free_forces"], a["free_moments"], a["roll_moments"], strict=True)
    ]
    parts.append(
        table(
            [
                "order",
                "force [N]",
                "forward [N]",
                "backward [N]",
                "moment [N·m]",
                "forward [N·m]",
                "backward [N·m]",
                "roll [N·m]",
            ],
            rows,
            "free",
        )
    )
    rot = a["rotating"]
    parts.append(
        f"<p>Rotating masses of the bare crank (no counterweights): force "
        f"{fmt(rot['force_N'])} N, moment {fmt(rot['moment_Nm'])} N·m.</p>"
    )

    # balancing masses
    parts.append("<h2>Balancing masses</h2>")
    for key, title in (
        ("counterweight", "Crank counterweights"),
        ("extra_counterweights", "Extra counterweights (Eq. 17)"),
    ):
        cw = b[key]
        if cw is None:
            continue
        parts.append(f"<h3>{title}</h3>")
        parts.append(
            f"<p>{cw['count']} counterweights, method {esc(cw['method'])}, scope "
            f"{esc(cw['scope'])}, CG radius {fmt(cw['cg_radius_m'] * 1e3)} mm"
            + ("" if cw["angle_deg"] is None else f", angle {fmt(_angle(cw['angle_deg']))}°")
            + f"; largest mass {fmt(cw['mass_kg'])} kg, total "
            f"{fmt(cw['total_mass_kg'])} kg.</p>"
        )
        parts.append(
            table(
                ["web", "throw", "position y [mm]", "mass [kg]", "direction [°]"],
                [
                    [
                        w["web"],
                        w["throw"],
                        w["position_m"] * 1e3,
                        w["mass_kg"],
                        _angle(w["direction_deg"]),
                    ]
                    for w in cw["webs"]
                ],
            )
        )
        if cw["note"]:
            parts.append(f'<p class="note">{esc(cw["note"])}</p>')
    for key, title in (
        ("primary_shafts", "Primary balance shafts (crank speed)"),
        ("secondary_shafts", "Secondary balance shafts (twice crank speed)"),
    ):
        group = b[key]
        if group is None:
            parts.append(f"<h3>{title}</h3><p>none</p>")
            continue
        parts.append(f"<h3>{title}</h3>")
        parts.append(
            f"<p>Arrangement {esc(group['arrangement'])}, distance between the outer "
            f"masses {fmt(group['length_m'] * 1e3)} mm; largest mass "
            f"{fmt(group['mass_kg'])} kg.</p>"
        )
        rows = [
            [
                s["rotation"],
                s["speed_ratio"],
                s["cg_radius_m"] * 1e3,
                x["position_m"] * 1e3,
                x["mass_kg"],
                _angle(x["phase_deg"]),
            ]
            for s in group["shafts"]
            for x in s["masses"]
        ]
        if rows:
            parts.append(
                table(
                    [
                        "shaft",
                        "speed ratio",
                        "CG radius [mm]",
                        "position y [mm]",
                        "mass [kg]",
                        "phase [°]",
                    ],
                    rows,
                )
            )
        for s in group["shafts"]:
            if s["note"]:
                parts.append(f'<p class="note">{esc(s["rotation"])}: {esc(s["note"])}</p>')

    # residuals
    parts.append("<h2>Residuals</h2>")
    parts.append(
        "<p>Amplitude of every component before and after balancing, every balancing "
        "mass added back to the free forces (targeted: cancelled by balance shafts).</p>"
    )
    from ..results import round_off

    tiny_f, tiny_m = round_off(report.study.model)

    def clean(value: float, tiny: float) -> float:
        return 0.0 if abs(value) < tiny else value

    parts.append(
        table(
            [
                "component",
                "targeted",
                "force before [N]",
                "force after [N]",
                "moment before [N·m]",
                "moment after [N·m]",
            ],
            [
                [
                    c["component"],
                    c["targeted"],
                    clean(c["force_before_N"], tiny_f),
                    clean(c["force_after_N"], tiny_f),
                    clean(c["moment_before_Nm"], tiny_m),
                    clean(c["moment_after_Nm"], tiny_m),
                ]
                for c in b["components"]
            ],
            "residuals",
        )
    )
    parts.append(
        f"<p>Values below round-off ({fmt(tiny_f)} N, {fmt(tiny_m)} N·m) are shown as 0.</p>"
    )
    if b["unbalanced"]:
        parts.append("<p>Left unbalanced: " + "; ".join(esc(u) for u in b["unbalanced"]) + ".</p>")
    for note in b["notes"]:
        parts.append(f'<p class="note">{esc(note)}</p>')

    if report.mounts is not None:
        parts += _mounts_section(report.mounts)

    # figures
    if figures:
        parts.append("<h2>Figures</h2>")
        for k, (fig_id, caption, fig) in enumerate(report_figures(report)):
            screen_only = fig_id in SCREEN_ONLY_FIGURES
            parts.append(figure_html(fig_id, caption, fig, static, k == 0, screen_only))

    # settings
    parts.append("<h2>Settings used</h2>")
    parts.append(
        "<pre>"
        + esc(json.dumps(to_jsonable(report.settings), indent=2, default=_json_default))
        + "</pre>"
    )
    parts.append("<h3>Engine file</h3>")
    parts.append("<pre>" + esc(report.engine_file) + "</pre>")

    data = json.dumps(to_jsonable(report.data()), default=_json_default)
    return page(f"{e['name']}: balancing report", parts, data)


def _mounts_section(result: MountsResult) -> list[str]:
    """The powertrain on its mounts (docs/mounts.md) under the forces the balancing leaves:
    the body, the six modes with their kinetic energy, the torque-roll axis, the crossings
    and the largest mount force of each order."""
    d = result.to_dict()
    pt, speed = d["powertrain"], d["sweep"]["speed_rpm"]
    out = ["<h2>The powertrain on its mounts</h2>"]
    out.append(
        f"<p>The engine file's [powertrain]: {fmt(pt['mass_kg'])} kg on {len(d['mounts'])} "
        f"mounts, driven by the free forces and moments of orders 1 to {len(d['orders'])} "
        "that the balancing above leaves, from "
        f"{fmt(speed[0], 4)} to {fmt(speed[-1], 4)} rpm (crankbalance mounts, "
        "docs/mounts.md).</p>"
    )
    out.append(
        table(
            [
                "mode",
                "frequency [Hz]",
                "x [%]",
                "y [%]",
                "z [%]",
                "roll [%]",
                "pitch [%]",
                "yaw [%]",
            ],
            [
                [m["mode"], round(m["frequency_Hz"], 2)]
                + [round(v, 1) + 0.0 for v in m["energy_percent"].values()]  # -0.0 as 0.0
                for m in d["modes"]
            ],
            "mount-modes",
        )
    )
    out.append(
        f"<p>The roll mode (mode {d['roll_mode']}) turns "
        f"{fmt(d['roll_mode_angle_to_torque_roll_axis_deg'], 3)}° from the torque-roll axis. "
        + (
            "Orders crossing a mode in the speed range: "
            + ", ".join(
                f"order {c['order']} × mode {c['mode']} at {fmt(c['speed_rpm'], 4)} rpm"
                for c in d["crossings"]
            )
            if d["crossings"]
            else "No order crosses a mode in the speed range"
        )
        + ".</p>"
    )
    out.append(
        table(
            ["order", "largest mount force [N]", "mount", "at [rpm]"],
            [
                [
                    o["order"],
                    o["largest"]["force_N"],
                    o["largest"]["mount"],
                    o["largest"]["speed_rpm"],
                ]
                for o in d["orders"]
            ],
            "mount-forces",
        )
    )
    return out


def _json_default(value: Any) -> Any:
    """Settings values JSON does not know (paths, enums) as their text."""
    return str(value)


# --------------------------------------------------------------------------- files
def write_report(
    engine: str | os.PathLike[str] | EngineSpec,
    path: str | os.PathLike[str],
    orders: int = 8,
    chromium: str | None = None,
    **overrides: Any,
) -> Path:
    """Write the report of ``engine`` to ``path`` (``.html``/``.htm`` or ``.pdf``),
    atomically (:class:`crankbalance.io.files.WriteError` when it cannot be written)."""
    from ..io.files import write_atomic

    target = Path(path)
    suffix = target.suffix.lower()
    if suffix not in (".html", ".htm", ".pdf"):
        raise InputError("output", str(path), "a file name ending in .html or .pdf")
    report = build_report(engine, orders, **overrides)
    write_atomic(target, report_bytes(report, "pdf" if suffix == ".pdf" else "html", chromium))
    return target


def report_bytes(report: Report, fmt: str, chromium: str | None = None) -> bytes:
    """The report as a file's bytes: ``fmt`` ``"html"`` (the interactive page, UTF-8) or
    ``"pdf"`` (the page with static SVG figures, printed by a headless Chromium:
    :func:`crankbalance.output.render.html_to_pdf`); the command line's ``report`` and the
    web's download both use it."""
    if fmt not in REPORT_FORMATS:
        raise InputError("format", fmt, "'html' or 'pdf'")
    if fmt == "html":
        return report_html(report).encode("utf-8")
    from .render import find_chromium, html_to_pdf

    exe = find_chromium(chromium)  # fail before the figures are drawn
    return html_to_pdf(report_html(report, static=True), exe)
