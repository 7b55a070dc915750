"""Pieces shared by the page shell (:mod:`.app`) and its tabs (``tab_*.py``).

:class:`FigureCard` is a figure with its downloads, :class:`Tab` the base of one tab of the
page, and the small helpers format numbers and send files to the browser. A tab sees the
page through its context (:class:`~.context.TabContext`, held as ``self.page``); nothing
here imports the shell or a tab, so there is no cycle.
"""

from __future__ import annotations

import json
import logging
import re
from abc import ABC, abstractmethod
from collections.abc import Callable, Coroutine, Mapping, Sequence
from typing import TYPE_CHECKING, Any, Literal

from nicegui import run, ui

from ..errors import InputError
from ..output import figures, render
from ..output.figures.common import ALL_ZERO, all_zero, value_ranges
from ..output.format import number
from ..schema.core import Schema, allowed, default_text
from .exports import figure_csv, figure_json

if TYPE_CHECKING:
    from .context import TabContext

log = logging.getLogger("crankbalance.web")
#: download formats of a figure card
FigureFormat = Literal["png", "svg", "csv", "json"]
#: layout of the figures on the page (not in their downloads): sized by their card, the
#: legend inside the figure below the plot, so that a phone-wide card keeps the plot and
#: its whole legend
FIGURE_LAYOUT: dict[str, Any] = {"autosize": True}
LEGEND: dict[str, Any] = {
    "orientation": "h",
    "x": 0,
    "xanchor": "left",
    "y": 0,
    "yref": "container",
    "yanchor": "bottom",
}
#: plotly's height of a figure that sets none [px]
DEFAULT_HEIGHT = 450
#: on a phone (below 600 px) a horizontal legend puts about one entry on a line: the
#: figure grows by this for each entry [px], so the plot keeps its height; figures with
#: subplots side by side keep at least this width per column [px] and scroll in their card
PHONE_LEGEND_LINE = 26
PHONE_COLUMN = 280
#: plotly's top margin of a figure that sets none, and the height a wrapped title's line
#: adds to it [px]
DEFAULT_TOP_MARGIN = 100
TITLE_LINE_PX = 24
#: characters of a figure's title line shown on one line (longer titles wrap at a space;
#: on a phone the title's font is smaller, so that this many fit the width)
TITLE_LINE = 48
#: the figure sizes of :class:`FigureCard` (added to the page once, by the Engine tab)
FIGURE_CSS = """
.cb-figure-box { width: 100%; overflow-x: auto; position: relative; }
/* a 3-D figure's still picture (FigureCard.preview) over its plot until plotly.js has
   drawn the scene (its WebGL container exists) */
.cb-preview { position: absolute; left: 0; right: 0; top: 50px; bottom: 40px;
  pointer-events: none; }
.cb-figure-box:has(.gl-container) > .cb-preview { display: none; }
/* subplots side by side are stacked on a phone (phone_stack, FIGURE_JS) */
.cb-figure { height: var(--cb-height); }
@media (max-width: 600px) {
  .cb-figure { height: var(--cb-phone-height) !important; min-width: var(--cb-phone-width); }
  .cb-figure .gtitle { font-size: 12px !important; }
}
"""

#: plotly's config of every figure card: not "responsive" (NiceGUI's plot then adds no
#: ResizeObserver of its own; that one resized figures of hidden tab panels too, and
#: plotly.js refused each with "Resize must be passed a displayed plot div element")
FIGURE_CONFIG = {"responsive": False}
#: the figures' own resizing (added to the page once, by the Engine tab): one ResizeObserver
#: on every figure card's plot (class ``cb-figure``, found as they are built), which resizes
#: a drawn plot when its box changes and it is displayed; a plot in a hidden tab panel is
#: resized when the panel is shown (its box then changes from nothing to the panel's width)
FIGURE_JS = """
<script>
(() => {
  const resize = (el) => {
    if (!el.isConnected || el.offsetParent === null || !el._fullLayout) return;
    const plot = window.getElement && getElement(Number(el.id.replace(/^c/, "")));
    if (plot && plot.Plotly) plot.Plotly.Plots.resize(el);
  };
  // subplots side by side stacked on a phone (the relayouts of phone_stack, in the layout's
  // meta): applied when the plot is drawn or the width crosses 600 px, idempotent
  const narrow = window.matchMedia("(max-width: 600px)");
  const value = (layout, key) => key.split(".").flatMap((p) => p.split("["))
    .map((p) => p.replace("]", "")).reduce((v, k) => (v == null ? v : v[k]), layout);
  const stack = (el) => {
    const meta = el.layout && el.layout.meta && el.layout.meta.cbStack;
    if (!meta || !el._fullLayout || el.offsetParent === null) return;
    const want = narrow.matches ? meta.phone : meta.wide;
    const same = Object.entries(want).every(
      ([k, v]) => JSON.stringify(value(el.layout, k)) === JSON.stringify(v));
    if (same) return;
    const plot = window.getElement && getElement(Number(el.id.replace(/^c/, "")));
    if (plot && plot.Plotly) plot.Plotly.relayout(el, want);
  };
  const observer = new ResizeObserver((entries) => entries.forEach((e) => {
    stack(e.target); resize(e.target);
  }));
  const plots = document.getElementsByClassName("cb-figure");
  const watched = new WeakSet();
  let pending = false;
  const watch = () => {
    pending = false;
    for (const el of plots) {
      if (!watched.has(el)) { watched.add(el); observer.observe(el); }
      stack(el);
    }
  };
  new MutationObserver(() => {
    if (!pending) { pending = true; requestAnimationFrame(watch); }
  }).observe(document.body, {childList: true, subtree: true});
  watch();
})();
</script>
"""


