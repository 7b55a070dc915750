"""The balance shop as one study (issue 16): from an engine and its weighed parts to matched
sets, bob-weights, the hole plan of a two-plane reading and the ISO 21940-11 sign-off.

The physics is in :mod:`crankbalance.physics.shop` (matching, bob-weights, holes, planes, scatter);
this module only derives their inputs from an engine, a parts file and the settings of
:class:`crankbalance.schema.settings.ShopOptions`, and gathers the results. The ``shop`` commands,
the shop sheet and the example call these functions; nothing else derives these quantities.
"""

from __future__ import annotations

import dataclasses
import os
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..output.format import keyed, plural
from ..physics.model import EngineModel
from ..physics.shop.bobweights import BobWeights, RemainingForces, bob_weights, remaining_forces
from ..physics.shop.holes import DrillingPlan, drilling_plan
from ..physics.shop.journals import JournalPairing, pair_journals
from ..physics.shop.matching import (
    Inventory,
    MachineToLightest,
    Matching,
    machine_to_lightest,
    match_parts,
)
from ..physics.shop.planes import (
    PlaneCheck,
    TwoPlanePlan,
    iso_check,
    plan_correction,
    predicted_residual,
    reading_unbalance,
)
from ..physics.shop.scatter import PartScatter, ScatterStudy, scatter_study
from ..records import record
from ..results import ResultMixin, number, to_jsonable
from ..schema.settings import ShopOptions

if TYPE_CHECKING:  # pragma: no cover
    from ..schema.engine import EngineSpec

    #: an engine as the shop takes it: a preset name, an engine file or a spec
    EngineSource = str | os.PathLike[str] | EngineSpec


@record(repr=False)
class PartsStudy(ResultMixin):
    """Matched sets and bob-weights of an engine's weighed parts.

    Attributes
    ----------
    engine : str
        Engine name.
    parts_source : str
        The parts file.
    cylinders : int
        Cylinders filled.
    inventory : Inventory
        The weighed parts [kg].
    as_listed : Matching
        Part i of every kind in cylinder i [kg].
    matching : Matching
        The matched sets (``ShopOptions.method``) [kg].
    machined : MachineToLightest
        The alternative: every part machined to the lightest of its kind [kg].
    crank_radius : float
        Radius the bob-weights are clamped at [m].
    bob_weights : BobWeights
        Bob-weight per crankpin from the matched sets [kg].
    remaining : RemainingForces
        Free forces [N] and couples [N m] the fraction leaves (orders 1 and 2).
    journals : JournalPairing
        Which sets share a journal (``ShopOptions.journals``) and the journals'
        bob-weights [kg]; ``matching`` lists the sets in their cylinders after it.
    """

    engine: str
    parts_source: str
    cylinders: int
    inventory: Inventory
    as_listed: Matching
    matching: Matching
    machined: MachineToLightest
    crank_radius: float
    bob_weights: BobWeights
    remaining: RemainingForces
    journals: JournalPairing


@record(repr=False)
class HolePlan(ResultMixin):
    """A two-plane reading turned into holes per correction plane, and the ISO check.

    Attributes
    ----------
    plan : TwoPlanePlan
        Unbalance and correction per correction plane [kg m].
    holes : tuple of DrillingPlan
        The holes (or heavy-metal slugs) of each correction plane, in the order given.
    residual : ndarray of complex, shape (2,)
        Predicted residual per correction plane after the holes [kg m].
    check : PlaneCheck
        ISO 21940-11 check of the predicted residual.
    grade : str
        The balance quality grade checked.
    rotor_mass : float
        Crank mass of the check [kg].
    speed : float
        Largest service speed of the check [rad/s].
    bearings : ndarray, shape (2,)
        Main-bearing positions of the check [m].
    center_of_mass : float
        Axial position of the crank's centre of mass [m].
    """

    plan: TwoPlanePlan
    holes: tuple[DrillingPlan, ...]
    residual: NDArray[np.complex128]
    check: PlaneCheck
    grade: str
    rotor_mass: float
    speed: float
    bearings: NDArray[np.float64]
    center_of_mass: float


