"""Chunked explorer runs: in this process, on a dask LocalCluster or on an existing cluster.

Before anything runs, :func:`crankbalance.physics.explore.work.plan` works out the run's work
(candidates, tasks, memory per task), refuses a run beyond its limits and chooses the
chunk. A run splits the index range of a problem's enumeration, ``[0, count)``, into
chunks of consecutive indices (or, for a space too large to enumerate, into groups of
sampled indices, see :class:`Sample`), made one at a time (:class:`Tasks`). Each chunk is
one task: candidates (the enumeration's ``chunk``), figures of merit (``evaluate``), the
filter (``select``), and the chunk's own Pareto set and top-N. The driver takes the
tasks' results in task order, whoever computed them, writes each chunk's rows to the
Parquet file as one row group (through :func:`crankbalance.io.parquet.parquet_stream`:
the file appears at the end, atomically), and merges the Pareto sets and top-N lists;
nothing else stays in memory. Because the tasks and the merge order are the same wherever
the tasks run, a run on dask gives exactly the rows, Pareto set and top-N of the run in
this process.

Where the tasks run: in this process by default; ``workers=N`` starts a
``dask.distributed.LocalCluster`` of N worker processes (one thread each) for the run;
``scheduler="tcp://HOST:PORT"`` uses an existing cluster, whose workers need crankbalance
installed, and which must answer within ``connect_timeout`` seconds. dask and pyarrow are
imported only when they are used.

Beyond enumeration (a W16's 1.3e12 firing orders), :class:`Sample` draws indices uniformly
at random (with a seed, so the run is repeatable); docs/explorer.md says what that
guarantees.
"""

from __future__ import annotations

import functools
import math
import sys
import time
from collections import deque
from collections.abc import Callable, Generator, Iterable, Mapping, Sequence
from contextlib import ExitStack
from typing import IO, TYPE_CHECKING, Any, Protocol, overload

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..physics.explore.candidates import Candidates
from ..physics.explore.work import (
    CONNECT_TIMEOUT,
    FIGURES_ROWS,
    FIGURES_SLICE,
    SCHEDULER_WORKERS,
    TASK_CANDIDATES,
    WORKER_ENVIRON,
    plan,
)
from ..records import record

if TYPE_CHECKING:  # pragma: no cover
    from ..physics.explore.orders import Size

Columns = dict[str, NDArray[Any]]

#: figures of merit of a batch of candidates: one column (B,) per figure
Evaluate = Callable[[Candidates], Mapping[str, NDArray[Any]]]
#: which rows to keep: a boolean (B,) from the columns
Select = Callable[[Mapping[str, NDArray[Any]]], NDArray[np.bool_]]
#: a task: a range (start, stop) of indices, or an array of sampled indices
Task = tuple[int, int] | NDArray[np.int64]

#: a dask scheduler's port when its address has none
SCHEDULER_PORT = 8786
#: the columns every row has besides the figures of merit
ROW_COLUMNS = ("index", "equivalents", "firing_order", "throw_angle_rad")


class Enumeration(Protocol):
    """What a run enumerates: :mod:`crankbalance.physics.explore.orders` (a module) or a
    stand-in with the same four functions of its problem (opaque to the run). A fifth,
    ``at(problem, indices)`` (the candidates among sorted distinct indices, as ``chunk``
    of each alone), is used for a random search's draws when the source has it; else
    each draw is a ``chunk`` of one index."""

    def count(self, problem: Any, /) -> int:
        """The number of indices of the problem [-]."""
        ...

    def size(self, problem: Any, start: int, stop: int, /) -> Size:
        """The candidates and memory of the indices ``start`` to before ``stop``."""
        ...

    def template(self, problem: Any, /) -> Candidates:
        """A few candidates of the problem, to learn the figures' columns."""
        ...

    def chunk(self, problem: Any, start: int, stop: int, /) -> Candidates:
        """The candidates of the indices ``start`` to before ``stop``."""
        ...