#: (browser) a click on a tab shows its panel at once: the tab bar's new value is set on the
#: tab bar and on the panels in the browser, before the server hears of it (``{panels}``:
#: the panels' element id). The value NiceGUI sets for a value not looped back is the
#: event's argument list; the tab bar needs the name itself.
SHOW_TAB_JS = """(name) => {{
  for (const id of [{tabs}, {panels}]) {{
    const element = mounted_app.elements[id];
    if (element) element.props["model-value"] = name;
  }}
}}"""


class TabBar(ui.tabs):
    """The page's tab bar, its value held in the browser (NiceGUI's ``LOOPBACK = False``, as
    for a text field): a click switches the tab at once and the server is told afterwards,
    never sending the value back, so a second click before the server answers the first is
    not lost (with the value looped back the tab shown changed only with the server's
    answer, and a click on the tab still shown as current changed nothing)."""

    LOOPBACK = False


class TabPanels(ui.tab_panels):
    """The panels of :class:`TabBar`, switched in the browser with it (:data:`SHOW_TAB_JS`).
    The server follows the browser (:meth:`shown`) without sending the value back; it sends
    a value only when it switches the tab itself (:meth:`set_value`, e.g. *Compute
    results*)."""

    LOOPBACK = False

    def shown(self, name: str) -> None:
        """The browser shows panel ``name`` already (the tab bar's click): hold it as the
        value without sending it (as NiceGUI does for a value the browser sent), and keep
        the browser's own value if the element is sent again for another reason. A value
        the server has just set (:meth:`set_value`, still to be sent) stays to be sent."""
        if self.value == name:
            return
        self._send_update_on_value_change = False
        try:
            self.set_value(name)
        finally:
            self._send_update_on_value_change = True
        self._client_value = name


def button_row() -> Any:
    """A row of buttons that wraps (and stays a row on a phone, where the page's rows turn
    into columns)."""
    return ui.element("div").classes("flex flex-wrap items-center gap-1")


def legend_entries(data: list[dict[str, Any]]) -> int:
    """How many entries the legend of a figure (its traces as plotly JSON) shows: a hidden
    trace (``visible=False``, e.g. another mode of a menu) has none; ``"legendonly"`` has."""
    groups = set()
    for trace in data:
        if trace.get("showlegend") is False or trace.get("visible") is False:
            continue
        if not trace.get("name"):
            continue
        groups.add(trace.get("legendgroup") or id(trace))
    return len(groups)


#: plotly's camera eye when a 3-D figure gives none
PLOTLY_EYE = {"x": 1.25, "y": 1.25, "z": 1.25}


def on_a_phone(figure: Any, camera: float, legend_below: bool = False) -> Any:
    """A 3-D figure with its relayouts for a phone and back, applied by the page as its width
    crosses 600 px (:data:`FIGURE_JS`, the layout's ``meta.cbStack`` that
    :func:`phone_stack` fills for subplots side by side): the camera ``camera`` times
    farther out than the figure's own (a narrow scene cut its tick labels), and with
    ``legend_below`` the bottom margin one legend line higher for each legend entry (a phone
    wraps the legend to a line per entry, which must stay below the scene and a slider)."""
    own = figure.layout.scene.camera.eye
    eye = {
        k: own[k] if own is not None and own[k] is not None else v for k, v in PLOTLY_EYE.items()
    }
    phone: dict[str, Any] = {"scene.camera.eye": {k: v * camera for k, v in eye.items()}}
    wide: dict[str, Any] = {"scene.camera.eye": eye}
    if legend_below:
        bottom = int(figure.layout.margin.b or 0)
        phone["margin.b"] = bottom + PHONE_LEGEND_LINE * legend_entries(
            figure.to_plotly_json()["data"]
        )
        wide["margin.b"] = bottom
    figure.update_layout(meta={"cbStack": {"phone": phone, "wide": wide}})
    return figure


def subplot_columns(layout: dict[str, Any]) -> int:
    """How many subplots stand side by side (distinct x domains of the 2-D axes)."""
    starts = {
        round(float(axis.get("domain", [0, 1])[0]), 3)
        for key, axis in layout.items()
        if key.startswith("xaxis") and isinstance(axis, dict)
    }
    return max(1, len(starts))


#: the share of a stacked subplot's slot kept free below it (its tick labels and the next
#: subplot's title) on a phone
PHONE_STACK_GAP = 0.3


