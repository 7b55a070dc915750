"""The documentation site (docs/conf.py) builds with warnings as errors, every relative link
of every page points at a file of the site, and Chromium shows the home page, an API page
and gallery examples with their output and figure.

The site is built from a copy of ``docs/`` and ``examples/`` in a scratch folder (Sphinx
writes the pages it generates, ``api/`` and ``gallery/``, beside its sources)."""

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

#: hang guard [s] of the build (it runs every example of the gallery)
BUILD_GUARD = 1200
HREF = re.compile(r'(?:href|src)="([^"#?]+)[^"]*"')


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site built from a copy of the clone's docs and examples (its code in place)."""
    root = tmp_path_factory.mktemp("site")
    skip = shutil.ignore_patterns("_build", "api", "gallery", "sg_execution_times.rst")
    shutil.copytree(ROOT / "docs", root / "docs", ignore=skip)
    shutil.copytree(ROOT / "examples", root / "examples")
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
    assert build.returncode == 0, build.stderr[-4000:]
    return out


def test_every_page_links_only_to_pages_and_files_of_the_site(site: Path) -> None:
    pages = sorted(site.rglob("*.html"))
    assert len(pages) > 40
    broken = []
    for page in pages:
        for target in HREF.findall(page.read_text(errors="replace")):
            if urlsplit(target).scheme or target.startswith("//"):
                continue  # an outside address (mathjax, the references' DOIs)
            if not (page.parent / unquote(target)).exists():
                broken.append(f"{page.relative_to(site)} -> {target}")
    assert not broken, broken[:20]
    for name in ("index.html", "api.html", "gallery/index.html", "theory.html"):
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
