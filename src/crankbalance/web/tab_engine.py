"""The Engine tab: general engine and balancing-component fields, the live 3-D crank."""

from __future__ import annotations

from typing import Any

from nicegui import ui

from ..output.figures.crank3d import crank_3d
from .crank_editor import CrankEditor
from .form import BALANCING_FIELDS, DETAIL_FIELDS, ENGINE_FIELDS, FIELD_BY_KEY
from .tab_results import balance_lines
from .widgets import FIGURE_CSS, FIGURE_JS, Tab, on_a_phone

#: on a phone (below 600 px) the 3-D crank's camera stands this much farther out than its
#: fitted one (fitted to a wide figure: a phone's narrow scene cut the tick labels at the
#: left)
PHONE_CRANK_CAMERA = 1.5

#: the key results beside the form list at most this many components the balancing leaves
#: (the largest first, as the balance result orders them; the Results tab has them all)
KEY_LEFT = 4

#: what the balance factor does, shown under the balancing fields
BALANCE_FACTOR_WORDS = (
    "Balance factor k: the crank counterweights carry the rotating masses and k times the "
    "reciprocating mass of the cylinders on each pin. On one cylinder, 0.5 halves the "
    "first-order shake and turns it into a force rotating with the crank. On a 90 deg V pair "
    "the two first-order forces add up to one forward force of one cylinder's size, turning "
    "with the crank: k = 0.5 per cylinder cancels it (and the crossplane V8's first-order "
    "couple); k = 1 reverses it instead of removing it. A backward first-order component, and "
    "any of order 2 or higher, needs balance shafts."
)

#: what the detail fields are, shown above them
DETAIL_WORDS = (
    "Lengths separated by commas. Offsets move a cylinder's bore axis off the crank axis "
    "(added to the wrist-pin offset); rod positions place each rod along its crankpin "
    "(side-by-side rods on a shared pin make a rocking couple); moments are taken about the "
    "moment reference. A VR engine, or a W from two VR banks (W type vr), has its rows' bore "
    "offset and pin split; a vee's pin split splits each crankpin in two, one per bank, "
    "placed along the crank by the rod positions; a radial engine gets master-and-link rods "
    "from the link pin radius and link rod length. Fields of other layouts are hidden while "
    "empty."
)


class EngineTab(Tab):
    name = "engine"

    def build(self) -> None:
        ui.add_css(".cb-warning .q-field__messages { color: #a15c00; font-weight: 500; }")
        ui.add_css(FIGURE_CSS)  # the figures of every tab
        ui.add_body_html(FIGURE_JS)
        with ui.row().classes("w-full items-start gap-6"):
            with ui.card():
                ui.label("Engine general parameters").classes("text-subtitle1")
                with ui.grid(columns=2):
                    for f in ENGINE_FIELDS:
                        self.page.field(f)
            # beside the general card from 1280 px wide: grows from 380 px, not from its
            # content's width (a long line of the results would push it below the form)
            with ui.column().style("flex: 1 1 380px; min-width: 0"):
                with (
                    ui.card().classes("w-full").props("data-testid=key-results").mark("key-results")
                ):
                    ui.label("Key results").classes("text-subtitle1")
                    self.key_stale = (
                        ui.label("")
                        .classes("text-negative text-body1")
                        .props("data-testid=key-stale")
                        .mark("key-stale")
                    )
                    self.key_stale.set_visibility(False)
                    self.key_results = (
                        ui.markdown("").props("data-testid=key-lines").mark("key-lines")
                    )
                self.show_3d = (
                    ui.switch("Live 3-D view", value=True, on_change=self._toggle_3d)
                    .props("data-testid=show-3d")
                    .mark("show-3d")
                )
                self.crank_card = self.card("crank3d", "Crankshaft (3-D)", self._crank_figure)
            with ui.card():
                ui.label("Balancing components parameters").classes("text-subtitle1")
                with ui.grid(columns=2):
                    for f in BALANCING_FIELDS:
                        self.page.field(f)
                self.offer_cg = (
                    ui.button("", on_click=self._use_cg_radius)
                    .props("outline dense no-caps data-testid=offer-cw-cg-radius")
                    .mark("offer-cw-cg-radius")
                )
                ui.label(BALANCE_FACTOR_WORDS).classes("text-caption text-grey-8 max-w-md").mark(
                    "balance-factor-explained"
                )
            with (
                ui.expansion("Offsets, rod positions and radial rods", value=self._details_used())
                .classes("q-card")
                .props("data-testid=engine-details header-class=text-subtitle1")
                .mark("engine-details") as self.details
            ):
                ui.label(DETAIL_WORDS).classes("text-caption text-grey-8 max-w-md")
                with ui.grid(columns=2):
                    for f in DETAIL_FIELDS:
                        self.page.field(f)
                # emptied when the layout is no longer W (else it is refused there)
                self.page.inputs["w_type"].props("clearable")
        self.editor = CrankEditor(self.page)
        self.editor.build()

    def show_errors(self, errors: dict[str, str]) -> None:
        self.editor.show_errors(errors)
        self._show_offer()
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

    def _use_cg_radius(self) -> None:
        offer = self.page.project.default_cw_cg_radius()
        if offer:
            self.page.inputs["cw_cg_radius"].set_value(offer)

    def _show_offer(self) -> None:
        """The button offering a counterweight CG radius, while that field is empty."""
        project = self.page.project
        offer = project.default_cw_cg_radius()
        empty = not project.texts.get("cw_cg_radius", "").strip()
        self.offer_cg.set_visibility(bool(offer) and empty)
        self.offer_cg.set_text(f"Use counterweight CG radius {offer} (3/4 of the crank radius)")

    def reset(self) -> None:
        self.editor.rebuild()
        self.details.set_value(self._details_used())

    def _details_used(self) -> bool:
        """Whether the engine uses a field of the detail card (offsets, rod positions,
        radial rods, VR): the card opens for it and stays folded for the others."""
        return any(self.page.project.texts.get(f.key, "").strip() for f in DETAIL_FIELDS)

    def show(self, c: Any) -> None:
        """The key results beside the form: the speed, the counterweights and shafts, the
        residuals, and the largest components the balancing leaves."""
        b = c.study.to_dict()
        left = b.get("remaining") or []
        lines = balance_lines(b)
        lines.append("**Left after balancing:** " + ("none" if not left else ""))
        items = [f"- {item['text']}" for item in left[:KEY_LEFT]]
        if len(left) > KEY_LEFT:
            items.append(f"- and {len(left) - KEY_LEFT} smaller (see Results)")
        self.key_results.set_content("  \n".join(lines) + "\n\n" + "\n".join(items))

    def show_fresh(self, fresh: bool, problem: str) -> None:
        """The key results only for the form as it is, else why not."""
        self.key_stale.set_text("" if fresh else f"Not computed: {problem}.")
        self.key_stale.set_visibility(not fresh)
        self.key_results.set_visibility(fresh)

    def _toggle_3d(self) -> None:
        """The 3-D view can be switched off (software WebGL is heavy on small machines)."""
        self.crank_card.card.set_visibility(self.show_3d.value)
        if self.show_3d.value:
            self.crank_card.refresh()

    def _crank_figure(self) -> Any | None:
        c = self.page.project.computed
        if c is None:
            return None
        return on_a_phone(crank_3d(c.analysis.model, c.study), PHONE_CRANK_CAMERA)