def phone_stack(layout: dict[str, Any]) -> dict[str, dict[str, Any]] | None:
    """For a figure with subplots side by side (:func:`subplot_columns` above 1): the
    relayouts that stack them in one column on a phone, in reading order (row by row, left
    to right), and that put them back (``{"phone": {...}, "wide": {...}}``, plotly's
    ``relayout`` keys: the axes' domains and the subplot titles' positions); None for one
    column. The page applies them as its width crosses 600 px (:data:`FIGURE_JS`)."""
    pairs = []
    for key, axis in layout.items():
        if not (key.startswith("xaxis") and isinstance(axis, dict)):
            continue
        y_axis = layout.get("y" + key[1:])
        if not isinstance(y_axis, dict):
            continue
        x_domain = [float(v) for v in axis.get("domain", [0, 1])]
        y_domain = [float(v) for v in y_axis.get("domain", [0, 1])]
        pairs.append((key[5:], x_domain, y_domain))
    columns = sorted({round(x[0], 3) for _, x, _ in pairs})
    rows = sorted({round(y[1], 3) for _, _, y in pairs}, reverse=True)  # top row first
    if len(columns) < 2:
        return None
    slots = len(columns) * len(rows)
    phone: dict[str, Any] = {}
    wide: dict[str, Any] = {}
    moved = {}  # (column's centre, row's top) -> (new centre, new top) of a subplot title
    for suffix, x, y in pairs:
        slot = rows.index(round(y[1], 3)) * len(columns) + columns.index(round(x[0], 3))
        top = 1.0 - slot / slots
        bottom = top - (1.0 - PHONE_STACK_GAP) / slots
        phone[f"xaxis{suffix}.domain"], wide[f"xaxis{suffix}.domain"] = [0.0, 1.0], x
        phone[f"yaxis{suffix}.domain"], wide[f"yaxis{suffix}.domain"] = [bottom, top], y
        moved[(round((x[0] + x[1]) / 2, 3), round(y[1], 3))] = (0.5, top)
    for k, note in enumerate(layout.get("annotations") or []):
        if note.get("xref") != "paper" or note.get("yref") != "paper":
            continue
        place = (round(float(note.get("x", -1)), 3), round(float(note.get("y", -1)), 3))
        if place in moved:
            phone[f"annotations[{k}].x"], phone[f"annotations[{k}].y"] = moved[place]
            wide[f"annotations[{k}].x"], wide[f"annotations[{k}].y"] = note["x"], note["y"]
    return {"phone": phone, "wide": wide}


def title_layout(layout: dict[str, Any]) -> dict[str, Any]:
    """The title and top margin of a figure card's layout: the title wrapped
    (:func:`wrap_title`), and the plot moved down by a line for each line the wrapping
    added, so that the title never sits over the subplots' own titles ("bearing 1" of the
    bearing loads, issue 28)."""
    title = layout.get("title")
    if not (isinstance(title, dict) and isinstance(title.get("text"), str)):
        return {}
    wrapped = wrap_title(title["text"])
    out: dict[str, Any] = {"title": {**title, "text": wrapped}}
    added = wrapped.count("<br>") - title["text"].count("<br>")
    if added:
        margin = layout.get("margin") or {}
        top = margin.get("t", DEFAULT_TOP_MARGIN)
        out["margin"] = {**margin, "t": top + TITLE_LINE_PX * added}
    return out


def _title_words(text: str) -> list[str]:
    """The words of a title, lower case, without "and" ("before/after" and "before and
    after" are the same words)."""
    return [w for w in re.findall(r"[a-z0-9]+", text.lower()) if w != "and"]


def without_card_title(text: str, card: str) -> str:
    """A figure's title as its card shows it: the first line dropped when the card's own
    title already says it (the same words, or one's words the start of the other's:
    "Drilling plan" under "Drilling plan to scale"), any second line (the engine, a note)
    kept; any other title as it is. The command line's and the reports' figures keep their
    titles (they have no card)."""
    first, _, rest = text.partition("<br>")
    mine, theirs = _title_words(first), _title_words(card)
    short = min(len(mine), len(theirs))
    if short and mine[:short] == theirs[:short]:
        return rest
    return text


def wrap_title(text: str, width: int = TITLE_LINE) -> str:
    """A figure title whose first line is longer than ``width`` characters, broken at the
    last space before it (plotly does not wrap titles; a phone would cut them)."""
    first, sep, rest = text.partition("<br>")
    if len(first) <= width or " " not in first[:width]:
        return text
    cut = first.rfind(" ", 0, width)
    return first[:cut] + "<br>" + first[cut + 1 :] + sep + rest


#: how long the server waits for the browser to make an image [s]: a hang guard (a 3-D
#: figure in software WebGL on a loaded machine takes seconds), not a timing target
IMAGE_TIMEOUT = 180.0
#: the answer of :data:`IMAGE_JS` when the page has no drawn figure to take the traces from
NOT_DRAWN = "not drawn"
#: a figure's PNG/SVG made and downloaded by plotly.js in the browser: the traces drawn in
#: the card's plot (a copy: plotly.js adds to the traces it plots) or those sent with it, the
#: figure's own layout and size; the busy bar shows meanwhile; answers "ok" or why not
IMAGE_JS = """(async () => {
  const plot = getElement(%(id)d);
  const gd = plot && plot.$el;
  const sent = %(data)s;
  if (!plot || !plot.Plotly || (!sent && !(gd && gd.data && gd.data.length))) return "%(missing)s";
  const data = sent || JSON.parse(JSON.stringify(gd.data,
    (key, value) => (ArrayBuffer.isView(value) ? Array.from(value) : value)));
  document.body.classList.add("cb-busy");
  try {
    await plot.Plotly.downloadImage({data, layout: %(layout)s, config: %(config)s}, %(options)s);
    return "ok";
  } catch (error) {
    return "failed: " + error;
  } finally {
    document.body.classList.remove("cb-busy");
  }
})()"""


