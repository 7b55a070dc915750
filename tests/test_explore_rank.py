"""Ranking of the explorer (explore.rank): the filter language, the Pareto front against
brute force, and the mergeability of the Pareto front and the top-N over chunks."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from crankbalance.errors import InputError
from crankbalance.physics.explore import merit, orders
from crankbalance.physics.explore.rank import (
    BLOCK,
    column_name,
    pareto,
    parse_filter,
    tolerances,
    top,
)
from crankbalance.results import round_off

COLUMNS = {
    "F1_N": np.array([0.0, 1.0, 2.0, 0.0]),
    "M1_Nm": np.array([0.0, 0.0, 3.0, 5.0]),
    "cw_mass_kg": np.array([4.0, 3.0, 2.0, 1.0]),
    "shafts": np.array([0.0, 2.0, 2.0, 4.0]),
}


@pytest.mark.parametrize(
    ("text", "kept"),
    [
        ("F1 == 0 and M1 == 0", [True, False, False, False]),
        ("F1_N <= 1 or cw_mass > 1.5 and shafts >= 2", [True, True, True, True]),
        ("(F1_N <= 1 or cw_mass > 1.5) and shafts >= 2", [False, True, True, True]),
        ("not (F1 > 0)", [True, False, False, True]),
        ("0 < F1 <= 2", [False, True, True, False]),
        ("abs(F1 - 2) < 0.5", [False, False, True, False]),
        ("F1 + 2 * M1 / 2 - -1 >= 6", [False, False, True, True]),
        ("cw_mass_kg != 3", [True, False, True, True]),
        ("1e-6 >= F1", [True, False, False, True]),
    ],
)
def test_filter_language(text: str, kept: list[bool]) -> None:
    assert parse_filter(text, COLUMNS)(COLUMNS).tolist() == kept


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("F1 <=", "not an expression"),
        ("F1 + 1", "a condition"),
        ("F1 and M1", "join conditions"),
        ("(F1 < 1) < 2", "compares numbers"),
        ("F3 < 1", "unknown column 'F3'"),
        ("__import__('os').system('true')", "abs"),
        ("F1.real < 1", "column names"),
        ("F1 < 'a'", "is not a number"),
        ("F1 < True", "is not a number"),
        ("[F1][0] < 1", "column names"),
        ("F1 < 1 if M1 else 2", "column names"),
        ("F1 ** 2 < 1", "column names"),
        ("lambda: 1", "column names"),
    ],
)
def test_bad_filters_name_the_text(text: str, says: str) -> None:
    with pytest.raises(InputError) as error:
        parse_filter(text, COLUMNS, field="--filter")
    assert error.value.field == "--filter"
    assert error.value.value == text
    assert says in error.value.allowed


def test_column_names_with_or_without_units() -> None:
    assert column_name("F1", COLUMNS) == "F1_N"
    assert column_name("M1_Nm", COLUMNS) == "M1_Nm"
    assert column_name("shafts", COLUMNS) == "shafts"
    with pytest.raises(InputError) as error:
        column_name("M1_N", COLUMNS, field="--objectives")
    assert error.value.field == "--objectives" and "closest: M1;" in str(error.value)


def brute_pareto(v: np.ndarray) -> np.ndarray:
    """Row i is on the front unless some row is <= in every column and < in one."""
    keep = np.ones(len(v), bool)
    for i in range(len(v)):
        for j in range(len(v)):
            if np.all(v[j] <= v[i]) and np.any(v[j] < v[i]):
                keep[i] = False
    return keep


# small integers: many ties and duplicate rows
objectives = st.integers(1, 4).flatmap(
    lambda k: arrays(
        np.float64, st.tuples(st.integers(0, 40), st.just(k)), elements=st.integers(0, 5)
    )
)


@settings(derandomize=True, database=None, deadline=None, max_examples=150)
@given(objectives)
def test_pareto_is_the_brute_force_front(values: np.ndarray) -> None:
    assert pareto(values).tolist() == brute_pareto(values).tolist()


@settings(derandomize=True, database=None, deadline=None, max_examples=150)
@given(objectives, st.data())
def test_pareto_merges_over_chunks(values: np.ndarray, data: st.DataObject) -> None:
    """pareto(concat(pareto of each chunk)) == pareto(all), whatever the split."""
    cuts = sorted(data.draw(st.lists(st.integers(0, len(values)), max_size=4)))
    kept = []
    for part in np.split(np.arange(len(values)), cuts):
        kept.append(part[pareto(values[part])])
    survivors = np.concatenate(kept) if kept else np.arange(0)
    merged = survivors[pareto(values[survivors])]
    assert sorted(merged.tolist()) == np.flatnonzero(pareto(values)).tolist()


#: the round-off added to the integer objectives below (a third of the tolerance)
NOISE = 1e-7


@settings(derandomize=True, database=None, deadline=None, max_examples=150)
@given(objectives, st.data())
def test_rows_equal_within_the_tolerance_both_stay(values: np.ndarray, data: st.DataObject) -> None:
    """Integer objectives with round-off added (up to a third of the tolerance): the front
    with the tolerance is the exact front of the clean integers, and merges over chunks."""
    noise = np.array(
        data.draw(st.lists(st.floats(-NOISE, NOISE), min_size=values.size, max_size=values.size))
    ).reshape(values.shape)
    noisy, tol = values + noise, 3 * NOISE
    assert pareto(noisy, tol).tolist() == brute_pareto(values).tolist()
    cuts = sorted(data.draw(st.lists(st.integers(0, len(values)), max_size=4)))
    kept = [p[pareto(noisy[p], tol)] for p in np.split(np.arange(len(values)), cuts)]
    survivors = np.concatenate(kept)
    merged = survivors[pareto(noisy[survivors], tol)]
    assert sorted(merged.tolist()) == np.flatnonzero(brute_pareto(values)).tolist()


def test_a_dominating_row_after_the_first_in_the_sort() -> None:
    """Row 1 sorts after row 0 (its first objective larger by round-off) and dominates it
    in the second: the last pass of the sweep drops row 0."""
    values = np.array([[1.0, 5.0], [1.0 + 1e-12, 3.0], [1.0 + 2e-12, 3.0 + 1e-12]])
    assert pareto(values, 1e-9).tolist() == [False, True, True]
    assert pareto(values).tolist() == [True, True, False]
    with pytest.raises(InputError, match="tolerance"):
        pareto(values, -1.0)


def test_the_inline5_orders_equal_to_round_off_all_stay() -> None:
    """Issue 27: the inline-5's orders come in pairs with the same (M1, M2) to the last
    bits (1-2-4-3-5 and 1-3-2-4-5: 3642.1426557924365 and 3642.142655792436 N·m); exact
    dominance dropped one of each pair, the engine's round-off keeps both, and all twelve
    distinct engines are on the front (M1 falls as M2 rises)."""
    problem = orders.problem("inline", 5, 4)
    candidates = orders.chunk(problem, 0, orders.count(problem))
    columns = merit.merit(candidates, target="none", orders=2)
    values = np.column_stack([columns["M1_Nm"], columns["M2_Nm"]])
    tol = tolerances(["M1_Nm", "M2_Nm"], problem.topology)
    assert tol.tolist() == [round_off(problem.topology)[1]] * 2
    assert candidates.size == 12 and pareto(values).sum() == 9  # the bug: three dropped
    assert pareto(values, tol).all()


def test_tolerances_follow_the_unit_of_each_column() -> None:
    engine = orders.problem("inline", 4, 4).topology
    force, moment = round_off(engine)
    tol = tolerances(["F2_N", "M1_Nm", "cw_mass_kg", "mirror_rad", "X2", "shafts"], engine)
    mass = force / (engine.crank_radius * engine.speed**2)
    assert tol.tolist() == pytest.approx([force, moment, mass, 1e-12 * np.pi, 1e-12, 1e-12])
    assert mass == pytest.approx(1e-12 * (4 * 0.5 + 4 * 1.0))


def test_pareto_across_blocks() -> None:
    """More rows than one block of the sweep, a front spread over several blocks."""
    rng = np.random.default_rng(7)
    values = rng.integers(0, 30, (3 * BLOCK + 17, 3)).astype(float)
    values[::5, 0] = 30 - values[::5, 1]  # anti-correlated rows: a wide front
    assert pareto(values).tolist() == brute_pareto(values).tolist()
    assert pareto(np.empty((0, 2))).tolist() == []
    assert pareto(np.ones((3, 0))).tolist() == [True] * 3
    with pytest.raises(InputError):
        pareto([[np.nan, 1.0]])


def test_equal_rows_share_their_fate_across_blocks() -> None:
    """The explorer's case: each crank's candidates repeat its forces and moments, over
    more rows than a block; a zero and a negative zero are one value."""
    rng = np.random.default_rng(11)
    distinct = rng.integers(0, 30, (120, 3)).astype(float)
    distinct[::4, 0] = 30 - distinct[::4, 1]  # a wide front
    distinct[0] = 0.0  # (0, 0, 0) dominates all but its equals
    distinct = np.unique(distinct, axis=0)[1:]  # without it: a front of many rows
    which = rng.integers(0, distinct.shape[0], 3 * BLOCK + 9)
    values = distinct[which]
    values[values == 0] *= rng.choice([1.0, -1.0], size=int((values == 0).sum()))
    front = brute_pareto(distinct)
    assert pareto(values).tolist() == front[which].tolist()
    assert pareto(values, [1e-9, 1e-9, 1e-9]).tolist() == front[which].tolist()


@settings(derandomize=True, database=None, deadline=None, max_examples=150)
@given(
    arrays(np.float64, st.integers(0, 40), elements=st.integers(0, 6)),
    st.integers(1, 8),
    st.data(),
)
def test_top_merges_over_chunks(key: np.ndarray, n: int, data: st.DataObject) -> None:
    """Ties are broken by the candidates' index, so top of the chunks' tops is top of all,
    in the same order."""
    index = np.array(data.draw(st.permutations(range(len(key)))), dtype=np.int64)
    values = {"X1": key}
    whole = index[top(values, "X1", n, index)]
    cuts = sorted(data.draw(st.lists(st.integers(0, len(key)), max_size=4)))
    kept = np.concatenate(
        [
            part[top({"X1": key[part]}, "X1", n, index[part])]
            for part in np.split(np.arange(len(key)), cuts)
        ]
    )
    merged = index[kept][top({"X1": key[kept]}, "X1", n, index[kept])]
    assert merged.tolist() == whole.tolist()
    expected = sorted(range(len(key)), key=lambda i: (key[i], index[i]))[:n]
    assert whole.tolist() == index[expected].tolist()


def test_top_checks_its_arguments() -> None:
    assert top(COLUMNS, "cw_mass", 2).tolist() == [3, 2]
    with pytest.raises(InputError) as error:
        top(COLUMNS, "cw_mass", 0, field="--top")
    assert error.value.field == "--top"
    with pytest.raises(InputError):
        top(COLUMNS, "nothing", 3)


@settings(derandomize=True, database=None, deadline=None, max_examples=150)
@given(objectives)
def test_pareto_of_rows_that_come_in_runs(values: np.ndarray) -> None:
    """Equal rows side by side (the explorer's candidates come crank by crank): swept one
    per run, the front is still the brute force's."""
    grouped = np.repeat(values, 1 + np.arange(len(values)) % 3, axis=0)
    assert pareto(grouped).tolist() == brute_pareto(grouped).tolist()
    assert pareto(grouped, 0.5).tolist() == pareto(grouped[::-1], 0.5)[::-1].tolist()


def test_top_puts_nan_last_as_a_full_sort() -> None:
    key = np.array([3.0, np.nan, 1.0, 1.0, np.nan, 0.0])
    index = np.array([5, 4, 3, 2, 1, 0])
    for n in range(1, 7):
        assert top({"X1": key}, "X1", n, index).tolist() == np.lexsort((index, key))[:n].tolist()


def test_the_probed_comparison_is_the_full_one() -> None:
    """_dominated_within (a few rows first, then the rest with all) gives what comparing
    every row with every row gives, with and without a tolerance."""
    from crankbalance.physics.explore.rank import PROBE, _dominated, _dominated_within

    rng = np.random.default_rng(5)
    for size in (1, PROBE, PROBE + 1, 200):
        values = rng.integers(0, 6, (size, 3)).astype(float) + rng.uniform(0, 1e-7, (size, 3))
        values = values[np.lexsort(values.T[::-1])]
        for tol in (np.zeros(3), np.full(3, 3e-7)):
            expected = _dominated(values, values, tol)
            assert _dominated_within(values, tol).tolist() == expected.tolist()
