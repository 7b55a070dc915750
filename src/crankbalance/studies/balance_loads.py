"""Performance against balance for a whole engine: main-bearing loads, friction and crank
bending over counterweight patterns and balance factors (docs/main_bearings.md, "Sweep of
patterns and balance factors"; issue 18 item 4).

Every case is one full balance solve (:func:`crankbalance.studies.engine.balance_engine`
with the pattern and the balance factor as overrides of the engine file's counterweights)
and then the bearing-load study of that balancing result
(:func:`crankbalance.studies.loads.bearing_loads`, both crank models with friction): a case
is exactly the ``bearings`` run with the same settings. The pattern ``none`` is the crank
without counterweights (the engine file's balance shafts kept), one case whatever the
balance factors. The CLI (``crankbalance bearings-sweep``) and the web tab "Crank loads"
call :func:`bearing_sweep`.

Every case also reports the free forces and couples its balancing leaves, every component
and order forward and backward apart, in words with the next step
(:attr:`~crankbalance.physics.balancing.BalanceResult.remaining`), and the study weighs
them in its summary (:meth:`SweepStudy.summary`): the Pareto set over the peak bearing
load and the free first-order force and couple left, and one suggested case by a stated
order of criteria (docs/main_bearings.md, "Which case the summary names").
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..physics.balance_remaining import FACTOR_OPTION, step_words
from ..physics.model import EngineModel
from ..records import record
from ..results import ResultMixin, number, round_off, to_jsonable
from ..schema.engine import EngineSpec
from ..schema.settings import (
    MAX_SWEEP_WORK,
    BearingOptions,
    BearingSweepOptions,
    BearingSweepStudyOptions,
    parse_options,
)
from .engine import BalanceStudy, balance_engine, balance_options, engine_summary
from .loads import BearingStudy, bearing_loads

SCHEMA = "crankbalance.bearings-sweep/1"
#: relative tolerance within which two cases' criteria count as equal in the summary (on
#: top of the engine's round-off for the free force and couple, results.round_off)
TIE = 1e-9
#: the summary's criteria, in the order the suggested case is chosen by: key of a case's
#: numbers, words
CRITERIA = (
    ("first_order_force_N", "free first-order force left"),
    ("first_order_moment_Nm", "free first-order couple left"),
    ("largest_load_N", "peak bearing load"),
)
#: the columns of a case in the CLI's table and CSV and the web tab's table: key of the
#: JSON (a case's, its free forces' or its crank model's), short label
COLUMNS = (
    ("pattern", "pattern"),
    ("balance_factor", "f_b"),
    ("counterweight_mass_kg", "CW kg"),
    ("worst_bearing", "worst"),
    ("largest_load_N", "max N"),
    ("largest_mean_load_N", "mean N"),
    ("largest_journal_moment_Nm", "journal N·m"),
    ("largest_pin_moment_Nm", "pin N·m"),
    ("coulomb_friction_power_W", "friction W"),
    ("rotating_force_N", "Frot N"),
    ("rotating_moment_Nm", "Mrot N·m"),
    ("order1_force_forward_N", "F1+ N"),
    ("order1_force_backward_N", "F1- N"),
    ("order1_moment_forward_Nm", "M1+ N·m"),
    ("order1_moment_backward_Nm", "M1- N·m"),
)


def case_rows(data: dict[str, Any]) -> list[list[Any]]:
    """One row per case of the JSON (``crankbalance.bearings-sweep/1``), in :data:`COLUMNS`
    order, for the crank model of ``data["crank_model"]``."""
    rows = []
    for case in data["cases"]:
        values = {**case, **case["free_forces"], **case["models"][data["crank_model"]]}
        rows.append([values[key] for key, _ in COLUMNS])
    return rows


@record
class SweepCase:
    """One pattern at one balance factor.

    Attributes
    ----------
    pattern : str
        The pattern as given (``all``, ``none``, ``file`` or 0/1 per web).
    balance_factor : float or None
        Balance factor [-]; None for ``none``.
    study : BearingStudy
        Its balancing result, cycle and both crank models with friction.
    """

    pattern: str
    balance_factor: float | None
    study: BearingStudy

    @property
    def counterweight_mass(self) -> float:
        """Mass of all counterweights, the extra crank masses of a single counter-rotating
        primary shaft included [kg]."""
        b = self.study.balance
        return float(
            sum(c.mass.sum() for c in (b.counterweights, b.extra_counterweights) if c is not None)
        )

    def metrics(self, model: str) -> dict[str, Any]:
        """The case's numbers of one crank model (the JSON of :meth:`SweepStudy.to_dict`)."""
        r = self.study.results[model]
        fr = r.friction
        assert fr is not None
        # the first of the bearings within round-off of the largest load (a symmetric crank
        # has pairs of equal bearings)
        worst = int(np.flatnonzero(r.max_load >= r.max_load.max() * (1.0 - 1e-9))[0])
        return {
            "bearings": [
                {
                    "bearing": k + 1,
                    "max_load_N": float(r.max_load[k]),
                    "mean_load_N": float(r.mean_load[k]),
                    "max_journal_moment_Nm": float(r.max_journal_moment[k]),
                    "coulomb_friction_power_W": float(fr.coulomb_power[k]),
                }
                for k in range(r.bearing_position.size)
            ],
            "worst_bearing": worst + 1,
            "largest_load_N": float(r.max_load[worst]),
            "largest_mean_load_N": float(r.mean_load.max()),
            "largest_journal_moment_Nm": float(r.max_journal_moment.max()),
            "largest_pin_moment_Nm": float(r.max_pin_moment.max()),
            "coulomb_friction_power_W": float(fr.coulomb_power.sum()),
            "petroff_friction_power_W": None
            if fr.petroff_power is None
            else float(fr.petroff_power.sum()),
        }

    def free_forces(self) -> dict[str, float]:
        """The free forces and couples (moments about the moment reference point) the
        balancing leaves, every component of its residuals (``rotating``, ``order1``,
        ``order2``, ...): the largest over a revolution and its forward- and
        backward-rotating parts; and the first-order sums the summary weighs
        (:meth:`first_order`) [N, N·m]."""
        out: dict[str, float] = {}
        for c in self.study.balance.residuals:
            name = c.component
            out[f"{name}_force_N"] = float(c.force_after)
            out[f"{name}_moment_Nm"] = float(c.moment_after)
            out[f"{name}_force_forward_N"] = float(c.force_forward_after)
            out[f"{name}_force_backward_N"] = float(c.force_backward_after)
            out[f"{name}_moment_forward_Nm"] = float(c.moment_forward_after)
            out[f"{name}_moment_backward_Nm"] = float(c.moment_backward_after)
        force, moment = self.first_order()
        out["first_order_force_N"] = force
        out["first_order_moment_Nm"] = moment
        return out

    def first_order(self) -> tuple[float, float]:
        """The free first-order force and couple left, as the summary weighs them: the
        rotating masses' (with the counterweights' share that carries them) plus the
        reciprocating first order's, forward and backward, in sum: their largest over a
        revolution when they act in phase, an upper bound of it otherwise [N, N·m]."""
        b = self.study.balance
        rot, o1 = b.residual("rotating"), b.residual("order1")
        return (
            float(rot.force_after + o1.force_after),
            float(rot.moment_after + o1.moment_after),
        )

    @property
    def label(self) -> str:
        """The case in words: its pattern and balance factor."""
        if self.balance_factor is None:
            return "no counterweights (none)" if self.pattern == "none" else self.pattern
        return f"{self.pattern} at balance factor {self.balance_factor:g}"


