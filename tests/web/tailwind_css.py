"""Capture the CSS that NiceGUI's Tailwind runtime generates for the web page, and write it
as the page's static stylesheet (``src/crankbalance/web/static/tailwind.css``).

The page is served with ``ui.run(tailwind=False)`` (web/server.py): NiceGUI's Tailwind
compiler in the browser (``tailwindcss.min.js``, Tailwind v4's browser build) is not loaded,
and the stylesheet written here styles the Tailwind classes instead. This module makes
that stylesheet and reads it back for ``test_web_tailwind_css.py``; it is a developer's
tool (Playwright and Debian's chromium), never imported by the package.

How: ``crankbalance.web.server.serve(tailwind=True)`` serves the page with NiceGUI's own
runtime and the configuration of its ``index.html`` template (the same compiler, the same
``<style type="text/tailwindcss">`` block), so what is captured is what that runtime
generates for this page. In chromium the page (the V12 preset) has every tab opened at
1280x800 and at 390x844, its preset menu opened and a notification of each type shown
(Quasar's popups), and a hidden element carries every class token written
literally in a ``.classes(...)`` call or a ``classes=`` argument of
``src/crankbalance/web/*.py`` (so a class shown only in a rare state counts too). Once the
runtime has built the CSS of all of them, its ``<style>`` element is read. The runtime's
output is deterministic for a set of classes (Tailwind sorts its rules), so it is written
as it comes, after a header, followed by NiceGUI's ``headwind.css`` in the ``overrides``
layer (the template adds it only when the runtime is on).

    python tests/web/tailwind_css.py --write    # rewrite the stylesheet
    python tests/web/tailwind_css.py            # say whether it is up to date (exit 1 if not)
"""

from __future__ import annotations

import argparse
import ast
import json
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
WEB = ROOT / "src" / "crankbalance" / "web"
STYLESHEET = WEB / "static" / "tailwind.css"
CHROMIUM = "/usr/bin/chromium"
PRESET = "v12-60"
PHONE = {"width": 390, "height": 844}
DESKTOP = {"width": 1280, "height": 800}
GUARD_MS = 180_000  # hang guard of every wait (not a timing target)
REGENERATE = "python tests/web/tailwind_css.py --write"
#: the shown tab panel holds its content (not the placeholder of a tab being built) and
#: no Quasar transition runs
SETTLED = """() => {
    const shown = [...document.querySelectorAll('.q-tab-panel')]
        .filter((p) => p.offsetParent !== null);
    return shown.length === 1
        && !document.querySelector('[class*="q-transition--"][class*="-active"]')
        && ![...document.querySelectorAll('[data-testid$="-opening"]')]
            .some((e) => e.offsetParent !== null);
}"""
#: the runtime's output: the <style> it appends to the head (Tailwind's banner first)
RUNTIME_CSS = """() => {
    const s = [...document.head.querySelectorAll('style')]
        .find((e) => e.textContent.startsWith('/*! tailwindcss'));
    return s ? s.textContent : null;
}"""
#: a build of the runtime that started at or after ``t`` [ms, performance.now()] is over
#: (the runtime measures each build as "Build #n (full|incremental)")
BUILT_SINCE = """(t) => performance.getEntriesByType('measure')
    .some((m) => m.name.startsWith('Build #') && m.startTime >= t)"""
HEADER = """/* The CSS that NiceGUI's Tailwind runtime (tailwindcss.min.js, Tailwind v{tailwind},
   NiceGUI {nicegui}) generates for the crankbalance web page, served as a static stylesheet
   instead of the runtime (web/server.py, ui.run(tailwind=False); docs/web.md, "Speed").
   Captured in chromium from the page with every tab opened at 1280x800 and 390x844, the
   preset menu and a notification of each type shown, and every class token written in a
   .classes(...) of src/crankbalance/web/*.py on a hidden element; then NiceGUI's
   headwind.css in the overrides layer, as its template adds it with the runtime.
   Generated: do not edit. After a change of the page's classes or of NiceGUI run
   {regenerate}
   (tests/web/test_web_tailwind_css.py fails until then). */
"""


