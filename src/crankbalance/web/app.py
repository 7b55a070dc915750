"""The NiceGUI page of ``crankbalance web``: the shell of the page.

Tabs follow the 2021 paper's interface (Sec. 5: input tabs, Next/Back, "Compute results",
a Results tab, a counterweight-design tab) and go on to the single-cylinder, balance-shaft
and performance studies. :func:`root` builds one page per browser tab; all state lives in
the :class:`Page` object it creates (one :class:`~.project.Project` per client) and in its
tabs, never in module globals, so several users work side by side without seeing each
other's project.

This module is the shell: header (preset, save), project upload, tab bar and Next/Back
navigation, the form fields and study settings, the recompute/update loop and the data
downloads. Each tab is one module (``tab_engine.py`` ... ``tab_performance.py``, a
:class:`~.widgets.Tab` each) that builds its panel and shows its numbers and figures;
every figure comes from :mod:`crankbalance.output.figures`, the tabs only lay them out.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from nicegui import ui

from ..errors import InputError
from ..io.engine_file import list_presets
from . import pool, studies
from .computation import Computed
from .exports import table_csv
from .form import FIELD_BY_KEY, FormField, key_label
from .project import MAX_BYTES, Project, read_text
from .tab_counterweight import CounterweightTab
from .tab_engine import EngineTab
from .tab_explore import ExploreTab
from .tab_loads import LoadsTab
from .tab_masses import MassesTab
from .tab_mounts import MountsTab
from .tab_performance import PerformanceTab
from .tab_results import ResultsTab, order_rows
from .tab_shaft import ShaftTab
from .tab_shop import ShopTab
from .tab_single import SingleTab
from .widgets import SHOW_TAB_JS, Tab, TabBar, TabPanels, send_download

log = logging.getLogger("crankbalance.web")
#: the preset a page opens on unless the server is given another (``crankbalance web
#: --preset``, :func:`page_root`) or the address names one (``/?preset=v8-crossplane``)
DEFAULT_PRESET = "paper-inline3"
TABS = (
    ("engine", "Engine"),
    ("masses", "Masses"),
    ("results", "Results"),
    ("counterweight", "Counterweight design"),
    ("single", "Single cylinder"),
    ("shaft", "Balance shaft"),
    ("performance", "Performance"),
    ("explore", "Explorer"),
    ("shop", "Balance shop"),
    ("loads", "Crank loads"),
    ("mounts", "Mounts"),
)
#: the one line under the header saying what the tool does
TAGLINE = (
    "crankbalance: the free forces and moments of an engine's crank train, and the "
    "counterweights and balance shafts that cancel them, as you type."
)
#: the tabs that show results of the computed engine (greyed, with the reason, while the
#: form cannot be computed)
RESULT_TABS = (
    "results",
    "counterweight",
    "single",
    "shaft",
    "performance",
    "shop",
    "loads",
    "mounts",
)
#: the preset menu's entry while the form holds a preset edited (:meth:`Page.show_preset`);
#: choosing the preset itself then loads it again
EDITED = "{name} (edited)"
#: the tabs built with the page (its first screen); every other tab's content is built when
#: the tab is first opened (:meth:`Page.open_tab`), which keeps the page the server sends
#: (and the browser mounts) small: about a third of the elements of all nine tabs
FIRST_SCREEN = ("engine", "results")
#: shown in a tab's panel until its content is built (the panel the browser switches to
#: before the server's answer arrives; the busy bar shows too after 0.2 s)
OPENING = "Opening the tab …"
CSS = """
.cb-stale { opacity: 0.45; }
/* a message under a field takes its own lines instead of being drawn over the next field */
.q-field__bottom { position: static; transform: none; white-space: normal; }
.q-field--with-bottom { padding-bottom: 4px; }
/* busy: shown by BUSY_JS when the server has not answered an action within 0.2 s */
#cb-busy { display: none; }
body.cb-busy #cb-busy { display: block; position: fixed; top: 0; left: 0; right: 0; height: 4px;
  z-index: 9999; background: linear-gradient(90deg, #ffb300 30%, transparent 30%);
  background-size: 200% 100%; animation: cb-slide 1s linear infinite; }
@keyframes cb-slide { from { background-position: 100% 0; } to { background-position: -100% 0; } }
/* the tab bar: tabs narrower than Quasar's (16 px each side) so that all eleven fit a
   1280 px screen (MOUNTS was behind the scroll arrow); a narrower screen scrolls them */
