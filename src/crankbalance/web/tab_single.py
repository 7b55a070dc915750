"""The Single cylinder tab: the balance-factor study of one cylinder, the ISO 21940-11
check and the rebalancing after new parts, carried to its drilling plan (holes: count,
diameter, drill point, depth, radius, angle, mass removed per web, passes) with a drawing.

The drill point (*Drill point angle*, *Depth read to the*) is that of
:class:`~crankbalance.schema.settings.RebalanceOptions` (the one schema of the command line's
``rebalance --point-angle/--depth-to`` and the Balance shop tab's settings): 180 deg, the
default, drills flat-bottomed holes; a pointed drill's depths are read to its tip or to its
shoulder, and the plan, the table and the drawing say which."""

from __future__ import annotations

import math
from typing import Any

from nicegui import ui

from ..errors import InputError
from ..output.format import depth_read_to
from ..schema.settings import DEPTH_TO
from . import studies
from .messages import show_error
from .widgets import CANCELLED, StudyTab, button_row, plot_or_none

#: argument names of the library -> the settings of this tab (messages beside the input)
ALIASES = {
    "grade": "sc_grade",
    "cylinder": "sc_cylinder",
    "balance_factor": "sc_balance_factor",
    "target_balance_factor": "sc_balance_factor",
    "hole_diameter": "rb_hole_diameter",
    "point_angle": "rb_point_angle",
    "depth_to": "rb_depth_to",
    "correction_radius": "rb_hole_radius",
    "correction": "rb_holes",
    "holes": "rb_holes",
    "web_thickness": "rb_web_thickness",
    "drill_length": "rb_drill_length",
}
#: settings of this tab that are a choice among words (a select, not a text input)
CHOICES = {"rb_depth_to": DEPTH_TO}
#: columns of the passes table (the thesis' steps 3-8, one row per pass)
PASS_COLUMNS = [
    {"name": "iteration", "label": "Pass", "field": "iteration"},
    {"name": "radius", "label": "Radius [mm]", "field": "radius"},
    {"name": "mass", "label": "Mass to remove [g]", "field": "mass"},
    {"name": "depth", "label": "Depth [mm]", "field": "depth"},
    {"name": "removed", "label": "Removed [g]", "field": "removed"},
    {"name": "residual", "label": "Residual [g·mm]", "field": "residual"},
    {"name": "within", "label": "Within tolerance", "field": "within"},
]


#: the balance factor's symbol in Markdown: an escaped underscore (two bare ones in a
#: line turn the text between them into italics)
F_B = "f\\_b"


def single_summary(study: Any) -> str:
    """The single-cylinder card's Markdown: the primary force, the peak resultant at the
    balance factor and its parts, and the balance factor of least peak."""
    return (
        f"Primary force **{study.primary_force:.1f} N**; with {F_B} = "
        f"{study.balance_factor:g}: peak resultant **{study.peak_resultant:.1f} N** "
        f"(in-line {study.in_line_amplitude:.1f} N, transverse "
        f"{study.transverse_amplitude:.1f} N)  \nLeast peak at {F_B} = "
        f"**{study.optimum_balance_factor:.3f}** ({study.optimum_peak_resultant:.1f} N)"
    )


def engine_factor_note(engine_factor: float | None, study_factor: float) -> str:
    """Beside the study: the balance factor the engine itself is balanced at (the Engine
    form's *Balance factor*, which the Results tab shows; None: no crank counterweights)
    and this study's, so two balancings of one crank are not read as one (docs/web.md,
    "Single cylinder tab")."""
    if engine_factor is None:
        engine = "the engine has no crank counterweights (Results tab)"
    else:
        engine = (
            f"the engine is balanced at {F_B} = {engine_factor:g} (the Engine form's "
            "*Balance factor*, shown in the Results tab)"
        )
    if engine_factor is not None and math.isclose(engine_factor, study_factor):
        return f"This study's {F_B} = {study_factor:g} is the engine's own: {engine}."
    return (
        f"This study is at {F_B} = {study_factor:g} (this tab's *Balance factor*); {engine}: "
        "two different balancings of the same crank."
    )


def rebalance_summary(reb: Any) -> str:
    """The rebalancing card's Markdown: the unbalance to remove, the balance factor
    achieved, the residual and the bob-weight."""
    return (
        f"Unbalance to remove **{reb.unbalance * 1e6:.1f} g·mm**; achieved {F_B} "
        f"{reb.achieved_balance_factor:.3f}; residual {reb.residual * 1e6:.2f} g·mm "
        f"({'within' if reb.passed else 'outside'} tolerance, {reb.status})  \n"
        f"Bob-weight {reb.bob_weight * 1e3:.1f} g"
    )


def depth_words(holes: Any) -> str:
    """What the depths of the plan are read to: "to the tip (118° drill point)" or "to the
    shoulder (...)" for a pointed drill, "(flat-bottomed)" for a 180° point."""
    to = depth_read_to(holes.point_angle, holes.depth_to)
    if not to:
        return "(flat-bottomed)"
    return f"{to.strip()} ({math.degrees(holes.point_angle):.4g}° drill point)"


