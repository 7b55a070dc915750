"""Start the NiceGUI server of the web application (used by ``crankbalance web``)."""

from __future__ import annotations

import hashlib
import json
import os
import secrets
import socket
import subprocess
import sys
import threading
import time
import urllib.request
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from .startup import import_nicegui

import_nicegui()  # before any module of NiceGUI: see .startup

from . import app as webapp  # noqa: E402
from .http_guard import HEAD_TIMEOUT, head_deadline_protocol  # noqa: E402

#: the CSS NiceGUI's Tailwind runtime generates for this page, captured in a browser by
#: ``tests/web/tailwind_css.py`` (see docs/web.md, "Speed"); served in its place
TAILWIND_CSS = Path(__file__).parent / "static" / "tailwind.css"
TAILWIND_URL = "/crankbalance/tailwind.css"


def serve(
    port: int = 8080,
    preset: str = webapp.DEFAULT_PRESET,
    show: bool = False,
    head_timeout: float = HEAD_TIMEOUT,
    **options: Any,
) -> None:
    """Serve :func:`crankbalance.web.app.root` on 127.0.0.1 (blocks until stopped).

    Every request's head must arrive within ``head_timeout`` seconds
    (:mod:`crankbalance.web.http_guard`).

    The page's Tailwind classes are styled by :data:`TAILWIND_CSS`, a static stylesheet,
    instead of NiceGUI's Tailwind compiler in the browser; ``tailwind=True`` (an option of
    ``ui.run``) serves NiceGUI's compiler instead, as the tests that capture and check that
    stylesheet need.
    """
    from nicegui import app, ui

    from . import api

    api.register(app)
    app.on_startup(
        lambda: threading.Thread(target=webapp.warm_up, args=(preset,), daemon=True).start()
    )
    app.on_connect(pool_starter())
    url = f"http://127.0.0.1:{port}/"
    print(f"crankbalance web: starting on {url} (Ctrl+C stops it)", flush=True)
    app.on_startup(
        lambda: threading.Thread(target=_say_ready, args=(port, url), daemon=True).start()
    )
    tailwind = bool(options.pop("tailwind", False))
    if not tailwind:
        app.add_static_file(local_file=TAILWIND_CSS, url_path=TAILWIND_URL)
        version = hashlib.sha256(TAILWIND_CSS.read_bytes()).hexdigest()[:12]  # cache key
        ui.add_head_html(f'<link rel="stylesheet" href="{TAILWIND_URL}?v={version}">', shared=True)
    ui.run(
        webapp.page_root(preset),
        host="127.0.0.1",
        port=port,
        title="crankbalance",
        reload=False,
        show=show,
        storage_secret=secrets.token_hex(16),
        show_welcome_message=False,
        reconnect_timeout=60.0,  # see docs/web.md, "Speed": a page busy drawing answers pings late
        tailwind=tailwind,
        http=head_deadline_protocol(head_timeout),
        **options,
    )


def pool_starter() -> Callable[[], None]:
    """The server's handler of a browser's connection (its page's websocket): at the first,
    it starts the worker pool's fork server (:func:`crankbalance.web.pool.warm_up`, which
    imports :data:`~crankbalance.web.pool.PRELOAD` in a process of its own, about 0.6 s of
    CPU), in a thread; later connections do nothing. A page's websocket connects once the
    page has been sent and its scripts have run, so on a two-core machine the pool's imports
    no longer compete with a fresh server's first page (before, they ran as the browser
    loaded it); a study asked for before (the API) starts the pool itself."""
    started = threading.Event()

    def on_connect() -> None:
        if not started.is_set():
            started.set()
            from . import pool

            threading.Thread(target=pool.warm_up, daemon=True).start()

    return on_connect


#: how long [s] the "ready" line waits for the server's socket before it gives up (silently)
READY_WAIT = 600.0


def _say_ready(port: int, url: str) -> None:
    """Print the "ready" line once the server accepts connections on ``port``.

    NiceGUI's start-up handlers run before uvicorn opens its socket, so this thread tries to
    connect until it can (at most :data:`READY_WAIT` seconds).
    """
    deadline = time.monotonic() + READY_WAIT
    while time.monotonic() < deadline:
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=2):
                print(f"crankbalance web: ready, open {url} in a browser", flush=True)
                return
        except OSError:
            time.sleep(0.1)


#: [s] between two asks whether a started server answers (a fresh server's start is timed
#: from outside by bench_web.py: a coarse poll would add half of it on average)
START_POLL = 0.02


@contextmanager
def running_server(
    log: Any = subprocess.DEVNULL, timeout: float = 180.0, **options: Any
) -> Iterator[str]:
    """``crankbalance web`` in a subprocess on a free port; yields its URL, stops it after.

    Used by the end-to-end tests and the benchmarks. ``PYTEST_CURRENT_TEST`` is removed
    from the server's environment (NiceGUI would otherwise think it runs under pytest).
    ``timeout`` [s] is a hang guard for the start, generous for a loaded machine.
    ``options`` (JSON values) are passed to :func:`serve` instead of starting the command,
    e.g. ``tailwind=True``.
    """
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = int(probe.getsockname()[1])
    env = {k: v for k, v in os.environ.items() if k != "PYTEST_CURRENT_TEST"}
    command = [sys.executable, "-m", "crankbalance", "web", "--port", str(port)]
    if options:
        call = "import json, sys; from crankbalance.web.server import serve; "
        call += "serve(port=int(sys.argv[1]), **json.loads(sys.argv[2]))"
        command = [sys.executable, "-c", call, str(port), json.dumps(options)]
    proc = subprocess.Popen(
        command,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + timeout
        while True:
            if proc.poll() is not None:
                raise RuntimeError("crankbalance web exited at start")
            try:
                with urllib.request.urlopen(url + "/api/presets", timeout=2) as response:
                    if response.status == 200:
                        break
            except OSError:
                if time.monotonic() > deadline:
                    raise RuntimeError("crankbalance web did not answer") from None
                time.sleep(START_POLL)
        yield url
    finally:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
