"""The Mounts tab: the powertrain of the current engine on its elastic mounts (issue 31
item 6; docs/mounts.md, docs/web.md "Mounts").

The tab needs an engine whose file has a ``[powertrain]`` table; for any other engine it says
so and offers the two worked examples of docs/mounts.md (``examples/mounts_inline4_car.toml``,
``examples/mounts_vtwin_motorcycle.toml``) as the current project. Its settings are those of
``crankbalance mounts`` (:class:`crankbalance.schema.settings.MountsOptions`, the schema's
titles, defaults and checks), as typed; the run is the registry's ``mounts`` study
(:func:`mounts_study`) in a worker process (:mod:`.pool`). The result belongs to the engine
and the settings it was run for (the never-stale rule of :class:`~.widgets.StudyTab`), and
is cleared while the engine form cannot be computed (the tab then says why). Shown: the
summary (statics, the torque-roll axis and the roll mode's angle to it, the crossings), the
six modes with their kinetic-energy table, the largest mount force per order, the layout
drawn with the powertrain, the mode shapes and the Campbell diagram with the force of every
mount over speed (the figures of :mod:`crankbalance.output.figures.mounts`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from nicegui import ui

from ..output.figures.mounts import (
    mode_play_script,
    mode_shapes_figure,
    mounts_figure,
    mounts_layout_figure,
)
from ..output.format import number
from ..schema.settings import MountsOptions, field_kind
from .widgets import (
    StudyTab,
    TabSettingsMixin,
    button_row,
    from_schema,
    on_a_phone,
    schema_choices,
)

#: the worked examples of docs/mounts.md: button label -> file (in a source checkout)
EXAMPLES_DIR = Path(__file__).resolve().parents[3] / "examples"
EXAMPLES = {
    "Inline-4 car, three mounts": EXAMPLES_DIR / "mounts_inline4_car.toml",
    "V-twin motorcycle, four mounts": EXAMPLES_DIR / "mounts_vtwin_motorcycle.toml",
}
#: the tab's settings: every field of MountsOptions, its title, default and hint the schema's
SETTINGS: dict[str, tuple[str, str, str]] = {
    name: from_schema(
        MountsOptions, name, hint="e.g. 0 mm, 0 mm, 100 mm" if name == "point" else ""
    )
    for name in MountsOptions.FIELDS
}
CHOICES = {"rotating": schema_choices(MountsOptions, "rotating")}
#: what the tab says of an engine without a [powertrain] table
NEEDS_POWERTRAIN = (
    "This engine has no [powertrain] table: the Mounts tab needs the powertrain's mass, centre "
    "of gravity, inertia and its mounts (docs/mounts.md, 'The [powertrain] table'). Add one to "
    "the engine file and load it above, or load a worked example:"
)
#: the energy table's columns: (JSON key of energy_percent, header)
ENERGY: tuple[tuple[str, str], ...] = tuple(
    (key, f"{key} %") for key in ("x", "y", "z", "roll", "pitch", "yaw")
)


#: on a phone (below 600 px) the 3-D figures' camera stands this much farther out: plotly
#: fits a scene to its height, and a phone's narrow figure cut the axes at both sides (the
#: layout, drawn to the data's proportions with the long crank axis across the view, needs
#: more than the mode shapes in their box)
PHONE_CAMERA = {"layout": 2.0, "modes": 1.5}


def _split(text: str) -> list[str]:
    return [p.strip() for p in text.replace(";", ",").split(",") if p.strip()]


def values_of(texts: dict[str, str]) -> dict[str, Any]:
    """The settings given by field (a text that is neither empty nor the schema's default as
    the field shows it: a default is not a setting given, so the combustion settings the
    tab shows do not count as typed without the gas torque); a list's text split."""
    out: dict[str, Any] = {}
    for name in MountsOptions.FIELDS:
        text = texts.get(name, "").strip()
        if text and text != SETTINGS[name][1]:
            out[name] = _split(text) if field_kind(MountsOptions, name)[0] == "list" else text
    return out


def parse(texts: dict[str, str]) -> tuple[dict[str, Any]]:
    """The tab's settings checked by the registry's ``mounts`` study (its model
    :class:`~crankbalance.schema.settings.MountsOptions`); the settings as given, for
    :func:`mounts_study`. An :class:`~crankbalance.errors.InputError` names the field."""
    from ..studies.registry import parse as parse_settings
    from ..studies.registry import study

    values = values_of(texts)
    parse_settings(study("mounts"), values, lambda name: name)
    return (values,)


