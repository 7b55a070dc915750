"""The design-space explorer as a study of the registry (``explore``, docs/explorer.md):
every firing order and crank of a layout, its figures of merit, the filter, the Pareto
front and the top-N list.

The enumeration is :mod:`crankbalance.physics.explore.orders`, the figures of merit
:mod:`crankbalance.physics.explore.merit`, the filter, Pareto front and top-N
:mod:`crankbalance.physics.explore.rank`, the chunked run (in this process, on a dask
LocalCluster or on an existing cluster, streaming to Parquet) :mod:`.explore`; dask and
pyarrow are imported only when a run asks for them.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..records import record
from ..results import ResultMixin, key_label, require_finite, shown, to_jsonable
from ..schema.settings import ExploreOptions, given
from .engine import EngineLike, engine_label
from .explore import Keep, RunResult, Sample, progress_line, run, spread

if TYPE_CHECKING:  # pragma: no cover
    from ..physics.explore.orders import Problem

SCHEMA = "crankbalance.explore/1"
#: a dask scheduler's address, ``tcp://10.0.0.5:8786``
SCHEDULER = re.compile(r"^[a-z]+://[^\s/:]+(:\d+)?$")
#: the settings of the run that are not of the problem (left out of the JSON's ``problem``)
RUN_SETTINGS = ("scheduler", "connect_timeout")


def _problem(engine: EngineLike | None, o: ExploreOptions) -> Problem:
    """The enumeration's problem of the settings (and the engine's masses and geometry)."""
    from ..physics.explore import orders

    base, vr_angle = None, None
    if engine is not None:
        from ..schema.engine import EngineSpec
        from .build import build_model

        if isinstance(engine, EngineSpec):
            spec = engine
        else:
            from ..io.engine_file import load_engine

            spec = load_engine(engine)  # type: ignore[arg-type]
        ct = spec.crank_train
        if ct.has_vr_rows and ct.layout == "w":  # a W from VR banks: the rows' narrow angle
            vr_angle = ct.vr_angle
        base = build_model(spec)
    try:
        return orders.problem(
            o.layout,
            o.cylinders,
            o.strokes,
            bank_angle=o.bank_angle,
            crank=o.crank,
            fixed_throw_angles=o.fixed_crank,
            base=base,
            mirror=o.mirror,
            reversal=o.reversal,
            vr_angle=vr_angle,
        )
    except InputError as error:
        if error.field == "fixed_throw_angles":
            raise InputError("fixed_crank", o.fixed_crank, error.allowed) from None
        if error.field != "base":
            raise
        raise InputError("engine", engine_label(engine), error.allowed) from None  # type: ignore[arg-type]


def mode_shape(text: str) -> str | list[float]:
    """``uniform``, ``linear`` or one weight per cylinder, comma separated."""
    from ..physics.explore.merit import MODE_SHAPES

    if text.strip() in MODE_SHAPES:
        return text.strip()
    try:
        weights = [float(w) for w in text.split(",")]
    except ValueError:
        weights = []
    if not weights or not all(math.isfinite(w) for w in weights):
        raise InputError(
            "mode_shape", text, f"{' or '.join(MODE_SHAPES)}, or one number per cylinder"
        )
    return weights


def _order_text(order: NDArray[Any]) -> str:
    return "-".join(str(int(c)) for c in order)


def records(
    rows: Mapping[str, NDArray[Any]], names: list[str], problem: Problem | None = None
) -> list[dict[str, Any]]:
    """Rows as dictionaries: the firing order as text, the throw angles as a list, and with
    a ``problem`` every firing order the row's engine stands for (``orders``, the first the
    row's own: :func:`crankbalance.physics.explore.orders.equivalent_orders`)."""
    out = []
    for i in range(rows["index"].size):
        record: dict[str, Any] = {
            "index": int(rows["index"][i]),
            "firing_order": _order_text(rows["firing_order"][i]),
            "equivalents": int(rows["equivalents"][i]),
            "throw_angle_rad": [float(a) for a in rows["throw_angle_rad"][i]],
        }
        if problem is not None:
            from ..physics.explore.orders import equivalent_orders

            listed = equivalent_orders(problem, rows["firing_order"][i].tolist())
            record["orders"] = ["-".join(map(str, order)) for order in listed]
        record.update({name: float(rows[name][i]) for name in names})
        out.append(record)
    return out


