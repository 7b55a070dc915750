"""The Balance shaft tab: where along a balance shaft to put its unbalance mass."""

from __future__ import annotations

from typing import Any

from nicegui import ui

from ..errors import InputError
from . import studies
from .widgets import Tab, plot_or_none


class ShaftTab(Tab):
    name = "shaft"
    result: Any = None

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("Shaft and objective").classes("text-subtitle1")
                for key in ("bs_length", "bs_diameter", "bs_weight"):
                    self.page.setting(key)
                ui.button("Find the optimum", on_click=self.run_study).props("color=primary").mark(
                    "run-shaft"
                )
            with ui.card().classes("grow"):
                self.shaft_summary = ui.markdown("").mark("shaft-summary")
        self.card("shaft", "Placement study", lambda: plot_or_none("shaft_study", self.result))

    def reset(self) -> None:
        self.result = None

    async def run_study(self) -> None:
        c = self.study_ready()
        if c is None:
            return
        try:
            study, which = studies.shaft_placement(c, self.page.project.settings)
        except InputError as error:
            self.study_error(error)
            return
        self.result = study
        self.shaft_summary.set_content(
            f"Unbalance of the {which}: optimum mass position **"
            f"{study.optimum_position * 100:.1f} %** of the shaft length (w = "
            f"{study.weight:g}, J = {study.optimum_objective:.3f})  \nFirst bending "
            f"frequency there {float(study.first_frequency[len(study.positions) // 2]):.0f} "
            "Hz (mid-range)"
        )
        for card in self.cards:
            card.refresh()
