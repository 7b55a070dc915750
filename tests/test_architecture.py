"""Architecture rules of DESIGN.md that a test can enforce."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

import pytest

import crankbalance

SRC = Path(crankbalance.__file__).parent
#: the layers of the package, by folder (docs/architecture.md): physics imports only
#: itself and the base modules; everything else may import physics
PHYSICS_DIR = SRC / "physics"
#: every physics module, found by its folder: numpy/scipy only, no I/O, no units, no edges
PHYSICS = tuple(
    sorted(
        ".".join(path.relative_to(SRC).with_suffix("").parts)
        for path in PHYSICS_DIR.rglob("*.py")
        if path.name != "__init__.py"
    )
)
#: the modules of crankbalance a physics module may import (beside physics itself)
BASE = {"errors", "records", "results"}
#: third-party packages that are edges (units, figures, web, command line)
EDGE_PACKAGES = {"pint", "plotly", "nicegui", "click", "matplotlib", "pydantic", "kaleido"}


def imported(path: Path) -> set[str]:
    """The modules ``path`` imports: crankbalance's as dotted names without the package
    prefix (``physics.model``, ``errors``), others by their top-level package."""
    tree = ast.parse(path.read_text())
    module = ".".join(path.relative_to(SRC).with_suffix("").parts)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    package = package.removesuffix(".__init__")
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                names.add(_own(alias.name) or alias.name.split(".")[0])
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative: from ..x import y
                parts = package.split(".") if package else []
                base = parts[: len(parts) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
                if node.module is None:  # from .. import a, b: the modules a and b
                    names |= {".".join([*base, a.name]).strip(".") for a in node.names}
                else:
                    names.add(target)
            elif node.module:
                own = _own(node.module)
                if own == "":  # from crankbalance import a, b
                    names |= {a.name for a in node.names}
                else:
                    names.add(own or node.module.split(".")[0])
    return names


def _own(name: str) -> str | None:
    """A crankbalance module's name without the package prefix, or None for another."""
    if name == "crankbalance":
        return ""
    return name.removeprefix("crankbalance.") if name.startswith("crankbalance.") else None


def test_physics_is_found_by_its_folder() -> None:
    assert "physics.shaking" in PHYSICS and "physics.shop.matching" in PHYSICS
    assert "physics.explore.orders" in PHYSICS and len(PHYSICS) >= 25
    stray = [
        path.name
        for path in SRC.glob("*.py")
        if path.stem not in {"__init__", "__main__", *BASE, "units"}
    ]
    assert not stray, f"modules at the top of the package, outside the layer folders: {stray}"


#: crankbalance's folders and top modules other than physics and the base
_LAYERS = {"studies", "schema", "io", "output", "cli", "web", "units"}


@pytest.mark.parametrize("name", PHYSICS)
def test_physics_modules_do_not_import_edges(name: str) -> None:
    path = SRC / f"{name.replace('.', '/')}.py"
    bad = sorted(t for t in imported(path) if t in EDGE_PACKAGES or t.split(".")[0] in _LAYERS)
    assert not bad, f"{name} imports {bad} (physics stays pure: docs/architecture.md)"


#: lines above which a physics module's docstring says why it is one module
LONG_MODULE = 800


@pytest.mark.parametrize("name", PHYSICS)
def test_a_long_physics_module_says_why(name: str) -> None:
    """Issue 26: no physics module over 800 lines unless its docstring says why (in the
    words "over 800 lines")."""
    path = SRC / f"{name.replace('.', '/')}.py"
    text = path.read_text()
    if text.count("\n") <= LONG_MODULE:
        return
    docstring = ast.get_docstring(ast.parse(text)) or ""
    assert "over 800 lines" in " ".join(docstring.split()), (
        f"{name} has {text.count(chr(10))} lines: split it by subject or say why it is one "
        "(docs/architecture.md)"
    )


def _module_graph() -> dict[str, set[str]]:
    """crankbalance's modules and the crankbalance modules each imports (a package stands
    for its ``__init__``; an import of a name from a package counts as its module)."""
    modules: dict[str, Path] = {}
    for path in SRC.rglob("*.py"):
        parts = path.relative_to(SRC).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        modules[name] = path
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        edges = set()
        for target in imported(path):
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target and target != name:
                edges.add(target)
        graph[name] = edges
    return graph