def image_size(figure: Any) -> tuple[int, int]:
    """Width and height of a figure's image [px]: :func:`crankbalance.output.render.to_image`'s (the
    figure's own, else 1000 x 600)."""
    layout = figure.layout
    return int(layout.width or 1000), int(layout.height or 600)


def browser_image_js(
    plot_id: int, figure: Any, fmt: str, name: str, with_data: bool = False
) -> str:
    """The JavaScript of :data:`IMAGE_JS` for ``figure`` shown in the plot element
    ``plot_id``: its layout (and its traces when ``with_data``) as JSON, the image's format,
    size (:func:`image_size`) and file name ``<name>.<fmt>``."""
    from plotly.utils import PlotlyJSONEncoder

    width, height = image_size(figure)
    options = {"format": fmt, "width": width, "height": height, "scale": 1, "filename": name}
    # a PNG's WebGL scene drawn at the image's own pixels (plotly's default, also kaleido's,
    # draws it at twice the size and scales it down: in software WebGL that takes about 1.4
    # times as long for the same image); an SVG keeps plotly's default for its raster
    config = {"plotGlPixelRatio": 1} if fmt == "png" else {}
    return IMAGE_JS % {
        "id": plot_id,
        "data": json.dumps(figure.data, cls=PlotlyJSONEncoder) if with_data else "null",
        "missing": NOT_DRAWN,
        "layout": json.dumps(figure.layout, cls=PlotlyJSONEncoder),
        "options": json.dumps(options),
        "config": json.dumps(config),
    }


#: what a study tab says of a run that was cancelled (its Cancel button, or the server
#: stopping): the worker was ended, there is no result
CANCELLED = "Run cancelled: no result."
#: the note of a figure card whose 3-D view comes after the page's first paint
DRAWING = "Drawing the 3-D view …"
#: plotly trace types drawn with WebGL (a 3-D scene)
WEBGL_TRACES = ("scatter3d", "mesh3d", "surface", "cone", "streamtube", "isosurface", "volume")


def webgl(figure: dict[str, Any]) -> bool:
    """Whether a figure (plotly JSON) draws a WebGL scene."""
    return any(trace.get("type") in WEBGL_TRACES for trace in figure.get("data", []))