def mounts_study(spec: Any, values: dict[str, Any]) -> Any:
    """The registry's ``mounts`` study of the engine ``spec`` with the settings given (run in
    a worker process: module-level, picklable arguments and result)."""
    from ..studies.registry import run

    return run("mounts", spec, values, naming=lambda name: name)


def mode_rows(data: dict[str, Any]) -> list[dict[str, str]]:
    """The modes table: frequency and per cent of kinetic energy by coordinate."""
    return [
        {
            "mode": str(m["mode"]),
            "frequency": number(m["frequency_Hz"], 5),
            **{key: number(m["energy_percent"][key], 3) for key, _ in ENERGY},
        }
        for m in data["modes"]
    ]


def order_rows(data: dict[str, Any]) -> list[dict[str, str]]:
    """The largest mount force per order over the speed range, its mount and speed, and the
    largest displacement of the point shown."""
    return [
        {
            "order": str(o["order"]),
            "mount": o["largest"]["mount"],
            "force": number(o["largest"]["force_N"], 5),
            "speed": number(o["largest"]["speed_rpm"], 5),
            "point": number(1000 * o["point_displacement_m"], 4),
            "point_speed": number(o["point_speed_rpm"], 5),
        }
        for o in data["orders"]
    ]


def summary_text(data: dict[str, Any]) -> str:
    """The summary (markdown): the powertrain, the statics, the torque-roll axis and the roll
    mode's angle to it, the crossings of the orders with the modes."""
    pt, st = data["powertrain"], data["statics"]
    axis = ", ".join(f"{v:+.3f}" for v in data["torque_roll_axis"])
    moved = ", ".join(f"{1000 * v:+.3f}" for v in st["cg_displacement_m"])
    crossings = ", ".join(
        f"order {c['order']} x mode {c['mode']} at {number(c['speed_rpm'], 4)} rpm"
        for c in data["crossings"]
    )
    loads = ", ".join(f"{m['mount']} {number(m['axial_N'], 4)} N" for m in st["mount_loads"])
    return (
        f"**{data['engine']['name']}**: powertrain {number(pt['mass_kg'], 4)} kg on "
        f"{len(data['mounts'])} mounts.\n\n"
        f"Statics (weight, mean torque {number(st['mean_torque_Nm'], 4)} N·m): the centre of "
        f"gravity moves {moved} mm (x, y, z); axial mount loads {loads}.\n\n"
        f"Torque-roll axis ({axis}); the roll mode (mode {data['roll_mode']}) turns "
        f"**{number(data['roll_mode_angle_to_torque_roll_axis_deg'], 3)} deg** from it.\n\n"
        "Orders crossing a mode in the speed range: " + (crossings or "none") + "."
    )


