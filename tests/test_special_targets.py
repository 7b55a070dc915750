"""Special targets (issue 25): what a writer does when its target is not a regular file.

Every writer goes through ``crankbalance.io.files``, whose one rule (docs/reliability.md,
"Files: atomic writes") is checked here: a FIFO with a reader, ``/dev/null``'s kind of
device, a terminal and the standard streams are written into and stay what they were; a
FIFO with no reader is refused at once; a directory, a socket, a block device or any other
device is refused unopened; a symbolic link is followed and stays a link. No test touches
the machine's own ``/dev/null``: device nodes of the same numbers are made in the test's
folder. Tests wait for a state (a process exit, a reader's end of file); ``HANG_GUARD``
only ends a test that would otherwise hang.
"""

from __future__ import annotations

import errno
import os
import re
import select
import socket
import stat
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import pytest

from crankbalance.io.files import ALLOWED, NULL_DEVICE, WriteError, atomic_open, write_atomic

from .conftest import run_cli
from .test_atomic_writes import HANG_GUARD, OLD, WRITERS, needs_proc, temp_files

NO_READER = "is a FIFO with no process reading it"


def whole_parquet(data: bytes) -> bool:
    return len(data) > 8 and data.startswith(b"PAR1") and data.endswith(b"PAR1")


def whole_html(data: bytes) -> bool:
    return data.lower().startswith(b"<!doctype html") and data.rstrip().endswith(b"</html>")


#: writer (a name of test_atomic_writes.WRITERS) -> a check that the bytes are a whole file
SPECIAL = {
    "explore-parquet": whole_parquet,
    "shop-sheet-html": whole_html,
    "torsional-plot-html": whole_html,
    "plot-html": whole_html,
    "report-html": whole_html,
    "counterweight-plot-html": whole_html,
    "counterweight-svg": lambda data: b"<svg" in data and data.rstrip().endswith(b"</svg>"),
    "bench-history-csv": lambda data: (
        data.startswith(b"time_s,speed_rpm,") and data.endswith(b"\n") and data.count(b"\n") > 2
    ),
}


def command(name: str, target: Path) -> list[str]:
    """The writer's command line with ``target`` as its file."""
    return [*WRITERS[name][1], str(target)]


class FifoReader:
    """A reader of ``fifo``, present before the writer opens it: the read end is opened at
    once (without waiting for a writer), a thread reads everything up to the end of file."""

    def __init__(self, fifo: Path) -> None:
        self.fifo = fifo
        self.fd = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
        self.data = bytearray()
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self) -> None:
        # a FIFO no writer has opened yet is not readable: this waits for the writer
        select.select([self.fd], [], [], HANG_GUARD)
        os.set_blocking(self.fd, True)
        while chunk := os.read(self.fd, 1 << 16):
            self.data += chunk

    def received(self) -> bytes:
        """Everything written, once the writer is done (a writer that never came is
        stood in for by an empty one, so the thread always ends; it opens the pipe the
        reader holds, even if something was renamed over the FIFO's name)."""
        os.close(os.open(f"/proc/self/fd/{self.fd}", os.O_WRONLY | os.O_NONBLOCK))
        self.thread.join(HANG_GUARD)
        assert not self.thread.is_alive(), "the reader of the FIFO did not end"
        os.close(self.fd)
        return bytes(self.data)


def still(path: Path, kind: object) -> bool:
    """``path`` (not followed) is still of ``kind`` (stat.S_ISFIFO, stat.S_ISCHR...)."""
    return bool(kind(os.lstat(path).st_mode))  # type: ignore[operator]


def run_child(args: list[str], stdout: Any = subprocess.PIPE) -> subprocess.CompletedProcess[str]:
    """Run a child interpreter to its exit (a hang guard only ends a stuck one)."""
    return subprocess.run(
        [sys.executable, *args],
        stdout=stdout,
        stderr=subprocess.PIPE,
        text=True,
        timeout=HANG_GUARD,
        check=False,
    )


def one_error_line(stderr: str) -> str:
    assert "Traceback" not in stderr, stderr
    errors = [line for line in stderr.splitlines() if "error" in line.lower()]
    assert len(errors) == 1 and stderr.rstrip().splitlines()[-1] == errors[0], stderr
    return errors[0]


