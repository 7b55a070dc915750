"""The explorer's figures computed once per distinct crank and per distinct set of fire
angles (issue 30): the same numbers, to the last bit, as candidate by candidate."""

from __future__ import annotations

import numpy as np
import pytest

from crankbalance.physics.explore import orders
from crankbalance.physics.explore.merit import (
    distinct_rows,
    interval_deviation,
    merit,
    torsional_excitation,
)


def test_distinct_rows_finds_each_row_once_in_first_seen_order() -> None:
    rows = np.array([[1.0, 2.0], [0.0, 1.0], [1.0, 2.0], [0.0, 1.0], [3.0, 0.0]])
    first, inverse = distinct_rows(rows)
    assert first.tolist() == [0, 1, 4]
    assert inverse.tolist() == [0, 1, 0, 1, 2]
    assert np.array_equal(rows[first][inverse], rows)
    one_first, one_inverse = distinct_rows(rows[:1])
    assert one_first.tolist() == [0] and one_inverse.tolist() == [0]
    # bit for bit: -0.0 and 0.0 are two rows (never merged by a tolerance)
    assert distinct_rows(np.array([[0.0], [-0.0]]))[0].tolist() == [0, 1]


@pytest.mark.parametrize("layout", [("inline", 8, 4), ("inline", 6, 4)])
def test_per_crank_figures_equal_those_of_each_candidate_alone(
    layout: tuple[str, int, int],
) -> None:
    problem = orders.problem(*layout)
    cands = orders.chunk(problem, 0, orders.count(problem))
    assert distinct_rows(cands.throw_angle)[0].size < cands.size  # cranks repeat here
    together = merit(cands, target="secondary", balance_factor=0.5)
    picks = np.linspace(0, cands.size - 1, 12).astype(int)
    for i in picks:
        alone = merit(cands.part(int(i), int(i) + 1), target="secondary", balance_factor=0.5)
        for name, column in together.items():
            assert column[i] == alone[name][0], (name, int(i))


def test_uniform_torsion_and_intervals_do_not_depend_on_the_cylinders_order() -> None:
    rng = np.random.default_rng(3)
    alpha = rng.uniform(0, 4 * np.pi, (1, 8))
    shuffled = np.concatenate([alpha, alpha[:, rng.permutation(8)], alpha[:, ::-1]])
    k = np.arange(1, 17) / 2
    x = torsional_excitation(shuffled, np.ones(8), k)
    assert np.array_equal(x[0], x[1]) and np.array_equal(x[0], x[2])
    dev = interval_deviation(shuffled, 4 * np.pi)
    assert dev[0] == dev[1] == dev[2]
    # a mode shape of unequal weights sees the order: each row its own value
    w = np.linspace(1.0, 0.2, 8)
    y = torsional_excitation(shuffled, w, k)
    assert not np.array_equal(y[0], y[1])
    assert np.array_equal(y[0], torsional_excitation(alpha, w, k)[0])


SAMPLED_LAYOUTS = [
    ("inline", 8, 4, {}),
    ("inline", 6, 2, {}),
    ("vee", 8, 4, {"bank_angle": np.radians(90)}),
    ("vee", 8, 4, {"bank_angle": np.radians(90), "crank": "flat"}),
    ("w", 12, 4, {"bank_angle": np.radians(60)}),
    ("vee", 12, 4, {"bank_angle": np.radians(60), "crank": "split"}),
    ("boxer", 6, 4, {}),
    ("radial", 5, 4, {}),
    ("inline", 4, 4, {"fixed_throw_angles": (0.0, np.pi, np.pi, 0.0)}),
    ("inline", 4, 4, {"intervals": (np.pi / 2, 3 * np.pi / 2, np.pi / 2, 3 * np.pi / 2)}),
    ("inline", 16, 4, {}),
]