@record(repr=False)
class ShopStudy(ResultMixin):
    """Everything the shop sheet shows: the parts study and, with readings, the hole plan.

    Attributes
    ----------
    parts : PartsStudy
        Matched sets, material to remove, bob-weights.
    holes : HolePlan or None
        The hole plan and the ISO sign-off (None without readings).
    settings : dict
        The settings used (:class:`~crankbalance.schema.settings.ShopOptions`, SI).
    """

    parts: PartsStudy
    holes: HolePlan | None
    settings: dict[str, Any]


def engine_model(engine: EngineSource) -> tuple[str, EngineModel]:
    """The name and model of ``engine``: a preset name, an engine file or an EngineSpec."""
    from ..io.engine_file import load_engine
    from ..schema.engine import EngineSpec
    from .build import build_model

    spec = engine if isinstance(engine, EngineSpec) else load_engine(engine)
    return spec.name, build_model(spec)


def parts_study(
    engine: EngineSource, parts: str | os.PathLike[str] | Inventory, options: ShopOptions
) -> PartsStudy:
    """Match the parts of ``parts`` (a parts file or an Inventory) to the cylinders of
    ``engine`` and give the bob-weights of the matched sets (``options.fraction``)."""
    from ..io.parts_file import load_parts_file

    name, model = engine_model(engine)
    source = "inventory" if isinstance(parts, Inventory) else str(parts)
    inventory = parts if isinstance(parts, Inventory) else load_parts_file(parts)
    inventory = inventory.per_rod(model.cylinder_throw, "journal_oil")
    cylinders = len(model.cylinder_throw)
    inventory.check(cylinders, "engine")
    joint = options.journals == "joint"
    if joint and options.method not in ("milp", "exhaustive"):
        raise InputError("journals", "joint", "needs method milp or exhaustive")
    matched = match_parts(
        inventory,
        cylinders,
        options.method,
        objective="journal" if joint else None,
        time_limit=options.time_limit,
        model=model,
        fraction=options.fraction,
    )
    journals = journal_pairing(model, matched, options)
    matched = in_cylinders(matched, journals.set_of_cylinder)
    return PartsStudy(
        engine=name,
        parts_source=source,
        cylinders=cylinders,
        inventory=inventory,
        as_listed=match_parts(inventory, cylinders, "as-listed"),
        matching=matched,
        machined=machine_to_lightest(inventory, cylinders),
        crank_radius=model.crank_radius,
        bob_weights=bob_weights(model, options.fraction, matched.rotating, matched.reciprocating),
        remaining=remaining_forces(model, options.fraction, matched.reciprocating),
        journals=journals,
    )


def spares_words(study: PartsStudy) -> str:
    """The parts the matching left out of every set, in words ("" when every part is in a
    set): a parts file may list more parts of a kind than the engine has cylinders (the
    spares stay on the shelf, docs/balance_shop.md "Parts and matching"), and the command
    line (``crankbalance shop match``), the result's headline and the web's Balance shop
    tab say which, in these words: "4 cylinders: 4 parts of each kind in the sets; spares,
    in no set: piston P3, P5, P7, P8; ..."."""
    m = study.matching
    left = []
    for kind in study.inventory.kinds:
        used = {int(i) for i in m.part[m.kinds.index(kind.name)]}
        spare = [mark for i, mark in enumerate(kind.ids) if i not in used]
        if spare:
            left.append(f"{kind.name} {', '.join(spare)}")
    if not left:
        return ""
    return (
        f"{plural(study.cylinders, 'cylinder')}: {plural(study.cylinders, 'part')} of each "
        f"kind in the sets; spares, in no set: {'; '.join(left)}"
    )


def journal_pairing(model: EngineModel, matched: Matching, options: ShopOptions) -> JournalPairing:
    """Which of the matched sets share a journal (``options.journals``): the least spread
    of the journals' bob-weights (:func:`~crankbalance.physics.shop.journals.pair_journals`,
    within ``options.time_limit``), the matching's own (``joint``: the parts were matched
    for it) or set c in cylinder c (``as-listed``)."""
    weight = matched.rotating + options.fraction * matched.reciprocating
    method = "milp" if options.journals == "paired" else "as-listed"
    pairing = pair_journals(
        weight, model.cylinder_throw, model.throws, method, time_limit=options.time_limit
    )
    if options.journals != "joint":
        return pairing
    # the parts were matched for the journals' spread: the matching's sets stay put
    return dataclasses.replace(
        pairing,
        method="joint",
        optimal=matched.optimal,
        status=f"matched with the journals: {matched.status}",
    )


