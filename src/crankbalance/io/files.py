"""Writing files safely: atomically, so that a failed save never destroys what the user had.

Every file crankbalance writes goes through this module (a test scans the package for
direct writes). A write goes to a hidden temporary file in the destination folder,
``.NAME.<12 hex digits>.tmp``, which is flushed, synced to the disk and then renamed over
``NAME`` in one step: the file is always either wholly the old content or wholly the new.
Any error (a full disk, permissions, an exception of the code writing) removes the
temporary file, leaves ``NAME`` untouched and raises :class:`WriteError`. Only a process
killed outright (``kill -9``, a power cut) can leave a temporary file behind, and it is
hidden and named after its target; the target itself is intact.

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
import secrets
import stat
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

#: the end of every temporary file name (``.NAME.<12 hex digits>.tmp``)
TEMP_SUFFIX = ".tmp"


class WriteError(OSError):
    """A file could not be written (disk full, permissions, a missing folder...); the
    previous file, if any, is intact. ``str()`` is one line: ``cannot write FILE: reason``.
    """

    def __init__(self, path: str | os.PathLike[str], error: OSError) -> None:
        reason = error.strerror or str(error) or type(error).__name__
        super().__init__(error.errno, reason, os.fspath(path))

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror}"


def write_atomic(path: str | os.PathLike[str], data: str | bytes) -> None:
    """Write ``data`` to ``path`` so that the file is either wholly the new content or
    untouched (text is written as UTF-8). Raises :class:`WriteError`."""
    with atomic_open(path, "wb" if isinstance(data, bytes) else "w") as handle:
        handle.write(data)


@contextlib.contextmanager
def atomic_open(path: str | os.PathLike[str], mode: str = "w") -> Iterator[IO[Any]]:
    """Open a temporary file beside ``path`` for writing (``mode`` "w" for UTF-8 text or
    "wb"); when the block ends without an error the file is synced and renamed to ``path``,
    otherwise it is removed and ``path`` is untouched. An OS error inside the block or while
    saving is raised as :class:`WriteError`."""
    if mode not in ("w", "wb"):
        raise ValueError(f"atomic_open writes with mode 'w' or 'wb', not {mode!r}")
    target = Path(path)
    fd, temp = _create_temp(target)
    try:
        encoding = None if mode == "wb" else "utf-8"
        with os.fdopen(fd, mode, encoding=encoding) as handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        _keep_mode(target, temp)
        os.replace(temp, target)
    except BaseException as error:
        with contextlib.suppress(OSError):
            os.unlink(temp)
        if isinstance(error, OSError) and not isinstance(error, WriteError):
            raise WriteError(target, error) from None
        raise
    _sync_folder(temp.parent)


def _create_temp(target: Path) -> tuple[int, Path]:
    """A new hidden file beside ``target`` (created with the permissions a plain ``open``
    would give: 0o666 less the umask) and its open descriptor."""
    folder = target.parent
    # the name is cut so that the temporary name stays within the 255-byte limit
    stem = "." + target.name[:200] + "."
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        temp = folder / f"{stem}{secrets.token_hex(6)}{TEMP_SUFFIX}"
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
