"""The Explorer tab: every firing order and crank of a layout (docs/explorer.md), ranked.

The problem (layout, cylinders, strokes, bank angle, crank family), the two objectives of
the scatter and Pareto set, a filter and the rows of the table are this tab's own settings:
they are not part of the engine, and the result belongs to them (the never-stale rule of
:class:`~.widgets.StudyTab`, with the settings in place of the engine): once a setting is
changed the result is cleared and the tab says to re-run. The run is
:func:`crankbalance.studies.explore.run` in a worker process (:mod:`.pool`), on the plain engine
of the enumeration (``orders.PLAIN``), for problems of at most :data:`MAX_INDICES` firing
orders; larger ones are for ``crankbalance explore --workers N``.

The problem starts from the page's engine when the tab is opened (:func:`engine_problem`:
its layout, cylinders, strokes and bank angle, where the explorer enumerates that layout in
the page's budget; else the schema's defaults, and one line says why), and a line above the
settings says which problem is explored and whether it is the page's engine's.

A click on a row of the table (or on a point of the scatter) loads that candidate as the
current engine: the form's layout, cylinders, strokes, bank angle, firing order and throw
angles are set, the rest of the engine (masses, geometry) is kept.
"""

from __future__ import annotations

import functools
import math
import threading
from typing import Any

import numpy as np
from nicegui import ui

from ..errors import InputError
from ..output.figures.explore import FREE_COLUMN, column_words, explore_candidate, explore_scatter
from ..schema.settings import ExploreOptions
from . import studies
from .widgets import StudyTab, TabSettingsMixin, fmt_g, from_schema, schema_choices

#: most firing orders (indices of the enumeration) the page explores in its own process
MAX_INDICES = 50_000
#: the tab's settings: key -> (label, default, hint)
#: most rows of the tab's table (the command line's top-N may ask for more)
MAX_ROWS = 1000
SETTINGS: dict[str, tuple[str, str, str]] = {
    "layout": from_schema(ExploreOptions, "layout"),
    "cylinders": from_schema(ExploreOptions, "cylinders", hint="e.g. 6"),
    "strokes": from_schema(ExploreOptions, "strokes"),  # a select of 4 and 2
    "bank_angle": from_schema(ExploreOptions, "bank_angle", hint="vee, W and VR only, e.g. 90 deg"),
    "crank": from_schema(ExploreOptions, "crank"),
    # the figure's two objectives are the page's own (the command line gives --objectives)
    "x": ("Objective (x axis)", "M1", "a column, e.g. F2, M1, X1p5"),
    "y": ("Objective (y axis)", "M2", "a column, e.g. M2, cw_mass"),
    "filter": from_schema(ExploreOptions, "filter", hint="e.g. F1 == 0 and M1 == 0 (empty: all)"),
    "top": from_schema(ExploreOptions, "top", hint=f"1 to {MAX_ROWS}"),
}
CHOICES = {
    "layout": schema_choices(ExploreOptions, "layout"),
    "strokes": ("4", "2"),  # the schema's whole number, 2 or 4
    "crank": schema_choices(ExploreOptions, "crank"),
}
#: the table's key: the largest moment left after crank counterweights
KEY = "residual_M_Nm"
#: what the table's column ``equiv`` counts
EQUIVALENTS_NOTE = (
    "*Orders giving it*: how many firing orders of the problem give this same engine "
    "(renumbered from the other end, run backwards or mirrored: the same forces, moments "
    "and excitations); the row shows the first of them."
)


