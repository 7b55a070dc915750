"""The slices of an explorer task hold whole cranks (issue 30): a crank's figures are
computed once in a task, a slice holds at most FIGURES_SLICE distinct cranks and
FIGURES_ROWS candidates, and the task's rows, Pareto set and top-N are those of one slice of
all its candidates, to the last bit."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from crankbalance.physics.explore import orders
from crankbalance.physics.explore.merit import merit
from crankbalance.physics.explore.work import FIGURES_ROWS, FIGURES_SLICE
from crankbalance.studies import explore
from crankbalance.studies.explore import Keep, evaluate_task, figures_slices


def _crank_keys(throw_angle: np.ndarray) -> list[bytes]:
    return [row.tobytes() for row in np.ascontiguousarray(throw_angle)]


def _sorted(throw_angle: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return throw_angle, np.lexsort(throw_angle.T[::-1])


@pytest.mark.parametrize(
    ("cranks", "rows", "slices"),
    [(FIGURES_SLICE, FIGURES_ROWS, 1), (100, 600, 6), (1000, 300, 9)],
)
def test_no_crank_of_the_inline8_falls_into_two_slices(
    monkeypatch: pytest.MonkeyPatch, cranks: int, rows: int, slices: int
) -> None:
    monkeypatch.setattr(explore, "FIGURES_SLICE", cranks)
    monkeypatch.setattr(explore, "FIGURES_ROWS", rows)
    problem = orders.problem("inline", 8, 4)
    cands = orders.chunk(problem, 0, orders.count(problem))
    by_crank = np.lexsort(cands.throw_angle.T[::-1])
    found = figures_slices(cands.throw_angle, by_crank)  # 546 distinct cranks, 2 544 rows
    assert len(found) == slices
    assert found[0][0] == 0 and found[-1][1] == cands.size
    assert all(a[1] == b[0] for a, b in zip(found, found[1:], strict=False))
    seen: set[bytes] = set()
    for start, stop in found:
        held = set(_crank_keys(cands.throw_angle[by_crank[start:stop]]))
        assert 0 < stop - start <= rows and len(held) <= cranks
        assert not held & seen  # every crank in one slice only
        seen |= held
    assert len(seen) == np.unique(cands.throw_angle, axis=0).shape[0]


def test_a_crank_larger_than_a_slice_is_cut_and_the_others_stay_whole() -> None:
    big = FIGURES_ROWS * 2 + 7
    angles = np.zeros((big + 30, 3))
    angles[big : big + 10] = [0.0, 1.0, 2.0]  # a small crank before and after the large one
    angles[big + 10 :] = [1.0, 2.0, 0.0]
    angles = np.roll(angles, 15, axis=0)  # the cranks' candidates not side by side
    by_crank = np.lexsort(angles.T[::-1])
    slices = figures_slices(angles, by_crank)
    sizes = [stop - start for start, stop in slices]
    assert sum(sizes) == angles.shape[0] and max(sizes) <= FIGURES_ROWS
    keys = [set(_crank_keys(angles[by_crank[a:b]])) for a, b in slices]
    large = np.zeros(3).tobytes()
    assert sum(large in k for k in keys) == 3  # the large crank: three slices
    for other in set(_crank_keys(angles)) - {large}:
        assert sum(other in k for k in keys) == 1  # the others whole


def test_no_candidates_is_one_empty_slice() -> None:
    assert figures_slices(np.zeros((0, 4)), None) == [(0, 0)]


@pytest.mark.parametrize(("cranks", "rows"), [(5, 37), (60, 10), (10, 1000)])
def test_a_task_in_small_slices_is_the_task_in_one(
    monkeypatch: pytest.MonkeyPatch, cranks: int, rows: int
) -> None:
    problem = orders.problem("inline", 6, 4)
    total = orders.count(problem)
    evaluate = functools.partial(merit, target="counterweights")
    keep = Keep(objectives=("F1_N", "M1_Nm", "F2_N"), key="residual_M_Nm", n=7)
    whole = evaluate_task(problem, evaluate, None, keep, True, None, (0, total))
    assert len(figures_slices(*_sorted(orders.chunk(problem, 0, total).throw_angle))) == 1
    monkeypatch.setattr(explore, "FIGURES_SLICE", cranks)
    monkeypatch.setattr(explore, "FIGURES_ROWS", rows)
    assert len(figures_slices(*_sorted(orders.chunk(problem, 0, total).throw_angle))) > 2
    sliced = evaluate_task(problem, evaluate, None, keep, True, None, (0, total))
    assert sliced.rows is not None and whole.rows is not None
    for kept, one in ((sliced.rows, whole.rows), (sliced.pareto, whole.pareto)):
        assert kept.keys() == one.keys()
        for name in one:
            assert np.array_equal(kept[name], one[name]), name
    assert np.array_equal(sliced.top["index"], whole.top["index"])
