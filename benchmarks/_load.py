"""A loaded machine for the benchmarks' ``--load K``: K ``yes > /dev/null`` processes."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def cpu_load(processes: int) -> Iterator[None]:
    """Keep ``processes`` CPU-bound ``yes`` processes running inside the ``with`` block."""
    loaders = [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) for _ in range(processes)]
    try:
        yield
    finally:
        for proc in loaders:
            proc.kill()
            proc.wait()
