"""The analysis study: from an engine (file, preset, spec or model) to its free forces and
moments, in the JSON contract ``crankbalance.analysis/4`` (docs/json.md)."""

from __future__ import annotations

import functools
import math
import os
from collections.abc import Sequence
from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np

from ..io.engine_file import load_engine
from ..output.format import keyed, moment_point, text
from ..physics.model import EngineModel, with_moment_point
from ..physics.shaking import Curves, FreeForces, curves, free_forces
from ..records import record
from ..results import ResultMixin, round_off, to_jsonable
from ..schema.engine import EngineSpec
from ..schema.settings import AnalysisOptions, parse_options
from .build import BUILD_CACHE, build_model

if TYPE_CHECKING:  # the verification and the solver are imported when asked for
    from numpy.typing import ArrayLike, NDArray

    from ..physics.balance_check import Verification
    from ..physics.balancing import (
        BalanceResult,
        CounterweightOptions,
        Counterweights,
        ShaftOptions,
        ShaftSet,
    )
    from ..schema.settings import BalanceOptions

SCHEMA = "crankbalance.analysis/4"
#: the keys of a conrod's two-mass split in the analysis JSON (unit in a suffix)
CONROD_KEYS: dict[str, str | tuple[str, float]] = {
    "mass": "mass_kg",
    "rotating": "rotating_kg",
    "reciprocating": "reciprocating_kg",
    "cg_from_big_end": "cg_from_big_end_m",
    "inertia_two_mass": "inertia_two_mass_kg_m2",
    "inertia_given": "inertia_given_kg_m2",
    "inertia_error": "inertia_error_kg_m2",
}
EngineLike = str | os.PathLike[str] | EngineSpec | EngineModel


def as_model(engine: EngineLike) -> EngineModel:
    """Accept a preset name, a file path, a spec or a model."""
    if isinstance(engine, EngineModel):
        return engine
    if not isinstance(engine, EngineSpec):
        engine = load_engine(engine)
    return build_model(engine)


def engine_label(engine: EngineLike) -> str:
    """An engine as a message or an output names it: the preset name or the path as given,
    else the name of the spec or model."""
    if isinstance(engine, EngineSpec | EngineModel):
        return str(engine.name)
    return str(engine)


