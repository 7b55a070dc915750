"""The studies of crankbalance, one entry each: the command line, the JSON API and the web
application look a study up here, parse its settings through the one model and call the
one function (docs/architecture.md, "Studies: one function each").

A study's **name** is its command, with a subcommand joined by a dash: ``analyze``,
``balance-factor``, ``counterweight-optimize``, ``shaft-inline4``, ``shop-match``. Its
**function** takes the engine (a preset name, an engine file, a spec or a model; none for
the studies without one) and one **settings** object, the study's model in
:mod:`crankbalance.schema.settings`, and returns one result whose ``to_dict()`` is the JSON
the command line prints with ``--format json`` (its ``"schema"`` key included). A
setting's **option** is its field's name with dashes (``balance_factor`` is
``--balance-factor`` on the command line and ``"balance-factor"`` in an API body) unless
:attr:`Study.options` names it otherwise (``patterns`` is ``--pattern``).

This module imports no study and no settings model until one is used, so that a command
starts with click alone.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import field
from typing import TYPE_CHECKING, Any, Literal

from ..errors import InputError
from ..records import record

if TYPE_CHECKING:
    from ..schema.settings import StudyOptions
    from .engine import EngineLike

#: whether a study takes an engine: always, when given, or never
EngineUse = Literal["required", "optional", "none"]


@record
class Study:
    """One study of the registry.

    Attributes
    ----------
    name : str
        The study's name: its command, a subcommand joined by a dash (``shop-match``).
    command : tuple of str
        The command line's words (``("shop", "match")``).
    function : str
        ``"module:function"`` of the study function in :mod:`crankbalance.studies`.
    settings : str
        The name of its settings model in :mod:`crankbalance.schema.settings`.
    engine : {"required", "optional", "none"}
        Whether it takes an engine.
    fields : tuple of str, optional
        The settings it takes when it takes only some of its model's (the subcommands of
        ``shop`` and ``shaft`` share one model); empty: all of them.
    exclude : tuple of str, optional
        Settings of its model it does not take.
    options : dict of str to str
        Field -> option where the option is not the field with dashes.
    edge : tuple of str
        The command's options that are not settings: output format, output files, progress
        (the command line's alone; the API refuses them).
    heavy : bool
        Whether the API runs it in a worker process (:mod:`crankbalance.web.pool`).
    files : tuple of str
        Settings that name files; the API takes their content (``{"name", "text"}``).
    local : tuple of str
        Settings that act on the machine that computes (dask workers and schedulers); the
        API refuses them.
    arguments : tuple of str
        Settings the command line takes as arguments rather than options (the parts file
        of ``shop match``); the API takes them by name as every other setting.
    """

    name: str
    command: tuple[str, ...]
    function: str
    settings: str
    engine: EngineUse
    fields: tuple[str, ...] = ()
    exclude: tuple[str, ...] = ()
    options: dict[str, str] = field(default_factory=dict)
    edge: tuple[str, ...] = ("format",)
    heavy: bool = False
    files: tuple[str, ...] = ()
    local: tuple[str, ...] = ()
    arguments: tuple[str, ...] = ()

    def load(self) -> Callable[..., Any]:
        """The study function."""
        module, _, attribute = self.function.partition(":")
        function = getattr(importlib.import_module(module), attribute)
        assert callable(function)
        return function

    def model(self) -> type[StudyOptions]:
        """The settings model."""
        from ..schema import settings

        model = getattr(settings, self.settings)
        assert isinstance(model, type) and issubclass(model, settings.StudyOptions)
        return model

    def field_names(self) -> tuple[str, ...]:
        """The settings the study takes, in the model's order."""
        names = tuple(self.model().FIELDS)
        if self.fields:
            names = tuple(n for n in names if n in self.fields)
        return tuple(n for n in names if n not in self.exclude)

    def option(self, name: str) -> str:
        """The option of a setting, without dashes: ``balance_factor`` -> ``balance-factor``."""
        if name in self.options:
            return self.options[name]
        return name.replace("_", "-")

    def field_of(self, option: str) -> str | None:
        """The setting of an option (without dashes), or None for another option."""
        found = {self.option(name): name for name in self.field_names()}
        return found.get(option)


def _shop(command: str, fields: tuple[str, ...], **more: Any) -> Study:
    return Study(
        f"shop-{command}",
        ("shop", command),
        f"crankbalance.studies.shop:shop_{command}",
        "ShopOptions",
        more.pop("engine", "required"),
        fields=fields,
        files=("parts",),
        **more,
    )


#: the settings of a shop study that reads a parts file: the matching and bob-weights
_PARTS = ("parts", "method", "time_limit", "journals", "fraction")
#: the settings of the hole plan and its ISO check
_PLAN = (
    "reading",
    "convention",
    "measuring_planes",
    "correction_planes",
    "hole_diameter",
    "hole_radius",
    "max_depth",
    "web_thickness",
    "depth_to",
    "point_angle",
    "direction",
    "spacing",
    "depth_resolution",
    "density",
    "slug_density",
    "grade",
    "rotor_mass",
    "speed",
    "bearings",
    "center_of_mass",
)
#: the settings of the shaft placement studies (inline4 and inline3)
_SHAFT = (
    "length",
    "diameter",
    "bore",
    "modulus",
    "density",
    "poisson",
    "unbalance_radius",
    "bearing_stiffness",
    "theory",
    "unbalance",
    "speed",
    "weight",
    "weights",
    "points",
    "secondary",
)
#: the profile of a counterweight design and its material
_DESIGN = (
    "first_moment",
    "cw_mass",
    "cg_radius",
    "web_radius",
    "rectangle_height",
    "trapezoid_angle",
    "segment_radius",
    "segment_angle",
    "thickness",
    "density",
)
#: the cycle's settings of one cylinder only (``sensitivity`` has no flywheel sizing)
_CYCLE_ONLY = ("flywheel_inertia", "speed_fluctuation_target", "balance_factor")

STUDIES: dict[str, Study] = {
    s.name: s
    for s in (
        Study(
            "analyze",
            ("analyze",),
            "crankbalance.studies.engine:analysis",
            "AnalysisOptions",
            "required",
            edge=("format",),
        ),
        Study(
            "balance",
            ("balance",),
            "crankbalance.studies.engine:balancing",
            "BalanceOptions",
            "required",
        ),
        Study(
            "balance-factor",
            ("balance-factor",),
            "crankbalance.studies.single:balance_factor",
            "BalanceFactorOptions",
            "optional",
        ),
        Study(
            "rebalance",
            ("rebalance",),
            "crankbalance.studies.single:rebalance",
            "RebalancePartsOptions",
            "none",
            files=("parts",),
        ),
        Study(
            "tolerance",
            ("tolerance",),
            "crankbalance.studies.single:tolerance",
            "ToleranceOptions",
            "optional",
            options={"list_grades": "list"},
        ),
        Study(
            "counterweight-optimize",
            ("counterweight", "optimize"),
            "crankbalance.studies.counterweight:optimize",
            "CounterweightOptimizeOptions",
            "optional",
            edge=("format", "quiet"),
            heavy=True,
        ),
        Study(
            "counterweight-show",
            ("counterweight", "show"),
            "crankbalance.studies.counterweight:show",
            "CounterweightDesignOptions",
            "optional",
            fields=_DESIGN,
            edge=("format", "plot"),
        ),
        Study(
            "shaft-inline4",
            ("shaft", "inline4"),
            "crankbalance.studies.shaft:inline4",
            "ShaftStudyOptions",
            "optional",
            fields=(*_SHAFT, "order"),
            heavy=True,
        ),
        Study(
            "shaft-inline3",
            ("shaft", "inline3"),
            "crankbalance.studies.shaft:inline3",
            "ShaftStudyOptions",
            "optional",
            fields=(*_SHAFT, "type", "hold", "bearing_offset", "z_min"),
            heavy=True,
        ),
        Study(
            "shaft-check",
            ("shaft", "check"),
            "crankbalance.studies.shaft:check",
            "ShaftCheckOptions",
            "none",
        ),
        Study(
            "friction",
            ("friction",),
            "crankbalance.studies.friction:friction",
            "FrictionOptions",
            "none",
        ),
        Study(
            "bench",
            ("bench",),
            "crankbalance.studies.friction:bench",
            "BenchOptions",
            "none",
            edge=("format", "history"),
            heavy=True,
        ),
        Study(
            "cycle",
            ("cycle",),
            "crankbalance.studies.cycle:cycle",
            "CycleOptions",
            "optional",
            edge=("format", "plot"),
            heavy=True,
            files=("pressure_csv",),
        ),
        Study(
            "sensitivity",
            ("sensitivity",),
            "crankbalance.studies.cycle:sensitivity",
            "SensitivityOptions",
            "optional",
            exclude=_CYCLE_ONLY,
            heavy=True,
            files=("pressure_csv",),
        ),
        Study(
            "bearings",
            ("bearings",),
            "crankbalance.studies.loads:bearings",
            "BearingOptions",
            "required",
            edge=("format", "plot"),
            heavy=True,
            files=("pressure_csv",),
        ),
        Study(
            "bearings-sweep",
            ("bearings-sweep",),
            "crankbalance.studies.balance_loads:bearings_sweep",
            "BearingSweepStudyOptions",
            "required",
            exclude=("balance_factor", "webs", "curves"),
            options={"patterns": "pattern"},
            edge=("format", "plot"),
            heavy=True,
            files=("pressure_csv",),
        ),
        Study(
            "torsional",
            ("torsional",),
            "crankbalance.studies.torsional:torsional",
            "TorsionalOptions",
            "required",
            edge=("format", "plot"),
            heavy=True,
            files=("pressure_csv",),
        ),
        Study(
            "mounts",
            ("mounts",),
            "crankbalance.studies.mounts:mounts",
            "MountsOptions",
            "required",
            options={"compare_patterns": "compare-pattern"},
            edge=("format", "plot", "quiet"),
            files=("pressure_csv",),
            heavy=True,
        ),
        Study(
            "explore",
            ("explore",),
            "crankbalance.studies.explorer:explore",
            "ExploreOptions",
            "optional",
            edge=("format", "output", "progress", "plot"),
            heavy=True,
            local=("workers", "scheduler", "connect_timeout"),
        ),
        _shop("match", _PARTS, heavy=True, arguments=("parts",)),
        _shop("bobweights", _PARTS, heavy=True, arguments=("parts",)),
        _shop("plan", _PLAN, engine="optional"),
        _shop(
            "scatter",
            (
                "parts",
                "fraction",
                "correction_planes",
                "rotor_mass",
                "grade",
                "speed",
                "bearings",
                "samples",
                "seed",
                "scale_step",
            ),
            heavy=True,
            arguments=("parts",),
        ),
    )
}

#: the commands that compute something but are no study of their own, and why: an output
#: of a study (a figure, a report, a file written from a design) or a listing
NOT_STUDIES: dict[tuple[str, ...], str] = {
    ("presets",): "lists the built-in engines (GET /api/presets)",
    ("plot",): "draws a figure of the analysis, the balancing or a single-cylinder study",
    ("report",): "writes the report of the analysis and the balancing (HTML or PDF)",
    ("web",): "serves the web application",
    ("counterweight", "export"): "writes the design of counterweight-show to a CAD file",
    ("counterweight", "check"): "reads a CAD file: the mass properties of a part made "
    "from a counterweight-show design",
    ("shop", "sheet"): "writes the printable sheet of the shop-match and shop-plan studies",
}


def study(name: str) -> Study:
    """The study of a name; :class:`InputError` naming the known ones for another."""
    if name not in STUDIES:
        raise InputError("study", name, f"must be one of: {', '.join(STUDIES)}")
    return STUDIES[name]


def parse(
    entry: Study, values: Mapping[str, Any], name: Callable[[str], str] | None = None
) -> StudyOptions:
    """The study's settings from ``values`` (field -> value as typed: a text, a number, a
    list); an error names the setting by ``name(field)`` (default: its option). A value of
    None is not given."""
    from ..schema.settings import parse_options

    namer = name or entry.option
    known = entry.field_names()
    for key, value in values.items():
        if key not in known and value is not None:
            raise InputError(
                namer(key),
                value,
                f"is not a setting of {entry.name}; its settings: "
                + ", ".join(entry.option(n) for n in known),
            )
    return parse_options(entry.model(), values, namer)


@contextmanager
def named(
    entry: Study,
    values: Mapping[str, Any],
    settings: StudyOptions,
    name: Callable[[str], str] | None = None,
) -> Iterator[None]:
    """Within the block, an :class:`InputError` of the study about one of its settings (or
    its engine) names the setting by ``name(field)`` (default: its option) and shows the
    value as it was given (``values``) when the error holds the setting's value."""
    with named_fields(entry.field_names(), values, settings, name or entry.option):
        yield


@contextmanager
def named_fields(
    fields: Iterable[str],
    values: Mapping[str, Any],
    settings: StudyOptions,
    name: Callable[[str], str],
) -> Iterator[None]:
    """:func:`named` for the settings ``fields`` of a model."""
    known = set(fields)
    try:
        yield
    except InputError as error:
        field_ = error.field
        if field_ != "engine" and field_ not in known:
            raise
        value = error.value
        typed = values.get(field_)
        if typed is not None and field_ != "engine" and _same(value, getattr(settings, field_)):
            value = typed
        raise InputError(name(field_), value, error.allowed) from None


def _same(a: Any, b: Any) -> bool:
    try:
        return bool(a == b)
    except Exception:  # arrays and other values without a plain equality
        return False


def run(
    name: str,
    engine: EngineLike | None,
    values: Mapping[str, Any],
    *,
    naming: Callable[[str], str] | None = None,
    **edge: Any,
) -> Any:
    """Run study ``name`` on ``engine`` (None for the studies without one) with ``values``
    (field -> value as typed) and the edge's own arguments (``progress``, ``output``):
    parse the settings, call the study function, name an error's setting as the edge does
    (``naming``, default: the option without dashes)."""
    entry = study(name)
    settings = parse(entry, values, naming or entry.option)
    return execute(name, engine, settings, values=values, naming=naming, **edge)


def execute(
    name: str,
    engine: EngineLike | None,
    settings: StudyOptions,
    *,
    values: Mapping[str, Any] | None = None,
    naming: Callable[[str], str] | None = None,
    **edge: Any,
) -> Any:
    """Call the function of study ``name`` with its settings already parsed (an instance of
    its model); an error about a setting is named as :func:`run` names it (``values``: the
    settings as typed, shown in its messages)."""
    entry = study(name)
    namer = naming or entry.option
    if not isinstance(settings, entry.model()):
        raise TypeError(f"{name} takes {entry.settings}, not {type(settings).__name__}")
    if entry.engine == "required" and engine is None:
        raise InputError(namer("engine"), None, "the engine file or preset is needed")
    if entry.engine == "none" and engine is not None:
        raise InputError(namer("engine"), engine, f"{entry.name} takes no engine")
    function = entry.load()
    with named(entry, values or {}, settings, namer):
        if entry.engine == "none":
            return function(settings, **edge)
        return function(engine, settings, **edge)
