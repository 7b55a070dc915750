"""The Counterweight design tab: the required first moment, the optimiser's constraints, the
Pareto front, the chosen design to scale and its SVG/DXF/STL export."""

from __future__ import annotations

from typing import Any

from nicegui import run, ui

from ..errors import InputError
from . import studies
from .widgets import Tab, plot_or_none, send_download


class CounterweightTab(Tab):
    name = "counterweight"
    optimum: Any = None

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("Main constraining parameters").classes("text-subtitle1")
                self.cw_requirement = ui.markdown("").mark("cw-requirement")
                for key in (
                    "cw_density",
                    "cw_max_mass",
                    "cw_max_radius",
                    "cw_min_balance",
                    "cw_iterations",
                    "cw_population",
                    "cw_seed",
                ):
                    self.page.setting(key)
                ui.button("Optimise", on_click=self.optimise).props("color=primary").mark(
                    "optimise"
                )
            with ui.card().classes("grow"):
                ui.label("Results").classes("text-subtitle1")
                self.cw_summary = ui.markdown("").mark("cw-summary")
                self.cw_choice = (
                    ui.select(
                        ["least mass", "least radius"],
                        value="least mass",
                        label="Design",
                        on_change=self.show_design,
                    )
                    .classes("w-48")
                    .mark("cw-choice")
                )
                with ui.row().classes("gap-1"):
                    for fmt in ("svg", "dxf", "stl"):
                        ui.button(
                            f"Export {fmt.upper()}", on_click=lambda f=fmt: self.export_design(f)
                        ).props("outline dense").mark(f"export-{fmt}")
        with ui.grid(columns=2).classes("w-full"):
            self.card(
                "pareto",
                "Pareto front (mass against radial space)",
                lambda: plot_or_none("pareto_front", self.optimum),
            )
            self.card(
                "profile",
                "Chosen design to scale",
                lambda: plot_or_none("counterweight_profile", self._design()),
            )

    def show(self, c: Any) -> None:
        try:
            moment, mass, radius = studies.counterweight_requirement(c)
            self.cw_requirement.set_content(
                f"Required first moment **{moment * 1e6:.0f} g·mm** "
                f"({mass * 1e3:.1f} g at {radius * 1e3:g} mm, from the balancing)"
            )
        except InputError as error:
            self.cw_requirement.set_content(str(error))

    def reset(self) -> None:
        self.optimum = None

    async def optimise(self) -> None:
        c = self.study_ready()
        if c is None:
            return
        settings = dict(self.page.project.settings)
        self.cw_summary.set_content("optimising …")
        try:
            optimum = await run.io_bound(studies.run_counterweight, c, settings)
        except InputError as error:
            self.cw_summary.set_content(str(error))
            self.study_error(error)
            return
        if optimum is None:
            self.cw_summary.set_content("optimisation cancelled (server stopping): no result")
            return
        self.optimum = optimum
        self.cw_choice.set_options(studies.design_choices(optimum), value="least mass")
        rows = [optimum.row(optimum.least_mass), optimum.row(optimum.least_radius)]
        text = [
            f"{len(optimum.designs)} feasible designs, {len(optimum.pareto)} on the "
            f"Pareto front, {optimum.nfev} evaluated in {optimum.elapsed:.2f} s"
        ]
        for label, row in zip(("Least mass", "Least radius"), rows, strict=True):
            text.append(
                f"**{label}:** {row['mass'] * 1e3:.1f} g, outer radius "
                f"{row['outer_radius'] * 1e3:.1f} mm, balance {row['balance']:.1f} %"
            )
        self.cw_summary.set_content("  \n".join(text))
        for card in self.cards:
            card.refresh()

    def show_design(self) -> None:
        for card in self.cards:
            if card.name == "profile":
                card.refresh()

    async def export_design(self, fmt: str) -> None:
        from ..io import cad as cwmod

        design = self._design()
        if design is None:
            ui.notify("Optimise first", type="warning")
            return
        if fmt == "svg":
            send_download(cwmod.profile_svg(design), "counterweight.svg", "image/svg+xml")
        elif fmt == "dxf":
            send_download(cwmod.profile_dxf(design), "counterweight.dxf", "application/dxf")
        else:
            data = await run.io_bound(cwmod.stl_bytes, design)
            if data is not None:  # None: the server is shutting down
                send_download(data, "counterweight.stl", "model/stl")

    def _design(self) -> Any | None:
        if self.optimum is None:
            return None
        return studies.pick_design(self.optimum, self.cw_choice.value or "least mass")
