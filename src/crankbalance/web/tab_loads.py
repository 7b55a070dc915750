"""The Crank loads tab: main-bearing loads, friction and crank bending of the current engine
against the counterweight pattern and the balance factor (issue 18 item 4;
docs/main_bearings.md, "Sweep of patterns and balance factors").

The settings are those of ``crankbalance bearings-sweep`` (:class:`crankbalance.schema.settings.
BearingSweepOptions` and a few of :class:`~crankbalance.schema.settings.BearingOptions`, the rest
at their defaults), as typed. The run is :func:`crankbalance.studies.balance_loads.
bearing_sweep` in a worker process (:mod:`.pool`). The result belongs to the engine and
the settings it was run for (the never-stale rule of :class:`~.widgets.StudyTab`): once
either changes it is cleared and the tab says to re-run. Shown: a table (one row per
case, the CLI's columns, the suggested case and the Pareto set marked), the study's
summary (:meth:`~crankbalance.studies.balance_loads.SweepStudy.summary`, its warning
highlighted), the polar load diagrams of every pattern at the middle balance
factor overlaid, and the sweep figure (metrics against the balance factor, peak load per
bearing per case).
"""

from __future__ import annotations

from typing import Any

from nicegui import ui

from ..errors import InputError
from ..output.figures.loads import bearing_loads_figure, bearing_sweep_figure
from ..schema.settings import BearingOptions, BearingSweepOptions
from .form import label_of
from .widgets import StudyTab, TabSettingsMixin, from_schema, schema_choices

#: the line under the table that says what its short column names are
#: (:data:`crankbalance.studies.balance_loads.COLUMNS`)
COLUMN_NOTE = (
    "f_b: balance factor; CW kg: counterweight mass; worst: the bearing of the largest peak "
    "load; max N, mean N: its peak and mean load (each throw's load shared among the main "
    "bearings on either side of it; the Performance tab's peak bearing load is one "
    "cylinder's whole load on one bearing); journal N·m, pin N·m: the largest bending "
    "moment at a journal, at a crankpin; friction W: Coulomb friction of all main bearings; "
    "Frot N, Mrot N·m: force and couple of the rotating masses left after balancing; "
    "F1+ N, F1- N, M1+ N·m, M1- N·m: the first-order free force and couple left, forward (+) "
    "and backward (-) rotating."
)
#: the schema's default of the gas forces (the page's select says on or off)
GAS_DEFAULT = bool(BearingOptions.FIELDS["gas"].default)
#: the tab's settings: key -> (label, default, hint), each starting at the schema's default
#: (the command line's)
SETTINGS: dict[str, tuple[str, str, str]] = {
    # the page's patterns are separated by ";" (the command line gives --pattern per pattern)
    "patterns": from_schema(
        BearingSweepOptions,
        "patterns",
        default="; ".join(BearingSweepOptions.FIELDS["patterns"].default),
        hint="all, none, file or 0/1 per web (two per throw); patterns separated by ;",
    ),
    "balance_factors": from_schema(BearingSweepOptions, "balance_factors"),
    "crank_model": from_schema(BearingSweepOptions, "crank_model"),
    # a select of on and off, starting at the schema's default
    "gas": from_schema(BearingOptions, "gas", default="on" if GAS_DEFAULT else "off"),
    "speed": from_schema(BearingOptions, "speed"),
    "samples": from_schema(BearingOptions, "samples"),
    "bearing_stiffness": from_schema(
        BearingOptions, "bearing_stiffness", hint="empty: rigid, e.g. 5e8 N/m"
    ),
    "friction_coefficient": from_schema(BearingOptions, "friction_coefficient", hint="e.g. 0.005"),
}
CHOICES = {"crank_model": schema_choices(BearingSweepOptions, "crank_model"), "gas": ("on", "off")}
#: the settings of the sweep itself; the others are the loads' (BearingOptions)
SWEEP = ("patterns", "balance_factors", "crank_model")


def _items(text: str, separator: str) -> list[str] | None:
    items = [item.strip() for item in text.split(separator) if item.strip()]
    return items or None


def parse(texts: dict[str, str]) -> tuple[Any, Any]:
    """The :class:`~crankbalance.schema.settings.BearingSweepOptions` and
    :class:`~crankbalance.schema.settings.BearingOptions` of the tab's texts; an
    :class:`InputError` names the setting's key."""
    from ..schema.settings import parse_options

    values = {k: texts.get(k, "").strip() for k in SETTINGS}
    sweep = parse_options(
        BearingSweepOptions,
        {
            "patterns": _items(values["patterns"], ";"),
            "balance_factors": _items(values["balance_factors"], ","),
            "crank_model": values["crank_model"] or None,
        },
    )
    if values["gas"] not in CHOICES["gas"]:
        raise InputError("gas", values["gas"], "must be on or off")
    loads = parse_options(
        BearingOptions,
        {
            **{k: (v or None) for k, v in values.items() if k not in (*SWEEP, "gas")},
            "gas": values["gas"] == "on",
        },
    )
    return sweep, loads