def find_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The cycles a depth-first walk of ``graph`` meets (each as its modules, the first
    repeated at the end); none when the graph flows one way."""
    cycles: list[list[str]] = []
    state: dict[str, int] = {}  # 1: on the walk's path, 2: done
    path: list[str] = []

    def visit(node: str) -> None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycles.append([*path[path.index(nxt) :], nxt])
            elif nxt not in state:
                visit(nxt)
        path.pop()
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node)
    return cycles


def test_no_import_cycles() -> None:
    """The import graph of the package has no cycle (a module that imports, directly or
    through others, a module that imports it), imports inside functions and for type
    checking included: every layer imports only downwards."""
    cycles = sorted(" -> ".join(c) for c in find_cycles(_module_graph()))
    assert not cycles, "import cycles:\n" + "\n".join(cycles)


def test_the_cycle_walk_finds_cycles() -> None:
    assert find_cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c", "a"]]
    assert find_cycles({"a": {"b"}, "b": set(), "c": {"a", "b"}}) == []


def private_imports(path: Path, root: Path = SRC) -> set[str]:
    """The private names (``_name``, not ``__dunder__``) that the module at ``path`` (in the
    package at ``root``) imports from another crankbalance module, each as
    ``module: source._name``."""
    module = ".".join(path.relative_to(root).with_suffix("").parts).removesuffix(".__init__")
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level:
            parts = package.split(".") if package else []
            source = ".".join(parts[: len(parts) - (node.level - 1)] + [node.module or ""])
        elif _own(node.module or "") is not None:
            source = _own(node.module or "") or ""
        else:
            continue
        found |= {
            f"{module}: {source.strip('.')}.{a.name}"
            for a in node.names
            if a.name.startswith("_") and not a.name.startswith("__")
        }
    return found


def test_no_private_names_across_modules() -> None:
    """No module imports another module's private name: what two modules share is public,
    with a docstring, in the module that owns it."""
    found = set().union(*(private_imports(path) for path in SRC.rglob("*.py")))
    assert not found, "private names imported across modules:\n" + "\n".join(sorted(found))


def test_the_private_import_scan_finds_them(tmp_path: Path) -> None:
    sheet = tmp_path / "output" / "sheet.py"
    sheet.parent.mkdir()
    sheet.write_text(
        "from .report import CSS, _table\n"
        "from . import _html, __version__\n"
        "from crankbalance.physics.model import _throws\n"
        "from numpy import _core\n"
    )
    assert private_imports(sheet, tmp_path) == {
        "output.sheet: output.report._table",
        "output.sheet: output._html",
        "output.sheet: physics.model._throws",
    }


#: third-party packages the command line may load, by command (``None``: the start alone,
#: ``crankbalance --help``); everything else (pint, scipy, plotly, nicegui, kaleido,
#: shapely, trimesh, pymoo, matplotlib, ...) must stay unloaded
CLI_PACKAGES: dict[str | None, set[str]] = {
    None: {"click"},
    "analyze": {"click", "numpy"},
}
CLI_PACKAGES["balance"] = CLI_PACKAGES["analyze"]
_CLI_PROBE = """
import contextlib, io, json, sys
before = set(sys.modules)
from crankbalance.cli import main
if len(sys.argv) > 1:
    with contextlib.redirect_stdout(io.StringIO()):
        main(sys.argv[1:])
new = {name.split(".")[0] for name in set(sys.modules) - before}
print(json.dumps(sorted(
    name for name in new - set(sys.stdlib_module_names) if not name.startswith("_")
)))
"""


@pytest.mark.parametrize("command", list(CLI_PACKAGES), ids=lambda c: c or "start")
def test_cli_loads_only_the_packages_it_needs(command: str | None) -> None:
    """A fresh interpreter runs ``crankbalance COMMAND inline4`` and lists the third-party
    packages it loaded (times nothing: docs/performance.md has the timings)."""
    args = [] if command is None else [command, "inline4"]
    out = subprocess.run(
        [sys.executable, "-c", _CLI_PROBE, *args], capture_output=True, text=True, check=True
    )
    loaded = set(json.loads(out.stdout)) - {"crankbalance"}
    assert loaded <= CLI_PACKAGES[command], (
        f"crankbalance {' '.join(args)} loads {', '.join(sorted(loaded - CLI_PACKAGES[command]))}"
    )


#: modules a command of one engine must not load (issue 30, the cold start): the physics
#: of other studies (the settings schema takes their limits from ``physics.limits``), the
#: other studies, and the standard library's heavier modules that nothing on these paths
#: needs (``importlib.resources`` brought zipfile and tempfile, ``secrets`` random,
#: ``pathlib`` urllib and ipaddress: io.files imports it on the first write)
CLI_MODULES_UNLOADED = (
    # the other studies' settings schemas (about 3 ms of a cold start, issue 30)
    *(
        f"crankbalance.schema.settings.{family}"
        for family in ("counterweight", "single", "shaft", "cycle", "crank", "shop", "explore")
    ),
    "numpy.typing",  # annotations only (0.6 ms: its docstrings are parsed at import)
    "crankbalance.physics.engine_cycle",
    "crankbalance.physics.engine_cycle_all",
    "crankbalance.physics.single_cylinder",
    "crankbalance.physics.torsional",
    "crankbalance.physics.explore.orders",
    "crankbalance.studies.explore",
    "crankbalance.studies.single",
    "crankbalance.output.figures",
    "importlib.resources",
    "importlib.metadata",
    "zipfile",
    "tempfile",
    "secrets",
    "pathlib",
    "json",
    "crankbalance.physics.articulated",
    "scipy",
    "plotly",
    "nicegui",
    "dask",
)
#: modules ``analyze`` must not load besides: the balancing (its records and dataclasses
#: cost about 12 ms of an idle machine's cold start; the web's next-step words imported
#: them into the analysis path once)
ANALYZE_MODULES_UNLOADED = (
    "crankbalance.physics.balance_types",
    "crankbalance.physics.balance_remaining",
    "crankbalance.physics.balancing",
    "crankbalance.physics.balance_solver",
    "crankbalance.physics.explore.work",
)
_CLI_MODULES_PROBE = """
import contextlib, io, sys
from crankbalance.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    try:
        main(sys.argv[1:])
    except SystemExit:
        pass
