"""Rendering: static images through kaleido and self-contained interactive HTML."""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

from crankbalance.errors import InputError  # noqa: E402
from crankbalance.output import render  # noqa: E402
from crankbalance.output.figures.engine import orders_bar  # noqa: E402
from crankbalance.studies.engine import analyze  # noqa: E402


@pytest.fixture(scope="module")
def fig() -> Any:
    return orders_bar(analyze("inline4"))


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


# ------------------------------------------------------------------ the persistent exporter
linux = pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="reads /proc (Linux)")
#: hang guard for waiting on a browser process [s]; generous for a loaded machine
HANG_GUARD = 120.0


def _children(pid: int) -> list[int]:
    """Process ids of the children of ``pid`` (Linux /proc)."""
    text = Path(f"/proc/{pid}/task/{pid}/children").read_text()
    return [int(child) for child in text.split()]


def _command_line(pid: int) -> list[str]:
    return Path(f"/proc/{pid}/cmdline").read_bytes().decode().split("\0")


def _gone(pid: int) -> bool:
    """The process has exited (a zombie waiting to be reaped counts as exited)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except FileNotFoundError:
        return True
    return state in ("Z", "X")


def _wait_until(condition: Any, what: str) -> None:
    deadline = time.monotonic() + HANG_GUARD
    while not condition():
        assert time.monotonic() < deadline, f"still waiting after {HANG_GUARD:g} s: {what}"
        time.sleep(0.05)


def _is_png(data: bytes) -> bool:
    return data[:8] == b"\x89PNG\r\n\x1a\n"


@chromium
@linux
def test_exporter_keeps_one_debian_chromium_with_the_flags(fig: Any) -> None:
    assert _is_png(render.to_image(fig, "png", width=400, height=300))
    launcher = render.EXPORTER.pid()
    assert launcher is not None
    assert _is_png(render.to_image(fig, "png", width=400, height=300))
    assert render.EXPORTER.pid() == launcher, "the second image reuses the browser"
    assert render.find_chromium() in _command_line(launcher)
    (browser,) = _children(launcher)
    arguments = _command_line(browser)
    for flag in ("--headless", "--disable-quic", "--disable-background-networking"):
        assert flag in arguments
    if render.find_chromium() == "/usr/bin/chromium":  # Debian's launcher execs this one
        assert arguments[0] == "/usr/lib/chromium/chromium"


@chromium
@linux
@pytest.mark.parametrize("wait", [True, False], ids=["dead-before", "dying"])
def test_exporter_starts_a_dead_browser_again(fig: Any, wait: bool) -> None:
    assert _is_png(render.to_image(fig, "png", width=400, height=300))
    launcher = render.EXPORTER.pid()
    assert launcher is not None
    (browser,) = _children(launcher)
    os.kill(browser, signal.SIGKILL)  # a browser crash
    if wait:
        _wait_until(lambda: render.EXPORTER.pid() is None, "the launcher to notice")
    assert _is_png(render.to_image(fig, "png", width=400, height=300))
    assert render.EXPORTER.pid() not in (None, launcher)


@chromium
def test_exporter_reports_a_browser_that_does_not_start(fig: Any) -> None:
    exporter = render.Exporter("/bin/false")
    try:
        with pytest.raises(InputError, match="chromium.*starts headless"):
            exporter.image(fig.to_dict(), {"format": "png", "width": 400, "height": 300})
    finally:
        exporter.close()


@chromium
@linux
def test_exporter_closes_the_browser_at_exit(tmp_path: Path) -> None:
    script = (
        "from crankbalance.output import render\n"
        "from crankbalance.output.figures.engine import orders_bar\n"
        "from crankbalance.studies.engine import analyze\n"
        "fig = orders_bar(analyze('inline4'))\n"
        "assert render.to_image(fig, 'png', width=400, height=300)[:4] == b'\\x89PNG'\n"
        "launcher = render.EXPORTER.pid()\n"
        "children = open(f'/proc/{launcher}/task/{launcher}/children').read().split()\n"
        "print(launcher, *children)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        timeout=HANG_GUARD,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr, done.stderr
    pids = [int(word) for word in done.stdout.split()]
    assert len(pids) == 2
    for pid in pids:
        _wait_until(lambda pid=pid: _gone(pid), f"process {pid} to exit")
