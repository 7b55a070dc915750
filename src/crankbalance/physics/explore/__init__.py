"""Design-space explorer: every firing order and crank arrangement of a layout, ranked.

Modules: :mod:`.candidates` (the batch every stage passes on), :mod:`.orders`
(enumeration and equivalences), :mod:`.merit` (figures of merit, batched), :mod:`.rank`
(filters, Pareto front, top-N), :mod:`.work` (the work of a run, known and bounded
before it starts, and its chunk), :mod:`.run` (chunked runs in this process or on dask,
streaming to Parquet). Pure numpy/scipy except :mod:`.run`, which imports dask and
pyarrow only when they are used.
"""