@record
class Keep:
    """What stays in memory: the Pareto set over ``objectives`` (all minimised,
    :func:`crankbalance.physics.explore.rank.pareto`) and the ``n`` rows of smallest ``key`` (ties
    broken by the smaller index, :func:`crankbalance.physics.explore.rank.top`).

    Parameters
    ----------
    objectives : tuple of str
        Columns of the Pareto front; empty for none.
    key : str or None
        Column of the top-N list; None for none.
    n : int
        Length of the top-N list.
    tolerance : tuple of float
        The round-off of each objective [its unit]
        (:func:`crankbalance.physics.explore.rank.tolerances`): rows equal within it both
        stay on the front; empty: exact comparison.
    """

    objectives: tuple[str, ...] = ()
    key: str | None = None
    n: int = 20
    tolerance: tuple[float, ...] = ()


@record
class Sample:
    """A random search: ``draws`` indices drawn uniformly, with replacement, from
    ``[0, count)`` with the seed ``seed`` (duplicates are evaluated once).

    Each draw that lands on a distinct engine's canonical index gives one candidate, and
    every distinct engine is as likely as any other; with ``h`` such hits the best sampled
    candidate is among the best fraction ``p`` of all distinct engines with probability
    ``1 - (1 - p)**h`` (at least 0.99 for p = 1 % and h = 459).

    Parameters
    ----------
    draws : int
        Indices drawn [-].
    seed : int
        Seed of the random generator (numpy's PCG64) [-].
    """

    draws: int
    seed: int = 0


@record
class RunResult:
    """What a run keeps.

    Parameters
    ----------
    total : int
        Indices in the enumeration (``count``).
    covered : int
        Indices looked at: ``total``, or the distinct sampled indices.
    candidates : int
        Distinct engines evaluated.
    rows : int
        Candidates that passed the filter (the rows of the Parquet file).
    pareto : dict of str to ndarray
        Rows of the Pareto set, by increasing index.
    top : dict of str to ndarray
        The top-N rows, by increasing key (then index).
    output : str or None
        The Parquet file written, None when none was asked for.
    seconds : float
        Wall time of the run [s].
    """

    total: int
    covered: int
    candidates: int
    rows: int
    pareto: Columns
    top: Columns
    output: str | None
    seconds: float


@record
class _Part:
    """What one task sends back."""

    candidates: int
    covered: int
    rows: Columns | None
    passed: int
    pareto: Columns
    top: Columns


class ChunkError(RuntimeError):
    """A task failed; the message names its candidates and the reason (one line)."""


# ------------------------------------------------------------------------------ rows
def _take(columns: Mapping[str, NDArray[Any]], which: NDArray[Any]) -> Columns:
    return {name: np.asarray(values)[which] for name, values in columns.items()}


def _concat(parts: Iterable[Mapping[str, NDArray[Any]]]) -> Columns:
    parts = list(parts)
    return {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}


def _rows(candidates: Candidates, merit: Mapping[str, NDArray[Any]]) -> Columns:
    """The candidates' rows: index, equivalents, firing order, throw angles, figures."""
    rows: Columns = {
        "index": candidates.index.astype(np.int64),
        "equivalents": candidates.equivalents.astype(np.int64),
        "firing_order": candidates.firing_order.astype(np.int64),
        "throw_angle_rad": candidates.throw_angle.astype(float),
    }
    for name, values in merit.items():
        column = np.asarray(values)
        if name in rows or column.shape[:1] != (candidates.size,):
            raise ValueError(
                f"figure of merit {name!r}: a column of {candidates.size} values with a "
                f"name other than {ROW_COLUMNS}, got shape {column.shape}"
            )
        rows[name] = column
    return rows


def _matrix(rows: Mapping[str, NDArray[Any]], names: Iterable[str]) -> NDArray[np.float64]:
    """The columns ``names`` as a (B, K) float matrix; every value must be finite."""
    names = list(names)
    values = np.column_stack([np.asarray(rows[n], dtype=float) for n in names])
    bad = ~np.isfinite(values)
    if bad.any():
        row, col = np.argwhere(bad)[0]
        raise ValueError(
            f"column {names[col]!r} of candidate {int(rows['index'][row])} is "
            f"{values[row, col]}; objectives and the top-N key must be finite"
        )
    return values