#: what the table says of its first rows when they tie on every free force and moment
TIE_NOTE = (
    "**Rows 1 to {n} tie**: these firing orders are equivalent in free forces and moments "
    "(every order up to {orders}, forward and backward, equal within round-off) and so in "
    "the balancing columns; what tells them apart is the firing sequence, in the columns "
    "after *orders giving it*: {columns}."
)
#: the note of tied rows that nothing computed tells apart
TIE_SAME = (
    "**Rows 1 to {n} tie**: these firing orders are equivalent in free forces and moments "
    "(every order up to {orders}, forward and backward, equal within round-off) and so in "
    "the balancing columns; neither the successive firings on neighbouring throws, the "
    "firing sequence per bank nor the torsional excitation of the minor orders (linear mode "
    "shape) tells them apart."
)
#: the tie-breaking columns: key -> (label, what the note says of it)
TIE_COLUMNS = {
    "neighbours": (
        "successive firings on neighbouring throws",
        "*successive firings on neighbouring throws* (a main-bearing load proxy: the "
        "bearing between two throws fired one after the other is loaded twice in a row; "
        "fewer is kinder to the main bearings)",
    ),
    "banks": ("firing sequence per bank", "*the firing sequence per bank*"),
    "linear": (
        "torsional excitation, order {k}, linear mode [-]",
        "*the torsional excitation of the minor orders below the first major one* with a "
        "linear mode shape (1 at cylinder 1 down to 1/C at the last, the crank's first "
        "torsional mode with its node beyond the flywheel; with equal weights every even "
        "firing order has the same excitation), where the tied orders differ",
    ),
}
#: bank names of the tie-breaking column, by increasing bank angle
BANK_NAMES = "ABCDEFGH"


def tied(rows: dict[str, Any], problem: Any, shown: int) -> int:
    """How many of the first ``shown`` rows of the explorer's ``rows`` (by the table's key)
    tie with the first on every free force and moment column (``F<n>``, ``M<n>`` and their
    forward and backward parts): equal within the round-off of
    :func:`crankbalance.physics.explore.rank.tolerances` for ``problem``'s engine. 1 when
    the second row differs (or there is one row)."""
    from ..physics.explore import rank

    names = [n for n in rows if FREE_COLUMN.match(n)]
    shown = min(shown, np.asarray(rows["index"]).size)
    if shown < 2 or not names:
        return min(shown, 1)
    values = np.array([np.asarray(rows[n][:shown], dtype=float) for n in names]).T
    tolerance = rank.tolerances(names, problem.topology)
    same = np.all(np.abs(values - values[0]) <= tolerance, axis=1)
    return int(shown if same.all() else np.argmin(same))


def tie_columns(rows: dict[str, Any], problem: Any, n: int) -> dict[str, list[str]]:
    """What tells the first ``n`` tied rows apart (:func:`tied`), as the table's texts per
    column (:data:`TIE_COLUMNS`; only the columns whose texts differ among them): the
    successive firings on neighbouring throws, the firing sequence per bank (engines of
    several banks), and the torsional excitation with a linear mode shape of each minor
    order below the first major one (per
    :func:`crankbalance.physics.explore.merit.torsional_excitation`) where the rows differ.
    Each row's fire angles come from its candidate (``orders.chunk`` of its index)."""
    from ..physics.explore import merit
    from ..physics.explore import orders as enumeration
    from ..results import ROUND_OFF

    topology = problem.topology
    slot = np.unique(topology.throw_position, return_inverse=True)[1].reshape(-1)
    throw = slot[np.asarray(topology.cylinder_throw)]  # each cylinder's place along the crank
    banks = np.unique(topology.cylinder_bank, return_inverse=True)[1].reshape(-1)
    sequences = [[int(c) for c in rows["firing_order"][k]] for k in range(n)]
    out: dict[str, list[str]] = {"neighbours": []}
    for seq in sequences:
        pairs = zip(seq, seq[1:] + seq[:1], strict=True)
        out["neighbours"].append(str(sum(abs(throw[a - 1] - throw[b - 1]) == 1 for a, b in pairs)))
    if banks.max() > 0:
        out["banks"] = [
            ", ".join(
                f"{BANK_NAMES[b]} {'-'.join(str(c) for c in seq if banks[c - 1] == b)}"
                for b in range(int(banks.max()) + 1)
            )
            for seq in sequences
        ]
    fire = np.concatenate(
        [
            enumeration.chunk(problem, i, i + 1).fire_angle
            for i in (int(v) for v in rows["index"][:n])
        ]
    )
    ks = merit.torsion_orders(int(problem.strokes), 8)
    uniform = merit.torsional_excitation(fire[:1], np.ones(fire.shape[1]), ks)[0]
    major = ks[np.flatnonzero(uniform >= 1 - 1e-9)]
    low = ks[ks < major[0]] if major.size else ks
    linear = merit.torsional_excitation(fire, merit.mode_weights(topology, "linear"), low)
    for j, k in enumerate(low):
        if np.ptp(linear[:, j]) > ROUND_OFF:
            out[f"X{k:g}"] = [f"{v:.3f}" for v in linear[:, j]]
    return {key: texts for key, texts in out.items() if len(set(texts)) > 1}


