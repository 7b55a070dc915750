"""The study tabs of the web application as plain functions (no NiceGUI).

Each takes the page's current computation (an :class:`Computation`: the engine's spec, its
analysis and balancing) and the project's settings (texts as typed), validates the
settings of its form through their model (:mod:`crankbalance.schema.settings`) and runs
the command line's study with those settings through :mod:`crankbalance.studies.registry`:
the same function, the same settings model, the same defaults (the Counterweight design
tab's optimiser is ``counterweight-optimize``, the Single cylinder tab's balance-factor
study and ISO check ``balance-factor`` and ``tolerance``, the Balance shaft tab's placement
``shaft-inline4``, the Performance tab's sweep ``sensitivity``).
A setting's key is its study's prefix and the schema's field name (``cw_population`` is
``population`` of :class:`~crankbalance.schema.settings.CounterweightOptions`); a bad setting
raises :class:`~crankbalance.errors.InputError` whose ``field`` is that key, so that the
page shows the message beside the input.

The tabs run these functions (and the study layer's ``bearing_sweep``, ``shop_study``) in
a worker process (:mod:`.pool`): they are module-level, take and return picklable data,
and their settings (with the work budgets of the schema) are checked in the server before
the run starts (:func:`counterweight_inputs`, :func:`check_single_cylinder`,
:func:`options`). The JSON API's studies run here too (:func:`api_answer`). The fork
server preloads this module.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping
from typing import Any, Protocol

from ..errors import InputError
from ..schema.engine import EngineSpec
from ..schema.settings import (
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

log = logging.getLogger("crankbalance.web")


class Computation(Protocol):
    """What a study of a tab takes from the page's computation
    (:class:`crankbalance.web.computation.Computed`)."""

    spec: EngineSpec
    analysis: Any
    study: Any


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


def _texts(settings: Mapping[str, Any], prefix: str, model: type[StudyOptions]) -> dict[str, Any]:
    """The settings of one form given (non-empty texts) by their field: a list's text split
    into its items."""
    out: dict[str, Any] = {}
    for name in model.FIELDS:
        text = str(settings.get(prefix + name, "")).strip()
        if text:
            out[name] = _split(text) if field_kind(model, name)[0] == "list" else text
    return out


def _run(name: str, engine: Any, values: dict[str, Any], prefix: str) -> Any:
    """Study ``name`` of the registry with the settings given (field -> text); an error
    about one of them names its setting key (the prefix and the field)."""
    from ..studies.registry import run

    return run(name, engine, values, naming=lambda f: prefix + f if f in values else f)


# --------------------------------------------------------------------------- counterweight
def counterweight_requirement(computed: Computation) -> tuple[float, float, float, bool]:
    """(first moment m_c r_c [kg m], counterweight mass [kg], CG radius [m], whether it is
    that of the halves) of the heaviest crank counterweight found by the balancing solver;
    for a crank balanced as a whole (which the balancing leaves without counterweights),
    that of each half balanced on its own, as the command line's ``counterweight optimize
    --engine`` takes it (the last item True)."""
    from ..studies.engine import balance_engine
    from ..studies.requirements import counterweight_requirement as requirement

    study = computed.study
    halves = False
    try:
        moment = requirement(study)
    except InputError:
        study = balance_engine(computed.spec, halves_if_balanced=True)
        moment, halves = requirement(study), True
    radius = float(study.result.counterweights.cg_radius)
    return moment, moment / radius, radius, halves


def counterweight_inputs(computed: Computation, settings: dict[str, Any]) -> tuple[float, Any]:
    """The required first moment [kg m] and the settings of the optimisation
    (:class:`~crankbalance.schema.settings.CounterweightOptimizeOptions` of the study
    ``counterweight-optimize``, its work budget checked), before it starts."""
    from ..studies.registry import parse, study

    required = counterweight_requirement(computed)[0]
    options(settings, CounterweightOptions)  # the form's own checks, named by its keys
    values = _texts(settings, "cw_", CounterweightOptions)
    values["first_moment"] = f"{required!r} kg*m"  # the balancing's, read back exactly
    o = parse(study("counterweight-optimize"), values, lambda f: "cw_" + f)
    return required, o


def optimise(required: float, o: Any) -> Any:
    """The counterweight optimiser (2021 paper, Sec. 4-5) for a required first moment
    [kg m]: the study ``counterweight-optimize`` of the command line with the settings of
    :func:`counterweight_inputs`; its result (the optimiser's designs and front)."""
    from ..studies.registry import execute
    from .pool import report

    def progress(state: Any) -> None:
        report(
            {
                "iteration": state.iteration,
                "iterations": state.n_iterations,
                "evaluated": state.nfev,
                "feasible": state.n_feasible,
                "elapsed": state.elapsed,
            }
        )

    assert abs(o.first_moment - required) <= 1e-12 * required
    return execute(
        "counterweight-optimize", None, o, naming=lambda f: "cw_" + f, progress=progress
    ).optimum


def progress_text(progress: dict[str, Any]) -> str:
    """The optimiser's progress in words, with the time left estimated from the rounds done
    (each round evaluates about as many designs)."""
    done, total = int(progress["iteration"]), int(progress["iterations"])
    elapsed = float(progress["elapsed"])
    left = elapsed / done * (total - done) if done else None
    estimate = "" if left is None else f", about {left:.0f} s left" if left >= 1 else ", <1 s left"
    return (
        f"optimising … round {done} of {total}, {progress['evaluated']:,} designs evaluated "
        f"({progress['feasible']:,} feasible), {elapsed:.1f} s{estimate}"
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
def _single(computed: Computation, settings: dict[str, Any]) -> SingleCylinderOptions:
    o = options(settings, SingleCylinderOptions)
    count = computed.analysis.model.cylinders
    if o.cylinder > count:
        raise InputError(
            "sc_cylinder", o.cylinder, f"must be a whole number from 1 to {count} (the engine's)"
        )
    return o


def single_study(computed: Computation, settings: dict[str, Any]) -> Any:
    """Balance-factor study of one cylinder (Hoem and Røsholm 2016, Sec. 4.1): the study
    ``balance-factor`` of the engine's cylinder at the balance factor."""
    _single(computed, settings)
    given = _texts(settings, "sc_", SingleCylinderOptions)
    values: dict[str, Any] = {k: given[k] for k in ("cylinder", "balance_factor") if k in given}
    return _run("balance-factor", computed.spec, values, "sc_").study


def iso_check(computed: Computation, settings: dict[str, Any]) -> dict[str, Any]:
    """ISO 21940-11 permissible residual unbalance at the engine speed and the verdict: the
    study ``tolerance`` of the engine (its rotor mass, when not given, the crank's rotating
    masses)."""
    _single(computed, settings)
    given = _texts(settings, "sc_", SingleCylinderOptions)
    values: dict[str, Any] = {
        k: given[k] for k in ("grade", "rotor_mass", "residual") if k in given
    }
    result = _run("tolerance", computed.spec, values, "sc_")
    return {
        "grade": result.grade,
        "rotor_mass": result.rotor_mass,
        "speed": result.speed,
        "permissible": result.permissible,
        "verdict": result.verdict,
    }


def rebalance_study(computed: Computation, settings: dict[str, Any]) -> Any:
    """Rebalance the cylinder's share of its throw after new parts (Hoem and Røsholm 2016,
    Sec. 6.4, eight steps): the engine's cylinder with drilled holes
    (:func:`crankbalance.studies.cylinder.rebalance_cylinder`; the command line's
    ``rebalance`` takes a parts file instead)."""
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


def single_cylinder(computed: Computation, settings: dict[str, Any]) -> tuple[Any, Any, Any]:
    """The Single cylinder tab's three results: the balance-factor study, the ISO check and
    the rebalancing (:func:`single_study`, :func:`iso_check`, :func:`rebalance_study`)."""
    return (
        single_study(computed, settings),
        iso_check(computed, settings),
        rebalance_study(computed, settings),
    )


def check_single_cylinder(computed: Computation, settings: dict[str, Any]) -> None:
    """Refuse bad settings of the Single cylinder tab before its study starts."""
    _single(computed, settings)
    options(settings, RebalanceOptions)


# --------------------------------------------------------------------------- balance shaft
#: what the shaft of each order is, in the tab's words
SHAFT_WORDS = {2: "secondary shaft pair", 1: "primary counter-rotating shaft"}


def shaft_placement(computed: Computation, settings: dict[str, Any]) -> tuple[Any, str]:
    """Unbalance-mass placement on a shaft with end bearings (Kim 2018, Sec. 3.1): the study
    ``shaft-inline4`` of the engine (a secondary shaft pair when the engine has a free
    second-order force or moment, else a primary counter-rotating shaft)."""
    options(settings, ShaftPlacementOptions)
    values = _texts(settings, "bs_", ShaftPlacementOptions)
    result = _run("shaft-inline4", computed.spec, values, "bs_")
    return result.studies[0], SHAFT_WORDS[result.requirement.order]


# --------------------------------------------------------------------------- performance
def performance_study(computed: Computation, settings: dict[str, Any]) -> Any:
    """Friction, bearing loads and shaking against the balance factor (Hoem and Røsholm
    2016, Sec. 5) for cylinder 1 of the engine: the study ``sensitivity`` with the tab's
    settings (every indicator over the balance factors, and what it assumed)."""
    options(settings, PerformanceOptions)
    values = _texts(settings, "pf_", PerformanceOptions)
    return _run("sensitivity", computed.spec, values, "pf_")


# --------------------------------------------------------------------------- explorer
def explore(settings: Any, most: int) -> Any:
    """The Explorer tab's run: the study ``explore`` of the command line (no engine: the
    layout's plain engine) with the tab's settings, its Pareto set with the round-off
    tolerance of :func:`crankbalance.physics.explore.rank.tolerances` (ties kept as the
    command line keeps them); the rows of its figure run, every candidate kept by the filter
    (at most ``most``) by increasing top-N key."""
    from ..studies.explorer import explore as explore_study

    return explore_study(None, settings, figure_points=most).figure


# --------------------------------------------------------------------------- the JSON API
def api_answer(
    name: str, engine: Any, values: dict[str, Any], files: dict[str, str]
) -> tuple[int, dict[str, Any]]:
    """The status and JSON answer of a study's API request (:func:`crankbalance.web.api.
    prepare` checked it): the study of the registry with the settings as sent, the files
    sent read from the request alone (:func:`crankbalance.io.reading.given_files`); 422 for
    bad input or a result that is not finite, 500 (logged) for a bug of crankbalance."""
    from ..io.reading import given_files
    from ..studies.registry import run

    try:
        with given_files(files):
            return 200, run(name, engine, values).to_dict()
    except InputError as error:
        return 422, {"error": str(error), "field": error.field}
    except ValueError as error:  # a result that is not finite (ResultError)
        field = getattr(error, "quantity", None)
        return 422, {"error": str(error), "field": field}
    except Exception as error:  # a bug of crankbalance: logged in full, answered 500
        log.exception("POST /api/%s failed", name)
        message = f"internal error ({type(error).__name__}); please report it with the body"
        return 500, {"error": message, "field": None}
