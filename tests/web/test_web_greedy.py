"""Issue 25: one user's largest study does not stall the others. ``crankbalance web`` in a
subprocess, the page in Debian's chromium: the counterweight optimiser with the largest
settings its form allows (population 100 000, 219 iterations: 997 024 designs, just under
the budget) runs in a worker process while another client's ``GET /api/presets`` is
answered; the study is still running when that answer has arrived (no timing is asserted:
``benchmarks/bench_web_greedy.py`` measures the latency). Its Cancel button ends it.
Every wait is for a state of the page, with the hang guard of ``conftest.py``.
"""

from __future__ import annotations

import json
import urllib.request
from typing import Any

import pytest

from crankbalance.schema.settings import MAX_COUNTERWEIGHT_DESIGNS, counterweight_designs
from crankbalance.web.widgets import CANCELLED

from .conftest import HANG_GUARD

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

#: the largest optimisation the form allows with its largest population
LARGEST = (219, 100_000)


def _start_the_largest_optimiser(page: Any, server: str) -> tuple[Any, Any]:
    """Open the Counterweight tab, type the largest settings, click Optimise; (its progress
    line, its Cancel button) once the study holds a worker."""
    iterations, population = LARGEST
    assert counterweight_designs(population, iterations) <= MAX_COUNTERWEIGHT_DESIGNS
    assert counterweight_designs(population, iterations + 1) > MAX_COUNTERWEIGHT_DESIGNS
    page.goto(f"{server}/?preset=paper-inline3")
    expect(page.locator(".q-header")).to_contain_text("Results of:")
    page.get_by_role("tab", name="Counterweight design").click()
    for key, value in (("cw_iterations", iterations), ("cw_population", population)):
        field = page.locator(f"[data-testid=setting-{key}]").first
        field.fill(str(value))
        expect(field).to_have_value(str(value))
    page.get_by_role("button", name="Optimise").click()
    summary = page.locator("[data-testid=cw-progress]", has_text="optimising").first
    cancel = page.locator("[data-testid=counterweight-cancel]").first
    expect(cancel).to_be_visible()  # the study is running in its worker
    return summary, cancel


def test_other_users_answered_while_the_largest_optimiser_runs(server: str, page: Any) -> None:
    summary, cancel = _start_the_largest_optimiser(page, server)
    with urllib.request.urlopen(server + "/api/presets", timeout=HANG_GUARD) as response:
        answer = json.loads(response.read())
    assert response.status == 200 and "paper-inline3" in [p["name"] for p in answer["presets"]]
    # the answer came while the study was still running
    assert cancel.is_visible() and "optimising" in summary.inner_text()
    # and the largest study the form allows finishes
    done = page.locator(".q-tab-panel:visible .nicegui-markdown", has_text="feasible designs")
    expect(done.first).to_contain_text("evaluated in")
    expect(cancel).to_be_hidden()


def test_cancel_ends_the_largest_optimiser(server: str, page: Any) -> None:
    summary, cancel = _start_the_largest_optimiser(page, server)
    cancel.click()
    panel = page.locator(".q-tab-panel:visible").first
    expect(panel).to_contain_text(CANCELLED)
    expect(cancel).to_be_hidden()
    # the page's next study runs (the cancelled one freed its worker)
    page.locator("[data-testid=setting-cw_iterations]").first.fill("2")
    page.get_by_role("button", name="Optimise").click()
    expect(panel).to_contain_text("feasible designs")
