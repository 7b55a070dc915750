"""The page's computation of the current engine: what the tabs (through their context,
:mod:`.context`) and the study functions of :mod:`.studies` read. A module of its own, so
that both can import it without importing the project (:mod:`.project`) that makes it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..schema.engine import EngineSpec


@dataclass
class Computed:
    """The results of one computation of the engine ``spec`` (None where a study failed):
    its analysis (:func:`crankbalance.studies.engine.analyze`) and balancing study
    (:func:`~crankbalance.studies.engine.balance_engine`), and how long they took [s]."""

    spec: EngineSpec
    analysis: Any
    study: Any
    elapsed: float
    error: str = ""