# ------------------------------------------------------------------ the classes in the code
def class_tokens(folder: Path = WEB) -> list[str]:
    """Every class token written literally in ``.classes(...)`` or ``classes=`` in the
    modules of ``folder``, sorted. A ``.classes(name)`` whose ``name`` is a parameter of
    the function around it counts that parameter's default and the strings passed for it
    where the function is called in the same module."""
    tokens: set[str] = set()
    for path in sorted(folder.glob("*.py")):
        tree = ast.parse(path.read_text(), filename=str(path))
        around: dict[ast.AST, ast.AST] = {}  # a node -> the innermost function it is in
        for function in ast.walk(tree):  # outer functions before the ones inside them
            if isinstance(function, ast.FunctionDef | ast.AsyncFunctionDef):
                around |= {node: function for node in ast.walk(function) if node is not function}
        for call in _calls(tree):
            values: list[ast.AST] = []
            if isinstance(call.func, ast.Attribute) and call.func.attr == "classes":
                values += call.args + [k.value for k in call.keywords]
            values += [k.value for k in call.keywords if k.arg == "classes"]
            for value in values:
                tokens |= _strings(value)
                if isinstance(value, ast.Name) and value in around:
                    tokens |= _parameter_strings(tree, around[value], value.id)
    return sorted(tokens)


def _calls(function: ast.AST) -> Iterator[ast.Call]:
    return (node for node in ast.walk(function) if isinstance(node, ast.Call))


def _strings(node: ast.AST | None) -> set[str]:
    """The whitespace-separated tokens of the strings in ``node`` (a dict's values only:
    ``.classes(**{"add": "cb-stale"})``)."""
    if isinstance(node, ast.Dict):
        return {t for value in node.values for t in _strings(value)}
    if isinstance(node, ast.Constant):
        return set(node.value.split()) if isinstance(node.value, str) else set()
    return {t for child in ast.iter_child_nodes(node) for t in _strings(child)} if node else set()


def _parameter_strings(tree: ast.Module, function: Any, name: str) -> set[str]:
    """The strings a parameter ``name`` of ``function`` takes: its default, and what the
    calls of ``function`` (by its name) in ``tree`` pass for it."""
    args = function.args
    positional = [a.arg for a in args.posonlyargs + args.args]
    if name not in positional + [a.arg for a in args.kwonlyargs]:
        return set()
    found: set[str] = set()
    with_default = positional[len(positional) - len(args.defaults) :]
    defaults = dict(zip(with_default, args.defaults, strict=True))
    keywords = zip(args.kwonlyargs, args.kw_defaults, strict=True)
    defaults |= {a.arg: d for a, d in keywords if d is not None}
    if name in defaults:
        found |= _strings(defaults[name])
    method = positional[:1] in (["self"], ["cls"])
    index = positional.index(name) - method if name in positional else None
    for call in _calls(tree):
        called = call.func.attr if isinstance(call.func, ast.Attribute) else None
        called = call.func.id if isinstance(call.func, ast.Name) else called
        if called != function.name:
            continue
        if index is not None and index < len(call.args):
            found |= _strings(call.args[index])
        found |= {t for k in call.keywords if k.arg == name for t in _strings(k.value)}
    return found


# ------------------------------------------------------------------ capture in the browser
def open_page(browser: Any, url: str) -> Any:
    """A new page at 1280x800 on :data:`PRESET`, its results shown."""
    page = browser.new_page(viewport=DESKTOP)
    page.set_default_timeout(GUARD_MS)
    try:
        page.goto(f"{url}/?preset={PRESET}")
        page.wait_for_function(
            "() => document.querySelector('[data-testid=status]')?.dataset.state === 'current'"
        )
    except BaseException:
        page.close()
        raise
    return page


def open_tab(page: Any, label: str) -> None:
    """Click the tab ``label`` and wait until its panel is shown with its content."""
    page.get_by_role("tab", name=label, exact=True).click()
    page.wait_for_function(
        "(t) => [...document.querySelectorAll('[role=tab]')].some((e) =>"
        " e.getAttribute('aria-selected') === 'true' && e.textContent.trim() === t)",
        arg=label,
    )
    page.wait_for_function(SETTLED)


def _open_every_tab(page: Any) -> None:
    from crankbalance.web.app import TABS

    for _name, label in TABS:
        open_tab(page, label)


def _popups(page: Any) -> None:
    """Quasar's popups the page shows: the preset menu opened (and closed), and a
    notification of each type ``ui.notify`` is called with (kept until the page closes)."""
    page.locator("[data-testid=preset]").first.click()
    page.get_by_role("option").first.wait_for()
    page.keyboard.press("Escape")
    page.get_by_role("option").first.wait_for(state="hidden")
    page.evaluate(
        """() => ['positive', 'negative', 'warning'].forEach((type) =>
            Quasar.Notify.create({type, message: type, multiLine: true, timeout: 0}))"""
    )
    page.locator(".q-notification").nth(2).wait_for()