@record(repr=False)
class Analysis(ResultMixin):
    """Free forces and moments of one engine (see :func:`analyze`); a force or moment at
    most the engine's round-off is exactly zero (:func:`without_round_off`)."""

    model: EngineModel
    forces: FreeForces

    def curves(self, angle: ArrayLike | None = None) -> Curves:
        """Curves versus crank angle (720 points over a revolution by default)."""
        return curves(self.model, self.forces, angle)

    def main_table(self) -> str:
        """The free forces, order by order."""
        return "free forces"

    def headline(self) -> tuple[str, ...]:
        """The largest free force and moment of the reciprocating masses (with their
        orders) and those of the rotating masses, in words with units."""
        f = without_round_off(self.model, self.forces)

        def largest(amplitudes: NDArray[np.float64], kind: str) -> str:
            if not np.any(amplitudes > 0):
                return text(0.0, kind)
            k = int(np.argmax(amplitudes))
            return f"{text(float(amplitudes[k]), kind)} (order {int(f.orders[k])})"

        return (
            f"free force {largest(f.force_amplitude, 'force')}, "
            f"free moment {largest(f.moment_amplitude, 'moment')}",
            f"rotating masses (bare crank): force {text(abs(f.rotating_force), 'force')}, "
            f"moment {text(abs(f.rotating_couple), 'moment')}",
        )

    def to_dict(self) -> dict[str, Any]:
        m = self.model
        f = without_round_off(m, self.forces)
        rows_f, rows_m, rows_roll = [], [], []
        for k, order in enumerate(f.orders):
            rows_f.append(
                {
                    "order": int(order),
                    "amplitude_N": float(f.force_amplitude[k]),
                    "forward_N": float(abs(f.force_forward[k])),
                    "backward_N": float(abs(f.force_backward[k])),
                    "forward_phase_deg": _phase(f.force_forward[k]),
                    "backward_phase_deg": _phase(f.force_backward[k]),
                }
            )
            rows_m.append(
                {
                    "order": int(order),
                    "amplitude_Nm": float(f.moment_amplitude[k]),
                    "forward_Nm": float(abs(f.couple_forward[k])),
                    "backward_Nm": float(abs(f.couple_backward[k])),
                    "forward_phase_deg": _phase(1j * f.couple_forward[k]),
                    "backward_phase_deg": _phase(1j * f.couple_backward[k]),
                }
            )
            rows_roll.append(
                {
                    "order": int(order),
                    "amplitude_Nm": float(f.roll_amplitude[k]),
                    "phase_deg": _roll_phase(f.roll[k]),
                }
            )
        out = {
            "schema": SCHEMA,
            "engine": {
                **engine_summary(m),
                "crank_radius_m": m.crank_radius,
                "rod_length_m": m.rod_length,
                "rod_ratio": m.rod_ratio,
                "cylinder_offset_m": m.cylinder_offset,
                "cylinder_axial_m": m.cylinder_axial,
                "moment_reference_m": m.moment_reference,
                "moment_point_m": list(m.moment_point),
                "throw_angle_deg": np.degrees(m.throw_angle),
                "throw_position_m": m.throw_position,
                "cylinder_throw": m.cylinder_throw + 1,
                "cylinder_bank_deg": np.degrees(m.cylinder_bank),
                **articulated_summary(m),
                **firing_summary(m),
            },
            "masses": {
                "reciprocating_kg": m.reciprocating_mass,
                "rotating_kg": m.throw_rotating_mass,
                "conrods": [keyed(c.to_dict(), CONROD_KEYS) for c in m.conrods],
            },
            "free_forces": rows_f,
            "free_moments": rows_m,
            "roll_moments": rows_roll,
            "rotating": {
                "force_N": abs(f.rotating_force),
                "moment_Nm": abs(f.rotating_couple),
                "force_phase_deg": _phase(f.rotating_force),
                "moment_phase_deg": _phase(1j * f.rotating_couple),
                "roll_Nm": abs(f.rotating_roll),
                "roll_phase_deg": _roll_phase(f.rotating_roll),
            },
            "conventions": "phases: direction at crank angle 0, degrees from +z toward +x; "
            "roll moments (about y, positive in the sense of rotation) amplitude * cos(n * "
            "crank angle + phase); no free force along y; "
            f"moments about {moment_point(m.moment_point)}",
        }
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def without_round_off(model: EngineModel, forces: FreeForces) -> FreeForces:
    """``forces`` with every force and moment at most the engine's round-off
    (:func:`crankbalance.results.round_off`) set to exactly zero, as every output shows
    them. The levels are the model's own, kept by it
    (:attr:`~crankbalance.physics.model.EngineModel.derived`)."""
    f, k = forces, forces.orders.size
    kept = model.derived.get(("round_off", k))
    if kept is None:  # each array value's level, in the order of the values below
        force, moment = round_off(model)
        level = np.repeat([force, force, moment, moment, moment], k)
        level.flags.writeable = False
        kept = model.derived[("round_off", k)] = (level, float(force), float(moment))
    level, force_level, moment_level = kept
    v = np.concatenate(
        (f.force_forward, f.force_backward, f.couple_forward, f.couple_backward, f.roll)
    )
    v[np.abs(v) <= level] = 0.0  # below_round_off's rule, in place on this own copy
    # the three rotating values by the same rule, as Python numbers (abs: the same hypot)
    rotating_force, rotating_couple, rotating_roll = (
        f.rotating_force,
        f.rotating_couple,
        f.rotating_roll,
    )
    if abs(rotating_force) <= force_level:
        rotating_force = 0j
    if abs(rotating_couple) <= moment_level:
        rotating_couple = 0j
    if abs(rotating_roll) <= moment_level:
        rotating_roll = 0j
    return FreeForces(
        orders=f.orders,
        force_forward=v[:k],
        force_backward=v[k : 2 * k],
        couple_forward=v[2 * k : 3 * k],
        couple_backward=v[3 * k : 4 * k],
        rotating_force=rotating_force,
        rotating_couple=rotating_couple,
        roll=v[4 * k : 5 * k],
        rotating_roll=rotating_roll,
    )


