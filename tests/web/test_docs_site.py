"""The documentation site (docs/conf.py) builds with warnings as errors, every relative link
of every page points at a file of the site, and Chromium shows the home page, an API page,
gallery examples with their output and figure, a tutorial (an executed notebook) with its
interactive figures drawn, and the validation page's tables with their verdicts.

The site is built from a copy of ``docs/``, ``examples/`` and ``validation/`` (the
validation page runs the multibody harness) in a scratch folder (Sphinx writes the pages it
generates, ``api/`` and ``gallery/``, beside its sources)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit

import pytest

from .conftest import ROOT

pytest.importorskip("sphinx")
pytest.importorskip("myst_parser")
pytest.importorskip("sphinx_gallery")
pytest.importorskip("myst_nb")

#: hang guard [s] of the build (it runs every example of the gallery)
BUILD_GUARD = 1200
HREF = re.compile(r'(?:href|src)="([^"#?]+)[^"]*"')
SCRIPT = re.compile(r"<script\b[^>]*>.*?</script>", re.S)


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site built from a copy of the clone's docs and examples (its code in place)."""
    root = tmp_path_factory.mktemp("site")
    skip = shutil.ignore_patterns("_build", "api", "gallery", "sg_execution_times.rst")
    shutil.copytree(ROOT / "docs", root / "docs", ignore=skip)
    shutil.copytree(ROOT / "examples", root / "examples")
    shutil.copytree(ROOT / "validation", root / "validation")
    (root / "src").symlink_to(ROOT / "src")
    env = {k: v for k, v in os.environ.items() if k != "PYTEST_CURRENT_TEST"}
    out = root / "docs" / "_build" / "html"
    build = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html"]
        + [str(root / "docs"), str(out)],
        env=env,
        capture_output=True,
        text=True,
        timeout=BUILD_GUARD,
        stdin=subprocess.DEVNULL,
    )
    said = [line for line in build.stderr.splitlines() if "Kernel is running over TCP" not in line]
    assert build.returncode == 0, "\n".join(said)[-4000:]  # (ipykernel's line for every notebook)
    return out


def test_every_page_links_only_to_pages_and_files_of_the_site(site: Path) -> None:
    pages = sorted(site.rglob("*.html"))
    assert len(pages) > 40
    broken = []
    for page in pages:
        html = SCRIPT.sub("", page.read_text(errors="replace"))  # plotly.js has src= in it
        for target in HREF.findall(html):
            if urlsplit(target).scheme or target.startswith("//"):
                continue  # an outside address (mathjax, the references' DOIs)
            if not (page.parent / unquote(target)).exists():
                broken.append(f"{page.relative_to(site)} -> {target}")
    assert not broken, broken[:20]
    tutorials = [f"tutorials/{p.stem}.html" for p in (ROOT / "docs" / "tutorials").glob("*.md")]
    assert len(tutorials) == 4
    for name in ("index.html", "api.html", "gallery/index.html", "theory.html", *tutorials):
        assert (site / name).is_file(), name


def test_chromium_shows_the_home_an_api_page_and_an_example(site: Path, page: Any) -> None:
    page.goto((site / "index.html").as_uri())
    assert page.title().startswith("crankbalance")
    assert page.locator("a", has_text="API reference").count() > 0
    page.locator("a", has_text="API reference").first.click()
    page.locator("a", has_text="crankbalance.studies.engine").first.click()
    assert "analyze" in page.locator("body").inner_text()
    assert page.locator("dl.py.function dt#crankbalance\\.studies\\.engine\\.analyze").count() == 1

    page.goto((site / "gallery" / "free_forces.html").as_uri())
    text = page.locator("body").inner_text()
    assert "Free forces and moments of classic engines" in text
    assert "order 1: force" in text, "the example's printed output is on its page"

    page.goto((site / "gallery" / "inline4_counterweights.html").as_uri())
    figure = page.locator("img.sphx-glr-single-img")
    assert figure.count() == 1, "the figure the example wrote is shown on its page"
    width = figure.evaluate("(img) => img.complete ? img.naturalWidth : 0")
    assert width > 300, "the figure is a drawn image"


def test_chromium_shows_a_tutorial_with_its_figures(site: Path, page: Any) -> None:
    page.goto((site / "index.html").as_uri())
    page.locator("a", has_text="Crossplane against flat-plane V8").first.click()
    page.wait_for_load_state("load")  # 5 MB: plotly.js is in the page
    assert page.title().startswith("Crossplane against flat-plane V8")
    text = page.locator("body").inner_text()
    assert "20320.8" in text, "the flat-plane's second-order force, computed by the build"
    shown = page.locator("div.crankbalance-result h4").all_inner_texts()
    assert "BalanceStudy: V8 90 deg, crossplane crank" in shown, "a result's HTML display"
    # plotly.js (embedded in the page, no outside address) draws each figure as SVG
    drawn = page.locator(".plotly-graph-div .main-svg")
    drawn.first.wait_for(state="attached")
    assert page.locator(".plotly-graph-div").count() == 3
    bars = page.locator(".plotly-graph-div").first.locator("g.trace.bars path")
    assert bars.count() > 0, "the first figure has its bars"


def test_chromium_shows_the_validation_page(site: Path, page: Any) -> None:
    page.goto((site / "index.html").as_uri())
    page.locator("a", has_text="Validation: published tables").first.click()
    page.wait_for_load_state("load")
    text = page.locator("body").inner_text()
    for source in (
        "Table 2: inline-3, counterweight m_c",
        "Fig. 7: optimum position",
        "Table 6.1",
        "Table 5.6",
        "force, order 1 [N]",
    ):
        assert source in text, source
    tables = page.locator("table")
    assert tables.count() >= 8, "three published sources and five engines"
    header = tables.nth(0).locator("th").all_inner_texts()
    assert header == ["quantity", "published", "crankbalance", "tolerance", "verdict"]
    assert "EXUDYN" in tables.nth(3).locator("th").all_inner_texts()
    verdicts = page.locator("table tbody tr td:last-child").all_inner_texts()
    assert len(verdicts) > 60 and set(verdicts) == {"ok"}
    assert "0 failed" in text
