"""Atomic writes (issue 12, items 4 and 7): every file crankbalance writes goes through
``crankbalance.io.files``, and a writer killed (``kill -9``) or stopped by a full disk
leaves the previous file byte for byte as it was.

The fault tests run each writer in a child interpreter that wraps ``os.fdopen`` and
``os.fsync`` (which the helper calls) for the one temporary file of the target: the child
either stalls there, tells the parent through a pipe, and is killed; or fails the way a
full disk does (``ENOSPC``); a small tmpfs gives a really full disk where mounting one is
allowed. Tests wait for the child's message, never for a time; ``HANG_GUARD`` only ends
a test that would otherwise hang.
"""

from __future__ import annotations

import ast
import errno
import importlib.util
import os
import re
import select
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from crankbalance.io.files import TEMP_SUFFIX, WriteError, atomic_open, write_atomic

from .conftest import EXAMPLES
from .test_counterweight import ROW2

SRC = Path(__file__).resolve().parents[1] / "src" / "crankbalance"
HANG_GUARD = 900.0  # seconds: a stuck child fails the test instead of hanging the suite
OLD = b"the previous file, which must survive\n"
NO_SPACE = os.strerror(errno.ENOSPC)

# --------------------------------------------------------------------------- the writers
CW = ["counterweight", "export", *ROW2, "--thickness", "5 mm", "-o"]
CW_PLOT = ["counterweight", "show", *ROW2, "--thickness", "5 mm", "--plot"]
BENCH = ["bench", "--friction-coefficient", "0.5", "--speed", "1000 rpm"]
BENCH += ["--ramp-time", "0.3 s", "--hold-time", "0.2 s", "--history"]
NO_CAD = importlib.util.find_spec("build123d") is None
EXPLORE = ["explore", "--cylinders", "4", "--output"]
SHEET = ["shop", "sheet", str(EXAMPLES / "v8_parts.csv"), "--engine", "v8-crossplane"]
SHEET += ["--time-limit", "1 s", "-o"]  # the matching's result does not matter here
TORSIONAL = ["torsional", "--engine", "inline6", "--speed-points", "40", "--plot"]
#: name: (file name, command line without the file, whole write() calls before the stall:
#: the history CSV is written row by row, so it is stopped in its second row; the Parquet
#: just after its magic number)
WRITERS = {
    "bench-history-csv": ("history.csv", BENCH, 2),
    "counterweight-svg": ("cw.svg", CW, 0),
    "counterweight-dxf": ("cw.dxf", CW, 0),
    "counterweight-stl": ("cw.stl", CW, 0),
    "counterweight-step": ("cw.step", CW, 0),
    "counterweight-plot-html": ("cw.html", CW_PLOT, 0),
    "plot-html": ("orders.html", ["plot", "orders", "inline3", "-o"], 0),
    "plot-png": ("orders.png", ["plot", "orders", "inline3", "-o"], 0),
    "report-html": ("report.html", ["report", "inline3", "-o"], 0),
    "report-pdf": ("report.pdf", ["report", "inline3", "-o"], 0),
    "engine-save": ("engine.toml", ["save-engine"], 0),
    "explore-parquet": ("rows.parquet", EXPLORE, 1),
    "shop-sheet-html": ("sheet.html", SHEET, 0),
    "torsional-plot-html": ("torsional.html", TORSIONAL, 0),
}
ALL_WRITERS = [
    pytest.param(
        name,
        marks=pytest.mark.skipif(
            NO_CAD, reason="STEP export needs the cad extra (build123d), not installed"
        ),
    )
    if name == "counterweight-step"
    else name
    for name in WRITERS
]

#: the child: argv = ready-fd, point (write/fsync/none), action (stall/enospc),
#: whole writes before the fault, target, then the command line (or save-engine)
CHILD = r"""
import errno, os, sys, threading

ready, point, action, after, target = sys.argv[1:6]
command = sys.argv[6:]
real = os.path.realpath(target)  # the temporary file is beside the file a link names
prefix = os.path.join(os.path.dirname(real), "." + os.path.basename(real) + ".")


def ours(fd):
    return os.readlink(f"/proc/self/fd/{fd}").startswith(prefix)


def fault():
    if action == "stall":
        os.write(int(ready), b"ready")
        threading.Event().wait()
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


class Faulty:
    # the temporary file's handle: whole writes first, then half of one and the fault
    def __init__(self, handle):
        self.handle, self.calls = handle, 0

    def __getattr__(self, name):
        return getattr(self.handle, name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return self.handle.__exit__(*exc)

    def write(self, data):
        if self.calls == int(after):
            self.handle.write(data[: len(data) // 2])
            self.handle.flush()
            fault()
        self.calls += 1
        return self.handle.write(data)


if point == "write":
    real_fdopen = os.fdopen

    def fdopen(fd, *args, **kwargs):
        handle = real_fdopen(fd, *args, **kwargs)
        return Faulty(handle) if ours(fd) else handle

    os.fdopen = fdopen
elif point == "fsync":
    real_fsync = os.fsync

    def fsync(fd):
        if ours(fd):
            fault()
        real_fsync(fd)

    os.fsync = fsync

if command == ["save-engine"]:
    from crankbalance.io.engine_file import parse_engine_text, preset_text, save_engine
    from crankbalance.io.files import WriteError

    try:
        save_engine(parse_engine_text(preset_text("inline3")), target)
    except WriteError as error:
        print(f"error: {error}", file=sys.stderr)
        sys.exit(2)
else:
    from crankbalance.cli import main

    main([*command, target])
"""