def engine_summary(m: EngineModel) -> dict[str, Any]:
    """Name, size, speed and kinematics of an engine, as every JSON output starts."""
    return {
        "name": m.name,
        "cylinders": m.cylinders,
        "throws": m.throws,
        "speed_rad_s": m.speed,
        "kinematics": m.kinematics,
    }


def articulated_summary(m: EngineModel) -> dict[str, Any]:
    """``{"articulated": ...}`` for an engine with master-and-link rods, else ``{}``: the
    rods' geometry and each piston's stroke and top dead centre (docs/json.md)."""
    rods = m.articulated_rods
    if rods is None:
        return {}
    from ..physics.articulated import dead_centres

    centres = dead_centres(rods)
    return {
        "articulated": {
            "master_cylinder": rods.master + 1,
            "rod_length_m": rods.rod_length,
            "link_pin_radius_m": rods.link_pin_radius,
            "link_pin_angle_deg": np.degrees(rods.link_pin_angle),
            "stroke_m": centres.stroke,
            "tdc_angle_deg": np.degrees(centres.tdc_angle),
            "tdc_travel_m": centres.tdc_travel,
        }
    }


def firing_summary(m: EngineModel) -> dict[str, Any]:
    """The firing order (crankbalance's numbering) when the engine file gives one, and with a
    maker's numbering also each cylinder's maker's number and the order in the maker's
    numbers (docs/json.md)."""
    if not m.firing_order_given:
        return {}
    out: dict[str, Any] = {"firing_order": list(m.firing_order)}
    if m.maker_number is not None:
        out["maker_number"] = list(m.maker_number)
        out["firing_order_maker"] = [m.maker_number[c - 1] for c in m.firing_order]
    return out


def _roll_phase(value: complex) -> float:
    """Phase of a roll moment phasor R, M_y = abs(R) cos(n theta + arg R), in degrees (0 for a
    zero phasor)."""
    if value == 0:
        return 0.0
    return float(np.degrees(np.angle(value)))


def firing(
    model: EngineModel, fire: ArrayLike | None = None
) -> tuple[list[int], NDArray[np.float64]]:
    """The firing order and the crank angle from each cylinder of it to the next, the last
    back to the first [rad], of the firing angles ``fire`` [rad] (default: the engine's own,
    :func:`crankbalance.physics.model.model_fire_angles`). The order is the
    engine's when given or with ``fire``, else the order of its firing angles (the most
    even firing its crank allows). A single cylinder's interval is the whole cycle.

    Raises :class:`~crankbalance.errors.InputError` for an engine without a firing order
    whose crank has too many firings to try
    (:data:`crankbalance.physics.firing.MAX_FREE_CYLINDERS`).
    """
    order = list(model.firing_order)
    if fire is None:
        from ..physics.model import model_fire_angles

        fire = model_fire_angles(model)
        if not model.firing_order_given:
            order = [int(c) + 1 for c in np.argsort(fire, kind="stable")]
            order = order[order.index(1) :] + order[: order.index(1)]  # from cylinder 1
    cycle = np.pi * model.strokes
    sequence = np.asarray(fire, dtype=float)[np.asarray(order) - 1]
    intervals = np.diff(np.append(sequence, sequence[0] + cycle))
    # one cylinder fires once a cycle: its interval is the cycle, not 0
    return order, np.mod(intervals, cycle) if model.cylinders > 1 else intervals


def _phase(value: complex) -> float:
    """Direction of a phasor in degrees from +z toward +x (0 for a zero phasor: one at
    most the round-off, which ``to_dict`` sets to zero first)."""
    if value == 0:
        return 0.0
    return float(np.degrees(np.arctan2(value.imag, value.real)))


@functools.lru_cache(maxsize=64)
def _orders(orders: Any) -> int:
    """The setting ``orders`` of :func:`analyze`, checked (a whole number is checked once)."""
    return parse_options(AnalysisOptions, {"orders": orders}).orders