def case_mark(n: int, summary: dict[str, Any]) -> str:
    """The mark of case ``n`` in the table: the study's suggested case and its Pareto set
    (the ``summary`` of the sweep's JSON)."""
    marks = ["suggested"] if n == summary["suggested"] else []
    if n in summary["pareto"]:
        marks.append("Pareto")
    return ", ".join(marks)


class LoadsTab(TabSettingsMixin, StudyTab):
    settings_table = SETTINGS
    parse_settings = staticmethod(parse)
    fallback = "patterns"
    choices = CHOICES
    name = "loads"
    what = "the crank loads sweep"

    def build(self) -> None:
        with ui.row().classes("w-full items-start gap-4"):
            self.settings_card("Patterns and balance factors", "w-96")
            with ui.card().classes("min-w-0").style("flex: 1 1 0"):
                ui.label("Bearing loads against balance").classes("text-subtitle1")
                self.rerun_note()
                self.summary = (
                    ui.markdown("").props("data-testid=loads-summary").mark("loads-summary")
                )
                self.warning = (
                    ui.label("")
                    .classes("text-body1 text-weight-bold bg-orange-2 q-pa-sm")
                    .props("data-testid=loads-warning")
                    .mark("loads-warning")
                )
                self.warning.set_visibility(False)
                self.table = (
                    ui.table(columns=[], rows=[], row_key="case")
                    .classes("w-full")
                    .props("dense flat data-testid=loads-cases")
                    .mark("loads-cases")
                )
                ui.label(COLUMN_NOTE).classes("text-caption text-grey-7").mark("loads-columns")
        self.card("loads-polar", "Polar load diagrams (middle balance factor)", self._polar)
        self.card("loads-sweep", "Loads, friction and bending against balance", self._sweep)

    # ------------------------------------------------------------------ StudyTab
    def clear(self) -> None:
        self.study = None
        self.summary.set_content("")
        self.warning.set_visibility(False)
        self.table.rows = []
        self.table.update()
        for card in self.cards:
            card.refresh()

    # ------------------------------------------------------------------ run
    def study_function(self) -> Any:
        from ..studies.balance_loads import bearing_sweep

        return bearing_sweep

    def work_check(self) -> Any:
        from ..studies.balance_loads import check_sweep_work

        return check_sweep_work

    def show_study(self) -> None:
        from ..output.format import number
        from ..studies.balance_loads import COLUMNS, case_rows
        from ..studies.loads import assumed_text

        data = self.study.to_dict()
        rows = case_rows(data)
        summary = data["summary"]
        lowest = rows[summary["lowest_load"]]
        s = data["settings"]
        assumed = assumed_text(s).replace("*", "\\*")  # a star marks the engine's values
        # the study's summary (the suggested case, the Pareto set), its warning highlighted;
        # a next step names the balance factor as the Engine form does
        words = self.study.summary(label_of("counterweights.balance_factor")).text
        lines = [t for t in words if not t.startswith("Warning: ")]
        self.summary.set_content(
            f"{data['engine']['name']}: {len(rows)} cases, {data['crank_model']} crank, "
            f"{'gas and inertia' if s['gas'] else 'inertia only'}.\n\n"
            + "\n\n".join(line.replace("*", "\\*") for line in lines)
            + f"\n\nLowest peak bearing load: {lowest[0]}"
            + ("" if lowest[1] is None else f" at balance factor {number(lowest[1], 3)}")
            + f" ({number(lowest[4], 5)} N on bearing {lowest[3]}).\n\nAssumed: {assumed}."
        )
        warning = summary["warning"]
        self.warning.set_text("" if not warning else f"Warning: {warning}.")
        self.warning.set_visibility(bool(warning))
        self.table.columns = [
            {"name": key, "label": label, "field": key, "align": "left" if i == 0 else "right"}
            for i, (key, label) in enumerate(COLUMNS)
        ] + [{"name": "mark", "label": "", "field": "mark", "align": "left"}]
        self.table.rows = [
            {
                "case": n,
                **{
                    key: "–" if v is None else (v if isinstance(v, (str, int)) else number(v, 5))
                    for (key, _), v in zip(COLUMNS, row, strict=True)
                },
                "mark": case_mark(n, summary),
            }
            for n, row in enumerate(rows)
        ]
        self.table.update()
        for card in self.cards:
            card.refresh()

    def _polar(self) -> Any | None:
        if self.study is None:
            return None
        factors = sorted(self.study.options.balance_factors)
        middle = factors[len(factors) // 2]
        cases = [
            c for c in self.study.cases if c.balance_factor in (None, middle)
        ]  # one per pattern
        labels = tuple(
            c.pattern + ("" if c.balance_factor is None else f", f_b {middle:.3g}") for c in cases
        )
        return bearing_loads_figure(
            [c.study for c in cases], self.study.options.crank_model, labels
        )

    def _sweep(self) -> Any | None:
        return None if self.study is None else bearing_sweep_figure(self.study)
