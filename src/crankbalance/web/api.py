"""A JSON API beside the web pages, on the same server (``crankbalance web``).

* ``GET  /api/presets``: the engine library.
* ``POST /api/<study>``: every study of :mod:`crankbalance.studies.registry` (``analyze``,
  ``balance-factor``, ``shop-match``, ...): the body ``{"engine": <preset name or engine-file
  object>, "<option>": value, ...}`` with the command line's option names without their
  dashes and values as the command line takes them (texts, JSON numbers, ``true`` for a
  flag, a list for a repeated option), a file option's content as ``{"name": ..., "text":
  ...}``; the answer is the command's ``--format json``, exactly.
* ``POST /api/analyze`` and ``POST /api/balance`` also take an engine file as the whole body
  (JSON, TOML, or a preset name as TOML), answered as ``analyze``/``balance`` of it.

What a request must be (``docs/web.md``, "JSON API"), checked in this order:

* **From this machine, not from a foreign page** (403): the ``Host`` is a loopback name
  (``127.0.0.1``, ``localhost``, ``[::1]``; a DNS-rebinding page has its own name there),
  and a browser's ``Origin`` (without one: ``Sec-Fetch-Site``, then ``Referer``) is this
  server. Clients that send none of these headers (curl, urllib, scripts) are served.
* **Content-Type** ``application/json`` (a study's settings, or a JSON engine file) or, for
  ``analyze`` and ``balance``, ``application/toml`` (a TOML engine file, or a preset name as
  the whole body); anything else is 415. A form or ``text/plain`` body, which a foreign page
  could send without asking the browser first, never reaches the parser.
* **At most** :data:`MAX_BODY` bytes (413): refused from ``Content-Length`` before the body
  is read, and while it is read when the length is not given.
* **Bounded work** (422): the engine's work units, (cylinders + throws) x orders, are at most
  :data:`MAX_WORK` before computing starts, and every study checks its own work budget
  before it starts (the optimiser's designs, a sweep's cases, the explorer's candidates);
  a computation still running after :data:`WALL_CLOCK` seconds is answered 503 (a study in
  a worker process is then ended; one in a thread finishes its work).
* **Nothing of the server's machine**: a file is sent with the request, never named by a
  path the server would read (:func:`crankbalance.io.reading.given_files`), and the
  settings that act on the computing machine (the explorer's dask workers and scheduler)
  are refused.

A client that closes the connection before its whole body arrived leaves one warning line in
the server's log (no traceback) and nothing is computed; one that stops sending in the middle
of its body is answered 408 after :data:`BODY_TIMEOUT` seconds.

Bad input answers 422 with ``{"error": message, "field": field}``, the message the command
line prints (naming the option without its dashes); a refused request answers its 4xx status
with the same two keys. 500 is left for a bug of crankbalance (logged with its traceback).
A light study is computed in a worker thread, a heavy one (:attr:`crankbalance.studies.
registry.Study.heavy`) in a worker process of :mod:`.pool`, so other users are answered
meanwhile; nothing is shared between requests.
"""

import asyncio
import json
import logging
from collections.abc import Mapping
from typing import Any
from urllib.parse import urlsplit

from ..errors import InputError
from ..io.engine_file import list_presets, load_engine
from ..schema.engine import EngineSpec
from ..studies.engine import analyze, balance_engine
from ..studies.registry import STUDIES, Study, study
from . import studies
from .project import MAX_BYTES, parse_untrusted, read_text

log = logging.getLogger("crankbalance.web")

MAX_BODY = MAX_BYTES
#: Content-Type (media type, parameters ignored) -> engine-file format of the body
CONTENT_TYPES = {"application/json": "json", "application/toml": "toml"}
#: host names of this machine; the server binds 127.0.0.1 only
LOOPBACK = ("127.0.0.1", "localhost", "::1")
#: harmonic orders of the answers (the command line's default)
ORDERS = 8
#: largest (cylinders + throws) x orders computed: a second line behind the engine file's
#: caps (64 cylinders on 64 throws at 8 orders is 1024)
MAX_WORK = 4096
#: seconds after which a computation is answered 503 (work within MAX_WORK takes well
#: under a second; this is the guard for what the budget does not foresee)
WALL_CLOCK = 120.0
#: seconds the whole body may take to arrive once the headers are in: a client that stops
#: sending in the middle of its body is answered 408 and its connection closed (a body of
#: at most MAX_BODY bytes from this machine arrives in milliseconds; without the limit a
#: client stopping mid-body held its connection open without end)
BODY_TIMEOUT = 10.0


class Refused(InputError):
    """A request answered with the 4xx ``status`` before anything is computed."""

    def __init__(self, status: int, field: str, value: Any, allowed: str) -> None:
        super().__init__(field, value, allowed)
        self.status = status