def in_cylinders(matched: Matching, set_of_cylinder: NDArray[np.int64]) -> Matching:
    """The matching with its set ``set_of_cylinder[c]`` in cylinder c (a spread or a
    variance does not change: the sets only move between cylinders)."""
    order = np.asarray(set_of_cylinder)
    if np.array_equal(order, np.arange(order.size)):
        return matched
    return dataclasses.replace(
        matched,
        part=matched.part[:, order],
        ids=tuple(matched.ids[s] for s in order),
        reciprocating=matched.reciprocating[order],
        rotating=matched.rotating[order],
        remove_reciprocating=matched.remove_reciprocating[order],
        remove_rotating=matched.remove_rotating[order],
    )


def _required(options: ShopOptions, *names: str) -> None:
    for name in names:
        if getattr(options, name) is None:
            raise InputError(name, None, "is required to plan the holes")


#: the settings (:class:`~crankbalance.schema.settings.ShopOptions`) a drilling plan's parameters
#: come from, to name them in its messages
PLAN_SETTINGS = {
    "diameter": "hole_diameter",
    "max_depth": "max_depth",
    "radius": "hole_radius",
    "web_thickness": "web_thickness",
}


def hole_plan(
    options: ShopOptions, speed: float | None = None, names: dict[str, str] | None = None
) -> HolePlan:
    """The two readings of ``options`` turned into holes per correction plane, and the ISO
    check of the predicted residual (``speed`` [rad/s]: the engine's, when ``options.speed``
    is not given). A plan the drill cannot make is refused naming the settings
    (``hole_diameter``, ``web_thickness``), or what ``names`` gives for them (the options:
    ``{"hole_diameter": "--hole-diameter"}``)."""
    if not options.reading:
        raise InputError("reading", None, "is required (twice, one per measuring plane)")
    _required(options, "measuring_planes", "correction_planes", "hole_radius", "depth_to")
    _required(options, "rotor_mass")
    speed = options.speed if options.speed is not None else speed
    if speed is None:
        raise InputError("speed", None, "is required for the ISO check (or give an engine)")
    mass, radius, angle = np.array(options.reading, dtype=float).T
    reading = reading_unbalance(mass, radius, angle, options.convention)
    assert options.correction_planes is not None and options.hole_radius is not None
    assert options.measuring_planes is not None
    assert options.depth_to is not None and options.rotor_mass is not None
    plan = plan_correction(
        reading, options.measuring_planes, options.correction_planes, options.hole_radius
    )
    given = names or {}
    plan_names = {name: given.get(key, key) for name, key in PLAN_SETTINGS.items()}
    holes = tuple(
        drilling_plan(
            float(plan.amount[j]),
            float(plan.remove_angle[j]),
            options.hole_diameter,
            options.hole_radius,
            options.max_depth,
            options.depth_to,
            direction=options.direction,
            point_angle=options.point_angle,
            density=options.density,
            spacing=options.spacing,
            depth_resolution=options.depth_resolution,
            slug_density=options.slug_density,
            web_thickness=options.web_thickness,
            names=plan_names,
        )
        for j in range(2)
    )
    # the holes take their correction off the heavy spot: they add minus it
    residual = predicted_residual(plan, [-h.correction for h in holes])
    bearings = np.asarray(options.bearings or options.correction_planes, dtype=float)
    centre = float(bearings.mean()) if options.center_of_mass is None else options.center_of_mass
    check = iso_check(
        residual,
        options.grade,
        options.rotor_mass,
        speed,
        bearings,
        centre,
        options.correction_planes,
    )
    return HolePlan(
        plan=plan,
        holes=holes,
        residual=residual,
        check=check,
        grade=options.grade,
        rotor_mass=options.rotor_mass,
        speed=speed,
        bearings=bearings,
        center_of_mass=centre,
    )


