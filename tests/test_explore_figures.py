"""The explorer's figures (explore_scatter, explore_candidate) and
``crankbalance explore --plot``: the points drawn are the run's rows."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import numpy as np
import pytest

from crankbalance.io.parquet import read_parquet
from crankbalance.output.figures.explore import (
    EXPLORE_POINTS,
    explore_candidate,
    explore_points,
    explore_scatter,
)
from crankbalance.physics.explore import merit, orders, rank
from crankbalance.studies.explore import Keep, run

from .conftest import run_cli

ZERO_1 = "F1 == 0 and M1 == 0"


def _inline6(
    tmp_path: Path, n: int, text: str | None = ZERO_1
) -> tuple[object, dict[str, np.ndarray]]:
    """The inline-6 (by default without first-order free effects): the run (Pareto over
    F2, M2, top-n by the residual moment) and every row it kept (its Parquet file)."""
    problem = orders.problem("inline", 6, 4)
    evaluate = functools.partial(merit.merit)
    columns = list(evaluate(orders.chunk(problem, 0, 8)))
    out = tmp_path / "rows.parquet"
    result = run(
        problem,
        evaluate,
        chunk=32,
        select=None if text is None else rank.parse_filter(text, columns),
        keep=Keep(objectives=("F2_N", "M2_Nm"), key="residual_M_Nm", n=n),
        output=str(out),
    )
    return result, read_parquet(out)


def _trace(fig: object, name: str) -> object:
    return next(t for t in fig.data if t.name.startswith(name))  # type: ignore[attr-defined]


def test_the_scatters_points_are_the_runs_rows(tmp_path: Path) -> None:
    result, rows = _inline6(tmp_path, EXPLORE_POINTS)
    assert 0 < rows["index"].size < 64  # the filter dropped some of the 64 engines
    points = explore_points(result.top, result.pareto)
    fig = explore_scatter(points, result.pareto, "F2_N", "M2_Nm", total=result.rows)
    drawn = _trace(fig, "candidates")
    order = np.argsort(rows["index"])
    assert list(drawn.customdata) == list(rows["index"][order])
    np.testing.assert_array_equal(drawn.x, rows["F2_N"][order])
    np.testing.assert_array_equal(drawn.y, rows["M2_Nm"][order])
    assert drawn.name == f"candidates ({rows['index'].size} of {result.rows})"
    front = _trace(fig, "Pareto set")
    assert list(front.customdata) == list(result.pareto["index"])
    # the Pareto set drawn is that of the rows (brute force over the two objectives)
    xy = np.column_stack([rows["F2_N"], rows["M2_Nm"]])
    brute = {
        int(rows["index"][i])
        for i in range(len(xy))
        if not any((xy[j] <= xy[i]).all() and (xy[j] < xy[i]).any() for j in range(len(xy)))
    }
    assert set(front.customdata) == brute
    # hover: the firing order, the throws in degrees and the values
    k = int(np.flatnonzero(drawn.customdata == rows["index"][order][0])[0])
    first = order[0]
    text = drawn.hovertext[k]
    assert "firing order " + "-".join(str(c) for c in rows["firing_order"][first]) in text
    degrees = ", ".join(f"{math.degrees(a) % 360:.0f}" for a in rows["throw_angle_rad"][first])
    assert f"throws [deg]: {degrees}" in text
    assert f"F2_N = {rows['F2_N'][first]:.5g}" in text
    # the axes name their objectives in words, as the web's table does, never raw
    assert fig.layout.xaxis.title.text == "free force, order 2 [N]"
    assert fig.layout.yaxis.title.text == "free moment, order 2 [N·m]"
    assert "_N" not in fig.layout.title.text


def test_a_short_top_list_draws_the_top_and_the_pareto_set(tmp_path: Path) -> None:
    result, rows = _inline6(tmp_path, 3, None)
    points = explore_points(result.top, result.pareto)
    expected = set(result.top["index"]) | set(result.pareto["index"])
    assert set(points["index"]) == expected
    assert len(points["index"]) == len(expected) < rows["index"].size
    fig = explore_scatter(points, result.pareto, "F2_N", "M2_Nm", total=result.rows)
    assert f"of {rows['index'].size})" in _trace(fig, "candidates").name


def test_candidate_bars_are_its_forces_and_moments() -> None:
    problem = orders.problem("inline", 4, 4, crank="flat")
    candidates = orders.chunk(problem, 0, orders.count(problem))
    values = merit.merit(candidates)
    i = next(
        k
        for k in range(candidates.size)
        if tuple(candidates.firing_order[k]) in orders.equivalent_orders(problem, (1, 3, 4, 2))
    )
    row = {name: v[i] for name, v in values.items()}
    row["firing_order"] = candidates.firing_order[i]
    fig = explore_candidate(row)
    bars = {(t.name, t.xaxis): list(t.y) for t in fig.data}
    assert bars[("forward", "x")] == [values[f"F{n}f_N"][i] for n in range(1, 5)]
    assert bars[("backward", "x2")] == [values[f"M{n}b_Nm"][i] for n in range(1, 5)]
    assert bars[("forward", "x")][1] > 0  # the flat inline-4's second-order force
    order = "-".join(str(c) for c in candidates.firing_order[i])
    assert order in fig.layout.title.text
    # the flat inline-4 has no free moment: that subplot says so, the force subplot not
    notes = [(a.text, a.xref) for a in fig.layout.annotations if "everywhere" in a.text]
    assert notes == [("0 N·m everywhere<br>(balanced)", "x2 domain")]


def test_plot_option_writes_the_runs_rows(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    out, plot = tmp_path / "rows.parquet", tmp_path / "six.html"
    args = ["explore", "--cylinders", "6", "--filter", ZERO_1, "--objectives", "F2,M2"]
    args += ["--top", "2", "--output", str(out), "--plot", str(plot)]
    code, text, err = run_cli(args, capsys)
    assert code == 0, err
    html = plot.read_text()
    rows = read_parquet(out)
    for order in rows["firing_order"]:
        assert "firing order " + "-".join(str(c) for c in order) in html
    assert f"candidates ({rows['index'].size} of {rows['index'].size})" in html
    table = [line for line in text.splitlines() if line[:1].isdigit()]
    assert len(table) == 2  # the top-N table keeps its length


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--plot", "x.pdf"], "a file name ending in .png, .svg, .html"),
        (["--plot", "x.html", "--objectives", "F2"], "two --objectives"),
    ],
)
def test_plot_option_refused(
    extra: list[str], words: str, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    extra = [str(tmp_path / e) if e.startswith("x.") else e for e in extra]
    code, _, err = run_cli(["explore", "--cylinders", "4", *extra], capsys)
    assert code == 2
    assert "--plot" in err and words in err
    assert not any(tmp_path.iterdir())