def child_command(name: str, target: Path, point: str, action: str, ready: int = -1) -> list[str]:
    _, command, after = WRITERS[name]
    return [sys.executable, "-c", CHILD, str(ready), point, action, str(after), str(target)] + (
        command
    )


def previous_file(tmp_path: Path, name: str) -> Path:
    """A folder holding only the writer's target, with :data:`OLD` in it."""
    folder = tmp_path / "out"
    folder.mkdir()
    target = folder / WRITERS[name][0]
    target.write_bytes(OLD)
    return target


def temp_files(target: Path) -> list[str]:
    """The names beside ``target`` other than itself; each must be a hidden temporary file
    named after it (the only thing a killed writer may leave)."""
    pattern = re.compile(re.escape(f".{target.name}.") + "[0-9a-f]{12}" + re.escape(TEMP_SUFFIX))
    others = sorted(p.name for p in target.parent.iterdir() if p.name != target.name)
    assert all(pattern.fullmatch(n) for n in others), others
    return others


def refused_for_lack_of_space(target: Path, name: str, point: str, action: str) -> None:
    """Run the writer on a full disk: exit 2, one line, the previous file intact and no
    temporary file left."""
    done = subprocess.run(
        child_command(name, target, point, action),
        capture_output=True,
        text=True,
        timeout=HANG_GUARD,
        check=False,
    )
    assert "Traceback" not in done.stderr, done.stderr
    errors = [line for line in done.stderr.splitlines() if "error" in line.lower()]
    assert errors == [f"error: cannot write {target}: {NO_SPACE}"], done.stderr
    assert done.returncode == 2, done.stderr
    assert done.stderr.rstrip().splitlines()[-1] == errors[0]
    assert target.read_bytes() == OLD
    assert temp_files(target) == []


needs_proc = pytest.mark.skipif(
    not Path("/proc/self/fd").is_dir(), reason="the fault injection finds files in /proc/self/fd"
)


# --------------------------------------------------------------------------- kill -9
@needs_proc
@pytest.mark.parametrize("name", ALL_WRITERS)
def test_kill_during_write_keeps_previous_file(tmp_path: Path, name: str) -> None:
    """Killed half way through writing its data, the writer leaves the previous file intact
    (and at most its hidden temporary file)."""
    target = previous_file(tmp_path, name)
    killed_while_writing(target, name, "write")


@needs_proc
@pytest.mark.parametrize("name", ["bench-history-csv", "counterweight-svg", "report-html"])
def test_kill_before_rename_keeps_previous_file(tmp_path: Path, name: str) -> None:
    """Killed with all the data written but not yet synced and renamed: still the old file."""
    target = previous_file(tmp_path, name)
    killed_while_writing(target, name, "fsync")


def killed_while_writing(target: Path, name: str, point: str) -> None:
    read, write = os.pipe()
    log = target.parent.parent / "child.log"
    with log.open("w") as stderr:
        child = subprocess.Popen(
            child_command(name, target, point, "stall", write),
            pass_fds=(write,),
            stdout=subprocess.DEVNULL,
            stderr=stderr,
        )
    os.close(write)
    try:
        ready, _, _ = select.select([read], [], [], HANG_GUARD)
        message = os.read(read, 16) if ready else b""
        assert message == b"ready", f"the child did not reach the write: {log.read_text()}"
        # the child stands inside the write: its temporary file exists, the target is old
        assert len(temp_files(target)) == 1
        assert target.read_bytes() == OLD
        child.kill()
        assert child.wait(timeout=HANG_GUARD) == -9
    finally:
        os.close(read)
        if child.poll() is None:
            child.kill()
            child.wait(timeout=HANG_GUARD)
    assert target.read_bytes() == OLD
    assert len(temp_files(target)) == 1  # the documented hidden leftover of a kill -9


# --------------------------------------------------------------------------- full disk
@needs_proc
@pytest.mark.parametrize("point", ["write", "fsync"])
@pytest.mark.parametrize("name", ALL_WRITERS)
def test_disk_full_keeps_previous_file(tmp_path: Path, name: str, point: str) -> None:
    """ENOSPC half way through the data, or when syncing it: one line, exit 2, the previous
    file intact and no temporary file left."""
    refused_for_lack_of_space(previous_file(tmp_path, name), name, point, "enospc")


