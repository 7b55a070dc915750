"""Rendering: static images through kaleido and self-contained interactive HTML."""

from __future__ import annotations

import re
import shutil
from typing import Any

import pytest

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

from crankbalance import figures, render  # noqa: E402
from crankbalance.errors import InputError  # noqa: E402
from crankbalance.studies.engine import analyze  # noqa: E402


@pytest.fixture(scope="module")
def fig() -> Any:
    return figures.orders_bar(analyze("inline4"))


chromium = pytest.mark.skipif(
    not (shutil.which("chromium") or shutil.which("google-chrome")),
    reason="static export needs a Chromium for kaleido (apt package chromium)",
)


@chromium
def test_to_image_png_and_svg(fig: Any) -> None:
    png = render.to_image(fig, "png", width=500, height=300)
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    # IHDR: width and height as asked
    assert int.from_bytes(png[16:20], "big") == 500 and int.from_bytes(png[20:24], "big") == 300
    svg = render.to_image(fig, "svg")
    assert svg.lstrip().startswith(b"<svg") and b"</svg>" in svg
    with pytest.raises(InputError, match="format"):
        render.to_image(fig, "gif")  # type: ignore[arg-type]


def test_to_html_is_self_contained(fig: Any) -> None:
    html = render.to_html(fig)
    assert html.lstrip().lower().startswith("<!doctype html>")
    assert not re.search(r"<script[^>]*\ssrc=", html), "plotly.js must be inlined"
    assert "Plotly.newPlot" in html
