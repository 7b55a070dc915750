"""The work of an explorer run, known before it starts, and its limits.

Before any enumeration, sample draw or task list, :func:`plan` works out what a run will
cause: the indices it looks at, the candidates it evaluates (the consistent firing orders
among the indices, counted or estimated by :func:`crankbalance.physics.explore.orders.size`; or
the draws of a random search), the prefixes its enumeration builds, the memory of one task
and the number of tasks. It refuses, with one :class:`~crankbalance.errors.InputError`, a
run beyond the time a machine gives it in reasonable time (:data:`MAX_CANDIDATES`,
:data:`MAX_DRAWS`, :data:`MAX_TASKS`) or a task beyond its memory (:data:`TASK_MEMORY`),
and chooses the chunk when none is given, so that a task holds about
:data:`TASK_CANDIDATES` candidates: a W12, whose 39.9 million indices hold 480 consistent
orders, is one task, an in-line 12 thousands. docs/explorer.md ("Limits") explains the
numbers.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from ...errors import InputError
from ...records import record
from ..limits import DRAW_COST, LARGEST_CHUNK, MAX_CANDIDATES, MAX_DRAWS  # noqa: F401 (its own)

if TYPE_CHECKING:
    from .candidates import Candidates

#: prefixes of the enumeration that cost as much as one candidate's figures of merit
#: (measured: 1.9 million prefixes/s against 3 300 to 8 800 candidates/s); a run's work is
#: its candidates plus its prefixes divided by this, against :data:`MAX_CANDIDATES`
PREFIXES_PER_CANDIDATE = 500
#: tasks of one run (each costs about a millisecond besides its candidates, more on dask)
MAX_TASKS = 100_000
#: memory one task may use [bytes]
TASK_MEMORY = 512 * 2**20
#: candidates per task of the chosen chunk: a task's own cost (about a millisecond) is
#: small beside them, and its arrays stay tens of MB
TASK_CANDIDATES = 8192
#: candidates per task of the chosen chunk of a run on dask (``--workers``,
#: ``--scheduler``): about a second of one core for the 12-cylinder two-stroke with
#: counterweights (issue 30), so that the scheduling, the result's transfer and the merge
#: in the driver stay small (46 tasks of 8 192 candidates on a LocalCluster of 2 took
#: 1.13-1.15 times the CPU time in process, the chosen chunk 1.09-1.13; load 17-43)
DASK_TASK_CANDIDATES = 8 * TASK_CANDIDATES
#: tasks per worker a run on dask has at least, when its indices give more than one
#: in-process chunk per task: the workers finish within about a quarter of a task of each
#: other
DASK_TASKS_PER_WORKER = 4
#: workers a cluster given by its address (``--scheduler``) is taken to have when the
#: chunk is chosen (the run plans before it connects); give ``--chunk`` for a larger one
SCHEDULER_WORKERS = 8
#: distinct cranks whose figures of merit (free forces, balancing) a task computes at
#: once: 512 candidates was measured fastest, or within 15 % of it, for 4 to 20 cylinders
#: and 1 to 64 orders, when the figures were computed per candidate with matrix products
#: (more made the BLAS library's threads slow them on a busy machine); per distinct crank
#: and without matrix products across engines (issue 30), 1024 cranks measured 5-10 %
#: faster than 512 on the in-line 8, 9 and 12 (two-stroke), within the noise on a 7 ms run
#: of the in-line 7 (CPU time, best of 5, BLAS 1 thread)
FIGURES_SLICE = 1024
#: candidates whose figures of merit a task computes at once, at most: a slice holds whole
#: cranks (issue 30: each crank's figures once per task, and few slices, each with its
#: fixed cost) up to FIGURES_SLICE distinct cranks and this many candidates
FIGURES_ROWS = 4096
#: seconds a dask scheduler has to answer (``--connect-timeout``; 0.1 s to 120 s) [s]
CONNECT_TIMEOUT = 5.0
#: the environment dask's nanny gives the worker processes of a LocalCluster the run
#: starts, over its defaults (``distributed.nanny.pre-spawn-environ``; None removes a
#: variable). dask sets MALLOC_TRIM_THRESHOLD_=65536, which makes glibc give freed memory
#: back at once (and keep every array above 128 KiB in an mmap of its own) and fault it in
#: again: a task of the 12-cylinder two-stroke took 3.6 times the page faults and 1.5
#: times the CPU time (issue 30); the workers keep glibc's default, as this process does.
#: OMP, MKL and OpenBLAS stay at one thread per worker (dask's defaults).
WORKER_ENVIRON: dict[str, str | None] = {"MALLOC_TRIM_THRESHOLD_": None}

# The memory of a task, measured with tracemalloc (in-line 4 to 20, vee 16 and W18 split,
# boxer 12; 1 to 64 orders; targets none to secondary), bounded from above:
#: fixed memory of a task [bytes]
TASK_BASE = 16 * 2**20
#: memory of a candidate's figures of merit while they are computed, per cylinder and
#: per column of its row [bytes] (a task computes them at most FIGURES_ROWS at a time)
CELL_BYTES = 3
#: the same per cylinder besides the columns (the balancing solver, at most FIGURES_SLICE
#: distinct cranks at a time) [bytes]
CYLINDER_BYTES = 400
#: memory of a consistent order in a task, per cylinder (its slots, fire and throw
#: angles, the indices of its equivalent descriptions) [bytes]
ORDER_BYTES = 64
#: memory of a prefix of the enumeration, per cylinder [bytes]
PREFIX_BYTES = 96


@record
class Work:
    """What a run will cause, worked out before it starts (:func:`plan`).

    Parameters
    ----------
    indices : int
        Indices looked at: the range's, or the draws of a random search [-].
    candidates : int
        Candidates evaluated, at most: the consistent firing orders among the indices
        (exact when ``exact``, else estimated), or the draws [-].
    prefixes : int
        Prefixes the enumeration builds [-] (exact when ``exact``).
    exact : bool
        Whether ``candidates`` and ``prefixes`` are counted rather than estimated.
    chunk : int
        Indices (or draws) per task [-]: the one given, or the one chosen.
    tasks : int
        Tasks of the run [-].
    candidate_bytes : int
        Memory of one candidate in a task [bytes].
    task_bytes : int
        Memory of one task [bytes], at most about :data:`TASK_MEMORY`.
    """

    indices: int
    candidates: int
    prefixes: int
    exact: bool
    chunk: int
    tasks: int
    candidate_bytes: int
    task_bytes: int


def candidate_bytes(cylinders: int, columns: int) -> int:
    """Memory of one candidate while its figures of merit are computed: the temporaries.

    Parameters
    ----------
    cylinders : int
        Cylinders of the engine [-].
    columns : int
        Columns of a candidate's row [-] (figures of merit and the enumeration's own).

    Returns
    -------
    int
        Bytes.
    """
    return cylinders * (CELL_BYTES * columns + CYLINDER_BYTES)


def figures_bytes(per_candidate: int, cylinders: int, held: int) -> int:
    """Memory of the figures of merit of a task holding ``held`` candidates while one slice
    of them is computed: the columns of at most :data:`FIGURES_ROWS` candidates and the
    balancing of at most :data:`FIGURES_SLICE` distinct cranks.

    Parameters
    ----------
    per_candidate : int
        :func:`candidate_bytes` of the problem [bytes].
    cylinders : int
        Cylinders of the engine [-].
    held : int
        Candidates of the task [-].

    Returns
    -------
    int
        Bytes.
    """
    solver = CYLINDER_BYTES * cylinders
    return (per_candidate - solver) * min(held, FIGURES_ROWS) + solver * min(held, FIGURES_SLICE)


def order_bytes(cylinders: int, columns: int) -> int:
    """Memory of one candidate held by a task: its enumeration arrays and its row (kept
    for the Parquet file).

    Parameters
    ----------
    cylinders : int
        Cylinders of the engine [-].
    columns : int
        Columns of a candidate's row [-].

    Returns
    -------
    int
        Bytes.
    """
    return ORDER_BYTES * cylinders + 8 * (columns + 2 * cylinders)


#: the keyword arguments of :func:`crankbalance.physics.explore.merit.merit` that
#: :func:`column_count` reads without evaluating (the others, the counterweight and shaft
#: options, are checked by an evaluation of the template)
NAMED_COLUMNS = frozenset({"target", "balance_factor", "mode_shape", "orders"})


def column_count(evaluate: Callable[[Candidates], Mapping[str, Any]], template: Candidates) -> int:
    """The number of columns ``evaluate`` gives: from
    :func:`~crankbalance.physics.explore.merit.column_names` when it is ``merit`` with
    keyword arguments among :data:`NAMED_COLUMNS` (a ``functools.partial``, as the command
    line and the benchmarks build it), which checks them as ``merit`` does; else by
    evaluating ``template``.

    Parameters
    ----------
    evaluate : callable
        The figures of merit.
    template : Candidates
        One candidate of the problem (:func:`~crankbalance.physics.explore.orders.template`).

    Returns
    -------
    int
        Columns [-].
    """
    from . import merit

    if (
        isinstance(evaluate, functools.partial)
        and evaluate.func is merit.merit
        and not evaluate.args
        and NAMED_COLUMNS.issuperset(evaluate.keywords)
    ):
        return len(merit.column_names(template.topology, **evaluate.keywords))
    return len(evaluate(template))


def plan(
    problem: Any,
    evaluate: Callable[[Candidates], Mapping[str, Any]],
    *,
    chunk: int | None = None,
    sample: Any = None,
    span: tuple[int, int] | None = None,
    source: Any = None,
    spread: int = 0,
) -> Work:
    """The work of a run, checked against the limits, with its chunk.

    Parameters
    ----------
    problem : Problem
        What to enumerate.
    evaluate : callable
        The figures of merit (their columns counted by :func:`column_count`: without an
        evaluation for ``merit`` itself, else called once on
        :func:`~crankbalance.physics.explore.orders.template` of the problem).
    chunk : int or None
        Indices (draws) per task [-]; None chooses it (about :data:`TASK_CANDIDATES`
        candidates per task, within :data:`TASK_MEMORY`).
    sample : Sample or None
        A random search of ``sample.draws`` draws instead of the enumeration.
    span : (int, int) or None
        Only these indices [-]; default all.
    source : module or None
        The enumeration (``count``, ``size``, ``template``); default
        :mod:`crankbalance.physics.explore.orders`.
    spread : int
        Workers the tasks are spread over on dask [-]; 0 (default) for a run in this
        process. On dask the chosen chunk holds about :data:`DASK_TASK_CANDIDATES`
        candidates, but gives at least :data:`DASK_TASKS_PER_WORKER` tasks per worker, and
        never fewer candidates than the chunk in process.

    Returns
    -------
    Work
        The run's indices, candidates, prefixes, chunk, tasks and memory.

    Raises
    ------
    InputError
        ``sample`` beyond :data:`MAX_DRAWS`; ``cylinders`` (``span`` when a span is given)
        for an enumeration beyond :data:`MAX_CANDIDATES`; ``chunk`` for a task beyond
        :data:`TASK_MEMORY` or a run beyond :data:`MAX_TASKS` tasks.
    """
    from .orders import TREE_BYTES

    if source is None:
        from . import orders as source
    if chunk is not None and chunk < 1:
        raise InputError("chunk", chunk, "1 or more")
    total = int(source.count(problem))
    low, high = (0, total) if span is None else span
    if not 0 <= low <= high <= total:
        raise InputError("span", list(span or ()), f"0 <= start <= stop <= {total}")
    template = source.template(problem)
    cylinders = template.topology.cylinders
    columns = column_count(evaluate, template) + 4  # and index, equivalents, order, throws
    per_candidate = candidate_bytes(cylinders, columns)
    per_order = order_bytes(cylinders, columns)
    if sample is not None:
        return _sampled(sample.draws, chunk, per_candidate, per_order, cylinders, spread)
    size = source.size(problem, low, high)
    indices = high - low
    work = size.orders + size.prefixes // PREFIXES_PER_CANDIDATE
    if work > MAX_CANDIDATES:
        field, value = ("span", list(span)) if span is not None else ("cylinders", cylinders)
        if size.orders == indices:
            found = f"{indices:,} firing orders to evaluate"
        else:
            counted = "" if size.exact else "about "
            found = f"{indices:,} firing orders, {counted}{size.orders:,} consistent ones"
        if size.prefixes // PREFIXES_PER_CANDIDATE > size.orders:
            found += f" and {size.prefixes:,} prefixes to enumerate"
        raise InputError(
            field,
            value,
            f"a run of at most {MAX_CANDIDATES:,} candidates (this one: {found}); take fewer "
            "cylinders, a fixed crank (--fixed-crank) or a random search (--sample N, at "
            f"most {MAX_DRAWS:,} draws)",
        )

    def task_bytes(c: int) -> int:
        share = min(c, indices) / indices if indices else 0.0
        held = min(c, math.ceil(size.orders * share))
        built = min(c + 1, math.ceil(size.widest * share))
        figures = figures_bytes(per_candidate, cylinders, held)
        prefixes = min(PREFIX_BYTES * cylinders * built, TREE_BYTES)
        return TASK_BASE + figures + per_order * held + prefixes

    most = _largest(task_bytes, max(indices, 1))
    least = -(-indices // MAX_TASKS)
    if chunk is None:
        wanted = _wanted(TASK_CANDIDATES, indices, size.orders)
        if spread > 0:
            spread_chunk = -(-indices // (DASK_TASKS_PER_WORKER * spread))
            larger = _wanted(DASK_TASK_CANDIDATES, indices, size.orders)
            wanted = max(wanted, min(larger, spread_chunk))
        chosen = max(min(wanted, most, max(indices, 1)), least, 1)
        field, value = ("span", list(span)) if span is not None else ("cylinders", cylinders)
        chunk = _bounded(chosen, least, most, indices, field, value)
    else:
        chunk = _bounded(chunk, least, most, indices, "chunk", chunk)
    return Work(
        indices=indices,
        candidates=size.orders,
        prefixes=size.prefixes,
        exact=size.exact,
        chunk=chunk,
        tasks=-(-indices // chunk),
        candidate_bytes=per_candidate,
        task_bytes=task_bytes(chunk),
    )


def _wanted(per_task: int, indices: int, candidates: int) -> int:
    """The indices of a chunk holding about ``per_task`` of the ``candidates`` among
    ``indices`` (all of them when there is no candidate)."""
    return -(-per_task * indices // candidates) if candidates else indices


def _sampled(
    draws: int, chunk: int | None, per_candidate: int, per_order: int, cylinders: int, spread: int
) -> Work:
    """The work of a random search of ``draws`` draws."""
    if not 1 <= draws <= MAX_DRAWS:
        raise InputError(
            "sample",
            draws,
            f"from 1 to {MAX_DRAWS:,} draws (a draw costs about {DRAW_COST} indices of an "
            f"enumeration: the time of {MAX_CANDIDATES:,} candidates)",
        )

    def task_bytes(c: int) -> int:
        held = min(c, draws)
        figures = figures_bytes(per_candidate, cylinders, held)
        return TASK_BASE + figures + per_order * held

    most = _largest(task_bytes, draws)
    least = -(-draws // MAX_TASKS)
    if chunk is None:
        wanted = TASK_CANDIDATES
        if spread > 0:
            spread_chunk = -(-draws // (DASK_TASKS_PER_WORKER * spread))
            wanted = max(wanted, min(DASK_TASK_CANDIDATES, spread_chunk))
        chosen = max(min(wanted, most), least)
        chunk = _bounded(chosen, least, most, draws, "sample", draws)
    else:
        chunk = _bounded(chunk, least, most, draws, "chunk", chunk)
    return Work(
        indices=draws,
        candidates=draws,
        prefixes=draws * cylinders,
        exact=False,
        chunk=chunk,
        tasks=-(-draws // chunk),
        candidate_bytes=per_candidate,
        task_bytes=task_bytes(chunk),
    )


def _largest(task_bytes: Callable[[int], int], high: int) -> int:
    """The largest chunk from 1 to ``high`` whose task fits :data:`TASK_MEMORY` (0 when
    none does); ``task_bytes`` grows with the chunk."""
    if task_bytes(high) <= TASK_MEMORY:
        return high
    low = 0  # task_bytes(low) fits (0: nothing), task_bytes(high) does not
    while high - low > 1:
        middle = (low + high) // 2
        low, high = (middle, high) if task_bytes(middle) <= TASK_MEMORY else (low, middle)
    return low


def _bounded(chunk: int, least: int, most: int, indices: int, field: str, value: Any) -> int:
    """``chunk`` if the run's tasks are at most :data:`MAX_TASKS` and each fits the memory,
    else one line naming ``field`` = ``value`` and saying what is allowed."""
    if least > most:
        raise InputError(
            field,
            value,
            f"no chunk fits: more than {MAX_TASKS:,} tasks below {least:,} indices per task, "
            f"more than {TASK_MEMORY // 2**20} MiB per task above {most:,}; take fewer "
            "cylinders or a random search (--sample)",
        )
    if min(chunk, max(indices, 1)) > most:
        raise InputError(
            field,
            value,
            f"at most {most:,} for this run: a task may use {TASK_MEMORY // 2**20} MiB",
        )
    if chunk < least:
        raise InputError(
            field, value, f"at least {least:,} for this run (at most {MAX_TASKS:,} tasks)"
        )
    return chunk
