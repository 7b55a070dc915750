"""The Balance shaft tab: where along a balance shaft to put its unbalance mass.

The placement study (Kim 2018, Sec. 3.1) is for one unbalance mass on a shaft between end
bearings: a shaft that carries a free force. An engine whose free effect of the shaft's
order is a moment (a couple: two masses in opposition at the shaft's ends) or that has no
free first- or second-order effect at all is told so; nothing falls back to another engine's
shaft.
"""

from __future__ import annotations

from typing import Any

from nicegui import ui

from ..errors import InputError
from ..output.format import text
from ..schema.settings import ShaftPlacementOptions
from . import studies
from .messages import show_error
from .widgets import CANCELLED, StudyTab, button_row, plot_or_none

#: argument names of the library -> the settings of this tab
ALIASES = {"length": "bs_length", "diameter": "bs_diameter", "weight": "bs_weight"}
ORDER_NAMES = {1: "first-order", 2: "second-order"}


def applicability(analysis: Any) -> tuple[bool, str]:
    """(whether the placement study applies to this engine, why in words) from its free
    forces and moments (:func:`~crankbalance.studies.requirements.default_shaft_order`
    picks the order)."""
    from ..studies.requirements import default_shaft_order

    try:
        order = default_shaft_order(analysis)
    except InputError:
        return False, (
            "**This engine needs no balance shaft:** it has no free first- or second-order "
            "force or moment, so the placement study does not apply to it."
        )
    row = analysis.to_dict()
    force = float(row["free_forces"][order - 1]["amplitude_N"])
    moment = float(row["free_moments"][order - 1]["amplitude_Nm"])
    name = ORDER_NAMES[order]
    if moment > 0:
        also = f" (and a free force of {text(force, 'force', 5)})" if force > 0 else ""
        return False, (
            f"**The placement study does not apply to this engine.** Its free {name} effect "
            f"is a moment of {text(moment, 'moment', 5)}{also}: a shaft cancels it with two "
            "masses in opposition at its ends, not with the one unbalance mass between end "
            "bearings whose position this study (Kim 2018) finds."
        )
    return True, f"For this engine's free {name} force of {text(force, 'force', 5)}."


def reason(why: str) -> str:
    """The reason of :func:`applicability`'s words, without their bold lead sentence."""
    return why.split("**")[-1].strip()


class ShaftTab(StudyTab):
    name = "shaft"
    what = "the balance-shaft placement"
    prefixes = ("bs_",)
    result: Any = None

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card().classes("max-w-full"):
                ui.label("Shaft and objective").classes("text-subtitle1")
                self.settings("bs_length", "bs_diameter", "bs_weight")
                with button_row():
                    ui.button("Find the optimum", on_click=self.run_study).props(
                        "color=primary"
                    ).mark("run-shaft")
                    self.cancel_button()
            with ui.card().classes("grow max-w-full"):
                self.rerun_note()
                self.applies = ui.markdown("").mark("shaft-applies")
                self.shaft_summary = ui.markdown("").mark("shaft-summary")
        self.card("shaft", "Placement study", self.figure).note.mark("shaft-not-applicable")

    def figure(self) -> Any | None:
        """The placement study's figure, titled with the engine and the free force the shaft
        balances; none (and a "not applicable" line in its card) when the study does not
        apply to the engine."""
        card = self.cards[0]
        c = self.page.project.computed
        ok, why = (True, "") if c is None else applicability(c.analysis)
        card.note.set_text("" if ok else f"not applicable: {reason(why)}")
        if not ok or self.result is None or c is None:
            return None
        balances = why.removeprefix("For this engine's ").rstrip(".")
        return plot_or_none("shaft_study", self.result, c.analysis.model.name, balances)

    def show(self, c: Any) -> None:
        super().show(c)
        ok, why = applicability(c.analysis)
        self.applies.set_content(why)
        if ok:
            self.applies.classes(remove="text-orange-10")
        else:
            self.applies.classes(add="text-orange-10")
        if not ok and self.result is not None:
            self._clear()

    def clear(self) -> None:
        self._clear()

    def _clear(self, text: str = "") -> None:
        self.result = None
        self.result_for = None
        self.shaft_summary.set_content(text)
        for card in self.cards:
            card.refresh()

    async def run_study(self) -> None:
        c = self.study_ready()
        if c is None:
            return
        ok, why = applicability(c.analysis)
        self.applies.set_content(why)
        if not ok:  # said once, in the red line (a toast would repeat it and cover it)
            self._clear()
            return
        started = self.stamp()
        settings = dict(self.page.project.settings)
        try:
            studies.options(settings, ShaftPlacementOptions)  # its limits, before it starts
            done = await self.in_worker(self.what, studies.shaft_placement, c, settings)
        except InputError as error:
            if error.field == "engine":  # the balancing leaves no unbalance for a shaft
                why = f"{error.allowed} (the crank counterweights cancel it)"
                self._clear(f"**The placement study does not apply to this engine:** {why}.")
                self.cards[0].note.set_text(f"not applicable: {why}")
                return
            self._clear(show_error(self.page, error, ALIASES))
            return
        if done is None:
            self._clear(CANCELLED)
            return
        if not self.owns(started):
            return
        study, which = done
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
