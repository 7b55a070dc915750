"""The web page in a real browser: first load, preset switch, edit -> updated figure.

Starts ``crankbalance web`` in a subprocess and drives Debian's chromium with Playwright
(async API). Measured from the browser, each a median of ``--repeat`` (5) unless a p95 is
named:

- first load: a new page opened on the V12 (the server is warm: one page was opened
  before), timed three ways: the browser's first contentful paint; the page shown with its
  results (the header says "current", the form is laid out and painted); every figure of
  the open tab drawn, the 3-D crank included (it is sent after the first paint);
- preset switch: choosing another preset in the header until the header shows the new
  engine and the figures are redrawn;
- PNG download: clicking a figure's PNG button until the browser has the file (made by
  plotly.js in the page; the server's ``render.to_image`` only where the browser cannot),
  after a first one, for the 3-D crank of the Engine tab and the orders bar of the Results
  tab in turn;
- edit -> figure: typing a new crank radius of the V12 (12 cylinders) until the page has
  redrawn the 3-D crank (plotly's ``afterplot``); p50 and p95 of ``--edits`` edits,
  in each of ``--sessions`` pages editing different engines at once.

The references, measured in the same run in this process: for an edit, the server's own
work (validating the form, analysis and balancing, and building the figure the page shows,
the 3-D crank); for a PNG, ``render.to_image`` of the same figure (after its first). The
ratio says what the page adds to the computation; for the first load and the preset
switch, whose work has no in-process twin, the ratio to the edit reference (p50) says how
many edits' worth of this machine's time they take, which keeps runs on a machine with a
different load comparable. The load average before and after is printed. With
``--sessions`` above 1 every session's p50 and p95 are printed too.

    python benchmarks/bench_web.py [--repeat 5] [--edits 20] [--sessions 1] [--sessions-only]

A page that NiceGUI reloads during the edits (its connection dropped and its client
deleted) ends its session with an error: its edit is lost and would be waited for in vain.

Targets (issue 14, item 9; issue 13, "web: edit -> updated figures, 12 cylinders"): first
load 2 s, preset switch 0.5 s, PNG after the first 1 s, edit -> figure p95 0.15 s.

``--fresh N`` measures instead a freshly started server, N times (issue 28, item 8): the
browser is started and a tab opened first, then ``crankbalance web``; timed from the
server's start (its warm-up included) to the first page on the crossplane V8 shown with
its results (target 2 s), to its 3-D crank seen (3 s: its still picture, sent with the
page, or the scene drawn) and to the scene drawn by plotly.js in WebGL (no target);
then, on that page, the shop example with two readings (examples/v8_parts.csv, the
settings of examples/v8_shop.py): from the click on Run to the ISO verdict shown (2 s;
the first study of the server's worker pool). The reference, measured in the same run:
``crankbalance analyze v8-crossplane`` in a fresh interpreter (the command line doing
the same first study), median of N. ``--load K`` keeps K ``yes > /dev/null`` processes
running during the whole run (a loaded machine).

As in ``bench_cold_start.py``: Python reads the compiled bytecode of an installed package
(pip writes it on installation); where ``PYTHONDONTWRITEBYTECODE`` is set, a source
checkout would be compiled at every start of the server (about 0.13 s of its imports and
more of its warm-up on this machine). So with ``--fresh`` the server and the reference run
with a bytecode cache of their own in a temporary folder (``PYTHONPYCACHEPREFIX``), filled
by one start of each before the clock; ``--as-is`` keeps the environment as it is.

    python benchmarks/bench_web.py --fresh 5 [--load 2] [--as-is]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from _load import cpu_load

from crankbalance.output.render import CHROMIUM_FLAGS

# the page's states and the shop example as typed are the browser tests' (tests/web), once
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from tests.web.test_web_screens import SETTLED  # noqa: E402
from tests.web.test_web_shop import TYPED as SHOP_TYPED  # noqa: E402

CHROMIUM = "/usr/bin/chromium"
ENGINE = "v12-60"
#: the header's update count (every processed edit raises it) and state
UPDATE = "() => Number(document.querySelector('[data-testid=status]')?.dataset.update || 0)"
#: every plotly figure shown in the open tab is drawn with its data
DRAWN = """() => {
    const s = document.querySelector('[data-testid=status]');
    return s && s.dataset.state === 'current' &&
        [...document.querySelectorAll('.q-tab-panel .js-plotly-plot')]
        .filter((e) => e.offsetParent !== null)
        .every((e) => e.querySelector('.main-svg') && e.data && e.data.length > 0);
}"""
#: the page is shown with its results: the header says the results are those of the form,
#: the form's fields are laid out and the browser has painted
SHOWN = """() => {
    const s = document.querySelector('[data-testid=status]');
    const f = document.querySelector('[data-testid=field-crank_radius]');
    return s && s.dataset.state === 'current' && f && f.offsetParent !== null &&
        performance.getEntriesByName('first-contentful-paint').length > 0;
}"""
#: the browser's first contentful paint [ms from the start of the navigation]
FIRST_PAINT = "() => performance.getEntriesByName('first-contentful-paint')[0].startTime"
#: count plotly's redraws of every figure of the page in window.cbPlots
COUNT_PLOTS = """() => {
    window.cbPlots = window.cbPlots || 0;
    for (const gd of document.querySelectorAll('.js-plotly-plot')) {
        if (gd.cbCounted) continue;
        gd.cbCounted = true;
        gd.on('plotly_afterplot', () => window.cbPlots++);
    }
}"""
GUARD_MS = 180_000  # hang guard of every wait, not a timing target
#: how often a wait looks at the page [ms]: Playwright's default polling waits for
#: animation frames, which a page among several (``--sessions``) may not get for minutes
POLL = 20
#: the figures whose PNG download is timed: (figure name, tab label)
PNG_FIGURES = (("crank3d", "Engine"), ("orders", "Results"))


async def new_page(browser: Any, url: str) -> Any:
    page = await browser.new_page(viewport={"width": 1280, "height": 800})
    page.set_default_timeout(GUARD_MS)
    return page


async def first_load(browser: Any, url: str) -> tuple[float, float, float]:
    """One first load: the browser's first contentful paint, the page shown with its results
    (:data:`SHOWN`) and every figure of the open tab drawn, the 3-D crank included
    (:data:`DRAWN`) [s from the start of the navigation]."""
    page = await new_page(browser, url)
    t0 = time.perf_counter()
    await page.goto(f"{url}/?preset={ENGINE}", wait_until="commit")
    await page.wait_for_function(SHOWN, polling=POLL)
    shown = time.perf_counter() - t0
    await page.wait_for_function(DRAWN, polling=POLL)
    drawn = time.perf_counter() - t0
    paint = await page.evaluate(FIRST_PAINT) / 1000
    await page.close()
    return paint, shown, drawn


async def preset_switches(page: Any, count: int) -> list[float]:
    times = []
    for k in range(count):
        name = ("v8-crossplane", ENGINE)[k % 2]
        before = await page.evaluate(UPDATE)
        await page.locator("[data-testid=preset]").first.click()
        option = page.get_by_role("option", name=name, exact=True)
        await option.wait_for()
        t0 = time.perf_counter()
        await option.click()
        await page.wait_for_function(f"() => ({UPDATE})() > {before}", polling=POLL)
        await page.wait_for_function(DRAWN, polling=POLL)
        times.append(time.perf_counter() - t0)
    return times


async def png_downloads(page: Any, count: int) -> dict[str, list[float]]:
    """``count`` PNG downloads of each figure of :data:`PNG_FIGURES`, after a first one."""
    times: dict[str, list[float]] = {name: [] for name, _ in PNG_FIGURES}
    for k in range(count + 1):
        for name, tab in PNG_FIGURES:
            await page.get_by_role("tab", name=tab, exact=True).click()
            await page.wait_for_function(DRAWN, polling=POLL)
            card = page.locator(".q-card", has=page.locator(f"[data-testid=figure-{name}]"))
            button = card.get_by_role("button", name="PNG", exact=True)
            t0 = time.perf_counter()
            async with page.expect_download() as info:
                await button.click()
            download = await info.value
            await download.path()
            if k > 0:  # the first export starts the server's kept Chromium
                times[name].append(time.perf_counter() - t0)
    return times


async def edits(page: Any, count: int, offset: int, errors: list[str]) -> list[float]:
    """``count`` edits of the V12's crank radius, each to a new value (never the preset's
    47 mm): an edit that leaves the 3-D crank as it is (the speed, or the same value)
    redraws nothing (``FigureCard.refresh``) and would be waited for in vain."""
    await page.evaluate(COUNT_PLOTS)
    times = []
    for k in range(count):
        key, value = "crank_radius", f"{40 + (k + offset) % 9}.5 mm"
        plots = await page.evaluate("() => window.cbPlots")
        t0 = time.perf_counter()
        await page.locator(f"[data-testid=field-{key}]").first.fill(value)
        # a page that NiceGUI reloaded (its client dropped) has no counter: the edit is lost
        # and would be waited for in vain, so the wait ends and the session stops there
        await page.wait_for_function(
            f"() => window.cbPlots === undefined || window.cbPlots > {plots}", polling=POLL
        )
        if await page.evaluate("() => window.cbPlots === undefined"):
            errors.append(
                f"edit {k + 1} ({key} = {value}): the page was reloaded (connection lost)"
            )
            break
        times.append(time.perf_counter() - t0)
        if await page.locator(".q-field--error").count():
            errors.append(
                f"{key} = {value}: {await page.locator('.q-field--error').first.inner_text()}"
            )
    return times


async def session(
    browser: Any, url: str, count: int, offset: int, errors: list[str]
) -> list[float]:
    page = await new_page(browser, url)
    page.on("pageerror", lambda e: errors.append(str(e)))
    await page.goto(f"{url}/?preset={ENGINE}")
    await page.wait_for_function(DRAWN, polling=POLL)
    times = await edits(page, count, offset, errors)
    await page.close()
    return times


async def run(
    url: str, repeat: int, count: int, sessions: int, sessions_only: bool = False
) -> dict[str, Any]:
    from playwright.async_api import async_playwright

    errors: list[str] = []
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=list(CHROMIUM_FLAGS))
        if sessions_only:
            groups = await asyncio.gather(
                *(session(browser, url, count, 7 * k, errors) for k in range(sessions))
            )
            await browser.close()
            return {"groups": groups, "errors": errors}
        await first_load(browser, url)  # warm the server (imports, first page)
        loads = [await first_load(browser, url) for _ in range(repeat)]
        page = await new_page(browser, url)
        await page.goto(f"{url}/?preset={ENGINE}")
        await page.wait_for_function(DRAWN, polling=POLL)
        switches = await preset_switches(page, repeat)
        await page.close()
        page = await browser.new_page(
            viewport={"width": 1280, "height": 800}, accept_downloads=True
        )
        page.set_default_timeout(GUARD_MS)
        await page.goto(f"{url}/?preset={ENGINE}")
        await page.wait_for_function(DRAWN, polling=POLL)
        pngs = await png_downloads(page, repeat)
        await page.close()
        groups = await asyncio.gather(
            *(session(browser, url, count, 7 * k, errors) for k in range(sessions))
        )
        await browser.close()
    return {
        "loads": loads,
        "switches": switches,
        "pngs": pngs,
        "groups": groups,
        "errors": errors,
    }


def reference(count: int) -> list[float]:
    """The server's work for one edit of the V12, in this process: the form validated,
    analysis and balancing, the 3-D crank figure and its JSON [s]."""
    from crankbalance.output.figures.crank3d import crank_3d
    from crankbalance.web.project import Project

    project = Project.from_preset(ENGINE)
    times = []
    for k in range(count):
        t0 = time.perf_counter()
        project.set("crank_radius", f"{40 + k % 9} mm")
        c = project.compute()
        assert c is not None
        crank_3d(c.study).to_plotly_json()
        times.append(time.perf_counter() - t0)
    return times


def png_reference(count: int) -> dict[str, list[float]]:
    """``render.to_image`` of the figures of :data:`PNG_FIGURES` for the V12 in this process,
    after a first export: ``count`` each [s]."""
    from crankbalance.output import render
    from crankbalance.output.figures.crank3d import crank_3d
    from crankbalance.output.figures.engine import orders_bar
    from crankbalance.web.project import Project

    c = Project.from_preset(ENGINE).compute()
    assert c is not None
    built = {
        "crank3d": crank_3d(c.analysis.model, c.study),
        "orders": orders_bar(c.analysis),
    }
    render.to_image(built["orders"], "png")
    times: dict[str, list[float]] = {name: [] for name, _ in PNG_FIGURES}
    for _ in range(count):
        for name, _tab in PNG_FIGURES:
            t0 = time.perf_counter()
            render.to_image(built[name], "png")
            times[name].append(time.perf_counter() - t0)
    return times


FRESH_ENGINE = "v8-crossplane"
PARTS = Path(__file__).resolve().parents[1] / "examples" / "v8_parts.csv"
#: the 3-D crank is seen: drawn by plotly.js (its WebGL scene and data), or its still picture
#: (``FigureCard.preview``, sent with the page until the scene is drawn) displayed with its
#: lines, the page painted
CRANK_SEEN = """() => {
    const f = document.querySelector('[data-testid=figure-crank3d]');
    if (f && f.querySelector('.gl-container') && f.data && f.data.length > 0) return true;
    const p = document.querySelector('[data-testid=preview-crank3d]');
    return !!(p && p.offsetParent !== null && p.querySelector('svg polyline') &&
        performance.getEntriesByName('first-contentful-paint').length > 0);
}"""
VERDICT = """() => {
    const v = document.querySelector('[data-testid=shop-verdict]');
    return v && v.offsetParent !== null && /G\\d/.test(v.textContent);
}"""


async def fresh_server(browser: Any) -> tuple[float, float, float, float]:
    """One freshly started server: [s] from its start to the first page shown with its
    results, to its 3-D crank seen (:data:`CRANK_SEEN`: its still picture or the scene),
    to the scene drawn by plotly.js (WebGL), and from Run to the shop example's verdict."""
    from crankbalance.web.server import running_server

    page = await new_page(browser, "")  # a browser tab open before the server starts
    t0 = time.perf_counter()
    with running_server(timeout=GUARD_MS / 1000) as url:
        await page.goto(f"{url}/?preset={FRESH_ENGINE}", wait_until="commit")
        await page.wait_for_function(SHOWN, polling=POLL)
        shown = time.perf_counter() - t0
        await page.wait_for_function(CRANK_SEEN, polling=POLL)
        seen = time.perf_counter() - t0
        await page.wait_for_function(DRAWN, polling=POLL)
        drawn = time.perf_counter() - t0
        await page.wait_for_function("() => window.socket && window.socket.connected")
        await page.get_by_role("tab", name="Balance shop", exact=True).click()
        await page.wait_for_function(SETTLED, polling=POLL)
        # the example's parts as "Load example" puts them (a click during the tab's opening
        # was lost once: typing them needs no click)
        await page.locator("[data-testid=shop-parts]").first.fill(PARTS.read_text(encoding="utf-8"))
        for key, value in SHOP_TYPED.items():
            await page.locator(f"[data-testid=shop-{key}]").first.fill(value)
        t1 = time.perf_counter()
        await page.get_by_role("button", name="Run", exact=True).click()
        await page.wait_for_function(VERDICT, polling=POLL)
        shop = time.perf_counter() - t1
        await page.close()
    return shown, seen, drawn, shop