def analyze(
    engine: EngineLike, orders: int = 8, moment_point: Sequence[float] | None = None
) -> Analysis:
    """Free forces and moments of an engine (orders 1..``orders``) and of its rotating masses.

    Parameters
    ----------
    engine : str, path, EngineSpec or EngineModel
        Preset name, engine file, validated spec or built model.
    orders : int
        Highest harmonic order (1..64).
    moment_point : sequence of three floats, optional
        The point (x, y, z) [m] moments are taken about, y from the crank's mid-point;
        None: the engine's (``crank_train.moment_point`` or ``moment_reference``).
    """
    orders = _orders(orders) if type(orders) is int else _orders.__wrapped__(orders)
    model = as_model(engine)
    if moment_point is not None:
        from ..errors import InputError

        point = [float(v) for v in moment_point]
        if len(point) != 3 or not all(math.isfinite(v) for v in point):
            raise InputError("moment_point", moment_point, "three finite lengths x, y, z [m]")
        model = with_moment_point(model, point)
    return Analysis(model=model, forces=without_round_off(model, free_forces(model, orders)))


# --------------------------------------------------------------------------- balancing study
BALANCE_SCHEMA = "crankbalance.balance/2"


def balance_options(
    spec: EngineSpec,
) -> tuple[CounterweightOptions, ShaftOptions | None, ShaftOptions | None]:
    """Solver options from an engine spec's [counterweights] and [balance_shafts] tables.

    Without a [counterweights] table the crank gets counterweights on every web at the
    crank radius, at the optimal angle (least mass), with no balance factor. The options
    are frozen: an equal spec among the last :data:`~crankbalance.studies.build.BUILD_CACHE`
    seen gets the same ones.
    """
    return _balance_options(spec)


@functools.lru_cache(maxsize=BUILD_CACHE)
def _balance_options(
    spec: EngineSpec,
) -> tuple[CounterweightOptions, ShaftOptions | None, ShaftOptions | None]:
    """:func:`balance_options`, kept by the spec (as its built model is, issue 30)."""
    from ..physics.balancing import CounterweightOptions, ShaftOptions

    c = spec.counterweights
    if c is None:
        cw = CounterweightOptions(cg_radius=spec.crank_train.crank_radius, angle="optimal")
    else:
        cw = CounterweightOptions(
            cg_radius=c.cg_radius,
            webs=tuple(c.webs) if c.webs is not None else None,
            angle=c.angle,
            balance_factor=c.balance_factor,
            scope=c.scope,
            method=c.method,
            web_offset=c.web_offset,
        )
    shafts = spec.balance_shafts
    primary = secondary = None
    if shafts is not None and shafts.primary is not None:
        primary = ShaftOptions(
            shafts.primary.cg_radius, shafts.primary.length, shafts.primary.arrangement
        )
    if shafts is not None and shafts.secondary is not None:
        secondary = ShaftOptions(
            shafts.secondary.cg_radius, shafts.secondary.length, shafts.secondary.arrangement
        )
    return cw, primary, secondary