def _pareto(keep: Keep, rows: Columns) -> Columns:
    """The non-dominated rows over ``keep.objectives``, by increasing index."""
    if not keep.objectives or rows["index"].size == 0:
        return _take(rows, np.zeros(0, dtype=np.int64)) if keep.objectives else {}
    from ..physics.explore.rank import pareto

    tolerance = keep.tolerance or 0.0
    mask = np.asarray(pareto(_matrix(rows, keep.objectives), tolerance), dtype=bool)
    kept = np.flatnonzero(mask)
    return _take(rows, kept[np.argsort(rows["index"][kept], kind="stable")])


def _top(keep: Keep, rows: Columns) -> Columns:
    """The ``keep.n`` rows of smallest ``keep.key``, ties by the smaller index."""
    if keep.key is None:
        return {}
    from ..physics.explore.rank import top

    _matrix(rows, [keep.key])  # finite
    return _take(rows, top(rows, keep.key, keep.n, index=rows["index"]))


def _merge(keep: Keep, a: Columns, b: Columns, kind: str) -> Columns:
    """Two Pareto sets or top-N lists merged into one (the same set whatever the order)."""
    if not a:
        return b
    both = _concat([a, b])
    return _pareto(keep, both) if kind == "pareto" else _top(keep, both)


# ------------------------------------------------------------------------------ tasks
def _enumeration(source: Enumeration | None) -> Enumeration:
    """``source``, or by default :mod:`crankbalance.physics.explore.orders`."""
    if source is None:
        from ..physics.explore import orders

        return orders
    return source


def _candidates(problem: Any, task: Task, source: Enumeration) -> tuple[Candidates, int]:
    """The candidates of ``task`` and the number of indices it covers."""
    if isinstance(task, tuple):
        start, stop = task
        return source.chunk(problem, start, stop), stop - start
    picked = getattr(source, "at", None)  # all the sampled indices at once, when it can
    if picked is not None:
        return picked(problem, task), int(task.size)
    parts = [source.chunk(problem, int(i), int(i) + 1) for i in task]
    first = parts[0]
    joined = {
        name: np.concatenate([getattr(p, name) for p in parts])
        for name in ("throw_angle", "firing_order", "fire_angle", "equivalents", "index")
    }
    return Candidates(first.topology, **joined), int(task.size)


def figures_slices(
    throw_angle: NDArray[np.float64], by_crank: NDArray[np.int64] | None
) -> list[tuple[int, int]]:
    """The slices of a task's candidates whose figures are computed at once: positions
    (start, stop) in ``by_crank`` (the candidates sorted crank by crank). A slice holds
    whole cranks, at most :data:`~crankbalance.physics.explore.work.FIGURES_SLICE` distinct
    ones and :data:`~crankbalance.physics.explore.work.FIGURES_ROWS` candidates, so that a
    crank's figures are computed once in the task and the slices, each with its fixed
    cost, are few (issue 30); a crank with more candidates than a slice is cut into slices
    of its own.

    Parameters
    ----------
    throw_angle : ndarray, shape (B, T)
        The candidates' throw angles [rad].
    by_crank : ndarray of int, shape (B,), or None
        The candidates' positions sorted crank by crank (``np.lexsort`` of the throw
        angles); None for no candidates.

    Returns
    -------
    list of (int, int)
        The slices, in order, covering every position once ([(0, 0)] for no candidates,
        which evaluates the empty batch).
    """
    if by_crank is None or not by_crank.size:
        return [(0, 0)]
    size = by_crank.size
    ordered = throw_angle[by_crank]
    # where each crank starts in the sorted order, and the end
    starts = np.flatnonzero(np.r_[True, np.any(ordered[1:] != ordered[:-1], axis=1), True])
    slices = []
    start, crank = 0, 0  # position, and its crank (starts[crank] <= start)
    while start < size:
        # whole cranks: at most FIGURES_SLICE of them and FIGURES_ROWS candidates
        last = min(crank + FIGURES_SLICE, starts.size - 1)
        last = int(np.searchsorted(starts[: last + 1], start + FIGURES_ROWS, side="right")) - 1
        stop = int(starts[last]) if last > crank else min(start + FIGURES_ROWS, size)
        slices.append((start, stop))
        start = stop
        crank = int(np.searchsorted(starts, start, side="right")) - 1
    return slices


