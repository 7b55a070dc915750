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
    "tolerance",
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
        path = SRC / f"{name}.py"
        bad = imported_modules(path) & EDGES
        assert not bad, f"{name}.py imports edge modules {bad} (DESIGN.md: physics stays pure)"


def test_cli_start_does_not_import_heavy_packages() -> None:
    code = (
        "import sys; import crankbalance.cli; "
        "heavy = [m for m in ('pint', 'scipy', 'plotly', 'nicegui', 'shapely', 'trimesh', "
        "'pymoo', 'matplotlib') if m in sys.modules]; print(','.join(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"imported at CLI start: {out.stdout.strip()}"


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
