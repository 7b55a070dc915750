"""Writing files safely: atomically, so that a failed save never destroys what the user had,
and never over a device, a FIFO or a folder the user named by mistake.

Every file crankbalance writes goes through this module (a test scans the package for
direct writes). What happens depends on what the target path is (one rule,
:func:`atomic_open`; docs/reliability.md, "Files: atomic writes"):

- **Missing, or a regular file**: written atomically. The data goes to a hidden temporary
  file in the destination folder, ``.NAME.<12 hex digits>.tmp``, which is flushed, synced
  to the disk and then renamed over ``NAME`` in one step: the file is always either wholly
  the old content or wholly the new. Right before the rename the target is looked at again
  (``lstat``): if it has become anything but a regular file meanwhile (a FIFO, a device),
  it is not replaced. Any error (a full disk, permissions, an exception of the code
  writing) removes the temporary file, leaves ``NAME`` untouched and raises
  :class:`WriteError`. Only a process killed outright (``kill -9``, a power cut) can leave
  a temporary file behind, and it is hidden and named after its target; the target itself
  is intact.
- **A symbolic link** is followed: the file it points to is replaced atomically in its own
  folder and the link stays a link. A dangling link: the file it names is written, if that
  file's folder exists.
- **The standard streams and the discard device**, where writing into a special file is
  what a user means, are written into directly (never renamed over): ``/dev/stdout``,
  ``/dev/stderr``, ``/dev/stdin``, ``/dev/fd/N`` and ``/proc/self/fd/N`` (the descriptor
  itself, whatever it is open on: a file the shell redirected to is written into, not
  replaced), Linux's null device (a character device 1:3 such as ``/dev/null``) and a
  terminal (a virtual console, ``/dev/tty``, ``/dev/console`` or a pseudo-terminal
  ``/dev/pts/N``, confirmed by ``isatty`` once opened).
- **A FIFO** is written into directly when a process is reading it; with no reader it is
  refused at once (it is opened without waiting).
- **Anything else that exists** (a directory, a socket, a block device, any other
  character device such as ``/dev/mem``) is refused with one line saying what it is;
  nothing is opened, created or renamed.

Direct writes are not atomic: what was written before an error stays written.

Public functions
----------------
- ``write_atomic(path, data)``: write ``str`` (UTF-8) or ``bytes`` in one go.
- ``atomic_open(path, mode="w")``: a context manager giving a file handle for writers that
  write progressively (rows of a CSV, a library that wants a file object); the file appears
  when the block ends without an error.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import stat
import sys
from collections.abc import Iterator
from typing import IO, TYPE_CHECKING, Any

if TYPE_CHECKING:  # pathlib (with urllib and ipaddress) is imported on the first write
    from pathlib import Path

#: the end of every temporary file name (``.NAME.<12 hex digits>.tmp``)
TEMP_SUFFIX = ".tmp"
#: the most symbolic links followed from the target's name while looking for a standard
#: stream's name (Linux's own limit, MAXSYMLINKS)
MAX_LINKS = 40
#: (major, minor) of Linux's null device, ``/dev/null``
NULL_DEVICE = (1, 3)
#: character devices that may be a terminal, (major, first minor, last minor): the virtual
#: consoles ``/dev/tty0``-``/dev/tty63``, ``/dev/tty`` and ``/dev/console``, the
#: pseudo-terminals ``/dev/pts/N``. Only these are opened (and then confirmed with
#: ``isatty``): opening some other character devices acts on the hardware (a watchdog
#: starts, a serial port resets what is plugged in), so they are refused unopened.
TERMINAL_DEVICES = ((4, 0, 63), (5, 0, 1), *((major, 0, 2**20 - 1) for major in range(136, 144)))
#: what a refusal says is allowed
ALLOWED = (
    "crankbalance writes regular files, or streams into a FIFO, a terminal, /dev/null or "
    "/dev/stdout"
)
#: the names of a standard stream or of one of this process's descriptors
_STREAM = re.compile(r"/dev/std(?P<std>in|out|err)|(?:/dev|/proc/(?P<proc>[^/]+))/fd/(?P<fd>\d+)")
_STD = {"in": 0, "out": 1, "err": 2}


class WriteError(OSError):
    """A file could not be written (disk full, permissions, a missing folder, a target that
    is not a file...); the previous file, if any, is intact. ``str()`` is one line:
    ``cannot write FILE: reason``.
    """

    def __init__(self, path: str | os.PathLike[str], error: OSError) -> None:
        reason = error.strerror or str(error) or type(error).__name__
        super().__init__(error.errno, reason, os.fspath(path))

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror}"


def write_atomic(path: str | os.PathLike[str], data: str | bytes) -> None:
    """Write ``data`` to ``path`` so that the file is either wholly the new content or
    untouched (text is written as UTF-8); a stream, ``/dev/null``, a terminal or a FIFO
    with a reader gets the data directly (see the module's rule). Raises
    :class:`WriteError`."""
    with atomic_open(path, "wb" if isinstance(data, bytes) else "w") as handle:
        handle.write(data)


@contextlib.contextmanager
def atomic_open(path: str | os.PathLike[str], mode: str = "w") -> Iterator[IO[Any]]:
    """Open ``path`` for writing (``mode`` "w" for UTF-8 text or "wb") by the module's rule.

    A regular or missing file (through its symbolic links): the handle is a temporary file
    beside it, synced and renamed to it when the block ends without an error, otherwise
    removed with the target untouched. A standard stream, ``/dev/null``, a terminal or a
    FIFO with a reader: the handle writes into it directly, flushed when the block ends.
    Anything else is refused before anything is opened. An OS error inside the block or
    while saving is raised as :class:`WriteError`.
    """
    from pathlib import Path  # here: a command that writes nothing does not load it

    if mode not in ("w", "wb"):
        raise ValueError(f"atomic_open writes with mode 'w' or 'wb', not {mode!r}")
    target = Path(path)
    encoding = None if mode == "wb" else "utf-8"
    direct = _open_direct(target)
    if direct is not None:
        with _direct_write(target, direct, mode, encoding) as handle:
            yield handle
        return
    real = Path(os.path.realpath(target))
    fd, temp = _create_temp(target, real)
    try:
        with os.fdopen(fd, mode, encoding=encoding) as handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        _keep_mode(real, temp)
        _still_a_file(target, real)
        os.replace(temp, real)
    except BaseException as error:
        with contextlib.suppress(OSError):
            os.unlink(temp)
        if isinstance(error, OSError) and not isinstance(error, WriteError):
            raise WriteError(target, error) from None
        raise
    _sync_folder(temp.parent)


def _refused(target: Path, reason: str, code: int = errno.EINVAL) -> WriteError:
    """A :class:`WriteError` of ``target`` saying ``reason`` (one line)."""
    return WriteError(target, OSError(code, reason))


def _kind(st: os.stat_result) -> str:
    """What a file that is not a regular file is, in words (a device with its numbers)."""
    mode = st.st_mode
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        which = "a character" if stat.S_ISCHR(mode) else "a block"
        return f"{which} device ({os.major(st.st_rdev)}:{os.minor(st.st_rdev)})"
    names = {
        stat.S_ISDIR: "a directory",
        stat.S_ISFIFO: "a FIFO",
        stat.S_ISSOCK: "a socket",
        stat.S_ISLNK: "a symbolic link",
    }
    return next((name for test, name in names.items() if test(mode)), "not a regular file")


def _stream_descriptor(target: Path) -> int | None:
    """The descriptor named by ``target`` when it names a standard stream or one of this
    process's descriptors (``/dev/stdout``, ``/dev/fd/N``, ``/proc/self/fd/N``...), itself
    or through the chain of its symbolic links; None otherwise."""
    hop = os.path.abspath(target)
    for _ in range(MAX_LINKS):
        found = _STREAM.fullmatch(hop)
        if found and found["std"]:
            return _STD[found["std"]]
        if found and found["proc"] in (None, "self", "thread-self", str(os.getpid())):
            return int(found["fd"])
        try:
            link = os.readlink(hop)
        except OSError:  # not a link, or missing: no stream
            return None
        hop = os.path.normpath(os.path.join(os.path.dirname(hop), link))
    return None


def _open_direct(target: Path) -> int | None:
    """An open descriptor to write into directly when ``target`` is a stream, the null
    device, a terminal or a FIFO with a reader; None when it is missing or a regular file
    (written atomically). Anything else raises :class:`WriteError` without opening it."""
    number = _stream_descriptor(target)
    if number is not None:
        for stream in (sys.stdout, sys.stderr):  # what was printed comes first
            with contextlib.suppress(AttributeError, OSError, ValueError):
                stream.flush()
        try:
            return os.dup(number)
        except (OSError, OverflowError):
            raise _refused(target, "no such open descriptor", errno.EBADF) from None
    try:
        st = os.stat(target)
    except FileNotFoundError:
        return None
    except OSError as error:
        raise WriteError(target, error) from None
    mode = st.st_mode
    if stat.S_ISREG(mode):
        return None
    device = (os.major(st.st_rdev), os.minor(st.st_rdev))
    terminal = any(m == device[0] and low <= device[1] <= high for m, low, high in TERMINAL_DEVICES)
    if not (stat.S_ISFIFO(mode) or stat.S_ISCHR(mode) and (device == NULL_DEVICE or terminal)):
        raise _refused(target, f"is {_kind(st)}; {ALLOWED}")
    flags = os.O_WRONLY | os.O_NONBLOCK | os.O_NOCTTY | getattr(os, "O_CLOEXEC", 0)
    try:  # without waiting: a FIFO with no reader fails at once (ENXIO)
        fd = os.open(target, flags)
    except OSError as error:
        if stat.S_ISFIFO(mode) and error.errno == errno.ENXIO:
            raise _refused(target, "is a FIFO with no process reading it", errno.ENXIO) from None
        raise WriteError(target, error) from None
    reason = None
    if _identity(os.fstat(fd)) != _identity(st):  # swapped between the stat and the open
        reason = "changed while it was being opened; nothing was written"
    elif terminal and not os.isatty(fd):
        reason = f"is {_kind(st)} that is not a terminal; {ALLOWED}"
    if reason is not None:
        os.close(fd)
        raise _refused(target, reason)
    os.set_blocking(fd, True)
    return fd


def _identity(st: os.stat_result) -> tuple[int, int, int, int]:
    """What makes a file the same file of the same kind: device, inode, type, numbers."""
    return st.st_dev, st.st_ino, stat.S_IFMT(st.st_mode), st.st_rdev


@contextlib.contextmanager
def _direct_write(target: Path, fd: int, mode: str, encoding: str | None) -> Iterator[IO[Any]]:
    """A handle on the open descriptor ``fd``, flushed and closed when the block ends; an
    OS error (the reader went away: EPIPE; a full disk) is a :class:`WriteError`."""
    handle = os.fdopen(fd, mode, encoding=encoding)
    try:
        yield handle
        handle.flush()
    except BaseException as error:
        with contextlib.suppress(OSError):
            handle.close()
        if isinstance(error, OSError) and not isinstance(error, WriteError):
            raise WriteError(target, error) from None
        raise
    try:
        handle.close()
    except OSError as error:
        raise WriteError(target, error) from None


def _still_a_file(target: Path, real: Path) -> None:
    """Refuse to rename over ``real`` when something other than a regular file has appeared
    there while the data was being written (a FIFO, a device, a link)."""
    try:
        st = os.lstat(real)
    except FileNotFoundError:
        return
    if not stat.S_ISREG(st.st_mode):
        raise _refused(target, f"became {_kind(st)} while it was being written; not replaced")


def _create_temp(target: Path, real: Path) -> tuple[int, Path]:
    """A new hidden file beside ``real`` (created with the permissions a plain ``open``
    would give: 0o666 less the umask) and its open descriptor; errors name ``target``."""
    folder = real.parent
    # the name is cut so that the temporary name stays within the 255-byte limit
    stem = "." + real.name[:200] + "."
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        temp = folder / f"{stem}{os.urandom(6).hex()}{TEMP_SUFFIX}"
        try:
            return os.open(temp, flags, 0o666), temp
        except FileExistsError:
            continue
        except OSError as error:
            raise WriteError(target, error) from None
    raise WriteError(target, OSError(errno.EEXIST, "no free temporary file name"))


def _keep_mode(target: Path, temp: Path) -> None:
    """Give the new file the permission bits of the file it replaces, if there is one."""
    try:
        bits = stat.S_IMODE(os.stat(target).st_mode)
    except FileNotFoundError:
        return
    os.chmod(temp, bits)


def _sync_folder(folder: Path) -> None:
    """Sync the folder so that the rename itself survives a power cut (best effort: some
    file systems cannot sync a folder, and the file is already in place)."""
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