def error_body(error: InputError) -> dict[str, Any]:
    """The JSON answer of a refused request or of bad input."""
    return {"error": str(error), "field": error.field}


def body_format(content_type: str | None) -> str:
    """The engine-file format ("json" or "toml") of a Content-Type; 415 for any other."""
    media = (content_type or "").split(";")[0].strip().lower()
    if media not in CONTENT_TYPES:
        raise Refused(
            415,
            "Content-Type",
            content_type,
            "must be application/json (a JSON engine file) or application/toml (a TOML engine "
            "file or a preset name)",
        )
    return CONTENT_TYPES[media]


def _netloc(url: str) -> str:
    try:
        return urlsplit(url).netloc.lower()
    except ValueError:  # e.g. an unclosed "[" of an IPv6 address
        return ""


def check_request(headers: Mapping[str, str]) -> str:
    """Refuse a foreign or malformed request from its headers alone (403, 415, 413, 400),
    before its body is read; return the body's format."""
    host = headers.get("host", "")
    try:
        hostname = urlsplit("//" + host).hostname
    except ValueError:
        hostname = None
    if hostname not in LOOPBACK:
        raise Refused(
            403, "Host", host, "must be this machine (127.0.0.1, localhost or [::1]:port)"
        )
    own = host.lower()
    foreign = "a page of another site cannot use the API"
    origin = headers.get("origin")
    if origin is not None:
        if _netloc(origin) != own:
            raise Refused(403, "Origin", origin, f"must be this server, http://{host}; {foreign}")
    elif headers.get("sec-fetch-site", "same-origin") not in ("same-origin", "none"):
        site = headers["sec-fetch-site"]
        raise Refused(403, "Sec-Fetch-Site", site, f"must be same-origin; {foreign}")
    elif "referer" in headers and _netloc(headers["referer"]) != own:
        raise Refused(403, "Referer", headers["referer"], f"must be this server; {foreign}")
    fmt = body_format(headers.get("content-type"))
    length = headers.get("content-length")
    if length is not None:
        if not (length.isascii() and length.isdigit() and len(length) < 20):
            raise Refused(400, "Content-Length", length, "must be a whole number of bytes")
        _check_size(int(length))
    return fmt


def _check_size(size: int) -> None:
    if size > MAX_BODY:
        raise Refused(
            413,
            "request body",
            f"{size} bytes",
            f"must be at most {MAX_BODY} bytes; an engine file is a few kB of TOML or JSON",
        )


def check_work(spec: EngineSpec, orders: int = ORDERS) -> None:
    """Refuse (422) an engine whose work units, (cylinders + throws) x orders, exceed
    :data:`MAX_WORK`, before any computing."""
    train = spec.crank_train
    cylinders = train.cylinder_count
    throws = train.throw_total
    work = (cylinders + throws) * orders
    if work > MAX_WORK:
        raise InputError(
            "crank_train",
            f"{cylinders} cylinders on {throws} throws",
            f"(cylinders + throws) x {orders} orders = {work} is over the API's work budget "
            f"of {MAX_WORK}",
        )


#: what a file option of a request is: its name (a file's suffix says its format) and text
FILE_WORDS = 'the file\'s content as {"name": "parts.csv", "text": "..."}'
#: longest name of a file sent with a request [characters]
MAX_FILE_NAME = 255


def _body_object(body: bytes, content_type: str | None, name: str) -> dict[str, Any]:
    """The JSON object of a study's request body (415, 413 or 422 for anything else)."""
    from ..io.reading import parse_json

    fmt = body_format(content_type)
    _check_size(len(body))
    if fmt != "json":
        raise Refused(
            415,
            "Content-Type",
            content_type,
            f"must be application/json: the settings of {name} are a JSON object",
        )
    data = parse_json(read_text(body, "request body"), "request body")
    if not isinstance(data, dict):
        raise InputError(
            "request body",
            type(data).__name__,
            'must be a JSON object: {"engine": ..., "<option>": value, ...}',
        )
    return data


def is_study_body(body: bytes, content_type: str | None) -> bool:
    """Whether a body of ``analyze`` or ``balance`` is a study's settings (a JSON object with
    an ``engine`` key; an engine file has none) rather than an engine file."""
    media = (content_type or "").split(";")[0].strip().lower()
    if media != "application/json" or len(body) > MAX_BODY:
        return False
    try:
        data = json.loads(body.decode("utf-8-sig"))
    except (ValueError, RecursionError):
        return False
    return isinstance(data, dict) and "engine" in data


