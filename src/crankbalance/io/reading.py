"""Reading what a user gives, with bounds: files and TOML or JSON text.

Every reader of a user file in ``io/`` goes through :func:`read_text`: it refuses what is
not a regular file (a folder, a device such as ``/dev/zero``, a pipe, a socket) before
reading, reads at most a given number of bytes, and refuses binary data; bytes a user
gives otherwise (an upload, an API body) are decoded by the same rule, :func:`decode_text`
(a UTF-8 byte-order mark dropped, binary data refused). TOML and JSON
text goes through :func:`parse_toml` and :func:`parse_json`, which refuse nesting deeper
than :data:`MAX_DEPTH` and numbers longer than :data:`MAX_NUMBER_CHARS` before the parser
sees them (a parser would otherwise recurse without bound or convert a 5000-digit integer),
and, for JSON, a key given twice in one object. Every refusal is one
:class:`~crankbalance.errors.InputError`.
"""

from __future__ import annotations

import os
import re
import stat
import tomllib
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any, NoReturn

from ..errors import InputError

#: Deepest nesting of tables, arrays and dotted keys in a TOML or JSON input; an engine
#: file needs 5 (``masses.override[0].cylinders``).
MAX_DEPTH = 32
#: Longest number (or bare TOML key) in a TOML or JSON input, in characters.
MAX_NUMBER_CHARS = 100

_READ_CHUNK = 1 << 16

#: the files a request gave with its content (:func:`given_files`): name -> text; None
#: outside such a request, where files are read from the file system
_GIVEN: ContextVar[Mapping[str, str] | None] = ContextVar("crankbalance_given_files", default=None)


@contextmanager
def given_files(files: Mapping[str, str]) -> Iterator[None]:
    """Within the block, :func:`read_text` reads the files a request gave with their content
    (``files``: name -> text, the JSON API's ``{"name", "text"}``) and no file of this
    machine: a server reads no path a client names."""
    token = _GIVEN.set(dict(files))
    try:
        yield
    finally:
        _GIVEN.reset(token)


def reading_given_files() -> bool:
    """Whether files are read from a request (:func:`given_files`), not from the disk."""
    return _GIVEN.get() is not None


def read_text(path: str | os.PathLike[str], field: str, what: str, limit: int) -> str:
    """The UTF-8 text of a user file, read with bounds.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    field : str
        How the user named the file (``"engine"``, ``"parts"``, ``"--pressure-csv"``); the
        error names it with the path as its value.
    what : str
        What the file should be, for messages: ``"an engine file (.toml or .json)"``.
    limit : int
        Largest size read [bytes]; a larger file is refused after reading ``limit + 1``
        bytes.

    Returns
    -------
    str
        The text (a UTF-8 byte-order mark dropped).

    Raises
    ------
    InputError
        If the path does not exist or cannot be read, is not a regular file, is larger
        than ``limit`` bytes, or is not UTF-8 text (or contains NUL bytes).
    """
    source = str(path)
    given = _GIVEN.get()
    if given is not None:
        if source not in given:
            raise InputError(
                field,
                source,
                "is not a file given with the request: the API reads no file of the server, "
                'send the file\'s content as {"name": ..., "text": ...}',
            )
        raw = given[source].encode("utf-8")
        if len(raw) > limit:
            raise InputError(field, source, f"is larger than {limit} bytes; give {what}")
        return decode_text(raw, field, source, what)
    try:
        _check_regular(os.stat(path).st_mode, field, source, what)
        # O_NONBLOCK: should the path have turned into a pipe since the stat, the open
        # does not wait for a writer (and fstat below refuses it)
        fd = os.open(
            path,
            os.O_RDONLY
            | getattr(os, "O_NONBLOCK", 0)
            | getattr(os, "O_NOCTTY", 0)
            | getattr(os, "O_BINARY", 0),
        )
        try:
            _check_regular(os.fstat(fd).st_mode, field, source, what)
            raw = b"".join(_chunks(fd, limit + 1))
        finally:
            os.close(fd)
    except OSError as error:
        raise InputError(field, source, f"cannot be read: {error.strerror}") from None
    if len(raw) > limit:
        raise InputError(field, source, f"is larger than {limit} bytes; give {what}")
    return decode_text(raw, field, source, what)


