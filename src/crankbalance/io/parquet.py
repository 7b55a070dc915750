"""Parquet tables of explorer results: written a row group at a time, atomically.

A table is a ``dict`` of numpy columns of one length: 1-D columns are plain Parquet
columns; 2-D columns (a firing order, the throw angles) are fixed-size lists, one list per
row, and read back as 2-D arrays. :class:`ParquetStream` writes through
:func:`crankbalance.io.files.atomic_open`: the rows of each :meth:`ParquetStream.write` go
to the hidden temporary file as one row group as they come, and the file appears under its
name only when the block ends without an error (an error or an interruption leaves no
file, and the previous one, if any, intact). A FIFO with a reader, ``/dev/stdout`` or
``/dev/null`` given as the path gets the row groups directly as they come, and a target
that is neither a file nor one of these is refused, by the rule of :mod:`crankbalance.io.files`.
pyarrow is imported here only.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError

Table = Mapping[str, NDArray[Any]]


def _arrow(table: Table) -> Any:
    """The columns as a ``pyarrow.Table`` (2-D columns as fixed-size lists)."""
    import pyarrow as pa

    columns = {}
    for name, values in table.items():
        a = np.asarray(values)
        if a.ndim == 2:
            columns[name] = pa.FixedSizeListArray.from_arrays(pa.array(a.ravel()), a.shape[1])
        elif a.ndim == 1:
            columns[name] = pa.array(a)
        else:
            raise ValueError(f"column {name!r} has {a.ndim} dimensions; 1 or 2 are stored")
    return pa.table(columns)


class ParquetStream:
    """A Parquet file written a row group at a time (use :func:`parquet_stream`)."""

    def __init__(self, handle: Any) -> None:
        self._handle = handle
        self._writer: Any = None
        self.rows = 0

    def write(self, table: Table) -> None:
        """Append the rows of ``table`` as one row group (an empty table fixes the columns
        of a file that gets no rows, and adds no row group)."""
        import pyarrow.parquet as pq

        arrow = _arrow(table)
        if self._writer is None:
            self._writer = pq.ParquetWriter(self._handle, arrow.schema)
        if arrow.num_rows:
            self._writer.write_table(arrow, row_group_size=arrow.num_rows)
            self.rows += arrow.num_rows

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()


@contextmanager
def parquet_stream(path: str | os.PathLike[str]) -> Iterator[ParquetStream]:
    """A :class:`ParquetStream` to ``path``; the file appears when the block ends without
    an error, otherwise nothing is left (``path``, if it existed, is untouched). Raises
    :class:`crankbalance.io.files.WriteError` when the file cannot be written."""
    from .files import atomic_open

    with atomic_open(path, "wb") as handle:
        stream = ParquetStream(handle)
        try:
            yield stream
        finally:  # the writer is closed while its file is open, error or not
            stream.close()
        if stream.rows == 0 and stream._writer is None:
            raise ValueError("parquet_stream: no table was written (not even its columns)")


def read_parquet(path: str | os.PathLike[str]) -> dict[str, NDArray[Any]]:
    """The columns of a file written by :func:`parquet_stream` (2-D columns as 2-D arrays).

    Raises :class:`~crankbalance.errors.InputError` naming the file when it is not one.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    try:
        table = pq.read_table(path)
    except (OSError, pa.ArrowException) as error:
        raise InputError("file", os.fspath(path), f"a Parquet file ({error})") from None
    out: dict[str, NDArray[Any]] = {}
    for name in table.column_names:
        column = table.column(name).combine_chunks()
        if pa.types.is_fixed_size_list(column.type):
            width = column.type.list_size
            out[name] = column.flatten().to_numpy().reshape(-1, width)
        else:
            out[name] = column.to_numpy()
    return out
