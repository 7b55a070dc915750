"""The crank editor of the Engine tab: throw angles, custom throws and mass overrides.

Engines whose crank does not follow from the firing order (odd-fire V6/V10, a crossplane
inline-4) need ``crank_train.throw_angles`` or custom throws (``[[crank_train.throw]]``); a
split-pin vee needs neither (the Engine tab's Pin split field); cylinders or throws whose
parts differ need ``[[masses.override]]``. This editor shows them as rows of inputs; the
texts live in the :class:`~.project.Project` (``throw_angles``, ``throws``,
``overrides``), which turns them into the engine file and names a bad cell by its key
(``throw.2.banks``), so its message is shown under that cell. The 3-D view follows
through the page's update.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from nicegui import ui

from ..schema.engine import throw_count
from .form import MASS_FIELDS

if TYPE_CHECKING:
    from .context import TabContext

#: mass fields an override may change, with their labels
OVERRIDE_MASSES = {f.key: f.label for f in MASS_FIELDS}


def _deg(radians: float) -> str:
    """An angle [rad] as the editor writes it (degrees, 0 <= a < 360, no float noise)."""
    value = round(math.degrees(radians) % 360.0, 6) % 360.0
    return f"{value:g} deg"


def _mm(metres: float) -> str:
    return f"{round(metres * 1e3, 6):g} mm"


class CrankEditor:
    """Rows of inputs for the crank and the mass overrides of ``page.project``."""

    def __init__(self, page: TabContext) -> None:
        self.page = page
        self.cells: dict[str, Any] = {}
        self.notes: dict[str, Any] = {}
        self.shape: tuple[Any, ...] = ()

    @property
    def project(self) -> Any:
        return self.page.project

    # ------------------------------------------------------------------ layout
    def build(self) -> None:
        with ui.card().classes("w-full").mark("crank-editor"):
            ui.label("Crank editor").classes("text-subtitle1")
            ui.label(
                "Give the throw angles when the crank does not follow from the firing order "
                "(odd-fire V6/V10, crossplane inline-4), custom throws for any other crank, "
                "and masses that differ for some cylinders or throws. A split-pin vee needs "
                "neither: give its Pin split (and the rods' positions) in the engine's fields."
            ).classes("text-caption text-grey-8")
            self.body = ui.column().classes("w-full gap-2")
        self.rebuild()

    def _shape(self) -> tuple[Any, ...]:
        p = self.project
        return (
            p.texts.get("layout") == "custom",
            None if p.throw_angles is None else len(p.throw_angles),
            len(p.throws),
            len(p.overrides),
        )

    def rebuild(self) -> None:
        """Lay the rows out again (a row added or removed, the layout changed, a new
        project loaded)."""
        self.shape = self._shape()
        self.cells, self.notes = {}, {}
        self.body.clear()
        with self.body:
            if self.project.texts.get("layout") == "custom":
                self._throws()
            else:
                self._angles()
            ui.separator()
            self._overrides()
        self.show_errors(self.project.errors)

    def _cell(self, key: str, label: str, value: str, width: str = "w-32") -> Any:
        element = (
            ui.input(label=label, value=value, on_change=lambda e, k=key: self.edit(k, e.value))
            .classes(width)
            .props(f"dense hide-bottom-space data-testid={key.replace('.', '-')}")
            .mark(key.replace(".", "-"))
            .without_auto_validation()
        )
        self.cells[key] = element
        return element

    def _note(self, key: str) -> None:
        """A message line of a whole table (e.g. the count of throw angles)."""
        self.notes[key] = (
            ui.label("").classes("text-negative text-caption").mark(f"editor-note-{key}")
        )

    def _angles(self) -> None:
        p = self.project
        ui.switch(
            "Give the throw angles (else they follow from the firing order)",
            value=p.throw_angles is not None,
            on_change=lambda e: self.give_angles(bool(e.value)),
        ).props("data-testid=editor-give-angles").mark("editor-give-angles")
        if p.throw_angles is not None:
            with ui.row().classes("gap-2"):
                for k, text in enumerate(p.throw_angles):
                    self._cell(f"throw_angles.{k}", f"Throw {k + 1} angle", text, "w-28")
            self._note("throw_angles")
        ui.button(
            "Make custom throws from this crank", on_click=self.make_custom, icon="tune"
        ).props("outline dense data-testid=editor-make-custom").mark("editor-make-custom")

    def _throws(self) -> None:
        ui.label("Custom throws: axial position, throw angle, bank angle of each cylinder")
        for k, row in enumerate(self.project.throws):
            with ui.row().classes("items-start gap-2 w-full"):
                ui.label(f"{k + 1}").classes("q-pt-md w-4")
                self._cell(f"throw.{k}.position", "Position", row["position"], "w-28")
                self._cell(f"throw.{k}.angle", "Angle", row["angle"], "w-28")
                self._cell(f"throw.{k}.banks", "Banks (one per cylinder)", row["banks"], "w-56")
                ui.button(icon="delete", on_click=lambda k=k: self.remove("throws", k)).props(
                    f"flat dense round data-testid=throw-{k}-remove"
                )
        self._note("throw")
        ui.button("Add a throw", icon="add", on_click=self.add_throw).props(
            "outline dense data-testid=editor-add-throw"
        ).mark("editor-add-throw")

    def _overrides(self) -> None:
        ui.label("Mass overrides (later rows win)")
        for k, row in enumerate(self.project.overrides):
            with ui.row().classes("items-start gap-2 w-full"):
                ui.select(
                    {"cylinders": "Cylinders", "throws": "Throws"},
                    value=row["target"],
                    on_change=lambda e, k=k: self.edit(f"override.{k}.target", e.value),
                ).classes("w-28").props(f"dense data-testid=override-{k}-target")
                self._cell(f"override.{k}.numbers", "Numbers", row["numbers"], "w-28")
                ui.select(
                    OVERRIDE_MASSES,
                    value=row["mass"],
                    on_change=lambda e, k=k: self.edit(f"override.{k}.mass", e.value),
                ).classes("w-56").props(f"dense data-testid=override-{k}-mass")
                self._cell(f"override.{k}.value", "Value", row["value"], "w-28")
                ui.button(icon="delete", on_click=lambda k=k: self.remove("overrides", k)).props(
                    f"flat dense round data-testid=override-{k}-remove"
                )
        self._note("override")
        ui.button("Add a mass override", icon="add", on_click=self.add_override).props(
            "outline dense data-testid=editor-add-override"
        ).mark("editor-add-override")

    # ------------------------------------------------------------------ events
    def edit(self, key: str, value: Any) -> None:
        """A cell was changed: store its text and update the page."""
        text = "" if value is None else str(value)
        p = self.project
        parts = key.split(".")
        if parts[0] == "throw_angles" and p.throw_angles is not None:
            p.throw_angles[int(parts[1])] = text
        elif parts[0] == "throw":
            p.throws[int(parts[1])][parts[2]] = text
        elif parts[0] == "override":
            p.overrides[int(parts[1])][parts[2]] = text
        self.changed()

    def changed(self) -> None:
        self.project.validate()
        self.page.update_all()

    def _last_model(self) -> Any | None:
        c = self.project.computed
        return None if c is None else c.analysis.model

    def _throws_now(self) -> int:
        """The number of throws the form's layout and cylinders give (0 if unknown)."""
        try:
            cylinders = int(self.project.texts.get("cylinders", ""))
        except ValueError:
            return 0
        texts = self.project.texts
        w_type = texts.get("w_type", "").strip() or None  # a field of the Engine tab
        layout = texts.get("layout", "inline")
        split = layout == "vee" and bool(texts.get("pin_split", "").strip())
        return throw_count(layout, max(cylinders, 0), w_type, split)

    def give_angles(self, on: bool) -> None:
        """Switch the throw angles on (filled with the crank of the last valid engine,
        so the engine keeps its crank) or off (the firing order decides)."""
        p = self.project
        if on and p.throw_angles is None:
            model = self._last_model()
            n = self._throws_now()
            known = [] if model is None else [_deg(a) for a in model.throw_angle]
            p.throw_angles = (known + ["0 deg"] * n)[:n] if n else known
        elif not on:
            p.throw_angles = None
        self.changed()

    def make_custom(self) -> None:
        """Turn the last valid engine's crank into custom throws (layout ``custom``)."""
        model = self._last_model()
        if model is None:
            ui.notify("Correct the engine first (fields marked in red)", type="warning")
            return
        p = self.project
        p.throws = [
            {
                "position": _mm(model.throw_position[t]),
                "angle": _deg(model.throw_angle[t]),
                "banks": ", ".join(
                    f"{round(math.degrees(b), 6):g} deg"
                    for c, b in enumerate(model.cylinder_bank)
                    if model.cylinder_throw[c] == t
                ),
            }
            for t in range(len(model.throw_angle))
        ]
        p.throw_angles = None
        self._renumber(model)
        # the throws carry their positions and banks: the crank pitch and the bank angle
        # describe nothing of a custom crank (a saved file holds neither); a split vee's pins
        # carry its pin split and its rods' positions (each rod centred on its own pin)
        cleared = ["bank_angle", "crank_pitch"]
        if p.texts.get("layout") == "vee" and p.texts.get("pin_split", "").strip():
            cleared += ["pin_split", "rod_positions"]
        for key, value in [("layout", "custom"), *((k, "") for k in cleared)]:
            p.texts[key] = value  # first: the inputs' change events then find nothing new
            self.page.inputs[key].set_value(value)
        self.changed()

    def _renumber(self, model: Any) -> None:
        """Custom throws number their cylinders throw after throw: a given firing order
        (in crankbalance's numbers) is rewritten in the new numbers, a maker's numbering
        becomes the maker's numbers of the new cylinders (the order typed in them stays)."""
        texts = self.project.texts
        new: dict[int, int] = {}  # old cylinder index -> new number
        for t in range(model.throws):
            for c in range(model.cylinders):
                if model.cylinder_throw[c] == t:
                    new[c] = len(new) + 1
        changed: dict[str, str] = {}
        if model.maker_number is not None:
            maker = [0] * model.cylinders
            for c, m in enumerate(model.maker_number):
                maker[m - 1] = new[c]
            changed = {"maker_numbers": ", ".join(map(str, maker)), "numbering": ""}
        elif texts.get("firing_order", "").strip():
            changed = {"firing_order": ", ".join(str(new[c - 1]) for c in model.firing_order)}
        for key, value in changed.items():
            texts[key] = value
            element = self.page.inputs[key]
            element.set_value((value or None) if isinstance(element, ui.select) else value)

    def add_throw(self) -> None:
        p = self.project
        last = p.throws[-1] if p.throws else {"position": "0 mm", "angle": "0 deg"}
        p.throws.append({"position": last["position"], "angle": last["angle"], "banks": "0 deg"})
        self.changed()

    def add_override(self) -> None:
        self.project.overrides.append(
            {"target": "cylinders", "numbers": "1", "mass": "piston", "value": ""}
        )
        self.changed()

    def remove(self, table: str, k: int) -> None:
        del getattr(self.project, table)[k]
        self.changed()

    # ------------------------------------------------------------------ messages
    def show_errors(self, errors: dict[str, str]) -> None:
        """Messages under the cells (and tables) they concern; rows laid out again first
        when their number or the layout changed."""
        if self._shape() != self.shape:
            self.rebuild()
            return
        for key, element in self.cells.items():
            element.error = errors.get(key)
        for key, label in self.notes.items():
            label.set_text(errors.get(key, ""))
