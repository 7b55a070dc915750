"""The Engine tab: general engine and balancing-component fields, the live 3-D crank."""

from __future__ import annotations

from typing import Any

from nicegui import ui

from .. import figures
from .crank_editor import CrankEditor
from .project import BALANCING_FIELDS, ENGINE_FIELDS, FIELD_BY_KEY
from .widgets import Tab


class EngineTab(Tab):
    name = "engine"

    def build(self) -> None:
        ui.add_css(".cb-warning .q-field__messages { color: #a15c00; font-weight: 500; }")
        with ui.row().classes("w-full items-start gap-6"):
            with ui.card():
                ui.label("Engine general parameters").classes("text-subtitle1")
                with ui.grid(columns=2):
                    for f in ENGINE_FIELDS:
                        self.page.field(f)
            with ui.card():
                ui.label("Balancing components parameters").classes("text-subtitle1")
                with ui.grid(columns=2):
                    for f in BALANCING_FIELDS:
                        self.page.field(f)
            with ui.column().classes("grow min-w-[420px]"):
                self.show_3d = (
                    ui.switch("Live 3-D view", value=True, on_change=self._toggle_3d)
                    .props("data-testid=show-3d")
                    .mark("show-3d")
                )
                self.crank_card = self.card("crank3d", "Crankshaft (3-D)", self._crank_figure)
        self.editor = CrankEditor(self.page)
        self.editor.build()

    def show_errors(self, errors: dict[str, str]) -> None:
        self.editor.show_errors(errors)
        warnings = self.page.project.warnings
        for key in ("speed", "rod_length"):
            element = self.page.inputs[key]
            text = warnings.get(key, FIELD_BY_KEY[key].hint)
            if element.props.get("hint") != text:
                element.props(f'hint="{text}"')
                if key in warnings:
                    element.classes(add="cb-warning")
                else:
                    element.classes(remove="cb-warning")

    def reset(self) -> None:
        self.editor.rebuild()

    def _toggle_3d(self) -> None:
        """The 3-D view can be switched off (software WebGL is heavy on small machines)."""
        self.crank_card.card.set_visibility(self.show_3d.value)
        if self.show_3d.value:
            self.crank_card.refresh()

    def _crank_figure(self) -> Any | None:
        c = self.page.project.computed
        if c is None:
            return None
        return figures.crank_3d(c.analysis.model, c.study)