def shop_study(
    engine: EngineSource,
    parts: str | os.PathLike[str] | Inventory,
    options: ShopOptions,
    names: dict[str, str] | None = None,
) -> ShopStudy:
    """The whole shop sheet: :func:`parts_study`, and :func:`hole_plan` when the options
    hold readings (the engine's speed for the ISO check unless ``options.speed``; ``names``
    as there)."""
    study = parts_study(engine, parts, options)
    holes = None
    if options.reading:
        holes = hole_plan(options, engine_model(engine)[1].speed, names)
    return ShopStudy(parts=study, holes=holes, settings=options.values())


def part_scatter(inventory: Inventory) -> tuple[PartScatter, ...]:
    """The scatter of every kind of part as the parts file shows it: per kind and share
    (reciprocating, rotating), the sample standard deviation of the weighed shares [kg]
    (a rod gives its small end and its big end)."""
    out = []
    ends = {"reciprocating": "small end", "rotating": "big end"}
    for kind in inventory.kinds:
        both = bool(np.any(kind.reciprocating) and np.any(kind.rotating))  # a rod
        for share, values in (("reciprocating", kind.reciprocating), ("rotating", kind.rotating)):
            if np.any(values) and kind.count > 1:
                label = f"{kind.name} ({ends[share]})" if both else kind.name
                sigma = float(np.std(values, ddof=1))
                out.append(PartScatter(label, share, sigma))  # type: ignore[arg-type]
    return tuple(out)


def scatter_of_parts(
    engine: EngineSource,
    parts: str | os.PathLike[str] | Inventory,
    options: ShopOptions,
    samples: int,
    seed: int = 0,
    scale_step: float = 0.0,
) -> ScatterStudy:
    """Monte Carlo of the parts file's scatter (:func:`part_scatter`) for ``engine`` balanced
    with ``options.fraction``; with ``rotor_mass`` and correction planes given, the
    probability of meeting ``options.grade`` (planes from the crankshaft mid-point)."""
    from ..io.parts_file import load_parts_file
    from ..physics.shop.planes import plane_tolerances

    _name, model = engine_model(engine)
    inventory = parts if isinstance(parts, Inventory) else load_parts_file(parts)
    if options.correction_planes is None:
        raise InputError("correction_planes", None, "is required for the residual per plane")
    tolerance = None
    if options.rotor_mass is not None:
        bearings = options.bearings or options.correction_planes
        centre = options.center_of_mass
        _allocation, tolerance = plane_tolerances(
            options.grade,
            options.rotor_mass,
            options.speed or model.speed,
            bearings,
            float(np.mean(bearings)) if centre is None else centre,
            options.correction_planes,
        )
    return scatter_study(
        model,
        part_scatter(inventory),
        options.correction_planes,
        options.fraction,
        samples,
        seed=seed,
        scale_step=scale_step,
        plane_tolerance=tolerance,
    )


# ---------------------------------------------------------------------------------------
# JSON: every key that carries a unit names it (docs/json.md), angles in degrees
# ---------------------------------------------------------------------------------------

#: the schemas of the shop's JSON outputs (docs/json.md)
MATCH_SCHEMA = "crankbalance.shop.match/2"
BOBWEIGHTS_SCHEMA = "crankbalance.shop.bobweights/2"
PLAN_SCHEMA = "crankbalance.shop.plan/2"
SCATTER_SCHEMA = "crankbalance.shop.scatter/2"

_DEG = 180.0 / np.pi
Names = dict[str, str | tuple[str, float]]

