"""Issue 25, the web studies: a work budget checked before a study starts (the command
line's words beside the field), studies in bounded worker processes that a Cancel button or
the page going away ends, and the server answering other users while one runs.

The worker pool is tested on its own (:mod:`crankbalance.web.pool`, with ``time.sleep`` or
``os.nice`` as the work), the tabs with NiceGUI's simulated user; the starvation test in
``test_web_greedy.py`` drives a real server with chromium. Every wait is for a state (a
process running, a message shown), never a sleep.
"""

from __future__ import annotations

import asyncio
import base64
import os
import re
import signal
import time
from collections.abc import Iterator
from typing import Any

import pytest
from nicegui.testing.user import User

from crankbalance.cli import main as cli
from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.schema.engine import spec_from_dict
from crankbalance.schema.settings import (
    COUNTERWEIGHT_CHILDREN,
    MAX_COUNTERWEIGHT_DESIGNS,
    MAX_SWEEP_WORK,
    CounterweightOptions,
)
from crankbalance.web import pool, studies
from crankbalance.web.widgets import CANCELLED

from .conftest import Form, until

pytestmark = pytest.mark.anyio
#: the optimiser's settings over the budget: the tester's 200 x 20 000 at 300 iterations
OVER = {"cw_iterations": "300", "cw_population": "20000"}
#: the largest optimisation the budget allows with the smallest population (999 440 designs)
LARGEST = {"cw_iterations": "244", "cw_population": "16"}


def settings(**typed: str) -> dict[str, str]:
    """A page's study settings (the defaults of a new project) with ``typed`` edited."""
    from crankbalance.web.project import Project

    return {**Project.from_preset("paper-inline3").settings, **typed}


@pytest.fixture
def jobs(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[pool.Job]]:
    """Every :class:`~crankbalance.web.pool.Job` a tab starts, in order; any still running
    at the end of the test is cancelled."""
    started: list[pool.Job] = []

    class Recorded(pool.Job):
        def __init__(self, what: str, owner: str = "") -> None:
            super().__init__(what, owner)
            started.append(self)

    monkeypatch.setattr(pool, "Job", Recorded)
    yield started
    for job in started:
        job.cancel()


# --------------------------------------------------------------------------- the budgets
def test_the_optimiser_default_breeds_the_budget_s_designs_per_round() -> None:
    """The budget counts the optimiser's own number of designs per round (its default,
    which the command line uses and the web passes)."""
    import inspect

    from crankbalance.physics.counterweight_optimize import optimize_counterweight

    default = inspect.signature(optimize_counterweight).parameters["children"].default
    assert default == COUNTERWEIGHT_CHILDREN


