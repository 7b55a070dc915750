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
