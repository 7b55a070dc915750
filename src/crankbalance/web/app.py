"""The NiceGUI page of ``crankbalance web``.

Tabs follow the 2021 paper's interface (Sec. 5: input tabs, Next/Back, "Compute results",
a Results tab, a counterweight-design tab) and go on to the single-cylinder, balance-shaft
and performance studies. :func:`root` builds one page per browser tab; all state lives in
the :class:`Page` object it creates (one :class:`~.project.Project` per client), never in
module globals, so several users work side by side without seeing each other's project.

Every figure comes from :mod:`crankbalance.plots`; this module only lays them out.
"""

from __future__ import annotations

import logging
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, Literal

from nicegui import run, ui

from .. import plots
from ..errors import InputError
from ..io.engine_file import MAX_FILE_BYTES, list_presets
from . import studies
from .exports import figure_csv, figure_json, table_csv
from .project import (
    BALANCING_FIELDS,
    ENGINE_FIELDS,
    FIELD_BY_KEY,
    MASS_FIELDS,
    FormField,
    Project,
)

log = logging.getLogger("crankbalance.web")
#: download formats of a figure card
FigureFormat = Literal["png", "svg", "csv", "json"]
DEFAULT_PRESET = "paper-inline3"
TABS = (
    ("engine", "Engine"),
    ("masses", "Masses"),
    ("results", "Results"),
    ("counterweight", "Counterweight design"),
    ("single", "Single cylinder"),
    ("shaft", "Balance shaft"),
    ("performance", "Performance"),
)


def root(preset: str | None = None) -> None:
    """The page: ``/`` or ``/?preset=v8-crossplane``."""
    Page(preset).build()


class FigureCard:
    """A plotly figure from :mod:`crankbalance.plots` with PNG/SVG/CSV/JSON downloads."""

    def __init__(
        self, page: Page, name: str, title: str, builder: Callable[[], Any | None]
    ) -> None:
        self.page, self.name, self.title, self.builder = page, name, title, builder
        self.figure: Any | None = None
        self.stale = True
        with ui.card().classes("w-full") as self.card:
            with ui.row().classes("w-full items-center justify-between"):
                ui.label(title).classes("text-subtitle1")
                with ui.row().classes("gap-1"):
                    formats: tuple[FigureFormat, ...] = ("png", "svg", "csv", "json")
                    for fmt in formats:
                        ui.button(fmt.upper(), on_click=lambda f=fmt: self.download(f)).props(
                            "flat dense size=sm"
                        ).mark(f"download-{name}-{fmt}")
            self.note = ui.label("").classes("text-grey-7")
            self.plot = (
                ui.plotly({"data": [], "layout": {}}).classes("w-full").mark(f"figure-{name}")
            )

    def refresh(self) -> None:
        try:
            self.figure = self.builder()
        except InputError as error:
            self.figure = None
            self.note.set_text(str(error))
        if self.figure is None:
            self.plot.set_visibility(False)
            return
        self.note.set_text("")
        self.plot.set_visibility(True)
        self.plot.update_figure(self.figure)
        self.stale = False

    async def download(self, fmt: FigureFormat) -> None:
        if self.figure is None or self.stale:
            self.refresh()
        if self.figure is None:
            ui.notify("nothing to download yet", type="warning")
            return
        if fmt == "csv":
            _download(figure_csv(self.figure), f"{self.name}.csv", "text/csv")
        elif fmt == "json":
            _download(figure_json(self.figure, self.title), f"{self.name}.json", "application/json")
        else:
            try:
                data = await run.io_bound(plots.to_image, self.figure, fmt)
            except Exception as error:  # kaleido / browser problems must not kill the page
                log.warning("image export failed: %s", error)
                ui.notify(f"{fmt.upper()} export failed: {error}", type="negative")
                return
            if data is None:  # NiceGUI is shutting down: the export was cancelled
                ui.notify(f"{fmt.upper()} export cancelled (server stopping)", type="warning")
                return
            media = "image/png" if fmt == "png" else "image/svg+xml"
            _download(data, f"{self.name}.{fmt}", media)


