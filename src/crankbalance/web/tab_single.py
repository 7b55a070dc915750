"""The Single cylinder tab: the balance-factor study of one cylinder, the ISO 21940-11
check and the rebalancing after new parts."""

from __future__ import annotations

from typing import Any

from nicegui import ui

from ..errors import InputError
from . import studies
from .widgets import Tab, plot_or_none


class SingleTab(Tab):
    name = "single"
    result: Any = None

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("Balance factor study").classes("text-subtitle1")
                for key in ("sc_cylinder", "sc_balance_factor"):
                    self.page.setting(key)
                ui.button("Compute study", on_click=self.run_study).props("color=primary").mark(
                    "run-single"
                )
                self.single_summary = ui.markdown("").mark("single-summary")
            with ui.card():
                ui.label("ISO 21940-11 check").classes("text-subtitle1")
                for key in ("sc_grade", "sc_rotor_mass", "sc_residual"):
                    self.page.setting(key)
                self.iso_summary = ui.markdown("").mark("iso-summary")
            with ui.card():
                ui.label("Rebalancing after new parts").classes("text-subtitle1")
                for key in (
                    "rb_new_reciprocating",
                    "rb_new_rotating",
                    "rb_cw_mass",
                    "rb_cw_radius",
                    "rb_hole_diameter",
                    "rb_hole_radius",
                ):
                    self.page.setting(key)
                self.rebalance_summary = ui.markdown("").mark("rebalance-summary")
        with ui.grid(columns=2).classes("w-full"):
            self.card(
                "single-forces",
                "Forces of one cylinder",
                lambda: plot_or_none("single_cylinder_forces", self.result),
            )
            self.card(
                "single-sweep",
                "Peak force against the balance factor",
                lambda: plot_or_none("balance_factor_sweep", self.result),
            )
            self.card(
                "single-polar",
                "Polar diagram of the residual force",
                lambda: plot_or_none("single_cylinder_polar", self.result),
            )

    def reset(self) -> None:
        self.result = None

    async def run_study(self) -> None:
        c = self.study_ready()
        if c is None:
            return
        s = self.page.project.settings
        try:
            study = studies.single_study(c, s)
            iso = studies.iso_check(c, s)
            reb = studies.rebalance_study(c, s)
        except InputError as error:
            self.study_error(error)
            return
        self.result = study
        self.single_summary.set_content(
            f"Primary force **{study.primary_force:.1f} N**; with f_b = "
            f"{study.balance_factor:g}: peak resultant **{study.peak_resultant:.1f} N** "
            f"(in-line {study.in_line_amplitude:.1f} N, transverse "
            f"{study.transverse_amplitude:.1f} N)  \nLeast peak at f_b = "
            f"**{study.optimum_balance_factor:.3f}** ({study.optimum_peak_resultant:.1f} N)"
        )
        verdict = iso["verdict"]
        self.iso_summary.set_content(
            f"{iso['grade'].name} at {iso['speed'] * 30 / 3.141592653589793:.0f} rpm, rotor "
            f"{iso['rotor_mass']:.3f} kg: U_per = **{iso['permissible'] * 1e6:.2f} g·mm**"
            + (
                ""
                if verdict is None
                else f"  \nMeasured {verdict.residual * 1e6:.2f} g·mm: **"
                f"{'PASS' if verdict.passed else 'FAIL'}** ({verdict.ratio * 100:.0f} %)"
            )
        )
        self.rebalance_summary.set_content(
            f"Unbalance to remove **{reb.unbalance * 1e6:.1f} g·mm**; achieved f_b "
            f"{reb.achieved_balance_factor:.3f}; residual {reb.residual * 1e6:.2f} g·mm "
            f"({'within' if reb.passed else 'outside'} tolerance, {reb.status})  \n"
            f"Bob-weight {reb.bob_weight * 1e3:.1f} g"
        )
        for card in self.cards:
            card.refresh()
