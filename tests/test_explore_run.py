"""The explorer's chunked runner: in process, on a dask LocalCluster, to Parquet, on failure.

The enumeration here is a small one of this file's own (the firing orders of an even-firing
four-stroke in-line six, one per time-reversal pair), so that the runner is tested apart
from :mod:`crankbalance.physics.explore.orders`; the figures of merit are real ones
(:func:`crankbalance.physics.shaking.batch_amplitudes`).
"""

from __future__ import annotations

import functools
import io
import itertools
import math
import os
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.io.parquet import read_parquet
from crankbalance.physics.explore import merit, orders, work
from crankbalance.physics.explore.candidates import Candidates
from crankbalance.physics.shaking import batch_amplitudes
from crankbalance.studies.build import build_model
from crankbalance.studies.explore import (
    ChunkError,
    Keep,
    Sample,
    local_cluster,
    progress_line,
    run,
    spread,
    tasks,
)

from .conftest import hang_guard

TOPOLOGY = build_model(load_engine("inline6"))
CYLINDERS = TOPOLOGY.cylinders
#: every firing order that starts with cylinder 1, in lexicographic order
ORDERS = np.array([(1, *p) for p in itertools.permutations(range(2, CYLINDERS + 1))])


def _canonical(order: np.ndarray) -> bool:
    """One order of each time-reversal pair: 1-a-b-c-d-e and 1-e-d-c-b-a fire alike
    backwards; keep the lexicographically smaller."""
    return tuple(order[1:]) <= tuple(order[1:][::-1])


class SixOrders:
    """count/chunk/size/template of the in-line six's firing orders (the interface of
    explore.orders)."""

    @staticmethod
    def count(problem: Any) -> int:
        return len(ORDERS)

    @staticmethod
    def size(problem: Any, start: int, stop: int) -> orders.Size:
        return orders.Size(stop - start, stop - start, stop - start, True)

    @staticmethod
    def template(problem: Any) -> Candidates:
        return SixOrders.chunk(problem, 0, 1)

    @staticmethod
    def chunk(problem: Any, start: int, stop: int) -> Candidates:
        index = np.array(
            [i for i in range(start, stop) if _canonical(ORDERS[i])], dtype=np.int64
        ).reshape(-1)
        order = ORDERS[index].reshape(-1, CYLINDERS)
        step = 4 * math.pi / CYLINDERS  # even firing, four-stroke
        fire = np.empty(order.shape)
        np.put_along_axis(fire, order - 1, step * np.arange(CYLINDERS), axis=1)
        throw = np.mod(-fire, 2 * math.pi)  # in-line: throw = -fire time (mod 2π)
        palindrome = np.array([tuple(o[1:]) == tuple(o[1:][::-1]) for o in order], dtype=bool)
        return Candidates(
            topology=TOPOLOGY,
            throw_angle=throw,
            firing_order=order,
            fire_angle=fire,
            equivalents=np.where(palindrome, 1, 2).astype(np.int64),
            index=index,
        )


def shaking(candidates: Candidates, orders: int = 2) -> dict[str, np.ndarray]:
    """Free forces and moments of orders 1..orders of the reciprocating masses."""
    t = candidates.topology
    force, moment = batch_amplitudes(
        t.crank_radius,
        t.rod_length,
        t.speed,
        t.reciprocating_mass,
        candidates.throw_angle[:, t.cylinder_throw],
        t.cylinder_bank,
        t.cylinder_position,
        orders=orders,
    )
    columns = {f"F{k + 1}_N": force[:, k] for k in range(orders)}
    return columns | {f"M{k + 1}_Nm": moment[:, k] for k in range(orders)}


def failing(candidates: Candidates, bad: int) -> dict[str, np.ndarray]:
    """:func:`shaking`, failing on the chunk holding candidate ``bad``."""
    if bad in candidates.index:
        raise FloatingPointError(f"candidate {bad} is unlucky")
    return shaking(candidates)


def brute_pareto(values: np.ndarray) -> np.ndarray:
    """Non-dominated rows (minimising), by the definition: no other row is at most as large
    in every column and smaller in one."""
    le = (values[None, :, :] <= values[:, None, :]).all(axis=2)
    lt = (values[None, :, :] < values[:, None, :]).any(axis=2)
    return ~(le & lt).any(axis=1)


def _small_moment(rows: dict[str, np.ndarray], limit: float) -> np.ndarray:
    return rows["M1_Nm"] <= limit


KEEP = Keep(objectives=("M1_Nm", "M2_Nm"), key="M2_Nm", n=7)


def _same(a: dict[str, np.ndarray], b: dict[str, np.ndarray]) -> None:
    assert list(a) == list(b)
    for name in a:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)


@pytest.fixture(scope="module", autouse=True)
def _pickled_by_value() -> Any:
    """This module's functions and classes travel to the dask workers by value (the
    workers cannot import a test module)."""
    import cloudpickle

    module = sys.modules[__name__]
    cloudpickle.register_pickle_by_value(module)
    yield
    cloudpickle.unregister_pickle_by_value(module)


