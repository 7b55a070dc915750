"""The figures package (docs/figures_reports.md): one module per study, every figure builder
also a name of the package, and importing it loads no plotly."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import subprocess
import sys

import crankbalance.output.figures as figures

#: the study modules of the package (common.py holds what they share and draws no figure)
STUDY_MODULES = tuple(
    importlib.import_module(f"{figures.__name__}.{info.name}")
    for info in pkgutil.iter_modules(figures.__path__)
    if info.name != "common"
)


def builders(module: object) -> dict[str, object]:
    """The public functions of ``module`` defined there that return a plotly Figure."""
    return {
        name: obj
        for name, obj in vars(module).items()
        if inspect.isfunction(obj)
        and not name.startswith("_")
        and obj.__module__ == module.__name__  # type: ignore[attr-defined]
        and obj.__annotations__.get("return") == "go.Figure"
    }


def test_every_builder_is_a_name_of_the_package() -> None:
    found = {}
    for module in STUDY_MODULES:
        found |= builders(module)
    assert len(found) >= 23, sorted(found)
    missing = sorted(set(found) - set(figures.__all__))
    assert not missing, f"builders the package does not offer: {missing}"
    for name, builder in found.items():
        assert getattr(figures, name) is builder, name


def test_every_name_of_the_package_comes_from_its_study_module() -> None:
    owners = {
        name: m
        for m in STUDY_MODULES
        for name, obj in vars(m).items()
        if getattr(obj, "__module__", None) == m.__name__
    }
    for name in figures.__all__:
        assert getattr(figures, name) is getattr(owners[name], name), name


def test_importing_the_figures_loads_no_plotly() -> None:
    """Importing the package (every study module) stays cheap: plotly is imported when a
    figure is built, not before."""
    probe = (
        "import sys, crankbalance.output.figures\n"
        "print(sorted(n for n in sys.modules if n.split('.')[0] in ('plotly', 'kaleido')))\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