@functools.lru_cache(maxsize=8)
def _columns(orders: int = 8) -> tuple[str, ...]:
    """The explorer's columns (those of the inline-4, the same for every problem)."""
    from ..physics.explore import merit
    from ..physics.explore import orders as enumeration

    problem = enumeration.problem("inline", 4, 4)
    return tuple(merit.merit(enumeration.chunk(problem, 0, 1), orders=orders))


def parse(texts: dict[str, str]) -> tuple[Any, tuple[str, str], ExploreOptions, int, float | None]:
    """The problem, the two objectives, the settings of the study ``explore`` (the tab's
    objectives, filter and the table's key :data:`KEY`), the table's rows and the bank angle
    [rad] from the tab's texts; an :class:`InputError` names the setting's key."""
    from ..physics.explore import orders, rank
    from ..schema.settings import parse_options

    values = {k: (texts.get(k, "").strip() or None) for k in SETTINGS}
    columns = _columns()
    x = rank.column_name(values["x"] or "", columns, "x")
    y = rank.column_name(values["y"] or "", columns, "y")
    text = values["filter"]
    if text is not None:  # checked here to be named beside the tab's field
        rank.parse_filter(text, columns, "filter")
    o = parse_options(
        ExploreOptions,
        {
            **{k: values[k] for k in ("layout", "cylinders", "strokes", "bank_angle", "crank")},
            **{"top": values["top"], "objectives": f"{x},{y}", "filter": text, "top_key": KEY},
        },
    )
    if o.top > MAX_ROWS:
        raise InputError("top", values["top"], f"1 to {MAX_ROWS} rows")
    problem = orders.problem(o.layout, o.cylinders, o.strokes, o.bank_angle, crank=o.crank)
    total = orders.count(problem)
    if total > MAX_INDICES:
        raise InputError(
            "cylinders",
            o.cylinders,
            f"a problem of at most {MAX_INDICES:,} firing orders in the web app (this one has "
            f"{total:,}): run it with `crankbalance explore --workers N` (docs/explorer.md)",
        )
    return problem, (x, y), o, o.top, o.bank_angle


#: the settings of the problem that :func:`engine_problem` takes from the page's engine
PROBLEM_KEYS = ("layout", "cylinders", "strokes", "bank_angle")
#: layouts with a bank angle (the explorer's)
BANKED = ("vee", "w", "vr")


def engine_problem(spec: Any) -> tuple[dict[str, str] | None, str]:
    """The texts of :data:`PROBLEM_KEYS` of the engine ``spec`` (an
    :class:`~crankbalance.schema.engine.EngineSpec`) for the explorer, and None with the
    reason in words when the explorer cannot explore that engine's problem here (a layout
    it does not enumerate, or more than :data:`MAX_INDICES` firing orders)."""
    from ..physics.explore import orders

    train = spec.crank_train
    layout = str(train.layout)
    if layout not in CHOICES["layout"]:
        return None, (
            f"the explorer enumerates {', '.join(CHOICES['layout'])} cranks, not a {layout} one"
        )
    bank = train.bank_angle if layout in BANKED else None
    texts = {
        "layout": layout,
        "cylinders": str(int(train.cylinders)),
        "strokes": str(int(train.strokes)),
        "bank_angle": "" if bank is None else f"{math.degrees(bank):.6g} deg",
    }
    try:
        problem = orders.problem(layout, int(train.cylinders), int(train.strokes), bank)
    except InputError as error:
        return None, f"the explorer cannot take it ({error})"
    total = orders.count(problem)
    if total > MAX_INDICES:
        return None, (
            f"its {total:,} firing orders are more than the {MAX_INDICES:,} the web app "
            "explores (`crankbalance explore --workers N` runs it)"
        )
    return texts, ""


