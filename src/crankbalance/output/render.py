"""Turning figures and HTML pages into files: the one place that talks to kaleido and
Chromium.

Owns the figure exporter (one headless Chromium driven by kaleido, started on first use,
reused, started again if it dies, closed at exit), static images of figures
(:func:`to_image`), interactive HTML of figures (:func:`to_html`), the Chromium lookup and
command-line flags (:data:`CHROMIUM_FLAGS`, :func:`find_chromium`) and printing HTML to PDF
(:func:`html_to_pdf`). The figures
themselves come from :mod:`crankbalance.output.figures`, the report page from
:mod:`crankbalance.output.report`. plotly and kaleido are imported inside the functions.

Public functions
----------------
- ``to_image(fig, fmt="png", width=None, height=None, scale=1.0) -> bytes``
    Static PNG or SVG through kaleido and one kept headless Chromium (:func:`find_chromium`).
- ``to_html(fig, include_plotlyjs=True, full_html=True, div_id=None) -> str``
    Interactive HTML; plotly.js inlined by default (no network needed).
- ``find_chromium(chromium=None) -> str``
    Path of a Chromium for printing.
- ``html_to_pdf(html, chromium=None, timeout=120) -> bytes``
    Print an HTML document to PDF with headless Chromium (no network, fresh profile).
- ``Exporter(chromium=None)``, ``EXPORTER``
    The kept browser behind :func:`to_image` (``EXPORTER.pid()``: its launcher's process
    id, for tests and benchmarks that watch it).
"""

from __future__ import annotations

import asyncio
import atexit
import concurrent.futures
import contextlib
import os
import shutil
import subprocess
import tempfile
import threading
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from ..errors import InputError
from .figures.common import readable

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
#: the flags above that concern printing only (a browser that kaleido drives does not start
#: with them)
_PRINT_FLAGS = ("--no-pdf-header-footer",)


# --------------------------------------------------------------------------- images
#: hang guards of the exporter [s]: starting Chromium, and one image (kaleido's own timeout)
_OPEN_TIMEOUT = 120.0
_IMAGE_TIMEOUT = 90.0


