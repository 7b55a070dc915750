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
#: every physics module: numpy/scipy only, no I/O, no units, no edges
PHYSICS = (
    "kinematics",
    "model",
    "shaking",
    "balancing",
    "single_cylinder",
    "counterweight",
    "counterweight_optimize",
    "beam",
    "balance_shaft",
    "friction",
    "rotor_bench",
    "engine_cycle",
    "engine_cycle_all",
    "torsional",
    "main_bearings",
    "tolerance",
    "articulated",
    "explore.orders",
    "explore.merit",
    "explore.rank",
    "shop.planes",
    "shop.scatter",
    "shop.matching",
    "shop.bobweights",
    "shop.holes",
)
EDGES = {
    "figures",
    "render",
    "report",
    "io",
    "cli",
    "web",
    "units",
    "format",
    "pint",
    "plotly",
    "nicegui",
    "click",
    "matplotlib",
}


def imported_modules(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative: from .x import y
                names.add((node.module or "").split(".")[0])
            elif node.module:
                names.add(node.module.split(".")[0])
                if node.module.startswith("crankbalance."):
                    names.add(node.module.split(".")[1])
    return names


def test_physics_modules_do_not_import_edges() -> None:
    for name in PHYSICS:
        path = SRC / f"{name.replace('.', '/')}.py"
        bad = imported_modules(path) & EDGES
        assert not bad, f"{name}.py imports edge modules {bad} (DESIGN.md: physics stays pure)"


#: third-party packages the command line may load, by command (``None``: the start alone,
#: ``crankbalance --help``); everything else (pint, scipy, plotly, nicegui, kaleido,
#: shapely, trimesh, pymoo, matplotlib, ...) must stay unloaded
CLI_PACKAGES: dict[str | None, set[str]] = {
    None: {"click"},
    "analyze": {"click", "numpy", "pydantic", "pydantic_core", "annotated_types"}
    | {"typing_extensions", "typing_inspection"},
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
    "crankbalance.spec",
    "crankbalance.units",
    "crankbalance.io",
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
