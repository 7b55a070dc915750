"""Start the NiceGUI server of the web application (used by ``crankbalance web``)."""

from __future__ import annotations

import os
import secrets
import socket
import subprocess
import sys
import threading
import time
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from . import app as webapp


def serve(
    port: int = 8080, preset: str = webapp.DEFAULT_PRESET, show: bool = False, **options: Any
) -> None:
    """Serve :func:`crankbalance.web.app.root` on 127.0.0.1 (blocks until stopped)."""
    from nicegui import app, ui

    from . import api

    webapp.DEFAULT_PRESET = preset  # the server's default, set once before serving
    api.register(app)
    app.on_startup(lambda: threading.Thread(target=webapp.warm_up, daemon=True).start())
    ui.run(
        webapp.root,
        host="127.0.0.1",
        port=port,
        title="crankbalance",
        reload=False,
        show=show,
        storage_secret=secrets.token_hex(16),
        show_welcome_message=False,
        reconnect_timeout=60.0,  # see docs/web.md, "Speed": a page busy drawing answers pings late
        **options,
    )


@contextmanager
def running_server(log: Any = subprocess.DEVNULL, timeout: float = 180.0) -> Iterator[str]:
    """``crankbalance web`` in a subprocess on a free port; yields its URL, stops it after.

    Used by the end-to-end tests and the benchmarks. ``PYTEST_CURRENT_TEST`` is removed
    from the server's environment (NiceGUI would otherwise think it runs under pytest).
    ``timeout`` [s] is a hang guard for the start, generous for a loaded machine.
    """
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = int(probe.getsockname()[1])
    env = {k: v for k, v in os.environ.items() if k != "PYTEST_CURRENT_TEST"}
    proc = subprocess.Popen(
        [sys.executable, "-m", "crankbalance", "web", "--port", str(port)],
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
                time.sleep(0.1)
        yield url
    finally:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