def test_in_process_run_is_the_whole_batch_at_once(tmp_path: Path) -> None:
    out = tmp_path / "six.parquet"
    result = run(None, shaking, chunk=7, keep=KEEP, output=str(out), source=SixOrders)
    whole = SixOrders.chunk(None, 0, len(ORDERS))
    rows = shaking(whole)
    assert result.total == 120 and result.covered == 120
    assert result.candidates == result.rows == whole.size
    assert whole.equivalents.sum() == 120  # the pairs and the palindromes cover every order
    # the file: every row, in index order
    table = read_parquet(out)
    np.testing.assert_array_equal(table["index"], whole.index)
    np.testing.assert_array_equal(table["firing_order"], whole.firing_order)
    np.testing.assert_array_equal(table["throw_angle_rad"], whole.throw_angle)
    for name, values in rows.items():
        np.testing.assert_array_equal(table[name], values)
    # Pareto set and top-N merged over the chunks == those of all the rows at once
    objectives = np.column_stack([rows["M1_Nm"], rows["M2_Nm"]])
    np.testing.assert_array_equal(result.pareto["index"], whole.index[brute_pareto(objectives)])
    best = np.lexsort((whole.index, rows["M2_Nm"]))[:7]
    np.testing.assert_array_equal(result.top["index"], whole.index[best])
    np.testing.assert_array_equal(result.top["M2_Nm"], rows["M2_Nm"][best])
    # the known result: the usual 1-5-3-6-2-4 (kept as its time reverse 1-4-2-6-3-5)
    # leaves no first or second order free moment (to round-off of the force scale)
    scale = TOPOLOGY.reciprocating_mass.sum() * TOPOLOGY.crank_radius * TOPOLOGY.speed**2
    usual = result.top["firing_order"].tolist().index([1, 4, 2, 6, 3, 5])
    assert result.top["M1_Nm"][usual] < 1e-9 * scale > result.top["M2_Nm"][usual]


def test_filter_and_no_file(tmp_path: Path) -> None:
    whole = shaking(SixOrders.chunk(None, 0, 120))
    select = functools.partial(_small_moment, limit=float(np.median(whole["M1_Nm"])))
    result = run(None, shaking, chunk=11, select=select, keep=KEEP, source=SixOrders)
    assert 0 < result.rows == int(select(whole).sum()) < result.candidates
    assert result.output is None and list(tmp_path.iterdir()) == []
    assert select(result.top).all() and select(result.pareto).all()


@pytest.mark.slow
def test_dask_local_cluster_gives_exactly_the_in_process_result(tmp_path: Path) -> None:
    here = run(
        None, shaking, chunk=5, keep=KEEP, output=str(tmp_path / "a.parquet"), source=SixOrders
    )
    with hang_guard(600):
        there = run(
            None,
            shaking,
            chunk=5,
            keep=KEEP,
            output=str(tmp_path / "b.parquet"),
            source=SixOrders,
            workers=2,
        )
    assert (here.total, here.covered, here.candidates, here.rows) == (
        there.total,
        there.covered,
        there.candidates,
        there.rows,
    )
    _same(here.pareto, there.pareto)
    _same(here.top, there.top)
    _same(read_parquet(tmp_path / "a.parquet"), read_parquet(tmp_path / "b.parquet"))


@pytest.mark.slow
def test_an_existing_cluster_by_its_address() -> None:
    """The real enumeration and figures of merit (balancing included) on a cluster given
    by its address: the result of the run in this process."""
    problem = orders.problem("inline", 6, 4)
    evaluate = functools.partial(merit.merit, target="counterweights", balance_factor=0.5)
    keep = Keep(objectives=("M1_Nm", "M2_Nm", "cw_mass_kg"), key="residual_M_Nm", n=9)
    here = run(problem, evaluate, chunk=16, keep=keep)
    with hang_guard(600), local_cluster(1) as cluster:
        address = cluster.scheduler_address
        there = run(problem, evaluate, chunk=16, keep=keep, scheduler=address)
    assert here.candidates == there.candidates == orders.chunk(problem, 0, 120).size
    _same(here.pareto, there.pareto)
    _same(here.top, there.top)


