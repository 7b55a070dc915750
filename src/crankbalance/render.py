"""Turning figures and HTML pages into files: the one place that talks to kaleido and
Chromium.

Owns the kaleido server (one headless Chromium, started on first use and reused, closed at
exit), static images of figures (:func:`to_image`), interactive HTML of figures
(:func:`to_html`), the Chromium lookup and command-line flags (:data:`CHROMIUM_FLAGS`,
:func:`find_chromium`) and printing HTML to PDF (:func:`html_to_pdf`). The figures
themselves come from :mod:`crankbalance.figures`, the report page from
:mod:`crankbalance.report`. plotly and kaleido are imported inside the functions.

Public functions
----------------
- ``to_image(fig, fmt="png", width=None, height=None, scale=1.0) -> bytes``
    Static PNG or SVG through kaleido (Chromium: found by kaleido, else /usr/bin/chromium).
- ``to_html(fig, include_plotlyjs=True, full_html=True, div_id=None) -> str``
    Interactive HTML; plotly.js inlined by default (no network needed).
- ``find_chromium(chromium=None) -> str``
    Path of a Chromium for printing.
- ``html_to_pdf(html, chromium=None, timeout=120) -> bytes``
    Print an HTML document to PDF with headless Chromium (no network, fresh profile).
"""

from __future__ import annotations

import atexit
import contextlib
import os
import shutil
import subprocess
import tempfile
import threading
from pathlib import Path
from typing import TYPE_CHECKING, Literal

from .errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    import plotly.graph_objects as go

ImageFormat = Literal["png", "svg"]
#: command-line flags of every headless Chromium crankbalance starts (PDF printing, tests,
#: benchmarks): no sandbox, GPU, network services or first-run pages
CHROMIUM_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-pdf-header-footer",
)


# --------------------------------------------------------------------------- images
def _ensure_browser() -> None:
    """Point kaleido (choreographer) at Debian's chromium when it finds no browser."""
    if os.environ.get("BROWSER_PATH"):
        return
    for candidate in (
        "/usr/bin/chromium",
        "/usr/bin/chromium-browser",
        shutil.which("chromium") or "",
        shutil.which("google-chrome") or "",
    ):
        if candidate and os.path.exists(candidate):
            os.environ["BROWSER_PATH"] = candidate
            return


def to_image(
    fig: go.Figure,
    fmt: ImageFormat = "png",
    width: int | None = None,
    height: int | None = None,
    scale: float = 1.0,
) -> bytes:
    """Static image of a figure (PNG or SVG bytes) through kaleido and a headless Chromium.

    The first call starts one kaleido server (a headless Chromium, closed at exit) that
    later calls reuse (about 0.1 s per image instead of 2-3 s). MathJax is switched off so
    that no network access is needed. Width and height default to the figure's own
    layout size, else 1000 x 600 px.
    """
    if fmt not in ("png", "svg"):
        raise InputError("format", fmt, "'png' or 'svg'")
    import kaleido

    _ensure_browser()
    layout = fig.layout
    opts = {
        "format": fmt,
        "width": width or layout.width or 1000,
        "height": height or layout.height or 600,
        "scale": scale,
    }
    fig_dict = fig.to_dict()
    with _SERVER_LOCK:
        _start_server()
        data = kaleido.calc_fig_sync(fig_dict, opts=opts)
    return data if isinstance(data, bytes) else str(data).encode()


_SERVER_LOCK = threading.Lock()
_SERVER: dict[str, bool] = {"running": False}


def _start_server() -> None:
    import kaleido

    if _SERVER["running"]:
        return
    kaleido.start_sync_server(mathjax=False, silence_warnings=True)
    _SERVER["running"] = True
    atexit.register(_stop_server)


def _stop_server() -> None:
    import kaleido

    if _SERVER["running"]:
        _SERVER["running"] = False
        # at exit, a browser that is already gone is fine
        with contextlib.suppress(Exception):
            kaleido.stop_sync_server(silence_warnings=True)


def to_html(
    fig: go.Figure,
    include_plotlyjs: bool | str = True,
    full_html: bool = True,
    div_id: str | None = None,
) -> str:
    """Interactive HTML of a figure; plotly.js inlined by default (works offline)."""
    import plotly.io as pio

    return str(
        pio.to_html(
            fig,
            include_plotlyjs=include_plotlyjs,
            full_html=full_html,
            div_id=div_id,
            config={"displaylogo": False},
        )
    )


# --------------------------------------------------------------------------- PDF
def find_chromium(chromium: str | None = None) -> str:
    """Path of a Chromium for printing: ``chromium``, $CRANKBALANCE_CHROMIUM, $BROWSER_PATH,
    /usr/bin/chromium or chromium/google-chrome on the PATH."""
    if chromium is not None and not (os.path.isfile(chromium) and os.access(chromium, os.X_OK)):
        raise InputError("chromium", chromium, "an executable Chromium (e.g. /usr/bin/chromium)")
    for candidate in (
        chromium,
        os.environ.get("CRANKBALANCE_CHROMIUM"),
        os.environ.get("BROWSER_PATH"),
        "/usr/bin/chromium",
        shutil.which("chromium"),
        shutil.which("chromium-browser"),
        shutil.which("google-chrome"),
    ):
        if candidate and os.path.exists(candidate):
            return candidate
    raise InputError(
        "chromium",
        chromium or "not found",
        "a Chromium executable to print the PDF (apt package chromium, or set "
        "CRANKBALANCE_CHROMIUM)",
    )


def html_to_pdf(html: str, chromium: str | None = None, timeout: float = 120.0) -> bytes:
    """Print an HTML document to PDF with headless Chromium (no network, fresh profile).

    Chromium prints into a private scratch folder and the bytes are returned, checked to be
    a whole PDF: the caller writes them with :func:`crankbalance.io.files.write_atomic`,
    which reports the real error (e.g. a full disk) of the write that matters."""
    from .io.files import write_atomic

    exe = find_chromium(chromium)
    with tempfile.TemporaryDirectory(prefix="crankbalance-report-") as tmp:
        page = Path(tmp) / "report.html"
        out = Path(tmp) / "report.pdf"
        write_atomic(page, html)
        command = [
            exe,
            *CHROMIUM_FLAGS,
            f"--user-data-dir={Path(tmp) / 'profile'}",
            f"--print-to-pdf={out}",
            page.as_uri(),
        ]
        try:
            done = subprocess.run(command, capture_output=True, timeout=timeout, check=False)
        except subprocess.TimeoutExpired:
            raise InputError("chromium", exe, f"to print the PDF within {timeout:g} s") from None
        pdf = out.read_bytes() if out.exists() else b""
        # a printer stopped part way (e.g. its scratch disk full) leaves no %%EOF at the end
        if not (pdf.startswith(b"%PDF-") and b"%%EOF" in pdf[-1024:]):
            tail = done.stderr.decode(errors="replace").strip().splitlines()[-3:]
            raise InputError(
                "chromium", exe, "a Chromium that prints PDFs (it failed: " + " | ".join(tail) + ")"
            )
        return pdf