def capture(browser: Any, url: str) -> str:
    """The CSS that the Tailwind runtime of the page at ``url`` (a server with
    ``tailwind=True``) generates for every tab at both widths and every class token of
    :func:`class_tokens`."""
    page = open_page(browser, url)
    try:
        for size in (DESKTOP, PHONE):
            page.set_viewport_size(size)
            _open_every_tab(page)
        _popups(page)
        start = page.evaluate(
            """(classes) => {
                const e = document.createElement('div');
                e.hidden = true;
                e.className = classes;
                document.body.append(e);
                return performance.now();
            }""",
            " ".join(class_tokens()),
        )
        page.wait_for_function(BUILT_SINCE, arg=start)
        css = page.evaluate(RUNTIME_CSS)
    finally:
        page.close()
    if not css:
        raise RuntimeError(f"the page at {url} has no Tailwind runtime (tailwind=False?)")
    return str(css)


def stylesheet(css: str) -> str:
    """The static stylesheet of the runtime's ``css``: header, ``css``, NiceGUI's
    headwind.css in the overrides layer (as the template adds it with the runtime)."""
    import nicegui

    tailwind = css.split("tailwindcss v", 1)[1].split()[0] if "tailwindcss v" in css else "4"
    headwind = (Path(nicegui.__file__).parent / "static" / "headwind.css").read_text().strip()
    headwind = "\n".join("  " + line if line else line for line in headwind.splitlines())
    header = HEADER.format(tailwind=tailwind, nicegui=nicegui.__version__, regenerate=REGENERATE)
    return f"{header}{css.strip()}\n@layer overrides {{\n{headwind}\n}}\n"


# ------------------------------------------------------------------ rules of a stylesheet
def rules(css: str) -> set[tuple[str, ...]]:
    """Every declaration of ``css`` with the at-rules and selectors around it, e.g.
    ``("@layer utilities", ".w-full", "width: 100%")``; a statement at-rule (``@layer a,
    b;``) is one too. Comments are dropped and white space is normalised, so two
    stylesheets with the same rules in another order or layout give the same set."""
    found: set[tuple[str, ...]] = set()
    stack: list[str] = []
    text = ""
    k = 0
    quote = ""
    while k < len(css):
        c = css[k]
        if quote:
            text += c
            if c == "\\":
                text += css[k + 1 : k + 2]
                k += 1
            elif c == quote:
                quote = ""
        elif css.startswith("/*", k):
            end = css.find("*/", k + 2)
            k = len(css) if end < 0 else end + 1
        elif c in "\"'":
            quote = c
            text += c
        elif c == "\\":
            text += css[k : k + 2]
            k += 1
        elif c == "{":
            stack.append(" ".join(text.split()))
            text = ""
        elif c in ";}":
            statement = " ".join(text.split())
            if statement:
                found.add((*stack, statement))
            text = ""
            if c == "}":
                if not stack:
                    raise ValueError(f"unbalanced '}}' at character {k} of the stylesheet")
                stack.pop()
        else:
            text += c
        k += 1
    if stack or text.strip():
        raise ValueError("the stylesheet ends inside a block")
    return found


def shipped() -> str:
    """The stylesheet in the package."""
    return STYLESHEET.read_text()


def missing(captured: str, css: str) -> list[str]:
    """The rules of ``captured`` (the runtime's output) that ``css`` lacks, as text."""
    return [" { ".join(rule) for rule in sorted(rules(captured) - rules(css))]


# ------------------------------------------------------------------ command line
def _capture_now() -> str:
    from playwright.sync_api import sync_playwright

    from crankbalance.output.render import CHROMIUM_FLAGS
    from crankbalance.web.server import running_server

    with running_server(tailwind=True) as url, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=list(CHROMIUM_FLAGS))
        try:
            return capture(browser, url)
        finally:
            browser.close()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--write", action="store_true", help=f"rewrite {STYLESHEET.name}")
    parser.add_argument("--tokens", action="store_true", help="print the class tokens")
    options = parser.parse_args(argv)
    if options.tokens:
        print(json.dumps(class_tokens(), indent=1))
        return 0
    css = stylesheet(_capture_now())
    if options.write:
        from crankbalance.io.files import write_atomic

        write_atomic(STYLESHEET, css)
        print(f"wrote {STYLESHEET.relative_to(ROOT)} ({len(css)} characters)")
        return 0
    lacking = missing(css, shipped()) if STYLESHEET.exists() else ["(no file)"]
    for rule in lacking:
        print("missing:", rule)
    print("up to date" if not lacking else f"out of date: run {REGENERATE}")
    return 1 if lacking else 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT / "src"))
    sys.exit(main())
