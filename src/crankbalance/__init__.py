"""crankbalance: balancing design of reciprocating-engine crank trains.

The public entry points are loaded on first use, so that ``import crankbalance.physics.shaking``
(or any physics module) stays free of the schemas and the unit parser::

    import crankbalance
    result = crankbalance.analyze("inline4")            # free forces and moments
    study = crankbalance.balance_engine("v8-crossplane")  # counterweights and shafts
"""

from __future__ import annotations

from typing import Any

from .errors import InputError

__all__ = ["InputError", "analyze", "balance_engine", "load_engine"]
__version__ = "0.1.0"

_LAZY = {
    "analyze": "crankbalance.studies.engine",
    "balance_engine": "crankbalance.studies.engine",
    "load_engine": "crankbalance.io.engine_file",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'crankbalance' has no attribute {name!r}")