class MountsTab(TabSettingsMixin, StudyTab):
    settings_table = SETTINGS
    parse_settings = staticmethod(parse)
    fallback = "speed_samples"
    choices = CHOICES
    name = "mounts"
    what = "the mount study"

    def build(self) -> None:
        with ui.column().classes("w-full") as self.needs:
            ui.label(NEEDS_POWERTRAIN).classes("text-body1").props("data-testid=mounts-needs").mark(
                "mounts-needs"
            )
            with button_row():
                for label, path in EXAMPLES.items():
                    ui.button(label, on_click=lambda p=path: self.load_example(p)).props(
                        "outline"
                    ).mark(f"mounts-example-{path.stem}")
        self.needs.set_visibility(False)
        with ui.row().classes("w-full items-start gap-4") as self.body:
            self.settings_card("Speed range and loads", "w-96")
            with ui.card().classes("min-w-0").style("flex: 1 1 0"):
                ui.label("The powertrain on its mounts").classes("text-subtitle1")
                self.rerun_note()
                self.summary = (
                    ui.markdown("").props("data-testid=mounts-summary").mark("mounts-summary")
                )
                ui.label("Rigid-body modes (kinetic energy, per cent)").classes("text-subtitle2")
                self.modes_table = (
                    ui.table(
                        columns=[
                            {"name": "mode", "label": "mode", "field": "mode"},
                            {"name": "frequency", "label": "f [Hz]", "field": "frequency"},
                            *({"name": k, "label": h, "field": k} for k, h in ENERGY),
                        ],
                        rows=[],
                        row_key="mode",
                    )
                    .classes("w-full")
                    .props("dense flat data-testid=mounts-modes-table")
                    .mark("mounts-modes-table")
                )
                ui.label("Largest mount force per order over the speed range").classes(
                    "text-subtitle2"
                )
                self.orders_table = (
                    ui.table(
                        columns=[
                            # Quasar's default alignment (right): a column aligned left
                            # would need a class the page's stylesheet does not ship
                            {"name": k, "label": label, "field": k}
                            for k, label in (
                                ("order", "order"),
                                ("mount", "mount"),
                                ("force", "force [N]"),
                                ("speed", "at [rpm]"),
                                ("point", "point moves [mm]"),
                                ("point_speed", "at [rpm]"),
                            )
                        ],
                        rows=[],
                        row_key="order",
                    )
                    .classes("w-full")
                    .props("dense flat data-testid=mounts-orders-table")
                    .mark("mounts-orders-table")
                )
        self.card("mounts-layout", "Mount layout with the powertrain", self._layout)
        modes = self.card("mounts-modes", "Mode shapes", self._modes)
        with modes.card, button_row() as self.play_row:
            # the chosen mode's motion (issue 28, item 4): the figure's frames, run here so
            # that an interrupted animation's rejected promise is caught
            for label, play in (("▶ Play the mode", True), ("❚❚ Pause", False)):
                ui.button(
                    label,
                    on_click=lambda p=play: ui.run_javascript(mode_play_script(modes.plot.id, p)),
                ).props(
                    f"outline dense data-testid=mounts-modes-{'play' if play else 'pause'}"
                ).mark(f"mounts-modes-{'play' if play else 'pause'}")
        self.play_row.set_visibility(False)  # shown with a result
        self.card("mounts-forces", "Campbell diagram and mount forces over speed", self._forces)

    # ------------------------------------------------------------------ the engine
    def show(self, c: Any) -> None:
        super().show(c)
        has = c.spec.powertrain is not None
        self.needs.set_visibility(not has)
        self.body.set_visibility(has)
        for card in self.cards:
            card.card.set_visibility(has)

    def show_errors(self, errors: dict[str, str]) -> None:
        """While the engine form cannot be computed, no result is shown: the tab says why."""
        if self.page.fresh() is None:
            if self.result_for is not None or self.study is not None:
                self.drop("this engine")
            if self.rerun.visible:
                self.rerun.set_text(f"Not computed: {self.page.problem()}")
        elif self.rerun.text.startswith("Not computed: "):  # the form is valid again
            self.rerun.set_text("Not computed for this engine: re-run the study.")

    def load_example(self, path: Path) -> None:
        """Make a worked example of docs/mounts.md the current project."""
        from .project import Project

        if not path.is_file():
            ui.notify(f"The example {path.name} is not installed here", type="warning")
            return
        self.page.load(Project.from_text(path.read_text(encoding="utf-8"), path.name))

    # ------------------------------------------------------------------ StudyTab
    def clear(self) -> None:
        self.study = None
        self.play_row.set_visibility(False)  # nothing to play without a figure
        self.summary.set_content("")
        for table in (self.modes_table, self.orders_table):
            table.rows = []
            table.update()
        for card in self.cards:
            card.refresh()

    def study_function(self) -> Any:
        return mounts_study

    def show_study(self) -> None:
        data = self.study.to_dict()
        self.summary.set_content(summary_text(data))
        self.modes_table.rows = mode_rows(data)
        self.modes_table.update()
        self.orders_table.rows = order_rows(data)
        self.orders_table.update()
        self.play_row.set_visibility(True)
        for card in self.cards:
            card.refresh()

    def _layout(self) -> Any | None:
        return (
            None
            if self.study is None
            else on_a_phone(
                mounts_layout_figure(self.study), PHONE_CAMERA["layout"], legend_below=True
            )
        )

    def _modes(self) -> Any | None:
        if self.study is None:
            return None
        return on_a_phone(
            mode_shapes_figure(self.study, animate=True), PHONE_CAMERA["modes"], legend_below=True
        )

    def _forces(self) -> Any | None:
        return None if self.study is None else mounts_figure(self.study)
