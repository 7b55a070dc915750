"""One schema for the settings of every study and every command, with one set of limits.

The command line, the web form and the API all validate a study's settings through these
schemas (:mod:`crankbalance.schema.core`), so that a setting has the same default, the
same limits and the same message everywhere. Quantities are unit strings
(``"8000 kg/m^3"``, ``"400 g"``) parsed to SI floats; plain numbers stay numbers. Every
field has a default (``None`` where the study derives the value from the engine when it is
not given), a title (the label of a form and of a help text), a description (what it
means; ``docs/settings.md`` is written from it) and, where a form shows one, a hint.

Limits. Every value is checked *after* unit conversion: it must be a finite number (no
NaN, no infinity, whatever the unit: ``"1e308 km"`` is refused) inside the physical range
of its kind (:data:`RANGES`), which a setting may narrow (a balance factor from 0 to 2, a
friction coefficient up to 1). Counts and indices are whole numbers within stated bounds;
the work of the long studies is capped (:data:`MAX_BENCH_REVOLUTIONS`, the design points
of a shaft sweep, the balance factors of a sensitivity sweep).

An edge names the fields as its users write them: the CLI as ``--max-mass``, the web form
by its setting key; :func:`parse_options` takes that naming as a function, so that an
error names the field the user typed.

One package, one vocabulary. Its module ``common`` holds what every study shares: the
limits and ranges, the kinds of setting (:func:`quantity`, :func:`whole`, ...), the base
:class:`StudyOptions`, the settings of ``analyze`` and ``balance``, and the parsing and
words by field; all of it is imported from here. The schemas of the other studies live in
modules by family (``counterweight``, ``single``, ``shaft``, ``cycle``, ``crank``,
``shop``, ``explore``) and are imported from here too, ``from crankbalance.schema.settings
import ShopOptions``, but only when first asked for: ``analyze`` and ``balance`` do not
build the other studies' 28 schemas of about 300 fields (about 3 ms of their cold start,
issue 30, docs/performance.md, "Round nine"). :func:`models` gives every study's schema.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .common import *  # noqa: F403 (the shared settings: the studies' vocabulary)
from .common import StudyOptions

if TYPE_CHECKING:  # what __getattr__ imports on first use, for the type checker
    from .counterweight import (
        PROFILE_PARAMETERS as PROFILE_PARAMETERS,
    )
    from .counterweight import (
        CounterweightDesignOptions as CounterweightDesignOptions,
    )
    from .counterweight import (
        CounterweightOptimizeOptions as CounterweightOptimizeOptions,
    )
    from .counterweight import (
        CounterweightOptions as CounterweightOptions,
    )
    from .counterweight import (
        CounterweightRequirementOptions as CounterweightRequirementOptions,
    )
    from .crank import (
        NOT_SWEPT as NOT_SWEPT,
    )
    from .crank import (
        BearingOptions as BearingOptions,
    )
    from .crank import (
        BearingSweepOptions as BearingSweepOptions,
    )
    from .crank import (
        BearingSweepStudyOptions as BearingSweepStudyOptions,
    )
    from .crank import (
        CrankDimensionOptions as CrankDimensionOptions,
    )
    from .crank import (
        MountsOptions as MountsOptions,
    )
    from .crank import (
        Part as Part,
    )
    from .crank import (
        TorsionalOptions as TorsionalOptions,
    )
    from .crank import (
        parse_torsional_stiffness as parse_torsional_stiffness,
    )
    from .cycle import (
        BenchOptions as BenchOptions,
    )
    from .cycle import (
        CombustionOptions as CombustionOptions,
    )
    from .cycle import (
        CycleOptions as CycleOptions,
    )
    from .cycle import (
        FrictionOptions as FrictionOptions,
    )
    from .cycle import (
        PerformanceOptions as PerformanceOptions,
    )
    from .cycle import (
        SensitivityOptions as SensitivityOptions,
    )
    from .explore import (
        EXPLORE_LAYOUTS as EXPLORE_LAYOUTS,
    )
    from .explore import (
        ExploreOptions as ExploreOptions,
    )
    from .explore import (
        PlotOptions as PlotOptions,
    )
    from .shaft import (
        ShaftCheckOptions as ShaftCheckOptions,
    )
    from .shaft import (
        ShaftPlacementOptions as ShaftPlacementOptions,
    )
    from .shaft import (
        ShaftSectionOptions as ShaftSectionOptions,
    )
    from .shaft import (
        ShaftStudyOptions as ShaftStudyOptions,
    )
    from .shop import (
        MAX_SCALE_STEP as MAX_SCALE_STEP,
    )
    from .shop import (
        MAX_SCATTER_SAMPLES as MAX_SCATTER_SAMPLES,
    )
    from .shop import (
        ShopOptions as ShopOptions,
    )
    from .single import (
        BalanceFactorOptions as BalanceFactorOptions,
    )
    from .single import (
        RebalanceOptions as RebalanceOptions,
    )
    from .single import (
        RebalancePartsOptions as RebalancePartsOptions,
    )
    from .single import (
        SingleCylinderOptions as SingleCylinderOptions,
    )
    from .single import (
        ToleranceOptions as ToleranceOptions,
    )

#: the module of this package that defines each of the other studies' names
_MODULES: dict[str, str] = {
    "CounterweightOptions": "counterweight",
    "PROFILE_PARAMETERS": "counterweight",
    "CounterweightRequirementOptions": "counterweight",
    "CounterweightOptimizeOptions": "counterweight",
    "CounterweightDesignOptions": "counterweight",
    "SingleCylinderOptions": "single",
    "RebalanceOptions": "single",
    "BalanceFactorOptions": "single",
    "RebalancePartsOptions": "single",
    "ToleranceOptions": "single",
    "ShaftPlacementOptions": "shaft",
    "ShaftSectionOptions": "shaft",
    "ShaftStudyOptions": "shaft",
    "ShaftCheckOptions": "shaft",
    "PerformanceOptions": "cycle",
    "FrictionOptions": "cycle",
    "BenchOptions": "cycle",
    "CombustionOptions": "cycle",
    "CycleOptions": "cycle",
    "SensitivityOptions": "cycle",
    "CrankDimensionOptions": "crank",
    "BearingOptions": "crank",
    "BearingSweepOptions": "crank",
    "NOT_SWEPT": "crank",
    "BearingSweepStudyOptions": "crank",
    "Part": "crank",
    "parse_torsional_stiffness": "crank",
    "TorsionalOptions": "crank",
    "MountsOptions": "crank",
    "MAX_SCATTER_SAMPLES": "shop",
    "MAX_SCALE_STEP": "shop",
    "ShopOptions": "shop",
    "PlotOptions": "explore",
    "EXPLORE_LAYOUTS": "explore",
    "ExploreOptions": "explore",
}
#: every study's schema, in the order of docs/settings.md
MODELS = (
    "AnalysisOptions",
    "CounterweightOptions",
    "CounterweightRequirementOptions",
    "CounterweightOptimizeOptions",
    "SingleCylinderOptions",
    "RebalanceOptions",
    "ShaftPlacementOptions",
    "PerformanceOptions",
    "BalanceOptions",
    "CounterweightDesignOptions",
    "FrictionOptions",
    "BenchOptions",
    "CombustionOptions",
    "CycleOptions",
    "SensitivityOptions",
    "CrankDimensionOptions",
    "BearingOptions",
    "BearingSweepOptions",
    "BearingSweepStudyOptions",
    "ShaftSectionOptions",
    "ShaftStudyOptions",
    "ShaftCheckOptions",
    "BalanceFactorOptions",
    "RebalancePartsOptions",
    "ShopOptions",
    "ToleranceOptions",
    "PlotOptions",
    "ExploreOptions",
    "TorsionalOptions",
    "MountsOptions",
)


def __getattr__(name: str) -> Any:
    """A name of one of the package's modules, imported when first asked for."""
    if name in _MODULES:
        import importlib

        value = getattr(importlib.import_module(f"{__name__}.{_MODULES[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def models() -> list[type[StudyOptions]]:
    """Every study's settings schema, in the order of :data:`MODELS` (imports them all)."""
    return [__getattr__(n) if n in _MODULES else globals()[n] for n in MODELS]
