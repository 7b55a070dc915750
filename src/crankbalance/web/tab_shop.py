"""The Balance shop tab: weighed parts to matched sets, bob-weights, a hole plan and the
ISO 21940-11 sign-off (issue 16; docs/balance_shop.md, "Commands and the shop sheet").

The parts file is pasted (or loaded from ``examples/v8_parts.csv``); the engine is the
page's current engine; the settings are those of :class:`crankbalance.schema.settings.ShopOptions`
as a shop person types them (units in the text). The run is
:func:`crankbalance.studies.shop.shop_study` in a worker process (:mod:`.pool`); without
readings only the parts study is shown. The result belongs to the engine and the settings
it was run for (the never-stale rule of :class:`~.widgets.StudyTab`): once either changes
it is cleared and the tab says to re-run. "Shop sheet HTML" downloads
:func:`crankbalance.output.shop_sheet.sheet_html`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from nicegui import run, ui

from ..errors import InputError
from ..output.figures.shop import hole_plan
from ..output.format import plural, text
from ..schema.settings import ShopOptions
from .widgets import (
    StudyTab,
    TabSettingsMixin,
    button_row,
    from_schema,
    schema_choices,
    send_download,
)

#: the worked example's parts file (docs/balance_shop.md)
EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "v8_parts.csv"
#: the first line of the example (a comment naming the V8 it weighs): parts that start
#: with it are the example's (:func:`parts_summary`)
EXAMPLE_HEADER = "# Parts of a 90 deg V8"
#: the tab's settings: key -> (label, default, hint); "parts" is the pasted parts file
SETTINGS: dict[str, tuple[str, str, str]] = {
    # the parts file and the two readings are the page's own inputs (the command line reads
    # a file and --reading-1/--reading-2 options), read by parse() below
    "parts": ("Parts (CSV)", "", "part,id,mass [g],big_end [g],small_end [g]"),
    "fraction": from_schema(ShopOptions, "fraction", hint="e.g. 50% or 0.5"),
    "reading_1": ("Reading, plane 1", "", "e.g. 12.5 g @ 40 mm, 35 deg"),
    "reading_2": ("Reading, plane 2", "", "e.g. 8 g @ 40 mm, 200 deg"),
    "convention": from_schema(ShopOptions, "convention"),
    "measuring_planes": from_schema(ShopOptions, "measuring_planes", hint="e.g. 0 mm, 400 mm"),
    "correction_planes": from_schema(ShopOptions, "correction_planes", hint="e.g. 50 mm, 350 mm"),
    "hole_diameter": from_schema(ShopOptions, "hole_diameter", hint="e.g. 8 mm"),
    "hole_radius": from_schema(ShopOptions, "hole_radius", hint="e.g. 45 mm"),
    "max_depth": from_schema(ShopOptions, "max_depth", hint="e.g. 15 mm"),
    # the select starts on the tip (the schema leaves it to the study: the tip)
    "depth_to": from_schema(ShopOptions, "depth_to", default="tip"),
    # the drill the sheet prints ("Ø8 mm, point 118°, axial"), and the web it must fit in
    "point_angle": from_schema(ShopOptions, "point_angle", hint="e.g. 118 deg (180 deg: flat)"),
    "direction": from_schema(ShopOptions, "direction"),
    "web_thickness": from_schema(
        ShopOptions, "web_thickness", hint="e.g. 14 mm (empty: the drill's reach alone)"
    ),
    "rotor_mass": from_schema(ShopOptions, "rotor_mass", hint="e.g. 25 kg"),
    "bearings": from_schema(
        ShopOptions, "bearings", hint="e.g. -20 mm, 420 mm (empty: the correction planes)"
    ),
    "grade": from_schema(ShopOptions, "grade", hint="e.g. G6.3"),
}
CHOICES = {
    "convention": schema_choices(ShopOptions, "convention"),
    "depth_to": schema_choices(ShopOptions, "depth_to"),
    "direction": schema_choices(ShopOptions, "direction"),
}
#: settings that only the hole plan needs (the parts study runs without them)
PLAN = ("measuring_planes", "correction_planes", "hole_radius", "rotor_mass", "bearings")


def parse(texts: dict[str, str]) -> tuple[Any, Any]:
    """The inventory and the :class:`~crankbalance.schema.settings.ShopOptions` of the tab's
    texts; an :class:`InputError` names the setting's key (``parts`` for the parts file)."""
    from ..io.parts_file import parts_from_csv
    from ..schema.settings import parse_options

    values = {k: (texts.get(k, "").strip() or None) for k in SETTINGS}
    if values["parts"] is None:
        raise InputError("parts", None, "paste a parts file (CSV) or load the example")
    try:
        inventory = parts_from_csv(values["parts"], source="parts")
    except InputError as error:
        raise InputError("parts", None, str(error)) from None
    readings = [values["reading_1"], values["reading_2"]]
    if readings.count(None) == 1:
        missing = "reading_1" if readings[0] is None else "reading_2"
        raise InputError(missing, None, "is required: give both readings or none")
    given: dict[str, Any] = {
        k: v for k, v in values.items() if k not in ("parts", "reading_1", "reading_2")
    }
    if None in readings:  # no readings: the parts study only
        given = {k: v for k, v in given.items() if k not in PLAN}
        given["depth_to"] = None
    else:
        for key in PLAN[:-1]:
            if given[key] is None:
                raise InputError(key, None, "is required to plan the holes")
        given["reading"] = readings
    try:
        options = parse_options(ShopOptions, given)
    except InputError as error:
        if error.field == "reading":
            index = 2 if error.value == readings[1] else 1
            raise InputError(f"reading_{index}", error.value, error.allowed) from None
        raise
    return inventory, options