def evaluate_task(
    problem: Any,
    evaluate: Evaluate,
    select: Select | None,
    keep: Keep,
    rows_wanted: bool,
    source: Enumeration | None,
    task: Task,
) -> _Part:
    """One task, where it runs: candidates, figures, filter, Pareto set and top-N.

    The figures are computed slice by slice (:func:`figures_slices`: at most
    :data:`~crankbalance.physics.explore.work.FIGURES_SLICE` distinct cranks and
    :data:`~crankbalance.physics.explore.work.FIGURES_ROWS` candidates; faster, and their
    temporaries stay small however many candidates a task of a shared-pin layout holds);
    the slices' Pareto sets and top-N lists merge into the task's. The slices take the
    candidates crank by crank (the candidates of one crank side by side) and end between
    two cranks, so that a crank's figures, which
    :func:`~crankbalance.physics.explore.merit.merit` computes once per distinct crank of a
    slice, are computed once in the task; the rows come back by increasing index."""
    candidates, covered = _candidates(problem, task, _enumeration(source))
    kept: list[Columns] = []
    pareto: Columns = {}
    top: Columns = {}
    passed = 0
    by_crank = np.lexsort(candidates.throw_angle.T[::-1]) if candidates.size else None
    for start, stop in figures_slices(candidates.throw_angle, by_crank):
        piece = (
            candidates.part(start, stop)
            if by_crank is None
            else candidates.take(by_crank[start:stop])
        )
        rows = _rows(piece, evaluate(piece))
        if select is not None:
            rows = _take(rows, np.flatnonzero(np.asarray(select(rows), dtype=bool)))
        passed += int(rows["index"].size)
        if rows_wanted:
            kept.append(rows)
        pareto = _merge(keep, pareto, _pareto(keep, rows), "pareto")
        top = _merge(keep, top, _top(keep, rows), "top")
    rows_of_task = None
    if rows_wanted:
        rows_of_task = _concat(kept)
        rows_of_task = _take(rows_of_task, np.argsort(rows_of_task["index"], kind="stable"))
    return _Part(
        candidates=candidates.size,
        covered=covered,
        rows=rows_of_task,
        passed=passed,
        pareto=pareto,
        top=top,
    )