class Page:
    """One client's page and project."""

    def __init__(self, preset: str | None) -> None:
        self.project = Project()
        self.inputs: dict[str, Any] = {}
        self.setting_inputs: dict[str, Any] = {}
        self.cards: dict[str, list[FigureCard]] = {name: [] for name, _ in TABS}
        self.last_update_ms = 0.0
        self.updates = 0
        self.optimum: Any = None
        self.study_results: dict[str, Any] = {}
        message = ""
        name = preset or DEFAULT_PRESET
        try:
            self.project = Project.from_preset(name)
        except InputError as error:
            message = f"{error}; loaded {DEFAULT_PRESET} instead"
            self.project = Project.from_preset(DEFAULT_PRESET)
            name = DEFAULT_PRESET
        self.preset_name = name
        self.startup_message = message

    # ================================================================== layout
    def build(self) -> None:
        ui.page_title("crankbalance")
        with ui.header().classes("items-center gap-4 bg-blue-grey-9"):
            ui.label("crankbalance").classes("text-h6")
            self.preset_select = (
                ui.select(
                    list_presets(), value=self.preset_name, label="Preset", on_change=self.on_preset
                )
                .classes("w-56")
                .props("dark dense options-dense")
                .mark("preset")
            )
            ui.button("Save TOML", on_click=lambda: self.save("toml")).props(
                "flat color=white"
            ).mark("save-toml")
            ui.button("Save JSON", on_click=lambda: self.save("json")).props(
                "flat color=white"
            ).mark("save-json")
            ui.space()
            self.status = ui.label("").classes("text-caption").mark("status")
        with (
            ui.expansion(
                "Load a project file (.toml or .json, the engine-file format)", icon="upload_file"
            )
            .classes("w-full")
            .mark("load-project")
        ):
            ui.upload(
                label="Project file",
                auto_upload=True,
                on_upload=self.on_upload,
                max_file_size=MAX_FILE_BYTES,
            ).props("accept=.toml,.json flat bordered").classes("w-96").mark("upload")
        self.general = ui.label("").classes("text-negative text-body1").mark("general-error")
        with ui.tabs().classes("w-full") as self.tabs:
            for name, label in TABS:
                ui.tab(name, label=label).mark(f"tab-{name}")
        with ui.tab_panels(self.tabs, value="engine", on_change=self.on_tab).classes(
            "w-full"
        ) as self.panels:
            for index, (name, _label) in enumerate(TABS):
                with ui.tab_panel(name):
                    getattr(self, f"_tab_{name}")()
                    self._nav(index)
        self.update_all()
        if self.startup_message:
            self.general.set_text(self.startup_message)

    def _nav(self, index: int) -> None:
        with ui.row().classes("w-full justify-end gap-2 q-mt-md"):
            if index > 0:
                ui.button("Back", on_click=lambda: self.go(TABS[index - 1][0])).props(
                    "outline"
                ).mark(f"back-{TABS[index][0]}")
            if TABS[index][0] == "masses":
                ui.button("Compute results", on_click=self.compute_results).props(
                    "color=primary"
                ).mark("compute")
            if TABS[index][0] == "results":
                ui.button("Return", on_click=lambda: self.go("engine")).props("outline")
            if index < len(TABS) - 1:
                ui.button("Next", on_click=lambda: self.go(TABS[index + 1][0])).mark(
                    f"next-{TABS[index][0]}"
                )

    def _field(self, f: FormField) -> None:
        value = self.project.texts.get(f.key, "")
        handler = self._on_field(f.key)
        element: ui.select | ui.input
        if f.kind == "choice":
            options = list(f.options)
            if value and value not in options:
                options.append(value)
            element = ui.select(options, value=value or None, label=f.label, on_change=handler)
        else:
            element = ui.input(label=f.label, value=value, placeholder=f.hint, on_change=handler)
        element.classes("w-64").props(f'hint="{f.hint}"' if f.hint else "")
        element.props(f"data-testid=field-{f.key}").mark(f"field-{f.key}")
        element.without_auto_validation()
        self.inputs[f.key] = element

    def _setting(self, key: str, on_change: Callable[[], None] | None = None) -> None:
        label, _kind, hint = studies.SETTING_FIELDS[key]

        def changed(event: Any, key: str = key) -> None:
            self.project.settings[key] = "" if event.value is None else str(event.value)
            self.show_setting_errors()
            if on_change is not None:
                on_change()

        element = (
            ui.input(
                label=label,
                value=str(self.project.settings.get(key, "")),
                placeholder=hint,
                on_change=changed,
            )
            .classes("w-64")
            .props(f'hint="{hint}"')
            .props(f"data-testid=setting-{key}")
            .mark(f"setting-{key}")
            .without_auto_validation()
        )
        self.setting_inputs[key] = element

    # ------------------------------------------------------------------ Engine
    def _tab_engine(self) -> None:
        with ui.row().classes("w-full items-start gap-6"):
            with ui.card():
                ui.label("Engine general parameters").classes("text-subtitle1")
                with ui.grid(columns=2):
                    for f in ENGINE_FIELDS:
                        self._field(f)
            with ui.card():
                ui.label("Balancing components parameters").classes("text-subtitle1")
                with ui.grid(columns=2):
                    for f in BALANCING_FIELDS:
                        self._field(f)
            with ui.column().classes("grow min-w-[420px]"):
                self.show_3d = (
                    ui.switch("Live 3-D view", value=True, on_change=self._toggle_3d)
                    .props("data-testid=show-3d")
                    .mark("show-3d")
                )
                self.crank_card = FigureCard(
                    self, "crank3d", "Crankshaft (3-D)", self._crank_figure
                )
                self.cards["engine"].append(self.crank_card)

    def _toggle_3d(self) -> None:
        """The 3-D view can be switched off (software WebGL is heavy on small machines)."""
        self.crank_card.card.set_visibility(self.show_3d.value)
        if self.show_3d.value:
            self.crank_card.refresh()

    def _crank_figure(self) -> Any | None:
        c = self.project.computed
        if c is None:
            return None
        return plots.crank_3d(c.analysis.model, c.study)

    # ------------------------------------------------------------------ Masses
    def _tab_masses(self) -> None:
        with ui.row().classes("w-full items-start gap-6"):
            with ui.card():
                ui.label("Masses of the crank mechanism").classes("text-subtitle1")
                with ui.row():
                    ui.radio(
                        {"parts": "Parts", "totals": "Totals"},
                        value=self.project.settings["mass_mode"],
                        on_change=lambda e: self.on_mode("mass_mode", e.value),
                    ).props("inline").mark("mass-mode")
                    ui.radio(
                        {"fraction": "Conrod rotating fraction", "cg": "Conrod CG from big end"},
                        value=self.project.settings["conrod_split"],
                        on_change=lambda e: self.on_mode("conrod_split", e.value),
                    ).props("inline").mark("conrod-split")
                with ui.grid(columns=2):
                    for f in MASS_FIELDS:
                        self._field(f)
            with ui.card().classes("min-w-[360px]"):
                ui.label("Resulting masses").classes("text-subtitle1")
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
                    .props("dense flat")
                    .mark("mass-table")
                )

    # ------------------------------------------------------------------ Results
    def _tab_results(self) -> None:
        self.stale_note = (
            ui.label(
                "The engine has errors (fields marked in red): the results below are those of "
                "the last valid engine."
            )
            .classes("text-negative")
            .mark("results-stale")
        )
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card().classes("min-w-[340px]"):
                ui.label("Balancing masses").classes("text-subtitle1")
                self.balance_summary = ui.markdown("").mark("balance-summary")
                with ui.row().classes("gap-1"):
                    ui.button(
                        "Analysis JSON", on_click=lambda: self.download_data("analysis")
                    ).props("outline dense").mark("download-analysis")
                    ui.button("Balance JSON", on_click=lambda: self.download_data("balance")).props(
                        "outline dense"
                    ).mark("download-balance")
                    ui.button("Orders CSV", on_click=lambda: self.download_data("orders")).props(
                        "outline dense"
                    ).mark("download-orders")
                    ui.button("Engine TOML", on_click=lambda: self.save("toml")).props(
                        "outline dense"
                    )
                    ui.button("Report HTML", on_click=self.download_report).props(
                        "outline dense"
                    ).mark("download-report")
                self._setting("orders", self.recompute)
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
                    .props("dense flat")
                    .mark("orders-table")
                )
        with ui.row().classes("w-full items-center gap-4"):
            self.curve_quantity = (
                ui.select(
                    ["force", "moment"],
                    value=self._leading_quantity(),
                    label="Curves and polar: quantity",
                    on_change=self.refresh_results,
                )
                .classes("w-48")
                .mark("curve-quantity")
            )
            self.polar_order = (
                ui.select(
                    ["rotating"] + [str(k) for k in range(1, 9)],
                    value="1",
                    label="Polar diagram: order",
                    on_change=self.refresh_results,
                )
                .classes("w-48")
                .mark("polar-order")
            )
        with ui.grid(columns=2).classes("w-full"):
            self.cards["results"] += [
                FigureCard(
                    self,
                    "orders",
                    "Free forces and moments by order",
                    self._fig(lambda c: plots.orders_bar(c.analysis)),
                ),
                FigureCard(
                    self,
                    "residuals",
                    "Residuals before/after balancing",
                    self._fig(lambda c: plots.residuals_bar(c.study)),
                ),
                FigureCard(
                    self,
                    "curves",
                    "Curves over a revolution, before and after balancing",
                    self._fig(
                        lambda c: plots.curves_figure(
                            c.analysis, c.study, quantity=self.curve_quantity.value
                        )
                    ),
                ),
                FigureCard(self, "polar", "Polar rotating-vector diagram", self._fig(self._polar)),
            ]

    def _leading_quantity(self) -> plots.Quantity:
        """Start the curves and polar diagram on the moment when every free force is zero
        but a moment is not (an in-line 3): the first thing shown is then not a flat line."""
        c = self.project.computed
        if c is None:
            c = self.project.compute() if self.project.spec is not None else None
        return "force" if c is None else plots.leading_quantity(c.analysis)

    def _polar(self, c: Any) -> Any:
        order: Any = self.polar_order.value
        order = order if order == "rotating" else int(order)
        if order != "rotating" and order > c.analysis.forces.orders[-1]:
            raise InputError("polar order", order, "is above the highest order computed")
        return plots.polar_figure(c.analysis, order, quantity=self.curve_quantity.value)

    def _fig(self, build: Callable[[Any], Any]) -> Callable[[], Any | None]:
        def builder() -> Any | None:
            c = self.project.computed
            return None if c is None else build(c)

        return builder

    # ------------------------------------------------------------------ Counterweight
    def _tab_counterweight(self) -> None:
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
                    self._setting(key)
                ui.button("Optimise", on_click=self.run_counterweight).props("color=primary").mark(
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
            self.cards["counterweight"] += [
                FigureCard(
                    self,
                    "pareto",
                    "Pareto front (mass against radial space)",
                    lambda: self._plot_or_none("pareto_front", self.optimum),
                ),
                FigureCard(
                    self,
                    "profile",
                    "Chosen design to scale",
                    lambda: self._plot_or_none("counterweight_profile", self._design()),
                ),
            ]

    def _design(self) -> Any | None:
        if self.optimum is None:
            return None
        return studies.pick_design(self.optimum, self.cw_choice.value or "least mass")

    def _plot_or_none(self, name: str, *args: Any) -> Any | None:
        if any(a is None for a in args):
            return None
        builder = getattr(plots, name, None)
        if builder is None:
            raise InputError("figure", name, "is not available in this version of plots.py")
        return builder(*args)

    # ------------------------------------------------------------------ Single cylinder
    def _tab_single(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("Balance factor study").classes("text-subtitle1")
                for key in ("sc_cylinder", "sc_balance_factor"):
                    self._setting(key)
                ui.button("Compute study", on_click=self.run_single).props("color=primary").mark(
                    "run-single"
                )
                self.single_summary = ui.markdown("").mark("single-summary")
            with ui.card():
                ui.label("ISO 21940-11 check").classes("text-subtitle1")
                for key in ("sc_grade", "sc_rotor_mass", "sc_residual"):
                    self._setting(key)
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
                    self._setting(key)
                self.rebalance_summary = ui.markdown("").mark("rebalance-summary")
        with ui.grid(columns=2).classes("w-full"):
            self.cards["single"] += [
                FigureCard(
                    self,
                    "single-forces",
                    "Forces of one cylinder",
                    lambda: self._plot_or_none(
                        "single_cylinder_forces", self.study_results.get("single")
                    ),
                ),
                FigureCard(
                    self,
                    "single-sweep",
                    "Peak force against the balance factor",
                    lambda: self._plot_or_none(
                        "balance_factor_sweep", self.study_results.get("single")
                    ),
                ),
                FigureCard(
                    self,
                    "single-polar",
                    "Polar diagram of the residual force",
                    lambda: self._plot_or_none(
                        "single_cylinder_polar", self.study_results.get("single")
                    ),
                ),
            ]

    # ------------------------------------------------------------------ Balance shaft
    def _tab_shaft(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("Shaft and objective").classes("text-subtitle1")
                for key in ("bs_length", "bs_diameter", "bs_weight"):
                    self._setting(key)
                ui.button("Find the optimum", on_click=self.run_shaft).props("color=primary").mark(
                    "run-shaft"
                )
            with ui.card().classes("grow"):
                self.shaft_summary = ui.markdown("").mark("shaft-summary")
        self.cards["shaft"].append(
            FigureCard(
                self,
                "shaft",
                "Placement study",
                lambda: self._plot_or_none("shaft_study", self.study_results.get("shaft")),
            )
        )

    # ------------------------------------------------------------------ Performance
    def _tab_performance(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("One cylinder of this engine").classes("text-subtitle1")
                for key in (
                    "pf_bore",
                    "pf_balance_factors",
                    "pf_crank_inertia",
                    "pf_friction_coefficient",
                    "pf_journal_diameter",
                ):
                    self._setting(key)
                ui.button("Run the sweep", on_click=self.run_performance).props(
                    "color=primary"
                ).mark("run-performance")
            with ui.card().classes("grow"):
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
        self.cards["performance"].append(
            FigureCard(
                self,
                "sensitivity",
                "Sensitivity to the balance factor",
                lambda: self._plot_or_none(
                    "sensitivity_figure", self.study_results.get("performance")
                ),
            )
        )

    # ================================================================== events
    def _on_field(self, key: str) -> Callable[[Any], None]:
        def handler(event: Any) -> None:
            value = "" if event.value is None else str(event.value)
            if self.project.texts.get(key, "") == value:
                return
            self.project.set(key, value)
            self.update_all()

        return handler

    def on_mode(self, key: str, value: str) -> None:
        self.project.set_setting(key, value)
        self.update_all()

    def on_preset(self, event: Any) -> None:
        if not event.value or event.value == self.preset_name:
            return
        self.load(Project.from_preset(event.value))
        self.preset_name = event.value

    def on_tab(self, event: Any) -> None:
        self.refresh_cards(str(event.value))

    def go(self, tab: str) -> None:
        self.panels.set_value(tab)

    def compute_results(self) -> None:
        self.recompute()
        if self.project.spec is None:
            ui.notify("Correct the fields marked in red first", type="warning")
            return
        self.go("results")

    async def on_upload(self, event: Any) -> None:
        upload = event.file
        name = str(getattr(upload, "name", "project.toml"))
        try:
            raw = await upload.read()
            if len(raw) > MAX_FILE_BYTES:
                raise InputError(
                    name,
                    f"{len(raw)} bytes",
                    f"is larger than {MAX_FILE_BYTES} bytes; an engine file is a few kB",
                )
            try:
                text = raw.decode("utf-8")
            except UnicodeDecodeError:
                raise InputError(
                    name, "binary data", "must be a UTF-8 text file (TOML or JSON)"
                ) from None
            fmt = "json" if name.lower().endswith(".json") else "toml"
            project = Project.from_text(text, name, fmt)
        except InputError as error:
            message = f"Upload of {name} refused, the current project is kept: {error}"
            self.general.set_text(message)
            ui.notify(message, type="negative", multi_line=True)
            return
        self.load(project)
        self.general.set_text("")
        ui.notify(f"Loaded {name}", type="positive")

    def load(self, project: Project) -> None:
        self.project = project
        self.optimum = None
        self.study_results = {}
        for key, element in self.inputs.items():
            value = project.texts.get(key, "")
            if isinstance(element, ui.select):
                if value and value not in element.options:
                    element.set_options([*element.options, value])
                element.set_value(value or None)
            else:
                element.set_value(value)
        for key, element in self.setting_inputs.items():
            element.set_value(str(project.settings.get(key, "")))
        self.update_all()
        self.curve_quantity.set_value(self._leading_quantity())

    def save(self, fmt: str) -> None:
        try:
            text = self.project.to_toml() if fmt == "toml" else self.project.to_json()
        except InputError as error:
            ui.notify(str(error), type="warning")
            return
        stem = "".join(
            ch if ch.isalnum() or ch in "-_" else "-"
            for ch in (self.project.spec.name if self.project.spec else "engine")
        )[:40]
        _download(
            text,
            f"{stem or 'engine'}.{fmt}",
            "application/toml" if fmt == "toml" else "application/json",
        )

    def download_data(self, what: str) -> None:
        import json

        c = self.project.computed
        if c is None or self.project.spec is None:
            ui.notify("no valid engine to export", type="warning")
            return
        if what == "analysis":
            _download(
                json.dumps(c.analysis.to_dict(), indent=1), "analysis.json", "application/json"
            )
        elif what == "balance":
            _download(json.dumps(c.study.to_dict(), indent=1), "balance.json", "application/json")
        else:
            _download(table_csv(self._order_rows()), "orders.csv", "text/csv")

    async def download_report(self) -> None:
        from .. import report

        c = self.project.computed
        if c is None or self.project.spec is None:
            ui.notify("no valid engine to report", type="warning")
            return
        try:
            html = await run.io_bound(
                _report_html, report, self.project.spec, len(c.analysis.forces.orders)
            )
        except Exception as error:  # the report must never take the page down
            log.warning("report failed: %s", error)
            ui.notify(f"report failed: {error}", type="negative")
            return
        if html is None:
            ui.notify("report cancelled (server stopping)", type="warning")
            return
        _download(html, "report.html", "text/html")

    # ================================================================== updates
    def update_all(self) -> None:
        """Show field errors and, for a valid engine, recompute and refresh what is shown."""
        t0 = time.perf_counter()
        for key, element in self.inputs.items():
            f = FIELD_BY_KEY[key]
            element.set_visibility(self.project.active(f))
        self.recompute()
        self.show_errors()
        self.last_update_ms = (time.perf_counter() - t0) * 1e3
        c = self.project.computed
        if self.project.spec is not None and c is not None:
            self.updates += 1
            self.status.set_text(
                f"update {self.updates}: computed in {c.elapsed * 1e3:.0f} ms, page updated "
                f"in {self.last_update_ms:.0f} ms"
            )
        else:
            self.status.set_text("engine has errors: see the fields marked in red")
        self.stale_note.set_visibility(self.project.spec is None)

    def recompute(self) -> None:
        self.show_setting_errors()
        if self.project.spec is None:
            return
        try:
            self.project.settings["orders"] = str(studies.setting(self.project.settings, "orders"))
        except InputError:
            self.project.settings["orders"] = "8"
        computed = self.project.compute()
        if computed is None:
            self.show_errors()
            return
        for cards in self.cards.values():
            for card in cards:
                card.stale = True
        self.show_numbers()
        self.refresh_cards(str(self.panels.value) if hasattr(self, "panels") else "engine")

    def refresh_results(self) -> None:
        self.refresh_cards("results")

    def refresh_cards(self, tab: str) -> None:
        for card in self.cards.get(tab, []):
            if card.stale and card.card.visible:
                card.refresh()

    def show_errors(self) -> None:
        for key, element in self.inputs.items():
            element.error = self.project.errors.get(key)
        self.general.set_text(self.project.general_error)

    def show_setting_errors(self, extra: dict[str, str] | None = None) -> None:
        errors = studies.check_settings(self.project.settings)
        errors.update(extra or {})
        for key, element in self.setting_inputs.items():
            element.error = errors.get(key)

    def _order_rows(self) -> list[dict[str, Any]]:
        c = self.project.computed
        assert c is not None
        d = c.analysis.to_dict()
        rows = []
        for f, m in zip(d["free_forces"], d["free_moments"], strict=True):
            rows.append(
                {
                    "order": f["order"],
                    "force": _g(f["amplitude_N"]),
                    "force_fwd": _g(f["forward_N"]),
                    "force_bwd": _g(f["backward_N"]),
                    "moment": _g(m["amplitude_Nm"]),
                    "moment_fwd": _g(m["forward_Nm"]),
                    "moment_bwd": _g(m["backward_Nm"]),
                }
            )
        return rows

    def show_numbers(self) -> None:
        c = self.project.computed
        if c is None:
            return
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
            f"**Reciprocating mass per cylinder:** {_distinct(model.reciprocating_mass)} kg  \n"
            f"**Rotating mass per throw:** {_distinct(model.throw_rotating_mass)} kg  \n"
            + ("  \n".join(conrods))
        )
        self.orders_table.rows = self._order_rows()
        self.orders_table.update()
        choices = ["rotating", *(str(int(k)) for k in c.analysis.forces.orders)]
        if list(self.polar_order.options) != choices:  # follow the "Highest order" setting
            keep = self.polar_order.value if self.polar_order.value in choices else "1"
            self.polar_order.set_options(choices, value=keep)
        b = c.study.to_dict()
        lines = []
        cw = b["counterweight"]
        if cw:
            angle = "—" if cw["angle_deg"] is None else f"{cw['angle_deg']:.2f}°"
            lines.append(
                f"**Counterweight mass:** {cw['mass_kg']:.4f} kg × {cw['count']} "
                f"at {cw['cg_radius_m'] * 1e3:g} mm, angle {angle}"
            )
        for key, label in (("primary_shafts", "Primary"), ("secondary_shafts", "Secondary")):
            group = b[key]
            if group:
                lines.append(
                    f"**{label} shaft mass:** {group['mass_kg']:.4f} kg ({group['arrangement']})"
                )
            else:
                lines.append(f"**{label} shafts:** none")
        r = b["residual"]
        lines.append(
            f"Residual primary force {r['order1_force_N']:.4g} N, moment "
            f"{r['order1_moment_Nm']:.4g} N·m; secondary force "
            f"{r['order2_force_N']:.4g} N, moment {r['order2_moment_Nm']:.4g} N·m"
        )
        lines += [f"_{n}_" for n in b["notes"]]
        self.balance_summary.set_content("  \n".join(lines))
        try:
            moment, mass, radius = studies.counterweight_requirement(c)
            self.cw_requirement.set_content(
                f"Required first moment **{moment * 1e6:.0f} g·mm** "
                f"({mass * 1e3:.1f} g at {radius * 1e3:g} mm, from the balancing)"
            )
        except InputError as error:
            self.cw_requirement.set_content(str(error))

    # ================================================================== studies
    def _study_ready(self) -> Any | None:
        c = self.project.computed
        if c is None or self.project.spec is None:
            ui.notify("Correct the engine first (fields marked in red)", type="warning")
            return None
        return c

    def _study_error(self, error: InputError) -> None:
        if error.field in self.setting_inputs:
            self.show_setting_errors({error.field: str(error)})
        else:
            ui.notify(str(error), type="negative", multi_line=True)

    async def run_counterweight(self) -> None:
        c = self._study_ready()
        if c is None:
            return
        settings = dict(self.project.settings)
        self.cw_summary.set_content("optimising …")
        try:
            optimum = await run.io_bound(studies.run_counterweight, c, settings)
        except InputError as error:
            self.cw_summary.set_content(str(error))
            self._study_error(error)
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
        for card in self.cards["counterweight"]:
            card.refresh()

    def show_design(self) -> None:
        for card in self.cards["counterweight"]:
            if card.name == "profile":
                card.refresh()

    async def export_design(self, fmt: str) -> None:
        from ..io import cad as cwmod

        design = self._design()
        if design is None:
            ui.notify("Optimise first", type="warning")
            return
        if fmt == "svg":
            _download(cwmod.profile_svg(design), "counterweight.svg", "image/svg+xml")
        elif fmt == "dxf":
            _download(cwmod.profile_dxf(design), "counterweight.dxf", "application/dxf")
        else:
            with tempfile.TemporaryDirectory() as folder:
                path = Path(folder) / "counterweight.stl"
                await run.io_bound(cwmod.write_stl, design, path)
                data = path.read_bytes()
            _download(data, "counterweight.stl", "model/stl")

    async def run_single(self) -> None:
        c = self._study_ready()
        if c is None:
            return
        s = self.project.settings
        try:
            study = studies.single_study(c, s)
            iso = studies.iso_check(c, s)
            reb = studies.rebalance_study(c, s)
        except InputError as error:
            self._study_error(error)
            return
        self.study_results["single"] = study
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
        for card in self.cards["single"]:
            card.refresh()

    async def run_shaft(self) -> None:
        c = self._study_ready()
        if c is None:
            return
        try:
            study, which = studies.shaft_placement(c, self.project.settings)
        except InputError as error:
            self._study_error(error)
            return
        self.study_results["shaft"] = study
        self.shaft_summary.set_content(
            f"Unbalance of the {which}: optimum mass position **"
            f"{study.optimum_position * 100:.1f} %** of the shaft length (w = "
            f"{study.weight:g}, J = {study.optimum_objective:.3f})  \nFirst bending "
            f"frequency there {float(study.first_frequency[len(study.positions) // 2]):.0f} "
            "Hz (mid-range)"
        )
        for card in self.cards["shaft"]:
            card.refresh()

    async def run_performance(self) -> None:
        c = self._study_ready()
        if c is None:
            return
        settings = dict(self.project.settings)
        try:
            result = await run.io_bound(studies.performance_study, c, settings)
        except InputError as error:
            self._study_error(error)
            return
        if result is None:
            ui.notify("sweep cancelled (server stopping): no result", type="warning")
            return
        self.study_results["performance"] = result
        rows = []
        for k, fb in enumerate(result.balance_factors):
            rows.append(
                {
                    "balance_factor": f"{fb:g}",
                    "friction_torque": _g(result.mean_friction_torque[0, k]),
                    "friction_power": _g(result.friction_power[0, k]),
                    "peak_load": _g(result.peak_bearing_load[0, k]),
                    "shaking": _g(result.peak_shaking_force[0, k]),
                    "fluctuation": _g(100 * result.speed_fluctuation[0, k]),
                }
            )
        self.performance_table.rows = rows
        self.performance_table.update()
        for card in self.cards["performance"]:
            card.refresh()


def _g(value: float) -> str:
    return f"{float(value):.5g}"


def _distinct(values: Any) -> str:
    """Masses [kg] as shown: one value when all cylinders (throws) agree, else each in turn
    (an engine file may override the masses of some cylinders)."""
    return ", ".join(dict.fromkeys(f"{float(v):.4f}" for v in values))


def _report_html(report: Any, spec: Any, orders: int) -> str:
    """The self-contained HTML report of :mod:`crankbalance.report` for the current engine,
    with the orders of the Results tab."""
    return str(report.report_html(report.build_report(spec, orders)))


def _download(content: str | bytes, filename: str, media_type: str) -> None:
    """Send a file to the browser (always as bytes: a str would be taken for a URL by some
    download implementations, e.g. NiceGUI's simulated user)."""
    data = content.encode("utf-8") if isinstance(content, str) else content
    ui.download.content(data, filename, media_type)