async def run_fresh(count: int) -> list[tuple[float, float, float, float]]:
    from playwright.async_api import async_playwright

    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=list(CHROMIUM_FLAGS))
        times = [await fresh_server(browser) for _ in range(count)]
        await browser.close()
    return times


def cli_reference(count: int) -> list[float]:
    """``crankbalance analyze v8-crossplane`` in a fresh interpreter, ``count`` times [s]."""
    command = [sys.executable, "-m", "crankbalance", "analyze", FRESH_ENGINE]
    times = []
    for _ in range(count):
        t0 = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - t0)
    return times


def fresh_main(count: int, as_is: bool) -> None:
    with tempfile.TemporaryDirectory(prefix="crankbalance-pycache-") as cache:
        if not as_is:  # the server (running_server) and the reference inherit os.environ
            os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
            os.environ["PYTHONPYCACHEPREFIX"] = cache
            cli_reference(1)  # the bytecode written, not timed
            asyncio.run(run_fresh(1))
        load_before = os.getloadavg()[0]
        ref = statistics.median(cli_reference(count))
        times = asyncio.run(run_fresh(count))
    bytecode = "as the environment is" if as_is else "bytecode cached"
    print(
        f"fresh server, {FRESH_ENGINE}, {count} runs ({bytecode}); load average "
        f"{load_before:.1f} before, {os.getloadavg()[0]:.1f} after ({os.cpu_count()} cores)"
    )
    print(f"reference: crankbalance analyze {FRESH_ENGINE}, fresh interpreter, median {ref:.3f} s")
    print(f"{'measure (median) [s]':50s} {'measured':>9s} {'target':>7s} {'ratio to ref':>12s}")
    labels = (
        ("server start -> first results shown", 2.0),
        ("server start -> 3-D crank seen (picture or WebGL)", 3.0),
        ("server start -> 3-D crank drawn in WebGL", None),
        ("shop example, two readings: Run -> verdict", 2.0),
    )
    for (label, target), values in zip(labels, zip(*times, strict=True), strict=True):
        value = statistics.median(values)
        t = "" if target is None else f"{target:.2f}"
        print(f"{label:50s} {value:9.3f} {t:>7s} {value / ref:12.1f}")