@pytest.fixture(scope="module")
def small_disk(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A 16 MiB tmpfs (room for the largest file, a report with plotly.js inlined)."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("mounting a tmpfs needs root and mount(8); the injected ENOSPC tests run")
    folder = tmp_path_factory.mktemp("tmpfs")
    done = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", "size=16m", "tmpfs", str(folder)],
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here ({done.stderr.strip()}); injected ENOSPC runs")
    yield folder
    subprocess.run(["umount", str(folder)], check=True)


@pytest.mark.parametrize("name", ALL_WRITERS)
def test_really_full_disk_keeps_previous_file(small_disk: Path, name: str) -> None:
    """On a tmpfs filled up to the last block, no write fakes a failure: the kernel refuses."""
    for leftover in small_disk.iterdir():
        shutil.rmtree(leftover) if leftover.is_dir() else leftover.unlink()
    folder = small_disk / "out"
    folder.mkdir()
    target = folder / WRITERS[name][0]
    target.write_bytes(OLD)
    with (small_disk / "filler").open("wb", buffering=0) as filler:
        with pytest.raises(OSError) as full:
            while True:
                filler.write(bytes(65536))
        assert full.value.errno == errno.ENOSPC
    refused_for_lack_of_space(target, name, "none", "none")


# --------------------------------------------------------------------------- the helper
def test_write_atomic_writes_and_replaces(tmp_path: Path) -> None:
    target = tmp_path / "a.txt"
    write_atomic(target, "é\n")
    assert target.read_bytes() == "é\n".encode()
    write_atomic(target, b"\x00\x01")
    assert target.read_bytes() == b"\x00\x01"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]


def test_streaming_writer_appears_only_when_done(tmp_path: Path) -> None:
    target = tmp_path / "rows.csv"
    target.write_bytes(OLD)
    with atomic_open(target) as handle:
        handle.write("a,b\n")
        assert target.read_bytes() == OLD
        handle.write("1,2\n")
    assert target.read_text() == "a,b\n1,2\n"


def test_error_in_the_block_keeps_the_previous_file(tmp_path: Path) -> None:
    """The caller's own exception passes through unchanged; an OS error becomes a
    WriteError; either way the target is untouched and the temporary file gone."""
    target = tmp_path / "rows.csv"
    target.write_bytes(OLD)
    with pytest.raises(ZeroDivisionError), atomic_open(target) as handle:
        handle.write("half a row,")
        _ = 1 / 0
    with pytest.raises(WriteError, match=f"cannot write {re.escape(str(target))}: {NO_SPACE}$"):
        with atomic_open(target, "wb") as handle:
            handle.write(b"x")
            raise OSError(errno.ENOSPC, NO_SPACE)
    assert target.read_bytes() == OLD
    assert temp_files(target) == []


def test_unwritable_targets_are_one_line(tmp_path: Path) -> None:
    missing = tmp_path / "no-such-folder" / "a.svg"
    with pytest.raises(WriteError) as error:
        write_atomic(missing, "x")
    assert error.value.errno == errno.ENOENT
    assert str(error.value) == f"cannot write {missing}: {os.strerror(errno.ENOENT)}"
    folder = tmp_path / "a-folder"
    folder.mkdir()
    (folder / "inside").write_bytes(OLD)
    with pytest.raises(WriteError, match="cannot write"):
        write_atomic(folder, "x")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-folder"]
    assert (folder / "inside").read_bytes() == OLD


def test_long_names_and_leftovers(tmp_path: Path) -> None:
    """A 255-byte file name still gets a temporary name within the limit, and a temporary
    file a killed writer left does not stop the next write."""
    target = tmp_path / ("n" * 251 + ".csv")
    write_atomic(target, "x")
    assert target.read_text() == "x"
    leftover = tmp_path / f".{target.name[:200]}.{'0' * 12}{TEMP_SUFFIX}"
    leftover.write_bytes(b"killed")
    write_atomic(target, "y")
    assert target.read_text() == "y" and leftover.read_bytes() == b"killed"


def test_atomic_open_modes() -> None:
    with pytest.raises(ValueError, match="mode"), atomic_open("x.txt", "a"):
        pass