def problem_words(texts: dict[str, str]) -> str:
    """The problem of the tab's texts in words: ``vee, 8 cylinders, 4-stroke, bank angle
    90 deg``."""
    words = [texts.get("layout", "").strip(), f"{texts.get('cylinders', '').strip()} cylinders"]
    words.append(f"{texts.get('strokes', '').strip()}-stroke")
    bank = texts.get("bank_angle", "").strip()
    if bank and texts.get("layout", "").strip() in BANKED:
        words.append(f"bank angle {bank}")
    return ", ".join(words)


def _in_maker_numbers(train: dict[str, Any], order: list[int]) -> list[int]:
    """The candidate's order (crankbalance's numbering) in the engine's maker's numbering
    when the engine file has one (``numbering`` or ``maker_numbers``), else unchanged."""
    from ..physics.firing import SCHEMES, to_maker_order

    if train.get("maker_numbers") is not None:
        return to_maker_order(order, [int(c) for c in train["maker_numbers"]])
    scheme = SCHEMES.get(str(train.get("numbering")))
    if scheme is None:
        return order
    return to_maker_order(order, scheme.to_crankbalance(len(order)))


def candidate_file(
    data: dict[str, Any], problem: Any, bank_angle: float | None, row: dict[str, Any]
) -> dict[str, Any]:
    """The engine-file dictionary ``data`` (the current engine) with the crank of the
    explorer's candidate ``row`` of ``problem``: layout, cylinders, strokes, bank angle
    [rad], firing order and throw angles; the description (the current engine's words),
    custom throws, mass overrides and the webs list (their counts follow the crank) are
    dropped, and so are the per-bank and per-cylinder
    offsets and rod positions unless the layout and the number of cylinders stay (then a
    maker's numbering stays too, and the firing order is written in it)."""
    order = [int(c) for c in row["firing_order"]]
    train = dict(data.get("crank_train", {}))
    same = train.get("layout") == problem.layout and train.get("cylinders") == len(order)
    for key in ("throw", "bank_angle", "throw_angles", "crank_offset"):
        train.pop(key, None)
    if not same:
        for key in ("bank_offsets", "cylinder_offsets", "rod_positions", "numbering"):
            train.pop(key, None)
        train.pop("maker_numbers", None)
    train.update(
        layout=problem.layout,
        cylinders=len(order),
        strokes=int(problem.strokes),
        firing_order=_in_maker_numbers(train, order),
        throw_angles=[f"{math.degrees(a) % 360:.6g} deg" for a in row["throw_angle_rad"]],
    )
    if bank_angle is not None and problem.layout in ("vee", "w", "vr"):
        train["bank_angle"] = f"{math.degrees(bank_angle):.9g} deg"
    out = {k: v for k, v in data.items() if k != "crank_train"}
    out["crank_train"] = train
    out["name"] = f"Explorer {problem.layout}-{len(order)} {'-'.join(map(str, order))}"
    out.pop("description", None)  # the current engine's words, not the candidate's
    out.get("masses", {}).pop("override", None)
    out.get("counterweights", {}).pop("webs", None)
    return out


