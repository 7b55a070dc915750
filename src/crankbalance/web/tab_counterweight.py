"""The Counterweight design tab: the required first moment, the optimiser's constraints, the
Pareto front, the chosen design to scale and its SVG/DXF/STL export.

The radial space a counterweight may take is limited by the engine: it must pass under the
piston at bottom dead centre, where the wrist pin is ``rod length - crank radius`` from the
crank axis. When *Largest radial space* is left empty the optimiser gets that limit, and a
design larger than it (with a larger limit typed in) is warned about.
"""

from __future__ import annotations

from typing import Any

from nicegui import run, ui

from ..errors import InputError
from ..studies.counterweight import crank_outline, radial_space
from . import studies
from .messages import show_error
from .widgets import CANCELLED, StudyTab, button_row, plot_or_none, send_download

#: where the requirement comes from when the balancing needs no counterweights (a crank
#: balanced as a whole, e.g. a flat inline-4)
HALVES = (
    "each half of the crank balanced on its own, as `counterweight optimize --engine` takes "
    "it: the crank balanced as a whole needs no counterweights"
)


def space_warnings(optimum: Any, limit: float) -> list[str]:
    """Warnings for the shown designs whose outer radius exceeds the engine's space."""
    out = []
    for label, row in (
        ("least mass", optimum.row(optimum.least_mass)),
        ("least radius", optimum.row(optimum.least_radius)),
    ):
        if row["outer_radius"] > limit:
            out.append(
                f"**Warning:** the {label} design's outer radius {row['outer_radius'] * 1e3:.1f}"
                f" mm is larger than the space the engine allows ({limit * 1e3:.1f} mm, rod "
                "length - crank radius): it would hit the piston at bottom dead centre."
            )
    return out


#: feasible designs drawn beside the Pareto front at most (a sample; the front is drawn
#: whole): a run evaluates up to a million designs, more than a browser draws smoothly
PARETO_CLOUD = 3000

#: argument names of the optimiser -> the settings of this tab
ALIASES = {
    name: f"cw_{name}"
    for name in ("density", "max_mass", "max_radius", "min_balance", "iterations", "population")
}