def _engine(entry: Study, value: Any) -> tuple[Any, EngineSpec | None]:
    """The engine of a request as the study takes it (a preset name as given, or the spec
    of an engine-file object) and its spec, for the work budget."""
    if value is None:
        if entry.engine == "required":
            raise InputError("engine", None, "the engine file or preset is needed")
        return None, None
    if entry.engine == "none":
        raise InputError("engine", value, f"{entry.name} takes no engine")
    if isinstance(value, str):
        if value not in list_presets():
            raise InputError(
                "engine",
                value,
                "must be a preset name (GET /api/presets) or an engine file as a JSON object; "
                "the API reads no file of the server",
            )
        return value, load_engine(value)
    if isinstance(value, dict):
        spec = parse_untrusted(json.dumps(value), "engine", "json")
        return spec, spec
    raise InputError(
        "engine", type(value).__name__, "must be a preset name or an engine file as a JSON object"
    )


def _files(option: str, value: Any, files: dict[str, str]) -> Any:
    """The file names of a file option (``{"name", "text"}``, or a list of them for a
    repeated one); their texts go into ``files``."""
    if isinstance(value, list):
        return [_files(option, item, files) for item in value]
    if not (
        isinstance(value, dict)
        and set(value) == {"name", "text"}
        and isinstance(value["name"], str)
        and isinstance(value["text"], str)
    ):
        raise InputError(option, value, f"must be {FILE_WORDS}")
    name, text = value["name"], value["text"]
    if not name.strip() or len(name) > MAX_FILE_NAME or any(c in name for c in "\x00\n\r"):
        raise InputError(
            option, name, f"must be a file name of 1 to {MAX_FILE_NAME} characters on one line"
        )
    if files.get(name, text) != text:
        raise InputError(option, name, "is given twice with different texts")
    files[name] = text
    return name


def prepare(
    name: str, body: bytes, content_type: str | None
) -> tuple[str, Any, dict[str, Any], dict[str, str]]:
    """A study's request before anything is computed: (study, engine, settings as given by
    field, files given), with the settings checked (422 naming the option) and the engine's
    work units within :data:`MAX_WORK`."""
    entry = study(name)
    data = _body_object(body, content_type, name)
    engine, spec = _engine(entry, data.pop("engine", None))
    values: dict[str, Any] = {}
    files: dict[str, str] = {}
    for option, value in data.items():
        field = entry.field_of(option)
        if field is None:
            words = [entry.option(n) for n in entry.field_names() if n not in entry.local]
            if option in entry.edge:
                why = "is an option of the command line (its output), not of the API"
            elif option in {entry.option(n) for n in entry.local}:
                why = "acts on the machine that computes: the API does not take it"
            else:
                why = "is not an option of " + name
            raise InputError(option, value, f"{why}; its options: engine, {', '.join(words)}")
        if field in entry.local:
            raise InputError(
                option, value, "acts on the machine that computes: the API does not take it"
            )
        values[field] = _files(option, value, files) if field in entry.files else value
    settings = parse(entry, values)
    if spec is not None:
        check_work(spec, getattr(settings, "orders", ORDERS) if name == "analyze" else ORDERS)
    return name, engine, values, files


def parse(entry: Study, values: dict[str, Any]) -> Any:
    """The settings of a request, each error naming the option as the body writes it."""
    from ..studies.registry import parse as parse_settings

    return parse_settings(entry, values)


def compute_study(name: str, body: bytes, content_type: str | None) -> tuple[int, dict[str, Any]]:
    """Status code and JSON answer of one study's request, computed in this process (no web
    framework involved): the handler of ``POST /api/<study>`` without its worker."""
    try:
        prepared = prepare(name, body, content_type)
    except Refused as refused:
        return refused.status, error_body(refused)
    except InputError as error:
        return 422, error_body(error)
    return studies.api_answer(*prepared)


def compute(kind: str, body: bytes, content_type: str | None) -> tuple[int, dict[str, Any]]:
    """Status code and JSON answer of one API call (no web framework involved): 415 or 413
    for a body of another type or too large, 422 for bad input, 200 with finite numbers. A
    body of study settings (:func:`is_study_body`) is answered by :func:`compute_study`."""
    if is_study_body(body, content_type):
        return compute_study(kind, body, content_type)
    try:
        fmt = body_format(content_type)
        _check_size(len(body))
        text = read_text(body, "engine file")
        stripped = text.strip()
        if fmt == "toml" and stripped and "\n" not in stripped and stripped in list_presets():
            spec = load_engine(stripped)  # a preset name as the whole body
        else:
            spec = parse_untrusted(text, "engine file", fmt)
        check_work(spec)
        result = (analyze if kind == "analyze" else balance_engine)(spec, orders=ORDERS)
    except Refused as refused:
        return refused.status, error_body(refused)
    except InputError as error:
        return 422, error_body(error)
    except Exception as error:  # a bug of crankbalance: logged in full, answered 500
        log.exception("POST /api/%s failed", kind)
        message = f"internal error ({type(error).__name__}); please report it with the body"
        return 500, {"error": message, "field": None}
    try:
        return 200, result.to_dict()
    except ValueError as error:  # to_jsonable refuses NaN and infinities
        problem = f"gives a result that is not finite ({error}); check its values"
        return 422, error_body(InputError("engine file", None, problem))