class FigureCard:
    """A plotly figure from :mod:`crankbalance.output.figures` with PNG/SVG/CSV/JSON downloads."""

    def __init__(
        self, page: TabContext, name: str, title: str, builder: Callable[[], Any | None]
    ) -> None:
        self.page, self.name, self.title, self.builder = page, name, title, builder
        self.figure: Any | None = None
        self.stale = True
        #: a WebGL figure not sent yet (see :meth:`refresh`) and the timer that sends it
        self.held: dict[str, Any] | None = None
        self.draw_later: Any | None = None
        #: the figure the browser has (JSON), sent again only when it changes
        self.sent: str | None = None
        #: the still picture of a 3-D figure shown until the browser has drawn it
        #: (:func:`~crankbalance.output.figures.crank3d_preview.scene_svg`), made only for
        #: a figure held back while the page is built
        self.preview: Any | None = None
        with ui.card().classes("w-full") as self.card:
            with ui.element("div").classes(
                "w-full flex flex-wrap items-center justify-between gap-1"
            ):
                ui.label(title).classes("text-subtitle1")
                with button_row():
                    formats: tuple[FigureFormat, ...] = ("png", "svg", "csv", "json")
                    for fmt in formats:
                        ui.button(fmt.upper(), on_click=lambda f=fmt: self.download(f)).props(
                            "flat dense size=sm"
                        ).mark(f"download-{name}-{fmt}")
            self.note = ui.label("").classes("text-grey-7")
            with ui.element("div").classes("cb-figure-box") as self.box:
                self.plot = (
                    ui.plotly({"data": [], "layout": {}, "config": FIGURE_CONFIG})
                    .classes("w-full cb-figure")
                    .props(f"data-testid=figure-{name}")
                    .mark(f"figure-{name}")
                )

    def refresh(self) -> None:
        from plotly.utils import PlotlyJSONEncoder

        try:
            self.figure = self.builder()
        except InputError as error:
            self.figure = None
            self.note.set_text(str(error))
        if self.figure is None:
            self.plot.set_visibility(False)
            self.sent = None
            return
        self.note.set_text(ALL_ZERO if all_zero(self.figure) else "")
        self.plot.set_visibility(True)
        shown = self.figure.to_plotly_json()
        layout = {**shown.get("layout", {}), **FIGURE_LAYOUT}
        for key, span in value_ranges(self.figure, layout).items():
            layout[key] = {**layout.get(key, {}), "range": span, "autorange": False}
        layout["legend"] = {**layout.get("legend", {}), **LEGEND}
        title = layout.get("title")
        if isinstance(title, dict) and isinstance(title.get("text"), str):
            layout["title"] = {**title, "text": without_card_title(title["text"], self.title)}
        layout.update(title_layout(layout))
        # the height goes to the element (CSS), so that a phone can make room for the legend
        height = int(layout.pop("height", None) or DEFAULT_HEIGHT)
        # subplots side by side are stacked on a phone (FIGURE_JS applies the relayouts kept
        # in the layout's meta); the figure grows by a row's height for each column
        stack = phone_stack(layout)
        columns = subplot_columns(layout) if stack else 1
        if stack:
            layout["meta"] = {**(layout.get("meta") or {}), "cbStack": stack}
        phone = height * columns + PHONE_LEGEND_LINE * legend_entries(shown.get("data", []))
        self.plot.style(
            f"--cb-height: {height}px; --cb-phone-height: {phone}px; "
            f"--cb-phone-width: {PHONE_COLUMN}px"
        )
        shown["layout"] = layout
        shown["config"] = FIGURE_CONFIG
        self.stale = False
        # an edit that leaves the figure as it is (the speed, for the 3-D crank) redraws
        # nothing: a 3-D scene costs the browser a fifth of a second in software WebGL
        sent = json.dumps(shown, cls=PlotlyJSONEncoder)
        if sent == self.sent:
            return
        self.sent = sent
        if webgl(shown) and not self.plot.client.has_socket_connection:
            # the page is being built: its first paint (the form and the 2-D results) comes
            # first, the 3-D scene (software WebGL: the heaviest drawing of the page) after
            self.held = shown
            self.note.set_text(DRAWING)
            self.show_preview(shown)
            if self.draw_later is None:
                with self.card:
                    self.draw_later = ui.timer(0, self.draw_held, once=True)
            return
        self.held = None
        self.plot.update_figure(shown)

    def show_preview(self, shown: dict[str, Any]) -> None:
        """Show the still picture of the 3-D figure ``shown`` (plotly JSON) in its place,
        sent with the page; the page's CSS hides it once plotly.js has drawn the scene."""
        from ..output.figures.crank3d_preview import scene_svg

        picture = scene_svg(shown)
        if self.preview is None:
            with self.box:
                self.preview = (
                    ui.html(picture, sanitize=False)  # made here, from numbers and colours
                    .classes("cb-preview")
                    .props(f"data-testid=preview-{self.name}")
                    .mark(f"preview-{self.name}")
                )
        else:
            self.preview.set_content(picture)

    def draw_held(self) -> None:
        """Send the figure held back while the page was built (runs once the browser has
        connected, i.e. after the page's first paint)."""
        if self.held is not None:
            self.note.set_text("")
            self.plot.update_figure(self.held)
            self.held = None

    async def download(self, fmt: FigureFormat) -> None:
        if self.figure is None or self.stale:
            self.refresh()
        if self.figure is None:
            ui.notify("nothing to download yet", type="warning")
            return
        if fmt == "csv":
            send_download(figure_csv(self.figure), f"{self.name}.csv", "text/csv")
        elif fmt == "json":
            send_download(
                figure_json(self.figure, self.title), f"{self.name}.json", "application/json"
            )
        else:
            await self.image(fmt)

    async def image(self, fmt: Literal["png", "svg"]) -> None:
        """A PNG or SVG of the figure, made by plotly.js in the user's browser from the traces
        already drawn (no server round trip through kaleido), with the figure's own layout
        and size (that of :func:`crankbalance.output.render.to_image`, not the page's: its width and
        height, else 1000 x 600 px). Where the browser cannot (the figure is not drawn yet,
        or plotly.js fails there), the server's :func:`~crankbalance.output.render.to_image`."""
        figure = self.figure
        assert figure is not None
        try:
            result = await ui.run_javascript(
                browser_image_js(self.plot.id, figure, fmt, self.name), timeout=IMAGE_TIMEOUT
            )
            if result == NOT_DRAWN:  # the page has not drawn it yet: its traces are sent too
                result = await ui.run_javascript(
                    browser_image_js(self.plot.id, figure, fmt, self.name, with_data=True),
                    timeout=IMAGE_TIMEOUT,
                )
        except TimeoutError:  # the page did not answer (e.g. it was reloaded meanwhile)
            log.warning("image export: the browser did not answer within %g s", IMAGE_TIMEOUT)
            ui.notify(f"{fmt.upper()} export: the page did not answer; try again", type="warning")
            return
        if result == "ok" or result is None:  # done, or the page was closed meanwhile
            return
        log.warning("image export in the browser failed (%s): made by the server", result)
        try:
            data = await run.io_bound(render.to_image, figure, fmt)
        except Exception as error:  # kaleido / browser problems must not kill the page
            log.warning("image export failed: %s", error)
            ui.notify(f"{fmt.upper()} export failed: {error}", type="negative")
            return
        if data is None:  # NiceGUI is shutting down: the export was cancelled
            ui.notify(f"{fmt.upper()} export cancelled (server stopping)", type="warning")
            return
        media = "image/png" if fmt == "png" else "image/svg+xml"
        send_download(data, f"{self.name}.{fmt}", media)