def example_name(parts: str) -> str | None:
    """The engine the pasted ``parts`` are the worked example of, from the example's first
    line ("Parts of a 90 deg V8 (small-block, 4.030 in bore, 5.7 in rods)"); None when
    they are the user's own."""
    if not parts.startswith(EXAMPLE_HEADER):
        return None
    return parts.splitlines()[0].lstrip("# ").split(", weighed")[0]


def fit_words(sets: int, cylinders: int, example: str | None) -> str:
    """Before the run, what the shop will do with parts that make ``sets`` sets (the fewest
    parts of a kind) on an engine of ``cylinders``: "" when they fit; on another engine
    that the example is another engine's (``example``: :func:`example_name`), and that the
    sets beyond the cylinders stay spare, or that the parts are too few."""
    if sets == cylinders:
        return ""
    words = f"The example: {example[0].lower()}{example[1:]}. " if example else ""
    words += f"This engine has {plural(cylinders, 'cylinder')}: "
    if sets > cylinders:
        words += (
            f"the shop matches {plural(cylinders, 'set')} from parts for {sets}, "
            "the other parts stay spare (the result lists them)"
        )
    else:
        words += f"the parts make {plural(sets, 'set')} only, too few to run"
    return words + ("; paste this engine's own parts." if example else ".")


def parts_summary(p: Any, example: str | None) -> str:
    """The shop's summary of a parts study ``p`` (``PartsStudy``): the engine, the matching
    and its spreads, the material to remove; the parts in no set (the command line's words,
    :func:`~crankbalance.studies.shop.spares_words`); and, with ``example`` (the parts are
    the worked example's, :func:`example_name`) on an engine of another cylinder count,
    whose parts they are."""
    from ..studies.shop import spares_words

    m = p.matching
    line = (
        f"{p.engine}: {plural(p.cylinders, 'cylinder')}, matching {m.method} ({m.status}); "
        f"spread {text(m.reciprocating_spread, 'mass', 4)} reciprocating, "
        f"{text(m.rotating_spread, 'mass', 4)} rotating; material to remove "
        f"{text(m.removed_total, 'mass', 4)} (every part machined to the lightest: "
        f"{text(p.machined.removed_total, 'mass', 4)})."
    )
    spares = spares_words(p)
    if spares:
        line += f"  \n{spares}."
        if example:
            line += (
                f"  \nThe example is not this engine's: {example}; paste this engine's own parts."
            )
    return line


