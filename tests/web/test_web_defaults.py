"""No edge decides a default (issue 28): the study settings of the page start at the settings
schema's defaults, the command line's, in chromium: the counterweight optimiser's iterations,
population and seed, and the Crank loads sweep's patterns, balance factors and samples.

Every wait is a wait for a state of the page (the hang guard of ``conftest.py``).
"""

from __future__ import annotations

import pytest

pytest.importorskip("nicegui")
playwright_api = pytest.importorskip("playwright.sync_api")
expect = playwright_api.expect

from crankbalance.schema.core import default_text  # noqa: E402
from crankbalance.schema.settings import (  # noqa: E402
    BearingOptions,
    BearingSweepOptions,
    CounterweightOptions,
)

from .test_web_fresh_browser import current, open_tab  # noqa: E402

#: the page's field -> the schema's field it starts from
OPTIMISER = {
    "setting-cw_iterations": (CounterweightOptions, "iterations"),
    "setting-cw_population": (CounterweightOptions, "population"),
    "setting-cw_seed": (CounterweightOptions, "seed"),
}
LOADS = {
    "loads-balance_factors": (BearingSweepOptions, "balance_factors"),
    "loads-samples": (BearingOptions, "samples"),
}


def test_study_settings_start_at_the_schema_s_defaults(server: str, page) -> None:
    """The optimiser starts at 40 iterations, a population of 4096 and no seed, the loads
    sweep at the pattern ``all``, the balance factors 0 to 1 by 0.25 and 360 samples, as
    ``crankbalance counterweight optimize`` and ``crankbalance bearings-sweep`` do."""
    page.goto(server + "/?preset=inline4")
    current(page)
    open_tab(page, "Counterweight design")
    for testid, (model, name) in OPTIMISER.items():
        field = page.locator(f"[data-testid={testid}]").first
        expect(field).to_have_value(default_text(model.FIELDS[name]))
    expect(page.locator("[data-testid=setting-cw_population]").first).to_have_value("4096")
    open_tab(page, "Crank loads")
    for testid, (model, name) in LOADS.items():
        field = page.locator(f"[data-testid={testid}]").first
        expect(field).to_have_value(default_text(model.FIELDS[name]))
    expect(page.locator("[data-testid=loads-patterns]").first).to_have_value("all")
    expect(page.locator("[data-testid=loads-samples]").first).to_have_value("360")