class Tasks(Sequence[Task]):
    """The tasks of a run, made one at a time as they are asked for (:func:`tasks`): a run
    of many tasks holds no list of them."""

    def __init__(self, low: int, high: int, chunk: int, drawn: NDArray[np.int64] | None) -> None:
        self._low, self._high, self._chunk, self._drawn = low, high, chunk, drawn
        size = high - low if drawn is None else drawn.size
        self._count = -(-size // chunk)
        #: indices the tasks cover
        self.covered = size

    def __len__(self) -> int:
        return self._count

    @overload
    def __getitem__(self, k: int) -> Task: ...

    @overload
    def __getitem__(self, k: slice) -> list[Task]: ...

    def __getitem__(self, k: int | slice) -> Task | list[Task]:
        if isinstance(k, slice):
            return [self[j] for j in range(*k.indices(self._count))]
        if k < 0:
            k += self._count
        if not 0 <= k < self._count:
            raise IndexError(k)
        start = k * self._chunk
        if self._drawn is not None:
            return self._drawn[start : start + self._chunk]
        return (self._low + start, min(self._low + start + self._chunk, self._high))


def tasks(
    total: int,
    chunk: int = TASK_CANDIDATES,
    sample: Sample | None = None,
    span: tuple[int, int] | None = None,
) -> Tasks:
    """The tasks of a run: ranges of ``chunk`` consecutive indices of ``[0, total)`` (or of
    ``span``), or the sorted distinct indices of ``sample`` in groups of ``chunk``.

    Parameters
    ----------
    total : int
        Indices in the enumeration [-].
    chunk : int
        Indices per task [-].
    sample : Sample or None
        Draw indices at random instead of taking them all.
    span : (int, int) or None
        Only the indices from ``span[0]`` to before ``span[1]`` [-] (a slice of a large
        enumeration: a benchmark, or one job of many); default all.

    Returns
    -------
    Tasks
        A sequence of ``(start, stop)`` tuples, or of int64 arrays of indices, each made
        when it is asked for (the sampled indices are drawn at once).
    """
    if chunk < 1:
        raise InputError("chunk", chunk, "1 or more")
    low, high = (0, total) if span is None else span
    if not 0 <= low <= high <= total:
        raise InputError("span", list(span or ()), f"0 <= start <= stop <= {total}")
    if sample is None:
        return Tasks(low, high, chunk, None)
    if sample.draws < 1:
        raise InputError("draws", sample.draws, "1 or more")
    rng = np.random.default_rng(sample.seed)
    # integers below 2**63: a V16's 1.3e12 and more fit
    drawn = np.unique(rng.integers(low, high, size=sample.draws, dtype=np.int64))
    return Tasks(low, high, chunk, drawn)


def _describe(task: Task) -> str:
    if isinstance(task, tuple):
        return f"candidates {task[0]}..{task[1] - 1}"
    return f"the {task.size} sampled candidates from index {int(task[0])}"


# ------------------------------------------------------------------------------ where
def _in_process(
    work: Callable[[Task], _Part], todo: Sequence[Task]
) -> Generator[_Part, None, None]:
    for task in todo:
        yield work(task)


def _on_dask(
    client: Any, work: Callable[[Task], _Part], todo: Sequence[Task]
) -> Generator[_Part, None, None]:
    """The results in task order, keeping a bounded number of tasks in flight."""
    window = 2 * max(1, len(client.scheduler_info().get("workers", {}))) + 2
    pending: deque[Any] = deque()
    upcoming = iter(todo)
    try:
        for task in upcoming:
            pending.append(client.submit(work, task, pure=False))
            if len(pending) >= window:
                break
        while pending:
            part = pending.popleft().result()
            following = next(upcoming, None)
            if following is not None:
                pending.append(client.submit(work, following, pure=False))
            yield part
    finally:
        for future in pending:
            future.cancel()


def _client(stack: ExitStack, scheduler: str | None, workers: int | None, timeout: float) -> Any:
    """A dask client: to ``scheduler`` (which must answer within ``timeout`` seconds), or
    to a new LocalCluster of ``workers`` processes."""
    from dask.distributed import Client

    if scheduler is not None:
        _reach(scheduler, timeout)
        try:
            return stack.enter_context(Client(scheduler, timeout=timeout))
        except (OSError, TimeoutError, ValueError) as error:
            raise InputError(
                "scheduler", scheduler, f"the address of a running dask scheduler ({error})"
            ) from None
    cluster = stack.enter_context(local_cluster(workers))
    return stack.enter_context(Client(cluster))


def spread(scheduler: str | None, workers: int | None) -> int:
    """The workers a run's tasks are spread over, for the choice of its chunk
    (:func:`~crankbalance.physics.explore.work.plan`): 0 in this process, ``workers`` on a
    LocalCluster, :data:`~crankbalance.physics.explore.work.SCHEDULER_WORKERS` on a
    cluster given by its address (the run plans before it connects).

    Parameters
    ----------
    scheduler : str or None
        Address of a running dask scheduler.
    workers : int or None
        Worker processes of a LocalCluster started for the run [-].

    Returns
    -------
    int
        Workers [-].
    """
    if scheduler is not None:
        return SCHEDULER_WORKERS
    return workers or 0


def local_cluster(workers: int | None) -> Any:
    """A ``dask.distributed.LocalCluster`` of ``workers`` processes of one thread each, as
    ``run(..., workers=N)`` starts it: no dashboard (the scheduler's HTTP server on a free
    port of this host, not dask's fixed 8787), quiet logs, and the workers'
    environment :data:`~crankbalance.physics.explore.work.WORKER_ENVIRON` (glibc's own
    memory trimming instead of dask's, which costs a task half its CPU time again).

    Parameters
    ----------
    workers : int or None
        Worker processes [-]; None lets dask choose (one per core).

    Returns
    -------
    LocalCluster
        The started cluster (a context manager that stops it).
    """
    import dask
    from dask.distributed import LocalCluster

    environ = {f"distributed.nanny.pre-spawn-environ.{k}": v for k, v in WORKER_ENVIRON.items()}
    with dask.config.set(environ):  # read when each worker's nanny is made
        return LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            # the scheduler's HTTP server (health and metrics, no dashboard) on a free port
            # of this host: dask's default 8787 warns, or clashes, when another cluster or
            # dashboard holds it
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
            silence_logs=50,  # logging.CRITICAL: no tracebacks of the shutdown
        )


