"""The Masses tab: the masses of the crank mechanism and the resulting masses per cylinder
and throw (shown as you type)."""

from __future__ import annotations

from typing import Any

from nicegui import ui

from .form import MASS_FIELDS
from .widgets import Tab, distinct

#: the labels of the tab's two choices
MASS_MODE_LABEL = "Masses given as"
CONROD_SPLIT_LABEL = "Conrod split by"


class MassesTab(Tab):
    name = "masses"

    def build(self) -> None:
        page = self.page
        with ui.row().classes("w-full items-start gap-6"):
            with ui.card():
                ui.label("Masses of the crank mechanism").classes("text-subtitle1")
                # two choices, each on its own row with its label (on one row at 1280 px
                # their four buttons read as one group)
                with ui.row().classes("items-center gap-2"):
                    ui.label(MASS_MODE_LABEL).classes("text-grey-8").mark("mass-mode-label")
                    ui.radio(
                        {"parts": "Parts", "totals": "Totals"},
                        value=page.project.settings["mass_mode"],
                        on_change=lambda e: page.on_mode("mass_mode", e.value),
                    ).props("inline").mark("mass-mode")
                with ui.row().classes("items-center gap-2"):
                    ui.label(CONROD_SPLIT_LABEL).classes("text-grey-8").mark("conrod-split-label")
                    ui.radio(
                        {"fraction": "Conrod rotating fraction", "cg": "Conrod CG from big end"},
                        value=page.project.settings["conrod_split"],
                        on_change=lambda e: page.on_mode("conrod_split", e.value),
                    ).props("inline").mark("conrod-split")
                with ui.grid(columns=2):
                    for f in MASS_FIELDS:
                        page.field(f)
            with ui.card().classes("min-w-[360px]"):
                ui.label("Resulting masses").classes("text-subtitle1")
                self.not_computed = (
                    ui.label("")
                    .classes("text-negative text-body1 max-w-sm")
                    .props("data-testid=masses-stale")
                    .mark("masses-stale")
                )
                self.not_computed.set_visibility(False)
                self.mass_summary = ui.markdown("").mark("mass-summary")
                self.mass_table = (
                    ui.table(
                        columns=[
                            {"name": "cylinder", "label": "Cylinder", "field": "cylinder"},
                            {
                                "name": "reciprocating",
                                "label": "Reciprocating kg",
                                "field": "reciprocating",
                            },
                            {"name": "throw", "label": "Throw", "field": "throw"},
                            {
                                "name": "rotating",
                                "label": "Rotating kg (throw)",
                                "field": "rotating",
                            },
                        ],
                        rows=[],
                        row_key="cylinder",
                    )
                    .props("dense flat data-testid=mass-table")
                    .mark("mass-table")
                )

    def show_fresh(self, fresh: bool, problem: str) -> None:
        """The resulting masses only for the form as it is: while it cannot be computed
        they are hidden and the card says why."""
        self.not_computed.set_text("" if fresh else f"Not computed: {problem}.")
        self.not_computed.set_visibility(not fresh)
        self.mass_summary.set_visibility(fresh)
        self.mass_table.set_visibility(fresh)

    def show(self, c: Any) -> None:
        model = c.analysis.model
        rows = [
            {
                "cylinder": k + 1,
                "reciprocating": f"{model.reciprocating_mass[k]:.4f}",
                "throw": int(model.cylinder_throw[k]) + 1,
                "rotating": f"{model.throw_rotating_mass[model.cylinder_throw[k]]:.4f}",
            }
            for k in range(model.cylinders)
        ]
        self.mass_table.rows = rows
        self.mass_table.update()
        conrods = [
            f"conrod {r.cylinder}: {r.rotating:.4f} kg rotating + "
            f"{r.reciprocating:.4f} kg reciprocating"
            for r in model.conrods[:1]
        ]
        self.mass_summary.set_content(
            f"**Reciprocating mass per cylinder:** {distinct(model.reciprocating_mass)} kg  \n"
            f"**Rotating mass per throw:** {distinct(model.throw_rotating_mass)} kg  \n"
            + ("  \n".join(conrods))
        )