#: per result dataclass, its fields' JSON keys (``format.keyed``): the unit in a suffix,
#: radians turned into degrees; fields not listed are dimensionless or text
_KEYS: dict[str, Names] = {
    "PartKind": {"reciprocating": "reciprocating_kg", "rotating": "rotating_kg"},
    "Inventory": {
        "reciprocating_allowance": "reciprocating_allowance_kg",
        "rotating_allowance": "rotating_allowance_kg",
        "journal_allowance": "journal_allowance_kg",
    },
    "Matching": {
        "reciprocating": "reciprocating_kg",
        "rotating": "rotating_kg",
        "reciprocating_spread": "reciprocating_spread_kg",
        "rotating_spread": "rotating_spread_kg",
        "remove_reciprocating": "remove_reciprocating_kg",
        "remove_rotating": "remove_rotating_kg",
        "removed_total": "removed_total_kg",
        "free_force": "free_force_N",
        "free_couple": "free_couple_Nm",
    },
    "MachineToLightest": {
        "remove_reciprocating": "remove_reciprocating_kg",
        "remove_rotating": "remove_rotating_kg",
        "reciprocating": "reciprocating_kg",
        "rotating": "rotating_kg",
        "removed_total": "removed_total_kg",
    },
    "BobWeights": {
        "rotating": "rotating_kg",
        "reciprocating": "reciprocating_kg",
        "bob_weight": "bob_weight_kg",
    },
    "RemainingForces": {
        "force_forward": "force_forward_N",
        "force_backward": "force_backward_N",
        "couple_forward": "couple_forward_Nm",
        "couple_backward": "couple_backward_Nm",
        "force_amplitude": "force_amplitude_N",
        "couple_amplitude": "couple_amplitude_Nm",
    },
    "PartsStudy": {"crank_radius": "crank_radius_m"},
    "JournalPairing": {
        "bob_weight": "bob_weight_kg",
        "spread": "spread_kg",
        "as_listed_spread": "as_listed_spread_kg",
    },
    "TwoPlanePlan": {
        "measuring_planes": "measuring_planes_m",
        "correction_planes": "correction_planes_m",
        "reading": "reading_kg_m",
        "unbalance": "unbalance_kg_m",
        "correction": "correction_kg_m",
        "amount": "amount_kg_m",
        "remove_angle": ("remove_angle_deg", _DEG),
        "add_angle": ("add_angle_deg", _DEG),
        "correction_radius": "correction_radius_m",
        "mass": "mass_kg",
        "applied_runs": "applied_runs_kg_m",
        "reading_changes": "reading_changes_kg_m",
    },
    "DrillingPlan": {
        "diameter": "diameter_m",
        "point_angle": ("point_angle_deg", _DEG),
        "radius": "radius_m",
        "unbalance": "unbalance_kg_m",
        "angles": ("angles_deg", _DEG),
        "pitch": ("pitch_deg", _DEG),
        "depth": "depth_m",
        "shoulder_depth": "shoulder_depth_m",
        "tip_depth": "tip_depth_m",
        "hole_mass": "hole_mass_kg",
        "slug_length": "slug_length_m",
        "hole_moment": "hole_moment_kg_m",
        "correction": "correction_kg_m",
        "residual": "residual_kg_m",
        "residual_amount": "residual_amount_kg_m",
    },
    # the keys of crankbalance.tolerance/2
    "PlaneAllocation": {
        "total": "total_kg_m",
        "bearing_a": "bearing_a_kg_m",
        "bearing_b": "bearing_b_kg_m",
        "plane_1": "plane_1_kg_m",
        "plane_2": "plane_2_kg_m",
    },
    "ToleranceVerdict": {"residual": "residual_kg_m", "permissible": "permissible_kg_m"},
    "PlaneCheck": {"tolerance": "tolerance_kg_m", "residual": "residual_kg_m"},
    "HolePlan": {
        "residual": "residual_kg_m",
        "rotor_mass": "rotor_mass_kg",
        "speed": "speed_rad_s",
        "bearings": "bearings_m",
        "center_of_mass": "center_of_mass_m",
    },
}

#: the unit of a matching's objective (and its bound), by objective
_OBJECTIVE_SUFFIX = {"spread": "_kg", "variance": "_kg2", "free": "_N", "journal": "_kg"}

#: the JSON keys of the settings (:class:`~crankbalance.schema.settings.ShopOptions`, SI)
_SETTING_KEYS: Names = {
    "time_limit": "time_limit_s",
    "measuring_planes": "measuring_planes_m",
    "correction_planes": "correction_planes_m",
    "hole_diameter": "hole_diameter_m",
    "hole_radius": "hole_radius_m",
    "max_depth": "max_depth_m",
    "web_thickness": "web_thickness_m",
    "point_angle": ("point_angle_deg", _DEG),
    "spacing": "spacing_m",
    "depth_resolution": "depth_resolution_m",
    "density": "density_kg_m3",
    "slug_density": "slug_density_kg_m3",
    "rotor_mass": "rotor_mass_kg",
    "speed": "speed_rad_s",
    "bearings": "bearings_m",
    "center_of_mass": "center_of_mass_m",
    "scale_step": "scale_step_kg",
}