def depth_limit_words(holes: Any) -> str:
    """The deepest hole the plan was checked against, to the tip, and where that limit
    comes from (the web's thickness, the drill's length or reach):
    :meth:`~crankbalance.physics.rebalancing.DrilledHoles.depth_limit` in the tab's words."""
    limit, words = holes.depth_limit(
        {"web_thickness": "Web thickness at the holes", "drill_length": "Drill length"}
    )
    return f"{limit * 1e3:.4g} mm to the tip ({words})"


def pass_columns(holes: Any) -> list[dict[str, Any]]:
    """:data:`PASS_COLUMNS` with the depth's header naming what it is read to."""
    to = depth_read_to(holes.point_angle, holes.depth_to)
    return [{**c, "label": f"Depth{to} [mm]"} if c["name"] == "depth" else c for c in PASS_COLUMNS]


def drilling_plan(result: Any) -> list[tuple[str, str]]:
    """The drilling plan of a rebalancing as (what, value) lines, from the library's
    :class:`~crankbalance.physics.single_cylinder.RebalanceResult` (its holes and last pass)."""
    holes = result.correction
    passes = len(result.iterations)
    verdict = (
        f"residual {abs(result.residual) * 1e6:.2f} g·mm "
        f"{'≤' if result.passed else '>'} tolerance {result.tolerance * 1e6:.2f} g·mm: "
        f"**{'PASS' if result.passed else 'FAIL'}**"
    )
    if passes == 0:
        return [("Holes", "none: the unbalance to remove is within the tolerance"), ("", verdict)]
    last = result.iterations[-1]
    axial = holes.direction == "axial"
    return [
        (
            "Holes",
            f"{holes.number} per web on {holes.webs} webs ({holes.number * holes.webs} in all), "
            + ("axial (parallel to the crank axis)" if axial else "radial, inward from the rim"),
        ),
        ("Drill diameter", f"{holes.diameter * 1e3:.4g} mm"),
        ("Depth", f"{last.depth * 1e3:.3f} mm {depth_words(holes)}"),
        ("Deepest possible", depth_limit_words(holes)),
        (
            "Radius" if axial else "Rim radius",
            f"{holes.radius * 1e3:.4g} mm from the crank axis",
        ),
        ("Angle", "180° from the crankpin (on the counterweight's centre line)"),
        (
            "Mass removed per web",
            f"{last.removed_mass / holes.webs * 1e3:.2f} g ({last.removed_mass * 1e3:.2f} g "
            "in all)",
        ),
        ("Passes", f"{passes} ({result.status}); {verdict}"),
    ]


def pass_rows(result: Any) -> list[dict[str, Any]]:
    """The passes of a rebalancing as rows of :data:`PASS_COLUMNS` (mm, g, g·mm)."""
    return [
        {
            "iteration": it.iteration,
            "radius": f"{it.correction_radius * 1e3:.3f}",
            "mass": f"{it.correction_mass * 1e3:.3f}",
            "depth": f"{it.depth * 1e3:.3f}",
            "removed": f"{it.removed_mass * 1e3:.3f}",
            "residual": f"{it.residual * 1e6:.3f}",
            "within": "yes" if it.within_tolerance else "no",
        }
        for it in result.iterations
    ]


def rotor_mass_note(iso: dict[str, Any], given: str) -> str:
    """Beside the ISO result: the rotor mass used, and when none was given, its stand-in
    named with what it does to the tolerance."""
    if given.strip():
        return f"Rotor mass {iso['rotor_mass']:.3f} kg, as given."
    return (
        f"**Rotor mass not given:** the crank's rotating masses ({iso['rotor_mass']:.3f} kg) "
        "stand in for it. The whole crank is heavier, so this tolerance is tighter than "
        "ISO 21940-11 asks; enter the crank's mass under *Rotor mass*."
    )