# --------------------------------------------------------------------------- no bypass
#: module-qualified calls that write, copy, move or create files (os.open: by its flags)
QUALIFIED = {
    "os": {"fdopen", "replace", "rename", "renames", "link", "symlink", "truncate"},
    "shutil": {"copy", "copy2", "copyfile", "copyfileobj", "copytree", "move"},
    "tempfile": {"mkstemp", "NamedTemporaryFile", "TemporaryFile", "SpooledTemporaryFile"},
    "json": {"dump"},
    "pickle": {"dump"},
    "np": {"save", "savez", "savez_compressed", "savetxt"},
    "numpy": {"save", "savez", "savez_compressed", "savetxt"},
}
#: method names that write a file whatever the object (pathlib, plotly, trimesh, build123d,
#: pandas, numpy arrays, matplotlib)
METHODS = {
    "write_text",
    "write_bytes",
    "write_image",
    "write_html",
    "write_json",
    "savefig",
    "to_csv",
    "tofile",
    "export",
    "export_step",
    "export_stl",
    "export_brep",
    "touch",
    "rename",
    "symlink_to",
    "hardlink_to",
}
#: Chromium command-line switches that make it write a file
SWITCHES = ("--print-to-pdf", "--screenshot")
#: the places that may write by a path a library needs, each into a private scratch folder
#: (tempfile.TemporaryDirectory) whose bytes are then written with write_atomic, so that an
#: error of the real write (a full disk) is reported as it is: (module, what) -> why
ALLOWED = {
    ("output/render.py", "--print-to-pdf"): "html_to_pdf: Chromium prints into a scratch folder; "
    "the checked PDF bytes are written by report.write_report with write_atomic",
    ("io/cad.py", "export_step"): "write_step: build123d writes into a scratch folder; "
    "the bytes are written with write_atomic",
}


def writes_in(source: str) -> list[tuple[int, str]]:
    """(line, what) of every direct file write in ``source``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            found += [(node.lineno, s) for s in SWITCHES if node.value.startswith(s)]
        if not isinstance(node, ast.Call):
            continue
        func = node.func
        if isinstance(func, ast.Attribute):
            owner = func.value.id if isinstance(func.value, ast.Name) else None
            if func.attr in QUALIFIED.get(owner or "", ()) or func.attr in METHODS:
                found.append((node.lineno, func.attr))
                continue
        name = func.id if isinstance(func, ast.Name) else getattr(func, "attr", "")
        if isinstance(func, ast.Attribute) and getattr(func.value, "id", "") == "os":
            # os.open(path, flags): a write unless the flags are written out and name
            # no writing mode
            if name == "open" and len(node.args) > 1:
                flags = {getattr(n, "attr", getattr(n, "id", "")) for n in ast.walk(node.args[1])}
                writing = {"O_WRONLY", "O_RDWR", "O_CREAT", "O_APPEND", "O_TRUNC"}
                if flags & writing or "O_RDONLY" not in flags:
                    found.append((node.lineno, "open"))
            continue
        if name == "open":  # builtin open(path, mode) or Path.open(mode)
            where = 1 if isinstance(func, ast.Name) else 0
            mode = node.args[where] if len(node.args) > where else None
            mode = next((k.value for k in node.keywords if k.arg == "mode"), mode)
            text = mode.value if isinstance(mode, ast.Constant) else "r" if mode is None else "?"
            if not isinstance(text, str) or set(text) & set("wax+?"):
                found.append((node.lineno, "open"))
    return found


def test_no_module_writes_a_file_but_io_files() -> None:
    """Every write goes through crankbalance.io.files (the allowed scratch writes aside)."""
    seen = set()
    bypass = []
    for path in sorted(SRC.rglob("*.py")):
        module = path.relative_to(SRC).as_posix()
        if module == "io/files.py":
            continue
        for line, what in writes_in(path.read_text(encoding="utf-8")):
            if (module, what) in ALLOWED:
                seen.add((module, what))
            else:
                bypass.append(f"{module}:{line}: {what}")
    assert bypass == [], "write through crankbalance.io.files instead"
    assert seen == set(ALLOWED), "an allowed scratch write is gone: drop it from ALLOWED"


def test_the_scan_finds_each_kind_of_write() -> None:
    writes = """
open(p, "w"); open(p, mode="ab"); open(p, m); path.open("w"); path.open(mode="x")
path.write_text(s); path.write_bytes(b); fig.write_image(p); fig.write_html(p)
plt.savefig(p); frame.to_csv(p); array.tofile(p); mesh.export(p); bd.export_step(s, p)
os.replace(a, b); os.open(p, flags); shutil.copy(a, b); tempfile.mkstemp(); json.dump(d, f)
np.save(p, a); path.touch(); path.rename(q); run(["chromium", "--screenshot=x.png"])
os.open(p, os.O_WRONLY | os.O_CREAT)
"""
    assert len(writes_in(writes)) == 24
    reads = """
open(p); open(p, "rb"); path.open(); path.open("r"); text.replace("a", "b"); d.copy()
json.dumps(d); model.model_dump(); path.read_bytes(); tempfile.TemporaryDirectory()
os.open(p, os.O_RDONLY | os.O_NONBLOCK)
"""
    assert writes_in(reads) == []