.q-tabs .q-tab { padding: 0 8px; }
/* narrow screens: one column, nothing wider than the screen */
/* a table wider than its box scrolls sideways; TABLE_CUE_JS marks it while more of it is to
   the right (data-cb-more), and a shaded edge with an arrow says so */
.q-table__container[data-cb-more] { position: relative; }
.q-table__container[data-cb-more]::after { content: "\\2192"; position: absolute; top: 0;
  right: 0; bottom: 0; width: 28px; pointer-events: none; z-index: 2; display: flex;
  align-items: flex-start; justify-content: center; padding-top: 4px; color: #263238;
  font-size: 18px; font-weight: bold;
  background: linear-gradient(to right, rgba(255,255,255,0), rgba(69,90,100,0.35)); }
@media (max-width: 600px) {
  /* the header in two short lines (issue 28: it took 172 of 844 px) */
  .q-header { flex-wrap: wrap; row-gap: 0; column-gap: 6px !important; padding: 2px 8px; }
  .q-header .text-h6 { font-size: 1rem; line-height: 1.75rem; }
  .q-header .q-select { width: 10.5rem !important; }
  .q-header .q-select .q-field__label { display: none; }
  .q-header .q-select .q-field__native { padding-top: 0; padding-bottom: 0; }
  .q-header .q-btn { padding: 0 4px; min-height: 28px; font-size: 12px; }
  .q-header .q-space { display: none; }
  .q-header [data-testid=status] { width: 100%; font-size: 12px; line-height: 1.3;
    white-space: nowrap; overflow: hidden; text-overflow: ellipsis; }
  .q-tab-panel { padding: 8px 4px; }
  .q-tab-panel .nicegui-grid { grid-template-columns: minmax(0, 1fr) !important; width: 100%; }
  /* one line (no wrap): a wrapping column sizes its line, and so every stretched item, by
     the widest content, and a figure still as wide as before a resize from a wide window
     held the Engine tab's key results and 3-D crank 650 px wide on a 390 px screen */
  .q-tab-panel .nicegui-row { flex-direction: column; flex-wrap: nowrap; align-items: stretch; }
  .q-tab-panel .q-card, .q-tab-panel .w-64, .q-tab-panel .w-48, .q-tab-panel .w-96 {
    width: 100% !important; min-width: 0 !important; max-width: 100%; }
  .q-tab-panel [class*="min-w-"] { min-width: 0 !important; width: 100%; }
  .q-tab-panel .q-table__container { max-width: 100%; overflow-x: auto; }
}
"""
#: toasts close with their tab: every toast's dismiss function is kept (Quasar's
#: ``Notify.create`` wrapped, which NiceGUI's ``ui.notify`` calls) and :meth:`Page.on_tab`
#: dismisses them all when another tab is opened (on a phone a toast covered a field of the
#: next tab)
TOASTS_JS = """
<script>
(() => {
  const toasts = window.cbToasts = {shown: new Set(), dismiss() {
    for (const close of this.shown) close();
    this.shown.clear();
  }};
  const hook = () => {
    if (!window.Quasar || !Quasar.Notify || !Quasar.Notify.create) {
      setTimeout(hook, 50); return;
    }
    const create = Quasar.Notify.create;
    Quasar.Notify.create = (options) => {
      const close = create.call(Quasar.Notify, options);
      if (typeof close === "function") toasts.shown.add(close);
      return close;
    };
  };
  hook();
})();
</script>
"""
#: the sideways-scroll cue of tables (:data:`CSS`): every table container whose scrolling
#: part has more to the right than it shows gets ``data-cb-more`` (checked as the page
#: changes, on resizes and as the table is scrolled)
TABLE_CUE_JS = """
<script>
(() => {
  let pending = false;
  const cue = () => {
    pending = false;
    for (const box of document.querySelectorAll('.q-table__container')) {
      const middle = box.querySelector('.q-table__middle') || box;
      const more = middle.scrollWidth - middle.clientWidth - middle.scrollLeft > 1;
      if (more !== box.hasAttribute('data-cb-more')) box.toggleAttribute('data-cb-more', more);
    }
  };
  const later = () => { if (!pending) { pending = true; requestAnimationFrame(cue); } };
  new MutationObserver(later).observe(document.body, {childList: true, subtree: true});
  window.addEventListener('resize', later);
  document.addEventListener('scroll', later, true);
  later();
})();
</script>
"""
#: closes the toasts shown (:data:`TOASTS_JS`)
DISMISS_TOASTS = "window.cbToasts && window.cbToasts.dismiss()"
#: the busy bar: an action of the page (an edit, a choice, a button) that the server has
#: not handled within 0.2 s shows a moving bar at the top until the server acknowledges it
#: (socket.io's acknowledgement, sent when NiceGUI's handler of the event returns), so the
#: bar stops with the work, also for an action that changes nothing on the page (a study
#: setting edited, the same preset chosen again). An async handler (a study's run)
#: returns at once: its work shows in its tab (spinner, progress, Cancel)
BUSY_JS = """
<div id="cb-busy" data-testid="busy"></div>
<script>
(() => {
  const state = window.cbBusy = {sent: 0, pending: 0, timer: null};
  const done = () => {
    state.pending = Math.max(0, state.pending - 1);
    if (state.pending > 0) return;
    clearTimeout(state.timer); state.timer = null; document.body.classList.remove('cb-busy');
  };
  const hook = () => {
    const s = window.socket;
    if (!s) { setTimeout(hook, 50); return; }
    const emit = s.emit.bind(s);
    s.emit = (name, ...args) => {
      if (name !== 'event' || typeof args[args.length - 1] === 'function')
        return emit(name, ...args);
      state.sent += 1; state.pending += 1;
      if (state.timer === null)
        state.timer = setTimeout(() => document.body.classList.add('cb-busy'), 200);
      return emit(name, ...args, done);  // the server's acknowledgement: handled
    };
    s.on('disconnect', () => { state.pending = 1; done(); });
  };
  hook();
})();
</script>
"""


def warm_up(preset: str = DEFAULT_PRESET) -> None:
    """Compute the server's default engine ``preset`` and build its 3-D crank once (the
    server runs this in the background as it starts): the first page of a fresh server
    would otherwise wait for the imports of the physics and of plotly's figure classes
    (about 0.6 s of a first load on an idle machine, seconds on a busy one)."""
    from ..output.figures.crank3d import crank_3d

    c = Project.from_preset(preset).compute()
    if c is not None:
        crank_3d(c.analysis.model, c.study).to_plotly_json()


def root(preset: str | None = None) -> None:
    """The page: ``/`` or ``/?preset=v8-crossplane`` (on :data:`DEFAULT_PRESET`)."""
    Page(preset).build()


def page_root(default_preset: str) -> Callable[[str | None], None]:
    """The page of a server whose pages open on ``default_preset``: :func:`root` with
    that default, passed to each page (and its tabs' context), no module state."""

    def root(preset: str | None = None) -> None:
        Page(preset, default_preset).build()

    return root


class Page:
    """One client's page and project; to its tabs, their context (it implements
    :class:`~.context.TabContext`: the tabs are given the page and see that much of it)."""

    def __init__(self, preset: str | None, default_preset: str = DEFAULT_PRESET) -> None:
        self.default_preset = default_preset
        self.project = Project()
        self.inputs: dict[str, Any] = {}
        self.setting_inputs: dict[str, Any] = {}
        self.results = ResultsTab(self)
        tabs: tuple[Tab, ...] = (
            EngineTab(self),
            MassesTab(self),
            self.results,
            CounterweightTab(self),
            SingleTab(self),
            ShaftTab(self),
            PerformanceTab(self),
            ExploreTab(self),
            ShopTab(self),
            LoadsTab(self),
            MountsTab(self),
        )
        self.tabs: dict[str, Tab] = {tab.name: tab for tab in tabs}
        assert list(self.tabs) == [name for name, _ in TABS]
        self.updates = 0
        #: what the computed results belong to: (engine spec, orders); see :meth:`fresh`
        self.computed_for: tuple[Any, int] | None = None
        self.stale_notes: dict[str, Any] = {}
        self.bodies: dict[str, Any] = {}
        #: the study of this page running in a worker process (one at a time), if any
        self.job: pool.Job | None = None
        message = ""
        name = preset or default_preset
        try:
            self.project = Project.from_preset(name)
        except InputError as error:
            message = f"{error}; loaded {default_preset} instead"
            self.project = Project.from_preset(default_preset)
            name = default_preset
        self.preset_name: str | None = name
        self.startup_message = message
        #: True while the page itself sets the preset menu (not the user's choice)
        self.setting_preset = False

    # ================================================================== layout
    def build(self) -> None:
        ui.page_title("crankbalance")
        ui.context.client.on_delete(self.cancel_job)  # the page went away: its study stops
        ui.add_css(CSS)
        ui.add_body_html(BUSY_JS)
        ui.add_body_html(TOASTS_JS)
        ui.add_body_html(TABLE_CUE_JS)
        with ui.header().classes("items-center gap-4 bg-blue-grey-9"):
            ui.label("crankbalance").classes("text-h6")
            self.preset_select = (
                ui.select(
                    list_presets(), value=self.preset_name, label="Preset", on_change=self.on_preset
                )
                .classes("w-56")
                .props("dark dense options-dense")
                .props("data-testid=preset")
                .mark("preset")
            )
            ui.button("Save TOML", on_click=lambda: self.save("toml")).props(
                "flat color=white"
            ).mark("save-toml")
            ui.button("Save JSON", on_click=lambda: self.save("json")).props(
                "flat color=white"
            ).mark("save-json")
            ui.space()
            self.status = (
                ui.label("").classes("text-body2").props("data-testid=status").mark("status")
            )
        ui.label(TAGLINE).classes("text-body2 text-grey-8 q-px-md").props(
            "data-testid=tagline"
        ).mark("tagline")
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
                on_rejected=self.on_rejected,
                max_file_size=MAX_BYTES,
            ).props("accept=.toml,.json flat bordered").classes("w-96").mark("upload")
        self.general = (
            ui.label("")
            .classes("text-negative text-body1")
            .props("data-testid=general-error")
            .mark("general-error")
        )
        # switched in the browser at once, the server told afterwards (:class:`TabBar`)
        with TabBar().classes("w-full").props("mobile-arrows") as self.tab_bar:
            for name, label in TABS:
                ui.tab(name, label=label).mark(f"tab-{name}")
        with TabPanels(value="engine").classes("w-full") as self.panels:
            for index, (name, _label) in enumerate(TABS):
                with ui.tab_panel(name):
                    if name in RESULT_TABS:
                        self.stale_notes[name] = (
                            ui.label("")
                            .classes("text-negative text-body1")
                            .props(f"data-testid={name}-stale")
                            .mark(f"{name}-stale")
                        )
                    with ui.column().classes("w-full") as self.bodies[name]:
                        if name in FIRST_SCREEN:
                            self.tabs[name].build()
                            self.tabs[name].built = True
                        else:  # built when first opened (:meth:`open_tab`)
                            with (
                                ui.row()
                                .classes("items-center gap-2")
                                .props(f"data-testid={name}-opening")
                                .mark(f"{name}-opening")
                            ):
                                ui.spinner(size="md")
                                ui.label(OPENING)
                    self._nav(index)
        self.tab_bar.set_value("engine")
        self.tab_bar.on_value_change(self.on_tab)
        self.tab_bar.on(
            "update:model-value",
            js_handler=SHOW_TAB_JS.format(tabs=self.tab_bar.id, panels=self.panels.id),
        )
        self.update_all()
        if self.startup_message:
            self.general.set_text(self.startup_message)

    def cancel_job(self) -> None:
        """End the page's running study (its worker process), if any."""
        if self.job is not None:
            self.job.cancel()

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

    def field(self, f: FormField) -> None:
        """The input of an engine field (tabs Engine and Masses)."""
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
        element.props("hide-bottom-space")  # a long message pushes the next field down
        element.props(f"data-testid=field-{f.key}").mark(f"field-{f.key}")
        element.without_auto_validation()
        self.inputs[f.key] = element

    def setting(self, key: str, on_change: Callable[[], None] | None = None) -> None:
        """The input of a study setting (saved with the project, not part of the engine)."""
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
        """The user chose a preset: load it, also the one shown when the form holds it
        edited (the menu then shows ``<name> (edited)``, :meth:`show_preset`)."""
        if self.setting_preset or not event.value or event.value not in list_presets():
            return
        self.load(Project.from_preset(event.value), preset=event.value)

    def show_preset(self) -> None:
        """The preset menu names the preset the form holds, ``<name> (edited)`` once the
        form differs from it, nothing for another project (:meth:`load`)."""
        name = self.preset_name
        if name is None or not hasattr(self, "preset_select"):
            return
        edited = EDITED.format(name=name)
        project = self.project
        value = edited if project.engine_state() != project.loaded_state else name
        if self.preset_select.value == value:
            return
        self.setting_preset = True
        try:
            options = list_presets()
            self.preset_select.set_options(
                [edited, *options] if value == edited else options, value=value
            )
        finally:
            self.setting_preset = False

    def on_tab(self, event: Any) -> None:
        """The tab bar's value changed: a click in the browser, which shows the tab already
        (the panels follow without being sent back), or :meth:`go`. The tab is built if it
        is new and its stale cards redrawn; the clicks of a fast user arrive in their order,
        each tab opened ends built, and the last one is the one shown."""
        name = str(event.value)
        self.panels.shown(name)
        ui.run_javascript(DISMISS_TOASTS)  # the toasts of the tab left close with it
        self.open_tab(name)
        self.refresh_cards(name)

    def open_tab(self, name: str) -> None:
        """Build a tab's content the first time it is opened, showing the project as it is:
        the form's values, the computed engine's numbers (:meth:`Tab.show`), the messages of
        its fields and settings. Its settings live in the project (``project.settings``),
        validated and saved whether or not the tab was ever opened."""
        tab = self.tabs.get(name)
        if tab is None or tab.built:
            return
        body = self.bodies[name]
        body.clear()
        with body:
            tab.build()
        tab.built = True
        for key, element in self.inputs.items():
            element.set_visibility(self.project.active(FIELD_BY_KEY[key]))
        if self.project.computed is not None:
            tab.show(self.project.computed)
        self.show_errors()
        self.show_setting_errors()
        self.show_state()

    def go(self, tab: str) -> None:
        """The server switches the tab (a button): the panels' and the tab bar's values are
        sent to the browser, the panels' first (:meth:`on_tab` then finds them shown)."""
        self.panels.set_value(tab)
        self.tab_bar.set_value(tab)

    def compute_results(self) -> None:
        self.recompute()
        if self.fresh() is None:
            ui.notify(f"Not computed: {self.problem()}", type="warning", multi_line=True)
            return
        self.go("results")

    async def on_upload(self, event: Any) -> None:
        upload = event.file
        name = str(getattr(upload, "name", "project.toml"))
        try:
            text = read_text(await upload.read(), name)
            fmt = "json" if name.lower().endswith(".json") else "toml"
            project = Project.from_text(text, name, fmt)
        except InputError as error:
            self.refuse_upload(f"Upload of {name} refused, the current project is kept: {error}")
            return
        self.load(project)
        self.general.set_text("")
        ui.notify(f"Loaded {name}", type="positive")

    def on_rejected(self) -> None:
        """The browser refused the chosen file before sending it (larger than MAX_BYTES)."""
        self.refuse_upload(
            f"Upload refused, the current project is kept: the file is larger than {MAX_BYTES} "
            "bytes; an engine file is a few kB of TOML or JSON"
        )

    def refuse_upload(self, message: str) -> None:
        self.general.set_text(message)
        ui.notify(message, type="negative", multi_line=True)

    def load(self, project: Project, preset: str | None = None) -> None:
        """Show ``project`` in the form and every built tab. The preset selector shows
        ``preset``, the preset it is, and is empty for any other project (an uploaded file,
        an explorer candidate), so that it never names an engine the form does not hold."""
        self.project = project
        self.preset_name = preset
        self.setting_preset = True
        try:
            self.preset_select.set_options(list_presets(), value=preset)
        finally:
            self.setting_preset = False
        for tab in self.built_tabs():
            tab.reset()
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
        send_download(
            text,
            f"{stem or 'engine'}.{fmt}",
            "application/toml" if fmt == "toml" else "application/json",
        )

    def download_data(self, what: str) -> None:
        from ..output.format import json_text

        c = self.fresh()
        if c is None:
            ui.notify(f"Not computed: {self.problem()}", type="warning", multi_line=True)
            return
        if what == "analysis":
            send_download(
                json_text(c.analysis.to_dict(), indent=1), "analysis.json", "application/json"
            )
        elif what == "balance":
            send_download(
                json_text(c.study.to_dict(), indent=1), "balance.json", "application/json"
            )
        else:
            send_download(table_csv(order_rows(c)), "orders.csv", "text/csv")

    async def download_report(self, fmt: str = "html") -> None:
        from .report_download import download_report

        await download_report(self, fmt)

    # ================================================================== updates
    def update_all(self) -> None:
        """Show field errors and, for a valid engine, recompute and refresh what is shown."""
        for key, element in self.inputs.items():
            f = FIELD_BY_KEY[key]
            element.set_visibility(self.project.active(f))
        self.recompute()
        self.show_errors()
        self.show_state()
        self.show_preset()

    def orders(self) -> int:
        """The highest order to compute (the setting; 8 while it is invalid)."""
        try:
            return int(studies.setting(self.project.settings, "orders"))
        except InputError:
            return 8

    def fresh(self) -> Computed | None:
        """The computed results when they belong to the form as it is now, else None (the
        form has errors, or the engine it describes could not be computed)."""
        spec = self.project.spec
        if spec is None or self.computed_for is None or self.project.computed is None:
            return None
        return self.project.computed if self.computed_for == (spec, self.orders()) else None

    def problem(self) -> str:
        """Why the form cannot be computed: the messages of the fields (by their label) and
        the general one."""
        lines = [
            message if message.startswith(key_label(key)) else f"{key_label(key)}: {message}"
            for key, message in self.project.errors.items()
        ]
        if self.project.general_error:
            lines.append(self.project.general_error)
        return "; ".join(lines) or "the engine could not be computed"

    def show_state(self) -> None:
        """The header and every result tab say whether the results belong to the form."""
        c = self.fresh()
        self.updates += 1
        if c is not None:
            self.status.set_text(f"Results of: {c.spec.name}")
            state = "current"
        else:
            # a form field by its label, a crank-editor cell (override.0.value) by its words
            fields = ", ".join(key_label(key) for key in self.project.errors)
            self.status.set_text(
                f"Not computed: see {fields}" if fields else "Not computed: see the message above"
            )
            state = "error"
        self.status.props(f"data-state={state} data-update={self.updates}")
        shown = self.project.computed
        for name, note in self.stale_notes.items():
            note.set_text(
                ""
                if c is not None
                else f"Not computed: {self.problem()}. The results below are those of the last "
                f"valid engine ({shown.spec.name if shown else 'none'}), not of the form."
            )
            note.set_visibility(c is None)
            self.bodies[name].classes(**{"add" if c is None else "remove": "cb-stale"})
        for tab in self.built_tabs():
            tab.show_fresh(c is not None, "" if c is not None else self.problem())

    def recompute(self) -> None:
        self.show_setting_errors()
        spec = self.project.spec
        if spec is None:
            return
        orders = self.orders()
        self.project.settings["orders"] = str(orders)
        if self.fresh() is not None:
            return  # the same engine and orders: nothing changed
        computed = self.project.compute()
        if computed is None:
            self.show_errors()
            return
        self.computed_for = (spec, orders)
        for tab in self.built_tabs():
            for card in tab.cards:
                card.stale = True
        self.show_numbers()
        self.refresh_cards(str(self.panels.value) if hasattr(self, "panels") else "engine")

    def refresh_cards(self, tab: str) -> None:
        for card in self.tabs[tab].cards if tab in self.tabs else []:
            if card.stale and card.card.visible:
                card.refresh()

    def show_errors(self) -> None:
        for key, element in self.inputs.items():
            element.error = self.project.errors.get(key)
        for tab in self.built_tabs():
            tab.show_errors(self.project.errors)
        self.general.set_text(self.project.general_error)

    def show_setting_errors(self, extra: dict[str, str] | None = None) -> None:
        errors = studies.check_settings(self.project.settings)
        errors.update(extra or {})
        for key, element in self.setting_inputs.items():
            element.error = errors.get(key)

    def show_numbers(self) -> None:
        """The numbers of the computed engine on every tab (masses, orders, balancing,
        counterweight requirement)."""
        c = self.project.computed
        if c is None:
            return
        for tab in self.built_tabs():
            tab.show(c)

    def built_tabs(self) -> list[Tab]:
        """The tabs whose content exists (the first screen and those opened so far)."""
        return [tab for tab in self.tabs.values() if tab.built]