@pytest.mark.parametrize("layout", SAMPLED_LAYOUTS, ids=lambda s: f"{s[0]}{s[1]}-{s[2]}{s[3]}")
def test_candidates_at_indices_are_those_of_a_chunk_of_each(
    layout: tuple[str, int, int, dict[str, object]],
) -> None:
    name, cylinders, strokes, options = layout
    problem = orders.problem(name, cylinders, strokes, **options)  # type: ignore[arg-type]
    total = orders.count(problem)
    index = np.unique(np.random.default_rng(5).integers(0, total, size=min(600, total)))
    together = orders.at(problem, index)
    alone = [orders.chunk(problem, int(i), int(i) + 1) for i in index]
    for field in ("throw_angle", "firing_order", "fire_angle", "equivalents", "index"):
        expected = np.concatenate([getattr(one, field) for one in alone])
        assert np.array_equal(getattr(together, field), expected), field


def test_candidates_at_refuses_indices_out_of_order_or_range() -> None:
    from crankbalance.errors import InputError

    problem = orders.problem("inline", 6, 4)
    for bad in ([3, 2], [1, 1], [-1], [orders.count(problem)]):
        with pytest.raises(InputError, match="increasing, distinct"):
            orders.at(problem, bad)
    assert orders.at(problem, []).size == 0


def test_a_task_evaluated_crank_by_crank_gives_its_rows_by_index() -> None:
    """The slices of a task take the candidates crank by crank; the rows come back in
    index order, each the figures of its candidate."""
    import functools

    from crankbalance.studies.explore import Keep, evaluate_task

    problem = orders.problem("inline", 8, 4)
    total = orders.count(problem)
    evaluate = functools.partial(merit, target="counterweights")
    keep = Keep(objectives=("F1_N", "M1_Nm"), key="residual_M_Nm", n=5)
    part = evaluate_task(problem, evaluate, None, keep, True, None, (0, total))
    assert part.rows is not None
    cands = orders.chunk(problem, 0, total)
    assert np.array_equal(part.rows["index"], cands.index)
    whole = evaluate(cands)
    for name, column in whole.items():
        assert np.array_equal(part.rows[name], column), name


def test_rank_deficient_counterweight_systems_are_solved_together_as_lstsq_would() -> None:
    """The nearly parallel two-unknown systems of the optimal pattern get their least-norm
    solutions from one stacked SVD: those of numpy.linalg.lstsq, system by system."""
    from crankbalance.physics.balance_counterweights import _lstsq2
    from crankbalance.results import ROUND_OFF

    rng = np.random.default_rng(0)
    matrix = rng.normal(size=(60, 6, 2))
    matrix[:20, :, 1] = matrix[:20, :, 0] * rng.normal(size=(20, 1))  # parallel columns
    matrix[20:25] = 0.0  # nothing to solve
    matrix[25:30, :, 1] = 3 * matrix[25:30, :, 0] + 1e-14 * rng.normal(size=(5, 6))
    rhs = rng.normal(size=(60, 6))
    x1, x2 = _lstsq2(matrix, rhs)
    for i in range(60):
        expected, *_ = np.linalg.lstsq(matrix[i], rhs[i], rcond=ROUND_OFF)
        assert np.allclose([x1[i], x2[i]], expected, rtol=1e-12, atol=1e-12), i


def test_distinct_rows_of_runs_of_equal_neighbours() -> None:
    """Rows in runs (a slice crank by crank, sorted fire angles): the same positions as a
    sort of every row, written here with numpy's unique, bit for bit."""
    rng = np.random.default_rng(3)
    base = np.array([[0.0, 1.0], [-0.0, 1.0], [2.0, 0.5], [1.0, 2.0]])
    for trial in range(100):
        rows = base[np.repeat(rng.integers(0, 4, 12), rng.integers(1, 4, 12))]
        if trial % 2:  # sorted by value, as a slice crank by crank (-0.0 beside 0.0)
            rows = rows[np.lexsort(rows.T[::-1])]
        key = np.ascontiguousarray(rows).view(np.dtype((np.void, 16))).ravel()
        _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
        seen = np.argsort(first)
        rank = np.empty_like(seen)
        rank[seen] = np.arange(seen.size)
        got_first, got_inverse = distinct_rows(rows)
        assert got_first.tolist() == first[seen].tolist()
        assert got_inverse.tolist() == rank[inverse].tolist()