class SingleTab(StudyTab):
    name = "single"
    what = "the single-cylinder study"
    prefixes = ("sc_", "rb_")
    result: Any = None
    rebalanced: Any = None

    def build(self) -> None:
        self.rerun_note()
        with ui.row().classes("w-full items-start gap-4"):
            with ui.card():
                ui.label("Balance factor study").classes("text-subtitle1")
                self.settings("sc_cylinder", "sc_balance_factor")
                with button_row():
                    ui.button("Compute study", on_click=self.run_study).props("color=primary").mark(
                        "run-single"
                    )
                    self.cancel_button()
                # at most 40 rem wide: the note on the engine's balance factor wraps
                self.single_summary = (
                    ui.markdown("").style("max-width: 40rem").mark("single-summary")
                )
            with ui.card():
                ui.label("ISO 21940-11 check").classes("text-subtitle1")
                self.settings("sc_grade", "sc_rotor_mass", "sc_residual")
                self.iso_summary = ui.markdown("").mark("iso-summary")
                self.iso_note = ui.markdown("").classes("text-orange-10").mark("iso-rotor-mass")
            with ui.card():
                ui.label("Rebalancing after new parts").classes("text-subtitle1")
                self.settings(
                    "rb_new_reciprocating",
                    "rb_new_rotating",
                    "rb_cw_mass",
                    "rb_cw_radius",
                    "rb_hole_diameter",
                    "rb_point_angle",
                )
                self.choice("rb_depth_to")
                self.settings("rb_holes", "rb_hole_radius", "rb_web_thickness", "rb_drill_length")
                self.rebalance_summary = ui.markdown("").mark("rebalance-summary")
            with ui.card().classes("grow max-w-full"):
                ui.label("Drilling plan").classes("text-subtitle1")
                self.plan = ui.markdown("Compute the study for the drilling plan.").mark(
                    "drilling-plan"
                )
                self.passes = (
                    ui.table(columns=PASS_COLUMNS, rows=[], row_key="iteration")
                    .classes("max-w-full")
                    .props("dense wrap-cells")
                    .mark("drilling-passes")
                )
                self.passes.set_visibility(False)
        with ui.grid().classes("w-full grid-cols-1 md:grid-cols-2"):
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
            self.card("drilling", "Drilling plan to scale", self._drawing)

    def choice(self, key: str) -> None:
        """The select of a setting that is a choice among words (:data:`CHOICES`), kept in
        the project's settings like the text settings of :meth:`settings`: its label from
        the options schema, its message beside it, an edit clears the shown result, a
        loaded project sets it."""
        assert key.startswith(self.prefixes), f"{key} is no setting of the {self.name} tab"
        label = studies.SETTING_FIELDS[key][0]
        page = self.page

        def changed(event: Any) -> None:
            page.project.settings[key] = "" if event.value is None else str(event.value)
            page.show_setting_errors()
            self.settings_changed()

        element = (
            ui.select(
                list(CHOICES[key]),
                label=label,
                value=str(page.project.settings.get(key, "")) or None,
                on_change=changed,
            )
            .classes("w-64")
            .props(f"data-testid=setting-{key}")
            .mark(f"setting-{key}")
            .without_auto_validation()
        )
        page.setting_inputs[key] = element

    def clear(self) -> None:
        self.result = self.rebalanced = None
        for summary in (self.single_summary, self.iso_summary, self.iso_note):
            summary.set_content("")
        self.rebalance_summary.set_content("")
        self.plan.set_content("Compute the study for the drilling plan.")
        self.passes.rows = []
        self.passes.set_visibility(False)
        for card in self.cards:
            card.refresh()

    def _drawing(self) -> Any | None:
        c = self.page.project.computed
        if self.rebalanced is None or c is None:
            return None
        crank_radius = float(c.analysis.model.crank_radius)
        return plot_or_none("drilling_plan", self.rebalanced, crank_radius)

    async def run_study(self) -> None:
        c = self.study_ready()
        if c is None:
            return
        s = self.page.project.settings
        started = self.stamp()
        try:
            studies.check_single_cylinder(c, s)  # its settings, before it starts
            done = await self.in_worker(self.what, studies.single_cylinder, c, dict(s))
        except InputError as error:
            self.result = self.rebalanced = None
            self.plan.set_content(f"No drilling plan: {show_error(self.page, error, ALIASES)}")
            self.passes.set_visibility(False)
            for card in self.cards:
                card.refresh()
            return
        if done is None:
            self.plan.set_content(CANCELLED)
            return
        if not self.owns(started):
            return
        study, iso, reb = done
        self.result, self.rebalanced = study, reb
        from ..studies.engine import balance_options

        counterweights = balance_options(c.spec)[0]
        factor = None if counterweights is None else float(counterweights.balance_factor)
        self.single_summary.set_content(
            f"{single_summary(study)}\n\n{engine_factor_note(factor, study.balance_factor)}"
        )
        verdict = iso["verdict"]
        self.iso_summary.set_content(
            f"{iso['grade'].name} at {iso['speed'] * 30 / 3.141592653589793:.0f} rpm, rotor "
            f"{iso['rotor_mass']:.3f} kg: U\\_per = **{iso['permissible'] * 1e6:.2f} g·mm**"
            + (
                ""
                if verdict is None
                else f"  \nMeasured {verdict.residual * 1e6:.2f} g·mm: **"
                f"{'PASS' if verdict.passed else 'FAIL'}** ({verdict.ratio * 100:.0f} %)"
            )
        )
        self.iso_note.set_content(rotor_mass_note(iso, str(s.get("sc_rotor_mass", ""))))
        self.rebalance_summary.set_content(rebalance_summary(reb))
        lines = [f"**{what}:** {value}" if what else value for what, value in drilling_plan(reb)]
        self.plan.set_content("  \n".join(lines))
        self.passes.columns = pass_columns(reb.correction)
        self.passes.rows = pass_rows(reb)
        self.passes.set_visibility(bool(reb.iterations))
        self.passes.update()
        for card in self.cards:
            card.refresh()