@record(repr=False)
class BalanceStudy(ResultMixin):
    """Counterweights and balance shafts of one engine (see :func:`balance_engine`), and
    the time-domain verification when it was asked for."""

    model: EngineModel
    result: BalanceResult
    verification: Verification | None = None  # when asked for

    def main_table(self) -> str:
        """Each component's free force and moment before and after balancing."""
        return "components"

    def to_dict(self, factor_name: str | None = None) -> dict[str, Any]:
        """The JSON contract ``crankbalance.balance/2`` (docs/json.md); each next step of
        ``remaining`` names the balance factor setting ``factor_name`` (None: the command
        line's option, ``--balance-factor``; the web passes its form's label)."""
        from ..physics.balance_remaining import FACTOR_OPTION, step_words

        name = FACTOR_OPTION if factor_name is None else factor_name
        res, m = self.result, self.model
        components = {c.component: c for c in res.residuals}

        def cw_dict(cw: Counterweights | None) -> dict[str, Any] | None:
            if cw is None:
                return None
            return {
                "mass_kg": float(cw.mass.max(initial=0.0)),
                "angle_deg": None if cw.alpha is None else math.degrees(cw.alpha),
                "count": cw.count,
                "method": cw.method,
                "scope": cw.scope,
                "cg_radius_m": cw.cg_radius,
                "total_mass_kg": float(cw.mass.sum()),
                "webs": [
                    {
                        "web": int(cw.web[k]),
                        "throw": int(cw.throw[k]),
                        "position_m": float(cw.position[k]),
                        "mass_kg": float(cw.mass[k]),
                        "direction_deg": math.degrees(cw.direction[k]),
                    }
                    for k in range(cw.count)
                ],
                "note": cw.note,
            }

        def shafts_dict(group: ShaftSet | None) -> dict[str, Any] | None:
            if group is None:
                return None
            return {
                "mass_kg": max((s.mass for s in group.shafts), default=0.0),
                "order": group.order,
                "arrangement": group.arrangement,
                "length_m": group.length,
                "shafts": [
                    {
                        "rotation": "co-rotating" if s.sense > 0 else "counter-rotating",
                        "speed_ratio": s.sense * s.order,
                        "cg_radius_m": s.cg_radius,
                        "mass_kg": s.mass,
                        "masses": [
                            {
                                "position_m": x.position,
                                "mass_kg": x.mass,
                                "phase_deg": math.degrees(x.phase),
                            }
                            for x in s.masses
                        ],
                        "note": s.note,
                    }
                    for s in group.shafts
                ],
            }

        rotating, o1, o2 = components["rotating"], components["order1"], components["order2"]
        unbalanced = [
            f"{c.component}: force {text(c.force_after, 'force')}, "
            f"moment {text(c.moment_after, 'moment')}"
            for c in res.residuals
            if c.force_after > 0 or c.moment_after > 0
        ]
        out = {
            "schema": BALANCE_SCHEMA,
            "engine": engine_summary(m),
            "counterweight": cw_dict(res.counterweights),
            "extra_counterweights": cw_dict(res.extra_counterweights),
            "primary_shafts": shafts_dict(res.primary),
            "secondary_shafts": shafts_dict(res.secondary),
            "residual": {
                "rotating_force_N": rotating.force_after,
                "rotating_moment_Nm": rotating.moment_after,
                "order1_force_N": o1.force_after,
                "order1_moment_Nm": o1.moment_after,
                "order2_force_N": o2.force_after,
                "order2_moment_Nm": o2.moment_after,
            },
            "components": [
                {
                    "component": c.component,
                    "targeted": c.targeted,
                    "force_before_N": c.force_before,
                    "force_after_N": c.force_after,
                    "moment_before_Nm": c.moment_before,
                    "moment_after_Nm": c.moment_after,
                }
                for c in res.residuals
            ],
            "unbalanced": unbalanced,
            "remaining": [
                {
                    "component": r.component,
                    "order": r.order,
                    "quantity": r.quantity,
                    "rotation": r.rotation,
                    "amount": r.amount,
                    "unit": "N" if r.quantity == "force" else "N·m",
                    "text": r.text,
                    "next_step": step_words(r.step_format, name),
                }
                for r in res.remaining
            ],
            "notes": list(res.notes),
        }
        if self.verification is not None:
            out["verification"] = verification_dict(self.verification)
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def verification_dict(verification: Verification) -> dict[str, Any]:
    """The ``verification`` block of ``crankbalance.balance/2`` (docs/json.md): the
    time-domain amplitudes and their largest differences from the solver's."""
    return {
        "samples": verification.samples,
        "agrees": verification.agrees,
        "force_difference_N": verification.force_difference,
        "moment_difference_Nm": verification.moment_difference,
        "force_round_off_N": verification.force_round_off,
        "moment_round_off_Nm": verification.moment_round_off,
        "components": [
            {
                "component": c.component,
                "targeted": c.targeted,
                "force_before_N": c.force_before,
                "force_after_N": c.force_after,
                "moment_before_Nm": c.moment_before,
                "moment_after_Nm": c.moment_after,
            }
            for c in verification.residuals
        ],
    }


@functools.cache
def _balancing() -> ModuleType:
    """:mod:`crankbalance.physics.balancing`, imported at the first balancing (not on the
    analysis path) and then read from here: a relative import statement costs about 1 us a
    call."""
    from ..physics import balancing

    return balancing