def _reach(scheduler: str, timeout: float) -> None:
    """Refuse, within about ``timeout`` seconds, a scheduler that cannot be reached or does
    not answer. A TCP address is tried with a plain socket first (a closed port answers at
    once). dask's own connection then waits for the scheduler's handshake without a time
    limit (a port that accepts and never speaks hangs ``Client`` for ever), so the handshake
    is made here, in an event loop of its own, under ``asyncio.wait_for``."""
    import asyncio
    import socket

    from distributed.comm import connect
    from distributed.comm.addressing import parse_address, parse_host_port

    deadline = time.monotonic() + timeout

    async def handshake() -> None:
        left = max(deadline - time.monotonic(), 0.1)
        comm = await asyncio.wait_for(connect(scheduler, timeout=left), left)
        await comm.close()

    try:
        scheme, location = parse_address(scheduler)
        if scheme in ("tcp", "tls"):
            socket.create_connection(parse_host_port(location, SCHEDULER_PORT), timeout).close()
        asyncio.run(handshake())
    except ConnectionRefusedError:
        reason = "nothing listens there (connection refused)"
    except TimeoutError:
        reason = "it did not answer"
    except (OSError, ValueError) as error:  # a name that does not resolve, a bad address
        reason = " ".join(str(error.__cause__ or error).split())
    else:
        return
    raise InputError(
        "scheduler", scheduler, f"a dask scheduler answering within {timeout:g} s: {reason}"
    )


# ------------------------------------------------------------------------------ progress
def progress_line(stream: IO[str] | None = None, every: float = 1.0) -> Callable[..., None]:
    """A progress reporter for :func:`run`: one line on ``stream`` (default stderr),
    rewritten at most every ``every`` seconds: indices done, rate, time left."""
    last = [-math.inf]

    def report(done: int, total: int, seconds: float) -> None:
        now = time.monotonic()
        final = done >= total
        if not final and now - last[0] < every:
            return
        last[0] = now
        rate = done / seconds if seconds > 0 else 0.0
        left = (total - done) / rate if rate > 0 else math.inf
        eta = "" if final else f", {_duration(left)} left"
        out = stream or sys.stderr
        out.write(
            f"\rexplore: {done:,}/{total:,} ({100 * done / max(total, 1):.1f} %), "
            f"{rate:,.0f}/s{eta}" + ("\n" if final else "")
        )
        out.flush()

    return report


