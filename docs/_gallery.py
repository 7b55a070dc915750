"""Helpers of the sphinx-gallery configuration (``docs/conf.py`` names them by string, so
that Sphinx can cache the configuration)."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

#: where examples that write a file write it when the gallery runs them (not examples/)
OUTPUT = Path(__file__).resolve().parent / "_build" / "gallery-output"

#: the examples that take the file they write as their first argument
WRITES_FILE = {
    "inline4_counterweights.py": "inline4_counterweights.png",  # shown by png_scraper
    "v8_shop.py": "v8_shop_sheet.html",
}


def reset_argv(gallery_conf: dict[str, Any], script_vars: dict[str, Any]) -> list[str]:
    """The arguments an example is run with: a file in :data:`OUTPUT` for one that writes."""
    name = Path(script_vars["src_file"]).name
    if name not in WRITES_FILE:
        return []
    OUTPUT.mkdir(parents=True, exist_ok=True)
    return [str(OUTPUT / WRITES_FILE[name])]


def png_scraper(block: Any, block_vars: dict[str, Any], gallery_conf: dict[str, Any]) -> str:
    """Show on the example's page the PNG figures it wrote into :data:`OUTPUT` (moved into
    the gallery's images, so that each is shown once)."""
    from sphinx_gallery.scrapers import figure_rst

    shown = []
    images = block_vars["image_path_iterator"]  # as many paths as asked for
    for png, image in zip(sorted(OUTPUT.glob("*.png")), images, strict=False):
        shutil.move(png, image)
        shown.append(image)
    return figure_rst(shown, gallery_conf["src_dir"]) if shown else ""
