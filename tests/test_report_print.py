"""Issue 28 item 6 without a browser: the report's 3-D crank prints as its flat views
(``figures.crank_flat``: the 3-D figure's own points in three projections), the WebGL
scene is on screen only, and ``report_bytes`` gives the command line's and the web's bytes."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("plotly")

from crankbalance.errors import InputError  # noqa: E402
from crankbalance.output.figures.crank3d import crank_3d  # noqa: E402
from crankbalance.output.figures.crank_flat import VIEWS, crank_views  # noqa: E402
from crankbalance.output.html import CSS  # noqa: E402
from crankbalance.output.report import build_report, report_bytes, report_html  # noqa: E402
from crankbalance.studies.engine import balance_engine  # noqa: E402


def _values(values: object) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in values], dtype=float)  # type: ignore[attr-defined]


def test_the_flat_views_are_the_3d_cranks_points() -> None:
    study = balance_engine("v8-crossplane")
    solid, flat = crank_3d(study.model, study), crank_views(study.model, study)
    assert len(flat.data) == len(VIEWS) * len(solid.data)
    for k, (_, across, up) in enumerate(VIEWS):
        for j, trace in enumerate(solid.data):
            drawn = flat.data[k * len(solid.data) + j]
            assert drawn.name == trace.name
            for mine, theirs in ((drawn.x, getattr(trace, across)), (drawn.y, getattr(trace, up))):
                np.testing.assert_array_equal(_values(mine), _values(theirs))
    assert "seen from three sides" in flat.layout.title.text
    # equal scales: each view's y axis anchored to its x axis
    assert [flat.layout[f"yaxis{s}"].scaleanchor for s in ("", "2", "3")] == ["x", "x2", "x3"]


def test_the_webgl_crank_is_on_screen_only_and_its_views_print() -> None:
    html = report_html(build_report("inline4"))
    assert '<figure id="figure-crank" class="screen-only">' in html
    assert '<figure id="figure-crank-views">' in html
    assert "figure.screen-only, .modebar { display: none; }" in CSS
    assert html.index('id="figure-crank"') < html.index('id="figure-crank-views"')


def test_report_bytes_html_and_a_bad_format() -> None:
    report = build_report("inline4")
    data = report_bytes(report, "html")
    assert data.startswith(b"<!DOCTYPE html>") and b"figure-crank-views" in data
    with pytest.raises(InputError, match="'html' or 'pdf'"):
        report_bytes(report, "docx")