class ExploreTab(TabSettingsMixin, StudyTab):
    settings_table = SETTINGS
    parse_settings = staticmethod(parse)
    fallback = "layout"
    choices = CHOICES
    name = "explore"
    what = "the exploration"
    result: Any = None
    problem: Any = None
    objectives: tuple[str, str] = ("F2_N", "M2_Nm")
    chosen: int | None = None
    bank_angle: float | None = None
    top = 20

    #: why the page's engine's problem was not taken when the tab was opened ("" if it was)
    not_taken = ""

    def build(self) -> None:
        # the explorer's modules and columns load in a thread: on the event loop their
        # first import (seconds on a busy machine) would stall every page of the server
        threading.Thread(target=_columns, daemon=True).start()
        self.problem_line = (
            ui.markdown("").props("data-testid=explore-problem").mark("explore-problem")
        )
        spec = self.page.project.spec
        starts, self.not_taken = engine_problem(spec) if spec is not None else (None, "")
        with ui.row().classes("w-full items-start gap-4"):
            self.settings_card("Problem", "w-64", run_label="Explore", starts=starts)
            with ui.card().classes("min-w-0").style("flex: 1 1 0"):
                ui.label("Results").classes("text-subtitle1")
                self.rerun_note()
                self.summary = (
                    ui.markdown("").props("data-testid=explore-summary").mark("explore-summary")
                )
                self.table = (
                    ui.table(columns=[], rows=[], row_key="index")
                    .classes("w-full")
                    .props("dense flat data-testid=explore-table")
                    .mark("explore-table")
                )
                self.table.on("rowClick", self.on_row)
                self.ties = ui.markdown("").props("data-testid=explore-ties").mark("explore-ties")
                ui.markdown(EQUIVALENTS_NOTE).classes("text-grey-7").mark("explore-equivalents")
                ui.label("Click a row (or a point) to load that engine in the form.").classes(
                    "text-grey-7"
                )
        with ui.grid(columns=2).classes("w-full"):
            scatter = self.card("explore-scatter", "Candidates and Pareto set", self._scatter)
            self.card("explore-candidate", "Chosen candidate", self._candidate)
        scatter.plot.on("plotly_click", self.on_point)
        self.say_problem()

    def say_problem(self) -> None:
        """The line that says which problem the tab explores and whether it is the page's
        engine's."""
        spec = self.page.project.spec
        shown = f"Explores **{problem_words(self.texts)}**"
        if spec is None:
            self.problem_line.set_content(f"{shown}.")
            return
        texts, why = engine_problem(spec)
        name = spec.name
        if texts is not None and all(self.texts.get(k, "").strip() == v for k, v in texts.items()):
            self.problem_line.set_content(f"{shown}: the crank of this page's engine ({name}).")
        elif texts is None:
            self.problem_line.set_content(f"{shown}, not this page's engine ({name}): {why}.")
        else:
            self.problem_line.set_content(
                f"{shown}, not this page's engine ({name}: {problem_words(texts)})."
            )

    def settings_changed(self) -> None:
        super().settings_changed()
        if hasattr(self, "problem_line"):
            self.say_problem()

    # ------------------------------------------------------------------ StudyTab
    def show(self, c: Any) -> None:
        """The engine's changes do not touch the result: it belongs to the tab's settings
        (the line above the settings says whether they are the new engine's)."""
        self.say_problem()

    def reset(self) -> None:
        """A new project (or a candidate loaded from here) keeps the explorer's result."""

    def clear(self) -> None:
        self.result = None
        self.chosen = None
        self.summary.set_content("")
        self.ties.set_content("")
        self.table.rows = []
        self.table.update()
        for card in self.cards:
            card.refresh()

    def stamp(self) -> tuple[Any, ...]:
        """What a run belongs to: the tab's settings (not the form's engine)."""
        return self.current_settings()

    def owns(self, started: Any) -> bool:
        if started == self.stamp():
            self.result_for = started
            self.rerun.set_visibility(False)
            return True
        self.drop("these settings")
        return False

    def drop(self, engine: str) -> None:
        super().drop(engine)
        self.rerun.set_text("Not computed for these settings: re-run the exploration.")

    # ------------------------------------------------------------------ run
    async def run(self) -> None:
        done = await self.run_study(
            studies.explore,
            lambda parsed, _: (parsed[2], MAX_INDICES),
            "exploring …",
            engine=False,
        )
        if done is None:
            return
        (problem, objectives, _study, top, bank_angle), result = done
        self.result, self.problem, self.objectives, self.top = result, problem, objectives, top
        self.bank_angle = bank_angle
        self.chosen = int(result.top["index"][0]) if result.rows else None
        self.summary.set_content(
            f"{result.total:,} firing orders, **{result.candidates:,} distinct engines**, "
            f"{result.rows:,} kept by the filter, Pareto set of "
            f"{result.pareto['index'].size if result.pareto else 0} over "
            f"{column_words(objectives[0])} (`{objectives[0]}`) and "
            f"{column_words(objectives[1])} (`{objectives[1]}`) ({result.seconds:.2f} s). "
            f"The table is ordered by the {column_words(KEY)} (`{KEY}`); figures are of the "
            "plain engine of the enumeration (docs/explorer.md)."
        )
        self._fill_table()
        for card in self.cards:
            card.refresh()

    def _fill_table(self) -> None:
        rows = self.result.top if self.result is not None and self.result.rows else {}
        names = list(dict.fromkeys([*self.objectives, KEY]))
        shown = min(self.top, rows["index"].size if rows else 0)
        tie = tied(rows, self.problem, shown) if rows else 0
        apart = tie_columns(rows, self.problem, tie) if tie > 1 else {}
        highest = max((int(m[2]) for m in map(FREE_COLUMN.match, rows) if m), default=0)
        what = "; ".join(
            dict.fromkeys(TIE_COLUMNS["linear" if k[0] == "X" else k][1] for k in apart)
        )
        self.ties.set_content(
            ""
            if tie < 2
            else (TIE_NOTE if apart else TIE_SAME).format(n=tie, orders=highest, columns=what)
        )
        self.table.columns = [
            {"name": "rank", "label": "#", "field": "rank"},
            {"name": "order", "label": "firing order", "field": "order", "align": "left"},
            {"name": "throws", "label": "throws [deg]", "field": "throws", "align": "left"},
            {"name": "equivalents", "label": "orders giving it", "field": "equivalents"},
            *(
                {
                    "name": f"tie-{key}",
                    "label": (
                        TIE_COLUMNS["linear"][0].format(k=key[1:])
                        if key[0] == "X"
                        else TIE_COLUMNS[key][0]
                    ),
                    "field": f"tie-{key}",
                    "align": "left" if key == "banks" else "right",
                }
                for key in apart
            ),
            *({"name": n, "label": column_words(n), "field": n} for n in names),
        ]
        self.table.rows = [
            {
                "rank": k + 1,
                "index": int(rows["index"][k]),
                "order": "-".join(str(int(c)) for c in rows["firing_order"][k]),
                "throws": ", ".join(
                    f"{math.degrees(a) % 360:.0f}" for a in rows["throw_angle_rad"][k]
                ),
                "equivalents": int(rows["equivalents"][k]),
                **{n: fmt_g(rows[n][k]) for n in names},
                **{f"tie-{key}": (texts[k : k + 1] or [""])[0] for key, texts in apart.items()},
            }
            for k in range(shown)
        ]
        self.table.update()

    # ------------------------------------------------------------------ figures
    def _row(self, index: int | None) -> dict[str, Any] | None:
        if self.result is None or index is None or not self.result.rows:
            return None
        rows = self.result.top
        found = np.flatnonzero(rows["index"] == index)
        return {n: v[found[0]] for n, v in rows.items()} if found.size else None

    def _scatter(self) -> Any | None:
        if self.result is None or not self.result.rows:
            return None
        return explore_scatter(
            self.result.top,
            self.result.pareto,
            *self.objectives,
            title="Candidates",
            total=self.result.rows,
        )

    def _candidate(self) -> Any | None:
        row = self._row(self.chosen)
        return None if row is None else explore_candidate(row)

    # ------------------------------------------------------------------ load
    def on_row(self, event: Any) -> None:
        args = event.args if isinstance(event.args, list) else [event.args]
        row = next((a for a in args if isinstance(a, dict) and "index" in a), None)
        if row is not None:
            self.load(int(row["index"]))

    def on_point(self, event: Any) -> None:
        points = (event.args or {}).get("points") or []
        if points and points[0].get("customdata") is not None:
            self.load(int(points[0]["customdata"]))

    def load(self, index: int) -> None:
        """Load the candidate of enumeration index ``index`` as the current engine."""
        from ..schema.engine import spec_from_dict
        from .project import Project

        row = self._row(index)
        if row is None:
            return
        project = self.page.project
        spec = project.spec or Project.from_preset(self.page.default_preset).spec
        assert spec is not None
        try:
            data = candidate_file(spec.to_data(), self.problem, self.bank_angle, row)
            new = spec_from_dict(data)
        except InputError as error:
            ui.notify(f"Cannot load this candidate: {error}", type="negative", multi_line=True)
            return
        self.chosen = index
        self.page.load(Project.from_spec(new, dict(project.settings)))
        for card in self.cards:
            if card.name == "explore-candidate":
                card.refresh()
        order = "-".join(str(int(c)) for c in row["firing_order"])
        ui.notify(f"Loaded firing order {order} as the current engine", type="positive")