#: the scatter's six magnitudes (:data:`crankbalance.physics.shop.scatter.OUTPUTS`) and ten phasors
#: (``PHASORS``) in three groups of one unit each: (group, slice of outputs, slice of
#: phasors, suffix of a magnitude, suffix of a second moment)
_SCATTER_GROUPS = (
    ("residual", slice(0, 2), slice(0, 2), "_kg_m", "_kg2_m2"),
    ("force", slice(2, 4), slice(2, 6), "_N", "_N2"),
    ("moment", slice(4, 6), slice(6, 10), "_Nm", "_N2_m2"),
)


def _scatter_json(study: ScatterStudy) -> dict[str, Any]:
    """The scatter study with one unit per key: its arrays over the six magnitudes (mixed
    kg m, N and N m) split into the groups ``residual`` (planes 1, 2), ``force`` and
    ``moment`` (orders 1, 2)."""
    limits = (study.plane_tolerance, study.force_limit, study.moment_limit)
    out: dict[str, Any] = {
        "samples": study.samples,
        "seed": study.seed,
        "quantile_levels": study.quantile_levels,
        "sources": study.sources,
    }
    for (group, at, phasor, unit, square), limit in zip(_SCATTER_GROUPS, limits, strict=True):
        out[group] = {
            "outputs": study.outputs[at],
            "mean" + unit: study.mean[at],
            "rms" + unit: study.rms[at],
            "maximum" + unit: study.maximum[at],
            "quantiles" + unit: study.quantiles[at],
            "histogram": study.histogram[at],
            "histogram_upper" + unit: study.histogram_upper[at],
            "overflow": study.overflow[at],
            "variance_share": study.variance_share[:, at],
            "dominant": study.dominant[at],
            "limit" + unit: limit,
            "phasors": study.phasors[phasor],
            "moments" + square: study.moments[phasor],
            "moments_analytic" + square: study.moments_analytic[phasor],
        }
    return out | {"p_grade": study.p_grade, "p_free": study.p_free, "p_all": study.p_all}


def _settings_json(settings: dict[str, Any]) -> dict[str, Any]:
    out = keyed(to_jsonable(settings, "settings"), _SETTING_KEYS)
    out["reading"] = [
        {"mass_kg": mass, "radius_m": radius, "angle_deg": angle * _DEG}
        for mass, radius, angle in out["reading"]
    ]
    return out


def shop_json(result: Any, path: str = "") -> Any:
    """The JSON form of a shop result (PartsStudy, BobWeights, HolePlan, ScatterStudy,
    ShopStudy): the dataclasses' fields with the unit of each in its key's suffix
    (``bob_weight_kg``, ``depth_m``, ``residual_kg_m``) and angles in degrees
    (``angles_deg``), as every JSON output has them (docs/json.md)."""
    if isinstance(result, ScatterStudy):
        return to_jsonable(_scatter_json(result), path)
    if dataclasses.is_dataclass(result) and not isinstance(result, type):
        name = type(result).__name__
        fields = {
            f.name: shop_json(getattr(result, f.name), f"{path}.{f.name}".lstrip("."))
            for f in dataclasses.fields(result)
        }
        names = dict(_KEYS.get(name, {}))
        if isinstance(result, Matching):
            suffix = _OBJECTIVE_SUFFIX[result.objective]
            names |= {"objective_value": "objective_value" + suffix, "bound": "bound" + suffix}
        if isinstance(result, ShopStudy):
            fields["settings"] = _settings_json(result.settings)
        return keyed(fields, names)
    if isinstance(result, list | tuple):
        return [shop_json(value, f"{path}[{k}]") for k, value in enumerate(result)]
    return to_jsonable(result, path)


# ---------------------------------------------------------------------------------------
# the shop's studies of the registry: one function each, one settings object
# ---------------------------------------------------------------------------------------

#: how the messages of a drilling plan name its settings: the command line's options
PLAN_NAMES = {name: "--" + name.replace("_", "-") for name in PLAN_SETTINGS.values()}