class Tab(ABC):
    """One tab of the page, given the page's context (:class:`~.context.TabContext`, kept
    as :attr:`page`). The shell (:class:`~.app.Page`) calls :meth:`build` inside the
    tab's panel (with the page, or when the tab is first opened: :attr:`built`),
    :meth:`show` after each recompute of a valid engine and :meth:`reset` when another
    project is loaded; the figure cards of the tab are in :attr:`cards` (refreshed by the
    shell when the tab is shown)."""

    #: the tab's name in :data:`~.app.TABS`
    name = ""
    #: whether :meth:`build` has run: the shell builds the first screen's tabs with the
    #: page and every other tab when it is first opened, and calls :meth:`show`,
    #: :meth:`reset` and :meth:`show_errors` only on built tabs
    built = False

    def __init__(self, page: TabContext) -> None:
        self.page = page
        self.cards: list[FigureCard] = []

    @abstractmethod
    def build(self) -> None:
        """Lay out the tab's inputs, tables and figure cards (inside its panel)."""

    def show(self, c: Any) -> None:  # noqa: B027 (optional: most tabs show only figures)
        """Show the numbers of the newly computed engine ``c``."""

    def show_fresh(self, fresh: bool, problem: str) -> None:  # noqa: B027 (optional)
        """Whether the computed engine is the form's (``fresh``), else why not (``problem``):
        a tab that shows numbers outside the greyed result tabs (the Masses tab's resulting
        masses) hides them while the form cannot be computed."""

    def reset(self) -> None:  # noqa: B027 (optional: only study tabs keep results)
        """Forget the results of the previous project (a new one was loaded)."""

    def show_errors(self, errors: dict[str, str]) -> None:  # noqa: B027 (optional)
        """Show the messages of the tab's own inputs (``errors`` by key)."""

    def card(self, name: str, title: str, builder: Callable[[], Any | None]) -> FigureCard:
        """A figure card of this tab, refreshed with the tab."""
        card = FigureCard(self.page, name, title, builder)
        self.cards.append(card)
        return card

    def computed(self, build: Callable[[Any], Any]) -> Callable[[], Any | None]:
        """A figure builder on the current computed engine (none while there is none)."""

        def builder() -> Any | None:
            c = self.page.project.computed
            return None if c is None else build(c)

        return builder

    def study_ready(self) -> Any | None:
        c = self.page.fresh()
        if c is None:
            ui.notify(f"Not computed: {self.page.problem()}", type="warning", multi_line=True)
        return c


class StudyTab(Tab):
    """A tab whose study runs when the user asks. Its result belongs to what it was run for,
    :meth:`stamp`: the engine (:attr:`~.app.Page.computed_for`, the one rule of
    :meth:`~.app.Page.fresh`: results belong to (engine spec, orders)) and the study's own
    settings as typed (those whose keys start with :attr:`prefixes`). Once the form's
    computed engine is another one, or one of those settings is edited, the result is
    cleared and the tab says "Not computed for this engine (or these settings): re-run";
    going back to the old engine or value does not bring it back, only a new run does."""

    #: :meth:`stamp` of the shown result; None while there is none
    result_for: tuple[Any, ...] | None = None
    #: the setting keys of this study start with one of these (``("cw_",)``)
    prefixes: tuple[str, ...] = ()
    #: the study in words, for messages ("the counterweight optimiser")
    what = "the study"

    def stamp(self) -> tuple[Any, ...]:
        """What a run started now belongs to: the engine and the study's settings."""
        own = tuple(
            (key, str(value).strip())
            for key, value in sorted(self.page.project.settings.items())
            if key.startswith(self.prefixes)
        )
        return (self.page.computed_for, own)

    def settings(self, *keys: str) -> None:
        """The inputs of the study's settings (inside the current layout element); an edit
        of one marks the shown result as not computed for these settings."""
        for key in keys:
            assert key.startswith(self.prefixes), f"{key} is no setting of the {self.name} tab"
            self.page.setting(key, self.settings_changed)

    def rerun_note(self) -> None:
        """The note shown in place of a cleared result (call it in :meth:`build`)."""
        self.rerun = (
            ui.label("")
            .classes("text-orange-10 text-body1")
            .props(f"data-testid={self.name}-rerun")
            .mark(f"{self.name}-rerun")
        )
        self.rerun.set_visibility(False)

    @abstractmethod
    def clear(self) -> None:
        """Forget the study's result and empty everything that shows it."""

    def show(self, c: Any) -> None:
        if self.result_for is not None and self.result_for[0] != self.page.computed_for:
            self.drop(f"this engine ({c.spec.name})")

    def settings_changed(self) -> None:
        if self.result_for is not None and self.result_for != self.stamp():
            self.drop("these settings")

    def cancel_button(self) -> None:
        """The study's *Cancel* button (in the current layout element), shown while its run
        waits for or holds a worker (:meth:`in_worker`)."""
        self.cancel = (
            ui.button("Cancel", on_click=self.cancel_run)
            .props(f"outline color=negative data-testid={self.name}-cancel")
            .mark(f"{self.name}-cancel")
        )
        self.cancel.set_visibility(False)

    def cancel_run(self) -> None:
        """Stop this tab's running study: its worker process is ended."""
        job = self.page.job
        if job is not None and job.owner == self.name:
            job.cancel()

    async def in_worker(
        self,
        what: str,
        function: Callable[..., Any],
        *args: Any,
        progress: Callable[[Any], None] | None = None,
    ) -> Any | None:
        """``function(*args)`` in a worker process (:func:`.pool.run`: bounded, second to
        the server, ended by :meth:`cancel_run` or when the page goes away); its result,
        None when cancelled. A page runs one study at a time; the study's own
        :class:`InputError` is raised (a second study of the page is refused with one).
        ``progress`` is given each progress report of the study (:func:`.pool.report`), on
        the server's event loop."""
        from . import pool

        page = self.page
        if page.job is not None:
            raise InputError(
                "study",
                page.job.what,
                "is still running on this page: wait for it or cancel it on its tab",
            )
        job = pool.Job(what, owner=self.name)
        job.on_progress = progress
        page.job = job
        self.cancel.set_visibility(True)
        try:
            return await pool.run(job, function, *args)
        except pool.Cancelled:
            return None
        finally:
            page.job = None
            self.cancel.set_visibility(False)

    def reset(self) -> None:
        self.result_for = None
        self.clear()
        self.rerun.set_visibility(False)

    def owns(self, started: tuple[Any, ...]) -> bool:
        """After a run that started at :meth:`stamp` ``started``: whether its result may be
        shown (the form's engine and the study's settings are still those); else the
        result is dropped."""
        now = self.stamp()
        if started[0] is not None and started == now:
            self.result_for = started
            self.rerun.set_visibility(False)
            return True
        c = self.page.project.computed
        engine = f"this engine ({c.spec.name if c is not None else ''})"
        self.drop(engine if started[0] != now[0] else "these settings")
        return False

    def drop(self, what: str) -> None:
        """Clear the result: it was computed for another engine or other settings."""
        self.result_for = None
        self.clear()
        self.rerun.set_text(f"Not computed for {what}: re-run the study.")
        self.rerun.set_visibility(True)