def _duration(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "?"
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


# ------------------------------------------------------------------------------ run
def run(
    problem: Any,
    evaluate: Evaluate,
    *,
    chunk: int | None = None,
    select: Select | None = None,
    keep: Keep = Keep(),
    output: str | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
    sample: Sample | None = None,
    span: tuple[int, int] | None = None,
    progress: Callable[[int, int, float], None] | None = None,
    source: Enumeration | None = None,
    connect_timeout: float = CONNECT_TIMEOUT,
) -> RunResult:
    """Evaluate every candidate of ``problem`` (or a sample), keeping the Pareto set and
    the top-N, and streaming the rows to a Parquet file.

    Parameters
    ----------
    problem : Problem
        What to enumerate (:func:`crankbalance.physics.explore.orders.problem`).
    evaluate : callable
        ``evaluate(candidates) -> {name: (B,) array}``, the figures of merit; it runs
        where the task runs, so on dask it must pickle (a module-level function or a
        ``functools.partial`` of one).
    chunk : int or None
        Indices per task [-]; default chosen from the problem
        (:func:`crankbalance.physics.explore.work.plan`: about
        :data:`~crankbalance.physics.explore.work.TASK_CANDIDATES` candidates per task).
    select : callable or None
        ``select(rows) -> bool (B,)``: the rows kept (filter); None keeps all.
    keep : Keep
        Objectives of the Pareto set, key and length of the top-N.
    output : str or None
        Parquet file of every kept row (one row group per task with rows), written
        atomically at the end.
    scheduler : str or None
        Address of a running dask scheduler, ``tcp://HOST:PORT``.
    workers : int or None
        Worker processes of a dask LocalCluster started for the run.
    sample : Sample or None
        Draw indices at random instead of enumerating them all.
    span : (int, int) or None
        Only the indices from ``span[0]`` to before ``span[1]``; default all.
    progress : callable or None
        ``progress(indices done, indices in all, seconds)``, after each task
        (:func:`progress_line` prints one).
    source : module or None
        The enumeration: ``count(problem)``, ``chunk(problem, start, stop)``,
        ``size(problem, start, stop)`` and ``template(problem)``; default
        :mod:`crankbalance.physics.explore.orders`.
    connect_timeout : float
        Seconds a scheduler has to answer [s].

    Returns
    -------
    RunResult
        The counts, the Pareto set, the top-N, the file and the wall time [s].

    Raises
    ------
    InputError
        For a bad setting, a run beyond the limits of
        :func:`crankbalance.physics.explore.work.plan` (before anything runs), a scheduler that
        does not answer, or an input error of a task (naming its candidates).
    ChunkError
        When a task fails otherwise; no file is left behind.
    """
    began = time.perf_counter()
    if scheduler is not None and workers is not None:
        raise InputError("workers", workers, "not with a scheduler (its cluster has workers)")
    if workers is not None and workers < 1:
        raise InputError("workers", workers, "1 or more")
    if keep.n < 1:
        raise InputError("top", keep.n, "1 or more")
    if not connect_timeout > 0:
        raise InputError("connect_timeout", connect_timeout, "a positive number of seconds")
    enumeration = _enumeration(source)
    total = int(enumeration.count(problem))
    work_of = plan(
        problem,
        evaluate,
        chunk=chunk,
        sample=sample,
        span=span,
        source=enumeration,
        spread=spread(scheduler, workers),
    )
    todo = tasks(total, work_of.chunk, sample, span)
    if output is not None and not len(todo):
        raise InputError("output", output, "a run with at least one candidate to write")
    covered_all = todo.covered
    work = functools.partial(
        evaluate_task, problem, evaluate, select, keep, output is not None, source
    )
    pareto: Columns = {}
    top: Columns = {}
    done = candidates = passed = 0
    with ExitStack() as stack:
        if output is not None:
            from ..io.parquet import parquet_stream

            stream = stack.enter_context(parquet_stream(output))
        if scheduler is None and workers is None:
            parts = _in_process(work, todo)
        else:
            client = _client(stack, scheduler, workers, connect_timeout)
            parts = _on_dask(client, work, todo)
        stack.callback(parts.close)
        for task in todo:
            try:
                part = next(parts)
            except InputError as error:
                raise InputError(
                    error.field, error.value, f"{error.allowed} ({_describe(task)})"
                ) from None
            except Exception as error:
                reason = " ".join(f"{type(error).__name__}: {error}".split())
                raise ChunkError(f"{_describe(task)} failed: {reason}") from error
            if output is not None:
                assert part.rows is not None
                stream.write(part.rows)
            pareto = _merge(keep, pareto, part.pareto, "pareto")
            top = _merge(keep, top, part.top, "top")
            done += part.covered
            candidates += part.candidates
            passed += part.passed
            if progress is not None:
                progress(done, covered_all, time.perf_counter() - began)
    return RunResult(
        total=total,
        covered=done,
        candidates=candidates,
        rows=passed,
        pareto=pareto,
        top=top,
        output=output,
        seconds=time.perf_counter() - began,
    )