@record
class SweepSummary(ResultMixin):
    """What the summary of a sweep says (docs/main_bearings.md, "Which case the summary
    names").

    Attributes
    ----------
    pareto : tuple of int
        The cases (indices into :attr:`SweepStudy.cases`) no other case beats on every
        criterion of :data:`CRITERIA` and strictly on one; equal cases all stay.
    suggested : int
        The case with the least free first-order force left, of those the least free
        first-order couple left, of those the lowest peak bearing load (each within
        :data:`TIE` and the engine's round-off).
    lowest_load : int
        The case with the lowest peak bearing load alone.
    text : tuple of str
        The summary in words: the suggested case and the first-order force and couple it
        leaves (with the next step; the higher orders are the same for every case, no
        counterweight acts on them), the Pareto set, and a
        warning when the lowest peak bearing load leaves a larger free first-order force
        or couple than the suggested case.
    warning : str
        That warning, or "".
    """

    pareto: tuple[int, ...]
    suggested: int
    lowest_load: int
    text: tuple[str, ...]
    warning: str


def criteria(cases: Sequence[SweepCase], model: str) -> NDArray[np.float64]:
    """The summary's criteria of every case (:data:`CRITERIA`), shape (cases, 3):
    free first-order force [N], couple [N·m], peak bearing load of ``model`` [N]."""
    rows = []
    for c in cases:
        force, moment = c.first_order()
        rows.append((force, moment, float(c.study.results[model].max_load.max())))
    return np.array(rows, dtype=float)


