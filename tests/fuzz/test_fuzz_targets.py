"""Special files as the target of every command that writes a file (issue 25, item 8).

Every writer (``explore --output`` and ``--plot``, ``shop sheet -o``, ``torsional --plot``,
``plot -o``, ``report -o``, ``counterweight export``, ``bench --history``, and the ``--plot``
of ``bearings``, ``bearings-sweep`` and ``cycle``) is given each kind of target the one rule
of ``crankbalance.io.files`` decides on (docs/reliability.md, "Files: atomic writes"): a
FIFO without a reader, a FIFO with a reader, a directory, a socket, a dangling link, a link
loop, and a character device node of ``/dev/null``'s numbers made in the test's folder (as
root; skipped with the reason otherwise; the machine's own ``/dev`` is never touched).

The command must end in one error line (the last on stderr; ``bench`` prints its progress
before it writes the rows) and exit 2, or in success, and the target must stay what
it was (a FIFO a FIFO, a folder a folder with its contents, a link the same link, the device
node 1:3), with nothing else left in the folder (no temporary file) but, for the dangling
link, the file it names. The helpers are those of ``tests/test_special_targets.py`` (the
FIFO's reader, device nodes) and ``tests/test_atomic_writes.py`` (the writers' command
lines); the runs are in-process (the runner and check of :mod:`.test_fuzz_options`), under
the hang guard.
"""

from __future__ import annotations

import errno
import os
import socket
import stat
from collections.abc import Callable
from pathlib import Path

import pytest

from crankbalance.io.files import ALLOWED, NULL_DEVICE

from ..conftest import hang_guard
from ..test_atomic_writes import WRITERS
from ..test_special_targets import (
    NO_READER,
    SPECIAL,
    FifoReader,
    device_node,
    one_error_line,
    whole_html,
)
from .test_fuzz_options import HANG_GUARD, assert_clean, run

#: every command with a file output: (file name, command line without the file, a check
#: that bytes are a whole file); the writers of test_special_targets, and the --plot of
#: explore, bearings, bearings-sweep and cycle
TARGET_WRITERS: dict[str, tuple[str, list[str], Callable[[bytes], bool]]] = {
    **{name: (WRITERS[name][0], WRITERS[name][1], check) for name, check in SPECIAL.items()},
    # the sheet's parts as listed: a matching would take its time limit in each case
    "shop-sheet-html": (
        WRITERS["shop-sheet-html"][0],
        [*WRITERS["shop-sheet-html"][1][:-1], "--method", "as-listed", "-o"],
        whole_html,
    ),
    "explore-plot-html": ("explore.html", ["explore", "--cylinders", "4", "--plot"], whole_html),
    "bearings-plot-html": (
        "bearings.html",
        ["bearings", "inline4", "--samples", "36", "--plot"],
        whole_html,
    ),
    "bearings-sweep-plot-html": (
        "sweep.html",
        ["bearings-sweep", "inline4", "--samples", "36", "--balance-factors", "0.5", "--plot"],
        whole_html,
    ),
    "cycle-plot-html": ("cycle.html", ["cycle", "--engine", "single", "--plot"], whole_html),
}
KINDS = [
    "FIFO without a reader",
    "FIFO with a reader",
    "directory",
    "socket",
    "dangling link",
    "link loop",
    "device 1:3",
]
TALLY: dict[str, int] = {"tried": 0, "clean": 0, "exit 0": 0, "exit 2": 0}


def identity(path: Path) -> tuple[int, int, str]:
    """What ``path`` is (not followed): its kind, its device numbers and a link's text."""
    st = os.lstat(path)
    text = os.readlink(path) if stat.S_ISLNK(st.st_mode) else ""
    return stat.S_IFMT(st.st_mode), st.st_rdev, text


@pytest.fixture(scope="module", autouse=True)
def _print_tally() -> object:
    yield
    print(
        f"\nfuzz targets: tried {TALLY['tried']}, clean {TALLY['clean']} "
        f"(exit 0: {TALLY['exit 0']}, exit 2: {TALLY['exit 2']})"
    )


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("writer", list(TARGET_WRITERS))
def test_special_target(writer: str, kind: str, tmp_path: Path) -> None:
    name, command, whole = TARGET_WRITERS[writer]
    target = tmp_path / name
    made = tmp_path / f"made{target.suffix}"  # the file a dangling link names
    inside = b"the folder's own file\n"
    reader = None
    if kind == "device 1:3":
        device_node(tmp_path, name, stat.S_IFCHR, NULL_DEVICE)
        try:
            os.close(os.open(target, os.O_WRONLY))
        except PermissionError:
            pytest.skip("the test folder's file system is mounted nodev")
    elif kind.startswith("FIFO"):
        os.mkfifo(target)
        if kind == "FIFO with a reader":
            reader = FifoReader(target)
    elif kind == "directory":
        target.mkdir()
        (target / "inside").write_bytes(inside)
    elif kind == "socket":
        with socket.socket(socket.AF_UNIX) as server:
            server.bind(str(target))
    elif kind == "dangling link":
        target.symlink_to(made.name)
    else:
        target.symlink_to(target.name)
    before = identity(target)
    call = [*command, str(target)]
    TALLY["tried"] += 1
    try:
        with hang_guard(HANG_GUARD):
            code, out, err = run(call)
    finally:
        data = reader.received() if reader is not None else b""
    assert identity(target) == before, (kind, identity(target), before)
    left = {p.name for p in tmp_path.iterdir()}
    refused = {
        "FIFO without a reader": NO_READER,
        # a folder: the writer's line, or the option's own check (click's, or "a file
        # name, not a directory") before any work
        "directory": "directory",
        "socket": f"is a socket; {ALLOWED}",
        "link loop": os.strerror(errno.ELOOP),
    }
    if kind in refused:
        # one line, the last (bench prints its progress line before it writes the rows)
        assert code == 2 and refused[kind] in one_error_line(err), (call, err)
        assert left == {name}, left
    else:
        assert_clean(call, code, out, err)
        assert code == 0, (call, err)
        if kind == "FIFO with a reader":
            assert whole(data), data[:200]
        if kind == "dangling link":
            assert whole(made.read_bytes()), made.read_bytes()[:200]
        assert left == ({name, made.name} if kind == "dangling link" else {name}), left
    if kind == "directory":
        assert [p.name for p in target.iterdir()] == ["inside"]
        assert (target / "inside").read_bytes() == inside
    TALLY["clean"] += 1
    TALLY[f"exit {code}"] += 1
