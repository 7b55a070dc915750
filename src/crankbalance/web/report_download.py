"""The web's report download: the balancing report of :mod:`crankbalance.output.report` for
the engine of the form, as HTML (interactive, the 3-D crank on screen and its flat views in
print) or PDF (printed by a headless Chromium, every figure an image), the same bytes as the
command line's ``crankbalance report -o report.html|report.pdf``.

The report is built in a worker thread (a PDF takes a few seconds: its figures are drawn by
kaleido, the page printed by Chromium); the page says it is being prepared, and a failure
(no Chromium) is one message, never a dead page.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Any

from nicegui import run, ui

from .widgets import send_download

if TYPE_CHECKING:  # pragma: no cover
    from .context import TabContext

log = logging.getLogger(__name__)

#: media type of each report format
MEDIA_TYPES = {"html": "text/html", "pdf": "application/pdf"}


def report_file(spec: Any, orders: int, fmt: str) -> bytes:
    """The report of ``spec`` with ``orders`` orders as a file's bytes (``fmt``: ``"html"``
    or ``"pdf"``), through :func:`crankbalance.output.report.report_bytes`."""
    from ..output.report import build_report, report_bytes

    return report_bytes(build_report(spec, orders), fmt)


async def download_report(page: TabContext, fmt: str = "html") -> None:
    """Send the report of the page's computed engine as ``report.<fmt>`` (``"html"`` or
    ``"pdf"``), or say why not (the form is not computed, the report failed)."""
    c = page.fresh()
    spec = page.project.spec
    if c is None or spec is None:
        ui.notify(f"Not computed: {page.problem()}", type="warning", multi_line=True)
        return
    if fmt == "pdf":
        ui.notify("Preparing the PDF report (its figures are drawn first) …", type="info")
    try:
        data = await run.io_bound(report_file, spec, len(c.analysis.forces.orders), fmt)
    except Exception as error:  # the report must never take the page down
        log.warning("report failed: %s", error)
        ui.notify(f"report failed: {error}", type="negative", multi_line=True)
        return
    if data is None:
        ui.notify("report cancelled (server stopping)", type="warning")
        return
    send_download(data, f"report.{fmt}", MEDIA_TYPES[fmt])
