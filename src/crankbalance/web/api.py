"""A JSON API beside the web pages, on the same server (``crankbalance web``).

* ``GET  /api/presets``: the engine library.
* ``POST /api/analyze``: body an engine file (TOML, or JSON with ``Content-Type:
  application/json``) -> the ``crankbalance.analysis/2`` JSON.
* ``POST /api/balance``: the same -> the ``crankbalance.balance/2`` JSON.

Bad input answers 422 with ``{"error": message, "field": field}``: the same message the
command line prints. Every request is computed on its own; nothing is shared between
requests or users.
"""

from typing import Any

from ..errors import InputError
from ..io.engine_file import list_presets, load_engine, parse_engine_text
from ..studies.engine import analyze, balance_engine

MAX_BODY = 200_000


def compute(kind: str, body: bytes, content_type: str) -> tuple[int, dict[str, Any]]:
    """Status code and JSON answer of one API call (no web framework involved)."""
    try:
        if len(body) > MAX_BODY:
            raise InputError("engine file", f"{len(body)} bytes", f"must be under {MAX_BODY} bytes")
        try:
            text = body.decode("utf-8")
        except UnicodeDecodeError:
            raise InputError("engine file", "binary data", "must be UTF-8 text") from None
        fmt = "json" if "json" in content_type else "toml"
        stripped = text.strip()
        if fmt == "toml" and stripped and "\n" not in stripped and stripped in list_presets():
            spec = load_engine(stripped)  # a preset name as the whole body
        else:
            spec = parse_engine_text(text, "engine file", fmt)
        if kind == "analyze":
            return 200, analyze(spec).to_dict()
        return 200, balance_engine(spec).to_dict()
    except InputError as error:
        return 422, {"error": str(error), "field": error.field}


def register(app: Any) -> None:
    """Add the API routes to the NiceGUI/FastAPI ``app``; the computing runs in worker
    threads so that the pages of other users stay responsive."""
    from fastapi import Request
    from fastapi.responses import JSONResponse
    from starlette.concurrency import run_in_threadpool

    async def answer(kind: str, request: Request) -> JSONResponse:
        body = await request.body()
        status, data = await run_in_threadpool(
            compute, kind, body, request.headers.get("content-type", "")
        )
        return JSONResponse(data, status_code=status)

    @app.get("/api/presets")
    def presets() -> JSONResponse:
        return JSONResponse({"schema": "crankbalance.presets/1", "presets": list_presets()})

    @app.post("/api/analyze")
    async def analyze_route(request: Request) -> JSONResponse:
        return await answer("analyze", request)

    @app.post("/api/balance")
    async def balance_route(request: Request) -> JSONResponse:
        return await answer("balance", request)
