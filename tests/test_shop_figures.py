"""The figures of the balance shop's results (issue 29, item 3): the matched sets, the
bob-weights and the scatter, each drawn from a real result and checked trace by trace
against the result's numbers; ``crankbalance.plot`` gives them."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import crankbalance
from crankbalance.output.figures.shop import (
    SCATTER_BARS,
    bob_weights_figure,
    matched_sets,
    merged_bins,
    scatter_histograms,
)
from crankbalance.studies.registry import run

from .conftest import hang_guard

pytest.importorskip("plotly")

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    shutil.copy(EXAMPLES / "v8_parts.csv", tmp_path / "v8_parts.csv")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _trace(figure: object, name: str, col: int = 1) -> object:
    """The trace named ``name`` in the panel ``col`` of a one-row figure."""
    axis = "x" if col == 1 else f"x{col}"
    found = [t for t in figure.data if t.name == name and t.xaxis == axis]  # type: ignore[attr-defined]
    assert len(found) == 1, (name, col, [(t.name, t.xaxis) for t in figure.data])  # type: ignore[attr-defined]
    return found[0]


def test_the_matched_sets_are_drawn_against_their_target_and_spread(folder: Path) -> None:
    with hang_guard(300):
        result = run("shop-match", "v8-crossplane", {"parts": "v8_parts.csv"})
    study = result.result
    m, listed, pairing = study.matching, study.as_listed, study.journals
    assert pairing.method == "milp"  # the sets paired on the journals: a third panel
    (figure,) = crankbalance.plot(result)
    assert len(figure.layout.annotations) == 3
    cylinders = list(range(1, 9))
    shares = (
        (m.reciprocating, listed.reciprocating, m.reciprocating_spread),
        (m.rotating, listed.rotating, m.rotating_spread),
    )
    for col, (sets, as_listed, spread) in enumerate(shares, start=1):
        matched = _trace(figure, f"matched ({m.method})", col)
        assert list(matched.x) == cylinders  # type: ignore[attr-defined]
        np.testing.assert_allclose(matched.y, sets * 1e3, rtol=1e-12)  # type: ignore[attr-defined]
        np.testing.assert_allclose(_trace(figure, "as listed", col).y, as_listed * 1e3)  # type: ignore[attr-defined]
        target = _trace(figure, "target (the lightest set)", col).y  # type: ignore[attr-defined]
        np.testing.assert_allclose(target, [sets.min() * 1e3] * 8, rtol=1e-12)
        band = _trace(figure, "spread", col).y  # type: ignore[attr-defined]
        np.testing.assert_allclose(band, [(sets.min() + spread) * 1e3] * 2, rtol=1e-12)
        assert f"spread {spread * 1e3:.4g} g" in figure.layout.annotations[col - 1].text
    journals = _trace(figure, "journal's bob-weight", 3)
    np.testing.assert_allclose(journals.y, pairing.bob_weight * 1e3, rtol=1e-12)  # type: ignore[attr-defined]
    on_pin = [
        ", ".join(str(c + 1) for c in np.flatnonzero(pairing.cylinder_throw == t)) for t in range(4)
    ]
    assert list(journals.customdata) == on_pin  # type: ignore[attr-defined]
    assert (
        f"(as listed {pairing.as_listed_spread * 1e3:.4g} g)" in figure.layout.annotations[2].text
    )
    assert matched_sets(study).to_dict() == figure.to_dict()


def test_sets_as_listed_on_the_journals_have_no_journal_panel(folder: Path) -> None:
    with hang_guard(300):
        result = run(
            "shop-match",
            "v8-flatplane",
            {"parts": "v8_parts.csv", "method": "as-listed", "journals": "as-listed"},
        )
    (figure,) = crankbalance.plot(result)
    assert len(figure.layout.annotations) == 2
    assert not [t for t in figure.data if t.name == "journal's bob-weight"]


def test_the_bob_weights_are_drawn_against_their_mean(folder: Path) -> None:
    with hang_guard(300):
        result = run(
            "shop-bobweights", "v8-flatplane", {"parts": "v8_parts.csv", "fraction": "0.45"}
        )
    b = result.result
    (figure,) = crankbalance.plot(result)
    weights = b.bob_weight * 1e3
    (points,) = [t for t in figure.data if t.name == "bob-weight"]
    assert list(points.x) == [1, 2, 3, 4]
    np.testing.assert_allclose(points.y, weights, rtol=1e-12)
    np.testing.assert_allclose(points.customdata[:, 0], b.rotating * 1e3, rtol=1e-12)
    np.testing.assert_allclose(points.customdata[:, 1], b.reciprocating * 1e3, rtol=1e-12)
    assert list(points.text) == [f"{w - weights.mean():+.3g} g" for w in weights]
    (mean,) = [t for t in figure.data if str(t.name).startswith("mean ")]
    np.testing.assert_allclose(mean.y, [weights.mean()] * 2, rtol=1e-12)
    assert "0.45 × reciprocating" in figure.layout.title.text
    assert result.parts.engine in figure.layout.title.text
    assert bob_weights_figure(b).to_dict()["data"] == figure.to_dict()["data"]


def test_the_scatter_draws_its_histograms_quantiles_and_tolerance(folder: Path) -> None:
    options = {
        "parts": "v8_parts.csv",
        "correction_planes": "-200 mm, 200 mm",
        "samples": "2000",
        "rotor_mass": "25 kg",
    }
    with hang_guard(300):
        result = run("shop-scatter", "v8-crossplane", options)
    study = result.result
    assert study.plane_tolerance is not None and study.force_limit is None
    (figure,) = crankbalance.plot(result)
    factors = (1e6, 1e6, 1.0, 1.0, 1.0, 1.0)  # g·mm, N, N·m
    for k, factor in enumerate(factors):
        axis = "x" if k == 0 else f"x{k + 1}"
        panel = [t for t in figure.data if t.xaxis == axis]
        (bars,) = [t for t in panel if t.type == "bar"]
        counts = np.asarray(bars.y)
        # every sample in the histogram is drawn, bins merged into at most SCATTER_BARS bars
        assert counts.sum() == study.histogram[k].sum() == study.samples - study.overflow[k]
        assert np.flatnonzero(counts).max() < SCATTER_BARS
        group = round(counts.size and study.histogram.shape[1] / counts.size)
        np.testing.assert_array_equal(counts, merged_bins(study.histogram[k], group))
        width = study.histogram_upper[k] * factor / study.histogram.shape[1] * group
        np.testing.assert_allclose(np.diff(bars.x), width, rtol=1e-9)
        lines = {t.name: t.x[0] for t in panel if t.type == "scatter"}
        for level, value in zip(study.quantile_levels, study.quantiles[k], strict=True):
            assert lines[f"{level * 100:g} % quantile"] == pytest.approx(value * factor, 1e-12)
        if k < 2:
            assert lines["tolerance"] == pytest.approx(study.plane_tolerance[k] * factor, 1e-12)
        else:
            assert "limit" not in lines
    assert f"= {study.p_grade:.4g}" in figure.layout.title.text
    assert scatter_histograms(study).to_dict()["data"] == figure.to_dict()["data"]


def test_merged_bins_sum_neighbouring_bins() -> None:
    counts = np.array([1, 2, 3, 4, 5], dtype=np.int64)
    np.testing.assert_array_equal(merged_bins(counts, 2), [3, 7, 5])
    np.testing.assert_array_equal(merged_bins(counts, 1), counts)


def test_the_shop_sheet_draws_the_matched_sets_before_the_hole_plan(folder: Path) -> None:
    """The sheet had one figure, the hole plan; it now draws the matched sets (with the
    journals' bob-weights) too, plotly.js inlined once, with the first figure."""
    from crankbalance.output.shop_sheet import sheet_html
    from crankbalance.schema.settings import ShopOptions, parse_options
    from crankbalance.studies.shop import shop_study

    from .test_study_contract import PLAN

    given = {"method": "as-listed", **{k.replace("-", "_"): v for k, v in PLAN.items()}}
    with hang_guard(300):
        study = shop_study("v8-crossplane", "v8_parts.csv", parse_options(ShopOptions, given))
    page = sheet_html(study)
    sets, holes = page.index('id="figure-sets"'), page.index('id="figure-holes"')
    assert page.count("plotly.js v") == 1 and sets < page.index("plotly.js v") < holes
    assert "Matched sets and their spread" in page


def test_the_hole_plan_spans_its_drawing_and_lists_the_angles() -> None:
    """Review findings 12 and 23 (issue 28): the V8 example's plan (a 45 mm hole circle)
    had axes of ±250 mm at 1280 px and ±600 mm at 390 px (equal aspect widened the range of
    the longer side), and its angle labels lay on one another ("213.3°" over "26.5°").
    Each panel now spans the hole circle and a margin, equal aspect kept by shrinking the
    panel (constrain "domain"), and each panel's title lists its holes' angles: no label
    sits beside a hole on the drawing."""
    from crankbalance.output.figures.shop import HOLE_MARGIN, hole_angles, hole_plan
    from crankbalance.schema.settings import ShopOptions, parse_options
    from crankbalance.studies.shop import hole_plan as plan_study

    from .test_study_contract import PLAN

    given = {k.replace("-", "_"): v for k, v in PLAN.items()}
    result = plan_study(parse_options(ShopOptions, {**given, "speed": "6000 rpm"}))
    figure = hole_plan(result)
    layout = figure.layout
    for row, holes in enumerate(result.holes, start=1):
        reach = HOLE_MARGIN * (holes.radius + holes.diameter / 2) * 1e3
        suffix = "" if row == 1 else str(row)
        for axis in (layout[f"xaxis{suffix}"], layout[f"yaxis{suffix}"]):
            assert axis.range == (-reach, reach) and axis.constrain == "domain"
        assert reach < 100  # a 45 mm hole circle and 8 mm holes: about ±61 mm
        assert layout[f"yaxis{suffix}"].scaleanchor == f"x{suffix}"
        title = layout.annotations[row - 1].text
        for angle in holes.angles:
            assert f"{np.degrees(angle) % 360:.1f}°" in title, title
        assert hole_angles(holes.angles) in title
    texts = [t.text for t in figure.data if t.mode == "text"]
    assert texts == [("0° (crankpin 1)",)] * 2  # no hole's label on the drawing


def test_hole_angles_wrap_four_to_a_line() -> None:
    from crankbalance.output.figures.shop import hole_angles

    angles = np.radians([10.0, 20.0, 30.0, 40.0, 370.0])
    assert hole_angles(angles) == "at 10.0°, 20.0°, 30.0°, 40.0°,<br>10.0°"
