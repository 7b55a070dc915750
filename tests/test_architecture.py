"""Architecture rules of DESIGN.md that a test can enforce."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import crankbalance

SRC = Path(crankbalance.__file__).parent
PHYSICS = [
    "kinematics",
    "shaking",
    "balancing",
    "single_cylinder",
    "counterweight",
    "beam",
    "counterweight_optimize",
    "balance_shaft",
    "friction",
    "rotor_bench",
    "engine_cycle",
    "tolerance",
]
EDGES = {
    "figures",
    "render",
    "report",
    "io",
    "cli",
    "web",
    "units",
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
        if not path.exists():
            continue
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