def tie_levels(values: NDArray[np.float64], model: EngineModel) -> NDArray[np.float64]:
    """How far apart two cases' criteria may be and still count as equal: :data:`TIE` of
    each criterion's largest value, and at least the engine's round-off for the free force
    and couple (:func:`crankbalance.results.round_off`)."""
    force, moment = round_off(model)
    return np.maximum(TIE * np.abs(values).max(axis=0), (force, moment, 0.0))


def summarize(
    cases: Sequence[SweepCase], model: str, factor_name: str = FACTOR_OPTION
) -> SweepSummary:
    """Weigh the cases of a sweep: their Pareto set over the peak bearing load and the free
    first-order force and couple left, the suggested case by the stated order of criteria,
    and the summary in words.

    Parameters
    ----------
    cases : sequence of SweepCase
        The sweep's cases (at least one).
    model : str
        The crank model whose peak bearing load counts.
    factor_name : str, optional
        How the reader's surface names the balance factor in a next step (the command
        line's option; the web's form label).

    Returns
    -------
    SweepSummary
        The Pareto set, the suggested case, the lowest-load case and the text.
    """
    values = criteria(cases, model)
    tie = tie_levels(values, cases[0].study.model)
    count = len(cases)

    def beats(a: int, b: int) -> bool:
        no_worse = np.all(values[a] <= values[b] + tie)
        better = np.any(values[a] < values[b] - tie)
        return bool(no_worse and better)

    pareto = tuple(i for i in range(count) if not any(beats(j, i) for j in range(count)))
    left = list(range(count))
    for k in range(values.shape[1]):  # the stated order of criteria
        best = min(values[i, k] for i in left)
        left = [i for i in left if values[i, k] <= best + tie[k]]
    suggested = left[0]
    loads = values[:, 2]
    lowest = int(np.flatnonzero(loads <= loads.min() + tie[2])[0])
    chosen = cases[suggested]
    load = chosen.metrics(model)
    text = [
        f"Suggested: {chosen.label} (least free first-order force left, then couple, then "
        f"peak bearing load): {number(load['largest_load_N'], 5)} N on bearing "
        f"{load['worst_bearing']}, free first-order force {number(values[suggested, 0])} N and "
        f"couple {number(values[suggested, 1])} N·m left."
    ]
    for r in chosen.study.balance.remaining:
        if r.order == 1:  # higher orders: the same for every case (no counterweight acts)
            text.append(
                f"It leaves the {r.text}; next step: {step_words(r.step_format, factor_name)}."
            )
    text.append(
        "Pareto set (peak bearing load, free first-order force and couple left): "
        + "; ".join(cases[i].label for i in pareto)
        + "."
    )
    warning = ""
    if any(values[lowest, k] > values[suggested, k] + tie[k] for k in (0, 1)):
        low = cases[lowest]
        warning = (
            f"the lowest peak bearing load, {low.label} ({number(loads[lowest], 5)} N), leaves "
            f"a free first-order force of {number(values[lowest, 0])} N and couple of "
            f"{number(values[lowest, 1])} N·m, where {chosen.label} leaves "
            f"{number(values[suggested, 0])} N and {number(values[suggested, 1])} N·m"
        )
        text.append(f"Warning: {warning}.")
    return SweepSummary(pareto, suggested, lowest, tuple(text), warning)