def plot_or_none(name: str, *args: Any) -> Any | None:
    """The figure ``figures.<name>(*args)``, or None while an argument is missing."""
    if any(a is None for a in args):
        return None
    builder = getattr(figures, name, None)
    if builder is None:
        raise InputError("figure", name, "is not available in this version of figures.py")
    return builder(*args)


def fmt_g(value: float) -> str:
    """A number in the one output vocabulary (5 significant digits, no -0)."""
    return number(float(value), 5)


def distinct(values: Any) -> str:
    """Masses [kg] as shown: one value when all cylinders (throws) agree, else each in turn
    (an engine file may override the masses of some cylinders)."""
    return ", ".join(dict.fromkeys(f"{float(v):.4f}" for v in values))


def send_download(content: str | bytes, filename: str, media_type: str) -> None:
    """Send a file to the browser (always as bytes: a str would be taken for a URL by some
    download implementations, e.g. NiceGUI's simulated user)."""
    data = content.encode("utf-8") if isinstance(content, str) else content
    ui.download.content(data, filename, media_type)


def from_schema(
    model: type[Schema], name: str, *, default: str | None = None, hint: str = ""
) -> tuple[str, str, str]:
    """A row of a tab's own settings table (:attr:`TabSettingsMixin.settings_table`) that is
    the field ``name`` of the settings schema ``model``: (label, default text, hint), the
    schema's title and default, and its hint or else what it allows. A tab gives its own
    ``default`` only where the page writes the schema's default its own way (a select's
    ``on`` for a flag, a study's choice where the schema leaves it empty), never another run
    than the command line's; and its own ``hint`` (an example, or where the page writes the
    value its own way) only where the schema has none or another."""
    spec = model.FIELDS[name]
    text = default_text(spec) if default is None else default
    return spec.title, text, hint or spec.hint or allowed(spec)


def schema_choices(model: type[Schema], name: str) -> tuple[str, ...]:
    """The choices of a setting's select: the schema's."""
    return tuple(str(choice) for choice in model.FIELDS[name].choices)