def decode_text(raw: bytes, field: str, value: Any, what: str) -> str:
    """The UTF-8 text of bytes a user gave (a file's content, an upload, an API body).

    The one rule of every reader: a UTF-8 byte-order mark is dropped, anything that is not
    UTF-8 text (or holds NUL bytes) is refused.

    Parameters
    ----------
    raw : bytes
        What was read.
    field : str
        How the user named the input; the error names it.
    value : Any
        The value the error shows (the path of a file).
    what : str
        What the input should be, for messages: ``"an engine file (.toml or .json)"``.

    Returns
    -------
    str
        The text, without a byte-order mark.

    Raises
    ------
    InputError
        If the bytes are not UTF-8 text or contain NUL bytes.
    """
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        _binary(raw, error.start, field, value, what)
    if "\x00" in text:
        _binary(raw, raw.index(b"\x00"), field, value, what)
    return text


def _binary(raw: bytes, at: int, field: str, source: Any, what: str) -> NoReturn:
    """Refuse binary data, naming the line and byte of the first NUL or non-UTF-8 byte."""
    line = raw.count(b"\n", 0, at) + 1
    column = at - (raw.rfind(b"\n", 0, at) + 1) + 1
    raise InputError(
        field,
        source,
        f"must be UTF-8 text, not binary data (byte {raw[at]:#04x} on line {line}, byte "
        f"{column} of the line); give {what}",
    )


def _check_regular(mode: int, field: str, source: str, what: str) -> None:
    if stat.S_ISREG(mode):
        return
    if stat.S_ISDIR(mode):
        kind = "is a folder"
    elif stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        kind = "is a device, not a file"
    elif stat.S_ISFIFO(mode):
        kind = "is a pipe (FIFO), not a file"
    elif stat.S_ISSOCK(mode):
        kind = "is a socket, not a file"
    else:
        kind = "is not a regular file"
    raise InputError(field, source, f"{kind}; give {what}")


def _chunks(fd: int, count: int) -> Iterator[bytes]:
    """At most ``count`` bytes of ``fd``, in chunks, up to the end of the file."""
    while count > 0:
        chunk = os.read(fd, min(count, _READ_CHUNK))
        if not chunk:
            return
        count -= len(chunk)
        yield chunk


def file_format(path: str | os.PathLike[str]) -> str:
    """``"json"`` for a ``.json`` file, else ``"toml"``."""
    suffix = os.path.splitext(os.path.basename(os.fspath(path)))[1]  # no pathlib at start
    return "json" if suffix.lower() == ".json" else "toml"


# --------------------------------------------------------------------------- TOML, JSON
def parse_toml(text: str, field: str, value: Any = None) -> dict[str, Any]:
    """Parse TOML text with bounds; errors name ``field`` (and ``value``, say the path).

    Raises
    ------
    InputError
        If the text nests deeper than :data:`MAX_DEPTH`, holds a number longer than
        :data:`MAX_NUMBER_CHARS` characters, or is not valid TOML.
    """
    _check_text(text, _TOML_TOKENS, field, value)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise InputError(field, value, f"is not valid TOML: {error}") from None
    _check_depth(data, field, value)
    return data