@record(repr=False)
class ShopResult(ResultMixin):
    """One result of the balance shop and its JSON schema.

    Attributes
    ----------
    schema : str
        ``crankbalance.shop.match/2``, ``.bobweights/2``, ``.plan/2`` or ``.scatter/2``.
    result : PartsStudy, BobWeights, HolePlan or ScatterStudy
        What the JSON holds.
    parts : PartsStudy, optional
        The matching the bob-weights come from.
    """

    schema: str
    result: PartsStudy | BobWeights | HolePlan | ScatterStudy
    parts: PartsStudy | None = None

    def headline(self) -> tuple[str, ...]:
        """The matching's spreads and the bob-weights, the plan's verdict, or the scatter's
        residual per plane, in words with units."""
        r = self.result

        def grams(values: Any) -> str:
            return ", ".join(number(float(v) * 1e3) for v in values) + " g"

        if isinstance(r, PartsStudy):
            m = r.matching
            return (
                f"matched ({m.method}{', proven optimal' if m.optimal else ''}): spread "
                f"{number(m.reciprocating_spread * 1e3)} g reciprocating, "
                f"{number(m.rotating_spread * 1e3)} g rotating; "
                f"{number(m.removed_total * 1e3)} g to machine off to even the sets",
                f"bob-weights per crankpin: {grams(r.bob_weights.bob_weight)}",
                *filter(None, [spares_words(r)]),
            )
        if isinstance(r, BobWeights):
            return (
                f"bob-weights per crankpin ({number(r.fraction * 100)} % of the "
                f"reciprocating): {grams(r.bob_weight)}",
            )
        if isinstance(r, HolePlan):
            verdict = "within" if r.check.passed else "NOT within"
            return (f"residual after the holes {verdict} {r.grade} in every plane",)
        return (
            f"{r.samples} engines drawn; residual unbalance [g·mm] of the correction planes:",
            *(
                f"plane {k}: mean {number(r.mean[k - 1] * 1e6)}, maximum "
                f"{number(r.maximum[k - 1] * 1e6)}"
                for k in (1, 2)
            ),
        )

    def main_table(self) -> str:
        """The holes of a plan (the other results' first table)."""
        return "result · holes"

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract of the schema: ``{"schema", "result"}``, every key with its
        unit (:func:`shop_json`)."""
        out = to_jsonable({"schema": self.schema, "result": shop_json(self.result)})
        assert isinstance(out, dict)
        return out


def _parts_file(options: ShopOptions) -> str:
    if options.parts is None:
        raise InputError("parts", None, "is required: the parts file (CSV or TOML)")
    return options.parts


def shop_match(engine: EngineSource, settings: ShopOptions) -> ShopResult:
    """The weighed parts of the parts file matched to the cylinders of ``engine``
    (:func:`parts_study`)."""
    study = parts_study(engine, _parts_file(settings), settings)
    result = ShopResult(MATCH_SCHEMA, study, study)
    result.to_dict()  # checked finite
    return result


def shop_bobweights(engine: EngineSource, settings: ShopOptions) -> ShopResult:
    """The bob-weight of every crankpin from the matched sets of the parts file
    (:func:`parts_study`)."""
    study = parts_study(engine, _parts_file(settings), settings)
    result = ShopResult(BOBWEIGHTS_SCHEMA, study.bob_weights, study)
    result.to_dict()  # checked finite
    return result


def shop_plan(engine: EngineSource | None, settings: ShopOptions) -> ShopResult:
    """Two-plane readings turned into holes per correction plane, and the ISO check
    (:func:`hole_plan`; the engine's speed unless ``speed`` is given)."""
    speed = engine_model(engine)[1].speed if engine is not None else None
    result = ShopResult(PLAN_SCHEMA, hole_plan(settings, speed, PLAN_NAMES))
    result.to_dict()  # checked finite
    return result


def shop_scatter(engine: EngineSource, settings: ShopOptions) -> ShopResult:
    """Monte Carlo of the weight scatter of the parts file: the residual per plane and the
    free forces (:func:`scatter_of_parts`, ``samples`` engines drawn from ``seed``, weighed
    to ``scale_step``)."""
    study = scatter_of_parts(
        engine,
        _parts_file(settings),
        settings,
        settings.samples,
        settings.seed,
        settings.scale_step,
    )
    result = ShopResult(SCATTER_SCHEMA, study)
    result.to_dict()  # checked finite
    return result
