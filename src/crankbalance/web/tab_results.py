"""The Results tab: balancing masses, free forces and moments by order, the figures of the
analysis (orders, residuals, curves, polar diagram) and the data downloads."""

from __future__ import annotations

from typing import Any

import numpy as np
from nicegui import ui

from ..errors import InputError
from ..output.figures.balancing import residuals_bar
from ..output.figures.common import Quantity, roundoff_levels
from ..output.figures.engine import curves_figure, leading_quantity, orders_bar, polar_figure
from ..output.format import text
from .form import label_of
from .widgets import FigureCard, Tab, button_row, fmt_g


def order_rows(c: Any) -> list[dict[str, Any]]:
    """The rows of the orders table (and of the orders CSV) of the computed engine ``c``."""
    d = c.analysis.to_dict()
    rows = []
    for f, m in zip(d["free_forces"], d["free_moments"], strict=True):
        rows.append(
            {
                "order": f["order"],
                "force": fmt_g(f["amplitude_N"]),
                "force_fwd": fmt_g(f["forward_N"]),
                "force_bwd": fmt_g(f["backward_N"]),
                "moment": fmt_g(m["amplitude_Nm"]),
                "moment_fwd": fmt_g(m["forward_Nm"]),
                "moment_bwd": fmt_g(m["backward_Nm"]),
            }
        )
    return rows


def leading_component(analysis: Any) -> tuple[Quantity, str]:
    """The quantity and order the curves and polar diagram open on: the free force or
    moment of largest amplitude, a moment M counted as the force M / L with L the crank's
    length (the ratio of the round-off levels of :func:`roundoff_levels`), so that
    a crossplane V8 opens on its first-order rocking couple, not on its small fourth-order
    force. The bare crank's rotating masses (``"rotating"``) when every order is zero,
    order 1 of the leading quantity when that is zero too."""
    f = analysis.forces
    tf, tm = roundoff_levels(analysis.model, 1e-12)
    forces = np.asarray(f.force_amplitude, dtype=float) / tf
    moments = np.asarray(f.moment_amplitude, dtype=float) / tm
    if max(forces.max(initial=0.0), moments.max(initial=0.0)) >= 1.0:
        if forces.max(initial=0.0) >= moments.max(initial=0.0):
            return "force", str(int(f.orders[int(np.argmax(forces))]))
        return "moment", str(int(f.orders[int(np.argmax(moments))]))
    if abs(f.rotating_force) >= tf or abs(f.rotating_couple) >= tm:
        return (
            "force" if abs(f.rotating_force) / tf >= abs(f.rotating_couple) / tm else "moment"
        ), "rotating"
    return leading_quantity(analysis), "1"


#: the components the summary card lists (the largest first); smaller ones are counted
SUMMARY_ROWS = 4


def _cure(order: int, quantity: str, forward: bool, backward: bool) -> str:
    """What cancels a free ``quantity`` of ``order`` that has a forward (co-rotating) and/or
    a backward (counter-rotating) part: crank counterweights take a first-order forward
    part; a backward one, and any of order n >= 2, needs balance shafts at n times crank
    speed, co-rotating for forward and counter-rotating for backward; a moment needs a pair
    (two masses in opposition, a couple)."""
    moment = quantity == "moment"
    one = "a shaft pair (masses in opposition)" if moment else "a balance shaft"
    speed = f"at {order}× crank speed"
    parts = []
    if forward:
        parts.append(
            ("crank counterweights in opposition (a couple)" if moment else "crank counterweights")
            if order == 1
            else f"{one} {speed}, co-rotating"
        )
    if backward:
        parts.append(f"{one} {speed}, counter-rotating")
    if len(parts) == 2 and order == 1:
        return f"{parts[0]} for the forward part; {parts[1]} for the backward part"
    if order >= 2 and forward and backward:
        return (
            f"two shaft pairs {speed} (one co-rotating, one counter-rotating)"
            if moment
            else f"two balance shafts {speed}, a counter-rotating pair (one co-rotating, one "
            "counter-rotating)"
        )
    return "; ".join(parts)