@pytest.mark.slow
def test_the_workers_of_a_local_cluster_keep_glibcs_memory_trimming(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """dask's nanny gives its workers MALLOC_TRIM_THRESHOLD_=65536 (a task then costs half
    its CPU time again in page faults); the workers ``run(..., workers=N)`` starts do not
    have it, and keep the one-thread BLAS."""
    from dask.distributed import Client

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    with hang_guard(600), local_cluster(1) as cluster, Client(cluster) as client:
        trim = client.run(os.environ.get, "MALLOC_TRIM_THRESHOLD_")
        threads = client.run(os.environ.get, "OPENBLAS_NUM_THREADS")
    assert list(trim.values()) == [None]
    assert list(threads.values()) == ["1"]


@pytest.mark.slow
def test_a_local_cluster_does_not_take_a_fixed_port() -> None:
    """The cluster a run starts binds its scheduler's HTTP server to a free port of this
    host: with port 8787 (dask's default) held by another program (a user's own dask
    dashboard, or a second run on the machine) it starts without a warning (a warning is an
    error in this suite, and it reached the user's terminal)."""
    import socket

    holder = socket.socket()
    try:
        holder.bind(("", 8787))
        holder.listen()
    except OSError:  # another program holds it already: the case under test
        pass
    try:
        with hang_guard(600), warnings.catch_warnings():
            warnings.simplefilter("error")
            with local_cluster(1) as cluster:
                port = cluster.scheduler.http_server.port
                host = cluster.scheduler.http_server.address
    finally:
        holder.close()
    assert port != 8787
    assert host == "127.0.0.1"


def test_a_failing_chunk_names_its_candidates_and_leaves_no_file(tmp_path: Path) -> None:
    out = tmp_path / "fail.parquet"
    with pytest.raises(ChunkError, match=r"candidates 40\.\.49 failed: FloatingPointError"):
        run(None, functools.partial(failing, bad=43), chunk=10, output=str(out), source=SixOrders)
    assert list(tmp_path.iterdir()) == []  # neither the file nor its temporary


def test_an_interrupted_run_leaves_the_old_file(tmp_path: Path) -> None:
    out = tmp_path / "old.parquet"
    run(None, shaking, chunk=50, output=str(out), source=SixOrders)
    before = out.read_bytes()

    def interrupt(done: int, total: int, seconds: float) -> None:
        if done >= 60:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run(
            None,
            shaking,
            chunk=20,
            output=str(out),
            source=SixOrders,
            progress=interrupt,
            keep=KEEP,
        )
    assert out.read_bytes() == before and [p.name for p in tmp_path.iterdir()] == [out.name]


def test_sample_is_repeatable_and_covers_its_draws() -> None:
    sample = Sample(draws=40, seed=3)
    a = run(None, shaking, chunk=8, keep=KEEP, sample=sample, source=SixOrders)
    b = run(None, shaking, chunk=3, keep=KEEP, sample=sample, source=SixOrders)
    drawn = np.concatenate(tasks(120, 8, sample))
    assert a.covered == b.covered == drawn.size == np.unique(drawn).size <= 40
    assert a.candidates == sum(_canonical(ORDERS[i]) for i in drawn)
    _same(a.pareto, b.pareto)
    _same(a.top, b.top)
    assert set(a.top["index"]) <= set(drawn.tolist())


def test_a_span_is_a_slice_of_the_whole() -> None:
    part = run(None, shaking, chunk=9, keep=KEEP, span=(30, 75), source=SixOrders)
    whole = SixOrders.chunk(None, 30, 75)
    assert part.covered == 45 and part.candidates == whole.size
    assert set(part.top["index"]) <= set(whole.index.tolist())
    with pytest.raises(InputError, match="span"):
        run(None, shaking, span=(75, 30), source=SixOrders)


def test_progress_line_and_bad_settings() -> None:
    stream = io.StringIO()
    run(None, shaking, chunk=60, source=SixOrders, progress=progress_line(stream, every=0))
    text = stream.getvalue()
    assert "explore: 60/120 (50.0 %)" in text and "left" in text
    assert text.endswith("explore: 120/120 (100.0 %), " + text.rsplit(", ", 1)[1])
    with pytest.raises(InputError, match="workers"):
        run(None, shaking, source=SixOrders, workers=2, scheduler="tcp://127.0.0.1:1")
    with pytest.raises(InputError, match="chunk"):
        run(None, shaking, source=SixOrders, chunk=0)


def test_a_run_on_dask_chooses_larger_tasks_but_enough_of_them() -> None:
    """On dask (``spread`` workers) the chosen chunk holds about DASK_TASK_CANDIDATES
    candidates, at least DASK_TASKS_PER_WORKER tasks per worker, never fewer candidates than
    in process; a given chunk is kept."""
    problem = orders.problem("inline", 12, 2)  # every index a candidate
    evaluate = functools.partial(merit.merit, target="counterweights")
    big, mid, small = (0, 2_000_000), (0, 100_000), (0, 20_000)
    assert work.plan(problem, evaluate, span=big).chunk == work.TASK_CANDIDATES
    assert work.plan(problem, evaluate, span=big, spread=2).chunk == work.DASK_TASK_CANDIDATES
    assert work.plan(problem, evaluate, span=mid, spread=2).chunk == 12_500  # 8 tasks
    assert work.plan(problem, evaluate, span=small, spread=2).chunk == work.TASK_CANDIDATES
    assert work.plan(problem, evaluate, span=big, spread=2, chunk=1000).chunk == 1000
    many = Sample(draws=1_000_000, seed=1)
    assert work.plan(problem, evaluate, sample=many).chunk == work.TASK_CANDIDATES
    assert work.plan(problem, evaluate, sample=many, spread=2).chunk == work.DASK_TASK_CANDIDATES
    assert (spread(None, None), spread(None, 3)) == (0, 3)
    assert spread("tcp://127.0.0.1:8786", None) == work.SCHEDULER_WORKERS