class TabSettingsMixin:
    """A study tab whose settings are its own fields (not the project's settings): their
    texts in :attr:`texts`, the inputs in :attr:`fields`, each input named
    ``<tab name>-<key>`` for tests. An edit stores the text and calls ``self.check()``."""

    name: str
    page: TabContext
    texts: dict[str, str]
    fields: dict[str, Any]
    #: key -> (label, default text, hint) of each setting, in the order of the form
    settings_table: Mapping[str, tuple[str, str, str]]
    #: the setting beside which an error that names none of the tab's settings is shown
    fallback: str
    #: key -> the choices of a select
    choices: Mapping[str, Sequence[str]] = {}
    #: keys of multi-line text areas
    multiline: tuple[str, ...] = ()
    #: the tab's settings parsed from their texts (raises InputError naming the setting)
    parse_settings: Callable[[dict[str, str]], Any]
    #: the tab's study, ``function(engine spec, *parsed settings)``, for :meth:`run` (the
    #: explorer, which needs no engine, has a run of its own)
    study_function: Callable[[], Callable[..., Any]]
    #: the study's work budget, ``check(engine spec, *parsed settings)``, raising an
    #: InputError before the run when the work is over it; None: the settings' own limits
    #: are its budget
    work_check: Callable[[], Callable[..., None]] | None = None
    #: the tab's own (:class:`StudyTab`): whether the result of a run that started at
    #: ``started`` may be shown
    owns: Callable[[Any], bool]
    settings_changed: Callable[[], None]
    study_ready: Callable[[], Any | None]
    #: the tab's summary (markdown) and busy spinner
    summary: Any
    spinner: Any
    #: the tab's own (:class:`StudyTab`): the study in words, a study in a worker process,
    #: its Cancel button
    what: str
    in_worker: Callable[..., Coroutine[Any, Any, Any | None]]
    cancel_button: Callable[[], None]
    #: the result of the last run (:meth:`run`) and the tab's own way of showing it
    study: Any = None
    show_study: Callable[[], None]

    def settings_card(
        self,
        title: str,
        width: str,
        run_label: str = "Run",
        before_run: Callable[[], object] | None = None,
        starts: Mapping[str, str] | None = None,
    ) -> None:
        """The card of the tab's settings, in the current layout element: an input per
        setting of :attr:`settings_table` (with its default text, or its text of ``starts``:
        an input is made with the text it starts from, never set after it is sent, which
        could overwrite what the user types into it first), then a row of ``before_run``'s
        buttons, the run button (:meth:`run`) and the busy spinner."""
        self.texts = {k: (starts or {}).get(k, v[1]) for k, v in self.settings_table.items()}
        self.fields = {}
        with ui.card().classes(width):
            ui.label(title).classes("text-subtitle1")
            for key, (label, _default, hint) in self.settings_table.items():
                self.field(key, label, self.texts[key], hint)
            with ui.row().classes("items-center gap-2"):
                if before_run is not None:
                    before_run()
                ui.button(run_label, on_click=self.run).props("color=primary").mark(
                    f"{self.name}-run"
                )
                self.spinner = ui.spinner(size="md").props(f"data-testid={self.name}-busy")
                self.spinner.set_visibility(False)
                self.cancel_button()

    def field(self, key: str, label: str, default: str, hint: str) -> None:
        """One input of the tab's settings, in the current layout element."""

        def changed(event: Any, key: str = key) -> None:
            self.texts[key] = "" if event.value is None else str(event.value)
            self.check()

        element: Any
        if key in self.choices:
            element = ui.select(
                list(self.choices[key]), value=default, label=label, on_change=changed
            )
        elif key in self.multiline:
            element = ui.textarea(label=label, value=default, placeholder=hint, on_change=changed)
            element.props("rows=6")
        else:
            element = ui.input(label=label, value=default, placeholder=hint, on_change=changed)
            element.props(f'hint="{hint}"')
        element.classes("w-full").props(f"data-testid={self.name}-{key} hide-bottom-space")
        element.mark(f"{self.name}-{key}").without_auto_validation()
        self.fields[key] = element

    def current_settings(self) -> tuple[tuple[str, str], ...]:
        """The tab's settings as typed: what its result belongs to."""
        return tuple(sorted((k, v.strip()) for k, v in self.texts.items()))

    def check(self) -> Any | None:
        """Show the settings' errors beside their fields (in the field's label words); the
        parsed settings or None. A result of other settings is dropped."""
        for element in self.fields.values():
            element.error = None
        self.settings_changed()
        try:
            return self.parse_settings(self.texts)
        except InputError as error:
            self.show_error(error)
            return None

    def stamp(self) -> tuple[Any, ...]:
        """What a run started now belongs to: the engine and the tab's settings as typed."""
        return (self.page.computed_for, self.current_settings())

    def show_error(self, error: InputError) -> None:
        """An error of the settings beside its field, in the words of the form (the field's
        label in place of its key); one that names no setting of the tab beside
        :attr:`fallback`."""
        key = error.field if error.field in self.fields else self.fallback
        message = str(error)
        if message.startswith(error.field):
            message = self.settings_table[key][0] + message[len(error.field) :]
        self.fields[key].error = message

    async def run(self) -> None:
        """Run the tab's study (:meth:`study_function`) on the form's engine and show it."""
        done = await self.run_study(
            self.study_function(), lambda parsed, c: (c.spec, *parsed), "running …"
        )
        if done is not None:
            self.study = done[1]
            self.show_study()

    async def run_study(
        self,
        function: Callable[..., Any],
        arguments: Callable[[Any, Any], tuple[Any, ...]],
        running: str,
        engine: bool = True,
    ) -> tuple[Any, Any] | None:
        """Run ``function(*arguments(settings, computed engine))`` in a worker process
        (:meth:`StudyTab.in_worker`): the settings parsed by :meth:`check` (with ``engine``,
        only while the form's engine is computed: else None), the spinner and the Cancel
        button shown and the summary saying ``running`` meanwhile. The settings and the
        result, or None when it cannot run, fails (the summary says why; an error of one of
        the tab's settings shows beside it too), is cancelled, or the engine or settings
        were changed meanwhile (:meth:`owns`)."""
        parsed = self.check()
        if parsed is None:
            self.summary.set_content("Not run: see the message beside the field.")
            return None
        c = self.study_ready() if engine else None
        if engine and c is None:
            return None
        started = self.stamp()
        self.spinner.set_visibility(True)
        self.summary.set_content(running)
        try:
            if self.work_check is not None and c is not None:  # before the run starts
                self.work_check()(c.spec, *parsed)
            result = await self.in_worker(self.what, function, *arguments(parsed, c))
        except InputError as error:
            self.summary.set_content(str(error))
            if error.field in self.fields:
                self.show_error(error)
            return None
        finally:
            self.spinner.set_visibility(False)
        if result is None:
            self.summary.set_content(CANCELLED)
            return None
        return (parsed, result) if self.owns(started) else None