def summary_lines(c: Any) -> list[str]:
    """The summary card of the computed engine ``c``: its largest free forces and moments
    by order (before balancing), forward/backward, and what would cancel each, from the
    analysis already computed. A moment M is ranked as the force M / L (L the crank's
    length, as :func:`leading_component`); values below round-off count as zero."""
    analysis = c.analysis
    d = analysis.to_dict()
    tf, tm = roundoff_levels(analysis.model)
    found: list[tuple[float, str]] = []
    for f, m in zip(d["free_forces"], d["free_moments"], strict=True):
        for row, quantity, unit, tiny, key in (
            (f, "force", "N", tf, "N"),
            (m, "moment", "N·m", tm, "Nm"),
        ):
            fwd, bwd = float(row[f"forward_{key}"]), float(row[f"backward_{key}"])
            fwd, bwd = (fwd if fwd >= tiny else 0.0), (bwd if bwd >= tiny else 0.0)
            if fwd == 0 and bwd == 0:
                continue
            amplitude = float(row[f"amplitude_{key}"])
            split = (
                "forward"
                if bwd == 0
                else "backward"
                if fwd == 0
                else f"forward {fmt_g(fwd)} {unit}, backward {fmt_g(bwd)} {unit}"
            )
            found.append(
                (
                    amplitude / tiny,
                    f"**Order {row['order']} {quantity} {fmt_g(amplitude)} {unit}** ({split})"
                    f" → {_cure(int(row['order']), quantity, fwd > 0, bwd > 0)}",
                )
            )
    found.sort(key=lambda item: -item[0])
    lines = [text for _, text in found[:SUMMARY_ROWS]]
    if not lines:
        lines.append("**No free force or moment** of the reciprocating masses up to this order.")
    elif len(found) > SUMMARY_ROWS:
        lines.append(f"_and {len(found) - SUMMARY_ROWS} smaller components (see the table)_")
    rotating = d["rotating"]
    force, couple = float(rotating["force_N"]), float(rotating["moment_Nm"])
    if force >= tf or couple >= tm:
        lines.append(
            f"**Rotating masses** of the throws: force {fmt_g(force)} N, couple "
            f"{fmt_g(couple)} N·m (first order, forward) → crank counterweights"
        )
    lines.append(
        "_Forward turns with the crank, backward against it. Crank counterweights cancel "
        "only first-order forward components; a backward one, and any of order n ≥ 2, needs "
        "balance shafts at n× crank speed (co-rotating for forward, counter-rotating for "
        "backward); a moment needs a pair in opposition._"
    )
    return lines


#: the columns of the balancing card's table: one row per crank counterweight and per mass
#: of each balance shaft (:func:`balance_rows`)
BALANCE_COLUMNS = [
    {"name": k, "label": label, "field": k, "align": "left" if k == "part" else "right"}
    for k, label in (
        ("part", "Part"),
        ("position", "Position"),
        ("mass", "Mass"),
        ("radius", "CG radius"),
        ("angle", "Angle / phase"),
    )
]


def _mass(kg: float) -> str:
    """A mass [kg] as shown: grams, 5 significant digits."""
    return text(kg, "mass", 5)


def none_needed(b: dict[str, Any], key: str = "counterweight") -> str | None:
    """Why the crank needs no counterweights, when the balancing put none on it (``key``'s
    webs all of mass 0: a crank balanced as a whole, as an inline-4), else None: the
    balancing's own note ("no counterweights: ...") up to its first ";", else the
    counterweights' note."""
    cw = b.get(key)
    if not cw or not cw.get("webs") or any(web["mass_kg"] for web in cw["webs"]):
        return None
    for note in b.get("notes") or []:
        if note.startswith("no counterweights: "):
            return note.removeprefix("no counterweights: ").split(";")[0]
    return str(cw.get("note") or "the balancing put no mass on them")


def balance_rows(b: dict[str, Any]) -> list[dict[str, Any]]:
    """The balancing card's rows of a balance result (``BalanceStudy.to_dict``): each crank
    counterweight (its web, throw, position along the crank, mass, CG radius, direction)
    and each mass of each balance shaft (its shaft's rotation and speed, position, mass,
    CG radius, phase); angles at crank angle 0, degrees from the first cylinder's pin.
    Counterweights of mass 0 (:func:`none_needed`) are one row "none needed"."""
    rows: list[dict[str, Any]] = []
    for key, label in (("counterweight", "Counterweight"), ("extra_counterweights", "Extra")):
        cw = b.get(key)
        if not cw:
            continue
        if none_needed(b, key) is not None:
            blank = dict.fromkeys(("position", "radius", "angle"), "")
            rows.append({"part": f"{label}s", "mass": "none needed", **blank})
            continue
        for web in cw.get("webs", []):
            rows.append(
                {
                    "part": f"{label} web {web['web']} (throw {web['throw']})",
                    "position": text(web["position_m"], "length"),
                    "mass": _mass(web["mass_kg"]),
                    "radius": text(cw["cg_radius_m"], "length"),
                    "angle": text(web["direction_deg"], "angle_deg", 5),
                }
            )
    for key, label in (("primary_shafts", "Primary"), ("secondary_shafts", "Secondary")):
        group = b.get(key)
        if not group:
            continue
        for k, shaft in enumerate(group["shafts"], start=1):
            name = f"{label} shaft {k} ({shaft['rotation']}, {abs(shaft['speed_ratio'])}×)"
            for mass in shaft["masses"]:
                rows.append(
                    {
                        "part": name,
                        "position": text(mass["position_m"], "length"),
                        "mass": _mass(mass["mass_kg"]),
                        "radius": text(shaft["cg_radius_m"], "length"),
                        "angle": f"phase {text(mass['phase_deg'], 'angle_deg', 5)}",
                    }
                )
    return [{**row, "key": k} for k, row in enumerate(rows)]


