"""Web application under load: N concurrent browser sessions, each computing M engines.

Starts ``crankbalance web`` in a subprocess, opens N pages in Debian's chromium (Playwright,
async API) and in each types M different engines into the form (cylinders, crank radius
and speed change each time; every change is a full recompute of the analysis and the
balancing and a page update). The response time is from one input (a whole value typed
into a field) to the page showing that update's status line; every input is a recompute
of a new engine. Prints p50/p95/max and the server-side times.

    python benchmarks/bench_web.py [--sessions 20] [--engines 20]

Target (issue 8): under 300 ms from input to updated plots for up to 12 cylinders.
"""

from __future__ import annotations

import argparse
import asyncio
import re
import subprocess
import time
from collections.abc import Iterator

from crankbalance.render import CHROMIUM_FLAGS

CHROMIUM = "/usr/bin/chromium"
ARGS = list(CHROMIUM_FLAGS)
STATUS = re.compile(r"update (\d+): computed in (\d+) ms, page updated in (\d+) ms")


def web_server(log: object = subprocess.DEVNULL) -> Iterator[str]:
    """``crankbalance web`` on a free port."""
    from crankbalance.web.server import running_server

    return running_server(log)


def engines(count: int) -> list[dict[str, str]]:
    """``count`` distinct in-line engines of 2..12 cylinders (no firing order: in turn)."""
    out = []
    for k in range(count):
        out.append(
            {
                "cylinders": str(2 + k % 11),
                "crank_radius": f"{38 + k % 7} mm",
                "speed": f"{2000 + 100 * k} rpm",
            }
        )
    return out


async def session(
    browser: object,
    url: str,
    count: int,
    times: list[float],
    server_ms: list[float],
    errors: list[str],
    delay: float = 0.0,
) -> None:
    await asyncio.sleep(delay)  # pages open staggered, then all type at once
    page = await browser.new_page()  # type: ignore[attr-defined]
    page.on("pageerror", lambda e: errors.append(str(e)))
    await page.goto(url + "/?preset=inline4", timeout=180000)
    status = page.locator(".q-header").first
    await page.get_by_text("update 1:").first.wait_for(timeout=180000)
    await page.locator("[data-testid=show-3d]").first.click()  # no software WebGL x N
    await page.locator("[data-testid=field-firing_order]").first.fill("")
    await page.locator("[data-testid=field-cw_webs]").first.fill("")
    last = int(STATUS.search(await status.inner_text()).group(1))  # type: ignore[union-attr]
    for engine in engines(count):
        for key, value in engine.items():  # each input is a recompute of a new engine
            t0 = time.perf_counter()
            await page.locator(f"[data-testid=field-{key}]").first.fill(value)
            expected = last + 1
            try:  # waits inside the browser, no polling from here
                await page.get_by_text(re.compile(rf"update {expected}: ")).wait_for(timeout=120000)
            except Exception as error:  # noqa: BLE001 - report, do not stop the load
                errors.append(f"no update after {engine}: {error}")
            times.append(time.perf_counter() - t0)
            match = STATUS.search(await status.inner_text())
            if match:
                server_ms.append(float(match.group(3)))
                last = int(match.group(1))
        bad = page.locator(".q-field--error")
        if await bad.count():
            errors.append(f"{engine}: {await bad.first.inner_text()}")
    await page.close()


async def run_load(url: str, sessions: int = 20, count: int = 20) -> dict[str, object]:
    """Run the load; return response times [s], server times [ms] and errors."""
    from playwright.async_api import async_playwright

    times: list[float] = []
    server_ms: list[float] = []
    errors: list[str] = []
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        t0 = time.perf_counter()
        await asyncio.gather(
            *(
                session(browser, url, count, times, server_ms, errors, delay=0.5 * k)
                for k in range(sessions)
            )
        )
        wall = time.perf_counter() - t0
        await browser.close()
    return {"times": times, "server_ms": server_ms, "errors": errors, "wall": wall}


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(q / 100 * (len(ordered) - 1))))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sessions", type=int, default=20)
    parser.add_argument("--engines", type=int, default=20)
    args = parser.parse_args()
    with web_server() as url:
        result = asyncio.run(run_load(url, args.sessions, args.engines))
    times = [t * 1e3 for t in result["times"]]  # type: ignore[union-attr]
    server = result["server_ms"]
    print(
        f"{args.sessions} sessions x {args.engines} engines, wall {result['wall']:.1f} s, "
        f"errors {len(result['errors'])}"
    )  # type: ignore[arg-type]
    print(f"{'measure':44s} {'p50':>8s} {'p95':>8s} {'max':>8s}")
    print(
        f"{'input to page update, under load [ms]':44s} {percentile(times, 50):8.0f} "
        f"{percentile(times, 95):8.0f} {max(times):8.0f}"
    )
    print(
        f"{'server: recompute + page update [ms]':44s} {percentile(server, 50):8.0f} "
        f"{percentile(server, 95):8.0f} {max(server):8.0f}"
    )
    with web_server() as url:
        single = asyncio.run(run_load(url, 1, args.engines))
    one = [t * 1e3 for t in single["times"]]  # type: ignore[union-attr]
    print(
        f"{'input to page update, one session [ms]':44s} {percentile(one, 50):8.0f} "
        f"{percentile(one, 95):8.0f} {max(one):8.0f}   (target 300)"
    )
    for error in list(result["errors"])[:5]:  # type: ignore[call-overload]
        print("error:", error)


if __name__ == "__main__":
    main()