def percentile(values: list[float], q: float) -> float:
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(q / 100 * (len(ordered) - 1))))]


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--edits", type=int, default=20)
    parser.add_argument("--sessions", type=int, default=1)
    parser.add_argument(
        "--sessions-only",
        action="store_true",
        help="only the edits of --sessions pages at once (no loads, switches or PNGs)",
    )
    parser.add_argument("--fresh", type=int, default=0, help="N freshly started servers")
    parser.add_argument("--load", type=int, default=0, help="K `yes` processes meanwhile")
    parser.add_argument(
        "--as-is", action="store_true", help="with --fresh: no bytecode cache of our own"
    )
    args = parser.parse_args()
    with cpu_load(args.load):
        if args.fresh:
            fresh_main(args.fresh, args.as_is)
        else:
            warm_main(args)


def warm_main(args: argparse.Namespace) -> None:
    from crankbalance.web.server import running_server

    load_before = os.getloadavg()[0]
    ref = reference(args.edits)
    png_ref = {} if args.sessions_only else png_reference(args.repeat)
    with running_server(timeout=GUARD_MS / 1000) as url:
        result = asyncio.run(run(url, args.repeat, args.edits, args.sessions, args.sessions_only))
    ref_p50, ref_p95 = percentile(ref, 50), percentile(ref, 95)
    groups: list[list[float]] = result["groups"]
    edit = [t for group in groups for t in group]
    n = args.sessions
    rows = (
        []
        if args.sessions_only
        else [
            *(
                (f"first load: {what}, median [s]", statistics.median(times), target, ref_p50)
                for what, times, target in zip(
                    ("first paint", "page and results shown", "3-D view drawn too"),
                    zip(*result["loads"], strict=True),
                    (None, 2.0, None),
                    strict=True,
                )
            ),
            ("preset switch, median [s]", statistics.median(result["switches"]), 0.5, ref_p50),
            *(
                (
                    f"PNG {name} after the first, median [s]",
                    statistics.median(result["pngs"][name]),
                    1.0,
                    statistics.median(png_ref[name]),
                )
                for name, _tab in PNG_FIGURES
            ),
        ]
    )
    rows += [
        (f"edit -> figure p50, {n} session(s) [s]", percentile(edit, 50), None, ref_p50),
        (f"edit -> figure p95, {n} session(s) [s]", percentile(edit, 95), 0.15, ref_p95),
    ]
    if n > 1:
        for k, group in enumerate(groups):
            rows.append(
                (f"  session {k + 1}: edit -> figure p50 [s]", percentile(group, 50), None, ref_p50)
            )
            rows.append(
                (f"  session {k + 1}: edit -> figure p95 [s]", percentile(group, 95), 0.15, ref_p95)
            )
    print(
        f"{ENGINE}, {0 if args.sessions_only else args.repeat} loads/switches/PNGs, "
        f"{len(edit)} of {n * args.edits} edits done in {n} session(s), "
        f"errors {len(result['errors'])}; load average {load_before:.1f} before, "
        f"{os.getloadavg()[0]:.1f} after ({os.cpu_count()} cores)"
    )
    print(
        f"references (in process): server work of one edit p50 {ref_p50:.3f} s, "
        f"p95 {ref_p95:.3f} s; PNG "
        + ", ".join(f"{name} {statistics.median(times):.3f} s" for name, times in png_ref.items())
    )
    print(f"{'measure':50s} {'measured':>9s} {'target':>7s} {'ratio to ref':>12s}")
    for label, value, target, ref_value in rows:
        t = "" if target is None else f"{target:.2f}"
        r = "" if ref_value is None else f"{value / ref_value:.1f}"
        print(f"{label:50s} {value:9.3f} {t:>7s} {r:>12s}")
    for error in result["errors"][:5]:
        print("error:", error)


if __name__ == "__main__":
    main()