loaded = sorted(sys.modules)  # before the probe's own json
import json
print(json.dumps(loaded))
"""


@pytest.mark.parametrize(
    "args",
    [["analyze", "--help"], ["analyze", "inline4"], ["balance", "inline4"]],
    ids=" ".join,
)
def test_cli_import_list_is_lean(args: list[str]) -> None:
    """A fresh ``crankbalance analyze`` or ``balance`` of a preset (or its help) loads none
    of :data:`CLI_MODULES_UNLOADED`, and ``analyze`` none of
    :data:`ANALYZE_MODULES_UNLOADED` (reads ``sys.modules``; times nothing)."""
    out = subprocess.run(
        [sys.executable, "-c", _CLI_MODULES_PROBE, *args],
        capture_output=True,
        text=True,
        check=True,
    )
    loaded = set(json.loads(out.stdout))
    unloaded = CLI_MODULES_UNLOADED + (ANALYZE_MODULES_UNLOADED if args[0] == "analyze" else ())
    unwanted = sorted(
        name for name in loaded if any(name == u or name.startswith(u + ".") for u in unloaded)
    )
    assert not unwanted, f"crankbalance {' '.join(args)} loads {', '.join(unwanted)}"


_EXIT_PROBE = """
import contextlib, gc, io, sys
from crankbalance.cli import main
given = sys.argv[1] == "given"
sys.argv = ["crankbalance", "analyze", "inline4"]
with contextlib.redirect_stdout(io.StringIO()):
    try:
        main(sys.argv[1:] if given else None)
    except SystemExit:
        pass
print(gc.get_freeze_count())
"""


@pytest.mark.parametrize("argv", ["given", "the process's"])
def test_the_command_lines_process_skips_the_last_collection(argv: str) -> None:
    """``main()`` on the process's own command line freezes the collector's objects
    before the process exits (the last collection at exit took about 10 ms of a cold
    start); ``main(argv)`` of a test or a script leaves its process's collector as it was."""
    out = subprocess.run(
        [sys.executable, "-c", _EXIT_PROBE, argv.split()[0]],
        capture_output=True,
        text=True,
        check=True,
    )
    frozen = int(out.stdout)
    if argv == "given":
        assert frozen == 0, f"main(argv) froze {frozen} objects of its caller's process"
    else:
        assert frozen > 10_000, f"main() froze {frozen} objects before exit"


# Transitive purity: importing a physics module must not load an edge, directly or through
# another module (docs: physics is numpy/scipy only). Each module is imported in a fresh
# interpreter of its own; all of them start at once, so the test takes about as long as
# one import.
FORBIDDEN_AT_IMPORT = (
    "pydantic",
    "pint",
    "click",
    "plotly",
    "nicegui",
    "kaleido",
    "crankbalance.schema",
    "crankbalance.units",
    "crankbalance.io",
    "crankbalance.output",
    "crankbalance.studies",
    "crankbalance.cli",
    "crankbalance.web",
)
_PURITY_PROBE = """
import importlib, json, sys
importlib.import_module("crankbalance." + sys.argv[1])
forbidden = sys.argv[2:]
print(json.dumps(sorted(
    name for name in sys.modules
    if any(name == f or name.startswith(f + ".") for f in forbidden)
    and name.count(".") <= 1
)))
"""


@pytest.fixture(scope="module")
def loaded_edges() -> dict[str, list[str]]:
    """Per physics module: the forbidden modules its import loads."""
    children = {
        name: subprocess.Popen(
            [sys.executable, "-c", _PURITY_PROBE, name, *FORBIDDEN_AT_IMPORT],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for name in PHYSICS
    }
    found: dict[str, list[str]] = {}
    for name, child in children.items():
        out, err = child.communicate()
        assert child.returncode == 0, f"import crankbalance.{name} failed:\n{err}"
        found[name] = json.loads(out)
    return found


@pytest.mark.parametrize("name", PHYSICS)
def test_physics_import_loads_no_edge(name: str, loaded_edges: dict[str, list[str]]) -> None:
    loaded = loaded_edges[name]
    assert loaded == [], f"import crankbalance.{name} loads {', '.join(loaded)}"
