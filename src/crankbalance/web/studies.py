"""The study tabs of the web application as plain functions (no NiceGUI).

Each takes the current computation (:class:`~.computation.Computed`) and the project's
settings (texts as typed), validates the settings of its study through the one options
schema (:mod:`crankbalance.schema.settings`) and calls the study layer
(:mod:`crankbalance.studies`).
A setting's key is its study's prefix and the schema's field name (``cw_population`` is
``population`` of :class:`~crankbalance.schema.settings.CounterweightOptions`); a bad setting
raises :class:`~crankbalance.errors.InputError` whose ``field`` is that key, so that the
page shows the message beside the input.

The tabs run these functions (and the study layer's ``bearing_sweep``, ``shop_study``) in
a worker process (:mod:`.pool`): they are module-level, take and return picklable data,
and their settings (with the work budgets of the schema) are checked in the server before
the run starts (:func:`counterweight_inputs`, :func:`check_single_cylinder`,
:func:`options`). The fork server preloads this module.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Literal

import numpy as np

from ..errors import InputError
from ..schema.settings import (
    COUNTERWEIGHT_CHILDREN,
    VERBS,
    AnalysisOptions,
    CounterweightOptions,
    Options,
    PerformanceOptions,
    RebalanceOptions,
    ShaftPlacementOptions,
    SingleCylinderOptions,
    StudyOptions,
    allowed,
    field_kind,
    parse_options,
)
from .computation import Computed

#: setting-key prefix -> the options model of that study ("" for the analysis)
PREFIXES: dict[str, type[StudyOptions]] = {
    "": AnalysisOptions,
    "cw_": CounterweightOptions,
    "sc_": SingleCylinderOptions,
    "rb_": RebalanceOptions,
    "bs_": ShaftPlacementOptions,
    "pf_": PerformanceOptions,
}


def _fields() -> dict[str, tuple[str, str, str]]:
    out = {}
    for prefix, model in PREFIXES.items():
        for name, spec in model.FIELDS.items():
            kind, quantity = field_kind(model, name)
            label = spec.title or name
            out[prefix + name] = (label, quantity or kind, spec.hint or allowed(model, name))
    return out


#: every setting of the study tabs: key -> (label, quantity kind or value kind, hint)
SETTING_FIELDS: dict[str, tuple[str, str, str]] = _fields()


def options(settings: dict[str, Any], model: type[Options]) -> Options:
    """The settings of one study, validated; an empty text takes the schema's default when
    that default is "derived from the engine" (None), and is an error otherwise."""
    prefix = next(p for p, m in PREFIXES.items() if m is model)
    values: dict[str, Any] = {}
    for name, spec in model.FIELDS.items():
        key = prefix + name
        text = str(settings.get(key, "")).strip()
        if not text:
            if spec.default is not None:
                raise InputError(key, None, f"must be given: {allowed(model, name)}")
            continue
        kind, _ = field_kind(model, name)
        values[name] = _split(text) if kind == "list" else text
    return parse_options(model, values, _namer(prefix))


def _namer(prefix: str) -> Callable[[str], str]:
    """The setting key of a schema field: its study's prefix and the field's name."""
    return lambda name: prefix + name


def _split(text: str) -> list[str]:
    return [p.strip() for p in text.replace(";", ",").split(",") if p.strip()]


def setting(settings: dict[str, Any], key: str) -> Any:
    """One setting's validated value (its study's other settings must be valid too)."""
    prefix = next(p for p in sorted(PREFIXES, key=len, reverse=True) if key.startswith(p))
    return getattr(options(settings, PREFIXES[prefix]), key[len(prefix) :])


def check_settings(settings: dict[str, Any]) -> dict[str, str]:
    """Messages of the settings that do not validate, by key, in the words of the form
    (:func:`worded`; empty ones are checked when their study runs)."""
    return {
        key: worded(key, error.value, error.allowed)
        for key, error in setting_errors(settings).items()
    }


def setting_errors(settings: dict[str, Any]) -> dict[str, InputError]:
    """The errors of the settings that do not validate, by key, each naming its key and the
    text as given (a saved project's settings line is refused with it). A study's settings
    are validated together, so that a check across them (a work budget) is made with the
    values as typed; a setting refused is left out and the rest validated again."""
    errors: dict[str, InputError] = {}
    for prefix, model in PREFIXES.items():
        texts: dict[str, str] = {}
        given: dict[str, Any] = {}
        for name in model.FIELDS:
            text = str(settings.get(prefix + name, "")).strip()
            if text:
                texts[name] = text
                given[name] = _split(text) if field_kind(model, name)[0] == "list" else text
        while True:
            try:
                parse_options(model, given, _namer(prefix))
                break
            except InputError as error:
                name = error.field[len(prefix) :]
                errors[error.field] = InputError(error.field, texts.get(name), error.allowed)
                if name not in given:  # a check across settings that names an empty one
                    break
                del given[name]
    return errors


def worded(key: str, value: Any, allowed: str) -> str:
    """A message about a setting in the words of the form: its label, the value as typed and
    what is wrong ("Density: '5 kg' has the wrong unit for a density; write e.g. ...")."""
    label = SETTING_FIELDS[key][0] if key in SETTING_FIELDS else key
    if allowed.startswith(VERBS):  # said of the value: "'5 kg' has the wrong unit ..."
        return f"{label} {allowed}" if value is None else f"{label}: {value!r} {allowed}"
    return f"{label}: {allowed}" if value is None else f"{label} ({value!r}): {allowed}"


# --------------------------------------------------------------------------- counterweight
def counterweight_requirement(computed: Computed) -> tuple[float, float, float]:
    """(first moment m_c r_c [kg m], counterweight mass [kg], CG radius [m]) of the heaviest
    crank counterweight found by the balancing solver."""
    from ..studies.requirements import counterweight_requirement as requirement

    moment = requirement(computed.study)
    radius = float(computed.study.result.counterweights.cg_radius)
    return moment, moment / radius, radius


def counterweight_inputs(computed: Computed, settings: dict[str, Any]) -> tuple[float, Any]:
    """The required first moment [kg m] and the validated :class:`CounterweightOptions` of
    an optimisation (its work budget checked), before it starts."""
    required, _mass, _radius = counterweight_requirement(computed)
    return required, options(settings, CounterweightOptions)


def optimise(required: float, o: CounterweightOptions) -> Any:
    """The counterweight optimiser (2021 paper, Sec. 4-5) for a required first moment
    [kg m], with the command line's number of designs per round
    (:data:`~crankbalance.schema.settings.COUNTERWEIGHT_CHILDREN`): the same settings search the
    same designs in both."""
    from ..physics.counterweight_optimize import optimize_counterweight

    return optimize_counterweight(
        required,
        density=o.density,
        max_mass=o.max_mass,
        max_radius=o.max_radius,
        min_balance=o.min_balance,
        iterations=o.iterations,
        population=o.population,
        children=COUNTERWEIGHT_CHILDREN,
        rng=o.seed,
    )


def pick_design(optimum: Any, choice: str) -> Any:
    """A design of an optimum: "least mass", "least radius" or "front k" (1-based)."""
    if choice == "least radius":
        return optimum.least_radius_design
    if choice.startswith("front "):
        k = int(choice.split()[1]) - 1
        return optimum.design(int(optimum.pareto[k]))
    return optimum.least_mass_design


def design_choices(optimum: Any, count: int = 10) -> list[str]:
    n = len(optimum.pareto)
    return ["least mass", "least radius"] + [f"front {k + 1}" for k in range(min(n, 50))]


# --------------------------------------------------------------------------- single cylinder
def _single(computed: Computed, settings: dict[str, Any]) -> SingleCylinderOptions:
    o = options(settings, SingleCylinderOptions)
    count = computed.analysis.model.cylinders
    if o.cylinder > count:
        raise InputError(
            "sc_cylinder", o.cylinder, f"must be a whole number from 1 to {count} (the engine's)"
        )
    return o


def single_study(computed: Computed, settings: dict[str, Any]) -> Any:
    """Balance-factor study of one cylinder (Hoem and Røsholm 2016, Sec. 4.1)."""
    from ..studies.cylinder import cylinder_study

    o = _single(computed, settings)
    return cylinder_study(computed.analysis.model, o.cylinder, o.balance_factor)


def iso_check(computed: Computed, settings: dict[str, Any]) -> dict[str, Any]:
    """ISO 21940-11 permissible residual unbalance at the engine speed and the verdict."""
    from ..studies.cylinder import iso_check as check

    try:
        result = check(computed.analysis.model, _single(computed, settings))
    except InputError as error:
        if error.field == "grade":
            raise InputError("sc_grade", error.value, error.allowed) from None
        raise
    return {name: getattr(result, name) for name in result.__dataclass_fields__}


def rebalance_study(computed: Computed, settings: dict[str, Any]) -> Any:
    """Rebalance the cylinder's share of its throw after new parts (Hoem and Røsholm 2016,
    Sec. 6.4, eight steps)."""
    from ..studies.cylinder import rebalance_cylinder

    model = computed.analysis.model
    try:
        return rebalance_cylinder(
            model, _single(computed, settings), options(settings, RebalanceOptions)
        )
    except InputError as error:
        if error.field == "grade":
            raise InputError("sc_grade", error.value, error.allowed) from None
        raise


def single_cylinder(computed: Computed, settings: dict[str, Any]) -> tuple[Any, Any, Any]:
    """The Single cylinder tab's three results: the balance-factor study, the ISO check and
    the rebalancing (:func:`single_study`, :func:`iso_check`, :func:`rebalance_study`)."""
    return (
        single_study(computed, settings),
        iso_check(computed, settings),
        rebalance_study(computed, settings),
    )


def check_single_cylinder(computed: Computed, settings: dict[str, Any]) -> None:
    """Refuse bad settings of the Single cylinder tab before its study starts."""
    _single(computed, settings)
    options(settings, RebalanceOptions)


# --------------------------------------------------------------------------- balance shaft
def shaft_requirement(computed: Computed, settings: dict[str, Any]) -> tuple[float, float, str]:
    """(first moment of one shaft's mass [kg m], shaft speed [rad/s], which) for the
    placement study, from the balancing solver: a secondary shaft pair when the engine has
    a free second-order force or moment, else a primary counter-rotating shaft."""
    from ..studies.requirements import default_shaft_order
    from ..studies.requirements import shaft_requirement as requirement

    o = options(settings, ShaftPlacementOptions)
    order = default_shaft_order(computed.analysis)
    need = requirement(computed.spec, order, o.length)
    which = "secondary shaft pair" if order == 2 else "primary counter-rotating shaft"
    return need.unbalance, need.speed, which


def shaft_placement(computed: Computed, settings: dict[str, Any]) -> tuple[Any, str]:
    """Unbalance-mass placement on a shaft with end bearings (Kim 2018, Sec. 3.1)."""
    from ..physics.balance_shaft import inline4_study
    from ..physics.beam import ShaftSection

    moment, speed, which = shaft_requirement(computed, settings)
    o = options(settings, ShaftPlacementOptions)
    study = inline4_study(
        moment,
        speed,
        o.length,
        ShaftSection(outer_diameter=o.diameter),
        weight=o.weight,
        positions=np.linspace(0.0, 1.0, o.points),
    )
    return study, which


# --------------------------------------------------------------------------- performance
def performance_study(computed: Computed, settings: dict[str, Any]) -> Any:
    """Friction, bearing loads and shaking against the balance factor (Hoem and Røsholm
    2016, Sec. 5) for one cylinder of the engine (its reciprocating mass, crank radius,
    rod length, speed)."""
    from ..physics.engine_cycle import balance_sensitivity
    from ..schema.settings import CombustionOptions
    from ..studies.crank import rotating_inertia
    from ..studies.performance import arithmetic_checked, cycle_cylinder, pressure_source

    model = computed.analysis.model
    o = options(settings, PerformanceOptions)
    fields = {
        "bore": "pf_bore",
        "crank_inertia": "pf_crank_inertia",
        "journal_diameter": "pf_journal_diameter",
        "friction_coefficient": "pf_friction_coefficient",
    }
    try:
        cylinder = cycle_cylinder(
            model,
            1,
            bore=o.bore,
            crank_inertia=rotating_inertia(model) if o.crank_inertia is None else o.crank_inertia,
            journal_diameter=o.journal_diameter,
            friction_coefficient=o.friction_coefficient,
        )
        pressure = pressure_source(CombustionOptions.parse({}))  # the studies' one default
        with arithmetic_checked("the performance study", "the engine and the tab's settings"):
            return balance_sensitivity(
                cylinder,
                float(model.speed),
                pressure,
                o.balance_factors,
                strokes=_strokes(model.strokes),
                samples_per_revolution=180,
            )
    except InputError as error:
        raise InputError(fields.get(error.field, error.field), error.value, error.allowed) from None


def _strokes(value: Any) -> Literal[2, 4]:
    """The engine's strokes per cycle as the Literal the dynamics API takes."""
    strokes = int(value)
    if strokes == 2:
        return 2
    if strokes == 4:
        return 4
    raise InputError("strokes", value, "2 or 4 strokes per cycle")


# --------------------------------------------------------------------------- explorer
def explore(problem: Any, objectives: tuple[str, str], select: Any, key: str, most: int) -> Any:
    """The Explorer tab's run: every candidate kept (at most ``most``), the Pareto set over
    the two objectives, the rows by increasing column ``key``."""
    from ..physics.explore import merit
    from ..studies.explore import Keep
    from ..studies.explore import run as run_explore

    keep = Keep(objectives=objectives, key=key, n=most)
    return run_explore(problem, merit.merit, select=select, keep=keep)