@record(repr=False)
class SweepStudy(ResultMixin):
    """Bearing loads of one engine over counterweight patterns and balance factors (see
    :func:`bearing_sweep`).

    Attributes
    ----------
    options : BearingSweepOptions
        The patterns, balance factors and the crank model shown.
    bearing_options : BearingOptions
        The loads' settings, the same for every case.
    cases : tuple of SweepCase
        Pattern by pattern in the order given, each over the balance factors in order.
    """

    options: BearingSweepOptions
    bearing_options: BearingOptions
    cases: tuple[SweepCase, ...]

    def of(self, pattern: str) -> tuple[SweepCase, ...]:
        """The cases of one pattern, over the balance factors."""
        return tuple(c for c in self.cases if c.pattern == pattern)

    def summary(self, factor_name: str = FACTOR_OPTION) -> SweepSummary:
        """The cases weighed (:func:`summarize`) with the sweep's crank model, a next step
        naming the balance factor ``factor_name``."""
        return summarize(self.cases, self.options.crank_model, factor_name)

    def headline(self) -> tuple[str, ...]:
        """The suggested case and the Pareto set, in words (:meth:`summary`)."""
        return self.summary().text

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.bearings-sweep/1`` (docs/json.md)."""
        first = self.cases[0].study
        summary = self.summary()
        settings = first.to_dict()["settings"]
        out = {
            "schema": SCHEMA,
            "engine": engine_summary(first.model),
            "settings": settings,
            "crank_model": self.options.crank_model,
            "bearing_position_m": first.bearing_positions,
            "cases": [
                {
                    "pattern": c.pattern,
                    "balance_factor": c.balance_factor,
                    "webs": None
                    if c.study.balance.counterweights is None
                    else c.study.balance.counterweights.web,
                    "counterweight_count": 0
                    if c.study.balance.counterweights is None
                    else c.study.balance.counterweights.count,
                    "counterweight_mass_kg": c.counterweight_mass,
                    "free_forces": c.free_forces(),
                    "remaining": [
                        {
                            "component": r.component,
                            "order": r.order,
                            "quantity": r.quantity,
                            "rotation": r.rotation,
                            "amount": r.amount,
                            "text": r.text,
                            "next_step": r.next_step,
                        }
                        for r in c.study.balance.remaining
                    ],
                    "models": {name: c.metrics(name) for name in c.study.results},
                }
                for c in self.cases
            ],
            "summary": {
                "criteria": [key for key, _ in CRITERIA],
                "pareto": list(summary.pareto),
                "suggested": summary.suggested,
                "lowest_load": summary.lowest_load,
                "text": list(summary.text),
                "warning": summary.warning or None,
            },
        }
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def _no_counterweights(spec: EngineSpec) -> BalanceStudy:
    """The engine's balancing without crank counterweights (its balance shafts kept)."""
    from ..physics.balancing import balance
    from .build import build_model

    model = build_model(spec)
    _cw, primary, secondary = balance_options(spec)
    return BalanceStudy(model, balance(model, None, primary, secondary))