def test_the_optimiser_over_budget_in_the_command_line_s_words(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """One rule: the settings model refuses it for the CLI and the web alike."""
    with pytest.raises(InputError) as raised:
        studies.options(settings(**OVER), CounterweightOptions)
    assert raised.value.field == "cw_iterations"
    assert f"at most {MAX_COUNTERWEIGHT_DESIGNS:,} designs" in raised.value.allowed
    assert "20,000 + 300 x 4096 = 1,248,800" in raised.value.allowed
    code = 0
    try:
        cli(
            [
                "counterweight",
                "optimize",
                "--first-moment",
                "7880 g*mm",
                "--iterations",
                "300",
                "--population",
                "20000",
                "--quiet",
            ]
        )
    except SystemExit as exit_:
        code = int(exit_.code or 0)
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.strip() == f"error: --iterations = '300': {raised.value.allowed}"
    # the largest allowed is allowed
    studies.options(settings(**LARGEST), CounterweightOptions)


async def test_optimiser_over_budget_refused_beside_the_field(
    user: User, form: Form, jobs: list[pool.Job]
) -> None:
    await user.open("/")
    await form.see("Results of:")
    form.open("counterweight")
    for key, value in OVER.items():
        form.set(f"setting-{key}", value)
    message = form.error("setting-cw_iterations") or ""
    assert message.startswith("Iterations: '300' must keep population + iterations x 4096")
    assert "1,248,800" in message
    user.find(marker="optimise").click()
    await form.until(lambda: "1,248,800" in form.text("cw-summary"), "the refusal")
    assert jobs == [], "a study over the budget must not start"


def test_bearing_sweep_over_budget_refused_before_the_first_case() -> None:
    """A 64-cylinder engine at 22 cases of 3600 samples is 5.1 million: refused, naming the
    samples, before any case is computed (the Crank loads tab shows it beside the field)."""
    from crankbalance.studies.balance_loads import bearing_sweep

    spec = _engine_64()
    calls: list[Any] = []
    sweep = {"patterns": ["all", "none"], "balance_factors": [0.05 * k for k in range(21)]}
    with pytest.raises(InputError) as raised:
        bearing_sweep(spec, sweep, {"samples": 3600}, progress=lambda *a: calls.append(a))
    assert raised.value.field == "samples" and raised.value.value == 3600
    assert f"at most {MAX_SWEEP_WORK:,}" in raised.value.allowed
    assert "(here 22 x 3600 x 64 = 5,068,800)" in raised.value.allowed
    assert calls == []


def _engine_64() -> Any:
    """The inline-4 preset with 64 cylinders (the engine file's most)."""
    data = load_engine("inline4").to_data()
    data["crank_train"] = {**data["crank_train"], "cylinders": 64}
    data["crank_train"].pop("firing_order", None)
    return spec_from_dict(data)


async def test_crank_loads_over_budget_refused_beside_samples(
    user: User, form: Form, jobs: list[pool.Job]
) -> None:
    """The Crank loads tab checks the sweep's budget with the page's engine before its
    worker starts: 64 cylinders x 22 cases x 3600 samples, refused beside the samples."""
    from nicegui.elements.upload_files import SmallFileUpload

    from crankbalance.io.engine_file import engine_to_toml

    await user.open("/")
    await form.see("Results of:")
    text = engine_to_toml(_engine_64()).encode()
    with user:
        await form.element("upload").handle_uploads(
            [SmallFileUpload("inline64.toml", "text/plain", text)]
        )
    await form.until(lambda: form.element("field-cylinders").value == "64", "the upload")
    form.open("loads")
    form.set("loads-patterns", "all; none")
    form.set("loads-balance_factors", ", ".join(f"{0.05 * k:.2f}" for k in range(21)))
    form.set("loads-samples", "3600")
    user.find(marker="loads-run").click()
    await form.until(lambda: form.element("loads-samples").error, "the refusal")
    message = form.element("loads-samples").error
    assert message.startswith("Samples per revolution = 3600: must keep cases x samples")
    assert "(here 22 x 3600 x 64 = 5,068,800)" in message
    assert jobs == [], "a sweep over the budget must not start"


# --------------------------------------------------------------------------- the pool
async def test_cancel_kills_the_worker() -> None:
    job = pool.Job("a sleep")
    task = asyncio.ensure_future(pool.run(job, time.sleep, 600))
    await until(lambda: job.running, "the worker to start")
    job.cancel()
    with pytest.raises(pool.Cancelled):
        await task
    assert job.process.exitcode == -signal.SIGKILL  # the work stopped, not just its result


async def test_a_worker_runs_second_to_the_server() -> None:
    niceness = await pool.run(pool.Job("nice"), os.nice, 0)
    assert niceness == min(os.nice(0) + pool.NICE, 19)


async def test_a_worker_s_memory_is_capped() -> None:
    with pytest.raises(InputError) as raised:
        await pool.run(pool.Job("a large allocation"), bytearray, pool.MEMORY_LIMIT)
    assert "needs more memory than a worker has" in raised.value.allowed


async def test_a_study_s_input_error_comes_back_as_it_was() -> None:
    with pytest.raises(InputError) as raised:
        await pool.run(pool.Job("options"), studies.options, settings(**OVER), CounterweightOptions)
    assert raised.value.field == "cw_iterations" and raised.value.value == "300"


async def test_bounded_workers_and_queue(monkeypatch: pytest.MonkeyPatch) -> None:
    """One worker, one waiting: a third study is refused in one line; a waiting study that
    is cancelled never starts; the running one is unaffected until cancelled."""
    monkeypatch.setattr(pool, "WORKERS", 1)
    monkeypatch.setattr(pool, "MAX_WAITING", 1)
    first, second = pool.Job("first"), pool.Job("second")
    running = asyncio.ensure_future(pool.run(first, time.sleep, 600))
    await until(lambda: first.running, "the first worker")
    waiting = asyncio.ensure_future(pool.run(second, time.sleep, 600))
    await until(lambda: pool._waiting == 1, "the second study to wait")
    with pytest.raises(pool.Busy) as raised:
        await pool.run(pool.Job("third"), time.sleep, 600)
    assert raised.value.field == "server" and "busy" in raised.value.allowed
    second.cancel()
    with pytest.raises(pool.Cancelled):
        await waiting
    assert second.process is None and first.running
    first.cancel()
    with pytest.raises(pool.Cancelled):
        await running


# --------------------------------------------------------------------------- the page
async def _start_the_largest_optimiser(user: User, form: Form, jobs: list[pool.Job]) -> pool.Job:
    await user.open("/")
    await form.see("Results of:")
    form.open("counterweight")
    for key, value in LARGEST.items():
        form.set(f"setting-{key}", value)
    assert form.error("setting-cw_iterations") is None
    user.find(marker="optimise").click()
    await form.until(lambda: jobs and jobs[0].running, "the optimiser's worker")
    return jobs[0]


async def test_cancel_button_ends_the_optimiser(
    user: User, form: Form, jobs: list[pool.Job]
) -> None:
    job = await _start_the_largest_optimiser(user, form, jobs)
    assert form.element("counterweight-cancel").visible
    button = form.element("optimise")
    assert not button.enabled  # no second run of the page meanwhile
    # progress after each round, with the time left
    await form.until(lambda: "round" in form.text("cw-progress"), "the optimiser's progress")
    progress = form.text("cw-progress")
    assert re.fullmatch(
        r"optimising … round \d+ of 244, [\d,]+ designs evaluated \([\d,]+ feasible\), "
        r"[\d.]+ s, (about \d+ s|<1 s) left",
        progress,
    ), progress
    assert len(jobs) == 1
    user.find(marker="counterweight-cancel").click()
    await form.until(lambda: form.text("cw-summary") == CANCELLED, "the cancel")
    assert job.process.exitcode == -signal.SIGKILL
    await user.should_not_see(marker="counterweight-cancel")  # hidden once it has ended
    assert button.enabled and form.text("cw-progress") == ""


async def test_a_second_study_of_the_page_is_refused(
    user: User, form: Form, jobs: list[pool.Job]
) -> None:
    """The optimiser's button is disabled while it runs; another tab's study is refused."""
    await _start_the_largest_optimiser(user, form, jobs)
    form.open("performance")
    await form.until(lambda: user.find(marker="run-performance").elements, "the tab")
    user.find(marker="run-performance").click()
    await form.until(
        lambda: any("is still running on this page" in m for m in user.notify.messages),
        "the refusal",
    )
    assert len(jobs) == 1


async def test_the_pareto_cloud_is_thinned(user: User, form: Form, jobs: list[pool.Job]) -> None:
    """The page draws the front and at most PARETO_CLOUD of the feasible designs."""
    from crankbalance.web.tab_counterweight import PARETO_CLOUD

    await user.open("/")
    await form.see("Results of:")
    form.open("counterweight")
    user.find(marker="optimise").click()
    await form.see("on the Pareto front")
    await form.until(lambda: form.element("figure-pareto").figure["data"], "the front drawn")
    data = form.element("figure-pareto").figure["data"]
    cloud = next(t for t in data if str(t.get("name", "")).startswith("feasible designs"))
    feasible = int(re.search(r"\((\d+)\)", cloud["name"]).group(1))
    assert feasible > PARETO_CLOUD, "the default run finds more designs than are drawn"
    x = cloud["x"]  # plotly's typed array: base64 of float64
    shown = len(x) if isinstance(x, list | tuple) else len(base64.b64decode(x["bdata"])) // 8
    assert shown == PARETO_CLOUD


@pytest.mark.anyio
async def test_a_worker_starts_with_the_shop_imported() -> None:
    """The fork server imports the shop's study and its MILP solver (pool.PRELOAD), so that
    a first shop run does not import them (issue 28, item 8)."""
    loaded = await pool.run(
        pool.Job("imports"),
        eval,
        "[m in __import__('sys').modules for m in "
        "('crankbalance.studies.shop', 'scipy.optimize', 'crankbalance.io.parts_file')]",
    )
    assert loaded == [True, True, True]
