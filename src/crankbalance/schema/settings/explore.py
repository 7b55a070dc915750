"""The settings of the figures and of the firing-order explorer.

Part of :mod:`crankbalance.schema.settings`, imported when one of its schemas is first
asked for (see there)."""

from __future__ import annotations

import math
import re
from typing import Any, Literal

from ...errors import InputError
from ...physics.limits import LARGEST_CHUNK, MAX_DRAWS
from ..core import entry, field
from .common import (
    MAX_EXPLORE_CYLINDERS,
    MAX_ORDER,
    RANGES,
    StudyOptions,
    choice,
    factor,
    quantity,
    text,
    whole,
)


def _angle_list(value: str, where: str) -> Any:
    """A list of angles typed as one text with one unit at its end, ``"0,90,270,180 deg"``:
    the unit is given to every number; any other text is read as a list of its own."""
    match = re.fullmatch(r"\s*([-+0-9.eE,\s]+?)\s*(deg|rad)\s*", value)
    if match is None:
        return value
    return [f"{number.strip()} {match.group(2)}" for number in match.group(1).split(",")]


def _plot_order(value: Any, where: str) -> Any:
    """A harmonic order from 1 to :data:`MAX_ORDER`, or ``"rotating"``."""
    if isinstance(value, str) and value.strip().lower() == "rotating":
        return "rotating"
    words = f"a harmonic order from 1 to {MAX_ORDER}, or 'rotating'"
    try:
        number = float(value) if not isinstance(value, bool) else math.nan
    except (TypeError, ValueError):
        raise InputError(where, value, f"must be {words}") from None
    if not (math.isfinite(number) and number == int(number) and 1 <= number <= MAX_ORDER):
        raise InputError(where, value, f"must be {words}")
    return int(number)


class PlotOptions(StudyOptions):
    """``plot``: the settings of the figures that take any."""

    order: int | str = field(
        "any",
        default=1,
        parse=_plot_order,
        metavar="{ORDER|rotating}",
        words=f"a harmonic order from 1 to {MAX_ORDER}, or 'rotating'",
        title="Harmonic order",
        description="The harmonic order of the polar figure, or rotating for the bare "
        "crank's masses.",
    )
    cylinder: int = whole(
        1, "Cylinder", "The cylinder of the single-cylinder figure (1-based).", ge=1, le=10_000
    )
    balance_factor: float = factor(
        0.5, "Balance factor", "The balance factor of the single-cylinder figure."
    )


EXPLORE_LAYOUTS = ("inline", "vee", "boxer", "w", "vr", "radial")


class ExploreOptions(StudyOptions):
    """``explore``: the design-space explorer (docs/explorer.md)."""

    layout: Literal["inline", "vee", "boxer", "w", "vr", "radial"] = choice(
        "inline",
        EXPLORE_LAYOUTS,
        "Layout",
        "The layout explored: inline, vee, boxer, w (broad arrow; a W from VR banks with "
        "its engine file), vr or radial.",
    )
    cylinders: int = whole(4, "Cylinders", "Number of cylinders.", ge=1, le=MAX_EXPLORE_CYLINDERS)
    strokes: int = whole(
        4, "Strokes per cycle (2 or 4)", "2 or 4 strokes per working cycle.", ge=2, le=4
    )
    bank_angle: float | None = quantity(
        "angle", None, "Vee or W bank angle", "The vee angle, or the angle between W banks."
    )
    crank: Literal["any", "flat", "cross", "split"] = choice(
        "any",
        ("any", "flat", "cross", "split"),
        "Crank family",
        "The cranks explored: any, flat, cross or split (split pins).",
    )
    fixed_crank: list[float] | None = field(
        "list",
        default=None,
        item=entry("angle", ge=RANGES["angle"][0], le=RANGES["angle"][1]),
        min_items=1,
        max_items=MAX_EXPLORE_CYLINDERS,
        parse=_angle_list,
        title="Fixed crank",
        description="Only the firing orders this crank allows: one throw angle per throw "
        "(per cylinder with crank split), e.g. '0,90,270,180 deg'.",
        hint="empty: every crank of the family",
    )
    mirror: bool = field(
        "flag",
        default=True,
        title="Mirror image the same engine",
        description="An engine numbered from the other end (its mirror image) counts as the "
        "same; off: a distinct engine.",
        hint="off: the mirror image is a distinct engine",
    )
    reversal: bool = field(
        "flag",
        default=False,
        title="Time reversal the same engine",
        description="An engine run backwards (the reverse firing order on the mirrored "
        "crank) counts as the same.",
    )
    list_orders: bool = field(
        "flag",
        default=False,
        title="List the orders of each engine",
        description="List every firing order each engine of the tables stands for (its "
        "equivalent descriptions).",
    )
    target: Literal["none", "counterweights", "primary", "secondary"] = choice(
        "counterweights",
        ("none", "counterweights", "primary", "secondary"),
        "Balancing target",
        "What each candidate is balanced with: none, counterweights, or "
        "primary or secondary shaft pairs.",
    )
    balance_factor: float = factor(
        0.0, "Balance factor", "The balance factor of the candidates' counterweights."
    )
    mode_shape: str = text(
        "uniform",
        "Torsional mode shape",
        "The torsional mode shape of the excitation merit: uniform, linear, or "
        "one weight per cylinder.",
    )
    orders: int = whole(
        8, "Highest order", "The highest harmonic order of the merits.", ge=1, le=MAX_ORDER
    )
    objectives: str = text(
        "F1,M1,F2,M2",
        "Pareto objectives (comma separated)",
        "The columns of the Pareto front, all minimised.",
    )
    filter: str | None = text(
        None, "Filter", "An expression on the columns that a candidate must meet to be kept."
    )
    top: int = whole(
        20, "Rows of the top-N table", "Rows of the table of the best candidates.", ge=1, le=100_000
    )
    top_key: str | None = text(
        None,
        "Column of the top-N table",
        "The column the top-N table is sorted by; empty: residual_M, the "
        "largest moment left after balancing (with target none the first objective).",
    )
    chunk: int | None = whole(
        None,
        "Indices per task (default: chosen from the problem; bounded by memory)",
        "Candidates per task; empty: chosen from the problem.",
        ge=1,
        le=LARGEST_CHUNK,
    )
    workers: int | None = whole(
        None,
        "Workers of a LocalCluster",
        "Run on a dask LocalCluster of this many worker processes.",
        ge=1,
        le=1024,
    )
    scheduler: str | None = text(
        None, "Address of a dask scheduler", "Run on an existing dask cluster, tcp://HOST:PORT."
    )
    connect_timeout: float = quantity(
        "time",
        5.0,
        "Time a scheduler has to answer",
        "The time the scheduler has to answer.",
        ge=0.1,
        le=120.0,
    )
    sample: int | None = whole(
        None,
        "Random draws (search)",
        "Random search: draw this many indices instead of enumerating all.",
        ge=1,
        le=MAX_DRAWS,
    )
    seed: int = whole(0, "Random seed", "Seed of the random search.", ge=0, le=2**32 - 1)