def balance_lines(b: dict[str, Any]) -> list[str]:
    """The lines above the balancing card's table: what balances the engine at which
    speed, how many parts of each kind, the first- and second-order residuals."""
    speed = float(b["engine"]["speed_rad_s"])
    lines = [
        f"Balanced for **{text(speed, 'speed', 5)}** (the masses hold at every speed; the "
        "forces left scale with its square)"
    ]
    cw = b["counterweight"]
    reason = none_needed(b)
    if reason is not None:
        lines.append(f"**Crank counterweights:** none needed ({reason})")
    elif cw and cw.get("webs"):
        lines.append(
            f"**Crank counterweights:** {len(cw['webs'])}, "
            f"{_mass(cw['total_mass_kg'])} in all ({cw['method']})"
        )
    else:
        lines.append("**Crank counterweights:** none")
    for key, label in (("primary_shafts", "Primary"), ("secondary_shafts", "Secondary")):
        group = b[key]
        if group:
            lines.append(
                f"**{label} balance shafts:** {len(group['shafts'])} ({group['arrangement']})"
            )
        else:
            lines.append(f"**{label} balance shafts:** none")
    r = b["residual"]
    lines.append(
        f"Residual primary force {text(r['order1_force_N'], 'force')}, moment "
        f"{text(r['order1_moment_Nm'], 'moment')}; secondary force "
        f"{text(r['order2_force_N'], 'force')}, moment {text(r['order2_moment_Nm'], 'moment')}"
    )
    return lines


def left_lines(b: dict[str, Any]) -> list[str]:
    """ "What is left" after the balancing (``remaining`` of the balance result): each free
    component that stays, and what would remove it; then the balancing's notes."""
    lines = ["**What is left**", ""]  # a blank line: Markdown starts the list after it
    remaining = b.get("remaining") or []
    for item in remaining:
        lines.append(f"- {item['text']} → {item['next_step']}")
    if not remaining:
        lines.append("- nothing: no free force or moment is left up to this order")
    for note in b["notes"]:  # each its own paragraph, not the last item's continuation
        lines += ["", f"_{note}_"]
    return lines