@record(repr=False)
class ExploreResult(ResultMixin):
    """One run of the explorer.

    Attributes
    ----------
    settings : ExploreOptions
    engine : str, optional
        The engine giving masses and geometry, as named.
    chunk : int
        Indices per task of the run.
    objectives : tuple of str
        Columns of the Pareto front.
    key : str, optional
        Column of the top-N list.
    names : list of str
        The columns of the rows, in the order of the merit.
    run : RunResult
        What the run kept; its ``top`` holds ``settings.top`` rows (:attr:`figure` more).
    figure : RunResult, optional
        The run with the rows of a figure (``figure_points`` of :func:`explore`).
    problem : Problem, optional
        The enumeration's problem when the rows list the orders they stand for
        (``list_orders``).
    """

    settings: ExploreOptions
    engine: str | None
    chunk: int
    objectives: tuple[str, ...]
    key: str | None
    names: list[str]
    run: RunResult
    figure: RunResult | None = None
    problem: Problem | None = None

    def counts(self) -> dict[str, Any]:
        result = self.run
        return {
            "orders": result.total,
            "looked_at": result.covered,
            "distinct_engines": result.candidates,
            "kept_by_filter": result.rows,
            "pareto": int(result.pareto["index"].size) if result.pareto else 0,
            "seconds": result.seconds,
        }

    def headline(self) -> tuple[str, ...]:
        """What was looked at, and the best candidate by the top-N key."""
        c = self.counts()
        said = (
            f"{c['orders']} firing orders, {c['distinct_engines']} distinct engines, "
            f"{c['kept_by_filter']} kept, {c['pareto']} in the Pareto set of "
            + ", ".join(key_label(name)[0] for name in self.objectives),
        )
        top = self.top()
        if self.key is None or not top:
            return said
        label, kind = key_label(self.key)
        best = top[0]
        return (
            *said,
            f"best by {label}: firing order {best['firing_order']} ({shown(best[self.key], kind)})",
        )

    def main_table(self) -> str:
        """The top-N list."""
        return "top"

    def main_columns(self) -> tuple[str, ...]:
        """The top-N list's firing order, then its key and the objectives (the columns it
        was ranked by), before the index, the equivalents and the throw angles."""
        key = () if self.key is None else (self.key,)
        return ("firing_order", *key, *self.objectives)

    def top(self) -> list[dict[str, Any]]:
        """The top-N rows."""
        return records(self.run.top, self.names, self.problem) if self.run.top else []

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.explore/1``."""
        from ..physics.explore import merit

        o = self.settings
        problem = {"engine": self.engine} | {
            k: v for k, v in o.values().items() if k not in RUN_SETTINGS
        }
        out = to_jsonable(
            {
                "schema": SCHEMA,
                "problem": problem | {"chunk": self.chunk},
                "counts": self.counts(),
                "objectives": list(self.objectives),
                "top_key": self.key,
                "torsion_assumption": merit.TORSION_ASSUMPTION,
                "top": self.top(),
                "pareto": records(self.run.pareto, self.names, self.problem)
                if self.run.pareto
                else [],
                "output": self.run.output,
            }
        )
        assert isinstance(out, dict)
        return out


def explore(
    engine: EngineLike | None,
    settings: ExploreOptions,
    *,
    output: str | None = None,
    progress: bool | None = False,
    figure_points: int = 0,
) -> ExploreResult:
    """Every firing order and crank of a layout (or a random sample): figures of merit,
    filter, Pareto front over ``objectives`` and the top-N by ``top_key`` (default: the
    largest moment left after balancing, else the first objective). The work of the run is
    counted and bounded before any enumeration (:func:`crankbalance.physics.explore.work.
    plan`).

    Parameters
    ----------
    engine : str, path, EngineSpec or None
        The engine giving the masses and geometry (none: the layout's plain engine).
    settings : ExploreOptions
    output : str, optional
        Parquet file of every row kept, written atomically at the end.
    progress : bool or None
        A progress line on standard error; None: when the run has more than 8 tasks.
    figure_points : int
        Rows to keep for a figure (by the top-N key) beside the top-N list; 0 for none.
    """
    from ..physics.explore import merit, rank
    from ..physics.explore.work import plan

    o = settings
    if o.scheduler is not None and o.workers is not None:
        raise InputError("workers", o.workers, "not with --scheduler")
    for name, needs in (("connect_timeout", "scheduler"), ("seed", "sample")):
        if name in given(o) and getattr(o, needs) is None:
            raise InputError(name, getattr(o, name), f"only acts with --{needs}")
    if o.scheduler is not None and not SCHEDULER.match(o.scheduler):
        raise InputError("scheduler", o.scheduler, "an address PROTOCOL://HOST:PORT")
    problem = _problem(engine, o)
    evaluate = functools.partial(
        merit.merit,
        target=o.target,
        balance_factor=o.balance_factor,
        mode_shape=mode_shape(o.mode_shape),
        orders=o.orders,
    )
    # the columns merit gives, named without evaluating a candidate (the same checks)
    columns = merit.column_names(problem.topology, **evaluate.keywords)
    names = [name.strip() for name in o.objectives.split(",")]
    if not all(names):  # an empty name was dropped without a word ("" left no front at all)
        raise InputError("objectives", o.objectives, "column names separated by commas, none empty")
    objectives = tuple(rank.column_name(name, columns, "objectives") for name in names)
    # an empty top_key is refused as an unknown column, not replaced by the default
    key = None if o.top_key is None else rank.column_name(o.top_key, columns, "top_key")
    if key is None:  # the largest moment left after balancing, else the first objective
        key = "residual_M_Nm" if "residual_M_Nm" in columns else next(iter(objectives), None)
    tolerance = tuple(float(t) for t in rank.tolerances(objectives, problem.topology))
    keep = Keep(objectives, key, max(o.top, figure_points), tolerance)
    select = None if o.filter is None else rank.parse_filter(o.filter, columns, "filter")
    sample = None if o.sample is None else Sample(draws=o.sample, seed=o.seed)
    # the work of the run, before any enumeration, draw or task list (explore.work)
    work = plan(
        problem, evaluate, chunk=o.chunk, sample=sample, spread=spread(o.scheduler, o.workers)
    )
    if sample is None and work.exact and work.candidates == 0:
        raise InputError(
            "cylinders",
            o.cylinders,
            f"a layout with a firing order: none of its {work.indices:,} firing orders puts "
            "the cylinders sharing a crankpin at one angle (try another --bank-angle, or "
            "--crank split)",
        )
    show = progress if progress is not None else work.tasks > 8
    result = run(
        problem,
        evaluate,
        chunk=work.chunk,
        select=select,
        keep=keep,
        output=output,
        scheduler=o.scheduler,
        workers=o.workers,
        sample=sample,
        progress=progress_line() if show else None,
        connect_timeout=o.connect_timeout,
    )
    figure = None
    if figure_points:
        figure = result
        result = dataclasses.replace(result, top={k: v[: o.top] for k, v in result.top.items()})
    names = [n for n in columns if n in result.top or n in result.pareto]
    for part in (result.top, result.pareto):
        require_finite({n: np.asarray(part[n], dtype=float) for n in names if n in part})
    label = None if engine is None else engine_label(engine)
    listing = problem if o.list_orders else None
    return ExploreResult(o, label, work.chunk, objectives, keep.key, names, result, figure, listing)