class CounterweightTab(StudyTab):
    name = "counterweight"
    what = "the counterweight optimiser"
    prefixes = ("cw_",)
    optimum: Any = None
    #: the crankpin, journal and radial limit the shown designs are drawn with
    crank: Any = None

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("Main constraining parameters").classes("text-subtitle1")
                self.cw_requirement = ui.markdown("").mark("cw-requirement")
                self.settings(
                    "cw_density",
                    "cw_max_mass",
                    "cw_max_radius",
                    "cw_min_balance",
                    "cw_iterations",
                    "cw_population",
                    "cw_seed",
                )
                self.cw_space = ui.markdown("").classes("text-grey-8 max-w-xs").mark("cw-space")
                with button_row():
                    self.optimise_button = (
                        ui.button("Optimise", on_click=self.optimise)
                        .props("color=primary data-testid=optimise")
                        .mark("optimise")
                    )
                    self.cancel_button()
            with ui.card().classes("grow"):
                ui.label("Results").classes("text-subtitle1")
                self.rerun_note()
                self.cw_progress = ui.label("").props("data-testid=cw-progress").mark("cw-progress")
                self.cw_summary = ui.markdown("").props("data-testid=cw-summary").mark("cw-summary")
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
                with button_row():
                    for fmt in ("svg", "dxf", "stl"):
                        ui.button(
                            f"Export {fmt.upper()}", on_click=lambda f=fmt: self.export_design(f)
                        ).props("outline dense").mark(f"export-{fmt}")
        with ui.grid(columns=2).classes("w-full"):
            self.card(
                "pareto",
                "Pareto front (mass against radial space)",
                lambda: plot_or_none("pareto_front", self.optimum, PARETO_CLOUD),
            )
            self.card(
                "profile",
                "Chosen design to scale",
                lambda: plot_or_none("counterweight_profile", self._design(), self.crank),
            )

    def show(self, c: Any) -> None:
        super().show(c)
        try:
            moment, mass, radius, halves = studies.counterweight_requirement(c)
            source = HALVES if halves else "from the balancing"
            self.cw_requirement.set_content(
                f"Required first moment **{moment * 1e6:.0f} g·mm** "
                f"({mass * 1e3:.1f} g at {radius * 1e3:g} mm, {source})"
            )
        except InputError as error:
            self.cw_requirement.set_content(f"No counterweight requirement: {error.allowed}")
        limit = radial_space(c.analysis.model)
        self.cw_space.set_content(
            f"Empty *Largest radial space*: the engine's {limit * 1e3:.1f} mm (rod length - "
            "crank radius, the wrist pin at bottom dead centre); the piston skirt needs more "
            "clearance, so type your own limit."
        )

    def clear(self) -> None:
        self.optimum = None
        self.crank = None
        self.cw_summary.set_content("")
        for card in self.cards:
            card.refresh()

    async def optimise(self) -> None:
        c = self.study_ready()
        if c is None:
            return
        settings = dict(self.page.project.settings)
        limit = radial_space(c.analysis.model)
        if not str(settings.get("cw_max_radius", "")).strip():
            settings["cw_max_radius"] = f"{limit * 1e3:.6g} mm"  # the engine's space
        started = self.stamp()
        self.optimise_button.disable()  # one run at a time; Cancel stops it
        self.cw_progress.set_text("optimising … starting")
        try:
            required, o = studies.counterweight_inputs(c, settings)  # and the work budget
            # the web circle clears the engine's main journal, as the drawing shows it
            o = o.replace(journal_diameter=crank_outline(c.analysis.model).journal_diameter)
            self.cw_summary.set_content("")
            optimum = await self.in_worker(
                self.what, studies.optimise, required, o, progress=self.show_progress
            )
        except InputError as error:
            message = show_error(self.page, error, ALIASES)
            if error.field == "constraints" and settings["cw_max_radius"] != (
                self.page.project.settings.get("cw_max_radius")
            ):
                message += f" (*Largest radial space* was empty: the engine's {limit * 1e3:.1f} mm)"
            self.cw_summary.set_content(message)
            return
        finally:
            self.optimise_button.enable()
            self.cw_progress.set_text("")
        if optimum is None:
            self.cw_summary.set_content(CANCELLED)
            return
        if not self.owns(started):  # the engine or a setting was edited meanwhile
            return
        self.optimum = optimum
        typed = str(self.page.project.settings.get("cw_max_radius", "")).strip()
        self.crank = crank_outline(c.analysis.model, o.max_radius if typed else None)
        self.cw_choice.set_options(studies.design_choices(optimum), value="least mass")
        rows = [optimum.row(optimum.least_mass), optimum.row(optimum.least_radius)]
        text = [
            f"{len(optimum.designs)} feasible designs, {len(optimum.pareto)} on the "
            f"Pareto front, {optimum.nfev} evaluated in {optimum.elapsed:.2f} s",
            f"Web circle radius r_cw from {self.crank.journal_diameter * 500:.1f} mm, the "
            f"main journal's radius (⌀ {self.crank.journal_diameter * 1e3:.1f} mm): every "
            "design clears the journal",
        ]
        for label, row in zip(("Least mass", "Least radius"), rows, strict=True):
            text.append(
                f"**{label}:** {row['mass'] * 1e3:.1f} g, outer radius "
                f"{row['outer_radius'] * 1e3:.1f} mm, balance {row['balance']:.1f} %"
            )
        self.cw_summary.set_content("  \n".join(text + space_warnings(optimum, limit)))
        for card in self.cards:
            card.refresh()

    def show_progress(self, progress: dict[str, Any]) -> None:
        """A progress report of the running optimiser (after each of its rounds)."""
        if self.page.job is not None and self.page.job.owner == self.name:
            self.cw_progress.set_text(studies.progress_text(progress))

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