def balance_engine(
    engine: str | os.PathLike[str] | EngineSpec,
    orders: int = 8,
    *,
    verify: bool = False,
    halves_if_balanced: bool = False,
    **overrides: Any,
) -> BalanceStudy:
    """Counterweights and balance shafts of an engine, as its file asks for.

    With ``halves_if_balanced`` (the studies that need counterweights on the crank: crank
    loads, the counterweight requirement), a crank the default scope ``"auto"`` leaves
    without counterweights, being balanced as a whole, gets each half balanced on its own
    (``scope = "halves"``, paper section 3.1), as ``auto`` did before issue 27.

    ``overrides`` replace fields of the counterweight options (``angle``,
    ``balance_factor``, ``method``, ``scope``, ``cg_radius``, ``webs``) or give
    ``primary``/``secondary`` as :class:`~crankbalance.physics.balancing.ShaftOptions` (or None).
    ``verify`` adds the time-domain verification of the result
    (:func:`crankbalance.physics.balance_check.verify`; the residuals themselves come from
    the solver's phasors).
    """
    import dataclasses

    balance = _balancing().balance
    orders = _orders(orders) if type(orders) is int else _orders.__wrapped__(orders)
    spec = engine if isinstance(engine, EngineSpec) else load_engine(engine)
    model = build_model(spec)
    cw, primary, secondary = balance_options(spec)
    primary = overrides.pop("primary", primary)
    secondary = overrides.pop("secondary", secondary)
    if overrides:
        cw = dataclasses.replace(cw, **overrides)
    result = balance(model, cw, primary, secondary, orders)
    if (
        halves_if_balanced
        and cw is not None
        and cw.scope == "auto"
        and result.counterweights is not None
        and not result.counterweights.mass.any()
        and model.throws >= 2
        and model.throws % 2 == 0
    ):
        result = balance(model, dataclasses.replace(cw, scope="halves"), primary, secondary, orders)
    checked = None
    if verify:
        from ..physics.balance_check import verify as time_domain

        checked = time_domain(model, result)
    return BalanceStudy(model, result, checked)


# --------------------------------------------------------------------------- the two studies
def analysis(engine: EngineLike, settings: AnalysisOptions) -> Analysis:
    """The analysis study of the registry (``analyze``): :func:`analyze` of ``engine`` with
    its settings (the highest order, the moment point)."""
    return analyze(engine, settings.orders, settings.moment_point)


def balancing(
    engine: str | os.PathLike[str] | EngineSpec, settings: BalanceOptions
) -> BalanceStudy:
    """The balancing study of the registry (``balance``): :func:`balance_engine` of
    ``engine`` with the counterweight settings given in ``settings``
    (:class:`~crankbalance.schema.settings.BalanceOptions`: angle, balance factor, method,
    scope) in place of the engine file's, with the time-domain verification when it asks
    for it (``verify``). An angle given for individual counterweights, which
    take no common angle, is refused."""
    from ..errors import InputError
    from ..schema.settings import given

    overrides = {
        name: getattr(settings, name)
        for name in ("angle", "balance_factor", "method", "scope")
        if getattr(settings, name) is not None
    }
    study = balance_engine(engine, verify=settings.verify, **overrides)
    counterweights = study.result.counterweights
    if "angle" in given(settings) and counterweights is not None:
        if counterweights.method == "individual":
            raise InputError(
                "angle", settings.angle, "only acts on equal counterweights (--method pattern)"
            )
    return study


# --------------------------------------------------------------------------- the library
PRESETS_SCHEMA = "crankbalance.presets/1"


@functools.cache
def preset_titles() -> tuple[tuple[str, str], ...]:
    """(name, title) of every built-in engine, read once per process."""
    from ..io.engine_file import list_presets

    return tuple((name, load_engine(name).name) for name in list_presets())


def presets_listing() -> dict[str, Any]:
    """The JSON contract ``crankbalance.presets/1``: every built-in engine's name and title
    (``crankbalance presets --format json`` and ``GET /api/presets``)."""
    return {
        "schema": PRESETS_SCHEMA,
        "presets": [{"name": name, "title": title} for name, title in preset_titles()],
    }
