"""Balancing many engines of one layout at once: a firing-order or crank study.

An :class:`~crankbalance.physics.model.EngineBatch` of arrays with a leading engine axis
in (:func:`~crankbalance.physics.model.engine_batch`,
:func:`~crankbalance.physics.model.stack_models`), a
:class:`~crankbalance.physics.balance_types.BatchBalance` of arrays out. The engines go
through the one implementation of the equations
(:func:`crankbalance.physics.balance_solver.solve`, which the one-engine
:func:`crankbalance.physics.balancing.balance` calls on a batch of one) in chunks of
:data:`BATCH_CHUNK` engines, so the temporaries stay bounded whatever the batch size
(docs/performance.md). A result does not depend on the chunk or the other engines of its
batch.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..errors import InputError
from .balance_solver import balance_residuals, solve, solver_input
from .balance_types import (
    BatchBalance,
    BatchResiduals,
    CounterweightOptions,
    EngineFailed,
    ShaftOptions,
)
from .model import EngineBatch, per_engine, take
from .shaking import BatchFreeForces, batch_free_forces

#: engines solved together in one pass of :func:`balance_batch` (bounds the temporaries to
#: a few MB; the result grows with the batch, about 1 kB per engine)
BATCH_CHUNK = 2048


def balance_batch(
    batch: EngineBatch,
    counterweights: CounterweightOptions | None = None,
    primary: ShaftOptions | None = None,
    secondary: ShaftOptions | None = None,
    orders: int = 8,
    chunk: int = BATCH_CHUNK,
    forces: BatchFreeForces | None = None,
) -> BatchBalance:
    """Counterweights and balance shafts for many engines of one layout at once.

    Engine by engine the results of :func:`crankbalance.physics.balancing.balance` (the
    same solver: nothing to cancel gives zero masses, rank-deficient equations the
    least-norm solution, and the inputs for which ``balance`` raises raise the same
    :class:`~crankbalance.errors.InputError`, naming the engine). The engines are solved
    ``chunk`` at a time.

    Parameters
    ----------
    batch : EngineBatch
        The engines.
    counterweights : CounterweightOptions, optional
        Crank counterweights, the same for every engine.
    primary, secondary : ShaftOptions, optional
        Balance shafts at crank speed and at twice crank speed.
    orders : int
        Orders reported in the residuals (orders 1 and 2 always are).
    chunk : int
        Engines solved together.
    forces : BatchFreeForces, optional
        The engines' free forces of orders 1..max(``orders``, 2), as
        :func:`~crankbalance.physics.shaking.batch_free_forces` gives them, when the caller
        has them already (the explorer's figures of merit); default: computed here.

    Returns
    -------
    BatchBalance
        Per engine: counterweight masses [kg] and directions [rad], shaft masses [kg] and
        phases [rad], residual forces [N] and moments [N·m] by order, and the check.

    Raises
    ------
    InputError
        As ``balance``, for the first engine it fails on; or a ``chunk`` below 1; or
        ``forces`` of another number of engines or orders.

    References
    ----------
    Appl. Sci. 2021, Eqs. 1-23, with the errata of docs/references.md.
    """
    count = max(orders, 2)
    if forces is not None and forces.force_forward.shape != (batch.size, count):
        raise InputError(
            "forces",
            f"shape {forces.force_forward.shape}",
            f"the free forces of the {batch.size} engines, orders 1..{count}",
        )
    out: Any = None  # _chunked gives one chunk or more
    for start, piece in _chunked(batch, chunk):
        piece_forces = (
            batch_free_forces(piece, count)
            if forces is None
            else _rows(forces, slice(start, start + piece.size))
        )
        inputs = solver_input(piece, piece_forces)
        try:
            part = solve(inputs, counterweights, primary, secondary)
        except EngineFailed as failed:
            e = failed.error
            raise InputError(
                e.field, e.value, f"{e.allowed} (engine {start + failed.engine} of the batch)"
            ) from None
        out = _gather(out, part, start, batch.size)
    return out


def check_batch(
    batch: EngineBatch, result: BatchBalance, chunk: int = BATCH_CHUNK
) -> BatchResiduals:
    """Residuals of the balancing masses in ``result`` on the engines of ``batch``.

    Recomputes the free forces and adds the forces of every counterweight and shaft mass
    from its reported mass, radius, phase and position: change a mass of ``result``
    (:func:`dataclasses.replace`) and the check shows what it leaves.

    Parameters
    ----------
    batch : EngineBatch
        The engines ``result`` was solved for.
    result : BatchBalance
        The balancing masses (from :func:`balance_batch`, possibly changed).
    chunk : int
        Engines checked together.

    Returns
    -------
    BatchResiduals
        Forces [N] and moments [N·m] before and after, per component, and the check.
    """
    orders = len(result.residuals.components) - 1
    out: Any = None  # _chunked gives one chunk or more
    for start, piece in _chunked(batch, chunk):
        got = take(result, slice(start, start + piece.size))
        part = balance_residuals(
            solver_input(piece, batch_free_forces(piece, orders)),
            got.counterweights,
            got.rotating_share,
            got.extra_counterweights,
            got.primary,
            got.secondary,
        )
        out = _gather(out, part, start, batch.size)
    return out


def _rows(forces: BatchFreeForces, index: slice) -> BatchFreeForces:
    """The engines ``index`` of ``forces`` (views; the orders are shared)."""
    if index.start == 0 and index.stop >= forces.rotating_force.size:
        return forces
    return replace(
        forces,
        **{
            name: value[index]
            for name, value in vars(forces).items()
            if isinstance(value, np.ndarray) and name != "orders"
        },
    )


def _chunked(batch: EngineBatch, chunk: int) -> list[tuple[int, EngineBatch]]:
    if not (isinstance(chunk, int | np.integer) and chunk >= 1):
        raise InputError("chunk", chunk, "an integer of 1 or more")
    if batch.size <= chunk:
        return [(0, batch)]
    return [
        (start, batch.take(slice(start, start + chunk))) for start in range(0, batch.size, chunk)
    ]


def _gather(out: Any, part: Any, start: int, total: int) -> Any:
    """Put the chunk ``part`` (engines from ``start``) into ``out``, the result of all
    ``total`` engines (allocated from the first chunk; the first chunk is the result when
    it holds every engine)."""
    size = part.size if isinstance(part, BatchBalance) else part.balanced.size
    if out is None:
        if size == total:
            return part
        out = per_engine(part, lambda a: np.empty((total, *a.shape[1:]), a.dtype))
    _fill(out, part, slice(start, start + size))
    return out


def _fill(out: Any, part: Any, index: slice) -> None:
    if out is None:
        return
    from dataclasses import fields

    for f in fields(out):
        value = getattr(out, f.name)
        if f.name in out.PER_ENGINE and value is not None:
            value[index] = getattr(part, f.name)
        elif hasattr(value, "PER_ENGINE"):
            _fill(value, getattr(part, f.name), index)
