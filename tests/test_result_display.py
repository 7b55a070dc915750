"""Every study of the registry displays its result in a notebook (issue 29, item 3): a
short ``repr`` (its key verdicts and one table with units, at most ``REPR_LINES`` lines),
an HTML display with tables whose columns name their units, and figures from
:func:`crankbalance.plot`, or a reason why the result has none (``NO_FIGURES``). Each study
runs on a case of tests/test_study_contract.py (its cheap settings and example files)."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest

import crankbalance
from crankbalance.output.figures.study import FIGURES, NO_FIGURES, figure_key
from crankbalance.results import REPR_LINES, REPR_WIDTH, key_label, shown
from crankbalance.studies.registry import STUDIES, run

from .conftest import hang_guard
from .test_study_contract import CASES, EXAMPLES, FILES, TABLE

#: the case of each study run here: the first of test_study_contract's, or another that is
#: as telling and cheaper (the matching of the listed order: no integer program)
CASE = {name: 1 if name == "shop-match" else 0 for name in CASES}


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    for name in FILES - {"table.csv"}:
        shutil.copy(EXAMPLES / name, tmp_path / name)
    (tmp_path / "table.csv").write_text(TABLE)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _result(name: str) -> object:
    engine, options = CASES[name][CASE[name]]
    entry = STUDIES[name]
    return run(name, engine, {entry.field_of(o): v for o, v in options.items()})


@pytest.mark.parametrize("name", sorted(STUDIES))
def test_every_study_result_displays_itself(name: str, folder: Path) -> None:
    pytest.importorskip("plotly")
    with hang_guard(300):
        result = _result(name)
        text = repr(result)
        html = result._repr_html_()  # type: ignore[attr-defined]
        lines = text.splitlines()
        assert 2 <= len(lines) <= REPR_LINES, text
        verdicts = result.display_summary().verdicts  # type: ignore[attr-defined]
        assert all(len(line) <= REPR_WIDTH for line in lines if line not in verdicts), text
        assert lines[0].startswith(type(result).__name__)
        assert "[" in text and "]" in text, f"no unit in the repr of {name}:\n{text}"
        assert "<table>" in html and "<th>" in html
        assert any("[" in cell for cell in html.split("<th>")[1:]), f"no unit in {name}'s tables"
        key = figure_key(result)
        assert (key in FIGURES) != (key in NO_FIGURES), key
        if key in NO_FIGURES:
            with pytest.raises(crankbalance.InputError, match="has no figure: "):
                crankbalance.plot(result)
        else:
            figures = crankbalance.plot(result)
            assert figures, f"{name}: no figure"
            assert all(figure.data for figure in figures), f"{name}: a figure with no trace"


def test_the_explorer_shows_its_verdicts_its_top_table_and_figures(folder: Path) -> None:
    """The explorer's repr was its objectives as bullet lines and a long text on the
    torsional excitation: now what was looked at, the best candidate and the top table, the
    text a note of the HTML display; ``crankbalance.plot`` gives its scatter and the best
    candidate's orders."""
    pytest.importorskip("plotly")
    result = run("explore", "inline4", {"cylinders": "4", "top": "5"})
    text = repr(result)
    assert "firing orders" in text and "distinct engines" in text and "Pareto set" in text
    assert "best by residual M [N·m]: firing order 1-2-4-3 (0)" in text, text
    # the top table's first columns are the ones it was ranked by, not its index,
    # equivalents and throw angles
    header = text.splitlines()[text.splitlines().index("top: (first 6 of 78 columns)") + 1]
    assert header.split() == "firing order residual M [N·m] F1 [N] M1 [N·m] F2 [N] M2 [N·m]".split()
    assert "throw angle" not in text and "equivalents" not in text
    assert "torsional excitation" not in text
    html = result._repr_html_()
    assert html.index("<caption>top</caption>") < html.index("<caption>values</caption>")
    assert "<details><summary>notes</summary>" in html and "torsional excitation" in html
    scatter, best = crankbalance.plot(result)
    assert "Pareto" in " ".join(str(t.name) for t in scatter.data)
    assert "1-2-4-3" in str(best.layout.title.text)


def test_a_shop_match_is_a_few_lines_with_its_spreads(folder: Path) -> None:
    """A shop match was 18 lines of "result · as listed · kinds: piston"."""
    result = run("shop-match", "v8-crossplane", {"parts": "v8_parts.csv", "method": "as-listed"})
    text = repr(result)
    assert text.count("kinds") <= 1, text
    assert "matched (as-listed): spread" in text and " g reciprocating" in text
    assert "bob-weights per crankpin: " in text


def test_a_rebalancing_has_its_before_and_after_figure(folder: Path) -> None:
    pytest.importorskip("plotly")
    result = run("rebalance", None, {"parts": "crf250r_rebalance.toml"})
    assert "residual" in repr(result) and "within the tolerance 10.69 g·mm" in repr(result)
    (figure,) = crankbalance.plot(result)  # a face removal: no drilling plan
    before, after = figure.data
    assert before.y[0] > after.y[0] > 0


def test_a_rebalancing_drilled_with_holes_has_its_drilling_plans(folder: Path) -> None:
    pytest.importorskip("plotly")
    holes = {"method": "holes", "hole_diameter": "12 mm", "holes": 3, "correction_radius": "40 mm"}
    result = run("rebalance", None, {"parts": "crf250r_rebalance.toml", **holes})
    unbalance, *plans = crankbalance.plot(result)
    assert len(plans) == 2  # one per target
    assert all("Drilling plan" in str(plan.layout.title.text) for plan in plans)
    assert "(the HTML display has 1 more verdict)" in repr(result)


def test_a_crank_position_is_shown_in_0_to_360_a_signed_angle_keeps_its_sign(
    folder: Path,
) -> None:
    """The bearings' peak-load crank angles were shown as -171° and -351° (the load's
    angle grid runs over [-360°, 360°)): a position of the crank is shown in [0, 360) as
    the text output has it; a twist or a deviation keeps its sign."""
    result = run("bearings", "inline4", {})
    rows = result.to_dict()["models"]["determinate"]["bearings"]
    radians = [row["peak_load_crank_angle_rad"] for row in rows]
    assert min(radians) < 0  # the case this is about
    table = next(
        t for t in result.display_summary().tables if t.caption == "models · determinate · bearings"
    )
    at = table.header.index("peak load crank angle [°]")
    shown_degrees = [float(row[at]) for row in table.rows]
    assert all(0 <= d < 360 for d in shown_degrees)
    assert shown_degrees == pytest.approx([math.degrees(r) % 360 for r in radians], abs=0.5)
    label, kind = key_label("crank_twist_rad")
    assert label == "crank twist [°]" and shown(-0.01, kind) == "-0.573"