def parse_json(text: str, field: str, value: Any = None) -> Any:
    """Parse JSON text with bounds; errors name ``field`` (and ``value``, say the path).

    Raises
    ------
    InputError
        If the text nests deeper than :data:`MAX_DEPTH`, holds a number longer than
        :data:`MAX_NUMBER_CHARS` characters, gives a key twice in one object, or is not
        valid JSON.
    """
    import json  # here: reading a TOML file does not load it

    _check_text(text, _JSON_TOKENS, field, value)

    def unique(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for key, item in pairs:
            if key in out:
                raise InputError(
                    field, value, f"gives the key {key!r} twice in one object; give it once"
                )
            out[key] = item
        return out

    try:
        data = json.loads(text, object_pairs_hook=unique)
    except json.JSONDecodeError as error:
        raise InputError(
            field,
            value,
            f"is not valid JSON: {error.msg} (line {error.lineno}, column {error.colno})",
        ) from None
    _check_depth(data, field, value)
    return data


# A scan of the text before parsing: strings and comments are skipped, brackets counted,
# bare words (TOML keys, numbers) measured. A dotted TOML key (a.b.c) nests one level per
# dot, and tomllib's work grows with the square of their number. An unterminated string
# runs to the end of its line (or of the text), so that the scan stays linear.
_TOML_PIECE = (
    r"(?:[A-Za-z0-9_+-]++"
    r'|"(?:[^"\\\n]|\\.)*+(?:"|(?=\n)|\Z)'
    r"|'[^'\n]*+(?:'|(?=\n)|\Z))"
)
_TOML_TOKENS = re.compile(
    r'(?P<skip>"""(?:[^"\\]|\\.|"(?!""))*+(?:"""|\Z)'
    r"|'''(?:[^']|'(?!''))*+(?:'''|\Z)"
    r"|#[^\n]*+)"
    rf"|(?P<word>{_TOML_PIECE}(?:[ \t]*+\.[ \t]*+{_TOML_PIECE})*+)"
    r"|(?P<open>[\[{])|(?P<close>[\]}])",
    re.DOTALL,
)
_JSON_TOKENS = re.compile(
    r'(?P<skip>"(?:[^"\\]|\\.)*+(?:"|\Z))'
    r"|(?P<word>[A-Za-z0-9_.+-]++)"
    r"|(?P<open>[\[{])|(?P<close>[\]}])",
    re.DOTALL,
)
_PIECES = re.compile(_TOML_PIECE, re.DOTALL)


def _check_text(text: str, tokens: re.Pattern[str], field: str, value: Any) -> None:
    depth = 0
    for match in tokens.finditer(text):
        kind = match.lastgroup
        if kind == "open":
            depth += 1
            if depth > MAX_DEPTH:
                _too_deep(text, match.start(), field, value)
        elif kind == "close":
            depth = max(depth - 1, 0)
        elif kind == "word":
            word = match.group()
            if len(word) <= MAX_NUMBER_CHARS and "." not in word:
                continue
            if tokens is _JSON_TOKENS:
                bare, dots = [word], 0
            else:
                pieces = _PIECES.findall(word)
                bare = [piece for piece in pieces if piece[0] not in "\"'"]
                dots = len(pieces) - 1
            if any(len(piece) > MAX_NUMBER_CHARS for piece in bare):
                line = text.count("\n", 0, match.start()) + 1
                raise InputError(
                    field,
                    value,
                    f"holds a number or key longer than {MAX_NUMBER_CHARS} characters "
                    f"(line {line})",
                )
            if dots > MAX_DEPTH:
                _too_deep(text, match.start(), field, value)


def _too_deep(text: str, position: int, field: str, value: Any) -> None:
    line = text.count("\n", 0, position) + 1
    raise InputError(field, value, f"nests deeper than {MAX_DEPTH} levels (line {line})")


def _check_depth(data: Any, field: str, value: Any) -> None:
    """Refuse parsed data nested deeper than :data:`MAX_DEPTH` (without recursion)."""
    stack: list[tuple[Any, int]] = [(data, 0)]
    while stack:
        item, depth = stack.pop()
        if depth > MAX_DEPTH:
            raise InputError(field, value, f"nests deeper than {MAX_DEPTH} levels")
        if isinstance(item, dict):
            stack.extend((child, depth + 1) for child in item.values())
        elif isinstance(item, list):
            stack.extend((child, depth + 1) for child in item)
