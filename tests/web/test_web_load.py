"""Load test (issue 8): 20 concurrent sessions, each computing 20 engines against one local
server, without an error, and each session getting its own engine's numbers back.

Each session opens the web page (its own NiceGUI client and project), then posts 20
different engines to the JSON API of the same server (``/api/balance``) over its own
connection. Every answer is compared with the in-process API for that very engine, so a
result that leaked from another session would fail. ``benchmarks/bench_web_load.py``
reports the p95 response time of the same load.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import pytest

from crankbalance.io.engine_file import parse_engine_text
from crankbalance.studies.engine import balance_engine

from .loadgen import engine_text, run_session

pytest.importorskip("nicegui")

SESSIONS, ENGINES = 20, 20


def test_20_sessions_of_20_engines(server: str) -> None:
    with ThreadPoolExecutor(SESSIONS) as pool:
        results = list(pool.map(lambda s: run_session(server, s, ENGINES), range(SESSIONS)))
    errors = [e for r in results for e in r.errors]
    assert not errors, errors[:5]
    for session, result in enumerate(results):
        assert len(result.answers) == ENGINES
        for k, answer in enumerate(result.answers):
            expected = balance_engine(parse_engine_text(engine_text(session, k))).to_dict()
            assert answer["engine"] == expected["engine"]
            assert answer["counterweight"]["mass_kg"] == pytest.approx(
                expected["counterweight"]["mass_kg"], rel=1e-12
            )
            assert answer["residual"] == expected["residual"]