class Exporter:
    """One headless Chromium (a ``kaleido.Kaleido``) kept open for every image of a process.

    kaleido 1.x starts a Chromium per call unless one is kept open; its own sync server
    (``kaleido.start_sync_server``) waits forever when the browser fails to start and goes
    on with a dead browser. This one runs the browser's event loop on a daemon thread,
    waits for every answer with a hang guard, starts the browser again once when it has
    died (before or during an export), and closes it at exit. Chromium is
    :func:`find_chromium`'s (Debian's ``/usr/bin/chromium`` unless told otherwise),
    started with the :data:`CHROMIUM_FLAGS` that kaleido does not pass itself (printing flags
    aside).
    """

    def __init__(self, chromium: str | None = None) -> None:
        self._chromium = chromium
        self._lock = threading.Lock()
        self._loop: asyncio.AbstractEventLoop | None = None
        self._thread: threading.Thread | None = None
        self._browser: Any = None  # kaleido.Kaleido

    def _run(self, coroutine: Any, timeout: float) -> Any:
        """Run a coroutine on the browser's loop and wait for it at most ``timeout`` s."""
        assert self._loop is not None
        future = asyncio.run_coroutine_threadsafe(coroutine, self._loop)
        try:
            return future.result(timeout)
        except concurrent.futures.TimeoutError:
            future.cancel()
            raise

    def pid(self) -> int | None:
        """Process id of the running browser's launcher (Chromium is its child), else None."""
        browser = self._browser
        if browser is None or browser.subprocess.poll() is not None:
            return None
        return int(browser.subprocess.pid)

    def _open(self) -> None:
        import logging

        import kaleido
        from choreographer.browsers import Chromium

        # choreographer reads the browser's pipe in pieces; a message split between two
        # reads (seen under load, at the browser's exit) fails to decode and is dropped,
        # "Ignoring", with its traceback logged to stderr. The message is dropped either
        # way; its traceback is no message for a user, so that one logger stays quiet.
        logging.getLogger("choreographer.channels.pipe").setLevel(logging.CRITICAL)

        class FlaggedChromium(Chromium):
            def get_cli(self) -> list[str]:
                cli = list(super().get_cli())
                extra = [f for f in CHROMIUM_FLAGS if f not in cli and f not in _PRINT_FLAGS]
                return cli + extra

        exe = find_chromium(self._chromium)
        if self._loop is None:
            self._loop = asyncio.new_event_loop()
            self._thread = threading.Thread(
                target=self._loop.run_forever, name="crankbalance-chromium", daemon=True
            )
            self._thread.start()
        browser = kaleido.Kaleido(
            path=exe, browser_cls=FlaggedChromium, mathjax=False, timeout=_IMAGE_TIMEOUT
        )
        try:
            self._run(browser.open(), _OPEN_TIMEOUT)
        except Exception as error:
            with contextlib.suppress(Exception):
                self._run(browser.close(), _OPEN_TIMEOUT)
            reason = str(error.args[0]) if error.args else type(error).__name__
            raise InputError(
                "chromium", exe, f"a Chromium that starts headless for kaleido ({reason})"
            ) from None
        self._browser = browser
        # (re)registered after the browser made its temporary directories, so that it runs
        # before their finalizers at exit (atexit is last in, first out)
        atexit.unregister(self.close)
        atexit.register(self.close)

    def _close_browser(self) -> None:
        browser, self._browser = self._browser, None
        if browser is not None:
            with contextlib.suppress(Exception):  # a browser that is already gone is fine
                self._run(browser.close(), _OPEN_TIMEOUT)

    def _image(self, figure: dict[str, Any], opts: dict[str, Any]) -> bytes:
        if self.pid() is None:
            self._close_browser()
            self._open()
        data = self._run(self._browser.calc_fig(figure, opts=opts), _IMAGE_TIMEOUT + 30.0)
        return data if isinstance(data, bytes) else str(data).encode()

    def image(self, figure: dict[str, Any], opts: dict[str, Any]) -> bytes:
        """PNG or SVG bytes of a plotly figure dictionary (kaleido ``opts``)."""
        from choreographer.errors import BrowserClosedError, BrowserFailedError, ChannelClosedError

        with self._lock:
            try:
                return self._image(figure, opts)
            except (
                BrowserClosedError,
                BrowserFailedError,
                ChannelClosedError,
                concurrent.futures.CancelledError,  # the browser died during the call
                concurrent.futures.TimeoutError,
            ):
                self._close_browser()  # the browser died or hangs: a fresh one, once
                return self._image(figure, opts)

    def close(self) -> None:
        """Close the browser and stop its thread (registered with atexit)."""
        with self._lock:
            self._close_browser()
            loop, thread, self._loop, self._thread = self._loop, self._thread, None, None
            if loop is not None and thread is not None:
                loop.call_soon_threadsafe(loop.stop)
                thread.join(_OPEN_TIMEOUT)
                if not thread.is_alive():
                    loop.close()
                atexit.unregister(self.close)


#: the one exporter of the process, which every :func:`to_image` uses
EXPORTER = Exporter()


def to_image(
    fig: go.Figure,
    fmt: ImageFormat = "png",
    width: int | None = None,
    height: int | None = None,
    scale: float = 1.0,
) -> bytes:
    """Static image of a figure (PNG or SVG bytes) through kaleido and a headless Chromium.

    The first call starts one headless Chromium (closed at exit, started again if it dies)
    that later calls reuse: a few seconds for the first image, a fraction of a second
    after. MathJax is switched off so that no network access is needed. Width and height
    default to the figure's own layout size, else 1000 x 600 px.
    """
    if fmt not in ("png", "svg"):
        raise InputError("format", fmt, "'png' or 'svg'")
    fig = readable(fig)
    layout = fig.layout
    opts = {
        "format": fmt,
        "width": width or layout.width or 1000,
        "height": height or layout.height or 600,
        "scale": scale,
    }
    return EXPORTER.image(fig.to_dict(), opts)


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
            readable(fig),
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
    from ..io.files import write_atomic

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
