"""crankbalance: balancing design of reciprocating-engine crank trains.

The public entry points are loaded on first use, so that ``import crankbalance.physics.shaking``
(or any physics module) stays free of the schemas and the unit parser::

    import crankbalance
    result = crankbalance.analyze("inline4")            # free forces and moments
    study = crankbalance.balance_engine("v8-crossplane")  # counterweights and shafts
    figures = crankbalance.plot(result)                 # the study's plotly figures
    loads = crankbalance.run("bearings", "inline4", {"speed": "4000 rpm"})  # any study

Every result displays itself in a notebook (a few lines as ``repr``, tables with units as
HTML); a number with a unit is given as a text (``"4000 rpm"``) or a pint quantity.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .errors import InputError

if TYPE_CHECKING:
    from .io.engine_file import load_engine
    from .output.figures import plot
    from .studies.engine import analyze, balance_engine
    from .studies.registry import run

__all__ = ["InputError", "analyze", "balance_engine", "load_engine", "plot", "run"]
__version__ = "0.1.0"

_LAZY = {
    "analyze": "crankbalance.studies.engine",
    "balance_engine": "crankbalance.studies.engine",
    "load_engine": "crankbalance.io.engine_file",
    "plot": "crankbalance.output.figures",
    "run": "crankbalance.studies.registry",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'crankbalance' has no attribute {name!r}")


def __dir__() -> list[str]:
    """The public API (what ``dir(crankbalance)`` and autocompletion show)."""
    return sorted([*__all__, "__version__"])