def check_sweep_work(spec: EngineSpec, sweep: BearingSweepOptions, options: BearingOptions) -> None:
    """Refuse a sweep over its work budget before any case: cases x samples per revolution
    x cylinders at most :data:`~crankbalance.schema.settings.MAX_SWEEP_WORK`.

    Parameters
    ----------
    spec : EngineSpec
        The engine.
    sweep : BearingSweepOptions
        Patterns and balance factors (``none`` is one case).
    options : BearingOptions
        The loads' settings (their samples per revolution).

    Raises
    ------
    InputError
        Naming ``samples``, with the product and the budget.
    """
    cases = sum(1 if p == "none" else len(sweep.balance_factors) for p in sweep.patterns)
    cylinders = spec.crank_train.cylinder_count
    work = cases * options.samples * cylinders
    if work > MAX_SWEEP_WORK:
        raise InputError(
            "samples",
            options.samples,
            f"must keep cases x samples per revolution x cylinders at most {MAX_SWEEP_WORK:,}, "
            f"the sweep's work budget (here {cases} x {options.samples} x {cylinders} = "
            f"{work:,}): fewer samples, patterns or balance factors",
        )


def bearing_sweep(
    engine: str | os.PathLike[str] | EngineSpec,
    sweep: BearingSweepOptions | Mapping[str, Any] | None = None,
    options: BearingOptions | Mapping[str, Any] | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> SweepStudy:
    """Main-bearing loads, friction and crank bending of an engine for every counterweight
    pattern at every balance factor.

    Parameters
    ----------
    engine : str, path or EngineSpec
        Preset name, engine file or validated spec.
    sweep : BearingSweepOptions or mapping, optional
        Patterns, balance factors (:class:`crankbalance.schema.settings.BearingSweepOptions`).
    options : BearingOptions or mapping, optional
        The loads' settings; their ``webs`` and ``balance_factor`` must be empty (swept).
    progress : callable, optional
        Called with (cases done, cases) after each case.

    Returns
    -------
    SweepStudy
        One case per pattern and balance factor (one for ``none``).
    """
    from ..io.engine_file import load_engine

    s = (
        sweep
        if isinstance(sweep, BearingSweepOptions)
        else parse_options(BearingSweepOptions, dict(sweep or {}))
    )
    o = (
        options
        if isinstance(options, BearingOptions)
        else parse_options(BearingOptions, dict(options or {}))
    )
    for name in ("webs", "balance_factor"):
        if getattr(o, name) is not None:
            raise InputError(name, getattr(o, name), "is swept here; leave it empty")
    spec = engine if isinstance(engine, EngineSpec) else load_engine(engine)
    plan: list[tuple[str, float | None]] = []
    for pattern in s.patterns:
        if pattern == "none":
            plan.append((pattern, None))
        else:
            plan.extend((pattern, float(f)) for f in s.balance_factors)
    check_sweep_work(spec, s, o)
    cases: list[SweepCase] = []
    for pattern, factor in plan:
        if factor is None:
            solved = _no_counterweights(spec)
        else:
            overrides: dict[str, Any] = {"balance_factor": factor}
            if pattern == "all":
                overrides["webs"] = None
            elif pattern != "file":
                overrides["webs"] = tuple(int(v) for v in pattern.split(","))
            try:
                solved = balance_engine(spec, halves_if_balanced=True, **overrides)
            except InputError as error:
                if error.field != "counterweights.webs" or pattern == "file":
                    raise
                raise InputError("patterns", pattern, error.allowed) from None
        cases.append(SweepCase(pattern, factor, bearing_loads(spec, o, balance=solved)))
        if progress is not None:
            progress(len(cases), len(plan))
    return SweepStudy(options=s, bearing_options=o, cases=tuple(cases))


def bearings_sweep(
    engine: str | os.PathLike[str] | EngineSpec,
    settings: BearingSweepStudyOptions,
    *,
    progress: Callable[[int, int], None] | None = None,
) -> SweepStudy:
    """The ``bearings-sweep`` study of the registry: :func:`bearing_sweep` of one settings
    object, the sweep's and the loads' (a combustion setting that would not act refused, an
    error of the physics named by its setting)."""
    from .loads import named_setting, refuse_without_gas

    loads = settings.loads()
    refuse_without_gas(loads)
    try:
        study = bearing_sweep(engine, settings.sweep(), loads, progress)
    except InputError as error:
        if error.field == "patterns":
            raise
        raise named_setting(loads, error) from None
    study.to_dict()  # checked finite
    return study
