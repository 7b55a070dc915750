"""The building blocks of crankbalance's HTML pages (the balancing report,
:mod:`crankbalance.output.report`, and the balance shop sheet,
:mod:`crankbalance.output.shop_sheet`): the style, a number as a table cell, a table, a
figure with its caption, and the page around them with its embedded JSON.

What a page shows is its own module's business; this module only says how a page is built,
so that both pages look and read alike. Figures are turned into HTML or SVG by
:mod:`crankbalance.output.render` (imported when a figure is drawn).

Public names
------------
- ``CSS``: the style of every page (screen and print).
- ``fmt(value, digits=5) -> str``: a value as a table cell.
- ``table(header, rows, cls="") -> str``: an HTML table.
- ``figure_html(fig_id, caption, fig, static, first, screen_only=False) -> str``: a figure
  and its caption.
- ``page(title, body, data) -> str``: the whole document.
"""

from __future__ import annotations

import base64
import html as _html
from typing import TYPE_CHECKING, Any

from .format import number

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

CSS = """
body { font-family: "DejaVu Sans", Arial, sans-serif; margin: 2em auto; max-width: 1100px;
       color: #222; line-height: 1.35; }
h1 { font-size: 1.6em; margin-bottom: 0.1em; } h2 { border-bottom: 2px solid #1f3b73;
  padding-bottom: 0.15em; margin-top: 1.6em; font-size: 1.25em; }
h3 { font-size: 1.05em; margin-bottom: 0.3em; }
table { border-collapse: collapse; margin: 0.4em 0 1em 0; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.6em; text-align: right; }
th { background: #eef1f7; } td:first-child, th:first-child { text-align: left; }
.meta { color: #666; font-size: 0.9em; } .note { color: #7a4b00; }
figure { margin: 0.6em 0 1.2em 0; page-break-inside: avoid; break-inside: avoid; }
figure img { width: 100%; max-width: 1000px; } figcaption { font-size: 0.85em; color: #555; }
pre { background: #f6f6f6; padding: 0.6em; font-size: 0.8em; white-space: pre-wrap; }
@media print { body { margin: 0; max-width: none; } h2 { page-break-after: avoid; }
  table { page-break-inside: avoid; } figure.screen-only, .modebar { display: none; } }
"""


def fmt(value: Any, digits: int = 5) -> str:
    """A value as a page prints it in a table cell: a float to ``digits`` significant
    figures (:func:`crankbalance.output.format.number`), an int as is, a bool as yes/no,
    None as a dash, anything else as its escaped text."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return number(value, digits)
    return _html.escape(str(value))


def table(header: list[str], rows: list[list[Any]], cls: str = "") -> str:
    """An HTML table: the ``header`` cells (text, escaped) and one row per list of
    ``rows``, each cell through :func:`fmt`; ``cls`` is the table's class."""
    head = "".join(f"<th>{_html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{fmt(c)}</td>" for c in row) + "</tr>" for row in rows)
    return f'<table class="{cls}"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def figure_html(
    fig_id: str,
    caption: str,
    fig: go.Figure,
    static: bool,
    first: bool,
    screen_only: bool = False,
) -> str:
    """A plotly figure and its caption as a ``<figure id="figure-<fig_id>">``: an inline SVG
    image when ``static`` (for printing; 1000 px wide, the figure's own height or 560 px),
    else the interactive figure, with plotly.js inlined when it is the page's ``first``.
    ``screen_only`` (an interactive figure that does not print, a WebGL scene) hides it in
    print (class ``screen-only``); a static figure always prints."""
    from . import render

    if static:
        svg = render.to_image(fig, "svg", width=1000, height=fig.layout.height or 560)
        data = base64.b64encode(svg).decode()
        body = f'<img alt="{_html.escape(caption)}" src="data:image/svg+xml;base64,{data}"/>'
    else:
        body = render.to_html(fig, include_plotlyjs=first, full_html=False, div_id=f"fig-{fig_id}")
    cls = ' class="screen-only"' if screen_only and not static else ""
    return (
        f'<figure id="figure-{fig_id}"{cls}>{body}<figcaption>{_html.escape(caption)}'
        "</figcaption></figure>"
    )


def page(title: str, body: list[str], data: str) -> str:
    """The whole HTML document: ``title`` (text, escaped), the :data:`CSS`, the ``body``
    parts (HTML) one per line, and ``data`` (JSON text) embedded as
    ``<script type="application/json" id="crankbalance-data">`` so that a reader or a test
    can check the page against the numbers (``</`` written ``<\\/``)."""
    script = data.replace("</", "<\\/")
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8"/>\n'
        f"<title>{_html.escape(title)}</title>\n<style>{CSS}</style>\n"
        "</head>\n<body>\n"
        + "\n".join(body)
        + f'\n<script type="application/json" id="crankbalance-data">{script}</script>\n'
        "</body>\n</html>\n"
    )