class ShopTab(TabSettingsMixin, StudyTab):
    settings_table = SETTINGS
    parse_settings = staticmethod(parse)
    fallback = "parts"
    choices = CHOICES
    multiline = ("parts",)
    name = "shop"
    what = "the balance shop"

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            self.settings_card(
                "Parts and readings",
                "w-96",
                before_run=lambda: (
                    ui.button("Load example", on_click=self.load_example)
                    .props("outline")
                    .mark("shop-example")
                ),
            )
            with ui.card().classes("min-w-0").style("flex: 1 1 0"):
                with ui.element("div").classes(
                    "w-full flex flex-wrap items-center justify-between gap-1"
                ):
                    ui.label("Results").classes("text-subtitle1")
                    with button_row():
                        ui.button("Shop sheet HTML", on_click=self.download).props(
                            "flat dense size=sm"
                        ).mark("shop-sheet")
                self.rerun_note()
                self.summary = (
                    ui.markdown("").props("data-testid=shop-summary").mark("shop-summary")
                )
                self.verdict = (
                    ui.label("")
                    .classes("text-body1")
                    .props("data-testid=shop-verdict")
                    .mark("shop-verdict")
                )
                ui.label("Matched sets").classes("text-subtitle2")
                self.sets = self._table("shop-sets", "cylinder")
                ui.label("Bob-weights per crankpin").classes("text-subtitle2")
                self.bobs = self._table("shop-bobweights", "pin")
        self.card("shop-holes", "Hole plan", self._holes)
        # what the shop will do with these parts on this engine, below the parts (before Run)
        parts = self.fields["parts"]
        card = parts.parent_slot.parent
        self.fit = (
            ui.label("")
            .classes("text-orange-10 text-body2")
            .props("data-testid=shop-fit")
            .mark("shop-fit")
        )
        self.fit.move(card, target_index=card.default_slot.children.index(parts) + 1)
        self.show_fit()

    def _table(self, testid: str, key: str) -> Any:
        return (
            ui.table(columns=[], rows=[], row_key=key)
            .classes("w-full")
            .props(f"dense flat data-testid={testid}")
            .mark(testid)
        )

    def load_example(self) -> None:
        if not EXAMPLE.is_file():
            ui.notify(f"The example {EXAMPLE.name} is not installed here", type="warning")
            return
        self.fields["parts"].set_value(EXAMPLE.read_text(encoding="utf-8"))

    # ------------------------------------------------------------------ settings
    def show_fit(self) -> None:
        """Below the parts, before the run: whether the pasted parts fit the form's engine
        (:func:`fit_words`; nothing while either is missing or the parts are unreadable)."""
        from ..io.parts_file import parts_from_csv

        words = ""
        c = self.page.project.computed
        model = None if c is None or c.analysis is None else c.analysis.model
        parts = self.texts.get("parts", "").strip()
        if model is not None and parts:
            try:
                inventory = parts_from_csv(parts, source="parts")
            except InputError:
                inventory = None
            if inventory is not None and inventory.kinds:
                sets = min(kind.count for kind in inventory.kinds)
                words = fit_words(sets, model.cylinders, example_name(parts))
        self.fit.set_text(words)
        self.fit.set_visibility(bool(words))

    def check(self) -> Any | None:
        parsed = super().check()
        self.show_fit()
        return parsed

    def show(self, c: Any) -> None:
        super().show(c)
        self.show_fit()

    def show_error(self, error: InputError) -> None:
        if error.field in self.fields and error.field != "parts":
            super().show_error(error)
        else:  # the parts table: its reader's own words (line and column)
            self.fields["parts"].error = f"{SETTINGS['parts'][0]}: {error.allowed}"

    # ------------------------------------------------------------------ StudyTab
    def clear(self) -> None:
        self.study = None
        self.summary.set_content("")
        self.verdict.set_text("")
        for table in (self.sets, self.bobs):
            table.rows = []
            table.update()
        for card in self.cards:
            card.refresh()

    # ------------------------------------------------------------------ run
    def study_function(self) -> Any:
        from ..studies.shop import shop_study

        return shop_study

    def show_study(self) -> None:
        p = self.study.parts
        m, b = p.matching, p.bob_weights
        example = example_name(str(self.fields["parts"].value or ""))
        self.summary.set_content(parts_summary(p, example))
        self.sets.columns = [
            {"name": "cylinder", "label": "cylinder", "field": "cylinder"},
            *({"name": k, "label": k, "field": k, "align": "left"} for k in m.kinds),
            {"name": "recip", "label": "reciprocating", "field": "recip"},
            {"name": "rot", "label": "rotating", "field": "rot"},
        ]
        self.sets.rows = [
            {
                "cylinder": c + 1,
                **dict(zip(m.kinds, m.ids[c], strict=True)),
                "recip": text(m.reciprocating[c], "mass", 5),
                "rot": text(m.rotating[c], "mass", 5),
            }
            for c in range(p.cylinders)
        ]
        self.sets.update()
        self.bobs.columns = [
            {"name": n, "label": label, "field": n}
            for n, label in (
                ("pin", "crankpin"),
                ("rods", "rods"),
                ("rot", "rotating"),
                ("recip", "reciprocating"),
                ("bob", "bob-weight"),
            )
        ]
        self.bobs.rows = [
            {
                "pin": t + 1,
                "rods": int(b.rods_on_pin[t]),
                "rot": text(b.rotating[t], "mass", 5),
                "recip": text(b.reciprocating[t], "mass", 5),
                "bob": text(b.bob_weight[t], "mass", 5),
            }
            for t in range(len(b.bob_weight))
        ]
        self.bobs.update()
        h = self.study.holes
        if h is None:
            self.verdict.set_text("No readings: no hole plan and no ISO check.")
        else:
            planes = "; ".join(
                f"plane {j + 1}: residual {text(abs(h.residual[j]), 'unbalance', 3)} of "
                f"{text(h.check.tolerance[j], 'unbalance', 3)}"
                for j in range(2)
            )
            verdict = "PASS" if h.check.passed else "FAIL"
            self.verdict.set_text(f"ISO 21940-11 {h.grade}: {verdict} ({planes})")
        for card in self.cards:
            card.refresh()

    def _holes(self) -> Any | None:
        holes = None if self.study is None else self.study.holes
        return None if holes is None else hole_plan(holes)

    async def download(self) -> None:
        from ..output.shop_sheet import sheet_html

        if self.study is None:
            ui.notify("Run the balance shop first", type="warning")
            return
        name = self.study.parts.engine.replace(" ", "-")
        page = await run.io_bound(sheet_html, self.study)
        if page is None:  # NiceGUI is shutting down
            return
        send_download(page, f"shop-{name}.html", "text/html")