class Disconnected(Refused):
    """The client closed the connection before its whole body arrived (no one reads the
    answer; the server logs one line, :func:`register`)."""


async def read_body(request: Any) -> bytes:
    """The request's body, refused (413) as soon as it grows over :data:`MAX_BODY`, and
    (408) when it has not all arrived within :data:`BODY_TIMEOUT` seconds;
    :class:`Disconnected` when the client closes the connection before sending it all."""
    from starlette.requests import ClientDisconnect

    chunks: list[bytes] = []
    size = 0
    length = request.headers.get("content-length")
    try:
        async with asyncio.timeout(BODY_TIMEOUT):
            async for chunk in request.stream():
                size += len(chunk)
                _check_size(size)
                chunks.append(chunk)
    except ClientDisconnect:
        raise Disconnected(
            400,
            "request body",
            f"{size} of {length} bytes received" if length else f"{size} bytes received",
            "the client closed the connection before the whole body arrived; nothing computed",
        ) from None
    except TimeoutError:
        raise Refused(
            408,
            "request body",
            f"{size} of {length} bytes received" if length else f"{size} bytes received",
            f"the whole body must arrive within {BODY_TIMEOUT:g} s; nothing computed",
        ) from None
    return b"".join(chunks)


def register(app: Any) -> None:
    """Add the API routes to the NiceGUI/FastAPI ``app``; the computing runs in worker
    threads so that the pages of other users stay responsive."""
    from fastapi import Request
    from fastapi.responses import JSONResponse
    from starlette.concurrency import run_in_threadpool

    async def answer(kind: str, request: Request) -> JSONResponse:
        try:
            check_request(request.headers)
            body = await read_body(request)
        except Refused as refused:
            if isinstance(refused, Disconnected):  # one line in the log, no traceback
                log.warning("POST /api/%s: %s", kind, refused)
            return JSONResponse(error_body(refused), status_code=refused.status)
        content_type = request.headers.get("content-type")
        if is_study_body(body, content_type) or kind not in ("analyze", "balance"):
            status, data = await answer_study(kind, body, content_type)
            return JSONResponse(data, status_code=status)
        work = run_in_threadpool(compute, kind, body, content_type)
        try:
            status, data = await asyncio.wait_for(work, WALL_CLOCK)
        except TimeoutError:
            log.warning("POST /api/%s still computing after %g s: answered 503", kind, WALL_CLOCK)
            status = 503
            data = {"error": f"the computation took longer than {WALL_CLOCK:g} s", "field": None}
        return JSONResponse(data, status_code=status)

    @app.get("/api/presets")
    def presets() -> JSONResponse:
        from ..studies.engine import presets_listing

        return JSONResponse(presets_listing())

    def route(kind: str) -> Any:
        async def handler(request: Request) -> JSONResponse:
            return await answer(kind, request)

        handler.__name__ = f"study_{kind.replace('-', '_')}"
        return handler

    for name in STUDIES:
        app.post(f"/api/{name}")(route(name))


async def answer_study(name: str, body: bytes, content_type: str | None) -> tuple[int, Any]:
    """The answer of a study's request: checked in a worker thread (:func:`prepare`), then
    computed in a worker process of :mod:`.pool` for a heavy study, in a worker thread for
    another; after :data:`WALL_CLOCK` seconds 503 (the worker process is ended)."""
    from starlette.concurrency import run_in_threadpool

    from . import pool

    try:
        prepared = await run_in_threadpool(prepare, name, body, content_type)
    except Refused as refused:
        return refused.status, error_body(refused)
    except InputError as error:
        return 422, error_body(error)
    too_long = {"error": f"the computation took longer than {WALL_CLOCK:g} s", "field": None}
    if not STUDIES[name].heavy:
        work = run_in_threadpool(studies.api_answer, *prepared)
        try:
            return await asyncio.wait_for(work, WALL_CLOCK)
        except TimeoutError:
            log.warning("POST /api/%s still computing after %g s: answered 503", name, WALL_CLOCK)
            return 503, too_long
    job = pool.Job(f"the study {name}")
    try:
        answer: tuple[int, Any] = await asyncio.wait_for(
            pool.run(job, studies.api_answer, *prepared), WALL_CLOCK
        )
        return answer
    except TimeoutError:
        job.cancel()
        log.warning("POST /api/%s still computing after %g s: ended, 503", name, WALL_CLOCK)
        return 503, too_long
    except pool.Busy as busy:
        return 503, error_body(busy)
    except pool.Cancelled:
        return 503, {"error": "the study was cancelled", "field": None}
    except InputError as error:  # the worker ended without an answer (out of memory)
        return 422, error_body(error)
