"""Issue 28 item 6: the web's report in HTML and in PDF, the 3-D crank drawn in both.

``crankbalance web`` in a subprocess, driven by Playwright in Debian's chromium: both
downloads of the Results tab; the PDF's text (``pdftotext`` of poppler-utils) holds the key
results and the titles of the crank's figures (the 3-D view as an image and its flat views);
the HTML page, printed, hides the WebGL scene (a browser prints it blank) and prints the
crank's flat views instead.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")

PRESET = "v8-crossplane"
NAME = "V8 90 deg, crossplane crank"


def _download(page, name: str, path: Path) -> Path:
    with page.expect_download() as info:
        page.get_by_role("button", name=name).click()
    info.value.save_as(path)
    return path


def _results_tab(server: str, page) -> None:
    page.goto(server + f"/?preset={PRESET}")
    page.get_by_text(NAME).first.wait_for()
    playwright_api.expect(page.locator(".q-header").first).to_contain_text(
        re.compile(r"Results of: V8 90 deg"), use_inner_text=True
    )
    page.get_by_role("tab", name="Results").click()


def _embedded(html: str) -> dict:
    found = re.search(
        r'<script type="application/json" id="crankbalance-data">(.*?)</script>', html, re.S
    )
    assert found, "the report embeds its numbers"
    return json.loads(found.group(1).replace("<\\/", "</"))


@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="poppler-utils (pdftotext)")
def test_report_pdf_holds_the_results_and_the_crank(server: str, page, tmp_path: Path) -> None:
    from crankbalance.studies.engine import analyze, balance_engine

    _results_tab(server, page)
    path = _download(page, "Report PDF", tmp_path / "report.pdf")
    data = path.read_bytes()
    assert data.startswith(b"%PDF-") and b"%%EOF" in data[-1024:]
    text = subprocess.run(
        ["pdftotext", "-layout", str(path), "-"], capture_output=True, check=True, text=True
    ).stdout
    api = analyze(PRESET).to_dict()
    study = balance_engine(PRESET).to_dict()
    assert NAME in text
    moment1 = api["free_moments"][0]["amplitude_Nm"]
    assert f"{moment1:.5g}" in text, f"first-order moment {moment1:.5g} N·m printed"
    cw = study["counterweight"]["mass_kg"]
    assert re.search(rf"largest mass\s+{re.escape(f'{cw:.5g}')} kg", text), "counterweight mass"
    # the crank's figures: the 3-D view (an image of the scene) and its flat views
    assert "Crankshaft at crank angle 0" in text
    assert "Crankshaft at crank angle 0, seen from three sides" in text
    assert "side: crank axis y across, z up" in text


def test_report_html_prints_the_crank_flat(server: str, page, tmp_path: Path) -> None:
    from crankbalance.studies.engine import balance_engine

    _results_tab(server, page)
    path = _download(page, "Report HTML", tmp_path / "report.html")
    html = path.read_text(encoding="utf-8")
    cw = balance_engine(PRESET).to_dict()["counterweight"]["mass_kg"]
    assert _embedded(html)["balance"]["counterweight"]["mass_kg"] == pytest.approx(cw, rel=1e-12)
    assert '<figure id="figure-crank" class="screen-only">' in html
    assert '<figure id="figure-crank-views">' in html
    # the page as a browser shows it and prints it
    page.goto(path.as_uri())
    views = page.locator("#figure-crank-views .js-plotly-plot")
    solid = page.locator("#figure-crank .js-plotly-plot")
    playwright_api.expect(views).to_be_visible()
    playwright_api.expect(solid).to_be_visible()  # on screen: the interactive 3-D crank
    page.emulate_media(media="print")
    playwright_api.expect(solid).to_be_hidden()  # in print: a WebGL scene prints blank
    playwright_api.expect(views).to_be_visible()
    assert views.locator(".main-svg").count() > 0  # drawn as SVG, which prints
    title = views.locator(".gtitle").first.text_content() or ""  # SVG text: no innerText
    assert "seen from three sides" in title, title
