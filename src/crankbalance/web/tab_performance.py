"""The Performance tab: friction, bearing load, shaking force and speed fluctuation of one
cylinder of the engine against the balance factor."""

from __future__ import annotations

from typing import Any

from nicegui import ui

from ..errors import InputError
from ..schema.settings import PerformanceOptions
from ..studies.performance import PEAK_BEARING_WORDS
from . import studies
from .messages import show_error
from .widgets import CANCELLED, StudyTab, button_row, fmt_g, plot_or_none


class PerformanceTab(StudyTab):
    name = "performance"
    what = "the performance sweep"
    prefixes = ("pf_",)
    result: Any = None

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("One cylinder of this engine").classes("text-subtitle1")
                self.settings(
                    "pf_bore",
                    "pf_balance_factors",
                    "pf_crank_inertia",
                    "pf_friction_coefficient",
                    "pf_journal_diameter",
                )
                with button_row():
                    ui.button("Run the sweep", on_click=self.run_study).props("color=primary").mark(
                        "run-performance"
                    )
                    self.cancel_button()
            with ui.card().classes("grow"):
                self.rerun_note()
                self.assumed = ui.markdown("").mark("performance-assumed")
                self.performance_table = (
                    ui.table(
                        columns=[
                            {"name": k, "label": label, "field": k}
                            for k, label in (
                                ("balance_factor", "f_b"),
                                ("friction_torque", "Friction N·m"),
                                ("friction_power", "Friction W"),
                                ("peak_load", "Peak bearing N"),
                                ("shaking", "Peak shaking N"),
                                ("fluctuation", "Speed fluct. %"),
                            )
                        ],
                        rows=[],
                        row_key="balance_factor",
                    )
                    .props("dense flat")
                    .mark("performance-table")
                )
        self.card(
            "sensitivity",
            "Sensitivity to the balance factor",
            lambda: plot_or_none("sensitivity_figure", self.result),
        )

    def clear(self) -> None:
        self.result = None
        self.assumed.set_content("")
        self.performance_table.rows = []
        self.performance_table.update()
        for card in self.cards:
            card.refresh()

    async def run_study(self) -> None:
        c = self.study_ready()
        if c is None:
            return
        settings = dict(self.page.project.settings)
        started = self.stamp()
        try:
            studies.options(settings, PerformanceOptions)  # its limits, before it starts
            study = await self.in_worker(self.what, studies.performance_study, c, settings)
        except InputError as error:
            show_error(self.page, error)
            return
        if study is None:
            ui.notify(CANCELLED, type="warning")
            return
        if not self.owns(started):  # the engine or a setting was edited meanwhile
            return
        self.assumed.set_content(
            f"Assumed: {study.assumption()}.\n\n{PEAK_BEARING_WORDS}".replace("*", "\\*")
        )
        self.result = result = study.result
        rows = []
        for k, fb in enumerate(result.balance_factors):
            rows.append(
                {
                    "balance_factor": f"{fb:g}",
                    "friction_torque": fmt_g(result.mean_friction_torque[0, k]),
                    "friction_power": fmt_g(result.friction_power[0, k]),
                    "peak_load": fmt_g(result.peak_bearing_load[0, k]),
                    "shaking": fmt_g(result.peak_shaking_force[0, k]),
                    "fluctuation": fmt_g(100 * result.speed_fluctuation[0, k]),
                }
            )
        self.performance_table.rows = rows
        self.performance_table.update()
        for card in self.cards:
            card.refresh()
