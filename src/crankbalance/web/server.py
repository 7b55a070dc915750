"""Start the NiceGUI server of the web application (used by ``crankbalance web``)."""

from __future__ import annotations

import secrets
from typing import Any

from . import app as webapp


def serve(
    port: int = 8080, preset: str = webapp.DEFAULT_PRESET, show: bool = False, **options: Any
) -> None:
    """Serve :func:`crankbalance.web.app.root` on 127.0.0.1 (blocks until stopped)."""
    from nicegui import ui

    webapp.DEFAULT_PRESET = preset  # the server's default, set once before serving
    ui.run(
        webapp.root,
        host="127.0.0.1",
        port=port,
        title="crankbalance",
        reload=False,
        show=show,
        storage_secret=secrets.token_hex(16),
        show_welcome_message=False,
        reconnect_timeout=10.0,
        **options,
    )