# --------------------------------------------------------------------------- FIFOs
@needs_proc
@pytest.mark.parametrize("name", list(SPECIAL))
def test_fifo_with_a_reader_gets_the_file_and_stays_a_fifo(
    tmp_path: Path, name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    """The writer streams into the FIFO (the reader gets the whole file) and the FIFO is
    still a FIFO afterwards (it used to be renamed over by a regular file)."""
    fifo = tmp_path / WRITERS[name][0]
    os.mkfifo(fifo)
    reader = FifoReader(fifo)
    code, _, err = run_cli(command(name, fifo), capsys)
    data = reader.received()
    assert code == 0, err
    assert SPECIAL[name](data), data[:200]
    assert still(fifo, stat.S_ISFIFO)
    assert sorted(p.name for p in tmp_path.iterdir()) == [fifo.name]


@pytest.mark.parametrize("name", list(SPECIAL))
def test_fifo_without_a_reader_is_refused_at_once(tmp_path: Path, name: str) -> None:
    """No process reads the FIFO: the command does not wait for one; exit 2, one line."""
    fifo = tmp_path / WRITERS[name][0]
    os.mkfifo(fifo)
    done = run_child(["-m", "crankbalance", *command(name, fifo)])
    assert one_error_line(done.stderr) == f"error: cannot write {fifo}: {NO_READER}"
    assert done.returncode == 2
    assert still(fifo, stat.S_ISFIFO)
    assert sorted(p.name for p in tmp_path.iterdir()) == [fifo.name]


@needs_proc
def test_fifo_helper(tmp_path: Path) -> None:
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    with pytest.raises(WriteError) as refused:
        write_atomic(fifo, "x")
    assert str(refused.value) == f"cannot write {fifo}: {NO_READER}"
    reader = FifoReader(fifo)
    write_atomic(fifo, "é")
    assert reader.received() == "é".encode()
    assert still(fifo, stat.S_ISFIFO)


def test_reader_going_away_is_one_line(tmp_path: Path) -> None:
    """The reader closes its end during the write: EPIPE, a WriteError of one line."""
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    with pytest.raises(WriteError) as broken, atomic_open(fifo, "wb") as handle:
        handle.write(b"first")
        handle.flush()
        assert os.read(reader, 5) == b"first"
        os.close(reader)
        handle.write(b"second")
    assert str(broken.value) == f"cannot write {fifo}: {os.strerror(errno.EPIPE)}"
    assert still(fifo, stat.S_ISFIFO)


def test_reader_going_away_ends_the_command_in_one_line(tmp_path: Path) -> None:
    """The reader of the FIFO closes it after the first bytes of a 4 MB figure: the
    command ends with exit 2 and one line (click alone would exit 1 without a word)."""
    fifo = tmp_path / WRITERS["plot-html"][0]
    os.mkfifo(fifo)
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    child = subprocess.Popen(
        [sys.executable, "-m", "crankbalance", *command("plot-html", fifo)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        select.select([reader], [], [], HANG_GUARD)  # the command has begun to write
        assert os.read(reader, 9).lower() == b"<!doctype"
    finally:
        os.close(reader)
        _, stderr = child.communicate(timeout=HANG_GUARD)
    assert one_error_line(stderr) == f"error: cannot write {fifo}: {os.strerror(errno.EPIPE)}"
    assert child.returncode == 2
    assert still(fifo, stat.S_ISFIFO)


# --------------------------------------------------------------------------- devices
def device_node(folder: Path, name: str, kind: int, numbers: tuple[int, int]) -> Path:
    """A device node in ``folder`` (skips when this process may not make one)."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        pytest.skip("making a device node needs root; the FIFO tests cover the streaming")
    node = folder / name
    try:
        os.mknod(node, kind | 0o666, os.makedev(*numbers))
    except OSError as error:
        pytest.skip(f"this file system refuses device nodes ({error.strerror})")
    return node


def test_null_device_stays_a_device(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The tester's example, on a node of /dev/null's numbers in the test's folder (the
    real /dev/null is not touched): the Parquet goes into it and the node stays 1:3."""
    null = device_node(tmp_path, "null", stat.S_IFCHR, NULL_DEVICE)
    try:
        os.close(os.open(null, os.O_WRONLY))
    except PermissionError:
        pytest.skip("the test folder's file system is mounted nodev")
    code, _, err = run_cli(command("explore-parquet", null), capsys)
    assert code == 0, err
    st = os.lstat(null)
    assert stat.S_ISCHR(st.st_mode)
    assert (os.major(st.st_rdev), os.minor(st.st_rdev)) == NULL_DEVICE
    assert sorted(p.name for p in tmp_path.iterdir()) == ["null"]


@pytest.mark.parametrize(
    ("kind", "numbers", "what"),
    [
        (stat.S_IFBLK, (7, 0), "a block device (7:0)"),  # a loop device's numbers
        (stat.S_IFCHR, (1, 1), "a character device (1:1)"),  # /dev/mem's numbers
        (stat.S_IFCHR, (10, 130), "a character device (10:130)"),  # a watchdog's numbers
    ],
)
def test_other_devices_are_refused(
    tmp_path: Path,
    kind: int,
    numbers: tuple[int, int],
    what: str,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """A block device or a character device that is neither a terminal nor /dev/null's
    kind: exit 2, one line saying what it is and what is allowed; the node is not
    replaced (and never opened: opening such a node may act on the hardware)."""
    node = device_node(tmp_path, "node.parquet", kind, numbers)
    code, _, err = run_cli(command("explore-parquet", node), capsys)
    assert code == 2
    assert one_error_line(err) == f"error: cannot write {node}: is {what}; {ALLOWED}"
    st = os.lstat(node)
    assert stat.S_IFMT(st.st_mode) == kind and st.st_rdev == os.makedev(*numbers)
    assert sorted(p.name for p in tmp_path.iterdir()) == [node.name]


def test_terminal_is_written_into(tmp_path: Path) -> None:
    """A pseudo-terminal gets the bytes (read back on its master side) and stays one."""
    master, slave = os.openpty()
    try:
        name = Path(os.ttyname(slave))
        write_atomic(name, "to the terminal")
        got = b""
        while len(got) < len("to the terminal"):
            ready, _, _ = select.select([master], [], [], HANG_GUARD)
            assert ready, "nothing reached the terminal"
            got += os.read(master, 100)
        assert got == b"to the terminal"
        assert still(name, stat.S_ISCHR)
    finally:
        os.close(slave)
        os.close(master)


# --------------------------------------------------------------------------- streams
STDOUT = """
import sys
from crankbalance.io.files import write_atomic
print("printed first", flush=True)
write_atomic(sys.argv[1], "written directly\\n")
print("printed last")
"""


@pytest.mark.parametrize("name", ["/dev/stdout", "/dev/fd/1", "/proc/self/fd/1", "a link"])
def test_stdout_redirected_to_a_file_is_written_into(tmp_path: Path, name: str) -> None:
    """``--output /dev/stdout`` with the shell's ``> file``: the data goes into the file
    the shell opened, after what was printed before; the file is not replaced (same
    inode). A symbolic link to /dev/stdout is the same."""
    made = ["link"] if name == "a link" else []
    if made:
        name = str(tmp_path / "link")
        os.symlink("/dev/stdout", name)
    out = tmp_path / "out.txt"
    out.write_text("")
    inode = out.stat().st_ino
    with out.open("a") as stdout:
        done = run_child(["-c", STDOUT, name], stdout=stdout)
    assert done.returncode == 0, done.stderr
    assert out.read_text() == "printed first\nwritten directly\nprinted last\n"
    assert out.stat().st_ino == inode
    assert sorted(p.name for p in tmp_path.iterdir()) == [*made, "out.txt"]


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="no /dev/full on this machine")
def test_full_disk_on_a_stream_is_one_line(tmp_path: Path) -> None:
    """A direct write that fails (standard output on /dev/full: ENOSPC) is one line."""
    with Path("/dev/full").open("w") as full:
        args = command("bench-history-csv", Path("/dev/stdout"))
        done = run_child(["-m", "crankbalance", *args], stdout=full)
    line = one_error_line(done.stderr)
    assert line == f"error: cannot write /dev/stdout: {os.strerror(errno.ENOSPC)}"
    assert done.returncode == 2


def test_descriptor_not_open_is_refused() -> None:
    with pytest.raises(WriteError, match=r"^cannot write /dev/fd/987: no such open descriptor$"):
        write_atomic("/dev/fd/987", "x")


# --------------------------------------------------------------------------- other kinds
def test_directory_is_refused(tmp_path: Path) -> None:
    folder = tmp_path / "folder"
    folder.mkdir()
    (folder / "inside").write_bytes(OLD)
    with pytest.raises(WriteError) as refused:
        write_atomic(folder, "x")
    assert str(refused.value) == f"cannot write {folder}: is a directory; {ALLOWED}"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["folder"]
    assert [p.name for p in folder.iterdir()] == ["inside"]


def test_socket_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "s.sock"
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(path))
        with pytest.raises(WriteError) as refused:
            write_atomic(path, "x")
    assert str(refused.value) == f"cannot write {path}: is a socket; {ALLOWED}"
    assert still(path, stat.S_ISSOCK)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.sock"]


def test_symlink_is_followed_and_stays_a_link(tmp_path: Path) -> None:
    """The file the link points to (in another folder) is replaced atomically; the link
    is still a link; the temporary file was beside the file, and is gone."""
    (tmp_path / "data").mkdir()
    real = tmp_path / "data" / "engine.toml"
    real.write_bytes(OLD)
    real.chmod(0o640)
    link = tmp_path / "link.toml"
    link.symlink_to(Path("data") / "engine.toml")
    write_atomic(link, "new")
    assert link.is_symlink() and os.readlink(link) == os.path.join("data", "engine.toml")
    assert real.read_text() == "new"
    assert stat.S_IMODE(real.stat().st_mode) == 0o640
    assert temp_files(real) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["data", "link.toml"]


def test_dangling_link(tmp_path: Path) -> None:
    """A link to a file not there yet: that file is written, the link stays; a link into
    a missing folder: the usual WriteError and nothing is created."""
    link = tmp_path / "link"
    link.symlink_to("made.txt")
    write_atomic(link, "x")
    assert link.is_symlink() and (tmp_path / "made.txt").read_text() == "x"
    nowhere = tmp_path / "nowhere"
    nowhere.symlink_to(Path("no-such-folder") / "a.txt")
    with pytest.raises(WriteError) as missing:
        write_atomic(nowhere, "x")
    assert str(missing.value) == f"cannot write {nowhere}: {os.strerror(errno.ENOENT)}"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link", "made.txt", "nowhere"]


def test_symlink_loop_is_one_line(tmp_path: Path) -> None:
    loop = tmp_path / "loop"
    loop.symlink_to("loop")
    with pytest.raises(WriteError, match=re.escape(os.strerror(errno.ELOOP))):
        write_atomic(loop, "x")
    assert loop.is_symlink()


@pytest.mark.parametrize("name", list(SPECIAL))
def test_symlink_loop_given_to_a_command_is_one_line(
    tmp_path: Path, name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    """A link that points to itself as a command's target: one line and exit 2 (explore
    --output and bench --history resolved it with Path.resolve, a RuntimeError traceback)."""
    loop = tmp_path / WRITERS[name][0]
    loop.symlink_to(loop.name)
    code, _, err = run_cli(command(name, loop), capsys)
    assert code == 2, err
    assert os.strerror(errno.ELOOP) in one_error_line(err)
    assert loop.is_symlink()


def test_target_that_becomes_a_fifo_is_not_replaced(tmp_path: Path) -> None:
    """A FIFO made at the target while the data is written: the rename is not done."""
    target = tmp_path / "rows.csv"
    with pytest.raises(WriteError) as refused, atomic_open(target) as handle:
        handle.write("a,b\n")
        os.mkfifo(target)
    assert str(refused.value) == (
        f"cannot write {target}: became a FIFO while it was being written; not replaced"
    )
    assert still(target, stat.S_ISFIFO)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rows.csv"]


def test_target_swapped_before_the_open_is_not_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Another file put at the target between the look at it and its opening (here
    another FIFO, renamed over it just before the open) is not written into."""
    fifo, other = tmp_path / "f", tmp_path / "other"
    os.mkfifo(fifo)
    os.mkfifo(other)
    readers = [os.open(p, os.O_RDONLY | os.O_NONBLOCK) for p in (fifo, other)]
    real_open = os.open

    def swapping_open(path: Any, flags: int, *args: Any) -> int:
        if Path(path) == fifo and flags & os.O_WRONLY:
            os.replace(other, fifo)
        return real_open(path, flags, *args)

    monkeypatch.setattr(os, "open", swapping_open)
    try:
        with pytest.raises(WriteError) as refused:
            write_atomic(fifo, "x")
    finally:
        monkeypatch.undo()
        for reader in readers:
            assert os.read(reader, 10) == b""
            os.close(reader)
    reason = "changed while it was being opened; nothing was written"
    assert str(refused.value) == f"cannot write {fifo}: {reason}"
