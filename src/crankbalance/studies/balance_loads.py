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
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InputError
from ..results import ResultMixin, to_jsonable
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
#: the residual components reported as the free forces left after balancing
RESIDUAL_COMPONENTS = ("rotating", "order1", "order2")
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
    ("order1_force_N", "free F1 N"),
    ("order1_moment_Nm", "free M1 N·m"),
    ("rotating_moment_Nm", "free Mrot N·m"),
)


def case_rows(data: dict[str, Any]) -> list[list[Any]]:
    """One row per case of the JSON (``crankbalance.bearings-sweep/1``), in :data:`COLUMNS`
    order, for the crank model of ``data["crank_model"]``."""
    rows = []
    for case in data["cases"]:
        values = {**case, **case["free_forces"], **case["models"][data["crank_model"]]}
        rows.append([values[key] for key, _ in COLUMNS])
    return rows


@dataclass(frozen=True)
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
        """The largest free force and moment about the crank's mid-point left after
        balancing, per component (the balancing result's time-domain residuals) [N, N m]."""
        out: dict[str, float] = {}
        for name in RESIDUAL_COMPONENTS:
            c = self.study.balance.residual(name)
            out[f"{name}_force_N"] = float(c.force_after)
            out[f"{name}_moment_Nm"] = float(c.moment_after)
        return out


@dataclass(frozen=True, repr=False)
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

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.bearings-sweep/1`` (docs/json.md)."""
        first = self.cases[0].study
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
                    "models": {name: c.metrics(name) for name in c.study.results},
                }
                for c in self.cases
            ],
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