class ResultsTab(Tab):
    name = "results"
    curves: FigureCard
    polar: FigureCard

    def __init__(self, page: Any) -> None:
        super().__init__(page)
        #: open the selectors on the leading component at the next computed engine (a new
        #: project); a choice of the user is kept while the engine is edited
        self.follow = True
        self.quiet = False

    def build(self) -> None:
        page = self.page
        with ui.card().classes("w-full").mark("summary-card"):
            ui.label("What is unbalanced and what would cancel it").classes("text-subtitle1")
            self.summary = ui.markdown("").props("data-testid=summary").mark("summary")
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card().classes("min-w-[340px]"):
                ui.label("Balancing masses").classes("text-subtitle1")
                self.balance_summary = ui.markdown("").mark("balance-summary")
                self.balance_table = (
                    ui.table(columns=BALANCE_COLUMNS, rows=[], row_key="part")
                    .props("dense flat wrap-cells")
                    .classes("w-full")
                    .props("data-testid=balance-table")
                    .mark("balance-table")
                )
                self.balance_left = (
                    ui.markdown("").props("data-testid=balance-left").mark("balance-left")
                )
                with button_row():
                    ui.button(
                        "Analysis JSON", on_click=lambda: page.download_data("analysis")
                    ).props("outline dense").mark("download-analysis")
                    ui.button("Balance JSON", on_click=lambda: page.download_data("balance")).props(
                        "outline dense"
                    ).mark("download-balance")
                    ui.button("Orders CSV", on_click=lambda: page.download_data("orders")).props(
                        "outline dense"
                    ).mark("download-orders")
                    ui.button("Engine TOML", on_click=lambda: page.save("toml")).props(
                        "outline dense"
                    )
                    ui.button("Report HTML", on_click=page.download_report).props(
                        "outline dense"
                    ).mark("download-report")
                    ui.button("Report PDF", on_click=lambda: page.download_report("pdf")).props(
                        "outline dense"
                    ).mark("download-report-pdf")
                page.setting("orders", page.update_all)
            with ui.card().classes("grow"):
                ui.label("Free forces and moments by order").classes("text-subtitle1")
                self.orders_table = (
                    ui.table(
                        columns=[
                            {"name": k, "label": label, "field": k}
                            for k, label in (
                                ("order", "Order"),
                                ("force", "Force N"),
                                ("force_fwd", "fwd N"),
                                ("force_bwd", "bwd N"),
                                ("moment", "Moment N·m"),
                                ("moment_fwd", "fwd N·m"),
                                ("moment_bwd", "bwd N·m"),
                            )
                        ],
                        rows=[],
                        row_key="order",
                    )
                    .props("dense flat data-testid=orders-table")
                    .mark("orders-table")
                )
        with ui.row().classes("w-full items-center gap-4"):
            self.curve_quantity = (
                ui.select(
                    ["force", "moment"],
                    value="force",
                    label="Curves and polar: quantity",
                    on_change=lambda: self.redraw(self.curves, self.polar),
                )
                .classes("w-48")
                .props("data-testid=curve-quantity")
                .mark("curve-quantity")
            )
            self.polar_order = (
                ui.select(
                    ["rotating"] + [str(k) for k in range(1, 9)],
                    value="1",
                    label="Polar diagram: order",
                    on_change=lambda: self.redraw(self.polar),
                )
                .classes("w-48")
                .props("data-testid=polar-order")
                .mark("polar-order")
            )
        with ui.grid(columns=2).classes("w-full"):
            self.card(
                "orders",
                "Free forces and moments by order",
                self.computed(lambda c: orders_bar(c.analysis)),
            )
            self.card(
                "residuals",
                "Residuals before/after balancing",
                self.computed(lambda c: residuals_bar(c.study)),
            )
            self.curves = self.card(
                "curves",
                "Curves over a revolution, before and after balancing",
                self.computed(
                    lambda c: curves_figure(c.analysis, c.study, quantity=self.curve_quantity.value)
                ),
            )
            self.polar = self.card(
                "polar", "Polar rotating-vector diagram", self.computed(self._polar)
            )

    def redraw(self, *cards: FigureCard) -> None:
        """A selector changed: redraw the figures it controls, now."""
        if self.quiet:
            return
        for card in cards:
            card.stale = True
        self.page.refresh_cards(self.name)

    def reset(self) -> None:
        self.follow = True

    def show(self, c: Any) -> None:
        self.summary.set_content("  \n".join(summary_lines(c)))
        self.orders_table.rows = order_rows(c)
        self.orders_table.update()
        choices = ["rotating", *(str(int(k)) for k in c.analysis.forces.orders)]
        self.quiet = True  # the cards are redrawn after show() anyway
        if list(self.polar_order.options) != choices:  # follow the "Highest order" setting
            keep = self.polar_order.value if self.polar_order.value in choices else "1"
            self.polar_order.set_options(choices, value=keep)
        if self.follow:
            self.follow = False
            quantity, order = leading_component(c.analysis)
            self.curve_quantity.set_value(quantity)
            self.polar_order.set_value(order)
        self.quiet = False
        # a next step of "What is left" names the balance factor as the Engine form does
        b = c.study.to_dict(factor_name=label_of("counterweights.balance_factor"))
        self.balance_table.rows = balance_rows(b)
        self.balance_table.update()
        self.balance_summary.set_content("  \n".join(balance_lines(b)))
        self.balance_left.set_content("\n".join(left_lines(b)))

    def _polar(self, c: Any) -> Any:
        order: Any = self.polar_order.value
        order = order if order == "rotating" else int(order)
        if order != "rotating" and order > c.analysis.forces.orders[-1]:
            raise InputError("polar order", order, "is above the highest order computed")
        return polar_figure(c.analysis, order, quantity=self.curve_quantity.value)
